//! The static solver's iteration: evaluating an iterate, the shifted factors and the
//! trust-region step over them, the lowest mode by inverse iteration, the trial step with its
//! energy test, and the restoration onto Φ = 0 (the module documentation gives the algorithm).

use super::iterate::{dot, entries, max_abs, shift_floor, Iterate, IterateVectors, Mode, RestoreFailure};
use super::report::{factor_error, non_finite_force, StaticError};
use super::{StaticSolver, ACCEPT_RATIO, INVERSE_ITERATIONS, ON_RADIUS, SHIFT_TRIALS, WORK_ROUNDING};
use crate::model::mechanism::NewtonMatrix;
use crate::model::workspace::{DenseScratch, Vectors};
use crate::real::Real;
use crate::solvers::kinematics::{first_non_finite, name};

impl<T: Real> StaticSolver<T> {
    /// The relative pivot ratio below which a multiplier is dropped as dependent: the ratio is
    /// about the squared sine of the row's angle to the rows eliminated before it (in the M⁻¹
    /// metric), so the square of [`StaticOptions::rank_tolerance`], and never below the pivot
    /// tolerance (rounding).
    pub(super) fn drop_ratio(&self) -> T {
        let o = &self.options;
        (o.rank_tolerance * o.rank_tolerance).max(o.pivot_tolerance).max(T::from_f64(f64::EPSILON))
    }

    /// Everything the iteration needs at an assembled `q`: the two matrices (in `mass` and
    /// `stiff`), the multipliers by least squares in the M⁻¹ norm ([[M, −Dᵀ], [D, 0]] [x; λ] =
    /// [h; 0], factored in `factors`) and the residual r = h + Dᵀλ = M x, into `vectors`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn evaluate<'a, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        t: T,
        mass: &'a mut M::NewtonStorage,
        stiff: &'a mut M::NewtonStorage,
        factors: &mut M::NewtonStorage,
        vectors: &'a mut IterateVectors<'_, T, NV, NC, N>,
        mut dense: DenseScratch<'_, T, NV, NC>,
    ) -> Result<Iterate<'a, M::NewtonStorage, T, NV, NC>, StaticError>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let time = t.to_f64();
        let nnz = M::JACOBIAN_PATTERN.len();
        let [h, r, mass_diagonal, row_sums, h_columns, d_columns, reaction_row, zero_v] = &mut *vectors.v;
        let [phi, lambda] = &mut *vectors.c;
        let b = &mut *vectors.b;
        for x in [&mut *h, &mut *mass_diagonal, row_sums, h_columns, d_columns, reaction_row, zero_v] {
            x.fill(T::ZERO);
        }
        phi.fill(T::ZERO);
        lambda.fill(T::ZERO);
        m.newton_matrix(q, zero_v, zero_v, t, lambda, None, T::ZERO, T::ZERO, phi, mass, dense.reborrow());
        m.forces(q, zero_v, t, h);
        if let Some(i) = first_non_finite(phi) {
            return Err(StaticError::NonFinite { t: time, row: name(M::CONSTRAINT_NAMES, i) });
        }
        if let Some(i) = first_non_finite(h) {
            return Err(non_finite_force::<M>(time, i));
        }
        factors.as_mut().copy_from_slice(mass.as_ref());
        let mut dropped = [false; NC];
        M::newton_factor(factors, self.drop_ratio(), true, &mut dropped).map_err(|e| factor_error::<M>(time, NV, e))?;
        b.fill(T::ZERO);
        b[..NV].copy_from_slice(h);
        M::newton_solve(factors, b);
        lambda.copy_from_slice(&b[NV..]);
        *r = *h;
        for (&value, &(row, c)) in mass.as_ref().iter().zip(M::JACOBIAN_PATTERN) {
            r[c as usize] += value * lambda[row as usize];
            reaction_row[c as usize] += (value * lambda[row as usize]).abs();
        }
        if let Some(i) = first_non_finite(r) {
            return Err(StaticError::NonFinite { t: time, row: name(M::VELOCITY_NAMES, i) });
        }
        m.newton_matrix(q, zero_v, zero_v, t, lambda, None, T::ZERO, T::ONE, phi, stiff, dense);
        let (mass, stiff) = (&*mass, &*stiff);
        // M's diagonal, then H = M − (M − H) entry by entry over the velocity block.
        for ((u, w), &value) in entries(&M::NEWTON_PATTERN).zip(&mass.as_ref()[nnz..]) {
            if u == w && u < NV {
                mass_diagonal[u] = value;
            }
        }
        let mut scale = T::ZERO;
        for ((u, w), (&m0, &m1)) in entries(&M::NEWTON_PATTERN).zip(mass.as_ref()[nnz..].iter().zip(&stiff.as_ref()[nnz..])) {
            if u < NV && w < NV {
                let hij = m0 - m1;
                if !hij.is_finite() {
                    return Err(non_finite_force::<M>(time, u));
                }
                row_sums[u] += hij.abs();
                h_columns[w] = h_columns[w].max(hij.abs());
                let weight = (mass_diagonal[u] * mass_diagonal[w]).abs().sqrt();
                if weight > T::ZERO {
                    scale = scale.max(hij.abs() / weight);
                }
            }
        }
        for (&value, &(_, c)) in mass.as_ref().iter().zip(M::JACOBIAN_PATTERN) {
            d_columns[c as usize] = d_columns[c as usize].max(value.abs());
        }
        Ok(Iterate {
            mass,
            stiff,
            dropped,
            h,
            phi,
            lambda,
            r,
            mass_diagonal,
            scale,
            stiffness_norm: max_abs(row_sums).0,
            reaction: max_abs(reaction_row).0,
            d_columns,
            h_columns,
        })
    }

    /// [[μM − H, −Dᵀ], [D, 0]] factored, if the reduced matrix of that shift μ (1/s²) is
    /// positive definite on the motions the joints allow: the factorization keeps the rows kept
    /// at the iterate, and its pivots' signs (velocity pivots positive, multiplier pivots
    /// negative, NV of them) say so (Sylvester's law of inertia: module documentation).
    pub(super) fn shifted_factor<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        mu: T,
        s: &mut M::NewtonStorage,
    ) -> bool
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let nnz = M::JACOBIAN_PATTERN.len();
        let pattern = M::NEWTON_PATTERN;
        s.as_mut().copy_from_slice(it.stiff.as_ref());
        for ((u, w), (x, &m0)) in entries(&pattern).zip(s.as_mut()[nnz..].iter_mut().zip(&it.mass.as_ref()[nnz..])) {
            if u < NV && w < NV {
                *x += (mu - T::ONE) * m0;
            }
        }
        let mut dropped = it.dropped;
        let tolerance = self.options.pivot_tolerance.max(T::EPSILON);
        if M::newton_factor(s, tolerance, true, &mut dropped).is_err() || dropped != it.dropped {
            return false;
        }
        let values = &s.as_ref()[nnz..];
        let positive = (0..pattern.size())
            .filter(|&p| {
                let (u, pivot) = (pattern.unknown[p] as usize, values[pattern.diagonal[p] as usize]);
                if u < NV {
                    pivot > T::ZERO
                } else {
                    !dropped[u - NV] && pivot < T::ZERO
                }
            })
            .count();
        positive == NV
    }

    /// The smallest shift of the ladder μ_k = 10^k · μ₀ (k = 0, 1, …; μ₀ = [`shift_floor`])
    /// whose reduced matrix is positive definite, with its factors in `s`.
    pub(super) fn definite_shift<M, const NQ: usize, const NV: usize, const NC: usize>(
        &self,
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        s: &mut M::NewtonStorage,
    ) -> Option<T>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let mut mu = shift_floor(it);
        for _ in 0..SHIFT_TRIALS {
            if self.shifted_factor::<M, NQ, NV, NC>(it, mu, s) {
                return Some(mu);
            }
            mu *= T::from_f64(10.0);
        }
        None
    }

    /// The Levenberg–Marquardt step in the M norm along the motions the joints allow:
    /// (μM − H)δ − Dᵀy = r, Dδ = 0 (the iterate is assembled; the restoration after the step
    /// meets Φ = 0 again), with the smallest shift of the ladder that makes the reduced matrix
    /// positive definite, raised ×4 until δ moves no body more than `radius`. Writes δ to
    /// `delta` and returns the decrease the quadratic model predicts, rᵀδ + ½δᵀHδ = ½(rᵀδ +
    /// μ δᵀMδ); `None` if no shift gives a finite step.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn shifted_step<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        radius: T,
        factors: &mut M::NewtonStorage,
        delta: &mut [T; NV],
        mut vectors: Vectors<'_, T>,
    ) -> Option<T>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        // The step at shift μ into `candidate`: `Err(true)` if the reduced matrix is definite
        // but the step does not fit, `Err(false)` if it is not definite (or the step not
        // finite).
        let floor = shift_floor(it);
        let (b, work) = (vectors.take::<N>(), vectors.rows::<N, 2>());
        let [candidate, md] = vectors.rows::<NV, 2>();
        let mut attempt = |mu: T, candidate: &mut [T; NV]| -> Result<T, bool> {
            if !self.shifted_factor::<M, NQ, NV, NC>(it, mu, factors) {
                return Err(false);
            }
            let factors = &*factors;
            b.fill(T::ZERO);
            b[..NV].copy_from_slice(it.r);
            // At the floor, Newton's own step (μ = 0) where the refinement converges to it.
            let mut mu = mu;
            if mu == floor && !it.shifted_solve::<M, NQ, N>(factors, T::ZERO, b, work) {
                b.fill(T::ZERO);
                b[..NV].copy_from_slice(it.r);
                it.shifted_solve::<M, NQ, N>(factors, mu, b, work);
            } else if mu == floor {
                mu = T::ZERO;
            } else {
                it.shifted_solve::<M, NQ, N>(factors, mu, b, work);
            }
            candidate.copy_from_slice(&b[..NV]);
            if first_non_finite(candidate).is_some() {
                return Err(false);
            }
            if m.motion_size(q, candidate) > radius {
                return Err(true);
            }
            m.mass_times(q, candidate, md);
            Ok(T::from_f64(0.5) * (dot(it.r, candidate) + mu * dot(candidate, md)))
        };
        // Up from the floor (Newton's step where it is definite and fits): ×10 while not
        // definite, ×4 while the step is too long. The best step so far is in `delta`.
        let (mut low, mut mu) = (T::ZERO, floor);
        let (mut high, mut predicted) = loop {
            match attempt(mu, delta) {
                Ok(predicted) => break (mu, predicted),
                Err(definite) => {
                    low = mu;
                    mu *= T::from_f64(if definite { 4.0 } else { 10.0 });
                    if !mu.is_finite() {
                        return None;
                    }
                }
            }
        };
        // Above the floor, the smallest shift that fits (to 5 %): the step on the radius, the
        // trust-region step (step length falls as μ grows past the definite threshold).
        if low > T::ZERO {
            for _ in 0..SHIFT_TRIALS {
                if m.motion_size(q, delta) >= T::from_f64(ON_RADIUS) * radius || high <= T::from_f64(1.05) * low {
                    break;
                }
                let middle = (low * high).sqrt();
                match attempt(middle, candidate) {
                    Ok(found) => {
                        (high, predicted) = (middle, found);
                        *delta = *candidate;
                    }
                    Err(_) => low = middle,
                }
            }
        }
        let _ = high;
        Some(predicted)
    }

    /// The lowest mode of the reduced stiffness, by inverse iteration on the factors of the
    /// smallest definite shift μ: x ← (μM − H)⁻¹ M x on the motions the joints allow
    /// ([[μM − H, −Dᵀ], [D, 0]] [x'; ·] = [M x; 0]), which converges to the mode of smallest
    /// ω² + μ > 0, i.e. the smallest ω²; ω² from the Rayleigh quotient
    /// x'ᵀ(−H)x' / x'ᵀMx' = x'ᵀMx / x'ᵀMx' − μ, which needs no product with H.
    /// Its shape is written to `shape`.
    pub(super) fn lowest_mode<'s, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        it: &Iterate<M::NewtonStorage, T, NV, NC>,
        factors: &mut M::NewtonStorage,
        shape: &'s mut [T; NV],
        mut vectors: Vectors<'_, T>,
    ) -> Option<Mode<'s, T, NV>>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let mu = self.definite_shift::<M, NQ, NV, NC>(it, factors)?;
        let factors = &*factors;
        let (b, work) = (vectors.take::<N>(), vectors.rows::<N, 2>());
        let [mx, next, m_next] = vectors.rows::<NV, 3>();
        // Start from M times a vector of unequal entries (fractional parts of multiples of the
        // golden ratio): no mode is missed by a symmetry of the start.
        for (i, x) in mx.iter_mut().enumerate() {
            let spread = libm::fmod(0.618_033_988_749_895 * (i + 1) as f64, 1.0);
            *x = it.mass_diagonal[i] * T::from_f64(0.5 + spread);
        }
        let x = shape;
        x.fill(T::ZERO);
        let mut omega_squared = T::ZERO;
        for k in 0..INVERSE_ITERATIONS {
            b.fill(T::ZERO);
            b[..NV].copy_from_slice(mx);
            it.shifted_solve::<M, NQ, N>(factors, mu, b, work);
            next.copy_from_slice(&b[..NV]);
            m.mass_times(q, next, m_next);
            let norm2 = dot(next, m_next);
            if !norm2.is_finite() || norm2 <= T::ZERO {
                return None;
            }
            let rayleigh = dot(next, mx) / norm2 - mu;
            let inverse = T::ONE / norm2.sqrt();
            for i in 0..NV {
                x[i] = next[i] * inverse;
                mx[i] = m_next[i] * inverse;
            }
            let settled = (rayleigh - omega_squared).abs() <= T::from_f64(1e-13) * rayleigh.abs().max(it.scale);
            omega_squared = rayleigh;
            if k > 0 && settled {
                break;
            }
        }
        // Without any stiffness (H = 0) every ω² is 0 exactly; the iteration gave the shape.
        if it.scale == T::ZERO {
            omega_squared = T::ZERO;
        }
        Some(Mode { omega_squared, shape: x, shift: mu })
    }

    /// One trial step from the equilibrium iterate `q` (forces `h`): `trial` = q ⊕ δ restored
    /// onto Φ = 0, and the work the loads did along the displacement δ' (δ plus the
    /// restoration's steps), by Simpson's rule on the chord: (h₀ + 4 h(q ⊕ δ'/2) + h₁)ᵀ δ' / 6,
    /// −ΔV to fifth order for conservative loads, and alert to a hill inside the step that the
    /// end points alone would miss. Returns the ratio of that work to the `predicted` decrease
    /// if the step is accepted (the work is at least [`ACCEPT_RATIO`] of the prediction, up to
    /// the rounding of the sum), `None` if it is rejected or its restoration failed.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn trial<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &[T; NQ],
        t: T,
        h: &[T; NV],
        delta: &[T; NV],
        predicted: T,
        trial: &mut [T; NQ],
        correction: &mut [T; NV],
        s: &mut M::NewtonStorage,
        mut dense: DenseScratch<'_, T, NV, NC>,
    ) -> Option<T>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let [zero_v, displacement, half_way, h_middle, h_end] = dense.vectors.rows::<NV, 5>();
        let middle = dense.vectors.take::<NQ>();
        *trial = *q;
        m.integrate_positions(trial, delta, T::ONE);
        correction.fill(T::ZERO);
        self.restore::<M, NQ, NV, NC, N>(m, trial, t, correction, s, dense).ok()?;
        for i in 0..NV {
            displacement[i] = delta[i] + correction[i];
            half_way[i] = T::from_f64(0.5) * displacement[i];
        }
        *middle = *q;
        m.integrate_positions(middle, half_way, T::ONE);
        m.forces(middle, zero_v, t, h_middle);
        m.forces(trial, zero_v, t, h_end);
        if first_non_finite(trial).is_some() || first_non_finite(h_middle).is_some() || first_non_finite(h_end).is_some() {
            return None;
        }
        let (mut work, mut size) = (T::ZERO, T::ZERO);
        let (four, sixth) = (T::from_f64(4.0), T::ONE / T::from_f64(6.0));
        for i in 0..NV {
            let term = sixth * (h[i] + four * h_middle[i] + h_end[i]) * displacement[i];
            work += term;
            size += term.abs();
        }
        let rounding = T::from_f64(WORK_ROUNDING) * T::EPSILON * size;
        if work + rounding < T::from_f64(ACCEPT_RATIO) * predicted {
            return None;
        }
        Some(if predicted > rounding { (work / predicted).max(T::ZERO) } else { T::ONE })
    }

    /// Newton onto Φ(q, t) = 0 with steps of least kinetic-energy norm,
    /// [[M, −Dᵀ], [D, 0]] [Δv; ·] = [0; −Φ], q ← q ⊕ Δv, over the planned factorization; the
    /// steps are added to `correction`. A constraint row that depends on the rows eliminated
    /// before it (a redundant constraint, or a singular pose) is dropped: its multiplier is 0
    /// and what it imposes is met through the others.
    pub(super) fn restore<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        correction: &mut [T; NV],
        s: &mut M::NewtonStorage,
        mut dense: DenseScratch<'_, T, NV, NC>,
    ) -> Result<u32, RestoreFailure>
    where
        M: NewtonMatrix<T, NQ, NV, NC>,
    {
        let time = t.to_f64();
        let tol = self.options.tolerance;
        let [zero_v, step] = dense.vectors.rows::<NV, 2>();
        let [phi, zero_c] = dense.vectors.rows::<NC, 2>();
        let b = dense.vectors.take::<N>();
        let mut iterations = 0;
        let mut dropped = [false; NC];
        loop {
            m.newton_matrix(q, zero_v, zero_v, t, zero_c, None, T::ZERO, T::ZERO, phi, s, dense.reborrow());
            if let Some(i) = first_non_finite(phi) {
                return Err(RestoreFailure::Static(StaticError::NonFinite { t: time, row: name(M::CONSTRAINT_NAMES, i) }));
            }
            let (norm, worst) = max_abs(phi);
            if norm <= tol {
                return Ok(iterations);
            }
            if iterations >= self.options.assembly_iterations {
                // The worst row unmet and dependent on the others: a singular pose whose
                // linearization cannot see that row (links lying collinear from `at:` left out).
                if dropped[worst] {
                    return Err(RestoreFailure::Static(StaticError::Singular { t: time, row: name(M::CONSTRAINT_NAMES, worst) }));
                }
                return Err(RestoreFailure::NotConverged { iterations, worst, residual: norm.to_f64() });
            }
            dropped = [false; NC];
            M::newton_factor(s, self.drop_ratio(), true, &mut dropped)
                .map_err(|e| RestoreFailure::Static(factor_error::<M>(time, NV, e)))?;
            b.fill(T::ZERO);
            for (x, &p) in b[NV..].iter_mut().zip(phi.iter()) {
                *x = -p;
            }
            M::newton_solve(s, b);
            step.copy_from_slice(&b[..NV]);
            if let Some(i) = first_non_finite(step) {
                return Err(RestoreFailure::Static(StaticError::NonFinite { t: time, row: name(M::VELOCITY_NAMES, i) }));
            }
            m.integrate_positions(q, step, T::ONE);
            for (c, &s) in correction.iter_mut().zip(step.iter()) {
                *c += s;
            }
            iterations += 1;
        }
    }
}

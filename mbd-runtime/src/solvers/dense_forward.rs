//! Forward dynamics by dense factorizations of M(q) and S = D M⁻¹ Dᵀ: what `mechanism!`
//! generates where M depends on q (joint coordinates), and a reference for any mechanism. M⁻¹
//! is applied by the mechanism's own recursion where it has one (`Dynamics::solve_mass`: a
//! tree's articulated-body algorithm, O(N) per solve), else by M's Cholesky factor.
//!
//! The equations are those of the generated sparse solve (docs/formulation.md, "Forward
//! dynamics"): M v̇ − Dᵀλ = h, D v̇ = γ − 2α(D v − ν) − β²Φ, solved as
//! S λ = γ − D M⁻¹h − 2α(D v − ν) − β²Φ, v̇ = M⁻¹(h + Dᵀλ), with M = L Lᵀ (Cholesky) and
//! S = L_S D_S L_Sᵀ whose pivots follow the same rule (`sparse::schur_pivot`: a dependent row
//! fails or, with `allow_redundant`, fades smoothly). Rows are eliminated in Φ's order.
//!
//! Cost per call: NV³/6 for M's factor and NC·NV² for M⁻¹Dᵀ (with the recursion instead: NC + 1
//! solves of O(N) each), NC²·NV for S and NC³/6 for its factor, against the generated sparse
//! solve's cost in the non-zeros. The arrays (NV² + 2 NC·NV + NC² values) are a
//! [`DenseScratch`]: a work space's ([`Workspace::dense`](crate::WorkArrays::dense)) in every
//! solver and integrator, on the stack only in a direct call of
//! [`ForwardDynamics::accelerations`](crate::ForwardDynamics::accelerations) or a projection.

// The factorizations index rows and columns as the formulas do (L_ij, S_kj d_j): iterators over
// rows would hide which entry is which.
#![allow(clippy::needless_range_loop)]

use crate::linalg::sparse::{max_abs_finite, schur_pivot};
use crate::model::dynamics::{DynamicsError, DynamicsOptions};
use crate::model::mechanism::Dynamics;
use crate::model::workspace::DenseScratch;
use crate::real::Real;

/// M = L Lᵀ in place (lower triangle), or the velocity whose pivot is not positive and finite
/// with that pivot.
fn cholesky<T: Real, const NV: usize>(a: &mut [[T; NV]; NV]) -> Result<(), (usize, T)> {
    for j in 0..NV {
        let mut d = a[j][j];
        for k in 0..j {
            d -= a[j][k] * a[j][k];
        }
        if !(d.is_finite() && d > T::ZERO) {
            return Err((j, d));
        }
        let ljj = d.sqrt();
        a[j][j] = ljj;
        let inv = T::ONE / ljj;
        for i in j + 1..NV {
            let mut s = a[i][j];
            for k in 0..j {
                s -= a[i][k] * a[j][k];
            }
            a[i][j] = s * inv;
        }
    }
    Ok(())
}

/// x ← M⁻¹ x with M = L Lᵀ from [`cholesky`].
fn cholesky_solve<T: Real, const NV: usize>(l: &[[T; NV]; NV], x: &mut [T; NV]) {
    for i in 0..NV {
        let mut s = x[i];
        for k in 0..i {
            s -= l[i][k] * x[k];
        }
        x[i] = s / l[i][i];
    }
    for i in (0..NV).rev() {
        let mut s = x[i];
        for k in i + 1..NV {
            s -= l[k][i] * x[k];
        }
        x[i] = s / l[i][i];
    }
}

/// The factors of M and of S = D M⁻¹ Dᵀ at one configuration, and M⁻¹Dᵀ, in the arrays of a
/// [`DenseScratch`] (D itself in its `d`).
struct Factors<'a, T, const NV: usize, const NC: usize> {
    /// D, as evaluated.
    d: &'a [[T; NV]; NC],
    /// M's Cholesky factor L, or `None` where the mechanism's recursion applies M⁻¹.
    l: Option<&'a [[T; NV]; NV]>,
    /// Row r: M⁻¹ D_rᵀ.
    y: &'a [[T; NV]; NC],
    /// S's LDLᵀ: L_S below the diagonal, 1/d (weighted) on it.
    s: &'a [[T; NC]; NC],
}

impl<'a, T: Real, const NV: usize, const NC: usize> Factors<'a, T, NV, NC> {
    /// Factors M and S for the D in `scratch.d`, or the error naming the body
    /// (`mass_bodies[i]`: the body velocity i moves) or the constraint row.
    fn new<M: Dynamics<T, NQ, NV, NC>, const NQ: usize>(
        m: &M,
        q: &[T; NQ],
        scratch: DenseScratch<'a, T, NV, NC>,
        t: T,
        options: &DynamicsOptions<T>,
        mass_bodies: &[u16],
    ) -> Result<Self, DynamicsError> {
        let DenseScratch { d, y, s, l, .. } = scratch;
        let body = |i: usize| M::BODY_NAMES.get(mass_bodies.get(i).copied().unwrap_or(0) as usize).copied().unwrap_or("?");
        y.copy_from_slice(&d[..]);
        // M⁻¹Dᵀ over one factorization of M shared by the rows.
        let l = if let Some(solved) = m.solve_mass_rows(q, y) {
            if let Err(i) = solved {
                return Err(non_positive::<T, M, NQ, NV, NC>(q, t, i, mass_bodies));
            }
            None
        } else {
            for row in l.iter_mut() {
                row.fill(T::ZERO);
            }
            m.add_mass_matrix(q, T::ONE, l);
            if let Err((i, pivot)) = cholesky(l) {
                if !pivot.is_finite() || !t.is_finite() {
                    return Err(DynamicsError::NonFinite { t: t.to_f64(), row: M::VELOCITY_NAMES.get(i).copied().unwrap_or("?") });
                }
                return Err(DynamicsError::NonPositiveMass { body: body(i), value: pivot.to_f64() });
            }
            for row in y.iter_mut() {
                cholesky_solve(l, row);
            }
            Some(&*l)
        };
        for i in 0..NC {
            for j in 0..=i {
                let mut x = T::ZERO;
                for c in 0..NV {
                    x += d[i][c] * y[j][c];
                }
                s[i][j] = x;
            }
        }
        let exact = T::from_f64(if options.allow_redundant { 1e2 } else { 1.0 });
        let mut pivots = [T::ZERO; NC];
        for k in 0..NC {
            let skk = s[k][k];
            let mut dk = skk;
            for j in 0..k {
                dk -= s[k][j] * s[k][j] * pivots[j];
            }
            let Some((dk, dinv)) = schur_pivot(skk, dk, exact, options.pivot_tolerance, options.allow_redundant) else {
                let finite = d[k].iter().all(|x| x.is_finite()) && t.is_finite();
                let row = M::CONSTRAINT_NAMES.get(k).copied().unwrap_or("?");
                return Err(if finite {
                    let zero_row = d[k].iter().all(|&x| x == T::ZERO);
                    DynamicsError::at_pivot(t.to_f64(), row, zero_row, options.allow_redundant)
                } else {
                    DynamicsError::NonFinite { t: t.to_f64(), row }
                });
            };
            pivots[k] = dk;
            s[k][k] = dinv;
            for i in k + 1..NC {
                let mut x = s[i][k];
                for j in 0..k {
                    x -= s[i][j] * s[k][j] * pivots[j];
                }
                s[i][k] = x * dinv;
            }
        }
        Ok(Factors { d, l, y, s })
    }

    /// x ← M⁻¹ x.
    fn mass_solve<M: Dynamics<T, NQ, NV, NC>, const NQ: usize>(&self, m: &M, q: &[T; NQ], x: &mut [T; NV]) {
        match self.l {
            Some(l) => cholesky_solve(l, x),
            // The configuration the factors were made at: its pivots were checked then.
            None => {
                let _ = m.solve_mass(q, x);
            }
        }
    }

    /// b ← S⁻¹ b.
    fn schur_solve(&self, b: &mut [T; NC]) {
        for i in 0..NC {
            for j in 0..i {
                b[i] -= self.s[i][j] * b[j];
            }
        }
        for i in 0..NC {
            b[i] *= self.s[i][i];
        }
        for i in (0..NC).rev() {
            for j in i + 1..NC {
                b[i] -= self.s[j][i] * b[j];
            }
        }
    }

    /// x −= M⁻¹ Dᵀ b.
    fn subtract_correction(&self, b: &[T; NC], x: &mut [T; NV]) {
        for (r, &br) in b.iter().enumerate() {
            for (xc, &yc) in x.iter_mut().zip(&self.y[r]) {
                *xc -= yc * br;
            }
        }
    }
}

/// The error of a non-positive pivot of `Dynamics::solve_mass` at velocity i: non-finite where
/// t or q is, else the body velocity i moves without mass (`value` 0: the recursion names the
/// link, not its pivot).
fn non_positive<T: Real, M: Dynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    q: &[T; NQ],
    t: T,
    i: usize,
    mass_bodies: &[u16],
) -> DynamicsError {
    if !t.is_finite() || q.iter().any(|x| !x.is_finite()) {
        return DynamicsError::NonFinite { t: t.to_f64(), row: M::VELOCITY_NAMES.get(i).copied().unwrap_or("?") };
    }
    let body = M::BODY_NAMES.get(mass_bodies.get(i).copied().unwrap_or(0) as usize).copied().unwrap_or("?");
    DynamicsError::NonPositiveMass { body, value: 0.0 }
}

/// v̇ and λ ([`ForwardDynamics::accelerations`](crate::ForwardDynamics::accelerations)) by
/// dense factorizations (module docs). `friction`: whether the mechanism has Coulomb friction,
/// whose loads are found by fixed-point iteration as in the generated solve; `mass_bodies[i]`:
/// the body velocity i moves, for naming it in an error.
///
/// # Errors
/// As [`ForwardDynamics::accelerations`](crate::ForwardDynamics::accelerations).
#[allow(clippy::too_many_arguments)]
pub fn accelerations<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    scratch: DenseScratch<'_, T, NV, NC>,
    q: &[T; NQ],
    v: &[T; NV],
    t: T,
    options: &DynamicsOptions<T>,
    friction: bool,
    mass_bodies: &[u16],
    vd: &mut [T; NV],
    lambda: &mut [T; NC],
) -> Result<(), DynamicsError>
where
    T: Real,
    M: Dynamics<T, NQ, NV, NC>,
{
    if NC == 0 {
        // A tree: v̇ = M⁻¹h, by the recursion where there is one (no rows, so no friction).
        match m.free_accelerations(q, v, t, vd) {
            Some(Ok(())) => return Ok(()),
            Some(Err(i)) => return Err(non_positive::<T, M, NQ, NV, NC>(q, t, i, mass_bodies)),
            None => {}
        }
    }
    let (mut phi, mut nu, mut gamma) = ([T::ZERO; NC], [T::ZERO; NC], [T::ZERO; NC]);
    m.full_eval(q, v, t, &mut phi, scratch.d, &mut nu, &mut gamma);
    let factors = Factors::<T, NV, NC>::new(m, q, scratch, t, options, mass_bodies)?;
    let d = factors.d;
    let mut applied = [T::ZERO; NV];
    m.forces(q, v, t, &mut applied);
    let two_alpha = options.baumgarte_alpha + options.baumgarte_alpha;
    let beta2 = options.baumgarte_beta * options.baumgarte_beta;
    let mut solve = |lambda: &mut [T; NC]| {
        let mut h = applied;
        if friction {
            m.friction_forces(q, v, t, lambda, &mut h);
        }
        // v̇ = M⁻¹h, then S λ = γ − D M⁻¹h − 2α(D v − ν) − β²Φ, v̇ += M⁻¹Dᵀλ
        *vd = h;
        factors.mass_solve(m, q, vd);
        for r in 0..NC {
            let (mut d_vd, mut d_v) = (T::ZERO, T::ZERO);
            for c in 0..NV {
                d_vd += d[r][c] * vd[c];
                d_v += d[r][c] * v[c];
            }
            lambda[r] = gamma[r] - d_vd - two_alpha * (d_v - nu[r]) - beta2 * phi[r];
        }
        factors.schur_solve(lambda);
        let minus: [T; NC] = lambda.map(|l| T::ZERO - l);
        factors.subtract_correction(&minus, vd);
    };
    if !friction {
        solve(lambda);
        return Ok(());
    }
    crate::solvers::friction::settle_loads(options.friction_tolerance, options.friction_iterations, lambda, solve)
        .map(|_| ())
        .map_err(|(_, change)| DynamicsError::FrictionNotConverged { t: t.to_f64(), change: change.to_f64() })
}

/// One Newton step of the mass-weighted projection of q onto Φ(q, t) = 0
/// ([`ForwardDynamics::project_positions_step`](crate::ForwardDynamics::project_positions_step)):
/// q ← q ⊕ (−M⁻¹ Dᵀ S⁻¹ Φ). Returns ‖Φ‖∞ before the step.
///
/// # Errors
/// As [`accelerations`].
pub fn project_positions_step<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    scratch: DenseScratch<'_, T, NV, NC>,
    q: &mut [T; NQ],
    t: T,
    options: &DynamicsOptions<T>,
    mass_bodies: &[u16],
) -> Result<T, DynamicsError>
where
    T: Real,
    M: Dynamics<T, NQ, NV, NC>,
{
    if NC == 0 {
        // Nothing to project onto.
        return Ok(T::ZERO);
    }
    let mut phi = [T::ZERO; NC];
    m.position_eval(q, t, &mut phi, scratch.d);
    let (worst, _) = max_abs_finite(&phi);
    let factors = Factors::<T, NV, NC>::new(m, q, scratch, t, options, mass_bodies)?;
    factors.schur_solve(&mut phi);
    let mut dv = [T::ZERO; NV];
    factors.subtract_correction(&phi, &mut dv);
    m.integrate_positions(q, &dv, T::ONE);
    Ok(worst)
}

/// The mass-weighted projection of v onto D v = ν
/// ([`ForwardDynamics::project_velocities`](crate::ForwardDynamics::project_velocities)):
/// v ← v − M⁻¹ Dᵀ S⁻¹ (D v − ν). Returns ‖D v − ν‖∞ before it.
///
/// # Errors
/// As [`accelerations`].
pub fn project_velocities<T, M, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    scratch: DenseScratch<'_, T, NV, NC>,
    q: &[T; NQ],
    v: &mut [T; NV],
    t: T,
    options: &DynamicsOptions<T>,
    mass_bodies: &[u16],
) -> Result<T, DynamicsError>
where
    T: Real,
    M: Dynamics<T, NQ, NV, NC>,
{
    if NC == 0 {
        return Ok(T::ZERO);
    }
    let (mut phi, mut nu) = ([T::ZERO; NC], [T::ZERO; NC]);
    m.position_eval(q, t, &mut phi, scratch.d);
    m.velocity_rhs(q, t, &mut nu);
    let mut b = [T::ZERO; NC];
    for r in 0..NC {
        let mut x = T::ZERO - nu[r];
        for c in 0..NV {
            x += scratch.d[r][c] * v[c];
        }
        b[r] = x;
    }
    let (worst, _) = max_abs_finite(&b);
    let factors = Factors::<T, NV, NC>::new(m, q, scratch, t, options, mass_bodies)?;
    factors.schur_solve(&mut b);
    factors.subtract_correction(&b, v);
    Ok(worst)
}

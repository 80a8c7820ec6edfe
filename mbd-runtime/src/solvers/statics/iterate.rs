//! One iterate of the static solver over the Newton matrix's planned storage, its shifted
//! solves refined against the matrix, and the lowest mode found at the end.

use super::report::StaticError;
use super::MAX_REFINEMENTS;
use crate::model::mechanism::NewtonMatrix;
use crate::model::workspace::Vectors;
use crate::real::Real;

/// (max |v_i|, i), the first index among equals; (0, 0) when empty.
pub(super) fn max_abs<T: Real>(values: &[T]) -> (T, usize) {
    values.iter().enumerate().fold((T::ZERO, 0), |(best, at), (i, v)| if v.abs() > best { (v.abs(), i) } else { (best, at) })
}

/// aᵀ b over the shorter length.
pub(super) fn dot<T: Real>(a: &[T], b: &[T]) -> T {
    a.iter().zip(b).fold(T::ZERO, |s, (&x, &y)| s + x * y)
}

/// Each stored entry of the Newton pattern with the unknowns of its row and column (v̇ entries
/// 0..NV, then multipliers), in storage order (after D's non-zeros).
pub(super) fn entries(pattern: &crate::linalg::sparse::SparsePattern) -> impl Iterator<Item = (usize, usize)> + '_ {
    (0..pattern.size()).flat_map(move |p| {
        let row = pattern.row_start[p] as usize..pattern.row_start[p + 1] as usize;
        pattern.columns[row].iter().map(move |&c| (pattern.unknown[p] as usize, pattern.unknown[c as usize] as usize))
    })
}

/// Why a restoration onto Φ = 0 failed.
pub(super) enum RestoreFailure {
    NotConverged { iterations: u32, worst: usize, residual: f64 },
    Static(StaticError),
}

/// One iterate, evaluated over the Newton matrix's planned storage: the matrices
/// [[M, −Dᵀ], [D, 0]] (`mass`) and
/// [[M − H, −Dᵀ], [D, 0]] (`stiff`, H = (∂h/∂q)B + K(λ) at the multipliers), the loads, the
/// multipliers and the projected residual r = h + Dᵀλ.
pub(super) struct Iterate<'a, S, T, const NV: usize, const NC: usize> {
    pub(super) mass: &'a S,
    pub(super) stiff: &'a S,
    /// The rows of D dropped as dependent on the rows eliminated before them.
    pub(super) dropped: [bool; NC],
    pub(super) h: &'a [T; NV],
    pub(super) phi: &'a [T; NC],
    pub(super) lambda: &'a [T; NC],
    pub(super) r: &'a [T; NV],
    /// M's diagonal.
    pub(super) mass_diagonal: &'a [T; NV],
    /// max |H_ij| / √(M_ii M_jj) (1/s²): the scale of the stiffness, of the neutral verdict and
    /// of the Levenberg–Marquardt shift.
    pub(super) scale: T,
    /// ‖H‖∞ and max_k Σ_r |D_rk λ_r|: the sizes entering the residual's rounding floor.
    pub(super) stiffness_norm: T,
    pub(super) reaction: T,
    /// max_r |D_ri| and max_r |H_ri| of each column i, for the angle wrap.
    pub(super) d_columns: &'a [T; NV],
    pub(super) h_columns: &'a [T; NV],
}

/// The vectors an [`Iterate`] is evaluated into and reads, taken from the work space once per
/// solve: h, r, M's diagonal, the column sizes and two more (zero velocities, row sums), Φ
/// and λ, and the right-hand side of the multipliers' solve.
pub(super) struct IterateVectors<'a, T, const NV: usize, const NC: usize, const N: usize> {
    pub(super) v: &'a mut [[T; NV]; 8],
    pub(super) c: &'a mut [[T; NC]; 2],
    pub(super) b: &'a mut [T; N],
}

impl<'a, T: Real, const NV: usize, const NC: usize, const N: usize> IterateVectors<'a, T, NV, NC, N> {
    pub(super) fn take(vectors: &mut Vectors<'a, T>) -> Self {
        Self { v: vectors.rows(), c: vectors.rows(), b: vectors.take() }
    }
}

impl<S: Copy + AsRef<[T]> + AsMut<[T]>, T: Real, const NV: usize, const NC: usize> Iterate<'_, S, T, NV, NC> {
    /// Multipliers kept by the factorization of [[M, −Dᵀ], [D, 0]].
    pub(super) fn kept(&self) -> usize {
        self.dropped.iter().filter(|&&d| !d).count()
    }

    /// Solves [[μM − H, −Dᵀ], [D, 0]] x = b in place (`b`: NV + NC entries) by iterative
    /// refinement against that matrix, with the `factors` of the one at a shift μ_f ≥ μ. For
    /// μ = μ_f this regains the digits the factors lose: the planned order eliminates
    /// velocities first, and where M − H/μ is nearly singular there (a small shift on a free
    /// direction: only the constraints' stiffness holds a pendulum's x) they lose up to
    /// log₁₀(s/μ). For μ below it (Newton's μ = 0 from the floor's factors) each refinement
    /// also gains a factor (μ_f − μ)/(ω²_min + μ_f): the exact Newton step, where the floor is
    /// tiny against the softest mode. Returns whether the corrections fell to rounding
    /// ([`MAX_REFINEMENTS`] at most, each at least halving the last). `work`: two vectors of N
    /// to work in.
    pub(super) fn shifted_solve<M, const NQ: usize, const N: usize>(
        &self,
        factors: &S,
        mu: T,
        b: &mut [T; N],
        work: &mut [[T; N]; 2],
    ) -> bool
    where
        M: NewtonMatrix<T, NQ, NV, NC, NewtonStorage = S>,
    {
        let nnz = M::JACOBIAN_PATTERN.len();
        let [rhs, r] = work;
        *rhs = *b;
        M::newton_solve(factors, b);
        let mut last: Option<T> = None;
        for _ in 0..MAX_REFINEMENTS {
            // r = rhs − A x over the stored entries; a dropped multiplier's row is the
            // identity's in the factors, and its unknown stays 0.
            *r = *rhs;
            let values = self.stiff.as_ref()[nnz..].iter().zip(&self.mass.as_ref()[nnz..]);
            for ((u, w), (&stiff, &mass)) in entries(&M::NEWTON_PATTERN).zip(values) {
                if u >= NV && self.dropped[u - NV] {
                    continue;
                }
                let a = if u < NV && w < NV { stiff + (mu - T::ONE) * mass } else { stiff };
                r[u] -= a * b[w];
            }
            for (r, &dropped) in r[NV..].iter_mut().zip(&self.dropped) {
                if dropped {
                    *r = T::ZERO;
                }
            }
            M::newton_solve(factors, r);
            let change = max_abs(r).0;
            if !change.is_finite() || last.is_some_and(|last| change > T::from_f64(0.5) * last) {
                return false;
            }
            for (x, &dx) in b.iter_mut().zip(r.iter()) {
                *x += dx;
            }
            if change <= T::from_f64(16.0) * T::EPSILON * max_abs(b).0 {
                return true;
            }
            last = Some(change);
        }
        false
    }
}

/// The lowest mode of the reduced stiffness: ω² (1/s²) and its shape z (M-normalized,
/// velocity space).
pub(super) struct Mode<'a, T, const NV: usize> {
    pub(super) omega_squared: T,
    pub(super) shape: &'a [T; NV],
    /// The shift of the inverse iteration: ω² is known to about ε times it.
    pub(super) shift: T,
}

/// The smallest Levenberg–Marquardt shift tried: √ε (1.5e-8 in f64) times the stiffness scale
/// s = max |H_ij| / √(M_ii M_jj). Small enough that the step is Newton's to √ε · s / ω²_min
/// (the iteration converges at least at that rate), large enough that the factors, eliminating
/// velocities first, keep half the digits where μM − H is singular but for μM (two iterative
/// refinements regain them). 1 (1/s²) where there is no stiffness at all (H = 0: every step is
/// then r/μ in the M norm, on the trust radius).
pub(super) fn shift_floor<S, T: Real, const NV: usize, const NC: usize>(it: &Iterate<S, T, NV, NC>) -> T {
    if it.scale > T::ZERO {
        T::EPSILON.sqrt() * it.scale
    } else {
        T::ONE
    }
}

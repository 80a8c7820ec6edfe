//! Static equilibrium (Nikravesh, *Planar Multibody Dynamics*, 14.2): at rest (v = 0, v̇ = 0) the
//! equations of motion reduce to
//!
//! h(q, 0, t) + Dᵀ λ = 0,   Φ(q, t) = 0,
//!
//! solved for (q, λ) by Newton–Raphson in velocity space with the exact Jacobian
//! [[(∂h/∂q)B + K, Dᵀ], [D, 0]], K = ∂(Dᵀλ)/∂q·B (generated, [`ConstraintForces`]); each step
//! (Δv, Δλ) updates q ← q ⊕ Δv ([`Kinematics::integrate_positions`](crate::Kinematics::integrate_positions),
//! h = 1). The saddle-point matrix has NV + NC rows, a size stable Rust cannot compute from the
//! mechanism's const generics, so the caller passes a [`KktWorkspace`] of that size, made once by
//! the generated `Name::kkt_workspace()`.

use crate::kinematics::{first_non_finite, name};
use crate::linalg::{lu_factor, lu_solve_in_place, LinalgError};
use crate::{ConstraintForces, Dynamics, Mechanism, Real};
use core::fmt;

/// Default tolerance on max(‖h + Dᵀλ‖∞ (N, N·m), ‖Φ‖∞ (m, rad)).
pub const DEFAULT_STATIC_TOLERANCE: f64 = 1e-9;
/// Default cap on Newton iterations.
pub const DEFAULT_STATIC_MAX_ITERATIONS: u32 = 50;
/// Default relative pivot tolerance of the saddle-point factorization.
pub const DEFAULT_STATIC_PIVOT_TOLERANCE: f64 = 1e-13;

/// Options of [`StaticSolver`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct StaticOptions {
    /// Converged when both residuals are at most this (N or N·m for forces, m or rad for Φ).
    pub tolerance: f64,
    /// Newton iterations before giving up.
    pub max_iterations: u32,
    /// Relative pivot tolerance of the LU factorization (see [`crate::linalg::lu_factor`]).
    pub pivot_tolerance: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        StaticOptions {
            tolerance: DEFAULT_STATIC_TOLERANCE,
            max_iterations: DEFAULT_STATIC_MAX_ITERATIONS,
            pivot_tolerance: DEFAULT_STATIC_PIVOT_TOLERANCE,
        }
    }
}

impl StaticOptions {
    /// With another residual tolerance.
    pub const fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }
    /// With another iteration cap.
    pub const fn with_max_iterations(mut self, max_iterations: u32) -> Self {
        self.max_iterations = max_iterations;
        self
    }
}

/// Why a static equilibrium was not found.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum StaticError {
    /// The workspace does not have NV + NC rows.
    WorkspaceSize {
        /// Rows the mechanism needs.
        expected: usize,
        /// Rows the workspace has.
        found: usize,
    },
    /// Newton did not converge; the worst residual is a force row (a velocity) or a constraint.
    NotConverged {
        /// Time (s).
        t: f64,
        /// Iterations made.
        iterations: u32,
        /// The row with the largest residual.
        worst_row: &'static str,
        /// Its value.
        residual: f64,
    },
    /// The saddle-point matrix is singular: no unique equilibrium (a mechanism free to move
    /// without changing its potential energy, or redundant constraints).
    Singular {
        /// Time (s).
        t: f64,
        /// The velocity or constraint row without a pivot.
        row: &'static str,
    },
    /// NaN or infinity in the state, forces or constraints.
    NonFinite {
        /// Time (s).
        t: f64,
        /// The row where it appeared.
        row: &'static str,
    },
}

impl fmt::Display for StaticError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StaticError::WorkspaceSize { expected, found } => {
                write!(f, "static equilibrium: the workspace has {found} rows but the mechanism needs NV + NC = {expected}; use Name::kkt_workspace()")
            }
            StaticError::NotConverged { t, iterations, worst_row, residual } => write!(
                f,
                "static equilibrium not found at t = {t} s after {iterations} iterations: worst residual {residual:.3e} in '{worst_row}'"
            ),
            StaticError::Singular { t, row } => {
                write!(f, "static equilibrium at t = {t} s is not unique: no pivot for '{row}' (a free motion without stiffness, or redundant constraints)")
            }
            StaticError::NonFinite { t, row } => write!(f, "static equilibrium at t = {t} s: non-finite value in '{row}'"),
        }
    }
}

impl core::error::Error for StaticError {}

/// Work space for the (NV + NC)-square saddle-point system; N must equal NV + NC.
#[derive(Clone, Debug)]
pub struct KktWorkspace<T, const N: usize> {
    matrix: [[T; N]; N],
    rhs: [T; N],
}

impl<T: Real, const N: usize> KktWorkspace<T, N> {
    /// A zeroed workspace.
    pub fn new() -> Self {
        KktWorkspace { matrix: [[T::ZERO; N]; N], rhs: [T::ZERO; N] }
    }
}

impl<T: Real, const N: usize> Default for KktWorkspace<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

/// Newton–Raphson static-equilibrium solver.
#[derive(Clone, Copy, Debug, Default)]
pub struct StaticSolver {
    /// Tolerances and iteration cap.
    pub options: StaticOptions,
}

/// Name of row `i` of the stacked system: a velocity (force balance) or a constraint.
fn row_name<M: Mechanism>(i: usize, nv: usize) -> &'static str {
    if i < nv {
        name(M::VELOCITY_NAMES, i)
    } else {
        name(M::CONSTRAINT_NAMES, i - nv)
    }
}

impl StaticSolver {
    /// A solver with the given options.
    pub const fn new(options: StaticOptions) -> Self {
        StaticSolver { options }
    }

    /// Finds q and λ with h(q, 0, t) + Dᵀλ = 0 and Φ(q, t) = 0, starting from `q` (and `lambda`,
    /// for example zeros). On success `q` and `lambda` hold the equilibrium and the number of
    /// iterations is returned; the joint reactions follow from λ with [`crate::joint_reaction`].
    pub fn solve<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        q: &mut [T; NQ],
        t: T,
        lambda: &mut [T; NC],
        ws: &mut KktWorkspace<T, N>,
    ) -> Result<u32, StaticError>
    where
        T: Real,
        M: Dynamics<T, NQ, NV, NC> + ConstraintForces<T, NQ, NV, NC>,
    {
        if N != NV + NC {
            return Err(StaticError::WorkspaceSize { expected: NV + NC, found: N });
        }
        let time = t.to_f64();
        let v = [T::ZERO; NV];
        let (mut h, mut phi) = ([T::ZERO; NV], [T::ZERO; NC]);
        let mut d = [[T::ZERO; NV]; NC];
        let (mut hq, mut k) = ([[T::ZERO; NV]; NV], [[T::ZERO; NV]; NV]);
        let mut step = [T::ZERO; NV];
        let tol = T::from_f64(self.options.tolerance);
        let mut worst = (T::ZERO, 0usize);
        for iteration in 0..=self.options.max_iterations {
            if let Some(i) = first_non_finite(q) {
                return Err(StaticError::NonFinite { t: time, row: name(M::COORDINATE_NAMES, i) });
            }
            m.forces(q, &v, t, &mut h);
            m.position_eval(q, t, &mut phi, &mut d);
            // Residual r = [h + Dᵀλ; Φ], stored negated as the Newton right-hand side.
            for (kv, hk) in h.iter().enumerate() {
                let mut f = *hk;
                for (r, row) in d.iter().enumerate() {
                    f += row[kv] * lambda[r];
                }
                ws.rhs[kv] = -f;
            }
            for (r, p) in phi.iter().enumerate() {
                ws.rhs[NV + r] = -*p;
            }
            if let Some(i) = first_non_finite(&ws.rhs) {
                return Err(StaticError::NonFinite { t: time, row: row_name::<M>(i, NV) });
            }
            worst = ws.rhs.iter().enumerate().fold((T::ZERO, 0), |(b, at), (i, v)| if v.abs() > b { (v.abs(), i) } else { (b, at) });
            if worst.0 <= tol {
                return Ok(iteration);
            }
            if iteration == self.options.max_iterations {
                break;
            }
            // J = [[(∂h/∂q)B + K, Dᵀ], [D, 0]]
            m.forces_q(q, &v, t, &mut hq);
            m.constraint_force_q(q, t, lambda, &mut k);
            for row in ws.matrix.iter_mut() {
                *row = [T::ZERO; N];
            }
            for a in 0..NV {
                for b in 0..NV {
                    ws.matrix[a][b] = hq[a][b] + k[a][b];
                }
            }
            for (r, row) in d.iter().enumerate() {
                for (c, &value) in row.iter().enumerate() {
                    ws.matrix[c][NV + r] = value;
                    ws.matrix[NV + r][c] = value;
                }
            }
            let permutation = lu_factor(&mut ws.matrix, T::from_f64(self.options.pivot_tolerance)).map_err(|e| match e {
                LinalgError::Singular { column, .. } => StaticError::Singular { t: time, row: row_name::<M>(column, NV) },
                LinalgError::NonFinite { row, .. } => StaticError::NonFinite { t: time, row: row_name::<M>(row, NV) },
                LinalgError::NotSquare { .. } | LinalgError::Overdetermined { .. } => {
                    StaticError::WorkspaceSize { expected: NV + NC, found: N }
                }
            })?;
            lu_solve_in_place(&ws.matrix, &permutation, &mut ws.rhs);
            step.copy_from_slice(&ws.rhs[..NV]);
            m.integrate_positions(q, &step, T::ONE);
            for (r, l) in lambda.iter_mut().enumerate() {
                *l += ws.rhs[NV + r];
            }
        }
        Err(StaticError::NotConverged {
            t: time,
            iterations: self.options.max_iterations,
            worst_row: row_name::<M>(worst.1, NV),
            residual: worst.0.to_f64(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{UnitPendulum, GRAVITY, LENGTH, MASS};

    /// NQ ≠ NV: Newton on (h + Dᵀλ = 0, Φ = 0) in velocity space, with q updated through
    /// `integrate_positions`, hangs the unit-complex pendulum straight down from a guess off the
    /// unit circle: q = (0, −L, 0, −1), the pin carrying the weight, λ = (0, m g). Newton's
    /// residual tolerance 1e-9 leaves q within about 1e-9 / (m g L) ≈ 1e-10. (From λ = 0 the
    /// pendulum has no stiffness at all — gravity's enters through K(λ) — so λ starts near the
    /// weight.)
    #[test]
    fn velocity_space_newton_finds_the_hanging_pendulum() {
        let mut q = [0.2, -0.4, 0.4, -0.95];
        let mut lambda = [0.0, 15.0];
        let iterations = StaticSolver::default().solve(&UnitPendulum, &mut q, 0.0, &mut lambda, &mut KktWorkspace::<f64, 5>::new());
        assert!(iterations.expect("equilibrium") < 20);
        let expected = [0.0, -LENGTH, 0.0, -1.0];
        for (x, e) in q.iter().zip(expected) {
            assert!((x - e).abs() < 1e-9, "q = {q:?}");
        }
        assert!((q[2].hypot(q[3]) - 1.0).abs() < 1e-15, "{q:?}");
        assert!(lambda[0].abs() < 1e-9 && (lambda[1] - MASS * GRAVITY).abs() < 1e-9, "λ = {lambda:?}");
        // A work space of NQ + NC rows is the wrong size: it takes NV + NC.
        let err = StaticSolver::default().solve(&UnitPendulum, &mut q, 0.0, &mut lambda, &mut KktWorkspace::<f64, 6>::new());
        assert_eq!(err, Err(StaticError::WorkspaceSize { expected: 5, found: 6 }));
    }
}

//! What the static solver returns: the stability verdict, the report and the errors, each
//! error naming the element, velocity or row where it arose.

use super::iterate::Mode;
#[cfg(doc)]
use super::{StaticOptions, StaticSolver};
use crate::linalg::LinalgError;
use crate::model::mechanism::Mechanism;
use crate::real::Real;
use crate::solvers::kinematics::name;
use core::fmt;

/// Whether an equilibrium is stable, from the lowest eigenvalue of the reduced stiffness −Zᵀ H Z
/// against the reduced mass Zᵀ M Z (Z a basis of the motions the joints allow): the squared
/// natural frequencies ω² (1/s²) of small oscillations about the equilibrium. A mode is
/// neutral when |ω²| ≤ [`StaticOptions::neutral_tolerance`] · s, s the largest of |ω²|,
/// |H_ij| / √(M_ii M_jj) and the inverse iteration's shift. The verdict assumes a symmetric
/// stiffness (conservative loads); for non-conservative ones (follower forces) it is that of
/// the lowest real mode of the non-symmetric −H and says nothing about flutter.
///
/// A mode is named by the velocity that carries the largest share of its kinetic energy
/// (the largest |z_i| √M_ii), from [`Mechanism::VELOCITY_NAMES`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Stability {
    /// Every motion the joints allow raises the energy: all ω² above the neutral band.
    Stable {
        /// The lowest ω² (1/s²).
        omega_squared: f64,
    },
    /// No motion is free (DOF = 0): the joints and drivers fix the configuration, and the
    /// multipliers are the loads the drivers hold it with. Nothing to be stable or unstable.
    Determined,
    /// No mode lowers the energy, but at least one leaves it unchanged to second order (a rod
    /// free to turn without gravity): an equilibrium, not a unique one.
    Neutral {
        /// The velocity that carries the neutral mode.
        direction: &'static str,
        /// Its ω² (1/s²), within the neutral band.
        omega_squared: f64,
    },
    /// Some motion lowers the energy (an upright pendulum): the mechanism falls away from here.
    Unstable {
        /// The velocity that carries the most unstable mode.
        direction: &'static str,
        /// Its ω² (1/s²), negative: the mode grows as e^{√(−ω²) t}.
        omega_squared: f64,
    },
}

/// What [`StaticSolver::solve`] found.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct StaticReport {
    /// Accepted steps (0 when the assembled start was already an equilibrium).
    pub iterations: u32,
    /// Trial steps rejected by the energy test (or whose restoration onto Φ = 0 failed).
    pub rejected: u32,
    /// max(‖h + Dᵀλ‖∞, ‖Φ‖∞) at the returned q (N, N·m; m, rad).
    pub residual: f64,
    /// Whether the equilibrium is stable.
    pub stability: Stability,
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
    /// The workspace's Newton slots do not have the mechanism's `NEWTON_STORAGE` scalars (a
    /// `Workspace` made by hand with another NS; `Name::workspace()` has the right one).
    NewtonSlotSize {
        /// Scalars the mechanism's planned Newton matrix needs.
        expected: usize,
        /// Scalars each slot of the workspace has (NS).
        found: usize,
    },
    /// The starting q could not be assembled onto Φ = 0.
    NotAssembled {
        /// Time (s).
        t: f64,
        /// Assembly iterations made.
        iterations: u32,
        /// The constraint row with the largest |Φ|.
        worst_row: &'static str,
        /// Its value (m, rad).
        residual: f64,
    },
    /// No equilibrium within the iterations; the worst residual is a force row (a velocity) or
    /// a constraint. A force that no stiffness balances (a free body under a constant load)
    /// ends here too.
    NotConverged {
        /// Time (s).
        t: f64,
        /// Trial steps made.
        iterations: u32,
        /// The row with the largest residual.
        worst_row: &'static str,
        /// Its value.
        residual: f64,
    },
    /// [[M, Dᵀ], [D, 0]] has no pivot: a velocity without mass, constraint rows nearly but not
    /// quite dependent (sine of their angle above [`StaticOptions::rank_tolerance`] yet below
    /// the pivot tolerance), or a singular start pose that cannot be assembled (links lying
    /// collinear, e.g. every angle 0 where `at:` was left out: the row named depends on the
    /// others there and is not met). Consistent redundant rows and singular poses met on the
    /// way are not this error: their dependent rows are dropped.
    Singular {
        /// Time (s).
        t: f64,
        /// The velocity or constraint row without a pivot.
        row: &'static str,
    },
    /// A force element gives a NaN or infinite generalized force (or stiffness) at the iterate:
    /// a law undefined there (a square root of a negative stretch, a division by a zero
    /// length).
    NonFiniteForce {
        /// Time (s).
        t: f64,
        /// The first force element (declaration order, gravity first) reaching that velocity,
        /// from [`crate::Mechanism::FORCE_ELEMENTS`].
        element: &'static str,
        /// How many other elements reach it too (0: `element` is the one).
        others: u16,
        /// The velocity whose generalized force or stiffness is not finite.
        velocity: &'static str,
    },
    /// NaN or infinity in t, the state, the forces, the constraints or their derivatives.
    NonFinite {
        /// Time (s).
        t: f64,
        /// The row where it appeared: `"t"`, a coordinate, a velocity (forces, stiffness) or a
        /// constraint.
        row: &'static str,
    },
    /// A body's mass or inertia, as the parameters make it, is not positive
    /// ([`crate::Dynamics::check_inertia`]): its weight and the stability verdict mean nothing.
    NonPositiveMass {
        /// The body, from [`crate::Mechanism::BODY_NAMES`].
        body: &'static str,
        /// The offending mass (kg) or moment of inertia (kg·m²; spatial: J′'s smallest
        /// principal moment).
        value: f64,
    },
}

impl fmt::Display for StaticError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StaticError::WorkspaceSize { expected, found } => {
                write!(f, "static equilibrium: the workspace has {found} rows but the mechanism needs NV + NC = {expected}; use Name::workspace()")
            }
            StaticError::NewtonSlotSize { expected, found } => write!(
                f,
                "static equilibrium: the workspace's Newton slots hold {found} scalars but the mechanism needs NEWTON_STORAGE = {expected}; use Name::workspace()"
            ),
            StaticError::NotAssembled { t, iterations, worst_row, residual } => write!(
                f,
                "static equilibrium at t = {t} s: the start does not assemble after {iterations} iterations: |Φ| = {residual:.3e} in '{worst_row}'"
            ),
            StaticError::NotConverged { t, iterations, worst_row, residual } => write!(
                f,
                "static equilibrium not found at t = {t} s after {iterations} iterations: worst residual {residual:.3e} in '{worst_row}'"
            ),
            StaticError::Singular { t, row } => {
                write!(f, "static equilibrium at t = {t} s: no pivot for '{row}' (a singular start pose such as collinear links — give `at:` angles near the equilibrium —, a velocity without mass, or constraint rows nearly but not quite dependent)")
            }
            StaticError::NonFiniteForce { t, element, others: 0, velocity } => {
                write!(f, "static equilibrium at t = {t} s: the force element `{element}` gives a NaN or infinite force on `{velocity}`")
            }
            StaticError::NonFiniteForce { t, element, others, velocity } => write!(
                f,
                "static equilibrium at t = {t} s: NaN or infinite force on `{velocity}`, from `{element}` or one of {others} other elements acting there"
            ),
            StaticError::NonFinite { t, row } => write!(f, "static equilibrium at t = {t} s: non-finite value in '{row}'"),
            StaticError::NonPositiveMass { body, value } => {
                write!(f, "static equilibrium: body `{body}` has a mass or moment of inertia of {value}: it must be positive")
            }
        }
    }
}

impl core::error::Error for StaticError {}

/// A non-finite generalized force or stiffness at velocity `i`: named by the force element that
/// reaches it (else by the velocity: the constraint stiffness K(λ) or a gyroscopic term).
pub(super) fn non_finite_force<M: Mechanism>(t: f64, i: usize) -> StaticError {
    let velocity = name(M::VELOCITY_NAMES, i);
    match crate::model::dynamics::force_element::<M>(i) {
        Some((element, others)) => StaticError::NonFiniteForce { t, element, others, velocity },
        None => StaticError::NonFinite { t, row: velocity },
    }
}

/// A failed factorization as the solver reports it: a velocity without pivot, or the row
/// (velocity: its force or stiffness; constraint: Φ or D) where a NaN appeared.
pub(super) fn factor_error<M: Mechanism>(t: f64, nv: usize, e: LinalgError) -> StaticError {
    match e {
        LinalgError::Singular { column, .. } if column < nv => StaticError::Singular { t, row: name(M::VELOCITY_NAMES, column) },
        LinalgError::Singular { column, .. } => StaticError::Singular { t, row: name(M::CONSTRAINT_NAMES, column - nv) },
        LinalgError::NonFinite { row, .. } if row < nv => non_finite_force::<M>(t, row),
        LinalgError::NonFinite { row, .. } => StaticError::NonFinite { t, row: name(M::CONSTRAINT_NAMES, row - nv) },
        LinalgError::NotSquare { .. } | LinalgError::Overdetermined { .. } => StaticError::NonFinite { t, row: "t" },
    }
}

/// The stability verdict from the lowest mode (`None`: no motion is free, DOF = 0); `neutral`
/// gives the half-width of the neutral band about its ω².
pub(super) fn classify<T: Real, M: Mechanism, const NV: usize>(
    mode: Option<&Mode<'_, T, NV>>,
    mass_diagonal: &[T; NV],
    neutral: impl Fn(&Mode<'_, T, NV>) -> T,
) -> Stability {
    let Some(mode) = mode else {
        return Stability::Determined;
    };
    let w = mode.omega_squared;
    let direction = {
        // The largest entry of the mass-weighted shape (the first among equals, as `max_abs`).
        let weighted = |i: usize| (mode.shape[i] * mass_diagonal[i].abs().sqrt()).abs();
        let largest = (0..NV).fold((T::ZERO, 0), |(best, at), i| if weighted(i) > best { (weighted(i), i) } else { (best, at) });
        name(M::VELOCITY_NAMES, largest.1)
    };
    let band = neutral(mode);
    if w < -band {
        Stability::Unstable { direction, omega_squared: w.to_f64() }
    } else if w <= band {
        Stability::Neutral { direction, omega_squared: w.to_f64() }
    } else {
        Stability::Stable { omega_squared: w.to_f64() }
    }
}

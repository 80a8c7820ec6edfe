//! Why a kinematic analysis failed, in the mechanism's own words: every error names the
//! constraint row and/or coordinate or velocity involved (from [`Mechanism::CONSTRAINT_NAMES`],
//! [`Mechanism::COORDINATE_NAMES`] and [`Mechanism::VELOCITY_NAMES`]; planar velocities are named
//! as their coordinates) and the time at which it happened.
//!
//! [`Mechanism::CONSTRAINT_NAMES`]: crate::Mechanism::CONSTRAINT_NAMES
//! [`Mechanism::COORDINATE_NAMES`]: crate::Mechanism::COORDINATE_NAMES
//! [`Mechanism::VELOCITY_NAMES`]: crate::Mechanism::VELOCITY_NAMES

use core::fmt;

/// Which quantity held a NaN or an infinity (see [`KinematicError::NonFinite`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum NonFiniteQuantity {
    /// The time t given to the solver (s).
    Time,
    /// A coordinate of q: given to the solver, or predicted from the previous point of a sweep
    /// (m or rad). The row is a coordinate name.
    Coordinate,
    /// A velocity of v: given to the solver, or computed by it (m/s or rad/s). The row is a
    /// velocity name.
    Velocity,
    /// A computed acceleration of v̇ (m/s² or rad/s²). The row is a velocity name.
    Acceleration,
    /// A constraint value Φ evaluated by the mechanism. The row is a constraint name.
    Constraint,
    /// An entry of the Jacobian D evaluated by the mechanism. The row is a constraint name.
    Jacobian,
    /// The velocity right-hand side ν = −Φ_t. The row is a constraint name.
    VelocityRhs,
    /// The acceleration right-hand side γ. The row is a constraint name.
    Gamma,
    /// A Newton correction Δv (overflow of a nearly singular solve). The row is a velocity name.
    Step,
    /// A Lagrange multiplier λ given to the solver (N or N·m). The row is a constraint name.
    Multiplier,
}

impl fmt::Display for NonFiniteQuantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            NonFiniteQuantity::Time => "time t",
            NonFiniteQuantity::Coordinate => "coordinate",
            NonFiniteQuantity::Velocity => "velocity",
            NonFiniteQuantity::Acceleration => "acceleration",
            NonFiniteQuantity::Constraint => "constraint Φ",
            NonFiniteQuantity::Jacobian => "Jacobian D, row",
            NonFiniteQuantity::VelocityRhs => "velocity right-hand side ν = −Φ_t, row",
            NonFiniteQuantity::Gamma => "acceleration right-hand side γ, row",
            NonFiniteQuantity::Step => "Newton step Δv, velocity",
            NonFiniteQuantity::Multiplier => "multiplier λ, row",
        })
    }
}

/// A failed kinematic analysis. Times are in s; residuals in the units of the constraint row
/// (m, rad, or m² for distance rows).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum KinematicError {
    /// Newton–Raphson on Φ(q, t) = 0 did not reach ‖Φ‖∞ ≤ tolerance within the allowed
    /// iterations (a guess too far from a solution, a tolerance below what the scalar type can
    /// resolve, or no solution: a mechanism that cannot assemble at t).
    NotConverged {
        /// Time of the failed solve (s).
        t: f64,
        /// Newton iterations performed.
        iterations: u32,
        /// The constraint row with the largest |Φ| after the last iteration.
        worst_row: &'static str,
        /// That |Φ|: ‖Φ‖∞ after the last iteration.
        residual: f64,
    },
    /// The square Jacobian D = Φ_q B has no acceptable pivot for a velocity (planar: a
    /// coordinate): at this configuration the constraints do not determine that velocity
    /// independently of the ones eliminated before it (a lock-up or toggle position, a missing driver, or redundant
    /// constraints). From [`KinematicSolver::analyze`](crate::KinematicSolver::analyze) and
    /// `sweep`, also where the position solved lies next to such a position as far as the
    /// position tolerance tells: the velocity is then not determined, and a smaller tolerance
    /// resolves positions closer to it.
    SingularJacobian {
        /// Time of the failed solve (s).
        t: f64,
        /// The velocity whose column of D had no acceptable pivot, from
        /// [`Mechanism::VELOCITY_NAMES`](crate::Mechanism::VELOCITY_NAMES) (planar: the
        /// coordinate).
        coordinate: &'static str,
        /// The constraint row that held the best (largest) candidate pivot for it; from an
        /// analysis's check next to a singular position, the row that bends most along the
        /// direction left undetermined.
        constraint: &'static str,
    },
    /// A kinematic analysis (position, velocity, acceleration) needs at least as many constraint
    /// rows, drivers included, as velocities (planar: coordinates): degrees of freedom
    /// DOF = NV − NC ≤ 0 (below 0 only with redundant rows).
    NotDriven {
        /// Velocities minus constraint rows: > 0 lacks drivers, < 0 has redundant rows.
        dof: i32,
    },
    /// A NaN or an infinity in the input or in an evaluated quantity: the solver stops instead
    /// of iterating on it.
    NonFinite {
        /// Time of the failed solve (s); itself NaN or infinite for [`NonFiniteQuantity::Time`].
        t: f64,
        /// What held the value.
        quantity: NonFiniteQuantity,
        /// The constraint row, coordinate or velocity name (see [`NonFiniteQuantity`]); `"t"`
        /// for the time.
        row: &'static str,
    },
}

impl fmt::Display for KinematicError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            KinematicError::NotConverged { t, iterations, worst_row, residual } => write!(
                f,
                "position solve did not converge at t = {t} s after {iterations} iterations: \
                 worst constraint '{worst_row}' |Φ| = {residual:.1e}"
            ),
            KinematicError::SingularJacobian { t, coordinate, constraint } => write!(
                f,
                "singular constraint Jacobian at t = {t} s: no usable pivot for coordinate \
                 '{coordinate}' (best candidate: constraint '{constraint}'); the mechanism is at a \
                 lock-up or toggle position (or next to one, as far as the position tolerance \
                 tells), or its constraints and drivers do not determine '{coordinate}'"
            ),
            KinematicError::NotDriven { dof } if dof > 0 => write!(
                f,
                "kinematic analysis needs as many constraints (drivers included) as coordinates, \
                 but the mechanism has {dof} degree(s) of freedom left: add {dof} driver(s)"
            ),
            KinematicError::NotDriven { dof } => write!(
                f,
                "this solve needs a square constraint Jacobian, but the mechanism has {} more \
                 constraint row(s) than coordinates (DOF = {dof}); the position, velocity and \
                 acceleration solves take redundant rows over their independent subset",
                dof.unsigned_abs()
            ),
            KinematicError::NonFinite { t, quantity: NonFiniteQuantity::Time, .. } => {
                write!(f, "non-finite time t = {t} s given to the kinematic solver")
            }
            KinematicError::NonFinite { t, quantity, row } => {
                write!(f, "non-finite value (NaN or ±∞) in {quantity} '{row}' at t = {t} s")
            }
        }
    }
}

/// `core::error::Error` is the trait `std::error::Error` re-exports, so this implements
/// `std::error::Error` with the `std` feature and still builds without it.
impl core::error::Error for KinematicError {}

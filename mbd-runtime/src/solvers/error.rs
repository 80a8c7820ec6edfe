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
    /// The constraints cannot all hold at t, as far as a descent from the guess can tell: after
    /// Newton failed, a Levenberg–Marquardt descent on ½‖Φ‖² stopped where no step lowers it,
    /// with ‖Φ‖∞ = `residual` above the tolerance — a loop that cannot close (a link too short
    /// to reach, a driver beyond a limit position) or a guess in the basin of such a local
    /// minimum. `rows` are the constraint rows left violated there: the loop that does not
    /// close (in joint coordinates, the rows of its cut joint), not the rows of loops that do.
    /// From [`KinematicSolver::assemble`](crate::KinematicSolver::assemble) `q` is left at that
    /// closest configuration; from the solves of a driven mechanism it is their last iterate.
    CannotAssemble {
        /// Time of the failed solve (s).
        t: f64,
        /// The smallest ‖Φ‖∞ the descent reached (m, rad, or m² for distance rows).
        residual: f64,
        /// The rows with |Φ| of at least a hundredth of `residual` there, largest first.
        rows: ConstraintRows,
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
            KinematicError::CannotAssemble { t, residual, rows } => write!(
                f,
                "the mechanism cannot assemble at t = {t} s: its constraints cannot all hold near \
                 the guess; the smallest ‖Φ‖∞ reached is {residual:.3e}, on {rows}: check the \
                 lengths and positions of the joints in that loop (or start from a guess nearer \
                 the wanted assembly)"
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

/// Constraint rows named by a [`KinematicError::CannotAssemble`]: the first
/// [`ConstraintRows::CAPACITY`] by name, and how many more. `Copy` and without allocation, so
/// that errors stay `no_std` (the names are the mechanism's `CONSTRAINT_NAMES`, by index).
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct ConstraintRows {
    all: &'static [&'static str],
    indices: [u16; ConstraintRows::CAPACITY],
    count: u16,
    total: u16,
}

impl ConstraintRows {
    /// How many rows are kept by name.
    pub const CAPACITY: usize = 8;

    /// The rows `indices` of `names` (`Mechanism::CONSTRAINT_NAMES`), in the order given.
    pub(crate) fn new(names: &'static [&'static str], indices: impl Iterator<Item = usize>) -> Self {
        let mut rows = ConstraintRows { all: names, indices: [0; Self::CAPACITY], count: 0, total: 0 };
        for index in indices.filter(|&i| i < names.len()) {
            if usize::from(rows.count) < Self::CAPACITY {
                rows.indices[usize::from(rows.count)] = index as u16;
                rows.count += 1;
            }
            rows.total = rows.total.saturating_add(1);
        }
        rows
    }

    /// The rows kept by name, in order.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.indices[..usize::from(self.count)].iter().map(|&i| self.all[usize::from(i)])
    }

    /// How many rows there are, named or not.
    pub fn len(&self) -> usize {
        usize::from(self.total)
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.total == 0
    }
}

/// The named rows and how many there are, not the mechanism's whole table of row names (a
/// 110-link bridge's error printed 222 of them).
impl fmt::Debug for ConstraintRows {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        struct Names<'a>(&'a ConstraintRows);
        impl fmt::Debug for Names<'_> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_list().entries(self.0.names()).finish()
            }
        }
        f.debug_struct("ConstraintRows").field("names", &Names(self)).field("total", &self.total).finish()
    }
}

impl fmt::Display for ConstraintRows {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(if self.total == 1 { "the row " } else { "the rows " })?;
        for (k, name) in self.names().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            write!(f, "'{name}'")?;
        }
        if self.total > self.count {
            write!(f, " and {} more", self.total - self.count)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `CannotAssemble`'s rows print as the rows it names and their count, in `{:?}` as in
    /// `{}`: not the mechanism's whole table of row names.
    #[test]
    fn constraint_rows_print_only_their_rows() {
        const NAMES: &[&str] = &["pin: x", "pin: y", "slot: n", "rod: length", "drive: phi"];
        let rows = ConstraintRows::new(NAMES, [3, 0].into_iter());
        assert_eq!(format!("{rows:?}"), r#"ConstraintRows { names: ["rod: length", "pin: x"], total: 2 }"#);
        assert_eq!(rows.to_string(), "the rows 'rod: length', 'pin: x'");
    }
}

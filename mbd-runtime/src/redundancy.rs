//! Redundant constraints and the true mobility of a configuration: which constraint rows of
//! D = Φ_q B depend on the rows before them, found by a rank-revealing orthogonalization.
//!
//! Grübler's count, NV − NC, is the mobility only when the NC rows of D are independent. A
//! parallelogram with a third parallel crank counts 0 but moves with one degree of freedom: one
//! of its rows repeats what the others already impose. At a singular position (a four-bar
//! lying flat) a row becomes dependent for that configuration only, and the mechanism has one
//! instantaneous mobility more than Grübler says.
//!
//! The rows are taken in declaration order and each is orthogonalized against the independent
//! rows before it (modified Gram–Schmidt, twice, which keeps the basis orthonormal to rounding);
//! the row is **redundant** when what is left of it is at most
//! [`KinematicOptions::rank_tolerance`] of its own length, i.e. when the sine of its angle to
//! the span of the rows before it is below that tolerance (default
//! [`DEFAULT_RANK_TOLERANCE`] = 1e-8). So the row named is the later-declared one, as in
//! [`KinematicError::DependentConstraint`]. Angles are measured in velocity space with m/s and
//! rad/s weighted alike. The report also gives the margins of that decision: the smallest sine
//! among the rows kept and the largest among the rows named, so a user can see whether a
//! configuration is near singular (a gap of a few orders of magnitude is clear-cut).
//!
//! Cost: NC² NV multiply-adds, in the caller's [`Workspace`]; nothing allocates.
//!
//! [`KinematicOptions::rank_tolerance`]: crate::KinematicOptions::rank_tolerance
//! [`DEFAULT_RANK_TOLERANCE`]: crate::DEFAULT_RANK_TOLERANCE
//! [`KinematicError::DependentConstraint`]: crate::KinematicError::DependentConstraint

use crate::error::NonFiniteQuantity;
use crate::kinematics::{check_finite, check_time};
use crate::{KinematicError, KinematicSolver, Kinematics, Real, Workspace};
use core::fmt;

/// Which constraint rows are redundant at a configuration, and the mobility that follows: the
/// result of [`KinematicSolver::redundancy`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Redundancy<const NC: usize> {
    /// Independent constraint rows: the rank of D.
    pub rank: usize,
    /// Grübler's count NV − NC (may be negative).
    pub grubler: i32,
    /// The mobility at this configuration, NV − rank.
    pub mobility: i32,
    /// The smallest sine of a kept row's angle to the rows before it (1 when none was kept):
    /// how close the rows kept came to being called redundant.
    pub smallest_kept: f64,
    /// The largest such sine among the redundant rows (0 when none): how close a redundant row
    /// came to being kept.
    pub largest_redundant: f64,
    redundant: [bool; NC],
    names: &'static [&'static str],
}

impl<const NC: usize> Redundancy<NC> {
    /// Whether constraint row `row` (an index into [`Mechanism::CONSTRAINT_NAMES`]) is redundant.
    ///
    /// [`Mechanism::CONSTRAINT_NAMES`]: crate::Mechanism::CONSTRAINT_NAMES
    pub fn is_redundant(&self, row: usize) -> bool {
        self.redundant.get(row).copied().unwrap_or(false)
    }

    /// The redundant rows by index, in declaration order.
    pub fn redundant_rows(&self) -> impl Iterator<Item = usize> + '_ {
        (0..NC).filter(|&r| self.redundant[r])
    }

    /// The redundant rows by name (`"revolute c3~coupler: y"`), in declaration order.
    pub fn redundant_names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.redundant_rows().map(|r| self.names.get(r).copied().unwrap_or("<unnamed>"))
    }
}

impl<const NC: usize> fmt::Display for Redundancy<NC> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let redundant = NC - self.rank;
        write!(f, "Grübler's count {}, mobility {} (rank {} of {NC} rows)", self.grubler, self.mobility, self.rank)?;
        if redundant == 0 {
            return write!(f, ": no redundant row (smallest sine kept {:.1e})", self.smallest_kept);
        }
        write!(f, "; {redundant} redundant row{}:", if redundant == 1 { "" } else { "s" })?;
        for (k, name) in self.redundant_names().enumerate() {
            write!(f, "{} '{name}'", if k == 0 { "" } else { "," })?;
        }
        write!(f, " (largest sine among them {:.1e}, smallest kept {:.1e})", self.largest_redundant, self.smallest_kept)
    }
}

impl KinematicSolver {
    /// Which constraint rows are redundant at (q, t) and the mobility NV − rank that follows,
    /// next to Grübler's count NV − NC (the algorithm: [the `redundancy` module](crate::redundancy)).
    /// `q` need not satisfy the constraints exactly, but the answer is about the configuration
    /// q: assemble first.
    ///
    /// # Errors
    /// [`KinematicError::NonFinite`] for a NaN or infinite t, q or D.
    pub fn redundancy<T, M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
        &self,
        m: &M,
        ws: &mut Workspace<T, NV, NC, N>,
        q: &[T; NQ],
        t: T,
    ) -> Result<Redundancy<NC>, KinematicError>
    where
        T: Real,
        M: Kinematics<T, NQ, NV, NC>,
    {
        check_time(t)?;
        check_finite(q, t, NonFiniteQuantity::Coordinate, M::COORDINATE_NAMES)?;
        let Workspace { jacobian: d, jacobian_scratch: basis, .. } = ws;
        m.jacobian(q, t, d);
        for row in d.iter() {
            check_finite(row, t, NonFiniteQuantity::Jacobian, M::CONSTRAINT_NAMES)?;
        }
        let tolerance = T::from_f64(self.options.rank_tolerance);
        let mut report = Redundancy {
            rank: 0,
            grubler: NV as i32 - NC as i32,
            mobility: NV as i32,
            smallest_kept: 1.0,
            largest_redundant: 0.0,
            redundant: [false; NC],
            names: M::CONSTRAINT_NAMES,
        };
        for (r, row) in d.iter().enumerate() {
            let length = norm(row);
            let mut w = *row;
            // Two passes of modified Gram–Schmidt: the second removes what rounding left of the
            // first ("twice is enough", Giraud et al. 2005).
            for _ in 0..2 {
                for b in basis.iter().take(report.rank) {
                    let c = dot(b, &w);
                    for (wi, &bi) in w.iter_mut().zip(b.iter()) {
                        *wi -= c * bi;
                    }
                }
            }
            let left = norm(&w);
            let sine = if length > T::ZERO { left / length } else { T::ZERO };
            if sine > tolerance {
                for (bi, &wi) in basis[report.rank].iter_mut().zip(w.iter()) {
                    *bi = wi / left;
                }
                report.rank += 1;
                report.smallest_kept = report.smallest_kept.min(sine.to_f64());
            } else {
                report.redundant[r] = true;
                report.largest_redundant = report.largest_redundant.max(sine.to_f64());
            }
        }
        report.mobility = NV as i32 - report.rank as i32;
        Ok(report)
    }
}

fn dot<T: Real, const N: usize>(a: &[T; N], b: &[T; N]) -> T {
    a.iter().zip(b.iter()).fold(T::ZERO, |s, (&x, &y)| s + x * y)
}

fn norm<T: Real, const N: usize>(a: &[T; N]) -> T {
    dot(a, a).sqrt()
}

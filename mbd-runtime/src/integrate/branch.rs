//! Where a run may have changed assembly branch (issue 39, item 7). At a singular position —
//! a parallelogram lying flat — two branches of Φ = 0 cross. The projection (the default
//! correction), partitioning and generalized-α each solve Φ = 0 by Newton from the step's
//! prediction and stay on the branch the step left; Baumgarte stabilization alone pulls the
//! state towards whichever branch is nearer, and takes a spinning parallelogram chain onto the
//! crossing one (measured on 4 loops, `mbd-long/tests/singular.rs`: with DOPRI5 at every rtol
//! from 1e-6 to 1e-12 and RK4 at 1 and 10 ms; the others kept the branch to 1e-9 rad). Such a
//! run is not refused — it is right wherever it keeps its branch, and Baumgarte-only runs are
//! a choice for speed — but it says where it passed a singular position, in
//! [`Statistics::singular`](super::Statistics::singular).
//!
//! A step end is near a singular position when a row of D has a sine below
//! [`SINGULAR_SINE`] to the span of the rows before it, as the forward-dynamics factorization
//! measures it (in the metric of M⁻¹: its pivot d_k ≤ sine² S_kk, by
//! [`ForwardDynamics::project_velocities`] on a copy of v with `allow_redundant` off): one
//! factorization of D M⁻¹ Dᵀ per step of a watched run, nothing for the others. A passage is
//! an interval of near step ends that begins and ends; a row dependent for the whole run is a
//! redundancy (a Bricard linkage's), not a passage.

use crate::model::dynamics::{DynamicsError, DynamicsOptions, ForwardDynamics};
use crate::real::Real;

/// The sine of a row's angle to the span of the rows before it (in the metric of M⁻¹) below
/// which a step end counts as at a singular position: 0.1. Measured on the 4-loop parallelogram
/// chain without a correction: each time it left its branch, the step end before had a sine of
/// at most 3e-3 (DOPRI5, rtol 1e-8), 1e-2 (rtol 1e-10, 1e-12; RK4 at 1 ms), 3e-2 (rtol 1e-6)
/// and 1e-1 (RK4 at 10 ms).
pub const SINGULAR_SINE: f64 = 0.1;

/// The passages through singular positions of a run that does not hold the assembly branch
/// ([`Correction::None`](super::Correction::None) with an explicit integrator).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SingularPassage {
    /// The first step end (s) of the first passage.
    pub t: f64,
    /// The constraint row that depended on the rows before it there, from
    /// [`Mechanism::CONSTRAINT_NAMES`](crate::Mechanism::CONSTRAINT_NAMES).
    pub row: &'static str,
    /// Passages in the run.
    pub passages: u32,
}

/// The watch over a run's step ends.
pub(super) struct BranchWatch {
    /// The first near step end of the passage under way, and its row.
    near_since: Option<(f64, &'static str)>,
    start: f64,
    seen: Option<SingularPassage>,
}

impl BranchWatch {
    pub(super) fn new(start: f64) -> Self {
        Self { near_since: None, start, seen: None }
    }

    /// Looks at the step end (t, q, v).
    pub(super) fn observe<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
        &mut self,
        mechanism: &M,
        t: T,
        q: &[T; NQ],
        v: &[T; NV],
        options: &DynamicsOptions<T>,
    ) {
        let probe = options.with_allow_redundant(false).with_pivot_tolerance(T::from_f64(SINGULAR_SINE * SINGULAR_SINE));
        let mut v = *v;
        // Any other failure is the run's own solves' to report.
        let near = match mechanism.project_velocities(q, &mut v, t, &probe) {
            Err(DynamicsError::DependentConstraint { row, .. }) => Some(row),
            _ => None,
        };
        match (self.near_since, near) {
            (None, Some(row)) => self.near_since = Some((t.to_f64(), row)),
            (Some((since, row)), None) => {
                self.record(since, row);
                self.near_since = None;
            }
            _ => {}
        }
    }

    /// The passages, the one under way counted unless it began at the start (a redundancy).
    pub(super) fn finish(mut self) -> Option<SingularPassage> {
        if let Some((since, row)) = self.near_since.filter(|&(since, _)| since > self.start) {
            self.record(since, row);
        }
        self.seen
    }

    fn record(&mut self, t: f64, row: &'static str) {
        match &mut self.seen {
            Some(seen) => seen.passages += 1,
            None => self.seen = Some(SingularPassage { t, row, passages: 1 }),
        }
    }
}

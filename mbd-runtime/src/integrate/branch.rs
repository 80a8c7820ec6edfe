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
//! A step end is near a singular position when a row of D has a sine to the span of the rows
//! before it (in the metric of M⁻¹, as the forward-dynamics factorization measures it: the
//! squared sine is its pivot over its diagonal, d_k / S_kk) below [`SINGULAR_SINE`] times the
//! smallest such sine at the best-conditioned step end the run has measured. Relative, because
//! the sines of a mechanism that is nowhere singular shrink with its size: the middle row of a
//! straight chain of 110 links has a sine of 0.09 (d_k / S_kk ≈ 8e-3), against 0.41 on a
//! parallelogram chain away from its flat position. A row the dynamics drops as redundant
//! (d_k ≤ [`DynamicsOptions::pivot_tolerance`] S_kk) is always near.
//!
//! The cost, on watched runs only: one factorization of D M⁻¹ Dᵀ per step end (by
//! [`ForwardDynamics::project_velocities`] on a copy of v with `allow_redundant` off, which
//! fails exactly where a ratio is below its tolerance), and every 32 step ends
//! five more that bisect the smallest ratio to a factor of 2. A passage is an interval of near
//! step ends that begins and ends; a row dependent for the whole run is a redundancy (a Bricard
//! linkage's), not a passage.

use crate::model::dynamics::{DynamicsError, DynamicsOptions, ForwardDynamics};
use crate::model::workspace::DenseScratch;
use crate::real::Real;

/// The smallest sine of a row's angle to the span of the rows before it (in the metric of
/// M⁻¹), relative to the same at the run's best-conditioned step end, below which a step end
/// counts as at a singular position: 0.25. Measured on the 4-loop parallelogram chain without a
/// correction, whose best sine is 0.41: each time it left its branch, the step end before had a
/// sine of at most 3e-3 (DOPRI5, rtol 1e-8), 1e-2 (rtol 1e-10, 1e-12; RK4 at 1 ms), 3e-2 (rtol
/// 1e-6) and 1e-1 (RK4 at 10 ms), all below 0.25 × 0.41 = 0.10.
pub const SINGULAR_SINE: f64 = 0.25;

/// Step ends between two measurements of the smallest pivot ratio (the first is at the start).
const MEASURE_EVERY: u32 = 32;

/// Probes that bisect the smallest pivot ratio, in its exponent between the pivot tolerance and
/// 1 (a factor of 2 for the default 1e-8).
const BISECTIONS: u32 = 5;

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
    /// The largest smallest pivot ratio d_k / S_kk measured so far.
    best: f64,
    /// Step ends observed.
    observed: u32,
}

impl BranchWatch {
    pub(super) fn new(start: f64) -> Self {
        Self { near_since: None, start, seen: None, best: 0.0, observed: 0 }
    }

    /// Looks at the step end (t, q, v).
    pub(super) fn observe<T: Real, M: ForwardDynamics<T, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
        &mut self,
        mechanism: &M,
        mut scratch: DenseScratch<'_, T, NV, NC>,
        t: T,
        q: &[T; NQ],
        v: &[T; NV],
        options: &DynamicsOptions<T>,
    ) {
        // The first row whose ratio is below `tolerance`, if any. Any other failure is the
        // run's own solves' to report.
        let mut below = |tolerance: f64| {
            let probe = options.with_allow_redundant(false).with_pivot_tolerance(T::from_f64(tolerance));
            match mechanism.project_velocities_in(scratch.reborrow(), q, &mut v.clone(), t, &probe) {
                Err(DynamicsError::DependentConstraint { row, .. }) => Some(row),
                _ => None,
            }
        };
        let floor = options.pivot_tolerance.to_f64();
        if self.observed.is_multiple_of(MEASURE_EVERY) && below(floor).is_none() {
            // The smallest ratio r is in [floor, 1]: bisect its exponent.
            let (mut lo, mut hi) = (floor.ln(), 0.0);
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (lo + hi);
                if below(mid.exp()).is_some() {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            self.best = self.best.max(lo.exp());
        }
        self.observed += 1;
        let near = below((SINGULAR_SINE * SINGULAR_SINE * self.best).max(floor));
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

//! Stiffness detection for the explicit Dormand–Prince methods (issue 39, item 2; Hairer &
//! Wanner, *Solving ODEs II*, IV.2, as in their codes DOPRI5 and DOP853). After each accepted
//! step two stages at the same time t + h — the last stage and the solution, whose derivative
//! the next step reuses — give an estimate of the step times the dominant eigenvalue,
//!
//! ```text
//! h|λ| ≈ h ‖f(y₊) − f(y_s)‖ / ‖y₊ − y_s‖
//! ```
//!
//! for free (the stages are computed anyway). Where it sits at the method's stability bound on
//! the negative real axis (3.25 for DOPRI5, 6.1 for DOP853) for 15 accepted steps, with fewer
//! than 6 in a row below it, the step size is set by stability, not by accuracy: the model is
//! stiff, and an implicit method would take far fewer steps. The run's [`Statistics`] say so
//! ([`Statistics::stiffness`]); nothing changes in the integration.
//!
//! [`Statistics`]: super::Statistics
//! [`Statistics::stiffness`]: super::Statistics::stiffness

use core::fmt;

use crate::real::Real;

/// Stiffness seen by an explicit method: from when, at which step size, and the estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StiffnessDetected {
    /// The method that saw it: `"DOPRI5"` or `"DOP853"`.
    pub method: &'static str,
    /// The end of the step at which it was seen (s): the 15th accepted step with h|λ| at the
    /// stability bound.
    pub t: f64,
    /// That step's size (s).
    pub step: f64,
    /// The estimate h|λ| there (the bound: 3.25 for DOPRI5, 6.1 for DOP853); |λ| ≈ h|λ| / step
    /// (1/s) is the fastest mode's rate.
    pub h_lambda: f64,
    /// How many times it was seen in the run (each after 15 steps at the bound).
    pub times: u32,
}

impl fmt::Display for StiffnessDetected {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "from t = {} s {}'s steps ({:.2e} s) were held by stability, not accuracy: a mode of about {:.1e} 1/s \
             makes the model stiff; an implicit method takes steps set by the tolerance \
             (Bdf, or GeneralizedAlpha for a fixed step)",
            self.t,
            self.method,
            self.step,
            self.h_lambda / self.step
        )
    }
}

/// Hairer's counters: steps at the bound, and steps below it since the last one at it.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct StiffnessTest {
    at_bound: u32,
    below: u32,
    found: Option<StiffnessDetected>,
}

impl StiffnessTest {
    /// After an accepted step of size `h` ending at `t`: the derivatives at the solution and at
    /// the last stage (`f1`, `fs`, over q then v) and the two states (`y1`, `ys`).
    // `!(x > y)` on purpose: it is also true when either side is NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    pub(super) fn observe<T: Real>(
        &mut self,
        method: &'static str,
        bound: f64,
        t: T,
        h: T,
        [f1q, f1v, fsq, fsv]: [&[T]; 4],
        [y1q, y1v, ysq, ysv]: [&[T]; 4],
    ) {
        let squares = |a: &[T], b: &[T]| a.iter().zip(b).fold(T::ZERO, |s, (x, y)| s + (*x - *y) * (*x - *y));
        let numerator = squares(f1q, fsq) + squares(f1v, fsv);
        let denominator = squares(y1q, ysq) + squares(y1v, ysv);
        if !(denominator > T::ZERO) {
            return;
        }
        let h_lambda = (h * (numerator / denominator).sqrt()).to_f64();
        if h_lambda > bound {
            self.below = 0;
            self.at_bound += 1;
            if self.at_bound == 15 {
                match &mut self.found {
                    Some(found) => found.times += 1,
                    None => self.found = Some(StiffnessDetected { method, t: t.to_f64(), step: h.to_f64(), h_lambda, times: 1 }),
                }
            }
        } else {
            self.below += 1;
            if self.below == 6 {
                self.at_bound = 0;
            }
        }
    }

    /// Counts afresh, keeping what was seen.
    pub(super) fn watch_again(&mut self) {
        (self.at_bound, self.below) = (0, 0);
    }

    /// What was seen since the integrator was made.
    pub(super) fn found(&self) -> Option<StiffnessDetected> {
        self.found
    }
}

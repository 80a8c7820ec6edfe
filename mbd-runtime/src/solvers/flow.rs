//! [`Flow`]: what an analysis's callback returns to go on or to stop — the kinematic sweep's
//! and the simulation's alike.

use core::ops::ControlFlow;

/// What an output callback of [`Simulation::run`](crate::Simulation::run) returns: `()` (go on), or a [`ControlFlow`] whose
/// `Break` ends the run after the sample it was given — to stop on a condition, at a deadline,
/// or when the user cancels ([`Statistics::stopped_by_output`](crate::Statistics::stopped_by_output)).
pub trait Flow {
    /// Whether the run should end here.
    fn stops(&self) -> bool;
}

impl Flow for () {
    fn stops(&self) -> bool {
        false
    }
}

impl<B, C> Flow for ControlFlow<B, C> {
    fn stops(&self) -> bool {
        self.is_break()
    }
}

//! The rules of Newton's iteration on Φ(q, t) = 0, written once for every position solve: the
//! loop `mechanism!` generates over the sparse factorization it plans
//! (the generated `sparse_position_solve`) and the
//! dense one of [`KinematicSolver`](crate::KinematicSolver). Each keeps its own loop — the
//! generated one evaluates Φ and D in stages that share their subexpressions, which a loop
//! calling them through closures could not — and asks [`Newton`] at each turn what to do:
//! whether Φ has converged, whether the iteration must stop, whether D is evaluated and factored
//! again or its last factors kept (simplified Newton), and how long a step may be.

use crate::linalg::sparse::{limit_step, max_abs_finite};
use crate::model::mechanism::PositionStep;
use crate::real::Real;

/// What a position solve does after Φ(q, t) is evaluated ([`Newton::after_residual`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NewtonNext {
    /// Stop, with what the iteration ended with.
    Stop(PositionStep),
    /// Evaluate D at q and factor it, then tell [`Newton::factored`].
    Factor,
    /// Solve with the factors of D kept from an earlier iterate.
    Reuse,
}

/// Where Newton's iteration on Φ(q, t) = 0 stands, with its rules:
/// - it has converged when ‖Φ‖∞ ≤ `tolerance` (Φ finite);
/// - it stops when Φ is not finite or `max_iterations` steps are taken;
/// - a step expected to end the iteration keeps D and its factors (simplified Newton, the chord
///   method): where ‖Φ‖∞ · (‖Φ‖∞ / ‖Φ‖∞ at the last step) · `reuse` ≤ `tolerance`, the last step's
///   contraction with the safety factor `reuse`; infinite `reuse` factors at every step;
/// - a step that is not finite stops it, and one longer than `max_step` (‖Δv‖∞) is shortened to
///   it along its direction (damped Newton).
#[doc(hidden)]
#[derive(Clone, Copy, Debug)]
pub struct Newton<T> {
    tolerance: T,
    max_iterations: u32,
    reuse: T,
    max_step: T,
    iterations: u32,
    factorizations: u32,
    /// ‖Φ‖∞ where the last step was taken.
    last: T,
}

impl<T: Real> Newton<T> {
    /// A new iteration with its rules (the fields of [`Newton`]).
    #[inline]
    pub fn new(tolerance: T, max_iterations: u32, reuse: T, max_step: T) -> Self {
        Self { tolerance, max_iterations, reuse, max_step, iterations: 0, factorizations: 0, last: T::ZERO }
    }

    /// The same iteration going on after `iterations` steps and `factorizations` of D made
    /// elsewhere (the dense solve where the sparse one stopped): the limit counts them.
    #[inline]
    pub fn resumed(mut self, iterations: u32, factorizations: u32) -> Self {
        (self.iterations, self.factorizations) = (iterations, factorizations);
        self
    }

    /// What to do with Φ(q, t) just evaluated at the current iterate.
    #[inline]
    pub fn after_residual(&mut self, phi: &[T]) -> NewtonNext {
        let (worst, finite) = max_abs_finite(phi);
        if finite && worst <= self.tolerance {
            return NewtonNext::Stop(PositionStep::Converged);
        }
        if !finite || self.iterations >= self.max_iterations {
            return NewtonNext::Stop(PositionStep::Step);
        }
        let keep = self.factorizations > 0 && worst * worst * self.reuse <= self.tolerance * self.last;
        self.last = worst;
        if keep {
            NewtonNext::Reuse
        } else {
            NewtonNext::Factor
        }
    }

    /// D was evaluated and factored.
    #[inline]
    pub fn factored(&mut self) {
        self.factorizations += 1;
    }

    /// The step Δv just solved, before q ← q ⊕ Δv: false where it is not finite (the iteration
    /// stops with [`PositionStep::Step`]); else shortened to `max_step` if longer, and counted.
    #[inline]
    pub fn accept_step(&mut self, step: &mut [T]) -> bool {
        if !step.iter().all(|x| x.is_finite()) {
            return false;
        }
        limit_step(step, self.max_step);
        self.iterations += 1;
        true
    }

    /// `(end, steps taken, factorizations of D)`: what a position solve returns.
    #[inline]
    pub fn end(&self, end: PositionStep) -> (PositionStep, u32, u32) {
        (end, self.iterations, self.factorizations)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Newton's iteration on φ(x) = x² − 2 = 0 from x = 1, with the loop written as the
    /// position solves write it: quadratic convergence to √2, the factors (here φ' = 2x) kept
    /// only for the last step, the step limit, and a NaN residual stopping it.
    #[test]
    fn converges_reuses_the_last_factors_and_limits_its_steps() {
        let solve = |newton: &mut Newton<f64>, x: &mut f64| -> (PositionStep, u32, u32) {
            let mut slope = f64::NAN;
            loop {
                let phi = [*x * *x - 2.0];
                match newton.after_residual(&phi) {
                    NewtonNext::Stop(end) => return newton.end(end),
                    NewtonNext::Factor => {
                        slope = 2.0 * *x;
                        newton.factored();
                    }
                    NewtonNext::Reuse => {}
                }
                let mut step = [-phi[0] / slope];
                if !newton.accept_step(&mut step) {
                    return newton.end(PositionStep::Step);
                }
                *x += step[0];
            }
        };
        let mut x = 1.0;
        let (end, steps, factored) = solve(&mut Newton::new(1e-12, 25, 10.0, 10.0), &mut x);
        assert_eq!(end, PositionStep::Converged);
        assert!((x - 2f64.sqrt()).abs() < 1e-12, "{x}");
        // 1 → 1.5 → 1.41667 → 1.4142157 → 1.41421356237469 → √2: five steps, the last on
        // the fourth's slope (φ = 4.5e-12 with a contraction of 1e-6 per step: 2e-22 · 10 ≤ 1e-12 · 6e-6).
        assert_eq!((steps, factored), (5, 4));
        // Infinite `reuse` factors at every step.
        let mut x = 1.0;
        assert_eq!(solve(&mut Newton::new(1e-12, 25, f64::INFINITY, 10.0), &mut x), (PositionStep::Converged, 5, 5));
        // A step limit of 0.1 takes five damped steps to cover 1 → 1.41.
        let mut x = 1.0;
        let (end, steps, _) = solve(&mut Newton::new(1e-12, 25, 10.0, 0.1), &mut x);
        assert!(end == PositionStep::Converged && steps >= 6, "{steps}");
        // The limit counts steps taken before a resume; a NaN stops at once.
        let mut x = 1.0;
        assert_eq!(solve(&mut Newton::new(1e-12, 25, 10.0, 10.0).resumed(25, 0), &mut x), (PositionStep::Step, 25, 0));
        let mut x = f64::NAN;
        assert_eq!(solve(&mut Newton::new(1e-12, 25, 10.0, 10.0), &mut x).0, PositionStep::Step);
    }
}

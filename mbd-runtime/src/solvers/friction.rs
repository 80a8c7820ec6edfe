//! Coulomb friction's loads by fixed-point iteration, written once for every solve that needs
//! them: the generated forward dynamics (`mechanism!` calls [`settle_loads`]), the dense solve
//! of joint coordinates ([`crate::dense_forward`]) and inverse dynamics. A friction force
//! depends on its joint's normal load, a multiplier in λ, which the solve with that force
//! changes: λ is iterated until it stops changing.

use crate::real::Real;

/// Iterates λ ← step(λ) — `step` solves the equations with the friction forces of the λ it is
/// given and overwrites λ with the result — until the largest change of λ is at most
/// `tolerance · max(1, max |λ|)`. At least one step is taken, at most `max_iterations`.
/// `Ok(steps)` when it settled; `Err((steps, last change))` when it did not (friction so large
/// that it changes the loads more than they change it), the change NaN where a step left λ not
/// finite — never a NaN λ passed off as settled.
pub fn settle_loads<T: Real, const NC: usize>(
    tolerance: T,
    max_iterations: u32,
    lambda: &mut [T; NC],
    mut step: impl FnMut(&mut [T; NC]),
) -> Result<u32, (u32, T)> {
    let mut change = T::ZERO;
    for steps in 1..=max_iterations.max(1) {
        let previous = *lambda;
        step(lambda);
        if !lambda.iter().all(|x| x.is_finite()) {
            return Err((steps, T::from_f64(f64::NAN)));
        }
        change = T::ZERO;
        let mut size = T::ONE;
        for (new, old) in lambda.iter().zip(previous.iter()) {
            change = change.max((*new - *old).abs());
            size = size.max(new.abs());
        }
        if change <= tolerance * size {
            return Ok(steps);
        }
    }
    Err((max_iterations.max(1), change))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// λ ← (1 + λ)/2 settles at 1 (each step halves the error); λ ← 2λ + 1 runs away and
    /// returns its last change; a NaN stops at once.
    #[test]
    fn settles_a_contraction_and_names_a_runaway() {
        let mut lambda = [0.0];
        let steps = settle_loads(1e-12, 100, &mut lambda, |l| l[0] = 0.5 * (1.0 + l[0])).expect("a contraction");
        assert!((lambda[0] - 1.0).abs() < 1e-11 && (40..=42).contains(&steps), "{lambda:?} after {steps}");
        let mut runaway = [0.0];
        assert_eq!(settle_loads(1e-12, 3, &mut runaway, |l| l[0] = 2.0 * l[0] + 1.0), Err((3, 4.0)));
        let mut nan = [0.0];
        let (steps, change) = settle_loads(1e-12, 50, &mut nan, |l| l[0] = f64::NAN).unwrap_err();
        assert!(steps == 1 && change.is_nan());
    }
}

//! The kinematic position solve over the factorization `mechanism!` plans: Newton's iteration
//! with, by default, a last step on the kept factors of D (simplified Newton, the chord method,
//! `KinematicOptions::reuse_safety`). Three settings must land on the same configuration; the
//! kept factors must really be used (the pure chord method converges linearly where Newton
//! converges quadratically), and the default must never take more steps than Newton.
use mbd::prelude::*;

#[allow(dead_code)]
#[path = "../examples/slider_crank.rs"]
mod slider_crank;
mod chain16 {
    include!("../benches/chain16.rs");
}
use chain16::Chain16;
use slider_crank::SliderCrank;

mechanism! {
    /// A four-bar driven by the relative angle of its coupler to its crank: the drivers do not
    /// fix any body's angle, so Φ stays nonlinear in every coordinate after the first step.
    pub RelativeFourBar {
        body crank   { mass: 1.0, inertia: 0.01, at: [0.05, 0.05, 0.785] }
        body coupler { mass: 1.0, inertia: 0.05, at: [0.35, 0.12, 0.1] }
        body rocker  { mass: 1.0, inertia: 0.02, at: [0.6, 0.1, 1.4] }
        revolute ground[0.0, 0.0] ~ crank[-0.07, 0.0];
        revolute crank[0.07, 0.0] ~ coupler[-0.25, 0.0];
        revolute coupler[0.25, 0.0] ~ rocker[-0.1, 0.0];
        revolute rocker[0.1, 0.0] ~ ground[0.55, 0.0];
        drive angle(crank, coupler) = -0.7 + 0.3 * sin(2.0 * t);
    }
}

mechanism! {
    /// A chain of 150 links driven at every joint (450 coordinates and rows): large enough for
    /// its position solve to evaluate Φ and D apart (more than `PART_NODES` operations
    /// together) and for its linear algebra to run in nested functions.
    pub DrivenChain150 {
        revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0];
        for k in 0..150 { body l[k] { mass: 0.1, inertia: 1.0e-4, at: [0.05 + 0.1 * k, 0.0, 0.0] } }
        for k in 1..150 { revolute l[k - 1][0.05, 0.0] ~ l[k][-0.05, 0.0]; }
        drive l[0].phi = 0.1 * sin(t);
        for k in 1..150 { drive angle(l[k - 1], l[k]) = 0.1 * sin(t + k); }
    }
}

/// Newton (a fresh D at every step), the default and the pure chord method (D's factors from
/// the first step kept to the end) along a sweep of `steps` steps of `h` seconds, each solve
/// started from the last configuration (no predictor: the first residual is the motion of one
/// step). All three must converge to ‖Φ‖∞ ≤ 1e-10 on the same configuration: they solve the
/// same equations, so their answers differ by at most the tolerance over D's smallest singular
/// value, 1e-9 m or rad for these mechanisms of O(0.1 m) links. Returns the Newton steps each
/// took in all, the factorizations of D each made in all, and the largest default count minus
/// Newton's at any one point.
fn sweep<M, const NQ: usize, const NC: usize, const N: usize>(m: &M, h: f64, steps: usize) -> ([u32; 3], [u32; 3], i64)
where
    M: Kinematics<f64, NQ, NQ, NC>,
{
    let mut ws = Workspace::<f64, NQ, NC, N>::boxed();
    let solvers =
        [f64::INFINITY, DEFAULT_REUSE_SAFETY, 0.0].map(|reuse| KinematicSolver::new(KinematicOptions::default().with_reuse_safety(reuse)));
    let mut q = m.initial_positions();
    solvers[0].assemble(m, &mut ws, &mut q, 0.0).expect("assembles");
    let (mut totals, mut factorizations, mut worst_excess) = ([0u32; 3], [0u32; 3], i64::MIN);
    for k in 1..=steps {
        let t = k as f64 * h;
        let mut answers = [q; 3];
        let mut counts = [0u32; 3];
        for (i, (solver, answer)) in solvers.iter().zip(&mut answers).enumerate() {
            let convergence = solver.solve_position(m, &mut ws, answer, t).unwrap_or_else(|e| panic!("{}: {e}", M::NAME));
            assert!(convergence.residual <= 1e-10, "{} at t = {t}: {convergence:?}", M::NAME);
            counts[i] = convergence.iterations;
            factorizations[i] += convergence.factorizations;
        }
        for answer in &answers[1..] {
            for (a, b) in answer.iter().zip(&answers[0]) {
                assert!((a - b).abs() < 1e-9, "{} at t = {t}: {answer:?} against Newton's {:?}", M::NAME, answers[0]);
            }
        }
        for (total, count) in totals.iter_mut().zip(counts) {
            *total += count;
        }
        worst_excess = worst_excess.max(counts[1] as i64 - counts[0] as i64);
        q = answers[0];
    }
    (totals, factorizations, worst_excess)
}

#[test]
fn the_kept_factors_land_where_newton_lands_in_no_more_steps() {
    for h in [1e-3, 1e-2, 5e-2] {
        let results = [
            ("slider-crank", 100, sweep::<_, 9, 9, 18>(&SliderCrank::default(), h, 100)),
            ("relative four-bar", 100, sweep::<_, 9, 9, 18>(&RelativeFourBar::default(), h, 100)),
            ("chain of 16", 100, sweep::<_, 48, 48, 96>(&Chain16::default(), h, 100)),
            ("driven chain of 150", 20, sweep::<_, 450, 450, 900>(&DrivenChain150::default(), h, 20)),
        ];
        for (name, solves, ([newton, default, chord], [newton_d, default_d, chord_d], excess)) in results {
            println!(
                "{name}, steps of {h} s, one sweep: Newton steps: Newton {newton}, default {default}, chord {chord}; factorizations {newton_d}, {default_d}, {chord_d}"
            );
            assert!(excess <= 0, "{name}, h = {h}: the default took {excess} more steps than Newton at one point");
            assert!(chord >= default, "{name}, h = {h}: the chord method took {chord} steps, the default {default}");
            // Full Newton factors at every step; the chord method once per solve.
            assert_eq!(newton_d, newton, "{name}");
            assert_eq!(chord_d, solves, "{name}");
            assert!(default_d <= default, "{name}");
        }
        // The default's savings: a millisecond on, every solve of the chain and of the relative
        // four-bar ends on the kept factors (one factorization, two steps); the slider-crank's
        // second step is Newton's (the test below).
        if h == 1e-3 {
            for (name, _, (steps, factorizations, _)) in &results[1..3] {
                assert_eq!((steps[1], factorizations[1]), (200, 100), "{name}");
            }
        }
    }
}

#[test]
fn the_chord_method_converges_linearly_and_the_default_sees_it() {
    let m = SliderCrank::default();
    let mut ws = SliderCrank::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.37).expect("assembles");
    let mut residual_after_two = |reuse: f64| {
        let options = KinematicOptions::default().with_reuse_safety(reuse).with_max_iterations(2).with_tolerance(1e-16);
        let mut qn = q;
        match KinematicSolver::new(options).solve_position(&m, &mut ws, &mut qn, 0.371) {
            Err(KinematicError::NotConverged { iterations: 2, residual, .. }) => residual,
            other => panic!("{other:?}"),
        }
    };
    let (newton, chord, default) = (residual_after_two(f64::INFINITY), residual_after_two(0.0), residual_after_two(DEFAULT_REUSE_SAFETY));
    println!("after two steps: Newton {newton:.2e}, chord {chord:.2e}, default {default:.2e}");
    assert!(newton < 1e-11, "{newton}");
    assert!(chord > 1e-10 && chord < 1e-8, "{chord}");
    assert_eq!(default, newton);
}

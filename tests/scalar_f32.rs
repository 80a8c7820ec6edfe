//! `scalar f32;` with the default options (issue 10, item 6): the position solve's tolerance
//! is tied to the scalar's precision, so the documented defaults converge in f32 (with 1e-10,
//! below f32's resolution, every solve stopped with "did not converge").
use mbd::prelude::*;

mechanism! {
    /// The README's slider-crank in single precision.
    pub SliderCrank32 {
        scalar f32;
        params { omega: 2.0 * PI, r: 0.1, l: 0.3 }
        body crank  { mass: 1.0, inertia: 0.002, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.25, 0.0, 0.0] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.4, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive crank.phi = omega * t;
    }
}

/// A full turn in 100 points with `KinematicSolver::default()`: every point converges, Φ is
/// held to the raised tolerance (64 ε ≈ 7.6e-6 m at these sub-metre coordinates), and the
/// slider follows the closed form x = r cos θ + √(l² − r² sin² θ) to 2e-5 m — a few times the
/// tolerance, since the position error is Φ's through a Jacobian of condition ≈ l/r.
#[test]
fn f32_slider_crank_sweeps_with_the_default_tolerance() {
    let m = SliderCrank32::default();
    let mut ws = SliderCrank32::workspace();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("assembles in f32 with the default tolerance");
    let mut points = 0;
    solver
        .sweep(&m, &mut ws, &mut q, (0..100).map(|k| k as f32 * 0.01), |t, q, _, _| {
            let mut phi = [0.0f32; 9];
            m.constraints(q, t, &mut phi);
            let worst = phi.iter().fold(0.0f32, |a, x| a.max(x.abs()));
            assert!(worst <= 7.7e-6, "t = {t}: ‖Φ‖∞ = {worst:e}");
            let theta = (m.omega * t) as f64;
            let (r, l) = (m.r as f64, m.l as f64);
            let exact = r * theta.cos() + (l * l - (r * theta.sin()).powi(2)).sqrt();
            let x = q[6] as f64;
            assert!((x - exact).abs() < 2e-5, "t = {t}: slider at {x} m, exact {exact} m");
            points += 1;
        })
        .expect("every point converges in f32");
    assert_eq!(points, 100);
}

mechanism! {
    /// The same slider-crank without its driver, free under gravity, in single precision.
    pub FreeSliderCrank32 {
        scalar f32;
        params { r: 0.1, l: 0.3 }
        gravity [0.0, -9.81];
        body crank  { mass: 1.0, inertia: 0.002, at: [0.0433, 0.025, 0.5236] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.2345, 0.025, -0.1674] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.3823, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
    }
}

include!("../benches/free_slider_crank.rs");

/// Forward dynamics in f32 with every integrator's defaults and the default drift correction:
/// each runs 2 s (before, the projection's 1e-10, DOPRI5's rtol 1e-8 and generalized-α's
/// 1e-10 could not be met in f32 and every run stopped with "did not converge" or a vanishing
/// step), held on the constraints to f32's resolution and following the f64 motion (DOPRI5 at
/// rtol 1e-12) to the bounds below.
#[test]
fn f32_simulations_run_with_the_default_options() {
    let m = FreeSliderCrank32::default();
    let mut ws = FreeSliderCrank32::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).unwrap();
    let times: Vec<f32> = (1..=20).map(|k| 0.1 * k as f32).collect();
    // The f64 reference: the same mechanism (benches/free_slider_crank.rs), the crank angle at
    // each output.
    let reference: Vec<f64> = {
        let m64 = FreeSliderCrank::default();
        let mut q64 = m64.initial_positions();
        KinematicSolver::default().assemble(&m64, &mut FreeSliderCrank::workspace(), &mut q64, 0.0).unwrap();
        let times64: Vec<f64> = times.iter().map(|&t| t as f64).collect();
        let mut out = Vec::new();
        let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-12).with_atol(1e-12));
        Simulation::new(&m64, &mut dopri)
            .start(0.0, &q64, &[0.0; 9])
            .times(&times64)
            .run(&mut FreeSliderCrank::workspace(), |s| out.push(FreeSliderCrank::CRANK.phi(&s.point.q)))
            .unwrap();
        out
    };
    let run = |name: &str, outcome: Result<(f32, f64), SimulationError>| {
        eprintln!("{name} in f32: {outcome:?} (‖Φ‖, crank angle off the f64 motion)");
        outcome
    };
    let rk4 = run("RK4", run32(&m, &mut ws, &mut Rk4::default(), &q, &times, &reference));
    let dopri = run("DOPRI5", run32(&m, &mut ws, &mut Dopri5::default(), &q, &times, &reference));
    let mut alpha = FreeSliderCrank32::generalized_alpha(GeneralizedAlphaOptions::default());
    let alpha = run("generalized-α", run32(&m, &mut ws, &mut alpha, &q, &times, &reference));
    // ‖Φ‖ within the resolution 64 ε ≈ 7.6e-6; the angle within BOUND rad of the f64 motion
    for (name, result, bound) in [("RK4", rk4, 1e-3), ("DOPRI5", dopri, 1e-3), ("generalized-α", alpha, 1e-2)] {
        let (phi, angle) = result.unwrap_or_else(|e| panic!("{name} in f32: {e}"));
        assert!(phi < 7.7e-6, "{name}: ‖Φ‖ = {phi}");
        assert!(angle < bound, "{name}: crank angle off the f64 motion by {angle} rad");
    }
}

/// Runs the f32 slider-crank with the default options: the largest ‖Φ‖∞ and the largest
/// distance of the crank angle from `reference` at the outputs.
fn run32<I: Integrator<f32, FreeSliderCrank32, 9, 9, 8, 17, { FreeSliderCrank32::NEWTON_STORAGE }>>(
    m: &FreeSliderCrank32,
    ws: &mut Workspace<f32, 9, 8, 17, { FreeSliderCrank32::NEWTON_STORAGE }>,
    integrator: &mut I,
    q: &[f32; 9],
    times: &[f32],
    reference: &[f64],
) -> Result<(f32, f64), SimulationError> {
    let (mut worst_phi, mut worst_angle, mut k) = (0.0f32, 0.0f64, 0);
    Simulation::new(m, integrator).start(0.0, q, &[0.0; 9]).times(times).run(ws, |s| {
        let mut phi = [0.0f32; 8];
        m.constraints(&s.point.q, s.point.t, &mut phi);
        worst_phi = phi.iter().fold(worst_phi, |a, x| a.max(x.abs()));
        worst_angle = worst_angle.max((FreeSliderCrank32::CRANK.phi(&s.point.q) as f64 - reference[k]).abs());
        k += 1;
    })?;
    Ok((worst_phi, worst_angle))
}

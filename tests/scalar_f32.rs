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

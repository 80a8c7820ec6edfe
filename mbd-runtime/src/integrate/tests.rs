//! The integrators and drift corrections on a mechanism with NQ ≠ NV — the pendulum whose
//! orientation is a unit complex number (crate::test_support) — against the pendulum's own
//! equation φ̈ = −m g L cos φ / (J + m L²), from horizontal rest.

use super::*;
use crate::integrate::{Correction, Dopri5, Dopri5Options, GeneralizedAlpha, GeneralizedAlphaOptions, Rk4, Rk4Options, SimulationOptions};
use crate::model::mechanism::{Dynamics, Kinematics};
use crate::model::workspace::Workspace;
use crate::test_support::{UnitPendulum, GRAVITY, INERTIA, LENGTH, MASS};

/// Output times (s): step ends and points between them, up to past the far turning point.
const TIMES: [f64; 8] = [0.1, 0.25, 0.3333, 0.5, 0.6, 0.75, 0.9, 1.0];

/// φ(t) for each output time, by RK4 on the pendulum's own equation with h = 1e-5 s (global
/// error ~ (ω h)⁴ ≈ 1e-16 relative).
fn reference_angles() -> [f64; 8] {
    let k = MASS * GRAVITY * LENGTH / (INERTIA + MASS * LENGTH * LENGTH);
    let f = |y: [f64; 2]| [y[1], -k * y[0].cos()];
    let h = 1e-5;
    let (mut y, mut t) = ([0.0f64, 0.0f64], 0.0);
    core::array::from_fn(|i| {
        let steps = ((TIMES[i] - t) / h).round() as usize;
        let h = (TIMES[i] - t) / steps as f64;
        for _ in 0..steps {
            let k1 = f(y);
            let k2 = f([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
            let k3 = f([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
            let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
            for c in 0..2 {
                y[c] += h / 6.0 * (k1[c] + 2.0 * (k2[c] + k3[c]) + k4[c]);
            }
        }
        t = TIMES[i];
        y[0]
    })
}

/// The largest errors over the samples: of (c, s) against (cos φ, sin φ), of |(c, s)| − 1, of
/// the pin's ‖Φ‖∞, and of T + V against its initial value.
fn run<I: Integrator<f64, UnitPendulum, 4, 3, 2, 5, 29>>(integrator: &mut I, correction: Correction<f64>) -> [f64; 4] {
    let m = UnitPendulum;
    let reference = reference_angles();
    let options = SimulationOptions::default().with_correction(correction);
    let mut worst = [0.0f64; 4];
    let mut k = 0;
    let q0 = m.initial_positions();
    let e0 = m.potential_energy(&q0, 0.0);
    Simulation::new(&m, integrator)
        .start(0.0, &q0, &[0.0; 3])
        .times(&TIMES)
        .options(options)
        .run(&mut Workspace::<f64, 3, 2, 5, 29>::new(), |s| {
            let q = &s.point.q;
            let (sin, cos) = reference[k].sin_cos();
            let mut phi = [0.0; 2];
            m.constraints(q, s.point.t, &mut phi);
            let errors = [
                (q[2] - cos).abs().max((q[3] - sin).abs()),
                (q[2].hypot(q[3]) - 1.0).abs(),
                phi[0].abs().max(phi[1].abs()),
                (s.energy.kinetic + s.energy.potential - e0).abs(),
            ];
            for (w, e) in worst.iter_mut().zip(errors) {
                *w = w.max(e);
            }
            k += 1;
        })
        .expect("the pendulum swings");
    assert_eq!(k, TIMES.len());
    worst
}

/// Every integrator, with each correction, follows the pendulum's equation with its orientation
/// kept unit by `normalize_positions` (steps and interpolated outputs; an ulp or two), and the
/// constraints and the energy (m g L = 9.81 J exchanged) held. Tolerances, about 100 times what
/// each run shows: RK4 at h = 1 ms and DOPRI5 at rtol 1e-10 reach 1e-10 in angle (ω ≈ 6 rad/s
/// over 1 s), Φ to 2e-11 with Baumgarte alone; generalized-α is second order, 2e-5 rad at
/// h = 1 ms, and its outputs between steps are cubic Hermite, off the manifold by 2e-9.
#[test]
fn integrators_follow_the_unit_pendulum() {
    let alpha = || GeneralizedAlpha::<f64, 3>::new(GeneralizedAlphaOptions::default());
    let dopri = || Dopri5::<f64, 4, 3>::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    // Tolerances: angle (rad), ‖Φ‖∞ (m), T + V (J).
    let (explicit, implicit) = ([1e-8, 1e-9, 1e-7], [1e-3, 1e-7, 1e-2]);
    let cases = [
        ("RK4", run(&mut Rk4::new(Rk4Options::default().with_step(1e-3)), Correction::None), explicit),
        ("RK4, projection", run(&mut Rk4::new(Rk4Options::default().with_step(1e-3)), Correction::projection()), explicit),
        ("RK4, partitioning", run(&mut Rk4::new(Rk4Options::default().with_step(1e-3)), Correction::partitioning()), explicit),
        ("DOPRI5", run(&mut dopri(), Correction::None), explicit),
        ("DOPRI5, projection", run(&mut dopri(), Correction::projection()), explicit),
        ("generalized-α", run(&mut alpha(), Correction::None), implicit),
        ("generalized-α, projection", run(&mut alpha(), Correction::projection()), implicit),
    ];
    for (name, [angle, norm, phi, energy], [angle_tolerance, phi_tolerance, energy_tolerance]) in cases {
        assert!(angle < angle_tolerance, "{name}: (c, s) off by {angle:e}");
        assert!(norm < 1e-15, "{name}: |(c, s)| − 1 = {norm:e}");
        assert!(phi < phi_tolerance, "{name}: ‖Φ‖∞ = {phi:e}");
        assert!(energy < energy_tolerance, "{name}: |Δ(T + V)| = {energy:e} J");
    }
}

/// DOPRI5's first step is Hairer's estimate h = 0.01 · ‖y‖ / ‖y'‖ in the tolerance's norm (y =
/// (q, v), y' = (q̇, v̇)), accepted at a loose tolerance: from horizontal rest q̇ = 0, so
/// ‖y'‖ is ‖v̇‖ = the gravity-driven accelerations, each entry scaled by atol + rtol·|y|.
#[test]
fn dopri5_first_step_is_hairers_estimate() {
    let m = UnitPendulum;
    let system = System { mechanism: &m, dynamics: crate::model::dynamics::DynamicsOptions::without_stabilization(), track_work: false };
    let from = system.point(0.0, m.initial_positions(), [0.0; 3], [0.0; 2]).unwrap();
    let (rtol, atol) = (1e-3, 1e-6);
    let mut dopri = Dopri5::<f64, 4, 3>::new(Dopri5Options::default().with_rtol(rtol).with_atol(atol));
    let mut to = from;
    Integrator::<f64, UnitPendulum, 4, 3, 2, 5>::step(&mut dopri, &system, &mut Workspace::new(), &from, 10.0, &mut to).unwrap();
    let scale = |y: f64| atol + rtol * y.abs();
    let d0: f64 = from.q.iter().map(|q| (q / scale(*q)).powi(2)).sum();
    let d1: f64 = from.vd.iter().zip(&from.v).map(|(a, v)| (a / scale(*v)).powi(2)).sum();
    let expected = 0.01 * (d0 / d1).sqrt();
    assert_eq!(dopri.rejected, 0);
    assert!((to.t - expected).abs() <= 1e-15 * expected, "first step {} s, Hairer's {expected} s", to.t);
}

/// Variable-step generalized-α: a first step so large that Newton cannot converge in its
/// iterations is retried at a quarter of its size until it does, and the run still follows the
/// pendulum; a minimum step above every step that converges fails naming the time; bad
/// tolerances are refused.
#[test]
fn adaptive_generalized_alpha_retries_failed_newton_steps_and_checks_its_options() {
    use crate::integrate::ErrorControl;
    let control = ErrorControl::default().with_rtol(1e-8).with_atol(1e-8);
    let options = GeneralizedAlphaOptions::default().with_step(0.5).with_max_iterations(3).with_error_control(Some(control));
    let mut alpha = GeneralizedAlpha::<f64, 3>::new(options);
    let [angle, ..] = run(&mut alpha, Correction::None);
    // Measured: 3.6e-8 rad in 18 189 steps at rtol 1e-8, the error bounded per unit time (the
    // default; 2.5e-5 in 700 steps bounded per step); the fixed 1 ms run above is held to 1e-3.
    assert!(angle < 1e-7, "(c, s) off by {angle:e}");
    assert!(alpha.rejected >= 2, "the 0.5 s and 0.125 s steps fail Newton: {} rejected", alpha.rejected);
    eprintln!("{} steps, {} rejected, error {angle:e}", alpha.accepted, alpha.rejected);

    let m = UnitPendulum;
    let q0 = m.initial_positions();
    let min_step = control.with_min_step(0.2);
    let mut alpha = GeneralizedAlpha::<f64, 3>::new(options.with_error_control(Some(min_step)));
    let error =
        Simulation::new(&m, &mut alpha).start(0.0, &q0, &[0.0; 3]).times(&[1.0]).run(&mut Workspace::<f64, 3, 2, 5, 29>::new(), |_| {});
    assert!(matches!(error, Err(SimulationError::StepSizeTooSmall { t: 0.0, .. })), "{error:?}");

    let negative = control.with_rtol(-1.0);
    let mut alpha = GeneralizedAlpha::<f64, 3>::new(options.with_error_control(Some(negative)));
    let error =
        Simulation::new(&m, &mut alpha).start(0.0, &q0, &[0.0; 3]).times(&[1.0]).run(&mut Workspace::<f64, 3, 2, 5, 29>::new(), |_| {});
    assert!(matches!(error, Err(SimulationError::InvalidOptions { .. })), "{error:?}");

    // A work space without the mechanism's Newton slots (NS = 0): named, not a panic.
    let mut alpha = GeneralizedAlpha::<f64, 3>::new(options);
    let error = Simulation::new(&m, &mut alpha).start(0.0, &q0, &[0.0; 3]).times(&[1.0]).run(&mut Workspace::<f64, 3, 2, 5>::new(), |_| {});
    assert!(matches!(error, Err(SimulationError::NewtonSlotSize { expected: 29, found: 0 })), "{error:?}");
}

/// A simulation without a start or without output times is refused with an error saying what
/// it lacks and how to give it, before anything is integrated; times out of order name the
/// first one.
#[test]
fn a_simulation_without_start_or_times_says_what_it_lacks() {
    let m = UnitPendulum;
    let q0 = m.initial_positions();
    let mut ws = Workspace::<f64, 3, 2, 5, 29>::new();
    let mut rk4 = Rk4::default();
    let mut samples = 0;
    let error = Simulation::new(&m, &mut rk4).times(&[1.0]).run(&mut ws, |_| samples += 1);
    assert!(matches!(error, Err(SimulationError::Incomplete { missing }) if missing.contains(".start(")), "{error:?}");
    let error = Simulation::new(&m, &mut rk4).start(0.0, &q0, &[0.0; 3]).run(&mut ws, |_| samples += 1);
    assert!(matches!(error, Err(SimulationError::Incomplete { missing }) if missing.contains(".times(")), "{error:?}");
    assert_eq!(error.unwrap_err().to_string(), "the simulation was run without output times: .times(&times)", "the message a user reads");
    let error = Simulation::new(&m, &mut rk4).start(0.5, &q0, &[0.0; 3]).times(&[1.0, 0.2]).run(&mut ws, |_| samples += 1);
    assert!(matches!(error, Err(SimulationError::TimesNotIncreasing { index: 1 })), "{error:?}");
    assert_eq!(samples, 0, "nothing was delivered");
}

/// A work space whose N is not NV + NC (0: the explicit integrators ask nothing of it) still
/// holds the explicit integrators' vectors and a simulation's points, which are sized by NV and
/// NC (`Rows`): DOPRI5 and RK4 run with projection and partitioning and give the same samples
/// as with the mechanism's own work space, bitwise.
#[test]
fn explicit_integrators_run_in_a_work_space_without_n() {
    /// DOPRI5's and RK4's samples, one after the other, in the work space `ws`.
    fn samples<const N: usize>(mut ws: Workspace<f64, 3, 2, N>, options: SimulationOptions<f64>) -> Vec<[f64; 4]> {
        let (m, mut out) = (UnitPendulum, Vec::new());
        let q0 = m.initial_positions();
        let mut dopri = Dopri5::new(Dopri5Options::default());
        Simulation::new(&m, &mut dopri)
            .start(0.0, &q0, &[0.0; 3])
            .times(&TIMES)
            .options(options)
            .run(&mut ws, |s| out.push(s.point.q))
            .unwrap();
        let mut rk4 = Rk4::new(Rk4Options::default().with_step(1e-2));
        Simulation::new(&m, &mut rk4)
            .start(0.0, &q0, &[0.0; 3])
            .times(&TIMES)
            .options(options)
            .run(&mut ws, |s| out.push(s.point.q))
            .unwrap();
        out
    }
    for correction in [Correction::projection(), Correction::partitioning()] {
        let options = SimulationOptions::default().with_correction(correction);
        let without_n = samples(Workspace::<f64, 3, 2, 0>::new(), options);
        assert_eq!(without_n.len(), 2 * TIMES.len());
        assert_eq!(without_n, samples(Workspace::<f64, 3, 2, 5>::new(), options), "{correction:?}");
    }
}

/// `project` without a work space, out of steps (none allowed) on a state off the constraints,
/// names the worst row in a `NotConverged` error: the vector it measures Φ in is `DenseArrays`'
/// (a panic, before it had one).
#[test]
fn project_out_of_steps_names_the_row_without_a_work_space() {
    let m = UnitPendulum;
    let mut q = m.initial_positions();
    q[0] += 0.1;
    let mut v = [0.0; 3];
    let err =
        crate::integrate::project(&m, 0.0, &mut q, &mut v, &crate::model::dynamics::DynamicsOptions::default(), 1e-10, 0).unwrap_err();
    assert!(matches!(err, SimulationError::NotConverged { iterations: 0, .. }), "{err:?}");
}

/// BDF ends each step on Φ = 0 with its velocities projected, and the simulation then leaves
/// the point as it is (`Integrator::projected_end`). A wrapper that hides that, so that
/// the simulation projects every step again, gives the same samples within rounding: the second
/// projection of a projected state moves it by a few ulps (1e-13 allows ten thousand steps of
/// them; both runs take the same steps).
#[test]
fn a_projected_step_end_is_not_projected_again() {
    use crate::integrate::{Bdf, BdfOptions};
    /// BDF, all but `projected_end` forwarded (its default, `None`).
    struct Hidden(Bdf<f64, 4, 3>);
    impl Integrator<f64, UnitPendulum, 4, 3, 2, 5, 29> for Hidden {
        fn holds_constraints(&self) -> bool {
            Integrator::<f64, UnitPendulum, 4, 3, 2, 5, 29>::holds_constraints(&self.0)
        }
        fn step(
            &mut self,
            system: &System<'_, UnitPendulum, f64>,
            ws: &mut WorkArrays<f64, 3, 2, 5, 29>,
            from: &Point<f64, 4, 3, 2>,
            t_max: f64,
            to: &mut Point<f64, 4, 3, 2>,
        ) -> Result<(), SimulationError> {
            self.0.step(system, ws, from, t_max, to)
        }
        fn prepare_interpolation(
            &mut self,
            system: &System<'_, UnitPendulum, f64>,
            ws: &mut WorkArrays<f64, 3, 2, 5, 29>,
            from: &Point<f64, 4, 3, 2>,
            to: &Point<f64, 4, 3, 2>,
        ) -> Result<(), SimulationError> {
            self.0.prepare_interpolation(system, ws, from, to)
        }
        fn interpolate(
            &self,
            m: &UnitPendulum,
            from: &Point<f64, 4, 3, 2>,
            to: &Point<f64, 4, 3, 2>,
            t: f64,
            q: &mut [f64; 4],
            v: &mut [f64; 3],
        ) {
            Integrator::<f64, UnitPendulum, 4, 3, 2, 5, 29>::interpolate(&self.0, m, from, to, t, q, v);
        }
        fn restart(&mut self) {
            self.0.restart();
        }
        fn after_correction(
            &mut self,
            system: &System<'_, UnitPendulum, f64>,
            ws: &mut WorkArrays<f64, 3, 2, 5, 29>,
            to: &mut Point<f64, 4, 3, 2>,
        ) -> Result<(), SimulationError> {
            self.0.after_correction(system, ws, to)
        }
    }
    /// The samples' positions of BDF at rtol 1e-8, its step ends' projection skipped or not.
    fn samples(skipped: bool) -> Vec<[f64; 4]> {
        let (m, mut out) = (UnitPendulum, Vec::new());
        let q0 = m.initial_positions();
        let mut ws = Workspace::<f64, 3, 2, 5, 29>::new();
        let bdf = Bdf::<f64, 4, 3>::new(BdfOptions::default().with_rtol(1e-8).with_atol(1e-10));
        let record = |s: &crate::integrate::Sample<f64, 4, 3, 2>| out.push(s.point.q);
        if skipped {
            let mut integrator = bdf;
            Simulation::new(&m, &mut integrator).start(0.0, &q0, &[0.0; 3]).times(&TIMES).run(&mut ws, record).unwrap();
            // The last step's end was projected from within the run's tolerance: it was skipped.
            let end = Integrator::<f64, UnitPendulum, 4, 3, 2, 5, 29>::projected_end(&integrator);
            assert!(end.is_some_and(|r| r <= 1e-10), "{end:?}");
        } else {
            let mut integrator = Hidden(bdf);
            Simulation::new(&m, &mut integrator).start(0.0, &q0, &[0.0; 3]).times(&TIMES).run(&mut ws, record).unwrap();
        }
        out
    }
    let (skipped, projected) = (samples(true), samples(false));
    assert_eq!(skipped.len(), TIMES.len());
    let worst = skipped.iter().zip(&projected).flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs())).fold(0.0, f64::max);
    assert!(worst < 1e-13, "the projection BDF's ends skip moved a sample by {worst:e}");
}

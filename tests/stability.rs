//! Numerical stability (issue 10): the hard cases a user's model meets, each with the bound it
//! must keep and why that bound. This file holds the generalized-α cases: ρ∞ = 1 over long
//! runs, steps that do not divide the run, its own state through drift correction, the
//! multipliers' convergence at small steps, and failures that say what they are.
use mbd::prelude::*;
use mbd::{Point, System};

mechanism! {
    /// A uniform 1 m rod pinned at one end, released horizontal: a physical pendulum of
    /// amplitude 90°.
    pub Pendulum {
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.083_333_333_333_333_33, at: [0.5, 0.0, 0.0] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
    }
}

mechanism! {
    /// A double pendulum of two rods (conservative and chaotic).
    pub DoublePendulum {
        gravity [0.0, -9.81];
        body a { mass: 1.0, inertia: 0.0208, at: [0.25, 0.0, 0.0] }
        body b { mass: 0.5, inertia: 0.0104, at: [0.75, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ a[-0.25, 0.0];
        revolute a[0.25, 0.0] ~ b[-0.25, 0.0];
    }
}

/// g (m/s²), and the rod's pivot-to-centre distance (m) and inertia about the pivot (kg·m²).
const G: f64 = 9.81;
const D: f64 = 0.5;
const J_PIVOT: f64 = 1.0 / 12.0 + D * D;

/// Exact period of the physical pendulum at amplitude θ₀ (s): T = 2π / (ω₀ · AGM(1, cos(θ₀/2))),
/// ω₀² = m g d / J (the complete elliptic integral K(k) = π / (2 AGM(1, √(1 − k²))), k = sin(θ₀/2)).
fn exact_period(amplitude: f64) -> f64 {
    let omega0 = (G * D / J_PIVOT).sqrt();
    let (mut a, mut b) = (1.0_f64, (amplitude / 2.0).cos());
    // The AGM converges quadratically: 8 rounds reach the last bit from any b in (0, 1].
    for _ in 0..8 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    2.0 * std::f64::consts::PI / (omega0 * a)
}

/// Times (s) at which the rod passes the bottom (φ = −π/2), by linear interpolation between
/// samples.
fn bottom_passages(samples: &[(f64, f64)]) -> Vec<f64> {
    let bottom = -std::f64::consts::FRAC_PI_2;
    samples
        .windows(2)
        .filter(|w| (w[0].1 - bottom) * (w[1].1 - bottom) < 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * (bottom - w[0].1) / (w[1].1 - w[0].1))
        .collect()
}

/// Runs the pendulum with generalized-α at step h and ρ∞ from horizontal rest to t_end, sampling
/// φ every `every` s; returns (t, φ) samples and the largest |E − E₀| (J).
fn pendulum_run(h: f64, rho: f64, t_end: f64, every: f64) -> (Vec<(f64, f64)>, f64) {
    let m = Pendulum::default();
    let q0 = m.initial_positions();
    let mut alpha = Pendulum::generalized_alpha(GeneralizedAlphaOptions::default().with_step(h).with_rho_infinity(rho));
    let n = (t_end / every).round() as usize;
    let times: Vec<f64> = (0..=n).map(|k| k as f64 * every).collect();
    let mut samples = Vec::with_capacity(times.len());
    let mut e0 = None;
    let mut drift = 0.0_f64;
    Simulation::new(&m, &mut alpha)
        .start(0.0, &q0, &[0.0; 3])
        .times(&times)
        .run(&mut Pendulum::workspace(), |s| {
            samples.push((s.point.t, Pendulum::ROD.phi(&s.point.q)));
            let e = s.energy.kinetic + s.energy.potential;
            drift = drift.max((e - *e0.get_or_insert(e)).abs());
        })
        .unwrap_or_else(|e| panic!("generalized-α, h = {h}, ρ∞ = {rho}: {e}"));
    (samples, drift)
}

/// ρ∞ = 1 (no numerical damping) over a long run: 300 s, about 155 periods, at two step sizes
/// (it stopped with "Newton did not converge" after 5–9 s at every step before velocities were
/// projected, its energy growing about 20× per second). The method is second order, so the
/// period comes out too long by about (ω h)²/12 relative (ω ≤ 3.9 rad/s): the phase error after
/// 300 s stays below 300 s · (ωh)²/12 · 2 (a factor 2 for the amplitude's nonlinearity). The
/// velocity projection removes the kinetic energy of the O(h²) velocity violation each step,
/// O((ωh)⁴) of the 4.9 J swing, so the energy drifts down by at most 4.9 J · (ωh)³ · ω t / 2
/// over the run (measured: 0.14 of 4.9 J · (ωh)³ · ω t at h = 5 ms) and does not grow.
#[test]
fn generalized_alpha_without_damping_runs_long() {
    let amplitude = std::f64::consts::FRAC_PI_2;
    let period = exact_period(amplitude);
    let t_end = 300.0;
    for h in [5e-3, 2e-3] {
        let (samples, drift) = pendulum_run(h, 1.0, t_end, 5e-3);
        let passages = bottom_passages(&samples);
        let k = passages.len() - 1;
        let expected = period / 4.0 + k as f64 * period / 2.0;
        let omega = 3.9_f64;
        let phase_bound = 2.0 * t_end * (omega * h).powi(2) / 12.0;
        let phase = passages[k] - expected;
        eprintln!("ρ∞ = 1, h = {h}: {} passages, phase error {phase:e} s (bound {phase_bound:e}), energy drift {drift:e} J", k + 1);
        assert!(k + 1 >= 2 * (t_end / period) as usize, "the pendulum kept swinging: {} passages", k + 1);
        assert!(phase.abs() < phase_bound, "phase error {phase:e} s at h = {h}");
        let energy_bound = 4.9 * (omega * h).powi(3) * omega * t_end / 2.0;
        assert!(drift < energy_bound, "energy drift {drift:e} J at h = {h} (bound {energy_bound:e})");
    }
}

/// q and v of the double pendulum at `t_end` from horizontal rest.
fn double_pendulum_at<I: Integrator<f64, DoublePendulum, 6, 6, 4, 10, { DoublePendulum::NEWTON_STORAGE }>>(
    integrator: &mut I,
    correction: Correction<f64>,
    t_end: f64,
) -> ([f64; 6], [f64; 6], u64) {
    let m = DoublePendulum::default();
    let options = SimulationOptions::default().with_correction(correction);
    let mut last = ([0.0; 6], [0.0; 6]);
    let stats = Simulation::new(&m, integrator)
        .start(0.0, &m.initial_positions(), &[0.0; 6])
        .times(&[t_end])
        .options(options)
        .run(&mut DoublePendulum::workspace(), |s| last = (s.point.q, s.point.v))
        .unwrap_or_else(|e| panic!("{e}"));
    (last.0, last.1, stats.steps)
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

fn alpha(step: f64) -> GeneralizedAlpha<f64, 6> {
    DoublePendulum::generalized_alpha(GeneralizedAlphaOptions::default().with_step(step).with_rho_infinity(0.8))
}

/// q and v of the pendulum at `t_end` from horizontal rest, and the steps taken.
fn pendulum_at<I: Integrator<f64, Pendulum, 3, 3, 2, 5, { Pendulum::NEWTON_STORAGE }>>(
    integrator: &mut I,
    t_end: f64,
) -> ([f64; 3], [f64; 3], u64) {
    let m = Pendulum::default();
    let mut last = ([0.0; 3], [0.0; 3]);
    let stats = Simulation::new(&m, integrator)
        .start(0.0, &m.initial_positions(), &[0.0; 3])
        .times(&[t_end])
        .run(&mut Pendulum::workspace(), |s| last = (s.point.q, s.point.v))
        .unwrap_or_else(|e| panic!("{e}"));
    (last.0, last.1, stats.steps)
}

/// A step that does not divide the run (twelve steps of 0.04 s sum to 0.4799999999999999 s in
/// f64): the twelfth step lands on t_end = 0.48 s itself, not on a sliver of 1e-16 s after it.
/// The velocities at t_end (the rod near the bottom, at full speed) then carry the methods'
/// errors at h = 0.04 s (ω h ≤ 0.16): a few percent against a tight DOPRI5 reference, not the
/// 55–110 % a 1e-16 s step divided by h² gave generalized-α. RK4 too.
#[test]
fn the_last_fixed_step_lands_on_t_end() {
    let mut reference = Dopri5::new(Dopri5Options::default().with_rtol(1e-12).with_atol(1e-14));
    let (t_end, h, n) = (0.48, 0.04_f64, 12);
    let (_, v_exact, _) = pendulum_at(&mut reference, t_end);
    let size = v_exact.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!((0..n).fold(0.0, |t, _| t + h) < t_end, "the sum of the steps falls short");
    let mut alpha = Pendulum::generalized_alpha(GeneralizedAlphaOptions::default().with_step(h));
    let (_, v, steps) = pendulum_at(&mut alpha, t_end);
    let error = max_diff(&v, &v_exact) / size;
    eprintln!("generalized-α h = {h} s: {steps} steps, relative velocity error at {t_end} s {error:e}");
    assert_eq!(steps, n);
    assert!(error < 0.1, "relative velocity error {error}");
    let (_, v, steps) = pendulum_at(&mut Rk4::new(Rk4Options::default().with_step(h)), t_end);
    let error = max_diff(&v, &v_exact) / size;
    eprintln!("RK4 h = {h} s: {steps} steps, relative velocity error at {t_end} s {error:e}");
    assert_eq!(steps, n);
    assert!(error < 0.1, "relative velocity error {error}");
}

/// With a drift correction after each step, generalized-α goes on from its own v̇ and λ (only q
/// and v are corrected), so it keeps its second order: the error at 1 s falls about 4× when h
/// halves, with projection and with partitioning alike (it fell far less when each step
/// restarted from forward dynamics' Baumgarte-stabilized v̇ and λ).
#[test]
fn generalized_alpha_keeps_its_order_through_drift_correction() {
    let mut reference = Dopri5::new(Dopri5Options::default().with_rtol(1e-12).with_atol(1e-14));
    let (exact, _, _) = double_pendulum_at(&mut reference, Correction::None, 1.0);
    for correction in [Correction::projection(), Correction::partitioning()] {
        let e1 = max_diff(&double_pendulum_at(&mut alpha(2e-3), correction, 1.0).0, &exact);
        let e2 = max_diff(&double_pendulum_at(&mut alpha(1e-3), correction, 1.0).0, &exact);
        eprintln!("{correction:?}: errors {e1:e} → {e2:e}, ratio {}", e1 / e2);
        assert!((3.0..5.5).contains(&(e1 / e2)), "{correction:?}: error ratio {} ({e1:e} → {e2:e})", e1 / e2);
    }
}

/// At small steps Newton converges in a few iterations and the multipliers converge too: λ of a step against λ of forward dynamics at the
/// step's own (q, v). The two differ by the method's error in v̇, O(h) relative here (the start
/// is not second-order consistent), so below 1e-3 of the 15 N weight-and-swing scale at h = 1e-5
/// s; without Δλ in the convergence test, λ was accepted as soon as β'h²Δv̇ fell below 1e-10 m,
/// i.e. with Δλ up to 1e-10 kg·m / (β'h²) ≈ 4 N.
#[test]
fn generalized_alpha_multipliers_converge_at_small_steps() {
    let m = Pendulum::default();
    let system = System::new(&m);
    let start = system.point(0.0, m.initial_positions(), [0.0; 3], [0.0; 2]).expect("forward dynamics");
    for h in [1e-4, 1e-5, 1e-6] {
        let mut alpha = Pendulum::generalized_alpha(GeneralizedAlphaOptions::default().with_step(h));
        let (mut from, mut to) = (start, start);
        let mut ws = Pendulum::workspace();
        for _ in 0..20 {
            alpha.step(&system, &mut ws, &from, f64::INFINITY, &mut to).expect("a step");
            // The constraint rows are scaled by 1/(β'h²), so the iteration matrix tends to
            // [[M, −Dᵀ], [D, 0]] as h shrinks instead of degrading: Newton still converges in
            // a few iterations at h = 1e-6 s.
            assert!(alpha.iterations <= 4, "h = {h}: {} Newton iterations", alpha.iterations);
            from = to;
        }
        let exact: Point<f64, 3, 3, 2> = system.point(to.t, to.q, to.v, [0.0; 2]).expect("forward dynamics");
        let error = max_diff(&to.lambda, &exact.lambda);
        eprintln!("h = {h}: λ = {:?}, forward dynamics {:?}, |Δλ| = {error:e} N", to.lambda, exact.lambda);
        assert!(error < 1e-3 * 15.0, "h = {h}: λ off by {error} N");
    }
}

mechanism! {
    /// A rod pinned twice at the same point: the second pin's rows repeat the first's.
    pub TwicePinned {
        params { mass: 1.0, inertia: 0.083 }
        gravity [0.0, -9.81];
        body rod { mass: mass, inertia: inertia, at: [0.5, 0.0, 0.0] }
        revolute first: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        revolute second: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
    }
}

mechanism! {
    /// A pendulum whose torque is √(k − 1): NaN for k < 1.
    pub BadTorque {
        params { k: 0.0 }
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.083, at: [0.5, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        torque rod = sqrt(k - 1.0);
    }
}

/// Each way a generalized-α step can fail says which: a dependent constraint row by name, a
/// direction with neither mass nor stiffness by its velocity, a NaN by its row — never a
/// dependent constraint for all three, never a NaN state.
#[test]
fn generalized_alpha_failures_say_what_they_are() {
    let step = GeneralizedAlphaOptions::default();
    let rest = |q: [f64; 3]| {
        let mut p = Point::<f64, 3, 3, 4>::zero();
        p.q = q;
        p
    };
    let m = TwicePinned::default();
    let mut to = Point::zero();
    // By default the repeated pin's rows are dropped (tests/forward.rs); asked to refuse them:
    let strict = System { dynamics: DynamicsOptions::default().with_allow_redundant(false), ..System::new(&m) };
    let err = TwicePinned::generalized_alpha(step)
        .step(&strict, &mut TwicePinned::workspace(), &rest(m.initial_positions()), 1.0, &mut to)
        .unwrap_err();
    eprintln!("{err}");
    match err {
        SimulationError::Dynamics(DynamicsError::DependentConstraint { row, .. }) => assert!(row.starts_with("second"), "{row}"),
        other => panic!("expected a dependent constraint, got {other:?}"),
    }
    // No inertia and no gravity load on it: the rotation has neither inertia nor stiffness (one
    // pin). (Every velocity needs a mass or a stiffness: the Newton matrix is factored in a
    // planned order without row exchanges, `mbd::sparse`.)
    mechanism! {
        pub Massless {
            params { mass: 1.0, inertia: 0.0 }
            body rod { mass: mass, inertia: inertia, at: [0.5, 0.0, 0.0] }
            revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        }
    }
    let m = Massless::default();
    let mut start = Point::<f64, 3, 3, 2>::zero();
    start.q = m.initial_positions();
    let mut to = start;
    let err = Massless::generalized_alpha(step).step(&System::new(&m), &mut Massless::workspace(), &start, 1.0, &mut to).unwrap_err();
    eprintln!("{err}");
    assert_eq!(err, SimulationError::SingularIterationMatrix { t: 1e-3, velocity: "rod.phi" });
    let m = BadTorque::default();
    let mut start = Point::<f64, 3, 3, 2>::zero();
    start.q = m.initial_positions();
    let mut to = start;
    let err = BadTorque::generalized_alpha(step).step(&System::new(&m), &mut BadTorque::workspace(), &start, 1.0, &mut to).unwrap_err();
    eprintln!("{err}");
    assert!(
        matches!(
            err,
            SimulationError::Dynamics(DynamicsError::NonFiniteForce { element: "torque on rod", others: 0, velocity: "rod.phi", .. })
        ),
        "{err:?}"
    );
}

mechanism! {
    /// A pendulum whose torque sqrt(1 − t) N·m turns NaN at t = 1 s, and a second torque on the
    /// same rod: which element it was is then one of two.
    pub FailingTorque {
        params { other: 0.0 }
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.083, at: [0.5, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        torque motor: rod = sqrt(1.0 - t);
        torque brake: rod = other;
    }
}

/// A force expression that turns NaN during a run is a typed error naming the force element and
/// the time, from every integrator — never a NaN state or a misleading "step too large" (the
/// explicit methods used to report the coordinate the NaN reached). The time is within one
/// step of 1 s: the first evaluation past it (DOPRI5's stages reach up to one step ahead).
#[test]
fn a_force_that_turns_nan_is_named_with_its_time() {
    let m = FailingTorque::default();
    let q0 = m.initial_positions();
    let times = [2.0];
    let options = SimulationOptions::default();
    let named = |err: SimulationError, h: f64, label: &str| {
        eprintln!("{label}: {err}");
        match err {
            SimulationError::Dynamics(DynamicsError::NonFiniteForce { t, element, others, velocity }) => {
                // `brake` reaches rod.phi too (gravity does not: it pulls on rod.y): `element`
                // is the first in declaration order, `others` counts the rest.
                assert_eq!((element, others, velocity), ("motor", 1, "rod.phi"), "{label}");
                assert!(t > 1.0 && t <= 1.0 + h, "{label}: t = {t}");
            }
            other => panic!("{label}: expected a named force element, got {other:?}"),
        }
    };
    let err = Simulation::new(&m, &mut Rk4::new(Rk4Options::default().with_step(1e-3)))
        .start(0.0, &q0, &[0.0; 3])
        .times(&times)
        .options(options)
        .run(&mut FailingTorque::workspace(), |_| {})
        .unwrap_err();
    named(err, 1e-3, "RK4");
    let mut dopri = Dopri5::new(Dopri5Options::default());
    let err = Simulation::new(&m, &mut dopri)
        .start(0.0, &q0, &[0.0; 3])
        .times(&times)
        .options(options)
        .run(&mut FailingTorque::workspace(), |_| {})
        .unwrap_err();
    named(err, 0.1, "DOPRI5");
    let mut alpha = FailingTorque::generalized_alpha(GeneralizedAlphaOptions::default());
    let err = Simulation::new(&m, &mut alpha)
        .start(0.0, &q0, &[0.0; 3])
        .times(&times)
        .options(options)
        .run(&mut FailingTorque::workspace(), |_| {})
        .unwrap_err();
    named(err, 1e-3, "generalized-α");
}

mechanism! {
    /// The uniform 1 m rod of `Pendulum`, written in units of s metres (s = 1e-3: mm; 1e3: km):
    /// lengths × 1/s, g × 1/s, inertia × 1/s² (kg·unit²). Its motion in radians is the same.
    pub ScaledPendulum {
        params { per_metre: 1.0 }
        gravity [0.0, -9.81 * per_metre];
        body rod { mass: 1.0, inertia: per_metre * per_metre / 12.0, at: [0.5 * per_metre, 0.0, 0.0] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5 * per_metre, 0.0];
    }
}

/// φ(t) of the scaled pendulum from horizontal rest, sampled every 0.05 s to `t_end`, with
/// DOPRI5 at `rtol` (atol rtol/100) and the default projection.
fn scaled_run(per_metre: f64, rtol: f64, t_end: f64) -> Vec<(f64, f64)> {
    let m = ScaledPendulum { per_metre };
    let mut ws = ScaledPendulum::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let times: Vec<f64> = (1..=(t_end / 0.05).round() as usize).map(|k| k as f64 * 0.05).collect();
    let mut samples = Vec::with_capacity(times.len());
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(rtol).with_atol(rtol * 1e-2));
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &[0.0; 3])
        .times(&times)
        .run(&mut ws, |s| samples.push((s.point.t, ScaledPendulum::ROD.phi(&s.point.q))))
        .unwrap_or_else(|e| panic!("{per_metre} units per metre: {e}"));
    samples
}

/// A long run: 2000 s, about 1030 periods of the 90° pendulum, with DOPRI5 at rtol 1e-10. The
/// bottom passages keep the elliptic-integral period: the last one is within 2e-5 s of
/// T/4 + k T/2 (measured 5.9e-6 s: DOPRI5's phase error grows about linearly, 3e-9 s per
/// period at this tolerance), and none is missing.
#[test]
fn pendulum_keeps_its_period_over_2000_s() {
    let t_end = 2000.0;
    let samples = scaled_run(1.0, 1e-10, t_end);
    let passages = bottom_passages(&samples);
    let period = exact_period(std::f64::consts::FRAC_PI_2);
    let k = passages.len() - 1;
    let phase = passages[k] - (period / 4.0 + k as f64 * period / 2.0);
    eprintln!("2000 s: {} bottom passages, last off by {phase:e} s (period {period} s)", k + 1);
    assert_eq!(k + 1, (2.0 * t_end / period + 0.5) as usize, "one passage per half period");
    assert!(phase.abs() < 2e-5, "phase error {phase:e} s after {t_end} s");
}

/// The same pendulum in millimetres, metres and kilometres moves the same in radians: 10 s at
/// rtol 1e-10 agree to 1e-7 rad (measured: 2.4e-11 rad in mm, 2.8e-9 rad in km, where atol =
/// 1e-12 km of the 5e-4 km coordinates starts to count; the error control is relative, and the
/// position solve's floor follows the coordinates' size).
#[test]
fn pendulum_in_millimetres_and_kilometres_moves_the_same() {
    let metres = scaled_run(1.0, 1e-10, 10.0);
    for per_metre in [1e3, 1e-3] {
        let scaled = scaled_run(per_metre, 1e-10, 10.0);
        let worst = metres.iter().zip(&scaled).fold(0.0f64, |a, (x, y)| a.max((x.1 - y.1).abs()));
        eprintln!("{per_metre} units per metre (1e3: mm, 1e-3: km): φ differs from metres' by at most {worst:e} rad");
        assert!(worst < 1e-7, "{per_metre} units per metre: φ off by {worst:e} rad");
    }
}

mechanism! {
    /// The 1 m rod pinned at one end with a 1 kg bob that slides along it on a very stiff
    /// spring: 1.5e9 N/m makes the bob's axial mode ω = √(k/m) = 3.9e4 rad/s, 1.3e4 times the
    /// pendulum's 3.07 rad/s.
    pub StiffBob {
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.083_333_333_333_333_33, at: [0.5, 0.0, 0.0] }
        body bob { mass: 1.0, inertia: 0.001, at: [1.2, 0.0, 0.0] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        translational slide: rod[0.0, 0.0] along [1.0, 0.0] ~ bob[0.0, 0.0] along [1.0, 0.0];
        spring stiff: rod[0.5, 0.0] ~ bob[0.0, 0.0] { k: 1.5e9, length: 0.2 };
    }
}

/// Stiff: the stiff bob from horizontal rest. RK4's stability limit is h ω ≤ 2.8, h ≤ 7.2e-5 s;
/// at 1 ms it blows up, and says so (a typed non-finite error naming a coordinate, never a NaN
/// state). Generalized-α (ρ∞ = 0.5) at h = 10 ms, 140 times that limit, stays stable over 20 s:
/// the energy never rises above its start by more than 1e-6 of the 16.7 J swing (ρ∞ < 1 only
/// takes energy out; measured 1.1e-6 J, the fast mode's share as the loads change), and the rod keeps the period of the compound pendulum
/// with the bob rigid at 1.2 m (the spring stretches by 1e-7 m under the swing's loads): the
/// last of its 17 bottom passages within 20 s · (ωh)² = 1.9e-2 s of the elliptic-integral time
/// (second order: a relative period error c (ωh)², c = 1/12 at ρ∞ = 1, more with damping;
/// measured c = 0.34 at ρ∞ = 0.5, a phase of 6.4e-3 s).
#[test]
fn a_stiff_spring_is_stable_far_past_the_explicit_limit() {
    let m = StiffBob::default();
    let mut ws = StiffBob::workspace();
    let q0 = m.initial_positions();
    let times: Vec<f64> = (1..=4000).map(|k| k as f64 * 5e-3).collect();
    let explicit = Simulation::new(&m, &mut Rk4::new(Rk4Options::default().with_step(1e-3)))
        .start(0.0, &q0, &[0.0; 6])
        .times(&times)
        .run(&mut ws, |_| {});
    // The default projection meets the blow-up first and names the row it cannot close.
    match explicit {
        Err(SimulationError::NonFinite { t, coordinate }) => eprintln!("RK4 at 1 ms: non-finite `{coordinate}` at t = {t} s"),
        Err(SimulationError::NotConverged { t, worst_row, residual, .. }) => {
            eprintln!("RK4 at 1 ms: projection did not close `{worst_row}` ({residual:e}) at t = {t} s")
        }
        other => panic!("RK4 at 14× its stability limit should fail with a named coordinate or row: {other:?}"),
    }
    let mut alpha = StiffBob::generalized_alpha(GeneralizedAlphaOptions::default().with_step(1e-2).with_rho_infinity(0.5));
    let (mut samples, mut e0, mut rise) = (Vec::new(), None, f64::NEG_INFINITY);
    Simulation::new(&m, &mut alpha)
        .start(0.0, &q0, &[0.0; 6])
        .times(&times)
        .run(&mut ws, |s| {
            samples.push((s.point.t, StiffBob::ROD.phi(&s.point.q)));
            let e = s.energy.kinetic + s.energy.potential;
            rise = rise.max(e - *e0.get_or_insert(e));
        })
        .expect("generalized-α is stable at 140× the explicit limit");
    // The compound pendulum: J_pivot = 1/3 + 0.001 + 1.2² kg·m², M g d = (0.5 + 1.2) g.
    let (j_pivot, mgd) = (1.0 / 3.0 + 0.001 + 1.44, 1.7 * G);
    let omega0 = (mgd / j_pivot).sqrt();
    let (mut a, mut b) = (1.0_f64, (std::f64::consts::FRAC_PI_4).cos());
    for _ in 0..8 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    let period = 2.0 * std::f64::consts::PI / (omega0 * a);
    let passages = bottom_passages(&samples);
    let k = passages.len() - 1;
    let phase = passages[k] - (period / 4.0 + k as f64 * period / 2.0);
    let bound = 20.0 * (omega0 * 1e-2).powi(2);
    eprintln!("stiff bob, generalized-α at 10 ms: {} passages, phase {phase:e} s (bound {bound:e}), energy rise {rise:e} J", k + 1);
    let expected = ((20.0 - period / 4.0) / (period / 2.0)).floor() as usize + 1;
    assert_eq!(k + 1, expected, "one passage per half period of {period} s");
    assert!(phase.abs() < bound, "phase error {phase:e} s");
    assert!(rise < 1e-6 * 16.7, "energy rose by {rise:e} J");
}

mechanism! {
    /// A 1 m, 1 kg rod pinned at one end, spinning in a horizontal plane (no gravity) at
    /// 1000 rad/s.
    pub Spinner {
        body rod { mass: 1.0, inertia: 0.083_333_333_333_333_33, at: [0.5, 0.0, 0.0], velocity: [0.0, 500.0, 1000.0] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
    }
}

/// Rotation at 10³ rad/s: with nothing to slow it the rod turns at exactly 1000 rad/s, 159
/// turns in 1 s. DOPRI5 at rtol 1e-10 keeps φ = ω t to 1e-6 rad, ω to 1e-9 relative, the pin
/// to 1e-9 m and the pin force at the centripetal m ω² d = 5e5 N to 1e-8 relative (measured
/// 2.7e-7 rad, 5.3e-10, 1.7e-11 m and 1.1e-9 with the default projection, which moves φ by up
/// to its 1e-10 m tolerance / 0.5 m at each of the run's 19 424 steps; with Baumgarte alone they had
/// been 8.8e-9 rad, 1.8e-11, 2.0e-10 m and 3.5e-11).
#[test]
fn a_rod_spinning_at_1000_rad_per_s_keeps_its_speed_and_pin() {
    let m = Spinner::default();
    let mut ws = Spinner::workspace();
    let q0 = m.initial_positions();
    let v0 = [0.0, 500.0, 1000.0];
    let times: Vec<f64> = (1..=10).map(|k| k as f64 * 0.1).collect();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    let mut worst = [0.0f64; 4];
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q0, &v0)
        .times(&times)
        .run(&mut ws, |s| {
            let (t, q, v) = (s.point.t, &s.point.q, &s.point.v);
            // φ is not wrapped by the integrator: it grows as ω t.
            let phi_error = (Spinner::ROD.phi(q) - 1000.0 * t).abs();
            let mut pin = [0.0; 2];
            m.constraints(q, t, &mut pin);
            let force = s.point.lambda[0].hypot(s.point.lambda[1]);
            let errors = [phi_error, (v[2] / 1000.0 - 1.0).abs(), pin[0].abs().max(pin[1].abs()), (force / 5e5 - 1.0).abs()];
            for (w, e) in worst.iter_mut().zip(errors) {
                *w = w.max(e);
            }
        })
        .expect("the spinning rod");
    eprintln!("1000 rad/s: φ − ωt {:.1e} rad, ω {:.1e} rel, pin {:.1e} m, pin force {:.1e} rel", worst[0], worst[1], worst[2], worst[3]);
    assert!(worst[0] < 1e-6 && worst[1] < 1e-9, "φ or ω drifted: {worst:?}");
    assert!(worst[2] < 1e-9, "the pin opened by {} m", worst[2]);
    assert!(worst[3] < 1e-8, "pin force off by {} relative", worst[3]);
}

mechanism! {
    /// A free block on a stiff spring to ground: no constraint rows at all.
    pub FreeBlock {
        body block { mass: 1.0, inertia: 0.01, at: [0.3, 0.1, 0.0] }
        spring ground[0.0, 0.0] ~ block[0.0, 0.0] { k: 1.0e4, length: 0.1 };
    }
}

/// Generalized-α out of Newton iterations on a mechanism without constraints names the velocity
/// whose correction did not settle and gives that correction as a position change, Δv̇ β'h²
/// (m): one iteration allowed at h = 1 ms, so the second correction is O(β'h² k Δq) ≈ 1e-4 m
/// at most — not a velocity (m/s) or an acceleration.
#[test]
fn generalized_alpha_out_of_iterations_reports_a_position_correction() {
    let m = FreeBlock::default();
    let options = GeneralizedAlphaOptions::default().with_step(1e-3).with_max_iterations(1);
    let mut alpha = FreeBlock::generalized_alpha(options);
    let run = SimulationOptions::default().with_correction(Correction::None);
    let err = Simulation::new(&m, &mut alpha)
        .start(0.0, &m.initial_positions(), &[0.0; 3])
        .times(&[0.01])
        .options(run)
        .run(&mut FreeBlock::workspace(), |_| {})
        .unwrap_err();
    match err {
        SimulationError::NotConverged { worst_row, residual, .. } => {
            assert!(worst_row.starts_with("block."), "{worst_row}");
            assert!(residual > 0.0 && residual < 1e-4, "residual {residual:e} m");
        }
        e => panic!("{e}"),
    }
}

/// Out of Newton iterations with Φ and the position correction met, generalized-α names the
/// multiplier whose force change has not settled, with that change (N): one iteration allowed at
/// a 1e-5 tolerance, which its first correction meets in Φ (quadratic from the predictor's
/// O(h² v̇) ≈ 1e-5 m) and in q (β'h²|Δv̇| ≈ 3e-7 |Δv̇|), while the force-change test (1e-12 of
/// the forces) is not met after one iteration. The velocity correction itself, |Δv̇| β' in
/// m/s², is larger than 1e-5 — naming a velocity would misplace the failure.
#[test]
fn generalized_alpha_out_of_iterations_names_an_unsettled_multiplier() {
    let m = Pendulum::default();
    let options =
        GeneralizedAlphaOptions::default().with_step(1e-3).with_tolerance(1e-5).with_lambda_tolerance(1e-12).with_max_iterations(1);
    let mut alpha = Pendulum::generalized_alpha(options);
    let run = SimulationOptions::default().with_correction(Correction::None);
    let (q0, v0) = (m.initial_positions(), m.initial_velocities());
    let err = Simulation::new(&m, &mut alpha)
        .start(0.0, &q0, &v0)
        .times(&[0.01])
        .options(run)
        .run(&mut Pendulum::workspace(), |_| {})
        .unwrap_err();
    match err {
        SimulationError::NotConverged { worst_row, residual, .. } => {
            assert!(Pendulum::CONSTRAINT_NAMES.contains(&worst_row), "{worst_row}");
            assert!(residual > 0.0, "Δλ {residual:e} N");
        }
        e => panic!("{e}"),
    }
}

//! Inverse dynamics: driver torques and joint reactions against hand statics and dynamics.
use mbd::prelude::*;

mechanism! {
    /// A rod of 1 m (centre of mass 0.5 m from its pin) held or turned by a driver.
    pub DrivenRod {
        params { theta0: 0.6, omega: 0.0 }
        gravity [0.0, -9.81];
        body rod { mass: 2.0, inertia: 0.1667, at: [0.4, 0.3, 0.6] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        drive motor: rod.phi = theta0 + omega * t;
    }
}

const G: f64 = 9.81;

fn solve(m: &DrivenRod, t: f64) -> ([f64; 3], [[f64; 3]; 3], [f64; 3]) {
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = DrivenRod::workspace();
    solver.assemble(m, &mut ws, &mut q, t).expect("assembles");
    let state = solver.analyze(m, &mut ws, &q, t).expect("analysis");
    let mut lambda = [0.0; 3];
    InverseDynamics::default().solve(m, &mut ws, &state.q, &state.v, &state.vd, t, &mut lambda).expect("inverse dynamics");
    // The work space holds D(q, t) after inverse dynamics, exactly the generated Jacobian's.
    let mut d = [[0.0; 3]; 3];
    m.jacobian(&state.q, t, &mut d);
    assert_eq!(ws.jacobian(), &d);
    (state.q, d, lambda)
}

/// Held still at θ: the pin carries the weight, (0, m g), and the motor supplies the static
/// torque m g (l/2) cos θ about the pin; about the centre of mass that is the pin force's arm,
/// 0.5 m g cos θ. Same arithmetic as the solver up to rounding: 1e-9 N is far below 1 ulp of the
/// 19.62 N involved times the Jacobian's condition.
#[test]
fn static_rod_against_hand_statics() {
    let m = DrivenRod::default();
    let (q, d, lambda) = solve(&m, 0.0);
    let pin = joint_reaction(&m, &q, &d, &lambda, 0).expect("joint 0 exists");
    let motor = joint_reaction(&m, &q, &d, &lambda, 1).expect("joint 1 exists");
    assert_eq!(pin.joint, "pin");
    assert!(pin.on_i.is_none(), "the pin's first body is ground");
    let on_rod = pin.on_j.expect("the pin acts on the rod");
    assert!((on_rod.force[0]).abs() < 1e-9 && (on_rod.force[1] - 2.0 * G).abs() < 1e-9, "{on_rod:?}");
    // A planar wrench: no force along z, a moment about z only.
    assert_eq!((on_rod.force[2], on_rod.moment[0], on_rod.moment[1]), (0.0, 0.0, 0.0));
    let torque = motor.on_i.expect("the motor acts on the rod").moment[2];
    let expected = 2.0 * G * 0.5 * m.theta0.cos();
    assert!((torque - expected).abs() < 1e-9, "motor torque {torque} vs {expected}");
    // The pin's moment about its own point is zero: a revolute joint transmits no torque.
    let (s, c) = q[2].sin_cos();
    let arm = [-0.5 * c, -0.5 * s, 0.0];
    assert!(on_rod.moment_about(arm)[2].abs() < 1e-9);
    // In the rod's frame the weight's reaction is (m g sin θ, m g cos θ).
    let local = on_rod.force_in_body_frame();
    assert!((local[0] - 2.0 * G * s).abs() < 1e-9 && (local[1] - 2.0 * G * c).abs() < 1e-9);
}

/// Turning at constant ω: the pin force is m (a − g) with the centripetal acceleration
/// a = −ω² r_cm, and the motor torque is still the gravity moment (no angular acceleration).
#[test]
fn spinning_rod_pin_force_is_centripetal() {
    let m = DrivenRod { omega: 3.0, ..Default::default() };
    let t = 0.37;
    let (q, d, lambda) = solve(&m, t);
    let on_rod = joint_reaction(&m, &q, &d, &lambda, 0).and_then(|r| r.on_j).expect("pin on rod");
    let motor = joint_reaction(&m, &q, &d, &lambda, 1).and_then(|r| r.on_i).expect("motor");
    let a = [-9.0 * q[0], -9.0 * q[1]];
    let expected = [2.0 * a[0], 2.0 * (a[1] + G)];
    assert!((on_rod.force[0] - expected[0]).abs() < 1e-9 && (on_rod.force[1] - expected[1]).abs() < 1e-9, "{on_rod:?} vs {expected:?}");
    assert!((motor.moment[2] - 2.0 * G * 0.5 * q[2].cos()).abs() < 1e-9);
}

/// A sweep with inverse dynamics written as CSV ([`CsvWriter::states`]): named columns with
/// units and no energy columns, one row per point, the motor's torque column reading back the
/// multipliers exactly, and a sweep stopped by its callback (`ControlFlow::Break`) after the
/// point it was given, its progress bar counting the points done.
#[test]
fn inverse_dynamics_sweep_to_csv() {
    let m = DrivenRod { omega: 2.0, ..DrivenRod::default() };
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = DrivenRod::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let mut inverse_ws = DrivenRod::workspace();
    let mut buffer = Vec::new();
    let mut csv = CsvWriter::states::<DrivenRod>(&mut buffer);
    let mut torques = Vec::new();
    let times: Vec<f64> = (0..50).map(|k| 0.02 * k as f64).collect();
    let progress = Progress::count(times.len() as u64).hidden();
    solver
        .sweep(&m, &mut ws, &mut q, &times, |t, q, v, vd| {
            progress.inc();
            let mut lambda = [0.0; 3];
            InverseDynamics::default().solve(&m, &mut inverse_ws, q, v, vd, t, &mut lambda).expect("inverse dynamics");
            csv.write_state(t, q, v, vd, &lambda);
            torques.push(lambda[2]);
            if t >= 0.5 {
                std::ops::ControlFlow::Break(())
            } else {
                std::ops::ControlFlow::Continue(())
            }
        })
        .expect("sweeps");
    assert_eq!(csv.finish().expect("written"), 26);
    assert_eq!(progress.fraction(), 26.0 / 50.0);
    let text = String::from_utf8(buffer).expect("UTF-8");
    let header: Vec<&str> = text.lines().next().expect("header").split(',').collect();
    assert_eq!(header.len(), 1 + 3 + 3 + 3 + 3);
    assert_eq!(header[12], "lambda motor: phi (N·m)");
    let read: Vec<f64> = text.lines().skip(1).map(|l| l.split(',').nth(12).expect("column").parse().expect("number")).collect();
    assert_eq!(read, torques);
}

mechanism! {
    /// A pendulum whose bob's mass and inertia are parameters: a user may set them to anything.
    pub WeighedPendulum {
        params { m_bob: 1.0, j_bob: 0.01 }
        gravity [0.0, -9.81];
        body bob { mass: m_bob, inertia: j_bob, at: [0.5, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ bob[-0.5, 0.0];
        drive swing: bob.phi = 0.3 * sin(t);
        scene FreeWeighedPendulum without swing;
    }
}

mechanism! {
    /// A top on a ball joint whose inertia tensor's product Jxy is a parameter.
    pub TensorTop {
        spatial;
        params { jxy: 0.0 }
        gravity [0.0, 0.0, -9.81];
        body top { mass: 1.0, inertia: [0.01, 0.01, 0.02, jxy, 0.0, 0.0], at: [0.0, 0.0, 0.5] }
        spherical ground[0.0, 0.0, 0.0] ~ top[0.0, 0.0, -0.5];
    }
}

/// A mass or inertia given as a parameter is checked by every analysis that uses M — inverse
/// dynamics, statics, linearization and simulation — which each refuse a non-positive one
/// naming the body, before anything else (a user found inverse dynamics accepting a negative
/// mass silently). Spatially, J′ must be positive definite: diag(0.01, 0.01, 0.02) with
/// Jxy = 0.02 has the principal moments −0.01, 0.02 and 0.03 (each diagonal entry positive),
/// and −0.01 is reported.
#[test]
fn every_analysis_refuses_a_non_positive_mass_or_inertia_naming_the_body() {
    for (m_bob, j_bob, value) in [(-1.0, 0.01, -1.0), (0.0, 0.01, 0.0), (1.0, -0.5, -0.5), (f64::NAN, 0.01, f64::NAN)] {
        let expected = |body: &str, v: f64| body == "bob" && (v == value || (v.is_nan() && value.is_nan()));
        let driven = WeighedPendulum { m_bob, j_bob };
        let mut lambda = [0.0; WeighedPendulum::NC];
        let error = InverseDynamics::default()
            .solve(&driven, &mut WeighedPendulum::workspace(), &driven.initial_positions(), &[0.0; 3], &[0.0; 3], 0.0, &mut lambda)
            .unwrap_err();
        assert!(matches!(error, InverseDynamicsError::NonPositiveMass { body, value: v } if expected(body, v)), "{error:?}");
        assert!(error.to_string().contains("body `bob`"), "{error}");

        let free = FreeWeighedPendulum { m_bob, j_bob };
        let mut q = free.initial_positions();
        let mut lambda = [0.0; FreeWeighedPendulum::NC];
        let error = StaticSolver::default().solve(&free, &mut FreeWeighedPendulum::workspace(), &mut q, 0.0, &mut lambda).unwrap_err();
        assert!(matches!(error, StaticError::NonPositiveMass { body, value: v } if expected(body, v)), "{error:?}");

        let error = Linearizer::default().linearize(&free, &free.initial_positions(), &[0.0; 3], 0.0).unwrap_err();
        assert!(
            matches!(error, LinearizeError::Dynamics(DynamicsError::NonPositiveMass { body, value: v }) if expected(body, v)),
            "{error:?}"
        );

        let error = Simulation::new(&free, &mut Auto::default())
            .start(0.0, &free.initial_positions(), &[0.0; 3])
            .times(&[0.1])
            .run(&mut FreeWeighedPendulum::workspace(), |_| {})
            .unwrap_err();
        assert!(
            matches!(error, SimulationError::Dynamics(DynamicsError::NonPositiveMass { body, value: v }) if expected(body, v)),
            "{error:?}"
        );
    }

    let top = TensorTop { jxy: 0.02 };
    let error = Simulation::new(&top, &mut Auto::default())
        .start(0.0, &top.initial_positions(), &[0.0; 6])
        .times(&[0.1])
        .run(&mut TensorTop::workspace(), |_| {})
        .unwrap_err();
    let SimulationError::Dynamics(DynamicsError::NonPositiveMass { body: "top", value }) = error else { panic!("{error:?}") };
    assert!((value + 0.01).abs() < 1e-15, "the smallest principal moment: {value}");
    let mut q = top.initial_positions();
    let mut lambda = [0.0; TensorTop::NC];
    let error = StaticSolver::default().solve(&top, &mut TensorTop::workspace(), &mut q, 0.0, &mut lambda).unwrap_err();
    assert!(matches!(error, StaticError::NonPositiveMass { body: "top", .. }), "{error:?}");

    // Valid values pass: the same analyses run.
    let top = TensorTop { jxy: 0.001 };
    let mut q = top.initial_positions();
    StaticSolver::default().solve(&top, &mut TensorTop::workspace(), &mut q, 0.0, &mut lambda).expect("a positive definite J′");
    let driven = WeighedPendulum::default();
    let mut lambda = [0.0; WeighedPendulum::NC];
    InverseDynamics::default()
        .solve(&driven, &mut WeighedPendulum::workspace(), &driven.initial_positions(), &[0.0; 3], &[0.0; 3], 0.0, &mut lambda)
        .expect("positive masses");
}

/// A mechanism its drivers fix (DOF = 0) has nothing to be stable or unstable: statics finds
/// the loads that hold it and says `Determined`, and so does linearization, instead of "stable
/// with ω² = ∞" and "decaying at an infinite rate" (what a new user read, 2026-12-02). The
/// pendulum held horizontal at t = 0 (φ = 0.3 sin 0): its driver holds m g · 0.5 m = 4.905 N·m.
#[test]
fn a_mechanism_without_freedom_is_determined_not_stable() {
    let m = WeighedPendulum::default();
    let mut q = m.initial_positions();
    let mut lambda = [0.0; WeighedPendulum::NC];
    let mut ws = WeighedPendulum::workspace();
    let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("held by its driver");
    assert_eq!(report.stability, Stability::Determined);
    let swing = joint_reaction(&m, &q, ws.jacobian(), &lambda, WeighedPendulum::SWING).and_then(|j| j.on_i).expect("the driver's load");
    // Tolerance: the statics residual (1e-10 N·m) on a 4.9 N·m load.
    assert!((swing.moment[2].abs() - 1.0 * 9.81 * 0.5).abs() < 1e-8, "{swing:?}");
    let mut v = [0.0; 3];
    KinematicSolver::default().sweep(&m, &mut ws, &mut q, [0.0], |_, _, velocity, _| v = *velocity).expect("the driven motion");
    let lin = Linearizer::default().linearize(&m, &q, &v, 0.0).expect("linearizes");
    assert_eq!((lin.dof(), lin.stability()), (0, LinearStability::Determined));
}

/// `use mbd::prelude::*;` beside `use nalgebra::*;` (here mbd's re-export of it): the prelude
/// has no name nalgebra has, so `Point`, `Matrix` and the rest are nalgebra's without an
/// ambiguity error, and the analyses are mbd's. (Before 2026-12-02 the prelude re-exported the
/// whole runtime, whose `Point` made this program ambiguous: today a future-incompatibility
/// warning, denied here.)
#[deny(ambiguous_glob_imports)]
mod prelude_beside_nalgebra {
    use mbd::nalgebra::*;
    use mbd::prelude::*;

    #[test]
    fn the_prelude_and_nalgebra_glob_imports_do_not_collide() {
        let p: Point<f64, 2> = Point2::new(1.0, 2.0);
        let m: Matrix2<f64> = Matrix2::identity();
        assert_eq!(m * p.coords, Vector2::new(1.0, 2.0));
        let rod = super::DrivenRod::default();
        let mut q = rod.initial_positions();
        KinematicSolver::default().assemble(&rod, &mut super::DrivenRod::workspace(), &mut q, 0.0).expect("assembles");
        assert!((q[2] - rod.theta0).abs() < 1e-12, "the driven angle");
    }
}

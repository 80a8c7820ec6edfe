//! Redundant constraints (issue 10, item 2): the rank-revealing report names the redundant rows
//! and gives the true mobility next to Grübler's count; forward dynamics with
//! `allow_redundant` follows the unique motion.
use mbd::prelude::*;

mechanism! {
    /// A parallelogram with a third parallel crank: three equal cranks pinned to ground 0.5 m
    /// apart and to one coupler. Grübler counts 12 − 12 = 0; it moves with one degree of freedom.
    pub ThreeCranks {
        gravity [0.0, -9.81];
        params { r: 0.3 }
        body c1 { mass: 1.0, inertia: 0.0075, at: [0.15, 0.0, 0.0] }
        body c2 { mass: 1.0, inertia: 0.0075, at: [0.65, 0.0, 0.0] }
        body c3 { mass: 1.0, inertia: 0.0075, at: [1.15, 0.0, 0.0] }
        body coupler { mass: 2.0, inertia: 0.1, at: [0.8, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ c1[-r / 2.0, 0.0];
        revolute ground[0.5, 0.0] ~ c2[-r / 2.0, 0.0];
        revolute ground[1.0, 0.0] ~ c3[-r / 2.0, 0.0];
        revolute c1[r / 2.0, 0.0] ~ coupler[-0.5, 0.0];
        revolute c2[r / 2.0, 0.0] ~ coupler[0.0, 0.0];
        revolute third: c3[r / 2.0, 0.0] ~ coupler[0.5, 0.0];
    }
}

mechanism! {
    /// A change-point four-bar: crank 0.2 m, coupler 0.5 m, rocker 0.3 m, ground pins 0.6 m
    /// apart (0.2 + 0.6 = 0.5 + 0.3), so it passes a configuration where all four links lie on
    /// the ground line: the crank pointing back (φ = π), coupler and rocker forward.
    pub FlatFourBar {
        body crank { mass: 1.0, inertia: 0.003, at: [-0.1, 0.0, PI] }
        body coupler { mass: 1.0, inertia: 0.02, at: [0.05, 0.0, 0.0] }
        body rocker { mass: 1.0, inertia: 0.008, at: [0.45, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-0.1, 0.0];
        revolute crank[0.1, 0.0] ~ coupler[-0.25, 0.0];
        revolute coupler[0.25, 0.0] ~ rocker[-0.15, 0.0];
        revolute rocker[0.15, 0.0] ~ ground[0.6, 0.0];
    }
}

mechanism! {
    /// A slider on two collinear guides: the second repeats both rows of the first, so Grübler
    /// counts 3 − 4 = −1 while it slides with one degree of freedom.
    pub TwoGuides {
        body slider { mass: 1.0, inertia: 0.01, at: [0.1, 0.05, 0.1] }
        translational front: slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        translational back: slider[0.2, 0.0] along [1.0, 0.0] ~ ground[0.2, 0.0] along [1.0, 0.0];
    }
}

/// Assembly steps past redundant rows (found by a new user: the third crank from a rough guess
/// stopped at "singular constraint Jacobian"; a negative Grübler count was refused outright).
/// Where D has no pivot, the step is the minimum-norm one over the independent rows, so a
/// consistent redundancy assembles as fast as a regular mechanism: ‖Φ‖∞ ≤ 1e-10, all rows met.
#[test]
fn redundant_mechanisms_assemble_from_rough_guesses() {
    let solver = KinematicSolver::default();
    let m = ThreeCranks::default();
    let mut ws = ThreeCranks::workspace();
    // Each coordinate 0.01–0.03 off a pose at θ = 0.7 rad.
    let (s, c, r) = (0.7f64.sin(), 0.7f64.cos(), m.r);
    let mut q = [0.0; 12];
    for (k, x) in [0.0, 0.5, 1.0].into_iter().enumerate() {
        q[3 * k..3 * k + 3].copy_from_slice(&[x + 0.5 * r * c, 0.5 * r * s, 0.7]);
    }
    q[9..12].copy_from_slice(&[0.5 + r * c, r * s, 0.0]);
    for (i, x) in q.iter_mut().enumerate() {
        *x += 0.01 + 0.01 * (i % 3) as f64;
    }
    let convergence = solver.assemble(&m, &mut ws, &mut q, 0.0).expect("a consistent redundancy assembles");
    let mut phi = [0.0; 12];
    m.constraints(&q, 0.0, &mut phi);
    assert!(phi.iter().all(|x| x.abs() <= 1e-10), "Φ = {phi:?}");
    let [a, b, cc] = [ThreeCranks::C1.phi(&q), ThreeCranks::C2.phi(&q), ThreeCranks::C3.phi(&q)];
    assert!((a - b).abs() < 1e-9 && (a - cc).abs() < 1e-9, "the cranks stay parallel: {a} {b} {cc}");
    assert!(convergence.iterations <= 8, "{convergence:?}");

    let m = TwoGuides::default();
    let mut ws = TwoGuides::workspace();
    let mut q = m.initial_positions();
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("Grübler's −1 is not an error when the rows agree");
    assert!(q[1].abs() <= 1e-10 && q[2].abs() <= 1e-10, "on the guide, square to it: {q:?}");
    let report = solver.redundancy(&m, &mut ws, &q, 0.0).expect("finite");
    assert_eq!((report.grubler, report.mobility, report.redundant_rows().count()), (-1, 1, 2), "{report}");
}

/// The third crank's pin repeats, in one direction, what the other two already impose: rank 11
/// of 12, mobility 1 against Grübler's 0, and the one redundant row is the last declared joint's
/// (rows are taken in declaration order). The decision is clear-cut at a general angle: the
/// redundant row's sine is rounding (≤ 1e-12), the rows kept are at least 1e-3 from dependent.
/// (At θ = 0 or π the cranks lie along the coupler: a singular position, mobility 2.)
#[test]
fn third_crank_is_one_redundant_row() {
    let m = ThreeCranks::default();
    let mut ws = ThreeCranks::workspace();
    let solver = KinematicSolver::default();
    for theta in [0.7_f64, -0.3, -2.0] {
        let (s, c) = theta.sin_cos();
        let r = m.r;
        let mut q = [0.0; 12];
        for (k, x) in [0.0, 0.5, 1.0].into_iter().enumerate() {
            q[3 * k..3 * k + 3].copy_from_slice(&[x + 0.5 * r * c, 0.5 * r * s, theta]);
        }
        q[9..12].copy_from_slice(&[0.5 + r * c, r * s, 0.0]);
        let report = solver.redundancy(&m, &mut ws, &q, 0.0).expect("finite");
        eprintln!("θ = {theta}: {report}");
        assert_eq!((report.rank, report.grubler, report.mobility), (11, 0, 1), "{report}");
        let names: Vec<_> = report.redundant_names().collect();
        assert_eq!(names.len(), 1, "{report}");
        assert!(names[0].starts_with("third"), "the last declared joint's row: {report}");
        assert!(report.largest_redundant < 1e-12 && report.smallest_kept > 1e-3, "{report}");
        assert!(report.to_string().contains("mobility 1") && report.to_string().contains(names[0]), "{report}");
    }
}

/// A four-bar is regular (mobility = Grübler = 1) except where it lies flat: there the pins'
/// rows lose one rank, and the report says mobility 2 at that configuration.
#[test]
fn flat_four_bar_has_one_more_instantaneous_mobility() {
    let m = FlatFourBar::default();
    let mut ws = FlatFourBar::workspace();
    let solver = KinematicSolver::default();
    let flat = m.initial_positions();
    let report = solver.redundancy(&m, &mut ws, &flat, 0.0).expect("finite");
    eprintln!("flat: {report}");
    assert_eq!((report.grubler, report.mobility, report.rank), (1, 2, 7), "{report}");
    // Bent: the crank at 2 rad (tip at (−0.083, 0.182) m), coupler and rocker from a rough
    // guess, assembled; then every row is independent.
    let mut q = flat;
    q[0..3].copy_from_slice(&[-0.04, 0.09, 2.0]);
    q[3..6].copy_from_slice(&[0.1, 0.15, -0.25]);
    q[6..9].copy_from_slice(&[0.5, 0.1, -0.6]);
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("assembles bent");
    let report = solver.redundancy(&m, &mut ws, &q, 0.0).expect("finite");
    eprintln!("bent: {report}");
    assert_eq!((report.grubler, report.mobility, report.rank), (1, 1, 8), "{report}");
    assert_eq!(report.redundant_rows().count(), 0);
    assert!(report.smallest_kept > 1e-3, "{report}");
}

/// The unique motion: the three cranks turn together, θ₁ = θ₂ = θ₃ = θ, the coupler translates,
/// and θ obeys one pendulum equation I θ̈ = −g (3 m r/2 + m_c r) cos θ with
/// I = 3 (J + m r²/4) + m_c r². Released at rest from θ = −0.3 rad it swings between −0.3 and
/// −π + 0.3 rad, never through the flat positions θ = 0, −π (where the rows lose a second rank).
/// Forward dynamics drops the redundant row (`allow_redundant`) and
/// DOPRI5 at rtol 1e-10 follows the 1-DOF equation (integrated here by RK4 at 1e-5 s, error
/// ~1e-14) to 1e-9 rad over 2 s (measured 2.5e-11 rad, DOPRI5's own error at that tolerance),
/// the three cranks equal to 1e-12 rad (measured: rounding, 4e-16).
#[test]
fn third_crank_moves_as_one_degree_of_freedom() {
    let m = ThreeCranks::default();
    let (r, mass, j, mc, g) = (m.r, 1.0, 0.0075, 2.0, 9.81);
    let inertia = 3.0 * (j + mass * r * r / 4.0) + mc * r * r;
    let torque = |theta: f64| -g * (3.0 * mass * r / 2.0 + mc * r) * theta.cos() / inertia;
    let times: Vec<f64> = (1..=8).map(|k| k as f64 * 0.25).collect();
    let mut exact = Vec::new();
    let theta0 = -0.3_f64;
    let (mut th, mut om, h) = (theta0, 0.0_f64, 1e-5);
    // The outputs are 0.25 s = 25 000 steps apart.
    for &t_out in &times {
        for _ in 0..25_000 {
            let k1 = (om, torque(th));
            let k2 = (om + 0.5 * h * k1.1, torque(th + 0.5 * h * k1.0));
            let k3 = (om + 0.5 * h * k2.1, torque(th + 0.5 * h * k2.0));
            let k4 = (om + h * k3.1, torque(th + h * k3.0));
            th += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            om += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
        exact.push((t_out, th));
    }
    let mut ws = ThreeCranks::workspace();
    let (s0, c0) = theta0.sin_cos();
    let mut q = [0.0; 12];
    for (k, x) in [0.0, 0.5, 1.0].into_iter().enumerate() {
        q[3 * k..3 * k + 3].copy_from_slice(&[x + 0.5 * r * c0, 0.5 * r * s0, theta0]);
    }
    q[9..12].copy_from_slice(&[0.5 + r * c0, r * s0, 0.0]);
    // The defaults: no Baumgarte terms, projection after each step, dependent rows dropped.
    let options = SimulationOptions::default();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    let mut k = 0;
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &[0.0; 12])
        .times(&times)
        .options(options)
        .run(&mut ws, |s| {
            let q = &s.point.q;
            let (t, theta) = exact[k];
            assert_eq!(s.point.t, t);
            let [a, b, c] = [ThreeCranks::C1.phi(q), ThreeCranks::C2.phi(q), ThreeCranks::C3.phi(q)];
            assert!((a - theta).abs() < 1e-9, "t = {t}: θ₁ = {a}, 1-DOF {theta}");
            eprintln!("t = {t}: |θ₁ − θ| = {:.1e} rad, cranks differ by {:.1e} rad", (a - theta).abs(), (a - b).abs().max((a - c).abs()));
            assert!((a - b).abs() < 1e-12 && (a - c).abs() < 1e-12, "t = {t}: cranks {a} {b} {c}");
            assert!(ThreeCranks::COUPLER.phi(q).abs() < 1e-9, "the coupler translates");
            // The rule for the reactions: the dropped row carries no load (here the same row the
            // report names, the last one, `third: y`; its pivot is rounding, weighted by < 1e-64);
            // the others carry all of it (~40 N).
            assert!(s.point.lambda[11].abs() < 1e-12, "t = {t}: λ = {:?}", s.point.lambda);
            k += 1;
        })
        .expect("the redundant row is dropped, not an error");
    assert_eq!(k, times.len());
}

/// A NaN in D (here from a NaN parameter) is an error naming its row, not a report.
#[test]
fn a_nan_in_the_jacobian_is_named() {
    let m = ThreeCranks { r: f64::NAN };
    let mut ws = ThreeCranks::workspace();
    let q = ThreeCranks::default().initial_positions();
    match KinematicSolver::default().redundancy(&m, &mut ws, &q, 0.0) {
        Err(KinematicError::NonFinite { row, .. }) => assert_eq!(row, "revolute ground~c1: x"),
        other => panic!("expected a non-finite Jacobian row, got {other:?}"),
    }
}

/// Statics with a redundant row (a new user's third crank stopped with "singular" before): the
/// row that depends on those declared before it is dropped with λ = 0, as in forward dynamics,
/// and the solver finds the hanging pose from a guess 0.7 rad away with the stability of the
/// one-degree-of-freedom linkage: V(θ) = g sin θ (3 m_c r/2 + m_k r) about θ = −π/2, and the
/// inertia of three cranks about their pins plus the coupler's translation, so
/// ω² = g (3 · 0.15 + 2 · 0.3) / (3 (0.0075 + 0.0225) + 2 · 0.09) = 10.3005 / 0.27.
#[test]
fn statics_drops_the_redundant_row() {
    let m = ThreeCranks::default();
    let mut ws = ThreeCranks::workspace();
    let mut q = [0.0; 12];
    let (s, c, r) = (0.7f64.sin(), 0.7f64.cos(), m.r);
    for (k, x) in [0.0, 0.5, 1.0].into_iter().enumerate() {
        q[3 * k..3 * k + 3].copy_from_slice(&[x + 0.5 * r * c, 0.5 * r * s, 0.7]);
    }
    q[9..12].copy_from_slice(&[0.5 + r * c, r * s, 0.0]);
    let mut lambda = [0.0; 12];
    let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("a redundant mechanism has an equilibrium");
    let down = -std::f64::consts::FRAC_PI_2;
    for crank in [ThreeCranks::C1, ThreeCranks::C2, ThreeCranks::C3] {
        // the solver's tolerance 1e-9 (N·m over a stiffness of 10 N·m/rad), with margin
        assert!((crank.phi(&q) - down).abs() < 1e-9, "{}: {}", crank.name, crank.phi(&q));
    }
    let expected = 9.81 * (3.0 * 0.15 + 2.0 * 0.3) / 0.27;
    match report.stability {
        Stability::Stable { omega_squared } => assert!((omega_squared - expected).abs() < 1e-6 * expected, "ω² = {omega_squared}"),
        other => panic!("{other:?}"),
    }
    // The dropped row (the last one: `third`'s second, which the parallel cranks repeat)
    // carries nothing; the ground pins carry the weight, 5 kg × g, between them.
    assert_eq!(lambda[11], 0.0, "λ = {lambda:?}");
    let mut d = [[0.0; 12]; 12];
    m.jacobian(&q, 0.0, &mut d);
    let lift: f64 =
        [0usize, 1, 2].into_iter().filter_map(|j| joint_reaction(&m, &q, &d, &lambda, j).and_then(|r| r.on_j)).map(|w| w.force[1]).sum();
    assert!((lift.abs() - 5.0 * 9.81).abs() < 1e-8, "ground pins carry {lift} N");
}

mechanism! {
    /// `ThreeCranks` driven at its first crank, θ = 0.7 + t: 13 rows for 12 velocities, one
    /// of them redundant.
    pub DrivenThreeCranks {
        gravity [0.0, -9.81];
        params { r: 0.3 }
        body c1 { mass: 1.0, inertia: 0.0075, at: [0.115, 0.097, 0.7] }
        body c2 { mass: 1.0, inertia: 0.0075, at: [0.615, 0.097, 0.7] }
        body c3 { mass: 1.0, inertia: 0.0075, at: [1.115, 0.097, 0.7] }
        body coupler { mass: 2.0, inertia: 0.1, at: [0.729, 0.193, 0.0] }
        revolute ground[0.0, 0.0] ~ c1[-r / 2.0, 0.0];
        revolute ground[0.5, 0.0] ~ c2[-r / 2.0, 0.0];
        revolute ground[1.0, 0.0] ~ c3[-r / 2.0, 0.0];
        revolute c1[r / 2.0, 0.0] ~ coupler[-0.5, 0.0];
        revolute c2[r / 2.0, 0.0] ~ coupler[0.0, 0.0];
        revolute third: c3[r / 2.0, 0.0] ~ coupler[0.5, 0.0];
        drive motor: c1.phi = 0.7 + t;
    }
}

/// Kinematic and inverse-dynamic analysis of a driven mechanism with a redundant row (13 rows,
/// 12 velocities; a new user's would stop at "1 more constraint row than coordinates"): the
/// sweep solves over the independent rows — every crank turns at the driver's 1 rad/s with
/// no angular acceleration, the coupler translates — and inverse dynamics gives the driver
/// torque of the 1-DOF energy balance, τ = dV/dθ = g (3 m_c r/2 + m_k r) cos θ (the kinetic
/// energy ½ J ω² is constant at ω = 1), with the dropped row carrying nothing.
#[test]
fn a_driven_redundant_mechanism_sweeps_and_gives_its_driver_torque() {
    let m = DrivenThreeCranks::default();
    let mut ws = DrivenThreeCranks::workspace();
    let mut inverse_ws = DrivenThreeCranks::workspace();
    let mut q = m.initial_positions();
    let solver = KinematicSolver::default();
    let mut points = 0;
    solver
        .sweep(&m, &mut ws, &mut q, (0..=40).map(|k| 0.05 * k as f64), |t, q, v, vd| {
            points += 1;
            let theta = 0.7 + t;
            for crank in [DrivenThreeCranks::C1, DrivenThreeCranks::C2, DrivenThreeCranks::C3] {
                // the solve's tolerance 1e-10 on positions, its rounding on v and v̇
                assert!((crank.phi(q) - theta).abs() < 1e-9, "t = {t}: {} at {}", crank.name, crank.phi(q));
                assert!((crank.omega(v) - 1.0).abs() < 1e-9 && crank.alpha(vd).abs() < 1e-9, "t = {t}: {}", crank.name);
            }
            let coupler = DrivenThreeCranks::COUPLER;
            assert!(coupler.omega(v).abs() < 1e-9 && (coupler.velocity(v).norm() - 0.3).abs() < 1e-9, "the coupler translates at r ω");
            let mut lambda = [0.0; 13];
            InverseDynamics::default()
                .solve(&m, &mut inverse_ws, q, v, vd, t, &mut lambda)
                .expect("redundant rows are dropped, not an error");
            let expected = 9.81 * (3.0 * 0.15 + 2.0 * 0.3) * theta.cos();
            let motor = joint_reaction(&m, q, inverse_ws.jacobian(), &lambda, DrivenThreeCranks::MOTOR).and_then(|j| j.on_i).unwrap();
            // the driver's moment on the crank is the drive torque, holding it against gravity
            // (to the solve's rounding)
            assert!((motor.moment[2] - expected).abs() < 1e-9, "t = {t}: driver torque {} vs {expected}", motor.moment[2]);
            assert_eq!(lambda[11], 0.0, "the dropped row ('third: y') carries nothing: {lambda:?}");
        })
        .expect("a driven mechanism with a redundant row sweeps");
    assert_eq!(points, 41);
}

/// Minimum-norm reactions: from statics' λ (the dropped row carrying nothing), the reactions of
/// least norm with the same generalized constraint force, against an independent pseudo-inverse
/// (nalgebra's SVD): λ* = (Dᵀ)⁺ Dᵀ λ. The third crank then carries its share.
#[test]
fn minimum_norm_reactions_match_the_pseudo_inverse() {
    use mbd::nalgebra::{DMatrix, DVector};
    let m = ThreeCranks::default();
    let mut ws = ThreeCranks::workspace();
    let mut q = [0.0; 12];
    let (s, c, r) = (0.7f64.sin(), 0.7f64.cos(), m.r);
    for (k, x) in [0.0, 0.5, 1.0].into_iter().enumerate() {
        q[3 * k..3 * k + 3].copy_from_slice(&[x + 0.5 * r * c, 0.5 * r * s, 0.7]);
    }
    q[9..12].copy_from_slice(&[0.5 + r * c, r * s, 0.0]);
    let mut lambda = [0.0; 12];
    StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).unwrap();
    let before = lambda;
    KinematicSolver::default().minimum_norm_reactions(&m, &mut ws, &q, 0.0, &mut lambda).unwrap();
    let mut d = [[0.0; 12]; 12];
    m.jacobian(&q, 0.0, &mut d);
    let dt = DMatrix::from_fn(12, 12, |i, j| d[j][i]);
    let load = &dt * DVector::from_row_slice(&before);
    let expected = dt.clone().pseudo_inverse(1e-10).unwrap() * &load;
    // the same load (to rounding of ~50 N loads), the pseudo-inverse's λ to 1e-9 N
    let after = &dt * DVector::from_row_slice(&lambda);
    assert!((after - &load).amax() < 1e-10, "the load changed");
    for i in 0..12 {
        assert!((lambda[i] - expected[i]).abs() < 1e-9, "row {i}: {} vs pseudo-inverse {}", lambda[i], expected[i]);
    }
    let norm = |x: &[f64; 12]| x.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(norm(&lambda) < norm(&before) && lambda[11] != 0.0, "{before:?} → {lambda:?}");
}

/// More rows than velocities is not enough: the slider on two collinear guides has 4 rows for 3
/// velocities but only 2 independent ones, so its slide is not determined. The kinematic and
/// inverse-dynamic solves say which velocity is left free (`slider.x`) instead of solving.
#[test]
fn redundant_rows_that_leave_a_velocity_free_are_named() {
    let m = TwoGuides::default();
    let mut ws = TwoGuides::workspace();
    let q = m.initial_positions();
    let mut v = [0.0; 3];
    let err = KinematicSolver::default().solve_velocity(&m, &mut ws, &q, 0.0, &mut v).unwrap_err();
    assert!(matches!(err, KinematicError::SingularJacobian { coordinate: "slider.x", .. }), "{err:?}");
    let err = InverseDynamics::default().solve(&m, &mut ws, &q, &[0.0; 3], &[0.0; 3], 0.0, &mut [0.0; 4]).unwrap_err();
    assert!(matches!(err, InverseDynamicsError::SingularJacobian { velocity: "slider.x", .. }), "{err:?}");
    // The position solve meets Φ = 0 (the slider is on both guides) but the position along them
    // is not determined either.
    let mut q = m.initial_positions();
    let err = KinematicSolver::default().solve_position(&m, &mut ws, &mut q, 0.0).unwrap_err();
    assert!(matches!(err, KinematicError::SingularJacobian { coordinate: "slider.x", .. }), "{err:?}");
}

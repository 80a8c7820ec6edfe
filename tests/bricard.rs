//! A Bricard linkage (issue 10, item 2): six links in a closed loop of six revolute joints, in
//! space. Grübler–Kutzbach counts 5 · 6 − 6 · 5 = 0 — it should not move — yet the
//! line-symmetric Bricard linkage (opposite links equal: a_i = a_{i+3}, α_i = α_{i+3},
//! d_i = d_{i+3}; Bricard 1897) moves with one degree of freedom, every joint angle equal to the
//! opposite one, θ_i = θ_{i+3}, all along its motion. One of its 30 constraint rows repeats what
//! the others impose: the runtime must find it, report mobility 1 against Grübler's 0 at every
//! configuration (a redundancy, not a singular pose), simulate the one motion, find its static
//! equilibrium, and give the reactions by its documented rule (the dropped row carries none).
//! Which row the sparse factorization drops is the one its elimination order meets last in the
//! dependent loop — here not the row the report names, which is the last declared.
//!
//! Geometry in Denavit–Hartenberg terms: link i carries joint i (its z-axis, at its frame's
//! origin) and joint i + 1 at (a_i, 0, d_i), along (0, −sin α_i, cos α_i). Link 6 is the ground;
//! joint 1 is the global z-axis. Each link's centre of mass is the middle of its common normal.
//! The initial poses are a solution of the loop closure Π Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i) = I
//! (numpy, θ = (−2.603443, −3.460582, 2.877449) twice), rounded to 6 digits and assembled by
//! the solver.
use mbd::prelude::*;
use mbd::{Point, System};

#[path = "common/joint.rs"]
#[allow(dead_code)] // this file uses the macro only
mod joint;
use joint::both_ways;

both_ways! {
    /// A line-symmetric Bricard linkage of five moving links and the ground (`BricardJoint`: in
    /// joint coordinates, the tree carrying j1–j5 and the loop cut at j6).
    Bricard, BricardJoint {
        spatial;
        params { a1: 0.4, a2: 0.5, a3: 0.3, al1: 0.9, al2: 1.4, al3: 2.1, d1: 0.05, d2: -0.08, d3: 0.06 }
        gravity [0.0, 0.0, -9.81];
        body l1 { mass: 1.0, inertia: [0.002, 0.02, 0.02], at: [-0.171732, -0.10251, 0.025], quaternion: [0.26584, 0.0, 0.0, -0.964017] }
        body l2 { mass: 1.2, inertia: [0.002, 0.03, 0.03], at: [-0.098589, -0.152098, 0.08655], quaternion: [0.895046, -0.395628, -0.180759, 0.098474] }
        body l3 { mass: 0.8, inertia: [0.002, 0.01, 0.01], at: [-0.003022, -0.131315, 0.131727], quaternion: [0.066382, 0.038078, 0.281478, -0.956511] }
        body l4 { mass: 1.0, inertia: [0.002, 0.02, 0.02], at: [0.025456, -0.115496, 0.058394], quaternion: [0.694182, -0.685174, 0.109561, 0.191429] }
        body l5 { mass: 1.2, inertia: [0.002, 0.03, 0.03], at: [-0.04838, -0.059666, 0.003362], quaternion: [0.023473, 0.129579, 0.339912, 0.931192] }
        revolute j1: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0]
            ~ l1[-a1 / 2.0, 0.0, -d1 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j2: l1[a1 / 2.0, 0.0, d1 / 2.0] along [0.0, -sin(al1), cos(al1)] reference [1.0, 0.0, 0.0]
            ~ l2[-a2 / 2.0, 0.0, -d2 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j3: l2[a2 / 2.0, 0.0, d2 / 2.0] along [0.0, -sin(al2), cos(al2)] reference [1.0, 0.0, 0.0]
            ~ l3[-a3 / 2.0, 0.0, -d3 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j4: l3[a3 / 2.0, 0.0, d3 / 2.0] along [0.0, -sin(al3), cos(al3)] reference [1.0, 0.0, 0.0]
            ~ l4[-a1 / 2.0, 0.0, -d1 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j5: l4[a1 / 2.0, 0.0, d1 / 2.0] along [0.0, -sin(al1), cos(al1)] reference [1.0, 0.0, 0.0]
            ~ l5[-a2 / 2.0, 0.0, -d2 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j6: l5[a2 / 2.0, 0.0, d2 / 2.0] along [0.0, -sin(al2), cos(al2)] reference [1.0, 0.0, 0.0]
            ~ ground[-a3, -d3 * sin(al3), -d3 * cos(al3)] along [0.0, sin(al3), cos(al3)] reference [1.0, 0.0, 0.0];
    }
}

mechanism! {
    /// The same linkage with joint 1 driven, θ₁ = t: the independent check of statics below
    /// scans its potential energy along the one motion (a copy of the text above plus the
    /// driver, as the DSL cannot yet derive a driven variant; issue 12's scenes).
    pub BricardDriven {
        spatial;
        params { a1: 0.4, a2: 0.5, a3: 0.3, al1: 0.9, al2: 1.4, al3: 2.1, d1: 0.05, d2: -0.08, d3: 0.06 }
        gravity [0.0, 0.0, -9.81];
        body l1 { mass: 1.0, inertia: [0.002, 0.02, 0.02], at: [-0.171732, -0.10251, 0.025], quaternion: [0.26584, 0.0, 0.0, -0.964017] }
        body l2 { mass: 1.2, inertia: [0.002, 0.03, 0.03], at: [-0.098589, -0.152098, 0.08655], quaternion: [0.895046, -0.395628, -0.180759, 0.098474] }
        body l3 { mass: 0.8, inertia: [0.002, 0.01, 0.01], at: [-0.003022, -0.131315, 0.131727], quaternion: [0.066382, 0.038078, 0.281478, -0.956511] }
        body l4 { mass: 1.0, inertia: [0.002, 0.02, 0.02], at: [0.025456, -0.115496, 0.058394], quaternion: [0.694182, -0.685174, 0.109561, 0.191429] }
        body l5 { mass: 1.2, inertia: [0.002, 0.03, 0.03], at: [-0.04838, -0.059666, 0.003362], quaternion: [0.023473, 0.129579, 0.339912, 0.931192] }
        revolute j1: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0]
            ~ l1[-a1 / 2.0, 0.0, -d1 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j2: l1[a1 / 2.0, 0.0, d1 / 2.0] along [0.0, -sin(al1), cos(al1)] reference [1.0, 0.0, 0.0]
            ~ l2[-a2 / 2.0, 0.0, -d2 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j3: l2[a2 / 2.0, 0.0, d2 / 2.0] along [0.0, -sin(al2), cos(al2)] reference [1.0, 0.0, 0.0]
            ~ l3[-a3 / 2.0, 0.0, -d3 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j4: l3[a3 / 2.0, 0.0, d3 / 2.0] along [0.0, -sin(al3), cos(al3)] reference [1.0, 0.0, 0.0]
            ~ l4[-a1 / 2.0, 0.0, -d1 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j5: l4[a1 / 2.0, 0.0, d1 / 2.0] along [0.0, -sin(al1), cos(al1)] reference [1.0, 0.0, 0.0]
            ~ l5[-a2 / 2.0, 0.0, -d2 / 2.0] along [0.0, 0.0, 1.0] reference [1.0, 0.0, 0.0];
        revolute j6: l5[a2 / 2.0, 0.0, d2 / 2.0] along [0.0, -sin(al2), cos(al2)] reference [1.0, 0.0, 0.0]
            ~ ground[-a3, -d3 * sin(al3), -d3 * cos(al3)] along [0.0, sin(al3), cos(al3)] reference [1.0, 0.0, 0.0];
        drive j1.angle = t;
    }
}

/// θ_i − θ_{i+3} for the three opposite pairs, wrapped into (−π, π].
fn asymmetry(m: &Bricard, q: &[f64; 35]) -> f64 {
    let pairs = [(m.j1_angle(q), m.j4_angle(q)), (m.j2_angle(q), m.j5_angle(q)), (m.j3_angle(q), m.j6_angle(q))];
    pairs
        .iter()
        .map(|(a, b)| (a - b + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI)
        .fold(0.0, |s, x| s.max(x.abs()))
}

/// The row of least |λ|: the one the factorization drops.
fn dropped_row(lambda: &[f64; 30]) -> usize {
    (0..30).min_by(|&a, &b| lambda[a].abs().total_cmp(&lambda[b].abs())).expect("30 rows")
}

fn assembled(m: &Bricard, ws: &mut Workspace<f64, 30, 30, 60, { Bricard::NEWTON_STORAGE }>) -> [f64; 35] {
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(m, ws, &mut q, 0.0).expect("the Bricard linkage assembles from its rounded pose");
    q
}

/// The redundancy report: one redundant row, rank 29 of 30, mobility 1 against Grübler's 0,
/// and the same at other configurations of the motion (a singular pose would change it). The
/// loop closes: the joints' angles keep the line symmetry (the rounded pose was 1e-6 off it).
#[test]
fn bricard_has_one_redundant_row() {
    let m = Bricard::default();
    let mut ws = Bricard::workspace();
    let q = assembled(&m, &mut ws);
    // assembly to the solver's tolerance; the symmetry then holds to the assembly's accuracy
    // (the closure itself forces it: the rounded pose's 1e-6 asymmetry is gone)
    let mut phi = [0.0; 30];
    m.constraints(&q, 0.0, &mut phi);
    assert!(phi.iter().all(|x| x.abs() <= 1e-10), "Φ = {phi:?}");
    assert!(asymmetry(&m, &q) < 1e-9, "θ_i − θ_(i+3) up to {}", asymmetry(&m, &q));
    let report = KinematicSolver::default().redundancy(&m, &mut ws, &q, 0.0).unwrap();
    eprintln!("{report}");
    assert_eq!((report.grubler, report.mobility, report.rank), (0, 1, 29), "{report}");
    let named: Vec<&str> = report.redundant_names().collect();
    assert_eq!(named.len(), 1);
    assert!(named[0].starts_with("j6"), "the last-declared joint closes the loop: {named:?}");
    // A clear-cut rank: the row named lies in the others' span to rounding, the kept rows are far
    // from it (measured 2.9e-13 against 1.3e-1; the rank tolerance is 1e-8).
    assert!(report.largest_redundant < 1e-10 && report.smallest_kept > 1e-3, "{report:?}");
}

/// Released at rest under gravity, it moves with its one degree of freedom (DOPRI5, the default
/// options: the dependent row is dropped smoothly, the projection keeps Φ): the line symmetry
/// holds, Φ stays at the projection's tolerance, the energy is conserved, the mobility stays 1
/// along the way (a redundancy, not a singular pose), and the dropped row carries no load.
#[test]
fn bricard_moves_with_one_degree_of_freedom() {
    let m = Bricard::default();
    let mut ws = Bricard::workspace();
    let q0 = assembled(&m, &mut ws);
    let e0 = m.potential_energy(&q0, 0.0);
    let times: Vec<f64> = (1..=40).map(|k| 0.05 * k as f64).collect();
    let (mut worst_sym, mut worst_phi, mut worst_e, mut moved, mut worst_dropped) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut samples = Vec::new();
    let mut dropped = None;
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q0, &[0.0; 30])
        .times(&times)
        .run(&mut ws, |s| {
            let q = &s.point.q;
            let mut phi = [0.0; 30];
            m.constraints(q, s.point.t, &mut phi);
            worst_phi = phi.iter().fold(worst_phi, |w, x| w.max(x.abs()));
            worst_sym = worst_sym.max(asymmetry(&m, q));
            worst_e = worst_e.max((s.energy.kinetic + s.energy.potential - e0).abs());
            moved = moved.max((m.j1_angle(q) - m.j1_angle(&q0)).abs());
            let row = dropped_row(&s.point.lambda);
            assert_eq!(*dropped.get_or_insert(row), row, "the dropped row is one row all along");
            worst_dropped = worst_dropped.max(s.point.lambda[row].abs());
            samples.push(*q);
        })
        .expect("the Bricard linkage moves");
    eprintln!("Bricard 2 s: θ1 moved up to {moved:.3} rad, asymmetry {worst_sym:.1e} rad, ‖Φ‖ {worst_phi:.1e}, |ΔE| {worst_e:.1e} J, dropped λ {worst_dropped:.1e}");
    assert!(moved > 0.3, "it should swing: θ1 moved {moved} rad");
    // the symmetry, kept by the constraints and the projection (measured 2.3e-12)
    assert!(worst_sym < 1e-9, "θ_i − θ_(i+3) up to {worst_sym}");
    // Φ at the projection's tolerance (1e-10; measured 1.2e-12); energy at rtol 1e-10 over 2 s
    // of a swing through several joules (measured 2.9e-11 J, bound 300× above)
    assert!(worst_phi < 1e-10, "‖Φ‖ = {worst_phi}");
    assert!(worst_e < 1e-8, "|ΔE| = {worst_e} J");
    // the row dropped by the smooth pivot rule: its weight w = 1/(1 + ρ⁸) is ~1e-40 at an exact
    // redundancy (measured λ 1.9e-48 N)
    assert!(worst_dropped < 1e-9, "λ of the dropped row up to {worst_dropped} N");
    for q in samples.iter().step_by(10) {
        let report = KinematicSolver::default().redundancy(&m, &mut ws, q, 0.0).unwrap();
        assert_eq!((report.grubler, report.mobility), (0, 1), "{report}");
    }
}

/// Coordinate partitioning (issue 39, item 6) on the same loop, with the default options: the
/// redundant row is dropped from the choice, so 29 rows decide 29 dependent velocities and one
/// stays independent (before, the run stopped at t = 0 advising `allow_redundant`, which was
/// on). The motion is the projection's: the line symmetry, Φ and the energy hold as above, and
/// θ₁ follows the projected run to DOPRI5's accuracy. With `allow_redundant` off the error names
/// a row of the loop and its advice is then true.
#[test]
fn bricard_partitioning_drops_its_redundant_row() {
    let m = Bricard::default();
    let mut ws = Bricard::workspace();
    let q0 = assembled(&m, &mut ws);
    let e0 = m.potential_energy(&q0, 0.0);
    let times: Vec<f64> = (1..=20).map(|k| 0.05 * k as f64).collect();
    let run = |correction: Correction, dynamics: DynamicsOptions, ws: &mut Workspace<f64, 30, 30, 60, { Bricard::NEWTON_STORAGE }>| {
        let mut out = Vec::new();
        let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
        let options = SimulationOptions::default().with_correction(correction).with_dynamics(dynamics);
        Simulation::new(&m, &mut dopri)
            .start(0.0, &q0, &[0.0; 30])
            .times(&times)
            .options(options)
            .run(ws, |s| out.push((s.point.q, s.energy.kinetic + s.energy.potential)))
            .map(|_| out)
    };
    let free = DynamicsOptions::without_stabilization();
    let partitioned = run(Correction::partitioning(), free, &mut ws).expect("partitioning drops the redundant row");
    let projected = run(Correction::projection(), free, &mut ws).expect("projection");
    let (mut worst_sym, mut worst_phi, mut worst_e, mut apart, mut moved) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for ((q, e), (p, _)) in partitioned.iter().zip(&projected) {
        let mut phi = [0.0; 30];
        m.constraints(q, 0.0, &mut phi);
        worst_phi = phi.iter().fold(worst_phi, |w, x| w.max(x.abs()));
        worst_sym = worst_sym.max(asymmetry(&m, q));
        worst_e = worst_e.max((e - e0).abs());
        apart = apart.max((m.j1_angle(q) - m.j1_angle(p)).abs());
        moved = moved.max((m.j1_angle(q) - m.j1_angle(&q0)).abs());
    }
    eprintln!("Bricard, partitioning 1 s: θ1 moved {moved:.3} rad, {apart:.1e} rad from projection, asymmetry {worst_sym:.1e}, ‖Φ‖ {worst_phi:.1e}, |ΔE| {worst_e:.1e} J");
    assert!(moved > 0.1, "it should swing: θ1 moved {moved} rad");
    // partitioning's tolerance 1e-10 on every row, the dropped one included
    assert!(worst_phi < 1e-10, "‖Φ‖ = {worst_phi}");
    // as with projection above (kept by the constraints; energy at rtol 1e-10 over 1 s)
    assert!(worst_sym < 1e-9, "θ_i − θ_(i+3) up to {worst_sym}");
    assert!(worst_e < 1e-8, "|ΔE| = {worst_e} J");
    // two corrections of one motion, each integrated at rtol 1e-10: 1e-7 rad is 1000 rtol
    assert!(apart < 1e-7, "θ1 differs from the projected run by {apart} rad");
    let strict = free.with_allow_redundant(false);
    let err = run(Correction::partitioning(), strict, &mut ws).unwrap_err();
    assert!(matches!(err, SimulationError::Dynamics(DynamicsError::DependentConstraint { t: 0.0, row }) if row.contains('j')), "{err:?}");
    assert!(err.to_string().contains("allow_redundant"), "{err}");
}

/// Advice that is true where it is given (issue 39, item 6). The runtime's errors that name an
/// option: `DependentConstraint` (`DynamicsOptions::allow_redundant`, here),
/// `ToleranceBelowResolution` (`ErrorControl::with_per_unit_time(false)`, given only where it
/// is on: `tests/integrators.rs`) and generalized-α's fixed-step `NotConverged`
/// (`with_max_iterations`, a shorter step, `with_error_control`, each run where it is given:
/// `tests/friction.rs`). `allow_redundant` drops a dependent row.
/// Under the default options no path meets it on this loop with its one redundant row: the
/// generated factorization in body coordinates, the dense one in joint coordinates, the
/// projection, generalized-α's Newton matrix and partitioning (above) all drop the row. With
/// the option off, each path refuses the row and its message says the option is off.
#[test]
fn dependent_row_advice_is_given_only_with_the_option_off() {
    let strict = DynamicsOptions::without_stabilization().with_allow_redundant(false);
    let refused = |err: DynamicsError, path: &str| {
        assert!(matches!(err, DynamicsError::DependentConstraint { .. }), "{path}: {err:?}");
        assert!(err.to_string().contains("allow_redundant, off in this solve"), "{path}: {err}");
    };
    let m = Bricard::default();
    let mut ws = Bricard::workspace();
    let q0 = assembled(&m, &mut ws);
    let (mut vd, mut lambda) = ([0.0; 30], [0.0; 30]);
    m.accelerations(&q0, &[0.0; 30], 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda).expect("generated, default");
    refused(m.accelerations(&q0, &[0.0; 30], 0.0, &strict, &mut vd, &mut lambda).unwrap_err(), "generated");
    let mut q = q0;
    m.project_positions_step(&mut q, 0.0, &DynamicsOptions::default()).expect("projection, default");
    refused(m.project_positions_step(&mut q, 0.0, &strict).unwrap_err(), "projection");

    let joint = BricardJoint::default();
    let mut joint_ws = BricardJoint::workspace();
    let mut p = joint.initial_positions();
    KinematicSolver::default().assemble(&joint, &mut joint_ws, &mut p, 0.0).unwrap();
    let (mut pd, mut mu) = ([0.0; 5], [0.0; 5]);
    joint.accelerations(&p, &[0.0; 5], 0.0, &DynamicsOptions::default(), &mut pd, &mut mu).expect("dense, default");
    refused(joint.accelerations(&p, &[0.0; 5], 0.0, &strict, &mut pd, &mut mu).unwrap_err(), "dense (joint coordinates)");

    let mut from = Point::<f64, 35, 30, 30>::zero();
    from.q = q0;
    let mut to = Point::zero();
    let mut alpha = Bricard::generalized_alpha(GeneralizedAlphaOptions::default().with_step(1e-3));
    alpha.step(&System::new(&m), &mut ws, &from, 1e-3, &mut to).expect("generalized-α, default");
    let system = System { dynamics: strict, ..System::new(&m) };
    match alpha.step(&system, &mut ws, &from, 1e-3, &mut to).unwrap_err() {
        SimulationError::Dynamics(err) => refused(err, "generalized-α"),
        other => panic!("generalized-α: {other:?}"),
    }
}

/// Statics with the redundant row: the hanging equilibrium, stable, symmetric, with the dropped
/// row's multiplier 0 and the mobility's one mode, checked along the motion of a driven copy.
#[test]
fn bricard_statics_finds_its_hanging_pose() {
    let m = Bricard::default();
    let mut ws = Bricard::workspace();
    let mut q = assembled(&m, &mut ws);
    let mut lambda = [0.0; 30];
    let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("an equilibrium");
    eprintln!("Bricard statics: {report:?}, θ1 = {}", m.j1_angle(&q));
    assert!(
        matches!(report.stability, Stability::Stable { omega_squared } if omega_squared > 0.0 && omega_squared.is_finite()),
        "{report:?}"
    );
    assert!(asymmetry(&m, &q) < 1e-9, "θ_i − θ_(i+3) up to {}", asymmetry(&m, &q));
    // One row is dropped, with λ = 0; every other carries load.
    let row = dropped_row(&lambda);
    assert_eq!(lambda[row], 0.0, "row {row}");
    let others = (0..30).filter(|&r| r != row).map(|r| lambda[r].abs()).fold(f64::INFINITY, f64::min);
    eprintln!("dropped: row {row}, {}; the smallest other |λ| {others:.3e}", Bricard::CONSTRAINT_NAMES[row]);
    assert!(others > 1e-3, "row {row} dropped, the smallest other |λ| {others} N");
    // Independently, along the one motion of the driven copy (positions and velocities by the
    // kinematic solver over the independent rows): the slope of the potential dV/dθ₁ = −hᵀv
    // (v for θ̇₁ = 1 rad/s, h gravity's generalized force) vanishes at the statics' θ₁, and
    // ω² = V″/J with V″ from the slopes at θ₁ ± δ (δ = 1e-3: error δ² V⁗/6 ≈ 1e-7 relative) and
    // J = vᵀ M v. (V itself cannot locate the minimum better than √(Φ-tolerance · m g / V″) ≈
    // 1e-4 rad: the slope is what the positions' tolerance leaves accurate.)
    let driven = BricardDriven::default();
    let mut dws = BricardDriven::workspace();
    let solver = KinematicSolver::default();
    let mut slope_at = |theta: f64| {
        let state = solver.analyze(&driven, &mut dws, &q, theta).expect("the driven Bricard linkage solves");
        let mut h = [0.0; 30];
        driven.forces(&state.q, &state.v, theta, &mut h);
        let mut mv = [0.0; 30];
        driven.mass_times(&state.q, &state.v, &mut mv);
        let dot = |a: &[f64; 30], b: &[f64; 30]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        (-dot(&h, &state.v), dot(&state.v, &mv))
    };
    let theta_star = m.j1_angle(&q);
    let (slope, inertia) = slope_at(theta_star);
    let delta = 1e-3;
    let second = (slope_at(theta_star + delta).0 - slope_at(theta_star - delta).0) / (2.0 * delta);
    let Stability::Stable { omega_squared } = report.stability else { unreachable!("checked above") };
    eprintln!(
        "Bricard at θ₁ = {theta_star}: dV/dθ₁ = {slope:.1e} N·m, ω² statics {omega_squared}, from the slopes {} (V″ {second}, J {inertia})",
        second / inertia
    );
    // the statics tolerance 1e-9 on each generalized force, times Σ|v| ≈ 1 m/s per rad/s
    assert!(slope.abs() < 1e-8, "dV/dθ₁ = {slope} N·m at the statics' equilibrium");
    assert!((omega_squared - second / inertia).abs() < 1e-5 * omega_squared, "ω² {omega_squared} vs {}", second / inertia);
    // and the solver's own residual, h + Dᵀλ = 0, to its tolerance
    let mut h = [0.0; 30];
    m.forces(&q, &[0.0; 30], 0.0, &mut h);
    let mut d = [[0.0; 30]; 30];
    m.jacobian(&q, 0.0, &mut d);
    let residual = (0..30).map(|i| (h[i] + (0..30).map(|r| d[r][i] * lambda[r]).sum::<f64>()).abs()).fold(0.0, f64::max);
    assert!(residual < 1e-8, "‖h + Dᵀλ‖ = {residual}");
    // The reactions of least norm for the same load, against nalgebra's pseudo-inverse.
    let before = lambda;
    KinematicSolver::default().minimum_norm_reactions(&m, &mut ws, &q, 0.0, &mut lambda).unwrap();
    let dt = mbd::nalgebra::DMatrix::from_fn(30, 30, |i, j| d[j][i]);
    let expected = dt.clone().pseudo_inverse(1e-10).unwrap() * (&dt * mbd::nalgebra::DVector::from_row_slice(&before));
    for i in 0..30 {
        // loads of ~50 N, rounding of the two computations: 1e-9 N
        assert!((lambda[i] - expected[i]).abs() < 1e-9, "row {i}: {} vs pseudo-inverse {}", lambda[i], expected[i]);
    }
}

/// In joint coordinates the same linkage is five angles and the cut joint j6's five rows, of
/// rank 4: the report finds the one redundant closure row there too, mobility 1 against
/// Grübler's 0 (issue 38: "a Bricard-like loop cut once: 5 closure rows of rank 4").
#[test]
fn bricard_in_joint_coordinates_has_one_redundant_closure_row() {
    let m = BricardJoint::default();
    let mut ws = BricardJoint::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the Bricard linkage assembles in joint coordinates");
    assert_eq!(BricardJoint::CONSTRAINT_NAMES.len(), 5, "{:?}", BricardJoint::CONSTRAINT_NAMES);
    assert!(BricardJoint::CONSTRAINT_NAMES.iter().all(|n| n.starts_with("j6")), "{:?}", BricardJoint::CONSTRAINT_NAMES);
    let mut phi = [0.0; 5];
    m.constraints(&q, 0.0, &mut phi);
    assert!(phi.iter().all(|x| x.abs() <= 1e-10), "Φ = {phi:?}");
    let report = KinematicSolver::default().redundancy(&m, &mut ws, &q, 0.0).unwrap();
    assert_eq!((report.grubler, report.mobility, report.rank), (0, 1, 4), "{report}");
    assert!(report.largest_redundant < 1e-10 && report.smallest_kept > 1e-3, "{report:?}");
    // the closure forces the line symmetry θ_i = θ_(i+3) on the angles the tree carries
    // (tolerance: the assembly's, as for body coordinates above)
    let apart = |a: f64, b: f64| ((a - b + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI).abs();
    assert!(apart(q[0], q[3]) < 1e-9 && apart(q[1], q[4]) < 1e-9, "θ = {q:?}");
}

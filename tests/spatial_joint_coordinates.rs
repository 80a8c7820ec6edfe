//! Spatial joint coordinates (`joint_coordinates;` with `spatial;`) against spatial body
//! coordinates: the same `mechanism!` text compiled both ways must describe the same physics.
//! At the same physical state — the joint state mapped to body coordinates through the
//! generated body frames — the body-coordinate constraints vanish, the kinetic and potential
//! energies agree, and so do the bodies' accelerations.
//!
//! Tolerances: both formulations evaluate exact symbolic derivatives of the same geometry and
//! solve well-conditioned systems (masses 0.3–2 kg, lengths 0.1–1 m), so values agree to
//! rounding times the condition: 1e-10 relative to max(1, |value|) separates a right
//! formulation from a wrong one (a wrong term is O(0.1) or more).

use mbd::prelude::*;
use mbd::{BodyCoordinates, BodyPose, JointLoads};

#[path = "common/joint.rs"]
mod joint;
use joint::{both_ways, close, on_constraints, reactions_agree};

both_ways! {
    /// An arm: a base turning about z, an upper arm on a pin about the base's y axis, a forearm
    /// on a ball joint, with products of inertia, turned `at:` poses, a spring from the tip to
    /// the ground and a damper across the elbow.
    ArmBody, ArmJoint {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body base { mass: 2.0, inertia: [0.02, 0.02, 0.03], at: [0.0, 0.0, 0.1] }
        body upper { mass: 1.2, inertia: [0.05, 0.048, 0.006, 0.001, -0.002, 0.0015], at: [0.0, 0.0, 0.45], angles: [0.3, 0.0, 0.0] }
        body fore { mass: 0.6, inertia: [0.02, 0.021, 0.003, 0.0, 0.001, 0.0], at: [0.1, 0.1, 0.8], axis_angle: [1.0, 1.0, 0.0, 0.4] }
        point fore.tip = [0.02, -0.01, 0.15];
        revolute yaw: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ base[0.0, 0.0, -0.1] along [0.0, 0.0, 1.0];
        revolute shoulder: base[0.0, 0.0, 0.1] along [0.0, 1.0, 0.0] ~ upper[0.0, 0.0, -0.25] along [0.0, 1.0, 0.0];
        spherical wrist: upper[0.0, 0.0, 0.25] ~ fore[0.0, 0.0, -0.15];
        spring ground[0.3, 0.2, 0.0] ~ fore[0.0, 0.0, 0.15] { k: 40.0, length: 0.5, c: 0.5 };
        damper upper[0.0, 0.0, 0.0] ~ fore[0.0, 0.0, 0.0] { c: 0.7 };
    }
}

both_ways! {
    /// A slide along an inclined rail, a sleeve on a cylindrical joint about the slide's x axis
    /// (declared sleeve first, so the tree runs it backwards), a pendulum pinned to the sleeve
    /// about an axis opposite to its own (a half-turn between the markers).
    SlideBody, SlideJoint {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body slide { mass: 1.5, inertia: [0.01, 0.02, 0.02], at: [0.2, 0.0, 0.1] }
        body sleeve { mass: 0.5, inertia: [0.002, 0.004, 0.004], at: [0.3, 0.0, 0.1] }
        body bob { mass: 0.3, inertia: [0.003, 0.003, 0.0005], at: [0.3, 0.0, -0.1] }
        translational rail: ground[0.0, 0.0, 0.0] along [1.0, 0.0, 0.3] ~ slide[-0.2, 0.0, 0.04] along [1.0, 0.0, 0.3];
        cylindrical sleeve[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0] ~ slide[0.1, 0.0, 0.0] along [1.0, 0.0, 0.0];
        revolute sleeve[0.0, 0.0, 0.0] along [0.0, 1.0, 0.0] ~ bob[0.0, 0.0, 0.2] along [0.0, -1.0, 0.0];
        spring ground[0.0, 0.0, 0.0] ~ slide[0.0, 0.0, 0.0] { k: 20.0, length: 0.3 };
        spring slide[0.1, 0.0, 0.0] ~ sleeve[0.05, 0.0, 0.0] { k: 15.0, length: 0.05 };
    }
}

both_ways! {
    /// A body on no joint (a free joint in the tree: r, p and ṙ, ω′) tied by springs to a
    /// pendulum on a ball joint.
    FloatBody, FloatJoint {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body float { mass: 0.4, inertia: [0.004, 0.005, 0.006], at: [0.5, 0.2, 0.3], angles: [0.2, -0.1, 0.4], velocity: [0.1, -0.2, 0.3], omega: [0.5, -0.4, 1.0] }
        body arm { mass: 1.0, inertia: [0.08, 0.08, 0.01], at: [0.0, 0.0, -0.5] }
        spherical ground[0.0, 0.0, 0.0] ~ arm[0.0, 0.0, 0.5];
        spring float[0.05, 0.0, 0.0] ~ arm[0.0, 0.0, -0.5] { k: 30.0, length: 0.6 };
        spring float[-0.05, 0.0, 0.0] ~ ground[0.6, 0.0, 0.5] { k: 10.0, length: 0.2 };
    }
}

both_ways! {
    /// A spatial four-bar (RSSR): a crank about z, a rocker about x, a coupler on ball joints;
    /// the tree cuts one ball joint (three closure rows).
    LoopBody, LoopJoint {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body crank { mass: 0.5, inertia: [1.0e-3, 1.0e-3, 2.0e-3], at: [0.0, 0.0, 0.0] }
        body coupler { mass: 0.4, inertia: [4.0e-3, 4.0e-3, 1.0e-4], at: [0.25, 0.1, 0.05] }
        body rocker { mass: 0.6, inertia: [2.0e-3, 1.0e-3, 1.0e-3], at: [0.4, 0.2, 0.0] }
        revolute ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ crank[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
        spherical crank[0.1, 0.0, 0.0] ~ coupler[-0.15, -0.1, -0.05];
        spherical coupler[0.15, 0.1, 0.05] ~ rocker[0.0, 0.0, 0.1];
        revolute ground[0.4, 0.2, 0.0] along [1.0, 0.0, 0.0] ~ rocker[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0];
        damper ground[0.0, 0.3, 0.0] ~ coupler[0.0, 0.0, 0.0] { c: 2.0 };
    }
}

/// The body-coordinate state of a joint state, through the joint mechanism's body frames:
/// r, p per body and ṙ, ω′.
fn to_bodies<J, const NQJ: usize, const NVJ: usize, const NQB: usize, const NVB: usize>(
    j: &J,
    q: &[f64; NQJ],
    v: &[f64; NVJ],
) -> ([f64; NQB], [f64; NVB])
where
    J: BodyFrames<f64, NQJ, NVJ>,
{
    let (mut qb, mut vb) = ([0.0; NQB], [0.0; NVB]);
    for k in 0..NVB / 6 {
        let pose = j.body_pose(k, q).expect("a body");
        let twist = j.body_twist(k, q, v).expect("a body");
        qb[7 * k..7 * k + 3].copy_from_slice(&pose.position);
        qb[7 * k + 3..7 * k + 7].copy_from_slice(&euler_parameters(&pose.rotation));
        vb[6 * k..6 * k + 3].copy_from_slice(&twist.velocity);
        vb[6 * k + 3..6 * k + 6].copy_from_slice(&pose.to_body(twist.angular_velocity));
    }
    (qb, vb)
}

/// The Euler parameters of a rotation matrix (Shepperd's method).
fn euler_parameters(a: &[[f64; 3]; 3]) -> [f64; 4] {
    let trace = a[0][0] + a[1][1] + a[2][2];
    let candidates = [trace, a[0][0], a[1][1], a[2][2]];
    let k = (0..4).fold(0, |best, k| if candidates[k] > candidates[best] { k } else { best });
    match k {
        0 => {
            let e0 = 0.5 * (1.0 + trace).sqrt();
            [e0, (a[2][1] - a[1][2]) / (4.0 * e0), (a[0][2] - a[2][0]) / (4.0 * e0), (a[1][0] - a[0][1]) / (4.0 * e0)]
        }
        1 => {
            let e1 = 0.5 * (1.0 + a[0][0] - a[1][1] - a[2][2]).sqrt();
            [(a[2][1] - a[1][2]) / (4.0 * e1), e1, (a[0][1] + a[1][0]) / (4.0 * e1), (a[0][2] + a[2][0]) / (4.0 * e1)]
        }
        2 => {
            let e2 = 0.5 * (1.0 - a[0][0] + a[1][1] - a[2][2]).sqrt();
            [(a[0][2] - a[2][0]) / (4.0 * e2), (a[0][1] + a[1][0]) / (4.0 * e2), e2, (a[1][2] + a[2][1]) / (4.0 * e2)]
        }
        _ => {
            let e3 = 0.5 * (1.0 - a[0][0] - a[1][1] + a[2][2]).sqrt();
            [(a[1][0] - a[0][1]) / (4.0 * e3), (a[0][2] + a[2][0]) / (4.0 * e3), (a[1][2] + a[2][1]) / (4.0 * e3), e3]
        }
    }
}

/// At a joint state on the constraints: the body-coordinate constraints vanish there, and the
/// energies, each body's acceleration and every joint's reaction agree.
fn agree<B, J, const NQB: usize, const NVB: usize, const NCB: usize, const NQJ: usize, const NVJ: usize, const NCJ: usize>(
    b: &B,
    j: &J,
    q: &[f64; NQJ],
    v: &[f64; NVJ],
    t: f64,
) where
    B: ForwardDynamics<f64, NQB, NVB, NCB> + JointLoads<f64, NQB, NVB, NCB> + BodyCoordinates,
    J: ForwardDynamics<f64, NQJ, NVJ, NCJ> + JointLoads<f64, NQJ, NVJ, NCJ>,
{
    let (qb, vb) = to_bodies::<J, NQJ, NVJ, NQB, NVB>(j, q, v);
    let name = B::NAME;
    let mut phi = [0.0; NCB];
    b.constraints(&qb, t, &mut phi);
    // Tolerance: the joint state is on its cut rows to 1e-12; the tree's rows hold to rounding.
    assert!(phi.iter().all(|x| x.abs() < 1e-11), "{name}: Φ of the body model at the mapped state {phi:?}");
    let (tb, tj) = (mbd::kinetic_energy(b, &qb, &vb), mbd::kinetic_energy(j, q, v));
    assert!(close(tb, tj), "{name}: kinetic energy {tb} in body coordinates, {tj} in joint coordinates");
    let (vb_pot, vj_pot) = (b.potential_energy(&qb, t), j.potential_energy(q, t));
    assert!(close(vb_pot, vj_pot), "{name}: potential energy {vb_pot} vs {vj_pot}");
    let options = DynamicsOptions::without_stabilization();
    let (mut ab, mut lb) = ([0.0; NVB], [0.0; NCB]);
    b.accelerations(&qb, &vb, t, &options, &mut ab, &mut lb).expect("body-coordinate dynamics");
    let (mut aj, mut lj) = ([0.0; NVJ], [0.0; NCJ]);
    j.accelerations(q, v, t, &options, &mut aj, &mut lj).expect("joint-coordinate dynamics");
    for k in 0..NVB / 6 {
        let a = j.body_acceleration(k, q, v, &aj).expect("a body");
        let pose = j.body_pose(k, q).expect("a body");
        let angular = pose.to_body(a.angular_velocity);
        let from_joints = [a.velocity[0], a.velocity[1], a.velocity[2], angular[0], angular[1], angular[2]];
        for c in 0..6 {
            assert!(
                close(ab[6 * k + c], from_joints[c]),
                "{name}: body {} acceleration {c}: {} in body coordinates, {} in joint coordinates",
                B::BODY_NAMES[k],
                ab[6 * k + c],
                from_joints[c]
            );
        }
    }
    reactions_agree(b, (&qb, &vb, &ab, &lb), j, (q, v, &aj, &lj), t);
}

/// States spread over the joint space (deterministic), each quaternion normalized.
fn states<J: ForwardDynamics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    j: &J,
    count: usize,
) -> impl Iterator<Item = ([f64; NQ], [f64; NV], f64)> + '_ {
    (0..count).map(move |s| {
        let x = |i: usize, scale: f64| scale * ((s * 7 + i * 13) as f64 * 0.618_034).sin();
        let mut q: [f64; NQ] = core::array::from_fn(|i| x(i, 1.2));
        j.normalize_positions(&mut q);
        (q, core::array::from_fn(|i| x(i + NQ, 2.0)), 0.1 * s as f64)
    })
}

#[test]
fn spatial_trees_agree_with_body_coordinates() {
    let (b, j) = (ArmBody::default(), ArmJoint::default());
    assert_eq!(ArmJoint::COORDINATE_NAMES, &["yaw.angle", "shoulder.angle", "wrist.e0", "wrist.e1", "wrist.e2", "wrist.e3"]);
    assert_eq!((ArmJoint::VELOCITY_NAMES.len(), ArmJoint::CONSTRAINT_NAMES.len()), (5, 0));
    for (q, v, t) in states(&j, 20) {
        agree(&b, &j, &q, &v, t);
    }
    let (b, j) = (SlideBody::default(), SlideJoint::default());
    for (q, v, t) in states(&j, 20) {
        agree(&b, &j, &q, &v, t);
    }
    let (b, j) = (FloatBody::default(), FloatJoint::default());
    for (q, v, t) in states(&j, 20) {
        agree(&b, &j, &q, &v, t);
    }
}

#[test]
fn a_spatial_loop_agrees_with_body_coordinates() {
    let (b, j) = (LoopBody::default(), LoopJoint::default());
    assert_eq!(LoopJoint::CONSTRAINT_NAMES.len(), 3, "{:?}", LoopJoint::CONSTRAINT_NAMES);
    let mut checked = 0;
    for s in 0..20 {
        // assembled from the initial guess with the crank turned, velocities projected
        let t = 0.1 * s as f64;
        let (mut q, mut v) = (j.initial_positions(), [0.0; 5]);
        q[0] += 0.1 * s as f64;
        for (i, x) in v.iter_mut().enumerate() {
            *x = ((s * 5 + i * 3) as f64).sin();
        }
        on_constraints(&j, &mut q, &mut v, t);
        agree(&b, &j, &q, &v, t);
        checked += 1;
    }
    assert_eq!(checked, 20);
}

/// Every spatial example's mechanism, written once in `examples/`, compiled both ways
/// (`mbd-examples/build.rs` adds `joint_coordinates;`): from the joint coordinates' assembly
/// with the examples' initial velocities projected onto D v = ν, mapped to body coordinates,
/// both simulate 0.15 s with DOPRI5 at rtol 1e-11 and end at the same poses (tolerance: each
/// run's error is about 1e-11 here, and 1e-9 leaves room for both; a wrong term moves a body by
/// far more in 0.15 s).
#[test]
fn every_spatial_example_agrees_both_ways() {
    let mut count = 0;
    macro_rules! check {
        ($joint:ty, $body:ty, $label:expr) => {{
            type J = $joint;
            type B = $body;
            let (mj, mb) = (J::default(), B::default());
            let mut wj = J::workspace();
            let mut qj = mj.initial_positions();
            KinematicSolver::default().assemble(&mj, &mut wj, &mut qj, 0.0).expect($label);
            let mut vj = mj.initial_velocities();
            mj.project_velocities(&qj, &mut vj, 0.0, &DynamicsOptions::default()).expect($label);
            let (qb, vb) = to_bodies::<J, { J::NQ }, { J::NV }, { B::NQ }, { B::NV }>(&mj, &qj, &vj);
            let options = Dopri5Options::default().with_rtol(1e-11).with_atol(1e-13);
            let (mut end_j, mut end_b) = (qj, qb);
            Simulation::new(&mj, &mut Dopri5::new(options))
                .start(0.0, &qj, &vj)
                .times(&[0.15])
                .run(&mut wj, |s| end_j = s.point.q)
                .expect($label);
            Simulation::new(&mb, &mut Dopri5::new(options))
                .start(0.0, &qb, &vb)
                .times(&[0.15])
                .run(&mut B::workspace(), |s| end_b = s.point.q)
                .expect($label);
            for k in 0..B::NV / 6 {
                let p = mj.body_pose(k, &end_j).expect("a body");
                let other = BodyPose::spatial(
                    [end_b[7 * k], end_b[7 * k + 1], end_b[7 * k + 2]],
                    [end_b[7 * k + 3], end_b[7 * k + 4], end_b[7 * k + 5], end_b[7 * k + 6]],
                );
                let mut worst = (0..3).map(|c| (p.position[c] - other.position[c]).abs()).fold(0.0f64, f64::max);
                for r in 0..3 {
                    for c in 0..3 {
                        worst = worst.max((p.rotation[r][c] - other.rotation[r][c]).abs());
                    }
                }
                assert!(worst < 1e-9, "{}: body {} differs by {worst:e} at 0.15 s", $label, B::BODY_NAMES[k]);
            }
            // the run moved the mechanism (the slider-crank's crank turns 1.5 times)
            let moved = (0..B::NQ).map(|i| (end_b[i] - qb[i]).abs()).fold(0.0f64, f64::max);
            assert!(moved > 1e-3, "{}: moved {moved:e}", $label);
            count += 1;
        }};
    }
    mbd_examples::every_spatial_example_both_ways!(check);
    assert!(count >= 5, "{count} examples checked");
}

/// `solve_mass` (the articulated-body recursion in 6-D) inverts `mass_times` on every tree and
/// loop above: revolute, spherical, cylindrical, translational and free links (tolerance: M's
/// condition here is below 1e5, so 1e-11 relative to |x|). Also where the quaternions are not
/// unit, as an explicit integrator's stages see them (q + h k/2 is off the unit sphere by
/// O(h²)): M is then that of the frames A(p) gives, and the solve must invert that M, not assume
/// A orthogonal — an RK4 step at 1 ms once lost 9 mm at a 16-ball chain's tip in 0.5 s that way.
#[test]
fn the_spatial_articulated_body_solve_inverts_the_mass_matrix() {
    fn check<M: ForwardDynamics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(m: &M) {
        let off_the_sphere = states(m, 10).map(|(mut q, x, t)| {
            for (i, kind) in M::COORDINATES.iter().enumerate() {
                if matches!(kind.kind, mbd::CoordinateKind::Quaternion { .. }) {
                    q[i] *= 1.01;
                }
            }
            (q, x, t)
        });
        for (q, x, _) in states(m, 10).chain(off_the_sphere) {
            let mut y = [0.0; NV];
            m.mass_times(&q, &x, &mut y);
            assert_eq!(m.solve_mass(&q, &mut y), Some(Ok(())), "{}", M::NAME);
            let scale = x.iter().fold(1.0f64, |a, b| a.max(b.abs()));
            for i in 0..NV {
                assert!((y[i] - x[i]).abs() < 1e-11 * scale, "{}: x[{i}] {} back as {}", M::NAME, x[i], y[i]);
            }
        }
    }
    check(&ArmJoint::default());
    check(&SlideJoint::default());
    check(&FloatJoint::default());
    check(&LoopJoint::default());
}

/// The exact linearization of a spatial tree (its ball joint's quaternion on the chart of
/// rotations) agrees with central differences of the forward dynamics (tolerance as in
/// `tests/linearize.rs`: the differences' O(ε²) truncation, 1e-7 relative).
#[test]
fn spatial_linearization_in_joint_coordinates_is_exact() {
    fn relative(a: &mbd::nalgebra::DMatrix<f64>, b: &mbd::nalgebra::DMatrix<f64>) -> f64 {
        (a - b).amax() / a.amax().max(b.amax()).max(1e-300)
    }
    let m = ArmJoint::default();
    let (q, v, _) = states(&m, 3).last().expect("a state");
    let exact = Linearizer::new(LinearizeOptions::default()).linearize(&m, &q, &v, 0.3).expect("exact");
    let fd = Linearizer::new(LinearizeOptions::default()).finite_differences(&m, &q, &v, 0.3).expect("differences");
    assert_eq!(exact.a.nrows(), 10, "five velocities: five displacements and five rates");
    assert!(relative(&exact.a, &fd.a) < 1e-7, "arm A: exact {} differences {}", exact.a, fd.a);
}

/// Generalized-α integrates a spatial tree in joint coordinates (a ball joint's quaternion
/// updated on the group) to second order: over 1 s of the swinging arm against DOPRI5 at rtol
/// 1e-12, halving h from 1e-3 divides the error by about 4 (measured 2026-11-29: 2.3e-4 at
/// h = 1e-3; a first-order or wrong term gives a ratio near 2 or 1).
#[test]
fn generalized_alpha_integrates_spatial_joint_coordinates() {
    let m = ArmJoint::default();
    let (q0, v0) = (m.initial_positions(), [0.5, -0.4, 1.0, 0.3, -0.8]);
    let mut reference = q0;
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-12).with_atol(1e-14));
    Simulation::new(&m, &mut dopri).start(0.0, &q0, &v0).times(&[1.0]).run(&mut ArmJoint::workspace(), |s| reference = s.point.q).unwrap();
    assert!((0..6).map(|i| (reference[i] - q0[i]).abs()).fold(0.0, f64::max) > 0.1, "the arm moved");
    let error = |h: f64| {
        let mut last = q0;
        let mut alpha = ArmJoint::generalized_alpha(GeneralizedAlphaOptions::default().with_step(h));
        Simulation::new(&m, &mut alpha).start(0.0, &q0, &v0).times(&[1.0]).run(&mut ArmJoint::workspace(), |s| last = s.point.q).unwrap();
        (0..6).map(|i| (last[i] - reference[i]).abs()).fold(0.0, f64::max)
    };
    let (coarse, fine) = (error(1e-3), error(5e-4));
    assert!(coarse < 1e-3 && (3.0..5.0).contains(&(coarse / fine)), "errors {coarse:e} at h = 1e-3, {fine:e} at h/2");
}

/// Statics both ways: the arm hanging on its springs comes to rest at the same poses from the
/// same start (tolerance: both solves stop at residuals near 1e-12, so poses agree to 1e-8).
#[test]
fn spatial_statics_agree_both_ways() {
    let (b, j) = (ArmBody::default(), ArmJoint::default());
    let mut qj = j.initial_positions();
    StaticSolver::default().solve(&j, &mut ArmJoint::workspace(), &mut qj, 0.0, &mut []).expect("joint statics");
    let (mut qb, _) = to_bodies::<ArmJoint, 6, 5, 21, 18>(&j, &j.initial_positions(), &[0.0; 5]);
    StaticSolver::default().solve(&b, &mut ArmBody::workspace(), &mut qb, 0.0, &mut [0.0; 13]).expect("body statics");
    for k in 0..3 {
        let (p, other) = (j.body_pose(k, &qj).unwrap(), b.body_pose(k, &qb).unwrap());
        for c in 0..3 {
            assert!((p.position[c] - other.position[c]).abs() < 1e-8, "body {k}: {:?} vs {:?}", p.position, other.position);
        }
    }
    let mut g = [0.0; 5];
    j.forces(&qj, &[0.0; 5], 0.0, &mut g);
    assert!(g.iter().all(|x| x.abs() < 1e-9), "generalized forces at rest {g:?}");
}

/// Named access in joint coordinates (`Name::BODY` a `TreeBody`, `m.body_point()` a
/// `TreePoint`, read through the body frames) gives what body coordinates' named access gives
/// at the same state (tolerance: rounding of O(1) values).
#[test]
fn named_points_and_bodies_agree_both_ways() {
    let (b, j) = (ArmBody::default(), ArmJoint::default());
    for (q, v, t) in states(&j, 5) {
        let (qb, vb) = to_bodies::<ArmJoint, 6, 5, 21, 18>(&j, &q, &v);
        let options = DynamicsOptions::without_stabilization();
        let (mut vd, mut lambda) = ([0.0; 5], [0.0; 0]);
        j.accelerations(&q, &v, t, &options, &mut vd, &mut lambda).expect("joint dynamics");
        let (mut vdb, mut lambda_b) = ([0.0; 18], [0.0; 13]);
        b.accelerations(&qb, &vb, t, &options, &mut vdb, &mut lambda_b).expect("body dynamics");
        let (pj, pb) = (j.fore_tip(), b.fore_tip());
        assert!((pj.position(&q) - pb.position(&qb)).norm() < 1e-12);
        assert!((pj.velocity(&q, &v) - pb.velocity(&qb, &vb)).norm() < 1e-12);
        assert!((pj.acceleration(&q, &v, &vd) - pb.acceleration(&qb, &vb, &vdb)).norm() < 1e-9);
        assert!((ArmJoint::UPPER.position(&j, &q) - ArmBody::UPPER.position(&qb)).norm() < 1e-12);
        let (_, w) = ArmJoint::UPPER.velocity(&j, &q, &v);
        assert!((w - ArmBody::UPPER.angular_velocity(&qb, &vb)).norm() < 1e-12);
    }
    assert_eq!(j.mass_of(ArmJoint::FORE), 0.6);
    assert_eq!(j.inertia_of(ArmJoint::UPPER), b.inertia_of(ArmBody::UPPER));
    assert_eq!(j.inertia_of(ArmJoint::UPPER)[(0, 1)], 0.001, "a product of inertia");
}

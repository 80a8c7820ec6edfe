//! Joint coordinates (`joint_coordinates;`) against body coordinates: the same `mechanism!` text
//! compiled both ways must describe the same physics. At the same physical state — the joint
//! state mapped to body coordinates through the generated body frames — the constraints of the
//! body-coordinate model vanish, the kinetic and potential energies agree, and so do the bodies'
//! accelerations; along a motion, the bodies' poses agree.
//!
//! Tolerances: both formulations evaluate exact symbolic derivatives of the same geometry and
//! solve well-conditioned systems (masses 0.2–2 kg, lengths 0.1–1 m, cond ≲ 1e4), so values
//! agree to rounding times the condition: 1e-10 relative to max(1, |value|) separates a right
//! formulation from a wrong one (a wrong term is O(0.1) or more).

use mbd::prelude::*;
use mbd::{BodyCoordinates, ConstraintForces, JointLoads};

#[path = "common/joint.rs"]
mod joint;
use joint::{both_ways, close, on_constraints, reactions_agree};

both_ways! {
    /// A double pendulum with a spring to ground and a torque: a tree of two revolute joints.
    DoubleBody, DoubleJoint {
        gravity [0.0, -9.81];
        body upper { mass: 1.5, inertia: 0.12, at: [0.5, 0.0, 0.0] }
        body lower { mass: 0.7, inertia: 0.05, at: [1.4, 0.0, 0.0] }
        revolute shoulder: ground[0.0, 0.0] ~ upper[-0.5, 0.0];
        revolute elbow: upper[0.5, 0.0] ~ lower[-0.4, 0.0];
        spring ground[0.3, 0.4] ~ lower[0.1, 0.05] { k: 25.0, length: 0.8, c: 0.3 };
        torque upper = 0.4 * sin(t);
    }
}

both_ways! {
    /// A cart on an inclined rail with a pendulum hung from it, the pendulum's pin declared
    /// pendulum first (the tree runs the joint backwards) and its slide from the cart's side.
    CartBody, CartJoint {
        gravity [0.0, -9.81];
        body cart { mass: 2.0, inertia: 0.1, at: [0.3, 0.1, 0.2] }
        body pole { mass: 0.5, inertia: 0.02, at: [0.3, -0.4, 0.4] }
        translational rail: ground[0.0, 0.0] along [1.0, 0.3] ~ cart[0.05, -0.02] along [0.0, 1.0];
        revolute pole[0.0, 0.5] ~ cart[0.1, 0.0];
        damper ground[0.0, 0.0] ~ cart[0.0, 0.0] { c: 0.8 };
    }
}

both_ways! {
    /// A free slider-crank under gravity: one loop, closed by the cut joint's rows.
    CrankBody, CrankJoint {
        params { r: 0.1, l: 0.3 }
        gravity [0.0, -9.81];
        body crank  { mass: 2.0, inertia: 0.01, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 0.8, inertia: 0.006, at: [0.25, 0.0, 0.0] }
        body piston { mass: 0.5, inertia: 1.0e-4, at: [0.4, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ piston[0.0, 0.0];
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ piston[0.0, 0.0] along [1.0, 0.0];
        damper ground[0.6, 0.0] ~ piston[0.0, 0.0] { c: 4.0 };
    }
}

both_ways! {
    /// A body on no joint (it floats on a free joint) tied to a pendulum by a spring.
    FloatBody, FloatJoint {
        gravity [0.0, -9.81];
        body float { mass: 0.4, inertia: 0.01, at: [0.5, 0.5, 0.3], velocity: [0.1, -0.2, 0.5] }
        body arm { mass: 1.0, inertia: 0.08, at: [0.0, -0.5, 0.0] }
        revolute ground[0.0, 0.0] ~ arm[0.0, 0.5];
        spring float[0.0, 0.0] ~ arm[0.0, -0.5] { k: 30.0, length: 0.6 };
    }
}

/// The body-coordinate state of a joint state, through the joint mechanism's body frames.
fn to_bodies<J: BodyFrames<f64, NQJ, NQJ>, const NQJ: usize, const NQB: usize>(
    j: &J,
    q: &[f64; NQJ],
    v: &[f64; NQJ],
) -> ([f64; NQB], [f64; NQB]) {
    let (mut qb, mut vb) = ([0.0; NQB], [0.0; NQB]);
    for k in 0..NQB / 3 {
        let pose = j.body_pose(k, q).expect("a body");
        let twist = j.body_twist(k, q, v).expect("a body");
        qb[3 * k..3 * k + 3].copy_from_slice(&[pose.position[0], pose.position[1], pose.angle()]);
        vb[3 * k..3 * k + 3].copy_from_slice(&[twist.velocity[0], twist.velocity[1], twist.angular_velocity[2]]);
    }
    (qb, vb)
}

/// At a joint state on the constraints: the body-coordinate constraints vanish there, and the
/// energies, each body's acceleration and every joint's reaction agree.
fn agree<B, J, const NQB: usize, const NCB: usize, const NQJ: usize, const NCJ: usize>(b: &B, j: &J, q: &[f64; NQJ], v: &[f64; NQJ], t: f64)
where
    B: ForwardDynamics<f64, NQB, NQB, NCB> + JointLoads<f64, NQB, NQB, NCB> + BodyCoordinates,
    J: ForwardDynamics<f64, NQJ, NQJ, NCJ> + JointLoads<f64, NQJ, NQJ, NCJ>,
{
    let (qb, vb) = to_bodies::<J, NQJ, NQB>(j, q, v);
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
    let (mut ab, mut lb) = ([0.0; NQB], [0.0; NCB]);
    b.accelerations(&qb, &vb, t, &options, &mut ab, &mut lb).expect("body-coordinate dynamics");
    let (mut aj, mut lj) = ([0.0; NQJ], [0.0; NCJ]);
    j.accelerations(q, v, t, &options, &mut aj, &mut lj).expect("joint-coordinate dynamics");
    for k in 0..NQB / 3 {
        let a = j.body_acceleration(k, q, v, &aj).expect("a body");
        let from_joints = [a.velocity[0], a.velocity[1], a.angular_velocity[2]];
        for c in 0..3 {
            assert!(
                close(ab[3 * k + c], from_joints[c]),
                "{name}: body {} acceleration {c}: {} in body coordinates, {} in joint coordinates",
                B::BODY_NAMES[k],
                ab[3 * k + c],
                from_joints[c]
            );
        }
    }
    reactions_agree(b, (&qb, &vb, &ab, &lb), j, (q, v, &aj, &lj), t);
}

/// States spread over the joint space (deterministic).
fn states<const N: usize>(count: usize) -> impl Iterator<Item = ([f64; N], [f64; N], f64)> {
    (0..count).map(|s| {
        let x = |i: usize, scale: f64| scale * ((s * 7 + i * 13) as f64 * 0.618_034).sin();
        (core::array::from_fn(|i| x(i, 1.2)), core::array::from_fn(|i| x(i + N, 2.0)), 0.1 * s as f64)
    })
}

#[test]
fn trees_agree_with_body_coordinates() {
    let (b, j) = (DoubleBody::default(), DoubleJoint::default());
    assert_eq!((DoubleJoint::COORDINATE_NAMES, DoubleJoint::CONSTRAINT_NAMES.len()), (&["shoulder.angle", "elbow.angle"][..], 0));
    for (q, v, t) in states::<2>(20) {
        agree(&b, &j, &q, &v, t);
    }
    let (b, j) = (CartBody::default(), CartJoint::default());
    assert_eq!(CartJoint::COORDINATE_NAMES, &["rail.stroke", "revolute pole~cart.angle"]);
    for (q, v, t) in states::<2>(20) {
        agree(&b, &j, &q, &v, t);
    }
    let (b, j) = (FloatBody::default(), FloatJoint::default());
    assert_eq!(FloatJoint::COORDINATE_NAMES, &["float.x", "float.y", "float.phi", "revolute ground~arm.angle"]);
    for (q, v, t) in states::<4>(20) {
        agree(&b, &j, &q, &v, t);
    }
}

/// The slider-crank's loop is cut at its last joint (all four have two rows): three angles
/// and the translational joint's two rows.
#[test]
fn a_closed_loop_agrees_with_body_coordinates() {
    let (b, j) = (CrankBody::default(), CrankJoint::default());
    assert_eq!(CrankJoint::CONSTRAINT_NAMES, &["translational ground~piston: normal", "translational ground~piston: angle"]);
    for (mut q, mut v, t) in states::<3>(20) {
        // a crank angle in (−1.2, 1.2) rad: the loop closes there, far from a dead centre
        on_constraints(&j, &mut q, &mut v, t);
        agree(&b, &j, &q, &v, t);
    }
}

/// The initial joint coordinates are the bodies' `at:` poses read through the joints: the
/// angles' differences, the stroke along the rail; a floating body's pose and velocity as they
/// are.
#[test]
fn initial_coordinates_come_from_the_bodies_poses() {
    let q = CartJoint::default().initial_positions();
    // the stroke of cart[0.05, −0.02] (turned by 0.2 rad) from the origin along (1, 0.3)/|·|
    let (s, c) = 0.2f64.sin_cos();
    let p = [0.3 + c * 0.05 + s * 0.02, 0.1 + s * 0.05 - c * 0.02];
    let stroke = (p[0] + 0.3 * p[1]) / 1.09f64.sqrt();
    assert!((q[0] - stroke).abs() < 1e-15 && (q[1] - (0.2 - 0.4)).abs() < 1e-15, "{q:?}");
    let m = FloatJoint::default();
    assert_eq!((m.initial_positions(), m.initial_velocities()), ([0.5, 0.5, 0.3, 0.0], [0.1, -0.2, 0.5, 0.0]));
}

/// (q, v) after 1 s of DOPRI5 at rtol 1e-12 (atol 1e-14) from (q0, v0) at t = 0:
/// `one_second!(mechanism, Type, q0, v0)`.
macro_rules! one_second {
    ($m:expr, $ty:ident, $q0:expr, $v0:expr) => {{
        let mut end = ($q0, $v0);
        let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-12).with_atol(1e-14));
        Simulation::new(&$m, &mut dopri)
            .start(0.0, &$q0, &$v0)
            .times(&[1.0])
            .run(&mut $ty::workspace(), |s| end = (s.point.q, s.point.v))
            .expect("the motion");
        end
    }};
}

/// The same motion both ways: DOPRI5 at rtol 1e-12 over 1 s, the bodies' poses compared
/// (tolerance: each run's error is about 1e-10 at this tolerance over 1 s of a non-chaotic
/// motion; 1e-8 leaves room for the two error paths).
#[test]
fn a_motion_agrees_with_body_coordinates() {
    let (b, j) = (DoubleBody::default(), DoubleJoint::default());
    let (qj, vj) = ([0.3, -0.5], [1.0, 0.5]);
    let (qb, vb) = to_bodies::<DoubleJoint, 2, 6>(&j, &qj, &vj);
    let (end_b, _) = one_second!(b, DoubleBody, qb, vb);
    let (end_j, _) = one_second!(j, DoubleJoint, qj, vj);
    let (end_jb, _) = to_bodies::<DoubleJoint, 2, 6>(&j, &end_j, &[0.0; 2]);
    for i in 0..6 {
        assert!((end_b[i] - end_jb[i]).abs() < 1e-8, "q[{i}] at 1 s: {} in body coordinates, {} in joint coordinates", end_b[i], end_jb[i]);
    }
}

/// The generated frames are consistent: the twist is the pose's rate (central differences
/// along q ± h v), the acceleration the twist's rate, and J_bᵀ the adjoint of J_b (a wrench's
/// generalized force does the wrench's power).
#[test]
fn body_frames_are_consistent() {
    let m = CartJoint::default();
    let (q, v, vd) = ([0.2, -0.7], [0.9, -1.3], [0.4, 2.0]);
    let h = 1e-6;
    let at = |s: f64| -> ([f64; 2], [f64; 2]) { (core::array::from_fn(|i| q[i] + s * v[i]), core::array::from_fn(|i| v[i] + s * vd[i])) };
    let ((qp, vp), (qm, vm)) = (at(h), at(-h));
    for b in 0..2 {
        let (p, n) = (m.body_pose(b, &qp).unwrap(), m.body_pose(b, &qm).unwrap());
        let twist = m.body_twist(b, &q, &v).unwrap();
        let rates =
            [(p.position[0] - n.position[0]) / (2.0 * h), (p.position[1] - n.position[1]) / (2.0 * h), (p.angle() - n.angle()) / (2.0 * h)];
        let (tp, tn) = (m.body_twist(b, &qp, &vp).unwrap(), m.body_twist(b, &qm, &vm).unwrap());
        let accelerations = [
            (tp.velocity[0] - tn.velocity[0]) / (2.0 * h),
            (tp.velocity[1] - tn.velocity[1]) / (2.0 * h),
            (tp.angular_velocity[2] - tn.angular_velocity[2]) / (2.0 * h),
        ];
        let a = m.body_acceleration(b, &q, &v, &vd).unwrap();
        // Tolerance: the central difference's O(h²) truncation and O(ε/h) rounding, about 1e-10.
        for (c, (rate, exact)) in rates.iter().zip([twist.velocity[0], twist.velocity[1], twist.angular_velocity[2]]).enumerate() {
            assert!((rate - exact).abs() < 1e-8, "body {b} twist {c}: {exact} vs difference {rate}");
        }
        for (c, (rate, exact)) in accelerations.iter().zip([a.velocity[0], a.velocity[1], a.angular_velocity[2]]).enumerate() {
            assert!((rate - exact).abs() < 1e-8, "body {b} acceleration {c}: {exact} vs difference {rate}");
        }
        let (force, moment) = ([0.3, -1.2, 0.7], [0.4, 0.25, -0.9]);
        let mut g = [0.0; 2];
        assert!(m.add_body_wrench(b, &q, force, moment, &mut g));
        let work = g[0] * v[0] + g[1] * v[1];
        let power = force[0] * twist.velocity[0] + force[1] * twist.velocity[1] + moment[2] * twist.angular_velocity[2];
        // Tolerance: rounding of a few O(1) products.
        assert!((work - power).abs() < 1e-13, "body {b}: Jᵀ is the adjoint of J: {work} vs {power}");
    }
    assert!(m.body_pose(2, &q).is_none() && !m.add_body_wrench(2, &q, [1.0; 3], [1.0; 3], &mut [0.0; 2]));
}

/// (∂(M x)/∂q) B against a central difference of M(q) x (tolerance as for the frames above,
/// scaled by |M| ≈ 3).
#[test]
fn the_mass_matrix_derivative_is_exact() {
    let m = CrankJoint::default();
    let (q, x) = ([0.4, 0.9, -0.3], [0.7, -0.2, 1.1]);
    let mut exact = [[0.0; 3]; 3];
    m.add_mass_derivative(&q, &x, 1.0, &mut exact);
    let h = 1e-6;
    for c in 0..3 {
        let (mut qp, mut qm) = (q, q);
        qp[c] += h;
        qm[c] -= h;
        let (mut yp, mut ym) = ([0.0; 3], [0.0; 3]);
        m.mass_times(&qp, &x, &mut yp);
        m.mass_times(&qm, &x, &mut ym);
        for r in 0..3 {
            let difference = (yp[r] - ym[r]) / (2.0 * h);
            assert!((difference - exact[r][c]).abs() < 3e-8, "∂(M x)_{r}/∂q_{c}: {} vs difference {difference}", exact[r][c]);
        }
    }
    assert!(exact.iter().flatten().any(|d| d.abs() > 1e-3), "M depends on q: {exact:?}");
}

/// K = ∂(Dᵀλ)/∂q, generated in joint coordinates a column at a time (a directional derivative
/// of Dᵀλ), agrees with central differences of Dᵀλ on the slider-crank's loop, whose rows reach
/// every angle (tolerance: the differences' O(h²) truncation and the rounding of D/h, 1e-7 of
/// Dᵀλ's scale).
#[test]
fn the_constraint_force_derivative_is_exact() {
    let m = CrankJoint::default();
    let lambda = [30.0, -7.0];
    let constraint_force = |q: &[f64; 3]| {
        let mut d = [[0.0; 3]; 2];
        m.jacobian(q, 0.2, &mut d);
        core::array::from_fn::<f64, 3, _>(|c| (0..2).map(|r| d[r][c] * lambda[r]).sum())
    };
    for q in [[0.4, 0.9, -0.3], [-1.0, 0.2, 0.8]] {
        let mut exact = [[0.0; 3]; 3];
        m.constraint_force_q(&q, 0.2, &lambda, &mut exact);
        let scale = constraint_force(&q).iter().fold(1.0f64, |a, b| a.max(b.abs()));
        let h = 1e-6;
        for c in 0..3 {
            let (mut qp, mut qm) = (q, q);
            qp[c] += h;
            qm[c] -= h;
            let (fp, fm) = (constraint_force(&qp), constraint_force(&qm));
            for r in 0..3 {
                let difference = (fp[r] - fm[r]) / (2.0 * h);
                assert!((difference - exact[r][c]).abs() < 1e-7 * scale, "K[{r}][{c}]: {} vs difference {difference}", exact[r][c]);
            }
        }
        assert!(exact.iter().flatten().any(|k| k.abs() > 1e-2), "K is not zero here: {exact:?}");
    }
}

/// The exact linearization of a tree and of a loop about moving states (v̇ ≠ 0, so the change of
/// M(q) v̇ with q is in play) agrees with central differences of the forward dynamics
/// (tolerance as in `tests/linearize.rs`: the differences' O(ε²) truncation, 1e-7 relative).
#[test]
fn linearization_in_joint_coordinates_is_exact() {
    fn relative(a: &mbd::nalgebra::DMatrix<f64>, b: &mbd::nalgebra::DMatrix<f64>) -> f64 {
        (a - b).amax() / a.amax().max(b.amax()).max(1e-300)
    }
    let m = DoubleJoint::default();
    let (q, v) = ([0.6, -0.4], [1.5, -2.0]);
    let exact = Linearizer::new(LinearizeOptions::default()).linearize(&m, &q, &v, 0.3).expect("exact");
    let fd = Linearizer::new(LinearizeOptions::default()).finite_differences(&m, &q, &v, 0.3).expect("differences");
    assert!(relative(&exact.a, &fd.a) < 1e-7, "double pendulum A: exact {} differences {}", exact.a, fd.a);

    let m = CrankJoint::default();
    let (mut q, mut v) = ([0.7, -0.9, 0.2], [3.0, 0.0, 0.0]);
    on_constraints(&m, &mut q, &mut v, 0.0);
    let options = || LinearizeOptions::default().with_independent(&["revolute ground~crank.angle"]);
    let exact = Linearizer::new(options()).linearize(&m, &q, &v, 0.0).expect("exact");
    let fd = Linearizer::new(options()).finite_differences(&m, &q, &v, 0.0).expect("differences");
    assert!(relative(&exact.a, &fd.a) < 1e-7, "slider-crank A: exact {} differences {}", exact.a, fd.a);
}

/// Generalized-α integrates a tree in joint coordinates: at h = 1e-3 its second-order error
/// over 1 s of the double pendulum is about 1e-5 against DOPRI5 at rtol 1e-12. Its Newton
/// matrix holds c_q ∂(M v̇)/∂q, so at a coarse step (h = 5e-2, fast swings, factors not
/// reused) Newton takes fewer iterations than without it.
#[test]
fn generalized_alpha_integrates_joint_coordinates() {
    let m = DoubleJoint::default();
    let (q0, v0) = ([0.3, -0.5], [1.0, 0.5]);
    let mut reference = q0;
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-12).with_atol(1e-14));
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q0, &v0)
        .times(&[1.0])
        .run(&mut DoubleJoint::workspace(), |s| reference = s.point.q)
        .unwrap();
    let mut last = q0;
    let mut alpha = DoubleJoint::generalized_alpha(GeneralizedAlphaOptions::default().with_step(1e-3));
    Simulation::new(&m, &mut alpha).start(0.0, &q0, &v0).times(&[1.0]).run(&mut DoubleJoint::workspace(), |s| last = s.point.q).unwrap();
    let error = (0..2).map(|i| (last[i] - reference[i]).abs()).fold(0.0, f64::max);
    assert!(error < 1e-4, "generalized-α error {error:e}: {last:?} vs {reference:?}");
    // Measured 2026-11-29: 3.75 iterations per step with the term, 5.95 without it.
    let options = GeneralizedAlphaOptions::default().with_step(5e-2).with_reuse_factors(false);
    let mut alpha = DoubleJoint::generalized_alpha(options);
    Simulation::new(&m, &mut alpha).start(0.0, &q0, &[8.0, -6.0]).times(&[1.0]).run(&mut DoubleJoint::workspace(), |_| {}).unwrap();
    let per_step = alpha.total_iterations as f64 / 20.0;
    assert!(per_step < 4.5, "{per_step} Newton iterations per step at h = 5e-2");
}

both_ways! {
    /// A two-link pendulum whose tip's mass is a parameter (`tip_mass`), for a massless branch.
    TipBody, TipJoint {
        params { tip_mass: 0.5 }
        gravity [0.0, -9.81];
        body link { mass: 1.0, inertia: 0.02, at: [0.25, 0.0, 0.0] }
        body tip { mass: tip_mass, inertia: 0.1 * tip_mass, at: [0.6, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ link[-0.25, 0.0];
        revolute link[0.25, 0.0] ~ tip[-0.1, 0.0];
    }
}

/// `solve_mass` (the articulated-body recursion) inverts `mass_times` on every tree and loop
/// above: the free joint's 3×3 pivot block, a translational joint run backwards, a cut loop
/// (tolerance: M's condition here is below 1e4, so 1e-12 relative to |x|); and
/// `solve_mass_rows`, the loop's rows over one factorization, gives each row's `solve_mass`
/// (the same operations in another order: 1e-13).
#[test]
fn the_articulated_body_solve_inverts_the_mass_matrix() {
    fn check<M: Dynamics<f64, N, N, NC>, const N: usize, const NC: usize>(m: &M) {
        for (q, x, _) in states::<N>(10) {
            let mut y = [0.0; N];
            m.mass_times(&q, &x, &mut y);
            assert_eq!(m.solve_mass(&q, &mut y), Some(Ok(())), "{}", M::NAME);
            let scale = x.iter().fold(1.0f64, |a, b| a.max(b.abs()));
            for i in 0..N {
                assert!((y[i] - x[i]).abs() < 1e-12 * scale, "{}: M⁻¹(M x)[{i}] = {} for x = {}", M::NAME, y[i], x[i]);
            }
            // The fused M⁻¹h is the solve of h (x for the velocities).
            let (mut h, mut free) = ([0.0; N], [0.0; N]);
            m.forces(&q, &x, 0.3, &mut h);
            assert_eq!(m.solve_mass(&q, &mut h), Some(Ok(())));
            assert_eq!(m.free_accelerations(&q, &x, 0.3, &mut free), Some(Ok(())));
            let scale = h.iter().fold(1.0f64, |a, b| a.max(b.abs()));
            for i in 0..N {
                assert!((free[i] - h[i]).abs() < 1e-12 * scale, "{}: free accelerations [{i}] {} vs M⁻¹h {}", M::NAME, free[i], h[i]);
            }
            // The rows' solves over one shared factorization (generated where there are rows)
            // are each row's solve.
            let generated = M::OP_COUNTS.iter().any(|o| o.function == "solve_mass_rows (each row)");
            assert_eq!(generated, NC > 0, "{}", M::NAME);
            let rows: [[f64; N]; NC] = core::array::from_fn(|r| core::array::from_fn(|i| x[(i + r) % N] * (1.0 + r as f64)));
            let mut shared = rows;
            assert_eq!(m.solve_mass_rows(&q, &mut shared), Some(Ok(())), "{}", M::NAME);
            for (r, row) in rows.iter().enumerate() {
                let mut alone = *row;
                assert_eq!(m.solve_mass(&q, &mut alone), Some(Ok(())));
                let scale = alone.iter().fold(1.0f64, |a, b| a.max(b.abs()));
                for i in 0..N {
                    assert!(
                        (shared[r][i] - alone[i]).abs() < 1e-13 * scale,
                        "{}: row {r} [{i}]: {} vs {}",
                        M::NAME,
                        shared[r][i],
                        alone[i]
                    );
                }
            }
        }
    }
    check(&DoubleJoint::default());
    check(&CartJoint::default());
    check(&CrankJoint::default());
    check(&FloatJoint::default());
    // Body coordinates solve by their planned Schur complement: no recursion.
    assert_eq!(DoubleBody::default().solve_mass(&[0.0; 6], &mut [1.0; 6]), None);
    assert_eq!(DoubleBody::default().free_accelerations(&[0.0; 6], &[0.0; 6], 0.0, &mut [0.0; 6]), None);
}

/// A massless tip: the recursion's pivot there is zero, and forward dynamics name the body, as
/// in body coordinates.
#[test]
fn a_massless_branch_is_named() {
    let m = TipJoint { tip_mass: 0.0 };
    assert_eq!(m.solve_mass(&[0.3, 0.2], &mut [1.0, 1.0]), Some(Err(1)));
    assert_eq!(m.free_accelerations(&[0.3, 0.2], &[0.0; 2], 0.0, &mut [0.0; 2]), Some(Err(1)));
    let (mut vd, mut lambda) = ([0.0; 2], [0.0; 0]);
    let err = m.accelerations(&[0.3, 0.2], &[0.0; 2], 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda).unwrap_err();
    assert_eq!(err, DynamicsError::NonPositiveMass { body: "tip", value: 0.0 });
    let b = TipBody { tip_mass: 0.0 };
    let (mut vd, mut lambda) = ([0.0; 6], [0.0; 4]);
    let (qb, _) = to_bodies::<TipJoint, 2, 6>(&TipJoint::default(), &[0.3, 0.2], &[0.0; 2]);
    let err = b.accelerations(&qb, &[0.0; 6], 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda).unwrap_err();
    assert_eq!(err, DynamicsError::NonPositiveMass { body: "tip", value: 0.0 });
}

both_ways! {
    /// The slider-crank with Coulomb friction in its cut joint (the slide), loaded by its
    /// multipliers.
    FrictionBody, FrictionJoint {
        gravity [0.0, -9.81];
        body crank  { mass: 2.0, inertia: 0.01, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 0.8, inertia: 0.006, at: [0.25, 0.0, 0.0] }
        body piston { mass: 0.5, inertia: 1.0e-4, at: [0.4, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-0.05, 0.0];
        revolute crank[0.05, 0.0] ~ rod[-0.15, 0.0];
        revolute rod[0.15, 0.0] ~ piston[0.0, 0.0];
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ piston[0.0, 0.0] along [1.0, 0.0]
            { coulomb: 0.3, slip_velocity: 0.05 };
    }
}

/// Coulomb friction in a cut joint: the same accelerations both ways (the fixed point over
/// the multipliers included), and its generated derivatives (a column at a time; in λ, the
/// loads' slope) against central differences at fixed λ (tolerance as for the frames: O(h²) and rounding, 1e-7
/// relative to the forces' scale).
#[test]
fn friction_in_a_cut_joint_agrees_and_differentiates() {
    let (b, j) = (FrictionBody::default(), FrictionJoint::default());
    for (mut q, mut v, t) in states::<3>(10) {
        on_constraints(&j, &mut q, &mut v, t);
        agree(&b, &j, &q, &v, t);
        let lambda = [40.0, -3.0];
        let (mut d_q, mut d_v) = ([[0.0; 3]; 3], [[0.0; 3]; 3]);
        j.friction_derivatives(&q, &v, t, &lambda, &mut d_q, &mut d_v);
        let friction = |q: &[f64; 3], v: &[f64; 3]| {
            let mut h = [0.0; 3];
            j.friction_forces(q, v, t, &lambda, &mut h);
            h
        };
        let scale = friction(&q, &v).iter().fold(1.0f64, |a, b| a.max(b.abs()));
        let e = 1e-6;
        for c in 0..3 {
            let (mut qp, mut qm, mut vp, mut vm) = (q, q, v, v);
            qp[c] += e;
            qm[c] -= e;
            vp[c] += e;
            vm[c] -= e;
            let (fqp, fqm, fvp, fvm) = (friction(&qp, &v), friction(&qm, &v), friction(&q, &vp), friction(&q, &vm));
            for r in 0..3 {
                let (dq, dv) = ((fqp[r] - fqm[r]) / (2.0 * e), (fvp[r] - fvm[r]) / (2.0 * e));
                assert!((dq - d_q[r][c]).abs() < 1e-7 * scale.max(dq.abs()), "∂f_{r}/∂q_{c}: {} vs {dq}", d_q[r][c]);
                assert!((dv - d_v[r][c]).abs() < 1e-7 * scale.max(dv.abs()), "∂f_{r}/∂v_{c}: {} vs {dv}", d_v[r][c]);
            }
        }
        assert!(d_v.iter().flatten().any(|x| x.abs() > 1e-6), "friction depends on the slip velocity");
        // Its slope in the slide's loads (the implicit methods' Newton matrix), against
        // central differences in λ: linear in the normal load, so exact to rounding.
        let mut d_lambda = [[0.0; 3]; 2];
        j.friction_multiplier_derivatives(&q, &v, t, &lambda, &mut d_lambda);
        for (r, row) in d_lambda.iter().enumerate() {
            let (mut plus, mut minus) = ([0.0; 3], [0.0; 3]);
            let (mut lp, mut lm) = (lambda, lambda);
            lp[r] += e;
            lm[r] -= e;
            j.friction_forces(&q, &v, t, &lp, &mut plus);
            j.friction_forces(&q, &v, t, &lm, &mut minus);
            for c in 0..3 {
                let fd = (plus[c] - minus[c]) / (2.0 * e);
                assert!((fd - row[c]).abs() < 1e-7 * scale.max(fd.abs()), "∂f_{c}/∂λ_{r}: {} vs {fd}", row[c]);
            }
        }
        assert!(d_lambda.iter().flatten().any(|x| x.abs() > 1e-3), "friction depends on the normal load");
    }
}

both_ways! {
    /// A hanging chain of 16 links held straight out by weak torsion springs: its statics swing
    /// the whole chain down.
    LimpBody, LimpJoint {
        gravity [0.0, -9.81];
        for k in 0..16 { body l[k] { mass: 0.1, inertia: 8.3e-5, at: [0.05 + 0.1 * k, 0.0, 0.0] } }
        revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0];
        for k in 1..16 {
            revolute l[k - 1][0.05, 0.0] ~ l[k][-0.05, 0.0];
            rotational_spring l[k - 1] ~ l[k] { k: 0.5, angle: 0.0 };
        }
    }
}

/// Statics with the defaults finds the same equilibrium both ways from the straight pose
/// (tolerance: both converge to 1e-10 in force; the poses' condition is about 1e2), each pin
/// then carries the weight below it, and the joint coordinates' trust region measures a step by the bodies it moves
/// (`Dynamics::motion_size`: the largest component of any body's twist).
#[test]
fn statics_of_a_chain_agree_with_body_coordinates() {
    let (b, j) = (LimpBody::default(), LimpJoint::default());
    let mut qj = j.initial_positions();
    let report_j = StaticSolver::default().solve(&j, &mut LimpJoint::workspace(), &mut qj, 0.0, &mut []).expect("joint statics");
    let mut qb = b.initial_positions();
    let report_b = StaticSolver::default().solve(&b, &mut LimpBody::workspace(), &mut qb, 0.0, &mut [0.0; 32]).expect("body statics");
    let (mapped, _) = to_bodies::<LimpJoint, 16, 48>(&j, &qj, &[0.0; 16]);
    for i in 0..48 {
        let (x, y) = (mapped[i], qb[i]);
        // angles compared modulo 2π (statics wraps them into (−π, π])
        let d = if i % 3 == 2 { ((x - y + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)) - std::f64::consts::PI } else { x - y };
        assert!(d.abs() < 1e-8, "q_body[{i}]: {x} from joint coordinates, {y} in body coordinates");
    }
    // At rest every pin carries the weight of the links below it, (0, (16 − k) m g) on l[k]
    // (tolerance: statics converges to 1e-10 N in force; the weights are 0.98–15.7 N).
    for k in 0..16 {
        let pin = joint_reaction_at(&j, &qj, &[0.0; 16], &[0.0; 16], 0.0, &[], k).and_then(|r| r.on_j).expect("the pin above l[k]");
        let weight = (16 - k) as f64 * 0.1 * 9.81;
        assert!(
            pin.force[0].abs() < 1e-9 && (pin.force[1] - weight).abs() < 1e-9,
            "pin above l[{k}]: {:?} N, weight below {weight} N",
            pin.force
        );
    }
    println!(
        "statics: {} + {} iterations in joint coordinates, {} + {} in body coordinates",
        report_j.iterations, report_j.rejected, report_b.iterations, report_b.rejected
    );
    // motion_size: the largest twist component over the bodies
    let x: [f64; 16] = core::array::from_fn(|i| 0.1 * (i as f64 - 7.5));
    let largest = (0..16)
        .map(|k| {
            let t = j.body_twist(k, &qj, &x).expect("a body");
            [t.velocity[0], t.velocity[1], t.angular_velocity[2]].iter().fold(0.0f64, |a, c| a.max(c.abs()))
        })
        .fold(0.0f64, f64::max);
    assert!((j.motion_size(&qj, &x) - largest).abs() < 1e-14 * largest, "{} vs {largest}", j.motion_size(&qj, &x));
    assert_eq!(b.motion_size(&qb, &[0.5; 48]), 0.5, "body coordinates: the largest entry");
}

/// Every planar example's mechanism, written once in `examples/`, compiled both ways
/// (`mbd-examples/build.rs` adds `joint_coordinates;`): from the joint coordinates' assembly at
/// rest, mapped to body coordinates, both simulate 0.2 s with DOPRI5 at rtol 1e-11 and end at
/// the same poses (tolerance: each run's error is about 1e-11 here — measured differences
/// 1e-17 to 7e-13 on 2026-11-29 — and 1e-9 leaves room for both; a wrong term moves a body by
/// far more in 0.2 s). Driven examples test the kinematics, free ones the dynamics.
#[test]
fn every_example_agrees_both_ways() {
    let mut count = 0;
    macro_rules! check {
        ($joint:ty, $body:ty, $label:expr) => {{
            type J = $joint;
            type B = $body;
            let (mj, mb) = (J::default(), B::default());
            let mut wj = J::workspace();
            let mut qj = mj.initial_positions();
            KinematicSolver::default().assemble(&mj, &mut wj, &mut qj, 0.0).expect($label);
            let mut qb = [0.0; B::NQ];
            for k in 0..B::NQ / 3 {
                let p = mj.body_pose(k, &qj).expect("a body");
                qb[3 * k..3 * k + 3].copy_from_slice(&[p.position[0], p.position[1], p.angle()]);
            }
            let options = Dopri5Options::default().with_rtol(1e-11).with_atol(1e-13);
            let (mut end_j, mut end_b) = (qj, qb);
            Simulation::new(&mj, &mut Dopri5::new(options))
                .start(0.0, &qj, &[0.0; J::NV])
                .times(&[0.2])
                .run(&mut wj, |s| end_j = s.point.q)
                .expect($label);
            Simulation::new(&mb, &mut Dopri5::new(options))
                .start(0.0, &qb, &[0.0; B::NV])
                .times(&[0.2])
                .run(&mut B::workspace(), |s| end_b = s.point.q)
                .expect($label);
            for k in 0..B::NQ / 3 {
                let p = mj.body_pose(k, &end_j).expect("a body");
                let turn = (p.angle() - end_b[3 * k + 2] + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
                let worst = (p.position[0] - end_b[3 * k]).abs().max((p.position[1] - end_b[3 * k + 1]).abs()).max(turn.abs());
                assert!(worst < 1e-9, "{}: body {} differs by {worst:e} at 0.2 s", $label, B::BODY_NAMES[k]);
            }
            count += 1;
        }};
    }
    mbd_examples::every_example_both_ways!(check);
    assert!(count >= 16, "{count} examples checked");
}

both_ways! {
    /// A two-link arm with both joints driven, carrying a load: inverse dynamics give the
    /// drivers' torques.
    ArmBody, ArmJoint {
        gravity [0.0, -9.81];
        body upper { mass: 2.0, inertia: 0.08, at: [0.3, 0.0, 0.0] }
        body lower { mass: 1.2, inertia: 0.04, at: [0.85, 0.0, 0.0] }
        revolute shoulder: ground[0.0, 0.0] ~ upper[-0.3, 0.0];
        revolute elbow: upper[0.3, 0.0] ~ lower[-0.25, 0.0];
        spring ground[0.0, 0.5] ~ lower[0.25, 0.0] { k: 40.0, length: 0.6, c: 0.5 };
        drive lift: angle(ground, upper) = 0.5 * sin(2.0 * t);
        drive bend: angle(upper, lower) = 0.3 * t + 0.2;
    }
}

/// Inverse dynamics in joint coordinates: the drivers' multipliers are the joint torques
/// (N·m), the same as the body-coordinate drivers' at the same motion (tolerance as `agree`).
#[test]
fn inverse_dynamics_gives_the_same_joint_torques() {
    let (b, j) = (ArmBody::default(), ArmJoint::default());
    assert_eq!(ArmJoint::CONSTRAINT_NAMES, &["lift: angle", "bend: angle"]);
    let mut q = j.initial_positions();
    let mut states = Vec::new();
    KinematicSolver::default()
        .sweep(&j, &mut ArmJoint::workspace(), &mut q, [0.0, 0.4, 1.3], |t, q, v, vd| states.push((t, *q, *v, *vd)))
        .unwrap();
    for (t, q, v, vd) in states {
        let mut torques = [0.0; 2];
        InverseDynamics::default().solve(&j, &mut ArmJoint::workspace(), &q, &v, &vd, t, &mut torques).expect("joint coordinates");
        let (qb, vb) = to_bodies::<ArmJoint, 2, 6>(&j, &q, &v);
        let vdb: [f64; 6] = core::array::from_fn(|i| {
            let a = j.body_acceleration(i / 3, &q, &v, &vd).expect("a body");
            [a.velocity[0], a.velocity[1], a.angular_velocity[2]][i % 3]
        });
        let mut lambda = [0.0; 6];
        InverseDynamics::default().solve(&b, &mut ArmBody::workspace(), &qb, &vb, &vdb, t, &mut lambda).expect("body coordinates");
        for (k, name) in ArmJoint::CONSTRAINT_NAMES.iter().enumerate() {
            let r = ArmBody::CONSTRAINT_NAMES.iter().position(|n| n == name).expect("the same driver");
            assert!(
                close(torques[k], lambda[r]),
                "{name} at t = {t}: {} N·m in joint coordinates, {} in body coordinates",
                torques[k],
                lambda[r]
            );
            assert!(torques[k].abs() > 0.1, "{name}: a real load");
        }
        reactions_agree(&b, (&qb, &vb, &vdb, &lambda), &j, (&q, &v, &vd, &torques), t);
    }
}

/// Nikravesh's variable-length pendulum (9.3.1, 13.4.1) in joint coordinates — `examples/
/// variable_pendulum.rs` compiled with `joint_coordinates;` (a collar angle and the rod's stroke
/// through it; both drivers cut) — against closed forms it does not compute: the bob's polar
/// kinematics (the example's `exact`, Coriolis term included), and by Lagrange, with no gravity
/// and the rod's centre of mass at the bob (mass m, J_r; collar J_c), the loads the drivers
/// supply: the swing torque τ = (J_c + J_r + m L²) θ̈ + 2 m L L̇ θ̇ on the collar and the
/// radial force m (L̈ − L θ̇²) on the rod; every joint's reaction must balance the bodies.
/// Tolerance: the sweep solves positions to 1e-13 and the loads are O(1–10) N, N·m; 1e-9
/// separates a right load from a wrong one (a missing Coriolis term is O(1)).
#[test]
fn nikravesh_variable_pendulum_in_joint_coordinates() {
    use mbd_examples::joint::variable_pendulum_0::VariablePendulum;
    use mbd_examples::variable_pendulum::exact;
    let m = VariablePendulum::default();
    // the closed form reads the parameters of the body-coordinate original (the same defaults)
    let original = mbd_examples::variable_pendulum::VariablePendulum::default();
    assert_eq!(VariablePendulum::COORDINATE_NAMES.len(), 2, "{:?}", VariablePendulum::COORDINATE_NAMES);
    let (mass, j_rod, j_collar) = (1.0, 0.05, 1.0e-3);
    let mut q = m.initial_positions();
    let mut states = Vec::new();
    let times = (0..=40).map(|k| 2.0 * k as f64 / 40.0);
    KinematicSolver::new(KinematicOptions::default().with_tolerance(1e-13))
        .sweep(&m, &mut VariablePendulum::workspace(), &mut q, times, |t, q, v, vd| states.push((t, *q, *v, *vd)))
        .unwrap();
    assert_eq!(states.len(), 41);
    let mut worst = [0.0f64; 5];
    for (t, q, v, vd) in states {
        let (p, velocity, acceleration, _) = exact(&original, t);
        let bob = m.rod_bob();
        let (bp, bv, ba) = (bob.position(&q), bob.velocity(&q, &v), bob.acceleration(&q, &v, &vd));
        // The same point by its body and plane coordinates, as `PlanarBody::point` takes them.
        let again = bob.body.point(&m, [bob.local[0], bob.local[1]]);
        assert_eq!((again.position(&q), again.acceleration(&q, &v, &vd)), (bp, ba));
        worst[0] = worst[0].max((bp.x - p[0]).abs().max((bp.y - p[1]).abs()));
        worst[1] = worst[1].max((bv.x - velocity[0]).abs().max((bv.y - velocity[1]).abs()));
        worst[2] = worst[2].max((ba.x - acceleration[0]).abs().max((ba.y - acceleration[1]).abs()));
        let mut lambda = [0.0; 2];
        InverseDynamics::default().solve(&m, &mut VariablePendulum::workspace(), &q, &v, &vd, t, &mut lambda).expect("driven");
        let w = m.omega;
        let (theta_d, theta_dd) = (m.theta0 * w * (w * t).cos(), -m.theta0 * w * w * (w * t).sin());
        let l = m.l0 + m.dl * (2.0 * w * t).sin();
        let (l_d, l_dd) = (2.0 * w * m.dl * (2.0 * w * t).cos(), -4.0 * w * w * m.dl * (2.0 * w * t).sin());
        let torque = (j_collar + j_rod + mass * l * l) * theta_dd + 2.0 * mass * l * l_d * theta_d;
        let radial = mass * (l_dd - l * theta_d * theta_d);
        let reaction = |joint: usize| joint_reaction_at(&m, &q, &v, &vd, t, &lambda, joint).expect("a joint");
        // JOINTS: the pin, the slide, the swing driver (on the collar), the length driver
        let swing = reaction(2).on_i.expect("the swing driver acts on the collar");
        worst[3] = worst[3].max((swing.moment[2] - torque).abs());
        let pull = reaction(3).on_j.expect("the length driver acts on the rod");
        let e_r = [p[0] / l, p[1] / l];
        worst[4] = worst[4].max((pull.force[0] * e_r[0] + pull.force[1] * e_r[1] - radial).abs());
        // the rod: the slide's and the length driver's forces are its whole load (no gravity)
        let slide = reaction(1).on_j.expect("the slide acts on the rod");
        for (c, a) in acceleration.iter().enumerate() {
            let total = slide.force[c] + pull.force[c];
            assert!((total - mass * a).abs() < 1e-9, "t = {t}: the rod's forces {total} N against m a = {} N", mass * a);
        }
    }
    let names = ["position (m)", "velocity (m/s)", "acceleration (m/s²)", "swing torque (N·m)", "radial force (N)"];
    for (name, error) in names.iter().zip(worst) {
        assert!(error < 1e-9, "variable pendulum in joint coordinates: {name} off the closed form by {error:e}");
    }
}

/// Nikravesh's slider-crank (9.5.1) in joint coordinates (`examples/slider_crank.rs` with
/// `joint_coordinates;`: the crank and rod angles and the slider's stroke; the slider pin cut)
/// against the closed form x = r cos θ + √(l² − r² sin² θ) and its derivatives (the example's
/// `exact`) over a turn. Tolerance as above: x is 0.2–0.4 m, ẍ up to 6 m/s².
#[test]
fn nikravesh_slider_crank_in_joint_coordinates() {
    use mbd_examples::joint::slider_crank_0::SliderCrank;
    use mbd_examples::slider_crank::exact;
    let m = SliderCrank::default();
    let mut q = m.initial_positions();
    let mut worst = [0.0f64; 3];
    let mut count = 0;
    let times = (0..=36).map(|k| k as f64 / 36.0);
    KinematicSolver::new(KinematicOptions::default().with_tolerance(1e-13))
        .sweep(&m, &mut SliderCrank::workspace(), &mut q, times, |t, q, v, vd| {
            let (x, xd, xdd) = exact(m.r, m.l, m.omega, t);
            let pin = m.slider_pin();
            worst[0] = worst[0].max((pin.position(q).x - x).abs());
            worst[1] = worst[1].max((pin.velocity(q, v).x - xd).abs());
            worst[2] = worst[2].max((pin.acceleration(q, v, vd).x - xdd).abs());
            count += 1;
        })
        .unwrap();
    assert_eq!(count, 37);
    assert!(worst.iter().all(|&e| e < 1e-9), "slider-crank in joint coordinates off the closed form by {worst:?} (x, ẋ, ẍ)");
}

mbd::mechanism! {
    /// Nikravesh's floating system (9.3.3) as a designer poses it: two bodies pinned together,
    /// joined by a torsion spring and damper, thrown with no path to ground — the first floats
    /// on a free joint (x, y, φ), the second hangs from it by its pin angle.
    pub ThrownPair {
        joint_coordinates;
        gravity [0.0, -9.81];
        body a { mass: 2.0, inertia: 0.1, at: [0.0, 1.0, 0.2], velocity: [1.0, 2.0, 3.0] }
        body b { mass: 1.0, inertia: 0.05, at: [0.5806, 0.9709, -0.3] }
        revolute pin: a[0.3, 0.0] ~ b[-0.3, 0.0];
        rotational_spring a ~ b { k: 5.0, angle: 0.0, c: 0.2 };
    }
}

/// The floating system in joint coordinates (three free coordinates and the pin's angle)
/// against what no formulation computes: thrown under gravity, its centre of mass flies the
/// parabola r(t) = r₀ + v₀ t − ½ g t² ŷ, and its angular momentum about the centre of mass stays
/// what it was (gravity has no moment there; the spring and damper are internal), while the pair
/// tumbles and the spring swings. Tolerance: DOPRI5 at rtol 1e-12 over 1 s leaves about 1e-11 m;
/// a missing inertia term moves the centre of mass by millimetres.
#[test]
fn nikravesh_floating_system_in_joint_coordinates() {
    let m = ThrownPair::default();
    assert_eq!(ThrownPair::COORDINATE_NAMES, &["a.x", "a.y", "a.phi", "pin.angle"]);
    let masses = [2.0, 1.0];
    let inertias = [0.1, 0.05];
    let centre = |q: &[f64; 4], v: &[f64; 4]| {
        let (mut r, mut rd, mut total) = ([0.0; 2], [0.0; 2], 0.0);
        for (k, &mass) in masses.iter().enumerate() {
            let (pose, twist) = (m.body_pose(k, q).unwrap(), m.body_twist(k, q, v).unwrap());
            for c in 0..2 {
                r[c] += mass * pose.position[c];
                rd[c] += mass * twist.velocity[c];
            }
            total += mass;
        }
        let (r, rd) = (r.map(|x| x / total), rd.map(|x| x / total));
        let mut momentum = 0.0;
        for (k, (&mass, &inertia)) in masses.iter().zip(&inertias).enumerate() {
            let (pose, twist) = (m.body_pose(k, q).unwrap(), m.body_twist(k, q, v).unwrap());
            let (d, dv) = ([pose.position[0] - r[0], pose.position[1] - r[1]], [twist.velocity[0] - rd[0], twist.velocity[1] - rd[1]]);
            momentum += inertia * twist.angular_velocity[2] + mass * (d[0] * dv[1] - d[1] * dv[0]);
        }
        (r, rd, momentum)
    };
    let (q0, v0) = (m.initial_positions(), m.initial_velocities());
    let (r0, rd0, momentum0) = centre(&q0, &v0);
    let end = one_second!(m, ThrownPair, q0, v0);
    let (r1, rd1, momentum1) = centre(&end.0, &end.1);
    let expected = [r0[0] + rd0[0], r0[1] + rd0[1] - 0.5 * 9.81];
    let expected_rate = [rd0[0], rd0[1] - 9.81];
    for c in 0..2 {
        assert!((r1[c] - expected[c]).abs() < 1e-9, "centre of mass {c} at 1 s: {} m, the parabola {} m", r1[c], expected[c]);
        assert!((rd1[c] - expected_rate[c]).abs() < 1e-9, "its velocity {c}: {} m/s, expected {} m/s", rd1[c], expected_rate[c]);
    }
    assert!((momentum1 - momentum0).abs() < 1e-9 * momentum0.abs().max(1.0), "angular momentum {momentum0} → {momentum1}");
    // not a rigid throw: the pin swung
    assert!((end.0[3] - q0[3]).abs() > 0.05, "the pin angle moved from {} to {}", q0[3], end.0[3]);
}

mbd::mechanism! {
    /// Nikravesh's three-body system (9.3.2) as a designer poses it: a cart on a frictionless
    /// horizontal rail carrying a double pendulum — a translational joint and two revolute
    /// joints in a chain from ground.
    pub CartDoublePendulum {
        joint_coordinates;
        gravity [0.0, -9.81];
        body cart { mass: 3.0, inertia: 0.2, at: [0.0, 0.0, 0.0] }
        body upper { mass: 1.0, inertia: 0.03, at: [0.25, 0.0, 0.0] }
        body lower { mass: 0.6, inertia: 0.02, at: [0.75, 0.0, 0.0] }
        translational rail: ground[0.0, 0.0] along [1.0, 0.0] ~ cart[0.0, 0.0] along [1.0, 0.0];
        revolute cart[0.0, 0.0] ~ upper[-0.25, 0.0];
        revolute upper[0.25, 0.0] ~ lower[-0.25, 0.0];
    }
}

/// The three-body system in joint coordinates (the cart's stroke and two angles, no rows)
/// released from the horizontal against two conservation laws computed by hand from the bodies'
/// poses and twists, not from the generated energies: the horizontal momentum Σ m ẋ (no
/// horizontal force acts) and the energy Σ ½ m |v|² + ½ J ω² + m g y. Tolerance: DOPRI5 at
/// rtol 1e-12 over 1 s leaves about 1e-10 J and kg·m/s; a wrong Coriolis term moves the energy
/// by joules.
#[test]
fn nikravesh_three_body_system_in_joint_coordinates() {
    let m = CartDoublePendulum::default();
    assert_eq!(CartDoublePendulum::COORDINATE_NAMES.len(), 3);
    let (masses, inertias) = ([3.0, 1.0, 0.6], [0.2, 0.03, 0.02]);
    let laws = |q: &[f64; 3], v: &[f64; 3]| {
        let (mut momentum, mut energy) = (0.0, 0.0);
        for k in 0..3 {
            let (pose, twist) = (m.body_pose(k, q).unwrap(), m.body_twist(k, q, v).unwrap());
            let speed2 = twist.velocity[0].powi(2) + twist.velocity[1].powi(2);
            momentum += masses[k] * twist.velocity[0];
            energy +=
                0.5 * masses[k] * speed2 + 0.5 * inertias[k] * twist.angular_velocity[2].powi(2) + masses[k] * 9.81 * pose.position[1];
        }
        (momentum, energy)
    };
    let (q0, v0) = (m.initial_positions(), [0.4, 0.0, 0.0]);
    let (p0, e0) = laws(&q0, &v0);
    let end = one_second!(m, CartDoublePendulum, q0, v0);
    let (p1, e1) = laws(&end.0, &end.1);
    assert!((p1 - p0).abs() < 1e-9, "horizontal momentum {p0} → {p1} kg·m/s");
    assert!((e1 - e0).abs() < 1e-9 * e0.abs().max(1.0), "energy {e0} → {e1} J");
    assert!(end.1[1].abs() > 1.0, "the pendulum swings: {:?}", end.1);
}

/// Nikravesh's double A-arm (9.6.1, 10.4.1; `examples/double_a_arm.rs` with
/// `joint_coordinates;`: the two arms' angles and the knuckle on the cut ball joints) against
/// its geometry solved here by hand: with the wheel centre's height y given, the arms' angles
/// φ_l, φ_u and the knuckle's x and φ_k close the two loops,
///
/// P_l + R(φ_l) (0.35, −0.02) = r_k + R(φ_k) (−0.07, −0.17),
/// P_u + R(φ_u) (0.22, 0.02) = r_k + R(φ_k) (−0.10, 0.17),
///
/// solved by Newton's method with a difference Jacobian from the design position. The knuckle's
/// x and camber angle over the travel must agree to 1e-9 (the sweep solves to 1e-13, the hand
/// Newton to 1e-14; a wrong placement is millimetres).
#[test]
fn nikravesh_double_a_arm_in_joint_coordinates() {
    use mbd_examples::joint::double_a_arm_0::DoubleAArm;
    let m = DoubleAArm::default();
    let rotate = |phi: f64, p: [f64; 2]| [phi.cos() * p[0] - phi.sin() * p[1], phi.sin() * p[0] + phi.cos() * p[1]];
    let residual = |x: [f64; 4], y: f64| -> [f64; 4] {
        let [phi_l, phi_u, x_k, phi_k] = x;
        let (lower, upper) = (rotate(phi_l, [0.35, -0.02]), rotate(phi_u, [0.22, 0.02]));
        let (ball_l, ball_u) = (rotate(phi_k, [-0.07, -0.17]), rotate(phi_k, [-0.10, 0.17]));
        [
            0.20 + lower[0] - x_k - ball_l[0],
            0.15 + lower[1] - y - ball_l[1],
            0.30 + upper[0] - x_k - ball_u[0],
            0.45 + upper[1] - y - ball_u[1],
        ]
    };
    let solve = |y: f64, mut x: [f64; 4]| -> [f64; 4] {
        for _ in 0..50 {
            let r = residual(x, y);
            if r.iter().all(|e| e.abs() < 1e-14) {
                break;
            }
            let mut jacobian = mbd::nalgebra::Matrix4::zeros();
            for c in 0..4 {
                let mut xp = x;
                xp[c] += 1e-7;
                let rp = residual(xp, y);
                for row in 0..4 {
                    jacobian[(row, c)] = (rp[row] - r[row]) / 1e-7;
                }
            }
            let step = jacobian.lu().solve(&mbd::nalgebra::Vector4::from(r)).expect("a regular Jacobian");
            for c in 0..4 {
                x[c] -= step[c];
            }
        }
        x
    };
    let knuckle = DoubleAArm::BODY_NAMES.iter().position(|b| *b == "knuckle").expect("the knuckle");
    let mut q = m.initial_positions();
    let mut guess = [0.0, 0.0, 0.62, 0.0];
    let mut worst = 0.0f64;
    let mut count = 0;
    KinematicSolver::new(KinematicOptions::default().with_tolerance(1e-13))
        .sweep(&m, &mut DoubleAArm::workspace(), &mut q, (0..=20).map(|k| k as f64 / 20.0), |t, q, _, _| {
            let y = m.wheel_y + m.travel * (m.omega * t).sin();
            guess = solve(y, guess);
            let pose = m.body_pose(knuckle, q).expect("the knuckle");
            assert!((pose.position[1] - y).abs() < 1e-13, "the driven height: {} m, driven to {y} m at t = {t}", pose.position[1]);
            worst = worst.max((pose.position[0] - guess[2]).abs()).max((pose.angle() - guess[3]).abs());
            count += 1;
        })
        .unwrap();
    assert_eq!(count, 21);
    assert!(worst < 1e-9, "the knuckle off the hand-solved geometry by {worst:e}");
}

/// Nikravesh's MacPherson strut (9.6.2; `examples/macpherson.rs` with `joint_coordinates;`: the
/// lower arm's angle, the knuckle on the cut ball joint, the rod on the top mount, the strut's
/// slide cut) against its geometry solved here by hand. With the lower arm at angle θ its
/// outer ball is B(θ) = P + R(θ) (0.35, −0.02), and the knuckle hangs from it: r_k = B − R(φ) b.
/// The strut's line through the knuckle's point s along its axis u passes through the top mount
/// T: cross(T − r_k − R(φ) s, R(φ) u) = 0, that is cross(T − B, R(φ) u) = −cross(b − s, u),
/// which gives φ in closed form: the axis turned from the direction of T − B by
/// asin(−cross(b − s, u) / (|T − B| |u|)). What is left, the driven height y_k of the wheel
/// centre, is one equation in θ, solved by the secant method. The knuckle's x and camber angle
/// over a period of ±80 mm travel must agree to 1e-9 (the sweep solves to 1e-13, the secant
/// to 1e-15; a wrong placement is millimetres).
#[test]
fn nikravesh_macpherson_strut_in_joint_coordinates() {
    use mbd_examples::joint::macpherson_0::MacPherson;
    let m = MacPherson::default();
    let rotate = |phi: f64, p: [f64; 2]| [phi.cos() * p[0] - phi.sin() * p[1], phi.sin() * p[0] + phi.cos() * p[1]];
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let (pivot, top) = ([0.25, 0.12], [0.50, 0.75]);
    let (ball, strut, axis) = ([-0.05, -0.20], [-0.08, 0.10], [-0.07, 0.35]);
    // (x_k, y_k, φ) of the knuckle with the lower arm at θ.
    let knuckle_at = |theta: f64| -> [f64; 3] {
        let arm = rotate(theta, [0.35, -0.02]);
        let b = [pivot[0] + arm[0], pivot[1] + arm[1]];
        let d = [top[0] - b[0], top[1] - b[1]];
        let c = cross([ball[0] - strut[0], ball[1] - strut[1]], axis);
        let (length_d, length_u) = (d[0].hypot(d[1]), axis[0].hypot(axis[1]));
        let turned = d[1].atan2(d[0]) + (-c / (length_d * length_u)).asin();
        let phi = turned - axis[1].atan2(axis[0]);
        let hung = rotate(phi, ball);
        [b[0] - hung[0], b[1] - hung[1], phi]
    };
    let solve = |y: f64, mut theta: f64| -> f64 {
        let mut previous = (theta + 1e-4, knuckle_at(theta + 1e-4)[1] - y);
        for _ in 0..50 {
            let f = knuckle_at(theta)[1] - y;
            if f.abs() < 1e-15 {
                break;
            }
            let next = theta - f * (theta - previous.0) / (f - previous.1);
            previous = (theta, f);
            theta = next;
        }
        theta
    };
    let knuckle = MacPherson::BODY_NAMES.iter().position(|b| *b == "knuckle").expect("the knuckle");
    let mut q = m.initial_positions();
    let mut theta = 0.0;
    let (mut worst, mut count, mut travel) = (0.0f64, 0, 0.0f64);
    KinematicSolver::new(KinematicOptions::default().with_tolerance(1e-13))
        .sweep(&m, &mut MacPherson::workspace(), &mut q, (0..=20).map(|k| k as f64 / 20.0), |t, q, _, _| {
            let y = m.wheel_y + m.travel * (m.omega * t).sin();
            theta = solve(y, theta);
            let hand = knuckle_at(theta);
            let pose = m.body_pose(knuckle, q).expect("the knuckle");
            assert!((pose.position[1] - y).abs() < 1e-13, "the driven height: {} m, driven to {y} m at t = {t}", pose.position[1]);
            worst = worst.max((pose.position[0] - hand[0]).abs()).max((pose.angle() - hand[2]).abs());
            travel = travel.max((y - m.wheel_y).abs());
            count += 1;
        })
        .unwrap();
    assert_eq!(count, 21);
    assert!(travel > 0.079, "the sweep covers the travel: {travel} m");
    assert!(worst < 1e-9, "the knuckle off the hand-solved geometry by {worst:e}");
}

/// Nikravesh's suspensions in motion (10.4.1 double A-arm, 10.4.2 MacPherson;
/// `examples/suspension_dynamics.rs` with `joint_coordinates;`), the dampers and the bump taken
/// out: released from the design position, each bounces on its coil spring and tyre, and the
/// energy computed here from the bodies' poses and twists — Σ ½ m |v|² + ½ J ω² + m g y, the
/// coil's ½ k_s (ℓ − ℓ₀)² between its two points and the tyre's ½ k_t y_c² at the contact
/// point — must stay what it was. Tolerance: DOPRI5 at rtol 1e-12 over 1 s leaves about 1e-10
/// of the energy (260 J for the MacPherson strut); a tyre stiffer by 5 ppm already moves it by
/// 8e-5 J, a wrong velocity term by joules.
#[test]
fn nikravesh_suspensions_conserve_energy_in_joint_coordinates() {
    use mbd_examples::joint::suspension_dynamics_0::DoubleAArmRide;
    use mbd_examples::joint::suspension_dynamics_1::MacPhersonRide;
    const G: f64 = 9.81;
    // (body masses, inertias, the coil's body, its point on it, its ground point, k_s, ℓ₀, k_t)
    type Data = ([f64; 3], [f64; 3], usize, [f64; 3], [f64; 2], f64, f64, f64);
    fn energy<M: BodyFrames<f64, N, N>, const N: usize>(m: &M, data: &Data, knuckle: usize, q: &[f64; N], v: &[f64; N]) -> f64 {
        let (masses, inertias, coil_body, coil_point, coil_ground, k_s, free_length, k_t) = *data;
        let mut energy = 0.0;
        for k in 0..3 {
            let (pose, twist) = (m.body_pose(k, q).unwrap(), m.body_twist(k, q, v).unwrap());
            let speed2 = twist.velocity[0].powi(2) + twist.velocity[1].powi(2);
            energy += 0.5 * masses[k] * speed2 + 0.5 * inertias[k] * twist.angular_velocity[2].powi(2) + masses[k] * G * pose.position[1];
        }
        let end = m.body_pose(coil_body, q).unwrap().point(coil_point);
        let length = (end[0] - coil_ground[0]).hypot(end[1] - coil_ground[1]);
        let contact = m.body_pose(knuckle, q).unwrap().point([0.0, -0.30, 0.0]);
        energy + 0.5 * k_s * (length - free_length).powi(2) + 0.5 * k_t * contact[1].powi(2)
    }
    macro_rules! check {
        ($ty:ident, $data:expr) => {{
            let m = $ty { c_s: 0.0, c_t: 0.0, bump: 0.0, ..$ty::default() };
            let data: Data = $data;
            let name = |body: &str| $ty::BODY_NAMES.iter().position(|b| *b == body).expect(body);
            let knuckle = name("knuckle");
            let mut q0 = m.initial_positions();
            KinematicSolver::default().assemble(&m, &mut $ty::workspace(), &mut q0, 0.0).expect(stringify!($ty));
            let v0 = [0.0; $ty::NV];
            let e0 = energy(&m, &data, knuckle, &q0, &v0);
            let end = one_second!(m, $ty, q0, v0);
            let e1 = energy(&m, &data, knuckle, &end.0, &end.1);
            assert!((e1 - e0).abs() < 1e-9 * e0.abs(), "{}: energy {e0} → {e1} J", stringify!($ty));
            let moved = m.body_pose(knuckle, &end.0).unwrap().position[1] - m.body_pose(knuckle, &q0).unwrap().position[1];
            assert!(moved.abs() > 1e-3, "{}: the wheel moved {moved} m", stringify!($ty));
        }};
    }
    let order = |names: &[&str], body: &str| names.iter().position(|b| *b == body).expect(body);
    let (a, mcp) = (DoubleAArmRide::BODY_NAMES, MacPhersonRide::BODY_NAMES);
    // The DSL's masses and inertias, in each mechanism's body order.
    let by_name = |names: &[&str], table: &[(&str, f64, f64)]| {
        let (mut masses, mut inertias) = ([0.0; 3], [0.0; 3]);
        for (body, mass, inertia) in table {
            let k = order(names, body);
            (masses[k], inertias[k]) = (*mass, *inertia);
        }
        (masses, inertias)
    };
    let (masses, inertias) = by_name(a, &[("lower", 4.0, 0.05), ("upper", 2.5, 0.02), ("knuckle", 18.0, 0.60)]);
    check!(DoubleAArmRide, (masses, inertias, order(a, "lower"), [0.1, 0.0, 0.0], [0.45, 0.60], 30000.0, 0.61, 200000.0));
    let (masses, inertias) = by_name(mcp, &[("lower", 4.0, 0.05), ("knuckle", 20.0, 0.65), ("rod", 1.0, 0.01)]);
    check!(MacPhersonRide, (masses, inertias, order(mcp, "knuckle"), [-0.08, 0.10, 0.0], [0.50, 0.75], 25000.0, 0.48, 200000.0));
}

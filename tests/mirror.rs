//! Mirrored instances (`corner front_right(...) mirrored y;`): a part's statements reflected in a
//! coordinate plane. In a world symmetric about that plane, the mirrored instance moves as the
//! mirror image of the plain one — checked here on a planar and a spatial part that between them
//! hold every kind of statement the reflection rewrites.
use mbd::nalgebra::Matrix3;
use mbd::prelude::*;

mechanism! {
    /// Two legs, the right one the left one mirrored in x: pins, a driven knee, a slider on a
    /// tilted guide, a pin in a slot, a welded plate; a spring-damper-actuator, a damper and
    /// rotational spring, a torque, global and local forces, each reading the state.
    pub Legs {
        gravity [0.0, -9.81];
        part leg(reach) {
            body thigh { mass: 1.0, inertia: 0.02, at: [0.45, 0.0, 0.0], velocity: [0.0, 0.25, 1.0] }
            body shin { mass: 0.6, inertia: 0.01, at: [0.9, 0.0, 0.0], velocity: [0.0, 0.76, 1.3] }
            body block { mass: 0.8, inertia: 0.004, at: [0.5, -0.5, 0.0] }
            body plate { mass: 0.3, inertia: 0.002, at: [0.7, -0.5, 0.4] }
            body rider { mass: 0.2, inertia: 0.001, at: [0.0, 1.1, 0.2] }
            point shin.toe = [0.2, -0.05];
            revolute hip: ground[0.2, 0.0] ~ thigh[-0.25, 0.0] { viscous: 0.01 };
            revolute knee: thigh[0.25, 0.0] ~ shin[-0.2, 0.0];
            drive bend: angle(thigh, shin) = 0.3 * sin(t);
            translational guide: ground[0.5, -0.5] along [1.0, 0.3] ~ block[0.0, 0.0] along [1.0, 0.3];
            rigid block[0.2, 0.0] ~ plate[0.0, 0.0] { angle: 0.4 };
            revolute_translational rider[0.0, 0.0] ~ ground[0.0, 1.0] along [1.0, 0.2] { distance: 0.1 };
            spring shin[0.2, 0.0] ~ block[0.0, 0.0] { k: 50.0, length: reach, c: 0.5, force: 2.0 * block.vx };
            damper shin.toe ~ ground[1.0, -1.0] { c: 0.8 };
            rotational_spring ground ~ thigh { k: 5.0, angle: 0.3, torque: 0.2 * thigh.phi };
            torque thigh = 0.5 * sin(3.0 * t) + 0.1 * shin.omega;
            force shin[0.1, 0.05] = [1.0 + shin.x, -2.0];
            local_force block[0.0, 0.1] = [0.5, 0.3 * t + rider.y];
        }
        leg left(reach: 0.4);
        leg right(reach: 0.4) mirrored x;
    }
}

mechanism! {
    /// Two arms in space, the right one the left one mirrored in y: a hinge along x (its default
    /// reference is the mirrored axis), a spherical joint, a sleeve on a tilted cylindrical
    /// joint driven in angle, a point on a plane; bodies oriented by angles, a quaternion and an
    /// axis and angle, with products of inertia; a rotational and a translational spring, a
    /// bushing with preload, a force, a body-frame and a global torque, each reading the state.
    pub Arms {
        spatial;
        gravity [0.0, 0.0, -9.81];
        part arm(lift) {
            body upper { mass: 1.0, inertia: [0.02, 0.03, 0.04, 0.001, 0.002, -0.003], at: [0.5, 0.3, 0.0], omega: [0.5, 0.0, 0.0] }
            body bob { mass: 0.5, inertia: [0.01, 0.012, 0.014], at: [0.8, 0.3, -0.3], angles: [0.3, 0.2, 0.1] }
            body slider { mass: 0.7, inertia: [0.01, 0.02, 0.03], at: [0.0, 1.0, 0.0], quaternion: [0.9, 0.1, 0.2, 0.3] }
            body box { mass: 0.4, inertia: [0.01, 0.015, 0.02, 0.001, 0.0, 0.002], at: [0.5, 0.8, -0.2], axis_angle: [1.0, 2.0, 3.0, 0.5] }
            revolute hinge: ground[0.2, 0.3, 0.0] along [1.0, 0.0, 0.0] ~ upper[-0.3, 0.0, 0.0] along [1.0, 0.0, 0.0];
            spherical upper[0.3, 0.0, 0.0] ~ bob[0.0, 0.0, 0.3];
            cylindrical sleeve: ground[0.0, 1.0, 0.0] along [0.0, 0.6, 0.8] ~ slider[0.0, 0.0, 0.0] along [0.0, 0.6, 0.8];
            drive turn: sleeve.angle = 0.5 * t;
            point_on_plane ground[0.0, 0.0, -0.5] along [0.1, 0.3, 1.0] ~ box[0.1, 0.0, 0.0] { distance: 0.3 };
            rotational_spring hinge { k: 2.0, angle: 0.4, c: 0.05, torque: 0.1 * bob.wz };
            translational_spring sleeve { k: 30.0, length: lift, c: 0.2 };
            bushing bob[0.0, 0.0, 0.0] ~ slider[0.0, 0.0, 0.3] { k: [100.0, 120.0, 140.0, 5.0, 6.0, 7.0], c: [1.0, 1.0, 1.0, 0.1, 0.1, 0.1], preload: [0.01, 0.02, 0.0, 0.03, 0.0, 0.04] };
            force bob[0.0, 0.1, 0.0] = [0.2, 1.0 + bob.y, slider.vz + box.e2];
            local_torque upper = [0.1, 0.2 * t, upper.wy];
            torque slider = [0.1 * slider.e1, 0.2, 0.3 * slider.wx];
        }
        arm left(lift: 0.1);
        arm right(lift: 0.1) mirrored y;
    }
}

/// The state after 0.5 s with DOPRI5 at rtol 1e-10 from the assembled start.
fn run<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    m: &M,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
) -> ([f64; NQ], [f64; NV])
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
{
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(m, ws, &mut q, 0.0).expect("assembles");
    let mut v = m.initial_velocities();
    m.project_velocities(&q, &mut v, 0.0, &DynamicsOptions::default()).expect("velocities on the constraints");
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    let mut last = (q, v);
    Simulation::new(m, &mut dopri).start(0.0, &q, &v).times(&[0.5]).run(ws, |s| last = (s.point.q, s.point.v)).expect("runs");
    last
}

/// Both halves are integrated in one state with the same steps, and the reflection only negates
/// numbers (exact in floating point), so they could agree bit for bit (measured: 0); 1e-9 leaves
/// room for a compiler that orders one half's sums differently. Each body moves by more than
/// 1 cm or 0.01 rad, so the images are not those of bodies at rest.
const SAME: f64 = 1e-9;

#[test]
fn a_mirrored_planar_instance_moves_as_the_mirror_image() {
    let m = Legs::default();
    let q0 = m.initial_positions();
    let (q, v) = run(&m, &mut Legs::workspace());
    let pairs = [
        (Legs::LEFT_THIGH, Legs::RIGHT_THIGH),
        (Legs::LEFT_SHIN, Legs::RIGHT_SHIN),
        (Legs::LEFT_BLOCK, Legs::RIGHT_BLOCK),
        (Legs::LEFT_PLATE, Legs::RIGHT_PLATE),
        (Legs::LEFT_RIDER, Legs::RIGHT_RIDER),
    ];
    let mut worst: f64 = 0.0;
    for (l, r) in pairs {
        let d = [r.x(&q) + l.x(&q), r.y(&q) - l.y(&q), r.phi(&q) + l.phi(&q)];
        let dv = [r.velocity(&v).x + l.velocity(&v).x, r.velocity(&v).y - l.velocity(&v).y, r.omega(&v) + l.omega(&v)];
        let off = d.iter().chain(&dv).fold(0.0, |m: f64, x| m.max(x.abs()));
        worst = worst.max(off);
        assert!(off <= SAME, "{}: {d:?} {dv:?}", r.name);
        assert!((l.position(&q) - l.position(&q0)).norm() > 0.01 || (l.phi(&q) - l.phi(&q0)).abs() > 0.01, "{} moved", l.name);
    }
    eprintln!("planar: mirror images to {worst:.1e}");
}

#[test]
fn a_mirrored_spatial_instance_moves_as_the_mirror_image() {
    let m = Arms::default();
    let (q, v) = run(&m, &mut Arms::workspace());
    let s = Matrix3::from_diagonal(&mbd::nalgebra::Vector3::new(1.0, -1.0, 1.0));
    let pairs = [
        (Arms::LEFT_UPPER, Arms::RIGHT_UPPER),
        (Arms::LEFT_BOB, Arms::RIGHT_BOB),
        (Arms::LEFT_SLIDER, Arms::RIGHT_SLIDER),
        (Arms::LEFT_BOX, Arms::RIGHT_BOX),
    ];
    let q0 = m.initial_positions();
    let mut worst: f64 = 0.0;
    for (l, r) in pairs {
        let moved = (l.position(&q) - l.position(&q0)).norm().max((l.rotation(&q) - l.rotation(&q0)).norm());
        assert!(moved > 0.01, "{} moved: {moved}", l.name);
        let position = (r.position(&q).coords - s * l.position(&q).coords).norm();
        let rotation = (r.rotation(&q) - s * l.rotation(&q) * s).norm();
        let velocity = (r.velocity(&v) - s * l.velocity(&v)).norm();
        // Angular velocity is axial: ω_right = −S ω_left.
        let omega = (r.angular_velocity(&q, &v) + s * l.angular_velocity(&q, &v)).norm();
        let off = position.max(rotation).max(velocity).max(omega);
        worst = worst.max(off);
        assert!(off <= SAME, "{}: {position:e} {rotation:e} {velocity:e} {omega:e}", r.name);
    }
    let (a, b) = (m.left_hinge_angle(&q), m.right_hinge_angle(&q));
    assert!((a + b).abs() <= SAME && a.abs() > 0.05, "a joint's angle is −θ in the mirror image: {a} {b}");
    assert!((m.left_sleeve_stroke(&q) - m.right_sleeve_stroke(&q)).abs() <= SAME, "its stroke is s");
    eprintln!("spatial: mirror images to {worst:.1e}");
}

mechanism! {
    /// Reflections compose: a pair of arms, plain and mirrored, used plain and mirrored. The
    /// mirrored pair's mirrored arm is reflected twice: the plain arm again, in its place.
    pub Pairs {
        gravity [0.0, -9.81];
        part arm(x0) {
            body link { mass: 1.0, inertia: 0.02, at: [x0 + 0.25, 0.1, 0.3] }
            body tip { mass: 0.3, inertia: 0.002, at: [x0 + 0.6, 0.2, -0.2] }
            revolute ground[x0, 0.0] ~ link[-0.25, 0.0];
            revolute link[0.25, 0.0] ~ tip[-0.1, 0.0];
            rotational_spring link ~ tip { k: 3.0, angle: 0.5 };
            torque link = 0.4 * sin(2.0 * t) + 0.1 * tip.omega;
        }
        part pair(x0) {
            arm own(x0: x0);
            arm image(x0: x0) mirrored x;
        }
        pair near(x0: 0.5);
        pair far(x0: 0.5) mirrored x;
    }
}

/// Reflecting twice is no reflection: `far.image` moves as `near.own` (the same statements,
/// each number negated twice), and `far.own` as `near.image`.
#[test]
fn a_mirrored_part_holding_a_mirrored_instance_reflects_it_back() {
    let m = Pairs::default();
    let (q, _) = run(&m, &mut Pairs::workspace());
    for (a, b) in [(Pairs::NEAR_OWN_LINK, Pairs::FAR_IMAGE_LINK), (Pairs::NEAR_OWN_TIP, Pairs::FAR_IMAGE_TIP)] {
        let d = [a.x(&q) - b.x(&q), a.y(&q) - b.y(&q), a.phi(&q) - b.phi(&q)];
        assert!(d.iter().all(|x| x.abs() <= SAME), "{}: {d:?}", b.name);
    }
    for (a, b) in [(Pairs::NEAR_IMAGE_LINK, Pairs::FAR_OWN_LINK), (Pairs::NEAR_IMAGE_TIP, Pairs::FAR_OWN_TIP)] {
        let d = [a.x(&q) - b.x(&q), a.y(&q) - b.y(&q), a.phi(&q) - b.phi(&q)];
        assert!(d.iter().all(|x| x.abs() <= SAME), "{}: {d:?}", b.name);
    }
    assert!(Pairs::NEAR_OWN_LINK.x(&q) > 0.0 && Pairs::NEAR_IMAGE_LINK.x(&q) < 0.0, "the two sides");
}

//! Spatial bodies against closed forms and invariants that know nothing of mbd: a torque-free
//! asymmetric body (energy and angular momentum conserved; rotation about the intermediate axis
//! unstable, about the others stable), a heavy symmetric top (steady precession rate), a conical
//! pendulum, an RSSR spatial four-bar (closed-form output angle) and a spatial slider-crank
//! (closed-form stroke, speed and acceleration).
//!
//! Tolerances: kinematic solves converge to ‖Φ‖∞ ≤ 1e-10 (the default), so positions agree with
//! the closed forms to about 1e-10 m or rad times the condition of the loop (≤ 10 here);
//! simulations use DOPRI5 at rtol 1e-10, whose global error over the runs below stays under
//! 1e-7 relative (each bound says where it comes from).
use mbd::nalgebra;
use mbd::prelude::*;

mechanism! {
    /// An asymmetric body spinning freely (principal moments 1, 2, 3 kg·m²).
    pub FreeBody {
        spatial;
        params { wx: 0.0, wy: 0.0, wz: 0.0 }
        body b { mass: 1.0, inertia: [1.0, 2.0, 3.0], axis_angle: [1.0, 2.0, 3.0, 0.7], omega: [wx, wy, wz] }
    }
}

mechanism! {
    /// A heavy symmetric top on a ball joint at the ground origin, its centre of mass l above the
    /// pivot along its symmetry axis, tilted θ about the global x-axis, spinning.
    pub Top {
        spatial;
        params { l: 0.1, theta: 0.5, wx: 0.0, wy: 0.0, wz: 0.0, vx: 0.0, vy: 0.0, vz: 0.0 }
        gravity [0.0, 0.0, -9.81];
        body top {
            mass: 1.0, inertia: [0.005, 0.005, 0.002],
            at: [0.0, -l * sin(theta), l * cos(theta)], axis_angle: [1.0, 0.0, 0.0, theta],
            velocity: [vx, vy, vz], omega: [wx, wy, wz]
        }
        spherical ground[0.0, 0.0, 0.0] ~ top[0.0, 0.0, -l];
    }
}

mechanism! {
    /// A bob on a massless spherical–spherical link of length L from a fixed pivot: its centre
    /// moves as a point mass, whatever its rotation does.
    pub ConicalPendulum {
        spatial;
        params { len: 1.0, theta: 0.4, speed: 0.0 }
        gravity [0.0, 0.0, -9.81];
        body bob { mass: 2.0, inertia: [0.01, 0.02, 0.03], at: [len * sin(theta), 0.0, -len * cos(theta)], velocity: [0.0, speed, 0.0] }
        distance ground[0.0, 0.0, 0.0] ~ bob[0.0, 0.0, 0.0] { length: len };
    }
}

mechanism! {
    /// RSSR spatial four-bar: a crank turning about the global z-axis at the origin, a rocker
    /// turning about the x-axis through (dx, 0, dz), a spherical–spherical coupler of length L.
    pub Rssr {
        spatial;
        params { a: 0.1, b: 0.25, len: 0.45, dx: 0.2, dz: 0.3, omega: 2.0 }
        body crank { mass: 0.5, inertia: [1.0e-4, 1.0e-3, 1.0e-3] }
        body rocker { mass: 0.8, inertia: [4.0e-3, 2.0e-4, 4.0e-3], at: [dx, 0.0, dz], axis_angle: [1.0, 0.0, 0.0, 0.27] }
        revolute input: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ crank[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
        revolute output: ground[dx, 0.0, dz] along [1.0, 0.0, 0.0] ~ rocker[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0];
        distance crank[a, 0.0, 0.0] ~ rocker[0.0, b, 0.0] { length: len };
        drive input.angle = omega * t;
    }
}

mechanism! {
    /// A spatial slider-crank: the crank turns about z at the origin, the slider runs along x on
    /// a line offset by (ey, ez) from the crank's plane, a spherical–spherical rod of length L.
    pub SpatialSliderCrank {
        spatial;
        params { a: 0.1, len: 0.35, ey: 0.05, ez: 0.08, omega: 3.0 }
        body crank { mass: 1.0, inertia: [1.0e-3, 1.0e-3, 2.0e-3] }
        body slider { mass: 0.5, inertia: [1.0e-4, 1.0e-4, 1.0e-4], at: [0.4, ey, ez] }
        point crank.pin = [a, 0.0, 0.0];
        point ground.guide = [0.0, ey, ez];
        revolute crankshaft: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ crank[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
        translational guide: ground.guide along [1.0, 0.0, 0.0] ~ slider[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0];
        distance crank.pin ~ slider[0.0, 0.0, 0.0] { length: len };
        drive crankshaft.angle = omega * t;
    }
}

mechanism! {
    /// A free body with products of inertia and a parameter mass, for `mass_of`/`inertia_of`.
    pub Tumbler {
        spatial;
        params { m: 2.5 }
        body block { mass: 2.0 * m, inertia: [0.2, 0.25, 0.1, 0.01, -0.03, 0.02] }
        body disc { mass: 0.5, inertia: [0.1, 0.1, 0.2] }
        spherical ground[0.0, 0.0, 0.0] ~ disc[0.0, 0.0, 0.0];
    }
}

/// A body's mass and inertia tensor by name, as written (Jxy in both off-diagonal places), with
/// a parameter read at its current value.
#[test]
fn mass_and_inertia_by_name() {
    let mut m = Tumbler::default();
    assert_eq!(m.mass_of(Tumbler::BLOCK), 5.0);
    assert_eq!(m.mass_of(Tumbler::DISC), 0.5);
    let j = nalgebra::Matrix3::new(0.2, 0.01, -0.03, 0.01, 0.25, 0.02, -0.03, 0.02, 0.1);
    assert_eq!(m.inertia_of(Tumbler::BLOCK), j);
    assert_eq!(m.inertia_of(Tumbler::DISC), nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::new(0.1, 0.1, 0.2)));
    m.m = 1.0;
    assert_eq!(m.mass_of(Tumbler::BLOCK), 2.0);
}

/// A(p) = (2e0² − 1)I + 2(eeᵀ + e0ẽ) of the Euler parameters at q[7k+3..7k+7].
fn rotation(q: &[f64], body: usize) -> [[f64; 3]; 3] {
    let [e0, e1, e2, e3] = [q[7 * body + 3], q[7 * body + 4], q[7 * body + 5], q[7 * body + 6]];
    let e = [e1, e2, e3];
    let tilde = [[0.0, -e3, e2], [e3, 0.0, -e1], [-e2, e1, 0.0]];
    core::array::from_fn(|r| {
        core::array::from_fn(|c| if r == c { 2.0 * e0 * e0 - 1.0 } else { 0.0 } + 2.0 * (e[r] * e[c] + e0 * tilde[r][c]))
    })
}

fn times(step: f64, end: f64) -> Vec<f64> {
    (1..=(end / step).round() as usize).map(|k| k as f64 * step).collect()
}

fn tight() -> Dopri5<f64, 7, 6> {
    Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12))
}

/// Energy and global angular momentum L = A J′ω′ of a torque-free body over 100 s, and the
/// stability of its three axes: a spin about the axis of least or greatest inertia with a 0.5 %
/// wobble keeps its wobble; about the intermediate axis the wobble grows at
/// ω √((J2 − J1)(J3 − J2)/(J1 J3)) = 1.15/s and the body tumbles.
#[test]
fn torque_free_body() {
    let j = [1.0, 2.0, 3.0];
    let cases = [([2.0, 0.01, 0.01], 0, false), ([0.01, 2.0, 0.01], 1, true), ([0.01, 0.01, 2.0], 2, false)];
    for (w0, axis, unstable) in cases {
        let m = FreeBody { wx: w0[0], wy: w0[1], wz: w0[2] };
        let (q0, v0) = (m.initial_positions(), m.initial_velocities());
        let momentum = |q: &[f64; 7], v: &[f64; 6]| -> [f64; 3] {
            let a = rotation(q, 0);
            core::array::from_fn(|r| (0..3).map(|c| a[r][c] * j[c] * v[3 + c]).sum())
        };
        let l0 = momentum(&q0, &v0);
        let e0: f64 = (0..3).map(|k| 0.5 * j[k] * w0[k] * w0[k]).sum();
        let (mut worst_e, mut worst_l, mut wobble) = (0.0f64, 0.0f64, 0.0f64);
        Simulation::new(&m, &mut tight())
            .start(0.0, &q0, &v0)
            .times(&times(0.05, 100.0))
            .run(&mut FreeBody::workspace(), |s| {
                let (q, v) = (&s.point.q, &s.point.v);
                let e: f64 = (0..3).map(|k| 0.5 * j[k] * v[3 + k] * v[3 + k]).sum();
                worst_e = worst_e.max((e - e0).abs() / e0);
                let l = momentum(q, v);
                let dl = ((l[0] - l0[0]).powi(2) + (l[1] - l0[1]).powi(2) + (l[2] - l0[2]).powi(2)).sqrt();
                worst_l = worst_l.max(dl / (l0[0] * l0[0] + l0[1] * l0[1] + l0[2] * l0[2]).sqrt());
                let off: f64 = (0..3).filter(|&k| k != axis).map(|k| v[3 + k].abs()).fold(0.0, f64::max);
                wobble = wobble.max(off);
            })
            .unwrap();
        println!("axis {axis}: energy drift {worst_e:.1e}, momentum drift {worst_l:.1e}, largest off-axis ω′ {wobble:.3} rad/s");
        // DOPRI5 at rtol 1e-10 over 2000 output intervals: the invariants drift by < 1e-7.
        assert!(worst_e < 1e-7 && worst_l < 1e-7, "axis {axis}: energy drift {worst_e:e}, momentum drift {worst_l:e}");
        if unstable {
            assert!(wobble > 1.0, "the intermediate axis is unstable: the wobble grew only to {wobble}");
        } else {
            assert!(wobble < 0.05, "axis {axis} is stable: the wobble grew to {wobble}");
        }
    }
}

/// A heavy top started in steady precession: with A and C its moments of inertia about the
/// pivot (A = A_cm + m l²) and ω3 its spin component, the precession rate Ω solves
/// A cos θ Ω² − C ω3 Ω + m g l = 0 (the slow root); the tilt θ stays and the symmetry axis
/// turns about the vertical at Ω.
#[test]
fn heavy_top_precesses_steadily() {
    let (m_, g, l, theta, a_cm, c) = (1.0, 9.81, 0.1, 0.5f64, 0.005, 0.002);
    let a = a_cm + m_ * l * l;
    let w3 = 200.0;
    let omega = (c * w3 - ((c * w3).powi(2) - 4.0 * a * theta.cos() * m_ * g * l).sqrt()) / (2.0 * a * theta.cos());
    // ω′ = Ω Aᵀẑ + ψ̇ ẑ′ with Aᵀẑ = (0, sin θ, cos θ) for a tilt about x; ω3 = Ω cos θ + ψ̇.
    let w = [0.0, omega * theta.sin(), w3];
    // ṙ = ω × r, ω = Ω ẑ + ψ̇ ẑ_b globally, r = l ẑ_b = l (0, −sin θ, cos θ): only Ω ẑ × r.
    let r = [0.0, -l * theta.sin(), l * theta.cos()];
    let vr = [-omega * r[1], omega * r[0], 0.0];
    let top = Top { l, theta, wx: w[0], wy: w[1], wz: w[2], vx: vr[0], vy: vr[1], vz: vr[2] };
    let (q0, v0) = (top.initial_positions(), top.initial_velocities());
    let (mut last, mut worst_tilt, mut azimuth) = (0.0, 0.0f64, Vec::new());
    let options = SimulationOptions::default().with_correction(Correction::projection());
    Simulation::new(&top, &mut tight())
        .start(0.0, &q0, &v0)
        .times(&times(0.01, 2.0))
        .options(options)
        .run(&mut Top::workspace(), |s| {
            let axis = rotation(&s.point.q, 0).map(|row| row[2]);
            worst_tilt = worst_tilt.max((axis[2].acos() - theta).abs());
            azimuth.push((s.point.t, axis[1].atan2(axis[0])));
            last = s.point.t;
        })
        .unwrap();
    let mut turned = 0.0;
    for pair in azimuth.windows(2) {
        let mut d = pair[1].1 - pair[0].1;
        d -= (d / (2.0 * PI)).round() * 2.0 * PI;
        turned += d;
    }
    assert_eq!(azimuth.len(), 200, "one sample per output time");
    let rate = turned / (last - azimuth[0].0);
    println!("precession {rate:.12} rad/s, closed form {omega:.12} rad/s; tilt drift {worst_tilt:.1e} rad");
    // Ω ≈ 2.7 rad/s: rtol 1e-10 over 2 s gives a rate within 1e-8 relative; the tilt within 1e-8.
    assert!((rate - omega).abs() < 1e-7 * omega, "precession {rate} rad/s, closed form {omega} rad/s");
    assert!(worst_tilt < 1e-7, "the tilt drifted by {worst_tilt} rad");
}

/// A conical pendulum at half-angle θ turns at Ω = √(g / (L cos θ)) with constant height.
#[test]
fn conical_pendulum() {
    let (len, theta, g) = (1.0, 0.4f64, 9.81);
    let omega = (g / (len * theta.cos())).sqrt();
    let m = ConicalPendulum { len, theta, speed: omega * len * theta.sin() };
    let (q0, v0) = (m.initial_positions(), m.initial_velocities());
    let (mut worst_z, mut angle_error) = (0.0f64, 0.0f64);
    let mut previous = 0.0f64;
    let (mut turned, mut samples) = (0.0, 0);
    Simulation::new(&m, &mut tight())
        .start(0.0, &q0, &v0)
        .times(&times(0.01, 5.0))
        .run(&mut ConicalPendulum::workspace(), |s| {
            samples += 1;
            let q = &s.point.q;
            worst_z = worst_z.max((q[2] + len * theta.cos()).abs());
            let angle = q[1].atan2(q[0]);
            let mut d = angle - previous;
            d -= (d / (2.0 * PI)).round() * 2.0 * PI;
            turned += d;
            previous = angle;
            angle_error = angle_error.max((turned - omega * s.point.t).abs());
        })
        .unwrap();
    println!("conical pendulum over 5 s: height error {worst_z:.1e} m, angle error {angle_error:.1e} rad");
    assert_eq!(samples, 500);
    assert!(worst_z < 1e-8 && angle_error < 1e-7, "height error {worst_z} m, angle error {angle_error} rad");
}

/// The RSSR four-bar's output angle ψ against its closed form over a full crank turn: with the
/// crank pin P = (a cos θ, a sin θ, 0) and the rocker pin Q = (dx, b cos ψ, dz + b sin ψ),
/// |P − Q| = L reads K1 cos ψ + K2 sin ψ = K3; its rate ψ̇ against the closed form's central
/// difference.
#[test]
fn rssr_output_angle() {
    let m = Rssr::default();
    let (a, b, len, dx, dz, w) = (m.a, m.b, m.len, m.dx, m.dz, m.omega);
    // the root of K1 cos ψ + K2 sin ψ = K3 nearest `near` (the branch the mechanism assembles on)
    let psi = |theta: f64, near: f64| {
        let (k1, k2) = (-2.0 * a * b * theta.sin(), 2.0 * dz * b);
        let k3 = len * len - (a * theta.cos() - dx).powi(2) - (a * theta.sin()).powi(2) - dz * dz - b * b;
        let (phase, spread) = (k2.atan2(k1), (k3 / k1.hypot(k2)).acos());
        let nearest = |p: f64| p - ((p - near) / (2.0 * PI)).round() * 2.0 * PI;
        let (x, y) = (nearest(phase + spread), nearest(phase - spread));
        if (x - near).abs() < (y - near).abs() {
            x
        } else {
            y
        }
    };
    let solver = KinematicSolver::new(KinematicOptions::default());
    let mut q = m.initial_positions();
    let (mut checked, mut previous) = (0, 0.27);
    solver
        .sweep(&m, &mut Rssr::workspace(), &mut q, times(0.05, 2.0 * PI / w), |t, q, v, _| {
            let theta = w * t;
            // the rocker turns about x: p = (cos ψ/2, sin ψ/2, 0, 0)
            let p = Rssr::ROCKER.orientation(q);
            let got = 2.0 * p.i.atan2(p.w);
            let want = psi(theta, previous);
            previous = want;
            let d = 1e-6;
            let rate = (psi(theta + d, want) - psi(theta - d, want)) / (2.0 * d) * w;
            assert!((got - want).abs() < 1e-9, "θ = {theta}: ψ = {got}, closed form {want}");
            // the joint's own angle accessor: from the y-axis (the default reference of an x axis)
            assert!((m.output_angle(q) - want).abs() < 1e-9, "θ = {theta}: output angle {}, closed form {want}", m.output_angle(q));
            // ω′x of the rocker is ψ̇ (the difference quotient is good to ~1e-9)
            let psi_dot = Rssr::ROCKER.body_angular_velocity(v).x;
            assert!((psi_dot - rate).abs() < 1e-7, "θ = {theta}: ψ̇ = {psi_dot}, closed form {rate}");
            checked += 1;
        })
        .unwrap();
    assert!(checked > 60);
}

/// The spatial slider-crank's stroke s = a cos θ + √(L² − (a sin θ − ey)² − ez²), its speed and
/// acceleration (closed-form derivatives by central differences of s(θ(t))).
#[test]
fn spatial_slider_crank_stroke() {
    let m = SpatialSliderCrank::default();
    let (a, len, ey, ez, w) = (m.a, m.len, m.ey, m.ez, m.omega);
    let s = |t: f64| {
        let theta = w * t;
        a * theta.cos() + (len * len - (a * theta.sin() - ey).powi(2) - ez * ez).sqrt()
    };
    assert_eq!(m.ground_guide(), nalgebra::Point3::new(0.0, ey, ez), "a ground point's accessor is its fixed position");
    let solver = KinematicSolver::new(KinematicOptions::default());
    let mut q = m.initial_positions();
    let mut checked = 0;
    solver
        .sweep(&m, &mut SpatialSliderCrank::workspace(), &mut q, times(0.02, 2.0 * PI / w), |t, q, v, vd| {
            checked += 1;
            let d = 1e-4;
            let (speed, accel) = ((s(t + d) - s(t - d)) / (2.0 * d), (s(t + d) - 2.0 * s(t) + s(t - d)) / (d * d));
            // the slider's centre is at x = s; central differences with d = 1e-4 s are good to
            // ~1e-7 (speed) and ~1e-5 (acceleration, with rounding ε s / d² ≈ 1e-8)
            let slider = SpatialSliderCrank::SLIDER;
            let (x, xd, xdd) = (slider.position(q).x, slider.velocity(v).x, slider.acceleration(vd).x);
            assert!((x - s(t)).abs() < 1e-9 && (m.guide_stroke(q) - s(t)).abs() < 1e-9, "t = {t}: x = {x}, closed form {}", s(t));
            assert!((xd - speed).abs() < 1e-6, "t = {t}: ẋ = {xd}, closed form {speed}");
            // the joint coordinates' rates, derived by the macro along q̇ = B(q) v: the stroke's
            // is the slider's speed, the crank angle's the drive's ω (both to the solve's rounding)
            assert!((m.guide_stroke_rate(q, v) - xd).abs() < 1e-9, "t = {t}: ṡ = {}", m.guide_stroke_rate(q, v));
            assert!((m.crankshaft_angle_rate(q, v) - w).abs() < 1e-9, "t = {t}: θ̇ = {}", m.crankshaft_angle_rate(q, v));
            assert!((xdd - accel).abs() < 1e-3 * (1.0 + accel.abs()), "t = {t}: ẍ = {xdd}, closed form {accel}");
            // the crank pin, a named point, stays a from the axis and the rod length from the slider
            let pin = m.crank_pin().position(q);
            assert!(((pin - slider.position(q)).norm() - len).abs() < 1e-9 && (pin.coords.xy().norm() - a).abs() < 1e-9);
        })
        .unwrap();
    assert!(checked > 100);
}

/// What each entry of q and v is (`Mechanism::COORDINATES`, `VELOCITIES`), for a spatial body and
/// for planar ones, and what reads it: the CSV header's units and names, the quantities a plot
/// accepts, and linearization's state names. The descriptors carry the names of
/// `COORDINATE_NAMES` and `VELOCITY_NAMES`, in order.
#[test]
fn descriptors_say_what_each_coordinate_and_velocity_is() {
    use mbd::{CoordinateKind, CsvWriter, Linearizer, VelocityKind};
    use mbd_examples::slider_crank::SliderCrank;
    fn names_agree<M: Mechanism>() {
        assert!(M::COORDINATES.iter().map(|c| c.name).eq(M::COORDINATE_NAMES.iter().copied()), "{}", M::NAME);
        assert!(M::VELOCITIES.iter().map(|v| v.name).eq(M::VELOCITY_NAMES.iter().copied()), "{}", M::NAME);
    }
    names_agree::<Top>();
    names_agree::<SliderCrank>();

    let kinds: Vec<_> = Top::COORDINATES.iter().map(|c| c.kind).collect();
    let quaternion = |part| CoordinateKind::Quaternion { part };
    let expected = [
        CoordinateKind::Length,
        CoordinateKind::Length,
        CoordinateKind::Length,
        quaternion(0),
        quaternion(1),
        quaternion(2),
        quaternion(3),
    ];
    assert_eq!(kinds, expected);
    for (i, v) in Top::VELOCITIES.iter().enumerate() {
        let (kind, displacement) = if i < 3 {
            (VelocityKind::Rate { coordinate: i as u16 }, ["top.x", "top.y", "top.z"][i])
        } else {
            (VelocityKind::Angular { quaternion: 3, axis: (i - 3) as u8 }, ["top.rx", "top.ry", "top.rz"][i - 3])
        };
        assert_eq!((v.kind, v.displacement), (kind, displacement), "{}", v.name);
    }
    for (i, (c, v)) in SliderCrank::COORDINATES.iter().zip(SliderCrank::VELOCITIES).enumerate() {
        let kind = if c.name.ends_with(".phi") { CoordinateKind::Angle } else { CoordinateKind::Length };
        assert_eq!((c.kind, v.kind, v.displacement), (kind, VelocityKind::Rate { coordinate: i as u16 }, c.name));
    }

    let header = |csv: Vec<u8>| String::from_utf8(csv).expect("UTF-8").lines().next().expect("a header").to_string();
    let mut out = Vec::new();
    CsvWriter::states::<Top>(&mut out).finish().expect("written");
    let spatial = header(out);
    for column in ["top.x (m)", "top.e0 (1)", "top.vx (m/s)", "top.wz (rad/s)", "d/dt top.vx (m/s²)", "d/dt top.wz (rad/s²)"] {
        assert!(spatial.split(',').any(|c| c == column), "{column} in {spatial}");
    }
    let mut out = Vec::new();
    CsvWriter::states::<SliderCrank>(&mut out).finish().expect("written");
    let planar = header(out);
    for column in ["crank.phi (rad)", "d/dt crank.phi (rad/s)", "d2/dt2 slider.x (m/s²)"] {
        assert!(planar.split(',').any(|c| c == column), "{column} in {planar}");
    }

    // The plot of a spatial simulation names its quantities as the CSV header does.
    let m = Top { wz: 20.0, ..Default::default() };
    let (q, v) = (m.initial_positions(), m.initial_velocities());
    let mut samples = Vec::new();
    Simulation::new(&m, &mut Rk4::new(Rk4Options::default().with_step(1e-3)))
        .start(0.0, &q, &v)
        .times(&[0.0, 0.01])
        .run(&mut Top::workspace(), |s| samples.push(*s))
        .expect("runs");
    for (x, y) in [("top.e0", "top.wz"), ("top.vx", "d/dt top.wz")] {
        Plot::xy::<Top, _, 7, 6, 3>("spatial", &samples, x, y).unwrap_or_else(|e| panic!("{x}, {y}: {e}"));
    }

    // Linearization names a spatial body's states by the displacements of its chart.
    let lin = Linearizer::default().linearize(&m, &q, &[0.0; 6], 0.0).expect("linearizes");
    let (positions, rates) = lin.state_names.split_at(lin.state_names.len() / 2);
    assert!(positions.iter().all(|n| ["top.x", "top.y", "top.z", "top.rx", "top.ry", "top.rz"].contains(&n.as_str())), "{positions:?}");
    assert!(rates.iter().all(|n| Top::VELOCITY_NAMES.contains(&n.as_str())), "{rates:?}");
    assert_eq!(positions.len(), 3, "{positions:?}");
}

/// Each body's pose, twist J_b x and J_bᵀ of a wrench (`BodyFrames`), read without a place in q:
/// the pose moves with the twist (a central difference along q ⊕ ±h v, as the integrators move
/// q), the acceleration is the twist's rate along the motion, J_bᵀ is the adjoint of J_b (the
/// power of a wrench on the twist is the work of its generalized force on v), the pose places the named points where named access does, and a body
/// past the last has none. Spatial (two bodies, one turned) and planar.
#[test]
fn body_frames_give_pose_twist_and_wrench() {
    use mbd_examples::slider_crank::SliderCrank;
    fn check<M: Kinematics<f64, NQ, NV, NC> + BodyFrames<f64, NQ, NV>, const NQ: usize, const NV: usize, const NC: usize>(
        m: &M,
        q: &[f64; NQ],
        v: &[f64; NV],
    ) {
        let h = 1e-6;
        let (mut plus, mut minus) = (*q, *q);
        m.integrate_positions(&mut plus, v, h);
        m.integrate_positions(&mut minus, v, -h);
        for b in 0..M::BODY_NAMES.len() {
            let name = M::BODY_NAMES[b];
            let (pose, twist) = (m.body_pose(b, q).expect("a body"), m.body_twist(b, q, v).expect("a body"));
            let (p, n) = (m.body_pose(b, &plus).expect("a body"), m.body_pose(b, &minus).expect("a body"));
            // ω̃ = Ȧ Aᵀ, Ȧ by the same central difference.
            let a_dot: [[f64; 3]; 3] =
                core::array::from_fn(|i| core::array::from_fn(|j| (p.rotation[i][j] - n.rotation[i][j]) / (2.0 * h)));
            let w_tilde: [[f64; 3]; 3] =
                core::array::from_fn(|i| core::array::from_fn(|j| (0..3).map(|k| a_dot[i][k] * pose.rotation[j][k]).sum()));
            let omega = [w_tilde[2][1], w_tilde[0][2], w_tilde[1][0]];
            // Tolerance: the central difference's O(h²) truncation and the O(ε/h) rounding of
            // O(1) values, about 1e-10; the rotation's O(h²) renormalization as much.
            for k in 0..3 {
                let dr = (p.position[k] - n.position[k]) / (2.0 * h);
                assert!((dr - twist.velocity[k]).abs() < 1e-8, "{name}: ṙ[{k}] {dr} vs {:?}", twist.velocity);
                assert!((omega[k] - twist.angular_velocity[k]).abs() < 1e-8, "{name}: ω[{k}] {omega:?} vs {:?}", twist.angular_velocity);
            }
            let (force, moment) = ([0.3, -1.2, 0.7], [0.4, 0.25, -0.9]);
            let mut g = [0.0; NV];
            assert!(m.add_body_wrench(b, q, force, moment, &mut g));
            let work: f64 = g.iter().zip(v).map(|(g, v)| g * v).sum();
            let planar = M::VELOCITIES.iter().all(|v| matches!(v.kind, mbd::VelocityKind::Rate { .. }));
            // In the plane a force along z and a moment about x or y do no work.
            let power: f64 = (0..3).map(|k| force[k] * twist.velocity[k] + moment[k] * twist.angular_velocity[k]).sum();
            let power = if planar { power - force[2] * twist.velocity[2] } else { power };
            // Tolerance: rounding of sums of a dozen O(1) products.
            assert!((work - power).abs() < 1e-13, "{name}: Jᵀ is the adjoint of J: {work} vs {power}");
            // The acceleration is the twist's rate along the motion: q ⊕ ±h v with v ± h v̇.
            let vd: [f64; NV] = core::array::from_fn(|i| 0.1 * i as f64 - 0.3);
            let (v_plus, v_minus): ([f64; NV], [f64; NV]) =
                (core::array::from_fn(|i| v[i] + h * vd[i]), core::array::from_fn(|i| v[i] - h * vd[i]));
            let (ahead, behind) = (m.body_twist(b, &plus, &v_plus).expect("a body"), m.body_twist(b, &minus, &v_minus).expect("a body"));
            let acceleration = m.body_acceleration(b, q, v, &vd).expect("a body");
            for k in 0..3 {
                let linear = (ahead.velocity[k] - behind.velocity[k]) / (2.0 * h);
                let angular = (ahead.angular_velocity[k] - behind.angular_velocity[k]) / (2.0 * h);
                // Tolerance: as for the twist above.
                assert!((linear - acceleration.velocity[k]).abs() < 1e-8, "{name}: r̈[{k}] {linear} vs {acceleration:?}");
                assert!((angular - acceleration.angular_velocity[k]).abs() < 1e-8, "{name}: ω̇[{k}] {angular} vs {acceleration:?}");
            }
        }
        let past = M::BODY_NAMES.len();
        assert!(m.body_pose(past, q).is_none() && m.body_twist(past, q, v).is_none());
        assert!(!m.add_body_wrench(past, q, [1.0; 3], [1.0; 3], &mut [0.0; NV]));
    }

    let m = Tumbler::default();
    let mut q = m.initial_positions();
    let turn = [(0.8f64).cos(), 0.6 * (0.8f64).sin(), 0.0, -0.8 * (0.8f64).sin()];
    q[3..7].copy_from_slice(&turn);
    q[7..10].copy_from_slice(&[0.1, -0.2, 0.3]);
    let v = [0.5, -0.3, 0.2, 1.5, -0.7, 2.0, -0.1, 0.4, 0.3, 0.9, 0.2, -1.1];
    check(&m, &q, &v);
    let pose = m.body_pose(0, &q).expect("the block");
    let named = Tumbler::BLOCK.point([0.2, -0.1, 0.3]).position(&q);
    let placed = pose.point([0.2, -0.1, 0.3]);
    // Tolerance: the same products summed in another order.
    assert!((0..3).all(|k| (placed[k] - named[k]).abs() < 1e-15), "{placed:?} vs {named:?}");

    let m = SliderCrank::default();
    let q = m.initial_positions();
    let v: [f64; 9] = core::array::from_fn(|i| 0.3 * i as f64 - 1.0);
    check(&m, &q, &v);
    let pose = m.body_pose(1, &q).expect("the rod");
    // Tolerance: atan2 of the sine and cosine of φ, a few ulps.
    assert!((pose.angle() - SliderCrank::ROD.phi(&q)).abs() < 1e-15);
    assert_eq!([pose.position[0], pose.position[1]], [SliderCrank::ROD.x(&q), SliderCrank::ROD.y(&q)]);
}

/// The reaction of the top's ball joint, from the generated Jacobian and any multipliers: a force
/// of the size of λ, and no moment about the pin.
#[test]
fn ball_joint_reaction_of_the_top_has_no_moment_about_its_pin() {
    let m = Top { theta: 0.9, ..Default::default() };
    let q = m.initial_positions();
    let mut d = [[0.0; 6]; 3];
    m.jacobian(&q, 0.0, &mut d);
    let lambda = [5.0, -3.0, 12.0];
    let reaction = joint_reaction(&m, &q, &d, &lambda, 0).expect("the ball joint");
    assert!(reaction.on_i.is_none(), "ground has no wrench");
    let w = reaction.on_j.expect("on the top");
    assert_eq!((w.body, w.body_index), ("top", 0));
    let pin = m.body_pose(0, &q).expect("the top").to_global([0.0, 0.0, -m.l]);
    // Tolerance: rounding of sums of O(10) products.
    let size = |x: [f64; 3]| x.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!((size(w.force) - size(lambda)).abs() < 1e-13, "{w:?}");
    assert!(size(w.moment_about(pin)) < 1e-13, "{w:?}");
    assert!(size(w.moment) > 0.5, "the pin, 0.1 m off the centre of mass, turns a 14 N force: {w:?}");
}

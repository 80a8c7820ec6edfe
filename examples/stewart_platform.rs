//! A 6-6 Stewart–Gough platform (Stewart 1965; Merlet, *Parallel Robots*, ch. 3–4): a platform
//! carried by six extensible legs, each a real UPS chain — a cylinder on a universal joint at the
//! base, a rod on a spherical joint at the platform, the two joined by a translational joint whose
//! stroke is the actuator. 13 bodies, 78 velocities, 72 joint rows and 6 stroke drivers.
//!
//! The platform (50 kg) is commanded to heave ±50 mm about 0.70 m and roll ±5° about x, both at
//! 0.5 Hz; the strokes are driven by the closed-form inverse kinematics, L_i = |r + R_x(φ) p_i −
//! b_i|, of that pose. Kinematic analysis solves the legs' and the platform's motion from the six
//! strokes (the hard, forward direction), and inverse dynamics the actuator forces — the
//! reactions of the stroke drivers, λ, positive pushing the platform away from the base — with
//! gravity and the inertia of all 13 bodies.
//!
//! Geometry (m): base joints on a circle of radius 0.6 at 10°, 110°, 130°, 230°, 250°, 350°,
//! platform joints on a circle of radius 0.35 at 50°, 70°, 170°, 190°, 290°, 310° (legs cross
//! between neighbouring pairs), rounded to the micrometre; each universal joint's cross is
//! perpendicular to its leg at the design pose. Cylinders 4 kg, rods 2 kg.
//!
//! Checked against what the example computes without mbd:
//! - the platform's pose found from the strokes against the commanded heave and roll, and each
//!   leg's length |P_i − b_i| from that pose against the inverse kinematics;
//! - statics: at every pose of the motion, with the legs' weight and all inertia switched off
//!   (g = 0, the platform's weight and a 20 kg payload off centre applied as forces), each leg is
//!   a two-force member, so the six leg forces f_i along the unit leg vectors ê_i balance the
//!   load: Σ f_i ê_i + F = 0, Σ (P_i − c) × f_i ê_i + M_c = 0, a 6×6 linear system solved here
//!   by Gaussian elimination; its solution against the stroke drivers' reactions.
//!
//! mbd's side is read by name: the platform's pose from the body `platform`, its joints P_i and
//! the payload as its named points, the base joints b_i as the cylinders' universal-joint centres
//! `cylinder_i.u` at the declared design pose, the strokes (printed) as the translational joints'
//! `leg_i_stroke`, the actuator forces as the reactions of the stroke drivers `actuator_i`.
//!
//! Run: `cargo run --release --example stewart_platform`
use mbd::nalgebra::{Point3, UnitQuaternion, Vector3};
use mbd::prelude::*;
use mbd::SpatialPoint;

mechanism! {
    /// 6-6 Stewart–Gough platform: six UPS legs, strokes driven for a heave + roll motion.
    pub StewartPlatform {
        spatial;
        params {
            z0: 0.70, heave: 0.05, roll: 5.0 * PI / 180.0, w: PI, g: 9.81, m_platform: 50.0, m_cylinder: 4.0, m_rod: 2.0,
            w_centre: 0.0, w_payload: 0.0
        }
        gravity [0.0, 0.0, -g];
        body platform { mass: m_platform, inertia: [2.0, 2.0, 3.8], at: [0.0, 0.0, z0] }
        // The platform joints p_i, in the platform frame (its centre of mass is its origin).
        point platform.p1 = [0.224976, 0.268116, 0.0];
        point platform.p2 = [0.119707, 0.328892, 0.0];
        point platform.p3 = [-0.344683, 0.060777, 0.0];
        point platform.p4 = [-0.344683, -0.060777, 0.0];
        point platform.p5 = [0.119707, -0.328892, 0.0];
        point platform.p6 = [0.224976, -0.268116, 0.0];
        // Loads for the static check: a weight at the platform's centre and a payload off centre.
        point platform.payload = [0.15, 0.05, 0.10];
        force weight: platform[0.0, 0.0, 0.0] = [0.0, 0.0, -w_centre];
        force payload: platform.payload = [0.0, 0.0, -w_payload];
        // Each leg i, with ê_i its unit vector from the base joint b_i to the platform joint p_i at
        // the design pose (numbers to the micrometre): a cylinder (centre 0.25 m up the leg) on a
        // universal joint at b_i, the cross's axes ẑ × ê_i on the base and ê_i × (ẑ × ê_i) on the
        // cylinder; a rod (centre 0.2 m below p_i) on a spherical joint at p_i; the translational
        // joint `leg_i` along ê_i between the universal's and the spherical's centres, so its
        // stroke is the leg length |p_i − b_i|, driven by the inverse kinematics of the commanded
        // pose (z = z0 + heave sin wt, roll φ = roll sin wt about x); the inertia tensors of slender
        // tubes along ê_i (products of inertia in body axes).
        // Leg 1: base 0.590885, 0.104189, platform 0.224976, 0.268116.
        body cylinder1 { mass: m_cylinder, inertia: [0.066846, 0.080024, 0.022996, 0.007386, 0.031540, -0.014130], at: [0.477488, 0.154991, 0.216934] }
        body rod1 { mass: m_rod, inertia: [0.021262, 0.025582, 0.006889, 0.002421, 0.010338, -0.004632], at: [0.315694, 0.227475, 0.526453] }
        point cylinder1.u = [0.113397, -0.050802, -0.216934];
        point rod1.s = [-0.090718, 0.040641, 0.173547];
        vector cylinder1.axis = [-0.453589, 0.203207, 0.867735];
        vector rod1.axis = [-0.453589, 0.203207, 0.867735];
        universal ground[0.590885, 0.104189, 0.0] along [-0.408846, -0.912603, 0.000000] ~ cylinder1.u along [0.791898, -0.354770, 0.497027];
        translational leg1: cylinder1.u along cylinder1.axis ~ rod1.s along rod1.axis;
        spherical rod1.s ~ platform.p1;
        drive actuator1: leg1.stroke = sqrt(0.365909^2 + (0.268116 * cos(roll * sin(w * t)) - 0.104189)^2 + (0.268116 * sin(roll * sin(w * t)) + z0 + heave * sin(w * t))^2);
        // Leg 2: base -0.205212, 0.563816, platform 0.119707, 0.328892.
        body cylinder2 { mass: m_cylinder, inertia: [0.070333, 0.076537, 0.022996, 0.009399, -0.028007, 0.020250], at: [-0.104518, 0.491012, 0.216934] }
        body rod2 { mass: m_rod, inertia: [0.022405, 0.024439, 0.006889, 0.003081, -0.009180, 0.006638], at: [0.039152, 0.387135, 0.526453] }
        point cylinder2.u = [-0.100694, 0.072804, -0.216934];
        point rod2.s = [0.080555, -0.058243, 0.173547];
        vector cylinder2.axis = [0.402777, -0.291217, 0.867735];
        vector rod2.axis = [0.402777, -0.291217, 0.867735];
        universal ground[-0.205212, 0.563816, 0.0] along [0.585917, 0.810371, 0.000000] ~ cylinder2.u along [-0.703187, 0.508421, 0.497027];
        translational leg2: cylinder2.u along cylinder2.axis ~ rod2.s along rod2.axis;
        spherical rod2.s ~ platform.p2;
        drive actuator2: leg2.stroke = sqrt(0.324919^2 + (0.328892 * cos(roll * sin(w * t)) - 0.563816)^2 + (0.328892 * sin(roll * sin(w * t)) + z0 + heave * sin(w * t))^2);
        // Leg 3: base -0.385673, 0.459627, platform -0.344683, 0.060777.
        body cylinder3 { mass: m_cylinder, inertia: [0.083126, 0.063744, 0.022996, 0.002013, -0.003533, 0.034379], at: [-0.372970, 0.336021, 0.216934] }
        body rod3 { mass: m_rod, inertia: [0.026599, 0.020246, 0.006889, 0.000660, -0.001158, 0.011269], at: [-0.354845, 0.159662, 0.526453] }
        point cylinder3.u = [-0.012703, 0.123606, -0.216934];
        point rod3.s = [0.010162, -0.098885, 0.173547];
        vector cylinder3.axis = [0.050812, -0.494423, 0.867735];
        vector rod3.axis = [0.050812, -0.494423, 0.867735];
        universal ground[-0.385673, 0.459627, 0.0] along [0.994761, 0.102232, 0.000000] ~ cylinder3.u along [-0.088710, 0.863189, 0.497027];
        translational leg3: cylinder3.u along cylinder3.axis ~ rod3.s along rod3.axis;
        spherical rod3.s ~ platform.p3;
        drive actuator3: leg3.stroke = sqrt(0.040990^2 + (0.060777 * cos(roll * sin(w * t)) - 0.459627)^2 + (0.060777 * sin(roll * sin(w * t)) + z0 + heave * sin(w * t))^2);
        // Leg 4: base -0.385673, -0.459627, platform -0.344683, -0.060777.
        body cylinder4 { mass: m_cylinder, inertia: [0.083126, 0.063744, 0.022996, -0.002013, -0.003533, -0.034379], at: [-0.372970, -0.336021, 0.216934] }
        body rod4 { mass: m_rod, inertia: [0.026599, 0.020246, 0.006889, -0.000660, -0.001158, -0.011269], at: [-0.354845, -0.159662, 0.526453] }
        point cylinder4.u = [-0.012703, -0.123606, -0.216934];
        point rod4.s = [0.010162, 0.098885, 0.173547];
        vector cylinder4.axis = [0.050812, 0.494423, 0.867735];
        vector rod4.axis = [0.050812, 0.494423, 0.867735];
        universal ground[-0.385673, -0.459627, 0.0] along [-0.994761, 0.102232, 0.000000] ~ cylinder4.u along [-0.088710, -0.863189, 0.497027];
        translational leg4: cylinder4.u along cylinder4.axis ~ rod4.s along rod4.axis;
        spherical rod4.s ~ platform.p4;
        drive actuator4: leg4.stroke = sqrt(0.040990^2 + (-0.060777 * cos(roll * sin(w * t)) + 0.459627)^2 + (-0.060777 * sin(roll * sin(w * t)) + z0 + heave * sin(w * t))^2);
        // Leg 5: base -0.205212, -0.563816, platform 0.119707, -0.328892.
        body cylinder5 { mass: m_cylinder, inertia: [0.070333, 0.076537, 0.022996, -0.009399, -0.028007, -0.020250], at: [-0.104518, -0.491012, 0.216934] }
        body rod5 { mass: m_rod, inertia: [0.022405, 0.024439, 0.006889, -0.003081, -0.009180, -0.006638], at: [0.039152, -0.387135, 0.526453] }
        point cylinder5.u = [-0.100694, -0.072804, -0.216934];
        point rod5.s = [0.080555, 0.058243, 0.173547];
        vector cylinder5.axis = [0.402777, 0.291217, 0.867735];
        vector rod5.axis = [0.402777, 0.291217, 0.867735];
        universal ground[-0.205212, -0.563816, 0.0] along [-0.585917, 0.810371, 0.000000] ~ cylinder5.u along [-0.703187, -0.508421, 0.497027];
        translational leg5: cylinder5.u along cylinder5.axis ~ rod5.s along rod5.axis;
        spherical rod5.s ~ platform.p5;
        drive actuator5: leg5.stroke = sqrt(0.324919^2 + (-0.328892 * cos(roll * sin(w * t)) + 0.563816)^2 + (-0.328892 * sin(roll * sin(w * t)) + z0 + heave * sin(w * t))^2);
        // Leg 6: base 0.590885, -0.104189, platform 0.224976, -0.268116.
        body cylinder6 { mass: m_cylinder, inertia: [0.066846, 0.080024, 0.022996, -0.007386, 0.031540, 0.014130], at: [0.477488, -0.154991, 0.216934] }
        body rod6 { mass: m_rod, inertia: [0.021262, 0.025582, 0.006889, -0.002421, 0.010338, 0.004632], at: [0.315694, -0.227475, 0.526453] }
        point cylinder6.u = [0.113397, 0.050802, -0.216934];
        point rod6.s = [-0.090718, -0.040641, 0.173547];
        vector cylinder6.axis = [-0.453589, -0.203207, 0.867735];
        vector rod6.axis = [-0.453589, -0.203207, 0.867735];
        universal ground[0.590885, -0.104189, 0.0] along [0.408846, -0.912603, 0.000000] ~ cylinder6.u along [0.791898, 0.354770, 0.497027];
        translational leg6: cylinder6.u along cylinder6.axis ~ rod6.s along rod6.axis;
        spherical rod6.s ~ platform.p6;
        drive actuator6: leg6.stroke = sqrt(0.365909^2 + (-0.268116 * cos(roll * sin(w * t)) + 0.104189)^2 + (-0.268116 * sin(roll * sin(w * t)) + z0 + heave * sin(w * t))^2);
    }
}

/// The payload's mass (kg) for the static check; it sits at the named point `platform.payload`.
const PAYLOAD_MASS: f64 = 20.0;
/// Samples over the period of the motion.
const SAMPLES: usize = 48;

/// What the run found.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// Poses analysed over one period.
    pub samples: usize,
    /// Largest distance (m) and rotation angle (rad) between the platform's pose solved from the
    /// strokes and the commanded pose.
    pub position_error: f64,
    pub rotation_error: f64,
    /// Largest | |P_i − b_i| − L_i | over legs and poses (m), and the range of the leg lengths.
    pub length_error: f64,
    pub length_min: f64,
    pub length_max: f64,
    /// Range of the actuator forces during the motion (N, positive pushing).
    pub force_min: f64,
    pub force_max: f64,
    /// Statics: largest |f_i (stroke driver) − f_i (6×6 solve)| over legs and poses (N), and the
    /// largest |f_i| (N).
    pub static_error: f64,
    pub static_peak: f64,
    /// Statics at the first pose: Σ vertical components of the leg forces (N) and the total load.
    pub static_vertical: f64,
    pub static_load: f64,
}

/// The stroke drivers, leg by leg: their indices into `JOINTS`.
const ACTUATORS: [usize; 6] = [
    StewartPlatform::ACTUATOR1,
    StewartPlatform::ACTUATOR2,
    StewartPlatform::ACTUATOR3,
    StewartPlatform::ACTUATOR4,
    StewartPlatform::ACTUATOR5,
    StewartPlatform::ACTUATOR6,
];

/// The legs' joints, read off the mechanism by name: the base joints b_i (global; the cylinders'
/// universal-joint centres `cylinder_i.u` at the declared design pose, where they sit on the base
/// hardpoints) and the platform joints `platform.p_i`.
struct Legs {
    base: [Point3<f64>; 6],
    platform: [SpatialPoint<f64, { StewartPlatform::NQ }, { StewartPlatform::NV }>; 6],
}

impl Legs {
    fn of(m: &StewartPlatform) -> Self {
        let design = m.initial_positions();
        let universal = [m.cylinder1_u(), m.cylinder2_u(), m.cylinder3_u(), m.cylinder4_u(), m.cylinder5_u(), m.cylinder6_u()];
        Legs {
            base: universal.map(|u| u.position(&design)),
            platform: [m.platform_p1(), m.platform_p2(), m.platform_p3(), m.platform_p4(), m.platform_p5(), m.platform_p6()],
        }
    }

    /// The strokes of the translational joints `leg_i` at q (m).
    fn strokes(m: &StewartPlatform, q: &[f64; StewartPlatform::NQ]) -> [f64; 6] {
        [m.leg1_stroke(q), m.leg2_stroke(q), m.leg3_stroke(q), m.leg4_stroke(q), m.leg5_stroke(q), m.leg6_stroke(q)]
    }

    /// Platform joint i of the commanded pose (height z, roll φ about x), global (m).
    fn commanded(&self, i: usize, z: f64, phi: f64) -> Point3<f64> {
        let (s, c) = phi.sin_cos();
        let [x, y, _] = self.platform[i].local;
        Point3::new(x, y * c, y * s + z)
    }
}

/// The commanded pose at t: the platform centre's height (m) and roll about x (rad).
pub fn command(m: &StewartPlatform, t: f64) -> (f64, f64) {
    let s = (m.w * t).sin();
    (m.z0 + m.heave * s, m.roll * s)
}

/// Solves a x = b by Gaussian elimination with partial pivoting (a nonsingular).
fn solve6(mut a: [[f64; 6]; 6], mut b: [f64; 6]) -> [f64; 6] {
    for k in 0..6 {
        let pivot = (k..6).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs())).unwrap_or(k);
        a.swap(k, pivot);
        b.swap(k, pivot);
        let (row, rhs) = (a[k], b[k]);
        for i in k + 1..6 {
            let f = a[i][k] / row[k];
            for (x, p) in a[i][k..].iter_mut().zip(&row[k..]) {
                *x -= f * p;
            }
            b[i] -= f * rhs;
        }
    }
    let mut x = [0.0; 6];
    for k in (0..6).rev() {
        x[k] = (b[k] - (k + 1..6).map(|j| a[k][j] * x[j]).sum::<f64>()) / a[k][k];
    }
    x
}

/// The six leg forces (N, positive pushing the platform away from the base) that hold the
/// platform, its centre at `centre`, against forces `load` at the points `at` (global), the
/// legs being two-force members along ê_i = (P_i − b_i)/|P_i − b_i|: Σ f_i ê_i + F = 0,
/// Σ (P_i − c) × f_i ê_i + (at − c) × F = 0.
fn static_forces(
    joints: &[Point3<f64>; 6],
    base: &[Point3<f64>; 6],
    centre: Point3<f64>,
    loads: &[(Point3<f64>, Vector3<f64>)],
) -> [f64; 6] {
    let mut a = [[0.0; 6]; 6];
    for (i, (p, b)) in joints.iter().zip(base).enumerate() {
        let leg = p - b;
        let e = leg / leg.norm();
        let moment = (p - centre).cross(&e);
        for k in 0..3 {
            a[k][i] = e[k];
            a[3 + k][i] = moment[k];
        }
    }
    let mut b = [0.0; 6];
    for (at, force) in loads {
        let moment = (at - centre).cross(force);
        for k in 0..3 {
            b[k] -= force[k];
            b[3 + k] -= moment[k];
        }
    }
    solve6(a, b)
}

/// Runs the analysis over one period of the motion; prints tables when `print` is set.
pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let m = StewartPlatform::default();
    // The statics: no gravity on any body, the platform's weight and the payload as forces.
    let loaded = StewartPlatform { g: 0.0, w_centre: m.m_platform * m.g, w_payload: PAYLOAD_MASS * m.g, ..m };
    let legs = Legs::of(&m);
    let (platform, payload) = (StewartPlatform::PLATFORM, m.platform_payload());
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = StewartPlatform::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let period = 2.0 * PI / m.w;
    let mut r = Report {
        samples: 0,
        position_error: 0.0,
        rotation_error: 0.0,
        length_error: 0.0,
        length_min: f64::INFINITY,
        length_max: 0.0,
        force_min: f64::INFINITY,
        force_max: f64::NEG_INFINITY,
        static_error: 0.0,
        static_peak: 0.0,
        static_vertical: f64::NAN,
        static_load: loaded.w_centre + loaded.w_payload,
    };
    let mut failure = None;
    let mut static_table = Vec::new();
    if print {
        println!(
            "Stewart–Gough platform: heave ±{} mm about {} m and roll ±{:.1}° at {} Hz; strokes (mm) and actuator forces (N)",
            m.heave * 1e3,
            m.z0,
            m.roll.to_degrees(),
            m.w / (2.0 * PI)
        );
        println!("{:>6} {:>9} {:>8} | {:>48} | {:>54}", "t (s)", "heave(mm)", "roll(°)", "L1 … L6 (mm)", "F1 … F6 (N)");
    }
    let times = (0..=SAMPLES).map(|k| period * k as f64 / SAMPLES as f64);
    let mut inverse_ws = StewartPlatform::workspace(); // the sweep holds `ws`
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, vd| {
        let (z, phi) = command(&m, t);
        // The pose solved from the strokes against the command.
        let commanded = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), phi);
        r.rotation_error = r.rotation_error.max(commanded.angle_to(&platform.orientation(q)));
        r.position_error = r.position_error.max((platform.position(q) - Point3::new(0.0, 0.0, z)).norm());
        let mut lengths = [0.0; 6];
        let mut joints = [Point3::origin(); 6];
        for i in 0..6 {
            lengths[i] = (legs.commanded(i, z, phi) - legs.base[i]).norm();
            joints[i] = legs.platform[i].position(q);
            let solved = (joints[i] - legs.base[i]).norm();
            r.length_error = r.length_error.max((solved - lengths[i]).abs());
            r.length_min = r.length_min.min(lengths[i]);
            r.length_max = r.length_max.max(lengths[i]);
        }

        // Actuator forces: the stroke drivers' reactions on the rods along the leg (the driver
        // row z_iᵀd − f(t) pushes rod i along the cylinder's axis z_i).
        let mut d = [[0.0; StewartPlatform::NV]; StewartPlatform::NC];
        m.jacobian(q, t, &mut d);
        let mut leg_forces = |mech: &StewartPlatform, v: &[f64; StewartPlatform::NV], vd: &[f64; StewartPlatform::NV]| {
            let mut lambda = [0.0; StewartPlatform::NC];
            InverseDynamics::default().solve(mech, &mut inverse_ws, q, v, vd, t, &mut lambda).map(|()| {
                core::array::from_fn::<f64, 6, _>(|i| {
                    let e = (joints[i] - legs.base[i]) / lengths[i];
                    joint_reaction(mech, q, &d, &lambda, ACTUATORS[i])
                        .and_then(|j| j.on_j)
                        .map_or(f64::NAN, |w| Vector3::from(w.force).dot(&e))
                })
            })
        };
        let (forces, statics) = match (leg_forces(&m, v, vd), leg_forces(&loaded, &[0.0; StewartPlatform::NV], &[0.0; StewartPlatform::NV]))
        {
            (Ok(f), Ok(s)) => (f, s),
            (Err(e), _) | (_, Err(e)) => {
                failure.get_or_insert(e);
                return;
            }
        };
        for f in forces {
            r.force_min = r.force_min.min(f);
            r.force_max = r.force_max.max(f);
        }
        // The independent statics of the solved pose.
        let centre = platform.position(q);
        let load_points =
            [(centre, Vector3::new(0.0, 0.0, -loaded.w_centre)), (payload.position(q), Vector3::new(0.0, 0.0, -loaded.w_payload))];
        let expected = static_forces(&joints, &legs.base, centre, &load_points);
        for i in 0..6 {
            r.static_error = r.static_error.max((statics[i] - expected[i]).abs());
            r.static_peak = r.static_peak.max(statics[i].abs());
        }
        if r.samples == 0 {
            r.static_vertical = (0..6).map(|i| statics[i] * (joints[i].z - legs.base[i].z) / lengths[i]).sum();
        }
        if r.samples == SAMPLES / 4 {
            static_table = (0..6).map(|i| (statics[i], expected[i])).collect();
        }
        if print && r.samples.is_multiple_of(6) {
            let list = |x: [f64; 6], scale: f64| x.iter().map(|v| format!("{:>8.1}", v * scale)).collect::<Vec<_>>().join("");
            let strokes = Legs::strokes(&m, q);
            println!("{t:>6.3} {:>9.2} {:>8.3} | {} | {}", (z - m.z0) * 1e3, phi.to_degrees(), list(strokes, 1e3), list(forces, 1.0));
        }
        r.samples += 1;
    })?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    if print {
        println!(
            "pose solved from the strokes vs commanded: position {:.1e} m, rotation {:.1e} rad; leg lengths vs inverse kinematics {:.1e} m",
            r.position_error, r.rotation_error, r.length_error
        );
        println!("actuator forces during the motion {:.1} … {:.1} N", r.force_min, r.force_max);
        println!(
            "statics (g = 0; platform weight {:.1} N at the centre, payload {:.1} N at {:?} m), at the pose of t = {:.2} s:",
            loaded.w_centre,
            loaded.w_payload,
            payload.local,
            period / 4.0
        );
        println!("{:>5} {:>16} {:>16} {:>10}", "leg", "driver λ (N)", "6×6 solve (N)", "difference");
        for (i, (a, b)) in static_table.iter().enumerate() {
            println!("{:>5} {a:>16.6} {b:>16.6} {:>10.1e}", i + 1, a - b);
        }
        println!(
            "over all {} poses: max |λ − 6×6| {:.1e} N (forces up to {:.1} N); at t = 0 Σ vertical components {:.6} N vs load {:.6} N",
            r.samples, r.static_error, r.static_peak, r.static_vertical, r.static_load
        );
    }
    Ok(r)
}

/// One period of the heave and roll, for the showcase's pictures: the kinematic sweep of `run`,
/// 48 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = StewartPlatform::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = StewartPlatform::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<StewartPlatform>(&m.params())
        .title("Stewart platform, one period of heave and roll")
        .trace("platform.payload");
    let period = 2.0 * PI / m.w;
    let times = (0..=SAMPLES).map(|k| period * k as f64 / SAMPLES as f64);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("stewart_platform: {e}");
        std::process::exit(1);
    }
}

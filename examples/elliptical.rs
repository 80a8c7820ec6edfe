//! Nikravesh's project 15.7, the elliptical exercise machine, posed as its designer asks it:
//! what path does the foot follow (stride, lift, the pedal's tilt), how well does the linkage
//! pass the user's effort on (transmission angle), and what torque, power and foot force must the
//! user give over a stride against the flywheel's brake?
//!
//! The model (planar, in the machine's side view; SI units; every number's source in `SOURCES`):
//! a rear-drive elliptical. The flywheel's crank carries two pins 180° apart; on each, a pedal
//! link whose front end hangs from a swing arm pivoted on the front upright — two crank-rocker
//! four-bars sharing the crank, the left and the right foot. The pedal (the foot's point) lies
//! on the link near its front end. The user keeps a steady cadence (`drive cadence`) against an
//! eddy-current brake on the flywheel, −c ω; inverse dynamics gives the crank torque the user's
//! feet must supply, and virtual power the force along the pedal's path that supplies it.
//!
//! **The checks** (each independent of the simulation's equations):
//!
//! - the left pedal's position at every sample against the four-bar's closed form (the
//!   intersection of the coupler's circle about the crank pin and the arm's about its pivot),
//!   and the stride and lift against the closed form's extent on a fine grid;
//! - the transmission angle against its closed form μ = acos((b² + c² − s²)/(2 b c)), s the
//!   distance from the crank pin to the arm's pivot;
//! - the crank torque against virtual power: τ ω = the brake's power plus the rate of the kinetic
//!   energy, written by hand from the bodies' velocities and accelerations; its mean against the
//!   brake's c ω², by hand.
//!
//! Run: `cargo run --release --example elliptical`
use mbd::prelude::*;

mechanism! {
    /// A rear-drive elliptical trainer (Nikravesh's project 15.7): flywheel and crank, two pedal
    /// links hanging from two swing arms, an eddy-current brake on the flywheel.
    pub Elliptical {
        // omega: the cadence, 60 strides a minute (rad/s of the crank); c_brake: the brake's
        // constant (N·m·s), 150 W at that cadence.
        params { omega: 2.0 * PI, c_brake: 150.0 / (4.0 * PI * PI) }
        gravity [0.0, -9.81];
        // The flywheel with its crank, balanced on its axle; each pedal link a 1.1 m tube with
        // its pedal; each swing arm with its handlebar, its centre of mass at its pivot.
        body flywheel    { mass: 9.0, inertia: 0.12, at: [0.0, 0.0, 0.0] }
        body link_left   { mass: 4.0, inertia: 0.4033, at: [0.7469, 0.1576, 0.2906] }
        body link_right  { mass: 4.0, inertia: 0.4033, at: [0.3034, 0.1690, 0.3124] }
        body arm_left    { mass: 3.0, inertia: 0.45, at: [1.1, 1.3, 0.1748] }
        body arm_right   { mass: 3.0, inertia: 0.45, at: [1.1, 1.3, -0.2767] }
        // Crank 0.22 m, pins 180° apart; links 1.1 m; arms 1.0 m from the pivot to the link,
        // pivoted at (1.1, 1.3) m from the flywheel's axle.
        revolute axle: ground[0.0, 0.0] ~ flywheel[0.0, 0.0];
        revolute crank_left: flywheel[0.22, 0.0] ~ link_left[-0.55, 0.0];
        revolute crank_right: flywheel[-0.22, 0.0] ~ link_right[-0.55, 0.0];
        revolute hanger_left: link_left[0.55, 0.0] ~ arm_left[0.0, -1.0];
        revolute hanger_right: link_right[0.55, 0.0] ~ arm_right[0.0, -1.0];
        revolute pivot_left: ground[1.1, 1.3] ~ arm_left[0.0, 0.0];
        revolute pivot_right: ground[1.1, 1.3] ~ arm_right[0.0, 0.0];
        // The pedals: 0.8 m along the link from the crank pin, 0.08 m above it.
        point link_left.pedal = [0.25, 0.08];
        point link_right.pedal = [0.25, 0.08];
        drive cadence: flywheel.phi = omega * t;
        torque brake: flywheel = -c_brake * flywheel.omega;
    }
}

/// Where the numbers come from (assumptions are marked so).
pub const SOURCES: [(&str, &str); 5] = [
    ("cadence 60 strides a minute (120 steps)", "assumption: a moderate pace"),
    ("brake taking 150 W at that cadence", "assumption: a moderate workload for an adult"),
    (
        "crank 0.22 m, links 1.1 m, arms 1.0 m, arm pivot 1.1 m ahead of and 1.3 m above the flywheel's axle, pedal 0.8 m along the link and 0.08 m above it",
        "assumption: chosen for a stride of 18–20 in (0.46–0.51 m) with a transmission angle of at least 45°",
    ),
    ("flywheel 9 kg, J = 0.12 kg·m²; links 4 kg (thin tubes); arms with handlebars 3 kg, J = 0.45 kg·m² about the pivot", "assumption"),
    ("the arms' centres of mass at their pivots (handlebar above, lower arm below)", "assumption"),
];

/// The linkage's geometry (m), as in the mechanism: for the closed forms.
const CRANK: f64 = 0.22;
const LINK: f64 = 1.1;
const ARM: f64 = 1.0;
const PIVOT: [f64; 2] = [1.1, 1.3];
const PEDAL: [f64; 2] = [0.8, 0.08];

/// What the run measured. Lengths in m, angles in rad, torques in N·m, power in W, forces in N.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// The left pedal's path: its horizontal extent (the stride) and vertical extent (the
    /// lift), from the samples and by the closed form on a 0.01° grid, and the range of the
    /// pedal's tilt (the link's angle) over the samples.
    pub stride: f64,
    pub lift: f64,
    pub stride_closed_form: f64,
    pub lift_closed_form: f64,
    pub tilt: f64,
    /// Largest |pedal − closed form| over the samples (m).
    pub path_error: f64,
    /// The least transmission angle (acute, between link and arm) over the samples, by the
    /// closed form at the extremes of the pin's distance from the arm's pivot, and the
    /// largest |from the positions − closed form at their s| (rad).
    pub transmission: f64,
    pub transmission_closed_form: f64,
    pub transmission_error: f64,
    /// The crank torque the user supplies: largest and smallest (N·m).
    pub torque_max: f64,
    pub torque_min: f64,
    /// Mean power over the stride (W), and the brake's c ω² by hand.
    pub mean_power: f64,
    pub brake_power: f64,
    /// Largest instantaneous power (W), and the largest |τ ω − (brake power + dT/dt)| (W).
    pub peak_power: f64,
    pub power_error: f64,
    /// The force along the left pedal's path that supplies all the power while that pedal
    /// moves rearward (the left foot's push), largest over that half (N); and the pedal's
    /// slowest speed there (m/s).
    pub push_force: f64,
    pub push_speed_min: f64,
}

/// The intersection of the circle about `centre` of radius `radius` with the circle about
/// `other` of radius `reach` on the side `side` (±1) of the line from `centre` to `other`.
fn meet(centre: [f64; 2], radius: f64, other: [f64; 2], reach: f64, side: f64) -> [f64; 2] {
    let (dx, dy) = (other[0] - centre[0], other[1] - centre[1]);
    let d = dx.hypot(dy);
    let along = (radius * radius - reach * reach + d * d) / (2.0 * d);
    let across = side * (radius * radius - along * along).sqrt();
    [centre[0] + (along * dx - across * dy) / d, centre[1] + (along * dy + across * dx) / d]
}

/// The left pedal's position at crank angle θ, by the closed form: the link's front end where
/// its circle about the crank pin meets the arm's about the pivot, and the pedal on the link.
fn closed_form(theta: f64) -> [f64; 2] {
    let pin = [CRANK * theta.cos(), CRANK * theta.sin()];
    let end = meet(PIVOT, ARM, pin, LINK, 1.0);
    let u = [(end[0] - pin[0]) / LINK, (end[1] - pin[1]) / LINK];
    [pin[0] + PEDAL[0] * u[0] - PEDAL[1] * u[1], pin[1] + PEDAL[0] * u[1] + PEDAL[1] * u[0]]
}

/// The acute transmission angle between a coupler b and a rocker c whose far ends are s apart.
fn transmission(b: f64, c: f64, s: f64) -> f64 {
    ((b * b + c * c - s * s) / (2.0 * b * c)).abs().acos()
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let m = Elliptical::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Elliptical::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let period = 2.0 * PI / m.omega;
    let n = 360;
    // The closed form's extent on a 0.01° grid.
    let grid: Vec<[f64; 2]> = (0..36000).map(|k| closed_form((k as f64 * 0.01).to_radians())).collect();
    let extent = |axis: usize| grid.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p[axis]), hi.max(p[axis])));
    let (x_range, y_range) = (extent(0), extent(1));
    // The least transmission angle: at an extreme of s, the pin's distance from the pivot,
    // d ± a (crank and ground line collinear).
    let d = PIVOT[0].hypot(PIVOT[1]);
    let mut r = Report {
        samples: 0,
        stride: 0.0,
        lift: 0.0,
        stride_closed_form: x_range.1 - x_range.0,
        lift_closed_form: y_range.1 - y_range.0,
        tilt: 0.0,
        path_error: 0.0,
        transmission: PI,
        transmission_closed_form: transmission(LINK, ARM, d + CRANK).min(transmission(LINK, ARM, d - CRANK)),
        transmission_error: 0.0,
        torque_max: f64::NEG_INFINITY,
        torque_min: f64::INFINITY,
        mean_power: 0.0,
        brake_power: m.c_brake * m.omega * m.omega,
        peak_power: 0.0,
        power_error: 0.0,
        push_force: 0.0,
        push_speed_min: f64::INFINITY,
    };
    let (mut xs, mut ys, mut tilts) =
        ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
    let widen = |range: &mut (f64, f64), x: f64| *range = (range.0.min(x), range.1.max(x));
    let inverse = InverseDynamics::default();
    let mut inverse_ws = Elliptical::workspace();
    let mut mass = [[0.0; Elliptical::NV]; Elliptical::NV];
    m.add_mass_matrix(&q, 1.0, &mut mass);
    let mut failure = None;
    // Each sample's angle, pedals and torque, for the plots.
    let mut trace: Vec<Trace> = Vec::with_capacity(n);
    // Samples at the midpoints of n equal intervals: the mean over them is the stride's.
    let times = (0..n).map(|k| period * (k as f64 + 0.5) / n as f64);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, vd| {
        let mut lambda = [0.0; Elliptical::NC];
        if let Err(e) = inverse.solve(&m, &mut inverse_ws, q, v, vd, t, &mut lambda) {
            failure.get_or_insert(e);
            return;
        }
        let mut jac = [[0.0; Elliptical::NV]; Elliptical::NC];
        m.jacobian(q, t, &mut jac);
        let Some(drive) = joint_reaction(&m, q, &jac, &lambda, Elliptical::CADENCE).and_then(|j| j.on("flywheel")) else { return };
        let theta = Elliptical::FLYWHEEL.phi(q);
        let pedal = m.link_left_pedal();
        let (at, at_v) = (pedal.position(q), pedal.velocity(q, v));
        let closed = closed_form(theta);
        r.path_error = r.path_error.max((at.x - closed[0]).hypot(at.y - closed[1]));
        widen(&mut xs, at.x);
        widen(&mut ys, at.y);
        widen(&mut tilts, Elliptical::LINK_LEFT.phi(q));
        let right = m.link_right_pedal().position(q);
        trace.push((theta.to_degrees(), [at.x, at.y], [right.x, right.y], 0.0));
        // The transmission angle from the positions, and by the closed form from s.
        let pin = Elliptical::FLYWHEEL.point([CRANK, 0.0]).position(q);
        let end = Elliptical::ARM_LEFT.point([0.0, -ARM]).position(q);
        let (u, w) = ([end.x - pin.x, end.y - pin.y], [end.x - PIVOT[0], end.y - PIVOT[1]]);
        let mu = ((u[0] * w[0] + u[1] * w[1]).abs() / (LINK * ARM)).min(1.0).acos();
        let s = (pin.x - PIVOT[0]).hypot(pin.y - PIVOT[1]);
        r.transmission_error = r.transmission_error.max((mu - transmission(LINK, ARM, s)).abs());
        r.transmission = r.transmission.min(mu);
        // The user's torque on the crank, and virtual power by hand: the brake's power and the
        // rate of the kinetic energy (the mass matrix is diagonal: m, m, J for each body), with
        // gravity's power (the links rise and fall).
        let torque = drive.moment[2];
        let omega = Elliptical::FLYWHEEL.omega(v);
        let power = torque * omega;
        let brake = -m.c_brake * omega * omega;
        let kinetic_rate: f64 = (0..Elliptical::NV).map(|i| mass[i][i] * vd[i] * v[i]).sum();
        let gravity: f64 = [Elliptical::LINK_LEFT, Elliptical::LINK_RIGHT, Elliptical::ARM_LEFT, Elliptical::ARM_RIGHT]
            .iter()
            .zip([4.0, 4.0, 3.0, 3.0])
            .map(|(body, mass)| -mass * 9.81 * body.velocity(v).y)
            .sum::<f64>();
        r.power_error = r.power_error.max((power + brake + gravity - kinetic_rate).abs());
        r.peak_power = r.peak_power.max(power.abs());
        r.torque_max = r.torque_max.max(torque);
        r.torque_min = r.torque_min.min(torque);
        r.mean_power += power / n as f64;
        if let Some(last) = trace.last_mut() {
            last.3 = torque;
        }
        // The left foot's push: its pedal moving rearward; the force along its path that
        // delivers the power, P / |v|.
        if at_v.x < 0.0 {
            let speed = at_v.norm();
            r.push_speed_min = r.push_speed_min.min(speed);
            r.push_force = r.push_force.max(power / speed);
        }
        r.samples += 1;
    })?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    (r.stride, r.lift, r.tilt) = (xs.1 - xs.0, ys.1 - ys.0, tilts.1 - tilts.0);
    if print {
        print_report(&m, &r, &trace)?;
    }
    Ok(r)
}

/// (crank angle in degrees, left pedal, right pedal, crank torque) at one sample.
type Trace = (f64, [f64; 2], [f64; 2], f64);

/// The answers, the checks and the sources, and the designer's plots in target/showcase: the
/// pedals' paths and the crank torque over the stride.
fn print_report(m: &Elliptical, r: &Report, trace: &[Trace]) -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "Elliptical trainer (Nikravesh's project 15.7): {:.0} strides a minute against a {:.0} W brake, {} samples of a stride",
        m.omega / (2.0 * PI) * 60.0,
        r.brake_power,
        r.samples
    );
    println!(
        "pedal path: stride {:.4} m (closed form {:.4} m), lift {:.4} m (closed form {:.4} m), the pedal tilting through {:.1}°; within {:.1e} m of the closed form",
        r.stride, r.stride_closed_form, r.lift, r.lift_closed_form, r.tilt.to_degrees(), r.path_error
    );
    println!(
        "transmission angle at least {:.1}° (closed form {:.2}°), within {:.1e} rad of the closed form at every sample",
        r.transmission.to_degrees(),
        r.transmission_closed_form.to_degrees(),
        r.transmission_error
    );
    println!(
        "crank torque {:.2} … {:.2} N·m; mean power {:.3} W (the brake's c ω² = {:.3} W), up to {:.1} W; virtual power within {:.1e} W",
        r.torque_min, r.torque_max, r.mean_power, r.brake_power, r.peak_power, r.power_error
    );
    println!(
        "the left foot pushing alone, along its pedal's path: up to {:.0} N (the pedal at least {:.2} m/s then)",
        r.push_force, r.push_speed_min
    );
    for (what, source) in SOURCES {
        println!("  {what}: {source}");
    }
    let dir = std::path::Path::new("target/showcase");
    std::fs::create_dir_all(dir)?;
    mbd::Plot::new("Elliptical trainer: the pedals' paths over a stride")
        .labels("x (m), forward from the flywheel's axle", "y (m)")
        .series("left pedal", trace.iter().map(|p| (p.1[0], p.1[1])))
        .series("right pedal", trace.iter().map(|p| (p.2[0], p.2[1])))
        .write_svg(dir.join("elliptical_path.svg"))?;
    mbd::Plot::new("Elliptical trainer at 60 strides a minute: the crank torque the user supplies against a 150 W brake")
        .labels("crank angle (deg)", "torque (N·m)")
        .series("crank torque", trace.iter().map(|p| (p.0, p.3)))
        .write_svg(dir.join("elliptical_torque.svg"))?;
    println!("plots → target/showcase/elliptical_path.svg, elliptical_torque.svg");
    Ok(())
}

/// One stride, for the showcase's animation: 72 frames.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = Elliptical::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Elliptical::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let period = 2.0 * PI / m.omega;
    let mut animation = mbd::Animation::new::<Elliptical>(&m.params()).title("Elliptical trainer: one stride");
    solver.sweep(&m, &mut ws, &mut q, (0..=72).map(|k| period * k as f64 / 72.0), |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("elliptical: {e}");
        std::process::exit(1);
    }
}

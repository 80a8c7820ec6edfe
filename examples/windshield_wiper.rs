//! Nikravesh's project 15.1, the windshield wiper, posed as its designer asks it: over one turn
//! of the motor, how far does each blade sweep, how well does the linkage transmit the motor's
//! torque (transmission angles), how far apart are the two blades, and what torque must the
//! motor give against the blades' friction on wet glass?
//!
//! The model (planar, in the plane of the linkage under the cowl; SI units; every number's
//! source in `SOURCES`): a tandem system of two four-bars in series. The motor's crank drives
//! the driver's-side pivot (`rocker1`) through `link1`; a second lever on that pivot drives the
//! passenger's-side pivot (`rocker2`) through `link2`. Each pivot carries its wiper arm and
//! blade; their friction on the glass is a torque resisting the pivot's rotation, regularized
//! near zero speed. The motor turns at a constant 45 cycles a minute (`drive motor`); inverse
//! dynamics gives its torque.
//!
//! **The checks** (each independent of the simulation's equations):
//!
//! - each blade's angle at every sample against the four-bar's closed form (the intersection of
//!   the coupler's and the rocker's circles), and the sweep against the limit positions, where
//!   crank and coupler are collinear (the law of cosines);
//! - the transmission angles against their closed form μ = acos((b² + r² − s²)/(2 b r)), s the
//!   distance from the crank pin (or driving lever's end) to the rocker's pivot;
//! - the motor torque against virtual power: τ ω = the blades' friction power plus the rate of
//!   the kinetic energy, written by hand from the bodies' velocities and accelerations.
//!
//! Run: `cargo run --release --example windshield_wiper`
use mbd::prelude::*;

mechanism! {
    /// A tandem windshield-wiper linkage (Nikravesh's project 15.1): motor crank, two
    /// four-bars in series, friction of the blades on wet glass at the two pivots.
    pub Wiper {
        // omega: the motor, 45 cycles a minute; tf1, tf2: the blades' friction torques at the
        // pivots (N·m); w_s: the regularization's speed (rad/s).
        params { omega: 1.5 * PI, tf1: 0.84, tf2: 0.72, w_s: 0.01 }
        // Links as thin rods of their length; the crank balanced on its shaft; each rocker the
        // pivot shaft with its levers, wiper arm and blade, taken about the pivot.
        body crank   { mass: 0.2, inertia: 2.0e-4, at: [0.0, 0.0, 0.0] }
        body link1   { mass: 0.12, inertia: 9.67e-4, at: [0.2003, 0.0081, 0.0524] }
        body rocker1 { mass: 0.35, inertia: 0.030, at: [0.30, 0.05, -0.5451] }
        body link2   { mass: 0.20, inertia: 7.04e-3, at: [0.5789, 0.1025, 0.0204] }
        body rocker2 { mass: 0.35, inertia: 0.025, at: [0.95, 0.05, 2.2333] }
        // Crank 45 mm; link1 0.31101 m; levers 65 mm (the second at 166.37° from the first)
        // and 75 mm; link2 0.65008 m; pivots at (0.30, 0.05) and (0.95, 0.05) m from the motor.
        revolute motor_shaft: ground[0.0, 0.0] ~ crank[0.0, 0.0];
        revolute crank_pin: crank[0.045, 0.0] ~ link1[-0.3110064308016797 / 2.0, 0.0];
        revolute lever1_pin: link1[0.3110064308016797 / 2.0, 0.0] ~ rocker1[0.065, 0.0];
        revolute driver_pivot: ground[0.30, 0.05] ~ rocker1[0.0, 0.0];
        revolute lever2_pin: rocker1[0.065 * cos(2.903681409520222), 0.065 * sin(2.903681409520222)] ~ link2[-0.6500769185258002 / 2.0, 0.0];
        revolute lever3_pin: link2[0.6500769185258002 / 2.0, 0.0] ~ rocker2[0.075, 0.0];
        revolute passenger_pivot: ground[0.95, 0.05] ~ rocker2[0.0, 0.0];
        drive motor: crank.phi = omega * t;
        torque driver_blade: rocker1 = -tf1 * rocker1.omega / sqrt(rocker1.omega^2 + w_s^2);
        torque passenger_blade: rocker2 = -tf2 * rocker2.omega / sqrt(rocker2.omega^2 + w_s^2);
    }
}

/// Where the numbers come from (assumptions are marked so).
pub const SOURCES: [(&str, &str); 6] = [
    ("45 wiping cycles a minute", "FMVSS No. 104 (49 CFR 571.104), S4.1.1.2: one frequency of at least 45 cycles a minute"),
    ("pivots 0.65 m apart, the driver's 0.30 m across and 0.05 m up from the motor", "assumption: a compact car's cowl"),
    ("crank 45 mm, levers 65 and 75 mm", "assumption: chosen for a driver's-side sweep of about 90°"),
    (
        "blade load 12 N on the glass, at 0.35 m (driver) and 0.30 m (passenger) from the pivot",
        "assumption: an arm spring's load on a 0.6 m blade",
    ),
    ("friction coefficient 0.2, rubber on wet glass", "assumption: wet rubber on glass, between a lubricated and a dry contact"),
    ("arm and blade 0.35 kg, J = 0.030 and 0.025 kg·m² about the pivots", "assumption"),
];

/// The linkage's geometry (m, rad), as in the mechanism: for the closed forms.
const CRANK: f64 = 0.045;
const LINK1: f64 = 0.3110064308016797;
const LEVER1: f64 = 0.065;
const LEVER2: f64 = 0.065;
const LEVER2_AT: f64 = 2.903681409520222;
const LINK2: f64 = 0.6500769185258002;
const LEVER3: f64 = 0.075;
const PIVOT1: [f64; 2] = [0.30, 0.05];
const PIVOT2: [f64; 2] = [0.95, 0.05];

/// What the run measured. Angles in rad, torques in N·m, power in W.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// Each blade's sweep over the turn (rad), and by the closed form at the limit positions.
    pub sweep1: f64,
    pub sweep2: f64,
    pub sweep1_closed_form: f64,
    pub sweep2_closed_form: f64,
    /// Largest |angle − closed form| of either blade over the turn (rad).
    pub angle_error: f64,
    /// The smallest transmission angle of each four-bar over the samples (rad, acute); the
    /// first's by the closed form, where the crank points at the driver's pivot (s = d − a); and
    /// the largest |from the positions − closed form at their s| of either (rad), which tests
    /// the couplers' lengths.
    pub transmission1: f64,
    pub transmission2: f64,
    pub transmission1_closed_form: f64,
    pub transmission_error: f64,
    /// The two blades' relative angle ψ₁ − ψ₂: its range over the turn (rad).
    pub relative_min: f64,
    pub relative_max: f64,
    /// The crank angles (rad, in [0, 2π)) at which each blade reverses, at its largest and its
    /// smallest angle, from the samples (1° apart); and the limit positions by the closed form
    /// (crank and coupler collinear, stretched and folded).
    pub reversals1: [f64; 2],
    pub reversals2: [f64; 2],
    pub limit_positions: [f64; 2],
    /// The motor's torque: largest and smallest over the turn (N·m) and its mean power (W); the
    /// mean power by hand: over a turn the kinetic energy returns, so the motor gives what the
    /// blades' friction takes, 2 (T_f1 Δψ₁ + T_f2 Δψ₂) per turn (each blade sweeps there and
    /// back), with the closed-form sweeps.
    pub torque_max: f64,
    pub torque_min: f64,
    pub mean_power: f64,
    pub mean_power_closed_form: f64,
    /// Largest |τ ω − (friction power + dT/dt)| over the turn (W), and the largest |τ ω| (W).
    pub power_error: f64,
    pub peak_power: f64,
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

/// The two blades' angles ψ₁, ψ₂ (the rockers' φ) at crank angle θ, by the closed form: the
/// lever's end where the coupler's circle about the crank pin meets the lever's about its pivot.
fn closed_form(theta: f64) -> (f64, f64) {
    let pin = [CRANK * theta.cos(), CRANK * theta.sin()];
    let end1 = meet(PIVOT1, LEVER1, pin, LINK1, 1.0);
    let psi1 = (end1[1] - PIVOT1[1]).atan2(end1[0] - PIVOT1[0]);
    let end2 = [PIVOT1[0] + LEVER2 * (psi1 + LEVER2_AT).cos(), PIVOT1[1] + LEVER2 * (psi1 + LEVER2_AT).sin()];
    let end3 = meet(PIVOT2, LEVER3, end2, LINK2, -1.0);
    (psi1, (end3[1] - PIVOT2[1]).atan2(end3[0] - PIVOT2[0]))
}

/// The acute transmission angle of a four-bar whose coupler b meets the rocker's lever r at
/// its end, s from the rocker's pivot to the coupler's driven end: acos |(b² + r² − s²)/(2 b r)|.
fn transmission(b: f64, r: f64, s: f64) -> f64 {
    ((b * b + r * r - s * s) / (2.0 * b * r)).abs().acos()
}

/// The sweep of a rocker of lever r, coupler b, crank a and pivots d apart, by the law of
/// cosines at its two limit positions (crank and coupler collinear: s = b ± a).
fn sweep(a: f64, b: f64, r: f64, d: f64) -> f64 {
    let at = |s: f64| ((d * d + r * r - s * s) / (2.0 * d * r)).acos();
    (at(b + a) - at(b - a)).abs()
}

/// The crank angles (rad, in [0, 2π)) of a crank-rocker's limit positions, stretched (crank
/// pin at a from the crank's pivot, on the line to the lever's end, b + a from it) and folded
/// (b − a): the triangle of the crank's pivot, the rocker's pivot (d away, at `towards`) and the
/// lever's end (r from it), on the branch `side` (±1) of the assembly.
fn limit_positions(a: f64, b: f64, r: f64, towards: [f64; 2], side: f64) -> [f64; 2] {
    let d = towards[0].hypot(towards[1]);
    let base = towards[1].atan2(towards[0]);
    // The lever's end at s from the crank's pivot, at α from the line to the rocker's pivot;
    // folded, the pin lies beyond the crank's pivot, opposite the lever's end.
    let at = |s: f64, turn: f64| {
        let alpha = ((d * d + s * s - r * r) / (2.0 * d * s)).acos();
        (base - side * alpha + turn).rem_euclid(2.0 * PI)
    };
    [at(b + a, 0.0), at(b - a, PI)]
}

/// The acute angle between two vectors (rad).
fn angle_between(u: [f64; 2], w: [f64; 2]) -> f64 {
    ((u[0] * w[0] + u[1] * w[1]).abs() / (u[0].hypot(u[1]) * w[0].hypot(w[1]))).min(1.0).acos()
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let m = Wiper::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Wiper::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let period = 2.0 * PI / m.omega;
    let n = 360;
    let mut r = Report {
        samples: 0,
        sweep1: 0.0,
        sweep2: 0.0,
        sweep1_closed_form: sweep(CRANK, LINK1, LEVER1, PIVOT1[0].hypot(PIVOT1[1])),
        sweep2_closed_form: 0.0,
        angle_error: 0.0,
        transmission1: PI,
        transmission2: PI,
        transmission1_closed_form: transmission(LINK1, LEVER1, PIVOT1[0].hypot(PIVOT1[1]) - CRANK),
        transmission_error: 0.0,
        relative_min: f64::INFINITY,
        relative_max: f64::NEG_INFINITY,
        reversals1: [0.0; 2],
        reversals2: [0.0; 2],
        limit_positions: limit_positions(CRANK, LINK1, LEVER1, PIVOT1, 1.0),
        torque_max: f64::NEG_INFINITY,
        torque_min: f64::INFINITY,
        mean_power: 0.0,
        mean_power_closed_form: 0.0,
        power_error: 0.0,
        peak_power: 0.0,
    };
    // The passenger's blade reverses where the driver's does (its four-bar has no limit position
    // of its own within the driver's sweep): its sweep is the closed form's between them.
    let [stretched, folded] = r.limit_positions;
    r.sweep2_closed_form = (closed_form(stretched).1 - closed_form(folded).1).abs();
    r.mean_power_closed_form = 2.0 * (m.tf1 * r.sweep1_closed_form + m.tf2 * r.sweep2_closed_form) / period;
    // Each blade's range seen, and the crank angles of its largest and smallest angle.
    let (mut psi1_seen, mut psi2_seen) = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
    let (mut extreme1, mut extreme2) = ([(f64::NEG_INFINITY, 0.0), (f64::INFINITY, 0.0)], [(f64::NEG_INFINITY, 0.0), (f64::INFINITY, 0.0)]);
    let inverse = InverseDynamics::default();
    let mut inverse_ws = Wiper::workspace();
    let mut mass = [[0.0; Wiper::NV]; Wiper::NV];
    m.add_mass_matrix(&q, 1.0, &mut mass);
    let mut failure = None;
    // Samples at the midpoints of n equal intervals: the mean over them is the cycle average.
    let times = (0..n).map(|k| period * (k as f64 + 0.5) / n as f64);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, vd| {
        let mut lambda = [0.0; Wiper::NC];
        if let Err(e) = inverse.solve(&m, &mut inverse_ws, q, v, vd, t, &mut lambda) {
            failure.get_or_insert(e);
            return;
        }
        let mut d = [[0.0; Wiper::NV]; Wiper::NC];
        m.jacobian(q, t, &mut d);
        let Some(motor) = joint_reaction(&m, q, &d, &lambda, Wiper::MOTOR).and_then(|j| j.on("crank")) else { return };
        let theta = Wiper::CRANK.phi(q);
        let (psi1, psi2) = (Wiper::ROCKER1.phi(q), Wiper::ROCKER2.phi(q));
        let (c1, c2) = closed_form(theta);
        r.angle_error = r.angle_error.max((psi1 - c1).abs()).max((psi2 - c2).abs());
        psi1_seen = (psi1_seen.0.min(psi1), psi1_seen.1.max(psi1));
        psi2_seen = (psi2_seen.0.min(psi2), psi2_seen.1.max(psi2));
        let crank = theta.rem_euclid(2.0 * PI);
        for (extreme, psi) in [(&mut extreme1, psi1), (&mut extreme2, psi2)] {
            if psi > extreme[0].0 {
                extreme[0] = (psi, crank);
            }
            if psi < extreme[1].0 {
                extreme[1] = (psi, crank);
            }
        }
        r.relative_min = r.relative_min.min(psi1 - psi2);
        r.relative_max = r.relative_max.max(psi1 - psi2);
        // Transmission angles from the positions, and by the closed form from the distance s.
        let point = |p: mbd::nalgebra::Point2<f64>| [p.x, p.y];
        let pin = point(Wiper::CRANK.point([CRANK, 0.0]).position(q));
        let end1 = point(Wiper::ROCKER1.point([LEVER1, 0.0]).position(q));
        let end2 = point(Wiper::ROCKER1.point([LEVER2 * LEVER2_AT.cos(), LEVER2 * LEVER2_AT.sin()]).position(q));
        let end3 = point(Wiper::ROCKER2.point([LEVER3, 0.0]).position(q));
        let minus = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
        let mu1 = angle_between(minus(end1, pin), minus(end1, PIVOT1));
        let mu2 = angle_between(minus(end3, end2), minus(end3, PIVOT2));
        let s1 = (pin[0] - PIVOT1[0]).hypot(pin[1] - PIVOT1[1]);
        let s2 = (end2[0] - PIVOT2[0]).hypot(end2[1] - PIVOT2[1]);
        r.transmission_error =
            r.transmission_error.max((mu1 - transmission(LINK1, LEVER1, s1)).abs()).max((mu2 - transmission(LINK2, LEVER3, s2)).abs());
        r.transmission1 = r.transmission1.min(mu1);
        r.transmission2 = r.transmission2.min(mu2);
        // The motor's torque on the crank, and virtual power by hand.
        let torque = motor.moment[2];
        let power = torque * Wiper::CRANK.omega(v);
        let friction = |tf: f64, w: f64| -tf * w / (w * w + m.w_s * m.w_s).sqrt() * w;
        let friction_power = friction(m.tf1, Wiper::ROCKER1.omega(v)) + friction(m.tf2, Wiper::ROCKER2.omega(v));
        // dT/dt = Σ m a·v + J α ω over the bodies, their masses and inertias the model's (its
        // mass matrix is diagonal: m, m, J for each body).
        let kinetic_rate: f64 = (0..Wiper::NV).map(|i| mass[i][i] * vd[i] * v[i]).sum();
        r.power_error = r.power_error.max((power + friction_power - kinetic_rate).abs());
        r.peak_power = r.peak_power.max(power.abs());
        r.torque_max = r.torque_max.max(torque);
        r.torque_min = r.torque_min.min(torque);
        r.mean_power += power / n as f64;
        r.samples += 1;
    })?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    r.reversals1 = [extreme1[0].1, extreme1[1].1];
    r.reversals2 = [extreme2[0].1, extreme2[1].1];
    r.sweep1 = psi1_seen.1 - psi1_seen.0;
    r.sweep2 = psi2_seen.1 - psi2_seen.0;
    if print {
        println!(
            "Windshield wiper (Nikravesh's project 15.1): motor at {:.0} cycles a minute, {} samples of a turn",
            m.omega / (2.0 * PI) * 60.0,
            r.samples
        );
        println!(
            "sweep: driver's blade {:.2}° (closed form {:.2}°), passenger's {:.2}° (closed form {:.2}°); angles within {:.1e} rad of the closed form",
            r.sweep1.to_degrees(),
            r.sweep1_closed_form.to_degrees(),
            r.sweep2.to_degrees(),
            r.sweep2_closed_form.to_degrees(),
            r.angle_error
        );
        println!(
            "transmission angle at least {:.1}° (motor to driver's pivot; closed form {:.2}° with the crank pointing at the pivot) and {:.1}° (driver's to passenger's pivot), within {:.1e} rad of the closed form at every sample",
            r.transmission1.to_degrees(),
            r.transmission1_closed_form.to_degrees(),
            r.transmission2.to_degrees(),
            r.transmission_error
        );
        let deg = |x: [f64; 2]| [x[0].to_degrees(), x[1].to_degrees()];
        println!(
            "phase: the blades reverse together, the driver's at crank angles {:.0?}°, the passenger's at {:.0?}° (limit positions by the closed form {:.1?}°); their angle apart changes by {:.1}° over a stroke",
            deg(r.reversals1),
            deg(r.reversals2),
            deg(r.limit_positions),
            (r.relative_max - r.relative_min).to_degrees()
        );
        println!(
            "motor torque {:.3} … {:.3} N·m; mean power {:.5} W, by hand 2 (T_f1 Δψ₁ + T_f2 Δψ₂)/T = {:.5} W; virtual power within {:.1e} W of {:.2} W",
            r.torque_min, r.torque_max, r.mean_power, r.mean_power_closed_form, r.power_error, r.peak_power
        );
        for (what, source) in SOURCES {
            println!("  {what}: {source}");
        }
    }
    Ok(r)
}

/// One turn of the motor, for the showcase's animation: 72 frames.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = Wiper::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Wiper::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let period = 2.0 * PI / m.omega;
    let mut animation = mbd::Animation::new::<Wiper>(&m.params()).title("Windshield wiper: a tandem linkage, one turn of the motor");
    solver.sweep(&m, &mut ws, &mut q, (0..=72).map(|k| period * k as f64 / 72.0), |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("windshield_wiper: {e}");
        std::process::exit(1);
    }
}

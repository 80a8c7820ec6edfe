//! RSSR spatial four-bar (Nikravesh, *Computer-Aided Analysis of Mechanical Systems*, ch. 11):
//! a crank on a horizontal shaft drives, through a spherical–spherical coupler, a rocker hinged
//! on an axis skew to the shaft. The crank turns at a constant 120 rpm; kinematic analysis over
//! one turn, then inverse dynamics with the links' inertia and gravity.
//!
//! Geometry (m): the crank (a = 0.05) turns about −y through the origin, its pin at
//! P(θ) = a (cos θ, 0, sin θ); the rocker (b = 0.10) turns about u = (2, 1, 2)/3 through
//! O = (0.10, 0.10, −0.10), its pin at Q(ψ) = O + b (cos ψ x̂ + sin ψ ŷ) with x̂ = (2, −2, −1)/3,
//! ŷ = u × x̂ = (1, 2, −2)/3; the coupler (L = 0.15) is massless, a `distance` joint. The rocker
//! is a slender bar (its inertia tensor has products in body axes); gravity is −z.
//!
//! Checked against what the example computes without mbd:
//! - the output angle: |P − Q| = L reads K1 cos ψ + K2 sin ψ = K3 with K1 = (P − O)·x̂,
//!   K2 = (P − O)·ŷ, K3 = (|P − O|² + b² − L²)/(2b), solved in closed form; its rate and
//!   acceleration by differentiating that equation in θ (ψ′ = −F_θ/F_ψ, and ψ″ likewise);
//! - the transmission index |ê·t̂| (ê the coupler's direction, t̂ the direction the rocker pin
//!   moves: 1 ideal, 0 at a dead point), from the closed-form geometry;
//! - the drive torque by virtual power: τ ω = d(T + V)/dt, with T = ½ J_O ψ̇² of the rocker
//!   about its hinge (J_O = m b²/3 + j0 of the declared bar; the crank's T is constant at
//!   constant ω) and V the links' weight, all from the closed-form ψ, ψ̇, ψ̈; over a revolution
//!   its mean, the mean drive power, is zero.
//!
//! mbd's side is read by name: ψ as the hinge `output`'s angle, ψ̇ and ψ̈ from the rocker's
//! angular velocity and acceleration, the pins as the named points `crank.pin` and `rocker.pin`,
//! the drive torque and the coupler force as the reactions of `motor` and `coupler`.
//!
//! Run: `cargo run --release --example rssr`
use mbd::nalgebra::{Point3, Vector3};
use mbd::prelude::*;

mechanism! {
    /// RSSR four-bar: crank about −y at the origin, rocker about (2, 1, 2)/3 through (ox, oy, oz),
    /// a massless spherical–spherical coupler of length `len`, the crank driven at ω.
    pub Rssr {
        spatial;
        params {
            a: 0.05, b: 0.10, len: 0.15, ox: 0.10, oy: 0.10, oz: -0.10, omega: 4.0 * PI,
            m_crank: 0.3, m_rocker: 0.5, j0: 1.0e-6, psi0: -0.34
        }
        gravity [0.0, 0.0, -9.81];
        // The crank's centre of mass halfway along its arm (body x at θ = 0).
        body crank { mass: m_crank, inertia: [1.0e-5, 8.0e-5, 8.0e-5], at: [a / 2.0, 0.0, 0.0] }
        // A slender bar along x̂ = (2, −2, −1)/3 at ψ = 0: J = (m b²/12)(I − x̂x̂ᵀ) + j0 I (j0 keeps
        // the mass matrix positive definite about the bar's own axis).
        body rocker {
            mass: m_rocker,
            inertia: [
                m_rocker * b^2 / 12.0 * 5.0 / 9.0 + j0, m_rocker * b^2 / 12.0 * 5.0 / 9.0 + j0,
                m_rocker * b^2 / 12.0 * 8.0 / 9.0 + j0,
                m_rocker * b^2 / 12.0 * 4.0 / 9.0, m_rocker * b^2 / 12.0 * 2.0 / 9.0, -m_rocker * b^2 / 12.0 * 2.0 / 9.0
            ],
            // The assembly guess: the rocker turned by psi0 from x̂.
            at: [
                ox + b / 2.0 * (2.0 * cos(psi0) + sin(psi0)) / 3.0,
                oy + b / 2.0 * (-2.0 * cos(psi0) + 2.0 * sin(psi0)) / 3.0,
                oz + b / 2.0 * (-cos(psi0) - 2.0 * sin(psi0)) / 3.0
            ],
            axis_angle: [2.0, 1.0, 2.0, psi0]
        }
        point crank.pin = [a / 2.0, 0.0, 0.0];
        point rocker.pivot = [-b / 3.0, b / 3.0, b / 6.0];
        point rocker.pin = [b / 3.0, -b / 3.0, -b / 6.0];
        revolute input: ground[0.0, 0.0, 0.0] along [0.0, -1.0, 0.0] ~ crank[-a / 2.0, 0.0, 0.0] along [0.0, -1.0, 0.0];
        revolute output: ground[ox, oy, oz] along [2.0, 1.0, 2.0] reference [2.0, -2.0, -1.0]
            ~ rocker.pivot along [2.0, 1.0, 2.0] reference [2.0, -2.0, -1.0];
        distance coupler: crank.pin ~ rocker.pin { length: len };
        drive motor: input.angle = omega * t;
    }
}

/// The rocker's hinge axis u, and x̂, ŷ spanning the plane its pin moves in.
pub const U: Vector3<f64> = Vector3::new(2.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0);
pub const X_HAT: Vector3<f64> = Vector3::new(2.0 / 3.0, -2.0 / 3.0, -1.0 / 3.0);
pub const Y_HAT: Vector3<f64> = Vector3::new(1.0 / 3.0, 2.0 / 3.0, -2.0 / 3.0);
/// Gravity (m/s²), as declared.
const G: f64 = 9.81;

/// What the run found: the largest deviations from the closed forms over one crank turn.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// Crank positions analysed.
    pub samples: usize,
    /// max |ψ − ψ_exact| (rad), |ψ̇ − ψ̇_exact| (rad/s), |ψ̈ − ψ̈_exact| (rad/s²).
    pub angle_error: f64,
    pub rate_error: f64,
    pub acceleration_error: f64,
    /// The rocker's swing (rad) and its largest angular acceleration (rad/s²).
    pub swing: f64,
    pub peak_acceleration: f64,
    /// Smallest transmission index |ê·t̂| over the turn, from mbd's positions and in closed form.
    pub min_transmission: f64,
    pub min_transmission_exact: f64,
    /// Largest |drive torque| from the inverse dynamics (N·m) and its largest deviation from
    /// the virtual-power closed form (N·m).
    pub peak_torque: f64,
    pub torque_error: f64,
    /// Mean drive power over the turn (W): zero for a conservative mechanism at constant speed.
    pub mean_drive_power: f64,
    /// Largest coupler force (N, tension positive).
    pub peak_coupler_force: f64,
}

/// The closed form at crank angle θ: ψ on the branch nearest `near`, ψ′ = dψ/dθ, ψ″ = d²ψ/dθ².
pub fn closed_form(m: &Rssr, theta: f64, near: f64) -> (f64, f64, f64) {
    let o = Point3::new(m.ox, m.oy, m.oz);
    let (s, c) = theta.sin_cos();
    let p = Point3::new(m.a * c, 0.0, m.a * s);
    let (p1, p2) = (Vector3::new(-m.a * s, 0.0, m.a * c), Vector3::new(-m.a * c, 0.0, -m.a * s));
    let d = p - o;
    let (k1, k2, k3) = (d.dot(&X_HAT), d.dot(&Y_HAT), (d.dot(&d) + m.b * m.b - m.len * m.len) / (2.0 * m.b));
    let (k1d, k2d, k3d) = (p1.dot(&X_HAT), p1.dot(&Y_HAT), d.dot(&p1) / m.b);
    let (k1dd, k2dd, k3dd) = (p2.dot(&X_HAT), p2.dot(&Y_HAT), (p1.dot(&p1) + d.dot(&p2)) / m.b);
    let (phase, spread) = (k2.atan2(k1), (k3 / k1.hypot(k2)).acos());
    let nearest = |x: f64| x - ((x - near) / (2.0 * PI)).round() * 2.0 * PI;
    let (x, y) = (nearest(phase + spread), nearest(phase - spread));
    let psi = if (x - near).abs() < (y - near).abs() { x } else { y };
    // F(θ, ψ) = K1 cos ψ + K2 sin ψ − K3 = 0: F_θ + F_ψ ψ′ = 0 and, once more in θ,
    // F_θθ + 2 F_θψ ψ′ + F_ψψ ψ′² + F_ψ ψ″ = 0.
    let (sp, cp) = psi.sin_cos();
    let f_psi = -k1 * sp + k2 * cp;
    let f_psipsi = -k1 * cp - k2 * sp;
    let f_theta = k1d * cp + k2d * sp - k3d;
    let f_thetapsi = -k1d * sp + k2d * cp;
    let f_thetatheta = k1dd * cp + k2dd * sp - k3dd;
    let d1 = -f_theta / f_psi;
    let d2 = -(f_thetatheta + 2.0 * f_thetapsi * d1 + f_psipsi * d1 * d1) / f_psi;
    (psi, d1, d2)
}

/// Runs the analyses over one crank turn; prints a table when `print` is set.
pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let m = Rssr::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Rssr::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    // Inertia of the rocker about its hinge: the declared slender bar's uᵀJ′u = m b²/12 + j0
    // (u ⟂ x̂) plus m (b/2)².
    let j_rocker = m.m_rocker * m.b * m.b / 12.0 + m.j0 + m.m_rocker * m.b * m.b / 4.0;
    // ψ is the hinge `output`'s angle: the rocker's reference x̂ turned about u from the ground's.
    let mut near = m.output_angle(&q);
    let n = 360;
    let period = 2.0 * PI / m.omega;
    let mut r = Report {
        samples: 0,
        angle_error: 0.0,
        rate_error: 0.0,
        acceleration_error: 0.0,
        swing: 0.0,
        peak_acceleration: 0.0,
        min_transmission: f64::INFINITY,
        min_transmission_exact: f64::INFINITY,
        peak_torque: 0.0,
        torque_error: 0.0,
        mean_drive_power: 0.0,
        peak_coupler_force: 0.0,
    };
    let (mut psi_min, mut psi_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut failure = None;
    if print {
        println!(
            "RSSR four-bar: crank a = {} m at {:.0} rpm, rocker b = {} m on a skew hinge, coupler L = {} m",
            m.a,
            m.omega * 30.0 / PI,
            m.b,
            m.len
        );
        println!(
            "{:>7} {:>9} {:>10} {:>11} {:>8} {:>11} {:>11} {:>11} {:>9}",
            "θ (deg)", "ψ (deg)", "ψ̇ (rad/s)", "ψ̈ (rad/s²)", "index", "τ (N·m)", "τ_vw (N·m)", "coupler (N)", "|ψ−exact|"
        );
    }
    // Equally spaced over the period: the mean of the samples is the cycle average.
    let times = (0..n).map(|k| period * k as f64 / n as f64);
    let o = Point3::new(m.ox, m.oy, m.oz);
    let mut inverse_ws = Rssr::workspace(); // the sweep holds `ws`
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, vd| {
        let theta = m.omega * t;
        let (psi_exact, d1, d2) = closed_form(&m, theta, near);
        near = psi_exact;
        let psi = m.output_angle(q);
        let psi = psi - ((psi - psi_exact) / (2.0 * PI)).round() * 2.0 * PI;
        // The rocker turns about u, global and body frame alike: ψ̇ = u·ω′.
        let (rate, accel) = (Rssr::ROCKER.body_angular_velocity(v).dot(&U), Rssr::ROCKER.body_angular_acceleration(vd).dot(&U));
        let (rate_exact, accel_exact) = (d1 * m.omega, d2 * m.omega * m.omega);
        r.angle_error = r.angle_error.max((psi - psi_exact).abs());
        r.rate_error = r.rate_error.max((rate - rate_exact).abs());
        r.acceleration_error = r.acceleration_error.max((accel - accel_exact).abs());
        r.peak_acceleration = r.peak_acceleration.max(accel_exact.abs());
        psi_min = psi_min.min(psi);
        psi_max = psi_max.max(psi);

        // Transmission index from mbd's pins, and from the closed form.
        let index = |p: Point3<f64>, pin: Point3<f64>| {
            let e = pin - p;
            e.dot(&U.cross(&(pin - o))).abs() / (e.norm() * m.b)
        };
        let (p_mbd, q_mbd) = (m.crank_pin().position(q), m.rocker_pin().position(q));
        let (s, c) = theta.sin_cos();
        let p_exact = Point3::new(m.a * c, 0.0, m.a * s);
        let q_exact = o + m.b * (psi_exact.cos() * X_HAT + psi_exact.sin() * Y_HAT);
        let ti = index(p_mbd, q_mbd);
        r.min_transmission = r.min_transmission.min(ti);
        r.min_transmission_exact = r.min_transmission_exact.min(index(p_exact, q_exact));

        // Drive torque: inverse dynamics, against virtual power.
        let mut lambda = [0.0; Rssr::NC];
        if let Err(e) = InverseDynamics::default().solve(&m, &mut inverse_ws, q, v, vd, t, &mut lambda) {
            failure.get_or_insert(e);
            return;
        }
        let mut d = [[0.0; Rssr::NV]; Rssr::NC];
        m.jacobian(q, t, &mut d);
        let reaction = |joint: usize| joint_reaction(&m, q, &d, &lambda, joint).and_then(|j| j.on_j);
        // The motor's moment on the crank about the shaft axis −y.
        let torque = reaction(Rssr::MOTOR).map_or(f64::NAN, |w| -w.moment[1]);
        // The coupler pulls the rocker pin toward the crank pin when in tension.
        let pull = reaction(Rssr::COUPLER).map_or(f64::NAN, |w| Vector3::from(w.force).dot(&(p_mbd - q_mbd)) / m.len);
        // d(T + V)/dt: the rocker's J_O ψ̇ ψ̈, the weights' m g ż (z of each centre of mass).
        let crank_zdot = m.a / 2.0 * c * m.omega;
        let rocker_zdot = m.b / 2.0 * (-psi_exact.sin() * X_HAT.z + psi_exact.cos() * Y_HAT.z) * rate_exact;
        let power = j_rocker * rate_exact * accel_exact + G * (m.m_crank * crank_zdot + m.m_rocker * rocker_zdot);
        let torque_exact = power / m.omega;
        r.peak_torque = r.peak_torque.max(torque.abs());
        r.torque_error = r.torque_error.max((torque - torque_exact).abs());
        r.mean_drive_power += torque * m.omega / n as f64;
        r.peak_coupler_force = r.peak_coupler_force.max(pull.abs());
        r.samples += 1;
        if print && r.samples % 20 == 1 {
            println!(
                "{:>7.1} {:>9.4} {:>10.5} {:>11.4} {:>8.4} {:>11.6} {:>11.6} {:>11.3} {:>9.1e}",
                theta.to_degrees(),
                psi.to_degrees(),
                rate,
                accel,
                ti,
                torque,
                torque_exact,
                pull,
                (psi - psi_exact).abs()
            );
        }
    })?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    r.swing = psi_max - psi_min;
    if print {
        println!(
            "rocker swing {:.3}°; max error vs closed form: ψ {:.1e} rad, ψ̇ {:.1e} rad/s, ψ̈ {:.1e} rad/s² (peak {:.2})",
            r.swing.to_degrees(),
            r.angle_error,
            r.rate_error,
            r.acceleration_error,
            r.peak_acceleration
        );
        println!(
            "transmission index ≥ {:.6} (closed form {:.6}); peak coupler force {:.2} N",
            r.min_transmission, r.min_transmission_exact, r.peak_coupler_force
        );
        println!(
            "drive torque peak {:.5} N·m, max |τ − τ_virtual power| {:.1e} N·m; mean drive power {:.1e} W",
            r.peak_torque, r.torque_error, r.mean_drive_power
        );
    }
    Ok(r)
}

/// One crank turn at 120 rpm, for the showcase's pictures: a kinematic sweep of 72 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = Rssr::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Rssr::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<Rssr>(&m.params()).title("RSSR spatial four-bar, one crank turn").trace("rocker.pin");
    let period = 2.0 * PI / m.omega;
    let times = (0..=72).map(|k| period * k as f64 / 72.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("rssr: {e}");
        std::process::exit(1);
    }
}

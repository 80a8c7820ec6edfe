//! Offset spatial slider-crank (Nikravesh, *Computer-Aided Analysis of Mechanical Systems*,
//! ch. 11): a crank turning about z drives a slider along a guide parallel to x that is offset
//! both within the crank's plane (ey) and out of it (ez), through a massless spherical–spherical
//! connecting rod (a `distance` joint). The crank turns at 600 rpm against a load on the slider;
//! kinematic analysis and inverse dynamics over one turn.
//!
//! Geometry (m): crank a = 0.05 (pin P = a (cos θ, sin θ, 0)), rod L = 0.20, guide through
//! (·, 0.02, 0.03). Slider 0.8 kg; the crank is balanced (its centre of mass on the shaft);
//! gravity −z, which the guide carries. Load on the slider F(θ) = −F0 (1 − cos θ)/2 along x,
//! F0 = 800 N.
//!
//! Checked against what the example computes without mbd:
//! - the stroke s(θ) = a cos θ + √(L² − (a sin θ − ey)² − ez²) and its exact derivatives,
//!   ẋ = s′ω, ẍ = s″ω²;
//! - the dead centres: with L′ = √(L² − ez²) the slider's extremes are √((L′ ± a)² − ey²),
//!   reached at θ = atan2(ey, s_max) and atan2(−ey, −s_min) (crank and rod in line in the
//!   projection along z), where ẋ = 0; the quick-return ratio of the two strokes' crank angles;
//! - the drive torque by virtual work: τ ω + F ẋ = d(½ m ẋ²)/dt, so τ = (m s″ω² − F) s′
//!   (the crank's kinetic energy is constant at constant ω, the rod is massless and gravity
//!   does no work on a slider moving along x);
//! - the rod force from the slider's equation along x: m ẍ = F + T ê_x, ê the unit vector from
//!   the slider to the crank pin, so T = (m ẍ − F)/ê_x (tension positive).
//!
//! mbd's side is read by name: x as the stroke of the translational joint `guide`, ẋ and ẍ as the
//! slider's, the drive torque and the rod force as the reactions of `motor` and `rod`.
//!
//! Run: `cargo run --release --example spatial_slider_crank`
use mbd::prelude::*;

mechanism! {
    /// Offset spatial slider-crank: crank about z, slider along x on the line (·, ey, ez), a
    /// massless rod of length `len`, the crank driven at ω against a load on the slider.
    pub SpatialSliderCrank {
        spatial;
        params { a: 0.05, len: 0.20, ey: 0.02, ez: 0.03, omega: 20.0 * PI, m_slider: 0.8, f0: 800.0 }
        gravity [0.0, 0.0, -9.81];
        body crank { mass: 2.0, inertia: [2.0e-3, 2.0e-3, 3.0e-3] }
        body slider { mass: m_slider, inertia: [1.0e-4, 2.0e-4, 2.0e-4], at: [0.25, ey, ez] }
        revolute crankshaft: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ crank[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
        translational guide: ground[0.0, ey, ez] along [1.0, 0.0, 0.0] ~ slider[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0];
        distance rod: crank[a, 0.0, 0.0] ~ slider[0.0, 0.0, 0.0] { length: len };
        drive motor: crankshaft.angle = omega * t;
        force load: slider[0.0, 0.0, 0.0] = [-f0 * (1.0 - cos(omega * t)) / 2.0, 0.0, 0.0];
    }
}

/// What the run found, next to the closed forms.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// Crank positions analysed over the turn (the two dead centres apart).
    pub samples: usize,
    /// max |x − s|, |ẋ − s′ω|, |ẍ − s″ω²| of the slider (m, m/s, m/s²) and the largest |ẍ|.
    pub position_error: f64,
    pub velocity_error: f64,
    pub acceleration_error: f64,
    pub peak_acceleration: f64,
    /// Stroke from mbd's positions at the closed-form dead centres, and √((L′+a)² − ey²) −
    /// √((L′−a)² − ey²) (m).
    pub stroke: f64,
    pub stroke_exact: f64,
    /// Largest |ẋ| at the two dead centres (m/s): zero.
    pub dead_centre_speed: f64,
    /// Quick-return ratio: crank angle of the slower stroke over that of the faster one.
    pub time_ratio: f64,
    /// Largest |drive torque| (N·m) and its largest deviation from the virtual-work closed form.
    pub peak_torque: f64,
    pub torque_error: f64,
    /// Largest |rod force| (N) and its largest deviation from the closed form (N).
    pub peak_rod_force: f64,
    pub rod_force_error: f64,
    /// Mean drive power and mean power of the load over the turn (W): they cancel.
    pub drive_power: f64,
    pub load_power: f64,
}

/// s, s′ = ds/dθ, s″ = d²s/dθ² of the slider's x at crank angle θ.
pub fn stroke(m: &SpatialSliderCrank, theta: f64) -> (f64, f64, f64) {
    let (sn, cs) = theta.sin_cos();
    let (a, h) = (m.a, m.a * sn - m.ey);
    let root = (m.len * m.len - h * h - m.ez * m.ez).sqrt();
    let s = a * cs + root;
    // W = L² − h² − ez², h′ = a cos θ, h″ = −a sin θ: (√W)′ = −h h′/√W,
    // (√W)″ = −(h′² + h h″)/√W − (h h′)²/√W³.
    let (h1, h2) = (a * cs, -a * sn);
    let d1 = -a * sn - h * h1 / root;
    let d2 = -a * cs - (h1 * h1 + h * h2) / root - (h * h1).powi(2) / root.powi(3);
    (s, d1, d2)
}

/// Runs the analyses over one crank turn; prints a table when `print` is set.
pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let m = SpatialSliderCrank::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = SpatialSliderCrank::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;

    // Dead centres: crank and rod in line seen along z (the ez offset only shortens the rod).
    let lp = (m.len * m.len - m.ez * m.ez).sqrt();
    let (s_max, s_min) = (((lp + m.a).powi(2) - m.ey * m.ey).sqrt(), ((lp - m.a).powi(2) - m.ey * m.ey).sqrt());
    let theta_outer = m.ey.atan2(s_max);
    let theta_inner = (-m.ey).atan2(-s_min).rem_euclid(2.0 * PI);
    let return_angle = theta_inner - theta_outer;
    let time_ratio = (2.0 * PI - return_angle).max(return_angle) / (2.0 * PI - return_angle).min(return_angle);

    let n = 360;
    let period = 2.0 * PI / m.omega;
    let (t_outer, t_inner) = (theta_outer / m.omega, theta_inner / m.omega);
    // Equally spaced over the period (their mean is the cycle average), and the dead centres.
    let mut times: Vec<f64> = (0..n).map(|k| period * k as f64 / n as f64).chain([t_outer, t_inner]).collect();
    times.sort_by(f64::total_cmp);

    let mut r = Report {
        samples: 0,
        position_error: 0.0,
        velocity_error: 0.0,
        acceleration_error: 0.0,
        peak_acceleration: 0.0,
        stroke: 0.0,
        stroke_exact: s_max - s_min,
        dead_centre_speed: 0.0,
        time_ratio,
        peak_torque: 0.0,
        torque_error: 0.0,
        peak_rod_force: 0.0,
        rod_force_error: 0.0,
        drive_power: 0.0,
        load_power: 0.0,
    };
    let mut failure = None;
    if print {
        println!(
            "Spatial slider-crank: a = {} m, L = {} m, offsets ey = {} m, ez = {} m, {:.0} rpm, load peak {} N",
            m.a,
            m.len,
            m.ey,
            m.ez,
            m.omega * 30.0 / PI,
            m.f0
        );
        println!(
            "{:>7} {:>10} {:>10} {:>11} {:>10} {:>11} {:>11} {:>10} {:>10}",
            "θ (deg)", "x (m)", "ẋ (m/s)", "ẍ (m/s²)", "|x−s|", "τ (N·m)", "τ_vw (N·m)", "rod (N)", "rod_cf (N)"
        );
    }
    let (mut x_outer, mut x_inner) = (f64::NAN, f64::NAN);
    let mut inverse_ws = SpatialSliderCrank::workspace(); // the sweep holds `ws`
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, vd| {
        let theta = m.omega * t;
        // The guide's stroke is the slider's x (the guide's ground marker is at x = 0), so its
        // rates are the slider's ẋ and ẍ.
        let slider = SpatialSliderCrank::SLIDER;
        let (x, xd, xdd) = (m.guide_stroke(q), slider.velocity(v).x, slider.acceleration(vd).x);
        if t == t_outer || t == t_inner {
            *(if t == t_outer { &mut x_outer } else { &mut x_inner }) = x;
            r.dead_centre_speed = r.dead_centre_speed.max(xd.abs());
            return;
        }
        let (s, d1, d2) = stroke(&m, theta);
        let (speed, accel) = (d1 * m.omega, d2 * m.omega * m.omega);
        r.position_error = r.position_error.max((x - s).abs());
        r.velocity_error = r.velocity_error.max((xd - speed).abs());
        r.acceleration_error = r.acceleration_error.max((xdd - accel).abs());
        r.peak_acceleration = r.peak_acceleration.max(accel.abs());

        let mut lambda = [0.0; SpatialSliderCrank::NC];
        if let Err(e) = InverseDynamics::default().solve(&m, &mut inverse_ws, q, v, vd, t, &mut lambda) {
            failure.get_or_insert(e);
            return;
        }
        let mut d = [[0.0; SpatialSliderCrank::NV]; SpatialSliderCrank::NC];
        m.jacobian(q, t, &mut d);
        let reaction = |joint: usize| joint_reaction(&m, q, &d, &lambda, joint).and_then(|j| j.on_j);
        // The motor's moment on the crank about z.
        let torque = reaction(SpatialSliderCrank::MOTOR).map_or(f64::NAN, |w| w.moment[2]);
        // ê from the slider to the crank pin, from the closed form.
        let (sn, cs) = theta.sin_cos();
        let e = [(m.a * cs - s) / m.len, (m.a * sn - m.ey) / m.len, -m.ez / m.len];
        let tension = reaction(SpatialSliderCrank::ROD).map_or(f64::NAN, |w| w.force[0] * e[0] + w.force[1] * e[1] + w.force[2] * e[2]);
        let load = -m.f0 * (1.0 - theta.cos()) / 2.0;
        let torque_exact = (m.m_slider * accel - load) * d1;
        let tension_exact = (m.m_slider * accel - load) / e[0];
        r.peak_torque = r.peak_torque.max(torque.abs());
        r.torque_error = r.torque_error.max((torque - torque_exact).abs());
        r.peak_rod_force = r.peak_rod_force.max(tension.abs());
        r.rod_force_error = r.rod_force_error.max((tension - tension_exact).abs());
        r.drive_power += torque * m.omega / n as f64;
        r.load_power += load * xd / n as f64;
        r.samples += 1;
        if print && r.samples % 30 == 1 {
            println!(
                "{:>7.1} {:>10.6} {:>10.5} {:>11.3} {:>10.1e} {:>11.5} {:>11.5} {:>10.3} {:>10.3}",
                theta.to_degrees(),
                x,
                xd,
                xdd,
                (x - s).abs(),
                torque,
                torque_exact,
                tension,
                tension_exact
            );
        }
    })?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    r.stroke = x_outer - x_inner;
    if print {
        println!(
            "max error vs closed form: x {:.1e} m, ẋ {:.1e} m/s, ẍ {:.1e} m/s² (peak {:.1} m/s²)",
            r.position_error, r.velocity_error, r.acceleration_error, r.peak_acceleration
        );
        println!(
            "dead centres at θ = {:.4}° and {:.4}°: stroke {:.12} m, closed form {:.12} m; |ẋ| there ≤ {:.1e} m/s; quick-return ratio {:.5}",
            theta_outer.to_degrees(),
            theta_inner.to_degrees(),
            r.stroke,
            r.stroke_exact,
            r.dead_centre_speed,
            r.time_ratio
        );
        println!(
            "drive torque peak {:.3} N·m, max |τ − τ_virtual work| {:.1e} N·m; rod force peak {:.1} N, max deviation {:.1e} N",
            r.peak_torque, r.torque_error, r.peak_rod_force, r.rod_force_error
        );
        println!(
            "mean drive power {:.6} W, mean load power {:.6} W (sum {:.1e} W)",
            r.drive_power,
            r.load_power,
            r.drive_power + r.load_power
        );
    }
    Ok(r)
}

/// One crank turn at 600 rpm, for the showcase's pictures: a kinematic sweep of 72 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = SpatialSliderCrank::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = SpatialSliderCrank::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<SpatialSliderCrank>(&m.params()).title("Offset spatial slider-crank, one crank turn");
    let period = 2.0 * PI / m.omega;
    let times = (0..=72).map(|k| period * k as f64 / 72.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("spatial_slider_crank: {e}");
        std::process::exit(1);
    }
}

//! Slider-crank driven at constant crank speed (Nikravesh, *Planar Multibody Dynamics*, ch. 7).
//!
//! Crank r = 0.1 m pinned to ground at the origin, connecting rod l = 0.3 m, slider on the x-axis.
//! Every body's frame sits at its centre of mass; links lie along their local x-axes. Over one
//! crank revolution the kinematic analysis gives the slider position, velocity and acceleration,
//! compared with the closed form x = r cos θ + √(l² − r² sin² θ).
//!
//! Run: `cargo run --release --example slider_crank`
use mbd::prelude::*;

mechanism! {
    /// Slider-crank driven at constant speed ω (Nikravesh, ch. 7).
    pub SliderCrank {
        params { omega: 2.0 * PI, r: 0.1, l: 0.3 }
        body crank  { mass: 1.0, inertia: 0.002, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.25, 0.0, 0.0] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.4, 0.0, 0.0] }
        point crank.O = [-r / 2.0, 0.0];
        point crank.A = [r / 2.0, 0.0];
        point rod.A = [-l / 2.0, 0.0];
        point rod.B = [l / 2.0, 0.0];
        point slider.pin = [0.0, 0.0];
        revolute ground[0.0, 0.0] ~ crank.O;
        revolute crank.A ~ rod.A;
        revolute rod.B ~ slider.pin;
        translational slider.pin along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive crank.phi = omega * t;
    }
}

/// What the run found: the largest deviations from the closed form over the revolution.
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// Crank positions analysed.
    pub samples: usize,
    /// max |x − x_exact| of the slider (m).
    pub position_error: f64,
    /// max |ẋ − ẋ_exact| (m/s).
    pub velocity_error: f64,
    /// max |ẍ − ẍ_exact| (m/s²).
    pub acceleration_error: f64,
    /// Largest |Φ| after the position solves.
    pub max_residual: f64,
    /// Stroke of the slider (m): 2r for any r < l.
    pub stroke: f64,
}

/// Closed-form slider position, velocity and acceleration for crank angle θ = ωt.
pub fn exact(r: f64, l: f64, omega: f64, t: f64) -> (f64, f64, f64) {
    let th = omega * t;
    let (s, c) = th.sin_cos();
    let root = (l * l - r * r * s * s).sqrt();
    let x = r * c + root;
    // ẋ = −rω sin θ − r²ω sin θ cos θ / root
    let xd = -r * omega * s - r * r * omega * s * c / root;
    // ẍ = −rω² cos θ − r²ω² [(c² − s²) root² + r² s² c²] / root³
    let xdd = -r * omega * omega * c - r * r * omega * omega * ((c * c - s * s) * root * root + r * r * s * s * c * c) / root.powi(3);
    (x, xd, xdd)
}

/// Runs the analysis over one revolution; prints a table when `print` is set.
pub fn run(print: bool) -> Result<Report, KinematicError> {
    let m = SliderCrank::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = SliderCrank::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let n = 72;
    let period = 2.0 * PI / m.omega;
    let mut report =
        Report { samples: 0, position_error: 0.0, velocity_error: 0.0, acceleration_error: 0.0, max_residual: 0.0, stroke: 0.0 };
    let (mut xmin, mut xmax) = (f64::INFINITY, f64::NEG_INFINITY);
    if print {
        println!("Slider-crank, r = {} m, l = {} m, ω = {:.4} rad/s", m.r, m.l, m.omega);
        println!("{:>8} {:>10} {:>12} {:>12} {:>12} {:>10}", "θ (deg)", "x (m)", "ẋ (m/s)", "ẍ (m/s²)", "rod φ (deg)", "|x−exact|");
    }
    let times = (0..=n).map(|k| period * k as f64 / n as f64);
    let pin = m.slider_pin();
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, vd| {
        let (x, xd, xdd) = exact(m.r, m.l, m.omega, t);
        let mut phi = [0.0; SliderCrank::NC];
        m.constraints(q, t, &mut phi);
        report.max_residual = phi.iter().fold(report.max_residual, |a, r| a.max(r.abs()));
        let (slider_x, slider_xd, slider_xdd) = (pin.position(q).x, pin.velocity(q, v).x, pin.acceleration(q, v, vd).x);
        report.position_error = report.position_error.max((slider_x - x).abs());
        report.velocity_error = report.velocity_error.max((slider_xd - xd).abs());
        report.acceleration_error = report.acceleration_error.max((slider_xdd - xdd).abs());
        xmin = xmin.min(slider_x);
        xmax = xmax.max(slider_x);
        report.samples += 1;
        if print && report.samples % 6 == 1 {
            println!(
                "{:>8.1} {:>10.6} {:>12.6} {:>12.4} {:>12.4} {:>10.2e}",
                (m.omega * t).to_degrees(),
                slider_x,
                slider_xd,
                slider_xdd,
                SliderCrank::ROD.phi(q).to_degrees(),
                (slider_x - x).abs()
            );
        }
    })?;
    report.stroke = xmax - xmin;
    if print {
        println!(
            "stroke {:.6} m (2r = {:.6}); max error vs closed form: x {:.1e} m, ẋ {:.1e} m/s, ẍ {:.1e} m/s²; max |Φ| {:.1e}",
            report.stroke,
            2.0 * m.r,
            report.position_error,
            report.velocity_error,
            report.acceleration_error,
            report.max_residual
        );
    }
    Ok(report)
}

/// One crank revolution, for the showcase's pictures: a kinematic sweep of 72 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = SliderCrank::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = SliderCrank::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<SliderCrank>(&m.params()).title("Slider-crank, one crank revolution").trace("crank.A");
    let period = 2.0 * PI / m.omega;
    let times = (0..=72).map(|k| period * k as f64 / 72.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("slider_crank: {e}");
        std::process::exit(1);
    }
}

//! Crank-rocker four-bar linkage (Nikravesh, *Planar Multibody Dynamics*, ch. 7).
//!
//! Ground pivots O₂ = (0, 0) and O₄ = (0.3, 0) m; crank a = 0.1 m, coupler b = 0.3 m,
//! rocker c = 0.25 m (Grashof: a + d ≤ b + c, so the crank turns fully). The crank turns at
//! 1 rev/s from a rough initial guess that the solver assembles. Reported per crank angle:
//! rocker angle, the path of a coupler point, and the transmission angle; checked against the
//! closed form (intersection of the circles about A and O₄).
//!
//! Run: `cargo run --release --example four_bar`
use mbd::prelude::*;

mechanism! {
    /// Crank-rocker four-bar linkage, crank driven at constant speed.
    pub FourBar {
        params { omega: 2.0 * PI, a: 0.1, b: 0.3, c: 0.25, d: 0.3 }
        body crank   { mass: 0.5, inertia: 5.0e-4, at: [0.05, 0.0, 0.0] }
        body coupler { mass: 1.2, inertia: 9.0e-3, at: [0.18, 0.12, 0.97] }
        body rocker  { mass: 1.0, inertia: 5.2e-3, at: [0.28, 0.12, 1.70] }
        revolute ground[0.0, 0.0] ~ crank[-a / 2.0, 0.0];
        revolute crank[a / 2.0, 0.0] ~ coupler[-b / 2.0, 0.0];
        revolute coupler.C ~ rocker[c / 2.0, 0.0];
        revolute rocker[-c / 2.0, 0.0] ~ ground[d, 0.0];
        point coupler.C = [b / 2.0, 0.0];
        point coupler.P = [0.0, 0.05];
        drive crank.phi = omega * t;
    }
}

/// Largest deviations from the closed form over one revolution, and the linkage's range.
#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// max |r_C − r_C,exact| of the coupler–rocker pin (m).
    pub pin_error: f64,
    /// Rocker swing: max − min rocker angle (rad).
    pub rocker_swing: f64,
    /// Smallest transmission angle (between coupler and rocker, folded to [0, 90°]) (deg).
    pub min_transmission_angle: f64,
    pub max_residual: f64,
}

/// Closed form: the coupler–rocker pin C for crank angle θ (open branch, C above the line AO₄).
pub fn pin_c(a: f64, b: f64, c: f64, d: f64, theta: f64) -> [f64; 2] {
    let ax = a * theta.cos();
    let ay = a * theta.sin();
    let (dx, dy) = (d - ax, -ay);
    let dist = (dx * dx + dy * dy).sqrt();
    let along = (b * b - c * c + dist * dist) / (2.0 * dist);
    let h = (b * b - along * along).sqrt();
    let (ex, ey) = (dx / dist, dy / dist);
    [ax + along * ex - h * ey, ay + along * ey + h * ex]
}

pub fn run(print: bool) -> Result<Report, KinematicError> {
    let m = FourBar::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = FourBar::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let n = 72;
    let period = 2.0 * PI / m.omega;
    let mut r = Report { samples: 0, pin_error: 0.0, rocker_swing: 0.0, min_transmission_angle: 90.0, max_residual: 0.0 };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    if print {
        println!("Four-bar: a = {} b = {} c = {} d = {} m, crank at {:.3} rad/s", m.a, m.b, m.c, m.d, m.omega);
        println!("{:>8} {:>12} {:>12} {:>12} {:>14} {:>10}", "θ (deg)", "rocker (deg)", "P x (m)", "P y (m)", "transm. (deg)", "|C−exact|");
    }
    let times = (0..=n).map(|k| period * k as f64 / n as f64);
    let (pin, tracer) = (m.coupler_c(), m.coupler_p());
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _v, _vd| {
        let c_exact = pin_c(m.a, m.b, m.c, m.d, m.omega * t);
        let c = pin.position(q);
        let p = tracer.position(q);
        let err = ((c.x - c_exact[0]).powi(2) + (c.y - c_exact[1]).powi(2)).sqrt();
        let (coupler, rocker) = (FourBar::COUPLER.phi(q), FourBar::ROCKER.phi(q));
        let mut phi = [0.0; FourBar::NC];
        m.constraints(q, t, &mut phi);
        r.max_residual = phi.iter().fold(r.max_residual, |a, v| a.max(v.abs()));
        r.pin_error = r.pin_error.max(err);
        lo = lo.min(rocker);
        hi = hi.max(rocker);
        // Transmission angle: between coupler and rocker directions, folded into [0°, 90°].
        let mu = (rocker - coupler).rem_euclid(PI).to_degrees();
        let mu = if mu > 90.0 { 180.0 - mu } else { mu };
        r.min_transmission_angle = r.min_transmission_angle.min(mu);
        r.samples += 1;
        if print && r.samples % 6 == 1 {
            println!(
                "{:>8.1} {:>12.4} {:>12.6} {:>12.6} {:>14.2} {:>10.2e}",
                (m.omega * t).to_degrees(),
                rocker.to_degrees(),
                p.x,
                p.y,
                mu,
                err
            );
        }
    })?;
    r.rocker_swing = hi - lo;
    if print {
        println!(
            "rocker swing {:.3}°, smallest transmission angle {:.2}°, max pin error vs closed form {:.1e} m, max |Φ| {:.1e}",
            r.rocker_swing.to_degrees(),
            r.min_transmission_angle,
            r.pin_error,
            r.max_residual
        );
    }
    Ok(r)
}

/// One crank revolution, for the showcase's pictures: a kinematic sweep of 72 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = FourBar::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = FourBar::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<FourBar>(&m.params()).title("Four-bar, one crank revolution").trace("coupler.P");
    let period = 2.0 * PI / m.omega;
    let times = (0..=72).map(|k| period * k as f64 / 72.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("four_bar: {e}");
        std::process::exit(1);
    }
}

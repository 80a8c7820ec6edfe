//! Web cutter on Chebyshev's straight-line linkage (after the web-cutter example of Nikravesh,
//! *Planar Multibody Dynamics*; the geometry here is Chebyshev's, documented, not the book's).
//! A knife at the coupler's midpoint must ride with the paper web, level and at the web's
//! speed, while it cuts. Ground pivots (0, 0) and (0.2, 0) m, crossed links of 0.25 m, coupler
//! 0.1 m: the midpoint moves on a nearly straight line y ≈ 0.2 m. The input link oscillates
//! ±0.2 rad about its mid position. Reported: how straight the knife's path is and its speed,
//! checked against the closed form (circle intersection on the crossed branch).
//!
//! Run: `cargo run --release --example web_cutter`
use mbd::prelude::*;

mechanism! {
    /// Chebyshev straight-line linkage carrying a knife at the coupler midpoint.
    pub WebCutter {
        params { omega: 2.0 * PI, amplitude: 0.2, phi_mid: atan2(0.2, 0.15) }
        body input   { mass: 0.4, inertia: 2.1e-3, at: [0.075, 0.1, 0.93] }
        body coupler { mass: 0.3, inertia: 2.5e-4, at: [0.1, 0.2, 3.14] }
        body output  { mass: 0.4, inertia: 2.1e-3, at: [0.125, 0.1, 2.21] }
        point input.O = [-0.125, 0.0];
        point input.A = [0.125, 0.0];
        point output.O = [-0.125, 0.0];
        point output.B = [0.125, 0.0];
        point coupler.knife = [0.0, 0.0];
        revolute ground[0.0, 0.0] ~ input.O;
        revolute ground[0.2, 0.0] ~ output.O;
        revolute input.A ~ coupler[-0.05, 0.0];
        revolute coupler[0.05, 0.0] ~ output.B;
        drive input.phi = phi_mid + amplitude * sin(omega * t);
    }
}

#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// max distance of the knife from the closed form (m).
    pub knife_error: f64,
    /// Horizontal travel of the knife (m) and its largest deviation from a level line (m).
    pub travel: f64,
    pub straightness: f64,
    /// Knife speed at mid-stroke (m/s): the web speed the cut is timed to.
    pub mid_speed: f64,
}

/// Knife position for input angle φ, in closed form.
pub fn knife_exact(phi: f64) -> [f64; 2] {
    let (a, b, c, d) = (0.25, 0.1, 0.25, 0.2);
    let pa = [a * phi.cos(), a * phi.sin()];
    let (dx, dy) = (d - pa[0], -pa[1]);
    let dist = (dx * dx + dy * dy).sqrt();
    let along = (b * b - c * c + dist * dist) / (2.0 * dist);
    let h = (b * b - along * along).sqrt();
    let (ex, ey) = (dx / dist, dy / dist);
    // crossed branch: B lies to the right of the direction A → O₄
    let pb = [pa[0] + along * ex + h * ey, pa[1] + along * ey - h * ex];
    [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0]
}

pub fn run(print: bool) -> Result<Report, KinematicError> {
    let m = WebCutter::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = WebCutter::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let n = 80;
    let period = 2.0 * PI / m.omega;
    let mut r = Report { samples: 0, knife_error: 0.0, travel: 0.0, straightness: 0.0, mid_speed: 0.0 };
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    if print {
        println!("Web cutter (Chebyshev linkage), input ±{} rad at {:.3} rad/s", m.amplitude, m.omega);
        println!("{:>7} {:>12} {:>12} {:>12} {:>10}", "t (s)", "knife x (m)", "knife y (m)", "vx (m/s)", "|err| (m)");
    }
    let times = (0..=n).map(|k| period * k as f64 / n as f64);
    let knife = m.coupler_knife();
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, _| {
        let k = knife.position(q);
        let knife_velocity = knife.velocity(q, v);
        let e = knife_exact(m.phi_mid + m.amplitude * (m.omega * t).sin());
        let err = ((k.x - e[0]).powi(2) + (k.y - e[1]).powi(2)).sqrt();
        r.knife_error = r.knife_error.max(err);
        x0 = x0.min(k.x);
        x1 = x1.max(k.x);
        y0 = y0.min(k.y);
        y1 = y1.max(k.y);
        if r.samples == 0 {
            r.mid_speed = knife_velocity.x.abs();
        }
        r.samples += 1;
        if print && r.samples % 8 == 1 {
            println!("{:>7.3} {:>12.6} {:>12.6} {:>12.5} {:>10.1e}", t, k.x, k.y, knife_velocity.x, err);
        }
    })?;
    r.travel = x1 - x0;
    r.straightness = y1 - y0;
    if print {
        println!(
            "knife travel {:.1} mm, level within {:.3} mm, mid-stroke speed {:.4} m/s, max error vs closed form {:.1e} m",
            r.travel * 1e3,
            r.straightness * 1e3,
            r.mid_speed,
            r.knife_error
        );
    }
    Ok(r)
}

/// One oscillation of the input link, for the showcase's pictures: a kinematic sweep of 80 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = WebCutter::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = WebCutter::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation =
        mbd::Animation::new::<WebCutter>(&m.params()).title("Web cutter (Chebyshev linkage), one oscillation").trace("coupler.knife");
    let period = 2.0 * PI / m.omega;
    let times = (0..=80).map(|k| period * k as f64 / 80.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("web_cutter: {e}");
        std::process::exit(1);
    }
}

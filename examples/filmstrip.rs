//! Filmstrip advancer (after Nikravesh, *Planar Multibody Dynamics*): a crank drives a claw link
//! that slides and swivels through a guide pin fixed to the frame — a revolute-translational
//! joint. The claw tip traces a closed loop: it enters a perforation, pulls the film forward and
//! withdraws. Geometry (documented, not the book's numbers): crank r = 20 mm about the origin,
//! guide pin at (60, 0) mm, claw tip 90 mm along the link from the crank pin and 5 mm below its
//! axis. Reported: the tip's loop, compared with the closed form A + 90 mm·u − 5 mm·n where
//! u points from the crank pin A to the guide pin.
//!
//! Run: `cargo run --release --example filmstrip`
use mbd::prelude::*;

mechanism! {
    /// Filmstrip advancer: crank, claw link, guide pin (revolute-translational joint).
    pub Filmstrip {
        params { omega: 2.0 * PI * 24.0, r: 0.02 }
        body crank { mass: 0.01, inertia: 1.0e-6, at: [0.01, 0.0, 0.0] }
        body claw  { mass: 0.02, inertia: 2.0e-5, at: [0.05, 0.0, 0.0] }
        point crank.O = [-r / 2.0, 0.0];
        point crank.A = [r / 2.0, 0.0];
        point claw.A = [-0.03, 0.0];
        point claw.tip = [0.06, -0.005];
        revolute ground[0.0, 0.0] ~ crank.O;
        revolute crank.A ~ claw.A;
        revolute_translational guide: ground[0.06, 0.0] ~ claw[0.0, 0.0] along [1.0, 0.0];
        drive crank.phi = omega * t;
    }
}

#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// max distance of the claw tip from the closed form (m).
    pub tip_error: f64,
    /// Horizontal and vertical extent of the tip's loop (m).
    pub stroke: f64,
    pub lift: f64,
    /// Largest tip speed (m/s) at 24 frames per second.
    pub max_speed: f64,
}

/// The claw tip for crank angle θ, in closed form.
pub fn tip_exact(r: f64, theta: f64) -> [f64; 2] {
    let a = [r * theta.cos(), r * theta.sin()];
    let (dx, dy) = (0.06 - a[0], -a[1]);
    let len = (dx * dx + dy * dy).sqrt();
    let u = [dx / len, dy / len];
    let n = [-u[1], u[0]];
    [a[0] + 0.09 * u[0] - 0.005 * n[0], a[1] + 0.09 * u[1] - 0.005 * n[1]]
}

pub fn run(print: bool) -> Result<Report, KinematicError> {
    let m = Filmstrip::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Filmstrip::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let period = 2.0 * PI / m.omega;
    let n = 96;
    let mut r = Report { samples: 0, tip_error: 0.0, stroke: 0.0, lift: 0.0, max_speed: 0.0 };
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    if print {
        println!("Filmstrip advancer at {:.0} frames/s: claw tip loop", m.omega / (2.0 * PI));
        println!("{:>8} {:>10} {:>10} {:>10} {:>10}", "θ (deg)", "tip x (mm)", "tip y (mm)", "speed (m/s)", "|err| (m)");
    }
    let times = (0..=n).map(|k| period * k as f64 / n as f64);
    let claw_tip = m.claw_tip();
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, _| {
        let tip = claw_tip.position(q);
        let tip_velocity = claw_tip.velocity(q, v);
        let exact = tip_exact(m.r, m.omega * t);
        let err = ((tip.x - exact[0]).powi(2) + (tip.y - exact[1]).powi(2)).sqrt();
        let speed = (tip_velocity.x * tip_velocity.x + tip_velocity.y * tip_velocity.y).sqrt();
        r.tip_error = r.tip_error.max(err);
        r.max_speed = r.max_speed.max(speed);
        x0 = x0.min(tip.x);
        x1 = x1.max(tip.x);
        y0 = y0.min(tip.y);
        y1 = y1.max(tip.y);
        r.samples += 1;
        if print && r.samples % 8 == 1 {
            println!("{:>8.1} {:>10.3} {:>10.3} {:>10.4} {:>10.1e}", (m.omega * t).to_degrees(), tip.x * 1e3, tip.y * 1e3, speed, err);
        }
    })?;
    r.stroke = x1 - x0;
    r.lift = y1 - y0;
    if print {
        println!(
            "loop {:.2} mm × {:.2} mm, top speed {:.3} m/s, max error vs closed form {:.1e} m",
            r.stroke * 1e3,
            r.lift * 1e3,
            r.max_speed,
            r.tip_error
        );
    }
    Ok(r)
}

/// One crank revolution, for the showcase's pictures: a kinematic sweep of 96 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = Filmstrip::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Filmstrip::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<Filmstrip>(&m.params()).title("Filmstrip advancer, one crank revolution").trace("claw.tip");
    let period = 2.0 * PI / m.omega;
    let times = (0..=96).map(|k| period * k as f64 / 96.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("filmstrip: {e}");
        std::process::exit(1);
    }
}

//! MacPherson strut suspension, front view, kinematic (after Nikravesh, *Planar Multibody
//! Dynamics*, ch. 7–8; documented, plausible hardpoints, not the book's). Chassis = ground; the
//! strut tube is part of the knuckle and slides on the piston rod, which swivels in the top mount
//! (revolute) — a translational joint between knuckle and rod. The wheel centre's height is
//! driven through ±80 mm; reported: camber change, track change, strut length and motion ratio.
//!
//! Hardpoints at design height (m): lower arm (0.25, 0.12)–(0.60, 0.10), wheel centre
//! (0.65, 0.30), strut axis from (0.57, 0.40) on the knuckle to the top mount (0.50, 0.75).
//!
//! Run: `cargo run --release --example macpherson`
use mbd::nalgebra::{distance, Point2};
use mbd::prelude::*;

mechanism! {
    /// MacPherson strut suspension with the wheel travel driven.
    pub MacPherson {
        params { travel: 0.08, omega: 2.0 * PI, wheel_y: 0.30 }
        body lower   { mass: 4.0, inertia: 0.05, at: [0.425, 0.11, 0.0] }
        body knuckle { mass: 10.0, inertia: 0.15, at: [0.65, 0.30, 0.0] }
        body rod     { mass: 1.0, inertia: 0.01, at: [0.535, 0.575, 0.0] }
        point lower.inner = [-0.175, 0.01];
        point lower.outer = [0.175, -0.01];
        point knuckle.ball = [-0.05, -0.20];
        point knuckle.strut = [-0.08, 0.10];
        point knuckle.contact = [0.0, -0.30];
        point rod.top = [-0.035, 0.175];
        point rod.bottom = [0.035, -0.175];
        vector knuckle.axis = [-0.07, 0.35];
        vector rod.axis = [-0.07, 0.35];
        revolute ground[0.25, 0.12] ~ lower.inner;
        revolute lower.outer ~ knuckle.ball;
        translational strut: knuckle.strut along knuckle.axis ~ rod.bottom along rod.axis;
        revolute top_mount: rod.top ~ ground[0.50, 0.75];
        drive knuckle.y = wheel_y + travel * sin(omega * t);
    }
}

/// The top mount on the chassis (m).
pub const TOP_MOUNT: Point2<f64> = Point2::new(0.50, 0.75);

#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// Camber angle range over the travel (deg, positive with the wheel's top leaning outward).
    pub camber_min: f64,
    pub camber_max: f64,
    pub track_change: f64,
    /// Strut length (top mount to the strut point on the knuckle) range (m).
    pub strut_min: f64,
    pub strut_max: f64,
    /// Motion ratio: strut compression per unit of wheel travel at design height, −dl/dz.
    pub motion_ratio: f64,
    /// Largest distance of the knuckle's strut point from the rod's axis (m): the slide is straight.
    pub axis_error: f64,
}

pub fn run(print: bool) -> Result<Report, KinematicError> {
    let m = MacPherson::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = MacPherson::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let knuckle = MacPherson::KNUCKLE;
    let (strut_point, contact_point) = (m.knuckle_strut(), m.knuckle_contact());
    let contact0 = contact_point.position(&q);
    let mut r = Report {
        samples: 0,
        camber_min: f64::INFINITY,
        camber_max: f64::NEG_INFINITY,
        track_change: 0.0,
        strut_min: f64::INFINITY,
        strut_max: f64::NEG_INFINITY,
        motion_ratio: f64::NAN,
        axis_error: 0.0,
    };
    if print {
        println!("MacPherson strut suspension: wheel travel ±{} mm", m.travel * 1e3);
        println!("{:>12} {:>12} {:>14} {:>12}", "travel (mm)", "camber (deg)", "track Δ (mm)", "strut (mm)");
    }
    let times = (0..=64).map(|k| k as f64 / 64.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, _| {
        let s = strut_point.position(q);
        let strut = distance(&s, &TOP_MOUNT);
        let contact = contact_point.position(q);
        // Camber: the wheel's tilt, positive with its top leaning outward (+x); the knuckle's
        // counter-clockwise rotation φ leans the top inward, so camber = −φ.
        let camber = -knuckle.phi(q).to_degrees();
        // distance of the knuckle's strut point from the line through the top mount along the rod
        let (sn, cs) = MacPherson::ROD.phi(q).sin_cos();
        let len = (0.07f64 * 0.07 + 0.35 * 0.35).sqrt();
        let u = [(cs * -0.07 - sn * 0.35) / len, (sn * -0.07 + cs * 0.35) / len];
        let d = s - TOP_MOUNT;
        r.axis_error = r.axis_error.max((d.x * u[1] - d.y * u[0]).abs());
        r.camber_min = r.camber_min.min(camber);
        r.camber_max = r.camber_max.max(camber);
        r.track_change = r.track_change.max((contact.x - contact0.x).abs());
        r.strut_min = r.strut_min.min(strut);
        r.strut_max = r.strut_max.max(strut);
        if t == 0.0 {
            let strut_rate = strut_point.velocity(q, v);
            r.motion_ratio = -strut_rate.dot(&d) / strut / knuckle.velocity(v).y;
        }
        r.samples += 1;
        if print && r.samples % 4 == 1 {
            println!(
                "{:>12.1} {:>12.4} {:>14.3} {:>12.2}",
                (knuckle.y(q) - m.wheel_y) * 1e3,
                camber,
                (contact.x - contact0.x) * 1e3,
                strut * 1e3
            );
        }
    })?;
    if print {
        println!(
            "camber {:.3}° … {:.3}°, track change up to {:.2} mm, strut {:.1} … {:.1} mm, motion ratio {:.4}, axis error {:.1e} m",
            r.camber_min,
            r.camber_max,
            r.track_change * 1e3,
            r.strut_min * 1e3,
            r.strut_max * 1e3,
            r.motion_ratio,
            r.axis_error
        );
    }
    Ok(r)
}

/// One cycle of ±80 mm wheel travel, for the showcase's pictures: a kinematic sweep of 64 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = MacPherson::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = MacPherson::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation =
        mbd::Animation::new::<MacPherson>(&m.params()).title("MacPherson strut, ±80 mm wheel travel").trace("knuckle.contact");
    let period = 2.0 * PI / m.omega;
    let times = (0..=64).map(|k| period * k as f64 / 64.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("macpherson: {e}");
        std::process::exit(1);
    }
}

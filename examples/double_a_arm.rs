//! Double A-arm (double-wishbone) suspension, front view, kinematic (after Nikravesh, *Planar
//! Multibody Dynamics*, ch. 7–8; the hardpoints are documented, plausible passenger-car values,
//! not the book's). Chassis = ground; y up, x outward. The wheel centre's height is driven through
//! ±80 mm of travel; reported are what a suspension engineer reads off a kinematic sweep: camber
//! change, track change at the contact patch, spring length and the motion ratio.
//!
//! Hardpoints at design height (m): lower arm (0.20, 0.15)–(0.55, 0.13), upper arm
//! (0.30, 0.45)–(0.52, 0.47), wheel centre (0.62, 0.30), tyre radius 0.30, spring from the lower
//! arm (0.475, 0.14) to the chassis (0.45, 0.60).
//!
//! Run: `cargo run --release --example double_a_arm`
use mbd::nalgebra::{distance, Point2};
use mbd::prelude::*;

mechanism! {
    /// Double A-arm suspension with the wheel travel driven.
    pub DoubleAArm {
        params { travel: 0.08, omega: 2.0 * PI, wheel_y: 0.30 }
        body lower   { mass: 4.0, inertia: 0.05, at: [0.375, 0.14, 0.0] }
        body upper   { mass: 2.5, inertia: 0.02, at: [0.41, 0.46, 0.0] }
        body knuckle { mass: 8.0, inertia: 0.10, at: [0.62, 0.30, 0.0] }
        point lower.inner = [-0.175, 0.01];
        point lower.outer = [0.175, -0.01];
        point lower.spring = [0.1, 0.0];
        point upper.inner = [-0.11, -0.01];
        point upper.outer = [0.11, 0.01];
        point knuckle.lower_ball = [-0.07, -0.17];
        point knuckle.upper_ball = [-0.10, 0.17];
        point knuckle.contact = [0.0, -0.30];
        revolute ground[0.20, 0.15] ~ lower.inner;
        revolute ground[0.30, 0.45] ~ upper.inner;
        revolute lower.outer ~ knuckle.lower_ball;
        revolute upper.outer ~ knuckle.upper_ball;
        drive knuckle.y = wheel_y + travel * sin(omega * t);
    }
}

/// Chassis end of the spring (m).
pub const SPRING_TOP: Point2<f64> = Point2::new(0.45, 0.60);
/// Chassis pivots of the lower and the upper arm (m), as in the mechanism.
const LOWER_PIVOT: Point2<f64> = Point2::new(0.20, 0.15);
const UPPER_PIVOT: Point2<f64> = Point2::new(0.30, 0.45);

#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// Camber angle range over the travel (deg, positive with the wheel's top leaning outward).
    pub camber_min: f64,
    pub camber_max: f64,
    /// Largest lateral movement of the contact patch from design (m).
    pub track_change: f64,
    /// Spring length range (m).
    pub spring_min: f64,
    pub spring_max: f64,
    /// Motion ratio: spring compression per unit of wheel travel at design height, −dl/dz.
    pub motion_ratio: f64,
    /// Largest error of the arms' pivot-to-ball-joint lengths (m): rigid links stay rigid.
    pub link_length_error: f64,
}

pub fn run(print: bool) -> Result<Report, KinematicError> {
    let m = DoubleAArm::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = DoubleAArm::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let knuckle = DoubleAArm::KNUCKLE;
    let (spring_point, contact_point) = (m.lower_spring(), m.knuckle_contact());
    let (lower_ball, upper_ball) = (m.lower_outer(), m.upper_outer());
    let contact0 = contact_point.position(&q);
    let lower_len = distance(&LOWER_PIVOT, &Point2::new(0.55, 0.13));
    let upper_len = distance(&UPPER_PIVOT, &Point2::new(0.52, 0.47));
    let mut r = Report {
        samples: 0,
        camber_min: f64::INFINITY,
        camber_max: f64::NEG_INFINITY,
        track_change: 0.0,
        spring_min: f64::INFINITY,
        spring_max: f64::NEG_INFINITY,
        motion_ratio: f64::NAN,
        link_length_error: 0.0,
    };
    if print {
        println!("Double A-arm suspension: wheel travel ±{} mm", m.travel * 1e3);
        println!("{:>12} {:>12} {:>14} {:>12}", "travel (mm)", "camber (deg)", "track Δ (mm)", "spring (mm)");
    }
    let times = (0..=64).map(|k| k as f64 / 64.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, _| {
        let spring_bottom = spring_point.position(q);
        let spring = distance(&spring_bottom, &SPRING_TOP);
        let contact = contact_point.position(q);
        // Camber: the wheel's tilt, positive with its top leaning outward (+x); the knuckle's
        // counter-clockwise rotation φ leans the top inward, so camber = −φ.
        let camber = -knuckle.phi(q).to_degrees();
        let travel = knuckle.y(q) - m.wheel_y;
        let lo = distance(&LOWER_PIVOT, &lower_ball.position(q));
        let up = distance(&UPPER_PIVOT, &upper_ball.position(q));
        r.link_length_error = r.link_length_error.max((lo - lower_len).abs()).max((up - upper_len).abs());
        r.camber_min = r.camber_min.min(camber);
        r.camber_max = r.camber_max.max(camber);
        r.track_change = r.track_change.max((contact.x - contact0.x).abs());
        r.spring_min = r.spring_min.min(spring);
        r.spring_max = r.spring_max.max(spring);
        if t == 0.0 {
            // d(spring)/dt divided by the wheel's vertical speed: both from the velocity solve.
            let spring_rate = spring_point.velocity(q, v);
            let e = (spring_bottom - SPRING_TOP) / spring;
            r.motion_ratio = -spring_rate.dot(&e) / knuckle.velocity(v).y;
        }
        r.samples += 1;
        if print && r.samples % 4 == 1 {
            println!("{:>12.1} {:>12.4} {:>14.3} {:>12.2}", travel * 1e3, camber, (contact.x - contact0.x) * 1e3, spring * 1e3);
        }
    })?;
    if print {
        println!(
            "camber {:.3}° … {:.3}°, track change up to {:.2} mm, spring {:.1} … {:.1} mm, motion ratio {:.4}, link length error {:.1e} m",
            r.camber_min,
            r.camber_max,
            r.track_change * 1e3,
            r.spring_min * 1e3,
            r.spring_max * 1e3,
            r.motion_ratio,
            r.link_length_error
        );
    }
    Ok(r)
}

/// One cycle of ±80 mm wheel travel, for the showcase's pictures: a kinematic sweep of 64 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = DoubleAArm::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = DoubleAArm::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<DoubleAArm>(&m.params()).title("Double A-arm, ±80 mm wheel travel").trace("knuckle.contact");
    let period = 2.0 * PI / m.omega;
    let times = (0..=64).map(|k| period * k as f64 / 64.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("double_a_arm: {e}");
        std::process::exit(1);
    }
}

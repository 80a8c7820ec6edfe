//! Inverse dynamics of a slider-crank with a flywheel (Nikravesh, *Planar Multibody Dynamics*,
//! ch. 12): the crank turns at a constant 300 rpm against a gas force on the piston; the analysis
//! gives, over one revolution, the torque the drive must supply and the reaction forces in the
//! main bearing and at the piston pin.
//!
//! The gas force acts during the expansion half of the revolution (θ in 0…π, piston moving down
//! the bore toward the crank): a pressure pulse F(θ) = F₀ sin θ pushing the piston toward the
//! crank. Gravity acts in −y. Energy check: over a revolution at constant speed the mean drive
//! power equals minus the mean gas power (the kinetic energy returns to its start and the
//! potential energy too), computed independently of the multipliers.
//!
//! Run: `cargo run --release --example slider_crank_inverse`
use mbd::prelude::*;

mechanism! {
    /// Slider-crank with a flywheel on the crank, driven at constant speed against a gas force.
    pub Engine {
        params { omega: 10.0 * PI, f0: 2000.0, r: 0.05, l: 0.2 }
        gravity [0.0, -9.81];
        body crank  { mass: 5.0, inertia: 0.05, at: [0.0, 0.0, 0.0] }
        body rod    { mass: 0.8, inertia: 3.0e-3, at: [0.15, 0.0, 0.0] }
        body piston { mass: 0.5, inertia: 1.0e-4, at: [0.25, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0] ~ crank[0.0, 0.0];
        revolute crankpin: crank[r, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute wristpin: rod[l / 2.0, 0.0] ~ piston[0.0, 0.0];
        translational bore: piston[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive motor: crank.phi = omega * t;
        // Gas pressure on the piston during the expansion half-revolution, toward the crank (−x).
        force piston[0.0, 0.0] = [-f0 * (sin(crank.phi) + sqrt(sin(crank.phi)^2)) / 2.0, 0.0];
    }
}

#[derive(Debug, Clone, Copy)]
pub struct Report {
    pub samples: usize,
    /// Largest and smallest torque of the drive on the crank over the revolution (N·m; negative
    /// while the gas force drives the crank and the drive brakes it to constant speed).
    pub torque_max: f64,
    pub torque_min: f64,
    /// Mean drive power (W) and mean power of the gas force on the piston (W).
    pub drive_power: f64,
    pub gas_power: f64,
    /// Largest main-bearing force on the crank (N).
    pub bearing_max: f64,
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let m = Engine::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Engine::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let period = 2.0 * PI / m.omega;
    let n = 360;
    let mut r =
        Report { samples: 0, torque_max: f64::NEG_INFINITY, torque_min: f64::INFINITY, drive_power: 0.0, gas_power: 0.0, bearing_max: 0.0 };
    let mut failure = None;
    if print {
        println!("Slider-crank engine at {:.0} rpm, gas force peak {} N", m.omega * 60.0 / (2.0 * PI), m.f0);
        println!("{:>7} {:>12} {:>14} {:>14} {:>14}", "θ (deg)", "torque (N·m)", "bearing x (N)", "bearing y (N)", "wrist pin (N)");
    }
    // Samples at the midpoints of n equal intervals: the mean over them is the cycle average.
    let times = (0..n).map(|k| period * (k as f64 + 0.5) / n as f64);
    let inverse = InverseDynamics::default();
    let mut inverse_ws = Engine::workspace(); // the sweep holds `ws`
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, v, vd| {
        let mut lambda = [0.0; Engine::NC];
        if let Err(e) = inverse.solve(&m, &mut inverse_ws, q, v, vd, t, &mut lambda) {
            failure.get_or_insert(e);
            return;
        }
        let mut d = [[0.0; Engine::NV]; Engine::NC];
        m.jacobian(q, t, &mut d);
        let motor = joint_reaction(&m, q, &d, &lambda, Engine::MOTOR).and_then(|j| j.on_i);
        let bearing = joint_reaction(&m, q, &d, &lambda, Engine::BEARING).and_then(|j| j.on_j);
        let wrist = joint_reaction(&m, q, &d, &lambda, Engine::WRISTPIN).and_then(|j| j.on_j);
        let (Some(motor), Some(bearing), Some(wrist)) = (motor, bearing, wrist) else { return };
        // Planar: the moment is about z.
        let torque = motor.moment[2];
        let theta = Engine::CRANK.phi(q);
        let gas = -m.f0 * (theta.sin() + theta.sin().abs()) / 2.0;
        r.torque_max = r.torque_max.max(torque);
        r.torque_min = r.torque_min.min(torque);
        r.drive_power += torque * Engine::CRANK.omega(v) / n as f64;
        r.gas_power += gas * Engine::PISTON.velocity(v).x / n as f64;
        let b = (bearing.force[0].powi(2) + bearing.force[1].powi(2)).sqrt();
        r.bearing_max = r.bearing_max.max(b);
        r.samples += 1;
        if print && r.samples % 30 == 1 {
            let w = (wrist.force[0].powi(2) + wrist.force[1].powi(2)).sqrt();
            println!("{:>7.1} {:>12.3} {:>14.2} {:>14.2} {:>14.2}", theta.to_degrees(), torque, bearing.force[0], bearing.force[1], w);
        }
    })?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    if print {
        println!(
            "drive torque {:.2} … {:.2} N·m; mean drive power {:.3} W vs mean gas power {:.3} W; peak bearing force {:.1} N",
            r.torque_min, r.torque_max, r.drive_power, r.gas_power, r.bearing_max
        );
    }
    Ok(r)
}

/// One revolution at 300 rpm, for the showcase's pictures: a kinematic sweep of 72 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = Engine::default();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = Engine::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<Engine>(&m.params()).title("Engine at 300 rpm (inverse dynamics), one revolution");
    let period = 2.0 * PI / m.omega;
    let times = (0..=72).map(|k| period * k as f64 / 72.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("slider_crank_inverse: {e}");
        std::process::exit(1);
    }
}

//! The engine of `slider_crank_inverse.rs`, now running free (Nikravesh ch. 13): the gas force
//! drives the piston, a generator on the crank shaft brakes it with a torque −c ω, and the
//! flywheel (J = 2 kg·m² on the crank) smooths the speed. Forward dynamics (DOPRI5 with
//! projection) from 300 rpm until the motion repeats; reported: the mean speed and the
//! coefficient of speed fluctuation δ = (ω_max − ω_min)/ω_mean over the last revolution.
//!
//! The inverse dynamics predicts both: at constant speed the drive torque τ_d(θ) (from
//! `slider_crank_inverse`) balances gas, gravity and inertia; a generator absorbing the mean
//! power −P_d at ω₀ = 300 rpm needs c = −P_d/ω₀², and the flywheel must store the largest
//! swing ΔE of ∫(−τ_d − mean) dθ, so δ ≈ ΔE / (J_eff ω₀²) (J_eff: the crank's J plus the
//! rod's and piston's mean reduced inertia). The two must agree to the first order in δ.
//!
//! Run: `cargo run --release --example flywheel_engine`
use mbd::prelude::*;

#[allow(dead_code)]
#[path = "slider_crank_inverse.rs"]
pub mod slider_crank_inverse;
use slider_crank_inverse::Engine;

mechanism! {
    /// The slider-crank engine, free: gas force on the piston, generator torque on the crank.
    pub FreeEngine {
        params { c_load: 1.0, flywheel: 2.0, f0: 2000.0, r: 0.05, l: 0.2 }
        gravity [0.0, -9.81];
        body crank  { mass: 5.0, inertia: flywheel, at: [0.0, 0.0, 0.0], velocity: [0.0, 0.0, 10.0 * PI] }
        body rod    { mass: 0.8, inertia: 3.0e-3, at: [0.15, 0.0, 0.0] }
        body piston { mass: 0.5, inertia: 1.0e-4, at: [0.25, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0] ~ crank[0.0, 0.0];
        revolute crankpin: crank[r, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute wristpin: rod[l / 2.0, 0.0] ~ piston[0.0, 0.0];
        translational bore: piston[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        force piston[0.0, 0.0] = [-f0 * (sin(crank.phi) + sqrt(sin(crank.phi)^2)) / 2.0, 0.0];
        torque generator: crank = -c_load * crank.omega;
    }
}

#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// Generator constant from the inverse dynamics (N·m·s).
    pub c_load: f64,
    /// Mean crank speed over the last revolution (rad/s) and the design speed (rad/s).
    pub omega_mean: f64,
    pub omega_design: f64,
    /// Coefficient of speed fluctuation, simulated and predicted from the inverse dynamics.
    pub delta: f64,
    pub delta_predicted: f64,
}

/// What the inverse dynamics at the design speed predicts for the free engine.
struct Design {
    /// Design speed (rad/s).
    omega0: f64,
    /// Mean drive torque over a revolution (N·m).
    mean_torque: f64,
    /// Generator constant that absorbs the mean power at the design speed (N·m·s).
    c_load: f64,
    /// Predicted coefficient of speed fluctuation.
    delta_predicted: f64,
}

/// Inverse dynamics at the design speed: drive torque over one revolution, and what follows.
fn design() -> Result<Design, Box<dyn std::error::Error>> {
    let engine = Engine::default();
    let solver = KinematicSolver::default();
    let mut q = engine.initial_positions();
    let mut ws = Engine::workspace();
    solver.assemble(&engine, &mut ws, &mut q, 0.0)?;
    let omega0 = engine.omega;
    let n = 720;
    let period = 2.0 * PI / omega0;
    let mut torque = Vec::with_capacity(n);
    let m = FreeEngine::default();
    let mut reduced = 0.0;
    let times = (0..n).map(|k| period * (k as f64 + 0.5) / n as f64);
    // The motor's row Φ = φ − ω t: Φ_qᵀλ on the crank's φ is its λ, the drive torque.
    let motor_row = Engine::JOINTS[Engine::MOTOR].row_range().start;
    let mut inverse_ws = Engine::workspace(); // the sweep holds `ws`
    solver.sweep(&engine, &mut ws, &mut q, times, |t, q, v, vd| {
        let mut lambda = [0.0; Engine::NC];
        if InverseDynamics::default().solve(&engine, &mut inverse_ws, q, v, vd, t, &mut lambda).is_ok() {
            torque.push(lambda[motor_row]);
        }
        // Kinetic energy / (½ω²): the reduced inertia at this angle.
        // (same geometry and coordinates: the engine's states are the free engine's too).
        reduced += 2.0 * kinetic_energy(&m, q, v) / (omega0 * omega0) / n as f64;
    })?;
    let mean_torque = torque.iter().sum::<f64>() / n as f64;
    // The drive brakes on average (τ_mean < 0); the generator takes that power: c = −τ_mean/ω₀.
    let c_load = -mean_torque / omega0;
    // Excess work of the gas over the generator, ∫(−τ_d − mean(−τ_d)) dθ, and its largest swing.
    let dtheta = 2.0 * PI / n as f64;
    let (mut w, mut w_min, mut w_max) = (0.0_f64, 0.0_f64, 0.0_f64);
    for &tau in &torque {
        w += -(tau - mean_torque) * dtheta;
        w_min = w_min.min(w);
        w_max = w_max.max(w);
    }
    let delta_predicted = (w_max - w_min) / (reduced * omega0 * omega0);
    Ok(Design { omega0, mean_torque, c_load, delta_predicted })
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let Design { omega0, mean_torque, c_load, delta_predicted } = design()?;
    // Forward dynamics of the free engine with that generator.
    let m = FreeEngine { c_load, ..FreeEngine::default() };
    let mut q = m.initial_positions();
    let mut ws = FreeEngine::workspace();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut v = m.initial_velocities();
    mbd::project(&m, 0.0, &mut q, &mut v, &DynamicsOptions::default(), 1e-12, 10)?;
    let t_end = 6.0;
    let times: Vec<f64> = (0..=(t_end * 2000.0) as usize).map(|k| k as f64 / 2000.0).collect();
    let options = SimulationOptions::default().with_correction(Correction::projection());
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-11));
    let mut last_rev: Vec<(f64, f64)> = Vec::new();
    let crank = FreeEngine::CRANK;
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &v)
        .times(&times)
        .options(options)
        .run(&mut ws, |s| last_rev.push((crank.phi(&s.point.q), crank.omega(&s.point.v))))?;
    // The last full revolution.
    let end_angle = last_rev.last().map(|p| p.0).unwrap_or(0.0);
    let rev: Vec<f64> = last_rev.iter().filter(|p| p.0 > end_angle - 2.0 * PI).map(|p| p.1).collect();
    let (lo, hi) = rev.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &w| (a.min(w), b.max(w)));
    let omega_mean = rev.iter().sum::<f64>() / rev.len() as f64;
    let r = Report { c_load, omega_mean, omega_design: omega0, delta: (hi - lo) / omega_mean, delta_predicted };
    if print {
        println!(
            "inverse dynamics at {:.0} rpm: mean drive torque {mean_torque:.3} N·m → generator c = {c_load:.5} N·m·s",
            omega0 * 30.0 / PI
        );
        println!(
            "free run, last revolution: mean speed {:.1} rpm (design {:.1}); speed fluctuation δ = {:.4} (predicted {:.4}); {} DOPRI5 steps",
            omega_mean * 30.0 / PI,
            omega0 * 30.0 / PI,
            r.delta,
            r.delta_predicted,
            dopri.accepted
        );
    }
    Ok(r)
}

/// The free engine's first second (five revolutions) with the generator the inverse dynamics
/// sizes, for the showcase's pictures: 200 frames, 5 ms apart.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = FreeEngine { c_load: design()?.c_load, ..FreeEngine::default() };
    let mut q = m.initial_positions();
    let mut ws = FreeEngine::workspace();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut v = m.initial_velocities();
    mbd::project(&m, 0.0, &mut q, &mut v, &DynamicsOptions::default(), 1e-12, 10)?;
    let times: Vec<f64> = (0..200).map(|k| 0.005 * k as f64).collect();
    let options = SimulationOptions::default().with_correction(Correction::projection());
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-11));
    let mut animation = mbd::Animation::new::<FreeEngine>(&m.params()).title("Free engine with flywheel and generator, first second");
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &v)
        .times(&times)
        .options(options)
        .run(&mut ws, |s| animation.frame(s.point.t, &s.point.q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("flywheel_engine: {e}");
        std::process::exit(1);
    }
}

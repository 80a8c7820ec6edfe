//! A free four-bar under gravity (the linkage of `four_bar.rs` without its motor, released from
//! rest) and what accuracy costs in time: the same 2 s of motion with RK4 and generalized-α at
//! several step sizes and DOPRI5 at several tolerances, each against a DOPRI5 reference at
//! rtol 1e-12. Reported per run: wall time, steps, the error of the rocker angle at t = 2 s,
//! and the energy drift (conservative mechanism with projection: T + V must stay constant).
//!
//! Run: `cargo run --release --example free_four_bar`
use std::time::Instant;

use mbd::prelude::*;

mechanism! {
    /// The four-bar of `four_bar.rs`, free, under gravity.
    pub FreeFourBar {
        gravity [0.0, -9.81];
        body crank   { mass: 0.5, inertia: 5.0e-4, at: [0.05, 0.0, 0.0] }
        body coupler { mass: 1.2, inertia: 9.0e-3, at: [0.18, 0.12, 0.97] }
        body rocker  { mass: 1.0, inertia: 5.2e-3, at: [0.28, 0.12, 1.70] }
        revolute ground[0.0, 0.0] ~ crank[-0.05, 0.0];
        revolute crank[0.05, 0.0] ~ coupler[-0.15, 0.0];
        revolute coupler[0.15, 0.0] ~ rocker[0.125, 0.0];
        revolute rocker[-0.125, 0.0] ~ ground[0.3, 0.0];
    }
}

/// One integrator setting's cost and accuracy.
#[derive(Debug, Clone, Copy)]
pub struct Run {
    pub method: &'static str,
    pub setting: f64,
    pub steps: u64,
    pub seconds: f64,
    /// |φ_rocker(2 s) − reference| (rad).
    pub error: f64,
    /// max |T + V − E₀| (J).
    pub energy_drift: f64,
}

const T_END: f64 = 2.0;

const NQ: usize = FreeFourBar::NQ;
const NV: usize = FreeFourBar::NV;
const NC: usize = FreeFourBar::NC;

/// One run with any integrator; the sizes are the mechanism's (no numbers to repeat).
fn one<I, const N: usize, const NS: usize>(
    m: &FreeFourBar,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    q: &[f64; NQ],
    integrator: &mut I,
) -> Result<(u64, f64, f64, f64), SimulationError>
where
    I: Integrator<f64, FreeFourBar, NQ, NV, NC, N, NS>,
{
    let options = SimulationOptions::default().with_correction(Correction::projection());
    let times: Vec<f64> = (1..=20).map(|k| k as f64 * T_END / 20.0).collect();
    let e0 = m.potential_energy(q, 0.0);
    let mut drift: f64 = 0.0;
    let mut last = 0.0;
    let start = Instant::now();
    let stats = Simulation::new(m, integrator).start(0.0, q, &[0.0; NV]).times(&times).options(options).run(ws, |s| {
        drift = drift.max((s.energy.kinetic + s.energy.potential - e0).abs());
        last = FreeFourBar::ROCKER.phi(&s.point.q);
    })?;
    Ok((stats.steps, start.elapsed().as_secs_f64(), last, drift))
}

pub fn run(print: bool) -> Result<Vec<Run>, Box<dyn std::error::Error>> {
    let m = FreeFourBar::default();
    let mut q = m.initial_positions();
    let mut ws = FreeFourBar::workspace();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0)?;
    let mut reference = Dopri5::new(Dopri5Options::default().with_rtol(1e-12).with_atol(1e-14));
    let (_, _, exact, _) = one(&m, &mut ws, &q, &mut reference)?;
    let mut runs = Vec::new();
    let mut record = |method, setting, (steps, seconds, last, drift): (u64, f64, f64, f64)| {
        runs.push(Run { method, setting, steps, seconds, error: (last - exact).abs(), energy_drift: drift });
    };
    for h in [4e-3, 2e-3, 1e-3, 5e-4] {
        record("RK4 (h)", h, one(&m, &mut ws, &q, &mut Rk4::new(Rk4Options::default().with_step(h)))?);
    }
    for rtol in [1e-4, 1e-6, 1e-8, 1e-10] {
        record(
            "DOPRI5 (rtol)",
            rtol,
            one(&m, &mut ws, &q, &mut Dopri5::new(Dopri5Options::default().with_rtol(rtol).with_atol(rtol * 1e-2)))?,
        );
    }
    for h in [4e-3, 2e-3, 1e-3] {
        let options = GeneralizedAlphaOptions::default().with_step(h).with_rho_infinity(0.9);
        record("generalized-α (h)", h, one(&m, &mut ws, &q, &mut FreeFourBar::generalized_alpha(options))?);
    }
    if print {
        println!("free four-bar, 2 s from rest; error of the rocker angle at 2 s against DOPRI5 at rtol 1e-12");
        println!("{:<20} {:>9} {:>7} {:>11} {:>11} {:>13}", "method", "setting", "steps", "time (µs)", "error (rad)", "|ΔE| (J)");
        for r in &runs {
            println!(
                "{:<20} {:>9.0e} {:>7} {:>11.1} {:>11.2e} {:>13.2e}",
                r.method,
                r.setting,
                r.steps,
                r.seconds * 1e6,
                r.error,
                r.energy_drift
            );
        }
    }
    Ok(runs)
}

/// The 2 s of motion `run` compares, released from rest, with DOPRI5 at rtol 1e-10, for the
/// showcase's pictures: 101 frames, 20 ms apart.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = FreeFourBar::default();
    let mut q = m.initial_positions();
    let mut ws = FreeFourBar::workspace();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0)?;
    let options = SimulationOptions::default().with_correction(Correction::projection());
    let times: Vec<f64> = (0..=100).map(|k| k as f64 * T_END / 100.0).collect();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    let mut animation = mbd::Animation::new::<FreeFourBar>(&m.params()).title("Free four-bar released from rest under gravity");
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &[0.0; FreeFourBar::NV])
        .times(&times)
        .options(options)
        .run(&mut ws, |s| animation.frame(s.point.t, &s.point.q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("free_four_bar: {e}");
        std::process::exit(1);
    }
}

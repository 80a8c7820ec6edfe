//! Tolerance proportionality (issue 39, item 4): each adaptive method on each case at
//! rtol = atol ∈ {1e-4, 1e-6, 1e-8, 1e-10}, with the default drift control (projection), and
//! the error: the largest over the output times of ‖q − q_ref‖∞ / max(1, ‖q_ref‖∞)
//! (angles in rad), over the case's output times up to a horizon (the 1 s for the
//! 4-link chain, whose motion is chaotic: over its study's 2 s any error grows by orders of
//! magnitude whatever the method). The factor error/rtol says how well a method delivers what
//! it is asked; where the error is below the reference's resolution the factor is not resolved.

use std::fmt::Write;
use std::time::Instant;

use mbd::prelude::*;

use crate::sweep::{output_times, Case, Reference};

/// The tolerances (rtol = atol).
pub const TOLERANCES: [f64; 4] = [1e-4, 1e-6, 1e-8, 1e-10];

/// The adaptive methods.
const METHODS: [&str; 7] = ["DOPRI5", "DOP853", "gen-α ρ∞=0.8, per step", "gen-α ρ∞=0.8, per unit time", "BDF", "Radau5", "Auto"];

/// A run's relative error and wall time (ms), or why it failed.
type Run = Result<(f64, f64), String>;

/// One case's errors: per method, per tolerance, the relative error (or why there is none).
pub struct Row {
    pub case: &'static str,
    /// The last output time compared (s).
    pub horizon: f64,
    /// The reference's resolution, relative like the errors.
    pub resolution: f64,
    /// Why the reference was not cross-checked against CasADi, where it was not (its
    /// resolution is then DOPRI5's difference alone).
    pub unchecked: Option<String>,
    /// Per method, per tolerance: the relative error and the run's wall time (ms), or why it
    /// failed.
    pub errors: Vec<(&'static str, Vec<Run>)>,
}

/// Runs every method at every tolerance on `case`, over its output times up to `horizon`.
pub fn measure<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    case: &Case<'_, M, NQ, NV>,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    reference: &Reference<NQ>,
    horizon: f64,
) -> Row
where
    M: NewtonMatrix<f64, NQ, NV, NC>,
{
    let times: Vec<f64> = output_times(case.t_end).into_iter().filter(|&t| t <= horizon + 1e-12).collect();
    let scale = reference.q.iter().fold(1.0f64, |s, q| q.iter().fold(s, |s, x| s.max(x.abs())));
    let mut errors = Vec::new();
    for method in METHODS {
        let runs = TOLERANCES
            .iter()
            .map(|&tol| match method {
                "DOPRI5" => error(case, ws, reference, &times, &mut Dopri5::new(Dopri5Options::default().with_rtol(tol).with_atol(tol))),
                "DOP853" => error(case, ws, reference, &times, &mut Dop853::new(Dop853Options::default().with_rtol(tol).with_atol(tol))),
                "BDF" => error(case, ws, reference, &times, &mut Bdf::new(BdfOptions::default().with_rtol(tol).with_atol(tol))),
                "Radau5" => error(case, ws, reference, &times, &mut Radau5::new(Radau5Options::default().with_rtol(tol).with_atol(tol))),
                "Auto" => error(case, ws, reference, &times, &mut Auto::new(AutoOptions::default().with_rtol(tol).with_atol(tol))),
                "gen-α ρ∞=0.8, per step" | "gen-α ρ∞=0.8, per unit time" => {
                    let per_unit_time = method.ends_with("per unit time");
                    let control = ErrorControl::default().with_rtol(tol).with_atol(tol).with_per_unit_time(per_unit_time);
                    let options = GeneralizedAlphaOptions::default().with_error_control(Some(control));
                    error(case, ws, reference, &times, &mut GeneralizedAlpha::new(options))
                }
                _ => unreachable!("{method} is in METHODS"),
            })
            .collect();
        errors.push((method, runs));
    }
    let unchecked = reference.casadi.as_ref().err().cloned();
    Row { case: case.name, horizon, resolution: reference.uncertainty / scale, unchecked, errors }
}

/// The run's error as the issue defines it, or its error message.
fn error<M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    case: &Case<'_, M, NQ, NV>,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    reference: &Reference<NQ>,
    times: &[f64],
    integrator: &mut I,
) -> Run
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
    I: Integrator<f64, M, NQ, NV, NC, N, NS>,
{
    let (mut worst, mut k) = (0.0f64, 0);
    let start = Instant::now();
    Simulation::new(case.mechanism, integrator)
        .start(0.0, &case.q0, &case.v0)
        .times(times)
        .run(ws, |s| {
            let r = &reference.q[k];
            let scale = r.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            let d = s.point.q.iter().zip(r).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            worst = worst.max(d / scale);
            k += 1;
        })
        .map_err(|e| match e {
            SimulationError::ToleranceBelowResolution { t, .. } => format!("at t = {t:.2e} s: `ToleranceBelowResolution`"),
            e => e.to_string(),
        })?;

    Ok((worst, start.elapsed().as_secs_f64() * 1e3))
}

/// The table, a page of its own (`proportionality.md`, dated `today` on `machine`): per case
/// and method, error/rtol and the run's time at each tolerance, and the largest resolved factor.
pub fn markdown(rows: &[Row], today: &str, machine: &str) -> String {
    let mut out = String::new();
    writeln!(
        out,
        "# Tolerance proportionality (rtol = atol, projection)\n\n`cargo run --release -p mbd-study -- proportionality`, {today} on {machine}. Error: the largest over the 50 output times of ‖q − q_ref‖∞ / max(1, ‖q_ref‖∞), against the case's reference (`study.md`); each cell is error / rtol at rtol = {}, then the run's wall time (one run, one thread); \"<\" where the error is below the reference's resolution (the factor is then at most the one shown). The last column is the largest resolved factor: what the method delivers over the range.\n",
        TOLERANCES.iter().map(|t| format!("{t:.0e}")).collect::<Vec<_>>().join(", ")
    )
    .unwrap();
    write!(out, "| case (horizon) | method |").unwrap();
    for t in TOLERANCES {
        write!(out, " {t:.0e} |").unwrap();
    }
    writeln!(out, " largest |\n|---|---|{}---|", "---|".repeat(TOLERANCES.len())).unwrap();
    for row in rows {
        for (method, runs) in &row.errors {
            write!(out, "| {} ({} s) | {method} |", row.case, row.horizon).unwrap();
            let mut largest: Option<f64> = None;
            for (run, tol) in runs.iter().zip(TOLERANCES) {
                let cell = match run {
                    Ok((e, ms)) if *e < row.resolution => format!("< {} · {}", factor(row.resolution / tol), milliseconds(*ms)),
                    Ok((e, ms)) => {
                        largest = Some(largest.map_or(e / tol, |l| l.max(e / tol)));
                        format!("{} · {}", factor(e / tol), milliseconds(*ms))
                    }
                    Err(message) => format!("failed: {}", message.chars().take(60).collect::<String>()),
                };
                write!(out, " {cell} |").unwrap();
            }
            writeln!(out, " {} |", largest.map_or("—".to_string(), |l| format!("**{}**", factor(l)))).unwrap();
        }
    }
    for row in rows {
        if let Some(why) = &row.unchecked {
            writeln!(
                out,
                "\n{}: the reference is **not cross-checked against CasADi** ({why}); its resolution is DOPRI5's difference alone.",
                row.case
            )
            .unwrap();
        }
    }
    out
}

/// A factor to two significant digits.
fn factor(f: f64) -> String {
    if f >= 100.0 {
        format!("{f:.0}")
    } else if f >= 0.1 {
        format!("{f:.2}")
    } else {
        format!("{f:.1e}")
    }
}

/// A wall time in ms to two significant digits.
fn milliseconds(ms: f64) -> String {
    if ms >= 10.0 {
        format!("{ms:.0} ms")
    } else {
        format!("{ms:.2} ms")
    }
}

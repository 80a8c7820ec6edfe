//! What a user would pick instead, in the same run: MuJoCo's RK4 on the pendulum chains.
//!
//! `mbd-study/mujoco_chain.py` builds each chain in MuJoCo's joint coordinates (hinges, the same
//! links, masses and inertias), times its C loop over the whole run at each of RK4's steps and
//! returns the bodies' coordinates at the study's output times; this file measures them against
//! the case's reference exactly as the mbd runs are measured (max |Δq| over the coordinates and
//! the outputs, angles compared modulo 2π), with ‖Φ‖∞ of mbd's constraints at MuJoCo's
//! coordinates and MuJoCo's own T + V. The Python environment is the peer benchmarks' pinned one
//! (`mbd-bench/peers/ensure_env.sh`, MuJoCo 4.0.0, made on first use); where it cannot be made,
//! each row says why.

use std::f64::consts::PI;
use std::path::Path;
use std::process::Command;

use mbd::prelude::*;
use serde_json::Value;

use crate::sweep::{output_times, pinned_python, Case, Drift, Measured, Method, Reference, Row, OUTPUTS, STEPS_RK4};

/// Repeats of each timed MuJoCo run (the median is reported).
const REPEATS: usize = 3;

/// MuJoCo's RK4 at each of [`STEPS_RK4`] on a chain of `links` links (mbd's coordinates
/// l0.x, l0.y, l0.phi, l1.x, …).
pub fn mujoco_chain<M, const NQ: usize, const NV: usize, const NC: usize>(
    case: &Case<'_, M, NQ, NV>,
    links: usize,
    reference: &Reference<NQ>,
) -> Vec<Row>
where
    M: Kinematics<f64, NQ, NV, NC>,
{
    assert_eq!(NQ, 3 * links, "{}: a chain of {links} planar links", case.name);
    assert!(M::COORDINATE_NAMES.chunks(3).all(|c| c[2].ends_with(".phi")), "{}: (x, y, φ) per link", case.name);
    let row = |setting: f64, outcome| Row { case: case.name, method: Method::MuJoCoRk4, setting, drift: Drift::None, outcome };
    let runs = match run_mujoco(case.name, links, case.t_end) {
        Ok(runs) => runs,
        Err(e) => return STEPS_RK4.iter().map(|&h| row(h, Err(format!("MuJoCo did not run: {e}")))).collect(),
    };
    let mut rows = Vec::new();
    for (&h, run) in STEPS_RK4.iter().zip(&runs) {
        rows.push(row(h, measure(case, reference, run)));
    }
    rows
}

/// One MuJoCo run measured against the reference.
fn measure<M, const NQ: usize, const NV: usize, const NC: usize>(
    case: &Case<'_, M, NQ, NV>,
    reference: &Reference<NQ>,
    run: &Value,
) -> Result<Measured, String>
where
    M: Kinematics<f64, NQ, NV, NC>,
{
    let number = |v: &Value| v.as_f64().ok_or("MuJoCo's output holds a non-number");
    if let Some(failure) = run["failure"].as_str() {
        return Err(failure.into());
    }
    let qs = run["q"].as_array().ok_or("MuJoCo's output has no q")?;
    let energies = run["energy"].as_array().ok_or("MuJoCo's output has no energy")?;
    if qs.len() != OUTPUTS || energies.len() != OUTPUTS {
        return Err(format!("MuJoCo gave {} outputs, not {OUTPUTS}", qs.len()));
    }
    let e0 = number(&run["energy0"])?;
    let (mut error, mut constraint, mut energy) = (0.0f64, 0.0f64, 0.0f64);
    for (k, (q, t)) in qs.iter().zip(output_times(case.t_end)).enumerate() {
        let values = q.as_array().ok_or("MuJoCo's q is not a list")?;
        let q: [f64; NQ] =
            values.iter().map(number).collect::<Result<Vec<f64>, _>>()?.try_into().map_err(|_| "MuJoCo's q has the wrong length")?;
        for (i, (&ours, &theirs)) in reference.q[k].iter().zip(&q).enumerate() {
            let mut d = theirs - ours;
            if i % 3 == 2 {
                // φ is MuJoCo's atan2 in (−π, π]; the reference's winds on.
                d = (d + PI).rem_euclid(2.0 * PI) - PI;
            }
            error = error.max(d.abs());
        }
        let mut phi = [0.0; NC];
        case.mechanism.constraints(&q, t, &mut phi);
        constraint = phi.iter().fold(constraint, |a, x| a.max(x.abs()));
        energy = energy.max((number(&energies[k])? - e0).abs());
    }
    let steps = run["steps"].as_u64().ok_or("MuJoCo's output has no step count")?;
    Ok(Measured {
        error,
        constraint,
        energy,
        seconds: number(&run["seconds"])?,
        repeats: REPEATS,
        steps,
        evaluations: 4 * steps,
        newton: 0,
    })
}

/// Runs `mujoco_chain.py` in the peers' pinned environment; its runs, one per step of RK4.
fn run_mujoco(name: &str, links: usize, t_end: f64) -> Result<Vec<Value>, String> {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let python = pinned_python(&here.join("../mbd-bench/peers/ensure_env.sh"))?;
    let input = std::env::temp_dir().join(format!("mbd-study-mujoco-{name}.json"));
    let spec = serde_json::json!({ "links": links, "t_end": t_end, "outputs": OUTPUTS, "steps": STEPS_RK4, "repeats": REPEATS });
    std::fs::write(&input, spec.to_string()).map_err(|e| e.to_string())?;
    let out = Command::new(python).arg(here.join("mujoco_chain.py")).arg(&input).output().map_err(|e| e.to_string())?;
    if !out.status.success() {
        return Err(format!("mujoco_chain.py failed: {}", String::from_utf8_lossy(&out.stderr).trim()));
    }
    let value: Value = serde_json::from_slice(&out.stdout).map_err(|e| format!("mujoco_chain.py printed no JSON: {e}"))?;
    let runs = value["runs"].as_array().ok_or("mujoco_chain.py printed no runs")?.clone();
    if runs.len() != STEPS_RK4.len() {
        return Err(format!("mujoco_chain.py gave {} runs for {} steps", runs.len(), STEPS_RK4.len()));
    }
    Ok(runs)
}

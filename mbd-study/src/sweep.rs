//! One case's sweep: every integrator over its settings, each with every drift control, timed
//! and checked against the case's reference run.

use std::process::Command;
use std::time::Instant;

use indicatif::ProgressBar;
use mbd::prelude::*;
use mbd::{project, Sample};

/// A mechanism, its start and its horizon.
pub struct Case<'a, M, const NQ: usize, const NV: usize> {
    /// Short name (file names, CSV).
    pub name: &'static str,
    pub mechanism: &'a M,
    pub q0: [f64; NQ],
    pub v0: [f64; NV],
    /// End time (s).
    pub t_end: f64,
    /// Non-conservative forces: the energy error is then that of the balance T + V − W
    /// (work tracked, which costs one more evaluation of h per stage).
    pub track_work: bool,
}

/// The integrators of the sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    Rk4,
    Dopri5,
    Dop853,
    GeneralizedAlpha {
        rho_infinity: f64,
    },
    /// Variable-step generalized-α ([`ErrorControl`]) over relative tolerances, its error bounded
    /// per step (`per_unit_time` off: the cheaper control, which `study.md` has measured since
    /// 2026-11-24; both are in `proportionality.md`).
    AdaptiveGeneralizedAlpha {
        rho_infinity: f64,
    },
    /// Variable-order BDF ([`Bdf`]) over relative tolerances: the stiff method.
    Bdf,
    /// Radau IIA of order 5 ([`Radau5`]) over relative tolerances: the stiff method of high order.
    Radau5,
    /// DOPRI5, or BDF where the model is stiff ([`Auto`]), over relative tolerances.
    Auto,
    /// MuJoCo's RK4 in joint coordinates, on the chains only (`peers.rs`).
    MuJoCoRk4,
}

impl Method {
    pub fn label(self) -> String {
        match self {
            Method::Rk4 => "RK4".into(),
            Method::Dopri5 => "DOPRI5".into(),
            Method::Dop853 => "DOP853".into(),
            Method::GeneralizedAlpha { rho_infinity } => format!("gen-α ρ∞={rho_infinity}"),
            Method::AdaptiveGeneralizedAlpha { rho_infinity } => format!("adaptive gen-α ρ∞={rho_infinity}"),
            Method::Bdf => "BDF".into(),
            Method::Radau5 => "Radau5".into(),
            Method::Auto => "Auto".into(),
            Method::MuJoCoRk4 => "MuJoCo RK4".into(),
        }
    }
    /// What the setting is: a step (s) or a relative tolerance.
    pub fn setting_name(self) -> &'static str {
        match self {
            Method::Dopri5 | Method::Dop853 | Method::AdaptiveGeneralizedAlpha { .. } | Method::Bdf | Method::Radau5 | Method::Auto => {
                "rtol"
            }
            _ => "h (s)",
        }
    }
}

/// The drift controls of the sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Drift {
    None,
    Baumgarte,
    Projection,
    Partitioning,
}

pub const DRIFTS: [Drift; 4] = [Drift::None, Drift::Baumgarte, Drift::Projection, Drift::Partitioning];

impl Drift {
    pub fn label(self) -> &'static str {
        match self {
            Drift::None => "none",
            Drift::Baumgarte => "Baumgarte α=β=5",
            Drift::Projection => "projection",
            Drift::Partitioning => "partitioning",
        }
    }
    fn options(self, track_work: bool) -> SimulationOptions<f64> {
        let (dynamics, correction) = match self {
            Drift::None => (DynamicsOptions::without_stabilization(), Correction::None),
            Drift::Baumgarte => (DynamicsOptions::default(), Correction::None),
            Drift::Projection => (DynamicsOptions::without_stabilization(), Correction::projection()),
            Drift::Partitioning => (DynamicsOptions::without_stabilization(), Correction::partitioning()),
        };
        SimulationOptions::default().with_dynamics(dynamics).with_correction(correction).with_track_work(track_work)
    }
}

/// The settings swept, cheapest first: RK4's steps (s), DOPRI5's and DOP853's relative
/// tolerances (absolute: 1e-2 of it), generalized-α's steps and ρ∞ (1: no numerical damping).
pub const STEPS_RK4: [f64; 8] = [2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4];
pub const TOLERANCES_DOPRI5: [f64; 10] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];
pub const TOLERANCES_DOP853: [f64; 8] = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12];
pub const STEPS_GENERALIZED_ALPHA: [f64; 7] = [1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4];
pub const RHO_INFINITY: [f64; 3] = [0.5, 0.8, 1.0];
/// Variable-step generalized-α's relative tolerances (absolute: 1e-2 of it), at the default ρ∞.
pub const TOLERANCES_GENERALIZED_ALPHA: [f64; 7] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9];
/// BDF's relative tolerances (absolute: 1e-2 of it).
pub const TOLERANCES_BDF: [f64; 8] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
/// Radau5's relative tolerances (absolute: 1e-2 of it).
pub const TOLERANCES_RADAU5: [f64; 8] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];

/// `Auto`'s relative tolerances (absolute: 1e-2 of it; at 1e-8 its defaults).
pub const TOLERANCES_AUTO: [f64; 4] = [1e-4, 1e-6, 1e-8, 1e-10];

/// The methods with their settings.
pub fn methods() -> Vec<(Method, Vec<f64>)> {
    let mut list =
        vec![(Method::Rk4, STEPS_RK4.to_vec()), (Method::Dopri5, TOLERANCES_DOPRI5.to_vec()), (Method::Dop853, TOLERANCES_DOP853.to_vec())];
    for rho_infinity in RHO_INFINITY {
        list.push((Method::GeneralizedAlpha { rho_infinity }, STEPS_GENERALIZED_ALPHA.to_vec()));
    }
    list.push((Method::AdaptiveGeneralizedAlpha { rho_infinity: 0.8 }, TOLERANCES_GENERALIZED_ALPHA.to_vec()));
    list.push((Method::Bdf, TOLERANCES_BDF.to_vec()));
    list.push((Method::Radau5, TOLERANCES_RADAU5.to_vec()));
    list.push((Method::Auto, TOLERANCES_AUTO.to_vec()));
    list
}

/// Runs per case (for the progress bar).
pub fn runs_per_case() -> u64 {
    methods().iter().map(|(_, s)| s.len() as u64).sum::<u64>() * DRIFTS.len() as u64
}

/// A setting whose run takes longer than this (s) ends its series: the smaller steps or
/// tighter tolerances after it would take longer still.
pub const RUN_BUDGET_S: f64 = 2.0;
/// Output times per run (where the errors in q, Φ and energy are sampled).
pub const OUTPUTS: usize = 50;

/// [`OUTPUTS`] times evenly spaced over (0, t_end].
pub fn output_times(t_end: f64) -> Vec<f64> {
    (1..=OUTPUTS).map(|k| t_end * k as f64 / OUTPUTS as f64).collect()
}

/// What one run measured.
#[derive(Clone, Debug)]
pub struct Measured {
    /// max over the output times and the coordinates of |q_i(t) − q_ref,i(t)| (m, rad; spatial:
    /// m and Euler parameters).
    pub error: f64,
    /// Largest ‖Φ‖∞ at the outputs (m).
    pub constraint: f64,
    /// Largest |E(t) − E(0)| at the outputs (J), E = T + V (− W with work tracked).
    pub energy: f64,
    /// Median wall time of the repeats (s).
    pub seconds: f64,
    pub repeats: usize,
    pub steps: u64,
    /// Evaluations of v̇ (explicit) or of the Newton residual (generalized-α).
    pub evaluations: u64,
    /// Newton iterations (generalized-α; 0 for explicit methods).
    pub newton: u64,
}

/// One row of the study.
#[derive(Clone, Debug)]
pub struct Row {
    pub case: &'static str,
    pub method: Method,
    pub setting: f64,
    pub drift: Drift,
    /// The measurement, or why there is none (the run's error, or the budget).
    pub outcome: Result<Measured, String>,
}

/// The reference motion at the output times and how far two independent integrations are from
/// it.
pub struct Reference<const NQ: usize> {
    /// q at each of the [`OUTPUTS`] output times ([`output_times`]).
    pub q: Vec<[f64; NQ]>,
    /// The larger of max |q_DOP853 − q_DOPRI5| over the output times and max |q_DOP853 −
    /// q_CVODES| at t_end: the floor below which errors are not resolved.
    pub uncertainty: f64,
    /// max |q_DOP853 − q_DOPRI5| over the output times (DOPRI5 at rtol 1e-12).
    pub dopri5: f64,
    pub seconds: f64,
    /// max |q_DOP853 − q_CVODES| at t_end, CasADi's CVODES (Adams, rtol 1e-12) on the oracle's
    /// rebuild of the model; or why it was not run.
    pub casadi: Result<f64, String>,
}

/// A consistent start (the mass-weighted projection to 1e-13), shared by every run.
pub fn consistent_start<M, const NQ: usize, const NV: usize, const NC: usize>(m: &M, q: &mut [f64; NQ], v: &mut [f64; NV])
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
{
    project(m, 0.0, q, v, &DynamicsOptions::without_stabilization(), 1e-13, 30).expect("the case's start projects onto its constraints");
}

/// DOP853 at rtol 1e-13 and DOPRI5 at 1e-12, neither corrected: the first is the reference, their
/// difference its uncertainty.
pub fn reference<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    case: &Case<'_, M, NQ, NV>,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
) -> Reference<NQ>
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
{
    let options = SimulationOptions::default().with_dynamics(DynamicsOptions::without_stabilization()).with_correction(Correction::None);
    let fail = |e: SimulationError| -> ! { panic!("{}: the reference run fails: {e}", case.name) };
    let times = output_times(case.t_end);
    let start = Instant::now();
    let (mut q, mut q2) = (Vec::new(), Vec::new());
    let tight = Dop853Options::default().with_rtol(1e-13).with_atol(1e-15);
    Simulation::new(case.mechanism, &mut Dop853::new(tight))
        .start(0.0, &case.q0, &case.v0)
        .times(&times)
        .options(options)
        .run(ws, |s| q.push(s.point.q))
        .unwrap_or_else(|e| fail(e));
    let seconds = start.elapsed().as_secs_f64();
    let check = Dopri5Options::default().with_rtol(1e-12).with_atol(1e-14);
    Simulation::new(case.mechanism, &mut Dopri5::new(check))
        .start(0.0, &case.q0, &case.v0)
        .times(&times)
        .options(options)
        .run(ws, |s| q2.push(s.point.q))
        .unwrap_or_else(|e| fail(e));
    let end = q.last().expect("OUTPUTS > 0");
    let casadi = casadi_end(case).map(|theirs| max_difference(end, &theirs));
    let dopri5 = q.iter().zip(&q2).map(|(a, b)| max_difference(a, b)).fold(0.0, f64::max);
    let uncertainty = dopri5.max(*casadi.as_ref().unwrap_or(&0.0));
    Reference { q, uncertainty, dopri5, seconds, casadi }
}

/// q(t_end) by CasADi's CVODES at rtol 1e-12 on the oracle's independent rebuild of the model
/// (`tests/oracle/mbd_oracle/integrate.py`), in the oracle's pinned Python environment (made by
/// `tests/oracle/ensure_env.sh` on first use).
/// The rebuild takes the parameters at their defaults: a case may set only parameters that
/// start it (the top's spin), never ones of its dynamics.
fn casadi_end<M: Mechanism, const NQ: usize, const NV: usize>(case: &Case<'_, M, NQ, NV>) -> Result<[f64; NQ], String> {
    let oracle = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/oracle");
    let python = pinned_python(&oracle.join("ensure_env.sh"))?;
    let input = std::env::temp_dir().join(format!("mbd-study-{}.json", case.name));
    let data = format!(
        "{{\"model\": {}, \"q0\": {:?}, \"v0\": {:?}, \"t_end\": {:?}, \"rtol\": 1e-12, \"atol\": 1e-14}}",
        M::MODEL_JSON,
        case.q0,
        case.v0,
        case.t_end
    );
    std::fs::write(&input, data).map_err(|e| e.to_string())?;
    let out =
        Command::new(python).args(["-m", "mbd_oracle.integrate"]).arg(&input).current_dir(&oracle).output().map_err(|e| e.to_string())?;
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let line = text.lines().find_map(|l| l.strip_prefix("q_end ")).ok_or_else(|| {
        // CasADi's last line says why (e.g. CV_TOO_MUCH_WORK where the Schur complement turns singular).
        format!("CVODES failed: {}", text.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("no output"))
    })?;
    let values: Vec<f64> = line.split_whitespace().map(|x| x.parse().unwrap_or(f64::NAN)).collect();
    values.try_into().map_err(|v: Vec<f64>| format!("CVODES gave {} coordinates, not {NQ}", v.len()))
}

/// Runs a pinned environment's `ensure_env.sh` (which creates it on first use) and returns the
/// interpreter it prints on its last line, or why there is none.
pub fn pinned_python(ensure_env: &std::path::Path) -> Result<String, String> {
    let setup = Command::new("bash").arg(ensure_env).output().map_err(|e| format!("bash: {e}"))?;
    let stdout = String::from_utf8_lossy(&setup.stdout);
    let python = stdout.lines().rev().find(|l| !l.trim().is_empty()).map(str::trim).unwrap_or_default();
    if !setup.status.success() || python.is_empty() {
        return Err(format!(
            "{} could not set up its Python environment: {}",
            ensure_env.display(),
            String::from_utf8_lossy(&setup.stderr)
        ));
    }
    Ok(python.to_string())
}

pub fn max_difference<const NQ: usize>(a: &[f64; NQ], b: &[f64; NQ]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// Every method, setting and drift control on `case`.
pub fn sweep<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    case: &Case<'_, M, NQ, NV>,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    reference: &Reference<NQ>,
    progress: &ProgressBar,
) -> Vec<Row>
where
    M: NewtonMatrix<f64, NQ, NV, NC>,
{
    let mut rows = Vec::new();
    for (method, settings) in methods() {
        for drift in DRIFTS {
            let mut over_budget = false;
            for &setting in &settings {
                progress.set_message(format!(
                    "{}: {} {} = {setting:e}, {}",
                    case.name,
                    method.label(),
                    method.setting_name(),
                    drift.label()
                ));
                let outcome = if over_budget {
                    Err(format!("skipped: a cheaper setting took over {RUN_BUDGET_S} s"))
                } else {
                    let measured = one(case, ws, reference, method, setting, drift);
                    if let Ok(m) = &measured {
                        over_budget = m.seconds > RUN_BUDGET_S;
                    }
                    measured
                };
                rows.push(Row { case: case.name, method, setting, drift, outcome });
                progress.inc(1);
            }
        }
    }
    rows
}

fn one<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    case: &Case<'_, M, NQ, NV>,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    reference: &Reference<NQ>,
    method: Method,
    setting: f64,
    drift: Drift,
) -> Result<Measured, String>
where
    M: NewtonMatrix<f64, NQ, NV, NC>,
{
    match method {
        Method::Rk4 => {
            timed(case, ws, reference, drift, || Rk4::new(Rk4Options::default().with_step(setting)), |_, stats| (4 * stats.steps, 0))
        }
        Method::Dopri5 => {
            let options = Dopri5Options::default().with_rtol(setting).with_atol(setting * 1e-2);
            timed(case, ws, reference, drift, || Dopri5::new(options), |i, _| (i.evaluations, 0))
        }
        Method::Dop853 => {
            let options = Dop853Options::default().with_rtol(setting).with_atol(setting * 1e-2);
            timed(case, ws, reference, drift, || Dop853::new(options), |i, _| (i.evaluations, 0))
        }
        Method::GeneralizedAlpha { rho_infinity } => {
            let options = GeneralizedAlphaOptions::default().with_step(setting).with_rho_infinity(rho_infinity);
            timed(case, ws, reference, drift, || GeneralizedAlpha::new(options), |i, _| (i.total_iterations, i.total_iterations))
        }
        Method::AdaptiveGeneralizedAlpha { rho_infinity } => {
            let control = ErrorControl::default().with_rtol(setting).with_atol(setting * 1e-2).with_per_unit_time(false);
            let options = GeneralizedAlphaOptions::default().with_rho_infinity(rho_infinity).with_error_control(Some(control));
            timed(case, ws, reference, drift, || GeneralizedAlpha::new(options), |i, _| (i.total_iterations, i.total_iterations))
        }
        Method::Bdf => {
            let options = BdfOptions::default().with_rtol(setting).with_atol(setting * 1e-2);
            timed(case, ws, reference, drift, || Bdf::new(options), |i, _| (i.iterations, i.iterations))
        }
        Method::Radau5 => {
            let options = Radau5Options::default().with_rtol(setting).with_atol(setting * 1e-2);
            // each Newton iteration evaluates the residual at the three stages
            timed(case, ws, reference, drift, || Radau5::new(options), |i, _| (3 * i.iterations, i.iterations))
        }
        Method::Auto => {
            let options = AutoOptions::default().with_rtol(setting).with_atol(setting * 1e-2);
            timed(
                case,
                ws,
                reference,
                drift,
                || Auto::new(options),
                |i, _| (i.explicit.evaluations + i.stiff.iterations, i.stiff.iterations),
            )
        }
        Method::MuJoCoRk4 => Err("MuJoCo runs in peers.rs".into()),
    }
}

/// Runs `make()` to the end time, repeated while cheap (5 runs under 0.05 s, 3 under 0.5 s),
/// and measures the last one against the reference; the time is the median.
fn timed<M, I, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    case: &Case<'_, M, NQ, NV>,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    reference: &Reference<NQ>,
    drift: Drift,
    make: impl Fn() -> I,
    counts: impl Fn(&I, &Statistics) -> (u64, u64),
) -> Result<Measured, String>
where
    M: ForwardDynamics<f64, NQ, NV, NC>,
    I: Integrator<f64, M, NQ, NV, NC, N, NS>,
{
    let options = drift.options(case.track_work);
    let times = output_times(case.t_end);
    let m = case.mechanism;
    let energy = |s: &Sample<f64, NQ, NV, NC>| if case.track_work { s.energy.balance() } else { s.energy.kinetic + s.energy.potential };
    let e0 = kinetic_energy(m, &case.q0, &case.v0) + m.potential_energy(&case.q0, 0.0);
    let mut seconds = Vec::new();
    loop {
        let mut integrator = make();
        let (mut constraint, mut energy_error, mut error, mut k) = (0.0f64, 0.0f64, 0.0f64, 0);
        let start = Instant::now();
        let stats = Simulation::new(m, &mut integrator)
            .start(0.0, &case.q0, &case.v0)
            .times(&times)
            .options(options)
            .run(ws, |s| {
                let mut phi = [0.0; NC];
                m.constraints(&s.point.q, s.point.t, &mut phi);
                constraint = phi.iter().fold(constraint, |a, x| a.max(x.abs()));
                energy_error = energy_error.max((energy(s) - e0).abs());
                error = error.max(max_difference(&s.point.q, &reference.q[k]));
                k += 1;
            })
            .map_err(|e| e.to_string())?;
        seconds.push(start.elapsed().as_secs_f64());
        let total: f64 = seconds.iter().sum();
        let wanted = if total < 0.05 {
            5
        } else if total < 0.5 {
            3
        } else {
            1
        };
        if seconds.len() >= wanted {
            seconds.sort_by(f64::total_cmp);
            let (evaluations, newton) = counts(&integrator, &stats);
            return Ok(Measured {
                error,
                constraint,
                energy: energy_error,
                seconds: seconds[seconds.len() / 2],
                repeats: seconds.len(),
                steps: stats.steps,
                evaluations,
                newton,
            });
        }
    }
}

//! What accuracy costs in time: every integrator (RK4 over steps, DOPRI5 and DOP853 over
//! tolerances, generalized-α over steps and ρ∞, and variable-step over tolerances, BDF over
//! tolerances) with every
//! drift control (none, Baumgarte, projection, partitioning) on mechanisms of several kinds: each
//! run's largest error over 50 output times against a tight reference, its constraint and energy
//! errors, CPU time (median of repeats), evaluations and Newton iterations. On the chains,
//! MuJoCo's RK4 in the same run against the same reference (`peers.rs`).
//!
//! Run: `cargo run --release -p mbd-study` (about 8 minutes on 2 cores). Writes
//! `mbd-study/results/study.csv` (every run), `study.md` (the tables), `proportionality.md`
//! (each adaptive method's error over its tolerance) and one `<case>.svg` per case (log-log
//! error against CPU time, a panel per drift control). `cargo run --release -p mbd-study --
//! proportionality` writes `proportionality.md` alone, from the six cases it uses.
//!
//! The reference of each case is DOP853 at rtol 1e-13 without drift correction, checked against
//! DOPRI5 at rtol 1e-12: their difference is reported as the reference's uncertainty, and errors
//! below it are not resolved; and against CasADi's CVODES (Adams, rtol 1e-12) on the oracle's
//! independent rebuild of the model (`tests/oracle/mbd_oracle/integrate.py`, in the oracle's
//! pinned Python environment, made on first use).

mod cases;
mod exactness;
mod peers;
mod proportionality;
mod report;
mod sweep;

use std::path::PathBuf;

use indicatif::{ProgressBar, ProgressStyle};
use mbd::prelude::*;

use cases::*;
use report::CaseSummary;
use sweep::{Case, Reference, Row};

struct Study {
    rows: Vec<Row>,
    proportionality: Vec<proportionality::Row>,
    exactness: Vec<exactness::Row>,
    summaries: Vec<CaseSummary>,
    progress: ProgressBar,
    out: PathBuf,
    /// `mbd-study proportionality`: only the cases of the proportionality table, each with its
    /// start and reference and no sweep.
    only_proportionality: bool,
}

impl Study {
    /// Assembles `m`, makes its start consistent, runs the reference and the sweep (and, for a
    /// chain of `mujoco` links, MuJoCo's RK4 on it), plots, and (with `exact`) compares exact and
    /// finite-difference derivatives; returns the start and the reference.
    #[allow(clippy::too_many_arguments)]
    fn case<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &mut self,
        name: &'static str,
        title: &'static str,
        m: &M,
        ws: &mut Workspace<f64, NV, NC, N, NS>,
        t_end: f64,
        track_work: bool,
        exact: bool,
        mujoco: Option<usize>,
    ) -> ([f64; NQ], [f64; NV], Reference<NQ>)
    where
        M: NewtonMatrix<f64, NQ, NV, NC>,
    {
        let mut q0 = m.initial_positions();
        KinematicSolver::default().assemble(m, ws, &mut q0, 0.0).unwrap_or_else(|e| panic!("{name} assembles: {e}"));
        let mut v0 = m.initial_velocities();
        sweep::consistent_start(m, &mut q0, &mut v0);
        let case = Case { name, mechanism: m, q0, v0, t_end, track_work };
        self.progress.set_message(format!("{name}: reference"));
        let reference = sweep::reference(&case, ws);
        if self.only_proportionality {
            return (q0, v0, reference);
        }
        let mut rows = sweep::sweep(&case, ws, &reference, &self.progress);
        if let Some(links) = mujoco {
            self.progress.set_message(format!("{name}: MuJoCo's RK4"));
            rows.extend(peers::mujoco_chain(&case, links, &reference));
            self.progress.inc(sweep::STEPS_RK4.len() as u64);
        }
        let summary = CaseSummary {
            name,
            title,
            sizes: [NQ, NV, NC],
            t_end,
            reference_seconds: reference.seconds,
            uncertainty: reference.uncertainty,
            dopri5: reference.dopri5,
            casadi: reference.casadi.clone(),
        };
        if let Err(e) = report::plot(&summary, &rows, &self.out.join(format!("{name}.svg"))) {
            self.progress.println(format!("{name}: the plot failed: {e}"));
        }
        self.rows.extend(rows);
        self.summaries.push(summary);
        if exact {
            self.progress.set_message(format!("{name}: exact against finite-difference derivatives"));
            let start = exactness::Start { case: name, q0: &q0, v0: &v0, t_end, reference: &reference };
            self.exactness.extend(exactness::compare(m, ws, &start));
        }
        (q0, v0, reference)
    }

    /// Tolerance proportionality on a case already swept (its start and reference), over its
    /// output times up to `horizon` (s).
    #[allow(clippy::too_many_arguments)]
    fn proportional<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
        &mut self,
        name: &'static str,
        m: &M,
        ws: &mut Workspace<f64, NV, NC, N, NS>,
        (q0, v0, reference): ([f64; NQ], [f64; NV], Reference<NQ>),
        t_end: f64,
        horizon: f64,
    ) where
        M: NewtonMatrix<f64, NQ, NV, NC>,
    {
        self.progress.set_message(format!("{name}: tolerance proportionality"));
        let case = Case { name, mechanism: m, q0, v0, t_end, track_work: false };
        self.proportionality.push(proportionality::measure(&case, ws, &reference, horizon));
    }
}

fn main() {
    let only_proportionality = match std::env::args().nth(1).as_deref() {
        None => false,
        Some("proportionality") => true,
        Some(other) => {
            panic!("unknown argument {other:?}: run without one for the whole study, or with `proportionality` for its table alone")
        }
    };
    let out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results");
    std::fs::create_dir_all(&out).expect("create mbd-study/results");
    let cases = 12;
    let mujoco_cases = 3;
    let runs = if only_proportionality { 0 } else { cases * sweep::runs_per_case() + mujoco_cases * sweep::STEPS_RK4.len() as u64 };
    let progress = ProgressBar::new(runs);
    progress.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} runs  {msg}").expect("template").progress_chars("=> "),
    );
    let mut study = Study {
        rows: Vec::new(),
        proportionality: Vec::new(),
        exactness: Vec::new(),
        summaries: Vec::new(),
        progress,
        out: out.clone(),
        only_proportionality,
    };

    let m = FlywheelSliderCrank::default();
    let run = study.case(
        "flywheel_slider_crank",
        "slider-crank with a 2 kg·m² flywheel at 5 rev/s",
        &m,
        &mut FlywheelSliderCrank::workspace(),
        2.0,
        false,
        true,
        None,
    );
    study.proportional("flywheel_slider_crank", &m, &mut FlywheelSliderCrank::workspace(), run, 2.0, 2.0);
    let m = Chain4::default();
    let run =
        study.case("chain4", "pendulum chain of 4 links released horizontal", &m, &mut Chain4::workspace(), 2.0, false, true, Some(4));
    study.proportional("chain4", &m, &mut Chain4::workspace(), run, 2.0, 1.0);
    if !only_proportionality {
        without_proportionality(&mut study);
    }
    let m = FreeSpatialSliderCrank::default();
    let run = study.case(
        "spatial_slider_crank",
        "spatial slider-crank falling under gravity",
        &m,
        &mut FreeSpatialSliderCrank::workspace(),
        2.0,
        false,
        true,
        None,
    );
    study.proportional("spatial_slider_crank", &m, &mut FreeSpatialSliderCrank::workspace(), run, 2.0, 2.0);
    let m = StiffFlywheel::default();
    let run = study.case(
        "stiff_flywheel",
        "flywheel slider-crank with a follower on a 1e7 N/m overdamped mount (stiff: −1.6e4 1/s)",
        &m,
        &mut StiffFlywheel::workspace(),
        10.0,
        false,
        false,
        None,
    );
    study.proportional("stiff_flywheel", &m, &mut StiffFlywheel::workspace(), run, 10.0, 10.0);
    let m = HeavyTop::default();
    let run = study.case(
        "heavy_top_benchmark",
        "heavy-top benchmark, 150 rad/s (Brüls, Cardona & Arnold 2012; spatial)",
        &m,
        &mut HeavyTop::workspace(),
        2.0,
        false,
        false,
        None,
    );
    study.proportional("heavy_top_benchmark", &m, &mut HeavyTop::workspace(), run, 2.0, 2.0);
    let m = BumpStopQuarterCar::default();
    let run = study.case(
        "bump_stop",
        "quarter car at 20 m/s over a 10 cm bump into a 1e6 N/m bump stop (contacts located)",
        &m,
        &mut BumpStopQuarterCar::workspace(),
        2.0,
        true,
        false,
        None,
    );
    study.proportional("bump_stop", &m, &mut BumpStopQuarterCar::workspace(), run, 2.0, 2.0);
    study.progress.finish();

    let table = proportionality::markdown(&study.proportionality, &today(), &machine());
    std::fs::write(out.join("proportionality.md"), table).expect("write proportionality.md");
    if only_proportionality {
        println!("wrote {}", out.join("proportionality.md").display());
        return;
    }
    report::csv(&study.rows, &out.join("study.csv")).expect("write study.csv");
    let header = format!(
        "# What accuracy costs in time\n\n`cargo run --release -p mbd-study`, {} on {} ({} runs). Error: max |Δq| over the coordinates (m, rad; spatial Euler parameters) and the run's 50 output times, against the case's reference at the same times. CPU: median wall time of up to 5 repeats, one thread, 50 output times per run where ‖Φ‖∞ and the energy error (T + V, or the balance T + V − W with work tracked for the damped suspension) are sampled. All runs: `study.csv`. Tolerance proportionality: `proportionality.md`.",
        today(),
        machine(),
        study.rows.len()
    );
    let mut markdown = report::markdown(&study.summaries, &study.rows, &header);
    markdown.push_str(&exactness::markdown(&study.exactness));
    std::fs::write(out.join("study.md"), markdown).expect("write study.md");
    println!("wrote {}", out.display());
}

/// The cases that are not in the proportionality table.
fn without_proportionality(study: &mut Study) {
    let m = DoublePendulum::default();
    study.case(
        "double_pendulum",
        "double pendulum released horizontal (chaotic)",
        &m,
        &mut DoublePendulum::workspace(),
        1.0,
        false,
        true,
        None,
    );
    let m = Chain16::default();
    let (q0, v0, reference) =
        study.case("chain16", "pendulum chain of 16 links released horizontal", &m, &mut Chain16::workspace(), 2.0, false, true, Some(16));
    let m32 = Chain16F32::default();
    study.progress.set_message("chain16: f32 against f64");
    let start = exactness::Start { case: "chain16", q0: &q0, v0: &v0, t_end: 2.0, reference: &reference };
    study.exactness.extend(exactness::precision((&m32, &mut Chain16F32::workspace()), (&m, &mut Chain16::workspace()), &start));
    let m = Chain64::default();
    study.case("chain64", "pendulum chain of 64 links released horizontal", &m, &mut Chain64::workspace(), 1.0, false, false, Some(64));
    let m = suspension::DoubleAArmRide::default();
    study.case(
        "suspension",
        "double A-arm corner on a 200 kN/m tyre over a 3 cm bump (damped)",
        &m,
        &mut suspension::DoubleAArmRide::workspace(),
        1.0,
        true,
        true,
        None,
    );
    let m = ChangePointFourBar::default();
    study.case(
        "change_point_four_bar",
        "four-bar turning through its flat (singular) position",
        &m,
        &mut ChangePointFourBar::workspace(),
        2.0,
        false,
        true,
        None,
    );
    let m = gyroscope::Gyroscope { wz: 100.0 * PI, ..gyroscope::Gyroscope::default() };
    study.case("heavy_top", "heavy top spinning at 50 rev/s (spatial)", &m, &mut gyroscope::Gyroscope::workspace(), 1.0, false, true, None);
}

/// The date (UTC) from the system clock.
fn today() -> String {
    let days = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs() / 86_400) as i64;
    // Civil from days (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y}-{m:02}-{d:02}")
}

/// The CPU model and core count (Linux), else "this machine".
fn machine() -> String {
    let info = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = info.lines().find_map(|l| l.strip_prefix("model name").map(|r| r.trim_start_matches([' ', '\t', ':']).to_string()));
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    model.map_or("this machine".into(), |m| format!("{m}, {cores} cores"))
}

//! What exactness costs: the same Newton solves — assembly, statics, generalized-α — with the
//! generated exact derivatives and with central differences of the generated functions
//! ([`FiniteDifferences`]: what a tool without symbolic derivatives does), and the same motion in
//! f32 and f64 generated code.

use std::time::Instant;

use mbd::prelude::*;
use mbd::FiniteDifferences;

use crate::sweep::Reference;

/// One solve, one way.
pub struct Row {
    pub case: &'static str,
    /// "assembly", "statics" or "generalized-α …".
    pub solve: String,
    /// "exact", "differences, D exact" or "differences, all".
    pub derivatives: &'static str,
    /// The outcome: (Newton iterations or steps, median seconds, the accuracy measure) or the
    /// error.
    pub outcome: Result<(u64, f64, f64), String>,
    /// What the accuracy measure is.
    pub accuracy: &'static str,
}

/// Median wall time of `f` (5 runs if cheap, else 1) and its last result.
fn timed<R>(mut f: impl FnMut() -> R) -> (f64, R) {
    let mut times = Vec::new();
    loop {
        let start = Instant::now();
        let r = f();
        times.push(start.elapsed().as_secs_f64());
        if times.len() >= 5 || times.iter().sum::<f64>() > 0.5 {
            times.sort_by(f64::total_cmp);
            return (times[times.len() / 2], r);
        }
    }
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// Where the solves start and what they are measured against.
pub struct Start<'a, const NQ: usize, const NV: usize> {
    pub case: &'static str,
    /// The assembled, consistent start.
    pub q0: &'a [f64; NQ],
    pub v0: &'a [f64; NV],
    pub t_end: f64,
    pub reference: &'a Reference<NQ>,
}

type Solved<const NQ: usize> = Result<(u64, [f64; NQ]), String>;

/// Assembly from `start` (Newton on Φ = 0 with D, the only derivative it uses).
fn assembly<K, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    k: &K,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    start: &[f64; NQ],
) -> (f64, Solved<NQ>)
where
    K: Kinematics<f64, NQ, NV, NC>,
{
    timed(|| {
        let mut q = *start;
        KinematicSolver::default().assemble(k, ws, &mut q, 0.0).map(|c| (u64::from(c.iterations), q)).map_err(|e| e.to_string())
    })
}

/// Statics from `start` (Newton on h + Dᵀλ = 0, Φ = 0 with ∂h/∂q, K and D).
fn statics<K, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    k: &K,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    start: &[f64; NQ],
) -> (f64, Solved<NQ>)
where
    K: NewtonMatrix<f64, NQ, NV, NC>,
{
    timed(|| {
        let mut q = *start;
        StaticSolver::default().solve(k, ws, &mut q, 0.0, &mut [0.0; NC]).map(|r| (u64::from(r.iterations), q)).map_err(|e| e.to_string())
    })
}

/// Generalized-α (h = 1 ms, ρ∞ = 0.8, the default projection) to t_end: its iteration matrix
/// holds ∂h/∂q, ∂h/∂v, K and D. Counts Newton iterations.
fn alpha<K, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    k: &K,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    s: &Start<'_, NQ, NV>,
) -> (f64, Solved<NQ>)
where
    K: NewtonMatrix<f64, NQ, NV, NC>,
{
    let options = GeneralizedAlphaOptions::default().with_step(1e-3).with_rho_infinity(0.8);
    timed(|| {
        let mut integrator = GeneralizedAlpha::new(options);
        let mut q = [0.0; NQ];
        Simulation::new(k, &mut integrator)
            .start(0.0, s.q0, s.v0)
            .times(&[s.t_end])
            .run(ws, |p| q = p.point.q)
            .map(|_| (integrator.total_iterations, q))
            .map_err(|e| e.to_string())
    })
}

/// Assembly from the start moved 0.05 in every coordinate (m, rad), statics from the start, and
/// generalized-α over the case, each with exact derivatives and by differences.
pub fn compare<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    m: &M,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    s: &Start<'_, NQ, NV>,
) -> Vec<Row>
where
    M: NewtonMatrix<f64, NQ, NV, NC>,
{
    let fd = FiniteDifferences::new(m);
    let all = FiniteDifferences::with_constraint_jacobian(m);
    let mut rows = Vec::new();
    let mut push = |solve: &str, derivatives, accuracy, (seconds, result): (f64, Solved<NQ>), against: &[f64; NQ]| {
        let outcome = result.map(|(iterations, q)| (iterations, seconds, max_difference(&q, against)));
        rows.push(Row { case: s.case, solve: solve.into(), derivatives, outcome, accuracy });
    };
    let from_exact = "max |Δq| from the exact solve (m, rad)";

    let mut start = *s.q0;
    for x in start.iter_mut() {
        *x += 0.05;
    }
    m.normalize_positions(&mut start);
    let exact = assembly(m, ws, &start);
    let solution = exact.1.as_ref().map_or([f64::NAN; NQ], |r| r.1);
    push("assembly", "exact", from_exact, exact, &solution);
    push("assembly", "differences, all", from_exact, assembly(&all, ws, &start), &solution);

    let exact = statics(m, ws, s.q0);
    let solution = exact.1.as_ref().map_or([f64::NAN; NQ], |r| r.1);
    push("statics", "exact", from_exact, exact, &solution);
    push("statics", "differences, D exact", from_exact, statics(&fd, ws, s.q0), &solution);
    push("statics", "differences, all", from_exact, statics(&all, ws, s.q0), &solution);

    let end = s.reference.q.last().expect("outputs");
    let from_reference = "max |Δq| at t_end from the reference (m, rad)";
    let solve = "generalized-α h = 1 ms, ρ∞ = 0.8";
    push(solve, "exact", from_reference, alpha(m, ws, s), end);
    push(solve, "differences, D exact", from_reference, alpha(&fd, ws, s), end);
    push(solve, "differences, all", from_reference, alpha(&all, ws, s), end);
    rows
}

/// The same motion in f32 and in f64 generated code (RK4 at 1 ms, DOPRI5 at rtol 1e-5 — f32
/// raises tighter tolerances to 16 ε — both with the default projection), each against the f64
/// reference; the start is the f64 one, rounded for f32.
pub fn precision<M32, M64, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    m32: (&M32, &mut Workspace<f32, NV, NC, N, NS>),
    m64: (&M64, &mut Workspace<f64, NV, NC, N, NS>),
    s: &Start<'_, NQ, NV>,
) -> Vec<Row>
where
    M32: ForwardDynamics<f32, NQ, NV, NC>,
    M64: ForwardDynamics<f64, NQ, NV, NC>,
{
    let ((m32, ws32), (m64, ws64)) = (m32, m64);
    let end = s.reference.q.last().expect("outputs");
    let mut rows = Vec::new();
    let accuracy = "max |Δq| at t_end from the f64 reference (m, rad)";
    let (q32, v32): ([f32; NQ], [f32; NV]) = (s.q0.map(|x| x as f32), s.v0.map(|x| x as f32));
    let options = SimulationOptions::default();
    for (solve, rk4) in [("RK4 h = 1 ms", true), ("DOPRI5 rtol 1e-5", false)] {
        let (seconds, result) = timed(|| {
            let mut q = [0.0f32; NQ];
            let options = SimulationOptions::default();
            let stats = if rk4 {
                Simulation::new(m32, &mut Rk4::new(Rk4Options::default().with_step(1e-3f32)))
                    .start(0.0, &q32, &v32)
                    .times(&[s.t_end as f32])
                    .options(options)
                    .run(ws32, |p| q = p.point.q)
            } else {
                let o = Dopri5Options::default().with_rtol(1e-5f32).with_atol(1e-7);
                Simulation::new(m32, &mut Dopri5::new(o))
                    .start(0.0, &q32, &v32)
                    .times(&[s.t_end as f32])
                    .options(options)
                    .run(ws32, |p| q = p.point.q)
            };
            stats.map(|st| (st.steps, q.map(f64::from)))
        });
        let outcome = result.map(|(steps, q)| (steps, seconds, max_difference(&q, end))).map_err(|e| e.to_string());
        rows.push(Row { case: s.case, solve: solve.into(), derivatives: "f32", outcome, accuracy });
        let (seconds, result) = timed(|| {
            let mut q = [0.0f64; NQ];
            let stats = if rk4 {
                Simulation::new(m64, &mut Rk4::new(Rk4Options::default().with_step(1e-3)))
                    .start(0.0, s.q0, s.v0)
                    .times(&[s.t_end])
                    .options(options)
                    .run(ws64, |p| q = p.point.q)
            } else {
                let o = Dopri5Options::default().with_rtol(1e-5).with_atol(1e-7);
                Simulation::new(m64, &mut Dopri5::new(o))
                    .start(0.0, s.q0, s.v0)
                    .times(&[s.t_end])
                    .options(options)
                    .run(ws64, |p| q = p.point.q)
            };
            stats.map(|st| (st.steps, q))
        });
        let outcome = result.map(|(steps, q)| (steps, seconds, max_difference(&q, end))).map_err(|e| e.to_string());
        rows.push(Row { case: s.case, solve: solve.into(), derivatives: "f64", outcome, accuracy });
    }
    rows
}

/// The exactness section of the report.
pub fn markdown(rows: &[Row]) -> String {
    use std::fmt::Write as _;
    let mut out = String::from(
        "\n## What exactness costs\n\nThe same Newton solves with the generated exact derivatives and with central differences of the generated functions (`mbd::FiniteDifferences`: ∂h/∂q·B, ∂h/∂v and D by first differences, 2 NV evaluations each; K = ∂(Dᵀλ)/∂q·B by differences of differences of λᵀΦ, 4 NV² evaluations of Φ; \"D exact\" keeps the generated D, which is also part of the equations). Assembly starts 0.05 m/rad off in every coordinate; statics from the assembled start; generalized-α with the default projection. Then the same motion in f32 and f64 generated code (iterations column: steps).\n\n| case | solve | derivatives / scalar | Newton iterations (steps) | CPU | accuracy | measured as |\n|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        match &r.outcome {
            Ok((iterations, seconds, accuracy)) => writeln!(
                out,
                "| {} | {} | {} | {iterations} | {} | {accuracy:.1e} | {} |",
                r.case,
                r.solve,
                r.derivatives,
                crate::report::time(*seconds),
                r.accuracy
            ),
            Err(e) => {
                writeln!(out, "| {} | {} | {} | failed: {} | | | |", r.case, r.solve, r.derivatives, e.replace('|', "/").replace('\n', " "))
            }
        }
        .unwrap();
    }
    out
}

//! Every generated function of the slider-crank and of a 16-link driven chain, the fused
//! evaluations, and kinematic-analysis steps: `cargo bench --bench kinematics`.
//!
//! States are fixed, consistent configurations; inputs go through `black_box` so nothing is
//! folded at compile time.
use criterion::{criterion_group, criterion_main, Criterion};
use mbd::{KinematicSolver, Kinematics};
use std::hint::black_box;

#[allow(dead_code)]
#[path = "../examples/slider_crank.rs"]
mod slider_crank;
mod chain16 {
    include!("chain16.rs");
}
use chain16::Chain16;
use slider_crank::SliderCrank;

macro_rules! bench_mechanism {
    ($c:expr, $label:literal, $m:expr, $ty:ty) => {{
        const NQ: usize = <$ty>::NQ;
        const NC: usize = <$ty>::NC;
        const NNZ: usize = <$ty>::NNZ;
        let m = $m;
        let solver = KinematicSolver::default();
        let t0 = 0.37;
        let mut q = m.initial_positions();
        let mut ws = <$ty>::workspace();
        solver.assemble(&m, &mut ws, &mut q, t0).expect("the benchmark mechanism assembles");
        let mut v = [0.0; NQ];
        solver.solve_velocity(&m, &mut ws, &q, t0, &mut v).expect("velocity solve");
        let mut g = $c.benchmark_group($label);
        let (mut phi, mut d, mut nu, mut gamma, mut values) = ([0.0; NC], [[0.0; NQ]; NC], [0.0; NC], [0.0; NC], [0.0; NNZ]);
        g.bench_function("constraints", |b| b.iter(|| m.constraints(black_box(&q), black_box(t0), &mut phi)));
        g.bench_function("jacobian (dense)", |b| b.iter(|| m.jacobian(black_box(&q), black_box(t0), &mut d)));
        g.bench_function("jacobian_values (sparse)", |b| b.iter(|| m.jacobian_values(black_box(&q), black_box(t0), &mut values)));
        g.bench_function("velocity_rhs", |b| b.iter(|| m.velocity_rhs(black_box(&q), black_box(t0), &mut nu)));
        g.bench_function("gamma", |b| b.iter(|| m.gamma(black_box(&q), black_box(&v), black_box(t0), &mut gamma)));
        g.bench_function("three calls: constraints + jacobian_values + gamma", |b| {
            b.iter(|| {
                m.constraints(black_box(&q), black_box(t0), &mut phi);
                m.jacobian_values(black_box(&q), black_box(t0), &mut values);
                m.gamma(black_box(&q), black_box(&v), black_box(t0), &mut gamma);
            })
        });
        g.bench_function("full_eval_values (fused Φ, Φ_q, ν, γ)", |b| {
            b.iter(|| m.full_eval_values(black_box(&q), black_box(&v), black_box(t0), &mut phi, &mut values, &mut nu, &mut gamma))
        });
        g.bench_function("full_eval (fused, dense Φ_q)", |b| {
            b.iter(|| m.full_eval(black_box(&q), black_box(&v), black_box(t0), &mut phi, &mut d, &mut nu, &mut gamma))
        });
        // One step of a kinematic sweep: Newton from the previous position at t + 1 ms.
        let mut qn = q;
        let convergence = solver.solve_position(&m, &mut ws, &mut qn, t0 + 1e-3).expect("converges");
        println!(
            "{}: the position solve takes {} Newton steps, {} factorizations of D",
            $label, convergence.iterations, convergence.factorizations
        );
        g.bench_function("position solve, t → t + 1 ms", |b| {
            b.iter(|| {
                let mut qn = q;
                solver.solve_position(&m, &mut ws, &mut qn, black_box(t0 + 1e-3)).expect("converges");
                qn
            })
        });
        // One point of a kinematic sweep: position, velocity and acceleration at t + 1 ms.
        g.bench_function("analysis (q, v, v̇), t → t + 1 ms", |b| {
            b.iter(|| solver.analyze(&m, &mut ws, black_box(&q), black_box(t0 + 1e-3)).expect("converges"))
        });
        // Inverse dynamics at that point: Dᵀλ = M v̇ − h for the multipliers.
        let state = solver.analyze(&m, &mut ws, &q, t0 + 1e-3).expect("converges");
        let mut lambda = [0.0; NC];
        g.bench_function("inverse dynamics (λ) at the analysed state", |b| {
            b.iter(|| {
                mbd::InverseDynamics::default()
                    .solve(&m, &mut ws, black_box(&state.q), black_box(&state.v), black_box(&state.vd), t0 + 1e-3, &mut lambda)
                    .expect("a regular D");
                lambda
            })
        });
        g.finish();
    }};
}

/// Operation counts of each generated function (after common-subexpression elimination): the
/// floor under its time, printed beside the measurements.
fn print_op_counts<M: mbd::Mechanism>() {
    println!("{} — operations per call (add, mul, div, calls):", M::NAME);
    for o in M::OP_COUNTS {
        println!("  {:<18} {:>4} {:>4} {:>4} {:>4}   total {}", o.function, o.add, o.mul, o.div, o.call, o.total());
    }
}

fn benches(c: &mut Criterion) {
    print_op_counts::<SliderCrank>();
    print_op_counts::<Chain16>();
    bench_mechanism!(c, "slider_crank", SliderCrank::default(), SliderCrank);
    bench_mechanism!(c, "chain16", Chain16::default(), Chain16);
}

criterion_group!(kinematics, benches);
criterion_main!(kinematics);

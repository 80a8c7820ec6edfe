//! Forward dynamics and integration steps of the free slider-crank and of free pendulum chains
//! of 4, 16 and 64 links, with Baumgarte α = β = 5: `cargo bench --bench dynamics`.
//!
//! Timed: the right-hand side (q̈ and λ from the generated sparse Schur-complement solve), one
//! RK4 step at h = 1 ms (four right-hand sides), one DOPRI5 step (six) and one generalized-α
//! step (Newton on the iteration matrix, factored over the sparse pattern planned at compile
//! time).
//! States are assembled, consistent configurations; inputs go through `black_box`.
use criterion::{criterion_group, criterion_main, Criterion};
use mbd::{
    Dopri5, DynamicsOptions, ForwardDynamics, GeneralizedAlphaOptions, Integrator, KinematicSolver, Kinematics, Mechanism, Point, Rk4,
    Rk4Options, System,
};
use std::hint::black_box;

mod free_slider_crank {
    include!("free_slider_crank.rs");
}
mod chains {
    include!("pendulum_chain4.rs");
    include!("pendulum_chain16.rs");
    include!("pendulum_chain64.rs");
}
use chains::{PendulumChain16, PendulumChain4, PendulumChain64};
use free_slider_crank::FreeSliderCrank;

macro_rules! bench_dynamics {
    ($c:expr, $label:literal, $ty:ty) => {{
        const NQ: usize = <$ty>::NQ;
        const NV: usize = <$ty>::NV;
        const NC: usize = <$ty>::NC;
        let m = <$ty>::default();
        let mut q = m.initial_positions();
        let mut ws = <$ty>::workspace();
        KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the benchmark mechanism assembles");
        let system = System::new(&m);
        let from: Point<f64, NQ, NV, NC> = system.point(0.0, q, [0.0; NV], [0.0; 2]).expect("forward dynamics");
        // Start from a moving state: 0.05 s into the fall.
        let mut rk4 = Rk4::new(Rk4Options::default().with_step(1e-3));
        let mut p = from;
        let mut next = from;
        for _ in 0..50 {
            rk4.step(&system, &mut ws, &p, f64::INFINITY, &mut next).expect("step");
            p = next;
        }
        let options = DynamicsOptions::default();
        let mut g = $c.benchmark_group($label);
        let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
        g.bench_function("accelerations (right-hand side)", |b| {
            b.iter(|| m.accelerations(black_box(&p.q), black_box(&p.v), black_box(p.t), &options, &mut vd, &mut lambda))
        });
        g.bench_function("RK4 step, h = 1 ms", |b| b.iter(|| rk4.step(&system, &mut ws, black_box(&p), f64::INFINITY, &mut next)));
        let mut dopri = Dopri5::<f64, NQ, NV>::default();
        dopri.next_step = 1e-3;
        dopri.options.max_step = 1e-3;
        g.bench_function("DOPRI5 step, h = 1 ms", |b| {
            b.iter(|| {
                dopri.next_step = 1e-3;
                dopri.step(&system, &mut ws, black_box(&p), f64::INFINITY, &mut next)
            })
        });
        let mut alpha = <$ty>::generalized_alpha(GeneralizedAlphaOptions::default());
        alpha.step(&system, &mut ws, &p, f64::INFINITY, &mut next).expect("generalized-α step");
        println!("{}: generalized-α takes {} Newton iterations for the timed step", $label, alpha.iterations);
        g.bench_function("generalized-α step, h = 1 ms", |b| {
            b.iter(|| alpha.step(&system, &mut ws, black_box(&p), f64::INFINITY, &mut next))
        });
        g.finish();
    }};
}

fn benches(c: &mut Criterion) {
    for o in FreeSliderCrank::OP_COUNTS.iter().chain(PendulumChain16::OP_COUNTS).filter(|o| o.function.starts_with("accelerations")) {
        println!("{}: {} add, {} mul, {} div, {} calls", o.function, o.add, o.mul, o.div, o.call);
    }
    bench_dynamics!(c, "free_slider_crank", FreeSliderCrank);
    bench_dynamics!(c, "pendulum_chain4", PendulumChain4);
    bench_dynamics!(c, "pendulum_chain16", PendulumChain16);
    bench_dynamics!(c, "pendulum_chain64", PendulumChain64);
}

criterion_group!(dynamics, benches);
criterion_main!(dynamics);

//! Static equilibrium of free pendulum chains of 16 and 64 links under gravity:
//! `cargo bench --bench statics`. Two starts each: the documented one (every link
//! horizontal: a large motion, the trust region at work) and the hanging pose with every angle
//! 0.01 rad off (the Newton phase and the stability verdict). Each solve checks its answer (the
//! chain straight down) before it is timed.
use criterion::{criterion_group, criterion_main, Criterion};
use mbd::prelude::*;
use std::hint::black_box;

mod chains {
    include!("pendulum_chain16.rs");
    include!("pendulum_chain64.rs");
}
use chains::{PendulumChain16, PendulumChain64};

macro_rules! bench_statics {
    ($c:expr, $label:literal, $ty:ty) => {{
        const NQ: usize = <$ty>::NQ;
        const NC: usize = <$ty>::NC;
        let m = <$ty>::default();
        let mut ws = <$ty>::workspace();
        let horizontal = m.initial_positions();
        // Hanging: link k's centre at (0, −(k + ½) 0.1 m), φ = −π/2, then every φ 0.01 rad off
        // (the solver assembles it).
        let mut near = horizontal;
        for k in 0..NQ / 3 {
            near[3 * k] = 0.0;
            near[3 * k + 1] = -(k as f64 + 0.5) * 0.1;
            near[3 * k + 2] = -std::f64::consts::FRAC_PI_2 + 0.01;
        }
        let solver = StaticSolver::default();
        let mut g = $c.benchmark_group($label);
        for (start, q0) in [("from horizontal", horizontal), ("from 0.01 rad off hanging", near)] {
            let mut q = q0;
            let mut lambda = [0.0; NC];
            let report = solver.solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("the chain hangs");
            let straight = (0..NQ / 3).all(|k| (q[3 * k + 2] + std::f64::consts::FRAC_PI_2).abs() < 1e-8);
            assert!(straight && matches!(report.stability, Stability::Stable { .. }), "{start}: {report:?}");
            println!("{} {start}: {} steps, {} rejected", $label, report.iterations, report.rejected);
            g.bench_function(start, |b| {
                b.iter(|| {
                    let mut q = q0;
                    solver.solve(&m, &mut ws, black_box(&mut q), 0.0, &mut lambda).expect("the chain hangs");
                    q
                })
            });
        }
        g.finish();
    }};
}

fn benches(c: &mut Criterion) {
    bench_statics!(c, "statics_chain16", PendulumChain16);
    bench_statics!(c, "statics_chain64", PendulumChain64);
}

criterion_group! {
    name = group;
    config = Criterion::default().sample_size(10).measurement_time(std::time::Duration::from_secs(3));
    targets = benches
}
criterion_main!(group);

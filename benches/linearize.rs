//! What an exact linearization costs against a finite-difference one of the same model, for a
//! small and a large mechanism: `cargo bench --bench linearize`.
//!
//! Free pendulum chains of 4 and 64 links (12 and 192 coordinates, 4 and 64 degrees of freedom)
//! 0.05 s into their fall from horizontal — a moving state, so every term of the exact path is
//! evaluated. Timed: [`mbd::linearize`] (the generated derivatives, and the saddle-point system
//! solved in the null space by one f × f Cholesky), [`mbd::linearize_finite_differences`]
//! (central differences of the forward dynamics in the same chart: 4f forward-dynamics solves
//! and projections), and the modes of the result (Schur decomposition of A and inverse
//! iteration per eigenvalue).
use criterion::{criterion_group, criterion_main, Criterion};
use mbd::{DynamicsOptions, ForwardDynamics, Integrator, KinematicSolver, Kinematics, Linearizer, Point, Rk4, Rk4Options, System};
use std::hint::black_box;
use std::time::Duration;

mod chains {
    include!("pendulum_chain4.rs");
    include!("pendulum_chain64.rs");
}
use chains::{PendulumChain4, PendulumChain64};

macro_rules! bench_linearize {
    ($c:expr, $label:literal, $ty:ty) => {{
        const NQ: usize = <$ty>::NQ;
        const NV: usize = <$ty>::NV;
        const NC: usize = <$ty>::NC;
        let m = <$ty>::default();
        let mut q = m.initial_positions();
        let mut ws = <$ty>::workspace();
        KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the benchmark mechanism assembles");
        let system = System::new(&m);
        let mut p: Point<f64, NQ, NV, NC> = system.point(0.0, q, [0.0; NV], [0.0; 2]).expect("forward dynamics");
        let mut rk4 = Rk4::new(Rk4Options::default().with_step(1e-3));
        let mut next = p;
        for _ in 0..50 {
            rk4.step(&system, &mut ws, &p, f64::INFINITY, &mut next).expect("step");
            p = next;
        }
        // RK4 leaves the state off the manifold by its truncation error: project it back.
        for _ in 0..4 {
            m.project_positions_step(&mut p.q, p.t, &DynamicsOptions::default()).expect("projects");
        }
        m.project_velocities(&p.q, &mut p.v, p.t, &DynamicsOptions::default()).expect("projects");
        let linearizer = Linearizer::default();
        let lin = linearizer.linearize(&m, &p.q, &p.v, p.t).expect("exact");
        let fd = linearizer.finite_differences(&m, &p.q, &p.v, p.t).expect("differences");
        eprintln!(
            "{}: f = {}, exact vs differences max |ΔA| / max |A| = {:.1e}",
            $label,
            lin.dof(),
            (&lin.a - &fd.a).amax() / lin.a.amax()
        );
        let mut g = $c.benchmark_group($label);
        g.sample_size(10).measurement_time(Duration::from_secs(5));
        g.bench_function("exact", |b| b.iter(|| linearizer.linearize(&m, black_box(&p.q), black_box(&p.v), p.t)));
        g.bench_function("finite differences", |b| b.iter(|| linearizer.finite_differences(&m, black_box(&p.q), black_box(&p.v), p.t)));
        g.bench_function("modes", |b| b.iter(|| black_box(&lin).modes()));
        g.finish();
    }};
}

fn benches(c: &mut Criterion) {
    bench_linearize!(c, "linearize chain 4", PendulumChain4);
    bench_linearize!(c, "linearize chain 64", PendulumChain64);
}

criterion_group!(linearize_benches, benches);
criterion_main!(linearize_benches);

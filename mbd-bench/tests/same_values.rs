//! The benchmark compares like with like: CasADi's generated C and mbd's generated Rust return the
//! same Φ, Jacobian non-zeros and γ at the benchmark state (to rounding: 1e-12 relative to the
//! functions' scale — both evaluate the same sums of products in possibly different orders).
use mbd::{KinematicSolver, Kinematics};

#[allow(dead_code)]
#[path = "../../examples/slider_crank.rs"]
mod slider_crank;
mod chain16 {
    include!("../../benches/chain16.rs");
}

fn check<M: Kinematics<f64, NQ, NC>, const NQ: usize, const NC: usize>(
    m: &M,
    params: &[f64],
    mut phi_c: mbd_bench::CasadiFunction,
    mut jac_c: mbd_bench::CasadiFunction,
    mut gamma_c: mbd_bench::CasadiFunction,
) {
    let t = 0.37;
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    solver.assemble(m, &mut q, t).expect("assembles");
    let qd: [f64; NQ] = core::array::from_fn(|i| 0.3 * (i as f64 + 1.0).sin());
    let (mut phi, mut d, mut gamma) = ([0.0; NC], [[0.0; NQ]; NC], [0.0; NC]);
    m.constraints(&q, t, &mut phi);
    m.jacobian(&q, t, &mut d);
    m.gamma(&q, &qd, t, &mut gamma);
    let (mut phi2, mut gamma2) = ([0.0; NC], [0.0; NC]);
    let mut nz = vec![0.0; M::JACOBIAN_PATTERN.len()];
    phi_c.call(&[&q, &[t], params], &mut phi2);
    jac_c.call(&[&q, &[t], params], &mut nz);
    gamma_c.call(&[&q, &qd, &[t], params], &mut gamma2);
    let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-12 * scale.max(1.0);
    let scale = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for r in 0..NC {
        assert!(close(phi[r], phi2[r], scale(&phi2)), "{} phi[{r}]", M::NAME);
        assert!(close(gamma[r], gamma2[r], scale(&gamma2)), "{} gamma[{r}]: {} vs {}", M::NAME, gamma[r], gamma2[r]);
    }
    // CasADi stores the sparse Jacobian column-major: order mbd's pattern the same way.
    let mut pattern: Vec<(u16, u16)> = M::JACOBIAN_PATTERN.to_vec();
    pattern.sort_by_key(|&(r, c)| (c, r));
    for (k, &(r, c)) in pattern.iter().enumerate() {
        assert!(close(d[r as usize][c as usize], nz[k], scale(&nz)), "{} jac[{r}][{c}]", M::NAME);
    }
}

#[test]
fn casadi_c_and_mbd_compute_the_same_functions() {
    let sc = slider_crank::SliderCrank::default();
    check(&sc, &sc.params(), mbd_bench::slider_crank::phi(), mbd_bench::slider_crank::jac(), mbd_bench::slider_crank::gamma());
    let ch = chain16::Chain16::default();
    check(&ch, &ch.params(), mbd_bench::chain16::phi(), mbd_bench::chain16::jac(), mbd_bench::chain16::gamma());
}

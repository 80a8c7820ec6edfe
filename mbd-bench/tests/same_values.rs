//! The benchmark compares like with like: CasADi's generated C and mbd's generated Rust return the
//! same Φ, Jacobian non-zeros and γ at the benchmark state (to rounding: 1e-12 relative to the
//! functions' scale — both evaluate the same sums of products in possibly different orders), and
//! the same q̈ and λ of forward dynamics.
use mbd::{DynamicsOptions, ForwardDynamics, KinematicSolver, Kinematics};

#[allow(dead_code)]
#[path = "../../examples/slider_crank.rs"]
mod slider_crank;
mod chain16 {
    include!("../../benches/chain16.rs");
}
mod free_slider_crank {
    include!("../../benches/free_slider_crank.rs");
}
mod pendulum_chain16 {
    include!("../../benches/pendulum_chain16.rs");
}

/// Planar mechanisms: v = q̇ (NV = NQ), the velocity CasADi's functions take.
fn check<M: Kinematics<f64, NQ, NQ, NC>, const NQ: usize, const NC: usize>(
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

/// q̈ and λ of mbd's sparse Schur-complement solve against CasADi's symbolic Schur form and its
/// sparse numeric QR of the KKT matrix, at an assembled state with non-zero velocities (so the
/// velocity terms of γ and h count) and Φ ≠ 0 (so the Baumgarte terms count), α = β = 5.
///
/// Tolerance: three solves of the same well-conditioned system (the benchmark states are far
/// from singular positions) whose inputs agree to rounding differ by about cond · ε ‖x‖; 1e-9
/// relative to ‖[q̈; λ]‖∞ leaves ample margin for cond(S) ≤ 1e5, and is still far below any
/// modelling difference (a wrong term moves the result by its own size).
fn check_forward<M: ForwardDynamics<f64, NQ, NQ, NC>, const NQ: usize, const NC: usize>(
    m: &M,
    params: &[f64],
    mut schur: mbd_bench::CasadiFunction,
    mut qr: mbd_bench::CasadiFunction,
) {
    let t = 0.37;
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(m, &mut q, t).expect("assembles");
    q[0] += 1e-4; // Φ ≠ 0: the β² Φ term contributes.
    let qd: [f64; NQ] = core::array::from_fn(|i| 0.3 * (i as f64 + 1.0).sin());
    let (alpha, beta) = (5.0, 5.0);
    let (mut qdd, mut lambda) = ([0.0; NQ], [0.0; NC]);
    m.accelerations(&q, &qd, t, &DynamicsOptions::baumgarte(alpha, beta), &mut qdd, &mut lambda).expect("forward dynamics");
    let mbd: Vec<f64> = qdd.iter().chain(&lambda).copied().collect();
    let scale = mbd.iter().fold(1.0f64, |a, x| a.max(x.abs()));
    for (form, f) in [("Schur", &mut schur), ("QR", &mut qr)] {
        let mut casadi = vec![0.0; NQ + NC];
        f.call(&[&q, &qd, &[t], params, &[alpha, beta]], &mut casadi);
        for (k, (a, b)) in mbd.iter().zip(&casadi).enumerate() {
            let what = if k < NQ { format!("q̈[{}]", M::COORDINATE_NAMES[k]) } else { format!("λ[{}]", k - NQ) };
            assert!((a - b).abs() <= 1e-9 * scale, "{} {what}: mbd {a} vs CasADi {form} {b}", M::NAME);
        }
    }
}

#[test]
fn casadi_c_and_mbd_compute_the_same_forward_dynamics() {
    let sc = free_slider_crank::FreeSliderCrank::default();
    check_forward(&sc, &sc.params(), mbd_bench::free_slider_crank::fd_schur(), mbd_bench::free_slider_crank::fd_qr());
    let ch = pendulum_chain16::PendulumChain16::default();
    check_forward(&ch, &ch.params(), mbd_bench::pendulum_chain16::fd_schur(), mbd_bench::pendulum_chain16::fd_qr());
}

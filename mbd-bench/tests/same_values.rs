//! The benchmark compares like with like: CasADi's generated C and mbd's generated Rust return the
//! same Φ, Jacobian non-zeros and γ at the benchmark state (to rounding: 1e-12 relative to the
//! functions' scale — both evaluate the same sums of products in possibly different orders), and
//! the same q̈ and λ of forward dynamics, M·x, h, its derivatives and the Newton-matrix fill.
use mbd::{DynamicsOptions, ForwardDynamics, KinematicSolver, Kinematics, NewtonMatrix, Workspace};

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
    solver.assemble(m, &mut Workspace::<f64, NQ, NC, 0>::boxed(), &mut q, t).expect("assembles");
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
    KinematicSolver::default().assemble(m, &mut Workspace::<f64, NQ, NC, 0>::boxed(), &mut q, t).expect("assembles");
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

mod spatial_slider_crank {
    include!("../mechanisms/spatial_slider_crank.rs");
}
mod free_spatial_slider_crank {
    include!("../mechanisms/free_spatial_slider_crank.rs");
}
mod spatial_chain16 {
    include!("../mechanisms/spatial_chain16.rs");
}

/// A few states of a spatial mechanism: the assembled one at t = 0.37 with velocities in ±0.3,
/// and two off the constraint manifold — every position moved by up to 0.05 m, every Euler
/// parameter by up to 0.1 and renormalized, velocities in ±2, at t = 1.1 and 1.9 — so Φ ≠ 0 and
/// every term of γ and of h counts. Deterministic (a fixed sine sequence), no random source.
fn spatial_states<M: Kinematics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
) -> Vec<(f64, [f64; NQ], [f64; NV])> {
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(m, &mut Workspace::<f64, NV, NC, 0>::boxed(), &mut q, 0.37).expect("assembles");
    let mut states = vec![(0.37, q, core::array::from_fn(|i| 0.3 * (i as f64 + 1.0).sin()))];
    for (k, t) in [(1.0, 1.1), (2.0, 1.9)] {
        let mut moved = q;
        for (i, x) in moved.iter_mut().enumerate() {
            let wiggle = (k * 7.3 + i as f64 * 1.7).sin();
            *x += if i % 7 < 3 { 0.05 } else { 0.1 } * wiggle;
        }
        m.normalize_positions(&mut moved);
        states.push((t, moved, core::array::from_fn(|i| 2.0 * (k * 3.1 + i as f64 * 0.9).cos())));
    }
    states
}

/// Spatial Φ, the non-zeros of D = Φ_q B and γ (velocity space, v = (ṙ, ω′) per body) of mbd
/// against CasADi's C at each of `spatial_states`, to 1e-12 relative to the function's largest
/// entry (same sums of products in different orders). Returns the largest relative difference.
fn check_spatial<M: Kinematics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    params: &[f64],
    mut phi_c: mbd_bench::CasadiFunction,
    mut jac_c: mbd_bench::CasadiFunction,
    mut gamma_c: mbd_bench::CasadiFunction,
) -> f64 {
    // CasADi's D is projected on mbd's pattern, column-major: order mbd's pattern the same way.
    let mut pattern: Vec<(u16, u16)> = M::JACOBIAN_PATTERN.to_vec();
    pattern.sort_by_key(|&(r, c)| (c, r));
    let scale = |v: &[f64]| v.iter().fold(1.0f64, |a, x| a.max(x.abs()));
    let mut worst = 0.0f64;
    for (t, q, v) in spatial_states(m) {
        let (mut phi, mut d, mut gamma) = ([0.0; NC], [[0.0; NV]; NC], [0.0; NC]);
        m.constraints(&q, t, &mut phi);
        m.jacobian(&q, t, &mut d);
        m.gamma(&q, &v, t, &mut gamma);
        let mbd_d: Vec<f64> = pattern.iter().map(|&(r, c)| d[r as usize][c as usize]).collect();
        let (mut phi2, mut gamma2, mut d2) = ([0.0; NC], [0.0; NC], vec![0.0; pattern.len()]);
        phi_c.call(&[&q, &[t], params], &mut phi2);
        jac_c.call(&[&q, &[t], params], &mut d2);
        gamma_c.call(&[&q, &v, &[t], params], &mut gamma2);
        for (what, a, b) in [("Φ", &phi[..], &phi2[..]), ("D", &mbd_d[..], &d2[..]), ("γ", &gamma[..], &gamma2[..])] {
            let s = scale(b);
            for (k, (x, y)) in a.iter().zip(b).enumerate() {
                let rel = (x - y).abs() / s;
                worst = worst.max(rel);
                let at = if what == "D" {
                    let (r, c) = pattern[k];
                    format!("[{}][{}]", M::CONSTRAINT_NAMES[r as usize], M::VELOCITY_NAMES[c as usize])
                } else {
                    format!("[{}]", M::CONSTRAINT_NAMES[k])
                };
                assert!(rel <= 1e-12, "{} t = {t}: {what}{at}: mbd {x} vs CasADi {y}", M::NAME);
            }
        }
    }
    worst
}

#[test]
fn casadi_c_and_mbd_compute_the_same_spatial_functions() {
    let sc = spatial_slider_crank::SpatialSliderCrank::default();
    let worst = check_spatial(
        &sc,
        &sc.params(),
        mbd_bench::spatial_slider_crank::phi(),
        mbd_bench::spatial_slider_crank::jac(),
        mbd_bench::spatial_slider_crank::gamma(),
    );
    println!("spatial slider-crank: Φ, D, γ agree to {worst:.1e} relative");
    let ch = spatial_chain16::SpatialChain16::default();
    let worst =
        check_spatial(&ch, &[], mbd_bench::spatial_chain16::phi(), mbd_bench::spatial_chain16::jac(), mbd_bench::spatial_chain16::gamma());
    println!("spatial chain of 16: Φ, D, γ agree to {worst:.1e} relative");
}

/// Spatial forward dynamics, v̇ and λ with α = β = 5, of mbd's planned Schur solve against
/// CasADi's symbolic Schur form and its sparse QR of the KKT matrix at each of
/// `spatial_states` (Φ ≠ 0 off the assembled one, so the Baumgarte terms count). Tolerance as
/// for the planar forward dynamics (three solves of one well-conditioned system); the largest
/// difference relative to ‖[v̇; λ]‖∞ is returned and printed.
fn check_spatial_forward<M: ForwardDynamics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    params: &[f64],
    mut schur: mbd_bench::CasadiFunction,
    mut qr: mbd_bench::CasadiFunction,
) -> f64 {
    let (alpha, beta) = (5.0, 5.0);
    let mut worst = 0.0f64;
    for (t, q, v) in spatial_states(m) {
        let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
        m.accelerations(&q, &v, t, &DynamicsOptions::baumgarte(alpha, beta), &mut vd, &mut lambda).expect("forward dynamics");
        let mbd: Vec<f64> = vd.iter().chain(&lambda).copied().collect();
        let scale = mbd.iter().fold(1.0f64, |a, x| a.max(x.abs()));
        for (form, f) in [("Schur", &mut schur), ("QR", &mut qr)] {
            let mut casadi = vec![0.0; NV + NC];
            f.call(&[&q, &v, &[t], params, &[alpha, beta]], &mut casadi);
            for (k, (a, b)) in mbd.iter().zip(&casadi).enumerate() {
                let what = if k < NV { format!("v̇[{}]", M::VELOCITY_NAMES[k]) } else { format!("λ[{}]", M::CONSTRAINT_NAMES[k - NV]) };
                worst = worst.max((a - b).abs() / scale);
                assert!((a - b).abs() <= 1e-9 * scale, "{} t = {t} {what}: mbd {a} vs CasADi {form} {b}", M::NAME);
            }
        }
    }
    worst
}

#[test]
fn casadi_c_and_mbd_compute_the_same_spatial_forward_dynamics() {
    let sc = free_spatial_slider_crank::FreeSpatialSliderCrank::default();
    let worst = check_spatial_forward(
        &sc,
        &sc.params(),
        mbd_bench::free_spatial_slider_crank::fd_schur(),
        mbd_bench::free_spatial_slider_crank::fd_qr(),
    );
    println!("free spatial slider-crank: v̇, λ agree to {worst:.1e} relative");
    let ch = spatial_chain16::SpatialChain16::default();
    let worst =
        check_spatial_forward(&ch, &[], mbd_bench::spatial_chain16_dynamics::fd_schur(), mbd_bench::spatial_chain16_dynamics::fd_qr());
    println!("spatial chain of 16: v̇, λ agree to {worst:.1e} relative");
}

/// A CasADi sparse output written whole (rows × columns, row-major as mbd's arrays).
fn dense(f: &mbd_bench::CasadiFunction, output: usize, values: &[f64]) -> Vec<Vec<f64>> {
    let (pattern, (rows, columns)) = f.output_pattern(output);
    assert_eq!(pattern.len(), values.len());
    let mut whole = vec![vec![0.0; columns]; rows];
    for (&(r, c), &x) in pattern.iter().zip(values) {
        whole[r][c] = x;
    }
    whole
}

/// M·x, h, ∂h/∂q (·B), ∂h/∂v and the Newton-matrix fill — Φ, D and the velocity block
/// A = M − c_v ∂h/∂v − c_q (∂h/∂q·B + K) of mbd's planned storage — against CasADi's C at each
/// of `spatial_states` (planar: v = q̇), with λ, x, c_v and c_q fixed sequences. Tolerance 1e-12
/// relative to each output's largest entry: the same sums of products in other orders. Every
/// entry of mbd's A block outside CasADi's pattern (the factors' fill) must be zero. Returns the
/// largest relative difference.
fn check_forces<M: NewtonMatrix<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    params: &[f64],
    mut f: mbd_bench::ForceFunctions,
) -> f64 {
    let scale = |v: &mut dyn Iterator<Item = f64>| v.fold(1.0f64, |a, x| a.max(x.abs()));
    let mut worst = 0.0f64;
    let mut compare = |what: &str, t: f64, a: &[Vec<f64>], b: &[Vec<f64>]| {
        let s = scale(&mut b.iter().flatten().copied());
        for (r, (x, y)) in a.iter().zip(b).enumerate() {
            for (c, (x, y)) in x.iter().zip(y).enumerate() {
                let rel = (x - y).abs() / s;
                worst = worst.max(rel);
                assert!(rel <= 1e-12, "{} t = {t}: {what}[{r}][{c}]: mbd {x} vs CasADi {y}", M::NAME);
            }
        }
    };
    let row = |v: &[f64]| vec![v.to_vec()];
    let mut ws = Workspace::<f64, NV, NC, 0>::boxed();
    let (c_v, c_q) = (0.3, 0.05);
    for (t, q, v) in spatial_states(m) {
        let x: [f64; NV] = core::array::from_fn(|i| (1.3 * i as f64 + 0.2).sin());
        let lambda: [f64; NC] = core::array::from_fn(|i| 10.0 * (0.7 * i as f64 + 0.4).cos());
        let state: [&[f64]; 4] = [&q, &v, &[t], params];
        let (mut y, mut y2) = ([0.0; NV], [0.0; NV]);
        m.mass_times(&q, &x, &mut y);
        f.mx.call(&[&q, &x, params], &mut y2);
        compare("M·x", t, &row(&y), &row(&y2));
        m.forces(&q, &v, t, &mut y);
        f.h.call(&state, &mut y2);
        compare("h", t, &row(&y), &row(&y2));
        let (mut h_q, mut h_v) = ([[0.0; NV]; NV], [[0.0; NV]; NV]);
        m.forces_q(&q, &v, t, &mut h_q);
        m.forces_v(&q, &v, t, &mut h_v);
        for (what, g, mine) in [("∂h/∂q", &mut f.h_q, &h_q), ("∂h/∂v", &mut f.h_v, &h_v)] {
            let mut values = vec![0.0; g.output_pattern(0).0.len()];
            g.call(&state, &mut values);
            compare(what, t, &mine.map(|r| r.to_vec()), &dense(g, 0, &values));
        }
        // mbd's planned storage: D's non-zeros, then the matrix's entries by (row, column) position.
        let mut s = M::newton_storage();
        let mut phi = [0.0; NC];
        m.newton_matrix(&q, &v, &[0.0; NV], t, &lambda, None, c_v, c_q, &mut phi, &mut s, ws.dense());
        let s = s.as_ref();
        let mut d = vec![vec![0.0; NV]; NC];
        for (&(r, c), &value) in M::JACOBIAN_PATTERN.iter().zip(s) {
            d[r as usize][c as usize] = value;
        }
        let (pattern, entries) = (M::NEWTON_PATTERN, &s[M::JACOBIAN_PATTERN.len()..]);
        let mut a = vec![vec![0.0; NV]; NV];
        for position in 0..pattern.size() {
            let row = pattern.row_start[position] as usize..pattern.row_start[position + 1] as usize;
            for (&column, &value) in pattern.columns[row.clone()].iter().zip(&entries[row]) {
                let (i, j) = (pattern.unknown[position] as usize, pattern.unknown[column as usize] as usize);
                if i < NV && j < NV {
                    a[i][j] = value;
                }
            }
        }
        let (nd, na) = (f.newton.output_pattern(1).0.len(), f.newton.output_pattern(2).0.len());
        let (mut phi2, mut d2, mut a2) = ([0.0; NC], vec![0.0; nd], vec![0.0; na]);
        f.newton.call_outputs(&[&q, &v, &[t], params, &lambda, &[c_v, c_q]], &mut [&mut phi2, &mut d2, &mut a2]);
        compare("Newton Φ", t, &row(&phi), &row(&phi2));
        compare("Newton D", t, &d, &dense(&f.newton, 1, &d2));
        compare("Newton A", t, &a, &dense(&f.newton, 2, &a2));
    }
    worst
}

#[test]
fn casadi_c_and_mbd_compute_the_same_forces_and_newton_matrices() {
    let sc = free_slider_crank::FreeSliderCrank::default();
    let worst = check_forces(&sc, &sc.params(), mbd_bench::force_functions!(free_slider_crank));
    println!("free slider-crank: M·x, h, ∂h/∂q, ∂h/∂v, Newton fill agree to {worst:.1e} relative");
    let ch = pendulum_chain16::PendulumChain16::default();
    let worst = check_forces(&ch, &ch.params(), mbd_bench::force_functions!(pendulum_chain16));
    println!("pendulum chain of 16: {worst:.1e}");
    let ssc = free_spatial_slider_crank::FreeSpatialSliderCrank::default();
    let worst = check_forces(&ssc, &ssc.params(), mbd_bench::force_functions!(free_spatial_slider_crank));
    println!("free spatial slider-crank: {worst:.1e}");
    let sch = spatial_chain16::SpatialChain16::default();
    let worst = check_forces(&sch, &[], mbd_bench::force_functions!(spatial_chain16_dynamics));
    println!("spatial chain of 16: {worst:.1e}");
}

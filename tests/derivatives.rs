//! The generated Φ_q, ν and γ of every example against central differences of the generated Φ.
//!
//! Φ_q[r][c] ≈ (Φ(q + h e_c) − Φ(q − h e_c)) / 2h, ν ≈ −(Φ(t + h) − Φ(t − h)) / 2h, and
//! γ = −d/dε [D(q + εq̇, t + ε) q̇ − ν(q + εq̇, t + ε)] at ε = 0 (the total time derivative of Φ̇
//! with q̈ = 0), differenced the same way. With h = 1e-6 the truncation error is O(h²·|Φ'''|)
//! ≈ 1e-12·O(1–1e3) and the rounding error O(ε_mach·|Φ|/h) ≈ 1e-10 for |Φ| = O(1): a tolerance of
//! 1e-6 relative to max(1, |value|) separates right from wrong by orders of magnitude (a wrong
//! term is O(1)), while the exact comparison is the CasADi oracle's job.
mod common;

use common::Rng;
use mbd::{Kinematics, Mechanism};

const H: f64 = 1e-6;
const TOL: f64 = 1e-6;

/// Planar mechanisms: v = q̇ and D = Φ_q, so D is checked against differences in q.
fn check<M: Kinematics<f64, NQ, NQ, NC>, const NQ: usize, const NC: usize>(m: &M, seed: u64) {
    let mut rng = Rng::new(seed);
    for sample in 0..50 {
        let mut q = m.initial_positions();
        for v in q.iter_mut() {
            *v += rng.uniform(-0.3, 0.3);
        }
        let qd: [f64; NQ] = core::array::from_fn(|_| rng.uniform(-3.0, 3.0));
        let t = rng.uniform(0.0, 2.0);
        let mut d = [[0.0; NQ]; NC];
        m.jacobian(&q, t, &mut d);
        let (mut p, mut n) = ([0.0; NC], [0.0; NC]);
        for c in 0..NQ {
            let (mut qp, mut qn) = (q, q);
            qp[c] += H;
            qn[c] -= H;
            m.constraints(&qp, t, &mut p);
            m.constraints(&qn, t, &mut n);
            for r in 0..NC {
                let fd = (p[r] - n[r]) / (2.0 * H);
                let structural = M::JACOBIAN_PATTERN.contains(&(r as u16, c as u16));
                assert!(
                    (d[r][c] - fd).abs() <= TOL * fd.abs().max(1.0),
                    "{} sample {sample}: Φ_q[{}][{}] = {} but central difference {fd}{}",
                    M::NAME,
                    M::CONSTRAINT_NAMES[r],
                    M::COORDINATE_NAMES[c],
                    d[r][c],
                    if structural { "" } else { " (a structural zero)" }
                );
            }
        }
        let mut nu = [0.0; NC];
        m.velocity_rhs(&q, t, &mut nu);
        m.constraints(&q, t + H, &mut p);
        m.constraints(&q, t - H, &mut n);
        for r in 0..NC {
            let fd = -(p[r] - n[r]) / (2.0 * H);
            assert!((nu[r] - fd).abs() <= TOL * fd.abs().max(1.0), "{} ν[{}] = {} vs {fd}", M::NAME, M::CONSTRAINT_NAMES[r], nu[r]);
        }
        // Φ̇(q, q̇, t) = D q̇ − ν
        let phi_dot = |q: &[f64; NQ], t: f64| {
            let mut d = [[0.0; NQ]; NC];
            let mut nu = [0.0; NC];
            m.jacobian(q, t, &mut d);
            m.velocity_rhs(q, t, &mut nu);
            core::array::from_fn::<f64, NC, _>(|r| (0..NQ).map(|c| d[r][c] * qd[c]).sum::<f64>() - nu[r])
        };
        let qp: [f64; NQ] = core::array::from_fn(|i| q[i] + H * qd[i]);
        let qn: [f64; NQ] = core::array::from_fn(|i| q[i] - H * qd[i]);
        let (fp, fn_) = (phi_dot(&qp, t + H), phi_dot(&qn, t - H));
        let mut gamma = [0.0; NC];
        m.gamma(&q, &qd, t, &mut gamma);
        for r in 0..NC {
            let fd = -(fp[r] - fn_[r]) / (2.0 * H);
            assert!(
                (gamma[r] - fd).abs() <= TOL * fd.abs().max(1.0),
                "{} sample {sample}: γ[{}] = {} but central difference {fd}",
                M::NAME,
                M::CONSTRAINT_NAMES[r],
                gamma[r]
            );
        }
        // The fused evaluations return exactly what the separate functions return.
        let (mut phi1, mut phi2) = ([0.0; NC], [0.0; NC]);
        let (mut d2, mut nu2, mut g2) = ([[0.0; NQ]; NC], [0.0; NC], [0.0; NC]);
        m.constraints(&q, t, &mut phi1);
        m.full_eval(&q, &qd, t, &mut phi2, &mut d2, &mut nu2, &mut g2);
        assert_eq!((phi1, d, nu, gamma), (phi2, d2, nu2, g2), "{}: full_eval differs from the separate functions", M::NAME);
        let (mut phi3, mut d3) = ([0.0; NC], [[0.0; NQ]; NC]);
        m.position_eval(&q, t, &mut phi3, &mut d3);
        assert_eq!((phi1, d), (phi3, d3), "{}: position_eval differs", M::NAME);
    }
}

#[test]
fn every_example_has_exact_derivatives() {
    check(&common::slider_crank::SliderCrank::default(), 1);
    check(&common::four_bar::FourBar::default(), 2);
    check(&common::variable_pendulum::VariablePendulum::default(), 3);
    check(&common::filmstrip::Filmstrip::default(), 4);
    check(&common::web_cutter::WebCutter::default(), 5);
    check(&common::double_a_arm::DoubleAArm::default(), 6);
    check(&common::macpherson::MacPherson::default(), 7);
}

/// The sparse values equal the dense Jacobian's entries at the pattern's positions.
#[test]
fn jacobian_values_follow_the_pattern() {
    use common::slider_crank::SliderCrank;
    let m = SliderCrank::default();
    let q = m.initial_positions();
    let mut d = [[0.0; SliderCrank::NQ]; SliderCrank::NC];
    let mut v = [0.0; SliderCrank::NNZ];
    m.jacobian(&q, 0.3, &mut d);
    m.jacobian_values(&q, 0.3, &mut v);
    for (k, &(r, c)) in SliderCrank::JACOBIAN_PATTERN.iter().enumerate() {
        assert_eq!(v[k], d[r as usize][c as usize]);
    }
    // and every entry outside the pattern is zero
    let nonzero = d.iter().flatten().filter(|x| **x != 0.0).count();
    assert!(nonzero <= SliderCrank::NNZ);
}

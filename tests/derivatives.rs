//! The generated Φ_q, ν and γ of every example against central differences of the generated Φ.
//!
//! Φ_q[r][c] ≈ (Φ(q + h e_c) − Φ(q − h e_c)) / 2h, ν ≈ −(Φ(t + h) − Φ(t − h)) / 2h, and
//! γ = −d/dε [D(q + εq̇, t + ε) q̇ − ν(q + εq̇, t + ε)] at ε = 0 (the total time derivative of Φ̇
//! with q̈ = 0), differenced the same way. With h = 1e-6 the truncation error is O(h²·|Φ'''|)
//! ≈ 1e-12·O(1–1e3) and the rounding error O(ε_mach·|Φ|/h) ≈ 1e-10 for |Φ| = O(1): a tolerance of
//! 1e-6 relative to max(1, |value|) separates right from wrong by orders of magnitude (a wrong
//! term is O(1)), while the exact comparison is the CasADi oracle's job.
use mbd_examples::{
    double_a_arm, filmstrip, four_bar, gyroscope, macpherson, slider_crank, suspension_dynamics, variable_pendulum, web_cutter,
};
#[path = "common/rng.rs"]
mod rng;
/// The examples this test uses (from mbd-examples, where they are compiled once) and the shared
/// generator (`tests/common/`).
mod common {
    pub(crate) use super::{
        double_a_arm, filmstrip, four_bar, gyroscope, macpherson, rng::Rng, slider_crank, suspension_dynamics, variable_pendulum,
        web_cutter,
    };
}

use common::Rng;
use mbd::{Kinematics, Mechanism};

const H: f64 = 1e-6;
const TOL: f64 = 1e-6;

/// Planar mechanisms: v = q̇ and D = Φ_q, so D is checked against differences in q.
fn check<M: Kinematics<f64, NQ, NQ, NC>, const NQ: usize, const NC: usize>(m: &M, seed: u64) {
    let mut rng = Rng::new(seed);
    for sample in 0..50 {
        let mut q = m.initial_positions();
        for x in q.iter_mut() {
            *x += rng.uniform(-0.3, 0.3);
        }
        let v: [f64; NQ] = core::array::from_fn(|_| rng.uniform(-3.0, 3.0));
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
            core::array::from_fn::<f64, NC, _>(|r| (0..NQ).map(|c| d[r][c] * v[c]).sum::<f64>() - nu[r])
        };
        let qp: [f64; NQ] = core::array::from_fn(|i| q[i] + H * v[i]);
        let qn: [f64; NQ] = core::array::from_fn(|i| q[i] - H * v[i]);
        let (fp, fn_) = (phi_dot(&qp, t + H), phi_dot(&qn, t - H));
        let mut gamma = [0.0; NC];
        m.gamma(&q, &v, t, &mut gamma);
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
        m.full_eval(&q, &v, t, &mut phi2, &mut d2, &mut nu2, &mut g2);
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

/// `FiniteDifferences` (the runtime's stand-in for a tool without symbolic derivatives) against
/// the generated exact derivatives, at random states of a planar suspension (springs, dampers, a
/// tyre force) and of the spatial heavy top (gyroscopic forces, a ball joint): ∂h/∂q·B, ∂h/∂v
/// and D by central differences to 1e-8 relative to the largest entry (their error is about
/// u^(2/3) ≈ 4e-11 relative, times the third derivative's scale; measured ≤ 8e-11), K =
/// ∂(Dᵀλ)/∂q·B by nested differences to 1e-6 (about u^(1/2) ≈ 1e-8 relative, times the scale of
/// Φ''''; measured 3.6e-8). A wrong or missing term is of the order of the entry itself.
#[test]
fn finite_differences_agree_with_the_exact_derivatives() {
    use mbd::{ConstraintForces, Dynamics, FiniteDifferences};
    fn compare<M, const NQ: usize, const NV: usize, const NC: usize>(m: &M, seed: u64)
    where
        M: Dynamics<f64, NQ, NV, NC> + ConstraintForces<f64, NQ, NV, NC>,
    {
        let fd = FiniteDifferences::with_constraint_jacobian(m);
        let mut rng = Rng::new(seed);
        let relative = |exact: &[[f64; NV]], approx: &[[f64; NV]]| -> f64 {
            let scale = exact.iter().flatten().fold(1e-300f64, |s, x| s.max(x.abs()));
            exact.iter().flatten().zip(approx.iter().flatten()).fold(0.0f64, |e, (a, b)| e.max((a - b).abs())) / scale
        };
        let mut worst = [0.0f64; 4];
        for _ in 0..10 {
            let mut q = m.initial_positions();
            for x in q.iter_mut() {
                *x += rng.uniform(-0.2, 0.2);
            }
            m.normalize_positions(&mut q);
            let v: [f64; NV] = core::array::from_fn(|_| rng.uniform(-2.0, 2.0));
            let lambda: [f64; NC] = core::array::from_fn(|_| rng.uniform(-50.0, 50.0));
            let t = rng.uniform(0.0, 1.0);
            let (mut exact, mut approx) = ([[0.0; NV]; NV], [[0.0; NV]; NV]);
            m.forces_q(&q, &v, t, &mut exact);
            fd.forces_q(&q, &v, t, &mut approx);
            worst[0] = worst[0].max(relative(&exact, &approx));
            assert!(relative(&exact, &approx) < 1e-8, "{}: ∂h/∂q off by {:e}", M::NAME, relative(&exact, &approx));
            m.forces_v(&q, &v, t, &mut exact);
            fd.forces_v(&q, &v, t, &mut approx);
            worst[1] = worst[1].max(relative(&exact, &approx));
            assert!(relative(&exact, &approx) < 1e-8, "{}: ∂h/∂v off by {:e}", M::NAME, relative(&exact, &approx));
            m.constraint_force_q(&q, t, &lambda, &mut exact);
            fd.constraint_force_q(&q, t, &lambda, &mut approx);
            worst[2] = worst[2].max(relative(&exact, &approx));
            assert!(relative(&exact, &approx) < 1e-6, "{}: K off by {:e}", M::NAME, relative(&exact, &approx));
            let (mut d, mut d_fd) = ([[0.0; NV]; NC], [[0.0; NV]; NC]);
            m.jacobian(&q, t, &mut d);
            fd.jacobian(&q, t, &mut d_fd);
            worst[3] = worst[3].max(relative(&d, &d_fd));
            assert!(relative(&d, &d_fd) < 1e-8, "{}: D off by {:e}", M::NAME, relative(&d, &d_fd));
        }
        eprintln!(
            "{}: largest relative differences ∂h/∂q {:.1e}, ∂h/∂v {:.1e}, K {:.1e}, D {:.1e}",
            M::NAME,
            worst[0],
            worst[1],
            worst[2],
            worst[3]
        );
    }
    compare(&common::suspension_dynamics::DoubleAArmRide::default(), 31);
    compare(&common::gyroscope::Gyroscope::default(), 32);
}

mbd::mechanism! {
    /// A spatial chain of three bars on ball joints, as the benchmark's chain of 16.
    pub BallChain {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body a { mass: 0.1, inertia: [1.0e-6, 8.3e-5, 8.3e-5], at: [0.05, 0.0, 0.0] }
        body b { mass: 0.1, inertia: [1.0e-6, 8.3e-5, 8.3e-5], at: [0.149, 0.0099, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.2] }
        body c { mass: 0.1, inertia: [1.0e-6, 8.3e-5, 8.3e-5], at: [0.244, 0.0393, 0.0], axis_angle: [0.0, 0.0, 1.0, 0.4] }
        spherical ground[0.0, 0.0, 0.0] ~ a[-0.05, 0.0, 0.0];
        spherical a[0.05, 0.0, 0.0] ~ b[-0.05, 0.0, 0.0];
        spherical b[0.05, 0.0, 0.0] ~ c[-0.05, 0.0, 0.0];
    }
}

/// The fused evaluations (`full_eval`, `position_eval`) of a spatial mechanism return exactly
/// what the separate functions return; whether the fused body shares subexpressions (its
/// operation count below the parts' sum) or, sharing none, is emitted as its parts in sequence.
/// Returns whether it was the latter.
fn spatial_fused<M: Kinematics<f64, NQ, NV, NC> + Mechanism, const NQ: usize, const NV: usize, const NC: usize>(m: &M, seed: u64) -> bool {
    let count = |name: &str| M::OP_COUNTS.iter().find(|o| o.function == name).map(|o| o.add + o.mul + o.div + o.call).unwrap();
    let parts = count("constraints") + count("jacobian") + count("velocity_rhs") + count("gamma");
    let mut rng = Rng::new(seed);
    for _ in 0..10 {
        let mut q = m.initial_positions();
        for x in q.iter_mut() {
            *x += rng.uniform(-0.2, 0.2);
        }
        m.normalize_positions(&mut q);
        let v: [f64; NV] = core::array::from_fn(|_| rng.uniform(-2.0, 2.0));
        let t = rng.uniform(0.0, 1.0);
        let (mut phi, mut d, mut nu, mut gamma) = ([0.0; NC], [[0.0; NV]; NC], [0.0; NC], [0.0; NC]);
        m.constraints(&q, t, &mut phi);
        m.jacobian(&q, t, &mut d);
        m.velocity_rhs(&q, t, &mut nu);
        m.gamma(&q, &v, t, &mut gamma);
        let (mut phi2, mut d2, mut nu2, mut gamma2) = ([0.0; NC], [[0.0; NV]; NC], [0.0; NC], [0.0; NC]);
        m.full_eval(&q, &v, t, &mut phi2, &mut d2, &mut nu2, &mut gamma2);
        assert_eq!((phi, d, nu, gamma), (phi2, d2, nu2, gamma2), "{}: full_eval differs from the separate functions", M::NAME);
        let (mut phi3, mut d3) = ([0.0; NC], [[0.0; NV]; NC]);
        m.position_eval(&q, t, &mut phi3, &mut d3);
        assert_eq!((phi, d), (phi3, d3), "{}: position_eval differs", M::NAME);
    }
    count("full_eval") == parts
}

#[test]
fn spatial_fused_evaluations_are_the_separate_ones() {
    // The gyroscope's parts share two operations (its fused body is one); the ball chain's share
    // none (its fused body is the parts in sequence): both ways are checked.
    assert!(!spatial_fused(&common::gyroscope::Gyroscope::default(), 33), "the gyroscope's fused evaluation shares");
    assert!(spatial_fused(&BallChain::default(), 34), "the ball chain's parts share nothing");
}

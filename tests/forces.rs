//! Generated forces: every force element at once, ∂h/∂q and ∂h/∂q̇ against central differences of
//! the generated h, conservative forces against −∂V/∂q of the generated potential energy, and a
//! spring's force against a hand computation.
//!
//! Tolerance: central differences with h = 1e-6 on forces of O(1–100) N carry a truncation error
//! O(h²·|h'''|) ≲ 1e-9 and a rounding error O(ε·|h|/h) ≈ 1e-8; 1e-5 relative to max(1, |value|)
//! separates right from wrong (a wrong term is O(1) or larger).
#[path = "common/rng.rs"]
mod rng;
use mbd_examples::slider_crank;
/// The examples this test uses (from mbd-examples, where they are compiled once) and the shared
/// generator (`tests/common/`).
mod common {
    pub(crate) use super::{rng::Rng, slider_crank};
}

use common::Rng;
use mbd::prelude::*;

mechanism! {
    /// Every force element of the DSL on two bodies.
    pub AllForces {
        params { k: 200.0, c: 3.0 }
        gravity [0.5, -9.81];
        body a { mass: 1.0, inertia: 0.1, at: [0.3, 0.1, 0.2] }
        body b { mass: 2.0, inertia: 0.2, at: [0.8, -0.2, -0.4] }
        revolute ground[0.0, 0.0] ~ a[-0.3, 0.0] { viscous: 0.05 };
        translational a[0.2, 0.0] along [1.0, 0.0] ~ b[0.0, 0.0] along [1.0, 0.0] { viscous: 0.7 };
        spring a[0.1, 0.05] ~ b[0.2, 0.0] { k: k, length: 0.4, c: c, force: 5.0 * sin(t) };
        damper ground[1.0, 1.0] ~ b[0.0, 0.1] { c: 2.0 };
        actuator ground[0.0, 1.0] ~ a[0.0, 0.0] { force: 10.0 * a.vx };
        rotational_spring a ~ b { k: 30.0, angle: 0.2, c: 0.4, torque: 1.0 };
        rotational_damper ground ~ a { c: 0.3 };
        force b[0.1, 0.0] = [1.0, -2.0 * t];
        local_force a[0.0, 0.1] = [3.0, b.omega];
        torque b = 0.5 * cos(t);
    }
}

mechanism! {
    /// Only conservative forces: h = −∂V/∂q.
    pub Conservative {
        gravity [0.3, -9.81];
        body a { mass: 1.5, inertia: 0.1, at: [0.3, 0.1, 0.2] }
        body b { mass: 2.0, inertia: 0.2, at: [0.8, -0.2, -0.4] }
        spring a[0.1, 0.05] ~ b[0.2, 0.0] { k: 150.0, length: 0.4 };
        spring ground[0.0, 0.0] ~ a[0.0, 0.0] { k: 80.0, length: 0.2 };
        rotational_spring a ~ b { k: 30.0, angle: 0.2 };
        rotational_spring ground ~ b { k: 12.0, angle: -0.1 };
    }
}

const H: f64 = 1e-6;
const TOL: f64 = 1e-5;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= TOL * a.abs().max(b.abs()).max(1.0)
}

fn random_state(rng: &mut Rng) -> ([f64; 6], [f64; 6], f64) {
    let q0 = [0.3, 0.1, 0.2, 0.8, -0.2, -0.4];
    let q = core::array::from_fn(|i| q0[i] + rng.uniform(-0.2, 0.2));
    let v = core::array::from_fn(|_| rng.uniform(-2.0, 2.0));
    (q, v, rng.uniform(0.0, 3.0))
}

#[test]
fn force_jacobians_match_central_differences() {
    let m = AllForces::default();
    let mut rng = Rng::new(21);
    for _ in 0..100 {
        let (q, v, t) = random_state(&mut rng);
        let (mut dq, mut dqd) = ([[0.0; 6]; 6], [[0.0; 6]; 6]);
        m.forces_q(&q, &v, t, &mut dq);
        m.forces_v(&q, &v, t, &mut dqd);
        for c in 0..6 {
            let (mut p, mut n) = ([0.0; 6], [0.0; 6]);
            let (mut qp, mut qn) = (q, q);
            qp[c] += H;
            qn[c] -= H;
            m.forces(&qp, &v, t, &mut p);
            m.forces(&qn, &v, t, &mut n);
            for r in 0..6 {
                let fd = (p[r] - n[r]) / (2.0 * H);
                assert!(close(dq[r][c], fd), "∂h[{r}]/∂q[{c}] = {} vs {fd}", dq[r][c]);
            }
            let (mut vp, mut vn) = (v, v);
            vp[c] += H;
            vn[c] -= H;
            m.forces(&q, &vp, t, &mut p);
            m.forces(&q, &vn, t, &mut n);
            for r in 0..6 {
                let fd = (p[r] - n[r]) / (2.0 * H);
                assert!(close(dqd[r][c], fd), "∂h[{r}]/∂q̇[{c}] = {} vs {fd}", dqd[r][c]);
            }
        }
    }
}

#[test]
fn conservative_forces_are_minus_the_potential_gradient() {
    let m = Conservative::default();
    let mut rng = Rng::new(22);
    for _ in 0..100 {
        let (q, v, t) = random_state(&mut rng);
        let mut h = [0.0; 6];
        m.forces(&q, &v, t, &mut h);
        for c in 0..6 {
            let (mut qp, mut qn) = (q, q);
            qp[c] += H;
            qn[c] -= H;
            let grad = (m.potential_energy(&qp, t) - m.potential_energy(&qn, t)) / (2.0 * H);
            assert!(close(h[c], -grad), "h[{c}] = {} but −∂V/∂q = {}", h[c], -grad);
        }
    }
}

mechanism! {
    /// One body on a spring-damper to a ground point.
    pub OneSpring {
        body a { mass: 1.0, inertia: 0.1 }
        spring ground[1.0, 2.0] ~ a[0.1, 0.2] { k: 100.0, length: 0.5, c: 4.0 };
    }
}

/// The spring-damper's generalized force by hand: the tension f = k (l − l₀) + c l̇ pulls the body's
/// point P toward the ground point G with F = f (G − P)/l, which acts on the body as the force F
/// and the moment (r_P − r) × F about its centre of mass.
#[test]
fn spring_damper_force_by_hand() {
    let m = OneSpring::default();
    let (q, v) = ([0.3, -0.4, 0.7], [0.5, -1.0, 2.0]);
    let mut h = [0.0; 3];
    m.forces(&q, &v, 0.0, &mut h);
    let (s, c) = q[2].sin_cos();
    let sp = [0.1, 0.2];
    let p = [q[0] + c * sp[0] - s * sp[1], q[1] + s * sp[0] + c * sp[1]];
    let pd = [v[0] + v[2] * (-s * sp[0] - c * sp[1]), v[1] + v[2] * (c * sp[0] - s * sp[1])];
    let g = [1.0, 2.0];
    let d = [g[0] - p[0], g[1] - p[1]];
    let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let u = [d[0] / l, d[1] / l];
    let ldot = -(u[0] * pd[0] + u[1] * pd[1]);
    let f = 100.0 * (l - 0.5) + 4.0 * ldot;
    let force = [f * u[0], f * u[1]];
    // moment of the force about the body's centre: (r_P − r) × F
    let arm = [p[0] - q[0], p[1] - q[1]];
    let moment = arm[0] * force[1] - arm[1] * force[0];
    for (got, want) in h.iter().zip([force[0], force[1], moment]) {
        // same arithmetic in another order: agreement to rounding
        assert!((got - want).abs() < 1e-12 * want.abs().max(1.0), "{h:?} vs {force:?}, {moment}");
    }
    assert_eq!(OneSpring::EFFECTS, &["point-to-point spring-damper-actuator"]);
    assert_eq!(AllForces::EFFECTS.len(), 6);
}

/// A mechanism without force elements generates no force code: h is identically zero, its
/// operation count is zero.
#[test]
fn undeclared_effects_cost_nothing() {
    let m = common::slider_crank::SliderCrank::default();
    let q = m.initial_positions();
    let mut h = [1.0; 9];
    m.forces(&q, &[0.3; 9], 0.5, &mut h);
    assert_eq!(h, [0.0; 9]);
    let ops = common::slider_crank::SliderCrank::OP_COUNTS.iter().find(|o| o.function == "forces").expect("forces is counted");
    assert_eq!(ops.total(), 0);
    assert!(common::slider_crank::SliderCrank::EFFECTS.is_empty());
}

mbd::mechanism! {
    /// Integer powers as the macro rewrites and emits them: (−x)ⁿ folded to ±xⁿ, x³ and x⁻³
    /// written as products, x⁵ and x⁻⁴ through `powi`, (x²)³ folded to x⁶, a negative base with an odd
    /// and an even power.
    pub Powers {
        body b { mass: 1.0, inertia: 0.1, at: [0.7, -0.4, 0.3] }
        torque b = (-b.x)^3 + b.x^(-3) + (-b.y)^2 + b.y^3 + b.x^5 + b.y^(-4) + (b.x^2)^3 + (-b.phi)^(-1);
    }
}

/// Each power rule against f64 evaluation of the same expression at several states (a sign
/// lost in (−x)ⁿ or a wrong exponent in the emitted products would show at the first).
#[test]
fn integer_powers_evaluate_as_written() {
    let m = Powers::default();
    for &(x, y, phi) in &[(0.7, -0.4, 0.3), (-1.3, 2.1, -0.8), (0.2, 0.9, 1.7)] {
        let q = [x, y, phi];
        let mut h = [0.0; 3];
        m.forces(&q, &[0.0; 3], 0.0, &mut h);
        let expected = (-x).powi(3) + x.powi(-3) + (-y).powi(2) + y.powi(3) + x.powi(5) + y.powi(-4) + x.powi(6) + (-phi).powi(-1);
        assert!((h[2] - expected).abs() <= 1e-12 * expected.abs().max(1.0), "at {q:?}: {} vs {expected}", h[2]);
    }
}

//! Static equilibrium against analytic solutions, and the generated geometric stiffness
//! K = ∂(Φ_qᵀλ)/∂q against central differences of Φ_qᵀλ.
mod common;

use common::Rng;
use mbd::prelude::*;

mechanism! {
    /// A 1 m rod pinned at its end, held by a torsion spring against gravity.
    pub SpringRod {
        params { k: 20.0 }
        gravity [0.0, -9.81];
        body rod { mass: 2.0, inertia: 0.1667, at: [0.5, 0.0, 0.0] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        rotational_spring ground ~ rod { k: k, angle: 0.0 };
    }
}

mechanism! {
    /// A mass hanging on a vertical spring, its rotation held by a torsion spring: no joints.
    pub Hanging {
        gravity [0.0, -9.81];
        body mass { mass: 3.0, inertia: 0.01, at: [0.0, -0.4, 0.2] }
        spring ground[0.0, 0.0] ~ mass[0.0, 0.0] { k: 100.0, length: 0.5 };
        rotational_spring ground ~ mass { k: 1.0 };
    }
}

/// Newton stops at a residual of 1e-9 N·m; with a torsional stiffness of O(10–20) N·m/rad the
/// angle is then within 1e-10 rad, checked to 1e-9.
#[test]
fn rod_on_a_torsion_spring() {
    let m = SpringRod::default();
    // Equilibrium: k θ = −m g (l/2) cos θ, by bisection.
    let f = |th: f64| 20.0 * th + 2.0 * 9.81 * 0.5 * th.cos();
    let (mut lo, mut hi) = (-1.0, 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let theta = 0.5 * (lo + hi);
    let mut q = m.initial_positions();
    let mut lambda = [0.0; 2];
    let mut ws = SpringRod::kkt_workspace();
    let report = StaticSolver::default().solve(&m, &mut q, 0.0, &mut lambda, &mut ws).expect("equilibrium");
    eprintln!("rod on a torsion spring: {report:?}");
    assert!(report.iterations < 20, "{report:?}");
    assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
    assert!((q[2] - theta).abs() < 1e-9, "θ = {} vs {theta}", q[2]);
    // At rest the pin carries the weight.
    let mut d = [[0.0; 3]; 2];
    m.jacobian(&q, 0.0, &mut d);
    let pin = joint_reaction(&m, &q, &d, &lambda, 0).and_then(|r| r.on_j).expect("pin on rod");
    assert!(pin.force[0].abs() < 1e-9 && (pin.force[1] - 2.0 * 9.81).abs() < 1e-9, "{pin:?}");
}

/// y = −(L₀ + m g / k) exactly; tolerance 1e-9 m from the solver's force tolerance /
/// stiffness. The spring starts compressed (0.4 m < 0.5 m), which makes it unstable sideways,
/// but nothing pushes it sideways: the solver does not follow a mode without a force, so the
/// mass drops straight down (x stays 0).
#[test]
fn hanging_mass_without_joints() {
    let m = Hanging::default();
    let mut q = m.initial_positions();
    let mut lambda = [0.0; 0];
    let mut ws = Hanging::kkt_workspace();
    let report = StaticSolver::default().solve(&m, &mut q, 0.0, &mut lambda, &mut ws).expect("equilibrium");
    eprintln!("hanging mass: {report:?}");
    assert!(report.iterations < 10 && matches!(report.stability, Stability::Stable { .. }), "{report:?}");
    assert!(q[0].abs() < 1e-9 && (q[1] + 0.5 + 3.0 * 9.81 / 100.0).abs() < 1e-9 && q[2].abs() < 1e-9, "{q:?}");
}

#[test]
fn wrong_workspace_is_an_error() {
    let m = SpringRod::default();
    let mut q = m.initial_positions();
    let mut ws = KktWorkspace::<f64, 4>::new();
    let err = StaticSolver::default().solve(&m, &mut q, 0.0, &mut [0.0; 2], &mut ws).unwrap_err();
    assert_eq!(err, StaticError::WorkspaceSize { expected: 5, found: 4 });
}

/// Without the torsion spring (and without gravity) the rod is free to turn: every angle is an
/// equilibrium. This used to be an error ("not unique"); now it is what it is, an equilibrium
/// with Neutral stability along the rod's turn (named by the velocity carrying most of the
/// mode's kinetic energy: the centre of mass moving in y as the horizontal rod turns).
#[test]
fn free_rotation_is_neutral() {
    mechanism! {
        pub FreeRod {
            body rod { mass: 2.0, inertia: 0.1667, at: [0.5, 0.0, 0.0] }
            revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        }
    }
    let m = FreeRod::default();
    let mut q = m.initial_positions();
    q[1] += 0.01; // not yet assembled
    let mut ws = FreeRod::kkt_workspace();
    let report = StaticSolver::default().solve(&m, &mut q, 0.0, &mut [0.0; 2], &mut ws).expect("an equilibrium");
    eprintln!("free rod: {report:?}");
    assert_eq!(report.iterations, 0, "assembled, it is at rest already: {report:?}");
    match report.stability {
        Stability::Neutral { direction, omega_squared } => {
            assert_eq!(direction, "rod.y");
            assert_eq!(omega_squared, 0.0, "no load, no stiffness at all");
        }
        other => panic!("{other:?}"),
    }
}

/// K = ∂(Φ_qᵀλ)/∂q against central differences of the generated Jacobian times λ, for every example.
/// Tolerance as in tests/derivatives.rs (h = 1e-6, 1e-6 relative).
fn check_k<M: ConstraintForces<f64, NQ, NQ, NC>, const NQ: usize, const NC: usize>(m: &M, seed: u64) {
    let mut rng = Rng::new(seed);
    let g = |q: &[f64; NQ], lambda: &[f64; NC]| {
        let mut d = [[0.0; NQ]; NC];
        m.jacobian(q, 0.4, &mut d);
        core::array::from_fn::<f64, NQ, _>(|c| (0..NC).map(|r| d[r][c] * lambda[r]).sum())
    };
    for _ in 0..20 {
        let mut q = m.initial_positions();
        for v in q.iter_mut() {
            *v += rng.uniform(-0.3, 0.3);
        }
        let lambda: [f64; NC] = core::array::from_fn(|_| rng.uniform(-5.0, 5.0));
        let mut k = [[0.0; NQ]; NQ];
        m.constraint_force_q(&q, 0.4, &lambda, &mut k);
        for c in 0..NQ {
            let (mut qp, mut qn) = (q, q);
            qp[c] += 1e-6;
            qn[c] -= 1e-6;
            let (gp, gn) = (g(&qp, &lambda), g(&qn, &lambda));
            for r in 0..NQ {
                let fd = (gp[r] - gn[r]) / 2e-6;
                assert!((k[r][c] - fd).abs() <= 1e-6 * fd.abs().max(1.0), "{} K[{r}][{c}] = {} vs {fd}", M::NAME, k[r][c]);
            }
        }
    }
}

#[test]
fn geometric_stiffness_matches_central_differences() {
    check_k(&common::slider_crank::SliderCrank::default(), 31);
    check_k(&common::four_bar::FourBar::default(), 32);
    check_k(&common::variable_pendulum::VariablePendulum::default(), 33);
    check_k(&common::filmstrip::Filmstrip::default(), 34);
    check_k(&common::web_cutter::WebCutter::default(), 35);
    check_k(&common::double_a_arm::DoubleAArm::default(), 36);
    check_k(&common::macpherson::MacPherson::default(), 37);
}

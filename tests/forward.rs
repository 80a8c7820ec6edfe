//! Forward dynamics: the generated sparse Schur-complement solve against a dense solve of the
//! saddle-point system, a pendulum against its closed form, and the projections.
//!
//! Tolerances: the dense reference solves the (NQ + NC)-square KKT system by LU with partial
//! pivoting, the generated code S = Φ_q M⁻¹ Φ_qᵀ by LDLᵀ; both are backward stable, so they agree
//! to about ε · cond(KKT) · |values|. With masses 0.1–3 kg, lengths 0.1–1 m and |q̇| ≤ 3 the
//! condition numbers stay below 1e5: 1e-9 relative to max(1, |value|) separates a right solve
//! from a wrong one (a wrong entry is O(1)). A double pendulum with a mass ratio of 10⁶ (1000 kg
//! carrying 1 g, issue 10 item 6) passes the same bound: the Schur complement D M⁻¹ Dᵀ is
//! formed with M⁻¹ exactly (M is diagonal), so the ratio costs no accuracy in either solve.
#[path = "common/rng.rs"]
mod rng;
/// The shared generator (`tests/common/`).
mod common {
    pub(crate) use super::rng::Rng;
}

use common::Rng;
use mbd::nalgebra;
use mbd::prelude::*;

mechanism! {
    /// A free four-bar under gravity (no driver, one degree of freedom), with a spring-damper.
    pub FreeFourBar {
        params { a: 0.1, b: 0.3, c: 0.25, d: 0.3 }
        gravity [0.0, -9.81];
        body crank   { mass: 0.5, inertia: 5.0e-4, at: [0.05, 0.0, 0.0] }
        body coupler { mass: 1.2, inertia: 9.0e-3, at: [0.18, 0.12, 0.97] }
        body rocker  { mass: 1.0, inertia: 5.2e-3, at: [0.28, 0.12, 1.70] }
        revolute ground[0.0, 0.0] ~ crank[-a / 2.0, 0.0];
        revolute crank[a / 2.0, 0.0] ~ coupler[-b / 2.0, 0.0];
        revolute coupler[b / 2.0, 0.0] ~ rocker[c / 2.0, 0.0];
        revolute rocker[-c / 2.0, 0.0] ~ ground[d, 0.0];
        spring ground[0.0, 0.2] ~ coupler[0.0, 0.0] { k: 40.0, length: 0.15, c: 0.5 };
    }
}

mechanism! {
    /// A slider-crank with a driver (rheonomic constraint), a translational joint and a torque.
    pub DrivenSliderCrank {
        params { r: 0.1, l: 0.3 }
        gravity [0.0, -9.81];
        body crank  { mass: 2.0, inertia: 0.01, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 0.8, inertia: 0.006, at: [0.25, 0.0, 0.0] }
        body piston { mass: 0.5, inertia: 1.0e-4, at: [0.4, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ piston[0.0, 0.0];
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ piston[0.0, 0.0] along [1.0, 0.0];
        drive crank.phi = 0.3 + 5.0 * t + 0.5 * sin(3.0 * t);
        damper ground[0.6, 0.0] ~ piston[0.0, 0.0] { c: 4.0 };
    }
}

mechanism! {
    /// A loop of four moving bodies that closes without ground (a jointed quadrilateral hung
    /// by one corner): its Schur complement has a 4-cycle of joints, so its factorization
    /// needs fill-in (every other mechanism here closes its loops through ground, where a
    /// planner that forgot the fill would pass).
    pub HangingQuad {
        gravity [0.0, -9.81];
        body a { mass: 0.4, inertia: 1.0e-3, at: [0.0, -0.1, 1.5708] }
        body b { mass: 0.6, inertia: 2.0e-3, at: [0.1, -0.2, 0.0] }
        body c { mass: 0.5, inertia: 1.5e-3, at: [0.2, -0.1, 1.5708] }
        body d { mass: 0.7, inertia: 2.5e-3, at: [0.1, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ d[-0.1, 0.0];
        revolute d[-0.1, 0.0] ~ a[0.1, 0.0];
        revolute a[-0.1, 0.0] ~ b[-0.1, 0.0];
        revolute b[0.1, 0.0] ~ c[-0.1, 0.0];
        revolute c[0.1, 0.0] ~ d[0.1, 0.0];
        spring ground[0.3, 0.0] ~ c[0.0, 0.0] { k: 20.0, length: 0.1, c: 0.2 };
    }
}

mechanism! {
    /// A double pendulum with a mass ratio of 10⁶: a 1000 kg link carrying a 1 g one.
    pub HeavyLight {
        gravity [0.0, -9.81];
        body heavy { mass: 1000.0, inertia: 83.3, at: [0.5, 0.0, 0.0] }
        body light { mass: 1.0e-3, inertia: 8.3e-6, at: [1.05, -0.05, -0.8] }
        revolute ground[0.0, 0.0] ~ heavy[-0.5, 0.0];
        revolute heavy[0.5, 0.0] ~ light[-0.05, 0.0];
    }
}

mechanism! {
    /// A single pendulum: a rod of length 2 l pinned at one end.
    pub Pendulum {
        params { l: 0.5, m: 1.5 }
        gravity [0.0, -9.81];
        body rod { mass: m, inertia: m * (2.0 * l) ^ 2 / 12.0, at: [l, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ rod[-l, 0.0];
    }
}

/// q̈ and λ by LU of the dense saddle-point matrix [[M, −Dᵀ], [D, 0]].
fn dense<M, const NQ: usize, const NC: usize, const N: usize>(
    m: &M,
    q: &[f64; NQ],
    v: &[f64; NQ],
    t: f64,
    alpha: f64,
    beta: f64,
) -> ([f64; NQ], [f64; NC])
where
    M: Dynamics<f64, NQ, NQ, NC>,
{
    let (mut phi, mut d, mut nu, mut gamma) = ([0.0; NC], [[0.0; NQ]; NC], [0.0; NC], [0.0; NC]);
    m.full_eval(q, v, t, &mut phi, &mut d, &mut nu, &mut gamma);
    let mut h = [0.0; NQ];
    m.forces(q, v, t, &mut h);
    let mut mass = [[0.0; NQ]; NQ];
    m.add_mass_matrix(q, 1.0, &mut mass);
    let mut a = [[0.0; N]; N];
    let mut b = [0.0; N];
    for i in 0..NQ {
        a[i][..NQ].copy_from_slice(&mass[i]);
        b[i] = h[i];
        for r in 0..NC {
            a[i][NQ + r] = -d[r][i];
            a[NQ + r][i] = d[r][i];
        }
    }
    for r in 0..NC {
        let dv: f64 = (0..NQ).map(|i| d[r][i] * v[i]).sum();
        b[NQ + r] = gamma[r] - 2.0 * alpha * (dv - nu[r]) - beta * beta * phi[r];
    }
    // nalgebra's LU with partial pivoting: a solver independent of mbd's own
    let x = nalgebra::DMatrix::from_fn(N, N, |i, j| a[i][j])
        .lu()
        .solve(&nalgebra::DVector::from_column_slice(&b))
        .expect("the saddle-point matrix is regular");
    b.copy_from_slice(x.as_slice());
    (core::array::from_fn(|i| b[i]), core::array::from_fn(|r| b[NQ + r]))
}

fn agree<const N: usize>(what: &str, a: &[f64; N], b: &[f64; N]) {
    for i in 0..N {
        let tol = 1e-9 * a[i].abs().max(b[i].abs()).max(1.0);
        assert!((a[i] - b[i]).abs() <= tol, "{what}[{i}]: generated {} vs dense {}", a[i], b[i]);
    }
}

fn check_against_dense<M, const NQ: usize, const NC: usize, const N: usize>(m: &M, seed: u64)
where
    M: ForwardDynamics<f64, NQ, NQ, NC>,
{
    let mut rng = Rng::new(seed);
    let q_ref = m.initial_positions();
    for _ in 0..100 {
        let q: [f64; NQ] = core::array::from_fn(|i| q_ref[i] + rng.uniform(-0.05, 0.05));
        let v: [f64; NQ] = core::array::from_fn(|_| rng.uniform(-3.0, 3.0));
        let t = rng.uniform(0.0, 2.0);
        let (alpha, beta) = (rng.uniform(0.0, 10.0), rng.uniform(0.0, 10.0));
        let options = DynamicsOptions::baumgarte(alpha, beta);
        let (mut vd, mut lambda) = ([0.0; NQ], [0.0; NC]);
        m.accelerations(&q, &v, t, &options, &mut vd, &mut lambda).expect("a regular configuration");
        let (vd_ref, lambda_ref) = dense::<M, NQ, NC, N>(m, &q, &v, t, alpha, beta);
        agree("q̈", &vd, &vd_ref);
        agree("λ", &lambda, &lambda_ref);
    }
}

#[test]
fn sparse_solve_matches_the_dense_saddle_point_solve() {
    check_against_dense::<_, 9, 8, 17>(&FreeFourBar::default(), 1);
    check_against_dense::<_, 9, 9, 18>(&DrivenSliderCrank::default(), 2);
    check_against_dense::<_, 3, 2, 5>(&Pendulum::default(), 3);
    check_against_dense::<_, 12, 10, 22>(&HangingQuad::default(), 4);
    check_against_dense::<_, 6, 4, 10>(&HeavyLight::default(), 5);
}

/// A rod pinned at one end: J_O θ̈ = −m g l cos θ with J_O = J + m l² and θ the rod's angle from
/// the x axis; the pin force balances gravity and the centripetal and tangential accelerations.
#[test]
fn pendulum_acceleration_matches_the_closed_form() {
    let p = Pendulum::default();
    let (l, m, g) = (p.l, p.m, 9.81);
    let j_o = m * (2.0 * l) * (2.0 * l) / 12.0 + m * l * l;
    for &(theta, omega) in &[(0.0, 0.0), (0.7, 1.3), (-2.0, -4.0), (3.0, 0.2)] {
        let (s, c) = f64::sin_cos(theta);
        let q = [l * c, l * s, theta];
        let v = [-l * s * omega, l * c * omega, omega];
        let (mut vd, mut lambda) = ([0.0; 3], [0.0; 2]);
        p.accelerations(&q, &v, 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda).unwrap();
        let alpha = -m * g * l * c / j_o;
        assert!((vd[2] - alpha).abs() < 1e-12, "θ̈ = {} vs {}", vd[2], alpha);
        // Centre of mass acceleration, then the pin force F = m a − m g.
        let ax = -l * s * alpha - l * c * omega * omega;
        let ay = l * c * alpha - l * s * omega * omega;
        assert!((vd[0] - ax).abs() < 1e-12 && (vd[1] - ay).abs() < 1e-12);
        // Φ = r^P_ground − r^P_rod, so (Φ_qᵀλ) on the rod's x, y rows is −λ: the pin force on
        // the rod, F = m a − m g.
        let (fx, fy) = (m * ax, m * ay + m * g);
        assert!((-lambda[0] - fx).abs() < 1e-12 && (-lambda[1] - fy).abs() < 1e-12, "λ = {lambda:?}, F = ({fx}, {fy})");
    }
}

/// Projection brings a perturbed state back onto Φ = 0 and Φ_q q̇ = ν, in few Newton steps.
#[test]
fn projection_restores_the_constraints() {
    let m = FreeFourBar::default();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut FreeFourBar::workspace(), &mut q, 0.0).unwrap();
    let mut rng = Rng::new(7);
    for x in q.iter_mut() {
        *x += rng.uniform(-1e-3, 1e-3);
    }
    let mut v: [f64; 9] = core::array::from_fn(|_| rng.uniform(-1.0, 1.0));
    mbd::project(&m, 0.0, &mut q, &mut v, &DynamicsOptions::default(), 1e-12, 8).unwrap();
    let (mut phi, mut d) = ([0.0; 8], [[0.0; 9]; 8]);
    m.position_eval(&q, 0.0, &mut phi, &mut d);
    assert!(phi.iter().all(|x| x.abs() <= 1e-12), "Φ = {phi:?}");
    for row in &d {
        let rate: f64 = row.iter().zip(&v).map(|(a, b)| a * b).sum();
        assert!(rate.abs() <= 1e-12, "Φ_q q̇ = {rate}");
    }
}

mechanism! {
    /// A duplicated revolute makes its rows dependent: without `allow_redundant` the error
    /// names one of them; with it (the default) the row is dropped and the motion is the single
    /// pin's.
    pub TwicePinned {
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.02, at: [0.25, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ rod[-0.25, 0.0];
        revolute rod[-0.25, 0.0] ~ ground[0.0, 0.0];
    }
}

#[test]
fn redundant_constraints_are_named_or_dropped() {
    let m = TwicePinned::default();
    let q = [0.25, 0.0, 0.0];
    let v = [0.0; 3];
    let (mut vd, mut lambda) = ([0.0; 3], [0.0; 4]);
    let strict = DynamicsOptions::default().with_allow_redundant(false);
    let err = m.accelerations(&q, &v, 0.0, &strict, &mut vd, &mut lambda).unwrap_err();
    match err {
        DynamicsError::DependentConstraint { row, .. } => assert!(row.starts_with("revolute rod~ground"), "{row}"),
        other => panic!("expected a dependent constraint, got {other:?}"),
    }
    m.accelerations(&q, &v, 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda).unwrap();
    let j_o = 0.02 + 0.25 * 0.25;
    assert!((vd[2] - (-9.81 * 0.25 / j_o)).abs() < 1e-12, "θ̈ = {}", vd[2]);
    // Each direction's load is carried by one of the two joints (which one is the ordering's
    // choice); the dropped row's pivot is 0 or rounding (d ≤ 1e-16 S_kk ≪ τ S_kk = 1e-8 S_kk:
    // weight 1/(1 + ρ⁸) < 1e-64), so its multiplier is zero to rounding of the ~10 N load.
    let tiny = |l: f64| l.abs() < 1e-12;
    assert!(tiny(lambda[0]) || tiny(lambda[2]), "λ = {lambda:?}");
    assert!(tiny(lambda[1]) || tiny(lambda[3]), "λ = {lambda:?}");
}

mechanism! {
    /// A block held on the x axis by y² = 0: a constraint with no direction where it holds.
    pub SquaredGuide {
        gravity [0.0, -9.81];
        body block { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        constraint block.y^2 = 0.0;
        fix block.phi;
    }
}

/// A zero row of D is degenerate, not redundant: no option drops it, so its error suggests none
/// — with `allow_redundant` on (the default) or off, it is not the dependent-row error whose
/// advice is that option (issue 39, item 6).
#[test]
fn a_constraint_without_direction_is_degenerate_under_any_option() {
    let m = SquaredGuide::default();
    let (mut vd, mut lambda) = ([0.0; 3], [0.0; 2]);
    for options in [DynamicsOptions::default(), DynamicsOptions::default().with_allow_redundant(false)] {
        let err = m.accelerations(&[0.0; 3], &[1.0, 0.0, 0.0], 0.0, &options, &mut vd, &mut lambda).unwrap_err();
        assert!(matches!(err, DynamicsError::DegenerateConstraint { t: 0.0, row } if row.starts_with("constraint")), "{err:?}");
        assert!(!err.to_string().contains("Options"), "{err}");
    }
}

#[test]
fn a_non_positive_mass_is_named() {
    let m = Pendulum { l: 0.5, m: 0.0 };
    let (mut vd, mut lambda) = ([0.0; 3], [0.0; 2]);
    let err = m.accelerations(&[0.5, 0.0, 0.0], &[0.0; 3], 0.0, &DynamicsOptions::default(), &mut vd, &mut lambda).unwrap_err();
    assert_eq!(err, DynamicsError::NonPositiveMass { body: "rod", value: 0.0 });
}

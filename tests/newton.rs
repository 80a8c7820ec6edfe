//! Generalized-α's Newton matrix in the sparse storage planned at compile time
//! (`NewtonMatrix`, `mbd::sparse`): its entries equal the dense matrix built from the generated
//! dense functions, nothing lies outside the planned pattern, and the generated straight-line
//! factorization and the runtime's loop over the pattern solve it alike — dropping a redundant
//! constraint's multiplier in both; and, where the step's end is q ⊕ Δ on the rotation group,
//! the matrix is the exact derivative of the residual it is the matrix of (finite differences
//! along the group's own update, body and joint coordinates).
/// `both_ways!` (the same mechanism in body and joint coordinates); the module's other helpers
/// are for other tests.
#[allow(dead_code)]
#[path = "common/joint.rs"]
mod joint;
#[path = "common/rng.rs"]
mod rng;
/// The shared generator (`tests/common/`).
mod common {
    pub(crate) use super::rng::Rng;
}

use common::Rng;
use mbd::prelude::*;

mechanism! {
    /// A slider-crank with a spring-damper on the slider: ∂h/∂q and ∂h/∂v off the diagonal.
    pub SpringCrank {
        gravity [0.0, -9.81];
        body crank  { mass: 1.0, inertia: 0.02, at: [0.05, 0.0, 0.0] }
        body rod    { mass: 2.0, inertia: 0.10, at: [0.3, 0.0, 0.0] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.5, 0.0, 0.0] }
        revolute  ground[0.0, 0.0]  ~ crank[-0.05, 0.0];
        revolute  crank[0.05, 0.0]  ~ rod[-0.2, 0.0];
        revolute  rod[0.2, 0.0]     ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        spring slider[0.0, 0.0] ~ crank[0.0, 0.02] { k: 2.0e3, length: 0.3, c: 5.0 };
    }
}

mechanism! {
    /// A rod on a pin with Coulomb friction, and a wheel on a rubbing axle through its centre
    /// at the rod's end: the friction's derivatives in the matrix, and its slope in the loads
    /// beside −Dᵀ — for the axle on entries D lacks (its rows leave the wheel's angle out).
    pub PinFriction {
        gravity [0.0, -9.81];
        body rod { mass: 1.5, inertia: 0.125, at: [0.5, 0.0, 0.0] }
        body bob { mass: 0.5, inertia: 0.01, at: [1.0, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0] { coulomb: 0.2, radius: 0.01, slip_velocity: 1.0e-3 };
        revolute rod[0.5, 0.0] ~ bob[0.0, 0.0] { coulomb: 0.3, radius: 0.005, slip_velocity: 1.0e-3 };
        rotational_spring rod ~ bob { k: 30.0, c: 0.4 };
    }
}

mechanism! {
    /// A spatial gyroscope-like rotor on a spherical joint, with products of inertia (M's
    /// off-diagonal entries) and the gyroscopic term in ∂h/∂v.
    pub Top {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body rotor { mass: 2.0, inertia: [0.02, 0.03, 0.05, 0.001, -0.002, 0.003], at: [0.0, 0.0, 0.3], angles: [0.1, 0.2, 0.0] }
        spherical ground[0.0, 0.0, 0.0] ~ rotor[0.0, 0.0, -0.3];
    }
}

mechanism! {
    /// A spatial arm on a rubbing hinge and a disc on a rubbing axle through its centre: the
    /// spatial friction's slope in the hinges' loads beside −Dᵀ.
    pub SpatialHingeFriction {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body arm { mass: 1.0, inertia: [0.01, 0.05, 0.05, 0.0, 0.001, 0.0], at: [0.5, 0.0, 0.0] }
        body disc { mass: 0.5, inertia: [0.002, 0.004, 0.002], at: [1.0, 0.0, 0.0] }
        revolute ground[0.0, 0.0, 0.0] along [0.0, 1.0, 0.0] ~ arm[-0.5, 0.0, 0.0] along [0.0, 1.0, 0.0]
            { coulomb: 0.2, radius: 0.01, slip_velocity: 1.0e-3 };
        revolute arm[0.5, 0.0, 0.0] along [1.0, 0.0, 0.0] ~ disc[0.0, 0.0, 0.0] along [1.0, 0.0, 0.0]
            { coulomb: 0.3, radius: 0.005, slip_velocity: 1.0e-3 };
    }
}

joint::both_ways! {
    /// Two spatial bodies, a ball joint and a hinge, a spring across them and products of
    /// inertia: rows of D and of the stiffness in some of a body's rotational columns only. In
    /// joint coordinates (`BallAndHingeJoints`) the ball joint's quaternion is in q, and M(q) and
    /// the matrix are dense (the trait's provided `newton_matrix`).
    BallAndHinge, BallAndHingeJoints {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body upper { mass: 1.0, inertia: [0.0835, 0.08, 0.002, 0.001, 0.0, 0.0], at: [0.0, 0.5, 0.0], axis_angle: [1.0, 0.0, 0.0, -1.5707963267948966] }
        body lower { mass: 0.7, inertia: [0.0585, 0.0585, 0.0007], at: [0.0, 1.0, 0.35] }
        spherical ground[0.0, 0.0, 0.0] ~ upper[0.0, 0.0, -0.5];
        revolute upper[0.0, 0.0, 0.5] along [1.0, 0.0, 0.0] ~ lower[0.0, 0.0, -0.35] along [1.0, 0.0, 0.0];
        spring ground[0.3, 0.0, 0.0] ~ lower[0.0, 0.0, 0.35] { k: 400.0, length: 0.8, c: 3.0 };
    }
}

mechanism! {
    /// A rod pinned twice at the same point: two rows that repeat two others.
    pub TwicePinned {
        gravity [0.0, -9.81];
        body rod { mass: 1.0, inertia: 0.083, at: [0.5, 0.0, 0.0] }
        revolute first: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        revolute second: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
    }
}

/// The dense Newton matrix from the dense generated functions, unknowns v̇ then λ.
#[allow(clippy::too_many_arguments)]
fn dense<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(
    m: &M,
    q: &[f64; NQ],
    v: &[f64; NV],
    t: f64,
    lambda: &[f64; NC],
    c_v: f64,
    c_q: f64,
) -> [[f64; N]; N]
where
    M: NewtonMatrix<f64, NQ, NV, NC>,
{
    let (mut hq, mut hv, mut k) = ([[0.0; NV]; NV], [[0.0; NV]; NV], [[0.0; NV]; NV]);
    m.forces_q(q, v, t, &mut hq);
    m.forces_v(q, v, t, &mut hv);
    m.friction_derivatives(q, v, t, lambda, &mut hq, &mut hv);
    m.constraint_force_q(q, t, lambda, &mut k);
    let mut a = [[0.0; NV]; NV];
    m.add_mass_matrix(q, 1.0, &mut a);
    let mut d = [[0.0; NV]; NC];
    m.jacobian(q, t, &mut d);
    let mut d_lambda = [[0.0; NV]; NC];
    m.friction_multiplier_derivatives(q, v, t, lambda, &mut d_lambda);
    let mut full = [[0.0; N]; N];
    for i in 0..NV {
        for j in 0..NV {
            full[i][j] = a[i][j] - c_v * hv[i][j] - c_q * (hq[i][j] + k[i][j]);
        }
        for r in 0..NC {
            full[i][NV + r] = -d[r][i] - d_lambda[r][i];
            full[NV + r][i] = d[r][i];
        }
    }
    full
}

/// At random states: the planned storage holds the dense matrix's entries and nothing of it
/// lies outside the pattern; then the generated factorization and `mbd::sparse::factor` both
/// solve A x = b for a known x. Returns how many multipliers were dropped.
fn check<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(m: &M, seed: u64) -> usize
where
    M: NewtonMatrix<f64, NQ, NV, NC>,
{
    let mut rng = Rng::new(seed);
    let pattern = M::NEWTON_PATTERN;
    let nnz = M::JACOBIAN_PATTERN.len();
    let mut dropped_rows = 0;
    for _ in 0..20 {
        let mut q = m.initial_positions();
        for x in q.iter_mut() {
            *x += rng.uniform(-0.1, 0.1);
        }
        m.normalize_positions(&mut q);
        let v: [f64; NV] = core::array::from_fn(|_| rng.uniform(-2.0, 2.0));
        let lambda: [f64; NC] = core::array::from_fn(|_| rng.uniform(-20.0, 20.0));
        let t = rng.uniform(0.0, 1.0);
        // h = 1 ms, ρ∞ = 0.8: c_v = γ'h, c_q = β'h² of that size.
        let (c_v, c_q) = (1.2e-3, 4.0e-7);
        let mut s = M::newton_storage();
        let mut phi = [0.0; NC];
        m.newton_matrix(&q, &v, &[0.0; NV], t, &lambda, None, c_v, c_q, &mut phi, &mut s, mbd::DenseArrays::new().scratch());
        let a = dense::<M, NQ, NV, NC, N>(m, &q, &v, t, &lambda, c_v, c_q);
        // Every entry: planned ones equal (same expressions, another CSE: rounding only), the
        // rest exactly zero.
        let mut planned = [[false; N]; N];
        for i in 0..N {
            let u = pattern.unknown[i] as usize;
            for p in pattern.row_start[i] as usize..pattern.row_start[i + 1] as usize {
                let w = pattern.unknown[pattern.columns[p] as usize] as usize;
                planned[u][w] = true;
                let (got, want) = (s.as_ref()[nnz + p], a[u][w]);
                assert!((got - want).abs() <= 1e-12 * want.abs().max(1.0), "{}: entry ({u}, {w}) {got} ≠ {want}", M::NAME);
            }
        }
        for u in 0..N {
            for w in 0..N {
                assert!(planned[u][w] || a[u][w] == 0.0, "{}: ({u}, {w}) = {} outside the pattern", M::NAME, a[u][w]);
            }
        }
        // A known solution, without components along dropped multipliers (checked below).
        let x: [f64; N] = core::array::from_fn(|_| rng.uniform(-1.0, 1.0));
        let (mut generated, mut runtime) = (s, s);
        let mut dropped = [false; NC];
        let ratio = M::newton_factor(&mut generated, 1e-13, true, &mut dropped).expect("regular velocities");
        let mut dropped_runtime = [false; NC];
        let ratio_runtime =
            mbd::sparse::factor(&pattern, &mut runtime.as_mut()[nnz..], NV, 1e-13, true, &mut dropped_runtime).expect("regular velocities");
        assert_eq!(dropped, dropped_runtime, "{}: both drop the same rows", M::NAME);
        // Both measure a multiplier's pivot against the same scale Σ D_rc² / |u_cc| (the
        // generated one keeps 1/u_cc on the diagonal): equal ratios, to rounding. Masses other
        // than 1 kg tell a scale in the wrong units.
        assert!((ratio - ratio_runtime).abs() <= 1e-9 * ratio_runtime, "{}: smallest pivot ratio {ratio} ≠ {ratio_runtime}", M::NAME);
        dropped_rows = dropped.iter().filter(|&&d| d).count();
        let mut x = x;
        for r in 0..NC {
            if dropped[r] {
                x[NV + r] = 0.0;
            }
        }
        let mut b: [f64; N] = core::array::from_fn(|i| (0..N).map(|j| a[i][j] * x[j]).sum());
        for r in 0..NC {
            if dropped[r] {
                b[NV + r] = 0.0;
            }
        }
        let mut b_runtime = b;
        M::newton_solve(&generated, &mut b);
        mbd::sparse::solve(&pattern, &runtime.as_ref()[nnz..], &mut b_runtime);
        // The matrix's condition here is O(1e4) (masses against β'h²-scaled stiffness and unit
        // rows of D): 1e-9 leaves a margin of 1e3 over rounding, while a wrong entry or update
        // is O(1).
        // A dropped multiplier comes out 0, as x has it.
        for i in 0..N {
            assert!((b[i] - x[i]).abs() < 1e-9, "{}: generated solve x[{i}] = {} ≠ {}", M::NAME, b[i], x[i]);
            assert!((b_runtime[i] - x[i]).abs() < 1e-9, "{}: runtime solve x[{i}] = {} ≠ {}", M::NAME, b_runtime[i], x[i]);
        }
    }
    dropped_rows
}

#[test]
fn the_planned_matrix_is_the_dense_one_and_both_factorizations_solve_it() {
    assert_eq!(check::<_, 9, 9, 8, 17>(&SpringCrank::default(), 1), 0);
    assert_eq!(check::<_, 6, 6, 4, 10>(&PinFriction::default(), 2), 0);
    assert_eq!(check::<_, 7, 6, 3, 9>(&Top::default(), 3), 0);
    assert_eq!(check::<_, 14, 12, 10, 22>(&SpatialHingeFriction::default(), 8), 0);
}

/// The repeated pin's two rows have no pivot of their own: both factorizations drop them (Δλ = 0
/// for them) and solve with the first pin carrying the load.
#[test]
fn both_factorizations_drop_a_repeated_pin() {
    assert_eq!(check::<_, 3, 3, 4, 7>(&TwicePinned::default(), 4), 2);
}

/// q ⊕ Δ on the group, written here from the quaternion product (as generalized-α moves q):
/// a coordinate's rate adds to it, a body-frame rotation vector w turns its Euler parameters
/// e ← e ⊗ (cos(θ/2), sin(θ/2) w/θ).
fn on_group<M: Kinematics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    q: &[f64; NQ],
    delta: &[f64; NV],
) -> [f64; NQ] {
    let mut q = *q;
    for (i, velocity) in M::VELOCITIES.iter().enumerate() {
        match velocity.kind {
            mbd::VelocityKind::Rate { coordinate } => q[coordinate as usize] += delta[i],
            mbd::VelocityKind::Angular { quaternion, axis: 0 } => {
                let (at, w) = (quaternion as usize, [delta[i], delta[i + 1], delta[i + 2]]);
                let theta = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
                let s = if theta > 0.0 { (theta / 2.0).sin() / theta } else { 0.5 };
                let p = [(theta / 2.0).cos(), s * w[0], s * w[1], s * w[2]];
                let e = [q[at], q[at + 1], q[at + 2], q[at + 3]];
                q[at] = e[0] * p[0] - e[1] * p[1] - e[2] * p[2] - e[3] * p[3];
                q[at + 1] = e[0] * p[1] + e[1] * p[0] + e[2] * p[3] - e[3] * p[2];
                q[at + 2] = e[0] * p[2] - e[1] * p[3] + e[2] * p[0] + e[3] * p[1];
                q[at + 3] = e[0] * p[3] + e[1] * p[2] - e[2] * p[1] + e[3] * p[0];
            }
            _ => {}
        }
    }
    q
}

/// At random states with rotations of 0.1–0.4 rad a step (a heavy top's 150 rad/s at h = 1–3
/// ms): the planned Newton matrix given the step's displacement Δ is the derivative of
/// generalized-α's residual r(v̇, λ) = [M v̇ − h − Dᵀλ; Φ/c_q] at q₊ = q ⊕ (Δ + c_q (v̇ − v̇₀)),
/// v₊ = v + c_v (v̇ − v̇₀), by central differences in v̇; and it is not the matrix without the
/// tangent operator (`None`), which this check tells apart. Returns the largest relative
/// differences (with T, without).
fn tangent_check<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize>(m: &M, seed: u64) -> (f64, f64)
where
    M: NewtonMatrix<f64, NQ, NV, NC>,
{
    let mut rng = Rng::new(seed);
    let pattern = M::NEWTON_PATTERN;
    let nnz = M::JACOBIAN_PATTERN.len();
    // A step of 10 ms at ρ∞ = 0.8 (c_v = γ'h, c_q = β'h²): the position terms well above the
    // differences' rounding.
    let (c_v, c_q) = (1.2e-2, 4.0e-5);
    let (mut with, mut without) = (0.0f64, 0.0f64);
    for _ in 0..10 {
        let mut q0 = m.initial_positions();
        for x in q0.iter_mut() {
            *x += rng.uniform(-0.1, 0.1);
        }
        m.normalize_positions(&mut q0);
        let v0: [f64; NV] = core::array::from_fn(|_| rng.uniform(-2.0, 2.0));
        let delta: [f64; NV] = core::array::from_fn(|_| rng.uniform(0.1, 0.4) * if rng.uniform(0.0, 1.0) < 0.5 { -1.0 } else { 1.0 });
        let lambda: [f64; NC] = core::array::from_fn(|_| rng.uniform(-20.0, 20.0));
        let t = rng.uniform(0.0, 1.0);
        let residual = |dvd: &[f64; NV]| -> [f64; N] {
            let q = on_group::<M, NQ, NV, NC>(&q0, &core::array::from_fn(|i| delta[i] + c_q * dvd[i]));
            let v: [f64; NV] = core::array::from_fn(|i| v0[i] + c_v * dvd[i]);
            let (mut force, mut inertia, mut phi, mut d) = ([0.0; NV], [0.0; NV], [0.0; NC], [[0.0; NV]; NC]);
            m.forces(&q, &v, t, &mut force);
            m.mass_times(&q, dvd, &mut inertia);
            m.constraints(&q, t, &mut phi);
            m.jacobian(&q, t, &mut d);
            core::array::from_fn(|i| {
                if i < NV {
                    inertia[i] - force[i] - (0..NC).map(|r| d[r][i] * lambda[r]).sum::<f64>()
                } else {
                    phi[i - NV] / c_q
                }
            })
        };
        let q = on_group::<M, NQ, NV, NC>(&q0, &delta);
        let planned = |displacement: Option<&[f64; NV]>| -> [[f64; N]; N] {
            let (mut s, mut phi) = (M::newton_storage(), [0.0; NC]);
            let mut arrays = mbd::DenseArrays::new();
            m.newton_matrix(&q, &v0, &[0.0; NV], t, &lambda, displacement, c_v, c_q, &mut phi, &mut s, arrays.scratch());
            let mut full = [[0.0; N]; N];
            for i in 0..N {
                let u = pattern.unknown[i] as usize;
                for p in pattern.row_start[i] as usize..pattern.row_start[i + 1] as usize {
                    full[u][pattern.unknown[pattern.columns[p] as usize] as usize] = s.as_ref()[nnz + p];
                }
            }
            full
        };
        let (tangent, identity) = (planned(Some(&delta)), planned(None));
        // Central differences of step 1e-4 in v̇ move q by c_q 1e-4 = 4e-9: truncation
        // O(1e-8) of an entry, rounding O(1e-16 |r| / 1e-4) = O(1e-10).
        let step = 1e-4;
        for j in 0..NV {
            let (mut up, mut down) = ([0.0; NV], [0.0; NV]);
            (up[j], down[j]) = (step, -step);
            let (ru, rd) = (residual(&up), residual(&down));
            for i in 0..N {
                let derivative = (ru[i] - rd[i]) / (2.0 * step);
                let scale = derivative.abs().max(1.0);
                with = with.max((tangent[i][j] - derivative).abs() / scale);
                without = without.max((identity[i][j] - derivative).abs() / scale);
            }
        }
        // The multipliers' columns: −Dᵀ at q₊, untouched by T.
        let mut d = [[0.0; NV]; NC];
        m.jacobian(&q, t, &mut d);
        for r in 0..NC {
            for i in 0..NV {
                assert!((tangent[i][NV + r] + d[r][i]).abs() <= 1e-12 * d[r][i].abs().max(1.0), "{}: −Dᵀ at ({i}, {r})", M::NAME);
            }
        }
    }
    (with, without)
}

#[test]
fn on_the_rotation_group_the_matrix_is_the_residuals_derivative() {
    for (name, (with, without)) in [
        ("Top", tangent_check::<_, 7, 6, 3, 9>(&Top::default(), 5)),
        ("BallAndHinge", tangent_check::<_, 14, 12, 8, 20>(&BallAndHinge::default(), 6)),
        ("BallAndHingeJoints", tangent_check::<_, 5, 4, 0, 4>(&BallAndHingeJoints::default(), 7)),
    ] {
        eprintln!("{name}: largest relative difference from the residual's derivative {with:.1e} with T(Δ), {without:.1e} without");
        // The differences' error (above) is O(1e-8) (measured 4e-8, 4e-8, 2e-9). T(Δ) − I at
        // |Δθ| of 0.2–0.7 rad is O(0.1): in D's rows that much (measured 0.07 and 0.23), and where
        // there are none (the joint coordinates' tree) through c_q K (T − I) against M alone
        // (measured 5.5e-4).
        assert!(with < 1e-6, "{name}: {with:e} from the derivative with the tangent operator");
        assert!(without > 1e-4, "{name}: {without:e} without it: the check would not see T");
    }
}

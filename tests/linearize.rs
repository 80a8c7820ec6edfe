//! Linearization and modal analysis against closed forms (Wallrapp 3.6.4–3.6.6): a pendulum
//! hanging and upright, a mass-spring-damper with a force input, a double pendulum's normal
//! modes, a four-bar on a torsion spring against its equivalent 1-DOF model, a free body
//! spinning about each principal axis; and the exact linearization against central differences
//! of the forward dynamics, about equilibria and about moving states, planar and spatial.
use mbd::prelude::*;
use mbd::{LinearStability, Linearization, LinearizeOptions, Linearizer, Output};

const G: f64 = 9.81;

mechanism! {
    /// A 1 m rod pinned at one end.
    pub Pendulum {
        gravity [0.0, -9.81];
        body rod { mass: 2.0, inertia: 0.25, at: [0.0, -0.5, -1.5707963267948966] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
    }
}

mechanism! {
    /// A block on a horizontal slide between a spring-damper and a force input.
    pub Oscillator {
        params { k: 400.0, c: 6.0, push: 0.0 }
        body block { mass: 2.5, inertia: 0.01, at: [1.0, 0.0, 0.0] }
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ block[0.0, 0.0] along [1.0, 0.0];
        spring ground[0.0, 0.0] ~ block[0.0, 0.0] { k: k, length: 1.0, c: c };
        force block[0.0, 0.0] = [push, 0.0];
    }
}

mechanism! {
    /// Two rods hanging from a pin, 1 m and 0.8 m.
    pub DoublePendulum {
        gravity [0.0, -9.81];
        body upper { mass: 1.0, inertia: 0.0833333333333333, at: [0.0, -0.5, -1.5707963267948966] }
        body lower { mass: 0.5, inertia: 0.0266666666666667, at: [0.0, -1.4, -1.5707963267948966] }
        revolute ground[0.0, 0.0] ~ upper[-0.5, 0.0];
        revolute upper[0.5, 0.0] ~ lower[-0.4, 0.0];
    }
}

mechanism! {
    /// A crank-rocker four-bar (crank 0.3, coupler 0.8, rocker 0.6, ground 0.7 m) whose crank is
    /// held at 1 rad by a torsion spring; no gravity.
    pub SprungFourBar {
        params { k: 30.0 }
        body crank { mass: 0.4, inertia: 0.003, at: [0.081, 0.126, 1.0] }
        body coupler { mass: 1.1, inertia: 0.06, at: [0.53, 0.409, 0.403] }
        body rocker { mass: 0.8, inertia: 0.024, at: [0.799, 0.283, 1.235] }
        revolute ground[0.0, 0.0] ~ crank[-0.15, 0.0];
        revolute crank[0.15, 0.0] ~ coupler[-0.4, 0.0];
        revolute coupler[0.4, 0.0] ~ rocker[0.3, 0.0];
        revolute rocker[-0.3, 0.0] ~ ground[0.7, 0.0];
        rotational_spring ground ~ crank { k: k, angle: 1.0 };
    }
}

mechanism! {
    /// A slider-crank with a heavy crank, a motor torque as input and a damped slider: the
    /// finite-difference check's planar moving state.
    pub DrivenSliderCrank {
        params { torque: 2.0 }
        gravity [0.0, -9.81];
        body crank { mass: 1.0, inertia: 0.02, at: [0.038, 0.032, 0.7], velocity: [0.0, 0.0, 8.0] }
        body rod { mass: 0.5, inertia: 0.01, at: [0.22, 0.03, -0.2] }
        body slider { mass: 0.8, inertia: 0.001, at: [0.37, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-0.05, 0.0];
        revolute crank[0.05, 0.0] ~ rod[-0.15, 0.0];
        revolute rod[0.15, 0.0] ~ slider[0.0, 0.0];
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ slider[0.0, 0.0] along [1.0, 0.0] { viscous: 3.0 };
        spring ground[0.6, 0.0] ~ slider[0.0, 0.0] { k: 200.0, length: 0.25 };
        torque crank = torque;
        point rod.B = [0.15, 0.0];
    }
}

mechanism! {
    /// An asymmetric free body (principal moments 1, 2, 3 kg·m²) spinning.
    pub Spinner {
        spatial;
        params { wx: 0.0, wy: 0.0, wz: 0.0 }
        body b { mass: 1.0, inertia: [1.0, 2.0, 3.0], omega: [wx, wy, wz] }
    }
}

mechanism! {
    /// A heavy symmetric top on a ball joint, tilted 0.5 rad and spinning: a spatial moving
    /// state (it starts to precess).
    pub SpinningTop {
        spatial;
        params { l: 0.1, theta: 0.5, spin: 40.0 }
        gravity [0.0, 0.0, -9.81];
        body top {
            mass: 1.0, inertia: [0.005, 0.006, 0.002],
            at: [0.0, -l * sin(theta), l * cos(theta)], axis_angle: [1.0, 0.0, 0.0, theta], omega: [0.0, 0.0, spin]
        }
        spherical ground[0.0, 0.0, 0.0] ~ top[0.0, 0.0, -l];
    }
}

mbd::mechanism! {
    /// A rod hanging from a cart that a driver moves along x at 0.1 m/s: base excitation.
    pub ShakenPendulum {
        gravity [0.0, -9.81];
        body cart { mass: 3.0, inertia: 0.1, at: [0.0, 0.0, 0.0], velocity: [0.1, 0.0, 0.0] }
        body rod { mass: 2.0, inertia: 0.25, at: [0.0, -0.5, -1.5707963267948966], velocity: [0.1, 0.0, 0.0] }
        translational ground[0.0, 0.0] along [1.0, 0.0] ~ cart[0.0, 0.0] along [1.0, 0.0];
        revolute cart[0.0, 0.0] ~ rod[-0.5, 0.0];
        drive carriage: cart.x = 0.1 * t;
    }
}

mbd::mechanism! {
    /// A rod whose length is a parameter, pushed at its tip.
    pub LongRod {
        params { len: 1.0, push: 0.0 }
        gravity [0.0, -9.81];
        body rod { mass: 2.0, inertia: 0.25, at: [0.0, -0.5 * len, -1.5707963267948966] }
        revolute ground[0.0, 0.0] ~ rod[-0.5 * len, 0.0];
        force rod[0.5 * len, 0.0] = [push, 0.0];
    }
}

/// Relative difference against a scale.
fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1e-300)
}

/// The pendulum hanging: ω² = m g c / (J + m c²), c = 0.5 m; undamped, so the modes come from
/// the symmetric problem. Both paths agree with the closed form to rounding of the
/// factorizations (1e-12 relative).
#[test]
fn pendulum_small_oscillation_and_upright_instability() {
    let m = Pendulum::default();
    let omega = (2.0 * G * 0.5 / (0.25 + 2.0 * 0.25_f64)).sqrt();
    let q = m.initial_positions();
    let lin = Linearizer::default().linearize(&m, &q, &[0.0; 3], 0.0).expect("linearizes");
    assert_eq!(lin.dof(), 1);
    let modes = lin.modes();
    assert_eq!(modes.len(), 1);
    assert!(close(modes[0].natural_frequency, omega / (2.0 * std::f64::consts::PI), 1e-12), "{modes:?}");
    assert_eq!(modes[0].damping_ratio, 0.0);
    assert_eq!(modes[0].dominant, "rod.x"); // √m · 0.5 m/rad on x against √J · 1 on φ
    assert_eq!(lin.stability(), LinearStability::Marginal);
    // The second-order form: M_r ÿ + K_r y = 0 with ω² = K_r / M_r.
    assert!(close(lin.stiffness[(0, 0)] / lin.mass[(0, 0)], omega * omega, 1e-12));

    // Upright: s = +ω, unstable along the swing.
    let q_up = [0.0, 0.5, std::f64::consts::FRAC_PI_2];
    let up = Linearizer::default().linearize(&m, &q_up, &[0.0; 3], 0.0).expect("linearizes");
    match up.stability() {
        LinearStability::Unstable { growth, .. } => assert!(close(growth, omega, 1e-12), "growth {growth} vs {omega}"),
        other => panic!("the upright pendulum is unstable, got {other:?}"),
    }
}

/// ω_n = √(k/m), ζ = c / (2√(k m)); the static gain from the force to the displacement is 1/k.
/// Tolerance 1e-12: a 2×2 eigenproblem and one solve.
#[test]
fn mass_spring_damper_frequency_damping_and_gain() {
    let m = Oscillator::default();
    let q = m.initial_positions();
    let options = LinearizeOptions::default().with_inputs(&["push"]).with_output(Output::Displacement("block.x"));
    let lin = Linearizer::new(options).linearize(&m, &q, &[0.0; 3], 0.0).expect("linearizes");
    assert_eq!(lin.state_names, ["block.x", "block.x_dot"]);
    let (k, c, mass) = (400.0, 6.0, 2.5);
    let modes = lin.modes();
    assert_eq!(modes.len(), 1, "{modes:?}");
    assert!(close(modes[0].natural_frequency, (k / mass).sqrt() / (2.0 * std::f64::consts::PI), 1e-12), "{modes:?}");
    assert!(close(modes[0].damping_ratio, c / (2.0 * (k * mass).sqrt()), 1e-12), "{modes:?}");
    assert!(matches!(lin.stability(), LinearStability::Asymptotic { .. }));
    // DC gain −C A⁻¹ B + D.
    let gain = -(&lin.c * lin.a.clone().try_inverse().expect("A regular") * &lin.b) + &lin.d;
    assert!(close(gain[(0, 0)], 1.0 / k, 1e-12), "gain {gain}");
    assert!(close(lin.input_forces[(0, 0)], 1.0, 1e-12));
}

/// The two normal modes of the compound double pendulum from det(K − ω² M) = 0 with
/// M = [[J₁ + m₁c₁² + m₂L₁², m₂L₁c₂], [m₂L₁c₂, J₂ + m₂c₂²]], K = diag((m₁c₁ + m₂L₁) g, m₂c₂g)
/// in the absolute angles; and the first mode's shape: both rods swing the same way.
#[test]
fn double_pendulum_normal_modes() {
    let m = DoublePendulum::default();
    let q = m.initial_positions();
    let lin = Linearizer::default().linearize(&m, &q, &[0.0; 6], 0.0).expect("linearizes");
    let (m1, m2, l1, c1, c2, j1, j2) = (1.0, 0.5, 1.0, 0.5, 0.4, 1.0 / 12.0, 0.5 * 0.64 / 12.0);
    let mm = [[j1 + m1 * c1 * c1 + m2 * l1 * l1, m2 * l1 * c2], [m2 * l1 * c2, j2 + m2 * c2 * c2]];
    let kk = [(m1 * c1 + m2 * l1) * G, m2 * c2 * G];
    // det(K − w M) = a w² + b w + c
    let a = mm[0][0] * mm[1][1] - mm[0][1] * mm[1][0];
    let b = -(kk[0] * mm[1][1] + kk[1] * mm[0][0]);
    let cc = kk[0] * kk[1];
    let disc = (b * b - 4.0 * a * cc).sqrt();
    let w = [(-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a)];
    let modes = lin.modes();
    assert_eq!(modes.len(), 2);
    for (mode, w2) in modes.iter().zip(w) {
        // 1e-9: the table's inertias are written to 15 digits
        assert!(close(mode.natural_frequency, w2.sqrt() / (2.0 * std::f64::consts::PI), 1e-9), "{mode:?} vs ω² = {w2}");
    }
    let phi = |mode: &mbd::Mode, name: &str| mode.shape[DoublePendulum::VELOCITY_NAMES.iter().position(|n| *n == name).unwrap()].re;
    assert!(phi(&modes[0], "upper.phi") * phi(&modes[0], "lower.phi") > 0.0, "first mode in phase: {:?}", modes[0]);
    assert!(phi(&modes[1], "upper.phi") * phi(&modes[1], "lower.phi") < 0.0, "second mode in opposition: {:?}", modes[1]);
}

/// A four-bar on a torsion spring: ω² = k / M_eq, M_eq = Σ mᵢ|v_cᵢ|² + Jᵢωᵢ² at unit crank rate,
/// the velocities from the closed-form loop closure computed here. The equilibrium is found by
/// the static solver; 1e-9 relative covers its tolerance on the angles.
#[test]
fn four_bar_on_a_torsion_spring_against_its_one_dof_model() {
    let m = SprungFourBar::default();
    let mut q = m.initial_positions();
    let mut ws = SprungFourBar::workspace();
    let mut lambda = [0.0; 8];
    StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("equilibrium");
    let lin = Linearizer::default().linearize(&m, &q, &[0.0; 9], 0.0).expect("linearizes");
    // Closed form at the crank angle θ₂ the solver found.
    let (a, b, c, d) = (0.3, 0.8, 0.6, 0.7);
    let t2 = q[2];
    let pa = [a * t2.cos(), a * t2.sin()];
    let (dx, dy) = (d - pa[0], -pa[1]);
    let l = dx.hypot(dy);
    let x = (b * b - c * c + l * l) / (2.0 * l);
    let h = (b * b - x * x).sqrt();
    let pb = [pa[0] + x * dx / l - h * dy / l, pa[1] + x * dy / l + h * dx / l];
    // a ω₂ k×(A) + ω₃ k×(B − A) = ω₄ k×(B − O₄), ω₂ = 1
    let (ab, ob) = ([pb[0] - pa[0], pb[1] - pa[1]], [pb[0] - d, pb[1]]);
    let va = [-pa[1], pa[0]];
    // ω₃ (−ab_y, ab_x) − ω₄ (−ob_y, ob_x) = −va
    let det = (-ab[1]) * ob[0] - (-ob[1]) * ab[0];
    let w3 = ((-va[0]) * ob[0] - (-ob[1]) * (-va[1])) / det;
    let w4 = ((-ab[1]) * (-va[1]) - (-va[0]) * ab[0]) / det;
    let v_crank = [va[0] / 2.0, va[1] / 2.0];
    let v_coupler = [va[0] - w3 * ab[1] / 2.0, va[1] + w3 * ab[0] / 2.0];
    let v_rocker = [-w4 * ob[1] / 2.0, w4 * ob[0] / 2.0];
    let sq = |v: [f64; 2]| v[0] * v[0] + v[1] * v[1];
    let m_eq = 0.4 * sq(v_crank) + 0.003 + 1.1 * sq(v_coupler) + 0.06 * w3 * w3 + 0.8 * sq(v_rocker) + 0.024 * w4 * w4;
    let omega = (30.0 / m_eq).sqrt();
    assert!((t2 - 1.0).abs() < 1e-9, "the spring holds the crank at 1 rad: {t2}");
    let modes = lin.modes();
    assert_eq!(modes.len(), 1);
    assert!(close(modes[0].natural_frequency, omega / (2.0 * std::f64::consts::PI), 1e-9), "{modes:?} vs ω = {omega}");
}

/// Torque-free rotation about each principal axis (moments 1, 2, 3): about the intermediate
/// axis the perturbations grow as e^{λt}, λ² = ω₀² (J₁ − J₂)(J₂ − J₃)/(J₁J₃) with the spin on 2;
/// about the others they oscillate at |λ|. A spinning body is a moving state: the chart's
/// rotation adds ±iω₀/2 and zeros, which do not change those eigenvalues (A is block
/// triangular: Euler's equations do not see the orientation).
#[test]
fn free_body_spin_about_each_principal_axis() {
    let j = [1.0, 2.0, 3.0];
    let w0 = 2.0;
    for axis in 0..3 {
        let mut m = Spinner::default();
        match axis {
            0 => m.wx = w0,
            1 => m.wy = w0,
            _ => m.wz = w0,
        }
        let (q, v) = (m.initial_positions(), m.initial_velocities());
        let lin = Linearizer::default().linearize(&m, &q, &v, 0.0).expect("linearizes");
        assert_eq!(lin.dof(), 6);
        let (i, k) = ((axis + 1) % 3, (axis + 2) % 3);
        // λ² = ω₀² (J_a − J_k)(J_i − J_a)/(J_i J_k)
        let l2 = w0 * w0 * (j[axis] - j[k]) * (j[i] - j[axis]) / (j[i] * j[k]);
        let eigenvalues = lin.eigenvalues();
        let expected = if l2 > 0.0 { Complex::new(l2.sqrt(), 0.0) } else { Complex::new(0.0, (-l2).sqrt()) };
        let found = eigenvalues.iter().any(|s| (s - expected).norm() < 1e-9 * w0);
        assert!(found, "spin about axis {axis}: expected {expected} among {eigenvalues:?}");
        let unstable = matches!(lin.stability(), LinearStability::Unstable { .. });
        assert_eq!(unstable, axis == 1, "spin about axis {axis}: {:?}", lin.stability());
    }
}

use mbd::nalgebra::Complex;

/// Largest entry-wise difference of two matrices relative to the larger's largest entry.
fn relative(a: &mbd::nalgebra::DMatrix<f64>, b: &mbd::nalgebra::DMatrix<f64>) -> f64 {
    (a - b).amax() / a.amax().max(b.amax()).max(1e-300)
}

/// Exact and finite-difference linearizations of the same state agree to the differences'
/// truncation and rounding: central differences with ε = ∛u·max(1, |x|) ≈ 6e-6 are exact to
/// O(ε²) ≈ 4e-11 of the second derivative's scale, and each evaluation's projection onto the
/// manifold converges to 1e-15; 1e-7 relative leaves two orders for the curvature of these
/// mechanisms. A wrong term (a missing Q(v̇₀), Ω or G) is O(1) of its entries.
fn agree(name: &str, exact: &Linearization, fd: &Linearization) {
    assert_eq!(exact.state_names, fd.state_names);
    for (what, e, f) in [("A", &exact.a, &fd.a), ("B", &exact.b, &fd.b), ("C", &exact.c, &fd.c), ("D", &exact.d, &fd.d)] {
        if e.is_empty() {
            continue;
        }
        let r = relative(e, f);
        eprintln!("{name}: {what} exact vs differences: {r:.1e}");
        assert!(r < 1e-7, "{name}: {what} differs by {r:e}\nexact {e}\ndifferences {f}");
    }
}

#[test]
fn exact_against_finite_differences_at_equilibria() {
    let m = Oscillator::default();
    let options = || {
        LinearizeOptions::default()
            .with_inputs(&["push"])
            .with_output(Output::Displacement("block.x"))
            .with_output(Output::Velocity("block.x"))
            .with_output(Output::Multiplier("translational ground~block: normal"))
    };
    let q = m.initial_positions();
    let exact = Linearizer::new(options()).linearize(&m, &q, &[0.0; 3], 0.0).expect("exact");
    let fd = Linearizer::new(options()).finite_differences(&m, &q, &[0.0; 3], 0.0).expect("differences");
    agree("oscillator", &exact, &fd);

    let m = SprungFourBar::default();
    let mut q = m.initial_positions();
    let mut ws = SprungFourBar::workspace();
    StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut [0.0; 8]).expect("equilibrium");
    let options = || LinearizeOptions::default().with_output(Output::Multiplier(SprungFourBar::CONSTRAINT_NAMES[6]));
    let exact = Linearizer::new(options()).linearize(&m, &q, &[0.0; 9], 0.0).expect("exact");
    let fd = Linearizer::new(options()).finite_differences(&m, &q, &[0.0; 9], 0.0).expect("differences");
    agree("four-bar", &exact, &fd);
}

/// About moving states — the slider-crank turning at 8 rad/s under gravity, a spring and a motor
/// torque; the top spinning and starting to precess — every term of the exact path is in play:
/// G (the velocity constraint moving with q), Q(v̇₀), Γ_q, Γ_v and, in space, the chart's Ω.
#[test]
fn exact_against_finite_differences_at_moving_states() {
    let m = DrivenSliderCrank::default();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut DrivenSliderCrank::workspace(), &mut q, 0.0).expect("assembles");
    let mut v = m.initial_velocities();
    m.project_velocities(&q, &mut v, 0.0, &DynamicsOptions::default()).expect("velocities");
    let options = || {
        LinearizeOptions::default()
            .with_inputs(&["torque"])
            .with_independent(&["crank.phi"])
            .with_output(Output::Displacement("slider.x"))
            .with_output(Output::Velocity("rod.phi"))
            .with_output(Output::Multiplier(DrivenSliderCrank::CONSTRAINT_NAMES[0]))
            .with_output(Output::rate("rod.B y", |q, v| DrivenSliderCrank::default().rod_b().velocity(q, v).y))
    };
    assert!((q[2] - 0.7).abs() < 0.01 && q[6] > 0.3, "assembled off the dead centres: {q:?}");
    let exact = Linearizer::new(options()).linearize(&m, &q, &v, 0.0).expect("exact");
    assert_eq!(exact.state_names, ["crank.phi", "crank.phi_dot"]);
    assert!(exact.d.amax() > 1.0 && exact.a[(1, 1)] != 0.0, "every term in play: D {} A {}", exact.d, exact.a);
    let fd = Linearizer::new(options()).finite_differences(&m, &q, &v, 0.0).expect("differences");
    agree("slider-crank at 8 rad/s", &exact, &fd);

    let m = SpinningTop::default();
    let (q, v) = (m.initial_positions(), m.initial_velocities());
    let exact = Linearizer::new(LinearizeOptions::default().with_output(Output::Multiplier(SpinningTop::CONSTRAINT_NAMES[2])))
        .linearize(&m, &q, &v, 0.0)
        .expect("exact");
    let fd = Linearizer::new(LinearizeOptions::default().with_output(Output::Multiplier(SpinningTop::CONSTRAINT_NAMES[2])))
        .finite_differences(&m, &q, &v, 0.0)
        .expect("differences");
    agree("spinning top", &exact, &fd);

    // A rate written for another mechanism's state (the slider-crank's 9 coordinates) is refused
    // by name before anything is computed, not evaluated on the top's 7.
    let other =
        LinearizeOptions::default().with_output(Output::rate("rod.B y", |q, v| DrivenSliderCrank::default().rod_b().velocity(q, v).y));
    match Linearizer::new(other).linearize(&m, &q, &v, 0.0) {
        Err(e @ LinearizeError::RateSizes { takes: (9, 9), mechanism: (7, 6), .. }) => assert!(e.to_string().contains("`rod.B y`"), "{e}"),
        other => panic!("expected RateSizes, got {:?}", other.map(|l| l.state_names)),
    }
}

/// A driver's acceleration as input: the rod swings at ω² = m g c / J_o (J_o = J + m c²) and the
/// carriage's acceleration a turns it by φ̈ = −m c a / J_o (a push to +x leaves the rod's lower
/// end behind: it turns clockwise, from −π/2 towards −π); the driver's force
/// per unit acceleration is the carriage's effective mass M + m − (m c)²/J_o. Closed forms to
/// 1e-12; the finite-difference model agrees to 1e-7 as everywhere.
#[test]
fn driver_acceleration_as_input() {
    let m = ShakenPendulum::default();
    let (q, v) = (m.initial_positions(), m.initial_velocities());
    let options = || LinearizeOptions::default().with_inputs(&["carriage"]).with_output(Output::Multiplier("carriage: x"));
    let lin = Linearizer::new(options()).linearize(&m, &q, &v, 0.0).expect("linearizes");
    assert_eq!(lin.state_names, ["rod.phi", "rod.phi_dot"]);
    let (mass, c, j) = (2.0, 0.5, 0.25);
    let jo = j + mass * c * c;
    assert!(close(-lin.a[(1, 0)], mass * G * c / jo, 1e-12), "{}", lin.a);
    assert!(close(lin.b[(1, 0)], -mass * c / jo, 1e-12), "{}", lin.b);
    assert!(close(lin.d[(0, 0)], 3.0 + mass - (mass * c).powi(2) / jo, 1e-12), "{}", lin.d);
    let fd = Linearizer::new(options()).finite_differences(&m, &q, &v, 0.0).expect("differences");
    agree("shaken pendulum", &lin, &fd);
}

/// A state off the manifold, an unknown name, and the wrong number of independent velocities
/// are errors that say what is wrong.
#[test]
fn errors_name_what_is_wrong() {
    let m = Pendulum::default();
    let e = Linearizer::default().linearize(&m, &[0.0, 0.0, 0.0], &[0.0; 3], 0.0).unwrap_err();
    assert!(e.to_string().contains("`pin: x`"), "{e}");
    let q = m.initial_positions();
    let e = Linearizer::default().linearize(&m, &q, &[1.0, 0.0, 0.0], 0.0).unwrap_err();
    assert!(e.to_string().contains("velocities violate"), "{e}");
    let e = Linearizer::new(LinearizeOptions::default().with_inputs(&["motor"])).linearize(&m, &q, &[0.0; 3], 0.0).unwrap_err();
    assert!(e.to_string().contains("unknown input `motor`"), "{e}");
    // A parameter that also sets the geometry is not an input.
    assert_eq!(LongRod::INPUTS, ["push"]);
    let rod = LongRod::default();
    let e = Linearizer::new(LinearizeOptions::default().with_inputs(&["len"]))
        .linearize(&rod, &rod.initial_positions(), &[0.0; 3], 0.0)
        .unwrap_err();
    assert!(e.to_string().contains("unknown input (a parameter that also sets the geometry, the masses or friction) `len`"), "{e}");
    let e = Linearizer::default().linearize(&ShakenPendulum::default(), &[0.0; 6], &[0.0; 6], 0.0).unwrap_err();
    assert!(e.to_string().contains("not assembled"), "{e}");
    let e =
        Linearizer::new(LinearizeOptions::default().with_independent(&["rod.x", "rod.y"])).linearize(&m, &q, &[0.0; 3], 0.0).unwrap_err();
    assert!(e.to_string().contains("2 named, but the mechanism has 1 degrees of freedom"), "{e}");
}

/// CSV and JSON carry the names and the numbers.
#[test]
fn export_with_names() {
    let m = Oscillator::default();
    let options = LinearizeOptions::default().with_inputs(&["push"]).with_output(Output::Displacement("block.x"));
    let lin = Linearizer::new(options).linearize(&m, &m.initial_positions(), &[0.0; 3], 0.0).expect("linearizes");
    let dir = std::env::temp_dir().join(format!("mbd-linearize-{}", std::process::id()));
    lin.write_csv(&dir).expect("writes");
    let a = std::fs::read_to_string(dir.join("A.csv")).expect("A.csv");
    let mut lines = a.lines();
    assert_eq!(lines.next(), Some(r#""","block.x","block.x_dot""#));
    assert_eq!(lines.next(), Some(r#""block.x",0e0,1e0"#));
    let second: Vec<f64> = lines.next().expect("row 2").split(',').skip(1).map(|x| x.parse().expect("number")).collect();
    assert!(close(second[0], -400.0 / 2.5, 1e-12) && close(second[1], -6.0 / 2.5, 1e-12), "{second:?}");
    let b = std::fs::read_to_string(dir.join("B.csv")).expect("B.csv");
    assert!(b.starts_with("\"\",\"push\"\n"), "{b}");
    let k = std::fs::read_to_string(dir.join("K_r.csv")).expect("K_r.csv");
    assert_eq!(k, "\"\",\"block.x\"\n\"block.x\",4e2\n");
    std::fs::remove_dir_all(&dir).ok();
    let json = lin.to_json();
    assert!(json.contains(r#""states": ["block.x", "block.x_dot"]"#) && json.contains(r#""inputs": ["push"]"#), "{json}");
    assert!(json.contains(r#""A": [[0e0, 1e0], [-1.6e2, -2.4e0]]"#), "{json}");
    assert!(json.contains(r#""independent": ["block.x"]"#) && json.contains(r#""K_r": [[4e2]]"#), "{json}");
}

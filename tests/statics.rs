//! Static equilibrium against analytic solutions and independent energy minima — the stable
//! equilibrium from the documented start (λ = 0) and from rough guesses, its stability verdict,
//! angles in (−π, π] — and the generated geometric stiffness K = ∂(Φ_qᵀλ)/∂q against central
//! differences of Φ_qᵀλ.
//!
//! Iteration counts are printed (`cargo test --test statics -- --nocapture`) and bounded.
use mbd_examples::excavator as excavator_example; // `excavator` is this file's own module below
use mbd_examples::{double_a_arm, filmstrip, four_bar, macpherson, slider_crank, suspension_dynamics, variable_pendulum, web_cutter};
#[path = "common/rng.rs"]
mod rng;
/// The examples this test uses (from mbd-examples, where they are compiled once) and the shared
/// generator (`tests/common/`).
mod common {
    pub(crate) use super::{
        double_a_arm, excavator_example as excavator, filmstrip, four_bar, macpherson, rng::Rng, slider_crank, suspension_dynamics,
        variable_pendulum, web_cutter,
    };
}

use common::Rng;
use mbd::prelude::*;
use mbd::{ConstraintForces, PlanarBody};

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
    let mut ws = SpringRod::workspace();
    let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("equilibrium");
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
    let mut ws = Hanging::workspace();
    let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("equilibrium");
    eprintln!("hanging mass: {report:?}");
    assert!(report.iterations < 10 && matches!(report.stability, Stability::Stable { .. }), "{report:?}");
    assert!(q[0].abs() < 1e-9 && (q[1] + 0.5 + 3.0 * 9.81 / 100.0).abs() < 1e-9 && q[2].abs() < 1e-9, "{q:?}");
}

#[test]
fn wrong_workspace_is_an_error() {
    let m = SpringRod::default();
    let mut q = m.initial_positions();
    let mut ws = Workspace::<f64, 3, 2, 4>::new();
    let err = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut [0.0; 2]).unwrap_err();
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
    let mut ws = FreeRod::workspace();
    let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut [0.0; 2]).expect("an equilibrium");
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

/// A NaN parameter is an error naming the force element that gives it (the torsion spring),
/// the velocity it acts on (the rod's angle) and the time, never a NaN result.
#[test]
fn a_nan_load_names_its_element() {
    let m = SpringRod { k: f64::NAN };
    let mut q = m.initial_positions();
    let mut ws = SpringRod::workspace();
    let err = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.25, &mut [0.0; 2]).unwrap_err();
    assert_eq!(err, StaticError::NonFiniteForce { t: 0.25, element: SpringRod::FORCE_ELEMENTS[1].name, others: 0, velocity: "rod.phi" });
    assert!(SpringRod::FORCE_ELEMENTS[1].name.contains("rotational_spring"), "{:?}", SpringRod::FORCE_ELEMENTS);
    let text = err.to_string();
    assert!(text.contains("t = 0.25 s") && text.contains("rod.phi") && text.contains("rotational_spring"), "{text}");
}

mechanism! {
    /// A 1 m rod of 2 kg pinned at one end: it hangs at φ = −π/2.
    pub Pendulum {
        gravity [0.0, -9.81];
        body rod { mass: 2.0, inertia: 0.1667, at: [0.5, 0.0, 0.0] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
    }
}

/// The pendulum's small-oscillation ω² about the pin, m g (l/2) / (J + m (l/2)²) (1/s²).
const PENDULUM_OMEGA2: f64 = 2.0 * 9.81 * 0.5 / (0.1667 + 2.0 * 0.25);

/// A rough guess of the pendulum at angle `phi` (rad, absolute): the centre of mass 0.1 m off
/// where the pin puts it, so the solver must assemble it.
fn pendulum_guess(phi: f64) -> [f64; 3] {
    [0.5 * phi.cos() + 0.1, 0.5 * phi.sin() - 0.1, phi]
}

/// The hanging pendulum, checked: φ = −π/2 within 1e-9 rad (the torque tolerance 1e-9 N·m over
/// the gravity stiffness m g l/2 = 9.81 N·m/rad leaves 1e-10), the pin carrying the weight to
/// 1e-9 N (the force tolerance), Stable with ω² = PENDULUM_OMEGA2 to 1e-9 relative (the
/// eigenvalue at a q within 1e-10 of the equilibrium). The reaction is read as the guide says (guide/dynamics.md),
/// from the D the solve left in the workspace: D at the returned q, bit for bit (the start's D,
/// which an earlier version left there, puts the pin's moment about the centre of mass off by
/// the weight times the lever's change, 9.81 N·m for the start from horizontal).
fn assert_hanging(
    q: &[f64; 3],
    lambda: &[f64; 2],
    ws: &Workspace<f64, 3, 2, 5, { Pendulum::NEWTON_STORAGE }>,
    report: &StaticReport,
    from: &str,
) {
    let m = Pendulum::default();
    assert!((Pendulum::ROD.phi(q) + PI / 2.0).abs() < 1e-9, "from {from}: φ = {}", Pendulum::ROD.phi(q));
    let mut d = [[0.0; 3]; 2];
    m.jacobian(q, 0.0, &mut d);
    assert_eq!(ws.jacobian(), &d, "from {from}: the workspace's D is D at the equilibrium");
    let pin = joint_reaction(&m, q, ws.jacobian(), lambda, Pendulum::PIN).and_then(|r| r.on_j).expect("the pin holds the rod");
    assert!(pin.force[0].abs() < 1e-9 && (pin.force[1] - 2.0 * 9.81).abs() < 1e-9, "from {from}: {pin:?}");
    // The pin is on the rod's axis, straight above its centre of mass: no moment about it.
    assert!(pin.moment[2].abs() < 1e-9, "from {from}: {pin:?}");
    match report.stability {
        Stability::Stable { omega_squared } => {
            assert!((omega_squared - PENDULUM_OMEGA2).abs() < 1e-9 * PENDULUM_OMEGA2, "from {from}: {report:?}")
        }
        other => panic!("from {from}: {other:?}"),
    }
}

/// From the documented start — the `at:` pose (horizontal) and λ = 0, which plain Newton could
/// not leave (with λ = 0 gravity gives no stiffness) — and from rough guesses on both sides of
/// upright, the pendulum comes to hang straight down. 20° and 170° are measured from hanging
/// down; 7 rad is an absolute angle past a full turn, and comes back in (−π, π].
#[test]
fn pendulum_hangs_from_the_documented_start_and_rough_guesses() {
    let m = Pendulum::default();
    let starts = [
        ("the documented start", m.initial_positions()),
        ("20°", pendulum_guess(-PI / 2.0 + 20f64.to_radians())),
        ("170°", pendulum_guess(-PI / 2.0 + 170f64.to_radians())),
        ("−170°", pendulum_guess(-PI / 2.0 - 170f64.to_radians())),
        ("7 rad", pendulum_guess(7.0)),
        ("−7 rad", pendulum_guess(-7.0)),
    ];
    for (from, start) in starts {
        let mut q = start;
        let mut lambda = [0.0; 2];
        let mut ws = Pendulum::workspace();
        let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect(from);
        eprintln!("pendulum from {from}: {report:?}");
        assert!(report.iterations + report.rejected <= 30, "from {from}: {report:?}");
        assert!(q[2] > -PI && q[2] <= PI, "from {from}: φ = {} out of (−π, π]", q[2]);
        assert_hanging(&q, &lambda, &ws, &report, from);
    }
}

/// Started exactly upright, the pendulum is at an equilibrium — an unstable one. By default the
/// solver steps off it along the falling mode and comes to hang; with `leave_unstable` off it
/// reports it: Unstable with ω² = −PENDULUM_OMEGA2 (to 1e-9 relative, as above), the mode named
/// by the velocity carrying most of its kinetic energy (the centre of mass moving sideways).
#[test]
fn upright_pendulum_is_left_or_reported_unstable() {
    let m = Pendulum::default();
    let upright = [0.0, 0.5, PI / 2.0];
    let mut q = upright;
    let mut lambda = [0.0; 2];
    let mut ws = Pendulum::workspace();
    let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("falls and hangs");
    eprintln!("pendulum from upright: {report:?}");
    assert!(report.iterations + report.rejected <= 30, "{report:?}");
    assert_hanging(&q, &lambda, &ws, &report, "upright");

    let mut q = upright;
    let solver = StaticSolver::new(StaticOptions::default().with_leave_unstable(false));
    let report = solver.solve(&m, &mut Pendulum::workspace(), &mut q, 0.0, &mut lambda).expect("an equilibrium");
    assert_eq!(report.iterations, 0, "{report:?}");
    match report.stability {
        Stability::Unstable { direction, omega_squared } => {
            assert_eq!(direction, "rod.x");
            assert!((omega_squared + PENDULUM_OMEGA2).abs() < 1e-9 * PENDULUM_OMEGA2, "{report:?}");
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(q, upright, "returned where it was");
}

mechanism! {
    /// Two 1 m rods, 2 kg and 1 kg, pinned end to end: they hang straight down at φ = −π/2.
    pub DoublePendulum {
        gravity [0.0, -9.81];
        body upper { mass: 2.0, inertia: 0.1667, at: [0.5, 0.0, 0.0] }
        body lower { mass: 1.0, inertia: 0.0833, at: [1.5, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ upper[-0.5, 0.0];
        revolute upper[0.5, 0.0] ~ lower[-0.5, 0.0];
    }
}

/// From the documented start (both rods horizontal, λ = 0) and from rough guesses — near both
/// upright, folded, one up one down, past a turn — both rods come to hang straight down,
/// Stable. Angles are checked to 1e-8 rad: the softer mode's stiffness is about 3 N·m/rad, so
/// the torque tolerance 1e-9 N·m leaves a few 1e-10.
#[test]
fn double_pendulum_hangs_straight_down() {
    let m = DoublePendulum::default();
    let guess = |a1: f64, a2: f64| {
        // Angles in degrees from hanging down; centres of mass 5 cm off their joints' places.
        let (p1, p2) = (-PI / 2.0 + a1.to_radians(), -PI / 2.0 + a2.to_radians());
        let elbow = [p1.cos(), p1.sin()];
        [0.5 * p1.cos() + 0.05, 0.5 * p1.sin(), p1, elbow[0] + 0.5 * p2.cos(), elbow[1] + 0.5 * p2.sin() - 0.05, p2]
    };
    let starts = [
        ("the documented start", m.initial_positions()),
        ("(170°, 170°)", guess(170.0, 170.0)),
        ("(120°, −60°)", guess(120.0, -60.0)),
        ("(−150°, 100°)", guess(-150.0, 100.0)),
        ("(90°, 180°)", guess(90.0, 180.0)),
        ("(10°, 175°)", guess(10.0, 175.0)),
        ("(400°, −380°)", guess(400.0, -380.0)),
    ];
    for (from, start) in starts {
        let mut q = start;
        let mut lambda = [0.0; 4];
        let report = StaticSolver::default().solve(&m, &mut DoublePendulum::workspace(), &mut q, 0.0, &mut lambda).expect(from);
        eprintln!("double pendulum from {from}: {report:?}");
        assert!(report.iterations + report.rejected <= 60, "from {from}: {report:?}");
        for body in [DoublePendulum::UPPER, DoublePendulum::LOWER] {
            assert!((body.phi(&q) + PI / 2.0).abs() < 1e-8, "from {from}: q = {q:?}");
        }
        assert!(matches!(report.stability, Stability::Stable { .. }), "from {from}: {report:?}");
    }
}

/// A driven mechanism (DOF = 0) has nothing free to move: its statics is the driver's torque,
/// m g (l/2) cos φ, and its stability is `Determined`. Tolerance 1e-9 N·m, the solver's.
#[test]
fn driven_pendulum_holds_its_angle() {
    mechanism! {
        pub HeldRod {
            gravity [0.0, -9.81];
            body rod { mass: 2.0, inertia: 0.1667, at: [0.5, 0.0, 0.0] }
            revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0];
            drive motor: rod.phi = 0.3;
        }
    }
    let m = HeldRod::default();
    let mut q = m.initial_positions();
    let mut lambda = [0.0; 3];
    let report = StaticSolver::default().solve(&m, &mut HeldRod::workspace(), &mut q, 0.0, &mut lambda).expect("held");
    assert_eq!(report.stability, Stability::Determined);
    let torque = lambda[HeldRod::JOINTS[HeldRod::MOTOR].row_range()][0];
    assert!((torque.abs() - 2.0 * 9.81 * 0.5 * 0.3f64.cos()).abs() < 1e-9, "motor torque {torque}");
}

/// The excavator arm of `examples/excavator.rs` in its scene held by its cylinders as stiff
/// springs (k = 2e7 N/m, the oil column's stiffness, rest lengths at the design pose: boom 40°
/// up, stick 75° and bucket 130° below the horizontal; the boom cylinder also pushes with a
/// constant 60 kN, an actuator force the generated potential energy V does not include).
use common::excavator::ExcavatorHeld as Excavator;

/// The excavator's geometry in joint angles (absolute, rad), written independently of the
/// generated code: the centres of mass and the three cylinder lengths.
mod excavator {
    pub const G: f64 = 9.81;
    pub const MASSES: [f64; 3] = [1800.0, 900.0, 700.0];
    pub const DESIGN: [f64; 3] = [40.0, -75.0, -130.0];
    const BOOM_FOOT: [f64; 2] = [-2.75, 0.0];
    const BOOM_TIP: [f64; 2] = [2.75, 0.0];
    const BOOM_LUG: [f64; 2] = [-0.4, -0.45];
    const BOOM_STICK_BASE: [f64; 2] = [0.2, 0.45];
    const STICK_PIN: [f64; 2] = [-0.8, 0.0];
    const STICK_TIP: [f64; 2] = [2.1, 0.0];
    const STICK_LEVER: [f64; 2] = [-1.3, 0.3];
    const STICK_BUCKET_BASE: [f64; 2] = [-0.3, 0.3];
    const BUCKET_PIN: [f64; 2] = [-0.45, 0.0];
    const BUCKET_LUG: [f64; 2] = [-0.55, 0.35];
    const BOOM_ANCHOR: [f64; 2] = [0.9, -0.9];

    fn at(r: [f64; 2], phi: f64, s: [f64; 2]) -> [f64; 2] {
        let (sn, c) = phi.sin_cos();
        [r[0] + c * s[0] - sn * s[1], r[1] + sn * s[0] + c * s[1]]
    }
    fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
        (a[0] - b[0]).hypot(a[1] - b[1])
    }
    /// The centres of mass for the angles `th`.
    pub fn centres(th: [f64; 3]) -> [[f64; 2]; 3] {
        let boom = at([0.0, 0.0], th[0], [-BOOM_FOOT[0], -BOOM_FOOT[1]]);
        let tip = at(boom, th[0], BOOM_TIP);
        let stick = at(tip, th[1], [-STICK_PIN[0], -STICK_PIN[1]]);
        let stick_tip = at(stick, th[1], STICK_TIP);
        let bucket = at(stick_tip, th[2], [-BUCKET_PIN[0], -BUCKET_PIN[1]]);
        [boom, stick, bucket]
    }
    /// The boom, stick and bucket cylinder lengths for the angles `th`.
    pub fn lengths(th: [f64; 3]) -> [f64; 3] {
        let [boom, stick, bucket] = centres(th);
        [
            distance(BOOM_ANCHOR, at(boom, th[0], BOOM_LUG)),
            distance(at(boom, th[0], BOOM_STICK_BASE), at(stick, th[1], STICK_LEVER)),
            distance(at(stick, th[1], STICK_BUCKET_BASE), at(bucket, th[2], BUCKET_LUG)),
        ]
    }
    /// The design pose in radians.
    pub fn design() -> [f64; 3] {
        DESIGN.map(f64::to_radians)
    }
    /// V = Σ m g y + Σ ½ k (l − L)² + f l (the boom cylinder's constant tension −push adds −push·l).
    pub fn energy(m: &super::Excavator, th: [f64; 3]) -> f64 {
        let c = centres(th);
        let l = lengths(th);
        let rest = [m.boom_rest, m.stick_rest, m.bucket_rest];
        let gravity: f64 = (0..3).map(|i| MASSES[i] * G * c[i][1]).sum();
        let springs: f64 = (0..3).map(|i| 0.5 * m.k_cyl * (l[i] - rest[i]).powi(2)).sum();
        gravity + springs - m.boom_push * l[0]
    }
    /// The minimum of `energy` near `th` by Newton on central differences (step 1e-4 rad for
    /// the Hessian, 1e-6 for the gradient): an independent solve in joint angles.
    pub fn minimum(m: &super::Excavator, mut th: [f64; 3]) -> [f64; 3] {
        let e = |th: [f64; 3]| energy(m, th);
        let shifted = |th: [f64; 3], i: usize, h: f64| {
            let mut t = th;
            t[i] += h;
            t
        };
        for _ in 0..30 {
            let g: [f64; 3] = core::array::from_fn(|i| (e(shifted(th, i, 1e-6)) - e(shifted(th, i, -1e-6))) / 2e-6);
            let hs = 1e-4;
            let hm: [[f64; 3]; 3] = core::array::from_fn(|i| {
                core::array::from_fn(|j| {
                    let pp = e(shifted(shifted(th, i, hs), j, hs));
                    let pm = e(shifted(shifted(th, i, hs), j, -hs));
                    let mp = e(shifted(shifted(th, i, -hs), j, hs));
                    let mm = e(shifted(shifted(th, i, -hs), j, -hs));
                    (pp - pm - mp + mm) / (4.0 * hs * hs)
                })
            });
            let step = solve3(hm, g);
            for (t, s) in th.iter_mut().zip(step) {
                *t -= s;
            }
            if step.iter().all(|s| s.abs() < 1e-13) {
                break;
            }
        }
        th
    }
    /// A x = b for a 3 × 3 A, by Cramer's rule.
    fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
        let det = |m: [[f64; 3]; 3]| {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        };
        let d = det(a);
        core::array::from_fn(|k| {
            let mut m = a;
            for (row, &bi) in m.iter_mut().zip(&b) {
                row[k] = bi;
            }
            det(m) / d
        })
    }
}

/// The excavator, from its documented start and from rough guesses (each angle 20–30° off, the
/// centres of mass where the design pose has them, so nothing is assembled), stays on its
/// branch: every angle within 1e-8 rad of the energy minimum found independently (Newton on
/// central differences of the hand-written V in joint angles, from the design pose), and the
/// boom within 1° of its design angle (the cylinders sag by millimetres). The old Newton jumped
/// to a boom angle of 210° from such starts. Tolerance: the independent minimum is resolved to
/// about 1e-11 rad (gradient differences of V ≈ 1e5 J round to 1e-16·1e5/1e-6 = 1e-5 J/rad,
/// over a stiffness above 1e6 J/rad²); the solver's to the rounding floor of its cylinder
/// forces, a few 1e-6 N over the same stiffness.
#[test]
fn excavator_stays_on_its_branch() {
    let mut m = Excavator::default();
    [m.boom_rest, m.stick_rest, m.bucket_rest] = excavator::lengths(excavator::design());
    let reference = excavator::minimum(&m, excavator::design());
    let design = excavator::design();
    let pose = |th: [f64; 3]| {
        let c = excavator::centres(design);
        [c[0][0], c[0][1], th[0], c[1][0], c[1][1], th[1], c[2][0], c[2][1], th[2]]
    };
    let off = |d: [f64; 3]| pose(core::array::from_fn(|i| design[i] + d[i].to_radians()));
    let starts = [
        ("the documented start", m.initial_positions()),
        ("(+25°, −20°, +30°)", off([25.0, -20.0, 30.0])),
        ("(−25°, +25°, −30°)", off([-25.0, 25.0, -30.0])),
        ("(+30°, +30°, +30°)", off([30.0, 30.0, 30.0])),
        ("(−20°, −30°, +40°)", off([-20.0, -30.0, 40.0])),
    ];
    for (from, start) in starts {
        let mut q = start;
        let mut lambda = [0.0; 6];
        let report = StaticSolver::default().solve(&m, &mut Excavator::workspace(), &mut q, 0.0, &mut lambda).expect(from);
        eprintln!("excavator from {from}: {report:?}");
        assert!(report.iterations + report.rejected <= 60, "from {from}: {report:?}");
        let angles = [Excavator::BOOM.phi(&q), Excavator::STICK.phi(&q), Excavator::BUCKET.phi(&q)];
        assert!((angles[0] - design[0]).abs() < 1f64.to_radians(), "from {from}: boom at {}°", angles[0].to_degrees());
        for (i, (a, r)) in angles.iter().zip(reference).enumerate() {
            assert!((a - r).abs() < 1e-8, "from {from}: angle {i} = {a} rad, independent minimum {r}");
        }
        assert!(matches!(report.stability, Stability::Stable { .. }), "from {from}: {report:?}");
    }
}

mechanism! {
    /// The double A-arm of examples/suspension_dynamics.rs with its lower arm's angle driven to
    /// `theta`: for the independent energy scan along the suspension's one degree of freedom.
    pub DoubleAArmScan {
        params { k_s: 30000.0, free_length: 0.61, theta: 0.0 }
        gravity [0.0, -9.81];
        body lower   { mass: 4.0, inertia: 0.05, at: [0.375, 0.14, 0.0] }
        body upper   { mass: 2.5, inertia: 0.02, at: [0.41, 0.46, 0.0] }
        body knuckle { mass: 18.0, inertia: 0.60, at: [0.62, 0.30, 0.0] }
        point lower.inner = [-0.175, 0.01];
        point lower.outer = [0.175, -0.01];
        point lower.spring = [0.1, 0.0];
        point upper.inner = [-0.11, -0.01];
        point upper.outer = [0.11, 0.01];
        point knuckle.lower_ball = [-0.07, -0.17];
        point knuckle.upper_ball = [-0.10, 0.17];
        revolute ground[0.20, 0.15] ~ lower.inner;
        revolute ground[0.30, 0.45] ~ upper.inner;
        revolute lower.outer ~ knuckle.lower_ball;
        revolute upper.outer ~ knuckle.upper_ball;
        spring coil_over: lower.spring ~ ground[0.45, 0.60] { k: k_s, length: free_length };
        drive lower.phi = theta;
    }
}

mechanism! {
    /// The MacPherson strut of examples/suspension_dynamics.rs with its lower arm's angle driven
    /// to `theta`, for the same scan.
    pub MacPhersonScan {
        params { k_s: 25000.0, free_length: 0.48, theta: 0.0 }
        gravity [0.0, -9.81];
        body lower   { mass: 4.0, inertia: 0.05, at: [0.425, 0.11, 0.0] }
        body knuckle { mass: 20.0, inertia: 0.65, at: [0.65, 0.30, 0.0] }
        body rod     { mass: 1.0, inertia: 0.01, at: [0.535, 0.575, 0.0] }
        point lower.inner = [-0.175, 0.01];
        point lower.outer = [0.175, -0.01];
        point knuckle.ball = [-0.05, -0.20];
        point knuckle.strut = [-0.08, 0.10];
        point rod.top = [-0.035, 0.175];
        point rod.bottom = [0.035, -0.175];
        vector knuckle.axis = [-0.07, 0.35];
        vector rod.axis = [-0.07, 0.35];
        revolute ground[0.25, 0.12] ~ lower.inner;
        revolute lower.outer ~ knuckle.ball;
        translational strut: knuckle.strut along knuckle.axis ~ rod.bottom along rod.axis;
        revolute top_mount: rod.top ~ ground[0.50, 0.75];
        spring coil_over: knuckle.strut ~ ground[0.50, 0.75] { k: k_s, length: free_length };
        drive lower.phi = theta;
    }
}

/// The tyre of examples/suspension_dynamics.rs at t = 0: a vertical spring k_t under the contact
/// point, 0.3 m below the knuckle's centre in its frame (the bump, 0.5 s away and 30 ms wide,
/// is e^{−278} of its height there). Returns (load (N), energy (J)).
fn tyre<const NQ: usize>(k_t: f64, knuckle: PlanarBody<NQ>, q: &[f64; NQ]) -> (f64, f64) {
    let contact = knuckle.y(q) - 0.3 * knuckle.phi(q).cos();
    (-k_t * contact, 0.5 * k_t * contact * contact)
}

/// Minimizes E(θ) = V(q(θ)) + tyre energy over the lower-arm angle θ of a driven copy: a coarse
/// scan over ±0.15 rad (about ±50 mm of wheel travel) around `around`, each point solved from
/// its neighbour's position (the linkage stays on its assembly branch), then bisection on the
/// sign of the central difference dE/dθ (step 1e-5 rad). Returns θ at the minimum and the tyre
/// load there.
fn scan<M, const NQ: usize, const NC: usize>(
    mut m: M,
    set: impl Fn(&mut M, f64),
    knuckle: PlanarBody<NQ>,
    k_t: f64,
    around: f64,
) -> (f64, f64)
where
    M: Dynamics<f64, NQ, NQ, NC>,
{
    const POINTS: usize = 61;
    let solver = KinematicSolver::new(KinematicOptions::default().with_tolerance(1e-14));
    // The kinematic solver uses no saddle-point work space: N = 0.
    let mut ws = Workspace::<f64, NQ, NC, 0>::boxed();
    let mut energy = |m: &mut M, theta: f64, q: &mut [f64; NQ]| {
        set(m, theta);
        q[2] = theta; // lower.phi: the driven coordinate
        solver.solve_position(m, &mut ws, q, 0.0).expect("the driven copy assembles");
        m.potential_energy(q, 0.0) + tyre(k_t, knuckle, q).1
    };
    let grid: Vec<f64> = (0..POINTS).map(|i| around - 0.15 + 0.005 * i as f64).collect();
    let mut values = vec![0.0; POINTS];
    let centre = POINTS / 2;
    let mut start = m.initial_positions();
    values[centre] = energy(&mut m, grid[centre], &mut start);
    let mut q = start;
    for i in (0..centre).rev() {
        values[i] = energy(&mut m, grid[i], &mut q);
    }
    q = start;
    for i in centre + 1..POINTS {
        values[i] = energy(&mut m, grid[i], &mut q);
    }
    // One minimum inside the scan, at the centre's neighbourhood.
    let best = (1..POINTS - 1).min_by(|&a, &b| values[a].total_cmp(&values[b])).expect("an interior minimum");
    assert!((1..POINTS - 1).filter(|&i| values[i] < values[i - 1] && values[i] < values[i + 1]).count() == 1, "one minimum");
    let mut q = start;
    let mut slope = |m: &mut M, th: f64, q: &mut [f64; NQ]| (energy(m, th + 1e-5, q) - energy(m, th - 1e-5, q)) / 2e-5;
    let (mut lo, mut hi) = (grid[best - 1], grid[best + 1]);
    assert!(slope(&mut m, lo, &mut q) < 0.0 && slope(&mut m, hi, &mut q) > 0.0, "bracketed");
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if slope(&mut m, mid, &mut q) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let theta = 0.5 * (lo + hi);
    energy(&mut m, theta, &mut q);
    (theta, tyre(k_t, knuckle, &q).0)
}

/// Both suspensions of examples/suspension_dynamics.rs settle on their coil-over springs and
/// tyres from their initial (unassembled) positions, Stable, at the minimum of the total energy
/// along their degree of freedom found by an independent scan of a driven copy (gravity and
/// coil-over from V, the tyre's energy by hand): the lower-arm angle within 1e-8 rad and the
/// tyre load within 1e-3 N (measured: 1.3e-10 rad and 4e-7 N for the double A-arm, 4e-12 rad
/// for the MacPherson). Tolerances: the scan's central differences of E ≈ 300 J with a step of
/// 1e-5 rad round to 1e-16·300/1e-5 ≈ 3e-9 J/rad, and the position solves to 1e-14 m add
/// λ·1e-14/1e-5 ≈ 1e-6 J/rad, over a stiffness of order 1e3–1e4 J/rad²: about 1e-9 rad; the
/// tyre load moves by k_t times the contact's travel, 2e5 N/m · 0.35 m/rad · 1e-8 rad.
#[test]
fn suspensions_settle_on_their_springs() {
    use common::suspension_dynamics::{DoubleAArmRide, MacPhersonRide};
    let a = DoubleAArmRide::default();
    let mut q = a.initial_positions();
    let mut lambda = [0.0; DoubleAArmRide::NC];
    let report = StaticSolver::default().solve(&a, &mut DoubleAArmRide::workspace(), &mut q, 0.0, &mut lambda).expect("double A-arm");
    eprintln!("double A-arm: {report:?}");
    assert!(report.iterations + report.rejected <= 30, "{report:?}");
    assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
    let (theta, load) =
        scan(DoubleAArmScan::default(), |m, th| m.theta = th, DoubleAArmScan::KNUCKLE, a.k_t, DoubleAArmRide::LOWER.phi(&q));
    let got = DoubleAArmRide::LOWER.phi(&q);
    let got_load = tyre(a.k_t, DoubleAArmRide::KNUCKLE, &q).0;
    eprintln!("double A-arm: lower arm {got} rad (scan {theta}), tyre load {got_load} N (scan {load})");
    assert!((got - theta).abs() < 1e-8 && (got_load - load).abs() < 1e-3, "θ {got} vs {theta}, load {got_load} vs {load}");

    let b = MacPhersonRide::default();
    let mut q = b.initial_positions();
    let mut lambda = [0.0; MacPhersonRide::NC];
    let report = StaticSolver::default().solve(&b, &mut MacPhersonRide::workspace(), &mut q, 0.0, &mut lambda).expect("MacPherson");
    eprintln!("MacPherson: {report:?}");
    assert!(report.iterations + report.rejected <= 30, "{report:?}");
    assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
    let (theta, load) =
        scan(MacPhersonScan::default(), |m, th| m.theta = th, MacPhersonScan::KNUCKLE, b.k_t, MacPhersonRide::LOWER.phi(&q));
    let got = MacPhersonRide::LOWER.phi(&q);
    let got_load = tyre(b.k_t, MacPhersonRide::KNUCKLE, &q).0;
    eprintln!("MacPherson: lower arm {got} rad (scan {theta}), tyre load {got_load} N (scan {load})");
    assert!((got - theta).abs() < 1e-8 && (got_load - load).abs() < 1e-3, "θ {got} vs {theta}, load {got_load} vs {load}");
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

mechanism! {
    /// A four-bar under gravity, its crank held by a torsion spring, with every `at:` left out:
    /// all bodies at the origin, every angle 0 — a start where the links lie collinear and
    /// constraint rows depend on each other.
    pub CollinearStart {
        gravity [0.0, -9.81];
        body crank { mass: 1.0, inertia: 0.003 }
        body coupler { mass: 1.0, inertia: 0.02 }
        body rocker { mass: 1.0, inertia: 0.008 }
        revolute ground[0.0, 0.0] ~ crank[-0.1, 0.0];
        revolute crank[0.1, 0.0] ~ coupler[-0.25, 0.0];
        revolute coupler[0.25, 0.0] ~ rocker[-0.2, 0.0];
        revolute rocker[0.2, 0.0] ~ ground[0.5, 0.0];
        rotational_spring ground ~ crank { k: 5.0, angle: 1.0 };
    }
}

/// From that start no Newton step can leave the ground line (by symmetry every step stays on
/// it, and the loop cannot close along it): the error names the unmet row that depends on the
/// others and says to give `at:` angles; a rough guess off the line finds the stable
/// equilibrium.
#[test]
fn statics_from_a_collinear_pose_says_what_to_do() {
    let m = CollinearStart::default();
    let mut ws = CollinearStart::workspace();
    let solver = StaticSolver::default();
    let mut from_zero = m.initial_positions();
    let err = solver.solve(&m, &mut ws, &mut from_zero, 0.0, &mut [0.0; 8]).unwrap_err();
    // Along the line the four pins' x rows depend on one another: the one named is whichever the
    // planned elimination order meets last (`revolute coupler~rocker: x` since 2026-11-27; the
    // last declared before), and it is unmet.
    let StaticError::Singular { row, .. } = err else { panic!("{err:?}") };
    assert!(row.starts_with("revolute") && row.ends_with(": x"), "{row}");
    let mut phi = [0.0; 8];
    m.constraints(&m.initial_positions(), 0.0, &mut phi);
    let named = CollinearStart::CONSTRAINT_NAMES.iter().position(|&n| n == row).expect("a row of the mechanism");
    assert!(phi[named].abs() > 1e-3, "{row}: Φ = {}", phi[named]);
    assert!(err.to_string().contains("give `at:` angles"), "{err}");
    // A guess off the line: the crank at 1 rad, the others roughly.
    let mut guess = m.initial_positions();
    let (s, c) = 1.0f64.sin_cos();
    guess[..3].copy_from_slice(&[0.1 * c, 0.1 * s, 1.0]);
    guess[3..6].copy_from_slice(&[0.35, 0.25, 0.0]);
    guess[6..9].copy_from_slice(&[0.45, 0.2, 1.6]);
    let report = solver.solve(&m, &mut ws, &mut guess, 0.0, &mut [0.0; 8]).expect("statics from a guess");
    assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
}

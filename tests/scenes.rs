//! Scenes (`scene Name without ...;`): one declaration, several generated types, each without
//! the effects it leaves out — absent from its code (its effects, force elements and operation
//! counts) and from its motion, which equals the base's with those effects made inert; and
//! scenes `actuating` their drivers, which follow the driven motion when pushed by the forces
//! inverse dynamics gives.
use mbd::prelude::*;
use mbd::{ForceInfo, OpCount};

mechanism! {
    /// A slider-crank under gravity with a return spring on the slider, pin and slide friction
    /// and a motor torque, and two scenes of it.
    pub Press {
        params { k: 400.0, c: 2.0, mu: 0.2, g: -9.81 }
        gravity [0.0, g];
        body crank  { mass: 2.0, inertia: 0.02, at: [0.05, 0.0, 0.0], velocity: [0.0, 0.0, 6.0] }
        body rod    { mass: 0.8, inertia: 0.006, at: [0.25, 0.0, 0.0] }
        body piston { mass: 0.5, inertia: 1.0e-4, at: [0.4, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0] ~ crank[-0.05, 0.0] { coulomb: mu, radius: 0.01 };
        revolute crankpin: crank[0.05, 0.0] ~ rod[-0.15, 0.0];
        revolute wristpin: rod[0.15, 0.0] ~ piston[0.0, 0.0];
        translational bore: ground[0.0, 0.0] along [1.0, 0.0] ~ piston[0.0, 0.0] along [1.0, 0.0] { coulomb: mu };
        spring return_spring: ground[0.6, 0.0] ~ piston[0.0, 0.0] { k: k, length: 0.2, c: c };
        torque motor: crank = 1.5;
        scene Frictionless without friction;
        scene Bare without return_spring, gravity, friction;
        scene OnlySpring without gravity, friction, motor;
        scene OnlyGravity without return_spring, friction, motor;
        scene Unloaded without return_spring, gravity, friction, motor;
    }
}

/// Integrates 0.5 s with DOPRI5 at rtol 1e-10 from the assembled start; q at the end.
fn run<M: ForwardDynamics<f64, 9, 9, 8>>(m: &M) -> [f64; 9] {
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(m, &mut Workspace::<f64, 9, 8, 17>::new(), &mut q, 0.0).expect("assembles");
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    let mut last = q;
    let v0 = m.initial_velocities();
    Simulation::new(m, &mut dopri)
        .start(0.0, &q, &v0)
        .times(&[0.5])
        .run(&mut Workspace::<f64, 9, 8, 17>::new(), |s| last = s.point.q)
        .expect("runs");
    last
}

fn ops(counts: &[OpCount], function: &str) -> u32 {
    let c = counts.iter().find(|c| c.function == function).unwrap_or_else(|| panic!("no op count for {function}"));
    c.add + c.mul + c.div + c.call
}

/// Each scene is its own type whose effects and force elements are the base's minus what it
/// leaves out, and whose force functions count fewer operations.
#[test]
fn a_scene_declares_and_generates_only_what_it_keeps() {
    assert!(Press::EFFECTS.contains(&"gravity"), "{:?}", Press::EFFECTS);
    assert!(Press::EFFECTS.iter().any(|e| e.contains("friction")), "{:?}", Press::EFFECTS);
    assert!(!Frictionless::EFFECTS.iter().any(|e| e.contains("friction")), "{:?}", Frictionless::EFFECTS);
    assert!(Frictionless::EFFECTS.contains(&"gravity"));
    assert!(!Bare::EFFECTS.contains(&"gravity") && !Bare::EFFECTS.iter().any(|e| e.contains("spring")), "{:?}", Bare::EFFECTS);
    let elements = |f: &[ForceInfo]| f.iter().map(|e| e.name).collect::<Vec<_>>();
    assert!(elements(Press::FORCE_ELEMENTS).contains(&"return_spring"));
    assert!(!elements(Bare::FORCE_ELEMENTS).contains(&"return_spring"), "{:?}", elements(Bare::FORCE_ELEMENTS));
    // The same coordinates and constraints in every scene.
    assert_eq!(Press::COORDINATE_NAMES, Bare::COORDINATE_NAMES);
    assert_eq!(Press::CONSTRAINT_NAMES, Bare::CONSTRAINT_NAMES);
    // What is left out costs nothing: the forces and their derivatives shrink, Φ does not change.
    for f in ["forces", "forces_q"] {
        let (base, bare) = (ops(Press::OP_COUNTS, f), ops(Bare::OP_COUNTS, f));
        eprintln!("{f}: {base} operations in Press, {bare} in Bare");
        assert!(bare < base, "{f}: {bare} ≥ {base}");
    }
    assert_eq!(ops(Press::OP_COUNTS, "constraints"), ops(Bare::OP_COUNTS, "constraints"));
}

/// The force functions' operations of a scene keeping one element, or none.
fn force_ops(counts: &[OpCount]) -> [u32; 3] {
    ["forces", "forces_q", "forces_v"].map(|f| ops(counts, f))
}

/// What an element costs alone (`ForceInfo::op_counts`) is what a scene keeping only it
/// generates, and the base (`BASE_FORCE_OP_COUNTS`) what a scene keeping none generates: in the
/// plane, where the base is empty, and in space, where it is the gyroscopic terms ω × Jω.
#[test]
fn an_element_alone_costs_what_a_scene_keeping_only_it_generates() {
    let alone = |elements: &[ForceInfo], name: &str| {
        force_ops(elements.iter().find(|e| e.name == name).unwrap_or_else(|| panic!("no element {name}")).op_counts)
    };
    let cases = [
        ("return_spring", alone(Press::FORCE_ELEMENTS, "return_spring"), force_ops(OnlySpring::OP_COUNTS)),
        ("gravity", alone(Press::FORCE_ELEMENTS, "gravity"), force_ops(OnlyGravity::OP_COUNTS)),
        ("motor", alone(Press::FORCE_ELEMENTS, "motor"), force_ops(Bare::OP_COUNTS)),
        ("(none)", force_ops(Press::BASE_FORCE_OP_COUNTS), force_ops(Unloaded::OP_COUNTS)),
        ("gravity in space", alone(SpatialDriven::FORCE_ELEMENTS, "gravity"), force_ops(SpatialDriven::OP_COUNTS)),
        ("e_lift", alone(SpatialActuated::FORCE_ELEMENTS, "e_lift"), force_ops(SpatialLifted::OP_COUNTS)),
        ("(none) in space", force_ops(SpatialActuated::BASE_FORCE_OP_COUNTS), force_ops(SpatialWeightless::OP_COUNTS)),
    ];
    for (name, alone, scene) in cases {
        eprintln!("{name}: {alone:?} operations (forces, forces_q, forces_v) alone, {scene:?} in its scene");
        assert_eq!(alone, scene, "{name}");
    }
    // Each costs something above its base: the spring in all three functions (its damping in
    // forces_v), gravity where g is a parameter (m g), and in space the gyroscopic terms.
    assert!(alone(Press::FORCE_ELEMENTS, "return_spring").iter().all(|&n| n > 0));
    assert!(alone(Press::FORCE_ELEMENTS, "gravity")[0] > 0);
    assert!(force_ops(SpatialWeightless::OP_COUNTS)[0] > 0);
}

/// A scene follows the base's motion with the effects it leaves out made inert (a spring of
/// stiffness 0, friction coefficient 0, no gravity): to 1e-12 m and rad after 0.5 s at rtol 1e-10
/// — the inert terms add exact zeros, so the two runs differ only where a zero changes the order
/// of a floating-point sum (measured: 0, bit for bit).
#[test]
fn a_scene_moves_as_the_base_with_its_effects_made_inert() {
    let cases = [
        ("Frictionless", run(&Frictionless::default()), run(&Press { mu: 0.0, ..Press::default() })),
        ("Bare", run(&Bare::default()), run(&Press { mu: 0.0, k: 0.0, c: 0.0, g: 0.0 })),
    ];
    for (name, scene, inert) in cases {
        let d = scene.iter().zip(&inert).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        eprintln!("{name}: {d:e} from the inert base");
        assert!(d <= 1e-12, "{name}: {d:e}");
    }
    // And the effects are not inert in the base: leaving them out changes the motion.
    let moved = |a: [f64; 9], b: [f64; 9]| a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    let base = run(&Press::default());
    assert!(moved(base, run(&Frictionless::default())) > 1e-4, "friction moves the base");
    assert!(moved(base, run(&Bare::default())) > 1e-3, "spring and gravity move the base");
}

mechanism! {
    /// A crank turned by a driver at 6 rad/s and a wobble, and its free scene without it.
    pub Spun {
        body crank { mass: 2.0, inertia: 0.02, at: [0.05, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-0.05, 0.0];
        drive spin: crank.phi = 6.0 * t + 0.1 * sin(3.0 * t);
        scene Unspun without spin;
    }
}

/// The runtime skips whole computations a scene does not need: without a driver nothing depends
/// on time, so ν = −Φ_t is not generated (its function counts no operation) and γ has no Φ_tt
/// terms; without friction the forward dynamics has no fixed-point iteration on the loads — one
/// pass is all there is, where the base needs more than one.
#[test]
fn a_scene_skips_what_it_does_not_need() {
    let time_free = [Spun::PHI_T_IS_ZERO, Unspun::PHI_T_IS_ZERO];
    assert_eq!(time_free, [false, true]);
    assert!(ops(Spun::OP_COUNTS, "velocity_rhs") > 0);
    assert_eq!(ops(Unspun::OP_COUNTS, "velocity_rhs"), 0);

    let (press, frictionless) = (Press::default(), Frictionless::default());
    let mut q = press.initial_positions();
    KinematicSolver::default().assemble(&press, &mut Workspace::<f64, 9, 8, 17>::new(), &mut q, 0.0).expect("assembles");
    let v = press.initial_velocities();
    let one_pass = DynamicsOptions::default().with_friction_iterations(1);
    let (mut vd, mut lambda) = ([0.0; 9], [0.0; 8]);
    let base = press.accelerations(&q, &v, 0.0, &one_pass, &mut vd, &mut lambda);
    assert!(matches!(base, Err(DynamicsError::FrictionNotConverged { .. })), "{base:?}");
    let (mut vd, mut lambda) = ([0.0; 9], [0.0; 8]);
    frictionless.accelerations(&q, &v, 0.0, &one_pass, &mut vd, &mut lambda).expect("one solve, no iteration");
}

mechanism! {
    /// Four bodies, each driven by a driver of another kind: a link by its absolute angle, a
    /// second link by its angle relative to the first, a slider by its x, a lever by the distance
    /// from its tip to a ground point — and the free scene with each driver an actuator.
    pub Driven {
        gravity [0.0, -9.81];
        body a { mass: 1.2, inertia: 0.03, at: [0.25, 0.0, 0.0] }
        body b { mass: 0.7, inertia: 0.01, at: [0.7, 0.0, 0.0] }
        body c { mass: 2.0, inertia: 0.05, at: [1.0, -1.0, 0.0] }
        body d { mass: 0.9, inertia: 0.012, at: [2.2, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ a[-0.25, 0.0];
        revolute a[0.25, 0.0] ~ b[-0.2, 0.0];
        translational ground[0.0, -1.0] along [1.0, 0.0] ~ c[0.0, 0.0] along [1.0, 0.0];
        revolute ground[2.0, 0.0] ~ d[-0.2, 0.0];
        drive a_turn: a.phi = 0.5 * sin(t);
        drive b_bend: angle(a, b) = 0.4 * t;
        drive c_push: c.x = 1.0 + 0.1 * sin(2.0 * t);
        drive d_reach: distance(ground[2.4, 0.5], d[0.2, 0.0]) = 0.5 + 0.05 * sin(t);
        scene Actuated actuating a_turn, b_bend, c_push, d_reach;
        scene Pushed actuating c_push = 3.0 * t;
        scene PushedByParameter actuating c_push;
    }
}

mechanism! {
    /// In space: a sleeve on a cylindrical joint driven in angle and stroke, and a block on a
    /// vertical rail driven in z; the free scene with the three drivers as actuators.
    pub SpatialDriven {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body e { mass: 1.0, inertia: [0.02, 0.03, 0.04, 0.002, 0.0, -0.001], at: [0.3, 0.0, 0.0] }
        body f { mass: 2.0, inertia: [0.05, 0.06, 0.07], at: [1.0, 1.0, 0.5] }
        cylindrical sleeve: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ e[-0.3, 0.0, 0.0] along [0.0, 0.0, 1.0];
        translational rail: ground[1.0, 1.0, 0.0] along [0.0, 0.0, 1.0] ~ f[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0];
        drive e_turn: sleeve.angle = 0.5 * sin(t);
        drive e_lift: sleeve.stroke = 0.1 * t * t;
        drive f_rise: f.z = 0.5 + 0.2 * sin(2.0 * t);
        scene SpatialActuated actuating e_turn, e_lift, f_rise;
        scene SpatialWeightless without gravity;
        scene SpatialLifted without gravity actuating e_lift;
    }
}

/// `max |a − b|`.
fn apart<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// A driven scene's inverse dynamics gives each driver's force (its multiplier λ, N or N·m);
/// the scene `actuating` those drivers, with those forces, follows the same motion: its forward
/// dynamics at the driven state gives the driven accelerations, and the joints it keeps carry
/// the same reactions. Tolerance 1e-8 relative: both sides are exact solves of well-conditioned
/// systems, at a state where Φ = 0 only to the kinematic solver's tolerance, and the forward
/// dynamics' Baumgarte terms act on that residue (measured: 1.2e-10 at most, planar; 3e-14 in
/// space).
#[test]
fn a_scene_actuating_its_drivers_follows_the_motion_inverse_dynamics_gives_its_forces() {
    let driven = Driven::default();
    let solver = KinematicSolver::default();
    let mut ws = Driven::workspace();
    let mut guess = driven.initial_positions();
    assert_eq!((Driven::NC, Actuated::NC), (12, 8), "four driver rows freed");
    for t in [0.0, 0.7, 1.9] {
        let s = solver.analyze(&driven, &mut ws, &guess, t).expect("driven");
        guess = s.q;
        let mut lambda = [0.0; 12];
        InverseDynamics::default().solve(&driven, &mut ws, &s.q, &s.v, &s.vd, t, &mut lambda).expect("inverse dynamics");
        let force = |joint: usize| lambda[Driven::JOINTS[joint].row_range()][0];
        let free = Actuated {
            a_turn_force: force(Driven::A_TURN),
            b_bend_force: force(Driven::B_BEND),
            c_push_force: force(Driven::C_PUSH),
            d_reach_force: force(Driven::D_REACH),
        };
        let (mut vd, mut reactions) = ([0.0; 12], [0.0; 8]);
        free.accelerations(&s.q, &s.v, t, &DynamicsOptions::default(), &mut vd, &mut reactions).expect("forward");
        let scale = s.vd.iter().fold(1.0, |m: f64, x| m.max(x.abs()));
        eprintln!("t = {t}: driver forces {free:?}, v̇ {:.1e} apart", apart(&vd, &s.vd));
        assert!(apart(&vd, &s.vd) <= 1e-8 * scale, "t = {t}: {vd:?} against {:?}", s.vd);
        // The kept rows, matched by name, carry the same reactions.
        for (k, name) in Actuated::CONSTRAINT_NAMES.iter().enumerate() {
            let b = Driven::CONSTRAINT_NAMES.iter().position(|n| n == name).expect("a kept row");
            assert!((reactions[k] - lambda[b]).abs() <= 1e-8 * lambda.iter().fold(1.0, |m: f64, x| m.max(x.abs())), "{name}");
        }
        assert!(force(Driven::A_TURN).abs() > 0.1 && force(Driven::D_REACH).abs() > 0.1, "the drivers carry load");
    }
    // The force as an expression of t is the parameter's value at that t.
    let (q, v) = (driven.initial_positions(), [0.0; 12]);
    let (mut vd_expr, mut vd_param, mut l) = ([0.0; 12], [0.0; 12], [0.0; 11]);
    Pushed::default().accelerations(&q, &v, 2.0, &DynamicsOptions::default(), &mut vd_expr, &mut l).expect("forward");
    let by_parameter = PushedByParameter { c_push_force: 6.0 };
    by_parameter.accelerations(&q, &v, 2.0, &DynamicsOptions::default(), &mut vd_param, &mut l).expect("forward");
    assert_eq!(vd_expr, vd_param);
    assert!((Driven::C.acceleration(&vd_param).x - 3.0).abs() < 1e-12, "6 N on 2 kg: {vd_param:?}");
}

/// The same in space: a joint's angle and stroke and a body's z, freed.
#[test]
fn a_spatial_scene_actuating_its_drivers_follows_the_driven_motion() {
    let driven = SpatialDriven::default();
    let solver = KinematicSolver::default();
    let mut ws = SpatialDriven::workspace();
    let mut guess = driven.initial_positions();
    for t in [0.0, 0.6, 1.3] {
        let s = solver.analyze(&driven, &mut ws, &guess, t).expect("driven");
        guess = s.q;
        let mut lambda = [0.0; 12];
        InverseDynamics::default().solve(&driven, &mut ws, &s.q, &s.v, &s.vd, t, &mut lambda).expect("inverse dynamics");
        let force = |joint: usize| lambda[SpatialDriven::JOINTS[joint].row_range()][0];
        let free = SpatialActuated {
            e_turn_force: force(SpatialDriven::E_TURN),
            e_lift_force: force(SpatialDriven::E_LIFT),
            f_rise_force: force(SpatialDriven::F_RISE),
        };
        let (mut vd, mut reactions) = ([0.0; 12], [0.0; 9]);
        free.accelerations(&s.q, &s.v, t, &DynamicsOptions::default(), &mut vd, &mut reactions).expect("forward");
        let scale = s.vd.iter().fold(1.0, |m: f64, x| m.max(x.abs()));
        eprintln!("t = {t}: v̇ {:.1e} apart", apart(&vd, &s.vd));
        assert!(apart(&vd, &s.vd) <= 1e-8 * scale, "t = {t}: {vd:?} against {:?}", s.vd);
        assert!(force(SpatialDriven::E_LIFT).abs() > 1.0 && force(SpatialDriven::F_RISE).abs() > 1.0, "the lift carries the weight");
    }
}

//! Scenes (`scene Name without ...;`): one declaration, several generated types, each without
//! the effects it leaves out — absent from its code (its effects, force elements and operation
//! counts) and from its motion, which equals the base's with those effects made inert.
use mbd::prelude::*;

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
    }
}

/// Integrates 0.5 s with DOPRI5 at rtol 1e-10 from the assembled start; q at the end.
fn run<M: ForwardDynamics<f64, 9, 9, 8>>(m: &M) -> [f64; 9] {
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(m, &mut Workspace::<f64, 9, 8, 17>::new(), &mut q, 0.0).expect("assembles");
    let mut dopri = Dopri5::new(Dopri5Options { rtol: 1e-10, atol: 1e-12, ..Dopri5Options::default() });
    let mut last = q;
    let v0 = m.initial_velocities();
    simulate(m, &mut Workspace::<f64, 9, 8, 17>::new(), &mut dopri, 0.0, &q, &v0, &[0.5], &SimulationOptions::default(), |s| {
        last = s.point.q
    })
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
    let one_pass = DynamicsOptions { friction_iterations: 1, ..DynamicsOptions::default() };
    let (mut vd, mut lambda) = ([0.0; 9], [0.0; 8]);
    let base = press.accelerations(&q, &v, 0.0, &one_pass, &mut vd, &mut lambda);
    assert!(matches!(base, Err(DynamicsError::FrictionNotConverged { .. })), "{base:?}");
    let (mut vd, mut lambda) = ([0.0; 9], [0.0; 8]);
    frictionless.accelerations(&q, &v, 0.0, &one_pass, &mut vd, &mut lambda).expect("one solve, no iteration");
}

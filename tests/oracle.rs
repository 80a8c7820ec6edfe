//! The CasADi oracle: every example's generated Φ, Φ_q, ν and γ, and its dynamics — the mass
//! diagonal M, the forces h(q, q̇, t), ∂h/∂q, ∂h/∂q̇, the potential energy V, Coulomb friction
//! forces at random loads λ with their ∂/∂q and ∂/∂q̇, and the forward dynamics q̈, λ — evaluated
//! at 200 random states (q, q̇, t and parameters within ±10 % of their defaults), are handed to an
//! independent CasADi rebuild of the model (`tests/oracle/`, Python) that compares them entry by
//! entry. `EveryForce` below declares every kind of force element so that every path of h is
//! checked, `EveryFriction` every form of Coulomb friction. Then the oracle must reject a
//! deliberately wrong Jacobian entry, γ entry, h entry, ∂h/∂q̇ entry, friction force, ∂f/∂q̇
//! entry and q̈ entry, naming where, and mbd's kinematic sweeps must match CasADi's reference
//! trajectories (`tests/oracle/reference/`).
//!
//! The Python environment (pinned CasADi and NumPy) is created on first use by
//! `tests/oracle/ensure_env.sh` under `target/oracle-venv`. A missing Python or CasADi is a
//! failure of this test, never a skip.
use mbd_examples::{double_a_arm, filmstrip, flywheel_engine, four_bar, macpherson, slider_crank, variable_pendulum, web_cutter};
#[path = "common/rng.rs"]
mod rng;
/// The examples this test uses (from mbd-examples, where they are compiled once) and the shared
/// generator (`tests/common/`).
mod common {
    pub(crate) use super::{
        double_a_arm, filmstrip, flywheel_engine, four_bar, macpherson, rng::Rng, slider_crank, variable_pendulum, web_cutter,
    };
}
mod oracle_env;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::Rng;
use oracle_env::{python, repo};

/// The benchmarks' 16-link chain: checked by the oracle too, and its samples file feeds the
/// CasADi C code generation of the side-by-side benchmark (`mbd-bench`).
mod chain16 {
    include!("../benches/chain16.rs");
}
/// The forward-dynamics benchmark's mechanisms: checked by the oracle (M, h, q̈, λ), and their
/// samples files feed the CasADi C code generation of `mbd-bench`'s forward-dynamics comparison.
mod free_slider_crank {
    include!("../benches/free_slider_crank.rs");
}
mod pendulum_chain16 {
    include!("../benches/pendulum_chain16.rs");
}
use mbd::{KinematicSolver, Kinematics, Workspace};
use serde_json::{json, Value};

mbd::mechanism! {
    /// Coulomb friction in every form: a revolute joint (radius and slip velocity from
    /// parameters), a translational joint with a bearing length (normal force and reaction
    /// moment both loading it) and one without, on axes that are not unit vectors and at offset
    /// points, with gravity and a spring-damper so that the loads vary. Three bodies, six
    /// constraint rows: three degrees of freedom.
    pub EveryFriction {
        params { mu: 0.3, r: 0.02, vs: 0.05, width: 0.2, k: 200.0 }
        gravity [0.3, -9.81];
        body arm    { mass: 1.0, inertia: 0.1, at: [0.5, 0.0, 0.1] }
        body slider { mass: 0.5, inertia: 0.01, at: [0.8, 0.1, 0.1] }
        body block  { mass: 0.3, inertia: 0.005, at: [0.75, 0.3, 0.1] }
        revolute ground[0.0, 0.0] ~ arm[-0.5, 0.0] { coulomb: mu, radius: r, slip_velocity: vs };
        translational arm[0.0, 0.05] along [2.0, 0.1] ~ slider[0.0, 0.0] along [1.0, 0.0]
            { coulomb: mu, bearing: width, slip_velocity: vs };
        translational slider[0.05, 0.1] along [0.0, 1.5] ~ block[0.0, -0.1] along [0.0, 1.0]
            { coulomb: 2.0 * mu, slip_velocity: 2.0 * vs };
        spring ground[1.0, 1.0] ~ block[0.0, 0.0] { k: k, length: 0.5, c: 3.0 };
    }
}

mbd::mechanism! {
    /// Every kind of force element the DSL has, with non-trivial parameters, so that the oracle
    /// checks every path of h, ∂h/∂q, ∂h/∂q̇ and V: gravity; point-to-point spring, damper and
    /// actuator, alone and combined, with ground on either side; rotational spring, damper and
    /// torque actuator, alone and combined, with ground on either side; forces at points in global
    /// and in body components (state-, velocity- and time-dependent); torques; viscous friction in
    /// revolute and translational joints (with an axis that is not a unit vector). Three bodies and
    /// six constraint rows: three degrees of freedom.
    pub EveryForce {
        params { k: 350.0, l0: 0.45, c: 4.0, kr: 25.0, g: 9.81, f0: 12.0, mu: 0.08, ax: 1.0, ml: 0.7 }
        gravity [0.4, -g];
        body arm    { mass: 1.2, inertia: 0.08, at: [0.3, 0.1, 0.2] }
        body slider { mass: 2.5, inertia: 0.2, at: [0.8, -0.2, -0.4], velocity: [0.1, 0.0, 0.3] }
        body link   { mass: ml, inertia: ml * 0.04, at: [1.2, 0.3, 0.5] }
        point link.tip = [0.25, -0.05];
        revolute ground[0.0, 0.0] ~ arm[-0.3, 0.0] { viscous: mu };
        translational arm[0.2, 0.05] along [ax, 0.5] ~ slider[0.0, 0.1] along [2.0, 1.0] { viscous: 0.7 };
        revolute slider[0.3, 0.0] ~ link[-0.2, 0.05] { viscous: 0.02 };
        spring full: arm[0.1, 0.05] ~ slider[0.2, -0.1] { k: k, length: l0, c: c, force: f0 * sin(2.0 * t) + arm.vx };
        spring ground[1.0, 1.0] ~ link.tip { k: 2.0 * k, length: 0.3 };
        spring link[-0.1, 0.0] ~ ground[-0.5, 0.8] { k: 80.0, length: l0 / 2.0, c: 1.5 };
        damper ground[1.0, -1.0] ~ slider[0.0, 0.1] { c: 2.0 * c };
        damper arm[0.0, -0.1] ~ link[0.0, 0.0] { c: 0.9 };
        actuator ground[0.0, 1.0] ~ arm[0.0, 0.0] { force: 10.0 * arm.vx + slider.y * link.omega };
        actuator link.tip ~ slider[0.1, 0.1] { force: f0 * cos(t) };
        rotational_spring arm ~ slider { k: kr, angle: 0.2, c: 0.4, torque: 1.0 + link.phi };
        rotational_spring link ~ ground { k: 5.0, angle: -0.3 };
        rotational_spring ground ~ slider { k: 2.0 * kr };
        rotational_damper ground ~ arm { c: 0.3 };
        rotational_damper slider ~ link { c: 0.15 };
        torque_actuator link ~ arm { torque: 2.0 * cos(3.0 * t) * slider.omega };
        force slider[0.1, 0.0] = [1.0, -2.0 * t];
        force link.tip = [arm.x * slider.vy, f0 * exp(-t)];
        local_force arm[0.0, 0.1] = [3.0, slider.omega];
        local_force link[0.1, -0.2] = [-f0 * link.phi, sqrt(1.0 + arm.vy^2)];
        torque slider = 0.5 * cos(t);
        torque link = -c * link.omega + atan2(arm.y, arm.x);
    }
}

mbd::mechanism! {
    /// Every non-smooth function and the conditional, in a driver (so in Φ, ν and γ) and in
    /// forces of coordinates and velocities (so in h, ∂h/∂q, ∂h/∂q̇), and the unilateral elements
    /// (contact with an exponent, cable, tyre on a moving road), with kinks and contacts the
    /// random samples land on either side of. Three bodies, seven rows: two degrees of freedom.
    pub EveryKink {
        params { k: 400.0, c: 6.0, stop: 0.9, w: 2.0 }
        gravity [0.0, -9.81];
        body arm   { mass: 1.0, inertia: 0.1, at: [0.5, 0.0, 0.0] }
        body block { mass: 0.5, inertia: 0.02, at: [1.0, 0.0, 0.0] }
        body cam   { mass: 0.3, inertia: 0.01, at: [2.0, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ arm[-0.5, 0.0];
        translational arm[0.0, 0.0] along [1.0, 0.0] ~ block[0.0, 0.0] along [1.0, 0.0];
        revolute ground[2.0, 0.0] ~ cam[0.0, 0.0];
        drive cam.phi = if t > 1.0 { deg(30.0) * (2.0 * t - 1.0) } else { deg(30.0) * t^2 } + 0.1 * clamp(sin(w * t), -0.5, 0.5);
        force block[0.0, 0.0] = [-k * max(block.x - stop, 0.0)^1.5 - c * abs(block.vx) * sign(block.vx), 10.0 * clamp(arm.phi, -0.2, 0.2)];
        torque arm = (if arm.omega > 0.0 { -c * arm.omega } else { -2.0 * c * arm.omega }) + min(arm.phi, cam.phi);
        torque block = if block.y <= arm.y { 3.0 } else { -abs(block.omega)^3 } + max(block.phi, -block.phi);
        spring arm[0.5, 0.0] ~ cam[0.2, 0.0] { k: 50.0, length: 0.3, force: 20.0 * min(cam.omega, 1.0) };
        point block.tip = [0.1, 0.05];
        contact stop: block.tip ~ ground[1.0, 0.0] along [-1.0, 0.2] { k: 1.0e4, exponent: 1.5, c: 30.0 };
        cable arm[0.3, 0.0] ~ ground[0.5, 1.0] { k: 2000.0, length: 0.9, c: 5.0 };
        tyre block[0.0, -0.1] ~ ground[0.0, -0.2] { radius: 0.15, k: 3000.0, c: 20.0, road: 0.05 * sin(3.0 * block.x - t) };
    }
}

const SAMPLES: usize = 200;

/// Runs the oracle's Python module `module` with `args`; returns (success, stdout + stderr).
fn oracle(py: &Path, module: &str, args: &[&Path]) -> (bool, String) {
    finish(start(py, module, args))
}

/// Starts the oracle's Python module `module` with `args` (one core each: two run side by side).
fn start(py: &Path, module: &str, args: &[&Path]) -> std::process::Child {
    Command::new(py)
        .arg("-m")
        .arg(module)
        .args(args)
        .current_dir(repo().join("tests/oracle"))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the oracle's Python runs")
}

/// Waits for a started module; returns (success, stdout + stderr).
fn finish(child: std::process::Child) -> (bool, String) {
    let out = child.wait_with_output().expect("the oracle's Python runs");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    (out.status.success(), text)
}

/// Evaluates a mechanism's generated functions at random states and writes the samples file.
/// Kinematics: "phi", "jacobian" (structural non-zeros in `JACOBIAN_PATTERN` order), "nu",
/// "gamma". Dynamics: "mass" (the diagonal of M, read from `add_mass_matrix`), "h", "h_q" and
/// "h_qd" (dense NQ×NQ, row r = h_r), "potential"; Coulomb friction at random loads:
/// "friction_lambda", "friction", "friction_q", "friction_qd"; forward dynamics: "qdd",
/// "lambda", "alpha", "beta"; γ's derivatives "gamma_q", "gamma_v" (dense NC×NQ). Planar mechanisms: v = q̇, so NV = NQ and every velocity-space
/// quantity is indexed by the coordinates.
fn write_samples<M, const NQ: usize, const NC: usize>(make: impl Fn(&[f64]) -> M, defaults: &[f64], seed: u64) -> PathBuf
where
    M: mbd::ForwardDynamics<f64, NQ, NQ, NC> + mbd::Linearize<f64, NQ, NQ, NC>,
{
    let mut forward = 0;
    let mut rng = Rng::new(seed);
    let mut samples = Vec::with_capacity(SAMPLES);
    for _ in 0..SAMPLES {
        let params: Vec<f64> = defaults.iter().map(|d| d * rng.uniform(0.9, 1.1)).collect();
        let m = make(&params);
        let mut q = m.initial_positions();
        for v in q.iter_mut() {
            *v += rng.uniform(-0.5, 0.5);
        }
        let v: [f64; NQ] = core::array::from_fn(|_| rng.uniform(-3.0, 3.0));
        let t = rng.uniform(0.0, 2.0);
        let (mut phi, mut d, mut nu, mut gamma) = ([0.0; NC], [[0.0; NQ]; NC], [0.0; NC], [0.0; NC]);
        m.constraints(&q, t, &mut phi);
        m.jacobian(&q, t, &mut d);
        m.velocity_rhs(&q, t, &mut nu);
        m.gamma(&q, &v, t, &mut gamma);
        let (mut h, mut h_q, mut h_v) = ([0.0; NQ], [[0.0; NQ]; NQ], [[0.0; NQ]; NQ]);
        m.forces(&q, &v, t, &mut h);
        m.forces_q(&q, &v, t, &mut h_q);
        m.forces_v(&q, &v, t, &mut h_v);
        let potential = m.potential_energy(&q, t);
        let jacobian: Vec<f64> = M::JACOBIAN_PATTERN.iter().map(|&(r, c)| d[r as usize][c as usize]).collect();
        let named: serde_json::Map<String, Value> = M::PARAM_NAMES.iter().zip(&params).map(|(n, x)| (n.to_string(), json!(x))).collect();
        let dense = |a: &[[f64; NQ]; NQ]| a.iter().map(|row| row.to_vec()).collect::<Vec<_>>();
        let mut mass = [[0.0; NQ]; NQ];
        m.add_mass_matrix(&q, 1.0, &mut mass);
        let mass_diagonal: Vec<f64> = (0..NQ).map(|i| mass[i][i]).collect();
        let mut sample = json!({"params": named, "t": t, "q": q.to_vec(), "qd": v.to_vec(), "phi": phi.to_vec(),
                            "nu": nu.to_vec(), "jacobian": jacobian, "gamma": gamma.to_vec(),
                            "mass": mass_diagonal, "h": h.to_vec(), "h_q": dense(&h_q), "h_qd": dense(&h_v),
                            "potential": potential});
        // Coulomb friction at random loads λ (zeros for a mechanism without it).
        // γ's derivatives (Linearize::gamma_derivatives), dense NC × NV.
        let (mut gamma_q, mut gamma_v) = ([[0.0; NQ]; NC], [[0.0; NQ]; NC]);
        m.gamma_derivatives(&q, &v, t, &mut gamma_q, &mut gamma_v);
        let rows = |a: &[[f64; NQ]; NC]| a.iter().map(|row| row.to_vec()).collect::<Vec<_>>();
        let fields = sample.as_object_mut().expect("a sample is an object");
        fields.insert("gamma_q".into(), json!(rows(&gamma_q)));
        fields.insert("gamma_v".into(), json!(rows(&gamma_v)));
        let friction_lambda: [f64; NC] = core::array::from_fn(|_| rng.uniform(-50.0, 50.0));
        let (mut friction, mut friction_q, mut friction_v) = ([0.0; NQ], [[0.0; NQ]; NQ], [[0.0; NQ]; NQ]);
        m.friction_forces(&q, &v, t, &friction_lambda, &mut friction);
        m.friction_derivatives(&q, &v, t, &friction_lambda, &mut friction_q, &mut friction_v);
        let fields = sample.as_object_mut().expect("a sample is an object");
        fields.insert("friction_lambda".into(), json!(friction_lambda.to_vec()));
        fields.insert("friction".into(), json!(friction.to_vec()));
        fields.insert("friction_q".into(), json!(dense(&friction_q)));
        fields.insert("friction_qd".into(), json!(dense(&friction_v)));
        // ∂f/∂λ, NV × NC (row r: ∂f_r/∂λ; mbd's array holds row k = ∂f/∂λ_k, D's layout).
        let mut slope = [[0.0; NQ]; NC];
        m.friction_multiplier_derivatives(&q, &v, t, &friction_lambda, &mut slope);
        let slope: Vec<Vec<f64>> = (0..NQ).map(|c| slope.iter().map(|row| row[c]).collect()).collect();
        fields.insert("friction_slope".into(), json!(slope));
        // Forward dynamics through the generated sparse Schur-complement solve, with random
        // Baumgarte gains; a random state can sit at a singular configuration, where the solve
        // rightly fails — those samples carry no q̈. With Coulomb friction, the fixed point on λ
        // is asked for to a change of 1e-13 (compare.py's bound accounts for it).
        let (alpha, beta) = (rng.uniform(0.0, 10.0), rng.uniform(0.0, 10.0));
        let (mut vd, mut lambda) = ([0.0; NQ], [0.0; NC]);
        let options = mbd::DynamicsOptions::baumgarte(alpha, beta).with_friction_tolerance(1e-13).with_friction_iterations(500);
        if m.accelerations(&q, &v, t, &options, &mut vd, &mut lambda).is_ok() {
            forward += 1;
            let fields = sample.as_object_mut().expect("a sample is an object");
            fields.insert("qdd".into(), json!(vd.to_vec()));
            fields.insert("lambda".into(), json!(lambda.to_vec()));
            fields.insert("alpha".into(), json!(alpha));
            fields.insert("beta".into(), json!(beta));
        }
        samples.push(sample);
    }
    assert!(forward >= SAMPLES * 9 / 10, "{}: forward dynamics failed at {} of {SAMPLES} random states", M::NAME, SAMPLES - forward);
    let model: Value = serde_json::from_str(M::MODEL_JSON).expect("MODEL_JSON is valid JSON");
    let dir = repo().join("target/oracle/samples");
    std::fs::create_dir_all(&dir).expect("create target/oracle/samples");
    let path = dir.join(format!("{}.json", M::NAME));
    std::fs::write(&path, json!({"model": model, "samples": samples}).to_string()).expect("write samples");
    path
}

macro_rules! samples {
    ($ty:ty, $seed:expr) => {
        write_samples(|p: &[f64]| <$ty>::from_params(p.try_into().expect("one value per parameter")), &<$ty>::default().params(), $seed)
    };
}

#[test]
fn casadi_oracle() {
    let py = python();
    let files = [
        samples!(common::slider_crank::SliderCrank, 11),
        samples!(common::four_bar::FourBar, 12),
        samples!(common::variable_pendulum::VariablePendulum, 13),
        samples!(common::filmstrip::Filmstrip, 14),
        samples!(common::web_cutter::WebCutter, 15),
        samples!(common::double_a_arm::DoubleAArm, 16),
        samples!(common::macpherson::MacPherson, 17),
        samples!(chain16::Chain16, 18),
        samples!(common::flywheel_engine::slider_crank_inverse::Engine, 19),
        samples!(free_slider_crank::FreeSliderCrank, 21),
        samples!(pendulum_chain16::PendulumChain16, 22),
        samples!(EveryFriction, 23),
        samples!(EveryForce, 20),
        samples!(EveryKink, 24),
    ];
    let args: Vec<&Path> = files.iter().map(|p| p.as_path()).collect();
    // The oracle can fail: it must reject a perturbed Jacobian entry, γ entry, h entry, ∂h/∂q̇
    // entry, friction force and ∂f/∂q̇ entry, and name the mechanism, the function, the row and
    // the column. (Started first, it runs beside the comparison.)
    let every = |name: &str| files.iter().find(|p| p.ends_with(format!("{name}.json"))).expect("written above").as_path();
    let selftest = start(&py, "mbd_oracle.selftest", &[files[0].as_path(), every("EveryForce"), every("EveryFriction")]);
    let (ok, text) = oracle(&py, "mbd_oracle.compare", &args);
    println!("{text}");
    assert!(ok, "the CasADi oracle rejected generated functions:\n{text}");

    let (ok, text) = finish(selftest);
    println!("{text}");
    assert!(ok, "the oracle's self-test failed: it accepted a wrong value or did not say where:\n{text}");
}

/// mbd's kinematic sweep against a stored CasADi reference trajectory (CVODES at rtol 1e-12 on
/// q̇ = Φ_q⁻¹ ν): the file's header names the coordinates; rows are t, q.
fn compare_reference<M: Kinematics<f64, NQ, NV, NC>, const NQ: usize, const NV: usize, const NC: usize>(
    m: &M,
    file: &str,
    tol: f64,
) -> f64 {
    let text = std::fs::read_to_string(repo().join("tests/oracle/reference").join(file)).expect("reference file");
    let mut rows = text.lines().filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header: Vec<&str> = rows.next().expect("header").split(',').map(str::trim).collect();
    assert_eq!(&header[1..], M::COORDINATE_NAMES, "{file}: columns are the mechanism's coordinates");
    let data: Vec<Vec<f64>> = rows.map(|l| l.split(',').map(|v| v.trim().parse().expect("number")).collect()).collect();
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    // The kinematic solver uses no saddle-point work space: N = 0.
    let mut ws = Workspace::<f64, NV, NC, 0>::boxed();
    solver.assemble(m, &mut ws, &mut q, data[0][0]).expect("assembles");
    let mut worst = 0.0f64;
    let mut k = 0;
    solver
        .sweep(m, &mut ws, &mut q, data.iter().map(|r| r[0]), |_, q, _, _| {
            for c in 0..NQ {
                worst = worst.max((q[c] - data[k][c + 1]).abs());
            }
            k += 1;
        })
        .expect("sweep");
    assert_eq!(k, data.len());
    assert!(worst <= tol, "{file}: max |q_mbd − q_casadi| = {worst:e} > {tol:e}");
    worst
}

/// Tolerance: the reference integrates at rtol = atol = 1e-12 over one period, so it carries a
/// global error of about 1e-10; mbd solves each position to |Φ| ≤ 1e-10. 1e-8 m (or rad) leaves a
/// margin of a hundred and is still six orders below any modelling error.
#[test]
fn kinematics_match_casadi_reference_trajectories() {
    let worst = [
        compare_reference(&common::slider_crank::SliderCrank::default(), "SliderCrank.csv", 1e-8),
        compare_reference(&common::four_bar::FourBar::default(), "FourBar.csv", 1e-8),
        compare_reference(&common::variable_pendulum::VariablePendulum::default(), "VariablePendulum.csv", 1e-8),
    ];
    println!("max |q_mbd − q_casadi|: slider-crank {:.1e}, four-bar {:.1e}, variable pendulum {:.1e}", worst[0], worst[1], worst[2]);
}

/// mbd's DOP853 against an independent integration: the oracle rebuilds the 16-link pendulum
/// chain from its model JSON, solves its equations of motion symbolically (CasADi's Schur
/// complement, no Baumgarte terms) and integrates them with SUNDIALS CVODES (Adams, rtol 1e-12;
/// `mbd_oracle.integrate`). Released horizontal, after 1 s both agree to 1e-9 (measured 1e-11:
/// each is within about that of the exact motion, local errors of 1e-12 grown by the chain's
/// sensitivity; DOPRI5 at 1e-12 is 4e-9 from DOP853 at 1e-13 over 2 s in `mbd-study`). This is
/// the cross-check of the work-precision study's reference runs.
#[test]
fn dop853_agrees_with_casadi_cvodes_on_the_pendulum_chain() {
    use mbd::{Correction, Dop853, Dop853Options, DynamicsOptions, Mechanism, Simulation, SimulationOptions};
    let py = python();
    let m = pendulum_chain16::PendulumChain16::default();
    let q0 = m.initial_positions();
    let t_end = 1.0;
    let options = SimulationOptions::default().with_dynamics(DynamicsOptions::without_stabilization()).with_correction(Correction::None);
    let mut q = [0.0; 48];
    let mut dop = Dop853::new(Dop853Options::default().with_rtol(1e-12).with_atol(1e-14));
    Simulation::new(&m, &mut dop)
        .start(0.0, &q0, &[0.0; 48])
        .times(&[t_end])
        .options(options)
        .run(&mut pendulum_chain16::PendulumChain16::workspace(), |s| q = s.point.q)
        .expect("DOP853 runs");

    let dir = repo().join("target/oracle/integrate");
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("PendulumChain16.json");
    let model: Value = serde_json::from_str(pendulum_chain16::PendulumChain16::MODEL_JSON).unwrap();
    let data = json!({ "model": model, "q0": q0.to_vec(), "v0": vec![0.0; 48], "t_end": t_end, "rtol": 1e-12, "atol": 1e-14 });
    std::fs::write(&input, data.to_string()).unwrap();
    let (ok, text) = oracle(&py, "mbd_oracle.integrate", &[input.as_path()]);
    assert!(ok, "the oracle's integration failed:\n{text}");
    let line = text.lines().find_map(|l| l.strip_prefix("q_end ")).unwrap_or_else(|| panic!("no q_end in:\n{text}"));
    let theirs: Vec<f64> = line.split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert_eq!(theirs.len(), 48);
    let difference = q.iter().zip(&theirs).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    println!("DOP853 ({} steps) against CVODES: max |Δq| = {difference:e}; {}", dop.accepted, text.lines().last().unwrap_or(""));
    assert!(difference < 1e-9, "DOP853 and CVODES differ by {difference:e} at t = {t_end} s");
}

//! Work space (issue 10, item 5): no solver keeps an O(N²) array on the stack, so a 120-body
//! mechanism (NV = 360, NC = 240: a 3.3 MB [`Workspace`] on the heap) runs assembly, statics
//! and every integrator with every drift correction on a thread with Rust's default 2 MB stack.
//! Before, generalized-α and statics overflowed it (their (NV + NC)² = 2.9 MB saddle-point
//! matrix alone was on the stack), and minimum-norm assembly, partitioning and inverse dynamics
//! kept NC × NV, NC × NC and NV × NV arrays there.
//!
//! The mechanism: a chain of 120 uniform links, 0.1 m and 0.1 kg each, pinned end to end and to
//! ground, straight and 0.3 rad from hanging (`for`).
use mbd::prelude::*;
use mbd::{DenseArrays, System};
use mbd_examples::stewart_platform::StewartPlatform;

mechanism! {
    /// A hanging chain of 120 links, straight and 0.3 rad from hanging.
    pub Chain120 {
        gravity [0.0, -9.81];
        revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0];
        for k in 0..120 {
            body l[k] { mass: 0.1, inertia: 8.333333e-05, at: [(0.05 + 0.1 * k) * sin(0.3), -(0.05 + 0.1 * k) * cos(0.3), 0.3 - PI / 2.0] }
        }
        for k in 1..120 {
            revolute l[k - 1][0.05, 0.0] ~ l[k][-0.05, 0.0];
        }
    }
}

/// Rust's default stack for spawned threads (and the main thread's on many systems).
const DEFAULT_STACK: usize = 2 << 20;

/// Runs `f` on a thread with the default 2 MB stack; an overflow aborts the test binary, so a
/// regression cannot pass silently.
fn on_default_stack<R: Send + 'static>(f: impl FnOnce() -> R + Send + 'static) -> R {
    std::thread::Builder::new().stack_size(DEFAULT_STACK).spawn(f).expect("spawn").join().expect("the run panicked")
}

/// Assembly and statics of the chain, and the top pin's reaction.
#[test]
fn statics_and_kinematics_of_120_bodies_on_a_2_mb_stack() {
    on_default_stack(|| {
        let m = Chain120::default();
        let mut ws = Chain120::workspace();
        assert_eq!(
            Workspace::<f64, 360, 240, 600>::BYTES,
            3_642_240,
            "D twice, D Dᵀ, one NV², two NC², 48 rows of N for the solvers' vectors, 12 for a simulation's points, 4 NC + 2 NV indices"
        );
        let mut q = m.initial_positions();
        KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the chain assembles");
        // Statics from the tilted chain: it hangs straight down, every link at φ = −π/2 (the
        // verdict is Stable, and the angles agree to the solver's tolerance; 1e-8 rad leaves
        // room for the conditioning of 120 links).
        let mut lambda = [0.0; 240];
        let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("the chain hangs");
        assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
        for k in 0..120 {
            let phi = q[3 * k + 2];
            assert!((phi + std::f64::consts::FRAC_PI_2).abs() < 1e-8, "link {k} at φ = {phi}");
        }
        // The pin at the top carries the whole chain's weight, 120 × 0.1 kg × 9.81 m/s² =
        // 117.72 N (λ from the static solve, D as the workspace holds it after inverse
        // dynamics; the chain is not driven, so here D is the generated Jacobian's, on the heap). 1e-9 N: rounding of a sum of 240
        // multipliers of size ≤ 118 N.
        let mut d = vec![[0.0; 360]; 240];
        let d: &mut [[f64; 360]; 240] = d.as_mut_slice().try_into().expect("240 rows");
        m.jacobian(&q, 0.0, d);
        let pin = joint_reaction(&m, &q, d, &lambda, 0).and_then(|r| r.on_j).expect("the top pin acts on l_0");
        assert!(pin.force[0].abs() < 1e-9 && (pin.force[1] - 117.72).abs() < 1e-9, "{pin:?}");
    });
}

/// Every integrator (RK4, DOPRI5, DOP853, generalized-α, BDF, Radau5) with every drift correction,
/// from the tilted chain at rest, for a few
/// steps (the point is the stack, not the motion: a debug build factors the 600-square
/// generalized-α matrix in about a second). Each run must keep the constraints (‖Φ‖∞ below
/// 1e-6 m after 5 ms: the explicit runs' drift is O(h⁵) per step, the corrected ones are held to
/// their correction's tolerance) and stay finite.
#[test]
fn every_integrator_runs_120_bodies_on_a_2_mb_stack() {
    on_default_stack(|| {
        let m = Chain120::default();
        let mut ws = Chain120::workspace();
        let mut q = m.initial_positions();
        KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the chain assembles");
        let times = [2.5e-3, 5e-3];
        for correction in [Correction::None, Correction::projection(), Correction::partitioning()] {
            let options = SimulationOptions::default().with_correction(correction);
            let check = |name: &str, q: &[f64; 360]| {
                let mut phi = [0.0; 240];
                m.constraints(q, 5e-3, &mut phi);
                let worst = phi.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                assert!(worst < 1e-6, "{name}, {correction:?}: ‖Φ‖∞ = {worst:e}");
            };
            let mut last = [0.0; 360];
            Simulation::new(&m, &mut Rk4::new(Rk4Options::default().with_step(1e-3)))
                .start(0.0, &q, &[0.0; 360])
                .times(&times)
                .options(options)
                .run(&mut ws, |s| last = s.point.q)
                .expect("RK4");
            check("RK4", &last);
            let mut dopri = Dopri5::new(Dopri5Options::default());
            Simulation::new(&m, &mut dopri)
                .start(0.0, &q, &[0.0; 360])
                .times(&times)
                .options(options)
                .run(&mut ws, |s| last = s.point.q)
                .expect("DOPRI5");
            check("DOPRI5", &last);
            let mut dop853 = Dop853::new(Dop853Options::default());
            Simulation::new(&m, &mut dop853)
                .start(0.0, &q, &[0.0; 360])
                .times(&times)
                .options(options)
                .run(&mut ws, |s| last = s.point.q)
                .expect("DOP853");
            check("DOP853", &last);
            let mut alpha = Chain120::generalized_alpha(GeneralizedAlphaOptions::default().with_step(2.5e-3));
            Simulation::new(&m, &mut alpha)
                .start(0.0, &q, &[0.0; 360])
                .times(&times)
                .options(options)
                .run(&mut ws, |s| last = s.point.q)
                .expect("generalized-α");
            check("generalized-α", &last);
            // BDF keeps its last seven points (7 × 720 scalars) in the integrator, on the stack.
            let mut bdf = Bdf::new(BdfOptions::default());
            Simulation::new(&m, &mut bdf)
                .start(0.0, &q, &[0.0; 360])
                .times(&times)
                .options(options)
                .run(&mut ws, |s| last = s.point.q)
                .expect("BDF");
            check("BDF", &last);
            Simulation::new(&m, &mut Radau5::default())
                .start(0.0, &q, &[0.0; 360])
                .times(&times)
                .options(options)
                .run(&mut ws, |s| last = s.point.q)
                .expect("Radau5");
            check("Radau5", &last);
        }
    });
}

/// The chain's evaluations are emitted in parts (`mbd-macros`' `PART_NODES`: each is more than
/// 2 000 expression nodes) and their long straight-line sequences in blocks: the accelerations
/// still satisfy the equations of motion written with the functions emitted whole,
/// M v̇ − Dᵀλ = h and D v̇ = γ (Baumgarte off), at a moving, tilted state.
#[test]
fn accelerations_emitted_in_parts_satisfy_the_equations_of_motion() {
    on_default_stack(|| {
        let m = Chain120::default();
        let mut ws = Chain120::workspace();
        let mut q = m.initial_positions();
        KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the chain assembles");
        let options = DynamicsOptions::default().with_baumgarte_alpha(0.0).with_baumgarte_beta(0.0);
        let mut v: [f64; 360] = core::array::from_fn(|i| (0.7 * i as f64).sin());
        m.project_velocities(&q, &mut v, 0.0, &options).expect("v onto D v = 0");
        let (mut vd, mut lambda) = ([0.0; 360], [0.0; 240]);
        m.accelerations(&q, &v, 0.0, &options, &mut vd, &mut lambda).expect("accelerations");
        let (mut mvd, mut h, mut gamma) = ([0.0; 360], [0.0; 360], [0.0; 240]);
        m.mass_times(&q, &vd, &mut mvd);
        m.forces(&q, &v, 0.0, &mut h);
        m.gamma(&q, &v, 0.0, &mut gamma);
        // D on the heap: 691 KB would crowd the 2 MB stack.
        let mut d: Box<[[f64; 360]; 240]> = vec![[0.0; 360]; 240].into_boxed_slice().try_into().expect("240 rows");
        m.jacobian(&q, 0.0, &mut d);
        // Rounding: λ reaches ~120 · 0.1 kg · 9.81 m/s² ≈ 12 N at the top pin and the velocities
        // are O(1); the LDLᵀ of a 240-row chain loses a few digits to its condition number, so
        // 1e-9 is far above rounding and far below any missing or misplaced term (≥ 1e-3).
        for i in 0..360 {
            let dt_lambda: f64 = (0..240).map(|r| d[r][i] * lambda[r]).sum();
            let force = mvd[i] - dt_lambda - h[i];
            assert!(force.abs() < 1e-9, "velocity {i}: M v̇ − Dᵀλ − h = {force:e}");
        }
        for r in 0..240 {
            let dvd: f64 = (0..360).map(|i| d[r][i] * vd[i]).sum();
            assert!((dvd - gamma[r]).abs() < 1e-9, "row {r}: D v̇ − γ = {:e}", dvd - gamma[r]);
        }
        // Generalized-α's matrix, in parts too: its Φ and D equal the functions emitted whole.
        let mut s = Chain120::newton_storage();
        let mut phi = [0.0; 240];
        m.newton_matrix(&q, &v, &[0.0; 360], 0.0, &lambda, None, 0.0, 1e-6, &mut phi, &mut s, ws.dense());
        let mut whole = [0.0; 240];
        m.constraints(&q, 0.0, &mut whole);
        assert_eq!(phi, whole);
        for (k, &(r, c)) in Chain120::JACOBIAN_PATTERN.iter().enumerate() {
            assert_eq!(s[k], d[r as usize][c as usize], "D[{r}][{c}]");
        }
    });
}

include!("common/ladder.rs");

ladder! {
    /// A hanging ladder of 100 four-bar loops (issue 37, item 4): 201 bodies, 503 rows, 100
    /// degrees of freedom.
    Ladder201, 100
}

/// The ladder's assembly, statics and every integrator (DOPRI5 also with partitioning and
/// without a correction) on one thread with the default 2 MB stack in a debug build (issue 37,
/// item 4). Before statics and generalized-α kept their planned
/// Newton matrices (NEWTON_STORAGE scalars each) in the work space, statics copying them a dozen
/// times on the stack, this test overflowed that thread (measured on a1b8d02).
#[test]
fn a_201_body_ladder_runs_statics_assembly_and_every_integrator_on_a_2_mb_stack() {
    on_default_stack(|| {
        let clock = std::time::Instant::now();
        let m = Ladder201::default();
        let mut ws = Ladder201::workspace();
        let mut q = m.initial_positions();
        KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the ladder assembles");
        eprintln!("assembly: {:.1} s", clock.elapsed().as_secs_f64());
        // Every integrator with the default correction (projection), two steps of 1 ms from the
        // assembled, sheared ladder at rest (it starts to swing); the constraints held to 1e-8 m after them.
        let (v0, times, options) = ([0.0; Ladder201::NV], [1e-3, 2e-3], SimulationOptions::default());
        let check = |name: &str, q: &[f64; Ladder201::NQ]| {
            let mut phi = [0.0; Ladder201::NC];
            m.constraints(q, 2e-3, &mut phi);
            let worst = phi.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            assert!(worst < 1e-8, "{name}: ‖Φ‖∞ = {worst:e}");
        };
        let mut last = [0.0; Ladder201::NQ];
        Simulation::new(&m, &mut Rk4::default())
            .start(0.0, &q, &v0)
            .times(&times)
            .options(options)
            .run(&mut ws, |s| last = s.point.q)
            .expect("RK4");
        check("RK4", &last);
        Simulation::new(&m, &mut Dopri5::default())
            .start(0.0, &q, &v0)
            .times(&times)
            .options(options)
            .run(&mut ws, |s| last = s.point.q)
            .expect("DOPRI5");
        check("DOPRI5", &last);
        Simulation::new(&m, &mut Dop853::default())
            .start(0.0, &q, &v0)
            .times(&times)
            .options(options)
            .run(&mut ws, |s| last = s.point.q)
            .expect("DOP853");
        check("DOP853", &last);
        let mut alpha = Ladder201::generalized_alpha(GeneralizedAlphaOptions::default());
        Simulation::new(&m, &mut alpha)
            .start(0.0, &q, &v0)
            .times(&times)
            .options(options)
            .run(&mut ws, |s| last = s.point.q)
            .expect("generalized-α");
        check("generalized-α", &last);
        Simulation::new(&m, &mut Bdf::new(BdfOptions::default()))
            .start(0.0, &q, &v0)
            .times(&times)
            .options(options)
            .run(&mut ws, |s| last = s.point.q)
            .expect("BDF");
        check("BDF", &last);
        Simulation::new(&m, &mut Radau5::default())
            .start(0.0, &q, &v0)
            .times(&times)
            .options(options)
            .run(&mut ws, |s| last = s.point.q)
            .expect("Radau5");
        check("Radau5", &last);
        Simulation::new(&m, &mut Auto::default())
            .start(0.0, &q, &v0)
            .times(&times)
            .options(options)
            .run(&mut ws, |s| last = s.point.q)
            .expect("Auto");
        check("Auto", &last);
        // The other corrections. Partitioning copied D (NC × NV, 2.4 MB here) on the stack in a
        // debug build, past this thread, until it copied row by row. Without a correction the
        // explicit steps' drift after 2 ms is O(h⁵) per step, far below 1e-8 m.
        for correction in [Correction::partitioning(), Correction::None] {
            Simulation::new(&m, &mut Dopri5::default())
                .start(0.0, &q, &v0)
                .times(&times)
                .options(options.with_correction(correction))
                .run(&mut ws, |s| last = s.point.q)
                .expect("DOPRI5");
            check(&format!("DOPRI5 with {correction:?}"), &last);
        }
        eprintln!("integrators: {:.1} s", clock.elapsed().as_secs_f64());
        // Statics from the sheared ladder: it swings back and hangs with its rails vertical, every rung level
        // (the verdict Stable; 1e-6 rad leaves room for the conditioning of 100 stacked loops).
        let mut lambda = [0.0; Ladder201::NC];
        let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("the ladder hangs");
        eprintln!("statics: {:.1} s, {report:?}", clock.elapsed().as_secs_f64());
        assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
        let index = |name: &str| Ladder201::COORDINATE_NAMES.iter().position(|c| *c == name).expect("a coordinate");
        for k in 0..100 {
            let (rail, rung) = (Ladder201::BODY_NAMES[101 + k], Ladder201::BODY_NAMES[k]);
            let phi_rail = q[index(&format!("{rail}.phi"))];
            let phi_rung = q[index(&format!("{rung}.phi"))];
            assert!((phi_rail + std::f64::consts::FRAC_PI_2).abs() < 1e-6, "{rail} at φ = {phi_rail}");
            assert!(phi_rung.abs() < 1e-6, "{rung} at φ = {phi_rung}");
        }
    });
}

/// The ladder's statics and the integrators that used the most stack (Radau5, `Auto`, DOPRI5
/// with partitioning) on an eighth of that, 256 KB, in a debug build (issue 37, item 4): the
/// integrators' stage, residual and Newton vectors, statics' iterate, a simulation's points
/// and, past 2 048 scalars, the generated forward dynamics' arrays are in the work space.
/// Measured by painting the stack (debug): Radau5 1 059 KB → 387 (2026-12-06) → 130
/// (2026-12-07), `Auto` 960 → 389 → 113, DOPRI5 with partitioning 136 → 112, statics 383 → 38.
/// What is left grows with the model by a few scalars a velocity: the sample handed to the
/// callback, the generated functions' temporaries, and an integrator's own arrays where the
/// integrator is on the stack (boxed here: DOP853 holds 216 KB of them for this ladder).
#[test]
fn a_201_body_ladder_runs_statics_and_its_largest_integrators_on_a_quarter_of_a_megabyte() {
    // Made on this thread: `Box::new` of a value builds it on the stack first in a debug build
    // (`Auto` is 141 KB here).
    let (mut radau5, mut auto, mut dopri5) = (Box::new(Radau5::default()), Box::new(Auto::default()), Box::new(Dopri5::default()));
    std::thread::Builder::new()
        .stack_size(256 << 10)
        .spawn(move || {
            // From the ladder as written, not assembled (7 s of the 2 MB test's 11 in a debug
            // build): each run's correction puts its start on the constraints, and statics
            // restores them first.
            let m = Ladder201::default();
            let mut ws = Ladder201::workspace();
            let mut q = m.initial_positions();
            let (v0, times) = ([0.0; Ladder201::NV], [1e-3, 2e-3]);
            let mut last = [0.0; Ladder201::NQ];
            // The constraints held to 1e-8 m after two steps of 1 ms, as on 2 MB above.
            let check = |name: &str, q: &[f64; Ladder201::NQ]| {
                let mut phi = [0.0; Ladder201::NC];
                m.constraints(q, 2e-3, &mut phi);
                let worst = phi.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                assert!(worst < 1e-8, "{name}: ‖Φ‖∞ = {worst:e}");
            };
            Simulation::new(&m, &mut *radau5).start(0.0, &q, &v0).times(&times).run(&mut ws, |s| last = s.point.q).expect("Radau5");
            check("Radau5", &last);
            Simulation::new(&m, &mut *auto).start(0.0, &q, &v0).times(&times).run(&mut ws, |s| last = s.point.q).expect("Auto");
            check("Auto", &last);
            Simulation::new(&m, &mut *dopri5)
                .start(0.0, &q, &v0)
                .times(&times)
                .options(SimulationOptions::default().with_correction(Correction::partitioning()))
                .run(&mut ws, |s| last = s.point.q)
                .expect("DOPRI5 with partitioning");
            check("DOPRI5 with partitioning", &last);
            let mut lambda = [0.0; Ladder201::NC];
            let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("the ladder hangs");
            assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
        })
        .expect("spawn")
        .join()
        .expect("the runs panicked");
}

mechanism! {
    /// A hanging chain of 80 links with Coulomb friction in every pin: its forward dynamics'
    /// arrays are past the 2 048 scalars a generated method keeps on the stack, and each solve
    /// iterates friction's fixed point on the normal loads.
    pub FrictionChain80 {
        gravity [0.0, -9.81];
        revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0] { coulomb: 0.2, radius: 0.01, slip_velocity: 1.0e-3 };
        for k in 0..80 {
            body l[k] { mass: 0.1, inertia: 8.333333e-05, at: [(0.05 + 0.1 * k) * sin(0.3), -(0.05 + 0.1 * k) * cos(0.3), 0.3 - PI / 2.0] }
        }
        for k in 1..80 {
            revolute l[k - 1][0.05, 0.0] ~ l[k][-0.05, 0.0] { coulomb: 0.2, radius: 0.01, slip_velocity: 1.0e-3 };
        }
    }
}

/// A mechanism whose forward-dynamics arrays (D's non-zeros, S's factor, Φ, ν, γ, h, M, M⁻¹,
/// …) are past 2 048 scalars borrows them from the work space when it is called through one
/// (`accelerations_in` and the projections' `_in`, what every solver calls) and keeps them on
/// the stack when called without: the same numbers either way, bit for bit, from a work space
/// that holds another call's values, with Coulomb friction's fixed point (the chain of 80),
/// without (the ladder of 201 bodies), and spatial with coupled inertia, quaternions and
/// drivers (ν ≠ 0): the Stewart platform of `examples/stewart_platform.rs`, 2 127 scalars, which
/// the tests have compiled already (a spatial chain of 18 links written here for it was a fifth
/// of this file's build). Measured by painting the stack (2026-12-07, release): a simulation of
/// the ladder took 141 KB before, 25–38 KB now.
#[test]
fn forward_dynamics_through_the_work_space_is_that_on_the_stack() {
    // 64 MB: the calls through `DenseArrays` put its dense arrays on the stack (the ladder's
    // 10 MB), as a caller without a work space asks.
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(|| {
            let ladder = Ladder201::default();
            same_either_way(&ladder, &mut Ladder201::workspace(), ladder.initial_positions());
            let chain = FrictionChain80::default();
            same_either_way(&chain, &mut FrictionChain80::workspace(), chain.initial_positions());
            let spatial = StewartPlatform::default();
            same_either_way(&spatial, &mut StewartPlatform::workspace(), spatial.initial_positions());
        })
        .expect("spawn")
        .join()
        .expect("the calls panicked");
}

/// [`forward_dynamics_through_the_work_space_is_that_on_the_stack`] for one mechanism from
/// `q` moved off its constraints.
fn same_either_way<M, const NQ: usize, const NV: usize, const NC: usize, const N: usize, const NS: usize>(
    m: &M,
    ws: &mut Workspace<f64, NV, NC, N, NS>,
    mut q: [f64; NQ],
) where
    M: ForwardDynamics<f64, NQ, NV, NC>,
{
    q[0] += 1e-3;
    let v: [f64; NV] = core::array::from_fn(|i| 0.3 * ((i * 7 % 11) as f64 / 10.0 - 0.5));
    let options = DynamicsOptions::default();
    let (mut vd, mut lambda) = ([0.0; NV], [0.0; NC]);
    m.accelerations_in(ws.dense(), &q, &[1.0; NV], 0.5, &options, &mut vd, &mut lambda).expect("another call first");
    let mut from_ws = ([0.0; NV], [0.0; NC]);
    m.accelerations_in(ws.dense(), &q, &v, 0.0, &options, &mut from_ws.0, &mut from_ws.1).expect("through the work space");
    let mut on_stack = ([0.0; NV], [0.0; NC]);
    m.accelerations(&q, &v, 0.0, &options, &mut on_stack.0, &mut on_stack.1).expect("on the stack");
    assert!(from_ws == on_stack, "v̇ and λ differ");
    assert!(on_stack.0.iter().any(|&x| x != 0.0) && on_stack.1.iter().any(|&x| x != 0.0), "a solve with loads");
    // Through a scratch with too few rows for them (`DenseArrays`, which `System::point` and
    // `project` use without a work space), the stack's arrays.
    let mut without = ([0.0; NV], [0.0; NC]);
    m.accelerations_in(DenseArrays::new().scratch(), &q, &v, 0.0, &options, &mut without.0, &mut without.1).expect("DenseArrays");
    assert!(without == on_stack, "v̇ and λ through DenseArrays differ");
    let system = System { mechanism: m, dynamics: options, track_work: true };
    let point = system.point(0.0, q, v, [0.0; 2]).expect("a point with its powers, without a work space");
    assert!((point.vd, point.lambda) == on_stack, "System::point's v̇ and λ differ");
    let (mut q_ws, mut q_stack) = (q, q);
    let moved_ws = m.project_positions_step_in(ws.dense(), &mut q_ws, 0.0, &options).expect("through the work space");
    let moved_stack = m.project_positions_step(&mut q_stack, 0.0, &options).expect("on the stack");
    assert!((moved_ws, q_ws) == (moved_stack, q_stack), "the position steps differ");
    assert!(moved_stack > 0.0 && q_stack != q, "a step that moves q");
    let (mut v_ws, mut v_stack) = (v, v);
    let moved_ws = m.project_velocities_in(ws.dense(), &q, &mut v_ws, 0.0, &options).expect("through the work space");
    let moved_stack = m.project_velocities(&q, &mut v_stack, 0.0, &options).expect("on the stack");
    assert!((moved_ws, v_ws) == (moved_stack, v_stack), "the velocity projections differ");
    assert!(moved_stack > 0.0 && v_stack != v, "a projection that moves v");
}

ladder! {
    /// The ladder with 50 loops (101 bodies) in joint coordinates: a spanning tree of 101
    /// revolutes (NV = 101) and the 51 links as closure rows (NC = 51). M depends on q and there
    /// are rows, so its forward dynamics is the dense one (`dense_forward`: D, M⁻¹Dᵀ, S and M's
    /// factor, 0.18 MB here).
    JointLadder101, 50, joint_coordinates
}

/// In joint coordinates the dense arrays of forward dynamics and of the Newton matrices are the
/// work space's ([`DenseScratch`]) and K = ∂(Dᵀλ)/∂q is generated a column at a time, so the
/// 101-body ladder in joint coordinates runs RK4, DOP853 and `Auto` with each correction,
/// generalized-α, BDF and statics on a 512 KB thread in a debug build. Measured by painting the
/// stack (2026-12-02): before, RK4 needed 0.67 MB in a release build, generalized-α 1.1 MB and
/// statics 1.0 MB in debug (the dense arrays, and K's entry-by-entry code in one 0.5 MB frame);
/// now 0.18, 0.24 and 0.17 MB in debug.
#[test]
fn dense_forward_dynamics_of_joint_coordinates_keeps_its_arrays_off_the_stack() {
    std::thread::Builder::new()
        .stack_size(512 << 10)
        .spawn(|| {
            let m = JointLadder101::default();
            let mut ws = JointLadder101::workspace();
            let mut q = m.initial_positions();
            KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("the ladder assembles");
            let (v0, times) = ([0.0; JointLadder101::NV], [1e-3, 2e-3]);
            let mut last = [0.0; JointLadder101::NQ];
            let check = |name: &str, q: &[f64; JointLadder101::NQ]| {
                let mut phi = [0.0; JointLadder101::NC];
                m.constraints(q, 2e-3, &mut phi);
                let worst = phi.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                // The corrected runs hold 1e-10 m; without a correction the drift of two DOPRI5
                // steps from an assembled start is O(h⁵), far below 1e-8 m.
                assert!(worst < 1e-8, "{name}: ‖Φ‖∞ = {worst:e}");
            };
            for correction in [Correction::projection(), Correction::partitioning(), Correction::None] {
                let options = SimulationOptions::default().with_correction(correction);
                Simulation::new(&m, &mut Rk4::default())
                    .start(0.0, &q, &v0)
                    .times(&times)
                    .options(options)
                    .run(&mut ws, |s| last = s.point.q)
                    .expect("RK4");
                check(&format!("RK4 with {correction:?}"), &last);
                Simulation::new(&m, &mut Dop853::default())
                    .start(0.0, &q, &v0)
                    .times(&times)
                    .options(options)
                    .run(&mut ws, |s| last = s.point.q)
                    .expect("DOP853");
                check(&format!("DOP853 with {correction:?}"), &last);
                Simulation::new(&m, &mut Auto::default())
                    .start(0.0, &q, &v0)
                    .times(&times)
                    .options(options)
                    .run(&mut ws, |s| last = s.point.q)
                    .expect("Auto");
                check(&format!("Auto with {correction:?}"), &last);
            }
            let options = SimulationOptions::default();
            let mut alpha = JointLadder101::generalized_alpha(GeneralizedAlphaOptions::default());
            Simulation::new(&m, &mut alpha)
                .start(0.0, &q, &v0)
                .times(&times)
                .options(options)
                .run(&mut ws, |s| last = s.point.q)
                .expect("generalized-α");
            check("generalized-α", &last);
            let mut bdf = Bdf::new(BdfOptions::default());
            Simulation::new(&m, &mut bdf)
                .start(0.0, &q, &v0)
                .times(&times)
                .options(options)
                .run(&mut ws, |s| last = s.point.q)
                .expect("BDF");
            check("BDF", &last);
            // Statics from the sheared ladder: it swings back to hanging, a stable equilibrium
            // (the angles are checked in body coordinates on the 201-body ladder above; here
            // the point is the stack).
            let mut lambda = [0.0; JointLadder101::NC];
            let report = StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("the ladder hangs");
            assert!(matches!(report.stability, Stability::Stable { .. }), "{report:?}");
        })
        .expect("spawn")
        .join()
        .expect("the runs panicked");
}

//! The kinematic solves over the factorization `mechanism!` plans. The position solve: Newton's
//! iteration with, by default, a last step on the kept factors of D (simplified Newton, the
//! chord method, `KinematicOptions::reuse_safety`). Three settings must land on the same
//! configuration; the kept factors must really be used (the pure chord method converges
//! linearly where Newton converges quadratically), and the default must never take more steps
//! than Newton. The velocity and acceleration of an analysis (`analyze`, `sweep`): through D Dᵀ
//! refined on the residual, they must match the dense LU's, near a singular position too; so
//! must inverse dynamics' multipliers over the same factors.
use mbd::prelude::*;
use mbd::{NonFiniteQuantity, DEFAULT_REUSE_SAFETY};

use mbd_examples::slider_crank;
mod chain16 {
    include!("../benches/chain16.rs");
}
use chain16::Chain16;
use slider_crank::SliderCrank;

mechanism! {
    /// A four-bar driven by the relative angle of its coupler to its crank: the drivers do not
    /// fix any body's angle, so Φ stays nonlinear in every coordinate after the first step.
    pub RelativeFourBar {
        body crank   { mass: 1.0, inertia: 0.01, at: [0.05, 0.05, 0.785] }
        body coupler { mass: 1.0, inertia: 0.05, at: [0.35, 0.12, 0.1] }
        body rocker  { mass: 1.0, inertia: 0.02, at: [0.6, 0.1, 1.4] }
        revolute ground[0.0, 0.0] ~ crank[-0.07, 0.0];
        revolute crank[0.07, 0.0] ~ coupler[-0.25, 0.0];
        revolute coupler[0.25, 0.0] ~ rocker[-0.1, 0.0];
        revolute rocker[0.1, 0.0] ~ ground[0.55, 0.0];
        drive angle(crank, coupler) = -0.7 + 0.3 * sin(2.0 * t);
    }
}

mechanism! {
    /// A chain of 150 links driven at every joint (450 coordinates and rows): large enough for
    /// its position solve to evaluate Φ and D apart (more than `PART_NODES` operations
    /// together) and for its linear algebra to run in nested functions.
    pub DrivenChain150 {
        revolute ground[0.0, 0.0] ~ l[0][-0.05, 0.0];
        for k in 0..150 { body l[k] { mass: 0.1, inertia: 1.0e-4, at: [0.05 + 0.1 * k, 0.0, 0.0] } }
        for k in 1..150 { revolute l[k - 1][0.05, 0.0] ~ l[k][-0.05, 0.0]; }
        drive l[0].phi = 0.1 * sin(t);
        for k in 1..150 { drive angle(l[k - 1], l[k]) = 0.1 * sin(t + k); }
    }
}

mechanism! {
    /// The slider-crank driven by its slider, `gap` short of the dead centre at t = 0 and
    /// moving away from it at 1 mm/s: D's smallest singular value is about r·θ, θ the crank
    /// angle, √(2 gap / (r (1 + r/l))) at t = 0 (3.9e-4 rad for gap = 1e-8 m).
    pub SliderDriven {
        params { gap: 1.0e-8, r: 0.1, l: 0.3 }
        body crank  { mass: 1.0, inertia: 0.002, at: [0.05, 0.0, 0.001] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.25, 0.0, 0.0] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.4, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive slider.x = r + l - gap - 0.001 * t;
    }
}

mechanism! {
    /// The slider-crank driven by its slider into the dead centre x = r + l, where it comes to
    /// rest at t = 1 s, and back out: x = r + l − 0.1 (t − 1)². The crank passes the dead centre
    /// at ω = −√(2 · 0.1 / (r (1 + r/l))) = −1.2247 rad/s and goes on turning the same way.
    pub ThroughDeadCentre {
        params { r: 0.1, l: 0.3 }
        body crank  { mass: 1.0, inertia: 0.002, at: [0.008, 0.049, 1.40] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.158, 0.049, -0.335] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.3, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive slider.x = r + l - 0.1 * (t - 1.0)^2;
    }
}

mechanism! {
    /// A crank-rocker four-bar (0.1, 0.35, 0.2 and 0.3 m) driven by its rocker along the motion
    /// a crank turning at 2π rad/s gives it: the crank passes both toggles (crank and coupler
    /// in line), where the rocker stops. A new user's mechanism, from the trial that found the
    /// sweep returning ω = 0 there.
    pub RockerDriven {
        params { a: 0.1, b: 0.35, c: 0.2, d: 0.3, omega: 2.0 * PI }
        body crank   { mass: 1.0, inertia: 0.001, at: [0.05, 0.0, 0.0] }
        body coupler { mass: 1.0, inertia: 0.01,  at: [0.25, 0.08, 0.5] }
        body rocker  { mass: 1.0, inertia: 0.004, at: [0.35, 0.08, 1.0] }
        revolute ground[0.0, 0.0] ~ crank[-a / 2.0, 0.0];
        revolute crank[a / 2.0, 0.0] ~ coupler[-b / 2.0, 0.0];
        revolute coupler[b / 2.0, 0.0] ~ rocker[c / 2.0, 0.0];
        revolute ground[d, 0.0] ~ rocker[-c / 2.0, 0.0];
        drive rock: rocker.phi = PI + atan2(-a * sin(omega * t), d - a * cos(omega * t))
            - acos((c^2 + a^2 + d^2 - 2.0 * a * d * cos(omega * t) - b^2)
                   / (2.0 * c * sqrt(a^2 + d^2 - 2.0 * a * d * cos(omega * t))));
    }
}

/// The largest |a − b| over max(1, ‖b‖∞).
fn relative_difference<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    let size = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / size
}

/// Along an analysis at `times`, from the `at:` pose solved for the first time (Newton; every
/// mechanism here is driven): its velocity and acceleration
/// (through the planned factors of D Dᵀ, refined) against the dense LU of D at the same q
/// (`solve_velocity`, `solve_acceleration`), and inverse dynamics' multipliers (the same
/// factors) against nalgebra's LU of Dᵀ for the same M v̇ − h. The largest differences over
/// max(1, ‖x‖∞): (v and v̇, λ).
fn against_dense_solves<M, const NQ: usize, const NC: usize, const N: usize>(m: &M, times: &[f64], solver: &KinematicSolver) -> (f64, f64)
where
    M: Dynamics<f64, NQ, NQ, NC>,
{
    use mbd::nalgebra::{DMatrix, DVector};
    let mut ws = Workspace::<f64, NQ, NC, N>::boxed();
    let mut q = m.initial_positions();
    solver.solve_position(m, &mut ws, &mut q, times[0]).expect("starts");
    let (mut kinematic, mut multipliers) = (0.0f64, 0.0f64);
    for &t in times {
        let state = solver.analyze(m, &mut ws, &q, t).unwrap_or_else(|e| panic!("{} at t = {t}: {e}", M::NAME));
        let (mut v, mut vd) = ([0.0; NQ], [0.0; NQ]);
        solver.solve_velocity(m, &mut ws, &state.q, t, &mut v).expect("the dense velocity solve");
        solver.solve_acceleration(m, &mut ws, &state.q, &v, t, &mut vd).expect("the dense acceleration solve");
        kinematic = kinematic.max(relative_difference(&state.v, &v)).max(relative_difference(&state.vd, &vd));

        let mut lambda = [0.0; NC];
        InverseDynamics::default()
            .solve(m, &mut ws, &state.q, &state.v, &state.vd, t, &mut lambda)
            .unwrap_or_else(|e| panic!("{} at t = {t}: {e}", M::NAME));
        let (mut h, mut inertia) = ([0.0; NQ], [0.0; NQ]);
        m.forces(&state.q, &state.v, t, &mut h);
        m.mass_times(&state.q, &state.vd, &mut inertia);
        let mut d = vec![[0.0; NQ]; NC];
        m.jacobian(&state.q, t, d.as_mut_slice().try_into().expect("NC rows"));
        let dt = DMatrix::from_fn(NQ, NC, |i, r| d[r][i]);
        let b = DVector::from_fn(NQ, |i, _| inertia[i] - h[i]);
        let expected = dt.lu().solve(&b).expect("a regular D");
        let expected: [f64; NC] = core::array::from_fn(|r| expected[r]);
        multipliers = multipliers.max(relative_difference(&lambda, &expected));
        q = state.q;
    }
    (kinematic, multipliers)
}

/// Regular positions: both ways leave a few κ(D) ε of relative error, κ(D) of order 10–100 for
/// these mechanisms of 0.1 m links, so they agree to 1e-12 of max(1, ‖x‖∞) (measured: 2e-15
/// and 4e-16; without the refinement the chain of 150 was 7.9e-12 and 1.5e-12 apart).
#[test]
fn the_planned_factors_match_the_dense_lu() {
    let times: Vec<f64> = (0..10).map(|k| 0.37 + 0.1 * k as f64).collect();
    let results = [
        ("slider-crank", against_dense_solves::<_, 9, 9, 18>(&SliderCrank::default(), &times, &KinematicSolver::default())),
        ("relative four-bar", against_dense_solves::<_, 9, 9, 18>(&RelativeFourBar::default(), &times, &KinematicSolver::default())),
        ("chain of 16", against_dense_solves::<_, 48, 48, 96>(&Chain16::default(), &times, &KinematicSolver::default())),
        (
            "driven chain of 150",
            against_dense_solves::<_, 450, 450, 900>(&DrivenChain150::default(), &times[..2], &KinematicSolver::default()),
        ),
    ];
    for (name, (kinematic, multipliers)) in results {
        println!("{name}: v and v̇ {kinematic:.1e} apart, λ {multipliers:.1e}");
        assert!(kinematic < 1e-12 && multipliers < 1e-12, "{name}: {kinematic:e}, {multipliers:e}");
    }
}

/// Near the dead centre κ(D) grows as 1/θ, to about 1e6 at gap = 1e-10 m: D Dᵀ alone leaves
/// about κ² ε of relative error (measured without the refinement: 5.4e-9 already at 1e-6 m),
/// the refinement brings it back to the LU's κ ε (≤ 2e-10), so they must agree to 1e-9 of
/// max(1, ‖x‖∞) (measured: 4e-16). At gap = 1e-10 m the default position tolerance (1e-10 m)
/// no longer resolves the position from the dead centre (D's rows meet at a sine of about
/// 5e-6, below √1e-10): the analysis names the crank's angle instead of answering; a
/// tolerance of 1e-14 m resolves it, and the solves agree again.
#[test]
fn near_a_singular_position_the_refined_solves_match_the_dense_lu() {
    let tight = KinematicSolver::new(KinematicOptions::default().with_tolerance(1e-14));
    let cases = [(1e-6, KinematicSolver::default()), (1e-8, KinematicSolver::default()), (1e-10, tight)];
    for (gap, solver) in cases {
        let m = SliderDriven { gap, ..Default::default() };
        let (kinematic, multipliers) = against_dense_solves::<_, 9, 9, 18>(&m, &[0.0, 1e-3, 2e-3], &solver);
        println!("gap {gap:e} m: v and v̇ {kinematic:.1e} apart, λ {multipliers:.1e}");
        assert!(kinematic < 1e-9 && multipliers < 1e-9, "gap {gap:e}: {kinematic:e}, {multipliers:e}");
    }
    let m = SliderDriven { gap: 1e-10, ..Default::default() };
    let mut ws = SliderDriven::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    match KinematicSolver::default().analyze(&m, &mut ws, &q, 0.0) {
        Err(KinematicError::SingularJacobian { coordinate, .. }) => assert!(coordinate.ends_with(".phi"), "{coordinate}"),
        other => panic!("1e-10 m from the dead centre at the default tolerance: {other:?}"),
    }
}

mechanism! {
    /// A slider driven along √t: at t = 0 its position is finite and its velocity infinite.
    pub RootDriven {
        body slider { mass: 1.0, inertia: 0.1, at: [0.0, 0.0, 0.0] }
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive slider.x = 0.01 * sqrt(t);
    }
}

/// Where the planned solve meets a value that is not finite it gives way to the dense LU,
/// which names the quantity and the row.
#[test]
fn an_infinite_velocity_is_named_by_the_analysis() {
    let m = RootDriven::default();
    let mut ws = RootDriven::workspace();
    match KinematicSolver::default().analyze(&m, &mut ws, &m.initial_positions(), 0.0) {
        Err(KinematicError::NonFinite { t: 0.0, quantity: NonFiniteQuantity::VelocityRhs, row }) => {
            assert!(row.starts_with("drive slider.x"), "{row}")
        }
        other => panic!("{other:?}"),
    }
    let state = KinematicSolver::default().analyze(&m, &mut ws, &m.initial_positions(), 0.25).expect("finite at t = 0.25 s");
    // ẋ = 0.005/√t, ẍ = −0.0025 t^(−3/2).
    assert!((state.v[0] - 0.01).abs() < 1e-15 && (state.vd[0] + 0.02).abs() < 1e-15, "{state:?}");
}

/// Newton (a fresh D at every step), the default and the pure chord method (D's factors from
/// the first step kept to the end) along a sweep of `steps` steps of `h` seconds, each solve
/// started from the last configuration (no predictor: the first residual is the motion of one
/// step). All three must converge to ‖Φ‖∞ ≤ 1e-10 on the same configuration: they solve the
/// same equations, so their answers differ by at most the tolerance over D's smallest singular
/// value, 1e-9 m or rad for these mechanisms of O(0.1 m) links. Returns the Newton steps each
/// took in all, the factorizations of D each made in all, and the largest default count minus
/// Newton's at any one point.
fn sweep<M, const NQ: usize, const NC: usize, const N: usize>(m: &M, h: f64, steps: usize) -> ([u32; 3], [u32; 3], i64)
where
    M: Kinematics<f64, NQ, NQ, NC>,
{
    let mut ws = Workspace::<f64, NQ, NC, N>::boxed();
    let solvers =
        [f64::INFINITY, DEFAULT_REUSE_SAFETY, 0.0].map(|reuse| KinematicSolver::new(KinematicOptions::default().with_reuse_safety(reuse)));
    let mut q = m.initial_positions();
    // Each mechanism is driven: its start is a Newton position solve from the declared pose
    // (assembly's dense minimum-norm steps would take seconds on the 150-link chain in a debug
    // build, and are not what this test is about).
    solvers[0].solve_position(m, &mut ws, &mut q, 0.0).expect("starts");
    let (mut totals, mut factorizations, mut worst_excess) = ([0u32; 3], [0u32; 3], i64::MIN);
    for k in 1..=steps {
        let t = k as f64 * h;
        let mut answers = [q; 3];
        let mut counts = [0u32; 3];
        for (i, (solver, answer)) in solvers.iter().zip(&mut answers).enumerate() {
            let convergence = solver.solve_position(m, &mut ws, answer, t).unwrap_or_else(|e| panic!("{}: {e}", M::NAME));
            assert!(convergence.residual <= 1e-10, "{} at t = {t}: {convergence:?}", M::NAME);
            counts[i] = convergence.iterations;
            factorizations[i] += convergence.factorizations;
        }
        for answer in &answers[1..] {
            for (a, b) in answer.iter().zip(&answers[0]) {
                assert!((a - b).abs() < 1e-9, "{} at t = {t}: {answer:?} against Newton's {:?}", M::NAME, answers[0]);
            }
        }
        for (total, count) in totals.iter_mut().zip(counts) {
            *total += count;
        }
        worst_excess = worst_excess.max(counts[1] as i64 - counts[0] as i64);
        q = answers[0];
    }
    (totals, factorizations, worst_excess)
}

#[test]
fn the_kept_factors_land_where_newton_lands_in_no_more_steps() {
    for h in [1e-3, 1e-2, 5e-2] {
        let results = [
            ("slider-crank", 100, sweep::<_, 9, 9, 18>(&SliderCrank::default(), h, 100)),
            ("relative four-bar", 100, sweep::<_, 9, 9, 18>(&RelativeFourBar::default(), h, 100)),
            ("chain of 16", 100, sweep::<_, 48, 48, 96>(&Chain16::default(), h, 100)),
            ("driven chain of 150", 20, sweep::<_, 450, 450, 900>(&DrivenChain150::default(), h, 20)),
        ];
        for (name, solves, ([newton, default, chord], [newton_d, default_d, chord_d], excess)) in results {
            println!(
                "{name}, steps of {h} s, one sweep: Newton steps: Newton {newton}, default {default}, chord {chord}; factorizations {newton_d}, {default_d}, {chord_d}"
            );
            assert!(excess <= 0, "{name}, h = {h}: the default took {excess} more steps than Newton at one point");
            assert!(chord >= default, "{name}, h = {h}: the chord method took {chord} steps, the default {default}");
            // Full Newton factors at every step; the chord method once per solve.
            assert_eq!(newton_d, newton, "{name}");
            assert_eq!(chord_d, solves, "{name}");
            assert!(default_d <= default, "{name}");
        }
        // The default's savings: a millisecond on, every solve of the chain and of the relative
        // four-bar ends on the kept factors (one factorization, two steps); the slider-crank's
        // second step is Newton's (the test below).
        if h == 1e-3 {
            for (name, _, (steps, factorizations, _)) in &results[1..3] {
                assert_eq!((steps[1], factorizations[1]), (200, 100), "{name}");
            }
        }
    }
}

#[test]
fn the_chord_method_converges_linearly_and_the_default_sees_it() {
    let m = SliderCrank::default();
    let mut ws = SliderCrank::workspace();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.37).expect("assembles");
    let mut residual_after_two = |reuse: f64| {
        let options = KinematicOptions::default().with_reuse_safety(reuse).with_max_iterations(2).with_tolerance(1e-16);
        let mut qn = q;
        match KinematicSolver::new(options).solve_position(&m, &mut ws, &mut qn, 0.371) {
            Err(KinematicError::NotConverged { iterations: 2, residual, .. }) => residual,
            other => panic!("{other:?}"),
        }
    };
    let (newton, chord, default) = (residual_after_two(f64::INFINITY), residual_after_two(0.0), residual_after_two(DEFAULT_REUSE_SAFETY));
    println!("after two steps: Newton {newton:.2e}, chord {chord:.2e}, default {default:.2e}");
    assert!(newton < 1e-11, "{newton}");
    assert!(chord > 1e-10 && chord < 1e-8, "{chord}");
    assert_eq!(default, newton);
}

/// A position solve started next to a dead centre stays on its branch. There D is nearly
/// singular, and Newton's full steps D⁻¹(−Φ) from 1e-7 rad off the dead centre to the pose
/// 0.01 s later land the crank 999 rad away (159 turns; a new user's sweep crossing the dead
/// centre had it 42 turns away), on a solution of the same pose with its angle no longer
/// continuous. The damped step (`KinematicOptions::max_step`, 1 rad) lands it next to
/// the dead centre, where the crank is 0.0122 rad from it either way (|cos φ| is fixed by the
/// slider; Newton picks the side), within 0.05 rad.
#[test]
fn a_position_solve_from_a_dead_centre_stays_on_its_branch() {
    let m = ThroughDeadCentre::default();
    let mut ws = ThroughDeadCentre::workspace();
    // The dead centre at t = 1 s: every body on the x axis, the crank 1e-7 rad off it.
    let (r, l, phi) = (m.r, m.l, 1e-7f64);
    let mut q = [r / 2.0 * phi.cos(), r / 2.0 * phi.sin(), phi, r * phi.cos() + l / 2.0, r * phi.sin() / 2.0, 0.0, r + l, 0.0, 0.0];
    let solver = KinematicSolver::default();
    solver.solve_position(&m, &mut ws, &mut q, 1.01).expect("converges next to the dead centre");
    let crank = ThroughDeadCentre::CRANK.phi(&q);
    println!("crank at 1.01 s: {crank} rad");
    assert!(crank.abs() < 0.05 && crank.abs() > 0.01, "the crank left its branch: {crank} rad");
}

/// On a grid that crosses the dead centre exactly, a sweep follows the crank up to it and stops
/// there with the coordinate D no longer determines named: at t = 1 s the velocity is not
/// determined by D v = ν (the slider is at rest, the crank turning at 1.2247 rad/s), and the
/// position the solve reaches is within what its tolerance resolves of the singular one. `q`
/// holds the last point solved, 0.01 s before. A grid that steps over the dead centre passes
/// it, the crank turning on at the speed it came with.
#[test]
fn a_sweep_stops_at_a_dead_centre_and_passes_it_between_grid_points() {
    let m = ThroughDeadCentre::default();
    let mut ws = ThroughDeadCentre::workspace();
    let solver = KinematicSolver::default();
    let mut start = m.initial_positions();
    solver.assemble(&m, &mut ws, &mut start, 0.0).expect("assembles");
    let mut q = start;
    let exact: Vec<f64> = (0..=200).map(|k| k as f64 * 0.01).collect();
    let mut last = 0.0;
    match solver.sweep(&m, &mut ws, &mut q, &exact, |t, _, _, _| last = t) {
        Err(KinematicError::SingularJacobian { t, coordinate, .. }) => {
            println!("stopped at {t} s: {coordinate}");
            assert_eq!(t, 1.0);
            assert!(coordinate.ends_with(".phi"), "{coordinate}");
        }
        other => panic!("expected a singular Jacobian at the dead centre, found {other:?}"),
    }
    assert!((last - 0.99).abs() < 1e-12 && (ThroughDeadCentre::CRANK.phi(&q) - 0.012248).abs() < 1e-5, "{last} s");
    // The grid of 0.01 s shifted by 0.005 s steps over the dead centre: the crank angle moves
    // 0.0122 rad per step, so no step may move it 0.05 rad; the motion is symmetric about
    // t = 1 s with the crank turning on (φ(2 − t) = −φ(t), checked to 1e-8 at the ends), and
    // the crank's speed 5 ms after the dead centre is the speed 5 ms before it, to 5e-4 rad/s:
    // ‖Φ‖∞ ≤ 1e-10 m leaves φ uncertain by at most about 1e-10 m / (r φ / 8) ≈ 1.3e-6 rad at
    // φ = 0.006 rad (D's rows meet at a sine of about φ/8), and ω, the slider's speed over
    // r φ there, by ω · 1.3e-6 / 0.006 ≈ 3e-4 ω (measured 3e-9: Newton ends far inside).
    let shifted: Vec<f64> = (0..200).map(|k| 0.005 + k as f64 * 0.01).collect();
    let mut q = start;
    let mut crank = Vec::new();
    solver
        .sweep(&m, &mut ws, &mut q, &shifted, |t, q, v, _| crank.push((t, ThroughDeadCentre::CRANK.phi(q), v[2])))
        .expect("the sweep steps over the dead centre");
    for pair in crank.windows(2) {
        let ((t0, phi0, _), (t1, phi1, _)) = (pair[0], pair[1]);
        assert!((phi1 - phi0).abs() < 0.05, "the crank jumped from {phi0} rad at {t0} s to {phi1} rad at {t1} s");
    }
    let (first, end) = (crank[0], crank[199]);
    assert!(first.1 > 1.0 && (first.1 + end.1).abs() < 1e-8, "φ(0.005) = {}, φ(1.995) = {}", first.1, end.1);
    let (before, after) = (crank[99], crank[100]);
    println!("ω at {} s: {} rad/s, at {} s: {} rad/s", before.0, before.2, after.0, after.2);
    assert!(before.2 < -1.2 && (before.2 - after.2).abs() < 5e-4, "ω before {}, after {}", before.2, after.2);
}

/// The same at a four-bar's toggle, where Φ bends more sharply than at the slider-crank's dead
/// centre (the rows meet at a sine of 5.5e-5 at the position solved, against 6e-6): a grid
/// reaching the extended toggle exactly, t* = α/ω with cos α = (d² + (a + b)² − c²) / (2 d (a + b)),
/// stops there naming a coordinate; a grid of 0.01 s over a whole turn passes both toggles
/// with the crank at φ = ωt, to 1e-6 rad (measured by the new user: 3.1e-8).
#[test]
fn a_four_bar_sweep_stops_at_its_toggle_and_passes_it_between_grid_points() {
    let m = RockerDriven::default();
    let (a, b, c, d) = (m.a, m.b, m.c, m.d);
    let toggle = ((d * d + (a + b) * (a + b) - c * c) / (2.0 * d * (a + b))).acos() / m.omega;
    let solver = KinematicSolver::default();
    let mut ws = RockerDriven::workspace();
    let mut start = m.initial_positions();
    solver.assemble(&m, &mut ws, &mut start, 0.0).expect("assembles");
    let mut q = start;
    let times = [0.0, 0.01, 0.02, 0.03, 0.04, 0.05, toggle, toggle + 0.002];
    match solver.sweep(&m, &mut ws, &mut q, times, |_, _, _, _| ()) {
        Err(KinematicError::SingularJacobian { t, coordinate, constraint }) => {
            println!("stopped at {t} s: {coordinate}, {constraint}");
            assert_eq!(t, toggle);
        }
        other => panic!("expected a singular Jacobian at the toggle {toggle} s, found {other:?}"),
    }
    let mut q = start;
    let grid: Vec<f64> = (0..=100).map(|k| k as f64 * 0.01).collect();
    let mut worst = 0.0f64;
    solver
        .sweep(&m, &mut ws, &mut q, &grid, |t, q, _, _| {
            let exact = m.omega * t;
            let phi = RockerDriven::CRANK.phi(q);
            worst = worst.max((phi - exact).abs());
        })
        .expect("a grid that steps over the toggles passes them");
    println!("crank angle within {worst:e} rad of ωt over a turn");
    assert!(worst < 1e-6, "{worst:e}");
}

/// A 1 m rod pinned to ground at both ends, 2 m apart: a loop that cannot close. Beside it a
/// pendulum, whose pin can hold. DOF 0 as counted (6 coordinates, 6 rows), and no solution.
/// Declared in body coordinates and, with `joint_coordinates;`, in joint coordinates, where the
/// tree holds `near` and `hang` exactly and `far` is cut.
macro_rules! too_short {
    ($name:ident $($formulation:tt)*) => {
        mechanism! {
            pub $name {
                $($formulation)*
                body rod { mass: 1.0, inertia: 0.08, at: [0.6, 0.1, 0.2] }
                body bob { mass: 1.0, inertia: 0.01, at: [0.1, -3.1, 0.1] }
                revolute near: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
                revolute far: ground[2.0, 0.0] ~ rod[0.5, 0.0];
                revolute hang: ground[0.0, -3.0] ~ bob[0.0, 0.2];
            }
        }
    };
}
too_short!(TooShort);
too_short!(TooShortJoint joint_coordinates;);

mechanism! {
    /// A 1 m rod pinned at one end, its tip driven to 1.5 m from a point 3 m away: out of reach.
    pub Unreachable {
        body rod { mass: 1.0, inertia: 0.08, at: [0.35, 0.35, 0.785] }
        point rod.tip = [0.5, 0.0];
        revolute ground[0.0, 0.0] ~ rod[-0.5, 0.0];
        drive reach: distance(ground[3.0, 0.0], rod.tip) = 1.5;
    }
}

mechanism! {
    /// The slider-crank driven by its slider out past the dead centre x = r + l: 1.5 mm short of
    /// it at t = 0, moving out at 10 mm/s, so the loop can close until t = 0.15 s and not after.
    pub PastDeadCentre {
        params { r: 0.1, l: 0.3 }
        body crank  { mass: 1.0, inertia: 0.002, at: [0.05, 0.0, 0.1] }
        body rod    { mass: 2.0, inertia: 0.015, at: [0.25, 0.0, -0.03] }
        body slider { mass: 0.5, inertia: 0.001, at: [0.4, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational slider[0.0, 0.0] along [1.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0];
        drive stroke: slider.x = r + l - 0.0015 + 0.01 * t;
    }
}

/// The rows and residual of a `CannotAssemble`, or a panic naming what came instead.
fn cannot_assemble<R: std::fmt::Debug>(result: Result<R, KinematicError>) -> (f64, Vec<&'static str>, String) {
    match result {
        Err(e @ KinematicError::CannotAssemble { residual, rows, .. }) => (residual, rows.names().collect(), e.to_string()),
        other => panic!("expected CannotAssemble, got {other:?}"),
    }
}

/// A loop that cannot close is reported as such, with the smallest residual a descent reaches
/// and the rows of that loop only — not a row of the pendulum beside it, which closes. In body
/// coordinates that minimum of ‖Φ‖² spreads the 1 m gap over both pins: the rod lies on the
/// x-axis centred at x = 1, each pin 0.5 m off in x and exact in y (the closed form: by symmetry
/// the two x residuals are equal, and they sum to the gap). In joint coordinates the tree's
/// pin holds exactly and the cut pin carries the whole gap: the rod along x, 1 m short. The
/// descent's tolerance on a minimum (a step lowering ‖Φ‖² by less than 1e-12 of it) puts q
/// within about 1e-6 of it, so the residuals are checked to 1e-6 m. A driven solve (this
/// mechanism counts DOF 0) says the same, and so does a sweep driven past a limit position.
#[test]
fn a_loop_that_cannot_close_is_named_with_its_smallest_residual() {
    let solver = KinematicSolver::default();
    let m = TooShort::default();
    let mut q = m.initial_positions();
    let (residual, mut rows, message) = cannot_assemble(solver.assemble(&m, &mut TooShort::workspace(), &mut q, 0.0));
    rows.sort();
    assert!((residual - 0.5).abs() < 1e-6, "{residual}");
    assert_eq!(rows, ["far: x", "near: x"], "{message}");
    assert!(message.contains("cannot assemble at t = 0 s") && message.contains("'far: x'"), "{message}");
    // `q` is the closest configuration: the rod on the x-axis centred at x = 1, the pendulum's
    // pin holding (to the position tolerance) wherever the bob swung.
    assert!((TooShort::ROD.x(&q) - 1.0).abs() < 1e-6 && TooShort::ROD.y(&q).abs() < 1e-6 && TooShort::ROD.phi(&q).abs() < 1e-6, "{q:?}");
    let mut phi = [0.0; TooShort::NC];
    m.constraints(&q, 0.0, &mut phi);
    for (name, value) in TooShort::CONSTRAINT_NAMES.iter().zip(phi) {
        assert!(!name.starts_with("hang") || value.abs() <= 1e-10, "{name}: {value}");
    }

    // A driven mechanism asked for a position it cannot reach: the rod's tip, 1 m from its pin,
    // driven to 1.5 m from a point 3 m away. Its driven solve says so, naming the driver.
    let d = Unreachable::default();
    let mut q = d.initial_positions();
    let (residual, rows, message) = cannot_assemble(solver.solve_position(&d, &mut Unreachable::workspace(), &mut q, 0.0));
    assert!(residual > 0.1 && rows.contains(&"reach: distance"), "{message}");
    assert!(matches!(solver.analyze(&d, &mut Unreachable::workspace(), &q, 0.0), Err(KinematicError::CannotAssemble { .. })));

    // Driven past a limit position: a sweep follows the slider to 0.5 mm short of the dead
    // centre (t = 0.1 s) and at t = 0.2 s, 0.5 mm beyond it, says the loop cannot close, naming
    // the driver and the pins' rows along the line. Closest is the crank and rod laid straight
    // along x, the 0.5 mm shared by the four rows along x (the three pins' and the driver's, each
    // a difference of x-coordinates, so the gap is their sum): ½‖Φ‖² least where each takes a
    // quarter, 0.125 mm.
    let p = PastDeadCentre::default();
    let mut q = p.initial_positions();
    let mut ws = PastDeadCentre::workspace();
    solver.assemble(&p, &mut ws, &mut q, 0.0).expect("assembles short of the dead centre");
    let mut reached = Vec::new();
    let past = solver.sweep(&p, &mut ws, &mut q, [0.0, 0.1, 0.2], |t, _, _, _| reached.push(t));
    let (residual, mut rows, message) = cannot_assemble(past);
    println!("{message}");
    assert_eq!(reached, [0.0, 0.1]);
    rows.sort();
    assert!(message.contains("t = 0.2 s"), "{message}");
    assert_eq!(rows, ["revolute crank~rod: x", "revolute ground~crank: x", "revolute rod~slider: x", "stroke: x"], "{message}");
    // to 1e-12 m: the descent's Newton steps on ½‖Φ‖² converge quadratically (measured 4e-17)
    assert!((residual - 1.25e-4).abs() < 1e-12, "{residual}");

    let j = TooShortJoint::default();
    let mut q = j.initial_positions();
    let (residual, rows, message) = cannot_assemble(solver.assemble(&j, &mut TooShortJoint::workspace(), &mut q, 0.0));
    assert!((residual - 1.0).abs() < 1e-6, "{residual}");
    assert_eq!(rows, ["far: x"], "{message}");
}

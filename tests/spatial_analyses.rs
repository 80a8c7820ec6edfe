//! Every analysis on spatial mechanisms: forward dynamics with every integrator and every drift
//! correction (energy of a conservative double pendulum), inverse dynamics with joint reactions
//! in N and N·m (a driven crank against a closed-form torque and its bearing reaction), and
//! statics (a hinged bar on a torsion spring against its equilibrium equation).
use mbd::prelude::*;
use mbd::{nalgebra, Sample};

mechanism! {
    /// A spatial double pendulum: a bar on a ball joint at the ground origin, a second bar on a
    /// hinge at its end; started out of any plane so that the motion is fully spatial.
    pub SpatialDoublePendulum {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body upper { mass: 1.0, inertia: [0.0835, 0.0835, 0.001], at: [0.0, 0.5, 0.0], axis_angle: [1.0, 0.0, 0.0, -1.5707963267948966], omega: [0.5, 0.0, 1.0] }
        body lower { mass: 0.7, inertia: [0.0585, 0.0585, 0.0007], at: [0.0, 1.0, 0.35], omega: [0.0, 0.3, 0.0] }
        spherical shoulder: ground[0.0, 0.0, 0.0] ~ upper[0.0, 0.0, -0.5];
        revolute elbow: upper[0.0, 0.0, 0.5] along [1.0, 0.0, 0.0] ~ lower[0.0, 0.0, -0.35] along [1.0, 0.0, 0.0];
    }
}

mechanism! {
    /// A crank on a horizontal hinge (axis global y), its centre of mass e from the axis, driven
    /// at a constant rate against gravity: the drive torque is m g e cos θ (+ nothing inertial at
    /// constant rate about a principal axis through... the hinge), the bearing carries m g plus
    /// the centripetal force m e ω².
    pub DrivenCrank {
        spatial;
        params { e: 0.2, w: 3.0 }
        gravity [0.0, 0.0, -9.81];
        body crank { mass: 2.0, inertia: [0.01, 0.02, 0.03], at: [e, 0.0, 0.0] }
        revolute bearing: ground[0.0, 0.0, 0.0] along [0.0, -1.0, 0.0] reference [1.0, 0.0, 0.0] ~ crank[-e, 0.0, 0.0] along [0.0, -1.0, 0.0] reference [1.0, 0.0, 0.0];
        drive motor: bearing.angle = w * t;
    }
}

mechanism! {
    /// A bar hinged at one end about the global y-axis, held by a torsion spring against gravity.
    pub SpringBar {
        spatial;
        params { k: 20.0 }
        gravity [0.0, 0.0, -9.81];
        body bar { mass: 2.0, inertia: [0.01, 0.17, 0.17], at: [0.5, 0.0, 0.0] }
        revolute hinge: ground[0.0, 0.0, 0.0] along [0.0, -1.0, 0.0] ~ bar[-0.5, 0.0, 0.0] along [0.0, -1.0, 0.0];
        rotational_spring hinge { k: k };
    }
}

/// T + V of the double pendulum, from the generated energies.
fn energy(m: &SpatialDoublePendulum, q: &[f64; 14], v: &[f64; 12]) -> f64 {
    kinetic_energy(m, q, v) + m.potential_energy(q, 0.0)
}

/// The largest |Φ| and |ΔE| (J) of a 2 s run of the double pendulum with `integrator`
/// ("rk4", "dopri5" or "generalized-α", at step `h` where it has one) and `correction`.
fn run(integrator: &str, h: f64, correction: Correction<f64>) -> (f64, f64, f64) {
    let m = SpatialDoublePendulum::default();
    let mut q0 = m.initial_positions();
    KinematicSolver::new(KinematicOptions::default())
        .assemble(&m, &mut SpatialDoublePendulum::workspace(), &mut q0, 0.0)
        .expect("assembles");
    let mut v0 = m.initial_velocities();
    m.project_velocities(&q0, &mut v0, 0.0, &DynamicsOptions::default()).expect("consistent velocities");
    let e0 = energy(&m, &q0, &v0);
    let times: Vec<f64> = (1..=200).map(|k| k as f64 * 0.01).collect();
    let options = SimulationOptions::default().with_correction(correction);
    let (mut worst_phi, mut worst_e) = (0.0f64, 0.0f64);
    let mut check = |s: &Sample<f64, 14, 12, 8>| {
        let mut phi = [0.0; 8];
        m.constraints(&s.point.q, s.point.t, &mut phi);
        worst_phi = phi.iter().fold(worst_phi, |w, x| w.max(x.abs()));
        worst_e = worst_e.max((energy(&m, &s.point.q, &s.point.v) - e0).abs());
    };
    let result = match integrator {
        "rk4" => Simulation::new(&m, &mut Rk4::new(Rk4Options::default().with_step(h)))
            .start(0.0, &q0, &v0)
            .times(&times)
            .options(options)
            .run(&mut SpatialDoublePendulum::workspace(), &mut check),
        "dopri5" => {
            let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-11));
            Simulation::new(&m, &mut dopri)
                .start(0.0, &q0, &v0)
                .times(&times)
                .options(options)
                .run(&mut SpatialDoublePendulum::workspace(), &mut check)
        }
        _ => {
            let ga = GeneralizedAlphaOptions::default().with_step(h).with_rho_infinity(0.9);
            Simulation::new(&m, &mut SpatialDoublePendulum::generalized_alpha(ga))
                .start(0.0, &q0, &v0)
                .times(&times)
                .options(options)
                .run(&mut SpatialDoublePendulum::workspace(), &mut check)
        }
    };
    let stats = result.unwrap_or_else(|e| panic!("{integrator} with {correction:?}: {e}"));
    // Watched without a correction (issue 39, item 7), a double pendulum has no singular
    // position: nothing is reported (its rows' sines stay near 1).
    assert_eq!(stats.singular, None, "{integrator} with {correction:?}");
    (worst_phi, worst_e, e0)
}

/// The conservative spatial double pendulum for 2 s with RK4 (h = 1 ms), DOPRI5 (rtol 1e-9) and
/// generalized-α (ρ∞ = 0.9), each with no correction, projection and partitioning: every run
/// stays on the constraints (to 1e-5 without correction, the integration error; to 1e-8 with
/// one, its 1e-10 at the steps plus the interpolation to the output times) and keeps its energy — RK4 and DOPRI5 to 1e-5 J of 2.4 J;
/// generalized-α, which does not conserve energy exactly, to 1 %, and its energy error falls
/// by ≥ 3× when h halves from 2 ms to 1 ms (second order: 4×) — except with partitioning (below).
#[test]
fn every_integrator_and_correction() {
    for correction in [Correction::None, Correction::projection(), Correction::partitioning()] {
        // outputs are interpolated within a step, so even corrected runs show the dense
        // output's own error there (observed 2e-9 for RK4 at 1 ms)
        let phi_bound = if matches!(correction, Correction::None) { 1e-5 } else { 1e-8 };
        // Partitioning corrects the dependent velocities only, not M-orthogonally as the
        // projection does, so at RK4's 1 ms it moves the energy more (observed 2.4e-5 J against
        // 3.3e-7 J); it converges: 2.5e-7 J at 0.5 ms, checked below.
        let energy_bound = if matches!(correction, Correction::Partitioning { .. }) { 1e-4 } else { 1e-5 };
        for integrator in ["rk4", "dopri5"] {
            let (phi, de, e0) = run(integrator, 1e-3, correction);
            println!("{integrator:>14} {correction:?}: |Φ| ≤ {phi:.1e}, |ΔE| ≤ {de:.1e} J of {e0:.3} J");
            assert!(phi < phi_bound && de < energy_bound, "{integrator} {correction:?}: |Φ| {phi}, ΔE {de} J");
        }
        if matches!(correction, Correction::Partitioning { .. }) {
            let (_, coarse, _) = run("rk4", 1e-3, correction);
            let (_, fine, _) = run("rk4", 5e-4, correction);
            assert!(coarse > 16.0 * fine, "RK4 with partitioning: ΔE {coarse} J at 1 ms, {fine} J at 0.5 ms");
        }
        let (phi, coarse, e0) = run("generalized-α", 2e-3, correction);
        let (phi_fine, fine, _) = run("generalized-α", 1e-3, correction);
        println!("generalized-α {correction:?}: |Φ| ≤ {phi_fine:.1e}, |ΔE| ≤ {coarse:.1e} J (h = 2 ms), {fine:.1e} J (1 ms) of {e0:.3} J");
        assert!(phi.max(phi_fine) < phi_bound, "generalized-α {correction:?}: |Φ| {phi}");
        assert!(coarse < 0.01 * e0 && coarse > 3.0 * fine, "generalized-α {correction:?}: ΔE {coarse} J at 2 ms, {fine} J at 1 ms");
    }
}

/// Inverse dynamics of the driven crank at constant rate ω: about the hinge (axis −y, angle θ
/// from +x toward +z), gravity's moment is m g e cos θ, so the motor supplies τ = m g e cos θ
/// (no angular acceleration); the bearing pushes the crank with m g upward plus the centripetal
/// force m e ω² toward the axis. Reactions come out in N and N·m, by joint label.
#[test]
fn inverse_dynamics_with_reactions() {
    let m = DrivenCrank::default();
    let (mass, g, e, w) = (2.0, 9.81, m.e, m.w);
    let solver = KinematicSolver::new(KinematicOptions::default());
    let mut q = m.initial_positions();
    let mut checked = 0;
    solver
        .sweep(&m, &mut DrivenCrank::workspace(), &mut q, (0..40).map(|k| k as f64 * 0.05), |t, q, v, vd| {
            let mut lambda = [0.0; 6];
            InverseDynamics::default().solve(&m, &mut DrivenCrank::workspace(), q, v, vd, t, &mut lambda).expect("inverse dynamics");
            let mut d = [[0.0; 6]; 6];
            m.jacobian(q, t, &mut d);
            let theta = w * t;
            let motor = joint_reaction(&m, q, &d, &lambda, DrivenCrank::MOTOR).and_then(|r| r.on_j).expect("the motor drives the crank");
            let bearing = joint_reaction(&m, q, &d, &lambda, DrivenCrank::BEARING).and_then(|r| r.on_j).expect("the bearing holds it");
            // the motor's moment about the hinge axis −y, taken at the pin (the crank's point −e x′)
            let pin = DrivenCrank::CRANK.point([-e, 0.0, 0.0]).position(q) - DrivenCrank::CRANK.position(q);
            let drive = -motor.moment_about(pin.into())[1];
            let want = mass * g * e * theta.cos();
            // Inverse dynamics is one LU solve at a converged position: ~1e-12 relative.
            assert!((drive - want).abs() < 1e-9, "θ = {theta}: motor torque {drive} N·m, closed form {want}");
            // the bearing force: weight support and centripetal pull toward the axis
            let centre = DrivenCrank::CRANK.position(q);
            let toward_axis = -nalgebra::Vector3::new(centre.x, 0.0, centre.z).normalize();
            let want_force = nalgebra::Vector3::new(0.0, 0.0, mass * g) + toward_axis * mass * e * w * w;
            // the bearing and the motor together give the crank's net joint force
            let total = nalgebra::Vector3::from(bearing.force) + nalgebra::Vector3::from(motor.force);
            assert!((total - want_force).norm() < 1e-9, "θ = {theta}: joint force {total:?}, closed form {want_force:?}");
            checked += 1;
        })
        .unwrap();
    assert_eq!(checked, 40);
}

/// The hinged bar on a torsion spring k: with θ the hinge angle (from +x toward +z about −y),
/// equilibrium is k θ = −m g (l/2) cos θ, solved here by bisection; the static solver starts
/// from the unloaded bar. Tolerance 1e-9 rad from its force tolerance over k.
#[test]
fn statics_of_a_sprung_bar() {
    let m = SpringBar::default();
    let f = |th: f64| m.k * th + 2.0 * 9.81 * 0.5 * th.cos();
    let (mut lo, mut hi) = (-1.5, 0.0);
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
    let mut lambda = [0.0; 5];
    let mut ws = SpringBar::workspace();
    StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda).expect("equilibrium");
    // the bar's axis x′ in global: (cos θ, 0, sin θ) for a turn θ about −y
    let axis = SpringBar::BAR.rotation(&q).column(0).into_owned();
    let got = axis.z.atan2(axis.x);
    assert!((got - theta).abs() < 1e-9, "θ = {got}, equilibrium {theta}");
    let mut d = [[0.0; 6]; 5];
    m.jacobian(&q, 0.0, &mut d);
    let hinge = joint_reaction(&m, &q, &d, &lambda, SpringBar::HINGE).and_then(|r| r.on_j).expect("the hinge holds the bar");
    assert!((hinge.force[2] - 2.0 * 9.81).abs() < 1e-9 && hinge.force[0].abs() < 1e-9, "{hinge:?}");
}

include!("../mbd-bench/mechanisms/heavy_top_benchmark.rs");

/// ω′ at 2 s of the heavy top with `integrator` (its centre of mass starts at ω × (0, 1, 0)).
fn heavy_top_spin<I: Integrator<f64, HeavyTop, 7, 6, 3, 9, { HeavyTop::NEWTON_STORAGE }>>(integrator: &mut I) -> [f64; 3] {
    let m = HeavyTop::default();
    let mut end = [0.0; 6];
    Simulation::new(&m, integrator)
        .start(0.0, &m.initial_positions(), &m.initial_velocities())
        .times(&[2.0])
        .run(&mut HeavyTop::workspace(), |s| end = s.point.v)
        .expect("the top spins");
    [end[3], end[4], end[5]]
}

/// Generalized-α on the spinning top (issue 39, item 3): rotations are updated by the exact
/// exponential of the body-frame rotation vector (`integrate_on_group`), so at h = 1 ms the
/// error in ω′ after 2 s is 0.28 rad/s against DOP853 at rtol 1e-13 — it was 3.4 rad/s with
/// q + B(q)Δ renormalized, which turns by 2 atan(θ/2) instead of θ (0.15 rad a step here) —
/// and falls by 4× when h halves (second order). What remains is the method's phase error on
/// the transverse ω′, which turns in the body frame at about the spin rate (145 rad/s). The
/// iteration matrix carries the exponential's tangent operator, so Newton converges as fast as
/// on a slow body.
#[test]
fn generalized_alpha_turns_a_spinning_top_by_the_exponential() {
    let reference = heavy_top_spin(&mut Dop853::new(Dop853Options::default().with_rtol(1e-13).with_atol(1e-13)));
    let run = |h: f64, options: GeneralizedAlphaOptions<f64>| {
        let mut integrator = HeavyTop::generalized_alpha(options.with_step(h));
        let w = heavy_top_spin(&mut integrator);
        let error = (0..3).map(|i| (w[i] - reference[i]).abs()).fold(0.0, f64::max);
        (error, integrator.total_iterations as f64 / integrator.accepted as f64)
    };
    let error = |h: f64| run(h, GeneralizedAlphaOptions::default()).0;
    let (coarse, fine) = (error(1e-3), error(5e-4));
    eprintln!("heavy top: ω′ at 2 s {reference:?}; generalized-α error {coarse:.3e} rad/s at 1 ms, {fine:.3e} at 0.5 ms");
    // The tangent operator T(Δ) in the iteration matrix (each step turns the top by 0.15 rad,
    // T − I ≈ 0.075): Newton converges in 3 iterations a step, modified or full; with T = I it
    // took 6 in both (measured 2026-12-06, the same error to five digits).
    for reuse in [true, false] {
        let (e, iterations) = run(1e-3, GeneralizedAlphaOptions::default().with_reuse_factors(reuse));
        eprintln!("  reuse_factors {reuse}: {iterations:.3} Newton iterations a step, error {e:.4e}");
        assert!(iterations < 4.0, "{iterations} Newton iterations a step (reuse_factors {reuse})");
    }
    // measured 0.2825 and 0.0697 rad/s; today's 3.4 rad/s was the first-order rotation update
    assert!(coarse < 0.35, "ω′ off by {coarse} rad/s at h = 1 ms");
    // second order: 4× per halving (measured 4.05)
    assert!((3.0..5.5).contains(&(coarse / fine)), "{coarse} at 1 ms, {fine} at 0.5 ms");
}

/// BDF on the spinning top (issue 39, item 1): its positions q₊ = q̂ ⊕ c v₊ solve the BDF
/// relation of the Euler parameters exactly (ė = ½ e ⊗ (0, ω′) is linear in e), so the method
/// keeps its order through the quaternions: the Euler parameters after 2 s within 100 rtol of
/// DOP853's at rtol 1e-6 and 1e-8 (measured 5.4e-5 and 8.9e-7; ω′ 1.0e-4 and 1.7e-6 rad/s of
/// 150), falling with the tolerance.
#[test]
fn bdf_keeps_its_order_through_the_quaternions() {
    let run = |integrator: &mut dyn FnMut() -> ([f64; 7], [f64; 6])| integrator();
    fn top<I: Integrator<f64, HeavyTop, 7, 6, 3, 9, { HeavyTop::NEWTON_STORAGE }>>(integrator: &mut I) -> ([f64; 7], [f64; 6]) {
        let m = HeavyTop::default();
        let mut end = ([0.0; 7], [0.0; 6]);
        Simulation::new(&m, integrator)
            .start(0.0, &m.initial_positions(), &m.initial_velocities())
            .times(&[2.0])
            .run(&mut HeavyTop::workspace(), |s| end = (s.point.q, s.point.v))
            .expect("the top spins");
        end
    }
    let reference = run(&mut || top(&mut Dop853::new(Dop853Options::default().with_rtol(1e-13).with_atol(1e-13))));
    let error = |rtol: f64| {
        let (q, v) = top(&mut Bdf::new(BdfOptions::default().with_rtol(rtol).with_atol(rtol)));
        let eq = (0..7).map(|i| (q[i] - reference.0[i]).abs()).fold(0.0, f64::max);
        let ew = (3..6).map(|i| (v[i] - reference.1[i]).abs()).fold(0.0, f64::max);
        (eq, ew)
    };
    let ((loose, w_loose), (tight, w_tight)) = (error(1e-6), error(1e-8));
    eprintln!("heavy top, BDF: q error {loose:.2e} at rtol 1e-6, {tight:.2e} at 1e-8 (ω′ {w_loose:.2e}, {w_tight:.2e} rad/s)");
    assert!(loose < 100.0 * 1e-6 && tight < 100.0 * 1e-8, "{loose} at 1e-6, {tight} at 1e-8");
    assert!(tight < loose / 20.0, "{loose} at 1e-6, {tight} at 1e-8");
}

/// Radau5 on the spinning top (issue 39, item 1): its stages collocate the Euler parameters
/// themselves (ė = ½ e ⊗ (0, ω′), by a contraction), so it keeps order 5 through the
/// quaternions: on fixed steps (a tolerance so loose every step is accepted, the step held at
/// `max_step`) the error of q after 0.2 s falls by about 2⁵ = 32 as h halves (measured 9.2e-8,
/// 3.0e-9, 9.3e-11 at h = 2, 1, 0.5 ms: ratios 30 and 32; at 4 ms, ω h = 0.6, Newton's rate held
/// the steps near 2 ms).
#[test]
fn radau5_keeps_fifth_order_through_the_quaternions() {
    fn top<I: Integrator<f64, HeavyTop, 7, 6, 3, 9, { HeavyTop::NEWTON_STORAGE }>>(integrator: &mut I) -> [f64; 7] {
        let m = HeavyTop::default();
        let mut end = [0.0; 7];
        Simulation::new(&m, integrator)
            .start(0.0, &m.initial_positions(), &m.initial_velocities())
            .times(&[0.2])
            .options(SimulationOptions::default().with_correction(Correction::None))
            .run(&mut HeavyTop::workspace(), |s| end = s.point.q)
            .expect("the top spins");
        end
    }
    let reference = top(&mut Dop853::new(Dop853Options::default().with_rtol(1e-13).with_atol(1e-13)));
    let steps = [2e-3, 1e-3, 5e-4];
    let errors: Vec<f64> = steps
        .iter()
        .map(|&h| {
            let options = Radau5Options::default().with_rtol(1.0).with_atol(1.0).with_initial_step(h).with_max_step(h);
            // Newton to 1e-12 of the (loose) tolerance: at 1e-9 its error was a floor of 3e-9.
            let mut radau = Radau5::new(options.with_newton_tolerance(1e-12).with_max_iterations(30));
            let q = top(&mut radau);
            (0..7).map(|i| (q[i] - reference[i]).abs()).fold(0.0, f64::max)
        })
        .collect();
    eprintln!("heavy top, Radau5 on fixed steps {steps:?}: q errors {errors:?}");
    for pair in errors.windows(2) {
        assert!((20.0..50.0).contains(&(pair[0] / pair[1])), "{errors:?}");
    }
}

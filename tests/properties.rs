//! Property tests (issue 10, item 8): random four-bars — Grashof or not, any driver speed and
//! phase — and random offset slider-cranks — driven at the crank or at the slider — either
//! assemble and satisfy their constraints to tolerance along a kinematic sweep, or stop with the
//! typed error that says why, and only where the closed-form geometry says the linkage cannot go
//! on (a limit position: two circles, or a circle and the guide, cease to meet or meet at a
//! tangent).
use mbd::prelude::*;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

/// The seed of the cases: `PROPTEST_RNG_SEED` if set, else a fixed one.
fn seed() -> u64 {
    std::env::var("PROPTEST_RNG_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(20_261_123)
}

mechanism! {
    /// A four-bar of any proportions: ground pivots A = (0, 0) and D = (a, 0), crank AB (b),
    /// coupler BC (c), rocker DC (d), the crank driven at θ₀ + ω t.
    pub AnyFourBar {
        params { a: 0.4, b: 0.15, c: 0.35, d: 0.3, theta0: 1.0, omega: 1.0 }
        body crank   { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        body coupler { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        body rocker  { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-b / 2.0, 0.0];
        revolute crank[b / 2.0, 0.0] ~ coupler[-c / 2.0, 0.0];
        revolute coupler[c / 2.0, 0.0] ~ rocker[d / 2.0, 0.0];
        revolute rocker[-d / 2.0, 0.0] ~ ground[a, 0.0];
        drive crank.phi = theta0 + omega * t;
    }
}

/// The closed-form pose at crank angle θ on the branch with C to the left of B→D (`sign` +1)
/// or to the right (−1), and sin of the angle between coupler and rocker at C (0 at a limit
/// position, where the Jacobian is singular); `None` where the circles about B (radius c) and
/// D (radius d) do not meet.
fn pose(m: &AnyFourBar, theta: f64, sign: f64) -> Option<([f64; 9], f64)> {
    let (bx, by) = (m.b * theta.cos(), m.b * theta.sin());
    let (ex, ey) = (m.a - bx, -by);
    let e = ex.hypot(ey);
    // Distance from B along B→D to the foot of C, and C's offset from that line.
    let along = (m.c * m.c - m.d * m.d + e * e) / (2.0 * e);
    let offset2 = m.c * m.c - along * along;
    if offset2 < 0.0 || e == 0.0 {
        return None;
    }
    let offset = sign * offset2.sqrt();
    let (ux, uy) = (ex / e, ey / e);
    let (cx, cy) = (bx + along * ux - offset * uy, by + along * uy + offset * ux);
    let coupler = (cy - by).atan2(cx - bx);
    let rocker = (cy - 0.0).atan2(cx - m.a);
    let q = [bx / 2.0, by / 2.0, theta, (bx + cx) / 2.0, (by + cy) / 2.0, coupler, (cx + m.a) / 2.0, cy / 2.0, rocker];
    Some((q, (rocker - coupler).sin()))
}

fn constraint_norm(m: &AnyFourBar, q: &[f64; 9], t: f64) -> f64 {
    let mut phi = [0.0; 9];
    m.constraints(q, t, &mut phi);
    phi.iter().fold(0.0, |s, x| s.max(x.abs()))
}

/// Link lengths from 0.05 to 1 m (any Grashof class), a start angle, a speed of up to 3 rad/s
/// either way, and the assembly branch.
fn four_bars() -> impl Strategy<Value = (AnyFourBar, f64)> {
    (0.05..1.0f64, 0.05..1.0f64, 0.05..1.0f64, 0.05..1.0f64, -3.2..3.2f64, -3.0..3.0f64, prop::bool::ANY)
        .prop_map(|(a, b, c, d, theta0, omega, left)| (AnyFourBar { a, b, c, d, theta0, omega }, if left { 1.0 } else { -1.0 }))
}

proptest! {
    // A fixed seed: CI sees the same 256 cases every run (set PROPTEST_RNG_SEED, or edit it,
    // to explore others; five other seeds passed when this was written).
    #![proptest_config(ProptestConfig { cases: 256, rng_seed: RngSeed::Fixed(seed()), ..ProptestConfig::default() })]

    /// From the closed-form pose perturbed by up to 5 % of the shortest link and 0.02 rad, Newton assembles onto the
    /// same branch with ‖Φ‖∞ ≤ 1e-10 (the solver's tolerance) wherever the pose is well away
    /// from a limit position (|sin μ| ≥ 0.2: the Jacobian's condition is then bounded, and the
    /// perturbation is inside Newton's basin); near one it may stop, but only with a typed
    /// error. Where the circles do not meet, no pose exists and the solver says so — it never
    /// returns a q that violates the constraints, and never a NaN.
    #[test]
    fn random_four_bars_assemble_or_say_why((m, sign) in four_bars(), noise in prop::array::uniform9(-1.0..1.0f64)) {
        let solver = KinematicSolver::default();
        match pose(&m, m.theta0, sign) {
            Some((exact, sin_mu)) => {
                // Up to 5 % of the shortest link in position, 0.02 rad in angle.
                let shortest = m.a.min(m.b).min(m.c).min(m.d);
                let mut q = exact;
                for (i, x) in q.iter_mut().enumerate() {
                    *x += noise[i] * if i % 3 == 2 { 0.02 } else { 0.05 * shortest };
                }
                match solver.solve_position(&m, &mut AnyFourBar::workspace(), &mut q, 0.0) {
                    Ok(_) => {
                        prop_assert!(constraint_norm(&m, &q, 0.0) <= 1e-10);
                        if sin_mu.abs() >= 0.2 {
                            // The same branch: the solution is the closed form (to Newton's
                            // tolerance over the Jacobian's bounded inverse).
                            let angle_error = (0..3).map(|k| ((q[3 * k + 2] - exact[3 * k + 2] + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI).abs()).fold(0.0, f64::max);
                            prop_assert!(angle_error < 1e-6, "another branch: {q:?} vs {exact:?}");
                        }
                    }
                    Err(e) => {
                        prop_assert!(sin_mu.abs() < 0.2, "a regular pose (sin μ = {sin_mu}) failed: {e}");
                        prop_assert!(matches!(e, KinematicError::NotConverged { .. } | KinematicError::CannotAssemble { .. } | KinematicError::SingularJacobian { .. }), "{e:?}");
                        prop_assert!(q.iter().all(|x| x.is_finite()));
                    }
                }
            }
            None => {
                // A pose the geometry does not allow: from the `at:` zeros Newton cannot reach
                // Φ = 0, and says why (not converged, singular, or a step that overflowed).
                let mut q = m.initial_positions();
                let result = solver.solve_position(&m, &mut AnyFourBar::workspace(), &mut q, 0.0);
                prop_assert!(result.is_err(), "assembled an impossible four-bar: {q:?}");
            }
        }
    }

    /// A kinematic sweep of 1 s (every 10 ms) from an assembled regular pose: every point it
    /// delivers satisfies Φ to 1e-10; if it stops, the error is typed and the linkage is at or
    /// near a limit position there (|sin μ| < 0.2 at the last point reached or in the step to
    /// the failed one, or no pose at all): never an error where the geometry is regular.
    #[test]
    fn random_four_bar_sweeps_hold_or_stop_at_a_limit((m, sign) in four_bars()) {
        let Some((start, sin_mu)) = pose(&m, m.theta0, sign) else { return Ok(()) };
        prop_assume!(sin_mu.abs() >= 0.2);
        let solver = KinematicSolver::default();
        let mut q = start;
        let mut last_t = 0.0;
        let mut worst: f64 = 0.0;
        let result = solver.sweep(&m, &mut AnyFourBar::workspace(), &mut q, (0..=100).map(|k| k as f64 * 0.01), |t, q, _, _| {
            worst = worst.max(constraint_norm(&m, q, t));
            last_t = t;
        });
        prop_assert!(worst <= 1e-10, "‖Φ‖ = {worst:e}");
        if let Err(e) = result {
            prop_assert!(matches!(e, KinematicError::NotConverged { .. } | KinematicError::CannotAssemble { .. } | KinematicError::SingularJacobian { .. }), "{e:?}");
            // Near a limit between the last point reached and the next one (checked finely).
            let near_limit = (0..=20).any(|j| {
                let t = last_t + 0.01 * j as f64 / 20.0;
                match pose(&m, m.theta0 + m.omega * t, sign).or_else(|| pose(&m, m.theta0 + m.omega * t, -sign)) {
                    Some((_, s)) => s.abs() < 0.2,
                    None => true,
                }
            });
            prop_assert!(near_limit, "stopped at t = {last_t} s where the linkage is regular: {e}");
        }
    }
}

mechanism! {
    /// An offset slider-crank of any proportions: crank AB (r) about A = (0, 0), rod BC (l), the
    /// slider's pin C on the guide y = e; the crank driven at θ₀ + ω t.
    pub AnySliderCrank {
        params { r: 0.1, l: 0.3, e: 0.0, theta0: 1.0, omega: 1.0 }
        body crank  { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        body rod    { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        body slider { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational ground[0.0, e] along [1.0, 0.0] ~ slider[0.0, 0.0] along [1.0, 0.0];
        drive crank.phi = theta0 + omega * t;
    }
}

mechanism! {
    /// The same slider-crank driven at the slider, x = x0 + u t (a compressor run backwards: the
    /// dead centres, crank and rod in line, are its limit positions).
    pub SliderDriven {
        params { r: 0.1, l: 0.3, e: 0.0, x0: 0.3, u: 0.1 }
        body crank  { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        body rod    { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        body slider { mass: 1.0, inertia: 0.01, at: [0.0, 0.0, 0.0] }
        revolute ground[0.0, 0.0] ~ crank[-r / 2.0, 0.0];
        revolute crank[r / 2.0, 0.0] ~ rod[-l / 2.0, 0.0];
        revolute rod[l / 2.0, 0.0] ~ slider[0.0, 0.0];
        translational ground[0.0, e] along [1.0, 0.0] ~ slider[0.0, 0.0] along [1.0, 0.0];
        drive slider.x = x0 + u * t;
    }
}

/// The slider-crank's pose from crank pin B and slider pin C: q of crank, rod and slider.
fn slider_crank_q(b: (f64, f64), c: (f64, f64)) -> [f64; 9] {
    let (theta, beta) = (b.1.atan2(b.0), (c.1 - b.1).atan2(c.0 - b.0));
    [b.0 / 2.0, b.1 / 2.0, theta, (b.0 + c.0) / 2.0, (b.1 + c.1) / 2.0, beta, c.0, c.1, 0.0]
}

/// One random slider-crank with its driver: the crank's (θ₀ + ω t) or the slider's (x0 + u t).
#[derive(Debug)]
enum Driven {
    Crank(AnySliderCrank),
    Slider(SliderDriven),
}

impl Driven {
    /// The closed-form pose at time t on the branch `sign` and its distance from a limit
    /// position (0 there, where the Jacobian is singular), or `None` where no pose exists.
    /// Crank driven: C = (x, e), x = B_x + sign √(l² − (e − B_y)²); the measure is cos β, the
    /// rod's angle to the guide (0: the rod stands across it). Slider driven: B where the
    /// circles about A (r) and C (l) meet, sign picking the side of A→C; the measure is
    /// sin(β − θ) (0: crank and rod in line, a dead centre).
    fn pose(&self, t: f64, sign: f64) -> Option<([f64; 9], f64)> {
        match self {
            Driven::Crank(m) => {
                let theta = m.theta0 + m.omega * t;
                let b = (m.r * theta.cos(), m.r * theta.sin());
                let across = m.e - b.1;
                let along2 = m.l * m.l - across * across;
                if along2 < 0.0 {
                    return None;
                }
                let c = (b.0 + sign * along2.sqrt(), m.e);
                let mut q = slider_crank_q(b, c);
                q[2] = theta; // the driver's angle itself, not atan2's in (−π, π]
                Some((q, sign * along2.sqrt() / m.l))
            }
            Driven::Slider(m) => {
                let c = (m.x0 + m.u * t, m.e);
                let dist = c.0.hypot(c.1);
                let along = (m.r * m.r - m.l * m.l + dist * dist) / (2.0 * dist);
                let offset2 = m.r * m.r - along * along;
                if offset2 < 0.0 || dist == 0.0 {
                    return None;
                }
                let (ux, uy) = (c.0 / dist, c.1 / dist);
                let offset = sign * offset2.sqrt();
                let b = (along * ux - offset * uy, along * uy + offset * ux);
                let q = slider_crank_q(b, c);
                Some((q, (q[5] - q[2]).sin()))
            }
        }
    }
    fn constraint_norm(&self, q: &[f64; 9], t: f64) -> f64 {
        let mut phi = [0.0; 9];
        match self {
            Driven::Crank(m) => m.constraints(q, t, &mut phi),
            Driven::Slider(m) => m.constraints(q, t, &mut phi),
        }
        phi.iter().fold(0.0, |s, x| s.max(x.abs()))
    }
    fn solve(&self, q: &mut [f64; 9], t: f64) -> Result<(), KinematicError> {
        let solver = KinematicSolver::default();
        match self {
            Driven::Crank(m) => solver.solve_position(m, &mut AnySliderCrank::workspace(), q, t).map(|_| ()),
            Driven::Slider(m) => solver.solve_position(m, &mut SliderDriven::workspace(), q, t).map(|_| ()),
        }
    }
    /// A kinematic sweep over `times`, `each(t, q)` at every point reached.
    fn sweep(
        &self,
        q: &mut [f64; 9],
        times: impl IntoIterator<Item = f64>,
        mut each: impl FnMut(f64, &[f64; 9]),
    ) -> Result<(), KinematicError> {
        let solver = KinematicSolver::default();
        match self {
            Driven::Crank(m) => solver.sweep(m, &mut AnySliderCrank::workspace(), q, times, |t, q, _, _| each(t, q)),
            Driven::Slider(m) => solver.sweep(m, &mut SliderDriven::workspace(), q, times, |t, q, _, _| each(t, q)),
        }
    }
    fn shortest(&self) -> f64 {
        match self {
            Driven::Crank(m) => m.r.min(m.l),
            Driven::Slider(m) => m.r.min(m.l),
        }
    }
}

/// Crank and rod from 0.05 to 1 m, an offset of up to ±1 m (so that some cannot assemble or
/// cannot turn fully), either driver with a random phase and speed (up to 3 rad/s or 1 m/s
/// either way), and the branch.
fn slider_cranks() -> impl Strategy<Value = (Driven, f64)> {
    (0.05..1.0f64, 0.05..1.0f64, -1.0..1.0f64, -3.2..3.2f64, -3.0..3.0f64, prop::bool::ANY, prop::bool::ANY).prop_map(
        |(r, l, e, phase, speed, at_crank, left)| {
            let driven = if at_crank {
                Driven::Crank(AnySliderCrank { r, l, e, theta0: phase, omega: speed })
            } else {
                // the slider's start within reach of the crank-and-rod for most cases
                Driven::Slider(SliderDriven { r, l, e, x0: 0.5 * phase * (r + l) / 3.2 + 0.5 * (r + l), u: speed / 3.0 })
            };
            (driven, if left { 1.0 } else { -1.0 })
        },
    )
}

proptest! {
    // Fixed seed, as for the four-bars (five other seeds passed when this was written).
    #![proptest_config(ProptestConfig { cases: 256, rng_seed: RngSeed::Fixed(seed()), ..ProptestConfig::default() })]

    /// As for the four-bars: from the closed-form pose perturbed by up to 5 % of the shorter
    /// link and 0.02 rad, Newton assembles onto the same branch with ‖Φ‖∞ ≤ 1e-10 wherever the
    /// pose is regular (measure ≥ 0.2); near a limit it may stop, with a typed error; where no
    /// pose exists it always fails, and never returns a NaN.
    #[test]
    fn random_slider_cranks_assemble_or_say_why((m, sign) in slider_cranks(), noise in prop::array::uniform9(-1.0..1.0f64)) {
        match m.pose(0.0, sign) {
            Some((exact, measure)) => {
                let mut q = exact;
                for (i, x) in q.iter_mut().enumerate() {
                    *x += noise[i] * if i % 3 == 2 { 0.02 } else { 0.05 * m.shortest() };
                }
                match m.solve(&mut q, 0.0) {
                    Ok(()) => {
                        prop_assert!(m.constraint_norm(&q, 0.0) <= 1e-10);
                        if measure.abs() >= 0.2 {
                            let angle_error = (0..3).map(|k| ((q[3 * k + 2] - exact[3 * k + 2] + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI).abs()).fold(0.0, f64::max);
                            let position_error = (0..3).map(|k| (q[3 * k] - exact[3 * k]).abs().max((q[3 * k + 1] - exact[3 * k + 1]).abs())).fold(0.0, f64::max);
                            prop_assert!(angle_error < 1e-6 && position_error < 1e-6, "another branch: {q:?} vs {exact:?}");
                        }
                    }
                    Err(e) => {
                        prop_assert!(measure.abs() < 0.2, "a regular pose (measure {measure}) failed: {e}");
                        prop_assert!(matches!(e, KinematicError::NotConverged { .. } | KinematicError::CannotAssemble { .. } | KinematicError::SingularJacobian { .. }), "{e:?}");
                        prop_assert!(q.iter().all(|x| x.is_finite()));
                    }
                }
            }
            None => {
                let mut q = [0.0; 9];
                prop_assert!(m.solve(&mut q, 0.0).is_err(), "assembled an impossible slider-crank: {q:?}");
            }
        }
    }

    /// A 1 s sweep (every 10 ms) from a regular assembled pose holds Φ to 1e-10 at every point,
    /// and stops only with a typed error near a limit position (measure < 0.2 between the last
    /// point reached and the next, checked finely, or no pose).
    #[test]
    fn random_slider_crank_sweeps_hold_or_stop_at_a_limit((m, sign) in slider_cranks()) {
        let Some((start, measure)) = m.pose(0.0, sign) else { return Ok(()) };
        prop_assume!(measure.abs() >= 0.2);
        let mut q = start;
        let (mut last_t, mut worst) = (0.0, 0.0f64);
        let result = m.sweep(&mut q, (0..=100).map(|k| k as f64 * 0.01), |t, q| {
            worst = worst.max(m.constraint_norm(q, t));
            last_t = t;
        });
        prop_assert!(worst <= 1e-10, "‖Φ‖ = {worst:e}");
        if let Err(e) = result {
            prop_assert!(matches!(e, KinematicError::NotConverged { .. } | KinematicError::CannotAssemble { .. } | KinematicError::SingularJacobian { .. }), "{e:?}");
            let near_limit = (0..=20).any(|j| {
                let t = last_t + 0.01 * j as f64 / 20.0;
                match m.pose(t, sign).or_else(|| m.pose(t, -sign)) {
                    Some((_, s)) => s.abs() < 0.2,
                    None => true,
                }
            });
            prop_assert!(near_limit, "stopped at t = {last_t} s where the linkage is regular: {e}");
        }
    }
}

/// Near (not at) a dead centre the Jacobian is near-singular: the slider driven at 0.1 m/s,
/// crank and rod 1e-13 rad from collinear. Its smallest pivot is then about 1e-13 of its
/// column, below the default relative pivot tolerance 1e-12, so the velocity solve says
/// "singular" instead of returning the crank rate ẋ/(r sin θ) ≈ 1e12 rad/s that the
/// arithmetic gives (which it does with the tolerance set to 0 — the reason for the default).
#[test]
fn a_near_singular_jacobian_is_refused_at_the_default_pivot_tolerance() {
    let m = SliderDriven { r: 0.1, l: 0.3, e: 0.0, x0: 0.4, u: 0.1 };
    let theta: f64 = 1e-13;
    let b = (m.r * theta.cos(), m.r * theta.sin());
    let c = (b.0 + (m.l * m.l - b.1 * b.1).sqrt(), 0.0);
    let q = slider_crank_q(b, c);
    let mut v = [0.0; 9];
    let refused = KinematicSolver::default().solve_velocity(&m, &mut SliderDriven::workspace(), &q, 0.0, &mut v);
    assert!(matches!(refused, Err(KinematicError::SingularJacobian { .. })), "{refused:?} with v = {v:?}");
    let careless = KinematicSolver::new(KinematicOptions::default().with_pivot_tolerance(0.0));
    careless.solve_velocity(&m, &mut SliderDriven::workspace(), &q, 0.0, &mut v).expect("no tolerance, no refusal");
    assert!(SliderDriven::CRANK.omega(&v).abs() > 1e10, "the crank rate without the tolerance: {v:?}");
}

//! A heavy symmetric top — a gyroscope's disc rotor on a ball pivot (Wallrapp ch. 3; Goldstein,
//! *Classical Mechanics*, 5.7): forward dynamics with DOPRI5 against the closed forms of the
//! Lagrange top.
//!
//! The rotor (m = 0.5 kg, a thin disc of radius 40 mm: C = ½ m R² about its axis, A_cm = ¼ m R²
//! across it) sits l = 50 mm up its symmetry axis from a spherical joint at the ground origin,
//! its axis tilted θ0 = 0.5 rad from the vertical, spinning at ω3 = 50 rev/s. With A = A_cm + m l²
//! and C the moments of inertia about the pivot:
//!
//! 1. **Steady precession.** Started with the precession velocity, the tilt stays and the axis
//!    turns about the vertical at a rate Ω solving A cos θ0 Ω² − C ω3 Ω + m g l = 0. Both roots
//!    are run: the slow precession (≈ m g l / (C ω3)) and the fast one (≈ C ω3 / (A cos θ0)).
//! 2. **Nutation.** Released spinning with the axis at rest, the top falls, nods and precesses on
//!    average. The first integrals (energy, the momenta about the vertical and about the axis)
//!    give u̇² = b (u0 − u)(u − u1)(u3 − u) for u = cos θ, a = C ω3/A, b = 2 m g l/A, so exactly:
//!    the nutation period 4 K(k)/√(b (u3 − u1)), k² = (u0 − u1)/(u3 − u1) (complete elliptic
//!    integral by the arithmetic-geometric mean), the largest tilt acos u1, and the mean
//!    precession rate (a quadrature of φ̇ = a (u0 − u)/(1 − u²) over one period). The familiar
//!    fast-top values — nutation frequency C ω3 / A, amplitude b sin θ0 / a², mean precession
//!    m g l / (C ω3) — are their leading terms in ε = b/a² = 2 m g l A / (C ω3)² (here 0.045): the
//!    run shows both, and how far the approximation is off.
//!
//! Run: `cargo run --release --example gyroscope`
use mbd::prelude::*;

mechanism! {
    /// A heavy symmetric top on a ball pivot at the ground origin: its centre of mass l up its
    /// symmetry axis (body z), the axis tilted θ about the global x-axis.
    pub Gyroscope {
        spatial;
        params {
            mass_rotor: 0.5, a_cm: 2.0e-4, c_spin: 4.0e-4, l: 0.05, g: 9.81, theta: 0.5,
            wx: 0.0, wy: 0.0, wz: 0.0, vx: 0.0, vy: 0.0, vz: 0.0
        }
        gravity [0.0, 0.0, -g];
        body rotor {
            mass: mass_rotor, inertia: [a_cm, a_cm, c_spin],
            at: [0.0, -l * sin(theta), l * cos(theta)], axis_angle: [1.0, 0.0, 0.0, theta],
            velocity: [vx, vy, vz], omega: [wx, wy, wz]
        }
        spherical pivot: ground[0.0, 0.0, 0.0] ~ rotor[0.0, 0.0, -l];
    }
}

/// The spin ω3 (rad/s): 50 rev/s.
pub const SPIN: f64 = 2.0 * PI * 50.0;

/// What the runs measured, next to the closed forms.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// Slow steady precession: measured rate and closed-form root (rad/s).
    pub slow_rate: f64,
    pub slow_exact: f64,
    /// Fast steady precession: measured rate and closed-form root (rad/s).
    pub fast_rate: f64,
    pub fast_exact: f64,
    /// Largest drift of the tilt from θ0 in both steady runs (rad).
    pub tilt_drift: f64,
    /// Nutation period: measured, exact (elliptic) and fast-top 2πA/(C ω3) (s).
    pub nutation_period: f64,
    pub nutation_period_exact: f64,
    pub nutation_period_fast_top: f64,
    /// Nutation amplitude θ_max − θ0: measured, exact, fast-top b sin θ0/a² (rad).
    pub nutation_amplitude: f64,
    pub nutation_amplitude_exact: f64,
    pub nutation_amplitude_fast_top: f64,
    /// Mean precession rate while nutating: measured, exact, fast-top m g l/(C ω3) (rad/s).
    pub mean_precession: f64,
    pub mean_precession_exact: f64,
    pub mean_precession_fast_top: f64,
    /// Nutation periods the measurement spans.
    pub periods: usize,
}

/// The top's tilt θ from the vertical and the azimuth of its axis (rad): its symmetry axis is
/// the rotor's body z, the third column of A.
fn axis_angles(q: &[f64; Gyroscope::NQ]) -> (f64, f64) {
    let axis = Gyroscope::ROTOR.rotation(q).column(2).into_owned();
    (axis.z.clamp(-1.0, 1.0).acos(), axis.y.atan2(axis.x))
}

/// Adds 2π k to `angle` to bring it within π of `previous` (unwrapping an azimuth).
fn unwrap(angle: f64, previous: f64) -> f64 {
    angle - ((angle - previous) / (2.0 * PI)).round() * 2.0 * PI
}

/// The complete elliptic integral of the first kind K(k) = π / (2 AGM(1, √(1 − k²))).
fn elliptic_k(k2: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k2).sqrt());
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// The closed forms of the nutating top released at tilt θ0 with spin ω3 and no precession:
/// (period, θ_max − θ0, mean precession rate). With u = cos θ, u̇² = b (u0 − u)(u − u1)(u3 − u),
/// where u1 < u0 < 1 < u3 and u1, u3 are the roots of b (1 − u²) = a² (u0 − u).
fn nutation_exact(a: f64, b: f64, theta0: f64) -> (f64, f64, f64) {
    let u0 = theta0.cos();
    let root = (a.powi(4) - 4.0 * b * (a * a * u0 - b)).sqrt();
    let (u1, u3) = ((a * a - root) / (2.0 * b), (a * a + root) / (2.0 * b));
    let period = 4.0 * elliptic_k((u0 - u1) / (u3 - u1)) / (b * (u3 - u1)).sqrt();
    // Over the half period from u0 down to u1, with u = u0 − (u0 − u1) sin² s: dt = 2 ds /
    // √(b (u3 − u)) and dφ = a (u0 − u)/(1 − u²) dt. Both integrands are smooth and even about
    // s = 0 and s = π/2, so the midpoint rule converges geometrically: 400 points reach rounding.
    let n = 400;
    let (mut half_time, mut half_turn) = (0.0, 0.0);
    for i in 0..n {
        let s = (i as f64 + 0.5) / n as f64 * PI / 2.0;
        let u = u0 - (u0 - u1) * s.sin().powi(2);
        let dt = 2.0 / (b * (u3 - u)).sqrt() * (PI / 2.0 / n as f64);
        half_time += dt;
        half_turn += a * (u0 - u) / (1.0 - u * u) * dt;
    }
    debug_assert!((2.0 * half_time - period).abs() < 1e-9 * period, "quadrature and AGM agree on the period");
    (period, u1.acos() - theta0, half_turn / half_time)
}

fn dopri() -> Dopri5<f64, { Gyroscope::NQ }, { Gyroscope::NV }> {
    // rtol 1e-10: the rates below come out to ~1e-9 relative.
    Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12))
}

fn options() -> SimulationOptions<f64> {
    SimulationOptions::default().with_correction(Correction::projection())
}

/// Runs the top started in steady precession at rate Ω for `duration` s; returns the measured
/// precession rate and the largest drift of the tilt.
fn steady(base: &Gyroscope, omega: f64, duration: f64) -> Result<(f64, f64), SimulationError> {
    let theta = base.theta;
    // ω′ = Ω Aᵀẑ + ψ̇ ẑ′ with Aᵀẑ = (0, sin θ, cos θ) for a tilt about x; its axial component is
    // the spin ω3 = Ω cos θ + ψ̇. The centre r, as declared, moves with Ω ẑ × r (ψ̇ ẑ′ is along r).
    let r = Gyroscope::ROTOR.position(&base.initial_positions());
    let m = Gyroscope { wx: 0.0, wy: omega * theta.sin(), wz: SPIN, vx: -omega * r.y, vy: omega * r.x, vz: 0.0, ..*base };
    let (q0, v0) = (m.initial_positions(), m.initial_velocities());
    let steps = (duration / 0.002).round() as usize;
    let times: Vec<f64> = (1..=steps).map(|k| k as f64 * 0.002).collect();
    let (mut azimuth, mut previous, mut drift, mut end) = (0.0, axis_angles(&q0).1, 0.0f64, 0.0);
    let mut ws = Gyroscope::workspace();
    Simulation::new(&m, &mut dopri()).start(0.0, &q0, &v0).times(&times).options(options()).run(&mut ws, |s| {
        let (tilt, az) = axis_angles(&s.point.q);
        let az = unwrap(az, previous);
        azimuth += az - previous;
        previous = az;
        drift = drift.max((tilt - theta).abs());
        end = s.point.t;
    })?;
    Ok((azimuth / end, drift))
}

/// Runs the analyses; prints what they found when `print` is set.
pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let base = Gyroscope::default();
    let (m, l, g, theta) = (base.mass_rotor, base.l, base.g, base.theta);
    let (a, c) = (base.a_cm + m * l * l, base.c_spin);
    let mgl = m * g * l;

    // 1. Steady precession: the two roots of A cos θ Ω² − C ω3 Ω + m g l = 0.
    let disc = ((c * SPIN).powi(2) - 4.0 * a * theta.cos() * mgl).sqrt();
    let slow_exact = (c * SPIN - disc) / (2.0 * a * theta.cos());
    let fast_exact = (c * SPIN + disc) / (2.0 * a * theta.cos());
    let (slow_rate, slow_drift) = steady(&base, slow_exact, 2.0)?;
    let (fast_rate, fast_drift) = steady(&base, fast_exact, 0.5)?;

    // 2. Nutation: released spinning, axis at rest.
    let (wa, wb) = (c * SPIN / a, 2.0 * mgl / a);
    let (period_exact, amplitude_exact, precession_exact) = nutation_exact(wa, wb, theta);
    let released = Gyroscope { wz: SPIN, ..base };
    let (q0, v0) = (released.initial_positions(), released.initial_velocities());
    let dt = period_exact / 400.0;
    let times: Vec<f64> = (1..=(20.5 * 400.0) as usize).map(|k| k as f64 * dt).collect();
    let mut track = Vec::with_capacity(times.len() + 1);
    track.push((0.0, theta, axis_angles(&q0).1));
    let mut ws = Gyroscope::workspace();
    Simulation::new(&released, &mut dopri()).start(0.0, &q0, &v0).times(&times).options(options()).run(&mut ws, |s| {
        let (tilt, az) = axis_angles(&s.point.q);
        let previous = track.last().map_or(az, |p: &(f64, f64, f64)| p.2);
        track.push((s.point.t, tilt, unwrap(az, previous)));
    })?;
    // The largest tilt, refined by the parabola through the largest sample and its neighbours;
    // the period from the upward crossings of the mid-level (θ's steepest point, where linear
    // interpolation is best); the mean precession over the whole periods between them.
    let mut theta_max = f64::NEG_INFINITY;
    for w in track.windows(3) {
        let (y0, y1, y2) = (w[0].1, w[1].1, w[2].1);
        if y1 >= y0 && y1 > y2 {
            let curvature = y0 - 2.0 * y1 + y2;
            theta_max = theta_max.max(y1 - (y2 - y0).powi(2) / (8.0 * curvature));
        }
    }
    let level = 0.5 * (theta + theta_max);
    let mut crossings = Vec::new();
    for w in track.windows(2) {
        let ((t0, y0, p0), (t1, y1, p1)) = (w[0], w[1]);
        if y0 < level && y1 >= level {
            let f = (level - y0) / (y1 - y0);
            crossings.push((t0 + f * (t1 - t0), p0 + f * (p1 - p0)));
        }
    }
    let (Some(&first), Some(&last)) = (crossings.first(), crossings.last()) else {
        return Err("the top did not nutate: no crossing of its mid-level tilt".into());
    };
    let periods = crossings.len() - 1;
    let report = Report {
        slow_rate,
        slow_exact,
        fast_rate,
        fast_exact,
        tilt_drift: slow_drift.max(fast_drift),
        nutation_period: (last.0 - first.0) / periods as f64,
        nutation_period_exact: period_exact,
        nutation_period_fast_top: 2.0 * PI / wa,
        nutation_amplitude: theta_max - theta,
        nutation_amplitude_exact: amplitude_exact,
        nutation_amplitude_fast_top: wb * theta.sin() / (wa * wa),
        mean_precession: (last.1 - first.1) / (last.0 - first.0),
        mean_precession_exact: precession_exact,
        mean_precession_fast_top: mgl / (c * SPIN),
        periods,
    };
    if print {
        print_report(&report, a, c, wb / (wa * wa));
    }
    Ok(report)
}

fn print_report(r: &Report, a: f64, c: f64, epsilon: f64) {
    let rel = |x: f64, y: f64| (x - y) / y;
    println!("Heavy symmetric top: A = {a:.4e} kg·m² about the pivot, C = {c:.1e} kg·m², ω3 = {SPIN:.2} rad/s (50 rev/s)");
    println!("steady precession, A cos θ Ω² − C ω3 Ω + m g l = 0 (DOPRI5, rtol 1e-10):");
    println!(
        "  slow root: measured {:.10} rad/s, closed form {:.10} rad/s (relative {:+.1e})",
        r.slow_rate,
        r.slow_exact,
        rel(r.slow_rate, r.slow_exact)
    );
    println!(
        "  fast root: measured {:.10} rad/s, closed form {:.10} rad/s (relative {:+.1e})",
        r.fast_rate,
        r.fast_exact,
        rel(r.fast_rate, r.fast_exact)
    );
    println!("  tilt drift {:.1e} rad", r.tilt_drift);
    println!("nutation, released with the axis at rest ({} periods measured; fast-top parameter ε = b/a² = {epsilon:.4}):", r.periods);
    println!("{:>26} {:>14} {:>14} {:>12} {:>14} {:>12}", "", "measured", "exact", "meas.−exact", "fast top", "fast-top error");
    let rows = [
        ("period (s)", r.nutation_period, r.nutation_period_exact, r.nutation_period_fast_top),
        ("amplitude θmax−θ0 (rad)", r.nutation_amplitude, r.nutation_amplitude_exact, r.nutation_amplitude_fast_top),
        ("mean precession (rad/s)", r.mean_precession, r.mean_precession_exact, r.mean_precession_fast_top),
    ];
    for (name, measured, exact, approx) in rows {
        println!(
            "{name:>26} {measured:>14.9} {exact:>14.9} {:>12.1e} {approx:>14.9} {:>11.2}%",
            measured - exact,
            100.0 * rel(approx, exact)
        );
    }
}

/// The top of `run`'s second part, released spinning with its axis at rest, nodding and
/// precessing through about one turn, for the showcase's pictures: 201 frames, 16 ms apart.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let released = Gyroscope { wz: SPIN, ..Gyroscope::default() };
    let (q0, v0) = (released.initial_positions(), released.initial_velocities());
    let times: Vec<f64> = (0..=200).map(|k| k as f64 * 0.016).collect();
    let mut animation = mbd::Animation::new::<Gyroscope>(&released.params()).title("Heavy symmetric top released at 50 rev/s");
    let mut ws = Gyroscope::workspace();
    Simulation::new(&released, &mut dopri())
        .start(0.0, &q0, &v0)
        .times(&times)
        .options(options())
        .run(&mut ws, |s| animation.frame(s.point.t, &s.point.q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("gyroscope: {e}");
        std::process::exit(1);
    }
}

//! Nikravesh's project 15.8, the swing, posed as a playground designer or a physics teacher asks
//! it: how fast does a child pump a swing up by standing and squatting, how much energy does the
//! child put in per cycle and with what leg force and power, and what load reaches the crossbar?
//!
//! The model (planar, SI units; every number's source below):
//!
//! - `swing`: both chains and the seat as one rigid body pinned to the crossbar (`crossbar`).
//! - `child`: the child's centre of mass, sliding along the chains (`legs`) and turning with
//!   them. Standing up and squatting on the seat moves it towards and away from the crossbar:
//!   its distance is driven, d(t) = d_mid + d_amp sin 2ωt (`posture`), at twice the swing's
//!   small-amplitude frequency ω, from rest at θ₀. The driver's reaction is the child's leg
//!   force; its work (tracked) is the energy the child puts in.
//!
//! Forward dynamics: DOPRI5 with projection, work tracking on.
//!
//! **The check** (a small-amplitude model by hand, independent of the simulation): with
//! I(t) = J_s + m_s l_s² + J_c + m d² the inertia about the crossbar (J_s, J_c about the swing
//! body's and the child's centres of mass) and K(t) = (m_s l_s + m d) g its gravity stiffness,
//! d/dt(I θ̇) + K θ = 0. With I = I₀(1 + α sin 2ωt), K = K₀(1 + β sin 2ωt), ω² = K₀/I₀,
//! averaging over a period (θ = a cos(ωt + φ)) gives ȧ/a = (ω/4)(α + β) cos 2φ: the swing
//! released from rest (φ = 0) grows fastest, as e^(γt), γ = (ω/4)(α + β),
//! α = 2 m d_mid d_amp / I₀, β = m g d_amp / K₀ (for a point mass on a massless rope,
//! γ = ¾ ε ω with ε = d_amp/d_mid). It holds to first order in d_amp/d_mid and in the
//! amplitude: the check runs at 0.02 rad with a tenth of the child's stroke. A second check is an energy balance: over each period, the driver's work
//! equals the change of T + V written by hand from θ, θ̇, d and ḋ.
//!
//! What the DSL could not say: the posture as a law of the swing's own motion (stand while
//! moving fast past the bottom, squat at the turning points: a velocity-dependent constraint,
//! which the DSL lacks). The child here pumps by the clock at the small-amplitude frequency, so
//! as the amplitude grows and the swing's period lengthens, the pumping falls out of phase.
//!
//! Run: `cargo run --release --example swing`
use mbd::prelude::*;

mechanism! {
    /// A playground swing pumped by a child standing up and squatting (Nikravesh's project
    /// 15.8). Lengths from the crossbar; the swing body's frame at its centre of mass.
    pub Swing {
        // d_mid, d_amp: the child's centre of mass 1.475 ± 0.175 m below the crossbar;
        // omega: the pumping's half frequency, set by `start` to the swing's own; theta0: the
        // release angle (rad).
        params { d_mid: 1.475, d_amp: 0.175, omega: 2.5, theta0: 0.1 }
        gravity [0.0, -9.81];
        // Two 2.0 m chains of 6 mm short-link chain (3.2 kg) and a 2.5 kg seat: centre of mass
        // 1.4386 m below the crossbar, J = 2.470 kg·m² about that centre of mass (chains as
        // rods, seat as a point at 2.0 m).
        body swing { mass: 5.7, inertia: 2.470, at: [1.4386 * sin(theta0), -1.4386 * cos(theta0), theta0] }
        // An 8-year-old: 25 kg, J = 2.4 kg·m² about the centre of mass (radius of gyration
        // 0.31 m).
        body child { mass: 25.0, inertia: 2.4, at: [d_mid * sin(theta0), -d_mid * cos(theta0), theta0] }
        point swing.hook = [0.0, 1.4386];
        revolute crossbar: ground[0.0, 0.0] ~ swing.hook;
        translational legs: swing[0.0, 0.0] along [0.0, 1.0] ~ child[0.0, 0.0] along [0.0, 1.0];
        // The legs push between the seat and the child, along the chains: measured from the
        // hook, where the chains hang from the crossbar.
        drive posture: distance(swing.hook, child[0.0, 0.0]) = d_mid + d_amp * sin(2.0 * omega * t);
    }
}

/// Where the numbers come from (assumptions are marked so).
pub const SOURCES: [(&str, &str); 6] = [
    ("chains 2.0 m, 2 × 1.6 kg", "assumption: a common playground swing; 6 mm short-link chain weighs about 0.8 kg/m (chain makers' tables for DIN 766 chain)"),
    ("seat 2.5 kg at the chains' end", "assumption: a flat rubber seat"),
    ("child 25 kg, 1.28 m tall", "CDC clinical growth charts (2000): 50th percentile of an 8-year-old"),
    ("child's centre of mass 0.70 m above the seat standing, 0.35 m squatting", "standing: 55 % of stature (Winter, Biomechanics and Motor Control of Human Movement, 4th ed., 2009, ch. 4); squatting: assumption, half of it"),
    ("child's J = 2.4 kg·m² about the centre of mass", "assumption: an adult's radius of gyration in the sagittal plane, 0.24 of stature, scaled to 1.28 m"),
    ("pumping at twice the swing's frequency, from rest at 0.1 rad", "assumption: a child who has been given a small push and pumps by a steady rhythm"),
];

/// What the runs measured. Angles in rad, energies in J, forces in N, power in W.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone)]
pub struct Report {
    /// The swing's small-amplitude natural frequency √(K₀/I₀) (rad/s), and its period (s).
    pub omega: f64,
    pub period: f64,
    /// The check run (0.02 rad, a tenth of the stroke): the amplitude's growth rate γ (1/s)
    /// fitted over periods 2 to 8, and the closed form (ω/4)(α + β).
    pub growth_rate: f64,
    pub growth_rate_closed_form: f64,
    /// The design run: the amplitude (largest |θ|) in each period.
    pub amplitudes: Vec<f64>,
    /// The energy the child puts in over each period: the driver's work (J).
    pub energy_per_cycle: Vec<f64>,
    /// Largest |driver work − Δ(T + V) by hand| over a period, in both runs (J).
    pub balance_error: f64,
    /// The periods, from the start, in which the child puts energy in, and its mean power over
    /// them (W); after them the clock-driven pumping is out of phase and takes energy out.
    pub pumping_periods: usize,
    pub pumping_power: f64,
    /// The child's largest leg force (N).
    pub peak_leg_force: f64,
    /// The largest force on the crossbar (N); the swing and child's weight W (N); a designer's
    /// estimate by hand for the bottom of the largest swing a, with the child at d_mid,
    /// W (1 + 2 κ (1 − cos a)), κ = (Σ m r)² / (I₀ Σ m) (W (3 − 2 cos a) for a point mass); and
    /// the size of the two largest terms it leaves out (N): the child's radial inertia, up to
    /// m 4ω² d_amp, and its offset from d_mid at the bottom, up to m d_amp θ̇²_max. (It also
    /// leaves out the energy the child puts in or takes out over the last half-swing.)
    pub peak_crossbar_force: f64,
    pub weight: f64,
    pub crossbar_estimate: f64,
    pub omitted: f64,
    /// The least pull of the crossbar along the chains over the design run (N): where it
    /// would fall below 0, real chains would go slack.
    pub least_chain_tension: f64,
}

/// The model's inertia about the crossbar and its gravity stiffness at the child's distance d:
/// I(d) = J_s + m_s l_s² + J_c + m d² (kg·m²), K(d) = (m_s l_s + m d) g (N·m).
fn inertia_and_stiffness(d: f64) -> (f64, f64) {
    let (m_s, l_s, j_s, m_c, j_c, g) = (5.7, 1.4386, 2.470, 25.0, 2.4, 9.81);
    (j_s + m_s * l_s * l_s + j_c + m_c * d * d, (m_s * l_s + m_c * d) * g)
}

/// The swing angle θ (rad, from hanging straight down), its rate, the child's distance d from
/// the crossbar and its rate, from the coordinates.
fn state(q: &[f64; Swing::NQ], v: &[f64; Swing::NV]) -> (f64, f64, f64, f64) {
    let (r, u) = (Swing::CHILD.position(q).coords, Swing::CHILD.velocity(v));
    let d = r.norm();
    (Swing::SWING.phi(q), Swing::SWING.omega(v), d, r.dot(&u) / d)
}

/// T + V by hand (J): the swing turning about the crossbar, the child turning with it and
/// sliding along it.
fn energy(theta: f64, theta_dot: f64, d: f64, d_dot: f64) -> f64 {
    let (i, k) = inertia_and_stiffness(d);
    0.5 * i * theta_dot * theta_dot + 0.5 * 25.0 * d_dot * d_dot - k * theta.cos()
}

/// A swing assembled at rest, its coordinates and velocities.
struct Start {
    m: Swing,
    q: [f64; Swing::NQ],
    v: [f64; Swing::NV],
}

/// The swing at rest at `theta0`, pumped at its small-amplitude frequency with the stroke
/// d_amp × `stroke`, assembled.
fn start(theta0: f64, stroke: f64) -> Result<Start, Box<dyn std::error::Error>> {
    let mut m = Swing { theta0, ..Default::default() };
    m.d_amp *= stroke;
    let (i0, k0) = inertia_and_stiffness(m.d_mid);
    m.omega = (k0 / i0).sqrt();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut Swing::workspace(), &mut q, 0.0)?;
    // At rest; the child's radial velocity is the driver's.
    let mut v = [0.0; Swing::NV];
    mbd::project(&m, 0.0, &mut q, &mut v, &DynamicsOptions::default(), 1e-12, 10)?;
    Ok(Start { m, q, v })
}

/// One run over `periods` periods: per period the largest |θ|, the driver's work and the
/// largest |work − Δ(T + V)|; the peak leg and crossbar forces; and the samples (t, θ, d) when
/// `trace`.
struct Run {
    amplitudes: Vec<f64>,
    work: Vec<f64>,
    balance_error: f64,
    peak_leg_force: f64,
    peak_crossbar_force: f64,
    least_chain_tension: f64,
    trace: Vec<(f64, f64, f64)>,
}

fn simulate(m: &Swing, q: &[f64; Swing::NQ], v: &[f64; Swing::NV], periods: usize, trace: bool) -> Result<Run, Box<dyn std::error::Error>> {
    let period = 2.0 * PI / m.omega;
    let per_period = 200;
    let times: Vec<f64> = (0..=periods * per_period).map(|k| k as f64 * period / per_period as f64).collect();
    let options = SimulationOptions::default().with_correction(Correction::projection()).with_track_work(true);
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    let mut run = Run {
        amplitudes: vec![0.0; periods],
        work: vec![0.0; periods],
        balance_error: 0.0,
        peak_leg_force: 0.0,
        peak_crossbar_force: 0.0,
        least_chain_tension: f64::INFINITY,
        trace: Vec::new(),
    };
    let posture_row = Swing::JOINTS[Swing::POSTURE].row_range().start;
    // T + V and the driver's work at the last period's start.
    let mut last: Option<(f64, f64)> = None;
    let mut d = [[0.0; Swing::NV]; Swing::NC];
    Simulation::new(m, &mut dopri).start(0.0, q, v).times(&times).options(options).run(&mut Swing::workspace(), |s| {
        let (q, v, t) = (&s.point.q, &s.point.v, s.point.t);
        let (theta, theta_dot, dist, dist_dot) = state(q, v);
        let k = ((t / period) as usize).min(periods - 1);
        run.amplitudes[k] = run.amplitudes[k].max(theta.abs());
        let e = energy(theta, theta_dot, dist, dist_dot);
        let w = s.energy.constraint_work;
        let sample = (s.point.t / period * per_period as f64).round() as usize;
        if sample.is_multiple_of(per_period) {
            if let Some((e0, w0)) = last {
                run.work[sample / per_period - 1] = w - w0;
                run.balance_error = run.balance_error.max(((w - w0) - (e - e0)).abs());
            }
            last = Some((e, w));
        }
        run.peak_leg_force = run.peak_leg_force.max(s.point.lambda[posture_row].abs());
        m.jacobian(q, t, &mut d);
        if let Some(f) = joint_reaction(m, q, &d, &s.point.lambda, Swing::CROSSBAR).and_then(|j| j.on_j) {
            run.peak_crossbar_force = run.peak_crossbar_force.max(f.force[0].hypot(f.force[1]));
            // The crossbar pulls the swing up along the chains, towards the hook.
            run.least_chain_tension = run.least_chain_tension.min(-f.force[0] * theta.sin() + f.force[1] * theta.cos());
        }
        if trace {
            run.trace.push((t, theta, dist));
        }
    })?;
    Ok(run)
}

/// The slope of ln a_k against time over periods `first..` of `amplitudes` (least squares).
fn growth_rate(amplitudes: &[f64], first: usize, period: f64) -> f64 {
    let points: Vec<(f64, f64)> = amplitudes.iter().enumerate().skip(first).map(|(k, a)| (k as f64 * period, a.ln())).collect();
    let n = points.len() as f64;
    let (sx, sy) = points.iter().fold((0.0, 0.0), |(sx, sy), (x, y)| (sx + x, sy + y));
    let (mx, my) = (sx / n, sy / n);
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + (x - mx) * (y - my), b + (x - mx) * (x - mx)));
    sxy / sxx
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    // The check: small amplitude, a tenth of the stroke, over 8 periods.
    let Start { m, q, v } = start(0.02, 0.1)?;
    let check = simulate(&m, &q, &v, 8, false)?;
    let period = 2.0 * PI / m.omega;
    let growth = growth_rate(&check.amplitudes, 1, period);
    let (i0, k0) = inertia_and_stiffness(m.d_mid);
    let (alpha, beta) = (2.0 * 25.0 * m.d_mid * m.d_amp / i0, 25.0 * 9.81 * m.d_amp / k0);
    let closed_form = m.omega / 4.0 * (alpha + beta);

    // The design run: the child's whole stroke from a push to 0.1 rad, 10 periods.
    let Start { m, q, v } = start(0.1, 1.0)?;
    let periods = 10;
    let design = simulate(&m, &q, &v, periods, print)?;
    let pumping_periods = design.work.iter().take_while(|&&w| w > 0.0).count();
    let weight = (5.7 + 25.0) * 9.81;
    let (i0, k0) = inertia_and_stiffness(m.d_mid);
    let kappa = (k0 / 9.81).powi(2) / (i0 * (5.7 + 25.0));
    let largest = design.amplitudes.iter().fold(0.0f64, |a, &b| a.max(b));
    let r = Report {
        omega: m.omega,
        period,
        growth_rate: growth,
        growth_rate_closed_form: closed_form,
        amplitudes: design.amplitudes.clone(),
        energy_per_cycle: design.work.clone(),
        balance_error: check.balance_error.max(design.balance_error),
        pumping_periods,
        pumping_power: design.work[..pumping_periods].iter().sum::<f64>() / (pumping_periods as f64 * period),
        peak_leg_force: design.peak_leg_force,
        peak_crossbar_force: design.peak_crossbar_force,
        weight,
        crossbar_estimate: weight * (1.0 + 2.0 * kappa * (1.0 - largest.cos())),
        omitted: 25.0 * m.d_amp * (4.0 * m.omega * m.omega + 2.0 * k0 * (1.0 - largest.cos()) / i0),
        least_chain_tension: design.least_chain_tension,
    };
    if print {
        println!("Swing pumped by a child (Nikravesh's project 15.8): ω = {:.4} rad/s, period {:.3} s", r.omega, r.period);
        println!(
            "growth of a small swing (0.02 rad, a tenth of the stroke): γ = {:.5} 1/s; closed form (ω/4)(α + β) = {:.5} 1/s",
            r.growth_rate, r.growth_rate_closed_form
        );
        println!("{:>7} {:>16} {:>20}", "period", "amplitude (deg)", "energy put in (J)");
        for (k, (a, w)) in r.amplitudes.iter().zip(&r.energy_per_cycle).enumerate() {
            println!("{:>7} {:>16.2} {:>20.2}", k + 1, a.to_degrees(), w);
        }
        println!(
            "the child pumps the swing up for {} periods at {:.1} W on average, then its steady rhythm falls out of phase with the longer swings",
            r.pumping_periods, r.pumping_power
        );
        println!("child's peak leg force {:.0} N ({:.2} × its weight)", r.peak_leg_force, r.peak_leg_force / (25.0 * 9.81));
        println!(
            "crossbar load up to {:.0} N ({:.2} × the swing and child's weight); a designer's estimate by hand {:.0} N, leaving out terms of the child's radial motion up to {:.0} N",
            r.peak_crossbar_force,
            r.peak_crossbar_force / r.weight,
            r.crossbar_estimate,
            r.omitted
        );
        println!("the chains stay taut: the crossbar pulls them with at least {:.1} N", r.least_chain_tension);
        println!("energy balance per period (driver's work against Δ(T + V) by hand): within {:.1e} J", r.balance_error);
        for (what, source) in SOURCES {
            println!("  {what}: {source}");
        }
        let dir = std::path::Path::new("target/showcase");
        std::fs::create_dir_all(dir)?;
        mbd::Plot::new("Swing pumped by a child: swing angle and the child's distance from the crossbar")
            .labels("t (s)", "θ (deg), d (cm − 150)")
            .series("swing angle θ (deg)", design.trace.iter().map(|&(t, theta, _)| (t, theta.to_degrees())))
            .series("child's distance d (cm − 150)", design.trace.iter().map(|&(t, _, d)| (t, 100.0 * d - 150.0)))
            .write_svg(dir.join("swing_angle.svg"))?;
        println!("plot → target/showcase/swing_angle.svg");
    }
    Ok(r)
}

/// The design run, for the showcase's animation: 16 frames per period over 10 periods.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let Start { m, q, v } = start(0.1, 1.0)?;
    let period = 2.0 * PI / m.omega;
    let times: Vec<f64> = (0..=10 * 16).map(|k| k as f64 * period / 16.0).collect();
    let options = SimulationOptions::default().with_correction(Correction::projection());
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    let mut animation = mbd::Animation::new::<Swing>(&m.params()).title("Swing pumped by a child standing up and squatting");
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &v)
        .times(&times)
        .options(options)
        .run(&mut Swing::workspace(), |s| animation.frame(s.point.t, &s.point.q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("swing: {e}");
        std::process::exit(1);
    }
}

//! Variable-length pendulum dynamics (Nikravesh, *Planar Multibody Dynamics*): the rod of
//! `variable_pendulum.rs` slides through the collar pinned to ground, but now only its length is
//! driven, L(t) = L0 + ΔL cos 2ωt, and the swing is free. Driving the length at twice the
//! natural frequency ω of the swing, shortest at the bottom and longest at the turning points,
//! pumps the swing up (parametric resonance — a child on a swing standing up and squatting).
//!
//! Forward dynamics: DOPRI5 with projection, work tracking on. The length driver's reaction λ
//! is the force that pulls the rod in (N); its work W_c = ∫ λᵀ Φ_q q̇ dt is the energy pumped in,
//! so T + V − W_c stays constant.
//!
//! Checked against the reduced model, written by hand from Lagrange's equations with θ the
//! swing angle, J = J_collar + J_rod, m the rod's mass at distance L from the pivot:
//!
//!   d/dt [(J + m L²) θ̇] = −m g L sin θ,  E = ½ (J + m L²) θ̇² + ½ m L̇² − m g L cos θ,
//!
//! integrated here with RK4 at a step 200 times smaller than the output interval: the swing
//! angle must match, and the driver's work must equal the reduced model's change of E.
//!
//! Run: `cargo run --release --example pumped_pendulum`
use mbd::prelude::*;

mechanism! {
    /// Pendulum whose length L(t) = L0 + ΔL cos 2ωt is driven; the swing is free.
    pub PumpedPendulum {
        params { l0: 1.0, dl: 0.05, omega: 3.0 }
        gravity [0.0, -9.81];
        body collar { mass: 0.2, inertia: 1.0e-3, at: [0.0, 0.0, -1.3708] }
        body rod    { mass: 1.0, inertia: 0.05, at: [0.2086, -1.0291, -1.3708] }
        revolute pivot: ground[0.0, 0.0] ~ collar[0.0, 0.0];
        translational sleeve: collar[0.0, 0.0] along [1.0, 0.0] ~ rod[0.0, 0.0] along [1.0, 0.0];
        drive length: distance(ground[0.0, 0.0], rod[0.0, 0.0]) = l0 + dl * cos(2.0 * omega * t);
    }
}

/// What the run measured.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// The swing's small-amplitude natural frequency √(m g L0 / (J + m L0²)) (rad/s).
    pub omega: f64,
    /// Swing amplitude (rad) over the first and over the last period.
    pub amplitude_start: f64,
    pub amplitude_end: f64,
    /// max |θ_mbd − θ_reduced| over the run (rad).
    pub angle_error: f64,
    /// Work of the length driver W_c (J) at the end, and the reduced model's E(end) − E(0).
    pub driver_work: f64,
    pub energy_gain_reduced: f64,
    /// max |T + V − W_c − (T + V)(0)| over the run (J).
    pub balance_drift: f64,
    /// Largest pull of the length driver on the rod (N).
    pub peak_pull: f64,
    /// DOPRI5 steps taken.
    pub steps: u64,
}

/// Swing angle θ (from hanging straight down) of the rod's coordinates.
fn swing(q: &[f64; PumpedPendulum::NQ]) -> f64 {
    PumpedPendulum::ROD.phi(q) + PI / 2.0
}

/// The reduced model's state (θ, θ̇) integrated by RK4 from `t` over `h`.
fn reduced_step(p: &PumpedPendulum, inertia: f64, mass: f64, g: f64, t: f64, h: f64, y: [f64; 2]) -> [f64; 2] {
    let f = |t: f64, y: [f64; 2]| {
        let l = p.l0 + p.dl * (2.0 * p.omega * t).cos();
        let ld = -2.0 * p.omega * p.dl * (2.0 * p.omega * t).sin();
        let j = inertia + mass * l * l;
        [y[1], -(mass * g * l * y[0].sin() + 2.0 * mass * l * ld * y[1]) / j]
    };
    let add = |y: [f64; 2], k: [f64; 2], s: f64| [y[0] + s * k[0], y[1] + s * k[1]];
    let k1 = f(t, y);
    let k2 = f(t + h / 2.0, add(y, k1, h / 2.0));
    let k3 = f(t + h / 2.0, add(y, k2, h / 2.0));
    let k4 = f(t + h, add(y, k3, h));
    [y[0] + h / 6.0 * (k1[0] + 2.0 * (k2[0] + k3[0]) + k4[0]), y[1] + h / 6.0 * (k1[1] + 2.0 * (k2[1] + k3[1]) + k4[1])]
}

/// The reduced model's energy at (t, θ, θ̇).
fn reduced_energy(p: &PumpedPendulum, inertia: f64, mass: f64, g: f64, t: f64, y: [f64; 2]) -> f64 {
    let l = p.l0 + p.dl * (2.0 * p.omega * t).cos();
    let ld = -2.0 * p.omega * p.dl * (2.0 * p.omega * t).sin();
    0.5 * (inertia + mass * l * l) * y[1] * y[1] + 0.5 * mass * ld * ld - mass * g * l * y[0].cos()
}

/// The swing pumped at twice its natural frequency, assembled at rest.
struct Start {
    m: PumpedPendulum,
    q: [f64; PumpedPendulum::NQ],
    v: [f64; PumpedPendulum::NV],
    /// The collar's and rod's J (kg·m²) and the rod's mass (kg), which set the frequency.
    inertia: f64,
    rod_mass: f64,
}

fn start() -> Result<Start, Box<dyn std::error::Error>> {
    let mut m = PumpedPendulum::default();
    // M is constant and diagonal: (m, m, J) per body.
    let mut mass = [[0.0; PumpedPendulum::NV]; PumpedPendulum::NV];
    m.add_mass_matrix(&m.initial_positions(), 1.0, &mut mass);
    let (inertia, rod_mass) = (mass[2][2] + mass[5][5], mass[3][3]);
    // Pump at twice the swing's natural frequency.
    m.omega = (rod_mass * 9.81 * m.l0 / (inertia + rod_mass * m.l0 * m.l0)).sqrt();
    let mut q = m.initial_positions();
    KinematicSolver::default().assemble(&m, &mut PumpedPendulum::workspace(), &mut q, 0.0)?;
    // At rest in the swing; the rod's radial velocity is the driver's (L̇(0) = 0 here).
    let mut v = [0.0; PumpedPendulum::NV];
    mbd::project(&m, 0.0, &mut q, &mut v, &DynamicsOptions::default(), 1e-12, 10)?;
    Ok(Start { m, q, v, inertia, rod_mass })
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let Start { m, q, v, inertia, rod_mass } = start()?;
    let g = 9.81;
    let mut ws = PumpedPendulum::workspace();

    let period = 2.0 * PI / m.omega;
    let cycles = 12.0;
    let per_period = 100;
    let n = (cycles * per_period as f64) as usize;
    let times: Vec<f64> = (0..=n).map(|k| k as f64 * period / per_period as f64).collect();
    let options = SimulationOptions::default().with_correction(Correction::projection()).with_track_work(true);
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));

    // The reduced model, stepped along with the outputs (200 RK4 steps per output interval:
    // its error, ~(ωh)⁴ per unit time, is below 1e-12 rad).
    let substeps = 200;
    let mut y = [swing(&q), 0.0];
    let e0 = reduced_energy(&m, inertia, rod_mass, g, 0.0, y);
    let mut t_reduced = 0.0;
    let mut r = Report {
        omega: m.omega,
        amplitude_start: 0.0,
        amplitude_end: 0.0,
        angle_error: 0.0,
        driver_work: 0.0,
        energy_gain_reduced: 0.0,
        balance_drift: 0.0,
        peak_pull: 0.0,
        steps: 0,
    };
    let mut balance0 = None;
    let t_end = *times.last().expect("output times");
    // The length driver's row of Φ, and so of λ.
    let length_row = PumpedPendulum::JOINTS[PumpedPendulum::LENGTH].row_range().start;
    let stats = Simulation::new(&m, &mut dopri).start(0.0, &q, &v).times(&times).options(options).run(&mut ws, |s| {
        let t = s.point.t;
        while t_reduced < t - 1e-12 {
            let h = (t - t_reduced) / substeps as f64;
            for _ in 0..substeps {
                y = reduced_step(&m, inertia, rod_mass, g, t_reduced, h, y);
                t_reduced += h;
            }
            t_reduced = t;
        }
        let theta = swing(&s.point.q);
        r.angle_error = r.angle_error.max((theta - y[0]).abs());
        if t <= period {
            r.amplitude_start = r.amplitude_start.max(theta.abs());
        }
        if t >= t_end - period {
            r.amplitude_end = r.amplitude_end.max(theta.abs());
        }
        let balance = s.energy.balance();
        let b0 = *balance0.get_or_insert(balance);
        r.balance_drift = r.balance_drift.max((balance - b0).abs());
        r.driver_work = s.energy.constraint_work;
        r.energy_gain_reduced = reduced_energy(&m, inertia, rod_mass, g, t, y) - e0;
        // λ > 0 pulls the rod towards the pivot.
        r.peak_pull = r.peak_pull.max(s.point.lambda[length_row].abs());
    })?;
    r.steps = stats.steps;
    if print {
        println!(
            "Pumped pendulum: L = {} + {} cos 2ωt m, ω = {:.4} rad/s (the swing's natural frequency), {cycles} periods",
            m.l0, m.dl, m.omega
        );
        println!(
            "swing amplitude {:.4} rad in the first period → {:.4} rad in the last ({:.1}×)",
            r.amplitude_start,
            r.amplitude_end,
            r.amplitude_end / r.amplitude_start
        );
        println!(
            "energy pumped in by the length driver W_c = {:.6} J (reduced model: {:.6} J); T + V − W_c drift {:.1e} J",
            r.driver_work, r.energy_gain_reduced, r.balance_drift
        );
        println!(
            "swing angle against the reduced model: max error {:.1e} rad; peak driver pull {:.2} N; {} DOPRI5 steps",
            r.angle_error, r.peak_pull, r.steps
        );
    }
    Ok(r)
}

/// The swing pumped up over the 12 periods of `run`, for the showcase's pictures: 16 frames per
/// period, 193 in all.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let Start { m, q, v, .. } = start()?;
    let mut ws = PumpedPendulum::workspace();
    let period = 2.0 * PI / m.omega;
    let times: Vec<f64> = (0..=12 * 16).map(|k| k as f64 * period / 16.0).collect();
    let options = SimulationOptions::default().with_correction(Correction::projection());
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    let mut animation =
        mbd::Animation::new::<PumpedPendulum>(&m.params()).title("Pumped pendulum: length driven at twice the swing frequency");
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &v)
        .times(&times)
        .options(options)
        .run(&mut ws, |s| animation.frame(s.point.t, &s.point.q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("pumped_pendulum: {e}");
        std::process::exit(1);
    }
}

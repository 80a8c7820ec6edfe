//! Double A-arm and MacPherson suspensions in motion (Nikravesh, *Planar Multibody Dynamics*,
//! ch. 8 style): the linkages of `double_a_arm.rs` and `macpherson.rs`, now free, under gravity,
//! with a coil-over spring-damper to the chassis (= ground, a quarter car on a rig) and a linear
//! tyre: a vertical force k_t (road(t) − y_contact) − c_t ẏ at the contact patch, with a 30 mm
//! smooth bump (Gaussian, 30 ms wide) under the wheel at t = 0.5 s.
//!
//! Each run: static equilibrium first (Nikravesh 14.2; the tyre then carries the spring preload
//! plus the unsprung weight), then forward dynamics with DOPRI5 and projection from that rest
//! state through the bump. Reported: static tyre load and wheel-centre height, peak wheel
//! travel and tyre load over the bump, how far the wheel still moves after 1.2 s (the damping
//! at work), the energy the bump puts in, and the energy balance T + V − W_nc − W_c, whose drift measures the integration.
//!
//! Run: `cargo run --release --example suspension_dynamics`
use mbd::prelude::*;
use mbd::PlanarBody;

mechanism! {
    /// Double A-arm suspension, free, with a coil-over and a tyre.
    pub DoubleAArmRide {
        params { k_s: 30000.0, free_length: 0.61, c_s: 1500.0, k_t: 200000.0, c_t: 100.0, bump: 0.03, t_bump: 0.5, width: 0.03 }
        gravity [0.0, -9.81];
        body lower   { mass: 4.0, inertia: 0.05, at: [0.375, 0.14, 0.0] }
        body upper   { mass: 2.5, inertia: 0.02, at: [0.41, 0.46, 0.0] }
        body knuckle { mass: 18.0, inertia: 0.60, at: [0.62, 0.30, 0.0] }
        point lower.inner = [-0.175, 0.01];
        point lower.outer = [0.175, -0.01];
        point lower.spring = [0.1, 0.0];
        point upper.inner = [-0.11, -0.01];
        point upper.outer = [0.11, 0.01];
        point knuckle.lower_ball = [-0.07, -0.17];
        point knuckle.upper_ball = [-0.10, 0.17];
        point knuckle.contact = [0.0, -0.30];
        revolute ground[0.20, 0.15] ~ lower.inner;
        revolute ground[0.30, 0.45] ~ upper.inner;
        revolute lower.outer ~ knuckle.lower_ball;
        revolute upper.outer ~ knuckle.upper_ball;
        spring coil_over: lower.spring ~ ground[0.45, 0.60] { k: k_s, length: free_length, c: c_s };
        force tyre: knuckle.contact = [0.0, k_t * (bump * exp(-((t - t_bump) / width) ^ 2) - (knuckle.y - 0.3 * cos(knuckle.phi)))
                                          - c_t * knuckle.vy];
    }
}

mechanism! {
    /// MacPherson strut suspension, free, with the coil-over on the strut and a tyre.
    pub MacPhersonRide {
        params { k_s: 25000.0, free_length: 0.48, c_s: 1500.0, k_t: 200000.0, c_t: 100.0, bump: 0.03, t_bump: 0.5, width: 0.03 }
        gravity [0.0, -9.81];
        body lower   { mass: 4.0, inertia: 0.05, at: [0.425, 0.11, 0.0] }
        body knuckle { mass: 20.0, inertia: 0.65, at: [0.65, 0.30, 0.0] }
        body rod     { mass: 1.0, inertia: 0.01, at: [0.535, 0.575, 0.0] }
        point lower.inner = [-0.175, 0.01];
        point lower.outer = [0.175, -0.01];
        point knuckle.ball = [-0.05, -0.20];
        point knuckle.strut = [-0.08, 0.10];
        point knuckle.contact = [0.0, -0.30];
        point rod.top = [-0.035, 0.175];
        point rod.bottom = [0.035, -0.175];
        vector knuckle.axis = [-0.07, 0.35];
        vector rod.axis = [-0.07, 0.35];
        revolute ground[0.25, 0.12] ~ lower.inner;
        revolute lower.outer ~ knuckle.ball;
        translational strut: knuckle.strut along knuckle.axis ~ rod.bottom along rod.axis;
        revolute top_mount: rod.top ~ ground[0.50, 0.75];
        spring coil_over: knuckle.strut ~ ground[0.50, 0.75] { k: k_s, length: free_length, c: c_s };
        force tyre: knuckle.contact = [0.0, k_t * (bump * exp(-((t - t_bump) / width) ^ 2) - (knuckle.y - 0.3 * cos(knuckle.phi)))
                                          - c_t * knuckle.vy];
    }
}

/// What a ride engineer reads off one run.
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// Wheel-centre height at static equilibrium (m).
    pub static_height: f64,
    /// Tyre load at static equilibrium (N).
    pub static_tyre_load: f64,
    /// Largest upward wheel travel from static over the bump (m).
    pub peak_travel: f64,
    /// Largest tyre load over the bump (N).
    pub peak_tyre_load: f64,
    /// Largest |y − y_static| of the wheel centre after t = 1.2 s (m).
    pub residual_motion: f64,
    /// Largest drift of T + V − W_nc − W_c over the run (J).
    pub energy_drift: f64,
    /// Largest net work of the non-conservative forces (road through the tyre, dampers) (J):
    /// the energy the bump puts in before the dampers take it out again.
    pub bump_energy: f64,
    /// Integration steps taken.
    pub steps: u64,
}

/// Static equilibrium, then the bump; `knuckle` is the wheel body.
fn ride<M, const NQ: usize, const NC: usize, const N: usize, const NS: usize>(
    m: &M,
    knuckle: PlanarBody<NQ>,
    tyre_load: impl Fn(&[f64; NQ], &[f64; NQ], f64) -> f64,
    mut ws: Box<Workspace<f64, NQ, NC, N, NS>>,
) -> Result<Report, Box<dyn std::error::Error>>
where
    M: NewtonMatrix<f64, NQ, NQ, NC>,
{
    // The stable rest state from the `at:` guesses (the solver assembles them first).
    let mut q = m.initial_positions();
    let mut lambda = [0.0; NC];
    let report = StaticSolver::default().solve(m, &mut ws, &mut q, 0.0, &mut lambda)?;
    if !matches!(report.stability, Stability::Stable { .. }) {
        return Err(format!("{}: the static equilibrium is not stable: {:?}", M::NAME, report.stability).into());
    }
    let y0 = knuckle.y(&q);
    let static_tyre_load = tyre_load(&q, &[0.0; NQ], 0.0);
    let options = SimulationOptions::default().with_correction(Correction::projection()).with_track_work(true);
    let times: Vec<f64> = (0..=1500).map(|k| k as f64 * 1e-3).collect();
    let mut r = Report {
        static_height: y0,
        static_tyre_load,
        peak_travel: 0.0,
        peak_tyre_load: 0.0,
        residual_motion: 0.0,
        energy_drift: 0.0,
        bump_energy: 0.0,
        steps: 0,
    };
    let mut balance0 = None;
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-11).with_max_step(2e-3));
    let stats = Simulation::new(m, &mut dopri).start(0.0, &q, &[0.0; NQ]).times(&times).options(options).run(&mut *ws, |s| {
        let p = &s.point;
        let travel = knuckle.y(&p.q) - y0;
        r.peak_travel = r.peak_travel.max(travel);
        r.peak_tyre_load = r.peak_tyre_load.max(tyre_load(&p.q, &p.v, p.t));
        if p.t >= 1.2 {
            r.residual_motion = r.residual_motion.max(travel.abs());
        }
        let b = s.energy.balance();
        let b0 = *balance0.get_or_insert(b);
        r.energy_drift = r.energy_drift.max((b - b0).abs());
        r.bump_energy = r.bump_energy.max(s.energy.nonconservative_work);
    })?;
    r.steps = stats.steps;
    Ok(r)
}

/// The tyre and the road of both mechanisms (their parameters of the same names).
#[derive(Debug, Clone, Copy)]
struct Tyre {
    /// Vertical stiffness (N/m).
    k_t: f64,
    /// Vertical damping (N·s/m).
    c_t: f64,
    /// Height of the bump (m).
    bump: f64,
    /// Time the bump is under the wheel (s).
    t_bump: f64,
    /// Width of the Gaussian bump (s).
    width: f64,
}

impl Tyre {
    /// The tyre's vertical force on the wheel body `wheel` (same law as in the mechanisms).
    fn force<const NQ: usize>(&self, q: &[f64; NQ], v: &[f64; NQ], t: f64, wheel: PlanarBody<NQ>) -> f64 {
        let road = self.bump * (-((t - self.t_bump) / self.width).powi(2)).exp();
        let contact = wheel.y(q) - 0.3 * wheel.phi(q).cos();
        self.k_t * (road - contact) - self.c_t * wheel.velocity(v).y
    }
}

pub fn run(print: bool) -> Result<[Report; 2], Box<dyn std::error::Error>> {
    let a = DoubleAArmRide::default();
    let tyre = Tyre { k_t: a.k_t, c_t: a.c_t, bump: a.bump, t_bump: a.t_bump, width: a.width };
    let wheel = DoubleAArmRide::KNUCKLE;
    let double_a_arm = ride(&a, wheel, |q, v, t| tyre.force(q, v, t, wheel), DoubleAArmRide::workspace())?;
    let b = MacPhersonRide::default();
    let tyre = Tyre { k_t: b.k_t, c_t: b.c_t, bump: b.bump, t_bump: b.t_bump, width: b.width };
    let wheel = MacPhersonRide::KNUCKLE;
    let macpherson = ride(&b, wheel, |q, v, t| tyre.force(q, v, t, wheel), MacPhersonRide::workspace())?;
    if print {
        for (name, r) in [("double A-arm", double_a_arm), ("MacPherson", macpherson)] {
            println!("{name}: static wheel centre at {:.4} m, tyre load {:.0} N", r.static_height, r.static_tyre_load);
            println!(
                "  30 mm bump at 0.5 s: peak travel {:.1} mm, peak tyre load {:.0} N; after 1.2 s the wheel moves ≤ {:.2e} m",
                1e3 * r.peak_travel,
                r.peak_tyre_load,
                r.residual_motion
            );
            println!("  bump energy {:.2} J; energy balance drift {:.1e} J; {} DOPRI5 steps", r.bump_energy, r.energy_drift, r.steps);
        }
    }
    Ok([double_a_arm, macpherson])
}

/// The double A-arm's ride over the bump, from its static equilibrium through the 1.5 s of
/// `run`, for the showcase's pictures: 201 frames, 7.5 ms apart.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = DoubleAArmRide::default();
    let mut ws = DoubleAArmRide::workspace();
    let mut q = m.initial_positions();
    StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut [0.0; DoubleAArmRide::NC])?;
    let options = SimulationOptions::default().with_correction(Correction::projection());
    let times: Vec<f64> = (0..=200).map(|k| k as f64 * 7.5e-3).collect();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-11).with_max_step(2e-3));
    let mut animation = mbd::Animation::new::<DoubleAArmRide>(&m.params()).title("Double A-arm over a 30 mm bump").trace("knuckle.contact");
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &[0.0; DoubleAArmRide::NV])
        .times(&times)
        .options(options)
        .run(&mut *ws, |s| animation.frame(s.point.t, &s.point.q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

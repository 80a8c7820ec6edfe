//! Nikravesh's project 15.2, the internal combustion engine, posed as its designer asks it: for
//! a small single-cylinder four-stroke engine at its speed of maximum torque, what torque does
//! the gas-pressure cycle put on the crank, what loads do the main bearing and the piston pin
//! carry over a cycle, how large a flywheel keeps the speed fluctuation within a target, and how
//! much does a crank counterweight reduce the shaking force on the engine's mounts?
//!
//! The model (planar, in the plane of the crank; SI units; every number's source in `SOURCES`):
//! the crank (crankshaft, counterweight and flywheel as one body), the connecting rod and the
//! piston, the cylinder vertical. The gas force on the piston is (p − p_atm) A, with p over the
//! 720° cycle a single-zone model: the compression polytrope p_atm (V_BDC / V)ⁿ, multiplied
//! while burning by 1 + (r_p − 1) x_b, x_b the Wiebe function of the mass fraction burned,
//! released to p_atm by a cosine blowdown between the exhaust valve's opening and BDC; at
//! p_atm through the exhaust and intake strokes. The combustion pressure ratio r_p is set so
//! that the cycle's work ∮ p dV, by quadrature in the example, gives the datasheet's maximum
//! torque. Two scenes of one declaration: driven at constant speed (`drive speed`) for the
//! inverse dynamics, and `Running`, the same engine braked by a generator (−c ω) for forward
//! dynamics.
//!
//! **The checks** (each independent of the simulation's equations):
//!
//! - the crank torque's mean against ∮ p dV / 4π, the cycle's work by quadrature over the
//!   closed-form cylinder volume;
//! - the drive torque and the main-bearing, crank-pin and piston-pin loads at every sample
//!   against a force analysis by hand: the slider-crank's closed-form kinematics at constant
//!   speed (rod angle β = asin(λ sin θ), its rates, the piston's and the rod's centre's
//!   accelerations) and Newton–Euler taken body by body, piston, rod, crank;
//! - the shaking force the reactions put on the engine's frame against −Σ mᵢ aᵢ from those
//!   accelerations, for each balance;
//! - the forward run's coefficient of speed fluctuation against the flywheel sizing's target,
//!   δ = ΔE / (J ω²), ΔE the largest swing of the excess work ∫ (τ − τ̄) dθ of the inverse
//!   dynamics' torque.
//!
//! Run: `cargo run --release --example engine`
use mbd::prelude::*;

mechanism! {
    /// A single-cylinder four-stroke engine (Nikravesh's project 15.2), the Honda GX160's bore,
    /// stroke and compression ratio: crank with counterweight and flywheel, rod, piston, a
    /// gas-pressure cycle on the piston; driven at constant speed, or braked by a generator.
    pub SingleCylinder {
        // omega: the speed (rad/s); c_load: the generator's constant (N·m·s), set by the
        // example; r, l: crank radius and rod length (m); a_rod: big-end centre to the rod's
        // centre of mass (m); e_cw: the crank's centre of mass below the axis (m), from the
        // balance; j_crank: the crank's inertia about its centre of mass (kg·m²), from the
        // flywheel sizing.
        params {
            omega: 2500.0 * PI / 30.0, c_load: 0.042,
            r: 0.0225, l: 0.080, a_rod: 0.025, e_cw: 0.0, j_crank: 0.06,
            // The gas: bore (m), compression ratio, ambient pressure (Pa), polytropic
            // exponent, combustion pressure ratio (set by the example); Wiebe's a, the start
            // and duration of burning and the exhaust valve's opening, in crank angle after
            // the firing TDC (rad).
            bore: 0.068, cr: 8.5, p_atm: 101325.0, n_poly: 1.3, rp: 3.66,
            wiebe_a: 5.0, burn_start: deg(-17.0), burn: deg(50.0), evo: deg(130.0)
        }
        gravity [0.0, -9.81];
        // Each body's frame at its centre of mass; the crank's axis e_cw above it, the pin
        // r beyond; the rod along its y axis, the big end a_rod below its centre.
        body crank  { mass: 2.5, inertia: j_crank, at: [0.0, 0.0, 0.0] }
        body rod    { mass: 0.12, inertia: 1.2e-4, at: [0.0, 0.0475, 0.0] }
        body piston { mass: 0.18, inertia: 1.0e-4, at: [0.0, 0.1025, 0.0] }
        revolute main_bearing: ground[0.0, 0.0] ~ crank[0.0, e_cw];
        revolute crank_pin: crank[0.0, e_cw + r] ~ rod[0.0, -a_rod];
        revolute wrist_pin: rod[0.0, l - a_rod] ~ piston[0.0, 0.0];
        translational cylinder: ground[0.0, 0.0] along [0.0, 1.0] ~ piston[0.0, 0.0] along [0.0, 1.0];
        // The crank angle θ = crank.phi from the firing TDC, counter-clockwise.
        drive speed: crank.phi = omega * t;
        // The gas: ψ, the crank angle in the 720° cycle, in (−2π, 2π]; the gas column's
        // height V/A = V_c/A + r + l − y (V_c = V_d/(cr − 1), V_d = 2 r A); the mass fraction
        // burned (Wiebe); the share of the combustion's pressure rise still held as the
        // exhaust valve opens (a cosine from EVO to BDC); the pressure.
        let psi = 2.0 * atan2(sin(crank.phi / 2.0), cos(crank.phi / 2.0));
        let area = PI * bore^2 / 4.0;
        let column = 2.0 * r / (cr - 1.0) + r + l - piston.y;
        let burned = 1.0 - exp(-wiebe_a * (max(psi - burn_start, 0.0) / burn)^3);
        let held = (1.0 + cos(PI * clamp((psi - evo) / (PI - evo), 0.0, 1.0))) / 2.0;
        let pressure = p_atm * (2.0 * r * cr / (cr - 1.0) / column)^n_poly * (1.0 + (rp - 1.0) * burned * held);
        // On the piston while the valves are shut (|ψ| < π); p_atm below it.
        force gas: piston[0.0, 0.0] = [0.0, if abs(psi) < PI { -(pressure - p_atm) * area } else { 0.0 }];
        scene Running actuating speed = -c_load * crank.omega;
    }
}

/// Where the numbers come from (assumptions are marked so).
pub const SOURCES: [(&str, &str); 10] = [
    (
        "bore 68.0 mm, stroke 45.0 mm, compression ratio 8.5, maximum torque 11.0 N·m at 2500 rpm",
        "Honda GX160 (K1) service data: bore, stroke, compression ratio (7.5:1 or 8.5:1; 8.5 taken) and maximum torque at the crank",
    ),
    (
        "rod 80 mm between centres (r/l = 0.28), its centre of mass 25 mm from the big end",
        "assumption: the proportions of small engines' rods",
    ),
    ("piston with pin and rings 0.18 kg; rod 0.12 kg, J = 1.2e-4 kg·m²; crank 2.5 kg", "assumption"),
    (
        "ambient 101 325 Pa, the cylinder filled at it, the crankcase at it",
        "assumption: full throttle, no intake loss; the standard atmosphere",
    ),
    ("polytropic exponent 1.3 for compression and expansion", "assumption: the usual value for spark-ignition engines"),
    ("Wiebe function a = 5, exponent 3; burning from 17° before TDC for 50°", "assumption: a typical burn, half of it at 9° after TDC"),
    ("exhaust valve opening 50° before BDC, blowdown to ambient by BDC", "assumption"),
    ("friction and pumping losses neglected: the gas's work is the crank's", "assumption"),
    ("speed fluctuation target δ = 0.04", "assumption: a pump or a saw, not a generator"),
    ("counterweight balancing the rotating masses and half of the reciprocating", "assumption: a common compromise for a single cylinder"),
];

/// The model's masses and inertias (kg, kg·m²), as in the mechanism: for the hand calculation.
const CRANK_MASS: f64 = 2.5;
const ROD_MASS: f64 = 0.12;
const ROD_INERTIA: f64 = 1.2e-4;
const PISTON_MASS: f64 = 0.18;
const GRAVITY: f64 = 9.81;
/// The datasheet's maximum torque (N·m), the flywheel's target and the design balance.
const TORQUE: f64 = 11.0;
const DELTA_TARGET: f64 = 0.04;
const BALANCE: f64 = 0.5;
/// Samples of the 720° cycle: one a degree, at the midpoints (their mean is the cycle's).
const SAMPLES: usize = 720;

/// The cylinder pressure (Pa) at crank angle ψ of the cycle (rad, 0 at the firing TDC, in
/// (−2π, 2π]) and cylinder volume `volume` (m³): the mechanism's gas law.
fn pressure(m: &SingleCylinder, psi: f64, volume: f64) -> f64 {
    if psi.abs() >= PI {
        return m.p_atm;
    }
    let area = PI * m.bore * m.bore / 4.0;
    let bdc = area * 2.0 * m.r * m.cr / (m.cr - 1.0);
    let burned = 1.0 - (-m.wiebe_a * ((psi - m.burn_start).max(0.0) / m.burn).powi(3)).exp();
    let open = (1.0 + (PI * ((psi - m.evo) / (PI - m.evo)).clamp(0.0, 1.0)).cos()) / 2.0;
    m.p_atm * (bdc / volume).powf(m.n_poly) * (1.0 + (m.rp - 1.0) * burned * open)
}

/// The slider-crank at crank angle θ (from the cylinder's axis, counter-clockwise) turning at a
/// constant ω, by its closed form: positions, velocities and accelerations.
struct Motion {
    /// The rod's angle from the axis, β = asin(λ sin θ), and its rates.
    beta: [f64; 3],
    /// The crank pin, the piston pin and the rod's centre of mass: positions, and the last two's
    /// accelerations.
    pin: [f64; 2],
    piston: [f64; 2],
    rod: [f64; 2],
    piston_acc: [f64; 2],
    rod_acc: [f64; 2],
    /// dy/dθ of the piston (m/rad).
    piston_rate: f64,
}

fn kinematics(m: &SingleCylinder, theta: f64, omega: f64) -> Motion {
    let (s, c) = theta.sin_cos();
    let lambda = m.r / m.l;
    let (sb, cb) = (lambda * s, (1.0 - lambda * lambda * s * s).sqrt());
    let db = lambda * c * omega / cb;
    let ddb = (sb * db * db - lambda * s * omega * omega) / cb;
    let pin = [-m.r * s, m.r * c];
    let pin_acc = [-omega * omega * pin[0], -omega * omega * pin[1]];
    // The rod's unit vector from big end to small end, (sin β, cos β), and its acceleration.
    let u_acc = [cb * ddb - sb * db * db, -sb * ddb - cb * db * db];
    let along = |d: f64| [pin[0] + d * sb, pin[1] + d * cb];
    let along_acc = |d: f64| [pin_acc[0] + d * u_acc[0], pin_acc[1] + d * u_acc[1]];
    Motion {
        beta: [sb.asin(), db, ddb],
        pin,
        piston: along(m.l),
        rod: along(m.a_rod),
        piston_acc: along_acc(m.l),
        rod_acc: along_acc(m.a_rod),
        piston_rate: -m.r * s - m.l * sb * lambda * c / cb,
    }
}

/// The 2-D cross product a × b.
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The force analysis by hand at crank angle θ and constant ω, with the gas force `gas` (N,
/// along y on the piston): Newton–Euler body by body. Returns the force of the rod on the
/// piston (piston pin), of the crank on the rod (crank pin), of the frame on the crank (main
/// bearing), of the cylinder wall on the piston (side thrust, along x), the drive torque on the
/// crank, and −Σ mᵢ aᵢ, the shaking force.
fn by_hand(m: &SingleCylinder, theta: f64, omega: f64, gas: f64) -> Loads {
    let k = kinematics(m, theta, omega);
    let g = [0.0, -GRAVITY];
    // Piston, along the bore: m_p ÿ = W_y + F_gas − m_p g.
    let wy = PISTON_MASS * (k.piston_acc[1] - g[1]) - gas;
    // Rod, moments about its centre: J α = (P − G) × K − (S − G) × W, with K = m (a_G − g) + W
    // from its forces, gives (P − S) × W = J α − (P − G) × m (a_G − g); P − S = −l u.
    let (sb, cb) = k.beta[0].sin_cos();
    let inertial = [ROD_MASS * (k.rod_acc[0] - g[0]), ROD_MASS * (k.rod_acc[1] - g[1])];
    let lever = [k.pin[0] - k.rod[0], k.pin[1] - k.rod[1]];
    // The rod's angle in the model is φ = −β, so its angular acceleration is −β̈.
    let rhs = ROD_INERTIA * -k.beta[2] - cross(lever, inertial);
    let wx = (rhs / m.l + sb * wy) / cb;
    let piston_pin = [wx, wy];
    let crank_pin = [inertial[0] + wx, inertial[1] + wy];
    // Crank, its centre of mass e below the axis, opposite the pin: B = m_c (a_C − g) + K, and
    // the drive torque from its moments about its centre (α = 0).
    let centre = [m.e_cw * theta.sin(), -m.e_cw * theta.cos()];
    let centre_acc = [-omega * omega * centre[0], -omega * omega * centre[1]];
    let main = [CRANK_MASS * (centre_acc[0] - g[0]) + crank_pin[0], CRANK_MASS * (centre_acc[1] - g[1]) + crank_pin[1]];
    let torque = cross([k.pin[0] - centre[0], k.pin[1] - centre[1]], crank_pin) - cross([-centre[0], -centre[1]], main);
    let shaking = [
        -(CRANK_MASS * centre_acc[0] + ROD_MASS * k.rod_acc[0] + PISTON_MASS * k.piston_acc[0]),
        -(CRANK_MASS * centre_acc[1] + ROD_MASS * k.rod_acc[1] + PISTON_MASS * k.piston_acc[1]),
    ];
    Loads { piston_pin, crank_pin, main, side: -wx, torque, shaking }
}

/// The loads of one instant (N, N·m), global components.
#[derive(Debug, Clone, Copy, Default)]
pub struct Loads {
    pub piston_pin: [f64; 2],
    pub crank_pin: [f64; 2],
    pub main: [f64; 2],
    pub side: f64,
    pub torque: f64,
    pub shaking: [f64; 2],
}

/// The crank's centre of mass below its axis (m) for a counterweight that balances the rod's
/// big-end share m_rod (l − a)/l, which turns with the crank pin, and the fraction `balance` of
/// the reciprocating mass (the piston and the rod's small-end share, m_rod a/l): m_c e =
/// (m_rod (l − a)/l + b m_rec) r, the crank with its pin and counterweight as one body.
fn counterweight(m: &SingleCylinder, balance: f64) -> f64 {
    let rotating = ROD_MASS * (m.l - m.a_rod) / m.l;
    let reciprocating = PISTON_MASS + ROD_MASS * m.a_rod / m.l;
    (rotating + balance * reciprocating) * m.r / CRANK_MASS
}

/// The cylinder volume (m³) with the piston pin at height y above the crank's axis.
fn volume(m: &SingleCylinder, y: f64) -> f64 {
    let area = PI * m.bore * m.bore / 4.0;
    area * (2.0 * m.r / (m.cr - 1.0) + m.r + m.l - y)
}

/// The cycle's work ∮ (p − p_atm) dV (J) by Simpson's rule over the closed-form volume, with
/// the combustion pressure ratio `rp`: the compression and expansion strokes (the exhaust and
/// intake strokes are at p_atm).
fn cycle_work(m: &SingleCylinder, rp: f64) -> f64 {
    let m = SingleCylinder { rp, ..*m };
    let area = PI * m.bore * m.bore / 4.0;
    let n = 7200;
    let h = 2.0 * PI / n as f64;
    (0..=n)
        .map(|k| {
            let psi = -PI + h * k as f64;
            let k_ = kinematics(&m, psi, 1.0);
            let weight = if k == 0 || k == n {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            // dV/dψ = −A dy/dψ.
            weight * (pressure(&m, psi, volume(&m, k_.piston[1])) - m.p_atm) * -area * k_.piston_rate
        })
        .sum::<f64>()
        * h
        / 3.0
}

/// The crank angle in the cycle, ψ = θ wrapped into (−2π, 2π] (rad).
fn cycle_angle(theta: f64) -> f64 {
    2.0 * (theta / 2.0).sin().atan2((theta / 2.0).cos())
}

/// One cycle of the driven engine: the loads from the inverse dynamics at each sample, and the
/// largest difference from the hand analysis.
struct Cycle {
    /// (ψ, the solver's loads) at each sample.
    samples: Vec<(f64, Loads)>,
    /// Largest |solver − hand| of the torque (N·m) and of any bearing load or the shaking force (N).
    torque_error: f64,
    load_error: f64,
    /// The mean reduced inertia of the rod and piston, 2 T / ω² over the cycle (kg·m²).
    reduced: f64,
}

fn cycle(m: &SingleCylinder) -> Result<Cycle, Box<dyn std::error::Error>> {
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = SingleCylinder::workspace();
    solver.assemble(m, &mut ws, &mut q, 0.0)?;
    let period = 4.0 * PI / m.omega;
    let inverse = InverseDynamics::default();
    let mut inverse_ws = SingleCylinder::workspace();
    let mut out = Cycle { samples: Vec::with_capacity(SAMPLES), torque_error: 0.0, load_error: 0.0, reduced: 0.0 };
    let mut failure = None;
    let times = (0..SAMPLES).map(|k| period * (k as f64 + 0.5) / SAMPLES as f64);
    let total_mass = CRANK_MASS + ROD_MASS + PISTON_MASS;
    solver.sweep(m, &mut ws, &mut q, times, |t, q, v, vd| {
        let mut lambda = [0.0; SingleCylinder::NC];
        if let Err(e) = inverse.solve(m, &mut inverse_ws, q, v, vd, t, &mut lambda) {
            failure.get_or_insert(e);
            return;
        }
        let mut d = [[0.0; SingleCylinder::NV]; SingleCylinder::NC];
        m.jacobian(q, t, &mut d);
        let on = |joint: usize, body: &str| joint_reaction(m, q, &d, &lambda, joint).and_then(|j| j.on(body));
        let (Some(main), Some(crank_pin), Some(piston_pin), Some(wall), Some(drive)) = (
            on(SingleCylinder::MAIN_BEARING, "crank"),
            on(SingleCylinder::CRANK_PIN, "rod"),
            on(SingleCylinder::WRIST_PIN, "piston"),
            on(SingleCylinder::CYLINDER, "piston"),
            on(SingleCylinder::SPEED, "crank"),
        ) else {
            return;
        };
        let theta = SingleCylinder::CRANK.phi(q);
        let psi = cycle_angle(theta);
        let y = SingleCylinder::PISTON.position(q).y;
        // The gas force the solver applied, at its piston position.
        let gas = -(pressure(m, psi, volume(m, y)) - m.p_atm) * PI * m.bore * m.bore / 4.0;
        let xy = |f: [f64; 3]| [f[0], f[1]];
        // The frame takes −B from the main bearing, −N from the wall and −F_gas on the head:
        // −(B + N + F_gas) = −Σ mᵢ aᵢ + M g, g = (0, −9.81).
        let shaking = [-(main.force[0] + wall.force[0]), -(main.force[1] + wall.force[1] + gas) + total_mass * GRAVITY];
        let loads = Loads {
            piston_pin: xy(piston_pin.force),
            crank_pin: xy(crank_pin.force),
            main: xy(main.force),
            side: wall.force[0],
            torque: drive.moment[2],
            shaking,
        };
        // The hand analysis takes the gas force at the closed form's piston position.
        let gas_by_hand = -(pressure(m, psi, volume(m, kinematics(m, theta, m.omega).piston[1])) - m.p_atm) * PI * m.bore * m.bore / 4.0;
        let hand = by_hand(m, theta, m.omega, gas_by_hand);
        out.torque_error = out.torque_error.max((loads.torque - hand.torque).abs());
        for (a, b) in
            [(loads.piston_pin, hand.piston_pin), (loads.crank_pin, hand.crank_pin), (loads.main, hand.main), (loads.shaking, hand.shaking)]
        {
            out.load_error = out.load_error.max((a[0] - b[0]).abs()).max((a[1] - b[1]).abs());
        }
        out.load_error = out.load_error.max((loads.side - hand.side).abs());
        // The rod's and the piston's kinetic energy, over ½ ω²: their reduced inertia here.
        let (vr, vp) = (SingleCylinder::ROD, SingleCylinder::PISTON);
        let kinetic =
            ROD_MASS * vr.velocity(v).norm_squared() + ROD_INERTIA * vr.omega(v).powi(2) + PISTON_MASS * vp.velocity(v).norm_squared();
        out.reduced += kinetic / (m.omega * m.omega) / SAMPLES as f64;
        out.samples.push((psi, loads));
    })?;
    if let Some(e) = failure {
        return Err(e.into());
    }
    if out.samples.len() != SAMPLES {
        return Err(format!("{} of the {SAMPLES} samples have every joint's reaction", out.samples.len()).into());
    }
    Ok(out)
}

/// What the run measured. Angles in degrees of crank (ψ, from the firing TDC), forces in N,
/// torques in N·m.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone)]
pub struct Report {
    /// The combustion pressure ratio that gives the datasheet's torque, the peak pressure (Pa)
    /// and its angle, and the cycle's work (J) by quadrature.
    pub rp: f64,
    pub peak_pressure: f64,
    pub peak_pressure_at: f64,
    pub work: f64,
    /// The torque the engine gives its load at constant speed (−the drive's): mean by the
    /// inverse dynamics and by hand (∮ p dV / 4π), largest and smallest, and where the largest is.
    pub torque_mean: f64,
    pub torque_by_hand: f64,
    pub torque_max: f64,
    pub torque_max_at: f64,
    pub torque_min: f64,
    pub torque_min_at: f64,
    /// Largest load over the cycle, at the design balance, and where: main bearing, crank pin,
    /// piston pin; the largest side thrust on the cylinder wall.
    pub main_max: (f64, f64),
    pub crank_pin_max: (f64, f64),
    pub piston_pin_max: (f64, f64),
    pub side_max: f64,
    /// The largest of the three bearing loads while the valves are open (|ψ| ≥ 180°, the
    /// exhaust and intake strokes: the parts' inertia and weight alone).
    pub open_valves_max: f64,
    /// Largest |solver − hand| over the samples of every balance: torque, and loads.
    pub torque_error: f64,
    pub load_error: f64,
    /// The shaking force's largest components along and across the cylinder's axis, for each
    /// balance (0, ½, 1 of the reciprocating mass).
    pub shaking: [(f64, f64, f64); 3],
    /// The flywheel: the energy swing ΔE (J); the crank's own inertia about its axis
    /// (kg·m²) and the rod's and piston's mean reduced inertia (kg·m²), which together are
    /// the J = ΔE/(δ ω²) the target asks; the generator's constant (N·m·s).
    pub energy_swing: f64,
    pub crank_inertia: f64,
    pub reduced: f64,
    pub c_load: f64,
    /// The forward run: mean speed over its last cycle (rpm), the coefficient of speed
    /// fluctuation there, the cycles run and the integrator's steps.
    pub rpm_mean: f64,
    pub delta: f64,
    pub cycles: usize,
    pub steps: usize,
}

/// The largest of `f` over the samples, and the ψ (degrees) where it is.
fn largest(samples: &[(f64, Loads)], f: impl Fn(&Loads) -> f64) -> (f64, f64) {
    samples.iter().map(|(psi, l)| (f(l), psi.to_degrees())).fold((f64::NEG_INFINITY, 0.0), |a, b| if b.0 > a.0 { b } else { a })
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let base = SingleCylinder::default();
    // The combustion pressure ratio: the work is linear in it, W = W(1) + (r_p − 1) ∂W/∂r_p.
    let (w1, w2) = (cycle_work(&base, 1.0), cycle_work(&base, 2.0));
    let rp = 1.0 + (4.0 * PI * TORQUE - w1) / (w2 - w1);
    let m = SingleCylinder { rp, e_cw: counterweight(&base, BALANCE), ..base };
    let work = cycle_work(&m, rp);
    // The peak pressure, on a 0.01° grid of the cycle.
    let (peak_pressure, peak_pressure_at) = (0..36000)
        .map(|k| {
            let psi = (-180.0 + 0.01 * k as f64).to_radians();
            (pressure(&m, psi, volume(&m, kinematics(&m, psi, 1.0).piston[1])), psi.to_degrees())
        })
        .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
    // The three balances; the design's is the second.
    let mut shaking = [(0.0, 0.0, 0.0); 3];
    let (mut torque_error, mut load_error) = (0.0_f64, 0.0_f64);
    let mut design = None;
    let mut loci = Vec::new();
    for (k, balance) in [0.0, 0.5, 1.0].into_iter().enumerate() {
        let c = cycle(&SingleCylinder { e_cw: counterweight(&base, balance), ..m })?;
        torque_error = torque_error.max(c.torque_error);
        load_error = load_error.max(c.load_error);
        let (along, across) = (largest(&c.samples, |l| l.shaking[1].abs()).0, largest(&c.samples, |l| l.shaking[0].abs()).0);
        shaking[k] = (balance, along, across);
        loci.push((balance, c.samples.iter().map(|(_, l)| (l.shaking[0], l.shaking[1])).collect::<Vec<_>>()));
        if balance == BALANCE {
            design = Some(c);
        }
    }
    let design = design.ok_or("the design balance is one of the three")?;
    let samples = &design.samples;
    // The engine's torque on its load, −τ_drive; its mean, and the excess work's largest swing.
    let torque = |l: &Loads| -l.torque;
    let torque_mean = samples.iter().map(|(_, l)| torque(l)).sum::<f64>() / SAMPLES as f64;
    let dtheta = 4.0 * PI / SAMPLES as f64;
    let (mut excess, mut low, mut high, mut excess_mean) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for (_, l) in samples {
        excess += (torque(l) - torque_mean) * dtheta;
        low = low.min(excess);
        high = high.max(excess);
        excess_mean += excess / SAMPLES as f64;
    }
    let energy_swing = high - low;
    // The flywheel: J ω² δ = ΔE, J the crank's inertia about its axis plus the rod's and
    // piston's mean reduced inertia.
    let total = energy_swing / (DELTA_TARGET * m.omega * m.omega);
    let crank_inertia = total - design.reduced;
    let c_load = torque_mean / m.omega;
    let e_cw = m.e_cw;
    // The run starts at the firing TDC at the speed the steady engine has there: the kinetic
    // energy ½ J ω² differs from its cycle mean by the excess work done since, E(0) − Ē = −Ē,
    // so ω(0) ≈ ω₀ (1 − Ē/(J ω₀²)); from ω₀ itself the mean speed would start ~60 rpm high and
    // take several J/c = 1.3 s to settle.
    let start = 1.0 - excess_mean / (total * m.omega * m.omega);
    let (rpm_mean, delta, cycles, steps) =
        run_free(&SingleCylinder { j_crank: crank_inertia - CRANK_MASS * e_cw * e_cw, c_load, ..m }, start)?;
    let r = Report {
        rp,
        peak_pressure,
        peak_pressure_at,
        work,
        torque_mean,
        torque_by_hand: work / (4.0 * PI),
        torque_max: largest(samples, torque).0,
        torque_max_at: largest(samples, torque).1,
        torque_min: -largest(samples, |l| -torque(l)).0,
        torque_min_at: largest(samples, |l| -torque(l)).1,
        main_max: largest(samples, |l| l.main[0].hypot(l.main[1])),
        crank_pin_max: largest(samples, |l| l.crank_pin[0].hypot(l.crank_pin[1])),
        piston_pin_max: largest(samples, |l| l.piston_pin[0].hypot(l.piston_pin[1])),
        side_max: largest(samples, |l| l.side.abs()).0,
        open_valves_max: samples
            .iter()
            .filter(|(psi, _)| psi.abs() >= PI)
            .map(|(_, l)| [l.main, l.crank_pin, l.piston_pin].iter().map(|f| f[0].hypot(f[1])).fold(0.0, f64::max))
            .fold(0.0, f64::max),
        torque_error,
        load_error,
        shaking,
        energy_swing,
        crank_inertia,
        reduced: design.reduced,
        c_load,
        rpm_mean,
        delta,
        cycles,
        steps,
    };
    if print {
        print_report(&m, &r);
        plot(&m, samples, &loci)?;
    }
    Ok(r)
}

/// The designer's pictures, in target/showcase: pressure and torque over the cycle, the bearing
/// loads, and the shaking force's locus for each balance.
fn plot(m: &SingleCylinder, samples: &[(f64, Loads)], loci: &[(f64, Vec<(f64, f64)>)]) -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::path::Path::new("target/showcase");
    std::fs::create_dir_all(dir)?;
    // The samples in the order of ψ from −360° (they start at the firing TDC).
    let mut by_angle: Vec<(f64, Loads)> = samples.to_vec();
    by_angle.sort_by(|a, b| a.0.total_cmp(&b.0));
    let deg = |psi: f64| psi.to_degrees();
    let bar = |psi: f64| pressure(m, psi, volume(m, kinematics(m, psi, 1.0).piston[1])) / 1e5;
    mbd::Plot::new("Single-cylinder engine at 2500 rpm: cylinder pressure and the torque on the load over the cycle")
        .labels("crank angle from the firing TDC (deg)", "p (bar), torque (N·m / 4)")
        .series("cylinder pressure (bar)", by_angle.iter().map(|(psi, _)| (deg(*psi), bar(*psi))))
        .series("torque on the load (N·m / 4)", by_angle.iter().map(|(psi, l)| (deg(*psi), -l.torque / 4.0)))
        .write_svg(dir.join("engine_cycle.svg"))?;
    let size = |f: [f64; 2]| f[0].hypot(f[1]) / 1e3;
    mbd::Plot::new("Single-cylinder engine at 2500 rpm: bearing loads over the cycle (half balance)")
        .labels("crank angle from the firing TDC (deg)", "load (kN)")
        .series("main bearing", by_angle.iter().map(|(psi, l)| (deg(*psi), size(l.main))))
        .series("crank pin", by_angle.iter().map(|(psi, l)| (deg(*psi), size(l.crank_pin))))
        .series("piston pin", by_angle.iter().map(|(psi, l)| (deg(*psi), size(l.piston_pin))))
        .write_svg(dir.join("engine_loads.svg"))?;
    let mut shaking = mbd::Plot::new("Shaking force on the engine's mounts over the cycle, by counterweight")
        .labels("across the cylinder (N)", "along the cylinder (N)");
    for (balance, locus) in loci {
        let mut closed = locus.clone();
        closed.extend(locus.first().copied());
        shaking = shaking.series(format!("balancing {:.0} % of the reciprocating mass", 100.0 * balance), closed);
    }
    shaking.write_svg(dir.join("engine_shaking.svg"))?;
    println!("plots → target/showcase/engine_cycle.svg, engine_loads.svg, engine_shaking.svg");
    Ok(())
}

/// The free engine braked by its generator, from the driven state at the firing TDC with its
/// velocities scaled by `start`, for `CYCLES` cycles: the mean speed (rpm) and the coefficient
/// of speed fluctuation over the last, the cycles and the steps.
fn run_free(driven: &SingleCylinder, start: f64) -> Result<(f64, f64, usize, usize), Box<dyn std::error::Error>> {
    const CYCLES: usize = 60;
    let d = driven;
    let m = Running {
        omega: d.omega,
        c_load: d.c_load,
        r: d.r,
        l: d.l,
        a_rod: d.a_rod,
        e_cw: d.e_cw,
        j_crank: d.j_crank,
        bore: d.bore,
        cr: d.cr,
        p_atm: d.p_atm,
        n_poly: d.n_poly,
        rp: d.rp,
        wiebe_a: d.wiebe_a,
        burn_start: d.burn_start,
        burn: d.burn,
        evo: d.evo,
    };
    let mut q = driven.initial_positions();
    let mut ws = SingleCylinder::workspace();
    KinematicSolver::default().assemble(driven, &mut ws, &mut q, 0.0)?;
    let mut v = [0.0; SingleCylinder::NV];
    KinematicSolver::default().solve_velocity(driven, &mut ws, &q, 0.0, &mut v)?;
    // One degree of freedom: every velocity is the crank speed's multiple.
    v.iter_mut().for_each(|x| *x *= start);
    let period = 4.0 * PI / m.omega;
    let per_cycle = 1440;
    let times: Vec<f64> = (0..=CYCLES * per_cycle).map(|k| period * k as f64 / per_cycle as f64).collect();
    // The defaults a user starts with: `Auto` (DOPRI5 at rtol 1e-8, BDF where the model turns
    // stiff) and the simulation's options (projection onto the constraints).
    let mut integrator = Auto::default();
    let mut speeds = Vec::with_capacity(times.len());
    let statistics = Simulation::new(&m, &mut integrator)
        .start(0.0, &q, &v)
        .times(&times)
        .run(&mut Running::workspace(), |s| speeds.push(Running::CRANK.omega(&s.point.v)))?;
    let last = &speeds[speeds.len() - per_cycle..];
    let (lo, hi) = last.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &w| (a.min(w), b.max(w)));
    let mean = last.iter().sum::<f64>() / per_cycle as f64;
    Ok((mean * 30.0 / PI, (hi - lo) / mean, CYCLES, statistics.steps as usize))
}

fn print_report(m: &SingleCylinder, r: &Report) {
    println!("Single-cylinder engine (Nikravesh's project 15.2): GX160 bore and stroke, at {:.0} rpm, full load", m.omega * 30.0 / PI);
    println!(
        "gas: combustion pressure ratio {:.3} for the datasheet's {TORQUE} N·m; peak pressure {:.1} bar at {:.1}° after TDC; cycle work ∮ p dV = {:.2} J",
        r.rp,
        r.peak_pressure / 1e5,
        r.peak_pressure_at,
        r.work
    );
    println!(
        "crank torque: mean {:.4} N·m (by hand ∮ p dV / 4π = {:.4} N·m), largest {:.1} N·m at {:.1}°, least {:.1} N·m at {:.1}°; within {:.1e} N·m of the hand analysis at every sample",
        r.torque_mean, r.torque_by_hand, r.torque_max, r.torque_max_at, r.torque_min, r.torque_min_at, r.torque_error
    );
    println!(
        "loads at the design balance: main bearing up to {:.0} N (at {:.1}°), crank pin {:.0} N (at {:.1}°), piston pin {:.0} N (at {:.1}°), side thrust {:.0} N; at most {:.0} N with the valves open; within {:.1e} N of the hand analysis",
        r.main_max.0, r.main_max.1, r.crank_pin_max.0, r.crank_pin_max.1, r.piston_pin_max.0, r.piston_pin_max.1, r.side_max, r.open_valves_max, r.load_error
    );
    for (balance, along, across) in r.shaking {
        println!(
            "shaking force, counterweight for {:.0} % of the reciprocating mass: {along:.0} N along the cylinder, {across:.0} N across",
            100.0 * balance
        );
    }
    println!(
        "flywheel for δ = {DELTA_TARGET}: energy swing {:.1} J → J = {:.4} kg·m² about the crank's axis, the rod and piston's mean share {:.2e} of it, the crank's own {:.4}; generator c = {:.5} N·m·s",
        r.energy_swing,
        r.crank_inertia + r.reduced,
        r.reduced,
        r.crank_inertia,
        r.c_load
    );
    println!(
        "free run (`Auto`), {} cycles ({} steps), the last: mean {:.1} rpm, speed fluctuation δ = {:.5} (target {DELTA_TARGET})",
        r.cycles, r.steps, r.rpm_mean, r.delta
    );
    for (what, source) in SOURCES {
        println!("  {what}: {source}");
    }
}

/// One cycle (two turns) at constant speed, for the showcase's animation: 96 frames.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let base = SingleCylinder::default();
    let m = SingleCylinder { e_cw: counterweight(&base, BALANCE), ..base };
    let solver = KinematicSolver::default();
    let mut q = m.initial_positions();
    let mut ws = SingleCylinder::workspace();
    solver.assemble(&m, &mut ws, &mut q, 0.0)?;
    let period = 4.0 * PI / m.omega;
    let mut animation =
        mbd::Animation::new::<SingleCylinder>(&m.params()).title("Single-cylinder engine: one four-stroke cycle at 2500 rpm");
    solver.sweep(&m, &mut ws, &mut q, (0..=96).map(|k| period * k as f64 / 96.0), |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("engine: {e}");
        std::process::exit(1);
    }
}

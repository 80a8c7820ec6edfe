//! Nikravesh's project 15.5, a full-suspension mountain bike, posed as a frame designer asks it:
//! how far does the rear suspension travel over a bump and what does the shock carry; how much
//! does the rear bob when the rider pedals seated up a climb; and how does the main pivot's
//! height (its anti-squat) change the bob?
//!
//! The model (planar, in the side view, x forward along the trail and y normal to it; SI units;
//! every number's source in `SOURCES`): a single-pivot 29er. The frame carries the rider as two
//! masses held rigidly (the head, arms and trunk on the saddle; the legs at the bottom bracket);
//! the rear wheel with the swingarm (the rear unsprung mass, at the axle) turns about the main
//! pivot on the frame against a coil-over shock; the front wheel with the fork's lowers slides
//! along the steering axis against the fork's spring and damper. Both tyres are point followers
//! on the trail's profile, a bump of 10 cm. Pedalling pulls the chain's top run between the
//! chainring and the cog; the rear wheel, its inertia neglected, turns that into the drive at the
//! ground, carried to the swingarm at the axle, and the chain's pull on the chainring acts on the
//! frame. The crank torque has two peaks a revolution, one per leg.
//!
//! **The checks** (each written by hand from the model's data, not from the generated equations):
//!
//! - the rest states' shock force, with the rider sitting and with the rider pedalling at the
//!   climb's mean torque, against the free bodies by hand: the whole bike's moment balance gives
//!   the rear tyre's load, the swingarm's moment balance about the main pivot the shock's force;
//! - the bike's speed (its centre of mass's) pedalling, against its closed form: along the trail
//!   only the drive and the weight act;
//! - the bob's mean against the rest state pedalling at the mean torque (the first check's);
//! - the bump against the energy balance by hand: the kinetic and potential energy (gravity,
//!   shock and fork springs) change by the tyres' work less the dampers' dissipation, each
//!   integrated over the samples from its element's law written by hand.
//!
//! Run: `cargo run --release --example mountain_bike`
use mbd::prelude::*;

mechanism! {
    /// A single-pivot full-suspension mountain bike with a seated rider (Nikravesh's project
    /// 15.5): the frame with the rider's two masses, the rear wheel on the swingarm, the front
    /// wheel on the fork; coil-over shock, fork spring and damper, two tyres, the chain's pull.
    pub MountainBike {
        // pivot_x, pivot_y: the main pivot from the rear contact patch (m); k_shock, c_shock:
        // the shock (N/m, N·s/m), eye to eye 210 mm, fully extended at the design position;
        // k_fork, c_fork: the fork (N/m, N·s/m); slope: the trail's angle (rad); tau_mean,
        // ripple, cadence: the crank torque τ (1 − ripple cos 2ωt) (N·m, rad/s); the chainring's
        // and the cog's pitch radii (m); the bump's height, start and length along the trail (m);
        // hold_x: where `hold` keeps the frame for the statics (m).
        params {
            pivot_x: 0.48, pivot_y: 0.40, k_shock: 8.0e4, c_shock: 3000.0, k_fork: 1.0e4, c_fork: 400.0,
            radius: 0.371, k_tyre: 1.2e5, c_tyre: 100.0, g: 9.81, slope: 0.0,
            tau_mean: 0.0, ripple: 0.0, cadence: 80.0 * PI / 30.0, r_ring: 0.06478, r_cog: 0.08497,
            bump_height: 0.1, bump_x: 2.0, bump_length: 0.4, hold_x: 0.6
        }
        gravity [-g * sin(slope), -g * cos(slope)];
        // The frame (with the cockpit, the drivetrain and the fork's crown and stanchions), the
        // rider's head, arms and trunk, and legs; the rear and front unsprung masses at the axles.
        body frame { mass: 8.0, inertia: 0.5, at: [0.6, 0.6, 0.0] }
        body torso { mass: 50.9, inertia: 2.0, at: [0.47, 1.26, 0.0] }
        body legs { mass: 24.1, inertia: 1.2, at: [0.35, 0.75, 0.0] }
        body rear { mass: 3.5, inertia: 0.15, at: [0.0, 0.371, 0.0] }
        body front { mass: 3.2, inertia: 0.12, at: [1.22, 0.371, 0.0] }
        // The rider sits on the saddle (0.257, 1.049) with the feet at the bottom bracket
        // (0.434, 0.341): both held rigidly to the frame.
        rigid saddle: frame[-0.343, 0.449] ~ torso[-0.213, -0.211];
        rigid pedals: frame[-0.166, -0.259] ~ legs[0.084, -0.409];
        // The swingarm about the main pivot; the shock from the swingarm's eye 0.2 m above the
        // pivot (and 2 cm behind it) forward to the frame's.
        revolute main_pivot: frame[pivot_x - 0.6, pivot_y - 0.6] ~ rear[pivot_x, pivot_y - 0.371];
        point rear.shock_eye = [pivot_x - 0.02, pivot_y + 0.2 - 0.371];
        point frame.shock_mount = [pivot_x + 0.19 - 0.6, pivot_y + 0.2 - 0.6];
        spring shock: rear.shock_eye ~ frame.shock_mount { k: k_shock, length: 0.21, c: c_shock };
        // The fork along the steering axis (head angle 65°, offset 44 mm): the axis 44 mm behind
        // the axle, its point 0.55 m up it at full extension on the frame (0.9477, 0.8509).
        point front.axis = [-0.039878, -0.018595];
        point frame.head = [0.347681, 0.250876];
        translational fork: frame.head along [-0.42262, 0.90631] ~ front.axis along [-0.42262, 0.90631];
        spring fork_spring: front.axis ~ frame.head { k: k_fork, length: 0.55, c: c_fork };
        // The trail: flat but for a bump of cos² shape.
        tyre rear_tyre: rear[0.0, 0.0] ~ ground[0.0, 0.0] {
            radius: radius, k: k_tyre, c: c_tyre,
            road: bump_height * sin(PI * clamp(rear.x - bump_x, 0.0, bump_length) / bump_length)^2
        };
        tyre front_tyre: front[0.0, 0.0] ~ ground[0.0, 0.0] {
            radius: radius, k: k_tyre, c: c_tyre,
            road: bump_height * sin(PI * clamp(front.x - bump_x, 0.0, bump_length) / bump_length)^2
        };
        // Pedalling: the chain's tension from the crank torque; its top run from the cog's top
        // (above the rear axle) to the chainring's (above the bottom bracket: within a mm of the
        // true tangent, the run sloping 6.6°). On the swingarm at the axle: the chain's pull and
        // the drive at the ground, T r_cog / radius; on the frame at the chainring's top: the
        // chain's pull back.
        let tension = tau_mean * (1.0 - ripple * cos(2.0 * cadence * t)) / r_ring;
        let run_x = frame.x - 0.166 * cos(frame.phi) + (0.259 - r_ring) * sin(frame.phi) - rear.x;
        let run_y = frame.y - 0.166 * sin(frame.phi) - (0.259 - r_ring) * cos(frame.phi) - rear.y - r_cog;
        let run = sqrt(run_x^2 + run_y^2);
        force chain: rear[0.0, 0.0] = [tension * (run_x / run + r_cog / radius), tension * run_y / run];
        point frame.ring_top = [-0.166, r_ring - 0.259];
        force chain_back: frame.ring_top = [-tension * run_x / run, -tension * run_y / run];
        // Holds the frame along the trail for the statics (the scene `Riding` lets it go).
        drive hold: frame.x = hold_x;
        scene Riding without hold;
    }
}

/// Where the numbers come from (assumptions are marked so).
pub const SOURCES: [(&str, &str); 12] = [
    (
        "wheels: radius 0.371 m (a 29 × 2.4 in tyre)",
        "ISO 5775 (ETRTO): a 29-inch wheel's bead seat diameter 622 mm; the tyre's 60 mm section height an assumption",
    ),
    (
        "geometry: wheelbase 1.22 m, chainstay 434 mm, bottom bracket 30 mm below the axles, head angle 65°, fork offset 44 mm",
        "assumption: a trail 29er's geometry, size M",
    ),
    (
        "main pivot 48 cm ahead of the rear axle, at 0.37, 0.40 or 0.44 m; shock 210 × 55 mm, its eyes 0.2 m above the pivot",
        "assumption: the shock a metric size (210 mm eye to eye, 55 mm stroke); the pivot heights span the anti-squat a designer weighs",
    ),
    (
        "shock rate set for 30 % sag seated, damping 3 000 N·s/m; fork 10 kN/m over 140 mm, 400 N·s/m",
        "assumption: 25–30 % sag is the shock makers' setup advice; the damping about 0.3 of critical at the wheel",
    ),
    (
        "rider 75 kg: head, arms and trunk 50.9 kg, legs 24.1 kg",
        "Winter, Biomechanics and Motor Control of Human Movement (Dempster's segment data): head, arms and trunk 0.678 of the body's mass; the 75 kg rider an assumption",
    ),
    (
        "the rider's two masses' centres (0.47, 1.26) and (0.35, 0.75) m, inertias 2.0 and 1.2 kg·m²",
        "assumption: seated, the trunk leaning 45° forward from the saddle",
    ),
    ("frame, cockpit and drivetrain 8.0 kg; rear unsprung 3.5 kg, front 3.2 kg", "assumption: a 14.7 kg bike"),
    ("tyre: 120 kN/m, 100 N·s/m", "assumption: a 2.4 in tyre at about 1.6 bar"),
    (
        "chainring 32 teeth, cog 42 teeth: pitch radii 64.8 and 85.0 mm",
        "ISO 606: a bicycle chain's pitch of 12.7 mm; r = p / (2 sin(π/N)); the gear an assumption (a low gear for a climb)",
    ),
    (
        "pedalling at 80 rpm, the crank torque τ (1 − cos 2ωt): two peaks a revolution, zero at the dead centres",
        "assumption: the torque's shape; its mean drives the bike up the grade at the gear's speed",
    ),
    ("the climb: a 10 % grade", "assumption"),
    ("the bump: 10 cm high, 0.4 m long, cos² shape, coasting at 5 m/s (18 km/h)", "assumption: a root or a step on a trail"),
];

/// The shock's length fully extended and its stroke (m), and the fraction of the stroke a rider
/// sets as sag; the fork's spring length fully extended (m); the axles' height at the design
/// position (m), the rear body's origin. As in the mechanism.
const EYE_TO_EYE: f64 = 0.21;
const STROKE: f64 = 0.055;
const FORK: f64 = 0.55;
const AXLE: f64 = 0.371;
const SAG: f64 = 0.3;
/// The grade of the climb (rise over run), and the speed over the bump (m/s).
const GRADE: f64 = 0.1;
const BUMP_SPEED: f64 = 5.0;
/// The main pivot's heights a designer compares (m above the trail; 48 cm ahead of the axle).
pub const PIVOTS: [f64; 3] = [0.37, 0.40, 0.44];

type Q = [f64; MountainBike::NQ];

/// The bodies, the rider's two among them, with their masses (kg) and inertias (kg·m²) as in
/// the mechanism.
const BODIES: [(mbd::PlanarBody<{ MountainBike::NQ }>, f64, f64); 5] = [
    (MountainBike::FRAME, 8.0, 0.5),
    (MountainBike::TORSO, 50.9, 2.0),
    (MountainBike::LEGS, 24.1, 1.2),
    (MountainBike::REAR, 3.5, 0.15),
    (MountainBike::FRONT, 3.2, 0.12),
];

fn total_mass() -> f64 {
    BODIES.iter().map(|b| b.1).sum()
}

/// The planar cross product a × b.
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn minus(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn at(p: mbd::nalgebra::Point2<f64>) -> [f64; 2] {
    [p.x, p.y]
}

/// The crank torque's mean (N·m) that drives the whole bike up `grade` at a steady speed: the
/// drive at the ground, τ r_cog / (r_ring R), equals the weight's component down the slope.
fn climbing_torque(m: &MountainBike, grade: f64) -> f64 {
    total_mass() * m.g * grade.atan().sin() * m.radius * m.r_ring / m.r_cog
}

/// The trail's height at x (m): the mechanism's bump, by hand.
fn trail(m: &MountainBike, x: f64) -> f64 {
    let s = (x - m.bump_x).clamp(0.0, m.bump_length);
    m.bump_height * (PI * s / m.bump_length).sin().powi(2)
}

/// The chain by hand at (q, t): its tension (N) and the unit vector of its top run, from the
/// cog's top to the chainring's.
fn chain(m: &MountainBike, q: &Q, t: f64) -> (f64, [f64; 2]) {
    let tension = m.tau_mean * (1.0 - m.ripple * (2.0 * m.cadence * t).cos()) / m.r_ring;
    let ring = at(m.frame_ring_top().position(q));
    let axle = at(MountainBike::REAR.position(q));
    let run = minus(ring, [axle[0], axle[1] + m.r_cog]);
    let length = run[0].hypot(run[1]);
    (tension, [run[0] / length, run[1] / length])
}

/// The rest state's free bodies by hand, at positions q and time t: (the rear tyre's load from
/// the whole bike's balance, the shock's force from the swingarm's), in N. Unknowns: the tyres' loads N_r, N_f (normal to the trail, at the axles)
/// and the hold's H (along it, on the frame). The whole bike: H = −F − m g_x along the trail;
/// moments about the front axle give N_r. The swingarm about the main pivot: the tyre, its
/// weight, the drive F and the chain's pull T ê at the axle, the shock's push at its eye.
fn rest_by_hand(m: &MountainBike, q: &Q, t: f64) -> (f64, f64) {
    let gravity = [-m.g * m.slope.sin(), -m.g * m.slope.cos()];
    let (tension, e) = chain(m, q, t);
    let drive = tension * m.r_cog / m.radius;
    let hold = -drive - total_mass() * gravity[0];
    let (axle, front) = (at(MountainBike::REAR.position(q)), at(MountainBike::FRONT.position(q)));
    let ring = at(m.frame_ring_top().position(q));
    let frame = at(MountainBike::FRAME.position(q));
    let mut moment: f64 = BODIES.iter().map(|(b, mass, _)| cross(minus(at(b.position(q)), front), gravity.map(|g| mass * g))).sum();
    moment += cross(minus(axle, front), [drive + tension * e[0], tension * e[1]]);
    moment += cross(minus(ring, front), [-tension * e[0], -tension * e[1]]);
    moment += cross(minus(frame, front), [hold, 0.0]);
    // (axle − front) × (0, N_r) = (axle − front).x N_r
    let rear_load = -moment / (axle[0] - front[0]);
    // The swingarm about the pivot.
    let pivot = at(MountainBike::REAR.point([m.pivot_x, m.pivot_y - AXLE]).position(q));
    let (eye, mount) = (at(m.rear_shock_eye().position(q)), at(m.frame_shock_mount().position(q)));
    let along = minus(eye, mount);
    let length = along[0].hypot(along[1]);
    let push = [along[0] / length, along[1] / length];
    let mass = BODIES[3].1;
    let at_axle = [drive + tension * e[0] + mass * gravity[0], rear_load + tension * e[1] + mass * gravity[1]];
    let shock = -cross(minus(axle, pivot), at_axle) / cross(minus(eye, pivot), push);
    (rear_load, shock)
}

/// The shock's length (m) at q.
fn shock_length(m: &MountainBike, q: &Q) -> f64 {
    let along = minus(at(m.rear_shock_eye().position(q)), at(m.frame_shock_mount().position(q)));
    along[0].hypot(along[1])
}

/// One pivot height's answers. Lengths in mm, forces in N.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Pivot {
    pub height: f64,
    /// The shock's rate set for 30 % sag (N/m), the leverage ratio at sag (wheel travel per shock
    /// stroke) and the anti-squat at sag by the drive line's construction (%).
    pub k_shock: f64,
    pub leverage: f64,
    pub anti_squat: f64,
    /// The shock's sag (mm): seated at rest on the flat, and pedalling up the climb at its mean
    /// torque (what the bob oscillates about); the squat (mm of shock stroke), the latter less
    /// the sag at rest on the flat under the climb's normal weight.
    pub sag: f64,
    pub sag_pedalling: f64,
    pub squat: f64,
    /// The largest difference (N) of the shock's force and the rear tyre's load, each by its
    /// element's law, from the free bodies by hand, over the three rest states.
    pub rest_error: f64,
    /// Pedalling: the shock stroke's bob, peak to peak, over the last 1.5 s of 4 s (mm), and its
    /// mean (mm of sag), against the rest state pedalling at the mean torque.
    pub bob: f64,
    pub bob_mean: f64,
    /// The bike's speed (its centre of mass's) swing over a pedal stroke, peak to peak, g sin α / ω
    /// (m/s), and the largest difference of the simulated speed from that closed form (m/s).
    pub speed_swing: f64,
    pub speed_error: f64,
}

/// What the run measured.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone)]
pub struct Report {
    /// The climb's mean crank torque (N·m), power (W) and speed (m/s).
    pub torque: f64,
    pub power: f64,
    pub speed: f64,
    pub pivots: Vec<Pivot>,
    /// Over the bump at 5 m/s (the middle pivot): the shock's largest and least stroke (mm; 0 is
    /// fully extended) and its largest force (N), the fork's largest stroke (mm), the time each
    /// wheel spends off the ground (s), and the energy balance's largest error relative to the
    /// kinetic energy.
    pub bump_stroke: f64,
    pub least_stroke: f64,
    pub bump_force: f64,
    pub fork_stroke: f64,
    pub rear_airborne: f64,
    pub front_airborne: f64,
    pub energy_error: f64,
}

/// The bike with its main pivot at `height`, the shock's rate set by hand for 30 % sag seated at
/// rest on the flat: the shock's force at the design position by the free bodies, over the sag's
/// stroke (the sag the statics then finds differs by what the geometry turns meanwhile).
fn bike(height: f64) -> MountainBike {
    let mut m = MountainBike { pivot_y: height, ..MountainBike::default() };
    let (_, shock) = rest_by_hand(&m, &m.initial_positions(), 0.0);
    m.k_shock = shock / (SAG * STROKE);
    m
}

/// The rest state of `m` from its design position (the frame held along the trail), and the
/// larger difference (N) of the shock's force and the rear tyre's load, each by its element's
/// law, from the free bodies by hand.
fn rest(m: &MountainBike) -> Result<(Q, f64), Box<dyn std::error::Error>> {
    let mut q = m.initial_positions();
    mbd::StaticSolver::default().solve(m, &mut MountainBike::workspace(), &mut q, 0.0, &mut [0.0; MountainBike::NC])?;
    let (rear_load, shock) = rest_by_hand(m, &q, 0.0);
    let spring = m.k_shock * (EYE_TO_EYE - shock_length(m, &q));
    let tyre = m.k_tyre * (m.radius + trail(m, MountainBike::REAR.x(&q)) - MountainBike::REAR.y(&q));
    Ok((q, (shock - spring).abs().max((rear_load - tyre).abs())))
}

/// The leverage ratio at q (the rear axle's travel normal to the trail per shock stroke), and the
/// anti-squat by the drive line's construction (%): the line from the rear contact patch through
/// where the chain's top run crosses the line from the axle through the main pivot (the wheel's
/// instant centre on the frame), its height under the front axle over the centre of mass's.
fn leverage_and_anti_squat(m: &MountainBike, q: &Q) -> (f64, f64) {
    let axle = at(MountainBike::REAR.position(q));
    let pivot = at(MountainBike::REAR.point([m.pivot_x, m.pivot_y - AXLE]).position(q));
    let (eye, mount) = (at(m.rear_shock_eye().position(q)), at(m.frame_shock_mount().position(q)));
    let along = minus(eye, mount);
    let arm = cross(minus(eye, pivot), along) / along[0].hypot(along[1]);
    let leverage = (axle[0] - pivot[0]).abs() / arm.abs();
    let (_, e) = chain(&MountainBike { tau_mean: 1.0, ..*m }, q, 0.0);
    let cog = [axle[0], axle[1] + m.r_cog];
    let arm_line = minus(pivot, axle);
    // cog + a e = axle + b arm_line
    let a = cross(minus(axle, cog), arm_line) / cross(e, arm_line);
    let crossing = [cog[0] + a * e[0], cog[1] + a * e[1]];
    let contact = [axle[0], 0.0];
    let front = MountainBike::FRONT.x(q);
    let height = crossing[1] / (crossing[0] - contact[0]) * (front - contact[0]);
    let centre: f64 = BODIES.iter().map(|(b, mass, _)| mass * b.y(q)).sum::<f64>() / total_mass();
    (leverage, 100.0 * height / centre)
}

/// A state moving at `speed` along the trail: every body's velocity.
fn rolling(speed: f64) -> [f64; MountainBike::NV] {
    let mut v = [0.0; MountainBike::NV];
    for (body, _, _) in BODIES {
        v[3 * body.index] = speed;
    }
    v
}

/// What the climb records at each sample, for the plot: (t, shock stroke in mm).
type Stroke = Vec<(f64, f64)>;

/// One pivot height on the climb: its answers, and the trace when `trace`.
fn climb(height: f64, trace: bool) -> Result<(Pivot, Stroke), Box<dyn std::error::Error>> {
    // A smooth climb: no bump.
    let mut m = MountainBike { bump_height: 0.0, ..bike(height) };
    let (flat, flat_error) = rest(&m)?;
    let sag = 1e3 * (EYE_TO_EYE - shock_length(&m, &flat));
    let (leverage, anti_squat) = leverage_and_anti_squat(&m, &flat);
    // Up the climb at the mean torque, the drive balancing the weight's pull down the slope: the
    // hold carries nothing. The weight's pull acts at the centre of mass, as the inertial force
    // of an acceleration at g sin α on the flat would: the squat is this state's sag less the
    // sag at rest on the flat under the climb's normal weight, g cos α.
    let slope = GRADE.atan();
    let (unloaded, unloaded_error) = rest(&MountainBike { g: m.g * slope.cos(), ..m })?;
    m.slope = slope;
    m.tau_mean = climbing_torque(&m, GRADE);
    let (pedalling, pedalling_error) = rest(&m)?;
    let sag_pedalling = 1e3 * (EYE_TO_EYE - shock_length(&m, &pedalling));
    // Let go with the torque's two peaks a revolution, at the gear's speed.
    m.ripple = 1.0;
    let speed = m.cadence * m.r_cog.recip() * m.r_ring * m.radius;
    let riding = Riding::from_params(m.params());
    let times: Vec<f64> = (1..=800).map(|k| 0.005 * k as f64).collect();
    let mut strokes = Vec::new();
    // Along the trail only the drive F̄ (1 − cos 2ωt) and the weight's pull M g sin α = F̄ act on
    // the whole bike: its centre of mass moves at v₀ − g sin α / (2ω) sin 2ωt.
    let swing = m.g * slope.sin() / m.cadence;
    let mut speed_error = 0.0f64;
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-8).with_atol(1e-11));
    Simulation::new(&riding, &mut dopri).start(0.0, &pedalling, &rolling(speed)).times(&times).run(&mut Riding::workspace(), |s| {
        let (t, q) = (s.point.t, &s.point.q);
        strokes.push((t, 1e3 * (EYE_TO_EYE - shock_length(&m, q))));
        let momentum: f64 = BODIES.iter().map(|(b, mass, _)| mass * b.velocity(&s.point.v).x).sum();
        let closed_form = speed - swing / 2.0 * (2.0 * m.cadence * t).sin();
        speed_error = speed_error.max((momentum / total_mass() - closed_form).abs());
    })?;
    // The last 1.5 s: four pedal strokes, each phase once.
    let late: Vec<f64> = strokes.iter().filter(|p| p.0 > 2.5).map(|p| p.1).collect();
    let (low, high) = late.iter().fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    let p = Pivot {
        height,
        k_shock: m.k_shock,
        leverage,
        anti_squat,
        sag,
        squat: 1e3 * (shock_length(&m, &unloaded) - shock_length(&m, &pedalling)),
        sag_pedalling,
        rest_error: flat_error.max(unloaded_error).max(pedalling_error),
        bob: high - low,
        bob_mean: late.iter().sum::<f64>() / late.len() as f64,
        speed_swing: swing,
        speed_error,
    };
    Ok((p, if trace { strokes } else { Vec::new() }))
}

/// What the bump run records at each sample, for the answers and the plots: (t, shock stroke,
/// fork stroke in mm).
type Trace = Vec<(f64, f64, f64)>;

/// The energy by hand at a sample: kinetic, gravity's and the two springs' (J); the power the
/// tyres put in less what the dampers dissipate (W), and each tyre's power apart (rear, front),
/// each from its element's law. Coasting: the chain, with no torque, does no work.
fn energy_by_hand(m: &MountainBike, q: &Q, v: &Q) -> (f64, f64, [f64; 2]) {
    let gravity = [-m.g * m.slope.sin(), -m.g * m.slope.cos()];
    let mut energy = 0.0;
    for (body, mass, inertia) in BODIES {
        let u = body.velocity(v);
        energy += 0.5 * mass * (u.x * u.x + u.y * u.y) + 0.5 * inertia * body.omega(v).powi(2);
        energy -= mass * (gravity[0] * body.x(q) + gravity[1] * body.y(q));
    }
    // The shock and the fork: lengths and their rates from the points' velocities.
    let spring = |a: [f64; 2], b: [f64; 2], va: [f64; 2], vb: [f64; 2], k: f64, free: f64, c: f64| {
        let d = minus(a, b);
        let l = d[0].hypot(d[1]);
        let rate = (d[0] * (va[0] - vb[0]) + d[1] * (va[1] - vb[1])) / l;
        (0.5 * k * (l - free).powi(2), c * rate * rate)
    };
    let vel = |p: mbd::nalgebra::Vector2<f64>| [p.x, p.y];
    let (eye, mount) = (m.rear_shock_eye(), m.frame_shock_mount());
    let shock = spring(
        at(eye.position(q)),
        at(mount.position(q)),
        vel(eye.velocity(q, v)),
        vel(mount.velocity(q, v)),
        m.k_shock,
        EYE_TO_EYE,
        m.c_shock,
    );
    let (axis, head) = (m.front_axis(), m.frame_head());
    let fork =
        spring(at(axis.position(q)), at(head.position(q)), vel(axis.velocity(q, v)), vel(head.velocity(q, v)), m.k_fork, FORK, m.c_fork);
    energy += shock.0 + fork.0;
    // The tyres: compression δ = R + trail(x) − y, its rate from the trail's slope.
    let slope = |x: f64| {
        let s = x - m.bump_x;
        if s > 0.0 && s < m.bump_length {
            m.bump_height * PI / m.bump_length * (2.0 * PI * s / m.bump_length).sin()
        } else {
            0.0
        }
    };
    let tyres = [MountainBike::REAR, MountainBike::FRONT].map(|body| {
        let (x, y, u) = (body.x(q), body.y(q), body.velocity(v));
        let (delta, rate) = (m.radius + trail(m, x) - y, slope(x) * u.x - u.y);
        // The force −f ∂δ/∂q (along the profile's normal), its power −f δ̇.
        if delta > 0.0 {
            -(m.k_tyre * delta + m.c_tyre * rate).max(0.0) * rate
        } else {
            0.0
        }
    });
    (energy, tyres[0] + tyres[1] - shock.1 - fork.1, tyres)
}

/// Over the bump at 5 m/s on the flat (the middle pivot), coasting: (the shock's largest and
/// least stroke and its largest force, the fork's largest stroke, the rear and front wheels'
/// times off the ground, the energy balance's error over the kinetic energy), and the trace.
fn bump() -> Result<([f64; 7], Trace), Box<dyn std::error::Error>> {
    let m = bike(PIVOTS[1]);
    assert!(m.tau_mean == 0.0, "coasting: the energy balance leaves the chain out");
    let (q0, _) = rest(&m)?;
    let riding = Riding::from_params(m.params());
    let times: Vec<f64> = (1..=1000).map(|k| 0.001 * k as f64).collect();
    let mut trace = Trace::new();
    let (mut stroke, mut force, mut fork, mut extension) = (0.0f64, 0.0f64, 0.0f64, f64::MAX);
    let (mut airborne, mut last) = ([0.0; 2], 0.0);
    let (e0, p0, _) = energy_by_hand(&m, &q0, &rolling(BUMP_SPEED));
    let kinetic = 0.5 * total_mass() * BUMP_SPEED * BUMP_SPEED;
    let (mut work, mut power_before, mut error) = (0.0, p0, 0.0f64);
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-10).with_atol(1e-12));
    Simulation::new(&riding, &mut dopri).start(0.0, &q0, &rolling(BUMP_SPEED)).times(&times).run(&mut Riding::workspace(), |s| {
        let (t, q, v) = (s.point.t, &s.point.q, &s.point.v);
        let (energy, power, tyres) = energy_by_hand(&m, q, v);
        // Every sample, the located switches' too, in time order: the trapezoid over each. A
        // tyre's switch is delivered on its new side, where a touching tyre's force jumps to
        // c δ̇: the interval before it ends on the old side, without it.
        let switched = match s.event {
            Some(mbd::EventHit::Switch(k)) => ["rear_tyre", "front_tyre"].iter().position(|&name| name == Riding::SWITCH_NAMES[k]),
            _ => None,
        };
        let before_switch = switched.map_or(power, |k| power - tyres[k]);
        work += 0.5 * (before_switch + power_before) * (t - last);
        power_before = power;
        error = error.max((energy - e0 - work).abs() / kinetic);
        for (k, body) in [MountainBike::REAR, MountainBike::FRONT].into_iter().enumerate() {
            if body.y(q) > m.radius + trail(&m, body.x(q)) {
                airborne[k] += t - last;
            }
        }
        last = t;
        let (eye, mount) = (m.rear_shock_eye(), m.frame_shock_mount());
        let along = minus(at(eye.position(q)), at(mount.position(q)));
        let l = along[0].hypot(along[1]);
        let (ve, vm) = (eye.velocity(q, v), mount.velocity(q, v));
        let rate = (along[0] * (ve.x - vm.x) + along[1] * (ve.y - vm.y)) / l;
        stroke = stroke.max(1e3 * (EYE_TO_EYE - l));
        extension = extension.min(1e3 * (EYE_TO_EYE - l));
        force = force.max(m.k_shock * (EYE_TO_EYE - l) - m.c_shock * rate);
        let axis = minus(at(m.front_axis().position(q)), at(m.frame_head().position(q)));
        let f = 1e3 * (FORK - axis[0].hypot(axis[1]));
        fork = fork.max(f);
        if s.event.is_none() {
            trace.push((t, 1e3 * (EYE_TO_EYE - l), f));
        }
    })?;
    Ok(([stroke, extension, force, fork, airborne[0], airborne[1], error], trace))
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let m = MountainBike { slope: GRADE.atan(), ..MountainBike::default() };
    let torque = climbing_torque(&m, GRADE);
    let speed = m.cadence * m.r_ring / m.r_cog * m.radius;
    let mut pivots = Vec::new();
    let mut traces = Vec::new();
    for height in PIVOTS {
        let (p, trace) = climb(height, print)?;
        pivots.push(p);
        traces.push(trace);
    }
    let ([bump_stroke, least_stroke, bump_force, fork_stroke, rear_airborne, front_airborne, energy_error], bump_trace) = bump()?;
    let r = Report {
        torque,
        power: torque * m.cadence,
        speed,
        pivots,
        bump_stroke,
        least_stroke,
        bump_force,
        fork_stroke,
        rear_airborne,
        front_airborne,
        energy_error,
    };
    if print {
        print_report(&r, &traces, &bump_trace)?;
    }
    Ok(r)
}

/// The answers, the checks and the sources, and the designer's plots in target/showcase.
fn print_report(r: &Report, traces: &[Stroke], bump: &Trace) -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "Mountain bike (Nikravesh's project 15.5): seated on a {:.0} % climb at {:.0} rpm, mean crank torque {:.1} N·m, {:.0} W, {:.2} m/s",
        100.0 * GRADE,
        MountainBike::default().cadence * 30.0 / PI,
        r.torque,
        r.power,
        r.speed
    );
    println!(
        "{:<10} {:>9} {:>9} {:>11} {:>9} {:>13} {:>9} {:>9} {:>10}",
        "pivot", "k N/mm", "leverage", "anti-squat", "sag mm", "pedalling mm", "squat mm", "bob mm", "bob mean"
    );
    for p in &r.pivots {
        println!(
            "{:<10} {:>9.1} {:>9.2} {:>10.0}% {:>9.2} {:>13.2} {:>9.2} {:>9.2} {:>10.2}",
            format!("{:.0} mm", 1e3 * p.height),
            1e-3 * p.k_shock,
            p.leverage,
            p.anti_squat,
            p.sag,
            p.sag_pedalling,
            p.squat,
            p.bob,
            p.bob_mean
        );
    }
    let (swing, speed_error) = (r.pivots[0].speed_swing, r.pivots.iter().map(|p| p.speed_error).fold(0.0, f64::max));
    println!(
        "the bike's speed swings {swing:.3} m/s peak to peak with each pedal stroke, for every pivot: within {speed_error:.1e} m/s of the closed form"
    );
    let rest = r.pivots.iter().map(|p| p.rest_error).fold(0.0, f64::max);
    println!("the rest states' shock forces and rear tyre loads within {rest:.1e} N of the free bodies by hand");
    println!(
        "over a 10 cm bump at {BUMP_SPEED} m/s: shock stroke {:.1} mm of {:.0} (least {:.2}), its force {:.0} N; fork stroke {:.1} mm; off the ground: rear {:.1} ms, front {:.1} ms",
        r.bump_stroke,
        1e3 * STROKE,
        r.least_stroke,
        r.bump_force,
        r.fork_stroke,
        1e3 * r.rear_airborne,
        1e3 * r.front_airborne
    );
    println!("the energy balance by hand holds over the bump within {:.1e} of the kinetic energy", r.energy_error);
    for (what, source) in SOURCES {
        println!("  {what}: {source}");
    }
    let dir = std::path::Path::new("target/showcase");
    std::fs::create_dir_all(dir)?;
    let mut plot = mbd::Plot::new("Seated climbing at 80 rpm: the shock's bob").labels("time (s)", "shock stroke (mm)");
    for (p, trace) in r.pivots.iter().zip(traces) {
        plot = plot.series(format!("pivot {:.0} mm, anti-squat {:.0} %", 1e3 * p.height, p.anti_squat), trace.iter().copied());
    }
    plot.write_svg(dir.join("mountain_bike_bob.svg"))?;
    mbd::Plot::new("A 10 cm bump at 5 m/s: suspension strokes")
        .labels("time (s)", "stroke (mm)")
        .series("shock", bump.iter().map(|p| (p.0, p.1)))
        .series("fork", bump.iter().map(|p| (p.0, p.2)))
        .write_svg(dir.join("mountain_bike_bump.svg"))?;
    println!("plots → target/showcase/mountain_bike_bob.svg, mountain_bike_bump.svg");
    Ok(())
}

/// The bump at 5 m/s over 0.8 s, for the showcase's animation: 80 frames.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = bike(PIVOTS[1]);
    let (q0, _) = rest(&m)?;
    let riding = Riding::from_params(m.params());
    let mut animation = mbd::Animation::new::<Riding>(&riding.params()).title("Mountain bike over a 10 cm bump at 5 m/s");
    let times: Vec<f64> = (0..=80).map(|k| 0.01 * k as f64).collect();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-8).with_atol(1e-11));
    Simulation::new(&riding, &mut dopri).start(0.0, &q0, &rolling(BUMP_SPEED)).times(&times).run(&mut Riding::workspace(), |s| {
        if s.event.is_none() {
            animation.frame(s.point.t, &s.point.q)
        }
    })?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("mountain_bike: {e}");
        std::process::exit(1);
    }
}

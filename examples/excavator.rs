//! One declaration, three scenes: an excavator arm (a 20 t class machine's proportions, SI units)
//! whose three hydraulic cylinders are stiff springs (the oil column, k = 2e7 N/m: the arm holds
//! itself — statics), length drivers (the cylinders' strokes prescribed — kinematics and inverse
//! dynamics) or force actuators (the cylinders' forces given — forward dynamics).
//!
//! The mechanism declares springs and drivers, labelled; `scene ExcavatorHeld without ...` leaves
//! the drivers out, `scene ExcavatorDriven without ...` the cylinder springs, and `scene
//! ExcavatorFree ... actuating ...` turns each driver into an actuator along the same cylinder,
//! its force a parameter — no scene repeats the geometry. The held and driven scenes answer one
//! question two independent ways: the statics of the held arm (a trust-region search for the
//! energy minimum) gives its pose and cylinder forces; the driven arm held still at that pose's
//! cylinder lengths needs, by inverse dynamics (the drivers' multipliers), the same forces. The
//! free arm, pushed by the forces inverse dynamics gives while the boom lifts, moves as the
//! driven arm does.
//!
//! A distance driver's row is (|d|² − l²)/(2l), |d| − l to first order, so its multiplier λ is a
//! force in N: the force it exerts on its second point is λ d/l, and the cylinder's tension is −λ.
//!
//! Run: `cargo run --release --example excavator`
use mbd::point_position;
use mbd::prelude::*;

mechanism! {
    /// An excavator arm: boom, stick and bucket on revolute joints, each turned by a hydraulic
    /// cylinder — as a stiff spring whose rest length is its length at the design pose (boom 40°
    /// up, stick 75° and bucket 130° below the horizontal; the boom cylinder also pushes with a
    /// constant 60 kN), or as a driven length.
    pub Excavator {
        params {
            k_cyl: 2.0e7, boom_push: 60000.0, boom_rest: 2.38, stick_rest: 3.04, bucket_rest: 2.63,
            boom_stroke: 2.38, stick_stroke: 3.04, bucket_stroke: 2.63, lift: 0.0
        }
        gravity [0.0, -9.81];
        body boom   { mass: 1800.0, inertia: 4500.0, at: [2.11, 1.77, 0.698] }
        body stick  { mass: 900.0, inertia: 640.0, at: [4.42, 2.76, -1.309] }
        body bucket { mass: 700.0, inertia: 90.0, at: [4.67, 0.39, -2.269] }
        point ground.boom_anchor = [0.9, -0.9];
        point boom.foot = [-2.75, 0.0];
        point boom.tip = [2.75, 0.0];
        point boom.lug = [-0.4, -0.45];
        point boom.stick_base = [0.2, 0.45];
        point stick.pin = [-0.8, 0.0];
        point stick.tip = [2.1, 0.0];
        point stick.lever = [-1.3, 0.3];
        point stick.bucket_base = [-0.3, 0.3];
        point bucket.pin = [-0.45, 0.0];
        point bucket.lug = [-0.55, 0.35];
        revolute ground[0.0, 0.0] ~ boom.foot;
        revolute boom.tip ~ stick.pin;
        revolute stick.tip ~ bucket.pin;
        // The cylinders as the oil column's stiffness ...
        spring boom_cylinder: ground.boom_anchor ~ boom.lug { k: k_cyl, length: boom_rest, force: -boom_push };
        spring stick_cylinder: boom.stick_base ~ stick.lever { k: k_cyl, length: stick_rest };
        spring bucket_cylinder: stick.bucket_base ~ bucket.lug { k: k_cyl, length: bucket_rest };
        // ... or as prescribed strokes (the boom's extends by `lift` per second).
        drive boom_drive: distance(ground.boom_anchor, boom.lug) = boom_stroke + lift * t;
        drive stick_drive: distance(boom.stick_base, stick.lever) = stick_stroke;
        drive bucket_drive: distance(stick.bucket_base, bucket.lug) = bucket_stroke;
        scene ExcavatorHeld without boom_drive, stick_drive, bucket_drive;
        scene ExcavatorDriven without boom_cylinder, stick_cylinder, bucket_cylinder;
        scene ExcavatorFree without boom_cylinder, stick_cylinder, bucket_cylinder
            actuating boom_drive, stick_drive, bucket_drive;
    }
}

/// A cylinder's end: the body's index (`None`: ground) and the point in its frame (m).
type End = (Option<usize>, [f64; 2]);

/// The cylinders' names and end points.
const CYLINDERS: [(&str, End, End); 3] = [
    ("boom", (None, [0.9, -0.9]), (Some(0), [-0.4, -0.45])),
    ("stick", (Some(0), [0.2, 0.45]), (Some(1), [-1.3, 0.3])),
    ("bucket", (Some(1), [-0.3, 0.3]), (Some(2), [-0.55, 0.35])),
];

/// The three cylinder lengths at q (m).
pub fn lengths(q: &[f64; 9]) -> [f64; 3] {
    let at = |(body, local): End| body.map_or(local, |b| point_position(q, b, local).expect("a body of q"));
    CYLINDERS.map(|(_, a, b)| {
        let (a, b) = (at(a), at(b));
        (b[0] - a[0]).hypot(b[1] - a[1])
    })
}

/// What the two scenes give.
#[derive(Debug, Clone, Copy)]
#[allow(dead_code)] // read by the tests
pub struct Report {
    /// The held arm's joint angles at equilibrium (deg) and how far they are from the design.
    pub held_angles: [f64; 3],
    /// Cylinder tensions at the held equilibrium: k (l − L) + force (N; negative = pushing).
    pub held_tensions: [f64; 3],
    /// Cylinder tensions the driven arm needs to stand still at the held pose's lengths, −λ (N).
    pub driven_tensions: [f64; 3],
    /// The largest relative difference between the two.
    pub disagreement: f64,
    /// The boom cylinder's tension while it extends at 0.1 m/s, at t = 0, 1 and 2 s (N).
    pub lifting: [f64; 3],
    /// The free arm pushed by the lifting forces at t = 1 s: its accelerations' largest
    /// difference from the driven arm's, relative to their largest (rad/s², m/s²).
    pub free_mismatch: f64,
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    // Statics of the held arm, from the design pose.
    let held = ExcavatorHeld::default();
    let mut q = held.initial_positions();
    let mut lambda = [0.0; 6];
    let report = StaticSolver::default().solve(&held, &mut ExcavatorHeld::workspace(), &mut q, 0.0, &mut lambda)?;
    let l = lengths(&q);
    let rest = [held.boom_rest, held.stick_rest, held.bucket_rest];
    let push = [-held.boom_push, 0.0, 0.0];
    let held_tensions: [f64; 3] = core::array::from_fn(|i| held.k_cyl * (l[i] - rest[i]) + push[i]);
    let held_angles = [q[2], q[5], q[8]].map(f64::to_degrees);

    // The driven arm standing still at those cylinder lengths: inverse dynamics at rest.
    let mut driven = ExcavatorDriven { boom_stroke: l[0], stick_stroke: l[1], bucket_stroke: l[2], ..ExcavatorDriven::default() };
    let solver = KinematicSolver::default();
    let mut ws = ExcavatorDriven::workspace();
    let mut driven_q = q;
    solver.assemble(&driven, &mut ws, &mut driven_q, 0.0)?;
    let mut multipliers = [0.0; 9];
    InverseDynamics::default().solve(&driven, &mut ws, &driven_q, &[0.0; 9], &[0.0; 9], 0.0, &mut multipliers)?;
    // Rows: three pins (2 each), then the three drivers.
    let driven_tensions: [f64; 3] = core::array::from_fn(|i| -multipliers[6 + i]);
    let disagreement = (0..3).map(|i| ((driven_tensions[i] - held_tensions[i]) / held_tensions[i]).abs()).fold(0.0, f64::max);

    // Lifting: the boom cylinder extends at 0.1 m/s; its tension over 2 s (motion included).
    driven.lift = 0.1;
    let mut lifting = [0.0; 3];
    let mut guess = driven_q;
    let mut free_mismatch = 0.0;
    for (k, t) in [0.0, 1.0, 2.0].into_iter().enumerate() {
        let s = solver.analyze(&driven, &mut ws, &guess, t)?;
        guess = s.q;
        InverseDynamics::default().solve(&driven, &mut ws, &s.q, &s.v, &s.vd, t, &mut multipliers)?;
        lifting[k] = -multipliers[6];
        if k == 1 {
            // The free arm, each cylinder pushing with the force its driver exerts (λ, N).
            let push = |driver: usize| multipliers[ExcavatorDriven::JOINTS[driver].row_range()][0];
            let free = ExcavatorFree {
                boom_drive_force: push(ExcavatorDriven::BOOM_DRIVE),
                stick_drive_force: push(ExcavatorDriven::STICK_DRIVE),
                bucket_drive_force: push(ExcavatorDriven::BUCKET_DRIVE),
                ..ExcavatorFree::default()
            };
            let (mut vd, mut reactions) = ([0.0; 9], [0.0; 6]);
            free.accelerations(&s.q, &s.v, t, &DynamicsOptions::default(), &mut vd, &mut reactions)?;
            let largest = s.vd.iter().fold(0.0, |m: f64, a| m.max(a.abs()));
            free_mismatch = vd.iter().zip(&s.vd).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / largest;
        }
    }

    if print {
        println!(
            "Excavator arm: one declaration, scenes ExcavatorHeld (cylinders as springs), ExcavatorDriven (as drivers), ExcavatorFree (as actuators)"
        );
        println!("held equilibrium in {} iterations, {:?}", report.iterations, report.stability);
        println!("{:>8} {:>12} {:>16} {:>18}", "cylinder", "length (m)", "held: tension (N)", "driven: −λ (N)");
        for i in 0..3 {
            println!("{:>8} {:>12.5} {:>16.1} {:>18.1}", CYLINDERS[i].0, l[i], held_tensions[i], driven_tensions[i]);
        }
        println!("joint angles (deg): boom {:.3}, stick {:.3}, bucket {:.3}", held_angles[0], held_angles[1], held_angles[2]);
        println!("largest relative difference between the scenes: {disagreement:.1e}");
        println!(
            "boom cylinder tension while extending at 0.1 m/s: {:.0} N, {:.0} N, {:.0} N at t = 0, 1, 2 s",
            lifting[0], lifting[1], lifting[2]
        );
        println!("the free arm pushed by those forces at t = 1 s accelerates as the driven arm: {free_mismatch:.1e} relative");
    }
    Ok(Report { held_angles, held_tensions, driven_tensions, disagreement, lifting, free_mismatch })
}

/// The driven arm of `run`'s last part, from the held arm's equilibrium, its boom cylinder
/// extending at 0.1 m/s for 2 s, for the showcase's pictures: a kinematic sweep of 40 steps.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let held = ExcavatorHeld::default();
    let mut q = held.initial_positions();
    StaticSolver::default().solve(&held, &mut ExcavatorHeld::workspace(), &mut q, 0.0, &mut [0.0; 6])?;
    let l = lengths(&q);
    let driven = ExcavatorDriven { boom_stroke: l[0], stick_stroke: l[1], bucket_stroke: l[2], lift: 0.1, ..ExcavatorDriven::default() };
    let solver = KinematicSolver::default();
    let mut ws = ExcavatorDriven::workspace();
    solver.assemble(&driven, &mut ws, &mut q, 0.0)?;
    let mut animation = mbd::Animation::new::<ExcavatorDriven>(&driven.params())
        .title("Excavator arm, boom cylinder extending at 0.1 m/s")
        .trace("stick.tip");
    solver.sweep(&driven, &mut ws, &mut q, (0..=40).map(|k| 0.05 * k as f64), |t, q, _, _| animation.frame(t, q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("excavator: {e}");
        std::process::exit(1);
    }
}

//! A double-wishbone corner in 3D (Nikravesh, *Computer-Aided Analysis of Mechanical Systems*,
//! ch. 11; Milliken, *Race Car Vehicle Dynamics*, ch. 17): lower and upper A-arms hinged to the
//! chassis (ground) on revolute joints, ball joints to the upright, and a tie rod — a `distance`
//! joint — from a fixed rack end to the steering arm behind the axle. The wheel centre's height
//! is driven through ±80 mm of travel; printed are the curves a suspension engineer reads off a
//! kinematic sweep: bump steer (toe change) and camber.
//!
//! Axes: x forward, y to the left (outboard: this is the left front corner), z up. Hardpoints at
//! design height (m): lower arm pivot (0, 0.25, 0.15), ball joint (0, 0.70, 0.13); upper arm
//! pivot (0, 0.35, 0.45), ball joint (−0.018, 0.66, 0.47) (3° of caster); wheel centre
//! (0, 0.76, 0.30), the upright's centre of mass; steering arm (−0.13, 0.70, 0.13); rack end
//! (−0.13, 0.25, 0.15).
//!
//! Two layouts:
//! - **A, pivot axes parallel to x.** The tie rod copies the lower arm: its rack end lies on the
//!   lower arm's pivot axis, its steering-arm end on the line through the lower ball joint
//!   parallel to that axis, and it has the lower arm's length. A motion of the upright in the
//!   front-view (y, z) plane — a turn about x and a shift — moves both ball joints along their
//!   arms' circles and keeps the tie rod's length (it stays a translated copy of the lower
//!   arm), so it is the motion: the upright never steers. Bump steer is zero, and the camber is
//!   minus the upright's front-view turn, which the planar four-bar of the two arms' front
//!   views gives in closed form (two circles' intersection; the lower arm angle that puts the
//!   wheel centre at the commanded height found by bisection; its hardpoints read off the
//!   mechanism's named points at the declared design configuration). Both checked.
//! - **B, inclined pivot axes** (anti-dive and plan-view angles), the same tie rod: the layout
//!   an engineer tunes; its bump steer and camber curves are the output.
//!
//! The sweep's "time" t is the wheel travel in metres: `drive upright.z = z0 + t`.
//!
//! Run: `cargo run --release --example double_wishbone_3d`
use mbd::nalgebra::Point3;
use mbd::prelude::*;

mechanism! {
    /// Double-wishbone corner with the wheel travel driven; the pivot axes' directions are
    /// (1, lower_y, lower_z) and (1, upper_y, upper_z).
    pub DoubleWishbone {
        spatial;
        params { lower_y: 0.0, lower_z: 0.0, upper_y: 0.0, upper_z: 0.0, z0: 0.30 }
        body lower { mass: 3.0, inertia: [0.06, 0.01, 0.06], at: [0.0, 0.475, 0.14] }
        body upper { mass: 2.0, inertia: [0.02, 0.005, 0.02], at: [-0.009, 0.505, 0.46] }
        body upright { mass: 15.0, inertia: [0.5, 0.8, 0.5], at: [0.0, 0.76, 0.30] }
        // Body points written as hardpoint − the body's centre at design (orientations are the
        // identity at design).
        point lower.pivot = [0.0, 0.25 - 0.475, 0.15 - 0.14];
        point lower.ball = [0.0, 0.70 - 0.475, 0.13 - 0.14];
        point upper.pivot = [0.0 + 0.009, 0.35 - 0.505, 0.45 - 0.46];
        point upper.ball = [-0.018 + 0.009, 0.66 - 0.505, 0.47 - 0.46];
        point upright.lower_ball = [0.0, 0.70 - 0.76, 0.13 - 0.30];
        point upright.upper_ball = [-0.018, 0.66 - 0.76, 0.47 - 0.30];
        point upright.steering_arm = [-0.13, 0.70 - 0.76, 0.13 - 0.30];
        revolute lower_pivot: ground[0.0, 0.25, 0.15] along [1.0, lower_y, lower_z] ~ lower.pivot along [1.0, lower_y, lower_z];
        revolute upper_pivot: ground[0.0, 0.35, 0.45] along [1.0, upper_y, upper_z] ~ upper.pivot along [1.0, upper_y, upper_z];
        spherical lower_ball: lower.ball ~ upright.lower_ball;
        spherical upper_ball: upper.ball ~ upright.upper_ball;
        distance tie_rod: ground[-0.13, 0.25, 0.15] ~ upright.steering_arm { length: sqrt((0.70 - 0.25)^2 + (0.13 - 0.15)^2) };
        drive upright.z = z0 + t;
    }
}

/// Wheel travel (m): ±80 mm in 5 mm steps.
const TRAVEL: f64 = 0.08;
const STEPS: usize = 32;

/// One layout's curves.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone)]
pub struct Curves {
    /// Wheel travel (m), toe (rad, toe-in positive), camber (rad, top leaning outward positive),
    /// lateral wheel-centre movement from design (m), at each point of the sweep.
    pub travel: Vec<f64>,
    pub toe: Vec<f64>,
    pub camber: Vec<f64>,
    pub track: Vec<f64>,
}

/// What the two sweeps found.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone)]
pub struct Report {
    /// Layout A (parallel pivot axes, the tie rod copying the lower arm).
    pub parallel: Curves,
    /// Largest |toe| of layout A (rad): zero.
    pub parallel_bump_steer: f64,
    /// Largest |camber − closed form| (rad) and |wheel centre y − closed form| (m) of layout A.
    pub camber_error: f64,
    pub track_error: f64,
    /// Layout B (inclined pivot axes).
    pub inclined: Curves,
}

/// The front-view (y, z) hardpoints of layout A at design (m), read off the mechanism: the arms'
/// named pivot and ball points and the wheel centre (the upright's centre of mass) at its declared
/// design configuration.
struct FrontView {
    lower_pivot: [f64; 2],
    lower_ball: [f64; 2],
    upper_pivot: [f64; 2],
    upper_ball: [f64; 2],
    wheel: [f64; 2],
}

impl FrontView {
    fn of(m: &DoubleWishbone) -> Self {
        let q = m.initial_positions();
        let yz = |p: Point3<f64>| [p.y, p.z];
        FrontView {
            lower_pivot: yz(m.lower_pivot().position(&q)),
            lower_ball: yz(m.lower_ball().position(&q)),
            upper_pivot: yz(m.upper_pivot().position(&q)),
            upper_ball: yz(m.upper_ball().position(&q)),
            wheel: yz(DoubleWishbone::UPRIGHT.position(&q)),
        }
    }
}

fn rotate2(p: [f64; 2], angle: f64) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn angle2(p: [f64; 2]) -> f64 {
    p[1].atan2(p[0])
}

fn norm2(p: [f64; 2]) -> f64 {
    p[0].hypot(p[1])
}

/// The front-view four-bar of layout A at lower arm angle `alpha` (from the y-axis, rad): the
/// upright's turn about x from design (rad) and the wheel centre (y, z) (m).
fn front_view(h: &FrontView, alpha: f64) -> (f64, [f64; 2]) {
    let (lower, upper) = (norm2(sub2(h.lower_ball, h.lower_pivot)), norm2(sub2(h.upper_ball, h.upper_pivot)));
    let kingpin = norm2(sub2(h.upper_ball, h.lower_ball));
    let ball = [h.lower_pivot[0] + lower * alpha.cos(), h.lower_pivot[1] + lower * alpha.sin()];
    // The upper ball: on the circle of radius `upper` about the upper pivot and `kingpin` from
    // the lower ball, on the design's side of the line between them.
    let to_pivot = sub2(h.upper_pivot, ball);
    let d = norm2(to_pivot);
    let along = (kingpin * kingpin - upper * upper + d * d) / (2.0 * d);
    let across = (kingpin * kingpin - along * along).sqrt();
    let (u, n) = ([to_pivot[0] / d, to_pivot[1] / d], [-to_pivot[1] / d, to_pivot[0] / d]);
    let side = {
        let (a, b) = (sub2(h.upper_pivot, h.lower_ball), sub2(h.upper_ball, h.lower_ball));
        (a[0] * b[1] - a[1] * b[0]).signum()
    };
    // n is u turned +90°: a point at +n lies to the left of the line ball → pivot, where
    // (pivot − ball) × (point − ball) > 0; keep the design's sign.
    let upper_ball = [ball[0] + along * u[0] + side * across * n[0], ball[1] + along * u[1] + side * across * n[1]];
    let turn = angle2(sub2(upper_ball, ball)) - angle2(sub2(h.upper_ball, h.lower_ball));
    let w = rotate2(sub2(h.wheel, h.lower_ball), turn);
    (turn, [ball[0] + w[0], ball[1] + w[1]])
}

/// Layout A's closed form at wheel travel `travel`: (camber, wheel centre y). The lower arm
/// angle is found by bisection on the wheel centre's height, which rises monotonically with it
/// over ±0.4 rad about design.
fn parallel_closed_form(h: &FrontView, travel: f64) -> (f64, f64) {
    let alpha0 = angle2(sub2(h.lower_ball, h.lower_pivot));
    let target = h.wheel[1] + travel;
    let (mut lo, mut hi) = (alpha0 - 0.4, alpha0 + 0.4);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if front_view(h, mid).1[1] < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (turn, wheel) = front_view(h, 0.5 * (lo + hi));
    // A turn by `turn` about +x tips the spin axis (0, 1, 0) up by `turn`: the wheel's top leans
    // inward, camber −turn.
    (-turn + 0.0, wheel[0])
}

/// Sweeps one layout over ±80 mm from its design position.
fn sweep(m: &DoubleWishbone) -> Result<Curves, KinematicError> {
    let solver = KinematicSolver::default();
    let q0 = m.initial_positions();
    let upright = DoubleWishbone::UPRIGHT;
    let mut curves = Curves { travel: Vec::new(), toe: Vec::new(), camber: Vec::new(), track: Vec::new() };
    let step = 2.0 * TRAVEL / STEPS as f64;
    // Out from design in each direction (each position solve starts from its neighbour), then
    // put in order of travel.
    let mut points = Vec::new();
    for direction in [-1.0, 1.0] {
        let mut q = q0;
        // (+ 0.0 turns the first point's −0.0 into 0.0.)
        let times = (0..=STEPS / 2).map(|k| direction * k as f64 * step + 0.0);
        let mut ws = DoubleWishbone::workspace();
        solver.sweep(m, &mut ws, &mut q, times, |t, q, _, _| {
            // The spin axis is the upright's y-axis: w = A (0, 1, 0); the wheel centre is its
            // centre of mass.
            let w = upright.rotation(q).column(1).into_owned();
            let track = upright.position(q).y - upright.position(&q0).y;
            points.push((t, w.x.atan2(w.y), -w.z.asin() + 0.0, track));
        })?;
    }
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    points.dedup_by(|a, b| a.0 == b.0);
    for (t, toe, camber, track) in points {
        curves.travel.push(t);
        curves.toe.push(toe);
        curves.camber.push(camber);
        curves.track.push(track);
    }
    Ok(curves)
}

/// Runs both layouts; prints their curves when `print` is set.
pub fn run(print: bool) -> Result<Report, KinematicError> {
    let parallel_layout = DoubleWishbone::default();
    let design = FrontView::of(&parallel_layout);
    let parallel = sweep(&parallel_layout)?;
    let inclined_layout = DoubleWishbone { lower_y: 0.05, lower_z: 0.10, upper_y: -0.04, upper_z: -0.06, ..DoubleWishbone::default() };
    let inclined = sweep(&inclined_layout)?;
    let (mut camber_error, mut track_error, mut bump_steer) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..parallel.travel.len() {
        let (camber, wheel_y) = parallel_closed_form(&design, parallel.travel[k]);
        camber_error = camber_error.max((parallel.camber[k] - camber).abs());
        track_error = track_error.max((parallel.track[k] - (wheel_y - design.wheel[0])).abs());
        bump_steer = bump_steer.max(parallel.toe[k].abs());
    }
    let r = Report { parallel, parallel_bump_steer: bump_steer, camber_error, track_error, inclined };
    if print {
        println!("Double-wishbone corner, wheel travel ±{} mm (toe-in and camber with the top outward positive)", TRAVEL * 1e3);
        println!("{:>12} | {:>12} {:>13} {:>13} {:>11} | {:>12} {:>13}", "", "A: parallel", "", "", "", "B: inclined", "");
        println!(
            "{:>12} | {:>12} {:>13} {:>13} {:>11} | {:>12} {:>13}",
            "travel (mm)", "toe (deg)", "camber (deg)", "closed form", "track (mm)", "toe (deg)", "camber (deg)"
        );
        for k in (0..r.parallel.travel.len()).step_by(4) {
            let (camber, _) = parallel_closed_form(&design, r.parallel.travel[k]);
            println!(
                "{:>12.1} | {:>12.2e} {:>13.6} {:>13.6} {:>11.3} | {:>12.5} {:>13.6}",
                r.parallel.travel[k] * 1e3,
                r.parallel.toe[k].to_degrees(),
                r.parallel.camber[k].to_degrees(),
                camber.to_degrees(),
                r.parallel.track[k] * 1e3,
                r.inclined.toe[k].to_degrees(),
                r.inclined.camber[k].to_degrees()
            );
        }
        let range = |v: &[f64]| (v.iter().cloned().fold(f64::INFINITY, f64::min), v.iter().cloned().fold(f64::NEG_INFINITY, f64::max));
        println!(
            "A: bump steer ≤ {:.1e} rad; camber vs front-view four-bar ≤ {:.1e} rad; wheel centre y vs closed form ≤ {:.1e} m",
            r.parallel_bump_steer, r.camber_error, r.track_error
        );
        let ((toe_lo, toe_hi), (camber_lo, camber_hi)) = (range(&r.inclined.toe), range(&r.inclined.camber));
        println!(
            "B: toe {:.4}° … {:.4}°, camber {:.4}° … {:.4}° over the travel",
            toe_lo.to_degrees(),
            toe_hi.to_degrees(),
            camber_lo.to_degrees(),
            camber_hi.to_degrees()
        );
    }
    Ok(r)
}

/// Layout B (inclined pivot axes) through ±80 mm of travel, for the showcase's pictures: 65
/// positions, travel 80 mm · sin 2πs over a nominal one-second cycle s ∈ [0, 1] (the sweep's t
/// is the travel; the frames' times are s).
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = DoubleWishbone { lower_y: 0.05, lower_z: 0.10, upper_y: -0.04, upper_z: -0.06, ..DoubleWishbone::default() };
    let mut q = m.initial_positions();
    let mut ws = DoubleWishbone::workspace();
    let mut animation = mbd::Animation::new::<DoubleWishbone>(&m.params())
        .title("Double wishbone (inclined pivots), ±80 mm wheel travel")
        .trace("upright.steering_arm");
    let phases: Vec<f64> = (0..=64).map(|k| k as f64 / 64.0).collect();
    let mut frame = phases.iter();
    let travels = phases.iter().map(|s| TRAVEL * (2.0 * PI * s).sin());
    KinematicSolver::default().sweep(&m, &mut ws, &mut q, travels, |_, q, _, _| {
        if let Some(&s) = frame.next() {
            animation.frame(s, q)
        }
    })?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("double_wishbone_3d: {e}");
        std::process::exit(1);
    }
}

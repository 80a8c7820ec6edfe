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
//!   wheel centre at the commanded height found by bisection). Both checked.
//! - **B, inclined pivot axes** (anti-dive and plan-view angles), the same tie rod: the layout
//!   an engineer tunes; its bump steer and camber curves are the output.
//!
//! The sweep's "time" t is the wheel travel in metres: `drive upright.z = z0 + t`.
//!
//! Run: `cargo run --release --example double_wishbone_3d`
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

/// Front-view (y, z) hardpoints at design (m): lower pivot, lower ball, upper pivot, upper
/// ball, wheel centre — as in the `mechanism!` above.
const LOWER_PIVOT: [f64; 2] = [0.25, 0.15];
const LOWER_BALL: [f64; 2] = [0.70, 0.13];
const UPPER_PIVOT: [f64; 2] = [0.35, 0.45];
const UPPER_BALL: [f64; 2] = [0.66, 0.47];
const WHEEL: [f64; 2] = [0.76, 0.30];
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

/// A(p) = (2e0² − 1)I + 2(eeᵀ + e0ẽ) of body `body`'s Euler parameters q[7k+3..7k+7]
/// (docs/formulation.md, "Spatial bodies").
fn rotation(q: &[f64], body: usize) -> [[f64; 3]; 3] {
    let [e0, e1, e2, e3] = [q[7 * body + 3], q[7 * body + 4], q[7 * body + 5], q[7 * body + 6]];
    let e = [e1, e2, e3];
    let tilde = [[0.0, -e3, e2], [e3, 0.0, -e1], [-e2, e1, 0.0]];
    core::array::from_fn(|r| {
        core::array::from_fn(|c| if r == c { 2.0 * e0 * e0 - 1.0 } else { 0.0 } + 2.0 * (e[r] * e[c] + e0 * tilde[r][c]))
    })
}

fn rotate2(v: [f64; 2], angle: f64) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn angle2(v: [f64; 2]) -> f64 {
    v[1].atan2(v[0])
}

fn norm2(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

/// The front-view four-bar of layout A at lower arm angle `alpha` (from the y-axis, rad): the
/// upright's turn about x from design (rad) and the wheel centre (y, z) (m).
fn front_view(alpha: f64) -> (f64, [f64; 2]) {
    let (lower, upper) = (norm2(sub2(LOWER_BALL, LOWER_PIVOT)), norm2(sub2(UPPER_BALL, UPPER_PIVOT)));
    let kingpin = norm2(sub2(UPPER_BALL, LOWER_BALL));
    let ball = [LOWER_PIVOT[0] + lower * alpha.cos(), LOWER_PIVOT[1] + lower * alpha.sin()];
    // The upper ball: on the circle of radius `upper` about the upper pivot and `kingpin` from
    // the lower ball, on the design's side of the line between them.
    let to_pivot = sub2(UPPER_PIVOT, ball);
    let d = norm2(to_pivot);
    let along = (kingpin * kingpin - upper * upper + d * d) / (2.0 * d);
    let across = (kingpin * kingpin - along * along).sqrt();
    let (u, n) = ([to_pivot[0] / d, to_pivot[1] / d], [-to_pivot[1] / d, to_pivot[0] / d]);
    let side = {
        let (a, b) = (sub2(UPPER_PIVOT, LOWER_BALL), sub2(UPPER_BALL, LOWER_BALL));
        (a[0] * b[1] - a[1] * b[0]).signum()
    };
    // n is u turned +90°: a point at +n lies to the left of the line ball → pivot, where
    // (pivot − ball) × (point − ball) > 0; keep the design's sign.
    let upper_ball = [ball[0] + along * u[0] + side * across * n[0], ball[1] + along * u[1] + side * across * n[1]];
    let turn = angle2(sub2(upper_ball, ball)) - angle2(sub2(UPPER_BALL, LOWER_BALL));
    let w = rotate2(sub2(WHEEL, LOWER_BALL), turn);
    (turn, [ball[0] + w[0], ball[1] + w[1]])
}

/// Layout A's closed form at wheel travel `travel`: (camber, wheel centre y). The lower arm
/// angle is found by bisection on the wheel centre's height, which rises monotonically with it
/// over ±0.4 rad about design.
fn parallel_closed_form(travel: f64) -> (f64, f64) {
    let alpha0 = angle2(sub2(LOWER_BALL, LOWER_PIVOT));
    let target = WHEEL[1] + travel;
    let (mut lo, mut hi) = (alpha0 - 0.4, alpha0 + 0.4);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if front_view(mid).1[1] < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (turn, wheel) = front_view(0.5 * (lo + hi));
    // A turn by `turn` about +x tips the spin axis (0, 1, 0) up by `turn`: the wheel's top leans
    // inward, camber −turn.
    (-turn + 0.0, wheel[0])
}

/// Sweeps one layout over ±80 mm from its design position.
fn sweep(m: &DoubleWishbone) -> Result<Curves, KinematicError> {
    let solver = KinematicSolver::default();
    let q0 = m.initial_positions();
    let mut curves = Curves { travel: Vec::new(), toe: Vec::new(), camber: Vec::new(), track: Vec::new() };
    let step = 2.0 * TRAVEL / STEPS as f64;
    // Out from design in each direction (each position solve starts from its neighbour), then
    // put in order of travel.
    let mut points = Vec::new();
    for direction in [-1.0, 1.0] {
        let mut q = q0;
        // (+ 0.0 turns the first point's −0.0 into 0.0.)
        let times = (0..=STEPS / 2).map(|k| direction * k as f64 * step + 0.0);
        solver.sweep(m, &mut q, times, |t, q, _, _| {
            let a = rotation(q, 2);
            // The spin axis is the upright's y-axis: w = A (0, 1, 0).
            let w = [a[0][1], a[1][1], a[2][1]];
            points.push((t, w[0].atan2(w[1]), -w[2].asin() + 0.0, q[14 + 1] - q0[14 + 1]));
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
    let parallel = sweep(&DoubleWishbone::default())?;
    let inclined_layout = DoubleWishbone { lower_y: 0.05, lower_z: 0.10, upper_y: -0.04, upper_z: -0.06, ..DoubleWishbone::default() };
    let inclined = sweep(&inclined_layout)?;
    let (mut camber_error, mut track_error, mut bump_steer) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..parallel.travel.len() {
        let (camber, wheel_y) = parallel_closed_form(parallel.travel[k]);
        camber_error = camber_error.max((parallel.camber[k] - camber).abs());
        track_error = track_error.max((parallel.track[k] - (wheel_y - WHEEL[0])).abs());
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
            let (camber, _) = parallel_closed_form(r.parallel.travel[k]);
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

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("double_wishbone_3d: {e}");
        std::process::exit(1);
    }
}

//! Nikravesh's project 15.3, the sled test of a belted dummy, posed as a restraint engineer asks
//! it: in a 50 km/h frontal crash pulse, how hard are the dummy's head and chest accelerated
//! (peak, HIC, the 3 ms clip), what do the belts carry, how far does the head travel forward,
//! and what does the seat cushion carry — with each peak's time?
//!
//! The model (planar, in the side view, x forward and y up; SI units; every number's source in
//! `SOURCES`): a seat on an acceleration sled (it reproduces the crash pulse as a push backwards
//! from rest, as a HYGE sled does); a dummy of three bodies — the pelvis with the legs, the
//! torso with the arms, the head with the neck — joined at the lumbar spine and at the neck by
//! revolutes with rotational springs and dampers; the seat cushion and the seat back as contacts
//! against the dummy's buttock, thigh and back; a three-point belt as three cables, tension only:
//! the lap belt, and the shoulder belt from the D-ring to the upper chest and from the lower chest
//! to the buckle. The dummy sits at rest in its seat (statics) with the belts snug before the
//! pulse.
//!
//! **The checks** (each written by hand from the model's data, not from the generated equations;
//! the last takes the simulated accelerations and checks the loads against them):
//!
//! - the seated posture against the dummy's force balance by hand: its weight equals the seat's
//!   contact forces, each written by hand from its law;
//! - the crash against the momentum and angular momentum theorems for the whole dummy: at every
//!   sample, Σ m a equals its weight, the belts' and the seat's forces, each written by hand from
//!   its element's law, and Σ (r × m a + J α) their moment (the joints' forces and the spines'
//!   torques are internal and cancel).
//!
//! Run: `cargo run --release --example sled_test`
use mbd::prelude::*;

mechanism! {
    /// A belted dummy on a sled in a frontal crash pulse (Nikravesh's project 15.3): pelvis,
    /// torso and head; the seat cushion and back as contacts; a three-point belt as three cables.
    pub SledTest {
        // dv: the pulse's change of speed (m/s); peak: its largest acceleration (m/s²); the
        // belts' free lengths (m), set snug at the seated posture; their effective stiffness
        // (N/m) and damping (N·s/m).
        params {
            dv: 50.0 / 3.6, peak: 25.0 * 9.81,
            lap_length: 0.3, upper_length: 0.26, lower_length: 0.46, k_belt: 4.0e4, c_belt: 800.0
        }
        gravity [0.0, -9.81];
        // The half-sine pulse: its duration, and the time into it. Both kinks at its end take,
        // at the instant itself, the branch before it (a tie takes the first argument's), so the
        // driver's velocity there is the pulse's, not the sum of both sides'.
        let pulse = PI * dv / (2.0 * peak);
        let into = min(t, pulse);
        // The sled on its rail, pushed backwards by the pulse.
        body sled { mass: 200.0, inertia: 20.0, at: [0.0, 0.0, 0.0] }
        translational rail: ground[0.0, 0.0] along [1.0, 0.0] ~ sled[0.0, 0.0] along [1.0, 0.0];
        drive crash: sled.x = -(peak * pulse / PI * (into - pulse / PI * sin(PI * into / pulse)) + dv * max(0.0, t - pulse));
        // The dummy, from the H-point at the sled's origin: the pelvis with the thighs and the
        // lower legs, the torso with the arms reclined 25°, the head with the neck.
        body pelvis { mass: 45.9, inertia: 1.6, at: [0.12, 0.0, 0.0] }
        body torso { mass: 25.8, inertia: 1.0, at: [-0.1414, 0.3375, deg(25.0)] }
        body head { mass: 6.08, inertia: 0.035, at: [-0.2229, 0.675, 0.0] }
        revolute lumbar: pelvis[-0.16, 0.12] ~ torso[0.0, -0.24];
        revolute neck: torso[0.0, 0.24] ~ head[-0.02, -0.12];
        rotational_spring lumbar_spine: pelvis ~ torso { k: 600.0, c: 10.0, angle: deg(25.0) };
        rotational_spring neck_spine: torso ~ head { k: 100.0, c: 1.0, angle: deg(-25.0) };
        // The seat: the cushion rising 12° to the front under the H-point, the back reclined 25°.
        point sled.cushion = [0.0, -0.1];
        point sled.back = [-0.1, 0.0];
        point pelvis.buttock = [-0.14, -0.1];
        point pelvis.thigh = [0.18, -0.0362];
        point torso.lower_back = [-0.1, -0.15];
        point torso.upper_back = [-0.1, 0.15];
        contact cushion_buttock: pelvis.buttock ~ sled.cushion along [-0.2079, 0.9781] { k: 5.0e4, c: 1.0e5 };
        contact cushion_thigh: pelvis.thigh ~ sled.cushion along [-0.2079, 0.9781] { k: 5.0e4, c: 1.0e5 };
        contact back_lower: torso.lower_back ~ sled.back along [0.9063, 0.4226] { k: 3.0e4, c: 6.0e4 };
        contact back_upper: torso.upper_back ~ sled.back along [0.9063, 0.4226] { k: 3.0e4, c: 6.0e4 };
        // The belt: the lap belt from its anchor over the pelvis; the shoulder belt from the
        // D-ring to the upper chest, and from the lower chest to the buckle.
        point sled.lap_anchor = [-0.12, -0.2];
        point sled.d_ring = [-0.35, 0.65];
        point sled.buckle = [-0.05, -0.12];
        point pelvis.lap = [-0.06, 0.03];
        point torso.upper_chest = [0.1, 0.17];
        point torso.lower_chest = [0.1, -0.05];
        cable lap: sled.lap_anchor ~ pelvis.lap { k: k_belt, length: lap_length, c: c_belt };
        cable shoulder_upper: sled.d_ring ~ torso.upper_chest { k: k_belt, length: upper_length, c: c_belt };
        cable shoulder_lower: torso.lower_chest ~ sled.buckle { k: k_belt, length: lower_length, c: c_belt };
        scene Unbelted without lap, shoulder_upper, shoulder_lower;
    }
}

/// Where the numbers come from (assumptions are marked so).
pub const SOURCES: [(&str, &str); 8] = [
    ("the pulse: Δv 50 km/h", "UN Regulation No. 16's dynamic test of seat belts, at 50 km/h"),
    ("its shape: a half-sine of 25 g peak (89.0 ms)", "assumption"),
    (
        "the dummy's 77.8 kg: pelvis with the thighs and lower legs 45.9 kg, torso with the arms 25.8 kg, head with the neck 6.08 kg",
        "the Hybrid III 50th-percentile male's segment masses (49 CFR Part 572 subpart E), lumped into three bodies",
    ),
    ("their moments of inertia (1.6, 1.0, 0.035 kg·m²) and the posture's dimensions (torso 0.48 m from the lumbar joint to the neck, reclined 25°)", "assumption"),
    ("lumbar spine 600 N·m/rad, 10 N·m·s/rad; neck 100 N·m/rad, 1 N·m·s/rad", "assumption"),
    ("seat cushion 5·10⁴ N/m a point, rising 12° to the front; seat back 3·10⁴ N/m a point, reclined 25°; Hunt–Crossley damping", "assumption"),
    ("belt anchors: lap anchor 0.12 m behind and 0.2 m below the H-point, D-ring 0.35 m behind and 0.65 m above it, buckle by the hip", "assumption"),
    ("each belt segment's effective stiffness 4·10⁴ N/m (webbing, retractor spool-out and the chest's give), 800 N·s/m (the webbing's hysteresis)", "assumption"),
];

/// The dummy's masses (kg): pelvis, torso, head, as in the mechanism.
const MASSES: [f64; 3] = [45.9, 25.8, 6.08];
const INERTIAS: [f64; 3] = [1.6, 1.0, 0.035];

/// The run's answers. Accelerations in g, times in s, forces in N, lengths in m.
#[allow(dead_code)] // read by the tests
#[derive(Debug, Clone, Copy)]
pub struct Report {
    /// The seated posture: the cushion's and the seat back's forces (N), and the largest
    /// |Σ external force| (N) and |Σ external moment about the H-point| (N·m) by hand there.
    pub seated_cushion: f64,
    pub seated_back: f64,
    pub seated_force_error: f64,
    pub seated_moment_error: f64,
    /// The head's largest resultant acceleration and when, and its HIC over windows of up to
    /// 15 ms; its largest forward travel on the sled.
    pub head_peak: (f64, f64),
    pub hic15: f64,
    pub head_excursion: f64,
    /// The chest's (the torso's centre of mass) largest resultant acceleration and when, and
    /// its 3 ms clip (the level exceeded for 3 ms in all).
    pub chest_peak: (f64, f64),
    pub chest_clip: f64,
    /// Each belt segment's largest tension and when: lap, shoulder (D-ring side), shoulder
    /// (buckle side).
    pub lap: (f64, f64),
    pub shoulder_upper: (f64, f64),
    pub shoulder_lower: (f64, f64),
    /// The cushion's largest force and when, and its least during the pulse.
    pub cushion_peak: (f64, f64),
    pub cushion_least: f64,
    /// The largest |Σ external force| by hand during the crash (N), and the largest |Σ m a − Σ
    /// external force| (N) and |Σ (r × m a + J α) − Σ external moment| (N·m) over the samples.
    pub force_peak: f64,
    pub force_error: f64,
    pub moment_error: f64,
}

/// The external forces on the dummy by hand, each from its element's law, at a state of the
/// mechanism (any scene: the coordinates are the same).
struct Loads {
    /// Σ of every external force on the dummy (N) and its moment about the ground's origin,
    /// the H-point at the start (N·m).
    total: [f64; 2],
    moment: f64,
    cushion: f64,
    back: f64,
    /// lap, shoulder (D-ring side), shoulder (buckle side), each a tension (N).
    belts: [f64; 3],
}

fn loads(m: &SledTest, q: &[f64; SledTest::NQ], v: &[f64; SledTest::NV], belted: bool) -> Loads {
    let origin = SledTest::SLED.position(q);
    let sled_v = SledTest::SLED.velocity(v);
    let mut l = Loads { total: [0.0; 2], moment: 0.0, cushion: 0.0, back: 0.0, belts: [0.0; 3] };
    let mut apply = |at: [f64; 2], f: [f64; 2]| {
        l.total[0] += f[0];
        l.total[1] += f[1];
        l.moment += at[0] * f[1] - at[1] * f[0];
    };
    for (body, mass) in [SledTest::PELVIS, SledTest::TORSO, SledTest::HEAD].iter().zip(MASSES) {
        let at = body.position(q);
        apply([at.x, at.y], [0.0, -9.81 * mass]);
    }
    // A contact: δ = −n̂ᵀ(r_P − r_Q), pushing along n̂ with δ (k + c δ̇) while δ > 0.
    let mut contact = |point: mbd::PlanarPoint<f64, { SledTest::NQ }>, plane: [f64; 2], n: [f64; 2], k: f64, c: f64| -> f64 {
        // The mechanism's normals are written to four digits: normalized where used.
        let normal = [n[0] / n[0].hypot(n[1]), n[1] / n[0].hypot(n[1])];
        let (at, at_v) = (point.position(q), point.velocity(q, v));
        let depth = -(normal[0] * (at.x - origin.x - plane[0]) + normal[1] * (at.y - origin.y - plane[1]));
        let rate = -(normal[0] * (at_v.x - sled_v.x) + normal[1] * (at_v.y - sled_v.y));
        let push = if depth > 0.0 { (depth * (k + c * rate)).max(0.0) } else { 0.0 };
        apply([at.x, at.y], [push * normal[0], push * normal[1]]);
        push
    };
    let (cushion, back) = ([-0.2079, 0.9781], [0.9063, 0.4226]);
    l.cushion =
        contact(m.pelvis_buttock(), [0.0, -0.1], cushion, 5.0e4, 1.0e5) + contact(m.pelvis_thigh(), [0.0, -0.1], cushion, 5.0e4, 1.0e5);
    l.back =
        contact(m.torso_lower_back(), [-0.1, 0.0], back, 3.0e4, 6.0e4) + contact(m.torso_upper_back(), [-0.1, 0.0], back, 3.0e4, 6.0e4);
    if belted {
        // A cable: tension k δ + c l̇ while its stretch δ = l − length > 0, pulling the dummy's
        // point towards the anchor.
        let belts = [
            (m.pelvis_lap(), [-0.12, -0.2], m.lap_length),
            (m.torso_upper_chest(), [-0.35, 0.65], m.upper_length),
            (m.torso_lower_chest(), [-0.05, -0.12], m.lower_length),
        ];
        for (k, (point, anchor, length)) in belts.into_iter().enumerate() {
            let (at, at_v) = (point.position(q), point.velocity(q, v));
            let d = [origin.x + anchor[0] - at.x, origin.y + anchor[1] - at.y];
            let span = d[0].hypot(d[1]);
            let rate = (d[0] * (sled_v.x - at_v.x) + d[1] * (sled_v.y - at_v.y)) / span;
            let stretch = span - length;
            let tension = if stretch > 0.0 { (m.k_belt * stretch + m.c_belt * rate).max(0.0) } else { 0.0 };
            apply([at.x, at.y], [tension * d[0] / span, tension * d[1] / span]);
            l.belts[k] = tension;
        }
    }
    l
}

/// The rates of the dummy's momentum Σ m a (N) and of its angular momentum about the ground's
/// origin Σ (r × m a + J α) (N·m), by hand from its bodies' accelerations.
fn rates_of_momentum(q: &[f64; SledTest::NQ], vd: &[f64; SledTest::NV]) -> ([f64; 2], f64) {
    let bodies = [SledTest::PELVIS, SledTest::TORSO, SledTest::HEAD];
    bodies.iter().zip(MASSES.iter().zip(INERTIAS)).fold(([0.0; 2], 0.0), |(f, n), (body, (&mass, inertia))| {
        let (at, a) = (body.position(q), body.acceleration(vd));
        ([f[0] + mass * a.x, f[1] + mass * a.y], n + mass * (at.x * a.y - at.y * a.x) + inertia * body.alpha(vd))
    })
}

/// HIC over windows of up to `window` s: the largest (t₂ − t₁) ā^2.5 of the mean acceleration ā
/// (g) over [t₁, t₂], from samples `a` every `dt` s (trapezoidal rule).
fn hic(a: &[f64], dt: f64, window: f64) -> f64 {
    let mut integral = vec![0.0; a.len()];
    for k in 1..a.len() {
        integral[k] = integral[k - 1] + 0.5 * dt * (a[k - 1] + a[k]);
    }
    let span = (window / dt).round() as usize;
    let mut best = 0.0_f64;
    for i in 0..a.len() {
        for j in i + 1..a.len().min(i + span + 1) {
            let duration = (j - i) as f64 * dt;
            best = best.max(duration * ((integral[j] - integral[i]) / duration).powf(2.5));
        }
    }
    best
}

/// The level a signal sampled every `dt` s exceeds for `duration` s in all (the "3 ms clip").
fn clip(a: &[f64], dt: f64, duration: f64) -> f64 {
    let mut sorted = a.to_vec();
    sorted.sort_by(|x, y| y.total_cmp(x));
    sorted[((duration / dt).round() as usize).min(sorted.len() - 1)]
}

/// The dummy seated at rest, the belts snug: the coordinates, and the mechanism with the belts'
/// lengths set to their spans there.
fn seated() -> Result<(SledTest, [f64; SledTest::NQ]), Box<dyn std::error::Error>> {
    let unbelted = Unbelted::default();
    let mut q = unbelted.initial_positions();
    mbd::StaticSolver::default().solve(&unbelted, &mut Unbelted::workspace(), &mut q, 0.0, &mut [0.0; Unbelted::NC])?;
    let base = SledTest::default();
    let span = |point: mbd::PlanarPoint<f64, { SledTest::NQ }>, anchor: [f64; 2]| {
        let at = point.position(&q);
        (at.x - anchor[0]).hypot(at.y - anchor[1])
    };
    let m = SledTest {
        lap_length: span(base.pelvis_lap(), [-0.12, -0.2]),
        upper_length: span(base.torso_upper_chest(), [-0.35, 0.65]),
        lower_length: span(base.torso_lower_chest(), [-0.05, -0.12]),
        ..base
    };
    Ok((m, q))
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let (m, q0) = seated()?;
    let still = loads(&m, &q0, &[0.0; SledTest::NV], true);
    let dt = 1e-4;
    let times: Vec<f64> = (1..=2000).map(|k| dt * k as f64).collect();
    let mut r = Report {
        seated_cushion: still.cushion,
        seated_back: still.back,
        seated_force_error: still.total[0].hypot(still.total[1]),
        seated_moment_error: still.moment.abs(),
        head_peak: (0.0, 0.0),
        hic15: 0.0,
        head_excursion: 0.0,
        chest_peak: (0.0, 0.0),
        chest_clip: 0.0,
        lap: (0.0, 0.0),
        shoulder_upper: (0.0, 0.0),
        shoulder_lower: (0.0, 0.0),
        cushion_peak: (0.0, 0.0),
        cushion_least: f64::INFINITY,
        force_peak: 0.0,
        force_error: 0.0,
        moment_error: 0.0,
    };
    let peak = |slot: &mut (f64, f64), value: f64, t: f64| {
        if value > slot.0 {
            *slot = (value, t);
        }
    };
    let head_start = SledTest::HEAD.position(&q0).x;
    let pulse = PI * m.dv / (2.0 * m.peak);
    let (mut head, mut chest) = (Vec::with_capacity(times.len()), Vec::with_capacity(times.len()));
    let mut trace: Vec<Trace> = Vec::new();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-12));
    Simulation::new(&m, &mut dopri).start(0.0, &q0, &[0.0; SledTest::NV]).times(&times).run(&mut SledTest::workspace(), |s| {
        let (q, v, vd, t) = (&s.point.q, &s.point.v, &s.point.vd, s.point.t);
        let l = loads(&m, q, v, true);
        let (force, moment) = rates_of_momentum(q, vd);
        r.force_error = r.force_error.max((force[0] - l.total[0]).hypot(force[1] - l.total[1]));
        r.moment_error = r.moment_error.max((moment - l.moment).abs());
        r.force_peak = r.force_peak.max(l.total[0].hypot(l.total[1]));
        if s.event.is_some() {
            return;
        }
        let (a_head, a_chest) = (SledTest::HEAD.acceleration(vd).norm() / 9.81, SledTest::TORSO.acceleration(vd).norm() / 9.81);
        head.push(a_head);
        chest.push(a_chest);
        peak(&mut r.head_peak, a_head, t);
        peak(&mut r.chest_peak, a_chest, t);
        r.head_excursion = r.head_excursion.max(SledTest::HEAD.position(q).x - SledTest::SLED.position(q).x - head_start);
        peak(&mut r.lap, l.belts[0], t);
        peak(&mut r.shoulder_upper, l.belts[1], t);
        peak(&mut r.shoulder_lower, l.belts[2], t);
        peak(&mut r.cushion_peak, l.cushion, t);
        if t <= pulse {
            r.cushion_least = r.cushion_least.min(l.cushion);
        }
        if print {
            trace.push((t, a_head, a_chest, l.belts, l.cushion));
        }
    })?;
    r.hic15 = hic(&head, dt, 0.015);
    r.chest_clip = clip(&chest, dt, 0.003);
    if print {
        print_report(&m, &r, &trace)?;
    }
    Ok(r)
}

/// (t, head and chest accelerations in g, the belts' tensions and the cushion's force in N) at
/// one sample, for the plots.
type Trace = (f64, f64, f64, [f64; 3], f64);

/// The answers, the checks and the sources, and the engineer's plots in target/showcase.
fn print_report(m: &SledTest, r: &Report, trace: &[Trace]) -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "Sled test of a belted dummy (Nikravesh's project 15.3): Δv {:.0} km/h, a half-sine of {:.0} g peak ({:.1} ms)",
        m.dv * 3.6,
        m.peak / 9.81,
        1e3 * PI * m.dv / (2.0 * m.peak)
    );
    println!(
        "seated: cushion {:.1} N, seat back {:.1} N; the dummy's force balance by hand within {:.1e} N and {:.1e} N·m",
        r.seated_cushion, r.seated_back, r.seated_force_error, r.seated_moment_error
    );
    println!(
        "head: {:.1} g at {:.1} ms, HIC15 {:.0}, forward travel {:.0} mm; chest: {:.1} g at {:.1} ms, 3 ms clip {:.1} g",
        r.head_peak.0,
        1e3 * r.head_peak.1,
        r.hic15,
        1e3 * r.head_excursion,
        r.chest_peak.0,
        1e3 * r.chest_peak.1,
        r.chest_clip
    );
    for (name, (force, t)) in [
        ("lap belt", r.lap),
        ("shoulder belt, D-ring side", r.shoulder_upper),
        ("shoulder belt, buckle side", r.shoulder_lower),
        ("cushion", r.cushion_peak),
    ] {
        println!("{name}: {force:.0} N at {:.1} ms", 1e3 * t);
    }
    println!("cushion's least force during the pulse {:.0} N", r.cushion_least);
    println!(
        "the momentum theorems by hand: Σ m a within {:.1e} N of the external forces (up to {:.0} N), Σ (r × m a + J α) within {:.1e} N·m of their moment",
        r.force_error, r.force_peak, r.moment_error
    );
    for (what, source) in SOURCES {
        println!("  {what}: {source}");
    }
    let dir = std::path::Path::new("target/showcase");
    std::fs::create_dir_all(dir)?;
    mbd::Plot::new("Sled test at 50 km/h: the belts and the cushion")
        .labels("time (ms)", "force (N)")
        .series("lap belt", trace.iter().map(|p| (1e3 * p.0, p.3[0])))
        .series("shoulder belt, D-ring side", trace.iter().map(|p| (1e3 * p.0, p.3[1])))
        .series("shoulder belt, buckle side", trace.iter().map(|p| (1e3 * p.0, p.3[2])))
        .series("cushion", trace.iter().map(|p| (1e3 * p.0, p.4)))
        .write_svg(dir.join("sled_test_belts.svg"))?;
    mbd::Plot::new("Sled test at 50 km/h: the head's and the chest's resultant acceleration")
        .labels("time (ms)", "acceleration (g)")
        .series("head", trace.iter().map(|p| (1e3 * p.0, p.1)))
        .series("chest", trace.iter().map(|p| (1e3 * p.0, p.2)))
        .write_svg(dir.join("sled_test_accelerations.svg"))?;
    println!("plots → target/showcase/sled_test_belts.svg, sled_test_accelerations.svg");
    Ok(())
}

/// The crash over 200 ms, for the showcase's animation: 100 frames.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let (m, q) = seated()?;
    let mut animation = mbd::Animation::new::<SledTest>(&m.params()).title("Sled test: a belted dummy in a 50 km/h frontal pulse");
    let times: Vec<f64> = (0..=100).map(|k| 0.002 * k as f64).collect();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-12));
    Simulation::new(&m, &mut dopri).start(0.0, &q, &[0.0; SledTest::NV]).times(&times).run(&mut SledTest::workspace(), |s| {
        if s.event.is_none() {
            animation.frame(s.point.t, &s.point.q)
        }
    })?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("sled_test: {e}");
        std::process::exit(1);
    }
}

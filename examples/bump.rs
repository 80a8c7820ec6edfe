//! A quarter car over a bump (Nikravesh's suspension models, reduced to a chassis and a wheel on
//! vertical slides): at 20 m/s a 10 cm bump throws the wheel into its bump stop and off the road.
//! The tyre and the bump stop are unilateral elements; `simulate` lands a step on each instant
//! one of them starts or stops pushing, and on each instant the road's profile changes law (its
//! `clamp` of t: the bump's start and end, "time events"), and the example lists those instants.
//!
//! Run with `cargo run --release --example bump`.

use mbd::prelude::*;
use mbd::{EventHit, StaticSolver};

mbd::mechanism! {
    /// A quarter car on a road with a bump of `height` and `length` (m) starting at x = 20 m,
    /// driven over at `speed` (m/s): the road under the wheel rises and falls with t.
    pub QuarterCar {
        params { speed: 20.0, height: 0.1, length: 0.5 }
        gravity [0.0, -9.81];
        body chassis { mass: 250.0, inertia: 10.0, at: [0.0, 0.71, 0.0] }
        body wheel { mass: 35.0, inertia: 1.0, at: [0.0, 0.29, 0.0] }
        translational ground[0.0, 0.0] along [0.0, 1.0] ~ chassis[0.0, 0.0] along [0.0, 1.0];
        translational chassis[0.0, 0.0] along [0.0, 1.0] ~ wheel[0.0, 0.0] along [0.0, 1.0];
        spring shock: chassis[0.0, 0.0] ~ wheel[0.0, 0.0] { k: 2.0e4, length: 0.55, c: 1500.0 };
        // the wheel's top (0.1 m above its centre) against the chassis 0.28 m below its centre: 4.7 cm of travel
        contact bump_stop: wheel[0.0, 0.1] ~ chassis[0.0, -0.28] along [0.0, -1.0] { k: 2.0e6, exponent: 1.5, c: 2.0e5 };
        tyre road: wheel[0.0, 0.0] ~ ground[0.0, 0.0] {
            radius: 0.3, k: 2.0e5, c: 200.0,
            road: height * sin(PI * clamp(speed * t - 20.0, 0.0, length) / length)^2
        };
    }
}

/// What the run gives.
#[derive(Debug)]
#[allow(dead_code)] // read by the tests
pub struct Report {
    /// The tyre's static compression and the closed form (m + M) g / k (m).
    pub static_compression: (f64, f64),
    /// Each located switch of the tyre and the bump stop: time (s), element, and whether its
    /// force starts (true) or stops.
    pub events: Vec<(f64, &'static str, bool)>,
    /// The instants the road's profile changes law: the bump's start and end (s).
    pub road_changes: Vec<f64>,
    /// The time the wheel spends in the air (s).
    pub airborne: f64,
}

pub fn run(print: bool) -> Result<Report, Box<dyn std::error::Error>> {
    let m = QuarterCar::default();
    let mut ws = QuarterCar::workspace();
    // At rest on the flat road before the bump.
    let mut q = m.initial_positions();
    let mut lambda = [0.0; 4];
    StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut lambda)?;
    let compression = 0.3 - QuarterCar::WHEEL.position(&q).y;
    let expected = (250.0 + 35.0) * 9.81 / 2.0e5;

    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-11));
    let times: Vec<f64> = (1..=300).map(|k| 0.005 * k as f64).collect();
    let (mut events, mut road_changes) = (Vec::new(), Vec::new());
    Simulation::new(&m, &mut dopri).start(0.0, &q, &[0.0; 6]).times(&times).run(&mut ws, |s| {
        if let Some(EventHit::Switch(k)) = s.event {
            let name = QuarterCar::SWITCH_NAMES[k];
            if name.starts_with("road: time event") {
                road_changes.push(s.point.t);
            } else {
                // An event's sample is on its new side: the element pushes there if it began to.
                let p = &s.point;
                events.push((p.t, name, m.switching_function(k, &p.q, &p.v, p.t) > 0.0));
            }
        }
    })?;
    // From each time the tyre lets go to the next time it pushes again.
    let road: Vec<&(f64, &str, bool)> = events.iter().filter(|e| e.1 == "road").collect();
    let airborne: f64 = road.windows(2).filter(|w| !w[0].2 && w[1].2).map(|w| w[1].0 - w[0].0).sum();
    if print {
        println!("Quarter car at {} m/s over a {} cm bump at x = 20 m (t = 1 s)", m.speed, 100.0 * m.height);
        println!("static tyre compression {:.6} m (closed form (m + M) g / k = {expected:.6} m)", compression);
        println!("{:>12}  {:<10}", "t (s)", "element");
        let changes = road_changes.iter().map(|&t| (t, "road", "profile changes law"));
        let switches = events.iter().map(|&(t, name, pushing)| (t, name, if pushing { "starts pushing" } else { "lets go" }));
        let mut all: Vec<(f64, &str, &str)> = changes.chain(switches).collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (t, name, what) in all {
            println!("{t:>12.6}  {name:<10} {what}");
        }
        println!("the wheel is in the air for {:.1} ms", 1e3 * airborne);
    }
    Ok(Report { static_compression: (compression, expected), events, road_changes, airborne })
}

/// The ride over the bump, from rest on the road, for the showcase's pictures: 0.9–1.5 s every
/// 3 ms (201 frames), and the located switches of tyre and bump stop in between.
#[allow(dead_code)] // used by the showcase and the tests, not by this example's `main`
pub fn animation() -> Result<mbd::Animation, Box<dyn std::error::Error>> {
    let m = QuarterCar::default();
    let mut ws = QuarterCar::workspace();
    let mut q = m.initial_positions();
    StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut [0.0; 4])?;
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-9).with_atol(1e-11));
    let times: Vec<f64> = (0..=200).map(|k| 0.9 + 0.003 * k as f64).collect();
    let mut animation = mbd::Animation::new::<QuarterCar>(&m.params()).title("Quarter car over a 10 cm bump at 20 m/s");
    Simulation::new(&m, &mut dopri).start(0.0, &q, &[0.0; 6]).times(&times).run(&mut ws, |s| animation.frame(s.point.t, &s.point.q))?;
    Ok(animation)
}

#[allow(dead_code)]
fn main() {
    if let Err(e) = run(true) {
        eprintln!("bump: {e}");
        std::process::exit(1);
    }
}

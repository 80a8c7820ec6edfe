//! SVG plots of named quantities from a simulation's samples, in one call: time histories of a
//! coordinate, a velocity, a reaction and the energies; a phase portrait; a series of the user's
//! own. The files are parsed back: every series is a polyline with as many vertices as samples,
//! the legend and axis labels carry the names, and an unknown name is an error that lists what
//! can be named.
use mbd::prelude::*;
use mbd::{Plot, Sample};

mechanism! {
    /// A 1 m rod on a pin, released from horizontal.
    pub Swing {
        gravity [0.0, -9.81];
        body rod { mass: 2.0, inertia: 0.1667, at: [0.5, 0.0, 0.0] }
        revolute pin: ground[0.0, 0.0] ~ rod[-0.5, 0.0];
    }
}

fn run() -> Vec<Sample<f64, 3, 3, 2>> {
    let m = Swing::default();
    let times: Vec<f64> = (1..=200).map(|k| 0.01 * k as f64).collect();
    let mut samples = Vec::new();
    Simulation::new(&m, &mut mbd::Dopri5::default())
        .start(0.0, &m.initial_positions(), &[0.0; 3])
        .times(&times)
        .run(&mut Swing::workspace(), |s| samples.push(*s))
        .expect("swings");
    samples
}

/// The vertices of each `<polyline>` of an SVG file.
fn polylines(svg: &str) -> Vec<usize> {
    svg.match_indices("<polyline")
        .map(|(i, _)| {
            let points = &svg[i..];
            let start = points.find("points=\"").expect("points") + 8;
            let end = start + points[start..].find('"').expect("closed");
            points[start..end].split_whitespace().count()
        })
        .collect()
}

#[test]
fn time_histories_and_phase_portrait_as_svg() {
    let samples = run();
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/plots");
    std::fs::create_dir_all(&dir).expect("target/plots");

    let names = ["rod.phi", "d/dt rod.phi", "lambda pin: y", "kinetic", "potential"];
    let plot = Plot::time_histories::<Swing, _, 3, 3, 2>("Swing released from horizontal", &samples, &names).expect("named quantities");
    assert_eq!(plot.series_points().len(), 5);
    // The energy balance shows in the series: T + V stays at its start (DOPRI5's tolerance).
    let (t, v) = (&plot.series_points()[3].1, &plot.series_points()[4].1);
    let total: Vec<f64> = t.iter().zip(v).map(|(a, b)| a.1 + b.1).collect();
    assert!(total.iter().all(|e| (e - total[0]).abs() < 1e-4), "{total:?}");
    plot.write_svg(dir.join("swing.svg")).expect("writes");
    let svg = std::fs::read_to_string(dir.join("swing.svg")).expect("reads");
    assert!(svg.contains("Swing released from horizontal") && svg.contains("lambda pin: y") && svg.contains("t (s)"));
    let lines = polylines(&svg);
    assert_eq!(lines.iter().filter(|&&n| n == 200).count(), 5, "{lines:?}");

    let phase = Plot::xy::<Swing, _, 3, 3, 2>("Phase portrait", &samples, "rod.phi", "d/dt rod.phi").expect("named");
    // A user's own series beside it: the closed-form energy bound ω² = 2 m g (l/2) (−sin φ) / J_o.
    let own = samples.iter().map(|s| {
        let phi = s.point.q[2];
        (phi, -(2.0 * 2.0 * 9.81 * 0.5 * (-phi.sin()) / (0.1667 + 0.5)).max(0.0).sqrt())
    });
    phase.series("energy: −√(2 m g c (−sin φ) / J_o)", own).write_svg(dir.join("swing_phase.svg")).expect("writes");
    let svg = std::fs::read_to_string(dir.join("swing_phase.svg")).expect("reads");
    assert_eq!(polylines(&svg).iter().filter(|&&n| n == 200).count(), 2);

    let e = Plot::time_histories::<Swing, _, 3, 3, 2>("x", &samples, &["rod.theta"]).unwrap_err();
    assert!(e.to_string().starts_with("Swing has no quantity `rod.theta`: name a coordinate"), "{e}");
}

//! The animation page in a real browser: headless Chromium (Debian's package, installed by
//! `.ci/ensure_chromium.sh`) loads each page with no network, runs its script, and the test
//! reads the DOM it leaves (`<p id="status">`: "drew frame k of n", or the error that stopped
//! it) and saves a screenshot under `target/animation/`. Pages: a four-bar's kinematic sweep with
//! a coupler-point trace, the quarter car of `examples/bump.rs` simulated over its bump (tyre,
//! bump stop, spring-damper), a spatial double pendulum; and a page asked to trace a point the
//! mechanism does not have, which must say so.
use mbd_examples::{bump, four_bar};
/// The examples this test uses (from mbd-examples, where they are compiled once) and the shared
/// generator (`tests/common/`).
mod common {
    pub(crate) use super::{bump, four_bar};
}

use std::path::{Path, PathBuf};
use std::process::Command;

use common::bump::QuarterCar;
use common::four_bar::FourBar;
use mbd::prelude::*;
use mbd::{Animation, Dopri5, Dopri5Options, StaticSolver};

mechanism! {
    /// Two bodies on ball joints hanging from the origin, released from a tilt.
    pub SpatialDoublePendulum {
        spatial;
        gravity [0.0, 0.0, -9.81];
        body upper { mass: 1.0, inertia: [0.02, 0.02, 0.005], at: [0.15, 0.0, -0.26], axis_angle: [0.0, 1.0, 0.0, 0.52] }
        body lower { mass: 0.5, inertia: [0.01, 0.01, 0.002], at: [0.3, 0.1, -0.7], axis_angle: [0.0, 1.0, 0.0, 0.2] }
        spherical ground[0.0, 0.0, 0.0] ~ upper[0.0, 0.0, 0.3];
        spherical upper[0.0, 0.0, -0.3] ~ lower[0.0, 0.0, 0.2];
        point lower.tip = [0.0, 0.0, -0.2];
    }
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Chromium's binary: installed by the project's script. Without CI a machine that cannot
/// install it skips the browser checks, saying so; under CI that is a failure.
fn chromium() -> Option<PathBuf> {
    let out = Command::new("bash").arg(repo().join(".ci/ensure_chromium.sh")).output().expect("bash runs");
    if out.status.success() {
        return Some(PathBuf::from(String::from_utf8_lossy(&out.stdout).trim()));
    }
    let why = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(std::env::var("CI").is_err(), "CI=true: Chromium could not be installed: {why}");
    eprintln!("SKIPPED: the browser checks need Chromium, which could not be installed here: {why}");
    None
}

/// Loads `page` headless; returns the DOM after its script ran, and writes a screenshot to
/// `png`, which must hold a drawing unless the page is `blank`.
fn load(browser: &Path, page: &Path, png: &Path, blank: bool) -> String {
    let url = format!("file://{}", page.canonicalize().expect("the page exists").display());
    let common =
        ["--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--window-size=860,720", "--virtual-time-budget=2000"];
    let dom = Command::new(browser).args(common).arg("--dump-dom").arg(&url).output().expect("chromium runs");
    assert!(dom.status.success(), "chromium failed: {}", String::from_utf8_lossy(&dom.stderr));
    let shot = Command::new(browser).args(common).arg(format!("--screenshot={}", png.display())).arg(&url).output().expect("chromium runs");
    assert!(shot.status.success(), "chromium failed: {}", String::from_utf8_lossy(&shot.stderr));
    // A blank canvas compresses to ~10 kB; a drawn mechanism adds lines, fills and text.
    let size = std::fs::metadata(png).map(|m| m.len()).unwrap_or(0);
    assert!(blank || size > 15_000, "screenshot {} has {size} bytes: nothing drawn?", png.display());
    String::from_utf8_lossy(&dom.stdout).to_string()
}

/// The status line the page leaves.
fn status(dom: &str) -> String {
    let start = dom.find("<p id=\"status\">").expect("the page has its status line") + "<p id=\"status\">".len();
    let end = start + dom[start..].find("</p>").expect("closed");
    dom[start..end].to_string()
}

fn out_dir() -> PathBuf {
    let dir = repo().join("target/animation");
    std::fs::create_dir_all(&dir).expect("target/animation");
    dir
}

/// Asserts that the page drew its frames without an error.
fn drew(dom: &str, frames: usize) {
    let s = status(dom);
    assert!(s.starts_with("drew frame ") && s.ends_with(&format!(" of {frames}")), "status: {s}");
}

fn four_bar_page() -> Animation {
    let m = FourBar::default();
    let mut ws = FourBar::workspace();
    let mut q = m.initial_positions();
    let solver = KinematicSolver::default();
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let mut animation = Animation::new::<FourBar>(&m.params()).title("Four-bar, one crank turn").trace("coupler.P");
    let period = 2.0 * std::f64::consts::PI / m.omega;
    let times = (0..=120).map(|k| period * k as f64 / 120.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.frame(t, q)).expect("sweeps");
    animation
}

#[test]
fn pages_draw_in_a_browser() {
    let Some(browser) = chromium() else { return };
    let dir = out_dir();

    let four_bar = four_bar_page();
    assert_eq!(four_bar.len(), 121);
    four_bar.write_html(dir.join("four_bar.html")).expect("writes");
    drew(&load(&browser, &dir.join("four_bar.html"), &dir.join("four_bar.png"), false), 121);

    // The quarter car over its bump: unilateral tyre and stop, spring-damper, sliders.
    let m = QuarterCar::default();
    let mut ws = QuarterCar::workspace();
    let mut q = m.initial_positions();
    StaticSolver::default().solve(&m, &mut ws, &mut q, 0.0, &mut [0.0; 4]).expect("rests on its tyre");
    let mut animation = Animation::new::<QuarterCar>(&m.params());
    let times: Vec<f64> = (0..=150).map(|k| 0.9 + 0.002 * k as f64).collect();
    let mut dopri = Dopri5::new(Dopri5Options::default().with_rtol(1e-8));
    let before: Vec<f64> = (0..90).map(|k| 0.01 * k as f64).collect();
    let mut state = (0.0, q, [0.0; 6]);
    Simulation::new(&m, &mut dopri)
        .start(0.0, &q, &[0.0; 6])
        .times(&before)
        .run(&mut ws, |s| {
            state = (s.point.t, s.point.q, s.point.v);
        })
        .expect("rolls to the bump");
    Simulation::new(&m, &mut dopri)
        .start(state.0, &state.1, &state.2)
        .times(&times)
        .run(&mut ws, |s| animation.frame(s.point.t, &s.point.q))
        .expect("rides the bump");
    animation.write_html(dir.join("quarter_car.html")).expect("writes");
    drew(&load(&browser, &dir.join("quarter_car.html"), &dir.join("quarter_car.png"), false), animation.len());

    // A spatial page: the orthographic view.
    let m = SpatialDoublePendulum::default();
    let mut q = m.initial_positions();
    let mut ws = SpatialDoublePendulum::workspace();
    KinematicSolver::default().assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let mut animation = Animation::new::<SpatialDoublePendulum>(&m.params()).trace("lower.tip");
    let times: Vec<f64> = (1..=100).map(|k| 0.02 * k as f64).collect();
    Simulation::new(&m, &mut Dopri5::default())
        .start(0.0, &q, &[0.0; 12])
        .times(&times)
        .run(&mut ws, |s| animation.frame(s.point.t, &s.point.q))
        .expect("swings");
    animation.write_html(dir.join("spatial_double_pendulum.html")).expect("writes");
    drew(&load(&browser, &dir.join("spatial_double_pendulum.html"), &dir.join("spatial_double_pendulum.png"), false), 100);

    // A trace of a point the mechanism does not have: the page says so instead of drawing.
    // (written past `write_html`'s own check, which `a_misspelt_trace_is_an_error` tests)
    let mut wrong = Animation::new::<FourBar>(&FourBar::default().params()).trace("coupler.Q");
    wrong.frame(0.0, &FourBar::default().initial_positions());
    std::fs::write(dir.join("wrong_trace.html"), wrong.to_html()).expect("writes");
    let s = status(&load(&browser, &dir.join("wrong_trace.html"), &dir.join("wrong_trace.png"), true));
    assert!(s.starts_with("error: no named point coupler.Q"), "status: {s}");

    // `#t=` opens the page paused at that time: the four-bar's frame 61 of 121 is at half a turn.
    let half = format!("{}#t={}", dir.join("four_bar.html").display(), std::f64::consts::PI / FourBar::default().omega + 1e-9);
    let dom = Command::new(&browser)
        .args(["--headless", "--no-sandbox", "--disable-gpu", "--virtual-time-budget=2000", "--dump-dom"])
        .arg(format!("file://{half}"))
        .output()
        .expect("chromium runs");
    assert_eq!(status(&String::from_utf8_lossy(&dom.stdout)), "drew frame 61 of 121");

    // The animated SVG draws in the browser too.
    four_bar.write_svg(dir.join("four_bar.svg")).expect("writes");
    load(&browser, &dir.join("four_bar.svg"), &dir.join("four_bar_svg.png"), false);

    // The four-bar in joint coordinates, drawn from its bodies' poses.
    joint_four_bar_page().write_html(dir.join("four_bar_joint.html")).expect("writes");
    drew(&load(&browser, &dir.join("four_bar_joint.html"), &dir.join("four_bar_joint.png"), false), 121);
}

/// The four-bar of `examples/four_bar.rs` in joint coordinates (`mbd_examples::joint`), swept
/// through one crank turn, its frames the bodies' poses (`Animation::from_bodies`).
fn joint_four_bar_page() -> Animation {
    use mbd_examples::joint::four_bar_0::FourBar as JointFourBar;
    let m = JointFourBar::default();
    let mut ws = JointFourBar::workspace();
    let mut q = m.initial_positions();
    let solver = KinematicSolver::default();
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let mut animation = Animation::from_bodies::<JointFourBar>(&m.params()).title("Four-bar, one crank turn").trace("coupler.P");
    let period = 2.0 * std::f64::consts::PI / m.omega;
    let times = (0..=120).map(|k| period * k as f64 / 120.0);
    solver.sweep(&m, &mut ws, &mut q, times, |t, q, _, _| animation.body_frame(&m, t, q)).expect("sweeps");
    animation
}

/// A mechanism in joint coordinates draws what the same mechanism in body coordinates draws:
/// the four-bar's animated SVG from its bodies' poses has the body-coordinate one's frames,
/// and in each the same pins, centres of mass and traced point where they are (both sweeps meet
/// the loop to 1e-10 m; the picture rounds to 0.01 px, so a coordinate may differ by one
/// rounding; the bodies' outlines may list a point on a straight edge or not, so they are not
/// compared); and `from_bodies` refuses a spatial mechanism, saying which constructor draws it.
#[test]
fn joint_coordinates_draw_from_the_bodies_poses() {
    let (joint, body) = (joint_four_bar_page().to_svg().expect("draws"), four_bar_page().to_svg().expect("draws"));
    // every number of every `<circle …>`, and of the trace's polyline, in order
    let marks = |svg: &str| -> Vec<f64> {
        let trace = svg.split("<polyline points=\"").nth(1).and_then(|t| t.split('"').next()).unwrap_or("").to_string();
        let circles = svg.split("<circle ").skip(1).map(|c| c.split("/>").next().unwrap_or("").to_string());
        std::iter::once(trace)
            .chain(circles)
            .flat_map(|s| {
                s.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-')).filter_map(|x| x.parse::<f64>().ok()).collect::<Vec<_>>()
            })
            .collect()
    };
    let (j, b) = (marks(&joint), marks(&body));
    assert_eq!(joint.matches("<g visibility=").count(), 121);
    assert!(j.len() > 121 * 6 * 3 && j.len() == b.len(), "{} and {} numbers", j.len(), b.len());
    let worst = j.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    assert!(worst <= 0.0100001, "a mark differs by {worst} px");
    let mut spatial = Animation::from_bodies::<SpatialDoublePendulum>(&SpatialDoublePendulum::default().params());
    let m = SpatialDoublePendulum::default();
    spatial.body_frame(&m, 0.0, &m.initial_positions());
    let e = spatial.to_svg().expect_err("planar only");
    assert!(e.to_string().contains("expected a planar mechanism, found a spatial one"), "{e}");
}

/// A traced point the mechanism does not name is an error when the page or picture is written,
/// naming it and the points there are.
#[test]
fn a_misspelt_trace_is_an_error() {
    let mut wrong = Animation::new::<FourBar>(&FourBar::default().params()).trace("coupler.Q");
    wrong.frame(0.0, &FourBar::default().initial_positions());
    let path = out_dir().join("never_written.html");
    let e = wrong.write_html(&path).expect_err("no point coupler.Q");
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput);
    assert!(e.to_string().contains("no named point `coupler.Q`") && e.to_string().contains("coupler.P"), "{e}");
    assert!(!path.exists());
    assert_eq!(wrong.to_svg().expect_err("no point coupler.Q").to_string(), e.to_string());
}

/// The animated SVG: one group per frame, each shown in turn by a discrete SMIL animation at its
/// own time; and what it draws is where the mechanism is — the traced coupler point's path in
/// the picture is the generated accessor's path, up to the view's scale and offset.
#[test]
fn the_animated_svg_shows_each_frame_at_its_time() {
    let animation = four_bar_page();
    let svg = animation.to_svg().expect("draws");
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\"") && svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<g visibility=").count(), 121);
    assert_eq!(svg.matches("calcMode=\"discrete\"").count(), 121);
    // three bodies in every frame, each drawn with its centre of mass marked
    assert_eq!(svg.matches("stroke-width=\"3\"").count(), 3 * 121);
    assert_eq!(svg.matches("r=\"2.5\"").count(), 3 * 121);
    // frame 61 of 121 (half the turn) shows from 0.5 to 0.5 + 1/120 of the duration
    let period = 2.0 * std::f64::consts::PI / FourBar::default().omega;
    assert!(svg.contains(&format!("keyTimes=\"0;{:.6};{:.6}\" dur=\"{period:.6}s\"", 0.5, 0.5 + 1.0 / 120.0)), "no frame at half the turn");

    // The trace: the first polyline after the legend's colour, 121 screen points.
    let start = svg.find("<polyline points=\"").expect("the trace") + "<polyline points=\"".len();
    let points: Vec<[f64; 2]> = svg[start..start + svg[start..].find('"').unwrap()]
        .split(' ')
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            [x.parse().unwrap(), y.parse().unwrap()]
        })
        .collect();
    assert_eq!(points.len(), 121);
    let m = FourBar::default();
    let mut ws = FourBar::workspace();
    let mut q = m.initial_positions();
    let solver = KinematicSolver::default();
    solver.assemble(&m, &mut ws, &mut q, 0.0).expect("assembles");
    let mut path = Vec::new();
    let times = (0..=120).map(|k| period * k as f64 / 120.0);
    solver.sweep(&m, &mut ws, &mut q, times, |_, q, _, _| path.push(m.coupler_p().position(q))).expect("sweeps");
    // screen = offset + scale (x, −y): the scale from the path's extent in x
    let (lo, hi) = path.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.x), h.max(p.x)));
    let (slo, shi) = points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p[0]), h.max(p[0])));
    let scale = (shi - slo) / (hi - lo);
    let offset = [points[0][0] - scale * path[0].x, points[0][1] + scale * path[0].y];
    for (p, s) in path.iter().zip(&points) {
        // the SVG's coordinates have 2 decimals: 0.005 px each, 0.02 px after the fit
        assert!((offset[0] + scale * p.x - s[0]).abs() < 0.02 && (offset[1] - scale * p.y - s[1]).abs() < 0.02, "{p:?} drawn at {s:?}");
    }

    // A long run keeps at most `svg_frames` frames, its last among them.
    let few = four_bar_page().svg_frames(50).to_svg().expect("draws");
    let groups = few.matches("<g visibility=").count();
    assert!((41..=50).contains(&groups), "{groups} frames");
    assert!(few.contains(&format!("t = {period:.3} s")), "the last frame is kept");
}

/// Everything is inline: no script, style or image is fetched.
#[test]
fn the_page_is_self_contained() {
    let html = four_bar_page().to_html();
    for needle in ["src=", "href=", "http:", "https:", "@MODEL@", "@DATA@", "@SCRIPT@"] {
        assert!(!html.contains(needle), "the page contains {needle}");
    }
    assert!(html.contains("\"traces\": [\"coupler.P\"]"));
}

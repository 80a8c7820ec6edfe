//! What the study writes: the CSV of every run, a log-log SVG per case (error against CPU time,
//! one panel per drift control) and the markdown summary.

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use crate::sweep::{methods, Drift, Measured, Method, Row, DRIFTS};

/// One case's header facts for the report.
pub struct CaseSummary {
    pub name: &'static str,
    pub title: &'static str,
    pub sizes: [usize; 3],
    pub t_end: f64,
    pub reference_seconds: f64,
    pub uncertainty: f64,
    pub dopri5: f64,
    /// max |Δq| of CasADi's CVODES from the reference, or why it was not run.
    pub casadi: Result<f64, String>,
}

/// The accuracy targets of the summary tables (max |Δq| over the output times, m and rad).
pub const TARGETS: [f64; 4] = [1e-3, 1e-6, 1e-9, 1e-11];

pub fn csv(rows: &[Row], path: &Path) -> std::io::Result<()> {
    let mut out = String::from(
        "case,method,rho_infinity,setting_name,setting,drift,outcome,error_q_max,constraint_max_m,energy_error_J,cpu_s,repeats,steps,evaluations,newton_iterations,message\n",
    );
    for r in rows {
        let rho = match r.method {
            Method::GeneralizedAlpha { rho_infinity } | Method::AdaptiveGeneralizedAlpha { rho_infinity } => rho_infinity.to_string(),
            _ => String::new(),
        };
        let name = match r.method {
            Method::GeneralizedAlpha { .. } => "GeneralizedAlpha".to_string(),
            Method::AdaptiveGeneralizedAlpha { .. } => "AdaptiveGeneralizedAlpha".to_string(),
            m => m.label(),
        };
        let head = format!(
            "{},{name},{rho},{},{:e},{}",
            r.case,
            r.method.setting_name().split(' ').next().unwrap_or(""),
            r.setting,
            r.drift.label()
        );
        match &r.outcome {
            Ok(m) => writeln!(
                out,
                "{head},ok,{:e},{:e},{:e},{:e},{},{},{},{},",
                m.error, m.constraint, m.energy, m.seconds, m.repeats, m.steps, m.evaluations, m.newton
            ),
            Err(e) => {
                let kind = if e.starts_with("skipped") { "skipped" } else { "failed" };
                writeln!(out, "{head},{kind},,,,,,,,,\"{}\"", e.replace('"', "'"))
            }
        }
        .unwrap();
    }
    std::fs::write(path, out)
}

fn colour(method: Method) -> RGBColor {
    match method {
        Method::Rk4 => RGBColor(31, 119, 180),
        Method::Dopri5 => RGBColor(44, 160, 44),
        Method::Dop853 => RGBColor(214, 39, 40),
        Method::GeneralizedAlpha { rho_infinity } if rho_infinity < 0.7 => RGBColor(140, 86, 75),
        Method::GeneralizedAlpha { rho_infinity } if rho_infinity < 0.9 => RGBColor(255, 127, 14),
        Method::GeneralizedAlpha { .. } => RGBColor(148, 103, 189),
        Method::AdaptiveGeneralizedAlpha { .. } => RGBColor(23, 190, 207),
        Method::Bdf => RGBColor(227, 119, 194),
        Method::Radau5 => RGBColor(188, 189, 34),
        Method::Auto => RGBColor(23, 190, 207),
        Method::MuJoCoRk4 => RGBColor(0, 0, 0),
    }
}

/// Every method of the sweep, then the peer.
fn plotted() -> impl Iterator<Item = Method> {
    methods().into_iter().map(|(m, _)| m).chain([Method::MuJoCoRk4])
}

/// Log-log error against CPU time, a panel per drift control, a series per method.
pub fn plot(summary: &CaseSummary, rows: &[Row], path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let ok: Vec<(&Row, &Measured)> = rows.iter().filter_map(|r| r.outcome.as_ref().ok().map(|m| (r, m))).collect();
    let floor = 1e-16;
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (_, m) in &ok {
        x0 = x0.min(m.seconds);
        x1 = x1.max(m.seconds);
        y0 = y0.min(m.error.max(floor));
        y1 = y1.max(m.error.max(floor));
    }
    if ok.is_empty() {
        (x0, x1, y0, y1) = (1e-4, 1.0, 1e-12, 1.0);
    }
    let (x0, x1) = (x0 / 2.0, x1 * 2.0);
    let (y0, y1) = ((y0 / 10.0).min(summary.uncertainty.max(floor) / 2.0), (y1 * 10.0).min(1e3));
    let root = SVGBackend::new(path, (1400, 1000)).into_drawing_area();
    root.fill(&WHITE)?;
    let title = format!(
        "{} — {} (NQ {}, NV {}, NC {}), {} s; reference DOP853 rtol 1e-13, resolved to {:.1e} (grey line)",
        summary.name, summary.title, summary.sizes[0], summary.sizes[1], summary.sizes[2], summary.t_end, summary.uncertainty
    );
    let root = root.titled(&title, ("sans-serif", 20))?;
    for (panel, drift) in root.split_evenly((2, 2)).iter().zip(DRIFTS) {
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("drift control: {}", drift.label()), ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("CPU time (s, median)")
            .y_desc("max |Δq| over the outputs (m, rad)")
            .x_label_formatter(&|x| format!("{x:.0e}"))
            .y_label_formatter(&|y| format!("{y:.0e}"))
            .draw()?;
        chart.draw_series(LineSeries::new([(x0, summary.uncertainty.max(floor)), (x1, summary.uncertainty.max(floor))], BLACK.mix(0.3)))?;
        for method in plotted() {
            let points: Vec<(f64, f64)> =
                ok.iter().filter(|(r, _)| r.method == method && r.drift == drift).map(|(_, m)| (m.seconds, m.error.max(floor))).collect();
            if points.is_empty() {
                continue;
            }
            let c = colour(method);
            chart
                .draw_series(LineSeries::new(points.clone(), c.stroke_width(2)))?
                .label(method.label())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
            chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, c.filled())))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()?;
    }
    root.present()?;
    Ok(())
}

/// The cheapest run (of any method and drift control) whose error is at most `target`.
fn cheapest<'a>(rows: &'a [Row], case: &str, target: f64, drift: Option<Drift>) -> Option<(&'a Row, &'a Measured)> {
    rows.iter()
        .filter(|r| r.case == case && drift.is_none_or(|d| r.drift == d))
        .filter_map(|r| r.outcome.as_ref().ok().map(|m| (r, m)))
        .filter(|(_, m)| m.error <= target)
        .min_by(|a, b| a.1.seconds.total_cmp(&b.1.seconds))
}

fn describe(r: &Row, m: &Measured) -> String {
    let setting = match r.method {
        Method::Dopri5 | Method::Dop853 | Method::AdaptiveGeneralizedAlpha { .. } | Method::Bdf | Method::Radau5 | Method::Auto => {
            format!("rtol {:.0e}", r.setting)
        }
        _ => format!("h {:.0e}", r.setting),
    };
    format!("{} ({setting}, {}): {}", r.method.label(), r.drift.label(), time(m.seconds))
}

pub fn time(s: f64) -> String {
    if s < 1e-3 {
        format!("{:.0} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.1} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

/// The markdown summary: the headline (cheapest run per accuracy target and case), then per
/// case the cheapest run of each method with the default drift control and the failures.
pub fn markdown(summaries: &[CaseSummary], rows: &[Row], header: &str) -> String {
    let mut out = String::new();
    writeln!(out, "{header}\n").unwrap();
    writeln!(out, "## Cheapest run reaching each accuracy (any method, any drift control)\n").unwrap();
    write!(out, "| case |").unwrap();
    for t in TARGETS {
        write!(out, " error ≤ {t:.0e} |").unwrap();
    }
    writeln!(out, "\n|---|{}", "---|".repeat(TARGETS.len())).unwrap();
    for s in summaries {
        write!(out, "| {} |", s.name).unwrap();
        for t in TARGETS {
            let cell = if t < s.uncertainty {
                "below the reference's resolution".to_string()
            } else {
                cheapest(rows, s.name, t, None).map_or("—".to_string(), |(r, m)| describe(r, m))
            };
            write!(out, " {cell} |").unwrap();
        }
        writeln!(out).unwrap();
    }
    peers(&mut out, summaries, rows);
    for s in summaries {
        writeln!(
            out,
            "\n## {} — {}\n\nNQ {}, NV {}, NC {}; {} s of motion; reference DOP853 at rtol 1e-13 ({}), DOPRI5 at 1e-12 within {:.1e} of it; {}; errors below {:.1e} are not resolved. Plot: [{}.svg]({}.svg).\n",
            s.name,
            s.title,
            s.sizes[0],
            s.sizes[1],
            s.sizes[2],
            s.t_end,
            time(s.reference_seconds),
            s.dopri5,
            match &s.casadi {
                Ok(d) => format!("CasADi's CVODES (Adams, rtol 1e-12) on the oracle's rebuild within {d:.1e}"),
                Err(e) => format!("**not cross-checked against CasADi**: {}", e.replace('\n', " ")),
            },
            s.uncertainty,
            s.name,
            s.name
        )
        .unwrap();
        writeln!(
            out,
            "| method | drift control | setting | error | ‖Φ‖∞ max (m) | energy error (J) | CPU | steps | evaluations | Newton |"
        )
        .unwrap();
        writeln!(out, "|---|---|---|---|---|---|---|---|---|---|").unwrap();
        for r in rows.iter().filter(|r| r.case == s.name) {
            let setting = format!("{} {:.0e}", r.method.setting_name(), r.setting);
            match &r.outcome {
                Ok(m) => writeln!(
                    out,
                    "| {} | {} | {setting} | {:.1e} | {:.1e} | {:.1e} | {} | {} | {} | {} |",
                    r.method.label(),
                    r.drift.label(),
                    m.error,
                    m.constraint,
                    m.energy,
                    time(m.seconds),
                    m.steps,
                    m.evaluations,
                    m.newton
                ),
                Err(e) if e.starts_with("skipped") => Ok(()),
                Err(e) => writeln!(
                    out,
                    "| {} | {} | {setting} | failed: {} | | | | | | |",
                    r.method.label(),
                    r.drift.label(),
                    e.replace('|', "/")
                ),
            }
            .unwrap();
        }
    }
    out
}

/// mbd's RK4 (no drift control, like MuJoCo's joint coordinates need none) against MuJoCo's RK4
/// at the same steps on the same chains: time per step and error against the same reference.
fn peers(out: &mut String, summaries: &[CaseSummary], rows: &[Row]) {
    let cases: Vec<&CaseSummary> =
        summaries.iter().filter(|s| rows.iter().any(|r| r.case == s.name && r.method == Method::MuJoCoRk4)).collect();
    if cases.is_empty() {
        return;
    }
    writeln!(out, "\n## Against MuJoCo's RK4 on the chains (same run, same reference)\n").unwrap();
    writeln!(out, "MuJoCo in joint coordinates (hinges), mbd in body coordinates with the joints as constraints (RK4, no drift control); time per step from each run's CPU time; ‖Φ‖∞ is mbd's constraints at MuJoCo's coordinates (zero up to rounding: joint coordinates hold the joints exactly). Where both runs are stable their errors agree to about ten digits, and should: in a planar chain the links' absolute angles are a linear function of the joint angles, and mbd's angular accelerations depend on the angles and rates alone (D and γ of a pin chain do not involve x and y), so both integrate the same ODE in linearly related variables, and RK4 is invariant under linear changes of variables. The same physics, then, and the difference is the time per step (and mbd's uncorrected drift in x and y, in its own rows above).\n").unwrap();
    writeln!(out, "| case | h (s) | mbd: µs/step | mbd: error | MuJoCo: µs/step | MuJoCo: error | time ratio mbd/MuJoCo |").unwrap();
    writeln!(out, "|---|---|---|---|---|---|---|").unwrap();
    for s in cases {
        let find = |method: Method, h: f64| {
            rows.iter().find(|r| r.case == s.name && r.method == method && r.drift == Drift::None && r.setting == h)
        };
        for h in crate::sweep::STEPS_RK4 {
            let cell = |r: Option<&Row>| match r.map(|r| &r.outcome) {
                Some(Ok(m)) => (format!("{:.2}", m.seconds / m.steps as f64 * 1e6), format!("{:.1e}", m.error), Some(m.seconds)),
                Some(Err(e)) => ("—".into(), format!("failed: {}", e.replace('|', "/")), None),
                None => ("—".into(), "—".into(), None),
            };
            let (ours, theirs) = (cell(find(Method::Rk4, h)), cell(find(Method::MuJoCoRk4, h)));
            let ratio = match (ours.2, theirs.2) {
                (Some(a), Some(b)) => format!("{:.2}", a / b),
                _ => "—".into(),
            };
            writeln!(out, "| {} | {h:.0e} | {} | {} | {} | {} | {ratio} |", s.name, ours.0, ours.1, theirs.0, theirs.1).unwrap();
        }
    }
}

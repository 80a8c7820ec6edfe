//! The mechanism's drawing, read from its [`crate::Mechanism::MODEL_JSON`]: every body's attachment
//! points (joint markers, force-element ends, named points) in its own frame, evaluated at the
//! parameter values; and [`Drawing::svg`], an animated SVG of frames (t, q) that plays in any
//! browser and in a README — the same picture as [`crate::Animation`]'s page draws on its canvas:
//! bodies as the hull of their attachment points, joints as rings, slider guides, ground hatched,
//! springs as zig-zags, dampers, cables, tyres with their road, contacts, and traced points.
//!
//! The SVG holds one group per frame, shown in turn by a discrete SMIL `<animate>` at the frame's
//! own time (real time, looping), so it needs no script.

use std::collections::HashMap;
use std::fmt::Write as _;

use serde_json::Value;

/// Canvas size of the SVG, as the HTML page's (px).
const WIDTH: f64 = 800.0;
const HEIGHT: f64 = 560.0;
/// The spatial view: turned about z by `YAW`, tilted by `PITCH` (rad), as the page opens.
const YAW: f64 = 0.6;
const PITCH: f64 = 0.35;
const BODY_COLOURS: [&str; 8] = ["#3465a4", "#c4a000", "#75507b", "#cc0000", "#4e9a06", "#ce5c00", "#204a87", "#8f5902"];
const TRACE_COLOURS: [&str; 5] = ["#555", "#c00", "#06c", "#080", "#a0a"];

/// A point held by a body (`None`: ground) in its frame, with a direction where the joint has one.
#[derive(Clone, Debug)]
struct Marker {
    body: Option<usize>,
    s: Vec<f64>,
    axis: Option<Vec<f64>>,
}

/// A force element's ends and what to draw between them.
#[derive(Clone, Debug)]
struct Element {
    kind: String,
    i: Marker,
    j: Marker,
    spring: bool,
    damper: bool,
    /// A tyre's radius (m) and road height expression.
    tyre: Option<(f64, Value)>,
}

/// What a mechanism's picture is made of.
#[derive(Clone, Debug)]
pub(crate) struct Drawing {
    spatial: bool,
    coordinates: HashMap<String, usize>,
    params: HashMap<String, f64>,
    bodies: Vec<String>,
    /// Per body: its attachment points in its frame.
    attach: Vec<Vec<Vec<f64>>>,
    ground: Vec<Vec<f64>>,
    joints: Vec<(String, Marker, Marker)>,
    elements: Vec<Element>,
    /// Named points, `"coupler.P"`, in the order declared.
    named: Vec<(String, Marker)>,
}

impl Drawing {
    /// The drawing of a mechanism from its `MODEL_JSON`, at these parameter values (in
    /// `PARAM_NAMES` order).
    pub(crate) fn from_json(model: &str, param_names: &[&str], params: &[f64]) -> Result<Self, String> {
        let model: Value = serde_json::from_str(model).map_err(|e| format!("the model JSON does not parse: {e}"))?;
        let list = |key: &str| model[key].as_array().cloned().unwrap_or_default();
        let bodies: Vec<String> = list("bodies").iter().map(|b| b["name"].as_str().unwrap_or("").to_string()).collect();
        let coordinates = list("coordinates").iter().enumerate().filter_map(|(k, c)| Some((c.as_str()?.to_string(), k))).collect();
        let params = param_names.iter().zip(params).map(|(n, v)| (n.to_string(), *v)).collect();
        let mut d = Drawing {
            spatial: model["dimension"].as_u64() == Some(3),
            coordinates,
            params,
            attach: vec![Vec::new(); bodies.len()],
            bodies,
            ground: Vec::new(),
            joints: Vec::new(),
            elements: Vec::new(),
            named: Vec::new(),
        };
        for c in list("constraints") {
            if let (Some(i), Some(j)) = (d.marker(&c["i"])?, d.marker(&c["j"])?) {
                d.joints.push((c["kind"].as_str().unwrap_or("").to_string(), i, j));
            }
        }
        for f in list("forces") {
            if f["i"].is_object() {
                let (Some(i), Some(j)) = (d.marker(&f["i"])?, d.marker(&f["j"])?) else { continue };
                let kind = f["kind"].as_str().unwrap_or("").to_string();
                let tyre = if kind == "tyre" { Some((d.constant(&f["radius"])?, f["road"].clone())) } else { None };
                d.elements.push(Element { kind, i, j, spring: !f["k"].is_null(), damper: !f["c"].is_null(), tyre });
            } else if f["at"].is_object() {
                d.marker(&f["at"])?;
            }
        }
        for p in list("points") {
            let body = p["body"].as_str().unwrap_or("");
            let s = d.local(&p["local"])?;
            let index = d.bodies.iter().position(|b| b == body);
            if let Some(k) = index {
                d.attach[k].push(s.clone());
            }
            d.named.push((format!("{body}.{}", p["name"].as_str().unwrap_or("")), Marker { body: index, s, axis: None }));
        }
        Ok(d)
    }

    /// How many shapes a frame draws: bodies, joints and force elements.
    pub(crate) fn shapes(&self) -> usize {
        self.bodies.len() + self.joints.len() + self.elements.len()
    }

    /// The names of the points a trace may follow.
    pub(crate) fn point_names(&self) -> impl Iterator<Item = &str> {
        self.named.iter().map(|(n, _)| n.as_str())
    }

    /// The named point `name`, or an error listing those there are.
    fn named(&self, name: &str) -> Result<&Marker, String> {
        self.named.iter().find(|(n, _)| n == name).map(|(_, m)| m).ok_or_else(|| {
            let known: Vec<&str> = self.point_names().collect();
            let known = if known.is_empty() { "it declares none".to_string() } else { format!("it declares {}", known.join(", ")) };
            format!("no named point `{name}` to trace (declare it with `point {name} = [...]`); {known}")
        })
    }

    /// Checks that every traced point exists.
    pub(crate) fn check_traces(&self, traces: &[String]) -> Result<(), String> {
        traces.iter().try_for_each(|t| self.named(t).map(|_| ()))
    }

    /// A joint's or element's marker, its point added to its body's attachments.
    fn marker(&mut self, m: &Value) -> Result<Option<Marker>, String> {
        if !m.is_object() || m["point"].is_null() {
            return Ok(None);
        }
        let s = self.local(&m["point"])?;
        let axis = if m["axis"].is_array() { Some(self.local(&m["axis"])?) } else { None };
        let body = m["body"].as_str().unwrap_or("ground");
        let index = self.bodies.iter().position(|b| b == body);
        match index {
            Some(k) => self.attach[k].push(s.clone()),
            None => self.ground.push(s.clone()),
        }
        Ok(Some(Marker { body: index, s, axis }))
    }

    /// A body-frame list of expressions, at the parameters (t = 0, q = 0, as the page does).
    fn local(&self, list: &Value) -> Result<Vec<f64>, String> {
        let zero = vec![0.0; self.coordinates.len()];
        list.as_array().ok_or("a point is not a list")?.iter().map(|e| self.eval(e, 0.0, &zero)).collect()
    }

    fn constant(&self, e: &Value) -> Result<f64, String> {
        self.eval(e, 0.0, &vec![0.0; self.coordinates.len()])
    }

    /// A model expression at time t and coordinates q (velocities 0: a picture has none).
    fn eval(&self, e: &Value, t: f64, q: &[f64]) -> Result<f64, String> {
        let Some(items) = e.as_array() else { return Ok(0.0) };
        let op = items.first().and_then(Value::as_str).unwrap_or("");
        let arg = |k: usize| self.eval(items.get(k).unwrap_or(&Value::Null), t, q);
        Ok(match op {
            "num" => items.get(1).and_then(Value::as_f64).unwrap_or(f64::NAN),
            "pi" => std::f64::consts::PI,
            "t" => t,
            "param" => *self.params.get(items[1].as_str().unwrap_or("")).ok_or("an unknown parameter")?,
            "coord" => {
                let name = format!("{}.{}", items[1].as_str().unwrap_or(""), items[2].as_str().unwrap_or(""));
                self.coordinates.get(&name).and_then(|&k| q.get(k)).copied().unwrap_or(0.0)
            }
            "vel" => 0.0,
            "neg" => -arg(1)?,
            "add" => arg(1)? + arg(2)?,
            "sub" => arg(1)? - arg(2)?,
            "mul" => arg(1)? * arg(2)?,
            "div" => arg(1)? / arg(2)?,
            "pow" => arg(1)?.powf(arg(2)?),
            "atan2" => arg(1)?.atan2(arg(2)?),
            "min" => arg(1)?.min(arg(2)?),
            "max" => arg(1)?.max(arg(2)?),
            "clamp" => arg(1)?.max(arg(2)?).min(arg(3)?),
            "if_gt" => (if arg(1)? > arg(2)? { arg(3) } else { arg(4) })?,
            "if_ge" => (if arg(1)? >= arg(2)? { arg(3) } else { arg(4) })?,
            "sin" => arg(1)?.sin(),
            "cos" => arg(1)?.cos(),
            "tan" => arg(1)?.tan(),
            "asin" => arg(1)?.asin(),
            "acos" => arg(1)?.acos(),
            "atan" => arg(1)?.atan(),
            "exp" => arg(1)?.exp(),
            "ln" | "log" => arg(1)?.ln(),
            "sqrt" => arg(1)?.sqrt(),
            "abs" => arg(1)?.abs(),
            "sinh" => arg(1)?.sinh(),
            "cosh" => arg(1)?.cosh(),
            "tanh" => arg(1)?.tanh(),
            "sign" => {
                let x = arg(1)?;
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            }
            "deg" => arg(1)?.to_radians(),
            other => return Err(format!("an expression the drawing does not know: {other}")),
        })
    }

    /// World position of body-frame point `s` of `body` at q.
    fn world(&self, body: Option<usize>, s: &[f64], q: &[f64]) -> Vec<f64> {
        let Some(k) = body else { return s.to_vec() };
        let at = |i: usize| q.get(i).copied().unwrap_or(f64::NAN);
        if !self.spatial {
            let (x, y, phi) = (at(3 * k), at(3 * k + 1), at(3 * k + 2));
            let (sn, c) = phi.sin_cos();
            return vec![x + c * s[0] - sn * s[1], y + sn * s[0] + c * s[1]];
        }
        let b = 7 * k;
        let e = [at(b + 3), at(b + 4), at(b + 5), at(b + 6)];
        let n = e.iter().map(|x| x * x).sum::<f64>().sqrt();
        let [e0, e1, e2, e3] = if n > 0.0 { e.map(|x| x / n) } else { [1.0, 0.0, 0.0, 0.0] };
        let a = [
            [2.0 * (e0 * e0 + e1 * e1) - 1.0, 2.0 * (e1 * e2 - e0 * e3), 2.0 * (e1 * e3 + e0 * e2)],
            [2.0 * (e1 * e2 + e0 * e3), 2.0 * (e0 * e0 + e2 * e2) - 1.0, 2.0 * (e2 * e3 - e0 * e1)],
            [2.0 * (e1 * e3 - e0 * e2), 2.0 * (e2 * e3 + e0 * e1), 2.0 * (e0 * e0 + e3 * e3) - 1.0],
        ];
        (0..3).map(|i| at(b + i) + a[i][0] * s[0] + a[i][1] * s[1] + a[i][2] * s[2]).collect()
    }

    fn at(&self, m: &Marker, q: &[f64]) -> Vec<f64> {
        self.world(m.body, &m.s, q)
    }

    fn origin(&self) -> Vec<f64> {
        vec![0.0; if self.spatial { 3 } else { 2 }]
    }

    /// Every drawn point at q (for the view's bounds).
    fn all_points(&self, q: &[f64]) -> Vec<Vec<f64>> {
        let mut points = self.ground.clone();
        for (k, attach) in self.attach.iter().enumerate() {
            points.push(self.world(Some(k), &self.origin(), q));
            points.extend(attach.iter().map(|s| self.world(Some(k), s, q)));
        }
        points
    }

    /// An animated SVG of `frames` (t, q), tracing the named points `traces` (module docs).
    pub(crate) fn svg(&self, title: &str, frames: &[(f64, &[f64])], traces: &[String]) -> Result<String, String> {
        self.check_traces(traces)?;
        let view = View::new(self, frames);
        let mut out = String::with_capacity(4096 + 2048 * frames.len());
        let _ = write!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{HEIGHT}\" viewBox=\"0 0 {WIDTH} {HEIGHT}\" \
             font-family=\"sans-serif\">\n<title>{}</title>\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n",
            escape(title)
        );
        let _ = writeln!(out, "<text x=\"10\" y=\"{}\" font-size=\"14\" fill=\"#222\">{}</text>", HEIGHT - 12.0, escape(title));
        for s in &self.ground {
            hatch(&mut out, view.screen(s));
        }
        // whole traces, faint, under everything; the legend
        for (n, name) in traces.iter().enumerate() {
            let marker = self.named(name)?;
            let colour = TRACE_COLOURS[n % TRACE_COLOURS.len()];
            let path: Vec<[f64; 2]> = frames.iter().map(|(_, q)| view.screen(&self.at(marker, q))).collect();
            polyline(&mut out, &path, false, colour, 1.2, "none", " stroke-opacity=\"0.6\"");
            let _ = writeln!(out, "<text x=\"10\" y=\"{}\" font-size=\"13\" fill=\"{colour}\">— {}</text>", 18 + 16 * n, escape(name));
        }
        let (t0, t1) = (frames.first().map_or(0.0, |f| f.0), frames.last().map_or(0.0, |f| f.0));
        // frames shown in real time; frames without a time span (a sequence of equilibria) 0.1 s each
        let timed = t1 > t0;
        let duration = if timed { t1 - t0 } else { 0.1 * frames.len().max(1) as f64 };
        for (k, (t, q)) in frames.iter().enumerate() {
            let start = if timed { (t - t0) / duration } else { k as f64 / frames.len() as f64 };
            let end = match frames.get(k + 1) {
                Some((next, _)) if timed => (next - t0) / duration,
                Some(_) => (k + 1) as f64 / frames.len() as f64,
                None => 1.0,
            };
            let (values, key_times) = match (start <= 0.0, end >= 1.0) {
                (true, true) => ("visible".to_string(), "0".to_string()),
                (true, false) => ("visible;hidden".to_string(), format!("0;{end:.6}")),
                (false, true) => ("hidden;visible".to_string(), format!("0;{start:.6}")),
                (false, false) => ("hidden;visible;hidden".to_string(), format!("0;{start:.6};{end:.6}")),
            };
            let _ = writeln!(
                out,
                "<g visibility=\"{}\"><animate attributeName=\"visibility\" values=\"{values}\" keyTimes=\"{key_times}\" \
                 dur=\"{duration:.6}s\" calcMode=\"discrete\" repeatCount=\"indefinite\"/>",
                if k == 0 { "visible" } else { "hidden" }
            );
            self.frame(&mut out, &view, *t, q, traces)?;
            let _ = writeln!(
                out,
                "<text x=\"{}\" y=\"{}\" font-size=\"14\" fill=\"#222\">t = {t:.3} s</text>\n</g>",
                WIDTH - 110.0,
                HEIGHT - 12.0
            );
        }
        out.push_str("</svg>\n");
        Ok(out)
    }

    /// The picture at (t, q), as the page's `draw` makes it.
    fn frame(&self, out: &mut String, view: &View, t: f64, q: &[f64], traces: &[String]) -> Result<(), String> {
        let extent = view.extent;
        for (kind, i, j) in &self.joints {
            // the guide along the ground's marker where it has one: it stays put while the slider moves
            let i = if j.body.is_none() && j.axis.is_some() { j } else { i };
            if let ("translational" | "revolute_translational" | "cylindrical", Some(axis)) = (kind.as_str(), &i.axis) {
                let (a, o, p) = (self.at(i, q), self.world(i.body, &vec![0.0; axis.len()], q), self.world(i.body, axis, q));
                let d: Vec<f64> = p.iter().zip(&o).map(|(p, o)| p - o).collect();
                let n = d.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-300);
                let end = |sign: f64| -> Vec<f64> { a.iter().zip(&d).map(|(a, d)| a + sign * d / n * extent * 0.6).collect() };
                line(out, view.screen(&end(-1.0)), view.screen(&end(1.0)), "#999", 1.0, " stroke-dasharray=\"6 4\"");
            }
        }
        for (n, attach) in self.attach.iter().enumerate() {
            let colour = BODY_COLOURS[n % BODY_COLOURS.len()];
            let centre = view.screen(&self.world(Some(n), &self.origin(), q));
            let points: Vec<[f64; 2]> =
                std::iter::once(centre).chain(attach.iter().map(|s| view.screen(&self.world(Some(n), s, q)))).collect();
            let spread = points.iter().map(|p| (p[0] - centre[0]).hypot(p[1] - centre[1])).fold(0.0, f64::max);
            if spread < 1.0 {
                let _ = writeln!(
                    out,
                    "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"18\" height=\"18\" fill=\"{colour}\" fill-opacity=\"0.33\" stroke=\"{colour}\" stroke-width=\"3\"/>",
                    centre[0] - 9.0,
                    centre[1] - 9.0
                );
            } else if self.spatial {
                for p in &points[1..] {
                    line(out, centre, *p, colour, 3.0, "");
                }
            } else {
                let h = hull(&points);
                if h.len() > 2 {
                    polyline(out, &h, true, colour, 3.0, colour, " fill-opacity=\"0.33\" stroke-linejoin=\"round\"");
                } else {
                    polyline(out, &h, false, colour, 3.0, "none", "");
                }
            }
            let _ = writeln!(out, "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"2.5\" fill=\"#000\"/>", centre[0], centre[1]);
        }
        let ring_radius = view.ring_radius;
        for (kind, i, j) in &self.joints {
            let (a, b) = (view.screen(&self.at(i, q)), view.screen(&self.at(j, q)));
            let link = kind == "revolute_revolute" || kind == "distance";
            if link {
                line(out, a, b, "#333", 2.5, "");
            }
            ring(out, a, ring_radius, "#333");
            if link {
                ring(out, b, ring_radius, "#333");
            }
        }
        for e in &self.elements {
            let (wa, wb) = (self.at(&e.i, q), self.at(&e.j, q));
            let (a, b) = (view.screen(&wa), view.screen(&wb));
            match e.kind.as_str() {
                "point_to_point" if e.spring => zigzag(out, a, b),
                "point_to_point" if e.damper => damper(out, a, b),
                "point_to_point" => line(out, a, b, "#c4a000", 2.0, " stroke-dasharray=\"2 3\""),
                "cable" => line(out, a, b, "#555", 1.5, " stroke-dasharray=\"8 4\""),
                "tyre" => {
                    let (radius, road) = e.tyre.clone().unwrap_or((0.0, Value::Null));
                    let _ = writeln!(
                        out,
                        "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"{:.2}\" fill=\"none\" stroke=\"#222\" stroke-width=\"3\"/>",
                        a[0],
                        a[1],
                        radius * view.scale
                    );
                    if !self.spatial {
                        let y = wb[1] + self.eval(&road, t, q)?;
                        line(out, view.screen(&[wa[0] - 2.0 * radius, y]), view.screen(&[wa[0] + 2.0 * radius, y]), "#555", 2.0, "");
                    }
                }
                "contact" => {
                    ring(out, a, 3.0, "#c00");
                    ring(out, b, 3.0, "#c00");
                }
                _ => line(out, a, b, "#777", 1.0, ""),
            }
        }
        for (n, name) in traces.iter().enumerate() {
            let c = view.screen(&self.at(self.named(name)?, q));
            let colour = TRACE_COLOURS[n % TRACE_COLOURS.len()];
            let _ = writeln!(out, "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"3.5\" fill=\"{colour}\"/>", c[0], c[1]);
            let _ = writeln!(
                out,
                "<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"12\" fill=\"{colour}\">{}</text>",
                c[0] + 6.0,
                c[1] - 6.0,
                escape(name)
            );
        }
        Ok(())
    }
}

/// World → screen, fitted to every frame's points as the page fits them.
struct View {
    centre: Vec<f64>,
    extent: f64,
    scale: f64,
    spatial: bool,
    ring_radius: f64,
}

impl View {
    fn new(d: &Drawing, frames: &[(f64, &[f64])]) -> Self {
        let dim = if d.spatial { 3 } else { 2 };
        let (mut lo, mut hi) = (vec![f64::INFINITY; dim], vec![f64::NEG_INFINITY; dim]);
        for (_, q) in frames {
            for p in d.all_points(q).iter().filter(|p| p.iter().all(|x| x.is_finite())) {
                for i in 0..dim {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
        }
        if lo[0] > hi[0] {
            (lo, hi) = (vec![-1.0; dim], vec![1.0; dim]);
        }
        let centre = lo.iter().zip(&hi).map(|(l, h)| (l + h) / 2.0).collect();
        let extent = lo.iter().zip(&hi).map(|(l, h)| h - l).fold(1e-3, f64::max);
        let scale = 0.8 * WIDTH.min(HEIGHT) / extent;
        // rings of 4 px, smaller where the bodies are short on screen (a chain of short links)
        let mut shortest = f64::INFINITY;
        if let Some((_, q)) = frames.first() {
            for (k, attach) in d.attach.iter().enumerate() {
                let points: Vec<Vec<f64>> = attach.iter().map(|s| d.world(Some(k), s, q)).collect();
                for (i, a) in points.iter().enumerate() {
                    for b in &points[i + 1..] {
                        let distance = a.iter().zip(b).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
                        if distance > 0.0 {
                            shortest = shortest.min(distance);
                        }
                    }
                }
            }
        }
        let ring_radius = if shortest.is_finite() { (0.2 * scale * shortest).clamp(1.5, 4.0) } else { 4.0 };
        View { centre, extent, scale, spatial: d.spatial, ring_radius }
    }

    fn screen(&self, p: &[f64]) -> [f64; 2] {
        let d: Vec<f64> = p.iter().zip(&self.centre).map(|(p, c)| p - c).collect();
        if !self.spatial {
            return [WIDTH / 2.0 + self.scale * d[0], HEIGHT / 2.0 - self.scale * d[1]];
        }
        let x1 = YAW.cos() * d[0] + YAW.sin() * d[1];
        let y1 = -YAW.sin() * d[0] + YAW.cos() * d[1];
        let up = PITCH.cos() * d[2] - PITCH.sin() * y1;
        [WIDTH / 2.0 + self.scale * x1, HEIGHT / 2.0 - self.scale * up]
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

fn line(out: &mut String, a: [f64; 2], b: [f64; 2], colour: &str, width: f64, extra: &str) {
    let _ = writeln!(
        out,
        "<line x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\" stroke=\"{colour}\" stroke-width=\"{width}\"{extra}/>",
        a[0], a[1], b[0], b[1]
    );
}

/// An open polyline, or (`closed`) a polygon, through screen points.
fn polyline(out: &mut String, points: &[[f64; 2]], closed: bool, colour: &str, width: f64, fill: &str, extra: &str) {
    let element = if closed { "polygon" } else { "polyline" };
    let _ = write!(out, "<{element} points=\"");
    for (k, p) in points.iter().enumerate() {
        let _ = write!(out, "{}{:.2},{:.2}", if k > 0 { " " } else { "" }, p[0], p[1]);
    }
    let _ = writeln!(out, "\" fill=\"{fill}\" stroke=\"{colour}\" stroke-width=\"{width}\"{extra}/>");
}

fn ring(out: &mut String, c: [f64; 2], r: f64, colour: &str) {
    let _ = writeln!(
        out,
        "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"{r:.2}\" fill=\"#fff\" stroke=\"{colour}\" stroke-width=\"1.5\"/>",
        c[0], c[1]
    );
}

fn hatch(out: &mut String, p: [f64; 2]) {
    let mut d = format!("M{:.2},{:.2}h20", p[0] - 10.0, p[1] + 7.0);
    for k in (-10..10).step_by(4) {
        let _ = write!(d, "M{:.2},{:.2}l-4,5", p[0] + k as f64, p[1] + 7.0);
    }
    let _ = write!(d, "M{:.2},{:.2}l-5,7h10z", p[0], p[1]);
    let _ = writeln!(out, "<path d=\"{d}\" fill=\"none\" stroke=\"#555\" stroke-width=\"1\"/>");
}

fn zigzag(out: &mut String, a: [f64; 2], b: [f64; 2]) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy).max(1e-9);
    let (nx, ny) = (-dy / len * 6.0, dx / len * 6.0);
    let turns = 10;
    let mut points = vec![a];
    for k in 1..2 * turns {
        let f = 0.1 + 0.8 * k as f64 / (2 * turns) as f64;
        let side = if k % 2 == 1 { 1.0 } else { -1.0 };
        points.push([a[0] + f * dx + side * nx, a[1] + f * dy + side * ny]);
    }
    points.push(b);
    polyline(out, &points, false, "#2a7", 1.5, "none", "");
}

fn damper(out: &mut String, a: [f64; 2], b: [f64; 2]) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy).max(1e-9);
    let (nx, ny) = (-dy / len * 5.0, dx / len * 5.0);
    let at = |f: f64, side: f64| [a[0] + f * dx + side * nx, a[1] + f * dy + side * ny];
    line(out, a, at(0.5, 0.0), "#a52", 1.5, "");
    line(out, at(0.35, 1.0), at(0.65, 1.0), "#a52", 1.5, "");
    line(out, at(0.35, -1.0), at(0.65, -1.0), "#a52", 1.5, "");
    line(out, at(0.65, 1.0), at(0.65, -1.0), "#a52", 1.5, "");
    line(out, at(0.65, 0.0), b, "#a52", 1.5, "");
}

/// The convex hull of screen points (monotone chain).
fn hull(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut pts = points.to_vec();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let chain = |iter: &mut dyn Iterator<Item = [f64; 2]>| {
        let mut h: Vec<[f64; 2]> = Vec::new();
        for p in iter {
            while h.len() >= 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
        h
    };
    let mut lower = chain(&mut pts.iter().copied());
    lower.extend(chain(&mut pts.iter().rev().copied()));
    lower
}

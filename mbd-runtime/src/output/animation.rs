//! [`Animation`]: a self-contained HTML page that animates a mechanism from any analysis's
//! output — a simulation's samples, a kinematic sweep, a sequence of static equilibria.
//!
//! The page needs no network: the model (its [`Mechanism::MODEL_JSON`], which holds every body,
//! joint marker, force element and named point with its body-frame coordinates as expressions of
//! the parameters), the parameter values and the frames (t, q) are inlined as JSON, and a small
//! inline script draws them on a canvas. What it draws:
//!
//! - each body as the polygon through its joint and force-element attachment points (its
//!   centre of mass alone: a disc), joints as rings at their markers, a slider's guide as a line
//!   along its axis;
//! - ground attachment points hatched;
//! - springs as zig-zags, dampers as a cylinder and rod, cables as dashed lines, contacts as a
//!   plane mark, tyres as a circle of their radius and the road profile under them;
//! - the traces of chosen points over the frames so far.
//!
//! Controls: a time slider, play/pause, speed (¼× to 4× real time, looping). Spatial mechanisms
//! are drawn in an orthographic view that the mouse turns (drag) and zooms (wheel). The page
//! reports what it drew in `<p id="status">` (`drew frame k of n`), or the error that stopped
//! it, which is what the browser test reads.
//!
//! [`Animation::to_svg`] draws the same picture as an animated SVG for a README or a report: one
//! group per frame, shown in turn at the frames' own times by SMIL, no script (`drawing.rs`).
//! The page opens with `#t=1.25` in its address at the frame of t = 1.25 s, paused.

use std::fmt::Write as _;
use std::io;
use std::path::Path;

use crate::model::body::BodyFrames;
use crate::model::mechanism::{BodyCoordinates, Mechanism};
use crate::output::drawing::Drawing;

/// Why an animation cannot be written: a traced point the mechanism does not name (the message
/// lists those it does), or a model description the drawing cannot read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AnimationError(pub String);

impl std::fmt::Display for AnimationError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for AnimationError {}

impl From<AnimationError> for io::Error {
    fn from(e: AnimationError) -> Self {
        io::Error::new(io::ErrorKind::InvalidInput, e)
    }
}

/// Default largest number of frames of an animated SVG.
pub const DEFAULT_SVG_FRAMES: usize = 240;
/// Default largest number of drawn shapes (bodies, joints and force elements, summed over the
/// frames) of an animated SVG: about 2 MB. A 105-link chain keeps 68 frames of 240 (2.0 MB).
pub const DEFAULT_SVG_SHAPES: usize = 20_000;

/// Frames of a mechanism's motion, written as a self-contained HTML page (module docs).
#[derive(Clone, Debug)]
pub struct Animation {
    title: String,
    /// The mechanism's `MODEL_JSON`; for [`Animation::from_bodies`] with its coordinates
    /// renamed to the bodies' poses the frames hold.
    model: String,
    param_names: &'static [&'static str],
    params: Vec<f64>,
    nq: usize,
    times: Vec<f64>,
    coordinates: Vec<f64>,
    traces: Vec<String>,
    /// Set by [`Animation::svg_frames`]; `None`: the defaults' budget.
    svg_frames: Option<usize>,
    /// Why the drawing cannot be made ([`Animation::from_bodies`] of a spatial mechanism).
    refused: Option<&'static str>,
}

impl Animation {
    /// An animation of mechanism `M` with these parameter values (in [`Mechanism::PARAM_NAMES`]
    /// order: `Name::params()`), no frames yet.
    pub fn new<M: BodyCoordinates>(params: &[f64]) -> Self {
        Animation {
            title: M::NAME.to_string(),
            model: M::MODEL_JSON.to_string(),
            param_names: M::PARAM_NAMES,
            params: params.to_vec(),
            nq: M::COORDINATE_NAMES.len(),
            times: Vec::new(),
            coordinates: Vec::new(),
            traces: Vec::new(),
            svg_frames: None,
            refused: None,
        }
    }

    /// An animation of a planar mechanism in any coordinates — joint coordinates included —
    /// drawn from its bodies' poses: each frame, added by [`Animation::body_frame`], holds every
    /// body's x, y and φ (read through [`BodyFrames`]) where [`Animation::new`]'s hold q.
    pub fn from_bodies<M: Mechanism>(params: &[f64]) -> Self {
        let poses: Vec<String> = M::BODY_NAMES.iter().flat_map(|b| ["x", "y", "phi"].map(|c| format!("{b}.{c}"))).collect();
        let mut refused = None;
        let model = match serde_json::from_str::<serde_json::Value>(M::MODEL_JSON) {
            Ok(mut model) => {
                if model["dimension"].as_u64() == Some(3) {
                    refused = Some(
                        "Animation::from_bodies draws planar mechanisms: expected a planar mechanism, found a spatial one \
                         (Animation::new draws it from q)",
                    );
                }
                model["coordinates"] = serde_json::json!(poses);
                model.to_string()
            }
            // Unreadable: left as it is, for the drawing to report.
            Err(_) => M::MODEL_JSON.to_string(),
        };
        Animation {
            title: M::NAME.to_string(),
            model,
            param_names: M::PARAM_NAMES,
            params: params.to_vec(),
            nq: poses.len(),
            times: Vec::new(),
            coordinates: Vec::new(),
            traces: Vec::new(),
            svg_frames: None,
            refused,
        }
    }

    /// A frame of an animation [`from_bodies`](Animation::from_bodies): the bodies' poses at
    /// (t, q) (planar: x, y and φ of each).
    pub fn body_frame<M: BodyFrames<f64, NQ, NV>, const NQ: usize, const NV: usize>(&mut self, m: &M, t: f64, q: &[f64; NQ]) {
        self.times.push(t);
        for k in 0..self.nq / 3 {
            match m.body_pose(k, q) {
                Some(p) => self.coordinates.extend([p.position[0], p.position[1], p.angle()]),
                None => self.coordinates.extend([f64::NAN; 3]),
            }
        }
    }

    /// With this title (default: the mechanism's name).
    pub fn title(mut self, title: impl Into<String>) -> Self {
        self.title = title.into();
        self
    }

    /// With the path of a named point drawn (`"coupler.P"`, as declared by `point coupler.P`).
    pub fn trace(mut self, point: impl Into<String>) -> Self {
        self.traces.push(point.into());
        self
    }

    /// With at most `n` frames in [`Animation::to_svg`]: a longer animation keeps every k-th
    /// frame and its last. By default at most [`DEFAULT_SVG_FRAMES`], and fewer for a big
    /// mechanism, so that the frames hold at most [`DEFAULT_SVG_SHAPES`] shapes in all.
    pub fn svg_frames(mut self, n: usize) -> Self {
        self.svg_frames = Some(n.max(2));
        self
    }

    /// Adds the frame of coordinates `q` (NQ entries; extra entries are ignored) at time `t` (s).
    pub fn frame(&mut self, t: f64, q: &[f64]) {
        self.times.push(t);
        self.coordinates.extend((0..self.nq).map(|i| q.get(i).copied().unwrap_or(f64::NAN)));
    }

    /// Adds every (t, q) of `frames`.
    pub fn frames<'a>(&mut self, frames: impl IntoIterator<Item = (f64, &'a [f64])>) {
        for (t, q) in frames {
            self.frame(t, q);
        }
    }

    /// How many frames it holds.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether it holds no frame.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// The page.
    pub fn to_html(&self) -> String {
        // 9 significant digits (sub-micrometre at a kilometre) keep a long run's page small.
        let number =
            |x: f64| if x.is_finite() { format!("{}", format!("{x:.8e}").parse::<f64>().unwrap_or(x)) } else { "null".to_string() };
        let mut data = String::with_capacity(64 + 20 * self.coordinates.len());
        data.push_str("{\"params\": {");
        for (k, (name, value)) in self.param_names.iter().zip(&self.params).enumerate() {
            let _ = write!(data, "{}{name:?}: {}", if k > 0 { ", " } else { "" }, number(*value));
        }
        data.push_str("}, \"traces\": [");
        for (k, name) in self.traces.iter().enumerate() {
            let _ = write!(data, "{}{name:?}", if k > 0 { ", " } else { "" });
        }
        data.push_str("], \"t\": [");
        for (k, t) in self.times.iter().enumerate() {
            let _ = write!(data, "{}{}", if k > 0 { "," } else { "" }, number(*t));
        }
        data.push_str("], \"q\": [");
        for (k, frame) in self.coordinates.chunks(self.nq.max(1)).enumerate() {
            data.push_str(if k > 0 { ",[" } else { "[" });
            for (i, x) in frame.iter().enumerate() {
                let _ = write!(data, "{}{}", if i > 0 { "," } else { "" }, number(*x));
            }
            data.push(']');
        }
        data.push_str("]}");
        // `</` cannot appear inside a script element: JSON never needs it unescaped.
        let safe = |s: &str| s.replace("</", "<\\/");
        let title = self.title.replace('&', "&amp;").replace('<', "&lt;");
        PAGE.replace("@TITLE@", &title).replace("@MODEL@", &safe(&self.model)).replace("@DATA@", &safe(&data)).replace("@SCRIPT@", SCRIPT)
    }

    /// Writes [`Animation::to_html`] to `path`, after checking that every traced point exists
    /// (an [`io::ErrorKind::InvalidInput`] error naming it and those there are).
    pub fn write_html(&self, path: impl AsRef<Path>) -> io::Result<()> {
        self.drawing()?.check_traces(&self.traces).map_err(AnimationError)?;
        std::fs::write(path, self.to_html())
    }

    fn drawing(&self) -> Result<Drawing, AnimationError> {
        if let Some(why) = self.refused {
            return Err(AnimationError(why.to_string()));
        }
        Drawing::from_json(&self.model, self.param_names, &self.params).map_err(AnimationError)
    }

    /// The animated SVG (module docs): at most [`Animation::svg_frames`] frames, played in real
    /// time and looping (frames all at one time, such as a sequence of equilibria, 0.1 s each).
    pub fn to_svg(&self) -> Result<String, AnimationError> {
        let all: Vec<(f64, &[f64])> = self.times.iter().copied().zip(self.coordinates.chunks(self.nq.max(1))).collect();
        let drawing = self.drawing()?;
        let budget = self.svg_frames.unwrap_or_else(|| DEFAULT_SVG_FRAMES.min(DEFAULT_SVG_SHAPES / drawing.shapes().max(1)).max(2));
        // every stride-th frame from the first, and the last: at most `budget` in all
        let stride = all.len().saturating_sub(1).div_ceil(budget - 1).max(1);
        let mut kept: Vec<(f64, &[f64])> = all.iter().copied().step_by(stride).collect();
        if let Some(&last) = all.last() {
            if !(all.len() - 1).is_multiple_of(stride) {
                kept.push(last);
            }
        }
        drawing.svg(&self.title, &kept, &self.traces).map_err(AnimationError)
    }

    /// Writes [`Animation::to_svg`] to `path`.
    pub fn write_svg(&self, path: impl AsRef<Path>) -> io::Result<()> {
        std::fs::write(path, self.to_svg()?)
    }
}

const PAGE: &str = r##"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>@TITLE@</title>
<style>
body { font: 14px sans-serif; margin: 12px; color: #222; }
canvas { border: 1px solid #ccc; display: block; margin-bottom: 8px; touch-action: none; }
#controls { display: flex; gap: 10px; align-items: center; }
#time { width: 520px; }
</style></head>
<body>
<h3>@TITLE@</h3>
<canvas id="view" width="800" height="560"></canvas>
<div id="controls">
<button id="play">Pause</button>
<input id="time" type="range" min="0" max="0" value="0">
<label>speed <select id="speed"><option>0.25</option><option>0.5</option><option selected>1</option><option>2</option><option>4</option></select></label>
<span id="clock"></span>
</div>
<p id="status">loading</p>
<script type="application/json" id="model">@MODEL@</script>
<script type="application/json" id="data">@DATA@</script>
<script>
@SCRIPT@
</script>
</body></html>
"##;

const SCRIPT: &str = r##""use strict";
const status = document.getElementById("status");
window.addEventListener("error", (e) => { status.textContent = "error: " + e.message; });
try {
const model = JSON.parse(document.getElementById("model").textContent);
const data = JSON.parse(document.getElementById("data").textContent);
const spatial = model.dimension === 3;
const per = spatial ? 7 : 3;
const bodyIndex = {};
model.bodies.forEach((b, k) => { bodyIndex[b.name] = k; });
const coordIndex = {};
model.coordinates.forEach((c, k) => { coordIndex[c] = k; });
const unary = { sin: Math.sin, cos: Math.cos, tan: Math.tan, asin: Math.asin, acos: Math.acos, atan: Math.atan,
  exp: Math.exp, ln: Math.log, log: Math.log, sqrt: Math.sqrt, abs: Math.abs, sinh: Math.sinh, cosh: Math.cosh, tanh: Math.tanh,
  sign: Math.sign, deg: (x) => x * Math.PI / 180 };
// Evaluates a model expression at time t with coordinates q (velocities are 0 in a picture).
function ev(e, t, q) {
  if (e === null || e === undefined) return 0;
  const op = e[0];
  switch (op) {
    case "num": return e[1];
    case "pi": return Math.PI;
    case "t": return t;
    case "param": return data.params[e[1]];
    case "coord": return q[coordIndex[e[1] + "." + e[2]]];
    case "vel": return 0;
    case "neg": return -ev(e[1], t, q);
    case "add": return ev(e[1], t, q) + ev(e[2], t, q);
    case "sub": return ev(e[1], t, q) - ev(e[2], t, q);
    case "mul": return ev(e[1], t, q) * ev(e[2], t, q);
    case "div": return ev(e[1], t, q) / ev(e[2], t, q);
    case "pow": return Math.pow(ev(e[1], t, q), ev(e[2], t, q));
    case "atan2": return Math.atan2(ev(e[1], t, q), ev(e[2], t, q));
    case "min": return Math.min(ev(e[1], t, q), ev(e[2], t, q));
    case "max": return Math.max(ev(e[1], t, q), ev(e[2], t, q));
    case "clamp": return Math.min(Math.max(ev(e[1], t, q), ev(e[2], t, q)), ev(e[3], t, q));
    case "if_gt": return ev(e[1], t, q) > ev(e[2], t, q) ? ev(e[3], t, q) : ev(e[4], t, q);
    case "if_ge": return ev(e[1], t, q) >= ev(e[2], t, q) ? ev(e[3], t, q) : ev(e[4], t, q);
    default:
      if (unary[op]) return unary[op](ev(e[1], t, q));
      throw new Error("unknown expression " + JSON.stringify(op));
  }
}
const zero = new Array(model.coordinates.length).fill(0);
const local = (list) => list.map((e) => ev(e, 0, zero));
// Rotation of body k at q: 2D angle or 3×3 matrix from Euler parameters.
function pose(k, q) {
  const b = per * k;
  if (!spatial) return { r: [q[b], q[b + 1]], phi: q[b + 2] };
  let [e0, e1, e2, e3] = [q[b + 3], q[b + 4], q[b + 5], q[b + 6]];
  const n = Math.hypot(e0, e1, e2, e3) || 1;
  [e0, e1, e2, e3] = [e0 / n, e1 / n, e2 / n, e3 / n];
  const a = [
    [2 * (e0 * e0 + e1 * e1) - 1, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)],
    [2 * (e1 * e2 + e0 * e3), 2 * (e0 * e0 + e2 * e2) - 1, 2 * (e2 * e3 - e0 * e1)],
    [2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), 2 * (e0 * e0 + e3 * e3) - 1]];
  return { r: [q[b], q[b + 1], q[b + 2]], a: a };
}
// World position of a body-frame point s on body `name` at q.
function world(name, s, q) {
  if (name === "ground" || !(name in bodyIndex)) return s.slice();
  const p = pose(bodyIndex[name], q);
  if (!spatial) {
    const c = Math.cos(p.phi), sn = Math.sin(p.phi);
    return [p.r[0] + c * s[0] - sn * s[1], p.r[1] + sn * s[0] + c * s[1]];
  }
  return [0, 1, 2].map((i) => p.r[i] + p.a[i][0] * s[0] + p.a[i][1] * s[1] + p.a[i][2] * s[2]);
}
function direction(name, s, q) {
  const o = world(name, s.map(() => 0), q), p = world(name, s, q);
  const d = p.map((x, i) => x - o[i]);
  const n = Math.hypot(...d) || 1;
  return d.map((x) => x / n);
}
// Attachments: per body, the body-frame points that joints and force elements hold.
const attach = {};
model.bodies.forEach((b) => { attach[b.name] = []; });
const groundPoints = [];
const joints = [];
function addMarker(m) {
  if (!m || typeof m !== "object" || !m.point) return null;
  const s = local(m.point);
  if (m.body === "ground") groundPoints.push(s); else if (attach[m.body]) attach[m.body].push(s);
  return { body: m.body, s: s, axis: m.axis ? local(m.axis) : null };
}
for (const c of model.constraints) {
  const i = addMarker(c.i), j = addMarker(c.j);
  if (i && j) joints.push({ kind: c.kind, i: i, j: j });
}
const elements = [];
for (const f of model.forces) {
  if (f.i && typeof f.i === "object") {
    const i = addMarker(f.i), j = addMarker(f.j);
    elements.push({ kind: f.kind, i: i, j: j, f: f });
  } else if (f.at) {
    addMarker(f.at);
  }
}
const named = {};
for (const p of model.points) {
  const s = local(p.local);
  named[p.body + "." + p.name] = { body: p.body, s: s };
  if (attach[p.body]) attach[p.body].push(s);
}
// The view: a bounding box of every drawn point over every frame (planar), or a sphere (spatial).
const frames = data.q.length;
function allPoints(q) {
  const pts = [];
  for (const b of model.bodies) {
    pts.push(world(b.name, spatial ? [0, 0, 0] : [0, 0], q));
    for (const s of attach[b.name]) pts.push(world(b.name, s, q));
  }
  for (const s of groundPoints) pts.push(s);
  return pts;
}
let lo = null, hi = null;
for (let k = 0; k < frames; k++) {
  for (const p of allPoints(data.q[k])) {
    if (p.some((x) => !isFinite(x))) continue;
    lo = lo ? lo.map((x, i) => Math.min(x, p[i])) : p.slice();
    hi = hi ? hi.map((x, i) => Math.max(x, p[i])) : p.slice();
  }
}
if (!lo) { lo = spatial ? [-1, -1, -1] : [-1, -1]; hi = spatial ? [1, 1, 1] : [1, 1]; }
const centre = lo.map((x, i) => (x + hi[i]) / 2);
const extent = Math.max(...lo.map((x, i) => hi[i] - x), 1e-3);
const canvas = document.getElementById("view");
const g = canvas.getContext("2d");
let yaw = 0.6, pitch = 0.35, zoom = 1;
const W = canvas.width, H = canvas.height;
// Screen position of a world point.
function screen(p) {
  const scale = zoom * 0.8 * Math.min(W, H) / extent;
  if (!spatial) return [W / 2 + scale * (p[0] - centre[0]), H / 2 - scale * (p[1] - centre[1])];
  const d = p.map((x, i) => x - centre[i]);
  // z up: turn about z by yaw, then tilt about the screen's x by pitch
  const x1 = Math.cos(yaw) * d[0] + Math.sin(yaw) * d[1];
  const y1 = -Math.sin(yaw) * d[0] + Math.cos(yaw) * d[1];
  const up = Math.cos(pitch) * d[2] - Math.sin(pitch) * y1;
  return [W / 2 + scale * x1, H / 2 - scale * up];
}
function line(a, b, style, width, dash) {
  const [p, q2] = [screen(a), screen(b)];
  g.strokeStyle = style; g.lineWidth = width || 1.5; g.setLineDash(dash || []);
  g.beginPath(); g.moveTo(p[0], p[1]); g.lineTo(q2[0], q2[1]); g.stroke(); g.setLineDash([]);
}
function ring(a, r, style) {
  const p = screen(a);
  g.strokeStyle = style; g.fillStyle = "#fff"; g.lineWidth = 1.5;
  g.beginPath(); g.arc(p[0], p[1], r, 0, 2 * Math.PI); g.fill(); g.stroke();
}
function hatch(a) {
  const p = screen(a);
  g.strokeStyle = "#555"; g.lineWidth = 1;
  g.beginPath(); g.moveTo(p[0] - 10, p[1] + 7); g.lineTo(p[0] + 10, p[1] + 7); g.stroke();
  for (let k = -10; k < 10; k += 4) { g.beginPath(); g.moveTo(p[0] + k, p[1] + 7); g.lineTo(p[0] + k - 4, p[1] + 12); g.stroke(); }
  g.beginPath(); g.moveTo(p[0], p[1]); g.lineTo(p[0] - 5, p[1] + 7); g.lineTo(p[0] + 5, p[1] + 7); g.closePath(); g.stroke();
}
function zigzag(a, b) {
  const [p, q2] = [screen(a), screen(b)];
  const dx = q2[0] - p[0], dy = q2[1] - p[1], len = Math.hypot(dx, dy) || 1;
  const nx = -dy / len * 6, ny = dx / len * 6;
  g.strokeStyle = "#2a7"; g.lineWidth = 1.5; g.beginPath(); g.moveTo(p[0], p[1]);
  const turns = 10;
  for (let k = 1; k < 2 * turns; k++) {
    const f = 0.1 + 0.8 * k / (2 * turns), side = k % 2 ? 1 : -1;
    g.lineTo(p[0] + f * dx + side * nx, p[1] + f * dy + side * ny);
  }
  g.lineTo(q2[0], q2[1]); g.stroke();
}
function damper(a, b) {
  const [p, q2] = [screen(a), screen(b)];
  const dx = q2[0] - p[0], dy = q2[1] - p[1], len = Math.hypot(dx, dy) || 1;
  const nx = -dy / len * 5, ny = dx / len * 5, m = 0.5;
  g.strokeStyle = "#a52"; g.lineWidth = 1.5;
  g.beginPath(); g.moveTo(p[0], p[1]); g.lineTo(p[0] + m * dx, p[1] + m * dy); g.stroke();
  g.beginPath(); g.moveTo(p[0] + 0.35 * dx + nx, p[1] + 0.35 * dy + ny); g.lineTo(p[0] + 0.65 * dx + nx, p[1] + 0.65 * dy + ny);
  g.moveTo(p[0] + 0.35 * dx - nx, p[1] + 0.35 * dy - ny); g.lineTo(p[0] + 0.65 * dx - nx, p[1] + 0.65 * dy - ny);
  g.moveTo(p[0] + 0.65 * dx + nx, p[1] + 0.65 * dy + ny); g.lineTo(p[0] + 0.65 * dx - nx, p[1] + 0.65 * dy - ny);
  g.moveTo(p[0] + 0.65 * dx, p[1] + 0.65 * dy); g.lineTo(q2[0], q2[1]); g.stroke();
}
const traceColours = ["#555", "#c00", "#06c", "#080", "#a0a"];
// Joint rings: 4 px, smaller where the bodies are short on screen (a chain of short links).
let shortest = Infinity;
if (frames > 0) {
  for (const b of model.bodies) {
    const pts = attach[b.name].map((s) => world(b.name, s, data.q[0]));
    for (let i = 0; i < pts.length; i++) for (let j = i + 1; j < pts.length; j++) {
      const d = Math.hypot(...pts[i].map((x, c) => x - pts[j][c]));
      if (d > 0) shortest = Math.min(shortest, d);
    }
  }
}
function ringRadius() {
  const px = zoom * 0.8 * Math.min(W, H) / extent * shortest;
  return isFinite(px) ? Math.max(1.5, Math.min(4, 0.2 * px)) : 4;
}
const colours = ["#3465a4", "#c4a000", "#75507b", "#cc0000", "#4e9a06", "#ce5c00", "#204a87", "#8f5902"];
// The convex hull of screen points (gift wrapping: few points per body).
function hull(points) {
  const pts = points.slice().sort((a, b) => a[0] - b[0] || a[1] - b[1]);
  if (pts.length < 3) return pts;
  const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  const lower = [], upper = [];
  for (const p of pts) { while (lower.length >= 2 && cross(lower[lower.length - 2], lower[lower.length - 1], p) <= 0) lower.pop(); lower.push(p); }
  for (const p of pts.slice().reverse()) { while (upper.length >= 2 && cross(upper[upper.length - 2], upper[upper.length - 1], p) <= 0) upper.pop(); upper.push(p); }
  return lower.slice(0, -1).concat(upper.slice(0, -1));
}
function draw(k) {
  const q = data.q[k], t = data.t[k];
  g.clearRect(0, 0, W, H);
  if (spatial) {
    const o = centre.map((x, i) => x - extent * 0.45 * (i === 2 ? 0 : 1));
    [[1, 0, 0, "#c00"], [0, 1, 0, "#0a0"], [0, 0, 1, "#00c"]].forEach(([x, y, z, c]) =>
      line(o, [o[0] + x * extent * 0.15, o[1] + y * extent * 0.15, o[2] + z * extent * 0.15], c, 2));
  }
  for (const s of groundPoints) hatch(s);
  // traces so far
  data.traces.forEach((name, n) => {
    const p = named[name];
    if (!p) throw new Error("no named point " + name + " (declare it with `point " + name + " = [...]`)");
    const colour = traceColours[n % traceColours.length];
    g.strokeStyle = colour; g.lineWidth = 1.2; g.beginPath();
    for (let m = 0; m <= k; m++) { const s = screen(world(p.body, p.s, data.q[m])); if (m) g.lineTo(s[0], s[1]); else g.moveTo(s[0], s[1]); }
    g.stroke();
    // the legend, top left
    g.fillStyle = colour; g.font = "13px sans-serif"; g.fillText("— " + name, 10, 18 + 16 * n);
  });
  // slider guides
  for (const j of joints) {
    // the guide along the ground's marker where it has one: it stays put while the slider moves
    const m = j.j.body === "ground" && j.j.axis ? j.j : j.i;
    if ((j.kind === "translational" || j.kind === "revolute_translational" || j.kind === "cylindrical") && m.axis) {
      const a = world(m.body, m.s, q), u = direction(m.body, m.axis, q);
      line(a.map((x, i) => x - u[i] * extent * 0.6), a.map((x, i) => x + u[i] * extent * 0.6), "#999", 1, [6, 4]);
    }
  }
  model.bodies.forEach((b, n) => {
    const origin = spatial ? [0, 0, 0] : [0, 0];
    const pts = [origin].concat(attach[b.name]).map((s) => screen(world(b.name, s, q)));
    const colour = colours[n % colours.length];
    g.fillStyle = colour + "55"; g.strokeStyle = colour; g.lineWidth = 3;
    if (pts.length === 1 || (pts.length === 2 && Math.hypot(pts[1][0] - pts[0][0], pts[1][1] - pts[0][1]) < 1)) {
      g.beginPath(); g.rect(pts[0][0] - 9, pts[0][1] - 9, 18, 18); g.fill(); g.stroke();
    } else if (spatial) {
      for (const p of pts.slice(1)) { g.beginPath(); g.moveTo(pts[0][0], pts[0][1]); g.lineTo(p[0], p[1]); g.stroke(); }
    } else {
      const h = hull(pts);
      g.lineJoin = "round"; g.beginPath(); h.forEach((p, i) => (i ? g.lineTo(p[0], p[1]) : g.moveTo(p[0], p[1])));
      if (h.length > 2) { g.closePath(); g.fill(); }
      g.stroke();
    }
    const c = pts[0]; g.fillStyle = "#000"; g.beginPath(); g.arc(c[0], c[1], 2.5, 0, 2 * Math.PI); g.fill();
  });
  for (const j of joints) {
    if (j.kind === "revolute_revolute" || j.kind === "distance") line(world(j.i.body, j.i.s, q), world(j.j.body, j.j.s, q), "#333", 2.5);
    ring(world(j.i.body, j.i.s, q), ringRadius(), "#333");
    if (j.kind === "revolute_revolute" || j.kind === "distance") ring(world(j.j.body, j.j.s, q), ringRadius(), "#333");
  }
  for (const e of elements) {
    const a = world(e.i.body, e.i.s, q), b = world(e.j.body, e.j.s, q);
    switch (e.kind) {
      case "point_to_point":
        if (e.f.k !== null) zigzag(a, b); else if (e.f.c !== null) damper(a, b); else line(a, b, "#c4a000", 2, [2, 3]);
        break;
      case "cable": line(a, b, "#555", 1.5, [8, 4]); break;
      case "tyre": {
        const r = ev(e.f.radius, t, q), p = screen(a), scale = screen([a[0] + r, a[1]].concat(spatial ? [a[2]] : []))[0] - p[0];
        g.strokeStyle = "#222"; g.lineWidth = 3; g.beginPath(); g.arc(p[0], p[1], Math.abs(scale), 0, 2 * Math.PI); g.stroke();
        if (!spatial) {
          // the road under the wheel: its height above the ground point, as the element reads it
          const y = b[1] + ev(e.f.road, t, q);
          line([a[0] - 2 * r, y], [a[0] + 2 * r, y], "#555", 2);
        }
        break;
      }
      case "contact": ring(b, 3, "#c00"); ring(a, 3, "#c00"); break;
      default: line(a, b, "#777", 1);
    }
  }
  // the traced points now, marked and named
  data.traces.forEach((name, n) => {
    const p = named[name], c = screen(world(p.body, p.s, q));
    g.fillStyle = traceColours[n % traceColours.length];
    g.beginPath(); g.arc(c[0], c[1], 3.5, 0, 2 * Math.PI); g.fill();
    g.font = "12px sans-serif"; g.fillText(name, c[0] + 6, c[1] - 6);
  });
  document.getElementById("clock").textContent = "t = " + t.toFixed(3) + " s";
  status.textContent = "drew frame " + (k + 1) + " of " + frames;
}
const slider = document.getElementById("time");
slider.max = Math.max(frames - 1, 0);
let frame = 0, playing = frames > 1, wall = null, start = 0;
function show(k) { frame = k; slider.value = k; draw(k); }
slider.addEventListener("input", () => { playing = false; document.getElementById("play").textContent = "Play"; show(+slider.value); });
document.getElementById("play").addEventListener("click", () => {
  playing = !playing; wall = null; document.getElementById("play").textContent = playing ? "Pause" : "Play";
  if (playing) requestAnimationFrame(tick);
});
function tick(now) {
  if (!playing || frames < 2) return;
  const speed = +document.getElementById("speed").value;
  if (wall === null) { wall = now; start = data.t[frame]; }
  const span = data.t[frames - 1] - data.t[0];
  let target = start + speed * (now - wall) / 1000;
  if (target > data.t[frames - 1]) { wall = now; start = data.t[0]; target = data.t[0]; }
  let k = frame;
  while (k + 1 < frames && data.t[k + 1] <= target) k++;
  if (target < data.t[frame]) k = 0;
  if (span <= 0) k = (frame + 1) % frames;
  show(k);
  requestAnimationFrame(tick);
}
if (spatial) {
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => { drag = [e.clientX, e.clientY]; });
  window.addEventListener("pointerup", () => { drag = null; });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    yaw += (e.clientX - drag[0]) * 0.01; pitch = Math.max(-1.5, Math.min(1.5, pitch + (e.clientY - drag[1]) * 0.01));
    drag = [e.clientX, e.clientY]; draw(frame);
  });
}
canvas.addEventListener("wheel", (e) => { e.preventDefault(); zoom *= Math.exp(-e.deltaY * 0.001); draw(frame); });
// `#t=1.25` in the address opens the frame of t = 1.25 s (the last at or before it), paused.
const seek = /[#&]t=([-+0-9.eE]+)/.exec(location.hash);
if (frames === 0) { status.textContent = "no frames"; }
else if (seek) {
  let k = 0;
  while (k + 1 < frames && data.t[k + 1] <= +seek[1]) k++;
  playing = false; document.getElementById("play").textContent = "Play"; show(k);
} else { show(0); if (playing) requestAnimationFrame(tick); }
} catch (e) {
  status.textContent = "error: " + e.message;
}
"##;

//! Stage 2: syntax tree → validated model. Every name is resolved here and every rule a user can
//! break is checked here, each mistake reported as a `syn::Error` on the offending token. All
//! mistakes are collected in one pass ([`Errors`]) so one compile shows them all.

use std::collections::{HashMap, HashSet};

use proc_macro2::Span;
use syn::{Attribute, Ident, Visibility};

use crate::elements::spatial::{self, Marker};
use crate::elements::{self, drive, drive_angle, drive_distance, fix, user, Constraint, Driven};
use crate::forces::{applied, bushing, cable, contact, point_to_point, rotational, stroke, torque, tyre, ForceElement};
use crate::parse::{self, AxisRef, BinOp, BodyDef, CmpOp, DriveTarget, Expr, ExprKind, Item, MechanismDef, PointRef, Value, VecLit};
use crate::sym::{Cmp, Func};

/// The errors of one expansion, combined into one at the end, and its warnings (a mechanism
/// with warnings still generates; each becomes a deprecation warning on its span).
#[derive(Default)]
pub struct Errors(Vec<syn::Error>, pub Vec<(Span, String)>);

impl Errors {
    pub fn warn(&mut self, span: Span, msg: impl std::fmt::Display) {
        self.1.push((span, msg.to_string()));
    }
    pub fn push(&mut self, span: Span, msg: impl std::fmt::Display) {
        self.0.push(syn::Error::new(span, msg));
    }
    /// An error underlining a whole expression.
    pub fn at_expr(&mut self, e: &Expr, msg: impl std::fmt::Display) {
        self.0.push(e.error(msg));
    }
    pub fn into_result(self) -> Result<(), syn::Error> {
        let mut it = self.0.into_iter();
        match it.next() {
            None => Ok(()),
            Some(mut first) => {
                first.extend(it);
                Err(first)
            }
        }
    }
}

/// The scalar type of the generated code.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Scalar {
    F32,
    F64,
}

impl Scalar {
    pub fn name(self) -> &'static str {
        match self {
            Scalar::F32 => "f32",
            Scalar::F64 => "f64",
        }
    }
}

/// Ground or a moving body, by index.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum BodyRef {
    Ground,
    Body(usize),
}

/// Where a mechanism lives: the plane (body coordinates x, y, φ) or space (`spatial;`: x, y, z
/// and Euler parameters e0 … e3, velocities ṙ and the body-frame angular velocity ω′).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Space {
    Planar,
    Spatial,
}

impl Space {
    /// Components of a point or vector.
    pub fn dim(self) -> usize {
        match self {
            Space::Planar => 2,
            Space::Spatial => 3,
        }
    }
    /// A body's coordinates, in the order of q.
    pub fn coordinates(self) -> &'static [Coord] {
        match self {
            Space::Planar => &[Coord::X, Coord::Y, Coord::Phi],
            Space::Spatial => &[Coord::X, Coord::Y, Coord::Z, Coord::E0, Coord::E1, Coord::E2, Coord::E3],
        }
    }
    /// A body's velocities, in the order of v.
    pub fn velocities(self) -> &'static [Vel] {
        match self {
            Space::Planar => &[Vel::Vx, Vel::Vy, Vel::Omega],
            Space::Spatial => &[Vel::Vx, Vel::Vy, Vel::Vz, Vel::Wx, Vel::Wy, Vel::Wz],
        }
    }
    /// "`x`, `y`, `phi`": a body's coordinates, for messages.
    pub fn coordinate_list(self) -> String {
        self.coordinates().iter().map(|c| format!("`{}`", c.name())).collect::<Vec<_>>().join(", ")
    }
    fn velocity_list(self) -> String {
        self.velocities().iter().map(|c| format!("`{}`", c.name())).collect::<Vec<_>>().join(", ")
    }
}

/// A body coordinate: x, y, z (m), φ (rad, planar) or an Euler parameter (spatial).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Coord {
    X,
    Y,
    Phi,
    Z,
    E0,
    E1,
    E2,
    E3,
}

impl Coord {
    pub fn name(self) -> &'static str {
        match self {
            Coord::X => "x",
            Coord::Y => "y",
            Coord::Phi => "phi",
            Coord::Z => "z",
            Coord::E0 => "e0",
            Coord::E1 => "e1",
            Coord::E2 => "e2",
            Coord::E3 => "e3",
        }
    }
    /// Its index among its body's coordinates (in its space).
    pub fn index(self) -> usize {
        match self {
            Coord::X => 0,
            Coord::Y => 1,
            Coord::Phi | Coord::Z => 2,
            Coord::E0 => 3,
            Coord::E1 => 4,
            Coord::E2 => 5,
            Coord::E3 => 6,
        }
    }
    /// e0…e3: a spatial body's orientation, which only joints fix or drive.
    pub fn is_euler_parameter(self) -> bool {
        matches!(self, Coord::E0 | Coord::E1 | Coord::E2 | Coord::E3)
    }
    pub fn from_ident(space: Space, id: &Ident) -> Option<Coord> {
        space.coordinates().iter().copied().find(|c| id == c.name())
    }
}

/// A body velocity: ẋ, ẏ, ż (m/s), φ̇ (rad/s, planar) or ω′ (rad/s, body frame, spatial).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Vel {
    Vx,
    Vy,
    Omega,
    Vz,
    Wx,
    Wy,
    Wz,
}

impl Vel {
    pub fn name(self) -> &'static str {
        match self {
            Vel::Vx => "vx",
            Vel::Vy => "vy",
            Vel::Omega => "omega",
            Vel::Vz => "vz",
            Vel::Wx => "wx",
            Vel::Wy => "wy",
            Vel::Wz => "wz",
        }
    }
    /// Its index among its body's velocities (in its space).
    pub fn index(self) -> usize {
        match self {
            Vel::Vx => 0,
            Vel::Vy => 1,
            Vel::Omega | Vel::Vz => 2,
            Vel::Wx => 3,
            Vel::Wy => 4,
            Vel::Wz => 5,
        }
    }
    fn from_ident(space: Space, id: &Ident) -> Option<Vel> {
        space.velocities().iter().copied().find(|c| id == c.name())
    }
}

/// A resolved expression.
#[derive(Clone, Debug)]
pub enum MExpr {
    Num(f64),
    Pi,
    T,
    Param(usize),
    Coord(BodyRef, Coord),
    /// A body velocity (force expressions only).
    Vel(BodyRef, Vel),
    Neg(Box<MExpr>),
    Bin(MBin, Box<MExpr>, Box<MExpr>),
    Call(Func, Box<MExpr>),
    Atan2(Box<MExpr>, Box<MExpr>),
    /// `abs`, `sign`, `min`, `max` or `clamp` of its arguments.
    Kink(Kink, Box<[MExpr]>),
    /// `if a cmp b { x } else { y }`, `<` and `<=` written as `>` and `>=` with the operands
    /// swapped: `[a, b, x, y]`.
    If(Cmp, Box<[MExpr; 4]>),
}

/// The non-smooth functions (`sym::Graph::abs` … define them and their derivatives at the kink).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kink {
    Abs,
    Sign,
    Min,
    Max,
    Clamp,
}

impl Kink {
    pub const ALL: [Kink; 5] = [Kink::Abs, Kink::Sign, Kink::Min, Kink::Max, Kink::Clamp];

    pub fn name(self) -> &'static str {
        match self {
            Kink::Abs => "abs",
            Kink::Sign => "sign",
            Kink::Min => "min",
            Kink::Max => "max",
            Kink::Clamp => "clamp",
        }
    }

    pub fn arity(self) -> usize {
        match self {
            Kink::Abs | Kink::Sign => 1,
            Kink::Min | Kink::Max => 2,
            Kink::Clamp => 3,
        }
    }

    pub fn from_name(name: &str) -> Option<Kink> {
        Kink::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Its value, defined as the graph defines it (`sign(0) = 0`; `clamp` tests `lo` first).
    pub fn apply(self, a: &[f64]) -> f64 {
        match self {
            Kink::Abs => a[0].abs(),
            Kink::Sign if a[0] > 0.0 => 1.0,
            Kink::Sign if a[0] < 0.0 => -1.0,
            Kink::Sign => 0.0,
            Kink::Min => {
                if a[1] >= a[0] {
                    a[0]
                } else {
                    a[1]
                }
            }
            Kink::Max => {
                if a[0] >= a[1] {
                    a[0]
                } else {
                    a[1]
                }
            }
            Kink::Clamp => {
                if a[1] > a[0] {
                    a[1]
                } else if a[0] > a[2] {
                    a[2]
                } else {
                    a[0]
                }
            }
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MBin {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

impl MExpr {
    /// The value of an expression made of numbers, `PI` and functions only.
    pub fn constant_value(&self) -> Option<f64> {
        self.value_with(&|_| None)
    }

    /// The value of an expression of numbers, `PI`, functions and parameters at the parameters'
    /// default values.
    pub fn default_value(&self, defaults: &[f64]) -> Option<f64> {
        self.value_with(&|k| defaults.get(k).copied())
    }

    /// Whether f(t) is 0 at every time, whatever the parameters (tried at a few times).
    pub fn is_zero_in_time(&self) -> bool {
        [0.0, 0.37, 1.0, 2.9].iter().all(|&t| self.value_with(&|k| (k == usize::MAX).then_some(t)) == Some(0.0))
    }

    /// The value of a driver f(t) at time t with the parameters' default values.
    pub fn value_at(&self, defaults: &[f64], t: f64) -> Option<f64> {
        self.value_with(&|k| if k == usize::MAX { Some(t) } else { defaults.get(k).copied() })
    }

    /// The value for the parameters `param(k)`; `param(usize::MAX)` is t.
    fn value_with(&self, param: &dyn Fn(usize) -> Option<f64>) -> Option<f64> {
        Some(match self {
            MExpr::Num(v) => *v,
            MExpr::Pi => std::f64::consts::PI,
            MExpr::Param(k) => return param(*k),
            MExpr::T => return param(usize::MAX),
            MExpr::Coord(..) | MExpr::Vel(..) => return None,
            MExpr::Neg(a) => -a.value_with(param)?,
            MExpr::Bin(op, a, b) => {
                let (a, b) = (a.value_with(param)?, b.value_with(param)?);
                match op {
                    MBin::Add => a + b,
                    MBin::Sub => a - b,
                    MBin::Mul => a * b,
                    MBin::Div => a / b,
                    MBin::Pow => a.powf(b),
                }
            }
            MExpr::Call(f, a) => {
                let a = a.value_with(param)?;
                match f {
                    Func::Sin => a.sin(),
                    Func::Cos => a.cos(),
                    Func::Tan => a.tan(),
                    Func::Asin => a.asin(),
                    Func::Acos => a.acos(),
                    Func::Atan => a.atan(),
                    Func::Sqrt => a.sqrt(),
                    Func::Exp => a.exp(),
                    Func::Ln => a.ln(),
                }
            }
            MExpr::Atan2(y, x) => y.value_with(param)?.atan2(x.value_with(param)?),
            MExpr::Kink(k, args) => {
                let a: Option<Vec<f64>> = args.iter().map(|a| a.value_with(param)).collect();
                k.apply(&a?)
            }
            MExpr::If(cmp, e) => {
                let [a, b, x, y] = &**e;
                if cmp.holds(a.value_with(param)?, b.value_with(param)?) {
                    x.value_with(param)?
                } else {
                    y.value_with(param)?
                }
            }
        })
    }
}

/// What an expression may refer to, by where it stands.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// Numbers, `PI` and functions: parameter defaults.
    Constant,
    /// Also parameters: geometry, masses, initial values.
    Params,
    /// Also `t`: drivers.
    Time,
    /// Also coordinates: user constraints.
    State,
    /// Also velocities: forces.
    Force,
}

impl Scope {
    /// What an expression of this scope may use, and why.
    fn describe(self) -> &'static str {
        match self {
            Scope::Constant => "numbers, `PI` and functions of them (a parameter's default is a constant)",
            Scope::Params => "numbers, `PI` and parameters (geometry, masses and initial values do not move)",
            Scope::Time => "`t` and parameters (a driver is a function of time)",
            Scope::State => "coordinates, `t` and parameters (a constraint does not depend on velocities)",
            Scope::Force => "",
        }
    }
}

pub struct Param {
    pub name: Ident,
    pub default: f64,
}

pub struct Body {
    pub name: Ident,
    /// A point mass (`particle`): its inertia is its mass times 1 m² and its angle (in space: its
    /// orientation) is held by rows of its own, so it neither rotates nor makes M singular.
    pub particle: bool,
    pub mass: MExpr,
    pub inertia: Inertia,
    /// Initial guess of the coordinates: (x, y, φ), or (x, y, z, e0, e1, e2, e3).
    pub q0: Vec<MExpr>,
    /// Initial velocities: (ẋ, ẏ, φ̇), or (ẋ, ẏ, ż, ω′x, ω′y, ω′z).
    pub v0: Vec<MExpr>,
}

/// A body's inertia about its centre of mass: J (planar) or the symmetric tensor J′ in body axes
/// (spatial; `J′_xy = −∫ x y dm`), rows of three.
pub enum Inertia {
    Planar(MExpr),
    Tensor([[MExpr; 3]; 3]),
}

/// The components of a point or vector (2 in the plane, 3 in space).
pub type Components = Vec<MExpr>;

/// A named point or vector, local to its body.
pub struct Local {
    pub body: BodyRef,
    pub name: String,
    pub local: Components,
}

/// A point on a body, by its body-fixed coordinates.
#[derive(Clone, Debug)]
pub struct Loc {
    pub body: BodyRef,
    pub point: Components,
}

/// A validated mechanism.
pub struct Model {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub scalar: Scalar,
    pub space: Space,
    pub params: Vec<Param>,
    pub bodies: Vec<Body>,
    pub points: Vec<Local>,
    pub vectors: Vec<Local>,
    pub constraints: Vec<Constraint>,
    /// Gravitational acceleration (m/s²), if declared.
    pub gravity: Option<Components>,
    pub forces: Vec<ForceElement>,
    /// What the macro can see is likely a mistake but is valid (an angle driver in degrees).
    pub warnings: Vec<(Span, String)>,
}

impl Model {
    pub fn body_name(&self, b: BodyRef) -> String {
        match b {
            BodyRef::Ground => "ground".to_string(),
            BodyRef::Body(k) => self.bodies[k].name.to_string(),
        }
    }
    /// Coordinate names, `"crank.phi"`.
    pub fn coordinate_names(&self) -> Vec<String> {
        let cs = self.space.coordinates();
        self.bodies.iter().flat_map(|b| cs.iter().map(move |c| format!("{}.{}", b.name, c.name()))).collect()
    }
    /// Velocity names, `"crank.omega"`, `"top.wz"`.
    pub fn velocity_names(&self) -> Vec<String> {
        let vs = self.space.velocities();
        self.bodies.iter().flat_map(|b| vs.iter().map(move |c| format!("{}.{}", b.name, c.name()))).collect()
    }
}

/// What a partially invalid mechanism still yields, so the macro can emit its type and keep
/// follow-up errors quiet.
pub struct Partial {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub scalar: Scalar,
    pub params: Vec<Ident>,
}

pub struct Resolver<'a> {
    pub errors: &'a mut Errors,
    pub space: Space,
    /// The largest magnitude the scalar type holds (f32 or f64).
    largest: f64,
    params: HashMap<String, usize>,
    /// The parameters' default values, by index (for marker defaults).
    pub defaults: Vec<f64>,
    bodies: HashMap<String, usize>,
    points: HashMap<(BodyRef, String), Components>,
    vectors: HashMap<(BodyRef, String), Components>,
}

const BODY_FIELDS: &[&str] = &["mass", "inertia", "at", "velocity"];
const SPATIAL_BODY_FIELDS: &[&str] = &["mass", "inertia", "at", "quaternion", "axis_angle", "angles", "velocity", "omega"];
const FUNCTIONS: &[&str] =
    &["sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "ln", "pow", "abs", "sign", "min", "max", "clamp", "deg"];

impl Resolver<'_> {
    /// Whether a name is `ground` or a declared body (nothing reported).
    pub fn is_body(&self, id: &Ident) -> bool {
        id == "ground" || self.bodies.contains_key(&id.to_string())
    }

    pub fn body(&mut self, id: &Ident) -> Option<BodyRef> {
        if id == "ground" {
            return Some(BodyRef::Ground);
        }
        match self.bodies.get(&id.to_string()) {
            Some(&k) => Some(BodyRef::Body(k)),
            None => {
                let names: Vec<&str> = self.bodies.keys().map(|s| s.as_str()).collect();
                let hint = parse::closest(&id.to_string(), &names, &["ground"]);
                self.errors
                    .push(id.span(), format!("unknown body: expected a declared body or `ground`, found `{id}`{hint}; declare it with `body {id} {{ mass: ..., inertia: ... }}`"));
                None
            }
        }
    }

    /// An expression resolved in its scope; a constant part of it that is not finite (`ln(0)`,
    /// `sqrt(-1)`, `1e999`), or beyond f32's range under `scalar f32;`, is an error on that part.
    pub fn expr(&mut self, e: &Expr, scope: Scope) -> Option<MExpr> {
        let m = self.expr_unchecked(e, scope)?;
        match m.constant_value() {
            Some(v) if !v.is_finite() => {
                self.errors.at_expr(
                    e,
                    format!("expected a finite value, found {v} for every state and time: a constant such as ln(0), 1/0 or sqrt(-1)"),
                );
                None
            }
            Some(v) if v.abs() > self.largest => {
                self.errors.at_expr(e, format!("this constant is beyond the range of f32: expected at most ±3.4e38, found {v:e}"));
                None
            }
            _ => Some(m),
        }
    }

    fn expr_unchecked(&mut self, e: &Expr, scope: Scope) -> Option<MExpr> {
        Some(match &e.kind {
            ExprKind::Num(v) => MExpr::Num(*v),
            ExprKind::Ident(id) => {
                let s = id.to_string();
                if s == "PI" {
                    MExpr::Pi
                } else if s == "t" {
                    if matches!(scope, Scope::Constant | Scope::Params) {
                        self.errors.push(id.span(), format!("time `t` is not allowed here: expected {}, found `t`", scope.describe()));
                        return None;
                    }
                    MExpr::T
                } else if let Some(&k) = self.params.get(&s) {
                    if scope == Scope::Constant {
                        self.errors
                            .push(id.span(), format!("parameter `{s}` is not allowed here: expected {}, found `{s}`", scope.describe()));
                        return None;
                    }
                    MExpr::Param(k)
                } else {
                    let names: Vec<&str> = self.params.keys().map(|s| s.as_str()).collect();
                    let hint = parse::closest(&s, &names, &["t", "PI"]);
                    self.errors.push(
                        id.span(),
                        format!("unknown identifier: expected a number, a parameter declared in `params {{ }}`, `t`, `PI` or a coordinate like `crank.phi`, found `{s}`{hint}"),
                    );
                    return None;
                }
            }
            ExprKind::Coord(b, c) => {
                let position = Coord::from_ident(self.space, c);
                let velocity = Vel::from_ident(self.space, c);
                if position.is_none() && velocity.is_none() {
                    self.errors.push(
                        c.span(),
                        format!(
                            "unknown coordinate: expected {} or, in forces, a velocity {}, found `{c}`",
                            self.space.coordinate_list(),
                            self.space.velocity_list()
                        ),
                    );
                    return None;
                }
                let allowed = matches!((position, scope), (Some(_), Scope::State | Scope::Force) | (None, Scope::Force));
                if !allowed {
                    let what = if position.is_some() { "coordinate" } else { "velocity" };
                    self.errors.at_expr(e, format!("{what} `{b}.{c}` is not allowed here: expected {}, found `{b}.{c}`", scope.describe()));
                    return None;
                }
                let body = self.body(b)?;
                match (position, velocity) {
                    (Some(coord), _) => MExpr::Coord(body, coord),
                    (None, Some(coord)) => MExpr::Vel(body, coord),
                    (None, None) => return None,
                }
            }
            ExprKind::Neg(a) => MExpr::Neg(Box::new(self.expr(a, scope)?)),
            ExprKind::Bin(op, a, b) => {
                let a = self.expr(a, scope);
                let b = self.expr(b, scope);
                let op = match op {
                    BinOp::Add => MBin::Add,
                    BinOp::Sub => MBin::Sub,
                    BinOp::Mul => MBin::Mul,
                    BinOp::Div => MBin::Div,
                    BinOp::Pow => MBin::Pow,
                };
                MExpr::Bin(op, Box::new(a?), Box::new(b?))
            }
            ExprKind::Call(f, args) => {
                let name = f.to_string();
                let arity = match name.as_str() {
                    "atan2" | "pow" => 2,
                    "deg" => 1,
                    n if Func::from_name(n).is_some() => 1,
                    n if Kink::from_name(n).is_some() => Kink::from_name(n)?.arity(),
                    _ => {
                        let hint = parse::closest(&name, FUNCTIONS, &[]);
                        self.errors.push(
                            f.span(),
                            format!("unknown function: expected {}, found `{name}`{hint}", parse::one_of(FUNCTIONS, "a function")),
                        );
                        return None;
                    }
                };
                if args.len() != arity {
                    self.errors.at_expr(e, format!("wrong number of arguments to `{name}`: expected {arity}, found {}", args.len()));
                    return None;
                }
                let resolved: Vec<Option<MExpr>> = args.iter().map(|a| self.expr(a, scope)).collect();
                let resolved = resolved.into_iter().collect::<Option<Vec<_>>>()?;
                if let Some(k) = Kink::from_name(&name) {
                    return Some(MExpr::Kink(k, resolved.into()));
                }
                let mut resolved = resolved.into_iter();
                let a = Box::new(resolved.next()?);
                match name.as_str() {
                    "atan2" => MExpr::Atan2(a, Box::new(resolved.next()?)),
                    "pow" => MExpr::Bin(MBin::Pow, a, Box::new(resolved.next()?)),
                    // degrees to radians
                    "deg" => MExpr::Bin(MBin::Mul, a, Box::new(MExpr::Num(std::f64::consts::PI / 180.0))),
                    n => MExpr::Call(Func::from_name(n)?, a),
                }
            }
            ExprKind::If(c, then, otherwise) => {
                let (a, b) = (self.expr(&c.lhs, scope), self.expr(&c.rhs, scope));
                let (x, y) = (self.expr(then, scope), self.expr(otherwise, scope));
                let (a, b, x, y) = (a?, b?, x?, y?);
                let (cmp, a, b) = match c.op {
                    CmpOp::Gt => (Cmp::Gt, a, b),
                    CmpOp::Ge => (Cmp::Ge, a, b),
                    CmpOp::Lt => (Cmp::Gt, b, a),
                    CmpOp::Le => (Cmp::Ge, b, a),
                };
                MExpr::If(cmp, Box::new([a, b, x, y]))
            }
        })
    }

    /// A list of as many components as the space has (2 or 3), each of the given scope.
    pub fn components(&mut self, v: &VecLit, scope: Scope, what: &str) -> Option<Components> {
        let n = self.space.dim();
        if v.items.len() != n {
            self.errors.push(v.span, format!("{what}: expected {n} entries, found {}", v.items.len()));
            return None;
        }
        let items: Vec<Option<MExpr>> = v.items.iter().map(|e| self.expr(e, scope)).collect();
        items.into_iter().collect()
    }

    /// "`[ξ, η]`" or "`[ξ, η, ζ]`".
    pub fn shape(&self, names: [&str; 3]) -> String {
        format!("[{}]", names[..self.space.dim()].join(", "))
    }

    pub fn point(&mut self, body: BodyRef, p: &PointRef) -> Option<Components> {
        let shape = self.shape(["ξ", "η", "ζ"]);
        match p {
            PointRef::Inline(v) => self.components(v, Scope::Params, &format!("a point `{shape}` in body coordinates")),
            PointRef::Named(name) => match self.points.get(&(body, name.to_string())) {
                Some(p) => Some(p.clone()),
                None => {
                    let body_name = match body {
                        BodyRef::Ground => "ground".to_string(),
                        BodyRef::Body(k) => self.bodies.iter().find(|(_, &i)| i == k).map(|(n, _)| n.clone()).unwrap_or_default(),
                    };
                    let mut declared: Vec<&str> = self.points.keys().filter(|(b, _)| *b == body).map(|(_, n)| n.as_str()).collect();
                    declared.sort_unstable();
                    let hint = parse::closest(&name.to_string(), &declared, &[]);
                    let expected = match declared.as_slice() {
                        [] => "a declared point".to_string(),
                        some => format!("one of {}", some.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")),
                    };
                    self.errors.push(
                        name.span(),
                        format!(
                            "unknown point on body `{body_name}`: expected {expected}, found `{name}`{hint}; declare it with `point {body_name}.{name} = {shape};`"
                        ),
                    );
                    None
                }
            },
        }
    }

    pub fn loc(&mut self, body_id: &Ident, p: &PointRef) -> Option<Loc> {
        let body = self.body(body_id)?;
        let point = self.point(body, p)?;
        Some(Loc { body, point })
    }

    pub fn axis(&mut self, body: BodyRef, a: &AxisRef) -> Option<Components> {
        match a {
            AxisRef::Inline(v) => {
                let shape = self.shape(["x", "y", "z"]);
                let axis = self.components(v, Scope::Params, &format!("an axis `{shape}` in body coordinates"))?;
                let values: Option<Vec<f64>> = axis.iter().map(|c| c.constant_value()).collect();
                if values.is_some_and(|v| v.iter().all(|&c| c == 0.0)) {
                    self.errors.push(v.span, "an axis has a direction: expected a non-zero vector, found the zero vector");
                    return None;
                }
                Some(axis)
            }
            AxisRef::Named(b, name) => {
                if self.body(b)? != body {
                    self.errors
                        .push(b.span(), "the axis must be a vector of the same body as the point: expected that body, found another");
                    return None;
                }
                match self.vectors.get(&(body, name.to_string())) {
                    Some(v) => Some(v.clone()),
                    None => {
                        let shape = self.shape(["x", "y", "z"]);
                        self.errors.push(name.span(), format!("unknown vector: expected a declared vector, found `{name}`; declare it with `vector {b}.{name} = {shape};`"));
                        None
                    }
                }
            }
        }
    }
}

/// The name of a joint, driver, constraint or force element — its label, or its default name —
/// if no other statement has it yet; otherwise an error on the label or the statement's keyword.
fn claim_name(
    names: &mut HashMap<String, Span>,
    errors: &mut Errors,
    label: Option<&Ident>,
    default_name: String,
    span: Span,
) -> Option<String> {
    let (name, span) = match label {
        Some(l) => (l.to_string(), l.span()),
        None => (default_name, span),
    };
    if names.insert(name.clone(), span).is_none() {
        return Some(name);
    }
    let msg = if label.is_some() {
        format!("duplicate name `{name}`: expected a new name, found `{name}` again; rename one of them")
    } else {
        format!("a second `{name}`: give one of them a name, e.g. `{} name: ...`", name.split(' ').next().unwrap_or(""))
    };
    errors.push(span, msg);
    None
}

/// Associated items of every generated mechanism type: a body or joint whose generated constant
/// (its name in upper case) or a point whose accessor (`body_point`) would take one of these
/// names is refused.
const GENERATED_ITEMS: &[&str] = &[
    "N_BODIES",
    "NQ",
    "NV",
    "NC",
    "DOF",
    "NNZ",
    "NP",
    "NEWTON_STORAGE",
    "NAME",
    "BODY_NAMES",
    "COORDINATE_NAMES",
    "VELOCITY_NAMES",
    "COORDINATES",
    "VELOCITIES",
    "CONSTRAINT_NAMES",
    "PARAM_NAMES",
    "JACOBIAN_PATTERN",
    "PHI_T_IS_ZERO",
    "OP_COUNTS",
    "JOINTS",
    "EFFECTS",
    "FORCE_ELEMENTS",
    "MODEL_JSON",
    "params",
    "from_params",
    "workspace",
    "generalized_alpha",
    "mass_of",
    "inertia_of",
    "jacobian_values",
    "full_eval_values",
    "schur_factor",
    "schur_solve",
    "NEWTON_PATTERN",
    "newton_storage",
    "newton_jacobian",
    "newton_matrix",
];

/// The joint coordinates a labelled spatial joint gets an accessor for (`hinge_angle(&q)`), by
/// the kinds that have them.
pub const JOINT_COORDINATES: &[(&str, &[&str])] = &[("angle", &["revolute", "cylindrical"]), ("stroke", &["translational", "cylindrical"])];

/// The generated constant of a body or labelled joint: its name in upper case (`Name::CRANK`).
pub fn constant_name(name: &str) -> String {
    name.to_uppercase()
}

/// The generated accessor of a named point: `crank.A` → `crank_a()`.
pub fn point_accessor(body: &str, point: &str) -> String {
    format!("{body}_{point}").to_lowercase()
}

/// `scalar f32;`: the scalar type, once.
fn declare_scalar(r: &mut Resolver, s: &Ident, scalar: &mut Option<(Scalar, Span)>) {
    let sc = match s.to_string().as_str() {
        "f64" => Scalar::F64,
        "f32" => Scalar::F32,
        other => {
            r.errors.push(s.span(), format!("unsupported scalar type: expected `f64` or `f32`, found `{other}`"));
            return;
        }
    };
    if scalar.is_some() {
        r.errors.push(s.span(), "the scalar type is declared twice: expected one `scalar`, found a second one");
    }
    *scalar = Some((sc, s.span()));
}

/// `params { ... }`: each parameter with its default, unless its name is taken or reserved.
/// False where one has a mistake (the others are still declared).
fn declare_params(r: &mut Resolver, ps: &[(Ident, Expr)], params: &mut Vec<Param>) -> bool {
    let mut ok = true;
    for (name, value) in ps {
        if r.params.contains_key(&name.to_string()) {
            r.errors
                .push(name.span(), format!("duplicate parameter `{name}`: expected a new name, found `{name}` again; rename one of them"));
            ok = false;
            continue;
        }
        if ["t", "PI", "ground"].contains(&name.to_string().as_str()) {
            r.errors.push(
                name.span(),
                format!(
                    "`{name}` is reserved: expected a parameter's name, found `{name}`, which expressions read as {}",
                    match name.to_string().as_str() {
                        "t" => "time",
                        "PI" => "π",
                        _ => "the fixed frame",
                    }
                ),
            );
            ok = false;
            continue;
        }
        // A default with a mistake is reported; the parameter is still declared,
        // so that what uses it is not reported too.
        let default = match r.expr(value, Scope::Constant).map(|d| d.constant_value().unwrap_or(f64::NAN)) {
            Some(d) if d.is_finite() => d,
            Some(d) => {
                r.errors.at_expr(value, format!("the default of `{name}` is not finite: expected a finite value, found {d}"));
                ok = false;
                0.0
            }
            None => {
                ok = false;
                0.0
            }
        };
        r.params.insert(name.to_string(), params.len());
        r.defaults.push(default);
        params.push(Param { name: name.clone(), default });
    }
    ok
}

/// A body's name, unless taken: false where it is `ground`, a duplicate, or generates an item
/// that clashes.
fn declare_body<'d>(r: &mut Resolver, b: &'d BodyDef, items: &mut HashMap<String, String>, bodies: &mut Vec<&'d BodyDef>) -> bool {
    if b.name == "ground" {
        r.errors.push(b.name.span(), "`ground` is the fixed frame, always present: expected another body name, found `ground`");
        return false;
    }
    if r.bodies.contains_key(&b.name.to_string()) {
        r.errors.push(b.name.span(), format!("duplicate body `{0}`: expected a new name, found `{0}` again; rename one of them", b.name));
        return false;
    }
    let item = constant_name(&b.name.to_string());
    if !claim_item(items, r.errors, item, format!("body `{}`", b.name), b.name.span()) {
        return false;
    }
    r.bodies.insert(b.name.to_string(), bodies.len());
    bodies.push(b);
    true
}

/// Claims a generated item name (a body's or labelled joint's constant, a point's accessor) for
/// `what`; an error on `span` if a generated item or an earlier name has it.
fn claim_item(items: &mut HashMap<String, String>, errors: &mut Errors, item: String, what: String, span: Span) -> bool {
    if GENERATED_ITEMS.contains(&item.as_str()) {
        errors.push(span, format!("{what} would generate `{item}`, which every mechanism already has: expected another name, found one that clashes; rename it"));
        return false;
    }
    if let Some(other) = items.insert(item.clone(), what.clone()) {
        errors.push(span, format!("{what} and {other} would both generate `{item}`: expected names that differ in more than case, found two that do not; rename one"));
        return false;
    }
    true
}

/// Checks a number that must be positive when it is a constant (a parameter's value is checked
/// at run time by the solver that needs it).
pub fn check_positive(errors: &mut Errors, e: &MExpr, written: &Expr, what: &str) {
    if let Some(v) = e.constant_value() {
        #[allow(clippy::neg_cmp_op_on_partial_ord)] // NaN is not positive either
        if !(v > 0.0) {
            errors.at_expr(written, format!("{what} must be positive: expected a value above 0, found {v}"));
        }
    }
}

impl MechanismDef {
    /// What survives of the mechanism's outline even when its body has mistakes.
    pub fn partial(&self) -> Partial {
        let mut scalar = Scalar::F64;
        let mut params = Vec::new();
        for item in &self.items {
            match item {
                Item::Scalar(s) if s == "f32" => scalar = Scalar::F32,
                Item::Params(ps) => params.extend(ps.iter().map(|(n, _)| n.clone())),
                _ => {}
            }
        }
        let mut seen = HashSet::new();
        params.retain(|p| seen.insert(p.to_string()));
        Partial { attrs: self.attrs.clone(), vis: self.vis.clone(), name: self.name.clone(), scalar, params }
    }

    /// Resolves and validates the mechanism.
    pub fn validate(&self) -> syn::Result<Model> {
        let mut errors = Errors::default();
        let model = self.build(&mut errors);
        let warnings = std::mem::take(&mut errors.1);
        errors.into_result()?;
        let mut model = model.ok_or_else(|| {
            syn::Error::new(self.name.span(), "invalid mechanism: expected a mechanism that resolves, found mistakes without a message")
        })?;
        model.warnings = warnings;
        Ok(model)
    }

    /// The named points and vectors on bodies, each once, in body coordinates.
    fn points_and_vectors(&self, r: &mut Resolver, items: &mut HashMap<String, String>, ok: &mut bool) -> (Vec<Local>, Vec<Local>) {
        let mut points = Vec::new();
        let mut vectors = Vec::new();
        for item in &self.items {
            let (nv, is_point) = match item {
                Item::Point(nv) => (nv, true),
                Item::Vector(nv) => (nv, false),
                _ => continue,
            };
            let Some(body) = r.body(&nv.body) else {
                *ok = false;
                continue;
            };
            let what = if is_point {
                format!("a point `{}` in body coordinates (m)", r.shape(["ξ", "η", "ζ"]))
            } else {
                format!("a vector `{}` in body coordinates", r.shape(["x", "y", "z"]))
            };
            let Some(local) = r.components(&nv.value, Scope::Params, &what) else {
                *ok = false;
                continue;
            };
            if is_point {
                let item = point_accessor(&nv.body.to_string(), &nv.name.to_string());
                if !claim_item(items, r.errors, item, format!("point `{}.{}`", nv.body, nv.name), nv.name.span()) {
                    *ok = false;
                    continue;
                }
            }
            let key = (body, nv.name.to_string());
            let table = if is_point { &mut r.points } else { &mut r.vectors };
            if table.insert(key, local.clone()).is_some() {
                r.errors.push(
                    nv.name.span(),
                    format!(
                        "duplicate {} `{}.{}`: expected a new name, found `{}` again; rename one of them",
                        if is_point { "point" } else { "vector" },
                        nv.body,
                        nv.name,
                        nv.name
                    ),
                );
                *ok = false;
                continue;
            }
            let l = Local { body, name: nv.name.to_string(), local };
            if is_point {
                points.push(l);
            } else {
                vectors.push(l);
            }
        }
        (points, vectors)
    }

    fn build(&self, errors: &mut Errors) -> Option<Model> {
        let mut scalar = None::<(Scalar, Span)>;
        let mut space = Space::Planar;
        for item in &self.items {
            if let Item::Spatial(kw) = item {
                if space == Space::Spatial {
                    errors.push(kw.span(), "`spatial;` is stated twice: expected it once, found it again");
                }
                space = Space::Spatial;
            }
        }
        let f32 = self.items.iter().any(|i| matches!(i, Item::Scalar(s) if s == "f32"));
        let mut r = Resolver {
            errors,
            space,
            largest: if f32 { f32::MAX as f64 } else { f64::MAX },
            params: HashMap::new(),
            defaults: Vec::new(),
            bodies: HashMap::new(),
            points: HashMap::new(),
            vectors: HashMap::new(),
        };
        let mut params = Vec::new();
        let mut bodies = Vec::new();
        let mut ok = true;
        // generated item names (constants of bodies and labelled joints, point accessors)
        let mut items: HashMap<String, String> = HashMap::new();

        // Pass 1: declarations (params, bodies) so statements can refer to them in any order.
        for item in &self.items {
            match item {
                Item::Scalar(s) => declare_scalar(&mut r, s, &mut scalar),
                Item::Params(ps) => ok &= declare_params(&mut r, ps, &mut params),
                Item::Body(b) => ok &= declare_body(&mut r, b, &mut items, &mut bodies),
                _ => {}
            }
        }

        let mut model_bodies = Vec::new();
        for b in &bodies {
            match resolve_body(&mut r, b) {
                Some(body) => model_bodies.push(body),
                None => ok = false,
            }
        }

        // Pass 2: points and vectors, then joints, drivers and constraints in declaration order.
        let (points, vectors) = self.points_and_vectors(&mut r, &mut items, &mut ok);

        let body_name = |b: BodyRef| match b {
            BodyRef::Ground => "ground".to_string(),
            BodyRef::Body(k) => bodies[k].name.to_string(),
        };
        let mut names: HashMap<String, Span> = HashMap::new();
        let (constraints, mut forces, joints) =
            constraints(&self.items, &mut r, &mut names, &mut items, &model_bodies, &body_name, &mut ok);
        let gravity = force_elements(&self.items, &mut r, &mut names, &body_name, &joints, &mut forces, &mut ok);

        if bodies.is_empty() {
            r.errors.push(
                self.name.span(),
                "a mechanism needs at least one body: expected `body name { mass: ..., inertia: ... }`, found none",
            );
            ok = false;
        }
        if !ok {
            return None;
        }
        Some(Model {
            attrs: self.attrs.clone(),
            vis: self.vis.clone(),
            name: self.name.clone(),
            scalar: scalar.map(|(s, _)| s).unwrap_or(Scalar::F64),
            space,
            params,
            bodies: model_bodies,
            points,
            vectors,
            constraints,
            gravity,
            forces,
            warnings: Vec::new(),
        })
    }
}

/// An angle driver whose rate, at the parameters' defaults, is above 100 rev/s or a whole
/// multiple of 90 rad/s — degrees per second written as radians (`360 * t` turns at 57 rev/s) —
/// gets a warning on its expression; `deg(360) * t` is one turn a second.
fn angle_rate_check(r: &mut Resolver, written: &Expr, f: &MExpr) {
    let rate = |t: f64| {
        let h = 1e-6 * t.abs().max(1.0);
        Some((f.value_at(&r.defaults, t + h)? - f.value_at(&r.defaults, t - h)?) / (2.0 * h))
    };
    let rates: Option<Vec<f64>> = [0.0, 0.25, 0.5, 1.0, 2.0].into_iter().map(rate).collect();
    let Some(rates) = rates else { return };
    let fastest = rates.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let whole = rates[0].round();
    let rev = |w: f64| w / std::f64::consts::TAU;
    if fastest > 100.0 * std::f64::consts::TAU && fastest.is_finite() {
        r.errors.warn(
            written.span,
            format!(
                "this angle driver turns at {:.0} rev/s ({fastest:.0} rad/s): expected an angle in radians, found a rate above 100 rev/s, which reads like degrees; for degrees write `deg(...)`",
                rev(fastest)
            ),
        );
    } else if whole.abs() >= 90.0 && whole % 90.0 == 0.0 && (rates[0] - whole).abs() < 1e-6 * whole.abs() {
        r.errors.warn(
            written.span,
            format!(
                "this angle driver turns at {whole} rad/s ({:.1} rev/s): expected an angle in radians, found a rate that reads like degrees per second; for {whole}°/s write `deg({whole}) * t`",
                rev(whole)
            ),
        );
    }
}

/// A spatial joint by its name: its kind and markers (what its drivers and force elements use).
pub type SpatialJoints = HashMap<String, (&'static str, Marker, Marker)>;

/// Pass 3: joints, drivers and user constraints in declaration order, each resolved by its
/// kind's file, with the joint friction their options declare. In space, joints are resolved
/// first, so a driver may name a joint declared after it; they are also returned by name.
fn constraints(
    items: &[Item],
    r: &mut Resolver,
    names: &mut HashMap<String, Span>,
    generated: &mut HashMap<String, String>,
    bodies: &[Body],
    body_name: &dyn Fn(BodyRef) -> String,
    ok: &mut bool,
) -> (Vec<Constraint>, Vec<ForceElement>, SpatialJoints) {
    let mut constraints = Vec::new();
    let mut forces = Vec::new();
    let mut driven = Driven::default();
    // A particle's angle is held by a row of its own, after the declared ones.
    if r.space == Space::Planar {
        for (k, b) in bodies.iter().enumerate().filter(|(_, b)| b.particle) {
            driven.coords.insert((k, Coord::Phi), b.name.span());
        }
    }
    let mut spatial_joints = HashMap::new();
    let mut joints = SpatialJoints::new();
    if r.space == Space::Spatial {
        // the index each joint will have among the constraints (exact when every statement
        // resolves; otherwise the mechanism is refused anyway)
        let mut joint_index = 0;
        for (index, item) in items.iter().enumerate() {
            if matches!(item, Item::Fix(_) | Item::Drive(_) | Item::Constraint(_)) {
                joint_index += 1;
            }
            if let Item::Joint(j) = item {
                let resolved = spatial::resolve(r, j, body_name, joint_index);
                joint_index += 1;
                if let Some((label, default_name, _, kind, _)) = &resolved {
                    if let Some([mi, mj]) = kind.markers() {
                        let name = label.map_or_else(|| default_name.clone(), |l| l.to_string());
                        joints.insert(name, (kind.kind(), mi.clone(), mj.clone()));
                    }
                }
                spatial_joints.insert(index, resolved);
            }
        }
    }
    for (index, item) in items.iter().enumerate() {
        let built = match item {
            Item::Joint(_) if r.space == Space::Spatial => spatial_joints.remove(&index).flatten(),
            Item::Joint(j) => elements::resolve(r, j, body_name, constraints.len()),
            Item::Fix(f) => fix::resolve(r, f, &mut driven, bodies),
            Item::Drive(d) => {
                let f = r.expr(&d.f, Scope::Time);
                let angle = match &d.target {
                    DriveTarget::Coordinate { coordinate, .. } => coordinate == "phi" || coordinate == "angle",
                    DriveTarget::Angle { .. } => true,
                    DriveTarget::Distance { .. } => false,
                };
                if let (true, Some(f)) = (angle, &f) {
                    angle_rate_check(r, &d.f, f);
                }
                match &d.target {
                    DriveTarget::Coordinate { body, coordinate } if r.space == Space::Spatial && !r.is_body(body) => {
                        spatial::drive_joint(r, d, body, coordinate, f, &joints, &mut driven)
                    }
                    DriveTarget::Angle { .. } | DriveTarget::Distance { .. } if r.space == Space::Spatial => {
                        r.errors.push(d.keyword.span(), "`angle(..)` and `distance(..)` drivers are planar: expected a joint to drive in space, found a relative driver; `drive hinge.angle = f;` or `drive slider.stroke = f;`");
                        None
                    }
                    DriveTarget::Coordinate { body, coordinate } => drive::resolve(r, d, body, coordinate, f, &mut driven),
                    DriveTarget::Angle { i, j, .. } => drive_angle::resolve(r, d, i, j, f, &mut driven),
                    DriveTarget::Distance { i, j, .. } => drive_distance::resolve(r, d, i, j, f),
                }
            }
            Item::Constraint(c) => user::resolve(r, c, index),
            _ => continue,
        };
        let Some((label, default_name, span, kind, friction)) = built else {
            *ok = false;
            continue;
        };
        let Some(name) = claim_name(names, r.errors, label, default_name, span) else {
            *ok = false;
            continue;
        };
        if let Some(l) = label {
            if !claim_item(generated, r.errors, constant_name(&name), format!("joint `{name}`"), l.span()) {
                *ok = false;
                continue;
            }
            let coordinates = JOINT_COORDINATES.iter().filter(|(_, kinds)| r.space == Space::Spatial && kinds.contains(&kind.kind()));
            for (what, _) in coordinates {
                if !claim_item(generated, r.errors, format!("{name}_{what}"), format!("the {what} of joint `{name}`"), l.span())
                    || !claim_item(
                        generated,
                        r.errors,
                        format!("{name}_{what}_rate"),
                        format!("the {what} rate of joint `{name}`"),
                        l.span(),
                    )
                {
                    *ok = false;
                }
            }
        }
        for (what, kind) in friction {
            forces.push(ForceElement { name: format!("{name} {what}"), kind });
        }
        constraints.push(Constraint { name, kind });
    }
    for (k, b) in bodies.iter().enumerate().filter(|(_, b)| b.particle) {
        let Some(name) = claim_name(names, r.errors, None, format!("particle {}", b.name), b.name.span()) else {
            *ok = false;
            continue;
        };
        let kind: Box<dyn elements::Joint> = match r.space {
            Space::Planar => Box::new(fix::Fix { body: k, coord: Coord::Phi, value: MExpr::Num(0.0) }),
            Space::Spatial => Box::new(spatial::rigid::Orientation::held(k)),
        };
        constraints.push(Constraint { name, kind });
    }
    (constraints, forces, joints)
}

/// Pass 4: gravity and the force elements (Nikravesh ch. 4), each resolved by its kind's file.
/// Returns gravity, if declared.
fn force_elements(
    items: &[Item],
    r: &mut Resolver,
    names: &mut HashMap<String, Span>,
    body_name: &dyn Fn(BodyRef) -> String,
    joints: &SpatialJoints,
    forces: &mut Vec<ForceElement>,
    ok: &mut bool,
) -> Option<Components> {
    let mut gravity = None;
    for item in items {
        let built = match item {
            Item::Gravity(kw, v) => {
                if gravity.is_some() {
                    r.errors.push(kw.span(), "gravity is declared twice: expected one `gravity`, found a second one");
                    *ok = false;
                }
                let shape = r.shape(["gx", "gy", "gz"]);
                gravity = r.components(v, Scope::Params, &format!("gravity `{shape}` (m/s²)"));
                if gravity.is_none() {
                    *ok = false;
                }
                continue;
            }
            Item::PointForce(f) if f.kind == "bushing" => bushing::resolve(r, f, body_name),
            Item::PointForce(f) if f.kind == "contact" => contact::resolve(r, f, body_name),
            Item::PointForce(f) if f.kind == "cable" => cable::resolve(r, f, body_name),
            Item::PointForce(f) if f.kind == "tyre" => tyre::resolve(r, f, body_name),
            Item::PointForce(f) => point_to_point::resolve(r, f, body_name),
            Item::AxisForce(f) if stroke::KINDS.contains(&f.kind.to_string().as_str()) => stroke::resolve(r, f, joints),
            Item::AxisForce(f) => rotational::resolve(r, f, joints),
            Item::Force(f) => applied::resolve(r, f),
            Item::Torque(tq) => torque::resolve(r, tq),
            _ => continue,
        };
        let Some((label, default_name, span, kind)) = built else {
            *ok = false;
            continue;
        };
        let Some(name) = claim_name(names, r.errors, label, default_name, span) else {
            *ok = false;
            continue;
        };
        forces.push(ForceElement { name, kind });
    }
    gravity
}

/// A body statement's fields by name; `false` when one is unknown or given twice (each reported).
fn body_fields<'b>(r: &mut Resolver, b: &'b parse::BodyDef, known: &[&str], help: &str) -> (HashMap<String, &'b Value>, bool) {
    let mut fields: HashMap<String, &Value> = HashMap::new();
    let mut ok = true;
    for f in &b.fields {
        let key = f.name.to_string();
        if !known.contains(&key.as_str()) {
            let hint = parse::closest(&key, known, &[]);
            r.errors.push(f.name.span(), format!("unknown body field: expected {help}, found `{key}`{hint}"));
            ok = false;
            // A misspelt field stands for the field it is near, so it is not also missing.
            if let Some(near) = parse::nearest(&key, known, &[]) {
                fields.entry(near.to_string()).or_insert(&f.value);
            }
        } else if fields.insert(key.clone(), &f.value).is_some() {
            r.errors.push(f.name.span(), format!("duplicate field `{key}`: expected each field once, found `{key}` again; keep one"));
            ok = false;
        }
    }
    (fields, ok)
}

/// A required positive number field of a body (mass, planar inertia).
fn positive_field(r: &mut Resolver, b: &parse::BodyDef, fields: &HashMap<String, &Value>, name: &str, unit: &str) -> Option<MExpr> {
    match fields.get(name) {
        None => {
            r.errors.push(
                b.name.span(),
                format!("body `{}` has no `{name}`: expected `{name}` in {unit}, e.g. `{name}: 1.0`, found none", b.name),
            );
            None
        }
        Some(Value::List(v)) => {
            r.errors.push(v.span, format!("`{name}` is a number: expected a number ({unit}), found a list"));
            None
        }
        Some(Value::Expr(e)) => {
            let m = r.expr(e, Scope::Params)?;
            if name == "inertia" && m.constant_value() == Some(0.0) {
                r.errors.at_expr(
                    e,
                    format!("the inertia of body `{0}` must be positive: expected a value above 0, found 0; a point mass is a particle, `particle {0} {{ mass: ..., at: [x, y] }}`", b.name),
                );
                return None;
            }
            check_positive(r.errors, &m, e, &format!("the {name} of body `{}`", b.name));
            Some(m)
        }
    }
}

/// An optional list field of a body with one of the allowed lengths (zeros when absent).
fn list_field(r: &mut Resolver, fields: &HashMap<String, &Value>, name: &str, what: &str, lengths: &[usize]) -> Option<Option<Vec<MExpr>>> {
    match fields.get(name) {
        None => Some(None),
        Some(Value::Expr(e)) => {
            r.errors.push(e.span, format!("`{name}` is a list: expected `[{what}]`, found a number"));
            None
        }
        Some(Value::List(v)) => {
            if !lengths.contains(&v.items.len()) {
                r.errors.push(v.span, format!("`{name}: [{what}]`: expected {} entries, found {}", lengths[0], v.items.len()));
                return None;
            }
            let items: Vec<Option<MExpr>> = v.items.iter().map(|e| r.expr(e, Scope::Params)).collect();
            items.into_iter().collect::<Option<Vec<_>>>().map(Some)
        }
    }
}

fn zeros(n: usize) -> Vec<MExpr> {
    vec![MExpr::Num(0.0); n]
}

/// A body statement, planar or spatial.
fn resolve_body(r: &mut Resolver, b: &parse::BodyDef) -> Option<Body> {
    match r.space {
        Space::Planar if b.particle => {
            let help = "`mass`, `at: [x, y]` or `velocity: [vx, vy]` (a particle)";
            let (fields, ok) = body_fields(r, b, &["mass", "at", "velocity"], help);
            let mass = positive_field(r, b, &fields, "mass", "kg");
            let q0 = list_field(r, &fields, "at", "x, y", &[2]);
            let v0 = list_field(r, &fields, "velocity", "vx, vy", &[2]);
            if !ok {
                return None;
            }
            let mass = mass?;
            let planar = |v: Option<Vec<MExpr>>| {
                let mut v = v.unwrap_or_else(|| zeros(2));
                v.push(MExpr::Num(0.0));
                v
            };
            Some(Body {
                name: b.name.clone(),
                particle: true,
                // J = m·(1 m)²: any positive value would do, since the angle is held; this one
                // keeps the angle's row as well scaled as the positions'.
                inertia: Inertia::Planar(mass.clone()),
                mass,
                q0: planar(q0?),
                v0: planar(v0?),
            })
        }
        Space::Planar => {
            let help = "`mass`, `inertia`, `at: [x, y, phi]` or `velocity: [vx, vy, omega]`";
            let (fields, ok) = body_fields(r, b, BODY_FIELDS, help);
            let mass = positive_field(r, b, &fields, "mass", "kg");
            let inertia = positive_field(r, b, &fields, "inertia", "kg·m² about the centre of mass");
            let q0 = list_field(r, &fields, "at", "x, y, phi", &[3]);
            let v0 = list_field(r, &fields, "velocity", "vx, vy, omega", &[3]);
            if !ok {
                return None;
            }
            Some(Body {
                name: b.name.clone(),
                particle: false,
                mass: mass?,
                inertia: Inertia::Planar(inertia?),
                q0: q0?.unwrap_or_else(|| zeros(3)),
                v0: v0?.unwrap_or_else(|| zeros(3)),
            })
        }
        Space::Spatial => spatial_body(r, b),
    }
}

/// A spatial body: mass, inertia tensor, initial pose (position and one of quaternion,
/// axis-angle or z-y-x angles) and twist (velocity, body-frame angular velocity).
fn spatial_body(r: &mut Resolver, b: &parse::BodyDef) -> Option<Body> {
    if b.particle {
        let help = "`mass`, `at: [x, y, z]` or `velocity: [vx, vy, vz]` (a particle)";
        let (fields, ok) = body_fields(r, b, &["mass", "at", "velocity"], help);
        let mass = positive_field(r, b, &fields, "mass", "kg");
        let at = list_field(r, &fields, "at", "x, y, z", &[3]);
        let velocity = list_field(r, &fields, "velocity", "vx, vy, vz", &[3]);
        if !ok {
            return None;
        }
        let mass = mass?;
        let mut q0 = at?.unwrap_or_else(|| zeros(3));
        q0.extend([1.0, 0.0, 0.0, 0.0].map(MExpr::Num));
        let mut v0 = velocity?.unwrap_or_else(|| zeros(3));
        v0.extend(zeros(3));
        // J′ = m·(1 m)² I: any positive tensor would do, since the orientation is held.
        let j = |a: usize, c: usize| if a == c { mass.clone() } else { MExpr::Num(0.0) };
        let inertia = [[j(0, 0), j(0, 1), j(0, 2)], [j(1, 0), j(1, 1), j(1, 2)], [j(2, 0), j(2, 1), j(2, 2)]];
        return Some(Body { name: b.name.clone(), particle: true, mass, inertia: Inertia::Tensor(inertia), q0, v0 });
    }
    let help = "`mass`, `inertia: [Jxx, Jyy, Jzz]` or `[Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]`, `at: [x, y, z]`, \
                one of `quaternion: [e0, e1, e2, e3]`, `axis_angle: [ax, ay, az, angle]`, `angles: [yaw, pitch, roll]`, \
                `velocity: [vx, vy, vz]` or `omega: [wx, wy, wz]` (body frame)";
    let (fields, ok) = body_fields(r, b, SPATIAL_BODY_FIELDS, help);
    let mass = positive_field(r, b, &fields, "mass", "kg");
    let inertia = match fields.get("inertia") {
        None => {
            r.errors.push(
                b.name.span(),
                format!("body `{}` has no `inertia`: expected `inertia: [Jxx, Jyy, Jzz]` (kg·m², body axes), found none", b.name),
            );
            None
        }
        Some(Value::Expr(e)) => {
            r.errors.push(e.span, "a spatial body's `inertia` is a list: expected `[Jxx, Jyy, Jzz]` or `[Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]` (kg·m²), found a number");
            None
        }
        Some(Value::List(v)) => inertia_tensor(r, b, v),
    };
    let at = list_field(r, &fields, "at", "x, y, z", &[3]);
    let rotation = orientation(r, b, &fields);
    let velocity = list_field(r, &fields, "velocity", "vx, vy, vz", &[3]);
    let omega = list_field(r, &fields, "omega", "wx, wy, wz", &[3]);
    if !ok {
        return None;
    }
    let mut q0 = at?.unwrap_or_else(|| zeros(3));
    q0.extend(rotation?);
    let mut v0 = velocity?.unwrap_or_else(|| zeros(3));
    v0.extend(omega?.unwrap_or_else(|| zeros(3)));
    Some(Body { name: b.name.clone(), particle: false, mass: mass?, inertia: Inertia::Tensor(inertia?), q0, v0 })
}

/// `[Jxx, Jyy, Jzz]` or `[Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]` as the symmetric tensor; constant
/// diagonal entries must be positive.
fn inertia_tensor(r: &mut Resolver, b: &parse::BodyDef, v: &parse::VecLit) -> Option<[[MExpr; 3]; 3]> {
    if v.items.len() != 3 && v.items.len() != 6 {
        r.errors.push(
            v.span,
            format!("`inertia`: expected 3 entries `[Jxx, Jyy, Jzz]` or 6 `[Jxx, Jyy, Jzz, Jxy, Jxz, Jyz]`, found {}", v.items.len()),
        );
        return None;
    }
    let items: Vec<Option<MExpr>> = v.items.iter().map(|e| r.expr(e, Scope::Params)).collect();
    let items: Vec<MExpr> = items.into_iter().collect::<Option<_>>()?;
    for (k, axis) in ["Jxx", "Jyy", "Jzz"].iter().enumerate() {
        check_positive(r.errors, &items[k], &v.items[k], &format!("the moment of inertia {axis} of body `{}`", b.name));
    }
    let off = |k: usize| items.get(k).cloned().unwrap_or(MExpr::Num(0.0));
    let (xy, xz, yz) = (off(3), off(4), off(5));
    Some([[items[0].clone(), xy.clone(), xz.clone()], [xy, items[1].clone(), yz.clone()], [xz, yz, items[2].clone()]])
}

fn bin(op: MBin, a: MExpr, b: MExpr) -> MExpr {
    MExpr::Bin(op, Box::new(a), Box::new(b))
}

fn call(f: Func, a: MExpr) -> MExpr {
    MExpr::Call(f, Box::new(a))
}

/// The initial Euler parameters (e0, e1, e2, e3) of a spatial body from at most one of
/// `quaternion` (normalized here), `axis_angle` (a unit turn about the normalized axis) or
/// `angles` (yaw ψ about z, then pitch θ about the new y, then roll φ about the new x:
/// A = R_z(ψ) R_y(θ) R_x(φ)); the identity when none is given.
fn orientation(r: &mut Resolver, b: &parse::BodyDef, fields: &HashMap<String, &Value>) -> Option<Vec<MExpr>> {
    let given: Vec<&str> = ["quaternion", "axis_angle", "angles"].into_iter().filter(|k| fields.contains_key(*k)).collect();
    if given.len() > 1 {
        r.errors.push(
            b.name.span(),
            format!(
                "body `{}` gives its orientation twice: expected one of `quaternion`, `axis_angle` or `angles`, found `{}`; keep one",
                b.name,
                given.join("` and `")
            ),
        );
        return None;
    }
    let norm = |v: &[MExpr]| {
        let sum = v.iter().map(|c| bin(MBin::Pow, c.clone(), MExpr::Num(2.0))).reduce(|a, c| bin(MBin::Add, a, c));
        call(Func::Sqrt, sum.unwrap_or(MExpr::Num(0.0)))
    };
    let half = |a: &MExpr| bin(MBin::Mul, MExpr::Num(0.5), a.clone());
    Some(match given.first() {
        None => vec![MExpr::Num(1.0), MExpr::Num(0.0), MExpr::Num(0.0), MExpr::Num(0.0)],
        Some(&"quaternion") => {
            let p = list_field(r, fields, "quaternion", "e0, e1, e2, e3", &[4])??;
            let n = norm(&p);
            p.into_iter().map(|e| bin(MBin::Div, e, n.clone())).collect()
        }
        Some(&"axis_angle") => {
            let v = list_field(r, fields, "axis_angle", "ax, ay, az, angle", &[4])??;
            let n = norm(&v[..3]);
            let s = call(Func::Sin, half(&v[3]));
            let mut p = vec![call(Func::Cos, half(&v[3]))];
            p.extend(v[..3].iter().map(|a| bin(MBin::Mul, s.clone(), bin(MBin::Div, a.clone(), n.clone()))));
            p
        }
        Some(_) => {
            let v = list_field(r, fields, "angles", "yaw, pitch, roll", &[3])??;
            let [(sy, cy), (sp, cp), (sr, cr)] = [0, 1, 2].map(|k| (call(Func::Sin, half(&v[k])), call(Func::Cos, half(&v[k]))));
            let prod = |a: &MExpr, b: &MExpr, c: &MExpr| bin(MBin::Mul, bin(MBin::Mul, a.clone(), b.clone()), c.clone());
            vec![
                bin(MBin::Add, prod(&cr, &cp, &cy), prod(&sr, &sp, &sy)),
                bin(MBin::Sub, prod(&sr, &cp, &cy), prod(&cr, &sp, &sy)),
                bin(MBin::Add, prod(&cr, &sp, &cy), prod(&sr, &cp, &sy)),
                bin(MBin::Sub, prod(&cr, &cp, &sy), prod(&sr, &sp, &cy)),
            ]
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn validate(src: &str) -> syn::Result<Model> {
        syn::parse_str::<MechanismDef>(src).expect("the test input parses").validate()
    }

    /// Each statement becomes its kind, named by default after its kind and bodies; joint
    /// friction options become force elements named after their joint.
    #[test]
    fn statements_become_typed_kinds() {
        let m = validate(
            "M { body a { mass: 1.0, inertia: 0.1 } body b { mass: 2.0, inertia: 0.2, at: [1.0, 0.0, 0.0] }
                 revolute ground[0.0, 0.0] ~ a[-0.5, 0.0] { viscous: 0.1 };
                 translational slide: a[0.5, 0.0] along [1.0, 0.0] ~ b[0.0, 0.0] along [1.0, 0.0] { coulomb: 0.2 };
                 drive a.phi = t; constraint b.y = 0.0; spring a[0.0, 0.0] ~ b[0.0, 0.0] { k: 10.0, length: 1.0 }; }",
        )
        .unwrap();
        let kinds: Vec<(&str, &str)> = m.constraints.iter().map(|c| (c.kind.kind(), c.name.as_str())).collect();
        assert_eq!(
            kinds,
            [("revolute", "revolute ground~a"), ("translational", "slide"), ("drive", "drive a.phi"), ("constraint", "constraint 5")]
        );
        // (an unlabelled constraint is named by its statement's position, the bodies counted)
        let forces: Vec<(&str, &str)> = m.forces.iter().map(|f| (f.kind.kind(), f.name.as_str())).collect();
        assert_eq!(
            forces,
            [
                ("revolute_viscous", "revolute ground~a viscous friction"),
                ("translational_coulomb", "slide Coulomb friction"),
                ("point_to_point", "spring a~b")
            ]
        );
        assert_eq!(m.constraints[1].kind.bodies(), (Some(BodyRef::Body(0)), Some(BodyRef::Body(1))));
    }

    /// Every mistake of one mechanism is reported, each on its own token.
    #[test]
    fn all_mistakes_are_collected() {
        let Err(e) = validate(
            "M { body a { mass: -1.0, inertia: 0.1 }
                 revolute ground[0.0, 0.0] ~ crnk[0.0, 0.0];
                 revolute_revolute a[0.0, 0.0] ~ ground[1.0, 0.0];
                 translational a[0.0, 0.0] ~ ground[0.0, 0.0] along [1.0, 0.0]; }",
        ) else {
            panic!("the mechanism has mistakes")
        };
        let messages: Vec<String> = e.into_iter().map(|e| e.to_string()).collect();
        assert_eq!(messages.len(), 4, "{messages:#?}");
        assert!(messages[0].contains("mass of body `a` must be positive"), "{}", messages[0]);
        assert!(messages.iter().any(|m| m.contains("unknown body: expected a declared body or `ground`, found `crnk`")));
        assert!(messages.iter().any(|m| m.contains("needs its length")));
        assert!(messages.iter().any(|m| m.contains("needs a sliding axis on its first body")));
    }

    /// An option a kind does not take is named with the list of those it does.
    #[test]
    fn unknown_option_lists_the_known_ones() {
        let Err(e) = validate("M { body a { mass: 1.0, inertia: 0.1 } rigid ground[0.0, 0.0] ~ a[0.0, 0.0] { length: 1.0 }; }") else {
            panic!("`length` is not an option of rigid")
        };
        assert!(e.to_string().contains("unknown option of a rigid joint: expected `angle`, found `length`"), "{e}");
    }

    /// A spatial body's orientation from z-y-x angles is the unit quaternion of
    /// R_z(ψ) R_y(θ) R_x(φ); a marker without a reference gets the coordinate axis least along
    /// its axis; drivers name joints declared after them.
    #[test]
    fn spatial_bodies_markers_and_drivers() {
        let m = validate(
            "S { spatial; params { a: 0.0 }
                 body b { mass: 1.0, inertia: [1.0, 2.0, 3.0], angles: [0.3, 0.0, 0.0], omega: [0.0, 0.0, 2.0] }
                 drive hinge.angle = t;
                 revolute hinge: ground[0.0, 0.0, 0.0] along [a, 0.2, 1.0] ~ b[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0]; }",
        )
        .unwrap();
        let p: Vec<f64> = m.bodies[0].q0[3..].iter().map(|e| e.constant_value().unwrap()).collect();
        // a yaw of 0.3 rad about z: p = (cos 0.15, 0, 0, sin 0.15)
        let want = [0.15f64.cos(), 0.0, 0.0, 0.15f64.sin()];
        assert!(p.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-15), "{p:?}");
        assert_eq!(m.constraints.iter().map(|c| c.name.as_str()).collect::<Vec<_>>(), ["drive hinge.angle", "hinge"]);
        let [mi, _] = m.constraints[1].kind.markers().unwrap();
        let reference: Vec<f64> = mi.reference.iter().map(|e| e.constant_value().unwrap()).collect();
        assert_eq!(reference, [1.0, 0.0, 0.0], "|a_x| = 0 at the default of `a`: the x-axis");
    }

    /// Planar and spatial kinds are not mixed up: each is refused in the other space by name.
    #[test]
    fn spatial_and_planar_kinds_stay_apart() {
        let Err(e) = validate("M { body a { mass: 1.0, inertia: 0.1 } spherical ground[0.0, 0.0] ~ a[0.0, 0.0]; }") else {
            panic!("a spherical joint is spatial")
        };
        assert!(e.to_string().contains("found `spherical`, a spatial joint, in the plane"), "{e}");
        let Err(e) = validate("S { spatial; body a { mass: 1.0, inertia: [1.0, 1.0, 1.0] } revolute_revolute ground[0.0, 0.0, 0.0] ~ a[0.0, 0.0, 0.0] { length: 1.0 }; }") else {
            panic!("revolute_revolute is planar")
        };
        assert!(e.to_string().contains("a planar joint, in space"), "{e}");
        let Err(e) = validate("S { spatial; body a { mass: 1.0, inertia: 0.1 } }") else { panic!("a spatial inertia is a tensor") };
        assert!(e.to_string().contains("a spatial body's `inertia` is a list"), "{e}");
    }

    /// Bodies, labelled joints and named points generate named items (`Name::CRANK`,
    /// `Name::MOTOR`, `crank_a()`): two that would generate the same one, or one that would take a
    /// name every mechanism has, are refused on the later name.
    #[test]
    fn generated_names_do_not_collide() {
        let cases = [
            (
                "M { body a { mass: 1.0, inertia: 0.1 } body A { mass: 1.0, inertia: 0.1 } }",
                "body `A` and body `a` would both generate `A`",
            ),
            ("M { body nq { mass: 1.0, inertia: 0.1 } }", "body `nq` would generate `NQ`, which every mechanism already has"),
            (
                "M { body a { mass: 1.0, inertia: 0.1 } revolute a: ground[0.0, 0.0] ~ a[0.0, 0.0]; }",
                "joint `a` and body `a` would both generate `A`",
            ),
            ("M { body a { mass: 1.0, inertia: 0.1 } point a.B = [0.0, 0.0]; point a.b = [1.0, 0.0]; }", "would both generate `a_b`"),
        ];
        for (src, want) in cases {
            let Err(e) = validate(src) else { panic!("{src} has a name collision") };
            assert!(e.to_string().contains(want), "{src}: {e}");
        }
    }
}

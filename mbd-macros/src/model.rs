//! Stage 2: syntax tree → validated model. Every name is resolved here and every rule a user can
//! break is checked here, each mistake reported as a `syn::Error` on the offending token. All
//! mistakes are collected in one pass ([`Errors`]) so one compile shows them all.

use std::collections::{HashMap, HashSet};

use proc_macro2::Span;
use syn::{Attribute, Ident, Visibility};

use crate::parse::{self, AxisRef, BinOp, DriveTarget, Expr, ExprKind, Field, Item, MechanismDef, PointRef, Value, VecLit};
use crate::sym::Func;

/// The errors of one expansion, combined into one at the end.
#[derive(Default)]
pub struct Errors(Vec<syn::Error>);

impl Errors {
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

/// A body coordinate: x, y (m) or φ (rad).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Coord {
    X,
    Y,
    Phi,
}

impl Coord {
    pub fn name(self) -> &'static str {
        match self {
            Coord::X => "x",
            Coord::Y => "y",
            Coord::Phi => "phi",
        }
    }
    pub fn index(self) -> usize {
        match self {
            Coord::X => 0,
            Coord::Y => 1,
            Coord::Phi => 2,
        }
    }
    fn from_ident(id: &Ident) -> Option<Coord> {
        match id.to_string().as_str() {
            "x" => Some(Coord::X),
            "y" => Some(Coord::Y),
            "phi" => Some(Coord::Phi),
            _ => None,
        }
    }
    fn from_velocity_ident(id: &Ident) -> Option<Coord> {
        match id.to_string().as_str() {
            "vx" => Some(Coord::X),
            "vy" => Some(Coord::Y),
            "omega" => Some(Coord::Phi),
            _ => None,
        }
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
    /// A body velocity ẋ, ẏ or φ̇ (force expressions only).
    Vel(BodyRef, Coord),
    Neg(Box<MExpr>),
    Bin(MBin, Box<MExpr>, Box<MExpr>),
    Call(Func, Box<MExpr>),
    Atan2(Box<MExpr>, Box<MExpr>),
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
        Some(match self {
            MExpr::Num(v) => *v,
            MExpr::Pi => std::f64::consts::PI,
            MExpr::T | MExpr::Param(_) | MExpr::Coord(..) | MExpr::Vel(..) => return None,
            MExpr::Neg(a) => -a.constant_value()?,
            MExpr::Bin(op, a, b) => {
                let (a, b) = (a.constant_value()?, b.constant_value()?);
                match op {
                    MBin::Add => a + b,
                    MBin::Sub => a - b,
                    MBin::Mul => a * b,
                    MBin::Div => a / b,
                    MBin::Pow => a.powf(b),
                }
            }
            MExpr::Call(f, a) => {
                let a = a.constant_value()?;
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
            MExpr::Atan2(y, x) => y.constant_value()?.atan2(x.constant_value()?),
        })
    }
}

/// What an expression may refer to, by where it stands.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Scope {
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
    fn describe(self) -> &'static str {
        match self {
            Scope::Constant => "a parameter default is a constant: numbers, `PI` and functions of them",
            Scope::Params => "geometry, masses and initial values may use numbers, `PI` and parameters, not `t` or coordinates",
            Scope::Time => "a driver is a function of `t` and parameters, not of coordinates",
            Scope::State => "a constraint is a function of coordinates, `t` and parameters, not of velocities",
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
    pub mass: MExpr,
    pub inertia: MExpr,
    /// Initial guess of (x, y, φ).
    pub q0: [MExpr; 3],
    /// Initial velocities (ẋ, ẏ, φ̇).
    pub qd0: [MExpr; 3],
}

/// A named point or vector, local to its body.
pub struct Local {
    pub body: BodyRef,
    pub name: String,
    pub local: [MExpr; 2],
}

/// A point on a body, by its body-fixed coordinates.
#[derive(Clone, Debug)]
pub struct Loc {
    pub body: BodyRef,
    pub point: [MExpr; 2],
}

/// One joint, driver or user constraint, with the rows it adds to Φ (see docs/formulation.md).
#[derive(Clone, Debug)]
pub enum ConstraintKind {
    Revolute { i: Loc, j: Loc },
    Translational { i: Loc, axis_i: [MExpr; 2], j: Loc, axis_j: [MExpr; 2] },
    RevoluteRevolute { i: Loc, j: Loc, length: MExpr },
    RevoluteTranslational { i: Loc, j: Loc, axis_j: [MExpr; 2], distance: MExpr },
    Rigid { i: Loc, j: Loc, angle: MExpr },
    Fix { body: usize, coord: Coord, value: MExpr },
    Drive { body: usize, coord: Coord, f: MExpr },
    DriveAngle { i: BodyRef, j: BodyRef, f: MExpr },
    DriveDistance { i: Loc, j: Loc, f: MExpr },
    User { expr: MExpr },
}

impl ConstraintKind {
    /// The kind's name (as in the model JSON) and the bodies it connects.
    pub fn kind_and_bodies(&self) -> (&'static str, Option<BodyRef>, Option<BodyRef>) {
        match self {
            ConstraintKind::Revolute { i, j } => ("revolute", Some(i.body), Some(j.body)),
            ConstraintKind::Translational { i, j, .. } => ("translational", Some(i.body), Some(j.body)),
            ConstraintKind::RevoluteRevolute { i, j, .. } => ("revolute_revolute", Some(i.body), Some(j.body)),
            ConstraintKind::RevoluteTranslational { i, j, .. } => ("revolute_translational", Some(i.body), Some(j.body)),
            ConstraintKind::Rigid { i, j, .. } => ("rigid", Some(i.body), Some(j.body)),
            ConstraintKind::Fix { body, .. } => ("fix", Some(BodyRef::Body(*body)), None),
            ConstraintKind::Drive { body, .. } => ("drive", Some(BodyRef::Body(*body)), None),
            ConstraintKind::DriveAngle { i, j, .. } => ("drive_angle", Some(*i), Some(*j)),
            ConstraintKind::DriveDistance { i, j, .. } => ("drive_distance", Some(i.body), Some(j.body)),
            ConstraintKind::User { .. } => ("constraint", None, None),
        }
    }

    /// Names of the rows this constraint adds, in order.
    pub fn row_names(&self) -> &'static [&'static str] {
        match self {
            ConstraintKind::Revolute { .. } => &["x", "y"],
            ConstraintKind::Translational { .. } => &["normal", "angle"],
            ConstraintKind::RevoluteRevolute { .. } => &["length"],
            ConstraintKind::RevoluteTranslational { .. } => &["distance"],
            ConstraintKind::Rigid { .. } => &["x", "y", "angle"],
            ConstraintKind::Fix { coord, .. } | ConstraintKind::Drive { coord, .. } => match coord {
                Coord::X => &["x"],
                Coord::Y => &["y"],
                Coord::Phi => &["phi"],
            },
            ConstraintKind::DriveAngle { .. } => &["angle"],
            ConstraintKind::DriveDistance { .. } => &["distance"],
            ConstraintKind::User { .. } => &["user"],
        }
    }
}

/// A force element (Nikravesh ch. 4): what it adds to h(q, q̇, t) and to the potential energy.
#[derive(Clone, Debug)]
pub enum ForceKind {
    /// Point-to-point spring–damper–actuator: tension f = k (l − length) + c l̇ + force.
    PointToPoint { i: Loc, j: Loc, k: Option<MExpr>, length: MExpr, c: Option<MExpr>, force: Option<MExpr> },
    /// Rotational spring–damper–actuator on θ = φ_j − φ_i: τ = k (θ − angle) + c θ̇ + torque,
    /// resisting θ.
    Rotational { i: BodyRef, j: BodyRef, k: Option<MExpr>, angle: MExpr, c: Option<MExpr>, torque: Option<MExpr> },
    /// A force at a point, components in the global frame or, `local`, in the body's frame.
    Applied { at: Loc, force: [MExpr; 2], local: bool },
    /// A torque on a body (N·m, counter-clockwise positive).
    Torque { body: usize, torque: MExpr },
    /// Viscous friction in a revolute joint: torque c (φ̇_j − φ̇_i) resisting relative rotation.
    RevoluteViscous { i: BodyRef, j: BodyRef, c: MExpr },
    /// Viscous friction in a translational joint: force c ṡ resisting sliding, s = u_iᵀ(r_Pj − r_Pi).
    TranslationalViscous { i: Loc, axis_i: [MExpr; 2], j: Loc, c: MExpr },
    /// Coulomb friction in a revolute joint (Nikravesh 4.5.3): torque μ R N ω/√(ω² + v_s²)
    /// resisting ω = φ̇_j − φ̇_i, N = |(λ_x, λ_y)| the pin force of the joint's rows `row`, `row + 1`.
    RevoluteCoulomb { i: BodyRef, j: BodyRef, mu: MExpr, radius: MExpr, slip: MExpr, row: usize },
    /// Coulomb friction in a translational joint: force μ N ṡ/√(ṡ² + v_s²) resisting sliding,
    /// N = |λ_normal|, or with a bearing length w the load of two pads w apart,
    /// |λ_n/2 + λ_a/w| + |λ_n/2 − λ_a/w| (λ_a the reaction moment of the angle row).
    TranslationalCoulomb { i: Loc, axis_i: [MExpr; 2], j: Loc, mu: MExpr, slip: MExpr, bearing: Option<MExpr>, row: usize },
}

pub struct ForceElement {
    /// `"spring crank~rod"`, or the user's label.
    pub name: String,
    pub kind: ForceKind,
}

impl ForceElement {
    /// The effect this element adds (for `Mechanism::EFFECTS`).
    pub fn effect(&self) -> &'static str {
        match &self.kind {
            ForceKind::PointToPoint { .. } => "point-to-point spring-damper-actuator",
            ForceKind::Rotational { .. } => "rotational spring-damper-actuator",
            ForceKind::Applied { .. } => "applied force",
            ForceKind::Torque { .. } => "applied torque",
            ForceKind::RevoluteViscous { .. } | ForceKind::TranslationalViscous { .. } => "viscous joint friction",
            ForceKind::RevoluteCoulomb { .. } | ForceKind::TranslationalCoulomb { .. } => "Coulomb joint friction",
        }
    }
}

pub struct Constraint {
    /// `"revolute crank~rod"`, or the user's label.
    pub name: String,
    pub kind: ConstraintKind,
}

/// A validated mechanism.
pub struct Model {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub scalar: Scalar,
    pub params: Vec<Param>,
    pub bodies: Vec<Body>,
    pub points: Vec<Local>,
    pub vectors: Vec<Local>,
    pub constraints: Vec<Constraint>,
    /// Gravitational acceleration (m/s²), if declared.
    pub gravity: Option<[MExpr; 2]>,
    pub forces: Vec<ForceElement>,
}

impl Model {
    pub fn body_name(&self, b: BodyRef) -> String {
        match b {
            BodyRef::Ground => "ground".to_string(),
            BodyRef::Body(k) => self.bodies[k].name.to_string(),
        }
    }
    pub fn n_coordinates(&self) -> usize {
        3 * self.bodies.len()
    }
    /// Constraint row names, `"revolute crank~rod: x"`.
    pub fn row_names(&self) -> Vec<String> {
        self.constraints
            .iter()
            .flat_map(|c| c.kind.row_names().iter().map(move |r| format!("{}: {}", c.name, r)))
            .collect()
    }
    /// Coordinate names, `"crank.phi"`.
    pub fn coordinate_names(&self) -> Vec<String> {
        self.bodies
            .iter()
            .flat_map(|b| ["x", "y", "phi"].into_iter().map(move |c| format!("{}.{}", b.name, c)))
            .collect()
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

struct Resolver<'a> {
    errors: &'a mut Errors,
    params: HashMap<String, usize>,
    bodies: HashMap<String, usize>,
    points: HashMap<(BodyRef, String), [MExpr; 2]>,
    vectors: HashMap<(BodyRef, String), [MExpr; 2]>,
}

const BODY_FIELDS: &[&str] = &["mass", "inertia", "at", "velocity"];
const FUNCTIONS: &[&str] = &["sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "ln", "pow"];

impl Resolver<'_> {
    fn body(&mut self, id: &Ident) -> Option<BodyRef> {
        if id == "ground" {
            return Some(BodyRef::Ground);
        }
        match self.bodies.get(&id.to_string()) {
            Some(&k) => Some(BodyRef::Body(k)),
            None => {
                let names: Vec<&str> = self.bodies.keys().map(|s| s.as_str()).collect();
                let hint = parse::closest(&id.to_string(), &names, &["ground"]);
                self.errors.push(id.span(), format!("unknown body `{id}`{hint}: declare it with `body {id} {{ mass: ..., inertia: ... }}`"));
                None
            }
        }
    }

    fn expr(&mut self, e: &Expr, scope: Scope) -> Option<MExpr> {
        Some(match &e.kind {
            ExprKind::Num(v) => MExpr::Num(*v),
            ExprKind::Ident(id) => {
                let s = id.to_string();
                if s == "PI" {
                    MExpr::Pi
                } else if s == "t" {
                    if matches!(scope, Scope::Constant | Scope::Params) {
                        self.errors.push(id.span(), format!("time `t` is not allowed here: {}", scope.describe()));
                        return None;
                    }
                    MExpr::T
                } else if let Some(&k) = self.params.get(&s) {
                    if scope == Scope::Constant {
                        self.errors.push(id.span(), format!("parameter `{s}` is not allowed here: {}", scope.describe()));
                        return None;
                    }
                    MExpr::Param(k)
                } else {
                    let names: Vec<&str> = self.params.keys().map(|s| s.as_str()).collect();
                    let hint = parse::closest(&s, &names, &["t", "PI"]);
                    self.errors.push(
                        id.span(),
                        format!("unknown identifier `{s}`{hint}: an expression may use numbers, parameters declared in `params {{ }}`, `t`, `PI` and coordinates like `crank.phi`"),
                    );
                    return None;
                }
            }
            ExprKind::Coord(b, c) => {
                let position = Coord::from_ident(c);
                let velocity = Coord::from_velocity_ident(c);
                if position.is_none() && velocity.is_none() {
                    self.errors.push(c.span(), format!("unknown coordinate `{c}`: a body has `x`, `y`, `phi` and, in forces, velocities `vx`, `vy`, `omega`"));
                    return None;
                }
                let allowed = match (position, scope) {
                    (Some(_), Scope::State | Scope::Force) => true,
                    (None, Scope::Force) => true,
                    _ => false,
                };
                if !allowed {
                    let what = if position.is_some() { "coordinate" } else { "velocity" };
                    self.errors.at_expr(e, format!("{what} `{b}.{c}` is not allowed here: {}", scope.describe()));
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
                    n if Func::from_name(n).is_some() => 1,
                    _ => {
                        let hint = parse::closest(&name, FUNCTIONS, &[]);
                        self.errors.push(
                            f.span(),
                            format!("unknown function `{name}`{hint}: available are sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, ln, pow"),
                        );
                        return None;
                    }
                };
                if args.len() != arity {
                    self.errors.at_expr(e, format!("`{name}` takes {arity} argument{}, found {}", if arity == 1 { "" } else { "s" }, args.len()));
                    return None;
                }
                let resolved: Vec<Option<MExpr>> = args.iter().map(|a| self.expr(a, scope)).collect();
                let mut resolved = resolved.into_iter().collect::<Option<Vec<_>>>()?.into_iter();
                let a = Box::new(resolved.next()?);
                match name.as_str() {
                    "atan2" => MExpr::Atan2(a, Box::new(resolved.next()?)),
                    "pow" => MExpr::Bin(MBin::Pow, a, Box::new(resolved.next()?)),
                    n => MExpr::Call(Func::from_name(n)?, a),
                }
            }
        })
    }

    /// A bracketed list of exactly `N` expressions.
    fn list<const N: usize>(&mut self, v: &VecLit, scope: Scope, what: &str) -> Option<[MExpr; N]> {
        if v.items.len() != N {
            self.errors.push(v.span, format!("{what} has {N} entries, found {}", v.items.len()));
            return None;
        }
        let items: Vec<Option<MExpr>> = v.items.iter().map(|e| self.expr(e, scope)).collect();
        let items: Vec<MExpr> = items.into_iter().collect::<Option<_>>()?;
        items.try_into().ok()
    }

    fn point(&mut self, body: BodyRef, p: &PointRef) -> Option<[MExpr; 2]> {
        match p {
            PointRef::Inline(v) => self.list::<2>(v, Scope::Params, "a point `[ξ, η]` in body coordinates"),
            PointRef::Named(name) => match self.points.get(&(body, name.to_string())) {
                Some(p) => Some(p.clone()),
                None => {
                    self.errors.push(name.span(), format!("unknown point `{name}` on this body: declare it with `point body.{name} = [ξ, η];`"));
                    None
                }
            },
        }
    }

    fn loc(&mut self, body_id: &Ident, p: &PointRef) -> Option<Loc> {
        let body = self.body(body_id)?;
        let point = self.point(body, p)?;
        Some(Loc { body, point })
    }

    fn axis(&mut self, body: BodyRef, a: &AxisRef) -> Option<[MExpr; 2]> {
        match a {
            AxisRef::Inline(v) => {
                let axis = self.list::<2>(v, Scope::Params, "an axis `[x, y]` in body coordinates")?;
                if let (Some(x), Some(y)) = (axis[0].constant_value(), axis[1].constant_value()) {
                    if x == 0.0 && y == 0.0 {
                        self.errors.push(v.span, "an axis must not be the zero vector");
                        return None;
                    }
                }
                Some(axis)
            }
            AxisRef::Named(b, name) => {
                if self.body(b)? != body {
                    self.errors.push(b.span(), "the axis must be a vector of the same body as the point");
                    return None;
                }
                match self.vectors.get(&(body, name.to_string())) {
                    Some(v) => Some(v.clone()),
                    None => {
                        self.errors.push(name.span(), format!("unknown vector `{name}`: declare it with `vector {b}.{name} = [x, y];`"));
                        None
                    }
                }
            }
        }
    }
}

/// The name of a joint, driver, constraint or force element — its label, or its default name —
/// if no other statement has it yet; otherwise an error on the label or the statement's keyword.
fn claim_name(names: &mut HashMap<String, Span>, errors: &mut Errors, label: Option<&Ident>, default_name: String, span: Span) -> Option<String> {
    let (name, span) = match label {
        Some(l) => (l.to_string(), l.span()),
        None => (default_name, span),
    };
    if names.insert(name.clone(), span).is_none() {
        return Some(name);
    }
    let msg = if label.is_some() {
        format!("duplicate name `{name}`")
    } else {
        format!("a second `{name}`: give one of them a name, e.g. `{} name: ...`", name.split(' ').next().unwrap_or(""))
    };
    errors.push(span, msg);
    None
}

/// Checks a number that must be positive when it is a constant (a parameter's value is checked
/// at run time by the solver that needs it).
fn check_positive(errors: &mut Errors, e: &MExpr, written: &Expr, what: &str) {
    if let Some(v) = e.constant_value() {
        if !(v > 0.0) {
            errors.at_expr(written, format!("{what} must be positive, found {v}"));
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
        errors.into_result()?;
        model.ok_or_else(|| syn::Error::new(self.name.span(), "invalid mechanism"))
    }

    fn build(&self, errors: &mut Errors) -> Option<Model> {
        let mut scalar = None::<(Scalar, Span)>;
        let mut r = Resolver { errors, params: HashMap::new(), bodies: HashMap::new(), points: HashMap::new(), vectors: HashMap::new() };
        let mut params = Vec::new();
        let mut bodies = Vec::new();
        let mut ok = true;

        // Pass 1: declarations (params, bodies) so statements can refer to them in any order.
        for item in &self.items {
            match item {
                Item::Scalar(s) => {
                    let sc = match s.to_string().as_str() {
                        "f64" => Scalar::F64,
                        "f32" => Scalar::F32,
                        other => {
                            r.errors.push(s.span(), format!("unsupported scalar type `{other}`: use `f64` or `f32`"));
                            continue;
                        }
                    };
                    if scalar.is_some() {
                        r.errors.push(s.span(), "the scalar type is declared twice");
                    }
                    scalar = Some((sc, s.span()));
                }
                Item::Params(ps) => {
                    for (name, value) in ps {
                        if r.params.contains_key(&name.to_string()) {
                            r.errors.push(name.span(), format!("duplicate parameter `{name}`"));
                            ok = false;
                            continue;
                        }
                        if ["t", "PI", "ground"].contains(&name.to_string().as_str()) {
                            r.errors.push(name.span(), format!("`{name}` is reserved and cannot name a parameter"));
                            ok = false;
                            continue;
                        }
                        let Some(default) = r.expr(value, Scope::Constant) else {
                            ok = false;
                            continue;
                        };
                        let default = default.constant_value().unwrap_or(f64::NAN);
                        if !default.is_finite() {
                            r.errors.at_expr(value, format!("the default of `{name}` evaluates to {default}"));
                            ok = false;
                            continue;
                        }
                        r.params.insert(name.to_string(), params.len());
                        params.push(Param { name: name.clone(), default });
                    }
                }
                Item::Body(b) => {
                    if b.name == "ground" {
                        r.errors.push(b.name.span(), "`ground` is the fixed frame, always present: it cannot be declared as a body");
                        ok = false;
                        continue;
                    }
                    if r.bodies.contains_key(&b.name.to_string()) {
                        r.errors.push(b.name.span(), format!("duplicate body `{}`", b.name));
                        ok = false;
                        continue;
                    }
                    r.bodies.insert(b.name.to_string(), bodies.len());
                    bodies.push(b);
                }
                _ => {}
            }
        }

        let mut model_bodies = Vec::new();
        for b in &bodies {
            let mut fields: HashMap<String, &Value> = HashMap::new();
            for f in &b.fields {
                let key = f.name.to_string();
                if !BODY_FIELDS.contains(&key.as_str()) {
                    let hint = parse::closest(&key, BODY_FIELDS, &[]);
                    r.errors.push(f.name.span(), format!("unknown body field `{key}`{hint}: a body has `mass`, `inertia`, `at: [x, y, phi]` and `velocity: [vx, vy, omega]`"));
                    ok = false;
                } else if fields.insert(key.clone(), &f.value).is_some() {
                    r.errors.push(f.name.span(), format!("duplicate field `{key}`"));
                    ok = false;
                }
            }
            let scalar_field = |r: &mut Resolver, name: &str, unit: &str| -> Option<MExpr> {
                match fields.get(name) {
                    None => {
                        r.errors.push(b.name.span(), format!("body `{}` has no `{name}`: give it in {unit}, e.g. `{name}: 1.0`", b.name));
                        None
                    }
                    Some(Value::List(v)) => {
                        r.errors.push(v.span, format!("`{name}` is a number ({unit}), not a list"));
                        None
                    }
                    Some(Value::Expr(e)) => {
                        let m = r.expr(e, Scope::Params)?;
                        check_positive(r.errors, &m, e, &format!("the {name} of body `{}`", b.name));
                        Some(m)
                    }
                }
            };
            let mass = scalar_field(&mut r, "mass", "kg");
            let inertia = scalar_field(&mut r, "inertia", "kg·m² about the centre of mass");
            let vec3 = |r: &mut Resolver, name: &str, what: &str| -> Option<[MExpr; 3]> {
                match fields.get(name) {
                    None => Some([MExpr::Num(0.0), MExpr::Num(0.0), MExpr::Num(0.0)]),
                    Some(Value::Expr(e)) => {
                        r.errors.push(e.span, format!("`{name}` is a list `[{what}]`"));
                        None
                    }
                    Some(Value::List(v)) => r.list::<3>(v, Scope::Params, &format!("`{name}: [{what}]`")),
                }
            };
            let q0 = vec3(&mut r, "at", "x, y, phi");
            let qd0 = vec3(&mut r, "velocity", "vx, vy, omega");
            match (mass, inertia, q0, qd0) {
                (Some(mass), Some(inertia), Some(q0), Some(qd0)) => {
                    model_bodies.push(Body { name: b.name.clone(), mass, inertia, q0, qd0 });
                }
                _ => ok = false,
            }
        }

        // Pass 2: points and vectors, then joints, drivers and constraints in declaration order.
        let mut points = Vec::new();
        let mut vectors = Vec::new();
        for item in &self.items {
            let (nv, is_point) = match item {
                Item::Point(nv) => (nv, true),
                Item::Vector(nv) => (nv, false),
                _ => continue,
            };
            let Some(body) = r.body(&nv.body) else {
                ok = false;
                continue;
            };
            let what = if is_point { "a point `[ξ, η]` in body coordinates (m)" } else { "a vector `[x, y]` in body coordinates" };
            let Some(local) = r.list::<2>(&nv.value, Scope::Params, what) else {
                ok = false;
                continue;
            };
            let key = (body, nv.name.to_string());
            let table = if is_point { &mut r.points } else { &mut r.vectors };
            if table.insert(key, local.clone()).is_some() {
                r.errors.push(nv.name.span(), format!("duplicate {} `{}.{}`", if is_point { "point" } else { "vector" }, nv.body, nv.name));
                ok = false;
                continue;
            }
            let l = Local { body, name: nv.name.to_string(), local };
            if is_point {
                points.push(l);
            } else {
                vectors.push(l);
            }
        }

        let body_name = |b: BodyRef| match b {
            BodyRef::Ground => "ground".to_string(),
            BodyRef::Body(k) => bodies[k].name.to_string(),
        };
        let mut constraints = Vec::new();
        let mut forces = Vec::new();
        let mut names: HashMap<String, Span> = HashMap::new();
        let mut driven: HashMap<(usize, Coord), Span> = HashMap::new();
        let mut driven_angles: HashSet<(BodyRef, BodyRef)> = HashSet::new();
        for (index, item) in self.items.iter().enumerate() {
            let first_row: usize = constraints.iter().map(|c: &Constraint| c.kind.row_names().len()).sum();
            let built: Option<(Option<&Ident>, String, Span, ConstraintKind, Vec<ForceKind>)> = match item {
                Item::Joint(j) => self.joint(&mut r, j, &body_name),
                Item::Fix(f) => {
                    let body = r.body(&f.body);
                    let coord = Coord::from_ident(&f.coordinate);
                    if coord.is_none() {
                        r.errors.push(f.coordinate.span(), format!("unknown coordinate `{}`: a body has `x`, `y` and `phi`", f.coordinate));
                    }
                    match (body, coord) {
                        (Some(BodyRef::Ground), _) => {
                            r.errors.push(f.body.span(), "the ground is fixed already");
                            None
                        }
                        (Some(BodyRef::Body(k)), Some(coord)) => {
                            if let Some(_prev) = driven.insert((k, coord), f.coordinate.span()) {
                                r.errors.push(f.coordinate.span(), format!("`{}.{}` is already fixed or driven", f.body, coord.name()));
                                None
                            } else {
                                let value = match &f.value {
                                    Some(e) => r.expr(e, Scope::Params),
                                    None => model_bodies.iter().find(|b| b.name == f.body).map(|b| b.q0[coord.index()].clone()),
                                };
                                value.map(|value| {
                                    let name = format!("fix {}.{}", f.body, coord.name());
                                    (f.label.as_ref(), name, f.keyword.span(), ConstraintKind::Fix { body: k, coord, value }, Vec::new())
                                })
                            }
                        }
                        _ => None,
                    }
                }
                Item::Drive(d) => {
                    let f = r.expr(&d.f, Scope::Time);
                    match &d.target {
                        DriveTarget::Coordinate { body, coordinate } => {
                            let b = r.body(body);
                            let coord = Coord::from_ident(coordinate);
                            if coord.is_none() {
                                r.errors.push(coordinate.span(), format!("unknown coordinate `{coordinate}`: a body has `x`, `y` and `phi`"));
                            }
                            match (b, coord, f) {
                                (Some(BodyRef::Ground), _, _) => {
                                    r.errors.push(body.span(), "the ground cannot be driven");
                                    None
                                }
                                (Some(BodyRef::Body(k)), Some(coord), f) => {
                                    if driven.insert((k, coord), coordinate.span()).is_some() {
                                        r.errors.push(coordinate.span(), format!("`{body}.{}` is already fixed or driven", coord.name()));
                                        None
                                    } else {
                                        f.map(|f| (d.label.as_ref(), format!("drive {body}.{}", coord.name()), d.keyword.span(), ConstraintKind::Drive { body: k, coord, f }, Vec::new()))
                                    }
                                }
                                _ => None,
                            }
                        }
                        DriveTarget::Angle { i, j, .. } => {
                            let (bi, bj) = (r.body(i), r.body(j));
                            match (bi, bj, f) {
                                (Some(bi), Some(bj), _) if bi == bj => {
                                    r.errors.push(j.span(), format!("a relative angle needs two different bodies, found `{j}` twice"));
                                    None
                                }
                                (Some(bi), Some(bj), f) => {
                                    let key = if format!("{bi:?}") < format!("{bj:?}") { (bi, bj) } else { (bj, bi) };
                                    if !driven_angles.insert(key) {
                                        r.errors.push(i.span(), format!("the angle between `{i}` and `{j}` is already driven"));
                                        None
                                    } else {
                                        f.map(|f| (d.label.as_ref(), format!("drive angle {i}~{j}"), d.keyword.span(), ConstraintKind::DriveAngle { i: bi, j: bj, f }, Vec::new()))
                                    }
                                }
                                _ => None,
                            }
                        }
                        DriveTarget::Distance { i, j, .. } => {
                            let li = r.loc(&i.0, &i.1);
                            let lj = r.loc(&j.0, &j.1);
                            match (li, lj, f) {
                                (Some(li), Some(lj), _) if li.body == lj.body => {
                                    r.errors.push(j.0.span(), "a distance driver needs points on two different bodies");
                                    None
                                }
                                (Some(li), Some(lj), Some(f)) => {
                                    let name = format!("drive distance {}~{}", i.0, j.0);
                                    Some((d.label.as_ref(), name, d.keyword.span(), ConstraintKind::DriveDistance { i: li, j: lj, f }, Vec::new()))
                                }
                                _ => None,
                            }
                        }
                    }
                }
                Item::Constraint(c) => {
                    let lhs = r.expr(&c.lhs, Scope::State);
                    let rhs = r.expr(&c.rhs, Scope::State);
                    match (lhs, rhs) {
                        (Some(l), Some(rh)) => {
                            let expr = match rh.constant_value() {
                                Some(v) if v == 0.0 => l,
                                _ => MExpr::Bin(MBin::Sub, Box::new(l), Box::new(rh)),
                            };
                            Some((c.label.as_ref(), format!("constraint {index}"), c.keyword.span(), ConstraintKind::User { expr }, Vec::new()))
                        }
                        _ => None,
                    }
                }
                _ => continue,
            };
            let Some((label, default_name, span, kind, friction)) = built else {
                ok = false;
                continue;
            };
            let Some(name) = claim_name(&mut names, r.errors, label, default_name, span) else {
                ok = false;
                continue;
            };
            for mut kind in friction {
                let what = match &mut kind {
                    ForceKind::RevoluteCoulomb { row, .. } | ForceKind::TranslationalCoulomb { row, .. } => {
                        *row = first_row;
                        "Coulomb friction"
                    }
                    _ => "viscous friction",
                };
                forces.push(ForceElement { name: format!("{name} {what}"), kind });
            }
            constraints.push(Constraint { name, kind });
        }

        // Force elements (Nikravesh ch. 4).
        let mut gravity = None;
        for item in &self.items {
            let built: Option<(Option<&Ident>, String, Span, ForceKind)> = match item {
                Item::Gravity(kw, v) => {
                    if gravity.is_some() {
                        r.errors.push(kw.span(), "gravity is declared twice");
                        ok = false;
                    }
                    gravity = r.list::<2>(v, Scope::Params, "gravity `[gx, gy]` (m/s²)");
                    if gravity.is_none() {
                        ok = false;
                    }
                    continue;
                }
                Item::PointForce(f) => self.point_force(&mut r, f, &body_name),
                Item::RotationalForce(f) => self.rotational_force(&mut r, f),
                Item::Force(f) => {
                    let at = r.loc(&f.body, &f.point);
                    let value = r.list::<2>(&f.value, Scope::Force, "a force `[fx, fy]` (N)");
                    match (at, value) {
                        (Some(at), _) if at.body == BodyRef::Ground => {
                            r.errors.push(f.body.span(), "a force on the ground does nothing: apply it to a moving body");
                            None
                        }
                        (Some(at), Some(force)) => {
                            let local = f.kind == "local_force";
                            Some((f.label.as_ref(), format!("{} on {}", f.kind, f.body), f.kind.span(), ForceKind::Applied { at, force, local }))
                        }
                        _ => None,
                    }
                }
                Item::Torque(tq) => {
                    let body = r.body(&tq.body);
                    let torque = r.expr(&tq.value, Scope::Force);
                    match (body, torque) {
                        (Some(BodyRef::Ground), _) => {
                            r.errors.push(tq.body.span(), "a torque on the ground does nothing: apply it to a moving body");
                            None
                        }
                        (Some(BodyRef::Body(k)), Some(torque)) => {
                            Some((tq.label.as_ref(), format!("torque on {}", tq.body), tq.keyword.span(), ForceKind::Torque { body: k, torque }))
                        }
                        _ => None,
                    }
                }
                _ => continue,
            };
            let Some((label, default_name, span, kind)) = built else {
                ok = false;
                continue;
            };
            let Some(name) = claim_name(&mut names, r.errors, label, default_name, span) else {
                ok = false;
                continue;
            };
            forces.push(ForceElement { name, kind });
        }

        if bodies.is_empty() {
            r.errors.push(self.name.span(), "a mechanism needs at least one body: `body name { mass: ..., inertia: ... }`");
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
            params,
            bodies: model_bodies,
            points,
            vectors,
            constraints,
            gravity,
            forces,
        })
    }

    #[allow(clippy::type_complexity)]
    fn joint<'a>(
        &self,
        r: &mut Resolver,
        j: &'a parse::JointDef,
        body_name: &dyn Fn(BodyRef) -> String,
    ) -> Option<(Option<&'a Ident>, String, Span, ConstraintKind, Vec<ForceKind>)> {
        let kind = j.kind.to_string();
        let li = r.loc(&j.i.body, &j.i.point);
        let lj = r.loc(&j.j.body, &j.j.point);
        let (li, lj) = (li?, lj?);
        if li.body == lj.body {
            r.errors.push(j.j.body.span(), format!("a joint of body `{}` to itself: a {kind} joint connects two different bodies", j.j.body));
            return None;
        }
        // Which sides take an axis, and which options the kind knows.
        let (axis_i_needed, axis_j_needed, known_options): (bool, bool, &[&str]) = match kind.as_str() {
            "revolute" => (false, false, &["viscous", "coulomb", "radius", "slip_velocity"]),
            "translational" => (true, true, &["viscous", "coulomb", "slip_velocity", "bearing"]),
            "revolute_revolute" => (false, false, &["length"]),
            "revolute_translational" => (false, true, &["distance"]),
            "rigid" => (false, false, &["angle"]),
            _ => unreachable!("parse only yields known joint kinds"),
        };
        let axis = |r: &mut Resolver, side: &parse::Attach, body: BodyRef, needed: bool, which: &str| -> Option<Option<[MExpr; 2]>> {
            match (&side.along, needed) {
                (Some(a), true) => r.axis(body, &a.axis).map(Some),
                (None, true) => {
                    r.errors.push(side.body.span(), format!("a {kind} joint needs a sliding axis on its {which} body: `{}.P along [x, y]`", side.body));
                    None
                }
                (Some(a), false) => {
                    r.errors.push(a.keyword.span(), format!("a {kind} joint takes no axis on its {which} body"));
                    None
                }
                (None, false) => Some(None),
            }
        };
        let axis_i = axis(r, &j.i, li.body, axis_i_needed, "first");
        let axis_j = axis(r, &j.j, lj.body, axis_j_needed, "second");
        let mut options: HashMap<String, MExpr> = HashMap::new();
        let mut bad = false;
        for f in &j.options {
            let key = f.name.to_string();
            if !known_options.contains(&key.as_str()) {
                let list = if known_options.is_empty() { "none".to_string() } else { known_options.join(", ") };
                r.errors.push(f.name.span(), format!("unknown option `{key}` of a {kind} joint (it takes: {list})"));
                bad = true;
                continue;
            }
            match &f.value {
                Value::List(v) => {
                    r.errors.push(v.span, format!("`{key}` is a number, not a list"));
                    bad = true;
                }
                Value::Expr(e) => match r.expr(e, Scope::Params) {
                    Some(m) => {
                        match key.as_str() {
                            "length" => check_positive(r.errors, &m, e, "the length of a revolute-revolute link"),
                            "radius" => check_positive(r.errors, &m, e, "a pin radius"),
                            "slip_velocity" => check_positive(r.errors, &m, e, "the slip velocity of Coulomb friction"),
                            "bearing" => check_positive(r.errors, &m, e, "a bearing length"),
                            _ => {}
                        }
                        options.insert(key, m);
                    }
                    None => bad = true,
                },
            }
        }
        let (axis_i, axis_j) = (axis_i?, axis_j?);
        if bad {
            return None;
        }
        let zero = || MExpr::Num(0.0);
        let mut friction: Vec<ForceKind> = options
            .remove("viscous")
            .map(|c| match &axis_i {
                Some(axis_i) => ForceKind::TranslationalViscous { i: li.clone(), axis_i: axis_i.clone(), j: lj.clone(), c },
                None => ForceKind::RevoluteViscous { i: li.body, j: lj.body, c },
            })
            .into_iter()
            .collect();
        // Coulomb friction, regularized below the slip velocity (default 1e-3 m/s or rad/s).
        let slip = options.remove("slip_velocity");
        let radius = options.remove("radius");
        let bearing = options.remove("bearing");
        match options.remove("coulomb") {
            Some(mu) => {
                let slip = slip.unwrap_or(MExpr::Num(1e-3));
                match &axis_i {
                    Some(axis_i) => friction.push(ForceKind::TranslationalCoulomb {
                        i: li.clone(),
                        axis_i: axis_i.clone(),
                        j: lj.clone(),
                        mu,
                        slip,
                        bearing,
                        row: 0,
                    }),
                    None => match radius {
                        Some(radius) => friction.push(ForceKind::RevoluteCoulomb { i: li.body, j: lj.body, mu, radius, slip, row: 0 }),
                        None => {
                            r.errors.push(j.kind.span(), "Coulomb friction in a revolute joint needs the pin radius: `{ coulomb: 0.1, radius: 0.01 }` (m)");
                            return None;
                        }
                    },
                }
            }
            None => {
                if slip.is_some() || radius.is_some() || bearing.is_some() {
                    r.errors.push(j.kind.span(), format!("`radius`, `slip_velocity` and `bearing` describe Coulomb friction: give the {kind} joint `coulomb: μ` too"));
                    return None;
                }
            }
        }
        let ck = match kind.as_str() {
            "revolute" => ConstraintKind::Revolute { i: li.clone(), j: lj.clone() },
            "translational" => ConstraintKind::Translational { i: li.clone(), axis_i: axis_i?, j: lj.clone(), axis_j: axis_j? },
            "revolute_revolute" => match options.remove("length") {
                Some(length) => ConstraintKind::RevoluteRevolute { i: li.clone(), j: lj.clone(), length },
                None => {
                    r.errors.push(j.kind.span(), "a revolute_revolute link needs its length: `{ length: 0.3 }` (m)");
                    return None;
                }
            },
            "revolute_translational" => ConstraintKind::RevoluteTranslational {
                i: li.clone(),
                j: lj.clone(),
                axis_j: axis_j?,
                distance: options.remove("distance").unwrap_or_else(zero),
            },
            "rigid" => ConstraintKind::Rigid { i: li.clone(), j: lj.clone(), angle: options.remove("angle").unwrap_or_else(zero) },
            _ => unreachable!(),
        };
        let name = format!("{kind} {}~{}", body_name(li.body), body_name(lj.body));
        Some((j.label.as_ref(), name, j.kind.span(), ck, friction))
    }

    /// The options of a force element: each known name at most once, each a number-valued
    /// expression of the given scope.
    fn force_options(&self, r: &mut Resolver, kind: &Ident, fields: &[Field], known: &[(&str, Scope)]) -> Option<HashMap<String, MExpr>> {
        let mut out = HashMap::new();
        let mut bad = false;
        for f in fields {
            let key = f.name.to_string();
            let Some(&(_, scope)) = known.iter().find(|(n, _)| *n == key) else {
                let list: Vec<&str> = known.iter().map(|(n, _)| *n).collect();
                r.errors.push(f.name.span(), format!("unknown option `{key}` of a {kind} (it takes: {})", list.join(", ")));
                bad = true;
                continue;
            };
            match &f.value {
                Value::List(v) => {
                    r.errors.push(v.span, format!("`{key}` is a number, not a list"));
                    bad = true;
                }
                Value::Expr(e) => match r.expr(e, scope) {
                    Some(m) => {
                        if out.insert(key.clone(), m).is_some() {
                            r.errors.push(f.name.span(), format!("duplicate option `{key}`"));
                            bad = true;
                        }
                    }
                    None => bad = true,
                },
            }
        }
        (!bad).then_some(out)
    }

    #[allow(clippy::type_complexity)]
    fn point_force<'a>(
        &self,
        r: &mut Resolver,
        f: &'a parse::JointDef,
        body_name: &dyn Fn(BodyRef) -> String,
    ) -> Option<(Option<&'a Ident>, String, Span, ForceKind)> {
        let kind = f.kind.to_string();
        let li = r.loc(&f.i.body, &f.i.point);
        let lj = r.loc(&f.j.body, &f.j.point);
        for side in [&f.i, &f.j] {
            if let Some(a) = &side.along {
                r.errors.push(a.keyword.span(), format!("a {kind} acts along the line between its points: it takes no axis"));
                return None;
            }
        }
        let known = [("k", Scope::Params), ("length", Scope::Params), ("c", Scope::Params), ("force", Scope::Force)];
        let mut o = self.force_options(r, &f.kind, &f.options, &known)?;
        let (li, lj) = (li?, lj?);
        if li.body == lj.body {
            r.errors.push(f.j.body.span(), format!("a {kind} of body `{}` to itself does nothing: it connects two different bodies", f.j.body));
            return None;
        }
        let required = match kind.as_str() {
            "spring" => ("k", "a spring needs its stiffness: `{ k: 2.0e3, length: 0.3 }` (N/m, m)"),
            "damper" => ("c", "a damper needs its damping coefficient: `{ c: 50.0 }` (N·s/m)"),
            _ => ("force", "an actuator needs its force: `{ force: 100.0 * sin(t) }` (N, tension positive)"),
        };
        if !o.contains_key(required.0) {
            r.errors.push(f.kind.span(), required.1);
            return None;
        }
        if o.contains_key("k") && !o.contains_key("length") {
            r.errors.push(f.kind.span(), "a spring needs its free length: `length: 0.3` (m)");
            return None;
        }
        let name = format!("{kind} {}~{}", body_name(li.body), body_name(lj.body));
        let kind = ForceKind::PointToPoint {
            i: li,
            j: lj,
            k: o.remove("k"),
            length: o.remove("length").unwrap_or(MExpr::Num(0.0)),
            c: o.remove("c"),
            force: o.remove("force"),
        };
        Some((f.label.as_ref(), name, f.kind.span(), kind))
    }

    #[allow(clippy::type_complexity)]
    fn rotational_force<'a>(&self, r: &mut Resolver, f: &'a parse::RotationalDef) -> Option<(Option<&'a Ident>, String, Span, ForceKind)> {
        let kind = f.kind.to_string();
        let bi = r.body(&f.i);
        let bj = r.body(&f.j);
        let known = [("k", Scope::Params), ("angle", Scope::Params), ("c", Scope::Params), ("torque", Scope::Force)];
        let mut o = self.force_options(r, &f.kind, &f.options, &known)?;
        let (bi, bj) = (bi?, bj?);
        if bi == bj {
            r.errors.push(f.j.span(), format!("a {kind} of body `{}` to itself does nothing: it connects two different bodies", f.j));
            return None;
        }
        let required = match kind.as_str() {
            "rotational_spring" => ("k", "a rotational spring needs its stiffness: `{ k: 50.0 }` (N·m/rad)"),
            "rotational_damper" => ("c", "a rotational damper needs its damping coefficient: `{ c: 0.5 }` (N·m·s/rad)"),
            _ => ("torque", "a torque actuator needs its torque: `{ torque: 2.0 * sin(t) }` (N·m)"),
        };
        if !o.contains_key(required.0) {
            r.errors.push(f.kind.span(), required.1);
            return None;
        }
        let name = format!("{kind} {}~{}", f.i, f.j);
        let kind = ForceKind::Rotational {
            i: bi,
            j: bj,
            k: o.remove("k"),
            angle: o.remove("angle").unwrap_or(MExpr::Num(0.0)),
            c: o.remove("c"),
            torque: o.remove("torque"),
        };
        Some((f.label.as_ref(), name, f.kind.span(), kind))
    }
}

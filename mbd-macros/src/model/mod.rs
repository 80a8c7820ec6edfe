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

mod bodies;
mod declare;
mod expr;
mod resolve;
mod statements;

use self::bodies::*;
use self::declare::*;
pub use self::declare::{check_positive, constant_name, point_accessor, JOINT_COORDINATES};
pub use self::expr::*;
use self::resolve::*;
pub use self::statements::SpatialJoints;
use self::statements::*;

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
    /// In joint coordinates (`joint_coordinates;`), the spanning tree of the joints; `None` in
    /// body coordinates.
    pub tree: Option<crate::tree::Tree>,
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
    /// Coordinate names, `"crank.phi"`; in joint coordinates a tree joint's `"pin.angle"` or
    /// `"slide.stroke"`, a floating body's `"float.x"`.
    pub fn coordinate_names(&self) -> Vec<String> {
        if let Some(tree) = &self.tree {
            return tree.coordinate_names(self).into_iter().map(|(name, _)| name).collect();
        }
        let cs = self.space.coordinates();
        self.bodies.iter().flat_map(|b| cs.iter().map(move |c| format!("{}.{}", b.name, c.name()))).collect()
    }
    /// Velocity names, `"crank.omega"`, `"top.wz"`.
    pub fn velocity_names(&self) -> Vec<String> {
        if let Some(tree) = &self.tree {
            return tree.velocity_names(self).into_iter().map(|(name, _, _)| name).collect();
        }
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
        let joint_coordinates = self.joint_coordinates(errors);
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
        let tree = joint_coordinates.then(|| spanning_tree(model_bodies.len(), &constraints, space));
        if let Some(tree) = &tree {
            // Coulomb friction reads its joint's normal load from λ: a tree joint has none. The
            // error is on the joint's statement (its label, or its keyword).
            let kw = self.items.iter().find_map(|i| if let Item::JointCoordinates(kw) = i { Some(kw.span()) } else { None });
            for element in &forces {
                let Some(joint) = element.kind.reads_multipliers_of().filter(|j| tree.joints.contains(j)) else { continue };
                r.errors.push(
                    names.get(&constraints[joint].name).copied().or(kw).unwrap_or_else(|| self.name.span()),
                    format!(
                        "Coulomb friction on a joint of the tree is not implemented yet: `{}` needs the normal \
                         load of `{}`, which joint coordinates carry in the tree, not as a multiplier; expected \
                         body coordinates (no `joint_coordinates;`) or no `coulomb:` on that joint, found both",
                        element.name, constraints[joint].name
                    ),
                );
                ok = false;
            }
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
            tree,
            forces,
            warnings: Vec::new(),
        })
    }

    /// Whether `joint_coordinates;` is stated (once).
    fn joint_coordinates(&self, errors: &mut Errors) -> bool {
        let mut stated = false;
        for item in &self.items {
            if let Item::JointCoordinates(kw) = item {
                if stated {
                    errors.push(kw.span(), "`joint_coordinates;` is stated twice: expected it once, found it again");
                }
                stated = true;
            }
        }
        stated
    }
}

/// The spanning tree of the joints that have a relative-coordinate form (`crate::tree`).
fn spanning_tree(bodies: usize, constraints: &[Constraint], space: Space) -> crate::tree::Tree {
    let candidates: Vec<crate::tree::Candidate> =
        constraints.iter().enumerate().filter_map(|(index, c)| c.kind.relative().map(|r| (index, r.bodies(), r.counts()))).collect();
    crate::tree::plan(bodies, &candidates, space)
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

//! Joints, drivers and user constraints: one file per kind.
//!
//! Each kind is a type implementing [`Joint`]: its validated data (resolved in its own file from
//! the syntax tree), its rows of Φ with their names (one function, so the count of rows and of
//! names cannot disagree) written against body frames ([`Builder`]), and its model JSON. The
//! kinds with the shape `keyword Pi [along ui] ~ Pj [along uj] { options };` are registered in
//! [`JOINTS`] with the axes and options they take; `fix`, `drive` and `constraint` have their
//! own statements.
//!
//! Adding a joint kind: a file here (its struct, `build`, `rows`, `json`), one entry in
//! [`JOINTS`], its row definitions in `docs/formulation.md`, and its twin in the oracle
//! (`tests/oracle/mbd_oracle/model.py`).

use std::collections::HashMap;
use std::fmt::Debug;

use proc_macro2::Span;
use serde_json::Value;
use syn::Ident;

use crate::forces::friction;
use crate::forces::Force;
use crate::frames::{Builder, Row};
use crate::json::Ctx;
use crate::model::{check_positive, BodyRef, Components, Loc, MExpr, Resolver, Scope};
use crate::parse::{self, Value as FieldValue};

pub mod drive;
pub mod drive_angle;
pub mod drive_distance;
pub mod fix;
pub mod revolute;
pub mod revolute_revolute;
pub mod revolute_translational;
pub mod rigid;
pub mod spatial;
pub mod translational;
pub mod user;

/// A joint, driver or user constraint: rows of Φ(q, t) between body frames.
pub trait Joint: Debug {
    /// The kind's name, as in the DSL, the model JSON and `JointInfo::kind`.
    fn kind(&self) -> &'static str;
    /// The bodies it connects (`None`: no particular body, or the second side of a driver).
    fn bodies(&self) -> (Option<BodyRef>, Option<BodyRef>);
    /// Its rows of Φ, named.
    fn rows(&self, b: &mut Builder) -> Vec<Row>;
    /// Its model JSON object without `"kind"` and `"name"`, which the caller adds.
    fn json(&self, cx: &Ctx) -> Value;
    /// A spatial joint's two markers with their triads, for what refers to the joint by name
    /// (its drivers, rotational springs, friction); `None` for every other kind.
    fn markers(&self) -> Option<[&spatial::Marker; 2]> {
        None
    }
    /// How the joint moves body j relative to body i, where that is a relative-coordinate form
    /// a spanning tree can carry (`tree`); `None` for a joint that is always cut (its rows stay).
    fn relative(&self) -> Option<Relative<'_>> {
        None
    }
}

/// A joint's relative-coordinate form: where body j is, given body i and the joint's
/// coordinates.
#[derive(Clone, Copy, Debug)]
pub enum Relative<'a> {
    /// P_j = P_i and φ_j = φ_i + θ, θ the joint's one coordinate.
    Revolute { i: &'a Loc, j: &'a Loc },
    /// u_j = u_i (the axes stay parallel: φ_j − φ_i is constant) and P_j = P_i + s u_i, s the
    /// joint's one coordinate (its stroke).
    Translational { i: &'a Loc, axis_i: &'a Components, j: &'a Loc, axis_j: &'a Components },
    /// P_j = P_i and φ_j = φ_i + angle: no coordinate.
    Rigid { i: &'a Loc, j: &'a Loc, angle: &'a MExpr },
    /// A spatial joint: marker j's frame relative to marker i's (`tree::spatial`).
    Spatial { kind: SpatialKind, i: &'a spatial::Marker, j: &'a spatial::Marker },
}

/// The spatial joints a tree carries, by their relative motion of marker j in marker i's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpatialKind {
    /// A turn θ about z_i: x_j = cos θ x_i + sin θ y_i.
    Revolute,
    /// A slide s along z_i: P_j = P_i + s z_i, the frames parallel.
    Translational,
    /// A turn θ about z_i and a slide s along it.
    Cylindrical,
    /// Any turn of body j relative to body i about P_i = P_j: a unit quaternion, with the
    /// relative angular velocity in body j's frame.
    Spherical,
    /// None: the frames stay together.
    Rigid,
}

impl Relative<'_> {
    /// The joint's velocities in the tree (the rows it would have as a constraint: 3 or 6 −
    /// this) and its coordinates (a spherical joint's quaternion has 4).
    pub fn counts(self) -> crate::tree::Counts {
        let (q, v) = match self {
            Relative::Revolute { .. } | Relative::Translational { .. } => (1, 1),
            Relative::Rigid { .. } => (0, 0),
            Relative::Spatial { kind, .. } => match kind {
                SpatialKind::Revolute | SpatialKind::Translational => (1, 1),
                SpatialKind::Cylindrical => (2, 2),
                SpatialKind::Spherical => (4, 3),
                SpatialKind::Rigid => (0, 0),
            },
        };
        crate::tree::Counts { q, v }
    }
    /// Its two bodies, i then j.
    pub fn bodies(self) -> [BodyRef; 2] {
        match self {
            Relative::Revolute { i, j } | Relative::Translational { i, j, .. } | Relative::Rigid { i, j, .. } => [i.body, j.body],
            Relative::Spatial { i, j, .. } => [i.loc.body, j.loc.body],
        }
    }
}

/// A validated joint, driver or user constraint with its name.
pub struct Constraint {
    /// `"revolute crank~rod"`, or the user's label.
    pub name: String,
    pub kind: Box<dyn Joint>,
}

/// What a two-attachment joint statement resolved to, handed to its kind's `build`.
pub struct Parts {
    pub i: Loc,
    pub j: Loc,
    pub axis_i: Option<Components>,
    pub axis_j: Option<Components>,
    /// The options the kind declared, resolved (friction options already taken out).
    pub options: HashMap<String, MExpr>,
    /// The joint's keyword, for errors about the statement as a whole.
    pub keyword: Ident,
}

/// A user's mistake: where, and what to say.
pub type Mistake = (Span, String);

/// A two-attachment joint kind: its keyword, which sides take an axis, its options and how it is
/// built from its resolved parts.
pub struct JointSpec {
    pub keyword: &'static str,
    pub axis_i: bool,
    pub axis_j: bool,
    /// Option names, each with "what must be positive" when it must be.
    pub options: &'static [(&'static str, Option<&'static str>)],
    /// The kind from its parts; `Err((span, message))` for a mistake.
    pub build: fn(Parts) -> Result<Box<dyn Joint>, Mistake>,
}

/// Every kind with the shape `keyword Pi [along ui] ~ Pj [along uj] { options };`.
pub const JOINTS: &[JointSpec] = &[revolute::SPEC, translational::SPEC, revolute_revolute::SPEC, revolute_translational::SPEC, rigid::SPEC];

pub fn spec(keyword: &str) -> Option<&'static JointSpec> {
    JOINTS.iter().find(|s| s.keyword == keyword)
}

/// Whether a keyword names a two-attachment joint, planar or spatial.
pub fn is_joint_keyword(keyword: &str) -> bool {
    spec(keyword).is_some() || spatial::spec(keyword).is_some()
}

/// A joint statement, resolved and validated: its label, default name, keyword span, kind and
/// the friction forces its options declare.
pub type Resolved<'a> = (Option<&'a Ident>, String, Span, Box<dyn Joint>, Vec<Named>);

/// A force element with the word that names it after its joint (`"viscous friction"`).
pub type Named = (&'static str, Box<dyn Force>);

/// Resolves a two-attachment joint statement: its points, axes and options, then its kind's
/// `build` and the joint friction its options ask for.
pub fn resolve<'a>(
    r: &mut Resolver,
    j: &'a parse::JointDef,
    body_name: &dyn Fn(BodyRef) -> String,
    joint_index: usize,
) -> Option<Resolved<'a>> {
    let kind = j.kind.to_string();
    let Some(spec) = spec(&kind) else {
        let spatial = spatial::spec(&kind).is_some();
        let why = if spatial { ", a spatial joint, in the plane; state `spatial;` for a spatial mechanism" } else { "" };
        r.errors.push(j.kind.span(), format!("unknown joint kind: expected a planar joint, found `{kind}`{why}"));
        return None;
    };
    let li = r.loc(&j.i.body, &j.i.point);
    let lj = r.loc(&j.j.body, &j.j.point);
    let (li, lj) = (li?, lj?);
    if li.body == lj.body {
        r.errors.push(
            j.j.body.span(),
            format!(
                "a joint of body `{0}` to itself: expected a second body, found `{0}` again; a {kind} joint connects two different bodies",
                j.j.body
            ),
        );
        return None;
    }
    let axis = |r: &mut Resolver, side: &parse::Attach, body: BodyRef, needed: bool, which: &str| -> Option<Option<Components>> {
        match (&side.along, needed) {
            (Some(a), true) => r.axis(body, &a.axis).map(Some),
            (None, true) => {
                r.errors.push(
                    side.body.span(),
                    format!(
                        "a {kind} joint needs a sliding axis on its {which} body: expected `{}.P along [x, y]`, found no `along`",
                        side.body
                    ),
                );
                None
            }
            (Some(a), false) => {
                r.errors.push(
                    a.keyword.span(),
                    format!("a {kind} joint takes no axis on its {which} body: expected a point, found `along`; remove the axis"),
                );
                None
            }
            (None, false) => Some(None),
        }
    };
    let axis_i = axis(r, &j.i, li.body, spec.axis_i, "first");
    let axis_j = axis(r, &j.j, lj.body, spec.axis_j, "second");
    let options = joint_options(r, &kind, spec.options, &j.options);
    let (axis_i, axis_j) = (axis_i?, axis_j?);
    let mut options = options?;
    let friction = match friction::from_joint_options(&mut options, &li, axis_i.as_ref(), &lj, joint_index) {
        Ok(f) => f,
        Err(msg) => {
            r.errors.push(j.kind.span(), msg.replace("{kind}", &kind));
            return None;
        }
    };
    let name = format!("{kind} {}~{}", body_name(li.body), body_name(lj.body));
    match (spec.build)(Parts { i: li, j: lj, axis_i, axis_j, options, keyword: j.kind.clone() }) {
        Ok(joint) => Some((j.label.as_ref(), name, j.kind.span(), joint, friction)),
        Err((span, msg)) => {
            r.errors.push(span, msg);
            None
        }
    }
}

/// A joint statement's options: each known, a number, positive where it must be.
pub fn joint_options(
    r: &mut Resolver,
    kind: &str,
    known: &[(&'static str, Option<&'static str>)],
    fields: &[parse::Field],
) -> Option<HashMap<String, MExpr>> {
    let mut options = HashMap::new();
    let mut bad = false;
    for f in fields {
        let key = f.name.to_string();
        let Some(&(_, positive)) = known.iter().find(|(n, _)| *n == key) else {
            let names: Vec<&str> = known.iter().map(|(n, _)| *n).collect();
            let (expected, hint) = (parse::one_of(&names, "no option"), parse::closest(&key, &names, &[]));
            r.errors.push(f.name.span(), format!("unknown option of a {kind} joint: expected {expected}, found `{key}`{hint}"));
            bad = true;
            continue;
        };
        match &f.value {
            FieldValue::List(v) => {
                r.errors.push(v.span, format!("`{key}` is a number: expected a number, found a list"));
                bad = true;
            }
            FieldValue::Expr(e) => match r.expr(e, Scope::Params) {
                Some(m) => {
                    if let Some(what) = positive {
                        check_positive(r.errors, &m, e, what);
                    }
                    if options.insert(key.clone(), m).is_some() {
                        r.errors.push(
                            f.name.span(),
                            format!("duplicate option `{key}`: expected each option once, found `{key}` again; keep one"),
                        );
                        bad = true;
                    }
                }
                None => bad = true,
            },
        }
    }
    (!bad).then_some(options)
}

/// Coordinates and relative angles already fixed or driven: each may be only once.
#[derive(Default)]
pub struct Driven {
    pub coords: HashMap<(usize, crate::model::Coord), Span>,
    pub angles: std::collections::HashSet<(BodyRef, BodyRef)>,
    /// Spatial joints' angles and strokes, `"hinge.angle"`.
    pub joints: std::collections::HashSet<String>,
}

//! Stage 1: tokens → syntax tree. Only the grammar is checked here; every name is resolved and
//! every rule of mechanics is checked by `model`. Every node keeps the span of its tokens so later
//! stages can point at them.
//!
//! ```text
//! mechanism   := attr* vis? Ident '{' item* '}'
//! item        := 'scalar' Ident ';' | 'spatial' ';' | 'joint_coordinates' ';'
//!              | 'params' '{' (Ident ':' expr),* '}'
//!              | 'body' Ident '{' (Ident ':' value),* '}'
//!              | 'point' Ident '.' Ident '=' vec ';'
//!              | 'vector' Ident '.' Ident '=' vec ';'
//!              | JOINT (Ident ':')? attach '~' attach options? ';'
//!              | ROTATIONAL (Ident ':')? Ident ('~' Ident)? options ';'
//!              | 'fix' Ident '.' Ident ('=' expr)? ';'
//!              | 'drive' (Ident ':')? target '=' expr ';'
//!              | 'constraint' (Ident ':')? expr '=' expr ';'
//! attach      := Ident ('.' Ident | vec) ('along' axis ('reference' axis)?)?
//! axis        := Ident '.' Ident | vec
//! target      := Ident '.' Ident | 'angle' '(' Ident ',' Ident ')' | 'distance' '(' point ',' point ')'
//! options     := '{' (Ident ':' expr),* '}'
//! vec         := '[' expr,* ']'
//! expr        := sum; sum := product (('+'|'-') product)*; product := unary (('*'|'/') unary)*
//! unary       := '-' unary | power; power := atom ('^' unary)?
//! atom        := number | Ident | Ident '.' Ident | Ident '(' expr,* ')' | '(' expr ')'
//! ```

use proc_macro2::Span;
use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream};
use syn::{braced, bracketed, parenthesized, Attribute, Ident, Token, Visibility};

/// The whole `mechanism! { ... }` input.
pub struct MechanismDef {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub items: Vec<Item>,
}

/// One statement inside the mechanism's braces.
pub enum Item {
    Scalar(Ident),
    /// `spatial;`: the mechanism lives in 3D.
    Spatial(Ident),
    /// `joint_coordinates;`: the mechanism is described by the relative coordinates of a
    /// spanning tree of its joints (`tree`), not by each body's pose.
    JointCoordinates(Ident),
    Params(Vec<(Ident, Expr)>),
    Body(BodyDef),
    Point(NamedVector),
    Vector(NamedVector),
    Joint(JointDef),
    Fix(FixDef),
    Drive(DriveDef),
    Constraint(ConstraintDef),
    Gravity(Ident, VecLit),
    /// `spring`, `damper`, `actuator` between two points (same shape as a joint).
    PointForce(JointDef),
    /// `rotational_spring`, `rotational_damper`, `torque_actuator` between two bodies (planar)
    /// or on a joint's angle (spatial); `translational_spring`, `translational_damper`,
    /// `force_actuator` on a spatial joint's stroke.
    AxisForce(AxisForceDef),
    /// `force` (global components) or `local_force` (body components) at a point.
    Force(ForceDef),
    Torque(TorqueDef),
}

#[derive(Clone)]
pub struct AxisForceDef {
    pub kind: Ident,
    pub label: Option<Ident>,
    pub i: Ident,
    /// The second body (planar); absent where `i` names a joint (spatial).
    pub j: Option<Ident>,
    pub options: Vec<Field>,
}

#[derive(Clone)]
pub struct ForceDef {
    pub kind: Ident,
    pub label: Option<Ident>,
    pub body: Ident,
    pub point: PointRef,
    pub value: VecLit,
}

#[derive(Clone)]
pub struct TorqueDef {
    pub keyword: Ident,
    pub label: Option<Ident>,
    pub body: Ident,
    /// A number (planar) or a list of three components (spatial).
    pub value: Value,
}

#[derive(Clone)]
pub struct BodyDef {
    pub name: Ident,
    pub fields: Vec<Field>,
    /// Declared with `particle`: a point mass, its angle held at 0.
    pub particle: bool,
}

/// `name: value` inside a body or an option block.
#[derive(Clone)]
pub struct Field {
    pub name: Ident,
    pub value: Value,
}

/// A field's value: an expression, or a bracketed list of them.
#[derive(Clone)]
pub enum Value {
    Expr(Expr),
    List(VecLit),
}

/// `[e1, e2, ...]`
#[derive(Clone)]
pub struct VecLit {
    pub items: Vec<Expr>,
    pub span: Span,
}

/// `point body.name = [ξ, η];` or `vector body.name = [x, y];`
#[derive(Clone)]
pub struct NamedVector {
    pub body: Ident,
    pub name: Ident,
    pub value: VecLit,
}

/// A point on a body, by name (`crank.B`) or written in place (`crank[0.05, 0.0]`).
#[derive(Clone)]
pub enum PointRef {
    Named(Ident),
    Inline(VecLit),
}

/// One side of a joint: a body, a point on it and, for sliding joints, an axis.
#[derive(Clone)]
pub struct Attach {
    pub body: Ident,
    pub point: PointRef,
    pub along: Option<Along>,
}

/// The axis after `along`: a named vector of the same body or a vector written in place; in
/// space, optionally the reference direction of the marker's x-axis after `reference`.
#[derive(Clone)]
pub struct Along {
    pub keyword: Ident,
    pub axis: AxisRef,
    pub reference: Option<AxisRef>,
}

#[derive(Clone)]
pub enum AxisRef {
    Named(Ident, Ident),
    Inline(VecLit),
}

#[derive(Clone)]
pub struct JointDef {
    pub kind: Ident,
    pub label: Option<Ident>,
    pub i: Attach,
    pub j: Attach,
    pub options: Vec<Field>,
}

#[derive(Clone)]
pub struct FixDef {
    pub keyword: Ident,
    pub label: Option<Ident>,
    pub body: Ident,
    pub coordinate: Ident,
    pub value: Option<Expr>,
}

#[derive(Clone)]
pub enum DriveTarget {
    Coordinate { body: Ident, coordinate: Ident },
    Angle { i: Ident, j: Ident },
    Distance { i: (Ident, PointRef), j: (Ident, PointRef) },
}

#[derive(Clone)]
pub struct DriveDef {
    pub keyword: Ident,
    pub label: Option<Ident>,
    pub target: DriveTarget,
    pub f: Expr,
}

#[derive(Clone)]
pub struct ConstraintDef {
    pub keyword: Ident,
    pub label: Option<Ident>,
    pub lhs: Expr,
    pub rhs: Expr,
}

/// An expression as written, with the spans of its first and last tokens (so errors can
/// underline all of it on stable Rust, where spans cannot be joined).
#[derive(Clone)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
    pub end: Span,
}

impl Expr {
    fn new(kind: ExprKind, span: Span, end: Span) -> Self {
        Expr { kind, span, end }
    }

    /// A number written between these spans.
    pub fn number(value: f64, span: Span, end: Span) -> Self {
        Expr::new(ExprKind::Num(value), span, end)
    }

    /// An error underlining the whole expression.
    pub fn error(&self, msg: impl std::fmt::Display) -> syn::Error {
        let first = quote::quote_spanned!(self.span=> a);
        let last = quote::quote_spanned!(self.end=> b);
        syn::Error::new_spanned(quote::quote!(#first #last), msg)
    }
}

#[derive(Clone)]
pub enum ExprKind {
    Num(f64),
    /// A parameter, `t` or `PI`.
    Ident(Ident),
    /// `body.coordinate`
    Coord(Ident, Ident),
    Neg(Box<Expr>),
    Bin(BinOp, Box<Expr>, Box<Expr>),
    Call(Ident, Vec<Expr>),
    /// `if a > b { x } else { y }` (`>`, `>=`, `<`, `<=`; `else if` chains).
    If(Box<Condition>, Box<Expr>, Box<Expr>),
}

/// The comparison of an `if` expression.
#[derive(Clone)]
pub struct Condition {
    pub lhs: Expr,
    pub op: CmpOp,
    pub rhs: Expr,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum CmpOp {
    Gt,
    Ge,
    Lt,
    Le,
}

#[derive(Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
}

/// Force elements between two points (and, `bushing`, between two markers): the keywords of the
/// two-attachment force rule.
pub const POINT_FORCE_KINDS: &[&str] = &["spring", "damper", "actuator", "bushing", "contact", "cable", "tyre"];

/// Force elements between two bodies' angles or on a joint's angle or stroke.
pub const AXIS_FORCE_KINDS: &[&str] =
    &["rotational_spring", "rotational_damper", "torque_actuator", "translational_spring", "translational_damper", "force_actuator"];

/// Every statement keyword, for "did you mean" hints (a test checks that every registered joint
/// kind is here).
pub const STATEMENTS: &[&str] = &[
    "let",
    "scalar",
    "spatial",
    "joint_coordinates",
    "params",
    "body",
    "particle",
    "point",
    "vector",
    "fix",
    "drive",
    "constraint",
    "gravity",
    "force",
    "local_force",
    "torque",
    "local_torque",
    "revolute",
    "translational",
    "revolute_revolute",
    "revolute_translational",
    "rigid",
    "spherical",
    "universal",
    "cylindrical",
    "planar",
    "point_on_line",
    "point_on_plane",
    "distance",
    "bushing",
    "spring",
    "damper",
    "actuator",
    "contact",
    "cable",
    "tyre",
    "rotational_spring",
    "rotational_damper",
    "torque_actuator",
    "translational_spring",
    "translational_damper",
    "force_actuator",
    "scene",
];

impl Parse for MechanismDef {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let (def, errors) = MechanismDef::parse_recovering(input)?;
        match errors {
            Some(e) => Err(e),
            None => Ok(def),
        }
    }
}

impl MechanismDef {
    /// Parses the mechanism statement by statement: a statement that does not parse is
    /// reported and skipped (to its `;`, or past its braces where the next statement begins), and
    /// the others are kept, so that a placeholder of the mechanism can still be made of them.
    /// Fails outright only where the name or the braces are wrong.
    pub fn parse_recovering(input: ParseStream) -> syn::Result<(Self, Option<syn::Error>)> {
        use syn::parse::discouraged::Speculative;
        let attrs = input.call(Attribute::parse_outer)?;
        let vis: Visibility = input.parse()?;
        let name: Ident = input.parse()?;
        let content;
        braced!(content in input);
        let mut items = Vec::new();
        let mut errors: Option<syn::Error> = None;
        let mut broken_bodies = Vec::new();
        while !content.is_empty() {
            let fork = content.fork();
            match fork.parse::<Item>() {
                Ok(item) => {
                    content.advance_to(&fork);
                    items.push(item);
                }
                Err(e) => {
                    match &mut errors {
                        Some(all) => all.combine(e),
                        None => errors = Some(e),
                    }
                    // A body stays, unit mass and inertia, and parameters stay, defaults 0, for
                    // what names them.
                    let head = content.fork();
                    match head.parse::<Ident>() {
                        Ok(k) if k == "body" => broken_bodies.extend(head.parse::<Ident>().ok()),
                        Ok(k) if k == "params" => items.extend(head.parse::<proc_macro2::Group>().ok().map(|g| stand_in_params(&g))),
                        _ => {}
                    }
                    // A statement whose only mistake is its missing `;` stays, for what names it;
                    // so does one written with another program's keyword (`prismatic`), as the
                    // DSL's joint it names (its label and rows are what the program uses).
                    let (mut skipped, cut_short) = skip_statement(&content)?;
                    let synonym = match skipped.first() {
                        Some(proc_macro2::TokenTree::Ident(k)) => {
                            SYNONYMS.iter().find(|(word, _)| k == word).map(|(_, ours)| Ident::new(ours, k.span()))
                        }
                        _ => None,
                    };
                    if let Some(ours) = &synonym {
                        skipped[0] = proc_macro2::TokenTree::Ident(ours.clone());
                    }
                    if cut_short || synonym.is_some() {
                        let end = (cut_short).then(|| quote::quote!(;).into_iter().next().expect("a `;`"));
                        let completed: proc_macro2::TokenStream = skipped.into_iter().chain(end).collect();
                        items.extend(syn::parse2::<Item>(completed).ok());
                    }
                }
            }
        }
        if !input.is_empty() {
            return Err(input.error("expected nothing after the mechanism's closing brace, found more"));
        }
        let spatial = items.iter().any(|i| matches!(i, Item::Spatial(_)));
        items.extend(broken_bodies.into_iter().map(|body| Item::Body(BodyDef::unit(body, spatial, false))));
        Ok((MechanismDef { attrs, vis, name, items }, errors))
    }
}

impl BodyDef {
    /// A body of unit mass and inertia, at the origin: what stands in for a body whose statement
    /// has a mistake, so that what names it still resolves.
    pub fn unit(name: Ident, spatial: bool, particle: bool) -> Self {
        let span = name.span();
        let one = || Expr::new(ExprKind::Num(1.0), span, span);
        let mut fields = vec![Field { name: Ident::new("mass", span), value: Value::Expr(one()) }];
        if !particle {
            let inertia = if spatial { Value::List(VecLit { items: vec![one(), one(), one()], span }) } else { Value::Expr(one()) };
            fields.push(Field { name: Ident::new("inertia", span), value: inertia });
        }
        BodyDef { name, fields, particle }
    }
}

/// The parameters of a `params { ... }` that does not parse, each `name:` at its top level with
/// the default 0 (a missing comma or a unit does not lose the names after it).
fn stand_in_params(group: &proc_macro2::Group) -> Item {
    use proc_macro2::{Spacing, TokenTree};
    let tokens: Vec<TokenTree> = group.stream().into_iter().collect();
    let names = tokens.windows(2).filter_map(|w| match w {
        [TokenTree::Ident(name), TokenTree::Punct(colon)] if colon.as_char() == ':' && colon.spacing() == Spacing::Alone => {
            Some((name.clone(), Expr::number(0.0, name.span(), name.span())))
        }
        _ => None,
    });
    Item::Params(names.collect())
}

/// Skips the rest of a statement that did not parse: through its `;`, through a braced group
/// not followed by `;` (`body b { ... }`, `params { ... }`), or up to the next statement's
/// keyword, so that a missing `;` costs only the statement before it (`gravity [0.0, -9.81]`
/// followed by `body crank { ... }` loses the gravity, not the body).
/// Returns the tokens skipped, and whether the statement was cut short (at the next statement's
/// keyword or the end: its `;` is missing).
fn skip_statement(input: ParseStream) -> syn::Result<(Vec<proc_macro2::TokenTree>, bool)> {
    let mut skipped = Vec::new();
    while !input.is_empty() {
        let next_statement =
            input.fork().call(Ident::parse_any).is_ok_and(|k| STATEMENTS.contains(&k.to_string().as_str()) || k == "scene")
                && !input.peek2(Token![:])
                && !input.peek2(Token![.]);
        if next_statement && !skipped.is_empty() {
            return Ok((skipped, true));
        }
        let tt: proc_macro2::TokenTree = input.parse()?;
        let ends = match &tt {
            proc_macro2::TokenTree::Punct(p) => p.as_char() == ';',
            proc_macro2::TokenTree::Group(g) => g.delimiter() == proc_macro2::Delimiter::Brace && !input.peek(Token![;]),
            _ => false,
        };
        skipped.push(tt);
        if ends {
            return Ok((skipped, false));
        }
    }
    Ok((skipped, true))
}

/// An optional `label:` before a statement's body.
fn label(input: ParseStream) -> syn::Result<Option<Ident>> {
    if input.peek(Ident) && input.peek2(Token![:]) && !input.peek2(Token![::]) {
        let l: Ident = input.parse()?;
        input.parse::<Token![:]>()?;
        Ok(Some(l))
    } else {
        Ok(None)
    }
}

impl Parse for Item {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let kw: Ident = input.call(Ident::parse_any).map_err(|e| {
            syn::Error::new(
                e.span(),
                "expected a statement: `scalar`, `params`, `body`, `point`, `vector`, a joint \
                 (`revolute`, `translational`, `revolute_revolute`, `revolute_translational`, `rigid`; \
                 in space also `spherical`, `universal`, `cylindrical`, `planar`, `point_on_line`, `point_on_plane`, \
                 `distance`), `fix`, `drive`, `constraint`, `gravity`, `spatial`, `joint_coordinates`, a force element (`spring`, `damper`, \
                 `actuator`, `bushing`, `rotational_spring`, `rotational_damper`, `torque_actuator`, \
                 in space also `translational_spring`, `translational_damper`, `force_actuator`; `force`, `local_force`, \
                 `torque`, `local_torque`), a `for` loop or a `scene`",
            )
        })?;
        let item = match kw.to_string().as_str() {
            "scalar" => {
                let ty: Ident = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Scalar(ty)
            }
            "spatial" => {
                input.parse::<Token![;]>()?;
                Item::Spatial(kw)
            }
            "joint_coordinates" => {
                input.parse::<Token![;]>()?;
                Item::JointCoordinates(kw)
            }
            "params" => parse_params(input)?,
            "body" | "particle" => {
                let name: Ident = input.parse()?;
                let fields = parse_fields(input)?;
                eat_optional_semi(input)?;
                Item::Body(BodyDef { name, fields, particle: kw == "particle" })
            }
            "point" | "vector" => parse_named_vector(kw, input)?,
            "fix" => parse_fix(kw, input)?,
            "drive" => {
                let label = label(input)?;
                let target = parse_drive_target(input)?;
                input.parse::<Token![=]>()?;
                let f: Expr = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Drive(DriveDef { keyword: kw, label, target, f })
            }
            "constraint" => {
                let label = label(input)?;
                let lhs: Expr = input.parse()?;
                input.parse::<Token![=]>()?;
                let rhs: Expr = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Constraint(ConstraintDef { keyword: kw, label, lhs, rhs })
            }
            "gravity" => {
                let value: VecLit = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Gravity(kw, value)
            }
            "force" | "local_force" => {
                let label = label(input)?;
                let body: Ident = input.call(Ident::parse_any)?;
                let point = parse_point_ref(input)?;
                input.parse::<Token![=]>()?;
                let value: VecLit = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Force(ForceDef { kind: kw, label, body, point, value })
            }
            "torque" | "local_torque" => {
                let label = label(input)?;
                let body: Ident = input.call(Ident::parse_any)?;
                input.parse::<Token![=]>()?;
                let value = if input.peek(syn::token::Bracket) { Value::List(input.parse()?) } else { Value::Expr(input.parse()?) };
                input.parse::<Token![;]>()?;
                Item::Torque(TorqueDef { keyword: kw, label, body, value })
            }
            k if AXIS_FORCE_KINDS.contains(&k) => parse_axis_force(kw, input)?,
            k if crate::elements::is_joint_keyword(k) || POINT_FORCE_KINDS.contains(&k) => parse_attached(kw, k, input)?,
            other => {
                // `motor: drive ...`: the keyword after the colon, if the word is a label.
                let fork = input.fork();
                let keyword = (input.peek(Token![:]) && !input.peek(Token![::]))
                    .then(|| fork.parse::<Token![:]>().and_then(|_| fork.call(Ident::parse_any)).ok())
                    .flatten();
                return Err(unknown_statement(&kw, other, keyword));
            }
        };
        Ok(item)
    }
}

/// `params { name: default, ... }`.
fn parse_params(input: ParseStream) -> syn::Result<Item> {
    let content;
    braced!(content in input);
    let mut params = Vec::new();
    while !content.is_empty() {
        let name: Ident = content.parse()?;
        content.parse::<Token![:]>()?;
        let value: Expr = content.parse()?;
        params.push((name, value));
        if !content.is_empty() {
            no_unit_after_value(&content)?;
            content.parse::<Token![,]>()?;
        }
    }
    eat_optional_semi(input)?;
    Ok(Item::Params(params))
}

/// `point body.name = [...];` or `vector body.name = [...];`.
fn parse_named_vector(kw: Ident, input: ParseStream) -> syn::Result<Item> {
    let body: Ident = input.call(Ident::parse_any)?;
    input.parse::<Token![.]>()?;
    let name: Ident = input.parse()?;
    input.parse::<Token![=]>()?;
    let value: VecLit = input.parse()?;
    input.parse::<Token![;]>()?;
    let nv = NamedVector { body, name, value };
    Ok(if kw == "point" { Item::Point(nv) } else { Item::Vector(nv) })
}

/// `fix label: body.coordinate [= value];`.
fn parse_fix(kw: Ident, input: ParseStream) -> syn::Result<Item> {
    let label = label(input)?;
    let body: Ident = input.call(Ident::parse_any)?;
    input.parse::<Token![.]>()?;
    let coordinate: Ident = input.parse()?;
    let value = if input.peek(Token![=]) {
        input.parse::<Token![=]>()?;
        Some(input.parse()?)
    } else {
        None
    };
    input.parse::<Token![;]>()?;
    Ok(Item::Fix(FixDef { keyword: kw, label, body, coordinate, value }))
}

/// A force element along an axis or about it, on one body or between two:
/// `rotational_spring a ~ b { ... };`.
fn parse_axis_force(kw: Ident, input: ParseStream) -> syn::Result<Item> {
    let label = label(input)?;
    let i: Ident = input.call(Ident::parse_any)?;
    let j = if input.peek(Token![~]) {
        input.parse::<Token![~]>()?;
        Some(input.call(Ident::parse_any)?)
    } else {
        None
    };
    let options = parse_fields(input)?;
    input.parse::<Token![;]>()?;
    Ok(Item::AxisForce(AxisForceDef { kind: kw, label, i, j, options }))
}

/// A joint or a point-to-point force element between two attachments,
/// `kind a[x, y] ~ b.P { ... };`.
fn parse_attached(kw: Ident, k: &str, input: ParseStream) -> syn::Result<Item> {
    let label = label(input)?;
    let i: Attach = input.parse()?;
    if !input.peek(Token![~]) {
        let what = if POINT_FORCE_KINDS.contains(&k) { "acts between" } else { "joins" };
        return Err(input.error(format!(
            "expected `~` and a second attachment: a {k} {what} two bodies, `{k} a[x, y] ~ b.P` (the ground is one: `~ ground[x, y]`)"
        )));
    }
    input.parse::<Token![~]>()?;
    let j: Attach = input.parse()?;
    let options = if input.peek(syn::token::Brace) { parse_fields(input)? } else { Vec::new() };
    input.parse::<Token![;]>()?;
    let def = JointDef { kind: kw, label, i, j, options };
    Ok(if POINT_FORCE_KINDS.contains(&k) { Item::PointForce(def) } else { Item::Joint(def) })
}

/// A word that starts no statement, with a hint: our name for another program's; for a label
/// written before its statement's `keyword` (`motor: drive ...`), that it goes after it; or the
/// closest keyword.
fn unknown_statement(kw: &Ident, other: &str, labelled: Option<Ident>) -> syn::Error {
    let hint = match SYNONYMS.iter().find(|(word, _)| *word == other) {
        Some((_, ours)) => format!(" (the same joint is called `{ours}` here)"),
        None => match labelled {
            Some(keyword) => format!(" (a label goes after its statement's keyword: `{keyword} {other}: ...`)"),
            None => closest(other, STATEMENTS, &[]),
        },
    };
    syn::Error::new(
        kw.span(),
        format!("unknown statement: expected a statement such as `body`, `revolute` or `spring`, found `{other}`{hint}"),
    )
}

/// Other programs' and textbooks' names of the joints and elements the DSL names otherwise.
const SYNONYMS: &[(&str, &str)] = &[
    ("prismatic", "translational"),
    ("pin_in_slot", "revolute_translational"),
    ("pin_slot", "revolute_translational"),
    ("slot", "revolute_translational"),
    ("slider", "translational"),
    ("pin", "revolute"),
    ("hinge", "revolute"),
    ("ball", "spherical"),
    ("ball_joint", "spherical"),
    ("cardan", "universal"),
    ("hooke", "universal"),
    ("fixed", "rigid"),
    ("weld", "rigid"),
    ("spring_damper", "spring"),
    ("tire", "tyre"),
    ("rope", "cable"),
    ("stop", "contact"),
];

/// "one of `a`, `b`, `c`" ("`a`" for one, `none` for none): what an error expected.
pub fn one_of(names: &[&str], none: &str) -> String {
    match names {
        [] => none.to_string(),
        [one] => format!("`{one}`"),
        _ => format!("one of {}", names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")),
    }
}

/// " (did you mean `x`?)" when a known word is one or two edits away.
pub fn closest(word: &str, a: &[&str], b: &[&str]) -> String {
    nearest(word, a, b).map(|c| format!(" (did you mean `{c}`?)")).unwrap_or_default()
}

/// The known word one or two edits away, the nearest; between equally near indexed names
/// (`l_3` against `l_0`, `l_1`, `l_2`: one edit each) the one of the nearest index, so that a
/// loop reaching one past its last body hears of the last one.
pub fn nearest<'a>(word: &str, a: &[&'a str], b: &[&'a str]) -> Option<&'a str> {
    let index = |name: &str| name.rsplit_once('_').and_then(|(_, n)| n.parse::<i64>().ok());
    let gap = |c: &str| index(word).zip(index(c)).map_or(0, |(w, c)| (w - c).unsigned_abs());
    a.iter().chain(b).map(|c| (edit_distance(word, c), gap(c), *c)).filter(|(d, ..)| *d <= 2).min().map(|(.., c)| c)
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1];
        for (j, cb) in b.iter().enumerate() {
            cur.push((prev[j] + usize::from(ca != *cb)).min(prev[j + 1] + 1).min(cur[j] + 1));
        }
        prev = cur;
    }
    prev[b.len()]
}

fn eat_optional_semi(input: ParseStream) -> syn::Result<()> {
    if input.peek(Token![;]) {
        input.parse::<Token![;]>()?;
    }
    Ok(())
}

/// `mass: 2.0 kg`, `d: 300 mm`, `[97.2 deg, 0.0]`: a unit after a number gets its own message,
/// not "expected `,`" (a next field's name, followed by `:`, is a missing comma instead).
fn no_unit_after_value(input: ParseStream) -> syn::Result<()> {
    if !input.peek(Ident::peek_any) || input.peek2(Token![:]) {
        return Ok(());
    }
    let unit: Ident = input.call(Ident::parse_any)?;
    let degrees = matches!(unit.to_string().as_str(), "deg" | "degree" | "degrees");
    let hint = if degrees { "; an angle in degrees is `deg(value)`" } else { "" };
    Err(syn::Error::new(
        unit.span(),
        format!(
            "expected `,` or the end after a value, found the unit `{unit}`: numbers are in SI units (kg, m, s, rad, N) and are written without one{hint}"
        ),
    ))
}

fn parse_fields(input: ParseStream) -> syn::Result<Vec<Field>> {
    let content;
    braced!(content in input);
    let mut fields = Vec::new();
    while !content.is_empty() {
        let name: Ident = content.call(Ident::parse_any)?;
        content.parse::<Token![:]>()?;
        let value = if content.peek(syn::token::Bracket) { Value::List(content.parse()?) } else { Value::Expr(content.parse()?) };
        fields.push(Field { name: name.clone(), value });
        if !content.is_empty() {
            no_unit_after_value(&content)?;
            if content.peek(Ident::peek_any) && content.peek2(Token![:]) {
                let next: Ident = content.call(Ident::parse_any)?;
                return Err(syn::Error::new(
                    next.span(),
                    format!("expected `,` between fields, found `{next}`: separate them with commas, `{}: ..., {next}: ...`", name),
                ));
            }
            content.parse::<Token![,]>()?;
        }
    }
    Ok(fields)
}

fn parse_point_ref(input: ParseStream) -> syn::Result<PointRef> {
    if input.peek(Token![.]) {
        input.parse::<Token![.]>()?;
        Ok(PointRef::Named(input.parse()?))
    } else if input.peek(syn::token::Bracket) {
        Ok(PointRef::Inline(input.parse()?))
    } else {
        Err(input.error("expected a point on the body: `.name` of a declared point or `[ξ, η]` in body coordinates (m)"))
    }
}

fn parse_drive_target(input: ParseStream) -> syn::Result<DriveTarget> {
    let head: Ident = input.call(Ident::parse_any)?;
    if input.peek(syn::token::Paren) && (head == "angle" || head == "distance") {
        let content;
        parenthesized!(content in input);
        let target = if head == "angle" {
            let i: Ident = content.call(Ident::parse_any)?;
            content.parse::<Token![,]>()?;
            let j: Ident = content.call(Ident::parse_any)?;
            DriveTarget::Angle { i, j }
        } else {
            let bi: Ident = content.call(Ident::parse_any)?;
            let pi = parse_point_ref(&content)?;
            content.parse::<Token![,]>()?;
            let bj: Ident = content.call(Ident::parse_any)?;
            let pj = parse_point_ref(&content)?;
            DriveTarget::Distance { i: (bi, pi), j: (bj, pj) }
        };
        if !content.is_empty() {
            return Err(content.error("expected two arguments to a relative driver, found more"));
        }
        Ok(target)
    } else {
        input.parse::<Token![.]>().map_err(|e| {
            syn::Error::new(
                e.span(),
                "expected what to drive: `body.x`, `body.y`, `body.phi`, `angle(body_i, body_j)` or `distance(body_i.P, body_j.Q)`; \
                 in space `body.x`, `body.y`, `body.z`, `joint.angle` or `joint.stroke`",
            )
        })?;
        let coordinate: Ident = input.parse()?;
        Ok(DriveTarget::Coordinate { body: head, coordinate })
    }
}

impl Parse for Attach {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let body: Ident = input.call(Ident::parse_any)?;
        let point = parse_point_ref(input)?;
        let along = if input.peek(Ident) && input.fork().parse::<Ident>().map(|i| i == "along").unwrap_or(false) {
            let keyword: Ident = input.parse()?;
            let axis = input.parse()?;
            let reference = if input.peek(Ident) && input.fork().parse::<Ident>().map(|i| i == "reference").unwrap_or(false) {
                input.parse::<Ident>()?;
                Some(input.parse()?)
            } else {
                None
            };
            Some(Along { keyword, axis, reference })
        } else {
            None
        };
        Ok(Attach { body, point, along })
    }
}

impl Parse for AxisRef {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        if input.peek(syn::token::Bracket) {
            Ok(AxisRef::Inline(input.parse()?))
        } else {
            let b: Ident = input.call(Ident::parse_any)?;
            input.parse::<Token![.]>()?;
            Ok(AxisRef::Named(b, input.parse()?))
        }
    }
}

impl Parse for VecLit {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let content;
        let bracket = bracketed!(content in input);
        let mut items = Vec::new();
        while !content.is_empty() {
            items.push(content.parse()?);
            if !content.is_empty() {
                no_unit_after_value(&content)?;
                content.parse::<Token![,]>()?;
            }
        }
        Ok(VecLit { items, span: bracket.span.join() })
    }
}

impl Parse for Expr {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        parse_sum(input)
    }
}

fn bin(op: BinOp, l: Expr, r: Expr) -> Expr {
    let (span, end) = (l.span, r.end);
    Expr::new(ExprKind::Bin(op, Box::new(l), Box::new(r)), span, end)
}

fn parse_sum(input: ParseStream) -> syn::Result<Expr> {
    let mut lhs = parse_product(input)?;
    loop {
        let op = if input.peek(Token![+]) {
            input.parse::<Token![+]>()?;
            BinOp::Add
        } else if input.peek(Token![-]) {
            input.parse::<Token![-]>()?;
            BinOp::Sub
        } else {
            return Ok(lhs);
        };
        let rhs = parse_product(input)?;
        lhs = bin(op, lhs, rhs);
    }
}

fn parse_product(input: ParseStream) -> syn::Result<Expr> {
    let mut lhs = parse_unary(input)?;
    loop {
        let op = if input.peek(Token![*]) && !input.peek(Token![*=]) {
            input.parse::<Token![*]>()?;
            BinOp::Mul
        } else if input.peek(Token![/]) {
            input.parse::<Token![/]>()?;
            BinOp::Div
        } else {
            return Ok(lhs);
        };
        let rhs = parse_unary(input)?;
        lhs = bin(op, lhs, rhs);
    }
}

fn parse_unary(input: ParseStream) -> syn::Result<Expr> {
    if input.peek(Token![-]) {
        let minus: Token![-] = input.parse()?;
        let inner = parse_unary(input)?;
        let end = inner.end;
        return Ok(Expr::new(ExprKind::Neg(Box::new(inner)), minus.span, end));
    }
    let base = parse_atom(input)?;
    if input.peek(Token![^]) {
        input.parse::<Token![^]>()?;
        // right-associative and binding tighter than unary minus on its left: -a^b = -(a^b)
        let exp = parse_unary(input)?;
        return Ok(bin(BinOp::Pow, base, exp));
    }
    Ok(base)
}

/// `if a > b { x } else { y }`, after the `if`; `else if` chains. Both branches are required: an
/// expression always has a value.
fn parse_if(input: ParseStream, keyword: Span) -> syn::Result<Expr> {
    let lhs = parse_sum(input)?;
    let op = if input.peek(Token![>=]) {
        input.parse::<Token![>=]>()?;
        CmpOp::Ge
    } else if input.peek(Token![<=]) {
        input.parse::<Token![<=]>()?;
        CmpOp::Le
    } else if input.peek(Token![==]) || input.peek(Token![!=]) {
        let (op, span) = if input.peek(Token![==]) {
            ("==", input.parse::<Token![==]>()?.spans[0])
        } else {
            ("!=", input.parse::<Token![!=]>()?.spans[0])
        };
        return Err(syn::Error::new(
            span,
            format!(
                "expected `>`, `>=`, `<` or `<=`, found `{op}`: it compares reals exactly, which a solver's rounding makes meaningless"
            ),
        ));
    } else if input.peek(Token![>]) {
        input.parse::<Token![>]>()?;
        CmpOp::Gt
    } else if input.peek(Token![<]) {
        input.parse::<Token![<]>()?;
        CmpOp::Lt
    } else {
        return Err(input.error("expected a comparison `>`, `>=`, `<` or `<=` after `if`'s first operand"));
    };
    let rhs = parse_sum(input)?;
    let then = parse_branch(input, "after the condition")?;
    if !input.peek(Token![else]) {
        return Err(input.error("expected `else { ... }`: an `if` expression needs a value in both cases"));
    }
    input.parse::<Token![else]>()?;
    let otherwise = if input.peek(Token![if]) {
        let kw: Token![if] = input.parse()?;
        parse_if(input, kw.span)?
    } else {
        parse_branch(input, "after `else`")?
    };
    let end = otherwise.end;
    let condition = Condition { lhs, op, rhs };
    Ok(Expr::new(ExprKind::If(Box::new(condition), Box::new(then), Box::new(otherwise)), keyword, end))
}

/// `{ expression }` of an `if`.
fn parse_branch(input: ParseStream, place: &str) -> syn::Result<Expr> {
    if !input.peek(syn::token::Brace) {
        return Err(input.error(format!("expected `{{ expression }}` {place}")));
    }
    let content;
    let brace = braced!(content in input);
    let mut inner: Expr = content.parse()?;
    if !content.is_empty() {
        return Err(content.error("expected `}`: an operator (+ - * / ^) is missing"));
    }
    inner.span = brace.span.open();
    inner.end = brace.span.close();
    Ok(inner)
}

fn parse_atom(input: ParseStream) -> syn::Result<Expr> {
    if input.peek(Token![if]) {
        let kw: Token![if] = input.parse()?;
        return parse_if(input, kw.span);
    }
    if input.peek(syn::LitFloat) {
        let lit: syn::LitFloat = input.parse()?;
        if !lit.suffix().is_empty() {
            return Err(syn::Error::new(
                lit.span(),
                "expected a number without a type suffix, found one: the mechanism's scalar type is used",
            ));
        }
        return Ok(Expr::new(ExprKind::Num(lit.base10_parse()?), lit.span(), lit.span()));
    }
    if input.peek(syn::LitInt) {
        let lit: syn::LitInt = input.parse()?;
        if !lit.suffix().is_empty() {
            return Err(syn::Error::new(
                lit.span(),
                "expected a number without a type suffix, found one: the mechanism's scalar type is used",
            ));
        }
        return Ok(Expr::new(ExprKind::Num(lit.base10_parse::<f64>()?), lit.span(), lit.span()));
    }
    if input.peek(syn::token::Paren) {
        let content;
        let paren = parenthesized!(content in input);
        let mut inner: Expr = content.parse()?;
        if !content.is_empty() {
            return Err(content.error("expected `)`: an operator (+ - * / ^) is missing"));
        }
        inner.span = paren.span.open();
        inner.end = paren.span.close();
        return Ok(inner);
    }
    if input.peek(Ident::peek_any) {
        let id: Ident = input.call(Ident::parse_any)?;
        if input.peek(Token![.]) && !input.peek(Token![..]) {
            input.parse::<Token![.]>()?;
            let coord: Ident = input.call(Ident::parse_any)?;
            let (span, end) = (id.span(), coord.span());
            return Ok(Expr::new(ExprKind::Coord(id, coord), span, end));
        }
        if input.peek(syn::token::Paren) {
            let content;
            let paren = parenthesized!(content in input);
            let mut args = Vec::new();
            while !content.is_empty() {
                args.push(content.parse()?);
                if !content.is_empty() {
                    content.parse::<Token![,]>()?;
                }
            }
            let (span, end) = (id.span(), paren.span.close());
            return Ok(Expr::new(ExprKind::Call(id, args), span, end));
        }
        let span = id.span();
        return Ok(Expr::new(ExprKind::Ident(id), span, span));
    }
    if input.is_empty() {
        return Err(input.error("expected an expression"));
    }
    let tt: proc_macro2::TokenTree = input.parse()?;
    Err(syn::Error::new(
        tt.span(),
        format!("expected a number, a parameter, `t`, `PI`, a coordinate like `crank.phi` or a function call, found `{tt}`"),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every joint kind registered in `elements::JOINTS` is a statement keyword (for did-you-mean
    /// hints) and is named in the "expected a statement" message.
    #[test]
    fn registered_joints_are_statements() {
        let keywords = crate::elements::JOINTS.iter().map(|s| s.keyword).chain(crate::elements::spatial::JOINTS.iter().map(|s| s.keyword));
        for keyword in keywords {
            assert!(STATEMENTS.contains(&keyword), "{keyword} missing from STATEMENTS");
            let err = syn::parse_str::<Item>("123").err().expect("a number is not a statement").to_string();
            assert!(err.contains(&format!("`{keyword}`")), "{keyword} missing from: {err}");
        }
    }

    /// A joint statement parses into its attachments, axis and options, keeping the label.
    #[test]
    fn a_joint_statement() {
        let item: Item =
            syn::parse_str("translational slide: a[0.0, 0.1] along [1.0, 0.0] ~ ground.O along b.u { viscous: 2.0 };").unwrap();
        let Item::Joint(j) = item else { panic!("not a joint") };
        assert_eq!(j.kind, "translational");
        assert_eq!(j.label.as_ref().map(|l| l.to_string()).as_deref(), Some("slide"));
        assert!(matches!(j.i.point, PointRef::Inline(ref v) if v.items.len() == 2));
        assert!(matches!(j.j.point, PointRef::Named(ref n) if n == "O"));
        assert!(matches!(j.j.along, Some(Along { axis: AxisRef::Named(ref b, ref u), .. }) if b == "b" && u == "u"));
        assert_eq!(j.options.len(), 1);
    }

    /// `-x^2` is `-(x^2)`: the power binds tighter than unary minus.
    #[test]
    fn power_binds_tighter_than_negation() {
        let e: Expr = syn::parse_str("-x^2").unwrap();
        let ExprKind::Neg(inner) = e.kind else { panic!("not a negation") };
        assert!(matches!(inner.kind, ExprKind::Bin(BinOp::Pow, ..)));
    }

    /// A unit after a value is named wherever a value stands: a field, a parameter, a list
    /// entry; degrees get `deg(...)`.
    #[test]
    fn a_unit_after_a_value_is_named_everywhere() {
        let cases = [
            ("body b { mass: 2.0 kg, inertia: 0.1 }", "found the unit `kg`"),
            ("params { d: 300 mm, k: 1.0 }", "found the unit `mm`"),
            ("body b { mass: 1.0, inertia: 0.1, at: [0.0, 0.0, 97.2 deg] }", "an angle in degrees is `deg(value)`"),
        ];
        for (statement, want) in cases {
            let err = syn::parse_str::<Item>(statement).err().expect(statement).to_string();
            assert!(err.contains(want), "{statement}: {err}");
        }
    }

    /// An unknown statement names the closest keyword, or the DSL's name of a joint another
    /// program calls otherwise.
    #[test]
    fn unknown_statement_hint() {
        let err = syn::parse_str::<Item>("revolut a[0.0, 0.0] ~ b[0.0, 0.0];").err().unwrap().to_string();
        assert!(err.contains("did you mean `revolute`"), "{err}");
        // another program's name of a joint: ours
        let err =
            syn::parse_str::<Item>("prismatic a[0.0, 0.0] along [1.0, 0.0] ~ b[0.0, 0.0] along [1.0, 0.0];").err().unwrap().to_string();
        assert!(err.contains("found `prismatic` (the same joint is called `translational` here)"), "{err}");
    }
}

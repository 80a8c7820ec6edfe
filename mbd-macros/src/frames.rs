//! The seam between elements and formulations (DESIGN.md §3): how the bodies' frames depend on
//! the generalized coordinates.
//!
//! Joints, drivers and force elements (`elements/`, `forces/`) are written once against body
//! frames — a body's origin r_i, its rotation A_i, points r^P = r_i + A_i s′ and axes A_i u′ — and
//! against the velocity map q̇ = B(q) v. They never name a coordinate index. A formulation
//! ([`Coordinates`]) says what those frames are in terms of q; everything else (Φ_q, γ, h by
//! virtual power) follows in the symbolic graph (`formulation`).
//!
//! Nodes are created on demand, in the order the elements ask for them, so one mechanism always
//! builds the same graph (the emitted code and its snapshot depend on that order).

use std::collections::{BTreeSet, HashMap};

pub use crate::coordinates::Coordinates;
use crate::model::{BodyRef, Coord, Kink, Loc, MBin, MExpr, Model, Vel};
use crate::sym::{Func, Graph, Id, Node, Var};

/// One named row of Φ: the name (`"x"`, `"angle"`), its symbolic value and what it measures. A
/// kind's rows, their names and their units come from one function, so they cannot disagree.
pub struct Row {
    pub name: &'static str,
    pub value: Id,
    pub unit: RowUnit,
}

/// What a row of Φ measures, and so the unit of its multiplier λ (the work of λ along the row
/// is in J): a length (λ in N), an angle or a product of unit vectors (λ in N·m), or something
/// the macro does not know (a user constraint's expression).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RowUnit {
    Length,
    Angle,
    Unknown,
}

impl RowUnit {
    /// A row fixing or driving a body coordinate: a length for x, y, z, an angle for φ.
    pub fn of(c: Coord) -> Self {
        match c {
            Coord::X | Coord::Y | Coord::Z => RowUnit::Length,
            Coord::Phi => RowUnit::Angle,
            Coord::E0 | Coord::E1 | Coord::E2 | Coord::E3 => RowUnit::Unknown,
        }
    }

    /// The unit of the row's multiplier: `"N"`, `"N·m"`, or `""` when not known.
    pub fn multiplier(self) -> &'static str {
        match self {
            RowUnit::Length => "N",
            RowUnit::Angle => "N·m",
            RowUnit::Unknown => "",
        }
    }
}

/// The symbolic workspace in which elements build their rows and forces.
pub struct Builder<'m> {
    pub g: Graph,
    pub model: &'m Model,
    pub coordinates: Coordinates,
    /// The first row of each constraint in Φ, filled as the rows are built (Coulomb friction
    /// reads its joint's multipliers by them).
    pub first_rows: Vec<usize>,
    /// In joint coordinates, each body's pose and twist as functions of (q, v), built along the
    /// tree (`tree::frames`); empty in body coordinates, where they are q's and v's own entries.
    tree_frames: Vec<crate::tree::TreeFrame>,
}

impl<'m> Builder<'m> {
    pub fn new(model: &'m Model) -> Self {
        let coordinates = Coordinates::of(model);
        let mut b = Builder { g: Graph::new(), model, coordinates, first_rows: Vec::new(), tree_frames: Vec::new() };
        if let Some(tree) = &model.tree {
            b.tree_frames = crate::tree::frames(&mut b, tree);
        }
        b
    }

    /// In joint coordinates, body k's twist in global components (ṙ, ω), of which its link's
    /// screws are the partials by the link's velocities.
    pub fn global_twist(&self, k: usize) -> &[Id] {
        &self.tree_frames[k].global
    }

    /// In joint coordinates, where the articulated-body solve takes body k's link (in space;
    /// `None`: at its centre of mass).
    pub fn tree_articulation(&self, k: usize) -> Option<&crate::tree::Articulation> {
        self.tree_frames.get(k).and_then(|f| f.articulation.as_ref())
    }

    /// In joint coordinates, body k's J̇ v where the tree builds it by recursion (`None`: take
    /// the twist's rate along q̇).
    pub fn tree_bias(&self, k: usize) -> Option<&[Id]> {
        self.tree_frames.get(k).and_then(|f| f.bias.as_deref())
    }

    /// A builder in the model's bodies' own coordinates (x, y, φ per body, v = q̇; r, p and
    /// ṙ, ω′ in space), whatever the model's formulation: where joint coordinates write the
    /// elements' rows and forces before mapping them through the tree (`formulation::joint`).
    pub fn body_level(model: &'m Model) -> Self {
        let coordinates = match model.space {
            crate::model::Space::Planar => Coordinates::PlanarBody,
            crate::model::Space::Spatial => Coordinates::SpatialBody,
        };
        Builder { g: Graph::new(), model, coordinates, first_rows: Vec::new(), tree_frames: Vec::new() }
    }

    pub fn nq(&self) -> usize {
        match (&self.model.tree, self.coordinates.is_joint()) {
            (Some(tree), true) => tree.nq,
            _ => self.coordinates.per_body() * self.model.bodies.len(),
        }
    }

    pub fn nv(&self) -> usize {
        match (&self.model.tree, self.coordinates.is_joint()) {
            (Some(tree), true) => tree.nv,
            _ => self.coordinates.velocities_per_body() * self.model.bodies.len(),
        }
    }

    pub fn expr(&mut self, e: &MExpr) -> Id {
        match e {
            MExpr::Num(v) => self.g.num(*v),
            MExpr::Pi => self.g.num(std::f64::consts::PI),
            MExpr::T => self.g.var(Var::T),
            MExpr::Param(k) => self.g.var(Var::Param(*k as u16)),
            MExpr::Coord(b, c) => self.coord(*b, *c),
            MExpr::Vel(b, c) => self.velocity(*b, *c),
            MExpr::Neg(a) => {
                let a = self.expr(a);
                self.g.neg(a)
            }
            MExpr::Bin(op, a, b) => {
                let a = self.expr(a);
                let b = self.expr(b);
                match op {
                    MBin::Add => self.g.add(a, b),
                    MBin::Sub => self.g.sub(a, b),
                    MBin::Mul => self.g.mul(a, b),
                    MBin::Div => self.g.div(a, b),
                    MBin::Pow => self.g.pow(a, b),
                }
            }
            MExpr::Call(f, a) => {
                let a = self.expr(a);
                self.g.call(*f, a)
            }
            MExpr::Atan2(y, x) => {
                let y = self.expr(y);
                let x = self.expr(x);
                self.g.atan2(y, x)
            }
            MExpr::Kink(k, args) => {
                let a: Vec<Id> = args.iter().map(|a| self.expr(a)).collect();
                match k {
                    Kink::Abs => self.g.abs(a[0]),
                    Kink::Sign => self.g.sign(a[0]),
                    Kink::Min => self.g.min(a[0], a[1]),
                    Kink::Max => self.g.max(a[0], a[1]),
                    Kink::Clamp => self.g.clamp(a[0], a[1], a[2]),
                }
            }
            MExpr::If(cmp, e) => {
                let [a, b, x, y] = [0, 1, 2, 3].map(|i| self.expr(&e[i]));
                self.g.select(*cmp, a, b, x, y)
            }
        }
    }

    // --- the seam: frames in terms of q ------------------------------------------------------

    /// A frame quantity of a body — its origin's x, y (z), its angle φ or an Euler parameter —
    /// or its value on ground (0; e0 = 1).
    pub fn coord(&mut self, b: BodyRef, c: Coord) -> Id {
        match b {
            BodyRef::Ground => self.g.num(if c == Coord::E0 { 1.0 } else { 0.0 }),
            BodyRef::Body(k) if !self.tree_frames.is_empty() => self.tree_frames[k].pose[c.index()],
            BodyRef::Body(k) => self.g.var(Var::Q((self.coordinates.per_body() * k + c.index()) as u16)),
        }
    }

    /// A velocity of a body (ẋ, ẏ, φ̇; or ẋ, ẏ, ż, ω′), or 0 on ground.
    pub fn velocity(&mut self, b: BodyRef, c: Vel) -> Id {
        match b {
            BodyRef::Ground => self.g.num(0.0),
            BodyRef::Body(k) if !self.tree_frames.is_empty() => self.tree_frames[k].twist[c.index()],
            BodyRef::Body(k) => self.g.var(Var::Qd((self.coordinates.velocities_per_body() * k + c.index()) as u16)),
        }
    }

    /// A body's twist, linear in v: the velocity of its centre of mass (global: x, y in the
    /// plane, x, y, z in space) and its angular velocity in its own frame (φ̇ in the plane, ω′ in
    /// space). The mass matrix and the inertia forces are derived from it
    /// (`formulation::inertia`), so a formulation gives its bodies' twists and gets M(q) and the
    /// velocity-quadratic terms of h.
    pub fn twist(&mut self, b: BodyRef) -> (Vec<Id>, Vec<Id>) {
        let (linear, angular): (&[Vel], &[Vel]) = match self.coordinates {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => (&[Vel::Vx, Vel::Vy], &[Vel::Omega]),
            Coordinates::SpatialBody | Coordinates::SpatialJoint => (&[Vel::Vx, Vel::Vy, Vel::Vz], &[Vel::Wx, Vel::Wy, Vel::Wz]),
        };
        (linear.iter().map(|&c| self.velocity(b, c)).collect(), angular.iter().map(|&c| self.velocity(b, c)).collect())
    }

    /// q̇_i = (B(q) v)_i: the velocity map, one node per coordinate.
    pub fn coordinate_rates(&mut self) -> Vec<Id> {
        match self.coordinates {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => (0..self.nq()).map(|i| self.g.var(Var::Qd(i as u16))).collect(),
            Coordinates::SpatialJoint => {
                let tree = self.model.tree.as_ref().expect("joint coordinates have a tree");
                crate::tree::spatial::coordinate_rates(self, tree)
            }
            Coordinates::SpatialBody => {
                let mut rates = Vec::with_capacity(self.nq());
                for k in 0..self.model.bodies.len() {
                    let b = BodyRef::Body(k);
                    for c in [Vel::Vx, Vel::Vy, Vel::Vz] {
                        rates.push(self.velocity(b, c));
                    }
                    let w = [Vel::Wx, Vel::Wy, Vel::Wz].map(|c| self.velocity(b, c));
                    let lt = self.l_transpose(b);
                    let half = self.g.num(0.5);
                    for row in lt {
                        let d = self.dot(&row, &w);
                        rates.push(self.g.mul(half, d));
                    }
                }
                rates
            }
        }
    }

    /// Lᵀ(p) (4×3) of a spatial body, with ṗ = ½ Lᵀ ω′ (docs/formulation.md).
    fn l_transpose(&mut self, b: BodyRef) -> [[Id; 3]; 4] {
        let p = [Coord::E0, Coord::E1, Coord::E2, Coord::E3].map(|c| self.coord(b, c));
        crate::tree::spatial::l_transpose(self, p)
    }

    /// A body's angle φ (planar).
    pub fn angle(&mut self, b: BodyRef) -> Id {
        self.coord(b, Coord::Phi)
    }

    /// (sin φ, cos φ) of a body.
    pub fn sin_cos(&mut self, b: BodyRef) -> (Id, Id) {
        let phi = self.angle(b);
        (self.g.call(Func::Sin, phi), self.g.call(Func::Cos, phi))
    }

    /// A(φ) v′ for a body-fixed vector v′.
    pub fn rotate(&mut self, b: BodyRef, v: [Id; 2]) -> [Id; 2] {
        let (s, c) = self.sin_cos(b);
        let cx = self.g.mul(c, v[0]);
        let sy = self.g.mul(s, v[1]);
        let sx = self.g.mul(s, v[0]);
        let cy = self.g.mul(c, v[1]);
        [self.g.sub(cx, sy), self.g.add(sx, cy)]
    }

    /// r^P = r + A(φ) s′^P.
    pub fn point(&mut self, loc: &Loc) -> [Id; 2] {
        let local = [self.expr(&loc.point[0]), self.expr(&loc.point[1])];
        let rot = self.rotate(loc.body, local);
        let x = self.coord(loc.body, Coord::X);
        let y = self.coord(loc.body, Coord::Y);
        [self.g.add(x, rot[0]), self.g.add(y, rot[1])]
    }

    /// The global unit vector A(φ) v′/|v′|.
    pub fn unit(&mut self, b: BodyRef, v: &[MExpr]) -> [Id; 2] {
        let v = [self.expr(&v[0]), self.expr(&v[1])];
        let x2 = self.g.powi(v[0], 2);
        let y2 = self.g.powi(v[1], 2);
        let n2 = self.g.add(x2, y2);
        let norm = self.g.call(Func::Sqrt, n2);
        let u = [self.g.div(v[0], norm), self.g.div(v[1], norm)];
        self.rotate(b, u)
    }

    // --- vector algebra ----------------------------------------------------------------------

    /// Rotation by +90°: (−v_y, v_x).
    pub fn perp(&mut self, v: [Id; 2]) -> [Id; 2] {
        [self.g.neg(v[1]), v[0]]
    }

    /// aᵀb, for vectors of any length.
    pub fn dot(&mut self, a: &[Id], b: &[Id]) -> Id {
        let mut terms = a.iter().zip(b).map(|(&x, &y)| self.g.mul(x, y)).collect::<Vec<_>>().into_iter();
        let first = terms.next().unwrap_or_else(|| self.g.num(0.0));
        terms.fold(first, |acc, t| self.g.add(acc, t))
    }

    /// a − b.
    pub fn diff2(&mut self, a: [Id; 2], b: [Id; 2]) -> [Id; 2] {
        [self.g.sub(a[0], b[0]), self.g.sub(a[1], b[1])]
    }

    /// (dᵀd − L²)/(2L), d = r^P_j − r^P_i ([`Builder::distance_row`]).
    pub fn distance_between(&mut self, i: &Loc, j: &Loc, length: Id) -> Id {
        let pi = self.point(i);
        let pj = self.point(j);
        let d = self.diff2(pj, pi);
        self.distance_row(&d, length)
    }

    /// (dᵀd − L²)/(2L): zero where |d| = L, smooth where |d| is not (at d = 0), and equal to
    /// |d| − L to first order there, so its gradient is the unit vector along d and its
    /// multiplier a force in N (½(dᵀd − L²) would give N/m).
    pub fn distance_row(&mut self, d: &[Id], length: Id) -> Id {
        let dd = self.dot(d, d);
        let l2 = self.g.powi(length, 2);
        let r = self.g.sub(dd, l2);
        let two = self.g.num(2.0);
        let twice = self.g.mul(two, length);
        self.g.div(r, twice)
    }

    /// u_iᵀ (r^P_j − r^P_i): the slide of P_j along the unit axis of body i through P_i.
    pub fn slide(&mut self, i: &Loc, axis_i: &[MExpr], j: &Loc) -> Id {
        let pi = self.point(i);
        let pj = self.point(j);
        let ui = self.unit(i.body, axis_i);
        let d = self.diff2(pj, pi);
        self.dot(&ui, &d)
    }

    /// φ_j − φ_i.
    pub fn relative_angle(&mut self, i: BodyRef, j: BodyRef) -> Id {
        let fi = self.angle(i);
        let fj = self.angle(j);
        self.g.sub(fj, fi)
    }

    /// |x| as √(x²): a value only (nothing differentiates it by λ).
    pub fn abs(&mut self, x: Id) -> Id {
        let x2 = self.g.powi(x, 2);
        self.g.call(Func::Sqrt, x2)
    }

    /// The multiplier of row `row` of constraint `joint`.
    pub fn lambda(&mut self, joint: usize, row: usize) -> Id {
        let r = self.first_rows[joint] + row;
        self.g.var(Var::Lambda(r as u16))
    }

    // --- virtual power -------------------------------------------------------------------------

    /// ∂ṡ/∂v_k for every velocity k that ṡ depends on, s a function of q and t: the direction in
    /// which a force working on s acts (Jourdain). With B = I it is ∂s/∂q_k.
    pub fn gradient(&mut self, s: Id) -> Vec<(usize, Id)> {
        let mut cols = BTreeSet::new();
        collect_vars(&self.g, s, &mut cols, |v| if let Var::Q(i) = v { Some(i) } else { None });
        let partials: Vec<(usize, Id)> = cols.into_iter().map(|c| (c as usize, self.g.partial(s, Var::Q(c)))).collect();
        match self.coordinates {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => partials,
            Coordinates::SpatialBody => self.through_velocity_map(partials),
            Coordinates::SpatialJoint => self.through_tree_velocity_map(partials),
        }
    }

    /// (∂s/∂q) B as sparse (velocity, node) pairs, from the sparse ∂s/∂q: a body's position
    /// partials carry over; its Euler-parameter partials combine as (∂s/∂p) ½ Lᵀ(p) into ω′.
    fn through_velocity_map(&mut self, partials: Vec<(usize, Id)>) -> Vec<(usize, Id)> {
        let (nq, nv) = (self.coordinates.per_body(), self.coordinates.velocities_per_body());
        let mut out: std::collections::BTreeMap<usize, Id> = std::collections::BTreeMap::new();
        let half = self.g.num(0.5);
        for (i, d) in partials {
            let (k, c) = (i / nq, i % nq);
            let mut add = |b: &mut Self, col: usize, term: Id| {
                let sum = match out.get(&col) {
                    Some(&acc) => b.g.add(acc, term),
                    None => term,
                };
                out.insert(col, sum);
            };
            if c < 3 {
                add(self, nv * k + c, d);
            } else {
                let row = self.l_transpose(BodyRef::Body(k))[c - 3];
                let hd = self.g.mul(half, d);
                for (m, l) in row.into_iter().enumerate() {
                    let term = self.g.mul(hd, l);
                    add(self, nv * k + 3 + m, term);
                }
            }
        }
        out.into_iter().filter(|&(_, d)| !self.g.is_zero(d)).collect()
    }

    /// (∂s/∂q) B for joint coordinates: each coordinate's partial carried to the velocities its
    /// rate reads, B_ij = ∂q̇_i/∂v_j (q̇ = B(q) v along the tree: one entry per angle or stroke,
    /// ½ Lᵀ of a quaternion).
    fn through_tree_velocity_map(&mut self, partials: Vec<(usize, Id)>) -> Vec<(usize, Id)> {
        let rates = self.coordinate_rates();
        let mut out: std::collections::BTreeMap<usize, Id> = std::collections::BTreeMap::new();
        for (i, d) in partials {
            for (j, b) in velocity_partials(&mut self.g, rates[i]) {
                let term = self.g.mul(d, b);
                let sum = match out.get(&j) {
                    Some(&acc) => self.g.add(acc, term),
                    None => term,
                };
                out.insert(j, sum);
            }
        }
        out.into_iter().filter(|&(_, d)| !self.g.is_zero(d)).collect()
    }

    /// ṡ = s_q q̇ for a function of q only, q̇ = B(q) v.
    pub fn rate(&mut self, s: Id) -> Id {
        let qd = self.coordinate_rates();
        let seed = |v: Var| match v {
            Var::Q(i) => Some(qd[i as usize]),
            _ => None,
        };
        self.g.directional(s, &seed, &mut HashMap::new())
    }

    /// ṡ = s_q q̇ + s_t for a function of q and t.
    pub fn rate_with_time(&mut self, s: Id) -> Id {
        let qd = self.coordinate_rates();
        let one = self.g.num(1.0);
        let seed = |v: Var| match v {
            Var::Q(i) => Some(qd[i as usize]),
            Var::T => Some(one),
            _ => None,
        };
        self.g.directional(s, &seed, &mut HashMap::new())
    }

    /// h += −f ∂ṡ/∂v: the generalized force of a force f that does work −f δs.
    pub fn add_along(&mut self, h: &mut [Id], s: Id, f: Id) {
        for (k, ds) in self.gradient(s) {
            let w = self.g.mul(f, ds);
            h[k] = self.g.sub(h[k], w);
        }
    }
}

/// The indices of the variables selected by `pick` that a node depends on.
pub fn collect_vars(g: &Graph, root: Id, out: &mut BTreeSet<u16>, pick: impl Fn(Var) -> Option<u16>) {
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![root];
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        if let Node::Var(v) = g.node(id) {
            if let Some(i) = pick(v) {
                out.insert(i);
            }
        }
        stack.extend(g.children(id).into_iter().flatten());
    }
}

impl Builder<'_> {
    /// h += (∂ṙ_a/∂v)ᵀ w: the generalized force of component `a` (global) of a force w through
    /// body `body`'s origin (its centre of mass), by the body's twist (`twist`).
    pub fn add_to_origin_velocity(&mut self, h: &mut [Id], body: usize, a: usize, w: Id) {
        let (linear, _) = self.twist(BodyRef::Body(body));
        self.add_along_velocity(h, linear[a], w);
    }

    /// h += (∂φ̇/∂v)ᵀ τ: the generalized force of a torque τ on a planar body.
    pub fn add_to_angular_velocity(&mut self, h: &mut [Id], body: usize, tau: Id) {
        let (_, angular) = self.twist(BodyRef::Body(body));
        self.add_along_velocity(h, angular[0], tau);
    }

    /// h += Wᵀ T′ with ω′ = W v: the generalized force of a torque with body-frame components T′
    /// on a spatial body.
    pub fn add_to_body_angular_velocity(&mut self, h: &mut [Id], body: usize, torque: [Id; 3]) {
        let (_, angular) = self.twist(BodyRef::Body(body));
        for (w, t) in angular.into_iter().zip(torque) {
            self.add_along_velocity(h, w, t);
        }
    }

    /// h += (∂x/∂v)ᵀ w for a quantity x linear in v (a component of a twist).
    fn add_along_velocity(&mut self, h: &mut [Id], x: Id, w: Id) {
        for (i, d) in velocity_partials(&mut self.g, x) {
            let term = self.g.mul(d, w);
            h[i] = self.g.add(h[i], term);
        }
    }

    // --- any dimension: what forces need in the plane and in space ------------------------------

    /// The global position of a body point, 2 or 3 components.
    pub fn point_n(&mut self, loc: &Loc) -> Vec<Id> {
        match self.coordinates {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => self.point(loc).to_vec(),
            Coordinates::SpatialBody | Coordinates::SpatialJoint => self.point3(loc).to_vec(),
        }
    }

    /// A body-frame vector in global components, 2 or 3 of them.
    pub fn rotate_n(&mut self, b: BodyRef, v: Vec<Id>) -> Vec<Id> {
        match self.coordinates {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => self.rotate(b, [v[0], v[1]]).to_vec(),
            Coordinates::SpatialBody | Coordinates::SpatialJoint => self.rotate3(b, [v[0], v[1], v[2]]).to_vec(),
        }
    }

    /// |r^P_j − r^P_i|, in the plane or in space.
    pub fn length_between(&mut self, i: &Loc, j: &Loc) -> Id {
        let pi = self.point_n(i);
        let pj = self.point_n(j);
        let d = self.diff_n(&pj, &pi);
        let dd = self.dot(&d, &d);
        self.g.call(Func::Sqrt, dd)
    }

    /// a − b, any length.
    pub fn diff_n(&mut self, a: &[Id], b: &[Id]) -> Vec<Id> {
        a.iter().zip(b).map(|(&x, &y)| self.g.sub(x, y)).collect()
    }

    /// A body's position coordinates (x, y[, z]): where gravity does work.
    pub fn origin(&mut self, b: BodyRef) -> Vec<Id> {
        let cs: &[Coord] = match self.coordinates {
            Coordinates::PlanarBody | Coordinates::PlanarJoint => &[Coord::X, Coord::Y],
            Coordinates::SpatialBody | Coordinates::SpatialJoint => &[Coord::X, Coord::Y, Coord::Z],
        };
        cs.iter().map(|&c| self.coord(b, c)).collect()
    }

    // --- space: rotations, points and marker frames (Euler parameters) --------------------------

    /// A(p) = (2 e0² − 1) I + 2 (e eᵀ + e0 ẽ) of a spatial body; I on ground.
    pub fn rotation(&mut self, b: BodyRef) -> [[Id; 3]; 3] {
        let p = [Coord::E0, Coord::E1, Coord::E2, Coord::E3].map(|c| self.coord(b, c));
        rotation_matrix(&mut self.g, p)
    }

    /// A v′ for a body-frame 3-vector.
    pub fn rotate3(&mut self, b: BodyRef, v: [Id; 3]) -> [Id; 3] {
        let a = self.rotation(b);
        std::array::from_fn(|r| self.dot(&a[r], &v))
    }

    /// Aᵀ v: a global 3-vector in body components.
    pub fn unrotate3(&mut self, b: BodyRef, v: [Id; 3]) -> [Id; 3] {
        let a = self.rotation(b);
        std::array::from_fn(|c| {
            let col = [a[0][c], a[1][c], a[2][c]];
            self.dot(&col, &v)
        })
    }

    /// r^P = r + A s′ in space.
    pub fn point3(&mut self, loc: &Loc) -> [Id; 3] {
        let local = [0, 1, 2].map(|k| self.expr(&loc.point[k]));
        let rot = self.rotate3(loc.body, local);
        let origin = self.origin(loc.body);
        std::array::from_fn(|k| self.g.add(origin[k], rot[k]))
    }

    /// The unit triad (x, y, z) of a marker, global components: z′ = a′/|a′|, x′ the reference
    /// b′ made orthogonal to z′ (Gram–Schmidt) and normalized, y′ = z′ × x′, each turned by A.
    pub fn triad(&mut self, body: BodyRef, axis: &[MExpr], reference: &[MExpr]) -> [[Id; 3]; 3] {
        self.local_triad(axis, reference).map(|v| self.rotate3(body, v))
    }

    /// The unit triad (x′, y′, z′) of a marker in its body's frame (`triad`).
    pub fn local_triad(&mut self, axis: &[MExpr], reference: &[MExpr]) -> [[Id; 3]; 3] {
        let a = [0, 1, 2].map(|k| self.expr(&axis[k]));
        let r = [0, 1, 2].map(|k| self.expr(&reference[k]));
        let z = self.normalized(a);
        let rz = self.dot(&r, &z);
        let along: [Id; 3] = std::array::from_fn(|k| self.g.mul(rz, z[k]));
        let ortho: [Id; 3] = std::array::from_fn(|k| self.g.sub(r[k], along[k]));
        let x = self.normalized(ortho);
        let y = self.cross(z, x);
        [x, y, z]
    }

    fn normalized(&mut self, v: [Id; 3]) -> [Id; 3] {
        let n2 = self.dot(&v, &v);
        let n = self.g.call(Func::Sqrt, n2);
        v.map(|c| self.g.div(c, n))
    }

    /// a × b.
    pub fn cross(&mut self, a: [Id; 3], b: [Id; 3]) -> [Id; 3] {
        std::array::from_fn(|k| {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let p = self.g.mul(a[i], b[j]);
            let q = self.g.mul(a[j], b[i]);
            self.g.sub(p, q)
        })
    }
}

/// A(p) = (2 e0² − 1) I + 2 (e eᵀ + e0 ẽ) for Euler parameters p = (e0, e); I for p = (1, 0).
pub fn rotation_matrix(g: &mut Graph, [e0, e1, e2, e3]: [Id; 4]) -> [[Id; 3]; 3] {
    let e = [e1, e2, e3];
    let two = g.num(2.0);
    let one = g.num(1.0);
    let e00 = g.powi(e0, 2);
    let two_e00 = g.mul(two, e00);
    let diag = g.sub(two_e00, one);
    // ẽ: rows (0, −e3, e2), (e3, 0, −e1), (−e2, e1, 0)
    let zero = g.num(0.0);
    let (n1, n2, n3) = (g.neg(e1), g.neg(e2), g.neg(e3));
    let tilde = [[zero, n3, e2], [e3, zero, n1], [n2, e1, zero]];
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            let ee = g.mul(e[r], e[c]);
            let et = g.mul(e0, tilde[r][c]);
            let sum = g.add(ee, et);
            let twice = g.mul(two, sum);
            if r == c {
                g.add(diag, twice)
            } else {
                twice
            }
        })
    })
}

/// ∂x/∂v_i for each velocity v_i that x depends on.
pub fn velocity_partials(g: &mut Graph, x: Id) -> Vec<(usize, Id)> {
    let mut cols = BTreeSet::new();
    collect_vars(g, x, &mut cols, |v| if let Var::Qd(i) = v { Some(i) } else { None });
    let mut out = Vec::new();
    for i in cols {
        let d = g.partial(x, Var::Qd(i));
        if !g.is_zero(d) {
            out.push((i as usize, d));
        }
    }
    out
}

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

use crate::model::{BodyRef, Coord, Loc, MBin, MExpr, Model};
use crate::sym::{Func, Graph, Id, Node, Var};

/// How body frames depend on the generalized coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinates {
    /// Planar body coordinates (Nikravesh ch. 7): body k owns q[3k..3k+3] = (x, y, φ), the
    /// origin of its frame (its centre of mass) and its angle; B = I, so v = q̇.
    PlanarBody,
}

impl Coordinates {
    /// Coordinates per moving body.
    pub fn per_body(self) -> usize {
        match self {
            Coordinates::PlanarBody => 3,
        }
    }

    /// Whether q̇ = v (B = I): then virtual-power gradients are plain gradients in q.
    pub fn velocity_is_rate(self) -> bool {
        match self {
            Coordinates::PlanarBody => true,
        }
    }
}

/// One named row of Φ: the name (`"x"`, `"angle"`) and its symbolic value. A kind's rows and
/// their names come from one function, so their counts cannot disagree.
pub struct Row {
    pub name: &'static str,
    pub value: Id,
}

/// The symbolic workspace in which elements build their rows and forces.
pub struct Builder<'m> {
    pub g: Graph,
    pub model: &'m Model,
    pub coordinates: Coordinates,
    /// The first row of each constraint in Φ, filled as the rows are built (Coulomb friction
    /// reads its joint's multipliers by them).
    pub first_rows: Vec<usize>,
}

impl<'m> Builder<'m> {
    pub fn new(model: &'m Model) -> Self {
        Builder { g: Graph::new(), model, coordinates: Coordinates::PlanarBody, first_rows: Vec::new() }
    }

    pub fn nq(&self) -> usize {
        self.coordinates.per_body() * self.model.bodies.len()
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
        }
    }

    pub fn exprs<const N: usize>(&mut self, e: &[MExpr; N]) -> [Id; N] {
        std::array::from_fn(|k| self.expr(&e[k]))
    }

    // --- the seam: frames in terms of q ------------------------------------------------------

    /// A frame quantity of a body — x, y of its origin or its angle φ — or 0 on ground.
    pub fn coord(&mut self, b: BodyRef, c: Coord) -> Id {
        match (b, self.coordinates) {
            (BodyRef::Ground, _) => self.g.num(0.0),
            (BodyRef::Body(k), Coordinates::PlanarBody) => self.g.var(Var::Q((3 * k + c.index()) as u16)),
        }
    }

    /// The rate of a frame quantity (ẋ, ẏ, φ̇), or 0 on ground.
    pub fn velocity(&mut self, b: BodyRef, c: Coord) -> Id {
        match (b, self.coordinates) {
            (BodyRef::Ground, _) => self.g.num(0.0),
            (BodyRef::Body(k), Coordinates::PlanarBody) => self.g.var(Var::Qd((3 * k + c.index()) as u16)),
        }
    }

    /// q̇_i = (B(q) v)_i: the velocity map, one node per coordinate.
    pub fn coordinate_rates(&mut self) -> Vec<Id> {
        match self.coordinates {
            Coordinates::PlanarBody => (0..self.nq()).map(|i| self.g.var(Var::Qd(i as u16))).collect(),
        }
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
    pub fn unit(&mut self, b: BodyRef, v: &[MExpr; 2]) -> [Id; 2] {
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

    pub fn dot(&mut self, a: [Id; 2], b: [Id; 2]) -> Id {
        let x = self.g.mul(a[0], b[0]);
        let y = self.g.mul(a[1], b[1]);
        self.g.add(x, y)
    }

    /// a − b.
    pub fn diff2(&mut self, a: [Id; 2], b: [Id; 2]) -> [Id; 2] {
        [self.g.sub(a[0], b[0]), self.g.sub(a[1], b[1])]
    }

    /// ½ (dᵀd − L²), d = r^P_j − r^P_i.
    pub fn half_sq_distance(&mut self, i: &Loc, j: &Loc, length: Id) -> Id {
        let pi = self.point(i);
        let pj = self.point(j);
        let d = self.diff2(pj, pi);
        let dd = self.dot(d, d);
        let l2 = self.g.powi(length, 2);
        let r = self.g.sub(dd, l2);
        let half = self.g.num(0.5);
        self.g.mul(half, r)
    }

    /// u_iᵀ (r^P_j − r^P_i): the slide of P_j along the unit axis of body i through P_i.
    pub fn slide(&mut self, i: &Loc, axis_i: &[MExpr; 2], j: &Loc) -> Id {
        let pi = self.point(i);
        let pj = self.point(j);
        let ui = self.unit(i.body, axis_i);
        let d = self.diff2(pj, pi);
        self.dot(ui, d)
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
        debug_assert!(self.coordinates.velocity_is_rate(), "only B = I formulations exist yet");
        let mut cols = BTreeSet::new();
        collect_vars(&self.g, s, &mut cols, |v| if let Var::Q(i) = v { Some(i) } else { None });
        let mut memo = HashMap::new();
        cols.into_iter()
            .map(|c| {
                memo.clear();
                (c as usize, self.g.diff(s, Var::Q(c), &mut memo))
            })
            .collect()
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
    /// h[k] += w where v[k] is component `a` of the velocity of body `body`'s origin (its centre
    /// of mass): where a force at the centre works.
    pub fn add_to_origin_velocity(&mut self, h: &mut [Id], body: usize, a: usize, w: Id) {
        let k = match self.coordinates {
            Coordinates::PlanarBody => 3 * body + a,
        };
        h[k] = self.g.add(h[k], w);
    }

    /// h[k] += τ where v[k] is body `body`'s angular velocity: where a torque on it works.
    pub fn add_to_angular_velocity(&mut self, h: &mut [Id], body: usize, tau: Id) {
        let k = match self.coordinates {
            Coordinates::PlanarBody => 3 * body + 2,
        };
        h[k] = self.g.add(h[k], tau);
    }
}

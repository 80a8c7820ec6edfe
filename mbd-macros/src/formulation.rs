//! Stage 3: validated model → symbolic equations in planar body coordinates (docs/formulation.md).
//!
//! Body k owns `q[3k..3k+3] = (x, y, φ)`. This stage writes Φ(q, t) row by row into one shared
//! [`Graph`] and derives from it, exactly: the sparse Jacobian Φ_q, Φ_t, ν = −Φ_t and
//! γ = −𝒟(𝒟Φ) with 𝒟f = f_q q̇ + f_t (a directional derivative taken twice; no Hessian is formed).

use std::collections::{BTreeSet, HashMap};

use crate::model::{BodyRef, ConstraintKind, Coord, ForceKind, Loc, MBin, MExpr, Model};
use crate::sym::{Func, Graph, Id, Node, Var};

/// The symbolic equations of one mechanism.
pub struct Formulation {
    pub graph: Graph,
    pub nq: usize,
    pub nc: usize,
    /// Φ, one node per row.
    pub phi: Vec<Id>,
    /// Structurally non-zero entries of Φ_q as (row, column, node), row-major.
    pub jacobian: Vec<(usize, usize, Id)>,
    /// ν = −Φ_t, one node per row.
    pub nu: Vec<Id>,
    /// γ, one node per row.
    pub gamma: Vec<Id>,
    /// Initial guesses of q and q̇ (functions of the parameters).
    pub q0: Vec<Id>,
    pub qd0: Vec<Id>,
    /// Diagonal of the mass matrix: (m, m, J) per body.
    pub mass: Vec<Id>,
    /// h(q, q̇, t), one node per coordinate.
    pub h: Vec<Id>,
    /// Structural non-zeros of ∂h/∂q and ∂h/∂q̇ as (row, column, node).
    pub h_q: Vec<(usize, usize, Id)>,
    pub h_qd: Vec<(usize, usize, Id)>,
    /// Potential energy of gravity and springs, V(q).
    pub potential: Id,
    /// Coulomb friction forces, one node per coordinate, functions of q, q̇ and the multipliers λ
    /// (the joints' normal loads); kept out of h, which does not depend on λ.
    pub friction: Vec<Id>,
    /// Structural non-zeros of the friction forces' ∂/∂q and ∂/∂q̇ at given λ (for implicit
    /// integration; empty without Coulomb friction).
    pub friction_q: Vec<(usize, usize, Id)>,
    pub friction_qd: Vec<(usize, usize, Id)>,
    /// Power of the non-conservative forces, q̇ᵀh + dV/dt: what dampers, actuators, applied
    /// forces and friction put in (J/s). Then d(T + V)/dt = this + λᵀ Φ_q q̇.
    pub power: Id,
    /// Structural non-zeros of ∂(Φ_qᵀλ)/∂q (the constraints' geometric stiffness), with λ as
    /// variables.
    pub constraint_force_q: Vec<(usize, usize, Id)>,
}

impl Formulation {
    /// Whether Φ does not depend on t (then ν = 0 and solvers skip it).
    pub fn phi_t_is_zero(&self) -> bool {
        self.nu.iter().all(|&n| self.graph.is_zero(n))
    }
}

/// Builds symbolic expressions of a model into a graph.
struct Builder<'m> {
    g: Graph,
    model: &'m Model,
}

impl Builder<'_> {
    fn expr(&mut self, e: &MExpr) -> Id {
        match e {
            MExpr::Num(v) => self.g.num(*v),
            MExpr::Pi => self.g.num(std::f64::consts::PI),
            MExpr::T => self.g.var(Var::T),
            MExpr::Param(k) => self.g.var(Var::Param(*k as u16)),
            MExpr::Coord(b, c) => self.coord(*b, *c),
            MExpr::Vel(b, c) => match b {
                BodyRef::Ground => self.g.num(0.0),
                BodyRef::Body(k) => self.g.var(Var::Qd((3 * k + c.index()) as u16)),
            },
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

    /// A body coordinate: a variable, or 0 on ground.
    fn coord(&mut self, b: BodyRef, c: Coord) -> Id {
        match b {
            BodyRef::Ground => self.g.num(0.0),
            BodyRef::Body(k) => self.g.var(Var::Q((3 * k + c.index()) as u16)),
        }
    }

    /// (sin φ, cos φ) of a body.
    fn sin_cos(&mut self, b: BodyRef) -> (Id, Id) {
        let phi = self.coord(b, Coord::Phi);
        (self.g.call(Func::Sin, phi), self.g.call(Func::Cos, phi))
    }

    /// A(φ) v' for a body-fixed vector v'.
    fn rotate(&mut self, b: BodyRef, v: [Id; 2]) -> [Id; 2] {
        let (s, c) = self.sin_cos(b);
        let cx = self.g.mul(c, v[0]);
        let sy = self.g.mul(s, v[1]);
        let sx = self.g.mul(s, v[0]);
        let cy = self.g.mul(c, v[1]);
        [self.g.sub(cx, sy), self.g.add(sx, cy)]
    }

    /// r^P = r + A(φ) s'^P.
    fn point(&mut self, loc: &Loc) -> [Id; 2] {
        let local = [self.expr(&loc.point[0]), self.expr(&loc.point[1])];
        let rot = self.rotate(loc.body, local);
        let x = self.coord(loc.body, Coord::X);
        let y = self.coord(loc.body, Coord::Y);
        [self.g.add(x, rot[0]), self.g.add(y, rot[1])]
    }

    /// The global unit vector A(φ) v'/|v'|.
    fn unit(&mut self, b: BodyRef, v: &[MExpr; 2]) -> [Id; 2] {
        let v = [self.expr(&v[0]), self.expr(&v[1])];
        let x2 = self.g.powi(v[0], 2);
        let y2 = self.g.powi(v[1], 2);
        let n2 = self.g.add(x2, y2);
        let norm = self.g.call(Func::Sqrt, n2);
        let u = [self.g.div(v[0], norm), self.g.div(v[1], norm)];
        self.rotate(b, u)
    }

    fn perp(&mut self, v: [Id; 2]) -> [Id; 2] {
        [self.g.neg(v[1]), v[0]]
    }

    fn dot(&mut self, a: [Id; 2], b: [Id; 2]) -> Id {
        let x = self.g.mul(a[0], b[0]);
        let y = self.g.mul(a[1], b[1]);
        self.g.add(x, y)
    }

    fn diff2(&mut self, a: [Id; 2], b: [Id; 2]) -> [Id; 2] {
        [self.g.sub(a[0], b[0]), self.g.sub(a[1], b[1])]
    }

    /// ½ (dᵀd − L²)
    fn half_sq_distance(&mut self, i: &Loc, j: &Loc, length: Id) -> Id {
        let pi = self.point(i);
        let pj = self.point(j);
        let d = self.diff2(pj, pi);
        let dd = self.dot(d, d);
        let l2 = self.g.powi(length, 2);
        let r = self.g.sub(dd, l2);
        let half = self.g.num(0.5);
        self.g.mul(half, r)
    }

    /// ∂f/∂q_k for every coordinate k that f depends on.
    fn gradient(&mut self, f: Id) -> Vec<(usize, Id)> {
        let mut cols = BTreeSet::new();
        collect_vars(&self.g, f, &mut cols, |v| if let Var::Q(i) = v { Some(i) } else { None });
        let mut memo = HashMap::new();
        cols.into_iter()
            .map(|c| {
                memo.clear();
                (c as usize, self.g.diff(f, Var::Q(c), &mut memo))
            })
            .collect()
    }

    /// ḟ = f_q q̇ for a function of q only.
    fn rate(&mut self, f: Id) -> Id {
        let qd: Vec<Id> = (0..self.model.n_coordinates()).map(|i| self.g.var(Var::Qd(i as u16))).collect();
        let seed = |v: Var| match v {
            Var::Q(i) => Some(qd[i as usize]),
            _ => None,
        };
        self.g.directional(f, &seed, &mut HashMap::new())
    }

    /// h += −f ∂s/∂q: the generalized force of a force f that does work −f δs.
    fn add_along(&mut self, h: &mut [Id], s: Id, f: Id) {
        for (k, ds) in self.gradient(s) {
            let w = self.g.mul(f, ds);
            h[k] = self.g.sub(h[k], w);
        }
    }

    /// k (x − x0) + c ẋ + extra, each term only when declared.
    fn law(&mut self, x: Id, xdot: Id, k: &Option<MExpr>, x0: &MExpr, c: &Option<MExpr>, extra: &Option<MExpr>) -> (Id, Option<(Id, Id)>) {
        let mut f = self.g.num(0.0);
        let mut spring = None;
        if let Some(k) = k {
            let k = self.expr(k);
            let x0 = self.expr(x0);
            let stretch = self.g.sub(x, x0);
            let fk = self.g.mul(k, stretch);
            f = self.g.add(f, fk);
            spring = Some((k, stretch));
        }
        if let Some(c) = c {
            let c = self.expr(c);
            let fc = self.g.mul(c, xdot);
            f = self.g.add(f, fc);
        }
        if let Some(e) = extra {
            let e = self.expr(e);
            f = self.g.add(f, e);
        }
        (f, spring)
    }

    /// ½ k s² added to the potential energy.
    fn add_spring_energy(&mut self, v: Id, spring: Option<(Id, Id)>) -> Id {
        match spring {
            None => v,
            Some((k, s)) => {
                let s2 = self.g.powi(s, 2);
                let ks2 = self.g.mul(k, s2);
                let half = self.g.num(0.5);
                let e = self.g.mul(half, ks2);
                self.g.add(v, e)
            }
        }
    }

    /// The generalized forces h and the potential energy V of gravity and every force element.
    fn forces(&mut self) -> (Vec<Id>, Vec<Id>, Id) {
        let model = self.model;
        let zero = self.g.num(0.0);
        let mut h = vec![zero; model.n_coordinates()];
        let mut friction = vec![zero; model.n_coordinates()];
        let mut v = zero;
        if let Some(g) = &model.gravity {
            let g = [self.expr(&g[0]), self.expr(&g[1])];
            for (k, body) in model.bodies.iter().enumerate() {
                let m = self.expr(&body.mass);
                for a in 0..2 {
                    let w = self.g.mul(m, g[a]);
                    h[3 * k + a] = self.g.add(h[3 * k + a], w);
                    // V = −m gᵀ r
                    let r = self.g.var(Var::Q((3 * k + a) as u16));
                    let e = self.g.mul(w, r);
                    v = self.g.sub(v, e);
                }
            }
        }
        for element in &model.forces {
            match &element.kind {
                ForceKind::PointToPoint { i, j, k, length, c, force } => {
                    let pi = self.point(i);
                    let pj = self.point(j);
                    let d = self.diff2(pj, pi);
                    let dd = self.dot(d, d);
                    let l = self.g.call(Func::Sqrt, dd);
                    let ldot = self.rate(l);
                    let (f, spring) = self.law(l, ldot, k, length, c, force);
                    self.add_along(&mut h, l, f);
                    v = self.add_spring_energy(v, spring);
                }
                ForceKind::Rotational { i, j, k, angle, c, torque } => {
                    let fi = self.coord(*i, Coord::Phi);
                    let fj = self.coord(*j, Coord::Phi);
                    let theta = self.g.sub(fj, fi);
                    let thetadot = self.rate(theta);
                    let (tau, spring) = self.law(theta, thetadot, k, angle, c, torque);
                    self.add_along(&mut h, theta, tau);
                    v = self.add_spring_energy(v, spring);
                }
                ForceKind::Applied { at, force, local } => {
                    let mut f = [self.expr(&force[0]), self.expr(&force[1])];
                    if *local {
                        f = self.rotate(at.body, f);
                    }
                    let p = self.point(at);
                    // h_k += Fᵀ ∂r_P/∂q_k
                    for a in 0..2 {
                        for (k, dp) in self.gradient(p[a]) {
                            let w = self.g.mul(f[a], dp);
                            h[k] = self.g.add(h[k], w);
                        }
                    }
                }
                ForceKind::Torque { body, torque } => {
                    let tau = self.expr(torque);
                    let k = 3 * body + 2;
                    h[k] = self.g.add(h[k], tau);
                }
                ForceKind::RevoluteViscous { i, j, c } => {
                    let fi = self.coord(*i, Coord::Phi);
                    let fj = self.coord(*j, Coord::Phi);
                    let theta = self.g.sub(fj, fi);
                    let thetadot = self.rate(theta);
                    let (tau, _) = self.law(theta, thetadot, &None, &MExpr::Num(0.0), &Some(c.clone()), &None);
                    self.add_along(&mut h, theta, tau);
                }
                ForceKind::TranslationalViscous { i, axis_i, j, c } => {
                    let pi = self.point(i);
                    let pj = self.point(j);
                    let ui = self.unit(i.body, axis_i);
                    let d = self.diff2(pj, pi);
                    let s = self.dot(ui, d);
                    let sdot = self.rate(s);
                    let (f, _) = self.law(s, sdot, &None, &MExpr::Num(0.0), &Some(c.clone()), &None);
                    self.add_along(&mut h, s, f);
                }
                ForceKind::RevoluteCoulomb { i, j, mu, radius, slip, row } => {
                    let fi = self.coord(*i, Coord::Phi);
                    let fj = self.coord(*j, Coord::Phi);
                    let theta = self.g.sub(fj, fi);
                    let omega = self.rate(theta);
                    let (lx, ly) = (self.g.var(Var::Lambda(*row as u16)), self.g.var(Var::Lambda(*row as u16 + 1)));
                    let (lx2, ly2) = (self.g.powi(lx, 2), self.g.powi(ly, 2));
                    let load2 = self.g.add(lx2, ly2);
                    let load = self.g.call(Func::Sqrt, load2);
                    let radius = self.expr(radius);
                    let arm = self.g.mul(radius, load);
                    let tau = self.coulomb(mu, slip, arm, omega);
                    self.add_along(&mut friction, theta, tau);
                }
                ForceKind::TranslationalCoulomb { i, axis_i, j, mu, slip, bearing, row } => {
                    let pi = self.point(i);
                    let pj = self.point(j);
                    let ui = self.unit(i.body, axis_i);
                    let d = self.diff2(pj, pi);
                    let s = self.dot(ui, d);
                    let sdot = self.rate(s);
                    let ln = self.g.var(Var::Lambda(*row as u16));
                    let load = match bearing {
                        None => self.abs(ln),
                        Some(w) => {
                            let la = self.g.var(Var::Lambda(*row as u16 + 1));
                            let w = self.expr(w);
                            let half = self.g.num(0.5);
                            let f = self.g.mul(half, ln);
                            let m = self.g.div(la, w);
                            let (p1, p2) = (self.g.add(f, m), self.g.sub(f, m));
                            let (a1, a2) = (self.abs(p1), self.abs(p2));
                            self.g.add(a1, a2)
                        }
                    };
                    let f = self.coulomb(mu, slip, load, sdot);
                    self.add_along(&mut friction, s, f);
                }
            }
        }
        (h, friction, v)
    }

    /// |x| as √(x²): a value only (nothing differentiates by λ).
    fn abs(&mut self, x: Id) -> Id {
        let x2 = self.g.powi(x, 2);
        self.g.call(Func::Sqrt, x2)
    }

    /// Regularized Coulomb law μ N v / √(v² + v_s²): ±μN beyond the slip velocity v_s, linear
    /// (a stiff viscous law) through v = 0, smooth for the integrators.
    fn coulomb(&mut self, mu: &MExpr, slip: &MExpr, load: Id, v: Id) -> Id {
        let mu = self.expr(mu);
        let vs = self.expr(slip);
        let v2 = self.g.powi(v, 2);
        let vs2 = self.g.powi(vs, 2);
        let r2 = self.g.add(v2, vs2);
        let r = self.g.call(Func::Sqrt, r2);
        let ratio = self.g.div(v, r);
        let mn = self.g.mul(mu, load);
        self.g.mul(mn, ratio)
    }

    /// The rows of one constraint (docs/formulation.md).
    fn rows(&mut self, kind: &ConstraintKind) -> Vec<Id> {
        match kind {
            ConstraintKind::Revolute { i, j } => {
                let pi = self.point(i);
                let pj = self.point(j);
                self.diff2(pi, pj).to_vec()
            }
            ConstraintKind::Translational { i, axis_i, j, axis_j } => {
                let pi = self.point(i);
                let pj = self.point(j);
                let ui = self.unit(i.body, axis_i);
                let ni = self.perp(ui);
                let uj = self.unit(j.body, axis_j);
                let d = self.diff2(pj, pi);
                vec![self.dot(ni, d), self.dot(ni, uj)]
            }
            ConstraintKind::RevoluteRevolute { i, j, length } => {
                let l = self.expr(length);
                vec![self.half_sq_distance(i, j, l)]
            }
            ConstraintKind::RevoluteTranslational { i, j, axis_j, distance } => {
                let pi = self.point(i);
                let pj = self.point(j);
                let uj = self.unit(j.body, axis_j);
                let nj = self.perp(uj);
                let d = self.diff2(pi, pj);
                let n = self.dot(nj, d);
                let l = self.expr(distance);
                vec![self.g.sub(n, l)]
            }
            ConstraintKind::Rigid { i, j, angle } => {
                let pi = self.point(i);
                let pj = self.point(j);
                let mut rows = self.diff2(pi, pj).to_vec();
                let fi = self.coord(i.body, Coord::Phi);
                let fj = self.coord(j.body, Coord::Phi);
                let rel = self.g.sub(fj, fi);
                let a = self.expr(angle);
                rows.push(self.g.sub(rel, a));
                rows
            }
            ConstraintKind::Fix { body, coord, value: f } | ConstraintKind::Drive { body, coord, f } => {
                let q = self.coord(BodyRef::Body(*body), *coord);
                let f = self.expr(f);
                vec![self.g.sub(q, f)]
            }
            ConstraintKind::DriveAngle { i, j, f } => {
                let fi = self.coord(*i, Coord::Phi);
                let fj = self.coord(*j, Coord::Phi);
                let rel = self.g.sub(fj, fi);
                let f = self.expr(f);
                vec![self.g.sub(rel, f)]
            }
            ConstraintKind::DriveDistance { i, j, f } => {
                let f = self.expr(f);
                vec![self.half_sq_distance(i, j, f)]
            }
            ConstraintKind::User { expr } => vec![self.expr(expr)],
        }
    }
}

/// Derives the symbolic equations of a model.
pub fn formulate(model: &Model) -> Formulation {
    let mut b = Builder { g: Graph::new(), model };
    let nq = model.n_coordinates();
    let mut phi = Vec::new();
    for c in &b.model.constraints {
        let rows = b.rows(&c.kind);
        phi.extend(rows);
    }
    let mut q0 = Vec::with_capacity(nq);
    let mut qd0 = Vec::with_capacity(nq);
    let mut mass = Vec::with_capacity(nq);
    for body in &b.model.bodies {
        for k in 0..3 {
            q0.push(b.expr(&body.q0[k]));
            qd0.push(b.expr(&body.qd0[k]));
        }
        let m = b.expr(&body.mass);
        let j = b.expr(&body.inertia);
        mass.extend([m, m, j]);
    }
    let (h, friction, potential) = b.forces();
    // dV/dt = V_q q̇ + V_t
    let v_rate = b.rate(potential);
    let mut memo_v = HashMap::new();
    let v_t = b.g.diff(potential, Var::T, &mut memo_v);
    let mut power = b.g.add(v_rate, v_t);
    for (i, &hi) in h.iter().enumerate() {
        let qd = b.g.var(Var::Qd(i as u16));
        let p = b.g.mul(qd, hi);
        power = b.g.add(power, p);
    }
    let mut g = b.g;
    let h_q = sparse_derivative(&mut g, &h, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q);
    let h_qd = sparse_derivative(&mut g, &h, |v| if let Var::Qd(i) = v { Some(i) } else { None }, Var::Qd);
    let friction_q = sparse_derivative(&mut g, &friction, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q);
    let friction_qd = sparse_derivative(&mut g, &friction, |v| if let Var::Qd(i) = v { Some(i) } else { None }, Var::Qd);

    // Φ_q: differentiate each row only by the coordinates it contains; every other entry is a
    // structural zero.
    let jacobian = sparse_derivative(&mut g, &phi, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q);

    // ν = −Φ_t
    let mut memo_t = HashMap::new();
    let nu: Vec<Id> = phi
        .iter()
        .map(|&row| {
            let d = g.diff(row, Var::T, &mut memo_t);
            g.neg(d)
        })
        .collect();

    // γ = −𝒟(𝒟Φ), 𝒟 the total time derivative with q̈ = 0: one seed, one memo for all rows.
    let qd: Vec<Id> = (0..nq).map(|i| g.var(Var::Qd(i as u16))).collect();
    let one = g.num(1.0);
    let seed = |v: Var| match v {
        Var::Q(i) => Some(qd[i as usize]),
        Var::T => Some(one),
        Var::Qd(_) | Var::Param(_) | Var::Lambda(_) => None,
    };
    let mut memo = HashMap::new();
    let first: Vec<Id> = phi.iter().map(|&row| g.directional(row, &seed, &mut memo)).collect();
    let gamma: Vec<Id> = first
        .iter()
        .map(|&d1| {
            let d2 = g.directional(d1, &seed, &mut memo);
            g.neg(d2)
        })
        .collect();

    // (Φ_qᵀλ)_k = Σ_r λ_r D_rk, then its exact derivative by q.
    let zero = g.num(0.0);
    let mut constraint_force = vec![zero; nq];
    for &(r, c, d) in &jacobian {
        let l = g.var(Var::Lambda(r as u16));
        let term = g.mul(l, d);
        constraint_force[c] = g.add(constraint_force[c], term);
    }
    let constraint_force_q = sparse_derivative(&mut g, &constraint_force, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q);

    Formulation {
        nc: phi.len(),
        graph: g,
        nq,
        phi,
        jacobian,
        nu,
        gamma,
        q0,
        qd0,
        mass,
        h,
        h_q,
        h_qd,
        potential,
        power,
        friction,
        friction_q,
        friction_qd,
        constraint_force_q,
    }
}

/// The structural non-zeros of ∂rows/∂v, v ranging over the variables `pick` selects.
fn sparse_derivative(
    g: &mut Graph,
    rows: &[Id],
    pick: impl Fn(Var) -> Option<u16> + Copy,
    var: impl Fn(u16) -> Var,
) -> Vec<(usize, usize, Id)> {
    let mut out = Vec::new();
    for (r, &row) in rows.iter().enumerate() {
        let mut cols = BTreeSet::new();
        collect_vars(g, row, &mut cols, pick);
        let mut memo = HashMap::new();
        for c in cols {
            memo.clear();
            let d = g.diff(row, var(c), &mut memo);
            if !g.is_zero(d) {
                out.push((r, c as usize, d));
            }
        }
    }
    out
}

/// The indices of the variables selected by `pick` that a node depends on.
fn collect_vars(g: &Graph, root: Id, out: &mut BTreeSet<u16>, pick: impl Fn(Var) -> Option<u16>) {
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

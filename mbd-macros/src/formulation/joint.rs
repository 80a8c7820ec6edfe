//! Joint coordinates (`joint_coordinates;`, planar; docs/formulation.md, "Planar joint
//! coordinates"), in O(N) code per function.
//!
//! The elements write their rows, forces and energies in the bodies' own coordinates
//! (`Builder::body_level`), exactly as in body coordinates, where each reads a few bodies. Each
//! body's pose (x, y, φ), twist (ẋ, ẏ, φ̇ = J_b v) and the twist's rate at constant v (J̇_b v)
//! are expressions of (q, v) built parent by parent along the tree (`tree::poses`; O(1) new
//! nodes per body). The rows, forces and energies are the body level's with those put in
//! ([`Graph::import`]). The tree maps the bodies' wrenches w_b = (F_x, F_y, n) — a force through
//! the body's centre of mass and a moment — to generalized forces by one backward pass
//! ([`backward`]):
//!
//! g = Σ_b J_bᵀ w_b,  g_i = s_ω,i N_k + s_i · F_k  for a coordinate i of body k's link,
//!
//! with F_k the force of k's subtree and N_k its moment about r_k, both summed from the tips
//! (N_p += N_k + (r_k − r_p) × F_k), and (s_i, s_ω,i) = ∂(ṙ_k, φ̇_k)/∂v_i the link's screw. Then
//!
//! - h = Σ_b J_bᵀ (f_b − M_b J̇_b v), f_b the body level's forces (gravity and the elements);
//! - M x = Σ_b J_bᵀ M_b J_b x, a pass over the twists with x in v's place;
//! - M, ∂h/∂q, ∂h/∂v, ∂(M x)/∂q and the friction's derivatives are dense (every coordinate
//!   moves the bodies beyond it): they are emitted as their derivatives along a direction
//!   `dir` ([`TreeTerms`]), O(N) code each, and filled one column at a time at run time
//!   (O(N²) work: the size of the matrix). Their entries one by one would be O(N²) code at
//!   least — O(N³) through the sums — which a 120-link chain does not build.
//!
//! Only the cut joints' rows, drivers and user constraints are rows of Φ; their D, γ and
//! derivatives are taken entry by entry, as in body coordinates (a row reads the coordinates
//! on its loop).

use std::collections::{BTreeSet, HashMap};

use super::{
    accessors, constraint_derivatives, constraint_rows, forces, linear_terms, newton_terms, ForceTerms, Forces, Formulation, FrameNodes,
};
use crate::frames::Builder;
use crate::model::{BodyRef, Inertia, Model};
use crate::sym::{Graph, Id, Var};
use crate::tree::Tree;

/// The functions of a tree emitted as derivatives along a direction `dir` (`Var::Dir`), or as
/// products with it, for the dense matrices filled a column at a time.
pub struct TreeTerms {
    /// M x, x standing in the velocities' variables: `Dynamics::mass_times`.
    pub mass_x: Vec<Id>,
    /// (∂(M x)/∂q) dir: a column of `Dynamics::add_mass_derivative`.
    pub mass_x_dq: Vec<Id>,
    /// (∂h/∂q) dir and (∂h/∂v) dir.
    pub h_dq: Vec<Id>,
    pub h_dv: Vec<Id>,
    /// The friction forces' (∂/∂q) dir and (∂/∂v) dir; empty without Coulomb friction.
    pub friction_dq: Vec<Id>,
    pub friction_dv: Vec<Id>,
    /// Σ_b J_bᵀ w_b with body b's wrench w_b = dir[3b..3b + 3] (force x, y through its centre of
    /// mass, moment): `BodyFrames::add_body_wrench`.
    pub wrench: Vec<Id>,
    /// M⁻¹ dir by the articulated-body recursion ([`Kinematics::mass_solve`]):
    /// `Dynamics::solve_mass`.
    pub mass_solve: Vec<Id>,
    /// Its pivots, each with the first velocity of its link: every one must be positive.
    pub pivots: Vec<(usize, Id)>,
    /// M⁻¹ h by the same recursion with h's nodes for τ: one function for the accelerations
    /// without constraint forces, its sines and cosines computed once
    /// (`Dynamics::free_accelerations`).
    pub free_accelerations: Vec<Id>,
}

/// The tree's kinematics the passes read: each body's pose and its link's screws.
struct Kinematics<'t> {
    tree: &'t Tree,
    poses: Vec<[Id; 3]>,
    /// ∂(ẋ_k, ẏ_k, φ̇_k)/∂v_i for each coordinate i of body k's link.
    screws: Vec<Vec<[Id; 3]>>,
}

/// The symbolic equations of a model in joint coordinates.
pub fn formulate(model: &Model, tree: &Tree) -> Formulation {
    // The body level: rows, forces and energies as in body coordinates.
    let mut body = Builder::body_level(model);
    let (phi_body, row_names, row_units) = constraint_rows(&mut body);
    let zero_body = body.g.num(0.0);
    let body_forces = forces(&mut body, vec![zero_body; 3 * model.bodies.len()]);
    let first_rows = std::mem::take(&mut body.first_rows);

    // The joint level: the frames along the tree.
    let mut b = Builder::new(model);
    b.first_rows = first_rows.clone();
    let (nq, nv) = (b.nq(), b.nv());
    let frames = super::frame_nodes(&mut b);
    let kinematics = Kinematics::of(&mut b, tree, &frames);
    let mut memo = HashMap::new();
    let mut import = |b: &mut Builder, node: Id| {
        let var = |g: &mut Graph, v: Var| match v {
            Var::Q(i) => frames[i as usize / 3].pose[i as usize % 3],
            Var::Qd(i) => frames[i as usize / 3].twist[i as usize % 3],
            other => g.var(other),
        };
        b.g.import(&body.g, node, &var, &mut memo)
    };
    let phi: Vec<Id> = phi_body.iter().map(|&row| import(&mut b, row)).collect();
    let (q0, qd0) = crate::tree::initial(&mut b, tree);

    // h = Σ J_bᵀ (f_b − M_b J̇_b v); M x = Σ J_bᵀ M_b J_b x.
    let inertia = inertias(&mut b, model);
    let bias: Vec<[Id; 3]> = frames.iter().zip(&inertia).map(|(frame, m)| m.times(&mut b, frame.bias)).collect();
    let wrenches_of = |b: &mut Builder, import: &mut dyn FnMut(&mut Builder, Id) -> Id, generalized: &[Id]| -> Vec<[Id; 3]> {
        (0..bias.len())
            .map(|k| {
                std::array::from_fn(|c| {
                    let f = import(b, generalized[3 * k + c]);
                    b.g.sub(f, bias[k][c])
                })
            })
            .collect()
    };
    let Forces { h: h_body, friction: friction_body, potential, switches, force_velocities, alone_forces, .. } = body_forces;
    let wrenches = wrenches_of(&mut b, &mut import, &h_body);
    let h = kinematics.backward(&mut b, wrenches);
    let friction = if friction_body.iter().all(|&f| body.g.is_zero(f)) {
        vec![b.g.num(0.0); nv]
    } else {
        let wrenches: Vec<[Id; 3]> =
            (0..model.bodies.len()).map(|k| std::array::from_fn(|c| import(&mut b, friction_body[3 * k + c]))).collect();
        kinematics.backward(&mut b, wrenches)
    };
    let potential = import(&mut b, potential);
    let switches: Vec<(String, Id)> = switches.into_iter().map(|(name, s)| (name, import(&mut b, s))).collect();
    let momenta: Vec<[Id; 3]> = frames.iter().zip(&inertia).map(|(frame, m)| m.times(&mut b, frame.twist)).collect();
    let mass_x = kinematics.backward(&mut b, momenta);

    // Each element alone (its op counts; the velocities its force reaches, for naming it
    // behind a NaN): the inertia terms and its wrenches through the same pass.
    let base_h = {
        let zeros = vec![zero_body; 3 * model.bodies.len()];
        let wrenches = wrenches_of(&mut b, &mut import, &zeros);
        kinematics.backward(&mut b, wrenches)
    };
    let alone_forces: Vec<ForceTerms> = alone_forces
        .iter()
        .map(|alone| {
            let wrenches = wrenches_of(&mut b, &mut import, &alone.h);
            ForceTerms { h: kinematics.backward(&mut b, wrenches), h_q: Vec::new(), h_qd: Vec::new() }
        })
        .collect();
    let force_velocities = force_velocities.into_iter().map(|(name, reached)| (name, kinematics.reached(&reached))).collect();

    let power = super::power(&mut b, potential, &h);

    let (jacobian, nu, gamma) = constraint_derivatives(&mut b, &phi);
    // ∂(Dᵀλ)/∂q over the rows' coordinates (the Newton matrix's other terms are by columns).
    let (constraint_force_q, _, _) = newton_terms(&mut b, &jacobian, [&Vec::new(), &Vec::new()], [&Vec::new(), &Vec::new()]);
    let zero = b.g.num(0.0);
    let super::Linear { gamma_q, gamma_v, inputs, h_u } = linear_terms(&mut b, &gamma, &h, [&phi, &mass_x, &friction], &Vec::new());
    let (points, joint_coordinates) = accessors(&mut b);

    let terms = tree_terms(&mut b, &kinematics, &inertia, mass_x, &h, &friction);
    b.g.forget_partials();
    Formulation {
        nc: phi.len(),
        row_names,
        row_units,
        first_rows,
        nq,
        nv,
        phi,
        jacobian,
        nu,
        gamma,
        q0,
        qd0,
        mass: vec![zero; nv],
        mass_coupling: Vec::new(),
        mass_inverse: Vec::new(),
        mass_blocks: false,
        h,
        force_velocities,
        base_forces: ForceTerms { h: base_h, h_q: Vec::new(), h_qd: Vec::new() },
        alone_forces,
        h_q: Vec::new(),
        h_qd: Vec::new(),
        inputs,
        h_u,
        gamma_q,
        gamma_v,
        potential,
        switches,
        power,
        friction,
        friction_q: Vec::new(),
        friction_qd: Vec::new(),
        constraint_force_q,
        // generalized-α's Newton matrix is filled densely at run time (`NewtonMatrix`'s provided
        // `newton_matrix`) from the functions above
        stiffness: Vec::new(),
        damping: Vec::new(),
        points,
        joint_coordinates,
        frames,
        tree: Some(terms),
        graph: b.g,
    }
}

/// M x, and the dense functions as products with a direction ([`TreeTerms`]).
fn tree_terms(b: &mut Builder, kinematics: &Kinematics, inertia: &[BodyInertia], mass_x: Vec<Id>, h: &[Id], friction: &[Id]) -> TreeTerms {
    let nv = kinematics.tree.nq;
    let directions: Vec<Id> = (0..nv).map(|i| b.g.var(Var::Dir(i as u16))).collect();
    let (mass_solve, pivots) = kinematics.mass_solve(b, inertia, &directions);
    let (free_accelerations, _) = kinematics.mass_solve(b, inertia, h);
    let dirs: Vec<Id> = (0..nv).map(|i| b.g.var(Var::Dir(i as u16))).collect();
    // rows differentiated along dir, the coordinates (Var::Q) or the velocities (Var::Qd)
    let along = |b: &mut Builder, rows: &[Id], moving: fn(u16) -> Var| -> Vec<Id> {
        let seed = |v: Var| match v {
            Var::Q(i) | Var::Qd(i) if moving(i) == v => Some(dirs[i as usize]),
            _ => None,
        };
        let mut memo = HashMap::new();
        rows.iter().map(|&row| b.g.directional(row, &seed, &mut memo)).collect()
    };
    let has_friction = friction.iter().any(|&f| !b.g.is_zero(f));
    let wrenches: Vec<[Id; 3]> =
        (0..kinematics.poses.len()).map(|k| std::array::from_fn(|c| b.g.var(Var::Dir((3 * k + c) as u16)))).collect();
    TreeTerms {
        mass_x_dq: along(b, &mass_x, Var::Q),
        h_dq: along(b, h, Var::Q),
        h_dv: along(b, h, Var::Qd),
        friction_dq: if has_friction { along(b, friction, Var::Q) } else { Vec::new() },
        friction_dv: if has_friction { along(b, friction, Var::Qd) } else { Vec::new() },
        wrench: kinematics.backward(b, wrenches),
        mass_x,
        mass_solve,
        pivots,
        free_accelerations,
    }
}

/// A planar body's mass and moment of inertia about its centre of mass.
struct BodyInertia {
    mass: Id,
    inertia: Id,
}

impl BodyInertia {
    /// M_b x for a twist-shaped x = (ẋ, ẏ, φ̇): (m ẋ, m ẏ, J φ̇).
    fn times(&self, b: &mut Builder, x: [Id; 3]) -> [Id; 3] {
        [b.g.mul(self.mass, x[0]), b.g.mul(self.mass, x[1]), b.g.mul(self.inertia, x[2])]
    }
}

fn inertias(b: &mut Builder, model: &Model) -> Vec<BodyInertia> {
    model
        .bodies
        .iter()
        .map(|body| {
            let Inertia::Planar(j) = &body.inertia else { unreachable!("joint coordinates are planar (refused in space by the model)") };
            BodyInertia { mass: b.expr(&body.mass), inertia: b.expr(j) }
        })
        .collect()
}

/// a · b of two 3-vectors.
fn dot3(b: &mut Builder, x: [Id; 3], y: [Id; 3]) -> Id {
    b.dot(&x, &y)
}

/// A twist at r_p moved to r_k = r_p + d: (ṙ + ω ⊥d, ω).
fn twist_moved(b: &mut Builder, t: [Id; 3], d: [Id; 2]) -> [Id; 3] {
    let (wy, wx) = (b.g.mul(t[2], d[1]), b.g.mul(t[2], d[0]));
    [b.g.sub(t[0], wy), b.g.add(t[1], wx), t[2]]
}

/// A wrench at r_k moved to r_p = r_k − d: (F, n + d × F), the transpose of [`twist_moved`].
fn force_moved(b: &mut Builder, f: [Id; 3], d: [Id; 2]) -> [Id; 3] {
    let (a, c) = (b.g.mul(d[0], f[1]), b.g.mul(d[1], f[0]));
    let arm = b.g.sub(a, c);
    [f[0], f[1], b.g.add(f[2], arm)]
}

/// A symmetric 3×3 matrix of nodes (a planar inertia at a point): each entry below the diagonal
/// is the node above it, so each is computed once.
#[derive(Clone)]
struct Matrix([[Id; 3]; 3]);

impl Matrix {
    fn diagonal(b: &mut Builder, d: [Id; 3]) -> Self {
        let zero = b.g.num(0.0);
        Matrix(std::array::from_fn(|r| std::array::from_fn(|c| if r == c { d[r] } else { zero })))
    }

    /// The symmetric matrix of the entries `upper(r, c)` gives for r ≤ c.
    fn symmetric(b: &mut Builder, mut upper: impl FnMut(&mut Builder, usize, usize) -> Id) -> Self {
        let mut m = [[0; 3]; 3];
        for (r, c) in [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)] {
            m[r][c] = upper(b, r, c);
            m[c][r] = m[r][c];
        }
        Matrix(m)
    }

    fn times(&self, b: &mut Builder, x: [Id; 3]) -> [Id; 3] {
        std::array::from_fn(|r| b.dot(&self.0[r], &x))
    }

    fn add(&mut self, b: &mut Builder, other: &Matrix) {
        let (this, other) = (self.0, other.0);
        *self = Matrix::symmetric(b, |b, r, c| b.g.add(this[r][c], other[r][c]));
    }

    /// self −= w wᵀ / d.
    fn subtract_outer(&mut self, b: &mut Builder, w: [Id; 3], d: Id) {
        let one = b.g.num(1.0);
        let inverse = b.g.div(one, d);
        let scaled = w.map(|x| b.g.mul(x, inverse));
        let this = self.0;
        *self = Matrix::symmetric(b, |b, r, c| {
            let t = b.g.mul(w[r], scaled[c]);
            b.g.sub(this[r][c], t)
        });
    }

    /// Xᵀ I X for the twist transform X from r_p to r_p + d (what the inertia at r_p + d is
    /// at r_p): with X = [[1, 0, −d_y], [0, 1, d_x], [0, 0, 1]], the first two rows and columns
    /// keep theirs, and the third is moved: e = I (−d_y, d_x, 1)ᵀ, R_a2 = e_a (a < 2),
    /// R_22 = (−d_y, d_x, 1) · e.
    fn transformed(&self, b: &mut Builder, d: [Id; 2]) -> Matrix {
        let minus_dy = b.g.neg(d[1]);
        let arm = [minus_dy, d[0], b.g.num(1.0)];
        let e = self.times(b, arm);
        let last = b.dot(&arm, &e);
        let i = self.0;
        Matrix::symmetric(b, |_, r, c| match (r, c) {
            (2, 2) => last,
            (r, 2) => e[r],
            (r, c) => i[r][c],
        })
    }
}

/// What the articulated-body recursion's forward pass reads of a link: U = I^A S by columns,
/// D's factors and u.
struct Articulated {
    u_columns: Vec<[Id; 3]>,
    ldl: Ldl,
    u: Vec<Id>,
}

/// The LDLᵀ factors of a link's D = Sᵀ I^A S (1×1, or 3×3 for a free body), as nodes.
struct Ldl {
    /// Strictly lower L by rows.
    lower: Vec<Vec<Id>>,
    pivots: Vec<Id>,
}

impl Ldl {
    fn new(b: &mut Builder, d: Vec<Vec<Id>>) -> Self {
        let n = d.len();
        let (mut lower, mut pivots): (Vec<Vec<Id>>, Vec<Id>) = (vec![Vec::new(); n], Vec::new());
        for i in 0..n {
            for j in 0..i {
                let mut s = d[i][j];
                for k in 0..j {
                    let t = b.g.mul(lower[i][k], lower[j][k]);
                    let t = b.g.mul(t, pivots[k]);
                    s = b.g.sub(s, t);
                }
                let l = b.g.div(s, pivots[j]);
                lower[i].push(l);
            }
            let mut p = d[i][i];
            for k in 0..i {
                let l2 = b.g.mul(lower[i][k], lower[i][k]);
                let t = b.g.mul(l2, pivots[k]);
                p = b.g.sub(p, t);
            }
            pivots.push(p);
        }
        Ldl { lower, pivots }
    }

    /// L⁻¹ applied to each of n rows of 3-vectors (Uᵀ's rows: U's columns).
    fn forward(&self, b: &mut Builder, rows: &[[Id; 3]]) -> Vec<[Id; 3]> {
        let mut out: Vec<[Id; 3]> = Vec::with_capacity(rows.len());
        for (i, row) in rows.iter().enumerate() {
            let mut r = *row;
            for (k, &l) in self.lower[i].iter().enumerate() {
                r = std::array::from_fn(|c| {
                    let t = b.g.mul(l, out[k][c]);
                    b.g.sub(r[c], t)
                });
            }
            out.push(r);
        }
        out
    }

    /// D⁻¹ x.
    fn solve(&self, b: &mut Builder, x: &[Id]) -> Vec<Id> {
        let n = x.len();
        // L z = x, then y = D⁻¹ z, then Lᵀ y ← y
        let mut y: Vec<Id> = Vec::with_capacity(n);
        for (&xi, lower) in x.iter().zip(&self.lower) {
            let mut s = xi;
            for (&l, &yk) in lower.iter().zip(&y) {
                let t = b.g.mul(l, yk);
                s = b.g.sub(s, t);
            }
            y.push(s);
        }
        for (yi, &d) in y.iter_mut().zip(&self.pivots) {
            *yi = b.g.div(*yi, d);
        }
        for i in (0..n).rev() {
            for k in i + 1..n {
                let t = b.g.mul(self.lower[k][i], y[k]);
                y[i] = b.g.sub(y[i], t);
            }
        }
        y
    }
}

impl<'t> Kinematics<'t> {
    fn of(b: &mut Builder, tree: &'t Tree, frames: &[FrameNodes]) -> Self {
        let poses: Vec<[Id; 3]> = frames.iter().map(|f| f.pose).collect();
        // A link's screw: its body's pose differentiated by the link's own coordinates (the
        // body's twist per unit rate of each).
        let screws = tree
            .links
            .iter()
            .enumerate()
            .map(|(k, link)| (link.first..link.first + link.count).map(|i| poses[k].map(|x| b.g.partial(x, Var::Q(i as u16)))).collect())
            .collect();
        Kinematics { tree, poses, screws }
    }

    /// g = Σ_b J_bᵀ w_b for the bodies' wrenches w_b = (F_x, F_y, n): the moments of each
    /// subtree's wrenches about its root, summed from the tips, projected on each link's screws.
    fn backward(&self, b: &mut Builder, mut total: Vec<[Id; 3]>) -> Vec<Id> {
        let zero = b.g.num(0.0);
        let mut g = vec![zero; self.tree.nq];
        for &k in self.tree.order.iter().rev() {
            let link = &self.tree.links[k];
            let [fx, fy, n] = total[k];
            for (i, s) in self.screws[k].iter().enumerate() {
                let terms = [b.g.mul(s[0], fx), b.g.mul(s[1], fy), b.g.mul(s[2], n)];
                let xy = b.g.add(terms[0], terms[1]);
                g[link.first + i] = b.g.add(xy, terms[2]);
            }
            if let BodyRef::Body(p) = link.parent {
                // N_p += N_k + (r_k − r_p) × F_k
                let dx = b.g.sub(self.poses[k][0], self.poses[p][0]);
                let dy = b.g.sub(self.poses[k][1], self.poses[p][1]);
                let (a, c) = (b.g.mul(dx, fy), b.g.mul(dy, fx));
                let arm = b.g.sub(a, c);
                let moment = b.g.add(n, arm);
                total[p] = [b.g.add(total[p][0], fx), b.g.add(total[p][1], fy), b.g.add(total[p][2], moment)];
            }
        }
        g
    }

    /// x = M⁻¹ τ by the articulated-body algorithm (Featherstone; planar, each body's
    /// twist and wrench at its centre of mass in global axes), O(N) operations, and its pivots
    /// (the diagonal of each link's D = Sᵀ I^A S in LDLᵀ form: all positive where M is).
    ///
    /// Tips first: I^A_k = M_k + Σ_c X_cᵀ I^a_c X_c and p_k = Σ_c X_cᵀ p^a_c over k's children
    /// c, X_c the twist transform from r_k to r_c; then for k's link with screws S (3 × n),
    /// U = I^A S, D = Sᵀ U, u = τ_k − Sᵀ p_k, I^a = I^A − U D⁻¹ Uᵀ, p^a = p_k + U D⁻¹ u.
    /// Root first: a′ = X a_parent (a = 0 at ground), x_k = D⁻¹(u − Uᵀ a′), a_k = a′ + S x_k.
    fn mass_solve(&self, b: &mut Builder, inertia: &[BodyInertia], tau: &[Id]) -> (Vec<Id>, Vec<(usize, Id)>) {
        let tree = self.tree;
        let zero = b.g.num(0.0);
        let mut articulated: Vec<Matrix> = inertia.iter().map(|m| Matrix::diagonal(b, [m.mass, m.mass, m.inertia])).collect();
        let mut bias: Vec<[Id; 3]> = vec![[zero; 3]; inertia.len()];
        let mut links: Vec<Option<Articulated>> = (0..inertia.len()).map(|_| None).collect();
        let mut pivots = Vec::new();
        for &k in tree.order.iter().rev() {
            let link = &tree.links[k];
            let screws = &self.screws[k];
            let (mut child_inertia, mut child_bias) = (articulated[k].clone(), bias[k]);
            if !screws.is_empty() {
                let u_columns: Vec<[Id; 3]> = screws.iter().map(|s| articulated[k].times(b, *s)).collect();
                let d: Vec<Vec<Id>> = screws.iter().map(|s| u_columns.iter().map(|u| dot3(b, *s, *u)).collect()).collect();
                let ldl = Ldl::new(b, d);
                pivots.extend(ldl.pivots.iter().map(|&p| (link.first, p)));
                let u: Vec<Id> = screws
                    .iter()
                    .enumerate()
                    .map(|(i, s)| {
                        let sp = dot3(b, *s, bias[k]);
                        b.g.sub(tau[link.first + i], sp)
                    })
                    .collect();
                // I^a = I^A − U D⁻¹ Uᵀ = I^A − Σ_j w_j w_jᵀ / d_j with W = L⁻¹ Uᵀ.
                let w = ldl.forward(b, &u_columns);
                for (wj, &dj) in w.iter().zip(&ldl.pivots) {
                    child_inertia.subtract_outer(b, *wj, dj);
                }
                // p^a = p + U D⁻¹ u
                let x = ldl.solve(b, &u);
                for (column, &xj) in u_columns.iter().zip(&x) {
                    child_bias = std::array::from_fn(|r| {
                        let t = b.g.mul(column[r], xj);
                        b.g.add(child_bias[r], t)
                    });
                }
                links[k] = Some(Articulated { u_columns, ldl, u });
            }
            if let BodyRef::Body(p) = link.parent {
                let d = self.offset(b, k, p);
                let moved = child_inertia.transformed(b, d);
                articulated[p].add(b, &moved);
                let f = force_moved(b, child_bias, d);
                bias[p] = std::array::from_fn(|r| b.g.add(bias[p][r], f[r]));
            }
        }
        let mut x = vec![zero; tree.nq];
        let mut acceleration: Vec<[Id; 3]> = vec![[zero; 3]; inertia.len()];
        for &k in &tree.order {
            let link = &tree.links[k];
            let mut a = match link.parent {
                BodyRef::Ground => [zero; 3],
                BodyRef::Body(p) => {
                    let d = self.offset(b, k, p);
                    twist_moved(b, acceleration[p], d)
                }
            };
            if let Some(Articulated { u_columns, ldl, u }) = &links[k] {
                let rhs: Vec<Id> = u_columns
                    .iter()
                    .zip(u)
                    .map(|(column, &ui)| {
                        let ua = dot3(b, *column, a);
                        b.g.sub(ui, ua)
                    })
                    .collect();
                let xs = ldl.solve(b, &rhs);
                for (i, (&xi, s)) in xs.iter().zip(&self.screws[k]).enumerate() {
                    x[link.first + i] = xi;
                    a = std::array::from_fn(|r| {
                        let t = b.g.mul(s[r], xi);
                        b.g.add(a[r], t)
                    });
                }
            }
            acceleration[k] = a;
        }
        (x, pivots)
    }

    /// r_k − r_p.
    fn offset(&self, b: &mut Builder, k: usize, p: usize) -> [Id; 2] {
        [b.g.sub(self.poses[k][0], self.poses[p][0]), b.g.sub(self.poses[k][1], self.poses[p][1])]
    }

    /// The joint coordinates a wrench on the given body-level velocities (3k + c) reaches: those
    /// of every link from each such body down to ground.
    fn reached(&self, body_velocities: &[usize]) -> Vec<usize> {
        let mut out = BTreeSet::new();
        for k in body_velocities.iter().map(|&i| i / 3).collect::<BTreeSet<_>>() {
            let mut at = BodyRef::Body(k);
            while let BodyRef::Body(j) = at {
                let link = &self.tree.links[j];
                out.extend(link.first..link.first + link.count);
                at = link.parent;
            }
        }
        out.into_iter().collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::parse::MechanismDef;

    /// A chain of n links with a torsion spring at every pin, in joint coordinates.
    fn chain(n: usize) -> String {
        let mut s = String::from("C { joint_coordinates; gravity [0.0, -9.81]; revolute ground[0.0, 0.0] ~ l0[-0.05, 0.0];");
        for i in 0..n {
            s += &format!(" body l{i} {{ mass: 0.1, inertia: 8.3e-5, at: [{}, 0.0, 0.0] }}", 0.05 + 0.1 * i as f64);
        }
        for i in 1..n {
            s += &format!(
                " revolute l{}[0.05, 0.0] ~ l{i}[-0.05, 0.0]; rotational_spring l{} ~ l{i} {{ k: 1.0, angle: 0.0 }};",
                i - 1,
                i - 1
            );
        }
        s + "}"
    }

    /// Every generated function of a tree is O(N) code: doubling the chain at most doubles the
    /// macro's output, apart from the dense Newton pattern's N² indices (a few % here). Entry
    /// by entry the output grew as N³ (37 MB of tokens at 40 links).
    #[test]
    fn a_chains_code_grows_linearly() {
        let size = |n: usize| {
            let model = syn::parse_str::<MechanismDef>(&chain(n)).unwrap().validate().unwrap();
            crate::expand::generate(&model).unwrap().to_string().len() as f64
        };
        let (small, large) = (size(12), size(24));
        assert!(large / small < 2.2, "{small} then {large} characters: growth {}", large / small);
    }
}

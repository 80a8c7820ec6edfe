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
    accessors, constraint_derivatives, constraint_forces, constraint_rows, forces, linear_terms, ForceTerms, Forces, Formulation,
    FrameNodes, Rows,
};
use crate::frames::Builder;
use crate::model::{BodyRef, Model};
use crate::sym::{Graph, Id, Var};
use crate::tree::{Articulation, Tree};

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
    /// (∂(Dᵀλ)/∂q) B dir: a column of `ConstraintForces::constraint_force_q`, filled a column
    /// at a time as the other dense derivatives (entry by entry, K was O(N²) code where the
    /// rows reach most of the tree, a ladder's loops: a 0.5 MB debug frame for 101 bodies).
    pub constraint_force_dq: Vec<Id>,
    /// The friction forces' (∂/∂q) dir and (∂/∂v) dir; empty without Coulomb friction.
    pub friction_dq: Vec<Id>,
    pub friction_dv: Vec<Id>,
    /// M entry by entry (rows of nodes) by the composite-rigid-body algorithm, for trees of at
    /// most [`CRBA_VELOCITIES`] velocities: `Dynamics::add_mass_matrix`.
    pub mass_matrix: Option<Vec<Vec<Id>>>,
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
    /// For each body, the wrench its tree joint applies to it (about its centre of mass) and to
    /// its parent (about the parent's), global, 2 nt entries, v̇ standing in `dir` and with λ:
    /// `JointLoads::tree_joint_wrenches` ([`Kinematics::joint_wrenches`]).
    pub joint_wrenches: Vec<Vec<Id>>,
    /// M v̇ − h by one recursive Newton–Euler pass, v̇ standing in `dir`:
    /// `Dynamics::inverse_forces`.
    pub inverse: Vec<Id>,
}

/// The symbolic equations of a model in joint coordinates.
pub fn formulate(model: &Model, tree: &Tree) -> Formulation {
    // The body level: rows, forces and energies as in body coordinates.
    let mut body = Builder::body_level(model);
    let Rows { phi: phi_body, names: row_names, units: row_units, owners: joints } = constraint_rows(&mut body);
    let zero_body = body.g.num(0.0);
    let (np, nt) = (model.space.coordinates().len(), model.space.velocities().len());
    let body_forces = forces(&mut body, vec![zero_body; nt * model.bodies.len()], &joints);
    let body_jacobian = super::tangent(&mut body, &phi_body);
    let body_constraint = super::constraint_wrenches(&mut body, &body_jacobian);
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
            Var::Q(i) => frames[i as usize / np].pose[i as usize % np],
            Var::Qd(i) => frames[i as usize / nt].twist[i as usize % nt],
            other => g.var(other),
        };
        b.g.import(&body.g, node, &var, &mut memo)
    };
    let phi: Vec<Id> = phi_body.iter().map(|&row| import(&mut b, row)).collect();
    let (q0, qd0) = crate::tree::initial(&mut b, tree);

    // h = Σ J_bᵀ (f_b − M_b J̇_b v − ω′ × J′ω′); M x = Σ J_bᵀ M_b J_b x.
    let inertia = super::inertias(&mut b, model);
    let bias = inertia_bias(&mut b, &frames, &inertia);
    let wrenches_of = |b: &mut Builder, import: &mut dyn FnMut(&mut Builder, Id) -> Id, generalized: &[Id]| -> Vec<Vec<Id>> {
        (0..bias.len())
            .map(|k| {
                let wrench: Vec<Id> = (0..nt)
                    .map(|c| {
                        let f = import(b, generalized[nt * k + c]);
                        b.g.sub(f, bias[k][c])
                    })
                    .collect();
                kinematics.global_wrench(b, k, wrench)
            })
            .collect()
    };
    let Forces { h: h_body, friction: friction_body, potential, switches, time_switches, force_velocities, alone_forces, .. } = body_forces;
    let wrenches = wrenches_of(&mut b, &mut import, &h_body);
    let h = kinematics.backward(&mut b, wrenches.clone());
    // Each body's wrench of body-level components (F global, n′ in its frame), global.
    let mut global = |b: &mut Builder, body_level: &[Id]| -> Vec<Vec<Id>> {
        (0..model.bodies.len())
            .map(|k| {
                let wrench = (0..nt).map(|c| import(b, body_level[nt * k + c])).collect();
                kinematics.global_wrench(b, k, wrench)
            })
            .collect()
    };
    let friction_wrenches = (!friction_body.iter().all(|&f| body.g.is_zero(f))).then(|| global(&mut b, &friction_body));
    let friction = match &friction_wrenches {
        Some(wrenches) => kinematics.backward(&mut b, wrenches.clone()),
        None => vec![b.g.num(0.0); nv],
    };
    let constraint_wrenches = global(&mut b, &body_constraint);
    let inertial = kinematics.inertial_wrenches(&mut b, &frames, &inertia);
    // M v̇ − h in one backward pass (recursive Newton–Euler)
    let inverse = {
        let residual = inertial.iter().zip(&wrenches).map(|(i, w)| i.iter().zip(w).map(|(&x, &y)| b.g.sub(x, y)).collect()).collect();
        kinematics.backward(&mut b, residual)
    };
    let mut loads = vec![&wrenches[..], &constraint_wrenches[..]];
    loads.extend(friction_wrenches.as_deref());
    let joint_wrenches = kinematics.joint_wrenches(&mut b, &inertial, &loads);
    let potential = import(&mut b, potential);
    let switches: Vec<(String, Id)> = switches.into_iter().map(|(name, s)| (name, import(&mut b, s))).collect();
    let mass_x = kinematics.mass_times(&mut b, &frames, &inertia);

    let zeros = vec![zero_body; nt * model.bodies.len()];
    let (base_forces, alone_forces) =
        forces_alone(&mut b, &kinematics, |b, generalized| wrenches_of(b, &mut import, generalized), &zeros, &alone_forces);
    let force_velocities = force_velocities.into_iter().map(|(name, reached)| (name, kinematics.reached(&reached, nt))).collect();

    let power = super::power(&mut b, potential, &h);

    let (jacobian, nu, gamma) = constraint_derivatives(&mut b, &phi);
    let friction_lambda = super::multiplier_slope(&mut b.g, &friction);
    let zero = b.g.num(0.0);
    let super::Linear { gamma_q, gamma_v, inputs, h_u } = linear_terms(&mut b, &gamma, &h, [&phi, &mass_x, &friction], &Vec::new());
    let (points, joint_coordinates) = accessors(&mut b);

    let terms = TreeTerms { joint_wrenches, inverse, ..tree_terms(&mut b, &kinematics, &inertia, mass_x, &h, &friction, &jacobian) };
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
        base_forces,
        alone_forces,
        h_q: Vec::new(),
        h_qd: Vec::new(),
        inputs,
        h_u,
        gamma_q,
        gamma_v,
        potential,
        switches,
        time_switches,
        power,
        friction,
        friction_q: Vec::new(),
        friction_qd: Vec::new(),
        friction_lambda,
        constraint_force_q: Vec::new(),
        // generalized-α's Newton matrix is filled densely at run time (`NewtonMatrix`'s provided
        // `newton_matrix`) from the functions above
        stiffness: Vec::new(),
        damping: Vec::new(),
        points,
        joint_coordinates,
        bodies: inertia,
        constraint_wrenches,
        frames,
        tree: Some(terms),
        graph: b.g,
    }
}

/// Each element alone (its op counts; the velocities its force reaches, for naming it behind a
/// NaN): the inertia terms alone (`zeros`: no force) and each element's forces, their wrenches
/// (`wrenches`, of body-level generalized forces) through the same backward pass.
fn forces_alone(
    b: &mut Builder,
    kinematics: &Kinematics,
    mut wrenches: impl FnMut(&mut Builder, &[Id]) -> Vec<Vec<Id>>,
    zeros: &[Id],
    alone: &[ForceTerms],
) -> (ForceTerms, Vec<ForceTerms>) {
    let mut through = |b: &mut Builder, generalized: &[Id]| {
        let w = wrenches(b, generalized);
        ForceTerms { h: kinematics.backward(b, w), h_q: Vec::new(), h_qd: Vec::new() }
    };
    let base = through(b, zeros);
    (base, alone.iter().map(|a| through(b, &a.h)).collect())
}

/// Each body's inertia terms at constant v, M_b J̇_b v plus (in space) the gyroscopic moment
/// ω′ × J′ω′, as body coordinates hold a wrench (moment in the body's frame).
fn inertia_bias(b: &mut Builder, frames: &[FrameNodes], inertia: &[super::BodyInertia]) -> Vec<Vec<Id>> {
    frames
        .iter()
        .zip(inertia)
        .map(|(frame, m)| {
            let mut bias = m.times(b, &frame.bias);
            if let [_, _, _, wx, wy, wz] = frame.twist[..] {
                let jw = m.times(b, &frame.twist);
                let gyroscopic = b.cross([wx, wy, wz], [jw[3], jw[4], jw[5]]);
                for (c, g) in gyroscopic.into_iter().enumerate() {
                    bias[3 + c] = b.g.add(bias[3 + c], g);
                }
            }
            bias
        })
        .collect()
}

/// M x, and the dense functions as products with a direction ([`TreeTerms`]).
fn tree_terms(
    b: &mut Builder,
    kinematics: &Kinematics,
    inertia: &[super::BodyInertia],
    mass_x: Vec<Id>,
    h: &[Id],
    friction: &[Id],
    jacobian: &[(usize, usize, Id)],
) -> TreeTerms {
    let nv = kinematics.tree.nv;
    let directions: Vec<Id> = (0..nv).map(|i| b.g.var(Var::Dir(i as u16))).collect();
    let (mass_solve, pivots) = kinematics.mass_solve(b, inertia, &directions);
    let (free_accelerations, _) = kinematics.mass_solve(b, inertia, h);
    // rows differentiated along dir: the coordinates along q̇ = B(q) dir (the tangent; B = I in
    // the plane), or the velocities along dir
    let rates = b.coordinate_rates();
    let to_dir = |v: Var| match v {
        Var::Qd(i) => Some(directions[i as usize]),
        _ => None,
    };
    let mut memo = HashMap::new();
    let rates_along: Vec<Id> = rates.iter().map(|&rate| b.g.directional(rate, &to_dir, &mut memo)).collect();
    let along = |b: &mut Builder, rows: &[Id], coordinates: bool| -> Vec<Id> {
        let seed = |v: Var| match v {
            Var::Q(i) if coordinates => Some(rates_along[i as usize]),
            Var::Qd(i) if !coordinates => Some(directions[i as usize]),
            _ => None,
        };
        let mut memo = HashMap::new();
        rows.iter().map(|&row| b.g.directional(row, &seed, &mut memo)).collect()
    };
    let has_friction = friction.iter().any(|&f| !b.g.is_zero(f));
    let nt = kinematics.twist_size();
    let wrenches: Vec<Vec<Id>> =
        (0..kinematics.origins.len()).map(|k| (0..nt).map(|c| b.g.var(Var::Dir((nt * k + c) as u16))).collect()).collect();
    TreeTerms {
        mass_matrix: (nv <= CRBA_VELOCITIES).then(|| kinematics.mass_matrix(b, inertia)),
        mass_x_dq: along(b, &mass_x, true),
        h_dq: along(b, h, true),
        h_dv: along(b, h, false),
        constraint_force_dq: {
            let constraint_force = constraint_forces(b, jacobian);
            along(b, &constraint_force, true)
        },
        friction_dq: if has_friction { along(b, friction, true) } else { Vec::new() },
        friction_dv: if has_friction { along(b, friction, false) } else { Vec::new() },
        wrench: kinematics.backward(b, wrenches),
        mass_x,
        mass_solve,
        pivots,
        free_accelerations,
        joint_wrenches: Vec::new(),
        inverse: Vec::new(),
    }
}

/// The trees whose M is emitted entry by entry by the composite-rigid-body algorithm
/// (`Kinematics::mass_matrix`, O(N²) code); larger ones fill it a column at a time from M x.
pub const CRBA_VELOCITIES: usize = 32;

/// I s for a rigid body's or a subtree's inertia about the origin, (m, h, Ī), and a twist s =
/// (v, ω) there: (m v + ω × h, Ī ω + h × v); in the plane (v_x, v_y, ω) ↦ (m v_x − ω h_y,
/// m v_y + ω h_x, Ī ω + h_x v_y − h_y v_x).
fn composite_times(b: &mut Builder, mass: Id, h: &[Id], rotational: &[Vec<Id>], s: &[Id]) -> Vec<Id> {
    if let [vx, vy, w] = s[..] {
        let (mx, my) = (b.g.mul(mass, vx), b.g.mul(mass, vy));
        let (wy, wx) = (b.g.mul(w, h[1]), b.g.mul(w, h[0]));
        let (hxv, hyv) = (b.g.mul(h[0], vy), b.g.mul(h[1], vx));
        let iw = b.g.mul(rotational[0][0], w);
        let moment = b.g.sub(hxv, hyv);
        return vec![b.g.sub(mx, wy), b.g.add(my, wx), b.g.add(iw, moment)];
    }
    let (v, w) = ([s[0], s[1], s[2]], [s[3], s[4], s[5]]);
    let (swing, arm) = (b.cross(w, [h[0], h[1], h[2]]), b.cross([h[0], h[1], h[2]], v));
    let force = (0..3).map(|c| {
        let mv = b.g.mul(mass, v[c]);
        b.g.add(mv, swing[c])
    });
    let force: Vec<Id> = force.collect();
    let moment: Vec<Id> = (0..3)
        .map(|c| {
            let iw = b.dot(&rotational[c], &w);
            b.g.add(iw, arm[c])
        })
        .collect();
    force.into_iter().chain(moment).collect()
}

/// A twist (ṙ, ω) at r_p moved to r_k = r_p + d: (ṙ + ω × d, ω), global components; in the
/// plane ω × d = ω (−d_y, d_x).
fn twist_moved(b: &mut Builder, t: &[Id], d: &[Id]) -> Vec<Id> {
    let mut out = t.to_vec();
    if let [dx, dy] = d[..] {
        let (wy, wx) = (b.g.mul(t[2], dy), b.g.mul(t[2], dx));
        out[0] = b.g.sub(t[0], wy);
        out[1] = b.g.add(t[1], wx);
    } else {
        let swing = b.cross([t[3], t[4], t[5]], [d[0], d[1], d[2]]);
        for c in 0..3 {
            out[c] = b.g.add(t[c], swing[c]);
        }
    }
    out
}

/// A wrench (F, N) at r_k moved to r_p = r_k − d: (F, N + d × F), the transpose of
/// [`twist_moved`].
fn force_moved(b: &mut Builder, f: &[Id], d: &[Id]) -> Vec<Id> {
    let mut out = f.to_vec();
    if let [dx, dy] = d[..] {
        let (a, c) = (b.g.mul(dx, f[1]), b.g.mul(dy, f[0]));
        let arm = b.g.sub(a, c);
        out[2] = b.g.add(f[2], arm);
    } else {
        let arm = b.cross([d[0], d[1], d[2]], [f[0], f[1], f[2]]);
        for c in 0..3 {
            out[3 + c] = b.g.add(f[3 + c], arm[c]);
        }
    }
    out
}

/// A symmetric matrix of nodes (a body's inertia at a point, 3×3 in the plane, 6×6 in space):
/// each entry below the diagonal is the node above it, so each is computed once.
#[derive(Clone)]
struct Matrix(Vec<Vec<Id>>);

impl Matrix {
    /// The symmetric n×n matrix of the entries `upper(r, c)` gives for r ≤ c.
    fn symmetric(b: &mut Builder, n: usize, mut upper: impl FnMut(&mut Builder, usize, usize) -> Id) -> Self {
        let mut m = vec![vec![0; n]; n];
        for (r, c) in (0..n).flat_map(|r| (r..n).map(move |c| (r, c))) {
            m[r][c] = upper(b, r, c);
            m[c][r] = m[r][c];
        }
        Matrix(m)
    }

    fn times(&self, b: &mut Builder, x: &[Id]) -> Vec<Id> {
        self.0.iter().map(|row| b.dot(row, x)).collect()
    }

    fn add(&mut self, b: &mut Builder, other: &Matrix) {
        let this = std::mem::take(&mut self.0);
        *self = Matrix::symmetric(b, this.len(), |b, r, c| b.g.add(this[r][c], other.0[r][c]));
    }

    /// Row and column j set to zero.
    fn clear(&mut self, b: &mut Builder, j: usize) {
        let zero = b.g.num(0.0);
        for (r, row) in self.0.iter_mut().enumerate() {
            row[j] = zero;
            if r == j {
                row.iter_mut().for_each(|x| *x = zero);
            }
        }
    }

    /// self −= w wᵀ / d.
    fn subtract_outer(&mut self, b: &mut Builder, w: &[Id], d: Id) {
        let one = b.g.num(1.0);
        let inverse = b.g.div(one, d);
        let scaled: Vec<Id> = w.iter().map(|&x| b.g.mul(x, inverse)).collect();
        let this = std::mem::take(&mut self.0);
        *self = Matrix::symmetric(b, this.len(), |b, r, c| {
            let t = b.g.mul(w[r], scaled[c]);
            b.g.sub(this[r][c], t)
        });
    }

    /// Xᵀ I X for the twist transform X from r_p to r_p + d ([`twist_moved`]): what the inertia
    /// at r_p + d is at r_p. Column c of X is the unit twist e_c moved; the constant entries of
    /// X fold, so the rows and columns of the linear velocities keep their entries.
    fn transformed(&self, b: &mut Builder, d: &[Id]) -> Matrix {
        let n = self.0.len();
        let columns: Vec<Vec<Id>> = (0..n)
            .map(|c| {
                let unit: Vec<Id> = (0..n).map(|r| b.g.num(if r == c { 1.0 } else { 0.0 })).collect();
                twist_moved(b, &unit, d)
            })
            .collect();
        let moved: Vec<Vec<Id>> = columns.iter().map(|x| self.times(b, x)).collect();
        Matrix::symmetric(b, n, |b, r, c| b.dot(&columns[r], &moved[c]))
    }
}

/// j where the screw s is the unit vector e_j (its entries the constants 0 and one 1).
fn unit(b: &Builder, s: &[Id]) -> Option<usize> {
    let ones: Vec<usize> = (0..s.len()).filter(|&j| b.g.as_const(s[j]) == Some(1.0)).collect();
    (ones.len() == 1 && s.iter().enumerate().all(|(j, &x)| j == ones[0] || b.g.is_zero(x))).then(|| ones[0])
}

/// What the articulated-body recursion's forward pass reads of a link: U = I^A S by columns,
/// D's factors and u.
struct Articulated {
    u_columns: Vec<Vec<Id>>,
    ldl: Ldl,
    u: Vec<Id>,
}

/// The LDLᵀ factors of a link's D = Sᵀ I^A S (its velocities square), as nodes.
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

    /// L⁻¹ applied to each of the rows (Uᵀ's rows: U's columns).
    fn forward(&self, b: &mut Builder, rows: &[Vec<Id>]) -> Vec<Vec<Id>> {
        let mut out: Vec<Vec<Id>> = Vec::with_capacity(rows.len());
        for (i, row) in rows.iter().enumerate() {
            let mut r = row.clone();
            for (k, &l) in self.lower[i].iter().enumerate() {
                for (c, x) in r.iter_mut().enumerate() {
                    let t = b.g.mul(l, out[k][c]);
                    *x = b.g.sub(*x, t);
                }
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
        // times 1/d, the node `subtract_outer` made: one division per pivot in the recursion
        let one = b.g.num(1.0);
        for (yi, &d) in y.iter_mut().zip(&self.pivots) {
            let inverse = b.g.div(one, d);
            *yi = b.g.mul(*yi, inverse);
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

/// The tree's kinematics the passes read: each body's origin (its centre of mass), its rotation
/// in space, and its link's screws.
struct Kinematics<'t> {
    tree: &'t Tree,
    origins: Vec<Vec<Id>>,
    rotations: Vec<Option<[[Id; 3]; 3]>>,
    /// ∂(ṙ_k, ω_k)/∂v_i (global; (ẋ, ẏ, φ̇) in the plane) for each velocity i of body k's link.
    screws: Vec<Vec<Vec<Id>>>,
    /// Where the articulated-body solve takes each link ([`Articulation`]): at its joint point
    /// (in the plane a revolute link at its pin, screw (0, 0, ±1)); elsewhere (a slide, a free
    /// body in the plane) at the centre of mass with the screws above.
    articulation: Vec<Articulation>,
}

impl<'t> Kinematics<'t> {
    fn of(b: &mut Builder, tree: &'t Tree, frames: &[FrameNodes]) -> Self {
        let spatial = b.model.space == crate::model::Space::Spatial;
        let lin = if spatial { 3 } else { 2 };
        let origins = frames.iter().map(|f| f.pose[..lin].to_vec()).collect();
        let rotations = (0..frames.len()).map(|k| spatial.then(|| b.rotation(BodyRef::Body(k)))).collect();
        // A link's screw: its body's global twist per unit rate of each of its velocities.
        let screws: Vec<Vec<Vec<Id>>> = tree
            .links
            .iter()
            .enumerate()
            .map(|(k, link)| {
                let global = b.global_twist(k).to_vec();
                (link.first_v..link.first_v + link.count_v)
                    .map(|i| global.iter().map(|&x| b.g.partial(x, Var::Qd(i as u16))).collect())
                    .collect()
            })
            .collect();
        let articulation = (0..frames.len())
            .map(|k| match b.tree_articulation(k) {
                Some(a) => a.clone(),
                None => Articulation { origin: frames[k].pose[..lin].to_vec(), screws: screws[k].clone(), rotated: None },
            })
            .collect();
        Kinematics { tree, origins, rotations, screws, articulation }
    }

    /// Entries of a twist: 3 in the plane, 6 in space.
    fn twist_size(&self) -> usize {
        if self.rotations.first().is_some_and(Option::is_some) {
            6
        } else {
            3
        }
    }

    /// A body wrench as body coordinates have it (F global, n′ in the body's frame in space)
    /// in global components (F, A n′).
    fn global_wrench(&self, b: &mut Builder, k: usize, w: Vec<Id>) -> Vec<Id> {
        super::global_wrench(b, self.rotations[k].as_ref(), w)
    }

    /// g = Σ_b J_bᵀ w_b for the bodies' wrenches w_b = (F, N) at their centres of mass, global:
    /// the wrench of each subtree about its root, summed from the tips, projected on each
    /// link's screws.
    fn backward(&self, b: &mut Builder, total: Vec<Vec<Id>>) -> Vec<Id> {
        let zero = b.g.num(0.0);
        let mut g = vec![zero; self.tree.nv];
        self.subtrees(b, total, |b, k, wrench| {
            for (i, s) in self.screws[k].iter().enumerate() {
                g[self.tree.links[k].first_v + i] = b.dot(s, wrench);
            }
        });
        g
    }

    /// Each subtree's wrench about its root's centre of mass, from the bodies' wrenches (F, N)
    /// at their centres, summed from the tips (N_p += N_k + (r_k − r_p) × F_k); `complete`
    /// sees each subtree's as soon as it is summed.
    fn subtrees(&self, b: &mut Builder, mut total: Vec<Vec<Id>>, mut complete: impl FnMut(&mut Builder, usize, &[Id])) -> Vec<Vec<Id>> {
        for &k in self.tree.order.iter().rev() {
            let link = &self.tree.links[k];
            complete(b, k, &total[k]);
            if let BodyRef::Body(p) = link.parent {
                // N_p += N_k + (r_k − r_p) × F_k
                let d = self.offset(b, k, p);
                let moved = force_moved(b, &total[k], &d);
                total[p] = total[p].iter().zip(&moved).map(|(&x, &y)| b.g.add(x, y)).collect();
            }
        }
        total
    }

    /// Each body's M_b J_b v̇ (global, at its centre of mass), v̇ standing in `dir`: J_b v̇ is the
    /// twist's derivative along v̇ (the twist is linear in v).
    fn inertial_wrenches(&self, b: &mut Builder, frames: &[FrameNodes], inertia: &[super::BodyInertia]) -> Vec<Vec<Id>> {
        let directions: Vec<Id> = (0..self.tree.nv).map(|i| b.g.var(Var::Dir(i as u16))).collect();
        let seed = |v: Var| match v {
            Var::Qd(i) => Some(directions[i as usize]),
            _ => None,
        };
        let mut memo = HashMap::new();
        frames
            .iter()
            .zip(inertia)
            .enumerate()
            .map(|(k, (frame, m))| {
                let acceleration: Vec<Id> = frame.twist.iter().map(|&x| b.g.directional(x, &seed, &mut memo)).collect();
                let inertial = m.times(b, &acceleration);
                self.global_wrench(b, k, inertial)
            })
            .collect()
    }

    /// What each tree joint transmits (`mbd::JointLoads::tree_joint_wrenches`), by Newton–Euler
    /// over the subtree of the body k it carries: the wrench on k about its centre of mass,
    ///
    /// W_k = Σ_{b ∈ subtree(k)} (M_b J_b v̇ + M_b J̇_b v + ω_b × J_b ω_b − f_b) moved to r_k,
    ///
    /// from `inertial` (M_b J_b v̇, [`inertial_wrenches`](Self::inertial_wrenches)) and the
    /// `loads` on each body (applied forces less the inertia bias, friction, the rows' D_bᵀλ;
    /// global); then −W_k moved to its parent's centre of mass (zeros for ground). 2 nt entries
    /// per body.
    fn joint_wrenches(&self, b: &mut Builder, inertial: &[Vec<Id>], loads: &[&[Vec<Id>]]) -> Vec<Vec<Id>> {
        let residual: Vec<Vec<Id>> = (0..inertial.len())
            .map(|k| {
                let mut sum = inertial[k].clone();
                for load in loads {
                    sum = sum.iter().zip(&load[k]).map(|(&x, &y)| b.g.sub(x, y)).collect();
                }
                sum
            })
            .collect();
        let total = self.subtrees(b, residual, |_, _, _| {});
        let zero = b.g.num(0.0);
        (0..total.len())
            .map(|k| {
                let on_parent = match self.tree.links[k].parent {
                    BodyRef::Body(p) => {
                        let d = self.offset(b, k, p);
                        force_moved(b, &total[k], &d).into_iter().map(|x| b.g.neg(x)).collect()
                    }
                    BodyRef::Ground => vec![zero; total[k].len()],
                };
                total[k].iter().copied().chain(on_parent).collect()
            })
            .collect()
    }

    /// A body's inertia at its centre of mass in global components: diag(m, m, J), or
    /// [[m I, 0], [0, A J′ Aᵀ]].
    fn global_inertia(&self, b: &mut Builder, k: usize, m: &super::BodyInertia) -> Matrix {
        let zero = b.g.num(0.0);
        let Some(a) = &self.rotations[k] else {
            let d = [m.mass, m.mass, m.inertia[0][0]];
            return Matrix::symmetric(b, 3, |_, r, c| if r == c { d[r] } else { zero });
        };
        let aj: Vec<Vec<Id>> =
            (0..3).map(|r| (0..3).map(|c| b.dot(&a[r], &[m.inertia[0][c], m.inertia[1][c], m.inertia[2][c]])).collect()).collect();
        Matrix::symmetric(b, 6, |b, r, c| match (r, c) {
            (r, c) if r < 3 && c < 3 => {
                if r == c {
                    m.mass
                } else {
                    zero
                }
            }
            (r, c) if r < 3 || c < 3 => zero,
            (r, c) => b.dot(&aj[r - 3], &a[c - 3]),
        })
    }

    /// x = M⁻¹ τ by the articulated-body algorithm (Featherstone; each link's twists and
    /// wrenches in global components at its point o_k, [`Articulation`]: the joint point in
    /// space, the centre of mass in the plane), O(N) operations, and its pivots (the diagonal of
    /// each link's D = Sᵀ I^A S in LDLᵀ form: all positive where M is).
    ///
    /// Tips first: I^A_k = M_k + Σ_c X_cᵀ I^a_c X_c and p_k = Σ_c X_cᵀ p^a_c over k's children
    /// c, X_c the twist transform from o_k to o_c (M_k moved from r_k to o_k likewise); then for
    /// k's link with screws S (τ and x of a rotated link turned to global axes and back),
    /// U = I^A S, D = Sᵀ U, u = τ_k − Sᵀ p_k, I^a = I^A − U D⁻¹ Uᵀ, p^a = p_k + U D⁻¹ u.
    /// Root first: a′ = X a_parent (a = 0 at ground), x_k = D⁻¹(u − Uᵀ a′), a_k = a′ + S x_k.
    fn mass_solve(&self, b: &mut Builder, inertia: &[super::BodyInertia], tau: &[Id]) -> (Vec<Id>, Vec<(usize, Id)>) {
        let tree = self.tree;
        let zero = b.g.num(0.0);
        let n = self.twist_size();
        // each body's inertia at its link's point o_k, from its centre of mass r_k
        let mut articulated: Vec<Matrix> = inertia
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let at_centre = self.global_inertia(b, k, m);
                let d = self.between(b, &self.origins[k], &self.articulation[k].origin);
                at_centre.transformed(b, &d)
            })
            .collect();
        // the generalized forces in the links' own bases (a ball joint's torques about global axes)
        let tau = self.rotated(b, tau, false);
        let mut bias: Vec<Vec<Id>> = vec![vec![zero; n]; inertia.len()];
        let mut links: Vec<Option<Articulated>> = (0..inertia.len()).map(|_| None).collect();
        let mut pivots = Vec::new();
        for &k in tree.order.iter().rev() {
            let link = &tree.links[k];
            let screws = &self.articulation[k].screws;
            let (mut child_inertia, mut child_bias) = (articulated[k].clone(), bias[k].clone());
            if !screws.is_empty() {
                let u_columns: Vec<Vec<Id>> = screws.iter().map(|s| articulated[k].times(b, s)).collect();
                let d: Vec<Vec<Id>> = screws.iter().map(|s| u_columns.iter().map(|u| b.dot(s, u)).collect()).collect();
                let ldl = Ldl::new(b, d);
                pivots.extend(ldl.pivots.iter().map(|&p| (link.first_v, p)));
                let u: Vec<Id> = screws
                    .iter()
                    .enumerate()
                    .map(|(i, s)| {
                        let sp = b.dot(s, &bias[k]);
                        b.g.sub(tau[link.first_v + i], sp)
                    })
                    .collect();
                // I^a = I^A − U D⁻¹ Uᵀ = I^A − Σ_j w_j w_jᵀ / d_j with W = L⁻¹ Uᵀ.
                let w = ldl.forward(b, &u_columns);
                for (wj, &dj) in w.iter().zip(&ldl.pivots) {
                    child_inertia.subtract_outer(b, wj, dj);
                }
                // p^a = p + U D⁻¹ u
                let x = ldl.solve(b, &u);
                for (column, &xj) in u_columns.iter().zip(&x) {
                    child_bias = child_bias
                        .iter()
                        .zip(column)
                        .map(|(&p, &c)| {
                            let t = b.g.mul(c, xj);
                            b.g.add(p, t)
                        })
                        .collect();
                }
                // I^a S = 0 and Sᵀ p^a = τ exactly: a unit screw e_j's row and column of I^a are
                // zero and p^a_j = τ_j, which the nodes above only reach to rounding
                for (i, s) in screws.iter().enumerate() {
                    if let Some(j) = unit(b, s) {
                        child_inertia.clear(b, j);
                        child_bias[j] = tau[link.first_v + i];
                    }
                }
                links[k] = Some(Articulated { u_columns, ldl, u });
            }
            if let BodyRef::Body(p) = link.parent {
                let d = self.between(b, &self.articulation[k].origin, &self.articulation[p].origin);
                let moved = child_inertia.transformed(b, &d);
                articulated[p].add(b, &moved);
                let f = force_moved(b, &child_bias, &d);
                bias[p] = bias[p].iter().zip(&f).map(|(&x, &y)| b.g.add(x, y)).collect();
            }
        }
        let mut x = vec![zero; tree.nv];
        let mut acceleration: Vec<Vec<Id>> = vec![vec![zero; n]; inertia.len()];
        for &k in &tree.order {
            let link = &tree.links[k];
            let mut a = match link.parent {
                BodyRef::Ground => vec![zero; n],
                BodyRef::Body(p) => {
                    let d = self.between(b, &self.articulation[k].origin, &self.articulation[p].origin);
                    twist_moved(b, &acceleration[p], &d)
                }
            };
            if let Some(Articulated { u_columns, ldl, u }) = &links[k] {
                let rhs: Vec<Id> = u_columns
                    .iter()
                    .zip(u)
                    .map(|(column, &ui)| {
                        let ua = b.dot(column, &a);
                        b.g.sub(ui, ua)
                    })
                    .collect();
                let xs = ldl.solve(b, &rhs);
                for (i, (&xi, s)) in xs.iter().zip(&self.articulation[k].screws).enumerate() {
                    x[link.first_v + i] = xi;
                    a = a
                        .iter()
                        .zip(s)
                        .map(|(&ar, &sr)| {
                            let t = b.g.mul(sr, xi);
                            b.g.add(ar, t)
                        })
                        .collect();
                }
            }
            acceleration[k] = a;
        }
        (self.rotated(b, &x, true), pivots)
    }

    /// x with each link's rotated velocities (`Articulation::rotated`) turned to global axes,
    /// A x (or back, Aᵀ x).
    fn rotated(&self, b: &mut Builder, x: &[Id], back: bool) -> Vec<Id> {
        let mut out = x.to_vec();
        for (link, articulation) in self.tree.links.iter().zip(&self.articulation) {
            if let Some((m, a)) = &articulation.rotated {
                let at = link.first_v + m;
                for r in 0..3 {
                    let row: Vec<Id> = (0..3).map(|c| if back { a[c][r] } else { a[r][c] }).collect();
                    out[at + r] = b.dot(&row, &x[at..at + 3]);
                }
            }
        }
        out
    }

    /// x − y.
    fn between(&self, b: &mut Builder, x: &[Id], y: &[Id]) -> Vec<Id> {
        x.iter().zip(y).map(|(&x, &y)| b.g.sub(x, y)).collect()
    }

    /// M by the composite-rigid-body algorithm, every link's screws and every body's inertia in
    /// global axes at the world origin, where a rigid body's inertia is m, its first moment
    /// h = m r and its rotational inertia Ī = A J′ Aᵀ + m (|r|² 1 − r rᵀ) about the origin (in
    /// the plane Ī = J + m |r|²), and a subtree's is their sum (no transforms):
    ///
    /// M_ij = s_iᵀ I^C_k s_j  for velocity j of link k and velocity i of k or of a link
    /// above it, I^C_k the composite inertia of k's subtree, I^C s = (m v + ω × h, Ī ω + h × v)
    /// for s = (v, ω).
    ///
    /// O(N²) entries of a few operations each (a 6-joint arm: about 900 against 4 500 for its
    /// six products M e_c), so emitted for trees of at most [`CRBA_VELOCITIES`] velocities.
    fn mass_matrix(&self, b: &mut Builder, inertia: &[super::BodyInertia]) -> Vec<Vec<Id>> {
        let tree = self.tree;
        let zero = b.g.num(0.0);
        let spatial = self.twist_size() == 6;
        // each body's (m, h, Ī) about the origin; Ī's entries by row (3×3 in space, 1×1 in the plane)
        let mut composite: Vec<(Id, Vec<Id>, Vec<Vec<Id>>)> = inertia
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let r = self.origins[k].clone();
                let h: Vec<Id> = r.iter().map(|&x| b.g.mul(m.mass, x)).collect();
                let rr = b.dot(&r, &r);
                let rotational = if spatial {
                    let centre = self.global_inertia(b, k, m);
                    (0..3)
                        .map(|i| {
                            (0..3)
                                .map(|j| {
                                    // J_g + m (|r|² δ_ij − r_i r_j)
                                    let rirj = b.g.mul(r[i], r[j]);
                                    let shift = if i == j { b.g.sub(rr, rirj) } else { b.g.neg(rirj) };
                                    let shift = b.g.mul(m.mass, shift);
                                    b.g.add(centre.0[3 + i][3 + j], shift)
                                })
                                .collect()
                        })
                        .collect()
                } else {
                    let shift = b.g.mul(m.mass, rr);
                    vec![vec![b.g.add(m.inertia[0][0], shift)]]
                };
                (m.mass, h, rotational)
            })
            .collect();
        for &k in tree.order.iter().rev() {
            if let BodyRef::Body(p) = tree.links[k].parent {
                let (mass, h, rotational) = composite[k].clone();
                let (pm, ph, pr) = &mut composite[p];
                *pm = b.g.add(*pm, mass);
                for (x, y) in ph.iter_mut().zip(&h) {
                    *x = b.g.add(*x, *y);
                }
                for (row, other) in pr.iter_mut().zip(&rotational) {
                    for (x, y) in row.iter_mut().zip(other) {
                        *x = b.g.add(*x, *y);
                    }
                }
            }
        }
        // every link's screws at the origin
        let screws: Vec<Vec<Vec<Id>>> = (0..inertia.len())
            .map(|k| {
                let to_origin: Vec<Id> = self.origins[k].iter().map(|&x| b.g.neg(x)).collect();
                self.screws[k].iter().map(|s| twist_moved(b, s, &to_origin)).collect()
            })
            .collect();
        let mut m = vec![vec![zero; tree.nv]; tree.nv];
        for k in 0..inertia.len() {
            let (mass, h, rotational) = composite[k].clone();
            for (j, s) in screws[k].iter().enumerate() {
                let momentum = composite_times(b, mass, &h, &rotational, s);
                let mut at = BodyRef::Body(k);
                while let BodyRef::Body(a) = at {
                    for (i, s_above) in screws[a].iter().enumerate() {
                        let (row, column) = (tree.links[a].first_v + i, tree.links[k].first_v + j);
                        if a == k && i > j {
                            continue;
                        }
                        m[row][column] = b.dot(s_above, &momentum);
                        m[column][row] = m[row][column];
                    }
                    at = tree.links[a].parent;
                }
            }
        }
        m
    }

    /// M x = Σ_b J_bᵀ M_b J_b x: the bodies' momenta M_b (J_b v), v standing for x, through the
    /// backward pass.
    fn mass_times(&self, b: &mut Builder, frames: &[FrameNodes], inertia: &[super::BodyInertia]) -> Vec<Id> {
        let momenta = frames
            .iter()
            .zip(inertia)
            .enumerate()
            .map(|(k, (frame, m))| {
                let momentum = m.times(b, &frame.twist);
                self.global_wrench(b, k, momentum)
            })
            .collect();
        self.backward(b, momenta)
    }

    /// r_k − r_p.
    fn offset(&self, b: &mut Builder, k: usize, p: usize) -> Vec<Id> {
        self.between(b, &self.origins[k], &self.origins[p])
    }

    /// The joint velocities a wrench on the given body-level velocities (nt k + c) reaches:
    /// those of every link from each such body down to ground.
    fn reached(&self, body_velocities: &[usize], nt: usize) -> Vec<usize> {
        let mut out = BTreeSet::new();
        for k in body_velocities.iter().map(|&i| i / nt).collect::<BTreeSet<_>>() {
            let mut at = BodyRef::Body(k);
            while let BodyRef::Body(j) = at {
                let link = &self.tree.links[j];
                out.extend(link.first_v..link.first_v + link.count_v);
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

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
    accessors, constraint_derivatives, constraint_rows, forces, linear_terms, tangent, ForceTerms, Forces, Formulation, FrameNodes,
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

    // dV/dt + v·h, as in body coordinates.
    let v_rate = b.rate(potential);
    let v_t = b.g.diff(potential, Var::T, &mut HashMap::new());
    let mut power = b.g.add(v_rate, v_t);
    for (i, &hi) in h.iter().enumerate() {
        let v = b.g.var(Var::Qd(i as u16));
        let p = b.g.mul(v, hi);
        power = b.g.add(power, p);
    }

    let (jacobian, nu, gamma) = constraint_derivatives(&mut b, &phi);
    // ∂(Dᵀλ)/∂q over the rows' coordinates.
    let zero = b.g.num(0.0);
    let mut constraint_force = vec![zero; nv];
    for &(r, c, d) in &jacobian {
        let l = b.g.var(Var::Lambda(r as u16));
        let term = b.g.mul(l, d);
        constraint_force[c] = b.g.add(constraint_force[c], term);
    }
    let constraint_force_q = tangent(&mut b, &constraint_force);
    let super::Linear { gamma_q, gamma_v, inputs, h_u } = linear_terms(&mut b, &gamma, &h, [&phi, &mass_x, &friction], &Vec::new());
    let (points, joint_coordinates) = accessors(&mut b);

    let terms = tree_terms(&mut b, &kinematics, mass_x, &h, &friction);
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
fn tree_terms(b: &mut Builder, kinematics: &Kinematics, mass_x: Vec<Id>, h: &[Id], friction: &[Id]) -> TreeTerms {
    let nv = kinematics.tree.nq;
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

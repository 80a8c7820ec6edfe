//! Stage 3: validated model → symbolic equations (docs/formulation.md), in the model's
//! formulation (`frames::Coordinates`: planar or spatial body coordinates).
//!
//! This stage writes Φ(q, t) row by row into one shared [`Graph`] and derives from it, exactly
//! and in velocity space (q̇ = B(q) v; B = I in the plane): the sparse D = Φ_q B, Φ_t,
//! ν = −Φ_t and γ = −𝒟(𝒟Φ) with 𝒟f = f_q B v + f_t (a directional derivative taken twice; no
//! Hessian is formed); M; h and its derivatives (∂h/∂q) B and ∂h/∂v.

mod joint;

use std::collections::{BTreeSet, HashMap, HashSet};

use crate::forces::{gravity, Generalized};
use crate::frames::{collect_vars, velocity_partials, Builder, Coordinates, RowUnit};
use crate::model::{Inertia, Model};
use crate::sym::{Graph, Id, Node, Var};

pub use joint::TreeTerms;

/// h and its structural derivatives ∂h/∂q and ∂h/∂q̇ as (row, column, node).
pub struct ForceTerms {
    pub h: Vec<Id>,
    pub h_q: Vec<(usize, usize, Id)>,
    pub h_qd: Vec<(usize, usize, Id)>,
}

/// The symbolic equations of one mechanism.
pub struct Formulation {
    pub graph: Graph,
    pub nq: usize,
    /// Velocities (NV = NQ for planar bodies, 6 per body in space).
    pub nv: usize,
    pub nc: usize,
    /// Constraint row names, `"revolute crank~rod: x"`, in the order of Φ.
    pub row_names: Vec<String>,
    /// What each row measures (the unit of its multiplier), in the order of Φ.
    pub row_units: Vec<RowUnit>,
    /// The first row of each constraint in Φ.
    pub first_rows: Vec<usize>,
    /// Φ, one node per row.
    pub phi: Vec<Id>,
    /// Structurally non-zero entries of D = Φ_q B as (row, velocity, node), row-major.
    pub jacobian: Vec<(usize, usize, Id)>,
    /// ν = −Φ_t, one node per row.
    pub nu: Vec<Id>,
    /// γ, one node per row.
    pub gamma: Vec<Id>,
    /// Initial guesses of q and v (functions of the parameters).
    pub q0: Vec<Id>,
    pub qd0: Vec<Id>,
    /// Diagonal of the mass matrix: (m, m, J) per planar body, (m, m, m, J′xx, J′yy, J′zz) per
    /// spatial body.
    pub mass: Vec<Id>,
    /// M's off-diagonal structural non-zeros (products of inertia) as (row, column, node), both
    /// triangles; empty in the plane.
    pub mass_coupling: Vec<(usize, usize, Id)>,
    /// For each spatial body with products of inertia, the structural non-zeros of its block of
    /// M⁻¹, J′⁻¹ = adj(J′)/det(J′), as (row, column, node); (M⁻¹)_cc = 1/M_cc everywhere else.
    pub mass_inverse: Vec<(usize, usize, Id)>,
    /// Whether M is constant and block-diagonal, each coupled block inverted in
    /// `mass_inverse` (body coordinates): the forward dynamics then solve with the Schur
    /// complement D M⁻¹ Dᵀ planned at compile time. Otherwise (joint coordinates: M(q)) they
    /// factor M at each call.
    pub mass_blocks: bool,
    /// h(q, q̇, t), one node per coordinate.
    pub h: Vec<Id>,
    /// Each force element (gravity first, as `"gravity"`) with the velocities its generalized
    /// force (or friction force) structurally reaches, in declaration order.
    pub force_velocities: Vec<(String, Vec<usize>)>,
    /// h and its derivatives with no force element and no gravity: nothing, or a spatial
    /// mechanism's gyroscopic terms.
    pub base_forces: ForceTerms,
    /// h and its derivatives were each element (in the order of `force_velocities`) the only
    /// one: the base's terms and its own, built exactly as a scene keeping only it builds them.
    pub alone_forces: Vec<ForceTerms>,
    /// Structural non-zeros of ∂h/∂q and ∂h/∂q̇ as (row, column, node).
    pub h_q: Vec<(usize, usize, Id)>,
    pub h_qd: Vec<(usize, usize, Id)>,
    /// The parameters that are inputs of a linearization: those that enter h and nothing else
    /// (not Φ, M or the friction forces), by index into `model.params`.
    pub inputs: Vec<usize>,
    /// Structural non-zeros of ∂h/∂u as (row, input, node), the input by its index into
    /// `inputs`.
    pub h_u: Vec<(usize, usize, Id)>,
    /// Structural non-zeros of (∂γ/∂q) B and ∂γ/∂v as (row, column, node).
    pub gamma_q: Vec<(usize, usize, Id)>,
    pub gamma_v: Vec<(usize, usize, Id)>,
    /// Potential energy of gravity and springs, V(q).
    pub potential: Id,
    /// The switching functions of (q, v, t), by name: the unilateral elements', then the time
    /// events ([`time_switches`]).
    pub switches: Vec<(String, Id)>,
    /// How many of `switches`, the last ones, are time events (functions of t alone).
    pub time_switches: usize,
    /// Coulomb friction forces, one node per coordinate, functions of q, q̇ and the multipliers λ
    /// (the joints' normal loads); kept out of h, which does not depend on λ.
    pub friction: Vec<Id>,
    /// Structural non-zeros of the friction forces' ∂/∂q and ∂/∂q̇ at given λ (for implicit
    /// integration; empty without Coulomb friction).
    pub friction_q: Vec<(usize, usize, Id)>,
    pub friction_qd: Vec<(usize, usize, Id)>,
    /// Structural non-zeros of the friction forces' ∂/∂λ as (velocity, row, node): their slope
    /// in the joints' normal loads, for the implicit methods' Newton matrix, where it stands
    /// beside −Dᵀ (empty without Coulomb friction).
    pub friction_lambda: Vec<(usize, usize, Id)>,
    /// Power of the non-conservative forces, q̇ᵀh + dV/dt: what dampers, actuators, applied
    /// forces and friction put in (J/s). Then d(T + V)/dt = this + λᵀ Φ_q q̇.
    pub power: Id,
    /// Structural non-zeros of ∂(Φ_qᵀλ)/∂q (the constraints' geometric stiffness), with λ as
    /// variables.
    pub constraint_force_q: Vec<(usize, usize, Id)>,
    /// ∂h/∂q·B + K + friction's ∂/∂q·B, and ∂h/∂v + friction's ∂/∂v, summed by entry (the
    /// structural non-zeros of either), for generalized-α's Newton matrix.
    pub stiffness: Vec<(usize, usize, Id)>,
    pub damping: Vec<(usize, usize, Id)>,
    /// The body-frame coordinates of each named point (`model.points`), functions of the
    /// parameters, for the generated point accessors.
    pub points: Vec<Vec<Id>>,
    /// The joint coordinates of each labelled spatial joint that has them — the angle θ_J of a
    /// revolute or cylindrical joint, the stroke s_J of a translational or cylindrical one — as
    /// (accessor name `hinge_angle`, its value, its rate along q̇ = B(q) v), for the generated
    /// accessors.
    pub joint_coordinates: Vec<(String, Id, Id)>,
    /// Each body's mass and inertia about its centre of mass (`mass_of`, `inertia_of`).
    pub bodies: Vec<BodyInertia>,
    /// Each body's wrench from the constraint rows, D_bᵀλ with λ as variables, global (F_x, F_y,
    /// n; or F, n): `JointLoads::constraint_wrench`.
    pub constraint_wrenches: Vec<Vec<Id>>,
    /// In joint coordinates, each body's frame as functions of q and v (`mbd::BodyFrames`);
    /// empty in body coordinates, whose frames are q's own entries.
    pub frames: Vec<FrameNodes>,
    /// In joint coordinates, M x and the dense derivatives as products with a direction
    /// (`joint`); `None` in body coordinates, whose M is `mass` and whose derivatives are the
    /// sparse entries above.
    pub tree: Option<TreeTerms>,
}

/// A body's frame in joint coordinates: its pose (x, y, φ; or r, p), its twist J_b v (ẋ, ẏ, φ̇;
/// or ṙ, ω′ in its own frame; linear in v) and the twist's rate at constant v (J̇_b v).
pub struct FrameNodes {
    pub pose: Vec<Id>,
    pub twist: Vec<Id>,
    pub bias: Vec<Id>,
}

impl Formulation {
    /// Whether Φ does not depend on t (then ν = 0 and solvers skip it).
    pub fn phi_t_is_zero(&self) -> bool {
        self.nu.iter().all(|&n| self.graph.is_zero(n))
    }
}

/// Derives the symbolic equations of a model.
pub fn formulate(model: &Model) -> Formulation {
    if let Some(tree) = &model.tree {
        return joint::formulate(model, tree);
    }
    let mut b = Builder::new(model);
    let (nq, nv) = (b.nq(), b.nv());
    let Rows { phi, names: row_names, units: row_units, owners: joints } = constraint_rows(&mut b);
    let (MassAndStart { q0, qd0, mass, mass_coupling, mass_inverse }, inertia_forces) = mass_and_start(&mut b);
    let mass_blocks = {
        let mut reads = BTreeSet::new();
        for &node in mass.iter().chain(mass_coupling.iter().map(|(_, _, n)| n)) {
            collect_vars(&b.g, node, &mut reads, |v| if let Var::Q(i) = v { Some(i) } else { None });
        }
        reads.is_empty() && mass_coupling.iter().all(|&(r, c, _)| mass_inverse.iter().any(|&(ri, ci, _)| (ri, ci) == (r, c)))
    };
    let Forces { h, friction, potential, switches, time_switches, force_velocities, base_forces, alone_forces } =
        forces(&mut b, inertia_forces, &joints);
    let power = power(&mut b, potential, &h);
    let first_rows = std::mem::take(&mut b.first_rows);
    let h_q = tangent(&mut b, &h);
    let h_qd = sparse_derivative(&mut b.g, &h, |v| if let Var::Qd(i) = v { Some(i) } else { None }, Var::Qd);
    let friction_q = tangent(&mut b, &friction);
    let friction_qd = sparse_derivative(&mut b.g, &friction, |v| if let Var::Qd(i) = v { Some(i) } else { None }, Var::Qd);
    let friction_lambda = multiplier_slope(&mut b.g, &friction);
    let (jacobian, nu, gamma) = constraint_derivatives(&mut b, &phi);
    let (constraint_force_q, stiffness, damping) = newton_terms(&mut b, &jacobian, [&h_q, &h_qd], [&friction_q, &friction_qd]);
    let Linear { gamma_q, gamma_v, inputs, h_u } = linear_terms(&mut b, &gamma, &h, [&phi, &mass, &friction], &mass_coupling);
    let (points, joint_coordinates) = accessors(&mut b);
    let bodies = inertias(&mut b, model);
    let constraint_wrenches = {
        let nt = model.space.velocities().len();
        let flat = constraint_wrenches(&mut b, &jacobian);
        (0..model.bodies.len())
            .map(|k| {
                let rotation = (model.space == crate::model::Space::Spatial).then(|| b.rotation(crate::model::BodyRef::Body(k)));
                global_wrench(&mut b, rotation.as_ref(), flat[nt * k..nt * (k + 1)].to_vec())
            })
            .collect()
    };
    b.g.forget_partials();
    Formulation {
        bodies,
        constraint_wrenches,
        nc: phi.len(),
        row_names,
        row_units,
        first_rows,
        graph: b.g,
        nq,
        nv,
        phi,
        jacobian,
        nu,
        gamma,
        q0,
        qd0,
        mass,
        mass_coupling,
        mass_inverse,
        mass_blocks,
        h,
        force_velocities,
        base_forces,
        alone_forces,
        h_q,
        h_qd,
        inputs,
        h_u,
        gamma_q,
        gamma_v,
        potential,
        switches,
        time_switches,
        power,
        friction,
        friction_q,
        friction_qd,
        friction_lambda,
        constraint_force_q,
        stiffness,
        damping,
        points,
        joint_coordinates,
        frames: Vec::new(),
        tree: None,
    }
}

/// A body's mass and its moment of inertia about its centre of mass: J (planar) or the tensor
/// J′ in its own frame (3×3).
pub struct BodyInertia {
    pub mass: Id,
    pub inertia: Vec<Vec<Id>>,
}

impl BodyInertia {
    /// M_b x for a twist-shaped x as body coordinates have it, (ṙ, φ̇) or (ṙ, ω′):
    /// (m ṙ, J φ̇) or (m ṙ, J′ ω′).
    fn times(&self, b: &mut Builder, x: &[Id]) -> Vec<Id> {
        let linear = x.len() - self.inertia.len();
        let mut out: Vec<Id> = x[..linear].iter().map(|&x| b.g.mul(self.mass, x)).collect();
        out.extend(self.inertia.iter().map(|row| b.dot(row, &x[linear..])));
        out
    }
}

fn inertias(b: &mut Builder, model: &Model) -> Vec<BodyInertia> {
    model
        .bodies
        .iter()
        .map(|body| {
            let inertia = match &body.inertia {
                Inertia::Planar(j) => vec![vec![b.expr(j)]],
                Inertia::Tensor(t) => t.iter().map(|row| row.iter().map(|e| b.expr(e)).collect()).collect(),
            };
            BodyInertia { mass: b.expr(&body.mass), inertia }
        })
        .collect()
}

/// The power of the non-conservative forces, dV/dt + vᵀh with dV/dt = V_q q̇ + V_t.
fn power(b: &mut Builder, potential: Id, h: &[Id]) -> Id {
    let v_rate = b.rate(potential);
    let v_t = b.g.diff(potential, Var::T, &mut HashMap::new());
    let mut power = b.g.add(v_rate, v_t);
    for (i, &hi) in h.iter().enumerate() {
        let v = b.g.var(Var::Qd(i as u16));
        let p = b.g.mul(v, hi);
        power = b.g.add(power, p);
    }
    power
}

/// Each body's frame as functions of q and v ([`FrameNodes`]).
fn frame_nodes(b: &mut Builder) -> Vec<FrameNodes> {
    use crate::model::BodyRef;
    let rates = b.coordinate_rates();
    let seed = |v: Var| match v {
        Var::Q(i) => Some(rates[i as usize]),
        _ => None,
    };
    let mut memo = HashMap::new();
    (0..b.model.bodies.len())
        .map(|k| {
            let body = BodyRef::Body(k);
            let pose: Vec<Id> = b.model.space.coordinates().iter().map(|&c| b.coord(body, c)).collect();
            let twist: Vec<Id> = b.model.space.velocities().iter().map(|&c| b.velocity(body, c)).collect();
            let bias = match b.tree_bias(k) {
                Some(bias) => bias.to_vec(),
                None => twist.iter().map(|&x| b.g.directional(x, &seed, &mut memo)).collect(),
            };
            FrameNodes { pose, twist, bias }
        })
        .collect()
}

/// Φ's rows, joint by joint in declaration order, with their names and units; in joint
/// coordinates the cut joints', drivers' and user constraints' only.
struct Rows {
    phi: Vec<Id>,
    names: Vec<String>,
    units: Vec<RowUnit>,
    /// Each joint's name with its rows, for [`time_switches`].
    owners: Vec<(String, Vec<Id>)>,
}

/// Φ's [`Rows`], each joint's first row recorded in `b.first_rows`.
fn constraint_rows(b: &mut Builder) -> Rows {
    let mut rows = Rows { phi: Vec::new(), names: Vec::new(), units: Vec::new(), owners: Vec::new() };
    for (index, c) in b.model.constraints.iter().enumerate() {
        b.first_rows.push(rows.phi.len());
        // A joint the tree carries holds by the coordinates themselves: it has no rows.
        if b.model.tree.as_ref().is_some_and(|tree| tree.joints.contains(&index)) {
            continue;
        }
        let mut own = Vec::new();
        for row in c.kind.rows(b) {
            rows.names.push(format!("{}: {}", c.name, row.name));
            rows.units.push(row.unit);
            rows.phi.push(row.value);
            own.push(row.value);
        }
        rows.owners.push((c.name.clone(), own));
    }
    rows
}

/// The instants where an expression of time alone changes branch — a `clamp`, `min`, `max`,
/// `abs`, `sign` or `if` of t in a road profile, a driver or a force law — as switching
/// functions: each comparison a > b of a `Select` reached from an owner's nodes (an element's
/// forces, a joint's rows) whose two sides read t and parameters but no state, as a − b, once
/// for the whole mechanism, named after its first owner (`"road: time event"`, numbered where
/// an owner has several).
///
/// Why: a law that changes between two steps' ends is invisible to the step's error estimate
/// when it depends on time alone — a stiff method's step of 0.1 s can step over a 25 ms bump in
/// the road and see a flat road at both ends. Located as switches, such instants end a step,
/// and the integrator restarts there (guide/dsl.md, "Switches and events"). A kink that reads
/// the state changes the dynamics the step integrates, so the estimate sees it; the unilateral
/// elements locate their own.
fn time_switches<'a>(g: &mut Graph, owners: impl IntoIterator<Item = &'a (String, Vec<Id>)>) -> Vec<(String, Id)> {
    const TIME: u8 = 1;
    const STATE: u8 = 2;
    // What each node reads; a node's children precede it in the graph.
    let mut reads = vec![0u8; g.node_count()];
    for id in 0..reads.len() {
        reads[id] = match g.node(id as Id) {
            Node::Var(Var::T) => TIME,
            Node::Var(Var::Param(_)) | Node::Const(_) => 0,
            Node::Var(_) => STATE,
            _ => g.children(id as Id).into_iter().flatten().fold(0, |r, c| r | reads[c as usize]),
        };
    }
    let (mut visited, mut compared) = (HashSet::new(), HashSet::new());
    let mut switches = Vec::new();
    for (owner, roots) in owners {
        let mut own = Vec::new();
        let mut stack: Vec<Id> = roots.iter().copied().filter(|&r| reads[r as usize] & TIME != 0).collect();
        while let Some(id) = stack.pop() {
            if !visited.insert(id) {
                continue;
            }
            if let Node::Select(_, a, b, _, _) = g.node(id) {
                if reads[a as usize] | reads[b as usize] == TIME && compared.insert((a.min(b), a.max(b))) {
                    own.push((a, b));
                }
            }
            stack.extend(g.children(id).into_iter().flatten().filter(|&c| reads[c as usize] & TIME != 0));
        }
        for (k, &(a, b)) in own.iter().enumerate() {
            let name = if own.len() == 1 { format!("{owner}: time event") } else { format!("{owner}: time event {}", k + 1) };
            switches.push((name, g.sub(a, b)));
        }
    }
    switches
}

/// The initial guesses of q and v, and M: its diagonal, its products of inertia and the blocks
/// of M⁻¹ they couple.
struct MassAndStart {
    q0: Vec<Id>,
    qd0: Vec<Id>,
    mass: Vec<Id>,
    mass_coupling: Vec<(usize, usize, Id)>,
    mass_inverse: Vec<(usize, usize, Id)>,
}

/// Each body's initial pose and velocity, body by body; then M and the inertia forces from the
/// bodies' twists ([`inertia`]).
fn mass_and_start(b: &mut Builder) -> (MassAndStart, Vec<Id>) {
    let model = b.model;
    let (nq, nv) = (b.nq(), b.nv());
    let mut q0 = Vec::with_capacity(nq);
    let mut qd0 = Vec::with_capacity(nv);
    if let Some(tree) = &model.tree {
        (q0, qd0) = crate::tree::initial(b, tree);
    }
    for body in model.bodies.iter().filter(|_| model.tree.is_none()) {
        if model.space == crate::model::Space::Planar {
            for c in 0..3 {
                q0.push(b.expr(&body.q0[c]));
                qd0.push(b.expr(&body.v0[c]));
            }
        } else {
            q0.extend(body.q0.iter().map(|e| b.expr(e)));
            qd0.extend(body.v0.iter().map(|e| b.expr(e)));
        }
    }
    let (entries, blocks, inertia_forces) = inertia(b);
    let zero = b.g.num(0.0);
    let mass: Vec<Id> = (0..nv).map(|i| entries.get(&(i, i)).copied().unwrap_or(zero)).collect();
    let mass_coupling: Vec<(usize, usize, Id)> = entries.iter().filter(|((r, c), _)| r != c).map(|(&(r, c), &e)| (r, c, e)).collect();
    // M⁻¹ of each block that products of inertia couple (the Schur complement's solve reads
    // 1/M_cc everywhere else).
    let mut mass_inverse = Vec::new();
    for block in blocks {
        if !mass_coupling.iter().any(|&(r, c, _)| block.contains(&r) && block.contains(&c)) {
            continue;
        }
        let [r0, r1, r2] = block[..] else { unreachable!("a body's angular velocity has three components in space") };
        let at = |r: usize, c: usize| entries.get(&(r, c)).copied().unwrap_or(zero);
        let j = [r0, r1, r2].map(|r| [r0, r1, r2].map(|c| at(r, c)));
        for (r, c, e) in inverse3(b, j) {
            mass_inverse.push((block[r], block[c], e));
        }
    }
    (MassAndStart { q0, qd0, mass, mass_coupling, mass_inverse }, inertia_forces)
}

/// M's structural non-zeros by (row, column); the velocities each spatial body's angular
/// velocity reaches (the blocks products of inertia may couple); and the inertia forces.
type InertiaTerms = (std::collections::BTreeMap<(usize, usize), Id>, Vec<Vec<usize>>, Vec<Id>);

/// The mass matrix and the inertia forces by virtual power, from each body's twist
/// (`Builder::twist`) — the velocity ṙ of its centre of mass and its angular velocity ω′ in its
/// own frame, both linear in v, ṙ = L(q) v and ω′ = W(q) v:
///
/// M = Σ_b m_b LᵀL + WᵀJ′_b W, and the inertia part of h,
/// −Σ_b Lᵀ m_b (L̇ v) + Wᵀ (J′_b (Ẇ v) + ω′ × J′_b ω′),
///
/// with L̇ v and Ẇ v the twist's rates along q̇ = B(q) v at constant v. In body coordinates L
/// and W pick the body's own velocities: M is block-diagonal and constant, L̇ = Ẇ = 0, and h
/// has the gyroscopic term alone. A formulation whose twists depend on q (joint coordinates)
/// gets M(q) and its velocity-quadratic terms from the same lines.
fn inertia(b: &mut Builder) -> InertiaTerms {
    let model = b.model;
    let nv = b.nv();
    let zero = b.g.num(0.0);
    let mut entries: std::collections::BTreeMap<(usize, usize), Id> = std::collections::BTreeMap::new();
    let mut blocks = Vec::new();
    let mut h = vec![zero; nv];
    let rates = b.coordinate_rates();
    let seed = |v: Var| match v {
        Var::Q(i) => Some(rates[i as usize]),
        _ => None,
    };
    let mut memo = HashMap::new();
    for (k, body) in model.bodies.iter().enumerate() {
        let (linear, angular) = b.twist(crate::model::BodyRef::Body(k));
        let m = b.expr(&body.mass);
        let j: Vec<Vec<Id>> = match &body.inertia {
            Inertia::Planar(j) => vec![vec![b.expr(j)]],
            Inertia::Tensor(t) => t.iter().map(|row| row.iter().map(|e| b.expr(e)).collect()).collect(),
        };
        let partials = |b: &mut Builder, x: &[Id]| -> Vec<Vec<(usize, Id)>> { x.iter().map(|&x| velocity_partials(&mut b.g, x)).collect() };
        let (dl, dw) = (partials(b, &linear), partials(b, &angular));
        let mut add = |b: &mut Builder, r: usize, c: usize, term: Id| {
            let sum = match entries.get(&(r, c)) {
                Some(&before) => b.g.add(before, term),
                None => term,
            };
            entries.insert((r, c), sum);
        };
        for row in &dl {
            for &(r, dr) in row {
                for &(c, dc) in row {
                    let t = b.g.mul(m, dr);
                    let term = b.g.mul(t, dc);
                    add(b, r, c, term);
                }
            }
        }
        for (a, row_a) in dw.iter().enumerate() {
            for (e, row_e) in dw.iter().enumerate() {
                if b.g.is_zero(j[a][e]) {
                    continue;
                }
                for &(r, dr) in row_a {
                    for &(c, dc) in row_e {
                        let t = b.g.mul(dr, j[a][e]);
                        let term = b.g.mul(t, dc);
                        add(b, r, c, term);
                    }
                }
            }
        }
        if angular.len() == 3 {
            let mut block: Vec<usize> = dw.iter().flatten().map(|&(i, _)| i).collect();
            block.sort_unstable();
            block.dedup();
            blocks.push(block);
        }
        // The rates of the twist at constant v, then the inertia forces they and the spin give.
        let mut rate = |b: &mut Builder, x: &[Id]| -> Vec<Id> { x.iter().map(|&x| b.g.directional(x, &seed, &mut memo)).collect() };
        let (linear_rate, angular_rate) = (rate(b, &linear), rate(b, &angular));
        let force: Vec<Id> = linear_rate.iter().map(|&a| b.g.mul(m, a)).collect();
        let mut moment: Vec<Id> = j.iter().map(|row| b.dot(row, &angular_rate)).collect();
        if angular.len() == 3 {
            let w = [angular[0], angular[1], angular[2]];
            let jw: [Id; 3] = std::array::from_fn(|r| b.dot(&j[r], &w));
            let wjw = b.cross(w, jw);
            moment = moment.iter().zip(wjw).map(|(&m, g)| b.g.add(m, g)).collect();
        }
        for (rows, loads) in [(&dl, &force), (&dw, &moment)] {
            for (row, &load) in rows.iter().zip(loads) {
                if b.g.is_zero(load) {
                    continue;
                }
                for &(i, d) in row {
                    let term = b.g.mul(d, load);
                    h[i] = b.g.sub(h[i], term);
                }
            }
        }
    }
    (entries, blocks, h)
}

/// The generalized forces (h, friction, V and the switching functions), and with each element
/// alone the velocities it reaches and its terms.
struct Forces {
    h: Vec<Id>,
    friction: Vec<Id>,
    potential: Id,
    switches: Vec<(String, Id)>,
    force_velocities: Vec<(String, Vec<usize>)>,
    base_forces: ForceTerms,
    alone_forces: Vec<ForceTerms>,
    /// How many of `switches`, the last ones, are time events.
    time_switches: usize,
}

/// h by virtual power: the inertia forces (`inertia`: in body coordinates the gyroscopic terms
/// of spatial bodies), gravity and each force element.
/// Also the time events ([`time_switches`]) of the elements' and the joints' (`joints`: each
/// joint's name and rows) expressions, after the unilateral elements' switches.
fn forces(b: &mut Builder, inertia_forces: Vec<Id>, joints: &[(String, Vec<Id>)]) -> Forces {
    let model = b.model;
    let nv = b.nv();
    let zero = b.g.num(0.0);
    let mut out = Generalized { h: inertia_forces, friction: vec![zero; nv], potential: zero, switches: Vec::new() };
    let base_h = out.h.clone();
    if let Some(g) = &model.gravity {
        gravity::apply(b, g, &mut out);
    }
    let mut switch_names = Vec::new();
    for element in &model.forces {
        element.kind.apply(b, &mut out);
        switch_names.resize(out.switches.len(), element.name.clone());
    }
    // Each element alone on the base: which velocities its generalized force reaches
    // (structurally), for naming the element behind a NaN force at run time
    // (`Mechanism::FORCE_ELEMENTS`), and what h and its derivatives would cost were it the only
    // one (`ForceInfo::op_counts`). Applying an element again only revisits nodes the graph
    // already holds.
    let terms = |b: &mut Builder, h: Vec<Id>| {
        let h_q = tangent(b, &h);
        let h_qd = sparse_derivative(&mut b.g, &h, |v| if let Var::Qd(i) = v { Some(i) } else { None }, Var::Qd);
        ForceTerms { h, h_q, h_qd }
    };
    let base_forces = terms(b, base_h.clone());
    let mut force_velocities = Vec::new();
    let mut alone_forces = Vec::new();
    let mut owners = Vec::new();
    let mut reach = |b: &mut Builder, name: &str, apply: &dyn Fn(&mut Builder, &mut Generalized)| {
        // On the base (zero, or the gyroscopic terms), an entry the element reaches is a new
        // node: adding a non-zero term never gives back what it was added to.
        let mut alone = Generalized { h: base_h.clone(), friction: vec![zero; nv], potential: zero, switches: Vec::new() };
        apply(b, &mut alone);
        let velocities: Vec<usize> = (0..nv).filter(|&i| alone.h[i] != base_h[i] || !b.g.is_zero(alone.friction[i])).collect();
        owners.push((name.to_string(), velocities.iter().flat_map(|&i| [alone.h[i], alone.friction[i]]).collect()));
        force_velocities.push((name.to_string(), velocities));
        alone_forces.push(terms(b, alone.h));
    };
    if let Some(g) = &model.gravity {
        reach(b, "gravity", &|b, out| gravity::apply(b, g, out));
    }
    for element in &model.forces {
        reach(b, &element.name, &|b, out| element.kind.apply(b, out));
    }
    let Generalized { h, friction, potential, switches } = out;
    let mut switches: Vec<(String, Id)> = switch_names.into_iter().zip(switches).collect();
    let events = time_switches(&mut b.g, owners.iter().chain(joints));
    let time_switches = events.len();
    switches.extend(events);
    Forces { h, friction, potential, switches, time_switches, force_velocities, base_forces, alone_forces }
}

/// Sparse matrix entries (row, column, node).
type Entries = Vec<(usize, usize, Id)>;

/// D = Φ_q B, ν = −Φ_t and γ = −𝒟(𝒟Φ).
fn constraint_derivatives(b: &mut Builder, phi: &[Id]) -> (Entries, Vec<Id>, Vec<Id>) {
    // D = Φ_q B: differentiate each row only by the coordinates it contains; every other entry
    // is a structural zero.
    let jacobian = tangent(b, phi);

    // ν = −Φ_t
    let g = &mut b.g;
    let mut memo_t = HashMap::new();
    let nu: Vec<Id> = phi
        .iter()
        .map(|&row| {
            let d = g.diff(row, Var::T, &mut memo_t);
            g.neg(d)
        })
        .collect();

    // γ = −𝒟(𝒟Φ), 𝒟 the total time derivative with v̇ = 0 along q̇ = B(q) v (the rates' nodes
    // read q and v): one seed, one memo for all rows.
    let rates = b.coordinate_rates();
    let g = &mut b.g;
    let one = g.num(1.0);
    let seed = |v: Var| match v {
        Var::Q(i) => Some(rates[i as usize]),
        Var::T => Some(one),
        Var::Qd(_) | Var::Param(_) | Var::Lambda(_) | Var::Dir(_) => None,
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
    (jacobian, nu, gamma)
}

/// Dᵀλ: (Dᵀλ)_k = Σ_r λ_r D_rk, λ_r the variables `Var::Lambda(r)`.
fn constraint_forces(b: &mut Builder, jacobian: &[(usize, usize, Id)]) -> Vec<Id> {
    let zero = b.g.num(0.0);
    let mut constraint_force = vec![zero; b.nv()];
    for &(r, c, d) in jacobian {
        let l = b.g.var(Var::Lambda(r as u16));
        let term = b.g.mul(l, d);
        constraint_force[c] = b.g.add(constraint_force[c], term);
    }
    constraint_force
}

/// ∂(Dᵀλ)/∂q B, and generalized-α's Newton matrix terms summed by entry: the stiffness
/// ∂h/∂q·B + K + friction's, the damping ∂h/∂v + friction's.
fn newton_terms(
    b: &mut Builder,
    jacobian: &[(usize, usize, Id)],
    [h_q, h_qd]: [&Entries; 2],
    [friction_q, friction_qd]: [&Entries; 2],
) -> (Entries, Entries, Entries) {
    // (Dᵀλ)_k = Σ_r λ_r D_rk, then its exact derivative by q along B.
    let constraint_force = constraint_forces(b, jacobian);
    let constraint_force_q = tangent(b, &constraint_force);
    // Generalized-α's Newton matrix takes them summed by entry: the stiffness part
    // ∂h/∂q·B + K + friction's, the damping part ∂h/∂v + friction's.
    let mut sum = |parts: [&[(usize, usize, Id)]; 3]| -> Vec<(usize, usize, Id)> {
        let mut by_entry: std::collections::BTreeMap<(usize, usize), Id> = std::collections::BTreeMap::new();
        for &(r, c, node) in parts.into_iter().flatten() {
            let total = match by_entry.get(&(r, c)) {
                Some(&before) => b.g.add(before, node),
                None => node,
            };
            by_entry.insert((r, c), total);
        }
        by_entry.into_iter().map(|((r, c), node)| (r, c, node)).collect()
    };
    let stiffness = sum([h_q, &constraint_force_q, friction_q]);
    let damping = sum([h_qd, friction_qd, &[]]);
    (constraint_force_q, stiffness, damping)
}

/// What a linearization needs beyond the rest.
struct Linear {
    gamma_q: Entries,
    gamma_v: Entries,
    inputs: Vec<usize>,
    h_u: Entries,
}

/// γ's derivatives (the forward dynamics' v̇ moves with q and v through γ too) and h's by the
/// inputs: the parameters h reads that Φ, M and friction do not.
fn linear_terms(b: &mut Builder, gamma: &[Id], h: &[Id], [phi, mass, friction]: [&[Id]; 3], mass_coupling: &Entries) -> Linear {
    let gamma_q = tangent(b, gamma);
    let gamma_v = sparse_derivative(&mut b.g, gamma, |v| if let Var::Qd(i) = v { Some(i) } else { None }, Var::Qd);
    let mut not_inputs = BTreeSet::new();
    let param = |v| if let Var::Param(k) = v { Some(k) } else { None };
    for &node in phi.iter().chain(mass).chain(mass_coupling.iter().map(|(_, _, n)| n)).chain(friction) {
        collect_vars(&b.g, node, &mut not_inputs, param);
    }
    let mut in_h = BTreeSet::new();
    for &node in h {
        collect_vars(&b.g, node, &mut in_h, param);
    }
    let inputs: Vec<usize> = in_h.difference(&not_inputs).map(|&k| k as usize).collect();
    let h_u = sparse_derivative(
        &mut b.g,
        h,
        |v| if let Var::Param(k) = v { inputs.iter().position(|&i| i == k as usize).map(|i| i as u16) } else { None },
        |i| Var::Param(inputs[i as usize] as u16),
    );
    Linear { gamma_q, gamma_v, inputs, h_u }
}

/// The body-frame coordinates of each named point and the joint coordinates of each labelled
/// spatial joint that has them, for the generated accessors.
#[allow(clippy::type_complexity)]
fn accessors(b: &mut Builder) -> (Vec<Vec<Id>>, Vec<(String, Id, Id)>) {
    let model = b.model;
    let points = model.points.iter().map(|p| p.local.iter().map(|e| b.expr(e)).collect()).collect();
    let mut joint_coordinates = Vec::new();
    for c in &model.constraints {
        let (Some([i, j]), true) = (c.kind.markers(), syn::parse_str::<syn::Ident>(&c.name).is_ok()) else { continue };
        for (what, kinds) in crate::model::JOINT_COORDINATES {
            if kinds.contains(&c.kind.kind()) {
                let node = if *what == "angle" { b.joint_angle(i, j) } else { b.joint_stroke(i, j) };
                let rate = b.rate(node);
                joint_coordinates.push((format!("{}_{what}", c.name), node, rate));
            }
        }
    }

    (points, joint_coordinates)
}

/// The structural non-zeros of (∂rows/∂q) B, the derivative along the velocity map: plain
/// ∂/∂q in the plane.
fn tangent(b: &mut Builder, rows: &[Id]) -> Vec<(usize, usize, Id)> {
    match b.coordinates {
        Coordinates::PlanarBody | Coordinates::PlanarJoint => {
            sparse_derivative(&mut b.g, rows, |v| if let Var::Q(i) = v { Some(i) } else { None }, Var::Q)
        }
        Coordinates::SpatialBody | Coordinates::SpatialJoint => {
            rows.iter().enumerate().flat_map(|(r, &row)| b.gradient(row).into_iter().map(move |(c, d)| (r, c, d))).collect::<Vec<_>>()
        }
    }
}

/// Each body's constraint wrench D_bᵀλ, the multipliers λ as variables, from D's entries over
/// the bodies' own velocities: nt entries per body (F_x, F_y, n; or F global and n′ in the
/// body's frame), body k's at nt k.
fn constraint_wrenches(b: &mut Builder, jacobian: &Entries) -> Vec<Id> {
    let nt = b.model.space.velocities().len();
    let zero = b.g.num(0.0);
    let mut out = vec![zero; nt * b.model.bodies.len()];
    for &(r, c, d) in jacobian {
        let l = b.g.var(Var::Lambda(r as u16));
        let term = b.g.mul(l, d);
        out[c] = b.g.add(out[c], term);
    }
    out
}

/// A body's wrench as body coordinates hold it (F global; n′ in the body's frame in space,
/// rotated by A to global components; the plane's (F_x, F_y, n) as they are).
fn global_wrench(b: &mut Builder, rotation: Option<&[[Id; 3]; 3]>, mut w: Vec<Id>) -> Vec<Id> {
    if let Some(a) = rotation {
        let n = [w[3], w[4], w[5]];
        for r in 0..3 {
            w[3 + r] = b.dot(&a[r], &n);
        }
    }
    w
}

/// The structural non-zeros of the inverse of a symmetric 3×3 matrix, adj(J)/det(J).
fn inverse3(b: &mut Builder, j: [[Id; 3]; 3]) -> Vec<(usize, usize, Id)> {
    // cofactor C_rc = J_(r+1)(c+1) J_(r+2)(c+2) − J_(r+1)(c+2) J_(r+2)(c+1) (indices mod 3)
    let cofactor: [[Id; 3]; 3] = std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            let (r1, r2, c1, c2) = ((r + 1) % 3, (r + 2) % 3, (c + 1) % 3, (c + 2) % 3);
            let a = b.g.mul(j[r1][c1], j[r2][c2]);
            let d = b.g.mul(j[r1][c2], j[r2][c1]);
            b.g.sub(a, d)
        })
    });
    let det = b.dot(&j[0], &cofactor[0]);
    let mut out = Vec::new();
    for (r, row) in cofactor.iter().enumerate() {
        for (c, _) in row.iter().enumerate() {
            // (J⁻¹)_rc = C_cr / det (J symmetric, so C is too)
            let e = b.g.div(cofactor[c][r], det);
            if !b.g.is_zero(e) {
                out.push((r, c, e));
            }
        }
    }
    out
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
        for c in cols {
            let d = g.partial(row, var(c));
            if !g.is_zero(d) {
                out.push((r, c as usize, d));
            }
        }
    }
    out
}

/// The structural non-zeros of the friction forces' ∂/∂λ, (velocity, row, node).
fn multiplier_slope(g: &mut Graph, friction: &[Id]) -> Vec<(usize, usize, Id)> {
    sparse_derivative(g, friction, |v| if let Var::Lambda(i) = v { Some(i) } else { None }, Var::Lambda)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::parse::MechanismDef;

    fn formulated(src: &str) -> (Model, Formulation) {
        let model = syn::parse_str::<MechanismDef>(src).unwrap().validate().unwrap();
        let f = formulate(&model);
        (model, f)
    }

    fn eval(f: &Formulation, node: Id, q: &[f64], qd: &[f64], t: f64) -> f64 {
        f.graph.eval(node, &|v| match v {
            Var::Q(i) => q[i as usize],
            Var::Qd(i) => qd[i as usize],
            Var::T => t,
            Var::Param(_) | Var::Lambda(_) | Var::Dir(_) => 0.0,
        })
    }

    const PENDULUM: &str = "P { gravity [0.0, -9.81]; body a { mass: 2.0, inertia: 0.5 }
        revolute pin: ground[0.0, 0.0] ~ a[-1.0, 0.0]; drive a.phi = 2.0 * t; }";

    /// A kink of t alone is a time event, each comparison once, named after its element or
    /// joint (in that order); a kink of the state (`abs(b.x)`: the dynamics see it) or of
    /// parameters alone (constant in a run) is not. Each event's function vanishes at its
    /// instant: t = 2 for the force's `if`, t = 0 and 1 for the driver's `clamp`.
    #[test]
    fn kinks_of_time_alone_are_time_events() {
        let (_, f) = formulated(
            "P { params { lo: 0.5 } gravity [0.0, -9.81];
            body a { mass: 2.0, inertia: 0.5 }
            body b { mass: 1.0, inertia: 0.1, at: [2.0, 0.0, 0.0] }
            revolute pin: ground[0.0, 0.0] ~ a[-1.0, 0.0];
            drive a.phi = clamp(t, 0.0, 1.0);
            force push: b[0.0, 0.0] = [if t > 2.0 { 1.0 } else { 0.0 } + abs(b.x) + max(lo, 1.0), 0.0]; }",
        );
        let names: Vec<&str> = f.switches.iter().map(|(name, _)| name.as_str()).collect();
        assert_eq!(names, ["push: time event", "drive a.phi: time event 1", "drive a.phi: time event 2"]);
        let zero_at = |node: Id| [0.0, 1.0, 2.0].into_iter().find(|&t| eval(&f, node, &[0.3; 6], &[0.1; 6], t) == 0.0);
        let mut instants: Vec<Option<f64>> = f.switches.iter().map(|&(_, node)| zero_at(node)).collect();
        assert_eq!(instants.remove(0), Some(2.0));
        instants.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(instants, [Some(0.0), Some(1.0)]);
    }

    /// Rows and their names come from one place; first rows follow the row counts.
    #[test]
    fn rows_and_names_agree() {
        let (_, f) = formulated(PENDULUM);
        assert_eq!(f.row_names, ["pin: x", "pin: y", "drive a.phi: phi"]);
        assert_eq!(f.first_rows, [0, 2]);
        assert_eq!((f.nq, f.nc, f.phi.len(), f.gamma.len()), (3, 3, 3, 3));
    }

    /// A pendulum pinned at its end: Φ = r^P_ground − r^P_a vanishes on the circle, γ is the
    /// centripetal term, h is its weight, M = diag(m, m, J).
    #[test]
    fn pendulum_equations() {
        let (_, f) = formulated(PENDULUM);
        let phi0 = 0.3f64;
        let q = [phi0.cos(), phi0.sin(), phi0];
        for &row in &f.phi[..2] {
            assert!(eval(&f, row, &q, &[0.0; 3], 0.0).abs() < 1e-15);
        }
        // Pin rows Φ = r_ground − (r + A s′), s′ = (−1, 0): with q̈ = 0, Φ̈ = ω² A s′ = −ω² (cos φ, sin φ),
        // so γ = −Φ̈|q̈=0 = ω² (cos φ, sin φ).
        let w = 2.0;
        let qd = [-w * phi0.sin(), w * phi0.cos(), w];
        let gx = eval(&f, f.gamma[0], &q, &qd, 0.0);
        let gy = eval(&f, f.gamma[1], &q, &qd, 0.0);
        assert!((gx - w * w * phi0.cos()).abs() < 1e-12 && (gy - w * w * phi0.sin()).abs() < 1e-12, "γ = ({gx}, {gy})");
        let h: Vec<f64> = f.h.iter().map(|&n| eval(&f, n, &q, &qd, 0.0)).collect();
        assert_eq!(h, [0.0, -2.0 * 9.81, 0.0]);
        let mass: Vec<f64> = f.mass.iter().map(|&n| eval(&f, n, &q, &qd, 0.0)).collect();
        assert_eq!(mass, [2.0, 2.0, 0.5]);
        assert_eq!(eval(&f, f.nu[2], &q, &qd, 0.0), 2.0, "ν of the driver is ḟ");
    }

    /// The Jacobian's structural non-zeros are exactly the coordinates each row reads.
    #[test]
    fn jacobian_is_sparse() {
        let (_, f) = formulated(PENDULUM);
        let pattern: Vec<(usize, usize)> = f.jacobian.iter().map(|&(r, c, _)| (r, c)).collect();
        assert_eq!(pattern, [(0, 0), (0, 2), (1, 1), (1, 2), (2, 2)]);
    }

    pub(crate) const SPATIAL: &str = "S { spatial; params { k: 30.0 } gravity [0.0, 0.0, -9.81];
        body a { mass: 1.0, inertia: [0.1, 0.2, 0.3], at: [0.1, 0.2, 0.3], angles: [0.3, 0.2, 0.1] }
        body b { mass: 2.0, inertia: [0.2, 0.25, 0.1, 0.01, 0.0, 0.02], at: [0.5, 0.1, 0.2], velocity: [0.1, 0.0, 0.0] }
        revolute hinge: ground[0.0, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ a[0.1, 0.0, 0.0] along [0.0, 0.3, 1.0] { viscous: 0.2 };
        universal a[0.2, 0.1, 0.0] along [1.0, 0.0, 0.0] ~ b[0.0, 0.0, 0.1] along [0.0, 1.0, 0.0];
        cylindrical a[0.0, 0.0, 0.0] along [0.0, 1.0, 0.0] ~ b[0.0, 0.0, 0.0] along [0.0, 1.0, 0.1];
        translational slide: a[0.0, 0.1, 0.0] along [1.0, 0.0, 0.0] reference [0.0, 1.0, 1.0] ~ b[0.1, 0.0, 0.0] along [1.0, 0.2, 0.0];
        planar ground[0.0, 0.0, 1.0] along [0.0, 0.0, 1.0] ~ b[0.0, 0.2, 0.0] along [0.0, 1.0, 1.0];
        rigid a[0.0, 0.0, 0.0] ~ b[0.1, 0.1, 0.1];
        point_on_line ground[0.0, 0.0, 0.0] along [1.0, 1.0, 0.0] ~ b[0.0, 0.0, 0.2];
        point_on_plane a[0.1, 0.0, 0.0] along [0.0, 0.0, 1.0] ~ b[0.0, 0.0, 0.0] { distance: 0.1 };
        distance ground[0.0, 1.0, 0.0] ~ a[0.0, 0.0, 0.3] { length: 0.8 };
        drive hinge.angle = 0.5 * t + 0.2 * t^2; drive slide.stroke = sin(t); drive b.z = 0.1 * t;
        constraint a.x * b.e1 = 0.1 * t;
        spring a[0.0, 0.0, 0.0] ~ b[0.1, 0.0, 0.0] { k: k, length: 0.2, c: 1.0 };
        bushing a[0.0, 0.1, 0.0] ~ b[0.0, 0.0, 0.0] { k: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0], c: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6] };
        rotational_spring hinge { k: 3.0, angle: 0.1, c: 0.2, torque: 0.1 * b.wz };
        torque a = [0.1, 0.2 * a.wx, 0.3]; local_torque b = [0.0, 0.1, t];
        force b[0.0, 0.1, 0.0] = [1.0, 0.0, b.vz]; local_force a[0.1, 0.0, 0.0] = [0.0, 2.0, 0.0]; }";

    /// q̇ = B(q) v per spatial body: ṙ = v_r, ṗ = ½ Lᵀ(p) ω′.
    fn spatial_rates(q: &[f64], v: &[f64]) -> Vec<f64> {
        let mut out = Vec::new();
        for k in 0..q.len() / 7 {
            let (p, w) = (&q[7 * k + 3..7 * k + 7], &v[6 * k + 3..6 * k + 6]);
            out.extend_from_slice(&v[6 * k..6 * k + 3]);
            let lt = [[-p[1], -p[2], -p[3]], [p[0], -p[3], p[2]], [p[3], p[0], -p[1]], [-p[2], p[1], p[0]]];
            out.extend(lt.iter().map(|row| 0.5 * (row[0] * w[0] + row[1] * w[1] + row[2] * w[2])));
        }
        out
    }

    /// Every spatial kind at once, at a state off the constraints (random-ish unit p): D v, γ,
    /// (∂h/∂q) B and ∂h/∂v against central differences along the straight line q + ε B(q) v,
    /// on which d/dε f = f_q B v exactly (so the difference's error is O(ε²) ≈ 1e-10 here).
    #[test]
    fn spatial_derivatives_follow_the_velocity_map() {
        let (model, f) = formulated(SPATIAL);
        assert_eq!((f.nq, f.nv), (14, 12));
        assert_eq!(model.forces.iter().map(|e| e.kind.kind()).collect::<Vec<_>>()[0], "revolute_viscous");
        let unit = |p: [f64; 4]| {
            let n = p.iter().map(|x| x * x).sum::<f64>().sqrt();
            p.map(|x| x / n)
        };
        let (pa, pb) = (unit([0.9, 0.2, -0.3, 0.1]), unit([0.5, -0.4, 0.6, 0.3]));
        let q: Vec<f64> = [0.1, 0.2, 0.3].into_iter().chain(pa).chain([0.5, 0.1, 0.2]).chain(pb).collect();
        let v = [0.3, -0.2, 0.1, 0.7, -0.5, 0.4, -0.1, 0.2, 0.3, -0.6, 0.8, 0.2];
        let t = 0.4;
        let ev = |node: Id, q: &[f64], v: &[f64], t: f64| eval(&f, node, q, v, t);
        let qdot = spatial_rates(&q, &v);
        let at = |e: f64| -> Vec<f64> { q.iter().zip(&qdot).map(|(x, d)| x + e * d).collect() };
        let eps = 1e-5;
        let (qp, qm) = (at(eps), at(-eps));
        // Φ̇ = D v − ν
        let phidot = |q: &[f64], t: f64| -> Vec<f64> {
            let mut out: Vec<f64> = f.nu.iter().map(|&n| -ev(n, q, &v, t)).collect();
            for &(r, c, d) in &f.jacobian {
                out[r] += ev(d, q, &v, t) * v[c];
            }
            out
        };
        let exact = phidot(&q, t);
        for (r, &want) in exact.iter().enumerate() {
            let fd = (ev(f.phi[r], &qp, &v, t + eps) - ev(f.phi[r], &qm, &v, t - eps)) / (2.0 * eps);
            assert!((fd - want).abs() < 1e-8, "{}: D v − ν = {want} but dΦ/dt = {fd}", f.row_names[r]);
        }
        let (fp, fm) = (phidot(&qp, t + eps), phidot(&qm, t - eps));
        for r in 0..f.nc {
            let fd = (fp[r] - fm[r]) / (2.0 * eps);
            let gamma = ev(f.gamma[r], &q, &v, t);
            assert!((fd + gamma).abs() < 1e-7 * (1.0 + gamma.abs()), "{}: γ = {gamma} but −d(Dv − ν)/dt = {}", f.row_names[r], -fd);
        }
        for (i, &h) in f.h.iter().enumerate() {
            let fd = (ev(h, &qp, &v, t) - ev(h, &qm, &v, t)) / (2.0 * eps);
            let exact: f64 = f.h_q.iter().filter(|e| e.0 == i).map(|&(_, c, d)| ev(d, &q, &v, t) * v[c]).sum();
            assert!((fd - exact).abs() < 1e-7 * (1.0 + fd.abs()), "h[{i}]: (h_q B) v = {exact} but dh/dε = {fd}");
            let vp: Vec<f64> = v.iter().map(|x| x * (1.0 + eps)).collect();
            let vm: Vec<f64> = v.iter().map(|x| x * (1.0 - eps)).collect();
            let fd_v = (ev(h, &q, &vp, t) - ev(h, &q, &vm, t)) / (2.0 * eps);
            let exact_v: f64 = f.h_qd.iter().filter(|e| e.0 == i).map(|&(_, c, d)| ev(d, &q, &v, t) * v[c]).sum();
            assert!((fd_v - exact_v).abs() < 1e-7 * (1.0 + fd_v.abs()), "h[{i}]: h_v v = {exact_v} but dh/dε = {fd_v}");
        }
    }

    /// A torque-free spinning body: h is the gyroscopic term −ω′ × J′ω′ alone, M is diag(m I, J′)
    /// with J′'s products of inertia off the diagonal.
    #[test]
    fn gyroscopic_term_and_inertia_tensor() {
        let (_, f) = formulated("T { spatial; body b { mass: 2.0, inertia: [1.0, 2.0, 3.0, 0.5, 0.0, 0.0] } }");
        let w = [0.3, -0.7, 1.1];
        let v = [0.0, 0.0, 0.0, w[0], w[1], w[2]];
        let q = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0];
        let jw = [1.0 * w[0] + 0.5 * w[1], 0.5 * w[0] + 2.0 * w[1], 3.0 * w[2]];
        let gyro = [-(w[1] * jw[2] - w[2] * jw[1]), -(w[2] * jw[0] - w[0] * jw[2]), -(w[0] * jw[1] - w[1] * jw[0])];
        for (a, want) in gyro.into_iter().enumerate() {
            let h = eval(&f, f.h[3 + a], &q, &v, 0.0);
            assert!((h - want).abs() < 1e-15, "h[{}] = {h}, −ω′×J′ω′ = {want}", 3 + a);
        }
        let mass: Vec<f64> = f.mass.iter().map(|&n| eval(&f, n, &q, &v, 0.0)).collect();
        assert_eq!(mass, [2.0, 2.0, 2.0, 1.0, 2.0, 3.0]);
        // J′⁻¹ of [[1, 0.5, 0], [0.5, 2, 0], [0, 0, 3]]: det of the 2×2 block 1.75
        let inverse: Vec<(usize, usize, f64)> = f.mass_inverse.iter().map(|&(r, c, n)| (r, c, eval(&f, n, &q, &v, 0.0))).collect();
        let want = [(3, 3, 2.0 / 1.75), (3, 4, -0.5 / 1.75), (4, 3, -0.5 / 1.75), (4, 4, 1.0 / 1.75), (5, 5, 1.0 / 3.0)];
        assert_eq!(inverse.len(), want.len());
        for ((r, c, x), (wr, wc, w)) in inverse.into_iter().zip(want) {
            assert!((r, c) == (wr, wc) && (x - w).abs() < 1e-15, "({r}, {c}) = {x}, want ({wr}, {wc}) = {w}");
        }
        let coupling: Vec<(usize, usize, f64)> = f.mass_coupling.iter().map(|&(r, c, n)| (r, c, eval(&f, n, &q, &v, 0.0))).collect();
        assert_eq!(coupling, [(3, 4, 0.5), (4, 3, 0.5)]);
    }
}

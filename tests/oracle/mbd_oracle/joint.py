"""Rebuilds a SPATIAL mechanism in JOINT coordinates ("dimension": 3 with a "tree") from mbd's
model JSON with CasADi SX, independently of mbd's own symbolic engine and of its recursions,
as docs/formulation.md, "Spatial joint coordinates", specifies it.

The model JSON's "tree" says, parents first, how each body hangs: its parent, the joint that
carries it (or none: a free body), whether the tree runs the joint from its j side, and its
slots in q and v. Everything else is derived here from the joint table of the spec:

- each body's Euler parameters and position as functions of q, by quaternion products
  (p_j = p_i ⊗ c_i ⊗ z(θ) ⊗ f ⊗ c_j*, or p_i = p_j ⊗ c_j ⊗ f* ⊗ z(−θ) ⊗ c_i* where the tree runs
  the joint backwards; p_c = p_p ⊗ s for a ball joint), with c the marker triad's quaternion and
  f the half-turn nearest the bodies' `at:` poses, both evaluated here;
- q̇ = B(q) v: v = q̇ for angles and strokes, ṡ = ½ Lᵀ(s) ω for a quaternion;
- each body's twist NOT by screws (mbd's route) but by differentiation: ṙ_b = (∂r_b/∂q) q̇ and
  ω′_b = 2 L(p_b) ṗ_b, ṗ_b = (∂p_b/∂q) q̇ (CasADi's jtimes);
- the body-coordinate rebuild (`spatial.Spatial`, every row and force of the spec) evaluated at
  those poses and twists; Φ keeps the rows of the joints the tree does not carry;
- D = Φ_q B, ν = −Φ_t, γ = −𝒟(𝒟Φ) by CasADi, as for body coordinates;
- with J = ∂v_b/∂v: M = Jᵀ M_b J and h = Jᵀ (h_b − M_b J̇ v), J̇ v = (∂v_b/∂q) q̇ at fixed v
  (Jourdain: the bodies' equations projected on the tree's velocities); V the bodies' V;
  h_q = (∂h/∂q) B, h_v = ∂h/∂v; Coulomb friction of a cut joint at its rows' λ.

The class has the attributes and Functions of `spatial.Spatial` that compare.py reads.
"""

import casadi as ca
import numpy as np

from .spatial import Spatial, define_functions, dot, l_matrix, rotation

TURNING = ("revolute", "cylindrical")
SLIDING = ("translational", "cylindrical")
TREE_KINDS = ("revolute", "translational", "cylindrical", "spherical", "rigid")


def has_tree(model_json):
    """A model in joint coordinates (planar or spatial)."""
    return "tree" in model_json


def qmul(a, b):
    """The Hamilton product a ⊗ b of two SX 4-vectors."""
    a0, av = a[0], a[1:4]
    b0, bv = b[0], b[1:4]
    return ca.vertcat(a0 * b0 - dot(av, bv), a0 * bv + b0 * av + ca.cross(av, bv))


def qconj(a):
    return ca.vertcat(a[0], -a[1:4])


class _Tree:
    """What both formulations share once their symbols and expressions are built: the
    Functions compare.py reads, 𝒟, and the KKT forward dynamics. Needs q, v, qdot, t, p, lam,
    B, phi, D, nu, gamma, mass, h, h_q, h_v, potential, friction (+ _q, _v)."""

    def _kinematics(self, phi_all, keep):
        """Φ: the cut rows `keep` of the body model's rows at the tree's poses; D = Φ_q B, ν, γ."""
        self.keep = keep
        self.phi = ca.vertcat(*[phi_all[r] for r in keep]) if keep else ca.SX(0, 1)
        self.nc = self.phi.shape[0]
        self.lam = ca.SX.sym("lambda", self.nc)
        self.D = ca.jacobian(self.phi, self.q) @ self.B
        self.nu = -ca.jacobian(self.phi, self.t)
        self.gamma = -self.rate(self.rate(self.phi))

    def _project(self, qb, vb, body_args, mass_b, body_contributions, body_lam, body_friction, nc_body):
        """The bodies' equations on the tree's velocities (Jourdain): with J = ∂v_b/∂v and J̇ v =
        (∂v_b/∂q) q̇ at fixed v, M = Jᵀ M_b J and each contribution Q_b to h as Jᵀ Q_b, plus the
        tree's inertia −Jᵀ M_b J̇ v; Coulomb friction of the cut joints as Jᵀ f_b(λ_b)."""
        jac = ca.jacobian(vb, self.v)
        bias = ca.jtimes(vb, self.q, self.qdot)
        self.mass = jac.T @ mass_b @ jac
        contributions = []
        for k, (name, q_b, v_b) in enumerate(body_contributions):
            qj, vj = ca.Function(f"Q{k}", body_args, [q_b, v_b])(qb, vb, self.t, self.p)
            contributions.append((name, jac.T @ qj, vj))
        contributions.append(("inertia of the tree", -jac.T @ (mass_b @ bias), ca.SX(0)))
        friction_b = ca.Function("friction_b", body_args + [body_lam], [body_friction])(qb, vb, self.t, self.p, self.cut_multipliers(nc_body))
        self._dynamics(contributions, friction_b, jac)

    def _dynamics(self, contributions, friction_b, jac):
        """h, V, their derivatives and magnitudes from the projected contributions, and the
        friction forces Jᵀ f_b; then the Functions. The contributions are differentiated once,
        stacked ((∂Q/∂q) B by forward derivatives along B's columns): h_q and h_v are the sums
        of their blocks and the floors' magnitudes the sums of the blocks' absolute values, so
        that f_dynamics shares them (the 16-link chain's rebuild took 85 s of one core with a
        Jacobian per contribution and another of h, 2026-12-06)."""
        self.contributions = contributions
        n = self.nv
        zero = ca.SX(n, 1)
        self.h = sum((c[1] for c in contributions), zero)
        self.potential = sum((c[2] for c in contributions), ca.SX(0))
        stacked = ca.vertcat(*[c[1] for c in contributions])
        by_q = ca.jtimes(stacked, self.q, self.B)
        by_v = ca.jacobian(stacked, self.v)
        blocks_q = [by_q[k * n:(k + 1) * n, :] for k in range(len(contributions))]
        blocks_v = [by_v[k * n:(k + 1) * n, :] for k in range(len(contributions))]
        self.h_q = sum(blocks_q, ca.SX(n, n))
        self.h_v = sum(blocks_v, ca.SX(n, n))
        mags = [sum((ca.fabs(c[1]) for c in contributions), zero),
                sum((ca.fabs(b) for b in blocks_q), ca.SX(n, n)),
                sum((ca.fabs(b) for b in blocks_v), ca.SX(n, n)),
                sum((ca.fabs(c[2]) for c in contributions), ca.SX(0))]
        self.friction = jac.T @ friction_b
        self.friction_q = ca.jacobian(self.friction, self.q) @ self.B
        self.friction_v = ca.jacobian(self.friction, self.v)
        fmags = [ca.fabs(self.friction), ca.fabs(self.friction_q), ca.fabs(self.friction_v),
                 ca.fabs(ca.jacobian(self.friction, self.lam))]
        define_functions(self, mags, fmags)

    def cut_multipliers(self, nc_body):
        """λ_b of the body model: the cut rows' λ in their places, zero for the tree's rows."""
        lam_b = [ca.SX(0)] * nc_body
        for i, r in enumerate(self.keep):
            lam_b[r] = self.lam[i]
        return ca.vertcat(*lam_b) if lam_b else ca.SX(0, 1)

    def rate(self, s):
        """𝒟s = (∂s/∂q) B(q) v + ∂s/∂t."""
        return ca.jtimes(s, self.q, self.qdot) + ca.jacobian(s, self.t)

    def params_vector(self, named):
        if isinstance(named, (list, tuple, np.ndarray)):
            return [float(x) for x in named]
        defaults = {p["name"]: p["default"] for p in self.json["params"]}
        return [named.get(n, defaults[n]) for n in self.param_names]

    def structural_jacobian(self):
        sp = self.D.sparsity()
        return set(zip(sp.row(), sp.get_col()))

    # the dense KKT solve reads only the Functions above, as for body coordinates
    forward = Spatial.forward


class JointSpatial(_Tree):
    """The symbolic equations of a spatial mechanism in joint coordinates (see the module)."""

    def __init__(self, model):
        if not has_tree(model):
            raise ValueError(f"{model.get('name')}: not a spatial model in joint coordinates")
        self.json = model
        self.name = model["name"]
        body_json = {k: v for k, v in model.items() if k not in ("tree", "coordinates", "velocities")}
        self.body = Spatial(body_json)
        b = self.body
        self.bodies = b.bodies
        self.param_names = b.param_names
        self.t, self.p = b.t, b.p
        self.tree = model["tree"]
        self.nq = sum(link["nq"] for link in self.tree)
        self.nv = sum(link["nv"] for link in self.tree)
        self.q = ca.SX.sym("q", self.nq)
        self.v = ca.SX.sym("v", self.nv)
        self.constraints = {c["name"]: c for c in model["constraints"]}
        self.defaults = np.array(b.params_vector({}), dtype=float)
        self.q0_bodies, _ = b.initial_state()

        # q̇ = B(q) v per link, and the names of the spec's table
        self.B = ca.SX(self.nq, self.nv)
        self.coordinate_names, self.velocity_names, self.quaternions = [], [], []
        for link in sorted(self.tree, key=lambda link: link["q"]):  # q's order: the bodies declared
            self.link_map(link)
        self.qdot = self.B @ self.v

        # poses along the tree, then the body-coordinate state
        placed = {}
        for link in self.tree:
            placed[link["body"]] = self.place(link, placed)
        qb = ca.vertcat(*[ca.vertcat(placed[n][0], placed[n][1]) for n in self.bodies])
        rates = lambda x: ca.jtimes(x, self.q, self.qdot)  # noqa: E731  (v held fixed)
        twists = []  # ṙ and ω′ = 2 L(p) ṗ
        for n in self.bodies:
            r, p = placed[n]
            twists.append(ca.vertcat(rates(r), 2 * l_matrix(p) @ rates(p)))
        vb = ca.vertcat(*twists)

        # kinematics: the cut rows
        carried = {link["joint"] for link in self.tree if link["joint"] is not None}
        keep = []
        for c in model["constraints"]:
            first = b.first_row[c["name"]]
            count = len(b.constraint(c)[0])
            if c["name"] not in carried:
                keep.extend(range(first, first + count))
        self.row_names = [b.row_names[r] for r in keep]
        self._kinematics(ca.Function("phi_b", [b.q, b.t, b.p], [b.phi])(qb, self.t, self.p), keep)
        # dynamics by Jourdain's principle over the bodies; Coulomb friction of the cut joints
        self.has_friction = b.has_friction
        self._project(qb, vb, [b.q, b.v, b.t, b.p], b.mass, [c[:3] for c in b.contributions], b.lam, b.friction, b.nc)

    # --- the tree ------------------------------------------------------------------------------
    def link_map(self, link):
        """B's block, the coordinates' and velocities' names of one link."""
        q0, v0, nq, nv = link["q"], link["v"], link["nq"], link["nv"]
        joint = link["joint"]
        owner = link["body"] if joint is None else joint
        if joint is None:
            names, quaternion_at = ["x", "y", "z", "e0", "e1", "e2", "e3"], 3
        else:
            kind = self.constraints[joint]["kind"]
            names = {"revolute": ["angle"], "translational": ["stroke"], "cylindrical": ["angle", "stroke"],
                     "spherical": ["e0", "e1", "e2", "e3"], "rigid": []}[kind]
            quaternion_at = 0 if kind == "spherical" else None
        if len(names) != nq:
            raise ValueError(f"{self.name}: the tree gives {link['body']} {nq} coordinates, its joint has {len(names)}")
        self.coordinate_names += [f"{owner}.{n}" for n in names]
        if quaternion_at is None:
            for i in range(nq):
                self.B[q0 + i, v0 + i] = 1
            self.velocity_names += [f"{owner}.{n}" for n in names]
            return
        for i in range(quaternion_at):
            self.B[q0 + i, v0 + i] = 1
        e = self.q[q0 + quaternion_at:q0 + quaternion_at + 4]
        self.B[q0 + quaternion_at:q0 + quaternion_at + 4, v0 + quaternion_at:v0 + quaternion_at + 3] = 0.5 * l_matrix(e).T
        self.quaternions.append(q0 + quaternion_at)
        self.velocity_names += [f"{owner}.v{a}" for a in "xyz"][:quaternion_at] + [f"{owner}.w{a}" for a in "xyz"]

    def local_triad(self, marker):
        """C = [x′ y′ z′] of a marker in its body's axes (SX 3×3)."""
        b = self.body
        a = b.vec(marker["axis"])
        z = a / ca.norm_2(a)
        r = b.vec(marker["reference"])
        xr = r - dot(r, z) * z
        x = xr / ca.norm_2(xr)
        return ca.horzcat(x, ca.cross(z, x), z)

    def numeric(self, x):
        """An SX expression of the parameters at their defaults."""
        return np.array(ca.Function("n", [self.p], [x])(self.defaults))

    def marker_quaternion(self, marker):
        """The quaternion of a marker's triad: Shepperd's formula on the branch of the largest of
        1 + tr C, 1 + 2 C_kk − tr C at the defaults (each exact where its root is real)."""
        c = self.local_triad(marker)
        tr = c[0, 0] + c[1, 1] + c[2, 2]
        candidates = [1 + tr] + [1 + 2 * c[k, k] - tr for k in range(3)]
        k = int(np.argmax([float(self.numeric(x)) for x in candidates]))
        w = 0.5 * ca.sqrt(candidates[k])
        if k == 0:
            return ca.vertcat(w, (c[2, 1] - c[1, 2]) / (4 * w), (c[0, 2] - c[2, 0]) / (4 * w), (c[1, 0] - c[0, 1]) / (4 * w))
        if k == 1:
            return ca.vertcat((c[2, 1] - c[1, 2]) / (4 * w), w, (c[0, 1] + c[1, 0]) / (4 * w), (c[0, 2] + c[2, 0]) / (4 * w))
        if k == 2:
            return ca.vertcat((c[0, 2] - c[2, 0]) / (4 * w), (c[0, 1] + c[1, 0]) / (4 * w), w, (c[1, 2] + c[2, 1]) / (4 * w))
        return ca.vertcat((c[1, 0] - c[0, 1]) / (4 * w), (c[0, 2] + c[2, 0]) / (4 * w), (c[1, 2] + c[2, 1]) / (4 * w), w)

    def initial_rotation(self, body):
        if body == "ground":
            return np.eye(3)
        k = self.bodies.index(body)
        e0, e = self.q0_bodies[7 * k + 3], np.asarray(self.q0_bodies[7 * k + 4:7 * k + 7])
        tilde = np.array([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
        return (2 * e0**2 - 1) * np.eye(3) + 2 * (np.outer(e, e) + e0 * tilde)

    def half_turn(self, kind, i, j):
        """f: the identity or a half-turn about x, y or z, nearest C_iᵀ A_iᵀ A_j C_j at the bodies'
        initial poses (for a turning joint: the identity or the half-turn about x, by z_iᵀ z_j)."""
        ci, cj = self.numeric(self.local_triad(i)), self.numeric(self.local_triad(j))
        d = ci.T @ self.initial_rotation(i["body"]).T @ self.initial_rotation(j["body"]) @ cj
        signs = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
        if kind in TURNING:
            best = 1 if d[2, 2] < 0 else 0
        else:
            best = int(np.argmax([sum(s[k] * d[k, k] for k in range(3)) for s in signs]))
        quaternion = ca.SX(4, 1)
        quaternion[best] = 1.0  # 1, or the half-turn (0, e_k) about axis k
        return quaternion

    def place(self, link, placed):
        """(r, p) of a link's body from its parent's."""
        q = self.q[link["q"]:link["q"] + link["nq"]]
        if link["joint"] is None:
            return q[0:3], q[3:7]
        joint = self.constraints[link["joint"]]
        kind = joint["kind"]
        if kind not in TREE_KINDS:
            raise ValueError(f"{self.name}: the tree carries {joint['name']}, a {kind} joint, which has no relative coordinates")
        i, j = joint["i"], joint["j"]
        parent_side, child_side = (j, i) if link["reversed"] else (i, j)
        if parent_side["body"] != link["parent"] or child_side["body"] != link["body"]:
            raise ValueError(f"{self.name}: the tree's link of {link['body']} does not match {joint['name']}'s bodies")
        rp, pp = (ca.SX.zeros(3, 1), ca.vertcat(1, 0, 0, 0)) if link["parent"] == "ground" else placed[link["parent"]]
        b = self.body
        if kind == "spherical":
            relative = q[0:4]
        else:
            theta = q[0] if kind in TURNING else ca.SX(0)
            ci, cj = self.marker_quaternion(i), self.marker_quaternion(j)
            f = self.half_turn(kind, i, j)
            if link["reversed"]:
                z = ca.vertcat(ca.cos(-theta / 2), 0, 0, ca.sin(-theta / 2))
                relative = qmul(qmul(qmul(cj, qconj(f)), z), qconj(ci))
            else:
                z = ca.vertcat(ca.cos(theta / 2), 0, 0, ca.sin(theta / 2))
                relative = qmul(qmul(qmul(ci, z), f), qconj(cj))
        p = qmul(pp, relative)
        a_parent, a_child = rotation(pp), rotation(p)
        r = rp + a_parent @ b.vec(parent_side["point"]) - a_child @ b.vec(child_side["point"])
        if kind in SLIDING:
            s = q[1] if kind == "cylindrical" else q[0]
            a_i = a_child if link["reversed"] else a_parent
            z_i = a_i @ self.local_triad(i)[:, 2]
            r = r + (-s if link["reversed"] else s) * z_i
        return r, p


# Row labels of the planar constraint kinds (docs/formulation.md, "Constraint rows").
PLANAR_ROWS = {"revolute": ("x", "y"), "translational": ("normal", "angle"), "revolute_revolute": ("length",),
               "revolute_translational": ("distance",), "rigid": ("x", "y", "angle"), "drive_angle": ("angle",),
               "drive_distance": ("distance",), "constraint": ("user",)}


def planar_row_names(c):
    """"name: label" of each row of a planar constraint of the model JSON."""
    labels = (c["coordinate"],) if c["kind"] in ("drive", "fix") else PLANAR_ROWS[c["kind"]]
    return [f"{c['name']}: {label}" for label in labels]


class JointPlanar(_Tree):
    """A PLANAR mechanism in joint coordinates ("tree" without "dimension": 3), as
    docs/formulation.md, "Planar joint coordinates", specifies it: each body's pose from its
    parent's (revolute φ_j = φ_i + θ; rigid φ_j = φ_i + angle; translational φ_j = φ_i + α_i − α_j
    (+ π where the axes point apart at the bodies' `at:` poses) and P_j = P_i + s u_i), v = q̇, the
    twists by differentiation, the body-coordinate rebuild (model.py, dynamics.py) evaluated there
    and projected on the tree's velocities (M = Jᵀ M_b J, h = Jᵀ (h_b − M_b J̇ v)). Samples use
    the spatial keys ("v", dense "mass", "h_v"), so the comparison is `SpatialJointLayout`'s."""

    def __init__(self, model):
        from .dynamics import Dynamics
        from .model import Model

        self.json = model
        self.name = model["name"]
        body_json = {k: v for k, v in model.items() if k not in ("tree", "velocities")}
        body_json["coordinates"] = [f"{b['name']}.{c}" for b in model["bodies"] for c in ("x", "y", "phi")]
        self.body = b = Model(body_json)
        db = Dynamics(b)
        self.bodies = b.bodies
        self.param_names = b.param_names
        self.t, self.p = b.t, b.p
        self.tree = model["tree"]
        self.nq = self.nv = sum(link["nq"] for link in self.tree)
        self.q = ca.SX.sym("q", self.nq)
        self.v = ca.SX.sym("v", self.nv)
        self.qdot = self.v
        self.B = ca.SX.eye(self.nq)
        self.quaternions = []
        self.constraints = {c["name"]: c for c in model["constraints"]}
        self.defaults = np.array([p["default"] for p in model["params"]], dtype=float)
        self.coordinate_names = []
        for link in sorted(self.tree, key=lambda link: link["q"]):
            if link["joint"] is None:
                self.coordinate_names += [f"{link['body']}.{c}" for c in ("x", "y", "phi")]
            else:
                kind = self.constraints[link["joint"]]["kind"]
                self.coordinate_names += {"revolute": [f"{link['joint']}.angle"], "translational": [f"{link['joint']}.stroke"],
                                          "rigid": []}[kind]
        self.velocity_names = list(self.coordinate_names)

        placed = {}
        for link in self.tree:
            placed[link["body"]] = self.place(link, placed)
        qb = ca.vertcat(*[ca.vertcat(*placed[n]) for n in self.bodies])
        vb = ca.jtimes(qb, self.q, self.v)

        carried = {link["joint"] for link in self.tree if link["joint"] is not None}
        keep, first = [], 0
        for c in model["constraints"]:
            count = len(b.constraint(c))
            if c["name"] not in carried:
                keep.extend(range(first, first + count))
            first += count
        self.row_names = [name for c in model["constraints"] if c["name"] not in carried for name in planar_row_names(c)]
        body_args = [b.q, b.qd, b.t, b.p]
        self._kinematics(ca.Function("phi_b", body_args, [b.phi])(qb, vb, self.t, self.p), keep)
        self.has_friction = db.has_friction
        self._project(qb, vb, body_args, ca.diag(db.mass), db.contributions, db.lam, db.friction, b.nc)

    def initial_pose(self, body):
        """(x, y, φ) of a body's `at:` at the parameters' defaults; the ground's zeros."""
        if body == "ground":
            return np.zeros(3)
        at = next(b for b in self.json["bodies"] if b["name"] == body)["q0"]
        return np.array([float(ca.Function("n", [self.p], [self.body.expr(e)])(self.defaults)) for e in at])

    def place(self, link, placed):
        """(x, y, φ) of a link's body from its parent's."""
        q = self.q[link["q"]:link["q"] + link["nq"]]
        if link["joint"] is None:
            return [q[0], q[1], q[2]]
        joint = self.constraints[link["joint"]]
        kind, i, j = joint["kind"], joint["i"], joint["j"]
        parent_side, child_side = (j, i) if link["reversed"] else (i, j)
        parent = [ca.SX(0)] * 3 if link["parent"] == "ground" else placed[link["parent"]]
        sign = -1 if link["reversed"] else 1
        if kind == "revolute":
            turn = q[0]
        elif kind == "rigid":
            turn = self.body.expr(joint["angle"])
        elif kind == "translational":
            alpha = [ca.atan2(self.body.expr(side["axis"][1]), self.body.expr(side["axis"][0])) for side in (i, j)]
            turn = alpha[0] - alpha[1]
            pi0, pj0 = self.initial_pose(i["body"]), self.initial_pose(j["body"])
            if np.cos(pj0[2] + float(ca.Function("n", [self.p], [alpha[1] - alpha[0]])(self.defaults)) - pi0[2]) < 0:
                turn = turn + np.pi
        else:
            raise ValueError(f"{self.name}: the tree carries {joint['name']}, a {kind} joint, which has no relative coordinates")
        phi = parent[2] + sign * turn

        def rot(angle, point):
            x, y = self.body.expr(point[0]), self.body.expr(point[1])
            return [ca.cos(angle) * x - ca.sin(angle) * y, ca.sin(angle) * x + ca.cos(angle) * y]

        arm_p, arm_c = rot(parent[2], parent_side["point"]), rot(phi, child_side["point"])
        r = [parent[a] + arm_p[a] - arm_c[a] for a in range(2)]
        if kind == "translational":
            phi_i = phi if link["reversed"] else parent[2]
            a = [self.body.expr(x) for x in i["axis"]]
            norm = ca.sqrt(a[0] ** 2 + a[1] ** 2)
            u = [(ca.cos(phi_i) * a[0] - ca.sin(phi_i) * a[1]) / norm, (ca.sin(phi_i) * a[0] + ca.cos(phi_i) * a[1]) / norm]
            r = [r[k] + sign * q[0] * u[k] for k in range(2)]
        return [r[0], r[1], phi]

"""Rebuilds a SPATIAL mechanism ("dimension": 3) from mbd's model JSON with CasADi SX,
independently of mbd's own symbolic engine, exactly as docs/formulation.md, "Spatial bodies",
specifies it. Nothing here is transcribed from mbd's Rust.

Symbols: q (7 per moving body: x, y, z, e0, e1, e2, e3), v (6 per body: ṙ global, ω′ body
frame), t, p (the parameters, model order) and lam (one per constraint row).

- A(p) = (2 e0² − 1) I + 2 (e eᵀ + e0 ẽ), exactly this polynomial; L(p) = [−e, −ẽ + e0 I];
  q̇ = B(q) v with ṙ = v_r, ṗ = ½ Lᵀ ω′.
- Markers: z′ = a′/|a′|, x′ = Gram–Schmidt of the reference b′ against z′, y′ = z′ × x′; global
  triads are A times these.
- Φ(q, t, p) row by row from the spec's joint and driver tables; then, all by CasADi:
  D = Φ_q B, ν = −Φ_t, γ = −𝒟(𝒟Φ) with 𝒟f = jtimes(f, q, B v) + ∂f/∂t (v held fixed).
- M = blockdiag(m I₃, J′); h by virtual power: an element that applies the force f to the rate
  ṡ(q, v, t) contributes Q = (∂ṡ/∂v)ᵀ f, where ṡ = 𝒟s and ∂/∂v are CasADi's; plus the
  gyroscopic −ω′ × J′ω′ per body. V is the sum of the elements' potentials.
- h_q = (∂h/∂q) B and h_v = ∂h/∂v; Coulomb friction at a λ symbol with its (∂/∂q) B and ∂/∂v.
- Forward dynamics: [M, −Dᵀ; D, 0] [v̇; λ] = [h (+ friction); γ − 2α(D v − ν) − β² Φ], dense,
  with NumPy (with friction, λ by Newton on the fixed point, as for planar models).

Every CasADi Function takes (q, v, t, p) (and lam where it says so).
"""

import casadi as ca
import numpy as np

from .dynamics import solve_friction_fixed_point
from .model import expression

COORDS = ("x", "y", "z", "e0", "e1", "e2", "e3")
VELS = ("vx", "vy", "vz", "wx", "wy", "wz")

# Row names of every joint and driver kind (docs/formulation.md, tables "Markers" and "Drivers").
JOINT_ROWS = {
    "spherical": ("x", "y", "z"),
    "universal": ("x", "y", "z", "cross"),
    "revolute": ("x", "y", "z", "axis_x", "axis_y"),
    "cylindrical": ("axis_x", "axis_y", "offset_x", "offset_y"),
    "translational": ("axis_x", "axis_y", "offset_x", "offset_y", "twist"),
    "planar": ("normal_x", "normal_y", "offset"),
    "rigid": ("x", "y", "z", "rx", "ry", "rz"),
    "orientation": ("rx", "ry", "rz"),
    "point_on_line": ("offset_x", "offset_y"),
    "point_on_plane": ("offset",),
    "distance": ("length",),
}


def is_spatial(model_json):
    """True for a spatial model JSON ("dimension": 3); planar JSON has 2 or no "dimension"."""
    return model_json.get("dimension", 2) == 3


def rotation(p):
    """A(p) = (2 e0² − 1) I + 2 (e eᵀ + e0 ẽ) of a 4-vector p = (e0, e1, e2, e3) (SX)."""
    e0, e = p[0], p[1:4]
    return (2 * e0**2 - 1) * ca.SX.eye(3) + 2 * (e @ e.T + e0 * ca.skew(e))


def l_matrix(p):
    """L(p) = [−e, −ẽ + e0 I] (3×4)."""
    e0, e = p[0], p[1:4]
    return ca.horzcat(-e, -ca.skew(e) + e0 * ca.SX.eye(3))


def cross(a, b):
    return ca.cross(a, b)


def dot(a, b):
    return ca.dot(a, b)


def define_functions(m, mags, fmags):
    """The CasADi Functions of a rebuilt spatial model m (body or joint coordinates) that compare.py
    reads, of (q, v, t, p) and, for friction, λ: from m's q, v, t, p, lam, B, phi, D, nu, gamma,
    mass, h, h_q, h_v, potential and friction terms, and the magnitudes of the floors."""
    args, names = [m.q, m.v, m.t, m.p], ["q", "v", "t", "p"]
    F = lambda n, outs, outnames: ca.Function(n, args, outs, names, outnames)  # noqa: E731
    m.f_phi = F("phi", [m.phi], ["phi"])
    m.f_jac = F("jacobian", [m.D], ["jacobian"])
    m.f_nu = F("nu", [m.nu], ["nu"])
    m.f_gamma = F("gamma", [m.gamma], ["gamma"])
    # γ's derivatives (∂γ/∂q) B and ∂γ/∂v, for the generated Linearize::gamma_derivatives.
    m.f_gamma_derivatives = F("gamma_derivatives", [ca.jacobian(m.gamma, m.q) @ m.B, ca.jacobian(m.gamma, m.v)],
                              ["gamma_q", "gamma_v"])
    m.f_kinematics = F("kinematics", [m.phi, m.D, m.nu, m.gamma], ["phi", "jacobian", "nu", "gamma"])
    m.f_B = F("B", [m.B], ["B"])
    m.f_mass = F("mass", [m.mass], ["mass"])
    m.f_h = F("h", [m.h], ["h"])
    m.f_h_q = F("h_q", [m.h_q], ["h_q"])
    m.f_h_v = F("h_v", [m.h_v], ["h_v"])
    m.f_potential = F("potential", [m.potential], ["potential"])
    # What compare.py reads at each sample, in one Function so that the values and the floors'
    # magnitudes share their subexpressions (evaluated once, not once per Function).
    m.f_dynamics = F("dynamics", [m.mass, m.h, m.h_q, m.h_v, m.potential] + mags,
                     ["mass", "h", "h_q", "h_v", "potential", "h_mag", "h_q_mag", "h_v_mag", "potential_mag"])
    contributions = m.contributions
    m.f_contributions = F("contributions", [c[1] for c in contributions] + [c[2] for c in contributions],
                          [f"Q{k}" for k in range(len(contributions))] + [f"V{k}" for k in range(len(contributions))])
    fargs, fnames = args + [m.lam], names + ["lambda"]
    m.f_friction = ca.Function("friction", fargs, [m.friction, m.friction_q, m.friction_v, ca.jacobian(m.friction, m.lam)], fnames,
                               ["friction", "friction_q", "friction_v", "friction_slope"])
    m.f_friction_lambda = ca.Function("friction_lambda", fargs, [ca.jacobian(m.friction, m.lam)], fnames,
                                      ["friction_lambda"])
    m.f_friction_magnitudes = ca.Function("friction_magnitudes", fargs, fmags, fnames,
                                          ["friction", "friction_q", "friction_v", "friction_slope"])


class Spatial:
    """The symbolic equations of one spatial mechanism (kinematics and dynamics).

    Attributes (SX): q (NQ), v (NV), t, p, lam (NC); B (NQ×NV); phi, D (= Φ_q B), nu, gamma;
    mass (NV×NV), h, h_q (= (∂h/∂q) B), h_v, potential; friction, friction_q, friction_v;
    row_names, coordinate_names, velocity_names; contributions: (name, Q, V, conservative) of
    gravity on each body, each force element and each body's gyroscopic term.
    Functions of (q, v, t, p): f_phi, f_jac (D), f_nu, f_gamma, f_kinematics, f_mass, f_h,
    f_h_q, f_h_v, f_potential, f_dynamics (these five and the floors' magnitudes), f_B,
    f_contributions; of (q, v, t, p, lam): f_friction, f_friction_lambda, f_friction_magnitudes.
    """

    def __init__(self, model):
        if not is_spatial(model):
            raise ValueError(f"{model.get('name')}: not a spatial model (\"dimension\": 3)")
        self.json = model
        self.name = model["name"]
        self.bodies = [b["name"] for b in model["bodies"]]
        nb = len(self.bodies)
        self.nq, self.nv = 7 * nb, 6 * nb
        self.param_names = [p["name"] for p in model["params"]]
        self.coordinate_names = [f"{b}.{c}" for b in self.bodies for c in COORDS]
        self.velocity_names = [f"{b}.{c}" for b in self.bodies for c in VELS]
        self.q = ca.SX.sym("q", self.nq)
        self.v = ca.SX.sym("v", self.nv)
        self.t = ca.SX.sym("t")
        self.p = ca.SX.sym("p", len(self.param_names))
        # The velocity map q̇ = B(q) v, per body [[I₃, 0], [0, ½ Lᵀ]].
        blocks = []
        for k in range(nb):
            b = ca.SX(7, 6)  # structural zeros (SX.zeros would be dense zeros, and D's pattern with them)
            b[0:3, 0:3] = ca.SX.eye(3)
            b[3:7, 3:6] = 0.5 * l_matrix(self.q[7 * k + 3:7 * k + 7]).T
            blocks.append(b)
        self.B = ca.diagcat(*blocks) if blocks else ca.SX(0, 0)
        self.qdot = self.B @ self.v if nb else ca.SX(0, 1)

        # --- constraints -----------------------------------------------------------------
        self.joints = {c["name"]: c for c in model["constraints"] if c["kind"] in JOINT_ROWS}
        rows, names, self.first_row = [], [], {}
        for c in model["constraints"]:
            self.first_row[c["name"]] = len(rows)
            values, labels = self.constraint(c)
            rows.extend(values)
            names.extend(f"{c['name']}: {label}" for label in labels)
        self.row_names = names
        self.phi = ca.vertcat(*rows) if rows else ca.SX(0, 1)
        self.nc = self.phi.shape[0]
        self.lam = ca.SX.sym("lambda", self.nc)
        self.D = ca.jacobian(self.phi, self.q) @ self.B
        self.phi_t = ca.jacobian(self.phi, self.t)
        self.nu = -self.phi_t
        # γ = −𝒟(𝒟Φ): two directional derivatives along q̇ = B(q) v (v fixed) plus t-derivatives.
        phi_dot = self.rate(self.phi)
        self.gamma = -self.rate(phi_dot)

        # --- dynamics --------------------------------------------------------------------
        self.masses = [self.expr(b["mass"]) for b in model["bodies"]]
        self.inertias = [ca.vertcat(*[ca.horzcat(*[self.expr(e) for e in row]) for row in b["inertia"]])
                         for b in model["bodies"]]
        mass_blocks = [ca.diagcat(m * ca.SX.eye(3), j) for m, j in zip(self.masses, self.inertias)]
        self.mass = ca.diagcat(*mass_blocks) if mass_blocks else ca.SX(0, 0)
        contributions = []
        gravity = model.get("gravity")
        if gravity is not None:
            g = self.vec(gravity)
            for k, body in enumerate(self.bodies):
                r = self.position(body)
                name, q = self.at_point(f"gravity on {body}", r, self.masses[k] * g)
                contributions.append((name, q, -self.masses[k] * dot(g, r), True))
        friction = []
        for f in model.get("forces", []):
            if f["kind"].endswith("_coulomb"):
                friction.append(self.coulomb(f))
            else:
                contributions.append(self.element(f))
        for k, body in enumerate(self.bodies):
            w = self.omega_body(body)
            q = ca.vertcat(ca.SX(6 * k + 3, 1), -cross(w, self.inertias[k] @ w), ca.SX(6 * (nb - k - 1), 1))
            contributions.append((f"gyroscopic {body}", q, ca.SX(0), True))
        self.contributions = contributions
        nv = self.nv
        zero = ca.SX(nv, 1)
        self.h = sum((c[1] for c in contributions), zero)
        self.potential = sum((c[2] for c in contributions), ca.SX(0))
        self.h_q = ca.jacobian(self.h, self.q) @ self.B
        self.h_v = ca.jacobian(self.h, self.v)
        mags = [sum((ca.fabs(c[1]) for c in contributions), zero),
                sum((ca.fabs(ca.jacobian(c[1], self.q) @ self.B) for c in contributions), ca.SX(nv, nv)),
                sum((ca.fabs(ca.jacobian(c[1], self.v)) for c in contributions), ca.SX(nv, nv)),
                sum((ca.fabs(c[2]) for c in contributions), ca.SX(0))]
        self.has_friction = bool(friction)
        self.friction_contributions = friction
        self.friction = sum((q for _, q in friction), zero)
        self.friction_q = ca.jacobian(self.friction, self.q) @ self.B
        self.friction_v = ca.jacobian(self.friction, self.v)
        fmags = [sum((ca.fabs(q) for _, q in friction), zero),
                 sum((ca.fabs(ca.jacobian(q, self.q) @ self.B) for _, q in friction), ca.SX(nv, nv)),
                 sum((ca.fabs(ca.jacobian(q, self.v)) for _, q in friction), ca.SX(nv, nv)),
                 sum((ca.fabs(ca.jacobian(q, self.lam)) for _, q in friction), ca.SX(nv, self.nc))]

        define_functions(self, mags, fmags)

    # --- expressions -----------------------------------------------------------------------
    def expr(self, e):
        """An expression tree (docs/formulation.md) as CasADi SX; coord/vel use spatial names."""
        return expression(self, e)

    def opt(self, e):
        """An optional expression (null: 0)."""
        return ca.SX(0) if e is None else self.expr(e)

    def vec(self, es):
        return ca.vertcat(*[self.expr(e) for e in es])

    # --- body kinematics ---------------------------------------------------------------------
    def coord(self, body, c):
        if body == "ground":
            return ca.SX(1.0 if c == "e0" else 0.0)
        return self.q[7 * self.bodies.index(body) + COORDS.index(c)]

    def velocity(self, body, c):
        if body == "ground":
            return ca.SX(0)
        return self.v[6 * self.bodies.index(body) + VELS.index(c)]

    def position(self, body):
        if body == "ground":
            return ca.SX.zeros(3, 1)
        k = self.bodies.index(body)
        return self.q[7 * k:7 * k + 3]

    def euler(self, body):
        k = self.bodies.index(body)
        return self.q[7 * k + 3:7 * k + 7]

    def A(self, body):
        if body == "ground":
            return ca.SX.eye(3)
        return rotation(self.euler(body))

    def omega_body(self, body):
        """ω′ (body frame)."""
        if body == "ground":
            return ca.SX.zeros(3, 1)
        k = self.bodies.index(body)
        return self.v[6 * k + 3:6 * k + 6]

    def rate(self, s):
        """𝒟s = (∂s/∂q) B(q) v + ∂s/∂t: the total time derivative along q̇ = B v."""
        return ca.jtimes(s, self.q, self.qdot) + ca.jacobian(s, self.t)

    def point(self, side):
        """r + A s′ of {"body", "point": [E, E, E]}."""
        return self.position(side["body"]) + self.A(side["body"]) @ self.vec(side["point"])

    def triad(self, marker, what):
        """The global (x, y, z) unit vectors of a marker (None where the marker does not carry
        what the kind needs). what: "z" (axis only) or "xyz" (axis and reference)."""
        if "axis" not in marker:
            raise ValueError(f"{self.name}: a marker on {marker['body']} needs an axis")
        a = self.vec(marker["axis"])
        z = a / ca.norm_2(a)
        rot = self.A(marker["body"])
        if what == "z":
            return None, None, rot @ z
        if "reference" not in marker:
            raise ValueError(f"{self.name}: a marker on {marker['body']} needs a reference")
        b = self.vec(marker["reference"])
        xr = b - dot(b, z) * z
        x = xr / ca.norm_2(xr)
        y = cross(z, x)
        return rot @ x, rot @ y, rot @ z

    # --- constraint rows ---------------------------------------------------------------------
    def constraint(self, c):
        """(rows, row labels) of one constraint of the model JSON."""
        kind = c["kind"]
        if kind in JOINT_ROWS:
            return self.joint(c), JOINT_ROWS[kind]
        if kind in ("drive_angle", "drive_stroke"):
            joint = self.joints.get(c["joint"])
            if joint is None:
                raise ValueError(f"{self.name}: {c['name']} drives {c['joint']!r}, which is no joint of the model")
            f = self.expr(c["f"])
            if kind == "drive_angle":
                if joint["kind"] not in ("revolute", "cylindrical"):
                    raise ValueError(f"{self.name}: {c['name']}: an angle drive needs a revolute or cylindrical joint")
                xi, yi, _ = self.triad(joint["i"], "xyz")
                xj, _, _ = self.triad(joint["j"], "xyz")
                return [dot(yi, xj) * ca.cos(f) - dot(xi, xj) * ca.sin(f)], ("angle",)
            if joint["kind"] not in ("translational", "cylindrical"):
                raise ValueError(f"{self.name}: {c['name']}: a stroke drive needs a translational or cylindrical joint")
            _, _, zi = self.triad(joint["i"], "z")
            d = self.point(joint["j"]) - self.point(joint["i"])
            return [dot(zi, d) - f], ("stroke",)
        if kind in ("drive", "fix"):
            if c["coordinate"] not in ("x", "y", "z"):
                raise ValueError(f"{self.name}: {c['name']}: a spatial {kind} is on x, y or z")
            value = c["f"] if kind == "drive" else c["value"]
            return [self.coord(c["body"], c["coordinate"]) - self.expr(value)], (c["coordinate"],)
        if kind == "constraint":
            return [self.expr(c["expr"])], ("user",)
        raise ValueError(f"{self.name}: unknown spatial constraint kind {kind!r}")

    def joint(self, c):
        kind, mi, mj = c["kind"], c["i"], c["j"]
        pi, pj = self.point(mi), self.point(mj)
        d = pj - pi
        if kind == "spherical":
            return list(ca.vertsplit(pi - pj))
        if kind == "universal":
            _, _, zi = self.triad(mi, "z")
            _, _, zj = self.triad(mj, "z")
            return list(ca.vertsplit(pi - pj)) + [dot(zi, zj)]
        if kind == "distance":
            length = self.expr(c["length"])
            return [(dot(d, d) - length ** 2) / (2 * length)]
        if kind == "point_on_plane":
            _, _, zi = self.triad(mi, "z")
            return [dot(zi, d) - self.expr(c["distance"])]
        xi, yi, zi = self.triad(mi, "xyz")
        if kind == "point_on_line":
            return [dot(xi, d), dot(yi, d)]
        if kind in ("revolute", "cylindrical", "planar"):
            _, _, zj = self.triad(mj, "z")
            if kind == "revolute":
                return list(ca.vertsplit(pi - pj)) + [dot(xi, zj), dot(yi, zj)]
            if kind == "cylindrical":
                return [dot(xi, zj), dot(yi, zj), dot(xi, d), dot(yi, d)]
            return [dot(xi, zj), dot(yi, zj), dot(zi, d)]
        xj, yj, zj = self.triad(mj, "xyz")
        if kind == "translational":
            return [dot(xi, zj), dot(yi, zj), dot(xi, d), dot(yi, d), dot(xi, yj)]
        if kind == "rigid":
            return list(ca.vertsplit(pi - pj)) + [dot(yi, zj), dot(zi, xj), dot(xi, yj)]
        if kind == "orientation":
            return [dot(yi, zj), dot(zi, xj), dot(xi, yj)]
        raise ValueError(f"{self.name}: unknown joint kind {kind!r}")

    # --- joint coordinates for force elements ------------------------------------------------
    def joint_angle(self, name):
        """θ_J = atan2(y_iᵀ x_j, x_iᵀ x_j) of a revolute or cylindrical joint."""
        joint = self.joints[name]
        if joint["kind"] not in ("revolute", "cylindrical"):
            raise ValueError(f"{self.name}: {name} is no revolute or cylindrical joint")
        xi, yi, _ = self.triad(joint["i"], "xyz")
        xj, _, _ = self.triad(joint["j"], "xyz")
        return ca.atan2(dot(yi, xj), dot(xi, xj))

    def joint_stroke(self, name):
        """s_J = z_iᵀ d of a translational or cylindrical joint."""
        joint = self.joints[name]
        if joint["kind"] not in ("translational", "cylindrical"):
            raise ValueError(f"{self.name}: {name} is no translational or cylindrical joint")
        _, _, zi = self.triad(joint["i"], "z")
        return dot(zi, self.point(joint["j"]) - self.point(joint["i"]))

    def bushing_components(self, mi, mj):
        """δ = (x_iᵀd, y_iᵀd, z_iᵀd, z_iᵀy_j, x_iᵀz_j, y_iᵀx_j)."""
        xi, yi, zi = self.triad(mi, "xyz")
        xj, yj, zj = self.triad(mj, "xyz")
        d = self.point(mj) - self.point(mi)
        return [dot(xi, d), dot(yi, d), dot(zi, d), dot(zi, yj), dot(xi, zj), dot(yi, xj)]

    # --- force elements ----------------------------------------------------------------------
    def power(self, force, s):
        """Q = (∂ṡ/∂v)ᵀ f of a force f (scalar or vector) working on the rate ṡ = 𝒟s."""
        return ca.jacobian(self.rate(s), self.v).T @ force

    def at_point(self, name, r, force):
        """A global force at the point r(q): Q = (∂ṙ/∂v)ᵀ F."""
        return name, self.power(force, r)

    def element(self, f):
        """(name, Q, V, conservative) of one force element."""
        kind, name = f["kind"], f["name"]
        if kind == "point_to_point":
            d = self.point(f["j"]) - self.point(f["i"])
            length = ca.norm_2(d)
            k, c = self.opt(f["k"]), self.opt(f["c"])
            free = self.expr(f["length"])
            tension = k * (length - free) + c * self.rate(length) + self.opt(f["force"])
            v = 0.5 * k * (length - free) ** 2 if f["k"] is not None else ca.SX(0)
            # The tension pulls the points together: it works on l̇ as −f.
            return name, self.power(-tension, length), v, f["c"] is None and f["force"] is None
        if kind in ("contact", "cable", "tyre"):
            # docs/formulation.md: a force that pushes only while its overlap s is positive
            pi, pj = self.point(f["i"]), self.point(f["j"])
            k, c = self.expr(f["k"]), self.opt(f["c"])
            if kind == "contact":
                n = self.vec(f["normal"])
                n = self.A(f["j"]["body"]) @ (n / ca.norm_2(n))
                s = ca.dot(n, pj - pi)
                e = self.expr(f["exponent"])
                push, v, works = s ** e * (k + c * self.rate(s)), k * s ** (e + 1) / (e + 1), s
            else:
                if kind == "cable":
                    length = ca.norm_2(pj - pi)
                    s, works = length - self.expr(f["length"]), length
                else:
                    s = pj[2] + self.expr(f["road"]) + self.expr(f["radius"]) - pi[2]
                    works = s
                push, v = k * s + c * self.rate(s), 0.5 * k * s ** 2
            force = ca.if_else(s > 0, ca.fmax(push, 0), 0)
            return name, self.power(-force, works), ca.if_else(s > 0, v, 0), f["c"] is None
        if kind == "rotational":
            theta = self.joint_angle(f["joint"])
            k, c = self.opt(f["k"]), self.opt(f["c"])
            angle = self.expr(f["angle"])
            torque = k * (theta - angle) + c * self.rate(theta) + self.opt(f["torque"])
            v = 0.5 * k * (theta - angle) ** 2 if f["k"] is not None else ca.SX(0)
            return name, self.power(-torque, theta), v, f["c"] is None and f["torque"] is None
        if kind == "translational":
            s = self.joint_stroke(f["joint"])
            k, c = self.opt(f["k"]), self.opt(f["c"])
            length = self.expr(f["length"])
            force = k * (s - length) + c * self.rate(s) + self.opt(f["force"])
            v = 0.5 * k * (s - length) ** 2 if f["k"] is not None else ca.SX(0)
            return name, self.power(-force, s), v, f["c"] is None and f["force"] is None
        if kind == "bushing":
            delta = self.bushing_components(f["i"], f["j"])
            q, v = ca.SX(self.nv, 1), ca.SX(0)
            for comp, k_e, c_e, pre in zip(delta, f["k"], f["c"], f["preload"]):
                k, c, d0 = self.opt(k_e), self.opt(c_e), self.expr(pre)
                force = k * (comp - d0) + c * self.rate(comp)
                q = q + self.power(-force, comp)
                if k_e is not None:
                    v = v + 0.5 * k * (comp - d0) ** 2
            return name, q, v, all(c is None for c in f["c"])
        if kind in ("force", "local_force"):
            side = f["at"]
            force = self.vec(f["force"])
            if kind == "local_force":
                force = self.A(side["body"]) @ force
            return (*self.at_point(name, self.point(side), force), ca.SX(0), False)
        if kind == "torque":
            body = f["body"]
            omega = self.A(body) @ self.omega_body(body)  # global ω = A ω′
            return name, ca.jacobian(omega, self.v).T @ self.vec(f["torque"]), ca.SX(0), False
        if kind == "local_torque":
            return name, ca.jacobian(self.omega_body(f["body"]), self.v).T @ self.vec(f["torque"]), ca.SX(0), False
        if kind == "revolute_viscous":
            theta = self.joint_angle(f["joint"])
            return name, self.power(-self.expr(f["c"]) * self.rate(theta), theta), ca.SX(0), False
        if kind == "translational_viscous":
            s = self.joint_stroke(f["joint"])
            return name, self.power(-self.expr(f["c"]) * self.rate(s), s), ca.SX(0), False
        raise ValueError(f"{self.name}: unknown spatial force element kind {kind!r}")

    def coulomb(self, f):
        """(name, Q) of a joint's Coulomb friction: a function of q, v, t, p and lam."""
        kind, name, row = f["kind"], f["name"], f["row"]
        joint = self.joints.get(f["joint"])
        want = {"revolute_coulomb": "revolute", "translational_coulomb": "translational"}.get(kind)
        if want is None:
            raise ValueError(f"{self.name}: unknown friction kind {kind!r}")
        if joint is None or joint["kind"] != want:
            raise ValueError(f"{self.name}: {name} needs a {want} joint, {f['joint']!r} is not one")
        if row != self.first_row[joint["name"]]:
            raise ValueError(f"{self.name}: {name} says its joint's rows start at {row}, they start at {self.first_row[joint['name']]}")
        mu, slip = self.expr(f["mu"]), self.expr(f["slip_velocity"])
        lam = self.lam
        if kind == "revolute_coulomb":
            theta = self.joint_angle(f["joint"])
            load = ca.sqrt(lam[row] ** 2 + lam[row + 1] ** 2 + lam[row + 2] ** 2)
            rate = self.rate(theta)
            torque = mu * self.expr(f["radius"]) * load * rate / ca.sqrt(rate**2 + slip**2)
            return name, self.power(-torque, theta)
        s = self.joint_stroke(f["joint"])
        load = ca.sqrt(lam[row + 2] ** 2 + lam[row + 3] ** 2)
        rate = self.rate(s)
        force = mu * load * rate / ca.sqrt(rate**2 + slip**2)
        return name, self.power(-force, s)

    # --- evaluation ----------------------------------------------------------------------------
    def params_vector(self, named):
        """Parameter values in model order from a {name: value} mapping (defaults fill gaps) or a
        list already in model order."""
        if isinstance(named, (list, tuple, np.ndarray)):
            if len(named) != len(self.param_names):
                raise ValueError(f"{self.name}: {len(named)} parameter values for {len(self.param_names)} parameters")
            return [float(x) for x in named]
        defaults = {p["name"]: p["default"] for p in self.json["params"]}
        return [named.get(n, defaults[n]) for n in self.param_names]

    def initial_state(self, p=None):
        """(q0, v0) of the bodies' "q0" and "v0" at parameters p (defaults)."""
        p = self.params_vector({}) if p is None else p
        q0 = ca.vertcat(*[self.expr(e) for b in self.json["bodies"] for e in b["q0"]])
        v0 = ca.vertcat(*[self.expr(e) for b in self.json["bodies"] for e in b["v0"]])
        f = ca.Function("initial", [self.p, self.t], [q0, v0])
        a, b = f(p, 0.0)
        return np.array(a).reshape(-1), np.array(b).reshape(-1)

    def structural_jacobian(self):
        """(row, column) of CasADi's structural non-zeros of D = Φ_q B."""
        sp = self.D.sparsity()
        return set(zip(sp.row(), sp.get_col()))

    def forward(self, q, v, t, p, alpha, beta):
        """[M, −Dᵀ; D, 0] [v̇; λ] = [h; γ − 2α (D v − ν) − β² Φ] (with Coulomb friction, h + f(λ)
        at the fixed point in λ), solved by LU. Returns (v̇, λ, cond₂ of the matrix)."""
        nv, nc = self.nv, self.nc
        args = (q, v, t, p)
        mass = np.array(self.f_mass(*args))
        h = np.array(self.f_h(*args)).reshape(-1)
        phi, jac, nu, gamma = (np.array(x) for x in self.f_kinematics(*args))
        phi, nu, gamma = phi.reshape(-1), nu.reshape(-1), gamma.reshape(-1)
        kkt = np.zeros((nv + nc, nv + nc))
        kkt[:nv, :nv] = mass
        kkt[:nv, nv:] = -jac.T
        kkt[nv:, :nv] = jac
        rhs = np.concatenate([h, gamma - 2.0 * alpha * (jac @ np.asarray(v, dtype=float) - nu) - beta**2 * phi])
        if self.has_friction:
            x = solve_friction_fixed_point(self.name, kkt, rhs, h, args, nv, self.f_friction, self.f_friction_lambda)
        else:
            x = np.linalg.solve(kkt, rhs)
        return x[:nv], x[nv:], float(np.linalg.cond(kkt))

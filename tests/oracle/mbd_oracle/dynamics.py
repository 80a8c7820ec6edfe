"""The dynamics of a mechanism rebuilt from its model JSON with CasADi SX, independently of mbd:
the mass matrix, the generalized applied forces h(q, q̇, t) of gravity and of every force
element, the potential energy V(q, t), CasADi's own ∂h/∂q and ∂h/∂q̇, and a numerical forward
dynamics solve of the equations of motion.

Every generalized force is derived here by virtual work from the element's definition (README.md,
"Force elements"; docs/formulation.md), not transcribed from mbd's formulas: an element that
does the virtual work δW = Fᵀ δr_P at a point, or τ δθ on an angle, or −f δl on a distance,
contributes Q = (∂r_P/∂q)ᵀ F, τ (∂θ/∂q)ᵀ or −f (∂l/∂q)ᵀ, with the partial derivatives taken by
CasADi. Rates (l̇, θ̇, ṡ) are total time derivatives, l̇ = (∂l/∂q) q̇ + ∂l/∂t, also by CasADi.

Sign conventions (README.md): a point-to-point element's tension f = k (l − length) + c l̇ +
force pulls its two points together (it resists l = |r_Pj − r_Pi|); a rotational element's torque
τ = k (θ − angle) + c θ̇ + torque resists θ = φ_j − φ_i; joint viscous friction c θ̇ (revolute,
θ = φ_j − φ_i) or c ṡ (translational, s = u_iᵀ (r_Pj − r_Pi), u_i the unit axis on body i)
resists the relative motion; gravity g acts on every body's centre of mass; torques are
counter-clockwise positive. Absent options (null in the JSON) contribute nothing.
"""

import casadi as ca
import numpy as np

from .model import Model


class Dynamics:
    """M, h, ∂h/∂q, ∂h/∂q̇ and V of one mechanism, on top of its kinematic Model.

    Attributes (CasADi SX, in the Model's symbols q, qd, t, p): mass (NQ, the diagonal of M),
    h (NQ), h_q = ∂h/∂q, h_qd = ∂h/∂q̇ (NQ×NQ), potential (scalar V), and for the tolerances the
    magnitudes h_mag, h_q_mag, h_qd_mag, potential_mag: the sums over gravity and the force
    elements of the absolute values of each one's contribution (what the rounding of a sum of
    those contributions is relative to).
    Functions (inputs q, qd, t, p): f_mass, f_h, f_h_q, f_h_qd, f_potential, f_magnitudes.
    """

    def __init__(self, model: Model):
        self.model = m = model
        self.name = m.name
        nq = m.nq
        contributions = []  # (name, Q (NQ SX), V (SX))
        gravity = m.json.get("gravity")
        masses = [m.expr(b["mass"]) for b in m.json["bodies"]]
        inertias = [m.expr(b["inertia"]) for b in m.json["bodies"]]
        if gravity is not None:
            g = [m.expr(gravity[0]), m.expr(gravity[1])]
            for k, body in enumerate(m.bodies):
                r = [m.coord(body, "x"), m.coord(body, "y")]
                contributions.append(self.at_point(f"gravity on {body}", r, [masses[k] * g[0], masses[k] * g[1]],
                                                   -masses[k] * (g[0] * r[0] + g[1] * r[1])))
        for f in m.json.get("forces", []):
            contributions.append(self.element(f))
        self.contributions = contributions
        zero = ca.SX.zeros(nq, 1)
        self.mass = ca.vertcat(*[v for k in range(len(m.bodies)) for v in (masses[k], masses[k], inertias[k])]) if nq else zero
        self.h = sum((q for _, q, _ in contributions), zero)
        self.potential = sum((v for _, _, v in contributions), ca.SX(0))
        self.h_q = ca.jacobian(self.h, m.q)
        self.h_qd = ca.jacobian(self.h, m.qd)
        self.h_mag = sum((ca.fabs(q) for _, q, _ in contributions), zero)
        self.h_q_mag = sum((ca.fabs(ca.jacobian(q, m.q)) for _, q, _ in contributions), ca.SX.zeros(nq, nq))
        self.h_qd_mag = sum((ca.fabs(ca.jacobian(q, m.qd)) for _, q, _ in contributions), ca.SX.zeros(nq, nq))
        self.potential_mag = sum((ca.fabs(v) for _, _, v in contributions), ca.SX(0))
        args = [m.q, m.qd, m.t, m.p]
        names = ["q", "qd", "t", "p"]
        self.f_mass = ca.Function("mass", args, [self.mass], names, ["mass"])
        self.f_h = ca.Function("h", args, [self.h], names, ["h"])
        self.f_h_q = ca.Function("h_q", args, [self.h_q], names, ["h_q"])
        self.f_h_qd = ca.Function("h_qd", args, [self.h_qd], names, ["h_qd"])
        self.f_potential = ca.Function("potential", args, [self.potential], names, ["potential"])
        self.f_magnitudes = ca.Function("magnitudes", args, [self.h_mag, self.h_q_mag, self.h_qd_mag, self.potential_mag], names,
                                        ["h", "h_q", "h_qd", "potential"])
        self.f_kinematics = ca.Function("kinematics", args, [m.phi, m.jac, m.nu, m.gamma], names, ["phi", "jacobian", "nu", "gamma"])

    # --- derivatives and rates --------------------------------------------------------------
    def grad(self, s):
        """(∂s/∂q)ᵀ: the NQ column of partial derivatives of a scalar s(q, qd, t, p)."""
        return ca.jacobian(s, self.model.q).T

    def rate(self, s):
        """ds/dt = (∂s/∂q) q̇ + ∂s/∂t of a scalar s(q, t, p)."""
        m = self.model
        return ca.jtimes(s, m.q, m.qd) + ca.jacobian(s, m.t)

    def opt(self, e):
        """An optional expression (null: 0)."""
        return ca.SX(0) if e is None else self.model.expr(e)

    def at_point(self, name, r, force, potential=ca.SX(0)):
        """A force (global components) acting at the point r(q): δW = Fᵀ δr, Q = (∂r/∂q)ᵀ F."""
        r = ca.vertcat(*r)
        q = ca.jacobian(r, self.model.q).T @ ca.vertcat(*force)
        return name, q, potential

    # --- force elements ----------------------------------------------------------------------
    def element(self, f):
        """(name, Q, V) of one force element of the model JSON."""
        m = self.model
        kind, name = f["kind"], f["name"]
        if kind == "point_to_point":
            pi, pj = m.point(f["i"]), m.point(f["j"])
            d = [pj[0] - pi[0], pj[1] - pi[1]]
            length = ca.sqrt(d[0] ** 2 + d[1] ** 2)
            k, c = self.opt(f["k"]), self.opt(f["c"])
            free = m.expr(f["length"])
            tension = k * (length - free) + c * self.rate(length) + self.opt(f["force"])
            # The tension pulls the points together: δW = −f δl.
            v = 0.5 * k * (length - free) ** 2 if f["k"] is not None else ca.SX(0)
            return name, -tension * self.grad(length), v
        if kind == "rotational":
            theta = m.coord(f["j"], "phi") - m.coord(f["i"], "phi")
            k, c = self.opt(f["k"]), self.opt(f["c"])
            angle = m.expr(f["angle"])
            torque = k * (theta - angle) + c * self.rate(theta) + self.opt(f["torque"])
            v = 0.5 * k * (theta - angle) ** 2 if f["k"] is not None else ca.SX(0)
            return name, -torque * self.grad(theta), v
        if kind in ("force", "local_force"):
            side = f["at"]
            components = [m.expr(f["force"][0]), m.expr(f["force"][1])]
            if kind == "local_force":
                components = m.rotate(side["body"], components)
            return self.at_point(name, m.point(side), components)
        if kind == "torque":
            return name, m.expr(f["torque"]) * self.grad(m.coord(f["body"], "phi")), ca.SX(0)
        if kind == "revolute_viscous":
            theta = m.coord(f["j"], "phi") - m.coord(f["i"], "phi")
            return name, -m.expr(f["c"]) * self.rate(theta) * self.grad(theta), ca.SX(0)
        if kind == "translational_viscous":
            pi, pj = m.point(f["i"]), m.point(f["j"])
            u = m.unit_axis(f["i"])
            s = m.dot(u, [pj[0] - pi[0], pj[1] - pi[1]])
            return name, -m.expr(f["c"]) * self.rate(s) * self.grad(s), ca.SX(0)
        raise ValueError(f"{self.name}: unknown force element kind {kind!r}")

    # --- forward dynamics ----------------------------------------------------------------------
    def forward(self, q, qd, t, p, alpha, beta):
        """Solves the equations of motion with Baumgarte stabilization for (q̈, λ):

            [ M    −Φ_qᵀ ] [ q̈ ]   [ h                                ]
            [ Φ_q   0    ] [ λ  ] = [ γ − 2α (Φ_q q̇ − ν) − β² Φ         ]

        (M q̈ − Φ_qᵀ λ = h; Φ̇ = Φ_q q̇ + Φ_t = Φ_q q̇ − ν), with every piece evaluated by CasADi
        and the system solved by LU (numpy.linalg.solve). Returns (q̈, λ, cond₂ of the matrix).
        """
        nq, nc = self.model.nq, self.model.nc
        args = (q, qd, t, p)
        mass = np.array(self.f_mass(*args)).reshape(-1)
        h = np.array(self.f_h(*args)).reshape(-1)
        phi, jac, nu, gamma = (np.array(x) for x in self.f_kinematics(*args))
        phi, nu, gamma = phi.reshape(-1), nu.reshape(-1), gamma.reshape(-1)
        kkt = np.zeros((nq + nc, nq + nc))
        kkt[:nq, :nq] = np.diag(mass)
        kkt[:nq, nq:] = -jac.T
        kkt[nq:, :nq] = jac
        rhs = np.concatenate([h, gamma - 2.0 * alpha * (jac @ np.asarray(qd, dtype=float) - nu) - beta**2 * phi])
        x = np.linalg.solve(kkt, rhs)
        return x[:nq], x[nq:], float(np.linalg.cond(kkt))

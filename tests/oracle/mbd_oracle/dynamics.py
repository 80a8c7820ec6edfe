"""The dynamics of a mechanism rebuilt from its model JSON with CasADi SX, independently of mbd:
the mass matrix, the generalized applied forces h(q, q̇, t) of gravity and of every force
element, the potential energy V(q, t), CasADi's own ∂h/∂q and ∂h/∂q̇, and a numerical forward
dynamics solve of the equations of motion.

Every generalized force is derived here by virtual work from the element's definition (guide/dsl.md,
"Force elements"; docs/formulation.md), not transcribed from mbd's formulas: an element that
does the virtual work δW = Fᵀ δr_P at a point, or τ δθ on an angle, or −f δl on a distance,
contributes Q = (∂r_P/∂q)ᵀ F, τ (∂θ/∂q)ᵀ or −f (∂l/∂q)ᵀ, with the partial derivatives taken by
CasADi. Rates (l̇, θ̇, ṡ) are total time derivatives, l̇ = (∂l/∂q) q̇ + ∂l/∂t, also by CasADi.

Coulomb friction in joints (docs/formulation.md, "Coulomb friction") depends on the joints'
reactions λ as well; it is rebuilt apart from h, as mbd keeps it apart: given λ (a symbol
`lam`), a revolute joint's normal load is N = √(λ_x² + λ_y²) of its two rows and its friction
torque τ = μ R N ω/√(ω² + v_s²) resists θ = φ_j − φ_i; a translational joint's load is |λ_n|, or
with a bearing length w, |λ_n/2 + λ_a/w| + |λ_n/2 − λ_a/w|, and its force f = μ N ṡ/√(ṡ² + v_s²)
resists s. The forward-dynamics solve then finds the fixed point in λ by Newton.

Sign conventions (guide/dsl.md): a point-to-point element's tension f = k (l − length) + c l̇ +
force pulls its two points together (it resists l = |r_Pj − r_Pi|); a rotational element's torque
τ = k (θ − angle) + c θ̇ + torque resists θ = φ_j − φ_i; joint viscous friction c θ̇ (revolute,
θ = φ_j − φ_i) or c ṡ (translational, s = u_iᵀ (r_Pj − r_Pi), u_i the unit axis on body i)
resists the relative motion; gravity g acts on every body's centre of mass; torques are
counter-clockwise positive. Absent options (null in the JSON) contribute nothing.
"""

import casadi as ca
import numpy as np

from .model import Model


class NoFixedPoint(Exception):
    """Newton found no λ = Λ(λ) with Coulomb friction (at a random state there may be none: the
    friction paradoxes of Painlevé)."""


def solve_friction_fixed_point(name, kkt, rhs, h, args, n, f_friction, f_friction_lambda):
    """[ẍ; λ] of K [ẍ; λ] = [h + f(args, λ); rhs_c] with Coulomb friction f (n = the size of h,
    f_friction(*args, λ)[0] = f, f_friction_lambda(*args, λ) = ∂f/∂λ): λ solves λ = Λ(λ), Λ(λ)
    the λ part of K⁻¹ [h + f(λ); rhs_c]. Not mbd's algorithm (fixed-point iteration): twenty
    fixed-point steps for a start, then Newton on Λ(λ) − λ with CasADi's ∂f/∂λ, to a step of
    1e-14 relative or the rounding floor of the solves."""
    rhs = rhs.copy()

    def solve(lam):
        rhs[:n] = h + np.array(f_friction(*args, lam)[0]).reshape(-1)
        return np.linalg.solve(kkt, rhs)

    x = np.linalg.solve(kkt, rhs)
    for _ in range(20):
        x = solve(x[n:])
    lam = x[n:]
    previous = np.inf
    for _ in range(50):
        x = solve(lam)
        residual = x[n:] - lam
        d_f = np.array(f_friction_lambda(*args, lam))
        # ∂Λ/∂λ = the λ rows of K⁻¹ [∂f/∂λ; 0].
        d_lambda = np.linalg.solve(kkt, np.vstack([d_f, np.zeros((len(lam), len(lam)))]))[n:]
        step = np.linalg.solve(np.eye(len(lam)) - d_lambda, residual)
        lam = lam + step
        # Converged: a step of 1e-14 relative, or steps that stopped shrinking below 1e-11
        # (Newton's quadratic convergence has reached the rounding of the solves).
        size = np.max(np.abs(step)) / max(1.0, float(np.max(np.abs(lam))))
        if size <= 1e-14 or (size <= 1e-11 and size > 0.5 * previous):
            return solve(lam)
        previous = size
    raise NoFixedPoint(f"{name}: Newton found no friction fixed point λ = Λ(λ)")


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
        self.lam = ca.SX.sym("lambda", m.nc)
        friction = []  # (name, Q (NQ SX)) of the Coulomb joints, functions of lam too
        for f in m.json.get("forces", []):
            if f["kind"].endswith("_coulomb"):
                friction.append(self.coulomb(f))
            else:
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
        # Friction forces at given λ, their ∂/∂q and ∂/∂q̇ (at fixed λ), and the magnitudes
        # Σ_joints |Q_e| (and of its derivatives) for the tolerances.
        self.has_friction = bool(friction)
        self.friction = sum((q for _, q in friction), zero)
        self.friction_q = ca.jacobian(self.friction, m.q)
        self.friction_qd = ca.jacobian(self.friction, m.qd)
        friction_mag = [sum((ca.fabs(q) for _, q in friction), zero),
                        sum((ca.fabs(ca.jacobian(q, m.q)) for _, q in friction), ca.SX.zeros(nq, nq)),
                        sum((ca.fabs(ca.jacobian(q, m.qd)) for _, q in friction), ca.SX.zeros(nq, nq)),
                        sum((ca.fabs(ca.jacobian(q, self.lam)) for _, q in friction), ca.SX.zeros(nq, m.nc))]
        fargs = args + [self.lam]
        fnames = names + ["lambda"]
        # ... and ∂/∂λ, the slope in the loads (Dynamics::friction_multiplier_derivatives), NQ × NC.
        self.f_friction = ca.Function("friction", fargs,
                                      [self.friction, self.friction_q, self.friction_qd, ca.jacobian(self.friction, self.lam)], fnames,
                                      ["friction", "friction_q", "friction_qd", "friction_slope"])
        self.f_friction_lambda = ca.Function("friction_lambda", fargs, [ca.jacobian(self.friction, self.lam)], fnames,
                                             ["friction_lambda"])
        self.f_friction_magnitudes = ca.Function("friction_magnitudes", fargs, friction_mag, fnames,
                                                 ["friction", "friction_q", "friction_qd", "friction_slope"])

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
        if kind in ("contact", "cable", "tyre"):
            return self.unilateral(f)
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

    def unilateral(self, f):
        """(name, Q, V) of a contact, cable or tyre (docs/formulation.md): a force that pushes only
        while its overlap s(q, t) is positive, and does work −F δs."""
        m = self.model
        kind = f["kind"]
        pi, pj = m.point(f["i"]), m.point(f["j"])
        k, c = m.expr(f["k"]), self.opt(f["c"])
        if kind == "contact":
            n = [m.expr(x) for x in f["normal"]]
            norm = ca.sqrt(n[0] ** 2 + n[1] ** 2)
            n = m.rotate(f["j"]["body"], [n[0] / norm, n[1] / norm])
            s = n[0] * (pj[0] - pi[0]) + n[1] * (pj[1] - pi[1])
            e = m.expr(f["exponent"])
            push, v = s ** e * (k + c * self.rate(s)), k * s ** (e + 1) / (e + 1)
        else:
            if kind == "cable":
                length = ca.sqrt((pj[0] - pi[0]) ** 2 + (pj[1] - pi[1]) ** 2)
                s = length - m.expr(f["length"])
            else:
                s = pj[1] + m.expr(f["road"]) + m.expr(f["radius"]) - pi[1]
            push, v = k * s + c * self.rate(s), 0.5 * k * s ** 2
        force = ca.if_else(s > 0, ca.fmax(push, 0), 0)
        # a cable's tension works on its length: δW = −F δl
        works_on = length if kind == "cable" else s
        return f["name"], -force * self.grad(works_on), ca.if_else(s > 0, v, 0)

    def coulomb(self, f):
        """(name, Q) of a joint's Coulomb friction, a function of q, q̇, t, p and lam."""
        m = self.model
        kind, name, row = f["kind"], f["name"], f["row"]
        mu, slip = m.expr(f["mu"]), m.expr(f["slip_velocity"])
        if kind == "revolute_coulomb":
            theta = m.coord(f["j"], "phi") - m.coord(f["i"], "phi")
            load = ca.sqrt(self.lam[row] ** 2 + self.lam[row + 1] ** 2)
            omega = self.rate(theta)
            torque = mu * m.expr(f["radius"]) * load * omega / ca.sqrt(omega**2 + slip**2)
            return name, -torque * self.grad(theta)
        if kind == "translational_coulomb":
            pi, pj = m.point(f["i"]), m.point(f["j"])
            s = m.dot(m.unit_axis(f["i"]), [pj[0] - pi[0], pj[1] - pi[1]])
            if f["bearing"] is None:
                load = ca.fabs(self.lam[row])
            else:
                half, moment = self.lam[row] / 2, self.lam[row + 1] / m.expr(f["bearing"])
                load = ca.fabs(half + moment) + ca.fabs(half - moment)
            sdot = self.rate(s)
            force = mu * load * sdot / ca.sqrt(sdot**2 + slip**2)
            return name, -force * self.grad(s)
        raise ValueError(f"{self.name}: unknown friction kind {kind!r}")

    # --- forward dynamics ----------------------------------------------------------------------
    def friction_fixed_point(self, kkt, rhs, h, args):
        """[q̈; λ] with Coulomb friction (see solve_friction_fixed_point)."""
        return solve_friction_fixed_point(self.name, kkt, rhs, h, args, self.model.nq, self.f_friction, self.f_friction_lambda)

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
        if self.has_friction:
            x = self.friction_fixed_point(kkt, rhs, h, args)
        return x[:nq], x[nq:], float(np.linalg.cond(kkt))

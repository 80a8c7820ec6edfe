"""Rebuilds a mechanism from mbd's model JSON with CasADi SX, independently of mbd's own symbolic
engine: every joint, driver and expression is implemented here from docs/formulation.md, and all
derivatives are CasADi's.

Body k owns q[3k:3k+3] = (x, y, phi); ground has no coordinates (x = y = phi = 0).
"""

import math

import casadi as ca


_BINARY = {"add": lambda x, y: x + y, "sub": lambda x, y: x - y, "mul": lambda x, y: x * y,
           "div": lambda x, y: x / y, "pow": lambda x, y: x ** y, "atan2": ca.atan2}
_UNARY = {"neg": lambda x: -x, "sin": ca.sin, "cos": ca.cos, "tan": ca.tan, "asin": ca.asin,
          "acos": ca.acos, "atan": ca.atan, "sqrt": ca.sqrt, "exp": ca.exp, "ln": ca.log,
          "abs": ca.fabs, "sign": ca.sign}
# the non-smooth functions, from CasADi's own primitives (docs/formulation.md, "Expressions")
_BINARY.update({"min": ca.fmin, "max": ca.fmax})
_OTHER = {"clamp": lambda x, lo, hi: ca.fmin(ca.fmax(x, lo), hi),
          "if_gt": lambda a, b, x, y: ca.if_else(a > b, x, y),
          "if_ge": lambda a, b, x, y: ca.if_else(a >= b, x, y)}


def expression(model, e):
    """An expression tree (docs/formulation.md) as CasADi SX, for a planar or spatial rebuild:
    `model` supplies t, p, param_names, name, and coord(body, c) / velocity(body, c) in its own
    coordinate names."""
    op = e[0]
    if op == "num":
        return ca.SX(e[1])
    if op == "pi":
        return ca.SX(math.pi)
    if op == "t":
        return model.t
    if op == "param":
        return model.p[model.param_names.index(e[1])]
    if op == "coord":
        return model.coord(e[1], e[2])
    if op == "vel":
        return model.velocity(e[1], e[2])
    a = [expression(model, x) for x in e[1:]]
    if op in _BINARY:
        return _BINARY[op](a[0], a[1])
    if op in _UNARY:
        return _UNARY[op](a[0])
    if op in _OTHER:
        return _OTHER[op](*a)
    raise ValueError(f"{model.name}: unknown expression node {op!r}")


class Model:
    """The symbolic equations of one mechanism.

    Attributes (CasADi SX): q, qd (NQ), t (scalar), p (one entry per parameter, model order),
    phi (NC), jac = dphi/dq, phi_t, nu = -phi_t, gamma.
    Functions (casadi.Function, inputs q, qd, t, p): f_phi, f_jac, f_nu, f_gamma.
    """

    def __init__(self, model):
        self.json = model
        self.name = model["name"]
        self.bodies = [b["name"] for b in model["bodies"]]
        self.nq = 3 * len(self.bodies)
        self.param_names = [p["name"] for p in model["params"]]
        self.q = ca.SX.sym("q", self.nq)
        self.qd = ca.SX.sym("qd", self.nq)
        self.t = ca.SX.sym("t")
        self.p = ca.SX.sym("p", len(self.param_names))
        rows = []
        for c in model["constraints"]:
            rows.extend(self.constraint(c))
        self.phi = ca.vertcat(*rows) if rows else ca.SX(0, 1)
        self.nc = self.phi.shape[0]
        self.jac = ca.jacobian(self.phi, self.q)
        self.phi_t = ca.jacobian(self.phi, self.t)
        self.nu = -self.phi_t
        # gamma = -(phi_q qd)_q qd - 2 phi_qt qd - phi_tt: the second total time derivative of phi
        # with qdd = 0, built from CasADi's directional derivatives (jtimes) and jacobians.
        phi_dot = ca.jtimes(self.phi, self.q, self.qd) + self.phi_t
        phi_ddot = ca.jtimes(phi_dot, self.q, self.qd) + ca.jacobian(phi_dot, self.t)
        self.gamma = -phi_ddot
        args = [self.q, self.qd, self.t, self.p]
        names = ["q", "qd", "t", "p"]
        self.f_phi = ca.Function("phi", args, [self.phi], names, ["phi"])
        self.f_jac = ca.Function("jacobian", args, [self.jac], names, ["jacobian"])
        self.f_nu = ca.Function("nu", args, [self.nu], names, ["nu"])
        self.f_gamma = ca.Function("gamma", args, [self.gamma], names, ["gamma"])
        # γ's derivatives, for the generated Linearize::gamma_derivatives.
        self.f_gamma_derivatives = ca.Function("gamma_derivatives", args,
                                               [ca.jacobian(self.gamma, self.q), ca.jacobian(self.gamma, self.qd)],
                                               names, ["gamma_q", "gamma_v"])

    # --- expressions -----------------------------------------------------------------------
    def expr(self, e):
        """An expression tree (docs/formulation.md) as CasADi SX."""
        return expression(self, e)

    # --- kinematics of body-fixed points and vectors ---------------------------------------------
    COORDS = {"x": 0, "y": 1, "phi": 2}

    def coord(self, body, c):
        if body == "ground":
            return ca.SX(0)
        return self.q[3 * self.bodies.index(body) + self.COORDS[c]]

    def velocity(self, body, c):
        if body == "ground":
            return ca.SX(0)
        return self.qd[3 * self.bodies.index(body) + self.COORDS[c]]

    def rotate(self, body, v):
        """A(phi) v for the body's angle phi."""
        phi = self.coord(body, "phi")
        c, s = ca.cos(phi), ca.sin(phi)
        return [c * v[0] - s * v[1], s * v[0] + c * v[1]]

    def point(self, side):
        """r + A s' of {"body", "point": [E, E]}."""
        local = [self.expr(side["point"][0]), self.expr(side["point"][1])]
        rot = self.rotate(side["body"], local)
        return [self.coord(side["body"], "x") + rot[0], self.coord(side["body"], "y") + rot[1]]

    def unit_axis(self, side):
        """The global unit vector A u'/|u'| of side["axis"]."""
        u = [self.expr(side["axis"][0]), self.expr(side["axis"][1])]
        norm = ca.sqrt(u[0] ** 2 + u[1] ** 2)
        return self.rotate(side["body"], [u[0] / norm, u[1] / norm])

    @staticmethod
    def perp(v):
        return [-v[1], v[0]]

    @staticmethod
    def dot(a, b):
        return a[0] * b[0] + a[1] * b[1]

    # --- constraint rows (docs/formulation.md, table "Constraint rows") ----------------------------
    def constraint(self, c):
        kind = c["kind"]
        if kind == "revolute":
            pi, pj = self.point(c["i"]), self.point(c["j"])
            return [pi[0] - pj[0], pi[1] - pj[1]]
        if kind == "translational":
            pi, pj = self.point(c["i"]), self.point(c["j"])
            ni = self.perp(self.unit_axis(c["i"]))
            uj = self.unit_axis(c["j"])
            return [self.dot(ni, [pj[0] - pi[0], pj[1] - pi[1]]), self.dot(ni, uj)]
        if kind == "revolute_revolute":
            pi, pj = self.point(c["i"]), self.point(c["j"])
            d = [pj[0] - pi[0], pj[1] - pi[1]]
            length = self.expr(c["length"])
            return [(self.dot(d, d) - length ** 2) / (2 * length)]
        if kind == "revolute_translational":
            pi, pj = self.point(c["i"]), self.point(c["j"])
            nj = self.perp(self.unit_axis(c["j"]))
            return [self.dot(nj, [pi[0] - pj[0], pi[1] - pj[1]]) - self.expr(c["distance"])]
        if kind == "rigid":
            pi, pj = self.point(c["i"]), self.point(c["j"])
            rel = self.coord(c["j"]["body"], "phi") - self.coord(c["i"]["body"], "phi")
            return [pi[0] - pj[0], pi[1] - pj[1], rel - self.expr(c["angle"])]
        if kind == "fix":
            return [self.coord(c["body"], c["coordinate"]) - self.expr(c["value"])]
        if kind == "drive":
            return [self.coord(c["body"], c["coordinate"]) - self.expr(c["f"])]
        if kind == "drive_angle":
            return [self.coord(c["j"], "phi") - self.coord(c["i"], "phi") - self.expr(c["f"])]
        if kind == "drive_distance":
            pi, pj = self.point(c["i"]), self.point(c["j"])
            d = [pj[0] - pi[0], pj[1] - pi[1]]
            f = self.expr(c["f"])
            return [(self.dot(d, d) - f ** 2) / (2 * f)]
        if kind == "constraint":
            return [self.expr(c["expr"])]
        raise ValueError(f"{self.name}: unknown constraint kind {kind!r}")

    # --- evaluation --------------------------------------------------------------------------
    def params_vector(self, named):
        """Parameter values in model order from a {name: value} mapping (defaults fill gaps)."""
        defaults = {p["name"]: p["default"] for p in self.json["params"]}
        return [named.get(n, defaults[n]) for n in self.param_names]

    def structural_jacobian(self):
        """(row, column) of CasADi's structural non-zeros of dphi/dq."""
        sp = self.jac.sparsity()
        return set(zip(sp.row(), sp.get_col()))

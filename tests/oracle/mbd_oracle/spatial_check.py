"""Proves the spatial oracle (spatial.py) right on the hand-made fixtures of fixtures/spatial/ by
independent means. Usage (from tests/oracle):  python -m mbd_oracle.spatial_check
[FIXTURE.json ...] checks only those fixtures; --except NAME every check but fixture NAME's.
Prints what it checked with the numbers; exit status 1 if any check fails.

The independent means:
- quat.py: rotations as the quaternion sandwich p ⊗ (0, v) ⊗ p*, and the EXACT flow of
  q̇ = B(q) v at fixed v, r(s) = r + s ṙ, p(s) = p ⊗ exp(s ω′/2) (unit p stays unit) — not the
  polynomial A(p) nor the matrix B(q) of spatial.py;
- a NumPy re-implementation of the markers, every joint row and driver, and every force
  element's definition (class Numeric below: plain floats, its own expression evaluator), whose
  rates are finite differences along the exact flow;
- finite differences: D v = Φ̇ and γ = −d/ds (D v − ν) along the flow (t advancing with s);
  each force element's Q against the numeric definition's virtual power along each velocity
  direction, and (for conservative elements) against −dV/ds; h_q B, h_v, friction_q, friction_v
  against differences of h and of the friction forces;
- physics: a torque-free body integrated by CVODES conserves kinetic energy and angular momentum,
  and is unstable about its intermediate principal axis only, at the rate linear theory gives;
  a heavy symmetric top on a spherical joint precesses steadily at the closed-form rate; the
  constrained fixtures integrated with the KKT forward dynamics (Baumgarte) stay on Φ = 0.

Finite differences are central with one Richardson step, (4 D(h/2) − D(h))/3, at h = 1e-3:
truncation O(h⁴) ≈ 1e-12 times the fifth derivative, rounding ≈ 1e-16 |f|/h = 1e-13 |f|.
Their tolerance, FD_TOL = 1e-7 relative to max(1, |value|∞, |f|∞), is > 100× the worst error
observed and still ~1e6 below any wrong term, which is O(1) of the term. Coulomb friction,
regularized as v / sqrt(v² + v_s²), has a fifth derivative of order 1/v_s⁵ where a joint barely
slides: at such a random state the truncation alone reached 2.6e-7. Its derivatives are compared
at h and at h/10 and the closer counts (fd_either): a right derivative's error falls 10⁴-fold,
a wrong term stays O(1) at both.
"""

import copy
import glob
import json
import math
import os
import sys

import casadi as ca
import numpy as np

from . import quat
from .dynamics import NoFixedPoint
from .spatial import COORDS, VELS, Spatial, rotation, l_matrix

HERE = os.path.dirname(os.path.abspath(__file__))
FIXTURES = os.path.normpath(os.path.join(HERE, "..", "fixtures", "spatial"))

FD_STEP = 1e-3
FD_TOL = 1e-7
STATES = 8  # random states per fixture


class Report:
    def __init__(self):
        self.failures = []

    def check(self, what, value, tol, detail=""):
        ok = bool(value <= tol)
        print(f"spatial_check: {what}: {value:.2e} (tolerance {tol:.0e}){' ' + detail if detail else ''} {'ok' if ok else 'FAIL'}")
        if not ok:
            self.failures.append(what)
        return ok

    def require(self, what, ok, detail):
        print(f"spatial_check: {what}: {detail} {'ok' if ok else 'FAIL'}")
        if not ok:
            self.failures.append(what)
        return ok


def fd(f, h=FD_STEP):
    """d/ds f(s) at s = 0: central differences with one Richardson step."""
    def central(k):
        return (np.asarray(f(k), dtype=float) - np.asarray(f(-k), dtype=float)) / (2 * k)
    return (4 * central(h / 2) - central(h)) / 3


def fd_either(value, f, scale):
    """rel(value, fd(f)) at the step FD_STEP and at FD_STEP / 10, the smaller (see the module doc)."""
    return min(rel(value, np.column_stack([fd(g, h) for g in f]), scale) for h in (FD_STEP, FD_STEP / 10))


def rel(a, b, *scales):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.size == 0:
        return 0.0
    s = max([1.0, float(np.max(np.abs(a))), float(np.max(np.abs(b)))] + [float(np.max(np.abs(x))) if np.size(x) else 0.0 for x in scales])
    return float(np.max(np.abs(a - b))) / s


# --- an independent numeric model ---------------------------------------------------------------
class Numeric:
    """The spec's kinematics, rows and force elements in plain NumPy at fixed parameters."""

    FUN = {"sin": math.sin, "cos": math.cos, "tan": math.tan, "asin": math.asin, "acos": math.acos, "atan": math.atan,
           "sqrt": math.sqrt, "exp": math.exp, "ln": math.log, "neg": lambda x: -x}

    def __init__(self, model, p):
        self.m = model
        self.bodies = [b["name"] for b in model["bodies"]]
        self.pv = dict(zip([x["name"] for x in model["params"]], p))
        self.joints = {c["name"]: c for c in model["constraints"] if "i" in c and "joint" not in c}

    def ev(self, e, q, v=None, t=0.0):
        op = e[0]
        if op == "num":
            return float(e[1])
        if op == "pi":
            return math.pi
        if op == "t":
            return t
        if op == "param":
            return self.pv[e[1]]
        if op == "coord":
            return 0.0 if e[1] == "ground" else q[7 * self.bodies.index(e[1]) + COORDS.index(e[2])]
        if op == "vel":
            return 0.0 if e[1] == "ground" else v[6 * self.bodies.index(e[1]) + VELS.index(e[2])]
        a = [self.ev(x, q, v, t) for x in e[1:]]
        if op in self.FUN:
            return self.FUN[op](a[0])
        return {"add": lambda: a[0] + a[1], "sub": lambda: a[0] - a[1], "mul": lambda: a[0] * a[1], "div": lambda: a[0] / a[1],
                "pow": lambda: a[0] ** a[1], "atan2": lambda: math.atan2(a[0], a[1])}[op]()

    def vec(self, es, q, v=None, t=0.0):
        return np.array([self.ev(e, q, v, t) for e in es])

    def pose(self, body, q):
        if body == "ground":
            return np.zeros(3), np.array([1.0, 0, 0, 0])
        k = self.bodies.index(body)
        return q[7 * k:7 * k + 3], q[7 * k + 3:7 * k + 7]

    def point(self, side, q, t=0.0):
        r, p = self.pose(side["body"], q)
        return r + quat.rotate(p, self.vec(side["point"], q, t=t))

    def triad(self, marker, q, t=0.0):
        _, p = self.pose(marker["body"], q)
        a = self.vec(marker["axis"], q, t=t)
        z = a / np.linalg.norm(a)
        if "reference" not in marker:
            return None, None, quat.rotate(p, z)
        b = self.vec(marker["reference"], q, t=t)
        x = b - (b @ z) * z
        x = x / np.linalg.norm(x)
        return quat.rotate(p, x), quat.rotate(p, np.cross(z, x)), quat.rotate(p, z)

    def rows(self, q, t):
        out = []
        for c in self.m["constraints"]:
            k = c["kind"]
            if k == "drive":
                out.append(self.ev(["coord", c["body"], c["coordinate"]], q) - self.ev(c["f"], q, t=t))
                continue
            if k == "constraint":
                out.append(self.ev(c["expr"], q, t=t))
                continue
            if k in ("drive_angle", "drive_stroke"):
                j, f = self.joints[c["joint"]], self.ev(c["f"], q, t=t)
                xi, yi, zi = self.triad(j["i"], q, t)
                if k == "drive_angle":
                    xj = self.triad(j["j"], q, t)[0]
                    out.append((yi @ xj) * math.cos(f) - (xi @ xj) * math.sin(f))
                else:
                    out.append(zi @ (self.point(j["j"], q, t) - self.point(j["i"], q, t)) - f)
                continue
            pi, pj = self.point(c["i"], q, t), self.point(c["j"], q, t)
            d = pj - pi
            ti = self.triad(c["i"], q, t) if "axis" in c["i"] else (None, None, None)
            tj = self.triad(c["j"], q, t) if "axis" in c["j"] else (None, None, None)
            (xi, yi, zi), (xj, yj, zj) = ti, tj
            rows = {
                "spherical": lambda: list(pi - pj),
                "universal": lambda: list(pi - pj) + [zi @ zj],
                "revolute": lambda: list(pi - pj) + [xi @ zj, yi @ zj],
                "cylindrical": lambda: [xi @ zj, yi @ zj, xi @ d, yi @ d],
                "translational": lambda: [xi @ zj, yi @ zj, xi @ d, yi @ d, xi @ yj],
                "planar": lambda: [xi @ zj, yi @ zj, zi @ d],
                "rigid": lambda: list(pi - pj) + [yi @ zj, zi @ xj, xi @ yj],
                "point_on_line": lambda: [xi @ d, yi @ d],
                "point_on_plane": lambda: [zi @ d - self.ev(c["distance"], q, t=t)],
                "distance": lambda: [(d @ d - self.ev(c["length"], q, t=t) ** 2) / (2 * self.ev(c["length"], q, t=t))],
            }
            out.extend(rows[k]())
        return np.array(out)

    # joint coordinates for the force elements
    def angle(self, name, q, t=0.0):
        j = self.joints[name]
        xi, yi, _ = self.triad(j["i"], q, t)
        xj = self.triad(j["j"], q, t)[0]
        return math.atan2(yi @ xj, xi @ xj)

    def stroke(self, name, q, t=0.0):
        j = self.joints[name]
        return self.triad(j["i"], q, t)[2] @ (self.point(j["j"], q, t) - self.point(j["i"], q, t))

    def bushing(self, f, q, t=0.0):
        xi, yi, zi = self.triad(f["i"], q, t)
        xj, yj, zj = self.triad(f["j"], q, t)
        d = self.point(f["j"], q, t) - self.point(f["i"], q, t)
        return np.array([xi @ d, yi @ d, zi @ d, zi @ yj, xi @ zj, yi @ xj])

    # virtual power
    def rate(self, g, q, v, t):
        """ġ: the difference quotient of g(q, t) along the exact flow with velocity v, t + s."""
        return fd(lambda s: g(quat.flow(q, v, s), t + s))

    def virtual(self, g, weight, q, t):
        """Q with Q_k = weight · dg/ds along the flow of the k-th unit velocity (t fixed)."""
        nv = 6 * len(self.bodies)
        return np.array([np.dot(weight, fd(lambda s: g(quat.flow(q, e, s), t))) for e in np.eye(nv)])

    def opt(self, e, q, v, t):
        return 0.0 if e is None else self.ev(e, q, v, t)

    def element(self, f, q, v, t, lam=None):
        """Q of one force element (or Coulomb joint) from its definition."""
        k = f["kind"]
        if k == "point_to_point":
            length = lambda q_, t_: np.linalg.norm(self.point(f["j"], q_, t_) - self.point(f["i"], q_, t_))  # noqa: E731
            tension = self.opt(f["k"], q, v, t) * (length(q, t) - self.ev(f["length"], q, v, t)) \
                + self.opt(f["c"], q, v, t) * self.rate(length, q, v, t) + self.opt(f["force"], q, v, t)
            return self.virtual(length, -tension, q, t)
        if k in ("rotational", "revolute_viscous", "revolute_coulomb"):
            theta = lambda q_, t_: self.angle(f["joint"], q_, t_)  # noqa: E731
            rate = self.rate(theta, q, v, t)
            if k == "rotational":
                torque = self.opt(f["k"], q, v, t) * (theta(q, t) - self.ev(f["angle"], q, v, t)) \
                    + self.opt(f["c"], q, v, t) * rate + self.opt(f["torque"], q, v, t)
            elif k == "revolute_viscous":
                torque = self.ev(f["c"], q, v, t) * rate
            else:
                r = f["row"]
                load = np.linalg.norm(lam[r:r + 3])
                slip = self.ev(f["slip_velocity"], q, v, t)
                torque = self.ev(f["mu"], q, v, t) * self.ev(f["radius"], q, v, t) * load * rate / math.sqrt(rate**2 + slip**2)
            return self.virtual(theta, -torque, q, t)
        if k in ("translational_viscous", "translational_coulomb"):
            s_ = lambda q_, t_: self.stroke(f["joint"], q_, t_)  # noqa: E731
            rate = self.rate(s_, q, v, t)
            if k == "translational_viscous":
                force = self.ev(f["c"], q, v, t) * rate
            else:
                r = f["row"]
                load = np.linalg.norm(lam[r + 2:r + 4])
                slip = self.ev(f["slip_velocity"], q, v, t)
                force = self.ev(f["mu"], q, v, t) * load * rate / math.sqrt(rate**2 + slip**2)
            return self.virtual(s_, -force, q, t)
        if k == "bushing":
            delta = lambda q_, t_: self.bushing(f, q_, t_)  # noqa: E731
            rates = self.rate(delta, q, v, t)
            d = delta(q, t)
            forces = np.array([self.opt(kc, q, v, t) * (d[c] - self.ev(f["preload"][c], q, v, t)) + self.opt(cc, q, v, t) * rates[c]
                               for c, (kc, cc) in enumerate(zip(f["k"], f["c"]))])
            return self.virtual(delta, -forces, q, t)
        if k in ("force", "local_force"):
            force = self.vec(f["force"], q, v, t)
            if k == "local_force":
                force = quat.rotate(self.pose(f["at"]["body"], q)[1], force)
            return self.virtual(lambda q_, t_: self.point(f["at"], q_, t_), force, q, t)
        if k in ("torque", "local_torque"):
            # Virtual power T·ω (global) or T′·ω′ (body frame), with the body's angular velocity
            # under each unit velocity read off the attitude's rate: ω̃ = Ȧ Aᵀ, ω̃′ = Aᵀ Ȧ.
            torque = self.vec(f["torque"], q, v, t)
            nv = 6 * len(self.bodies)
            if f["body"] == "ground":
                return np.zeros(nv)
            att = lambda q_: quat.matrix(self.pose(f["body"], q_)[1])  # noqa: E731
            a = att(q)
            out = []
            for e in np.eye(nv):
                adot = fd(lambda s: att(quat.flow(q, e, s)))
                w = adot @ a.T if k == "torque" else a.T @ adot
                out.append(torque @ np.array([w[2, 1], w[0, 2], w[1, 0]]))
            return np.array(out)
        raise ValueError(k)

    def gravity(self, body, q):
        m = self.ev(self.m["bodies"][self.bodies.index(body)]["mass"], q)
        g = self.vec(self.m["gravity"], q)
        return self.virtual(lambda q_, t_: self.pose(body, q_)[0], m * g, q, 0.0)

    def gyroscopic(self, body, q, v):
        b = self.bodies.index(body)
        jt = np.array([[self.ev(e, q) for e in row] for row in self.m["bodies"][b]["inertia"]])
        w = v[6 * b + 3:6 * b + 6]
        out = np.zeros(6 * len(self.bodies))
        out[6 * b + 3:6 * b + 6] = -np.cross(w, jt @ w)
        return out


# --- helpers ------------------------------------------------------------------------------------
def load(name):
    with open(os.path.join(FIXTURES, f"{name}.json")) as f:
        return json.load(f)


def random_state(s, rng, q0):
    """Centres within ±0.5 of q0, attitudes turned by up to 0.5 rad, v in ±3, t in [0, 2],
    parameters ±10 % (unit Euler parameters)."""
    q = np.array(q0, dtype=float)
    for k in range(len(s.bodies)):
        q[7 * k:7 * k + 3] += rng.uniform(-0.5, 0.5, 3)
        p = quat.mul(q[7 * k + 3:7 * k + 7], quat.axis_angle(rng.normal(size=3), rng.uniform(0, 0.5)))
        q[7 * k + 3:7 * k + 7] = p / np.linalg.norm(p)
    return q, rng.uniform(-3, 3, s.nv), float(rng.uniform(0, 2)), [d * rng.uniform(0.9, 1.1) for d in s.params_vector({})]


def arr(x):
    return np.array(x, dtype=float)


# --- 1. conventions --------------------------------------------------------------------------------
def check_conventions(rep):
    rng = np.random.default_rng(1)
    P = ca.SX.sym("p", 4)
    fa = ca.Function("A", [P], [rotation(P)])
    fl = ca.Function("L", [P], [l_matrix(P)])
    err_a = err_o = err_b = err_w = 0.0
    for _ in range(20):
        p = quat.axis_angle(rng.normal(size=3), rng.uniform(-3, 3))
        w = rng.normal(size=3)
        a = arr(fa(p))
        err_a = max(err_a, np.max(np.abs(a - quat.matrix(p))))
        err_o = max(err_o, np.max(np.abs(a.T @ a - np.eye(3))), abs(np.linalg.det(a) - 1))
        # ṗ = ½ Lᵀ ω′ against the derivative of the exact flow p ⊗ exp(s ω′/2) (= ½ p ⊗ (0, ω′)).
        err_b = max(err_b, np.max(np.abs(0.5 * arr(fl(p)).T @ w - 0.5 * quat.mul(p, np.concatenate([[0.0], w])))))
        # ω′ is the body-frame angular velocity: Aᵀ dA/ds = ω̃′ along the flow.
        adot = fd(lambda s: quat.matrix(quat.mul(p, quat.exp_body(w, s))))
        err_w = max(err_w, np.max(np.abs(quat.matrix(p).T @ adot - np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]]))))
    rep.check("A(p) polynomial = quaternion sandwich rotation (20 random unit p)", err_a, 1e-15)
    rep.check("A(p) orthonormal, det 1", err_o, 1e-14)
    rep.check("½ Lᵀ ω′ = ½ p ⊗ (0, ω′), the exact flow's ṗ", err_b, 1e-15)
    rep.check("Aᵀ dA/ds = ω̃′ along the flow (FD): ω′ is body-frame", err_w, 1e-9)


# --- 2. fixtures at q0 ------------------------------------------------------------------------------
def check_assembly(rep, name, mj, s):
    p = s.params_vector({})
    q0, v0 = s.initial_state()
    norms = max(abs(np.linalg.norm(q0[7 * k + 3:7 * k + 7]) - 1) for k in range(len(s.bodies)))
    rep.check(f"{name}: unit Euler parameters at q0, max ||p| − 1|", norms, 1e-15)
    names_ok = s.row_names == mj["constraint_rows"] and s.coordinate_names == mj["coordinates"] and s.velocity_names == mj["velocities"]
    rep.require(f"{name}: row, coordinate and velocity names are the spec's", names_ok, f"{s.nc} rows, {s.nq} coordinates, {s.nv} velocities")
    if not s.nc:
        return
    phi = arr(s.f_phi(q0, v0, 0.0, p)).reshape(-1)
    rep.check(f"{name}: max |Φ(q0, 0)|", float(np.max(np.abs(phi))), 1e-12)
    d = arr(s.f_jac(q0, v0, 0.0, p))
    res = d @ v0 - arr(s.f_nu(q0, v0, 0.0, p)).reshape(-1)
    rep.check(f"{name}: max |D v0 − ν| (hand-made rigid-body velocities)", float(np.max(np.abs(res))), 1e-12)
    sv = np.linalg.svd(d, compute_uv=False)
    rep.require(f"{name}: D(q0) has full row rank", sv[-1] > 1e-3, f"smallest singular value {sv[-1]:.2e} of {s.nc}")


# --- 3. derivatives by finite differences at random states -----------------------------------------
def check_kinematics(rep, name, mj, s, rng):
    q0, _ = s.initial_state()
    e_phi = e_dv = e_gamma = 0.0
    for _ in range(STATES):
        q, v, t, p = random_state(s, rng, q0)
        num = Numeric(mj, p)
        args = (q, v, t, p)
        phi = arr(s.f_phi(*args)).reshape(-1)
        e_phi = max(e_phi, rel(phi, num.rows(q, t)))
        f_phi = lambda qq, tt: arr(s.f_phi(qq, v, tt, p)).reshape(-1)  # noqa: E731
        phidot = arr(s.f_jac(*args)) @ v - arr(s.f_nu(*args)).reshape(-1)
        e_dv = max(e_dv, rel(phidot, fd(lambda h: f_phi(quat.flow(q, v, h), t + h)), phi))
        # γ = −d/ds (D v − ν) along the flow with v fixed.
        f_dot = lambda qq, tt: arr(s.f_jac(qq, v, tt, p)) @ v - arr(s.f_nu(qq, v, tt, p)).reshape(-1)  # noqa: E731
        gamma = arr(s.f_gamma(*args)).reshape(-1)
        e_gamma = max(e_gamma, rel(gamma, -fd(lambda h: f_dot(quat.flow(q, v, h), t + h)), phidot))
    rep.check(f"{name}: Φ against the NumPy rows (quaternion sandwich), {STATES} random states", e_phi, 1e-13)
    rep.check(f"{name}: D v − ν against dΦ/ds along the exact flow (FD)", e_dv, FD_TOL)
    rep.check(f"{name}: γ against −d(D v − ν)/ds along the exact flow (FD)", e_gamma, FD_TOL)


def conservative_variant(mj):
    """The model with every damping, actuator force and torque option set to null: every element
    with a stiffness is then conservative (Q = −(∂V/∂q) B)."""
    m = copy.deepcopy(mj)
    keep = []
    for f in m["forces"]:
        if f["kind"] == "point_to_point":
            f["c"], f["force"] = None, None
        elif f["kind"] == "rotational":
            f["c"], f["torque"] = None, None
        elif f["kind"] == "bushing":
            f["c"] = [None] * 6
        else:
            continue
        keep.append(f)
    m["forces"] = keep
    return m


def check_forces(rep, name, mj, s, rng):
    q0, _ = s.initial_state()
    names = [c[0] for c in s.contributions]
    worst = {}
    e_h = e_hq = e_hv = e_pow = 0.0
    e_fr = e_frq = e_frv = 0.0
    forces = {f["name"]: f for f in mj.get("forces", [])}
    for _ in range(max(2, STATES // 2)):
        q, v, t, p = random_state(s, rng, q0)
        num = Numeric(mj, p)
        args = (q, v, t, p)
        out = s.f_contributions(*args)
        qs = [arr(out[k]).reshape(-1) for k in range(len(names))]
        for k, cname in enumerate(names):
            if cname.startswith("gravity on "):
                want = num.gravity(cname[len("gravity on "):], q)
            elif cname.startswith("gyroscopic "):
                want = num.gyroscopic(cname[len("gyroscopic "):], q, v)
                e_pow = max(e_pow, abs(qs[k] @ v) / max(1.0, np.max(np.abs(qs[k])) * np.max(np.abs(v))))
            else:
                want = num.element(forces[cname], q, v, t)
            kind = cname.split(" on ")[0] if cname.startswith("gravity") else ("gyroscopic" if cname.startswith("gyroscopic") else forces[cname]["kind"])
            worst[kind] = max(worst.get(kind, 0.0), rel(qs[k], want))
        h = arr(s.f_h(*args)).reshape(-1)
        e_h = max(e_h, rel(h, sum(qs)))
        # (∂h/∂q) B w = dh/ds along the flow of w (v, t fixed); ∂h/∂v by differences in v.
        hq = arr(s.f_h_q(*args))
        hv = arr(s.f_h_v(*args))
        fq = np.column_stack([fd(lambda h_: arr(s.f_h(quat.flow(q, e, h_), v, t, p)).reshape(-1)) for e in np.eye(s.nv)])
        fv = np.column_stack([fd(lambda h_: arr(s.f_h(q, v + h_ * e, t, p)).reshape(-1)) for e in np.eye(s.nv)])
        e_hq = max(e_hq, rel(hq, fq, h))
        e_hv = max(e_hv, rel(hv, fv, h))
        if s.has_friction:
            lam = rng.uniform(-50, 50, s.nc)
            fr, frq, frv = (arr(x) for x in s.f_friction(*args, lam)[:3])
            fr = fr.reshape(-1)
            want = sum(num.element(f, q, v, t, lam) for f in mj["forces"] if f["kind"].endswith("_coulomb"))
            e_fr = max(e_fr, rel(fr, want))
            f_of = lambda qq, vv: arr(s.f_friction(qq, vv, t, p, lam)[0]).reshape(-1)  # noqa: E731
            along_q = [lambda h_, e=e: f_of(quat.flow(q, e, h_), v) for e in np.eye(s.nv)]
            along_v = [lambda h_, e=e: f_of(q, v + h_ * e) for e in np.eye(s.nv)]
            e_frq = max(e_frq, fd_either(frq, along_q, fr))
            e_frv = max(e_frv, fd_either(frv, along_v, fr))
    for kind, e in sorted(worst.items()):
        rep.check(f"{name}: Q of {kind} against the NumPy definition's virtual power (FD along each velocity)", e, FD_TOL)
    if any(n.startswith("gyroscopic") for n in names):
        rep.check(f"{name}: power of the gyroscopic terms, |Qᵀv|/(|Q| |v|)", e_pow, 1e-14)
    rep.check(f"{name}: h = Σ contributions", e_h, 1e-14)
    rep.check(f"{name}: h_q = (∂h/∂q) B against dh/ds along the flow (FD)", e_hq, FD_TOL)
    rep.check(f"{name}: h_v against differences of h in v (FD)", e_hv, FD_TOL)
    if s.has_friction:
        rep.check(f"{name}: Coulomb friction against the NumPy definition (random λ in ±50)", e_fr, FD_TOL)
        rep.check(f"{name}: friction_q = (∂f/∂q) B (FD)", e_frq, FD_TOL)
        rep.check(f"{name}: friction_v (FD)", e_frv, FD_TOL)
    # Conservative elements: Q = −(∂V/∂q) B, i.e. Q_k = −dV/ds along the flow of the k-th velocity.
    cons = Spatial(conservative_variant(mj)) if mj.get("forces") else s
    worst_v, count = 0.0, 0
    for _ in range(max(2, STATES // 2)):
        q, v, t, p = random_state(s, rng, q0)
        out = cons.f_contributions(q, v, t, p)
        n = len(cons.contributions)
        for k, (cname, _, _, conservative) in enumerate(cons.contributions):
            if not conservative or cname.startswith("gyroscopic"):
                continue
            qk = arr(out[k]).reshape(-1)
            f_v = lambda qq: float(cons.f_contributions(qq, v, t, p)[n + k])  # noqa: E731
            dv = np.array([fd(lambda h_: f_v(quat.flow(q, e, h_))) for e in np.eye(s.nv)])
            worst_v = max(worst_v, rel(qk, -dv, float(out[n + k])))
            count += 1
    if count:
        rep.check(f"{name}: Q = −(∂V/∂q) B of each conservative element (gravity, springs, rotational springs, bushings) by FD of V",
                  worst_v, FD_TOL, f"({count} element-states)")


# --- 4. the torque-free body -----------------------------------------------------------------------
def ode_free(s, p):
    """CVODES on q̇ = B(q) v, v̇ = M⁻¹ h (no constraints)."""
    x = ca.SX.sym("x", s.nq + s.nv)
    q, v = x[:s.nq], x[s.nq:]
    b = s.f_B(q, v, 0.0, p)
    h = s.f_h(q, v, 0.0, p)
    m = s.f_mass(q, v, 0.0, p)
    return x, ca.vertcat(b @ v, ca.solve(m, h))


def integrate(x, ode, x0, times, tol=1e-12):
    f = ca.integrator("F", "cvodes", {"x": x, "ode": ode}, 0.0, list(times), {"reltol": tol, "abstol": tol, "max_num_steps": 1000000})
    return arr(f(x0=x0)["xf"]).T


def check_torque_free(rep):
    mj = load("torque_free")
    s = Spatial(mj)
    p = s.params_vector({})
    q0, v0 = s.initial_state()
    jt = arr(s.f_mass(q0, v0, 0.0, p))[3:6, 3:6]
    x, ode = ode_free(s, p)
    times = np.linspace(0.5, 100.0, 200)
    xs = integrate(x, ode, np.concatenate([q0, v0]), times)

    def invariants(state):
        q, v = state[:7], state[7:]
        pn = q[3:7] / np.linalg.norm(q[3:7])
        w = v[3:6]
        return 0.5 * float(w @ jt @ w) + 0.5 * float(p[0] * v[:3] @ v[:3]), quat.rotate(pn, jt @ w), abs(np.linalg.norm(q[3:7]) - 1)

    e0, l0, _ = invariants(np.concatenate([q0, v0]))
    de = max(abs(invariants(xx)[0] - e0) for xx in xs) / e0
    dl = max(np.linalg.norm(invariants(xx)[1] - l0) for xx in xs) / np.linalg.norm(l0)
    dp = max(invariants(xx)[2] for xx in xs)
    # Tolerance: CVODES holds each step's local error to rtol = atol = 1e-12; over 100 s (~30
    # turns, some 1e4 steps) these errors accumulate at worst linearly to ~1e-8. The invariants
    # are not enforced by the integrator, so their drift measures the accumulated error, and a
    # wrong gyroscopic term (or a wrong B) would change them at O(1) within a turn.
    rep.check("torque-free body, 100 s CVODES rtol 1e-12: relative drift of kinetic energy", de, 1e-8)
    rep.check("torque-free body: relative drift of global angular momentum A J′ω′ (p normalized)", dl, 1e-8)
    rep.check("torque-free body: max ||p| − 1| (the flow keeps |p| = 1; only integration error moves it)", dp, 1e-8)
    # Stability of rotation about the principal axes (eigenvectors of J′).
    moments, axes = np.linalg.eigh(jt)
    big = 2.0
    eps = 1e-6 * big
    growth, rates = [], []
    for k in range(3):
        u = axes[:, k]
        others = [axes[:, j] for j in range(3) if j != k]
        w0 = big * u + eps * (others[0] + others[1])
        state = np.concatenate([q0, np.zeros(3), w0])
        times = np.linspace(0.05, 60.0, 1200)
        xs = integrate(x, ode, state, times)
        perp = np.array([np.linalg.norm(xx[10:13] - (xx[10:13] @ u) * u) for xx in xs])
        amp0 = np.linalg.norm(w0 - (w0 @ u) * u)
        growth.append(float(np.max(perp) / amp0))
        if k == 1:
            # Early growth rate against linear theory σ = Ω √((J2 − J1)(J3 − J2)/(J1 J3)).
            i1 = int(np.argmax(perp > 1e2 * amp0))
            i2 = int(np.argmax(perp > 1e4 * amp0))
            rates = [math.log(perp[i2] / perp[i1]) / (times[i2] - times[i1]),
                     big * math.sqrt((moments[1] - moments[0]) * (moments[2] - moments[1]) / (moments[0] * moments[2]))]
    rep.require("torque-free body: rotation about the minimum and maximum principal axes is stable",
                growth[0] < 10 and growth[2] < 10,
                f"perturbation of 1e-6 grows by at most {growth[0]:.2f} (J_min = {moments[0]:.3f}) and {growth[2]:.2f} (J_max = {moments[2]:.3f}) in 60 s (limit 10)")
    rep.require("torque-free body: rotation about the intermediate axis is unstable",
                growth[1] > 1e4, f"the same perturbation grows by {growth[1]:.2e} (J_mid = {moments[1]:.3f}; limit > 1e4)")
    rep.check("torque-free body: intermediate-axis growth rate against linear theory, relative",
              abs(rates[0] / rates[1] - 1), 0.02, f"(measured {rates[0]:.5f}/s, theory {rates[1]:.5f}/s)")


# --- 5/6. forward dynamics as an ODE (KKT with Baumgarte) -------------------------------------------
def ode_dae(s, p, alpha, beta, gamma_scale=1.0):
    """q̇ = B v, v̇ from [M, −Dᵀ; D, 0] [v̇; λ] = [h; γ − 2α(Dv − ν) − β²Φ] (a CasADi linear
    solve inside the ODE, so CVODES gets exact Jacobians). gamma_scale ≠ 1 makes γ wrong on
    purpose (the sensitivity control of check_dae)."""
    x = ca.MX.sym("x", s.nq + s.nv)
    t = ca.MX.sym("t")
    q, v = x[:s.nq], x[s.nq:]
    phi, d, nu, gamma = s.f_kinematics(q, v, t, p)
    m, h, b = s.f_mass(q, v, t, p), s.f_h(q, v, t, p), s.f_B(q, v, t, p)
    kkt = ca.blockcat([[m, -d.T], [d, ca.MX(s.nc, s.nc)]])
    rhs = ca.vertcat(h, gamma_scale * gamma - 2 * alpha * (d @ v - nu) - beta**2 * phi)
    sol = ca.solve(kkt, rhs, "qr")
    return x, t, ca.vertcat(b @ v, sol[:s.nv])


def integrate_t(x, t, ode, x0, times, tol):
    f = ca.integrator("F", "cvodes", {"x": x, "t": t, "ode": ode}, 0.0, list(times), {"reltol": tol, "abstol": tol, "max_num_steps": 1000000})
    return arr(f(x0=x0)["xf"]).T


def check_heavy_top(rep):
    """Steady precession of a heavy symmetric top (fixed point O, symmetry axis z_b, centre of
    mass at l along z_b, transverse moment about O J1 = J_t + m l², axial J3, tilt θ from the
    vertical, precession Ω = φ̇ about the vertical, spin ψ̇ relative to the precessing frame,
    ω3 = ψ̇ + Ω cos θ the total body-axis component). From the Lagrangian
    L = ½ J1 (θ̇² + φ̇² sin²θ) + ½ J3 ω3² − m g l cos θ, the θ equation with θ̈ = 0 reads
        m g l = J3 ω3 Ω − J1 Ω² cos θ = Ω (J3 ψ̇ − (J1 − J3) Ω cos θ),
    whose two roots (slow and fast precession) are Ω = (J3 ω3 ∓ √(J3² ω3² − 4 J1 cos θ m g l)) / (2 J1 cos θ)."""
    mj = load("heavy_top")
    s = Spatial(mj)
    p = s.params_vector({})
    pv = dict(zip(s.param_names, p))
    q0, v0 = s.initial_state()
    m, l, g, jt, ja = pv["m"], pv["l"], pv["g"], pv["jt"], pv["ja"]
    j1, j3 = jt + m * l**2, ja
    att = q0[3:7]
    axis = quat.rotate(att, [0, 0, 1])
    theta = math.acos(axis[2])
    omega3 = float(v0[5])  # ω′_z: the body-axis component of the fixture's angular velocity
    c = math.cos(theta)
    disc = math.sqrt((j3 * omega3) ** 2 - 4 * j1 * c * m * g * l)
    x, t, ode = ode_dae(s, p, 10.0, 10.0)

    def run(big_omega, t_end):
        w = big_omega * np.array([0, 0, 1.0]) + (omega3 - big_omega * c) * axis
        r = l * axis
        state = np.concatenate([r, att, np.cross(w, r), quat.rotate(quat.conj(att), w)])
        times = np.linspace(t_end / 400, t_end, 400)
        xs = integrate_t(x, t, ode, state, times, 1e-12)
        axes = [quat.rotate(xx[3:7] / np.linalg.norm(xx[3:7]), [0, 0, 1]) for xx in xs]
        tilt = max(abs(math.acos(a[2]) - theta) for a in axes)
        az = np.unwrap([math.atan2(axis[1], axis[0])] + [math.atan2(a[1], a[0]) for a in axes])
        rate = (az[-1] - az[0]) / t_end
        return tilt, rate

    for label, big in (("slow", (j3 * omega3 - disc) / (2 * j1 * c)), ("fast", (j3 * omega3 + disc) / (2 * j1 * c))):
        t_end = 2 * (2 * math.pi / big)  # two precession periods
        tilt, rate = run(big, t_end)
        rep.check(f"heavy top ({label} root, θ = {theta:.3f}, ω3 = {omega3:g}, Ω = {big:.6f} rad/s): relative error of the precession rate over 2 periods",
                  abs(rate / big - 1), 1e-8, f"(measured {rate:.10f})")
        rep.check(f"heavy top ({label} root): max |θ(t) − θ0| (steady: no nutation)", tilt, 1e-8)
        off, _ = run(big * (1 + 1e-3), t_end)
        rep.require(f"heavy top ({label} root): the check is sensitive: Ω off by 1e-3 nutates",
                    off > 100 * max(tilt, 1e-12), f"max |θ − θ0| = {off:.2e} with Ω(1 + 1e-3)")


def check_dae(rep, name, mj, s):
    """Forward dynamics from the KKT solve integrated for 1 s keeps Φ small with Baumgarte."""
    p = s.params_vector({})
    q0, v0 = s.initial_state()
    alpha, beta = 5.0, 5.0
    times = np.linspace(0.01, 1.0, 100)

    def run(gamma_scale):
        x, t, ode = ode_dae(s, p, alpha, beta, gamma_scale)
        xs = integrate_t(x, t, ode, np.concatenate([q0, v0]), times, 1e-12)
        return xs, max(float(np.max(np.abs(arr(s.f_phi(xx[:s.nq], xx[s.nq:], tt, p))))) for xx, tt in zip(xs, times))

    xs, phi = run(1.0)
    dphi = max(float(np.max(np.abs(arr(s.f_jac(xx[:s.nq], xx[s.nq:], tt, p)) @ xx[s.nq:] - arr(s.f_nu(xx[:s.nq], xx[s.nq:], tt, p)).reshape(-1))))
               for xx, tt in zip(xs, times))
    dp = max(abs(np.linalg.norm(xx[7 * k + 3:7 * k + 7]) - 1) for xx in xs for k in range(len(s.bodies)))
    # CVODES at rtol = atol = 1e-12 leaves errors ~1e-10 after 1 s (|p| drifts as much, and A(p)
    # is not orthogonal off |p| = 1); Baumgarte (α = β = 5) damps their projection on Φ. 1e-8 is
    # a hundred times that; a γ wrong by δγ drives Φ to ~δγ/β² (the control below).
    rep.check(f"{name}: KKT forward dynamics (α = β = 5) integrated 1 s by CVODES rtol 1e-12: max |Φ|", phi, 1e-8,
              f"(max |D v − ν| {dphi:.1e}, max ||p| − 1| {dp:.1e})")
    _, wrong = run(1.0 + 1e-3)
    rep.require(f"{name}: the check is sensitive: with γ off by a relative 1e-3, Φ leaves the tolerance",
                wrong > 100 * 1e-8, f"max |Φ| = {wrong:.1e}")
    conservative = not any(f["kind"] != "point_to_point" or f["c"] is not None or f["force"] is not None for f in mj.get("forces", [])) \
        and not any(c["kind"] in ("drive", "drive_angle", "drive_stroke") for c in mj["constraints"]) \
        and not any("\"t\"" in json.dumps(c) for c in mj["constraints"])
    if conservative:
        def energy(xx):
            qq, vv = xx[:s.nq], xx[s.nq:]
            return 0.5 * vv @ arr(s.f_mass(qq, vv, 0.0, p)) @ vv + float(s.f_potential(qq, vv, 0.0, p))
        e0 = energy(np.concatenate([q0, v0]))
        de = max(abs(energy(xx) - e0) for xx in xs) / max(1.0, abs(e0))
        rep.check(f"{name}: relative energy drift over 1 s (conservative)", de, 1e-7)


# --- main ---------------------------------------------------------------------------------------------
def main(argv):
    rep = Report()
    rng = np.random.default_rng(2024)
    print(f"spatial_check: CasADi {ca.__version__}, fixtures in {FIXTURES}")
    check_conventions(rep)
    every = sorted(glob.glob(os.path.join(FIXTURES, "*.json")))
    if argv[:1] == ["--except"]:
        # Every check but the named fixture's (run in a process of its own, beside this one).
        paths, argv = [p for p in every if os.path.basename(p) != f"{argv[1]}.json"], []
    else:
        paths = argv or every
    for path in paths:
        with open(path) as f:
            mj = json.load(f)
        s = Spatial(mj)
        name = s.name
        print(f"spatial_check: {name}: {len(s.bodies)} bodies, {s.nc} rows, {len(mj.get('forces', []))} force elements")
        check_assembly(rep, name, mj, s)
        if s.nc:
            check_kinematics(rep, name, mj, s, rng)
        check_forces(rep, name, mj, s, rng)
        if s.nc and not s.has_friction:
            check_dae(rep, name, mj, s)
    if not argv:
        kinds = set()
        for path in every:
            with open(path) as f:
                mj = json.load(f)
            kinds |= {c["kind"] for c in mj["constraints"]} | {f["kind"] for f in mj.get("forces", [])}
            kinds |= {f"drive {c['coordinate']}" for c in mj["constraints"] if c["kind"] == "drive"}
            kinds |= {"gravity"} if mj.get("gravity") else set()
        spec = {"spherical", "universal", "revolute", "cylindrical", "translational", "planar", "rigid", "point_on_line",
                "point_on_plane", "distance", "drive_angle", "drive_stroke", "drive x", "drive y", "drive z", "constraint",
                "gravity", "point_to_point", "rotational", "bushing", "force", "local_force", "torque", "local_torque",
                "revolute_viscous", "translational_viscous", "revolute_coulomb", "translational_coulomb"}
        rep.require("the fixtures use every joint, driver and force element kind of the spec", spec <= kinds,
                    f"missing: {sorted(spec - kinds)}" if spec - kinds else f"all {len(spec)} kinds")
        check_torque_free(rep)
        check_heavy_top(rep)
    if rep.failures:
        print(f"spatial_check: {len(rep.failures)} FAILED: " + "; ".join(rep.failures))
        return 1
    print("spatial_check: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""Writes the hand-made spatial model JSON fixtures of tests/oracle/fixtures/spatial/ (each a
complete model JSON as docs/formulation.md, "Spatial model JSON", specifies it).

Usage (from tests/oracle):  python -m mbd_oracle.spatial_fixtures [OUT_DIR]

Each fixture is built from its geometry: a body is placed at a centre r and an attitude (a unit
quaternion from quat.py, i.e. NOT from the polynomial A(p) the oracle uses), and every marker
is given by its GLOBAL point, axis and reference in the assembled configuration and converted
to body coordinates (s′ = Aᵀ (P − r), ...): the joint rows then vanish at q0 up to rounding.
Axes are written scaled by a non-unit factor and references with a component along the axis, so
that the reader's normalization and Gram–Schmidt are exercised. Velocities v0 are built from
the same geometry (rigid-body velocity fields that respect every joint and driver at t = 0),
never from the oracle: spatial_check requires D v0 = ν, an independent test of D and ν at q0.
Row names, coordinate and velocity names are written by this script from the spec's tables; the
Jacobian pattern is CasADi's structural pattern of D.
"""

import json
import os
import sys

import numpy as np

from . import quat
from .spatial import Spatial

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.normpath(os.path.join(HERE, "..", "fixtures", "spatial"))

ROWS = {
    "spherical": ["x", "y", "z"], "universal": ["x", "y", "z", "cross"],
    "revolute": ["x", "y", "z", "axis_x", "axis_y"],
    "cylindrical": ["axis_x", "axis_y", "offset_x", "offset_y"],
    "translational": ["axis_x", "axis_y", "offset_x", "offset_y", "twist"],
    "planar": ["normal_x", "normal_y", "offset"], "rigid": ["x", "y", "z", "rx", "ry", "rz"],
    "point_on_line": ["offset_x", "offset_y"], "point_on_plane": ["offset"], "distance": ["length"],
    "drive_angle": ["angle"], "drive_stroke": ["stroke"], "constraint": ["user"],
}


def N(x):
    return ["num", float(x)]


def P(name):
    return ["param", name]


def vec(v):
    return [N(c) for c in v]


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


class Builder:
    def __init__(self, name, params):
        self.name = name
        self.params = params  # [(name, default)]
        self.bodies = []  # dicts
        self.pose = {"ground": (np.zeros(3), np.array([1.0, 0, 0, 0]), np.zeros(3), np.zeros(3))}
        self.constraints = []
        self.forces = []
        self.gravity = None

    def body(self, name, mass, inertia, r, p, rdot=(0, 0, 0), omega=(0, 0, 0)):
        """A body at centre r, attitude p, with global velocity ṙ and global angular velocity ω."""
        r, p = np.asarray(r, float), unit(p)
        rdot, omega = np.asarray(rdot, float), np.asarray(omega, float)
        self.pose[name] = (r, p, rdot, omega)
        inertia = [[e if isinstance(e, list) else N(e) for e in row] for row in inertia]
        self.bodies.append({"name": name, "mass": mass if isinstance(mass, list) else N(mass), "inertia": inertia,
                            "q0": vec(list(r) + list(p)), "v0": vec(list(rdot) + list(quat.rotate(quat.conj(p), omega)))})

    def velocity_of(self, body, point):
        """The global velocity of the global point of a body (rigid-body field)."""
        r, _, rdot, omega = self.pose[body]
        return rdot + np.cross(omega, np.asarray(point) - r)

    def local(self, body, vector):
        return quat.rotate(quat.conj(self.pose[body][1]), np.asarray(vector, float))

    def marker(self, body, point, axis=None, reference=None, scale=1.0):
        """A marker from its global point, axis and reference (body coordinates written)."""
        r = self.pose[body][0]
        m = {"body": body, "point": vec(self.local(body, np.asarray(point, float) - r))}
        if axis is not None:
            a = self.local(body, axis)
            m["axis"] = vec(scale * a)
            if reference is not None:
                # A reference with a component along the axis: Gram–Schmidt removes it.
                m["reference"] = vec(1.5 * self.local(body, reference) + 0.7 * unit(a))
        return m

    def joint(self, kind, name, i, j, **extra):
        c = {"kind": kind, "name": name or f"{kind} {i['body']}~{j['body']}", "i": i, "j": j}
        c.update(extra)
        self.constraints.append(c)
        return c["name"]

    def add(self, c):
        self.constraints.append(c)

    def row_names(self):
        names = []
        for c in self.constraints:
            rows = [c["coordinate"]] if c["kind"] == "drive" else ROWS[c["kind"]]
            names.extend(f"{c['name']}: {r}" for r in rows)
        return names

    def first_row(self, joint):
        k = 0
        for c in self.constraints:
            if c["name"] == joint:
                return k
            k += 1 if c["kind"] == "drive" else len(ROWS[c["kind"]])
        raise KeyError(joint)

    def model(self):
        names = [b["name"] for b in self.bodies]
        m = {
            "name": self.name, "scalar": "f64", "dimension": 3,
            "params": [{"name": n, "default": float(d)} for n, d in self.params],
            "bodies": self.bodies, "points": [], "vectors": [],
            "coordinates": [f"{b}.{c}" for b in names for c in ("x", "y", "z", "e0", "e1", "e2", "e3")],
            "velocities": [f"{b}.{c}" for b in names for c in ("vx", "vy", "vz", "wx", "wy", "wz")],
            "constraint_rows": self.row_names(), "jacobian_pattern": [],
            "constraints": self.constraints, "gravity": self.gravity, "forces": self.forces,
        }
        s = Spatial(m)
        m["jacobian_pattern"] = [list(map(int, rc)) for rc in sorted(s.structural_jacobian())]
        if s.nc:
            q0, v0 = s.initial_state()
            p = s.params_vector({})
            res = np.array(s.f_jac(q0, v0, 0.0, p)) @ v0 - np.array(s.f_nu(q0, v0, 0.0, p)).reshape(-1)
            print(f"{self.name}: max |Φ(q0)| = {np.max(np.abs(np.array(s.f_phi(q0, v0, 0.0, p)))):.1e}, "
                  f"max |D v0 − ν| = {np.max(np.abs(res)):.1e}")
        return m


def inertia_tensor(moments, rotation):
    """R diag(moments) Rᵀ: a full inertia tensor with the given principal moments."""
    r = np.asarray(rotation)
    return (r @ np.diag(moments) @ r.T).tolist()


def torque_free():
    """(a) A free asymmetric rigid body: no joints, no forces. Its inertia tensor is full (the
    principal axes are turned away from the body axes), principal moments 0.1, 0.2, 0.3 · k."""
    b = Builder("TorqueFree", [("m", 2.0), ("k", 1.0)])
    rot = quat.matrix(quat.axis_angle([1, 2, 3], 0.7))
    jt = inertia_tensor([0.1, 0.2, 0.3], rot)
    b.body("brick", P("m"), [[["mul", P("k"), N(e)] for e in row] for row in jt], [0.1, -0.2, 0.3],
           quat.axis_angle([0.3, -1, 0.4], 1.1), rdot=[0.5, 0.0, -0.2], omega=[1.0, -2.0, 0.5])
    return b.model()


def heavy_top():
    """(b) A heavy symmetric top: spherical joint at the ground origin, the centre of mass at l
    along the body z axis from the pivot, tilted by θ0 = 0.5 from the vertical, spinning about
    its axis (ω3 = 80 rad/s) and precessing at the slow steady rate (see spatial_check)."""
    m, l, g, jt, ja, theta, omega3 = 1.5, 0.1, 9.81, 0.02, 0.015, 0.5, 80.0
    b = Builder("HeavyTop", [("m", m), ("l", l), ("g", g), ("jt", jt), ("ja", ja)])
    b.gravity = [N(0), N(0), ["neg", P("g")]]
    att = quat.mul(quat.axis_angle([0, 0, 1], 0.3), quat.axis_angle([1, 0, 0], theta))
    axis = quat.rotate(att, [0, 0, 1])
    j1 = jt + m * l**2
    c = np.cos(theta)
    big = (ja * omega3 + np.sqrt((ja * omega3) ** 2 - 4 * j1 * c * m * g * l)) / (2 * j1 * c)
    slow = m * g * l / (j1 * c * big)  # the product of the two roots is m g l/(J1 cos θ)
    omega = slow * np.array([0, 0, 1.0]) + (omega3 - slow * c) * axis
    r = l * axis
    b.body("top", P("m"), [[P("jt"), N(0), N(0)], [N(0), P("jt"), N(0)], [N(0), N(0), P("ja")]], r, att,
           rdot=np.cross(omega, r), omega=omega)
    b.joint("spherical", None, {"body": "ground", "point": vec([0, 0, 0])},
            {"body": "top", "point": [N(0), N(0), ["neg", P("l")]]})
    return b.model()


def double_pendulum():
    """(c) A spatial double pendulum: a rod on a spherical joint at the ground origin, a second
    rod on a revolute joint at its lower end (hinge axis across the upper rod), gravity −z."""
    b = Builder("SpatialDoublePendulum", [("g", 9.81), ("m1", 1.0), ("m2", 0.7)])
    b.gravity = [N(0), N(0), ["neg", P("g")]]
    a1 = quat.mul(quat.axis_angle([0, 0, 1], 0.2), quat.axis_angle([1, 0.3, 0], 0.6))
    a2 = quat.mul(a1, quat.axis_angle([1, 0, 0], 0.5))
    z1, z2 = quat.rotate(a1, [0, 0, 1]), quat.rotate(a2, [0, 0, 1])
    r1 = -0.5 * z1
    elbow = -1.0 * z1
    r2 = elbow - 0.4 * z2
    w1 = np.array([0.8, -1.1, 0.4])
    hinge = quat.rotate(a1, [1, 0, 0])
    w2 = w1 + 2.0 * hinge
    v1 = np.cross(w1, r1)
    v2 = np.cross(w1, elbow) + np.cross(w2, r2 - elbow)
    rod = lambda m, l: [[["mul", m, N(l * l / 12)], N(0), N(0)], [N(0), ["mul", m, N(l * l / 12)], N(0)],  # noqa: E731
                        [N(0), N(0), ["mul", m, N(0.001)]]]
    b.body("upper", P("m1"), rod(P("m1"), 1.0), r1, a1, rdot=v1, omega=w1)
    b.body("lower", P("m2"), rod(P("m2"), 0.8), r2, a2, rdot=v2, omega=w2)
    b.joint("spherical", None, b.marker("ground", [0, 0, 0]), b.marker("upper", [0, 0, 0]))
    y1 = quat.rotate(a1, [0, 1, 0])
    b.joint("revolute", "elbow", b.marker("upper", elbow, hinge, y1, scale=2.0),
            b.marker("lower", elbow, hinge, quat.rotate(a2, [0, 1, 0]), scale=0.5))
    return b.model()


def every_joint():
    """(d) Every joint kind and driver of the spec: independent sub-mechanisms on ground (and one
    rigid joint between two moving bodies). Drivers: the angle of a revolute and of a cylindrical
    joint, the stroke of a cylindrical and of a translational joint, a body's x, y and z, and a
    user constraint on coordinates including Euler parameters. 10 bodies, 42 rows."""
    w, s0, c, length = 1.2, 0.15, 0.05, 0.8
    b = Builder("EveryJoint", [("w", w), ("s0", s0), ("c", c), ("L", length)])
    b.gravity = [N(0.5), N(-1.0), N(-9.81)]
    box = lambda m, a, bb, cc: [[N(m * (bb * bb + cc * cc) / 12), N(0), N(0)], [N(0), N(m * (a * a + cc * cc) / 12), N(0)],  # noqa: E731
                                [N(0), N(0), N(m * (a * a + bb * bb) / 12)]]
    rng = np.random.default_rng(7)

    def att():
        return unit(rng.normal(size=4))

    # 1. spherical
    piv = np.array([0.0, 0.0, 1.0])
    r = piv + np.array([0.3, -0.2, -0.4])
    om = np.array([0.5, 0.3, -0.7])
    b.body("sph", 1.0, box(1.0, 0.4, 0.5, 0.6), r, att(), rdot=np.cross(om, r - piv), omega=om)
    b.joint("spherical", None, b.marker("ground", piv), b.marker("sph", piv))
    # 2. universal: z_i (ground) ⊥ z_j (body) at the same point.
    piv = np.array([1.0, 0.0, 1.0])
    ag, au = unit([0, 1, 0.2]), unit(np.cross([0, 1, 0.2], [0.3, 0.2, 1]))
    r = piv + np.array([0.1, 0.2, -0.5])
    om = 0.8 * ag - 0.6 * au  # a rotation about the two cross axes keeps them perpendicular
    b.body("uni", 0.8, box(0.8, 0.4, 0.4, 0.8), r, att(), rdot=np.cross(om, r - piv), omega=om)
    b.joint("universal", None, b.marker("ground", piv, ag, scale=3.0), b.marker("uni", piv, au, scale=0.4))
    # 3. revolute "hinge", its angle driven: θ = 0.4 + w t.
    piv, ax = np.array([2.0, 0.0, 1.0]), unit([0.2, -0.3, 1.0])
    xg = unit(np.cross(ax, [1, 0, 0]))
    theta0 = 0.4
    turn = quat.axis_angle(ax, theta0)
    a_rev = att()
    r = piv + np.array([0.3, 0.1, 0.05])
    om = w * ax
    b.body("rev", 1.3, box(1.3, 0.8, 0.3, 0.3), r, a_rev, rdot=np.cross(om, r - piv), omega=om)
    b.joint("revolute", "hinge", b.marker("ground", piv, ax, xg, scale=2.0),
            b.marker("rev", piv, ax, quat.rotate(turn, xg), scale=1.0))
    b.add({"kind": "drive_angle", "name": "drive hinge.angle", "joint": "hinge", "f": ["add", N(theta0), ["mul", P("w"), ["t"]]]})
    # 4. rigid: a body welded to "rev" at a marker with a full triad.
    weld = r + np.array([0.2, 0.2, 0.1])
    rr = weld + np.array([0.1, 0.0, 0.2])
    wa, wb = unit([1, 1, 0]), unit([0, 0.2, 1])
    b.body("rig", 0.5, box(0.5, 0.4, 0.4, 0.6), rr, att(), rdot=b.velocity_of("rev", rr), omega=om)
    b.joint("rigid", None, b.marker("rev", weld, wa, wb, scale=1.7), b.marker("rig", weld, wa, wb, scale=0.6))
    # 5. cylindrical "sleeve": angle 0.3 + 0.5 sin t, stroke s0 + 0.2 t.
    piv, ax = np.array([3.0, 0.0, 1.0]), unit([1.0, 0.4, 0.3])
    xg = unit(np.cross(ax, [0, 0, 1]))
    theta0 = 0.3
    pj = piv + s0 * ax
    r = pj + np.array([0.0, 0.2, 0.1])
    om = 0.5 * ax
    b.body("cyl", 0.9, box(0.9, 0.5, 0.5, 0.5), r, att(), rdot=0.2 * ax + np.cross(om, r - pj), omega=om)
    b.joint("cylindrical", "sleeve", b.marker("ground", piv, ax, xg, scale=0.5),
            b.marker("cyl", pj, ax, quat.rotate(quat.axis_angle(ax, theta0), xg), scale=4.0))
    b.add({"kind": "drive_angle", "name": "drive sleeve.angle", "joint": "sleeve", "f": ["add", N(theta0), ["mul", N(0.5), ["sin", ["t"]]]]})
    b.add({"kind": "drive_stroke", "name": "drive sleeve.stroke", "joint": "sleeve", "f": ["add", P("s0"), ["mul", N(0.2), ["t"]]]})
    # 6. translational "slide": stroke 0.25 + 0.3 sin(w t).
    piv, ax = np.array([4.0, 0.0, 1.0]), unit([-0.3, 1.0, 0.5])
    xg = unit(np.cross(ax, [1, 0, 0]))
    pj = piv + 0.25 * ax
    r = pj + np.array([0.05, -0.1, 0.2])
    b.body("pri", 1.1, box(1.1, 0.4, 0.6, 0.4), r, att(), rdot=0.3 * w * ax, omega=[0, 0, 0])
    b.joint("translational", "slide", b.marker("ground", piv, ax, xg, scale=1.0), b.marker("pri", pj, ax, xg, scale=2.5))
    b.add({"kind": "drive_stroke", "name": "drive slide.stroke", "joint": "slide",
           "f": ["add", N(0.25), ["mul", N(0.3), ["sin", ["mul", P("w"), ["t"]]]]]})
    # 7. planar: the body slides and turns in a tilted plane; its x is driven: x0 + 0.1 t.
    piv, nrm = np.array([5.0, 0.0, 0.5]), unit([0.1, 0.2, 1.0])
    xg = unit(np.cross(nrm, [0, 1, 0]))
    pj = piv + 0.3 * xg + 0.1 * np.cross(nrm, xg)
    r = pj + np.array([0.0, 0.0, 0.15])
    om = -0.9 * nrm
    rdot = np.cross(om, r - pj)
    rdot = rdot + (0.1 - rdot[0]) / xg[0] * xg  # the marker point moves along xg (in the plane); ẋ = 0.1
    b.body("pla", 0.7, box(0.7, 0.6, 0.6, 0.2), r, att(), rdot=rdot, omega=om)
    b.joint("planar", None, b.marker("ground", piv, nrm, xg, scale=2.0),
            b.marker("pla", pj, nrm, quat.rotate(quat.axis_angle(nrm, 1.0), xg), scale=1.0))
    b.add({"kind": "drive", "name": "drive pla.x", "body": "pla", "coordinate": "x", "f": ["add", N(r[0]), ["mul", N(0.1), ["t"]]]})
    # 8. point on a line, and a user constraint on its z and Euler parameters.
    piv, ax = np.array([6.0, 0.0, 1.0]), unit([0.2, 1.0, -0.1])
    xg = unit(np.cross(ax, [0, 0, 1]))
    pj = piv + 0.4 * ax
    r = pj + np.array([0.1, 0.1, -0.2])
    om = np.array([0.2, -0.4, 0.3])
    a_pol = att()
    # pol.z − 0.3 pol.e1 pol.e0 + 0.2 pol.e3² − C = 0 at q0; its rate vanishes for the speed
    # along the line below (ṗ = ½ (0, ω) ⊗ p for the global ω).
    user = lambda q: q[2] - 0.3 * q[4] * q[3] + 0.2 * q[6] ** 2  # noqa: E731
    const = user(np.concatenate([r, a_pol]))
    pdot = 0.5 * quat.mul(np.concatenate([[0.0], om]), a_pol)
    zdot = 0.3 * (pdot[1] * a_pol[0] + a_pol[1] * pdot[0]) - 0.4 * a_pol[3] * pdot[3]
    speed = (zdot - np.cross(om, r - pj)[2]) / ax[2]
    b.body("pol", 0.6, box(0.6, 0.5, 0.5, 0.5), r, a_pol, rdot=speed * ax + np.cross(om, r - pj), omega=om)
    b.joint("point_on_line", None, b.marker("ground", piv, ax, xg, scale=0.3), b.marker("pol", pj))
    co = lambda c_: ["coord", "pol", c_]  # noqa: E731
    b.add({"kind": "constraint", "name": "constraint 0",
           "expr": ["sub", ["add", ["sub", co("z"), ["mul", ["mul", N(0.3), co("e1")], co("e0")]],
                            ["mul", N(0.2), ["pow", co("e3"), N(2)]]], N(const)]})
    # 9. point on a plane at distance c, the body's y driven: y0 + 0.2 t.
    piv, nrm = np.array([7.0, 0.0, 0.3]), unit([0.3, -0.1, 1.0])
    xg = unit(np.cross(nrm, [0, 1, 0]))
    pj = piv + 0.2 * xg - 0.1 * np.cross(nrm, xg) + c * nrm
    r = pj + np.array([0.2, -0.1, 0.3])
    om = np.array([0.3, 0.2, -0.5])
    rdot = np.cross(om, r - pj)
    inplane = unit(np.cross(nrm, [1, 0, 0]))  # in the plane, with a y component
    rdot = rdot + (0.2 - rdot[1]) / inplane[1] * inplane
    b.body("pop", 0.4, box(0.4, 0.5, 0.6, 0.7), r, att(), rdot=rdot, omega=om)
    b.joint("point_on_plane", None, b.marker("ground", piv, nrm, scale=5.0), b.marker("pop", pj), distance=P("c"))
    b.add({"kind": "drive", "name": "drive pop.y", "body": "pop", "coordinate": "y", "f": ["add", N(r[1]), ["mul", N(0.2), ["t"]]]})
    # 10. distance L to a ground point; the body's z driven: z0 + 0.1 sin t.
    piv = np.array([8.0, 0.0, 1.0])
    dirn = unit([0.3, 0.4, -1.0])
    pj = piv + length * dirn
    r = pj + np.array([0.1, 0.0, -0.1])
    om = np.array([0.0, 0.6, 0.2])
    rdot = np.cross(om, r - pj)
    perp = unit(np.cross(dirn, [1, 0, 0]))  # moves the point across the rod, with a z component
    rdot = rdot + (0.1 - rdot[2]) / perp[2] * perp
    b.body("dst", 0.5, box(0.5, 0.5, 0.5, 0.5), r, att(), rdot=rdot, omega=om)
    b.joint("distance", None, b.marker("ground", piv), b.marker("dst", pj), length=P("L"))
    b.add({"kind": "drive", "name": "drive dst.z", "body": "dst", "coordinate": "z", "f": ["add", N(r[2]), ["mul", N(0.1), ["sin", ["t"]]]]})
    return b.model()


def every_force():
    """(e) Every force element kind: gravity; point-to-point spring, damper and actuator, alone
    and combined, with ground on either side, state-, velocity- and time-dependent; rotational
    spring-damper-actuator on a revolute joint and a spring alone on a cylindrical joint; two
    bushings (one with damping and some null stiffnesses, one between moving bodies, stiffness
    only); global and body-frame forces and torques; revolute and translational viscous friction
    (the latter in a translational and in a cylindrical joint). 4 bodies, 14 rows."""
    b = Builder("EveryForce3", [("k", 300.0), ("c", 3.0), ("kr", 20.0), ("f0", 8.0), ("mu", 0.1)])
    b.gravity = [N(0.3), N(-0.2), N(-9.81)]
    full = [[0.05, 0.004, -0.002], [0.004, 0.08, 0.003], [-0.002, 0.003, 0.06]]
    rng = np.random.default_rng(11)

    def att():
        return unit(rng.normal(size=4))

    piv, ax = np.array([0.0, 0.0, 0.0]), unit([0.1, 0.2, 1.0])
    xg = unit(np.cross(ax, [1, 0, 0]))
    r_arm = piv + np.array([0.4, 0.1, 0.05])
    om_arm = 1.5 * ax
    b.body("arm", 1.2, full, r_arm, att(), rdot=np.cross(om_arm, r_arm - piv), omega=om_arm)
    b.joint("revolute", "pivot", b.marker("ground", piv, ax, xg, scale=2.0),
            b.marker("arm", piv, ax, quat.rotate(quat.axis_angle(ax, 0.35), xg), scale=1.0))
    # slider on the arm (translational between moving bodies)
    rail0, rail = r_arm + np.array([0.1, 0.0, 0.05]), unit([1.0, 0.3, -0.1])
    rx = unit(np.cross(rail, [0, 0, 1]))
    pj = rail0 + 0.2 * rail
    r_sl = pj + np.array([0.0, 0.05, 0.02])
    b.body("slider", 0.6, [[0.01, 0, 0], [0, 0.012, 0], [0, 0, 0.015]], r_sl, att(),
           rdot=b.velocity_of("arm", r_sl) + 0.4 * rail, omega=om_arm)
    b.joint("translational", "rail", b.marker("arm", rail0, rail, rx, scale=0.5), b.marker("slider", pj, rail, rx, scale=1.5))
    # drum on a cylindrical joint to ground
    piv2, ax2 = np.array([1.0, 0.5, 0.2]), unit([0.0, 1.0, 0.2])
    x2 = unit(np.cross(ax2, [0, 0, 1]))
    pj2 = piv2 + 0.1 * ax2
    r_dr = pj2 + np.array([0.02, 0.0, 0.03])
    om_dr = -2.0 * ax2
    b.body("drum", 2.0, [[0.1, 0, 0], [0, 0.2, 0], [0, 0, 0.1]], r_dr, att(), rdot=-0.3 * ax2 + np.cross(om_dr, r_dr - pj2), omega=om_dr)
    b.joint("cylindrical", "sleeve", b.marker("ground", piv2, ax2, x2, scale=1.0),
            b.marker("drum", pj2, ax2, quat.rotate(quat.axis_angle(ax2, -0.2), x2), scale=3.0))
    # puck: free
    r_pk = np.array([-0.5, 0.8, 0.4])
    b.body("puck", 0.3, [[0.002, 0.0002, 0], [0.0002, 0.003, 0], [0, 0, 0.004]], r_pk, att(), rdot=[0.3, -0.2, 0.5], omega=[1.0, 2.0, -1.5])

    def at(body, point):
        return {"body": body, "point": vec(b.local(body, np.asarray(point) - b.pose[body][0]))}

    vel, co = (lambda bd, c_: ["vel", bd, c_]), (lambda bd, c_: ["coord", bd, c_])
    F = b.forces.append
    F({"kind": "point_to_point", "name": "spring full", "i": at("arm", r_arm + [0.1, 0.1, 0]), "j": at("puck", r_pk + [0, 0.05, 0]),
       "k": P("k"), "length": N(0.6), "c": P("c"),
       "force": ["add", ["mul", P("f0"), ["sin", ["mul", N(2), ["t"]]]], ["mul", vel("arm", "wz"), co("puck", "e2")]]})
    F({"kind": "point_to_point", "name": "spring ground~slider", "i": at("ground", [0.5, -0.5, 1.0]), "j": at("slider", r_sl),
       "k": ["mul", N(2), P("k")], "length": N(0.9), "c": None, "force": None})
    F({"kind": "point_to_point", "name": "damper drum~ground", "i": at("drum", r_dr + [0.1, 0, 0]), "j": at("ground", [1.5, 1.0, 1.0]),
       "k": None, "length": N(0.0), "c": ["mul", N(2), P("c")], "force": None})
    F({"kind": "point_to_point", "name": "actuator puck~ground", "i": at("puck", r_pk), "j": at("ground", [0, 1, 1]),
       "k": None, "length": N(0.0), "c": None, "force": ["mul", P("f0"), ["cos", ["t"]]]})
    F({"kind": "rotational", "name": "rotational pivot", "joint": "pivot", "k": P("kr"), "angle": N(0.2), "c": N(0.4),
       "torque": ["add", N(1.0), co("drum", "e1")]})
    F({"kind": "rotational", "name": "rotational sleeve", "joint": "sleeve", "k": N(5.0), "angle": N(-0.3), "c": None, "torque": None})
    mk_g = b.marker("ground", [-0.4, 0.7, 0.5], unit([0.2, 0.1, 1]), unit([1, 0, 0]), scale=2.0)
    mk_p = b.marker("puck", r_pk + [0.02, 0.03, 0], unit([0.1, 0.3, 1]), unit([1, 0.2, 0]), scale=0.5)
    F({"kind": "bushing", "name": "bushing ground~puck", "i": mk_g, "j": mk_p,
       "k": [P("k"), ["mul", N(1.5), P("k")], None, P("kr"), N(12.0), N(8.0)],
       "c": [N(1.0), None, N(2.0), N(0.1), None, N(0.05)],
       "preload": [N(0.01), N(-0.02), N(0.0), N(0.05), N(0.0), N(-0.1)]})
    F({"kind": "bushing", "name": "bushing arm~puck", "i": b.marker("arm", r_arm + [0, 0.2, 0.1], unit([1, 0, 0.2]), unit([0, 1, 0]), scale=1.0),
       "j": b.marker("puck", r_pk, unit([0.9, 0.1, 0.2]), unit([0.1, 1, 0]), scale=1.0),
       "k": [N(50.0), N(60.0), N(70.0), N(3.0), N(4.0), N(5.0)], "c": [None] * 6,
       "preload": [N(0.0), N(0.1), N(0.0), N(0.0), N(0.02), N(0.0)]})
    F({"kind": "force", "name": "force slider", "at": at("slider", r_sl + [0.05, 0, 0]),
       "force": [N(1.0), ["mul", N(-2.0), ["t"]], ["mul", co("arm", "x"), vel("slider", "vy")]]})
    F({"kind": "local_force", "name": "local_force puck", "at": at("puck", r_pk + [0, 0, 0.05]),
       "force": [N(3.0), vel("puck", "wx"), ["mul", P("f0"), co("puck", "e3")]]})
    F({"kind": "torque", "name": "torque drum", "body": "drum", "torque": [["mul", N(0.5), ["cos", ["t"]]], N(0.2), vel("drum", "wy")]})
    F({"kind": "local_torque", "name": "local_torque puck", "body": "puck",
       "torque": [["neg", ["mul", P("mu"), vel("puck", "wx")]], N(0.01), ["atan2", co("arm", "y"), co("arm", "x")]]})
    F({"kind": "revolute_viscous", "name": "viscous pivot", "joint": "pivot", "c": P("mu")})
    F({"kind": "translational_viscous", "name": "viscous rail", "joint": "rail", "c": N(0.7)})
    F({"kind": "translational_viscous", "name": "viscous sleeve", "joint": "sleeve", "c": N(0.3)})
    return b.model()


def every_friction():
    """(f) Coulomb friction in a revolute joint (pin force of rows x, y, z) and a translational
    joint (rows offset_x, offset_y), with gravity and a spring so the loads vary. 2 bodies,
    10 rows: 2 degrees of freedom."""
    b = Builder("EveryFriction3", [("mu", 0.3), ("r", 0.02), ("vs", 0.05)])
    b.gravity = [N(0.5), N(-1.0), N(-9.81)]
    piv, ax = np.array([0.0, 0.0, 0.5]), unit([0.3, 1.0, 0.2])
    xg = unit(np.cross(ax, [0, 0, 1]))
    r_arm = piv + np.array([0.5, 0.0, 0.1])
    om = 1.2 * ax
    b.body("arm", 1.0, [[0.01, 0, 0], [0, 0.1, 0], [0, 0, 0.1]], r_arm, unit([0.9, 0.1, -0.3, 0.2]), rdot=np.cross(om, r_arm - piv), omega=om)
    b.joint("revolute", "pin", b.marker("ground", piv, ax, xg, scale=1.0), b.marker("arm", piv, ax, xg, scale=2.0))
    rail0, rail = r_arm + np.array([0.1, 0.05, 0.0]), unit([1.0, 0.0, 0.3])
    rx = unit(np.cross(rail, [0, 1, 0]))
    pj = rail0 + 0.1 * rail
    r_sl = pj + np.array([0.0, 0.0, 0.05])
    b.body("slider", 0.5, [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]], r_sl, unit([0.2, 0.9, 0.1, 0.3]),
           rdot=b.velocity_of("arm", r_sl) + 0.5 * rail, omega=om)
    b.joint("translational", "rail", b.marker("arm", rail0, rail, rx, scale=3.0), b.marker("slider", pj, rail, rx, scale=1.0))
    b.forces.append({"kind": "point_to_point", "name": "spring ground~slider", "i": {"body": "ground", "point": vec([1.0, 1.0, 1.5])},
                     "j": {"body": "slider", "point": vec([0, 0, 0])}, "k": N(200.0), "length": N(0.5), "c": N(3.0), "force": None})
    b.forces.append({"kind": "revolute_coulomb", "name": "coulomb pin", "joint": "pin", "mu": P("mu"), "radius": P("r"),
                     "slip_velocity": P("vs"), "row": b.first_row("pin")})
    b.forces.append({"kind": "translational_coulomb", "name": "coulomb rail", "joint": "rail", "mu": ["mul", N(2), P("mu")],
                     "slip_velocity": ["mul", N(2), P("vs")], "row": b.first_row("rail")})
    return b.model()


FIXTURES = {"torque_free": torque_free, "heavy_top": heavy_top, "double_pendulum": double_pendulum,
            "every_joint": every_joint, "every_force": every_force, "every_friction": every_friction}


def main(argv):
    out = argv[0] if argv else OUT
    os.makedirs(out, exist_ok=True)
    for name, make in FIXTURES.items():
        model = make()
        path = os.path.join(out, f"{name}.json")
        with open(path, "w") as f:
            json.dump(model, f, indent=1)
            f.write("\n")
        print(f"wrote {path}: {len(model['bodies'])} bodies, {len(model['constraint_rows'])} rows")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

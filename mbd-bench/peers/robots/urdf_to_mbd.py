#!/usr/bin/env python3
"""URDF -> mbd `mechanism!` DSL (spatial; joint_coordinates) for the UR5 and the Panda.

Reads the URDFs shipped by pip's `example-robot-data` (cmeel.prefix/share/example-robot-data)
and writes `mbd-bench/mechanisms/ur5.rs` and `panda.rs` (one `mbd::mechanism!` each). Run with the
peer benchmarks' environment (`bash mbd-bench/peers/ensure_env.sh` prints its interpreter):
`target/peers-venv/bin/python mbd-bench/peers/robots/urdf_to_mbd.py`.

The map from Pinocchio's q to mbd's (`mbd-bench/tests/robots.rs`): for Pinocchio's joint k and mbd's
coordinate `<urdf joint>.angle`, θ_mbd = θ0 + q_pin, θ0 from mbd's `initial_positions()` (the URDF's
zero pose written as the bodies' `at:` poses); v and v̇ map as they are. The sign is +1 by
construction: both markers of a joint are written along the URDF axis.

Modelling choices:
- one mbd body per link carried by a moving (revolute/continuous) joint; every link hanging on it
  by fixed joints (and locked joints) is merged into it: masses add, the centre of mass is the
  mass-weighted mean, inertias are rotated to the body frame and shifted by the parallel-axis
  theorem (I_c = sum R_i I_i R_i^T + m_i (|d_i|^2 E - d_i d_i^T), d_i = c_i - c);
- links reached from the root through fixed/locked joints only are ground (not declared);
- body frame = the link frame's orientation at q = 0 (all joints at 0, locked joints at their
  lock value), `at:` = the merged centre of mass at q = 0 (global), orientation as `quaternion:`;
- each moving joint is `revolute <urdf joint name>: parent[p] along [a] ~ child[p] along [a];`
  with points relative to each body's centre of mass in its body frame, the axis in each body
  frame (same direction on both sides, so s = +1 and the marker axes point along the URDF axis);
- the Panda's finger joints (prismatic) are locked at FINGER_LOCK (m) each, and the hand and
  fingers merge into panda_link7 (as pinocchio.buildReducedModel does).
All numbers are written with repr() (shortest round-trip, full f64 precision); below 1e-15 in
magnitude (the rounding left by rotations, e.g. 2.7e-18 m) as 0.0, which changes M by less than
1e-14 relative and keeps the zeros structural in the generated code.
"""
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
MECHANISMS = os.path.join(HERE, "..", "..", "mechanisms")
FINGER_LOCK = 0.02  # m, each Panda finger joint (range 0 .. 0.04): half open

ROBOTS = {
    # name: (struct name, URDF path under share/example-robot-data/robots, locked joints {name: value})
    "ur5": ("Ur5", "ur_description/urdf/ur5_robot.urdf", {}),
    "panda": ("Panda", "panda_description/urdf/panda.urdf",
              {"panda_finger_joint1": FINGER_LOCK, "panda_finger_joint2": FINGER_LOCK}),
}


def share_dir():
    """example-robot-data's robots folder inside the venv running this script (or $ERD_ROBOTS)."""
    if "ERD_ROBOTS" in os.environ:
        return os.environ["ERD_ROBOTS"]
    import sysconfig
    site = sysconfig.get_paths()["purelib"]
    return os.path.join(site, "cmeel.prefix", "share", "example-robot-data", "robots")


def urdf_path(robot):
    return os.path.join(share_dir(), ROBOTS[robot][1])


def rpy_matrix(rpy):
    """URDF: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def origin(elem):
    o = elem.find("origin") if elem is not None else None
    if o is None:
        return np.eye(3), np.zeros(3)
    xyz = [float(x) for x in o.get("xyz", "0 0 0").split()]
    rpy = [float(x) for x in o.get("rpy", "0 0 0").split()]
    return rpy_matrix(rpy), np.array(xyz)


def parse(path):
    root = ET.parse(path).getroot()
    links = {}
    for link in root.findall("link"):
        inertial = link.find("inertial")
        if inertial is None:
            links[link.get("name")] = (0.0, np.zeros(3), np.zeros((3, 3)))
            continue
        r, c = origin(inertial)
        m = float(inertial.find("mass").get("value"))
        i = inertial.find("inertia")
        g = lambda k: float(i.get(k, "0"))
        # URDF's ixy etc. are the tensor's entries (-∫xy dm), like mbd's Jxy.
        tensor = np.array([[g("ixx"), g("ixy"), g("ixz")], [g("ixy"), g("iyy"), g("iyz")], [g("ixz"), g("iyz"), g("izz")]])
        links[link.get("name")] = (m, c, r @ tensor @ r.T)  # in the link frame, about the com
    joints = {}
    for j in root.findall("joint"):
        r, p = origin(j)
        ax = j.find("axis")
        axis = np.array([float(x) for x in ax.get("xyz").split()]) if ax is not None else np.array([1.0, 0.0, 0.0])
        joints[j.get("name")] = dict(type=j.get("type"), parent=j.find("parent").get("link"),
                                     child=j.find("child").get("link"), R=r, p=p, axis=axis / np.linalg.norm(axis))
    return links, joints


def fmt(x):
    x = float(x)
    if abs(x) < 1e-15:
        return "0.0"
    s = repr(x)
    assert float(s) == x
    return s


def vec(v):
    return "[" + ", ".join(fmt(x) for x in v) + "]"


def quaternion(r):
    """Unit Euler parameters (e0 scalar) of a rotation matrix (Shepperd)."""
    t = np.trace(r)
    k = int(np.argmax([t, r[0, 0], r[1, 1], r[2, 2]]))
    if k == 0:
        e0 = 0.5 * math.sqrt(1 + t)
        q = [e0, (r[2, 1] - r[1, 2]) / (4 * e0), (r[0, 2] - r[2, 0]) / (4 * e0), (r[1, 0] - r[0, 1]) / (4 * e0)]
    elif k == 1:
        e1 = 0.5 * math.sqrt(1 + r[0, 0] - r[1, 1] - r[2, 2])
        q = [(r[2, 1] - r[1, 2]) / (4 * e1), e1, (r[0, 1] + r[1, 0]) / (4 * e1), (r[0, 2] + r[2, 0]) / (4 * e1)]
    elif k == 2:
        e2 = 0.5 * math.sqrt(1 - r[0, 0] + r[1, 1] - r[2, 2])
        q = [(r[0, 2] - r[2, 0]) / (4 * e2), (r[0, 1] + r[1, 0]) / (4 * e2), e2, (r[1, 2] + r[2, 1]) / (4 * e2)]
    else:
        e3 = 0.5 * math.sqrt(1 - r[0, 0] - r[1, 1] + r[2, 2])
        q = [(r[1, 0] - r[0, 1]) / (4 * e3), (r[0, 2] + r[2, 0]) / (4 * e3), (r[1, 2] + r[2, 1]) / (4 * e3), e3]
    q = np.array(q)
    return q / np.linalg.norm(q)


def convert(robot):
    struct, rel, locked = ROBOTS[robot]
    path = urdf_path(robot)
    links, joints = parse(path)
    children = {}
    for name, j in joints.items():
        children.setdefault(j["parent"], []).append(name)
    root = ({j["parent"] for j in joints.values()} - {j["child"] for j in joints.values()}).pop()

    # World pose of every link frame at q = 0 (locked joints at their value) and its body.
    pose = {root: (np.eye(3), np.zeros(3))}
    body_of = {root: None}  # None: ground
    moving = []  # moving joints in depth-first (URDF tree) order, as Pinocchio numbers them
    stack = [root]
    order = []
    while stack:
        link = stack.pop()
        order.append(link)
        for jn in reversed(children.get(link, [])):
            j = joints[jn]
            rp, pp = pose[link]
            r = rp @ j["R"]
            p = pp + rp @ j["p"]
            if j["type"] in ("revolute", "continuous") and jn not in locked:
                body_of[j["child"]] = j["child"]
                moving.append(jn)
            elif j["type"] == "fixed" or jn in locked:
                if j["type"] == "prismatic":
                    p = p + r @ (j["axis"] * locked[jn])
                elif j["type"] in ("revolute", "continuous") and locked.get(jn, 0.0) != 0.0:
                    raise SystemExit(f"{jn}: a locked revolute joint away from 0 is not handled")
                body_of[j["child"]] = body_of[link]
            else:
                raise SystemExit(f"{robot}: joint {jn} of type {j['type']} is not handled (lock it)")
            pose[j["child"]] = (r, p)
            stack.append(j["child"])
    # Pinocchio numbers joints depth-first in URDF child order; keep that order.
    moving.sort(key=lambda jn: order.index(joints[jn]["child"]))

    # Merge each body's links (global axes at q = 0, about the merged centre of mass).
    bodies = {}
    for jn in moving:
        b = joints[jn]["child"]
        members = [l for l in order if body_of[l] == b]
        m, mc, inertia = 0.0, np.zeros(3), np.zeros((3, 3))
        parts = []
        for l in members:
            ml, cl, il = links[l]
            if ml == 0.0:
                continue
            rl, pl = pose[l]
            parts.append((ml, pl + rl @ cl, rl @ il @ rl.T))
            m += ml
            mc += ml * (pl + rl @ cl)
        if m <= 0.0:
            raise SystemExit(f"{robot}: body {b} has no mass")
        c = mc / m
        for ml, cl, il in parts:
            d = cl - c
            inertia += il + ml * (d @ d * np.eye(3) - np.outer(d, d))
        rb = pose[b][0]
        jb = rb.T @ inertia @ rb
        jb = 0.5 * (jb + jb.T)
        bodies[b] = dict(mass=m, com=c, R=rb, J=jb, members=members)

    def marker(body, point_world, axis_world):
        if body is None:
            return f"ground{vec(point_world)} along {vec(axis_world)}"
        bd = bodies[body]
        return f"{body}{vec(bd['R'].T @ (point_world - bd['com']))} along {vec(bd['R'].T @ axis_world)}"

    lines = []
    ground_links = [l for l in order if body_of[l] is None]
    lines.append(f"// Generated by mbd-bench/peers/robots/urdf_to_mbd.py from example-robot-data's {rel}; do not edit.")
    lines.append("mbd::mechanism! {")
    note = f"fingers locked at {FINGER_LOCK} m each, hand and fingers merged into panda_link7" if locked else "fixed links merged"
    lines.append(f"    /// {struct} from example-robot-data's URDF ({note}); ground: {', '.join(ground_links)}.")
    lines.append(f"    pub {struct} {{")
    lines.append("        spatial;")
    lines.append("        joint_coordinates;")
    lines.append("        gravity [0.0, 0.0, -9.81];")
    for jn in moving:
        b = joints[jn]["child"]
        bd = bodies[b]
        jj = bd["J"]
        inertia = [jj[0, 0], jj[1, 1], jj[2, 2], jj[0, 1], jj[0, 2], jj[1, 2]]
        merged = [l for l in bd["members"] if l != b]
        comment = f"  // + {', '.join(merged)}" if merged else ""
        lines.append(f"        body {b} {{ mass: {fmt(bd['mass'])}, inertia: {vec(inertia)}, at: {vec(bd['com'])}, "
                     f"quaternion: {vec(quaternion(bd['R']))} }}{comment}")
    for jn in moving:
        j = joints[jn]
        r, p = pose[j["child"]]
        axis_world = r @ j["axis"]
        parent = body_of[j["parent"]]
        child = j["child"]
        lines.append(f"        revolute {jn}: {marker(parent, p, axis_world)} ~ "
                     f"{child}{vec(bodies[child]['R'].T @ (p - bodies[child]['com']))} along {vec(j['axis'])};")
    lines.append("    }")
    lines.append("}")
    with open(os.path.join(MECHANISMS, f"{robot}.rs"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"{robot}: {len(moving)} bodies/joints -> mechanisms/{robot}.rs; ground = {ground_links}")


if __name__ == "__main__":
    for robot in sys.argv[1:] or ["ur5", "panda"]:
        convert(robot)

"""MuJoCo's side of the UR5 / Panda comparison (`mbd-bench/benches/vs_pinocchio.rs`).

Builds each arm for MuJoCo from the URDF of pip's `example-robot-data` (the same files Pinocchio's
fixtures and mbd's mechanisms/ur5.rs and panda.rs were made from, by fixtures.py and
urdf_to_mbd.py beside this file), with only the <inertial> data kept:
  - every <visual> and <collision> element is removed (MuJoCo cannot load the meshes);
  - the Panda's finger joints (prismatic) are locked at FINGER_LOCK each: they become fixed joints
    whose origin is moved by FINGER_LOCK along the joint axis (their <mimic> goes with them, which
    MuJoCo would otherwise turn into an equality constraint), so the Panda has 7 DOF, as
    Pinocchio's buildReducedModel and mbd's panda.rs have;
  - every <dynamics> element is dropped: MuJoCo reads `damping` (the Panda has 0.003 on its arm
    joints, 0.3 on its fingers) into dof_damping, and `friction` into dof_frictionloss; Pinocchio's
    fixtures and mbd have neither;
  - `<mujoco><compiler discardvisual="true" fusestatic=".." balanceinertia="false" boundmass="0"
    boundinertia="0" inertiafromgeom="false"/></mujoco>` is added so the URDF's inertias are used
    as written. fusestatic="true" (MuJoCo's default for URDF) merges the links hanging on fixed
    joints into their parent (7 moving bodies for the Panda, as mbd's panda.rs); "false" keeps them
    as separate welded bodies (used to check each link's inertial data against the URDF).
Options: gravity (0, 0, -9.81), RK4, h = 1 ms, contacts and joint limits disabled (flags), no
damping, armature, friction loss or springs (checked on the compiled model).

Checks (stderr; the worst figures also in the JSON):
  - MuJoCo's joints (qpos order) are Pinocchio's (fixture "joints"), all hinges, nq = nv;
  - unfused model: each link's mass, centre of mass and inertia (from body_ipos, body_iquat,
    body_inertia) equal the URDF's <inertial> (max relative error);
  - both models, all fixture states: mj_fullM after mj_forward vs Pinocchio's crba, qfrc_bias vs
    nle, qacc (zero applied force) vs aba, as max ||diff||_inf / ||ref||_inf; and no constraint row
    is ever active (nefc = 0, also far outside the joint limits).

For each robot it prints (stdout, one JSON object), for the fused model (the step of the unfused
one is reported too):
  - q0, v0: the initial state, fixture state 0's q and 0.5 times its v (Pinocchio's order);
  - step_seconds / step_us: one RK4 step of MuJoCo's C loop, `mujoco.rollout.rollout` over NSTEP
    steps from that state (mjSTATE_FULLPHYSICS, one MjData, one thread), first call discarded,
    median of REPEATS calls divided by NSTEP;
  - finals: qpos and qvel at t = FINAL_TIME stepped with mj_step at h = 1 ms and h = 0.25 ms (their
    difference is MuJoCo's RK4 error at 1 ms, to 1/256).

Usage: target/peers-venv/bin/python mbd-bench/peers/robots/mujoco_robot.py [ur5] [panda]
(default: both), with the peer benchmarks' environment (`mbd-bench/peers/ensure_env.sh`), whose
example-robot-data provides the URDFs; the fixtures are ur5.json and panda.json beside this file.
"""

import json
import os
import sys
import xml.etree.ElementTree as ET

import mujoco
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.dont_write_bytecode = True
from mujoco_timing import SPEC, timed_rollout  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# The robots, their URDFs, the finger lock and URDF's rotations as the converter has them.
from urdf_to_mbd import ROBOTS, rpy_matrix, urdf_path  # noqa: E402

GRAVITY = (0.0, 0.0, -9.81)
STEP = 1.0e-3
NSTEP = 10000
REPEATS = 7
FINAL_TIME = 0.5
FINAL_STEPS = (1.0e-3, 0.25e-3)
V_SCALE = 0.5  # initial v = V_SCALE * fixture state 0's v
FIXTURES = os.path.dirname(os.path.abspath(__file__))


def floats(text, default):
    return [float(x) for x in (text if text is not None else default).split()]


def urdf_for_mujoco(path, locked, fuse):
    """The URDF's text for MuJoCo (see the module's docstring) and the settings overridden."""
    root = ET.parse(path).getroot()
    overrides = []
    for link in root.iter("link"):
        for e in link.findall("visual") + link.findall("collision"):
            link.remove(e)
    for joint in root.iter("joint"):
        name = joint.get("name")
        if name in locked:
            assert joint.get("type") == "prismatic", name
            o = joint.find("origin")
            if o is None:
                o = ET.SubElement(joint, "origin")
            xyz = np.array(floats(o.get("xyz"), "0 0 0"))
            axis = np.array(floats(joint.find("axis").get("xyz") if joint.find("axis") is not None else None, "1 0 0"))
            xyz = xyz + rpy_matrix(floats(o.get("rpy"), "0 0 0")) @ axis * locked[name]
            o.set("xyz", " ".join(repr(float(x)) for x in xyz))
            joint.set("type", "fixed")
            for tag in ("axis", "limit", "dynamics", "mimic", "safety_controller", "calibration"):
                for e in joint.findall(tag):
                    joint.remove(e)
            overrides.append(f"{name}: prismatic locked at {locked[name]} m (fixed joint, origin {xyz.tolist()})")
            continue
        for dyn in joint.findall("dynamics"):
            set_ = {k: v for k, v in dyn.attrib.items() if k in ("damping", "friction") and float(v) != 0.0}
            if set_:
                overrides.append(f"{name}: <dynamics> {set_} dropped (MuJoCo reads damping -> dof_damping, "
                                 f"friction -> dof_frictionloss)")
            joint.remove(dyn)
    for old in root.findall("mujoco"):
        root.remove(old)
    mj = ET.SubElement(root, "mujoco")
    ET.SubElement(mj, "compiler", discardvisual="true", fusestatic="true" if fuse else "false",
                  balanceinertia="false", boundmass="0", boundinertia="0", inertiafromgeom="false")
    return ET.tostring(root, encoding="unicode"), overrides, root


def build(robot, fuse):
    """Compiled MjModel (options set on its MjSpec), the settings overridden, the edited URDF tree."""
    text, overrides, root = urdf_for_mujoco(urdf_path(robot), ROBOTS[robot][2], fuse)
    spec = mujoco.MjSpec.from_string(text)
    spec.option.gravity = GRAVITY
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_RK4
    spec.option.timestep = STEP
    spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT | mujoco.mjtDisableBit.mjDSBL_LIMIT
    model = spec.compile()
    for field in ("dof_damping", "dof_armature", "dof_frictionloss", "jnt_stiffness"):
        assert not np.any(getattr(model, field)), (robot, field, getattr(model, field))
    assert model.nu == 0 and model.neq == 0 and model.ngeom == 0, (model.nu, model.neq, model.ngeom)
    assert np.all(model.jnt_type == mujoco.mjtJoint.mjJNT_HINGE) and model.nq == model.nv == model.njnt
    return model, overrides, root


def rel(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def link_inertia_error(model, root):
    """Unfused model: max relative error of each URDF link's mass, com and inertia in MuJoCo."""
    worst = {"mass": 0.0, "com": 0.0, "inertia": 0.0, "links": 0}
    for link in root.iter("link"):
        inertial = link.find("inertial")
        if inertial is None or float(inertial.find("mass").get("value")) == 0.0:
            continue
        b = model.body(link.get("name"))
        o = inertial.find("origin")
        rot = rpy_matrix(floats(o.get("rpy") if o is not None else None, "0 0 0"))
        com = np.array(floats(o.get("xyz") if o is not None else None, "0 0 0"))
        i = {k: float(v) for k, v in inertial.find("inertia").attrib.items()}
        inertia = rot @ np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]],
                                  [i["ixz"], i["iyz"], i["izz"]]]) @ rot.T
        r = np.empty(9)
        mujoco.mju_quat2Mat(r, b.iquat)
        r = r.reshape(3, 3)
        mj_inertia = r @ np.diag(b.inertia) @ r.T
        worst["mass"] = max(worst["mass"], rel(b.mass, float(inertial.find("mass").get("value"))))
        worst["com"] = max(worst["com"], rel(b.ipos, com) if np.any(com) else float(np.max(np.abs(b.ipos))))
        worst["inertia"] = max(worst["inertia"], rel(mj_inertia, inertia))
        worst["links"] += 1
    return worst


def fixture_errors(model, fixture):
    """Max ||diff||_inf / ||ref||_inf over the fixture states: M, bias (nle), qacc at zero force (aba)."""
    assert [model.joint(i).name for i in range(model.njnt)] == fixture["joints"], fixture["joints"]
    assert list(model.opt.gravity) == list(fixture["gravity"])
    data = mujoco.MjData(model)
    dense = np.zeros((model.nv, model.nv))
    worst = {"M": 0.0, "bias": 0.0, "qacc": 0.0, "nefc": 0}
    for s in fixture["states"]:
        mujoco.mj_resetData(model, data)
        data.qpos[:] = s["q"]
        data.qvel[:] = s["v"]
        mujoco.mj_forward(model, data)
        mujoco.mj_fullM(model, data, dense)
        worst["M"] = max(worst["M"], rel(dense, s["M"]))
        worst["bias"] = max(worst["bias"], rel(data.qfrc_bias, s["nle"]))
        worst["qacc"] = max(worst["qacc"], rel(data.qacc, s["aba"]))
        worst["nefc"] = max(worst["nefc"], int(data.nefc))
    return worst


def state_at(model, data, q, v):
    mujoco.mj_resetData(model, data)
    data.qpos[:] = q
    data.qvel[:] = v
    x0 = np.empty(mujoco.mj_stateSize(model, SPEC))
    mujoco.mj_getState(model, data, x0, SPEC)
    return x0


def finals(model, data, q0, v0):
    """qpos, qvel at t = FINAL_TIME from (q0, v0), mj_step at each of FINAL_STEPS."""
    out = []
    for h in FINAL_STEPS:
        model.opt.timestep = h
        state_at(model, data, q0, v0)
        for _ in range(round(FINAL_TIME / h)):
            mujoco.mj_step(model, data)
        out.append({"h": h, "t": float(data.time), "q": data.qpos.tolist(), "v": data.qvel.tolist()})
    model.opt.timestep = STEP
    return out


def step_time(model, q0, v0):
    data = mujoco.MjData(model)
    x0 = state_at(model, data, q0, v0)
    seconds, state = timed_rollout(model, data, x0, NSTEP, REPEATS)
    return seconds / NSTEP, bool(np.isfinite(state).all())


def measure(robot):
    with open(os.path.join(FIXTURES, f"{robot}.json")) as f:
        fixture = json.load(f)
    fused, overrides, _ = build(robot, True)
    unfused, _, unfused_root = build(robot, False)
    checks = {
        "links_unfused": link_inertia_error(unfused, unfused_root),
        "pinocchio_fused": fixture_errors(fused, fixture),
        "pinocchio_unfused": fixture_errors(unfused, fixture),
    }
    q0 = np.array(fixture["states"][0]["q"])
    v0 = V_SCALE * np.array(fixture["states"][0]["v"])
    data = mujoco.MjData(fused)
    ends = finals(fused, data, q0, v0)
    ends_unfused = finals(unfused, mujoco.MjData(unfused), q0, v0)
    seconds, finite = step_time(fused, q0, v0)
    seconds_unfused, finite_unfused = step_time(unfused, q0, v0)
    return {
        "robot": robot,
        "nq": int(fused.nq),
        "nbody": int(fused.nbody),
        "nbody_unfused": int(unfused.nbody),
        "joints": fixture["joints"],
        "q0": q0.tolist(),
        "v0": v0.tolist(),
        "step_seconds": seconds,
        "step_us": seconds * 1e6,
        "step_us_unfused": seconds_unfused * 1e6,
        "steps_timed": NSTEP,
        "repeats": REPEATS,
        "finite": finite and finite_unfused,
        "finals": ends,
        "rk4_diff_1ms_vs_0.25ms": float(np.max(np.abs(np.array(ends[0]["q"]) - ends[1]["q"]))),
        "fused_vs_unfused_q": max(float(np.max(np.abs(np.array(a["q"]) - b["q"]))) for a, b in zip(ends, ends_unfused)),
        "checks": checks,
        "overrides": overrides,
    }


def main(argv):
    names = argv or list(ROBOTS)
    robots = [measure(r) for r in names]
    for r in robots:
        c = r["checks"]
        print(f"MuJoCo {mujoco.__version__}, {r['robot']} ({r['nq']} DOF, {r['nbody']} bodies fused / "
              f"{r['nbody_unfused']} unfused): {r['step_us']:.3f} µs per RK4 step fused, "
              f"{r['step_us_unfused']:.3f} µs unfused (median of {REPEATS} rollouts of {NSTEP} steps)", file=sys.stderr)
        print(f"  URDF links ({c['links_unfused']['links']}) vs MuJoCo bodies, max rel. error: mass "
              f"{c['links_unfused']['mass']:.1e}, com {c['links_unfused']['com']:.1e}, inertia "
              f"{c['links_unfused']['inertia']:.1e}", file=sys.stderr)
        for k in ("pinocchio_fused", "pinocchio_unfused"):
            p = c[k]
            print(f"  vs Pinocchio ({k.split('_')[1]}), 20 states, max ||d||/||ref||: M {p['M']:.1e}, bias "
                  f"{p['bias']:.1e}, qacc {p['qacc']:.1e}; max nefc {p['nefc']}", file=sys.stderr)
        print(f"  q(t={FINAL_TIME}) h=1ms {r['finals'][0]['q']}\n  q(t={FINAL_TIME}) h=0.25ms {r['finals'][1]['q']}\n"
              f"  max |dq| 1 ms vs 0.25 ms {r['rk4_diff_1ms_vs_0.25ms']:.2e}; fused vs unfused {r['fused_vs_unfused_q']:.1e}",
              file=sys.stderr)
        for o in r["overrides"]:
            print(f"  override: {o}", file=sys.stderr)
    print(json.dumps({"mujoco": mujoco.__version__, "robots": robots}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

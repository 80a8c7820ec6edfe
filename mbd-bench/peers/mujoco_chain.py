"""MuJoCo's side of the spatial pendulum-chain comparison (mbd-bench/benches/vs_mujoco.rs runs it).

Builds the chains of mbd-bench/mechanisms/spatial_chain{4,16}.rs for MuJoCo — the same physical
chain in joint coordinates: nested bodies, each a bar of L = 0.1 m and m = 0.1 kg on a ball joint
at its start (the first at the world origin), centre of mass at L/2 along the body x-axis,
principal inertia (1e-6, m L²/12, m L²/12) kg·m² about it, body k+1 at (L, 0, 0) in body k and
turned 0.2 rad about z from it, so link k points along (cos 0.2k, sin 0.2k, 0): a horizontal arc
at rest, as mbd's `at:`/`axis_angle:` start. Gravity 9.81 m/s² along −z, RK4, h = 1 ms, contacts
off.

For each chain it prints (stdout, one JSON object):
  - step_seconds: the time of one RK4 step of MuJoCo's C loop, `mujoco.rollout.rollout` over
    NSTEP steps from the initial state (mjSTATE_FULLPHYSICS) with one MjData (one thread); the
    first call is discarded (setup), the median of REPEATS calls divided by NSTEP is reported;
  - tips: the position of the last link's free end (a site at (L, 0, 0)) at t = 0.5 s from the
    same state, stepped with mj_step at h = 1 ms and at h = 0.25 ms (to show how much of a
    difference to mbd is integration error: it must shrink about 4⁴ = 256 times), read after
    mj_kinematics;
  - finite: whether every state of the timed rollout stayed finite (a chain that blows up would
    time MuJoCo's reset path, not its dynamics).

With --hinge the chains are planar, as `vs_mujoco`'s planar chains in joint coordinates: the
same links on hinges about z (the first at the world origin), gravity 9.81 m/s² along −y, so the
arc falls in its own plane; each entry then says "joint": "hinge" (else "ball").

Usage: python mujoco_chain.py [--hinge] [N ...]   (default: 4 16)
"""

import json
import sys

import mujoco
import numpy as np

from mujoco_timing import initial_state, timed_rollout

LENGTH, MASS = 0.1, 0.1
TRANSVERSE = MASS * LENGTH * LENGTH / 12.0  # m L²/12 of a thin rod about its centre
AXIAL = 1.0e-6  # about the rod's axis (mbd needs a regular M; no joint torques about the axis)
TURN = 0.2  # rad about z between consecutive links
NSTEP = 2000
REPEATS = 7
TIP_TIME = 0.5
TIP_STEPS = (1.0e-3, 0.25e-3)


def chain_xml(n, joint="ball"):
    """MJCF of the chain of n links on `joint`s ("ball", or "hinge": about z, gravity along −y)."""
    joint_xml = '<joint type="ball"/>' if joint == "ball" else '<joint type="hinge" axis="0 0 1"/>'
    gravity = "0 0 -9.81" if joint == "ball" else "0 -9.81 0"
    inertial = (f'<inertial pos="{LENGTH / 2!r} 0 0" mass="{MASS!r}" '
                f'diaginertia="{AXIAL!r} {TRANSVERSE!r} {TRANSVERSE!r}"/>')
    body = f'<site name="tip" pos="{LENGTH!r} 0 0"/>'
    for k in reversed(range(n)):
        pos = "0 0 0" if k == 0 else f"{LENGTH!r} 0 0"
        turn = 0.0 if k == 0 else TURN
        body = (f'<body name="l{k}" pos="{pos}" axisangle="0 0 1 {turn!r}">'
                f'{joint_xml}{inertial}{body}</body>')
    return f"""<mujoco model="{joint}_chain{n}">
  <compiler angle="radian"/>
  <option timestep="0.001" integrator="RK4" gravity="{gravity}"><flag contact="disable"/></option>
  <worldbody>{body}</worldbody>
</mujoco>"""


def measure(n, joint="ball"):
    model = mujoco.MjModel.from_xml_string(chain_xml(n, joint))
    data = mujoco.MjData(model)
    x0 = initial_state(model, data)

    # Same motion: 0.5 s from the start, then the tip's position, at two step sizes.
    tips = []
    for h in TIP_STEPS:
        model.opt.timestep = h
        mujoco.mj_resetData(model, data)
        for _ in range(round(TIP_TIME / h)):
            mujoco.mj_step(model, data)
        mujoco.mj_kinematics(model, data)
        tips.append({"h": h, "t": float(data.time), "tip": data.site("tip").xpos.tolist()})
    model.opt.timestep = 1.0e-3
    mujoco.mj_resetData(model, data)

    # Timing: rollout's C loop; the first call sets up and is discarded.
    seconds, state = timed_rollout(model, data, x0, NSTEP, REPEATS)
    return {
        "links": n,
        "joint": joint,
        "nq": int(model.nq),
        "nv": int(model.nv),
        "step_seconds": seconds / NSTEP,
        "steps_timed": NSTEP,
        "repeats": REPEATS,
        "tips": tips,
        "finite": bool(np.isfinite(state).all()),
    }


def main(argv):
    joint = "hinge" if "--hinge" in argv else "ball"
    sizes = [int(a) for a in argv if not a.startswith("--")] or [4, 16]
    chains = [measure(n, joint) for n in sizes]
    for c in chains:
        print(f"MuJoCo {mujoco.__version__}, {c['joint']} chain of {c['links']}: {c['step_seconds'] * 1e6:.2f} µs per RK4 step "
              f"(median of {REPEATS} rollouts of {NSTEP} steps); tip at t = {TIP_TIME} s: {c['tips'][0]['tip']}",
              file=sys.stderr)
    print(json.dumps({"mujoco": mujoco.__version__, "chains": chains}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

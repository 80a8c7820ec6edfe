"""MuJoCo's RK4 on the study's planar pendulum chains (mbd-study/src/peers.rs runs it).

The chains of mbd-study/build.rs in MuJoCo's joint coordinates: n nested bodies, each a link of
L = 0.1 m and m = 0.1 kg on a hinge at its start (the first at the world origin), centre of mass
at L/2 along the body's x-axis, inertia 8.3333e-5 kg·m² about the hinge axis (the value mbd's
`inertia:` holds; 1e-9 about the link's own axis, which a planar motion never turns), gravity
9.81 m/s² along −z; released horizontal at rest. mbd's plane (x, y) is MuJoCo's (x, z); the hinge
axis is −y, so a positive joint angle turns a link from x towards z as mbd's φ turns it from x
towards y. Contacts off.

Input (argv[1], JSON): {"links": n, "t_end": s, "outputs": k, "steps": [h, ...], "repeats": r}.
For each step h (stdout, one JSON object, "runs": [...]):
  - seconds: the time of the whole run, t_end/h RK4 steps of MuJoCo's C loop
    (`mujoco.rollout.rollout` with one MjData, one thread) from the initial state; the first call
    is discarded (setup), the median of `repeats` calls is reported;
  - q: at each of the k output times t_end·j/k, the bodies' coordinates as mbd orders them,
    (x, y, φ) of each link's centre of mass, from the same rollout's states (mj_kinematics);
  - energy: T + V at the output times (mj_energyPos, mj_energyVel), and at t = 0;
  - failure: instead of q and energy, why there are none (MuJoCo reset an unstable run).
"""

import json
import os
import sys

import mujoco
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mbd-bench", "peers"))
from mujoco_timing import SPEC, initial_state, timed_rollout  # noqa: E402  (shared with the peer benchmark)

LENGTH, MASS, INERTIA, AXIAL = 0.1, 0.1, 8.3333e-5, 1.0e-9


def chain_xml(n, h):
    """MJCF of the chain of n links at step h."""
    inertial = (f'<inertial pos="{LENGTH / 2!r} 0 0" mass="{MASS!r}" '
                f'diaginertia="{AXIAL!r} {INERTIA!r} {INERTIA!r}"/>')
    body = ""
    for k in reversed(range(n)):
        pos = "0 0 0" if k == 0 else f"{LENGTH!r} 0 0"
        body = f'<body name="l{k}" pos="{pos}"><joint type="hinge" axis="0 -1 0"/>{inertial}{body}</body>'
    return f"""<mujoco model="chain{n}">
  <option timestep="{h!r}" integrator="RK4" gravity="0 0 -9.81"><flag contact="disable"/></option>
  <worldbody>{body}</worldbody>
</mujoco>"""


def coordinates(model, data):
    """(x, y, φ) of each link's centre of mass in mbd's plane."""
    mujoco.mj_kinematics(model, data)
    q = []
    for k in range(1, model.nbody):
        centre = data.xipos[k]
        axis = data.xmat[k].reshape(3, 3)[:, 0]  # the link's x-axis in the world
        q += [float(centre[0]), float(centre[2]), float(np.arctan2(axis[2], axis[0]))]
    return q


def energy(model, data):
    """T + V, computed on demand (the energy flag would add it to every timed step)."""
    mujoco.mj_forward(model, data)
    mujoco.mj_energyPos(model, data)
    mujoco.mj_energyVel(model, data)
    return float(data.energy[0] + data.energy[1])


def run(n, t_end, outputs, h, repeats):
    model = mujoco.MjModel.from_xml_string(chain_xml(n, h))
    data = mujoco.MjData(model)
    x0 = initial_state(model, data)
    e0 = energy(model, data)
    nstep = round(t_end / h)
    seconds, state = timed_rollout(model, data, x0, nstep, repeats)
    # The state after each step carries its time first (mjSTATE_TIME). MuJoCo resets a run whose
    # velocities become NaN, infinite or huge (warning "the simulation is unstable"): its clock
    # then jumps back.
    stamps = state[0, :, 0]
    finite = bool(np.isfinite(state).all()) and bool(np.all(np.diff(stamps) > 0))
    q, e = [], []
    if not finite:  # a run that blew up has no outputs to compare (and JSON has no NaN)
        first = int(np.argmax(np.diff(stamps) <= 0)) if np.isfinite(stamps).all() else 0
        return {"h": h, "steps": nstep, "seconds": seconds, "repeats": repeats,
                "failure": f"MuJoCo reset the unstable simulation (NaN, Inf or huge velocity) at t = {stamps[first]:.4g} s"}
    for j in range(1, outputs + 1):
        t = t_end * j / outputs
        i = int(np.argmin(np.abs(stamps - t)))
        if abs(stamps[i] - t) > 1e-9 * max(1.0, t):
            raise SystemExit(f"no state at t = {t} s with h = {h} s (steps must divide the output interval)")
        mujoco.mj_setState(model, data, state[0, i], SPEC)
        q.append(coordinates(model, data))
        e.append(energy(model, data))
    return {"h": h, "steps": nstep, "seconds": seconds, "repeats": repeats,
            "q": q, "energy": e, "energy0": e0, "finite": finite}


def main(argv):
    spec = json.load(open(argv[0]))
    runs = [run(spec["links"], spec["t_end"], spec["outputs"], h, spec["repeats"]) for h in spec["steps"]]
    print(json.dumps({"mujoco": mujoco.__version__, "runs": runs}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""What the MuJoCo comparisons share (mbd-bench/peers/mujoco_chain.py, mbd-study/mujoco_chain.py):
the model's full initial state and the timing of its C loop."""

import time

import mujoco
import mujoco.rollout
import numpy as np

SPEC = mujoco.mjtState.mjSTATE_FULLPHYSICS


def initial_state(model, data):
    """The full physics state (time first) after mj_resetData."""
    mujoco.mj_resetData(model, data)
    x0 = np.empty(mujoco.mj_stateSize(model, SPEC))
    mujoco.mj_getState(model, data, x0, SPEC)
    return x0


def timed_rollout(model, data, x0, nstep, repeats):
    """nstep steps of `mujoco.rollout.rollout` (one MjData, one thread) from x0: the first call
    sets up and is discarded; returns the median wall time of `repeats` calls (s) and the states
    after each step of the last, shape (1, nstep, len(x0))."""
    state = np.empty((1, nstep, x0.size))
    mujoco.rollout.rollout(model, data, x0, nstep=nstep, state=state)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        mujoco.rollout.rollout(model, data, x0, nstep=nstep, state=state)
        times.append(time.perf_counter() - start)
    return float(np.median(times)), state

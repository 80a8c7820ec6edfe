#!/usr/bin/env python3
"""Pinocchio fixtures for the UR5 and the Panda (fingers locked): `ur5.json`, `panda.json`.

20 random states per robot, numpy default_rng(SEED), uniform:
  q in [-pi, pi] rad, v in [-2, 2] rad/s, a in [-5, 5] rad/s^2 (Pinocchio's convention and order).
Per state: M = crba(q) symmetrized, nle = nle(q, v) (= C(q,v) v + g(q)),
aba = aba(q, v, tau = 0) (forward dynamics at zero torque), tau = rnea(q, v, a) (= M a + nle),
and each joint's load from that RNEA: the force and the moment about the joint's origin (world
axes) its parent applies to its child. mbd's h (Dynamics::forces) should be -nle, its free
accelerations aba, M a - h = tau, `joint_reaction_at` the joint loads
(`mbd-bench/tests/robots.rs`). Run with the peer benchmarks' environment:
`target/peers-venv/bin/python mbd-bench/peers/robots/fixtures.py`.
"""
import json
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from urdf_to_mbd import ROBOTS, urdf_path  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SEED = 20261130
N = 20
Q_RANGE, V_RANGE, A_RANGE = np.pi, 2.0, 5.0


def model(robot):
    """Pinocchio's fixed-base model of the URDF, locked joints removed (buildReducedModel)."""
    m = pin.buildModelFromUrdf(urdf_path(robot))
    locked = ROBOTS[robot][2]
    if locked:
        q_ref = pin.neutral(m)
        ids = []
        for name, value in locked.items():
            jid = m.getJointId(name)
            q_ref[m.joints[jid].idx_q] = value
            ids.append(jid)
        m = pin.buildReducedModel(m, ids, q_ref)
    return m


def main():
    for robot in ROBOTS:
        m = model(robot)
        d = m.createData()
        assert m.nq == m.nv, "revolute joints only"
        rng = np.random.default_rng(SEED)
        states = []
        for _ in range(N):
            q = rng.uniform(-Q_RANGE, Q_RANGE, m.nq)
            v = rng.uniform(-V_RANGE, V_RANGE, m.nv)
            a = rng.uniform(-A_RANGE, A_RANGE, m.nv)
            mass = pin.crba(m, d, q).copy()
            mass = np.triu(mass) + np.triu(mass, 1).T
            nle = pin.nle(m, d, q, v).copy()
            fd = pin.aba(m, d, q, v, np.zeros(m.nv)).copy()
            tau = pin.rnea(m, d, q, v, a).copy()
            assert np.allclose(mass @ fd, -nle, rtol=1e-10, atol=1e-10)
            # What each joint transmits from its parent to its child at (q, v, a) (RNEA's f_i, in
            # joint i's frame at its origin), turned to world axes; the moment about the origin.
            pin.forwardKinematics(m, d, q)
            loads = []
            for i in range(1, m.njoints):
                rotation, f = d.oMi[i].rotation, d.f[i]
                loads.append(dict(origin=d.oMi[i].translation.tolist(), force=(rotation @ f.linear).tolist(),
                                  moment=(rotation @ f.angular).tolist()))
            states.append(dict(q=q.tolist(), v=v.tolist(), a=a.tolist(), M=mass.tolist(), nle=nle.tolist(),
                               aba=fd.tolist(), rnea=tau.tolist(), joint_loads=loads))
        out = dict(robot=robot, pinocchio=pin.__version__, seed=SEED,
                   ranges=dict(q=Q_RANGE, v=V_RANGE, a=A_RANGE), gravity=list(m.gravity.linear),
                   joints=[m.names[i] for i in range(1, m.njoints)], states=states)
        with open(os.path.join(HERE, f"{robot}.json"), "w") as f:
            json.dump(out, f)
        print(f"{robot}: nq = {m.nq}, joints {out['joints']}, {N} states -> {robot}.json")


if __name__ == "__main__":
    main()

"""An independent reference motion: the mechanism rebuilt from its model JSON by the oracle
(planar: mbd_oracle.model and .dynamics; spatial: mbd_oracle.spatial), its equations of motion
solved for the accelerations by CasADi's symbolic Schur complement (the forward dynamics of
mbd_oracle.codegen, without Baumgarte terms), and integrated by SUNDIALS CVODES through CasADi.

Usage (from tests/oracle):
    python -m mbd_oracle.integrate INPUT.json

INPUT.json: {"model": MODEL_JSON, "q0": [...], "v0": [...], "t_end": T, "rtol": 1e-12,
"atol": 1e-14} (parameters at their defaults). Prints q(T) as one line of floats (repr, so they
read back exactly), prefixed "q_end ", then "rhs_evaluations N".

The ODE is y = (q, v), y' = (q̇, v̇): planar q̇ = v; spatial q̇ = B(q) v (Euler parameter rates
from body-frame ω′). Nothing holds the constraints but the integrator's accuracy: at rtol 1e-12
over a few seconds they drift by about the tolerance, which is the reference's resolution.
CVODES runs its Adams method (non-stiff, up to order 12), the fit for tight tolerances.
"""

import json
import sys

import casadi as ca
import numpy as np

from .codegen import forward_dynamics, spatial_forward_dynamics
from .model import Model
from .spatial import Spatial, is_spatial


def motion(model_json):
    """(y, y', p, p values, nq) of the ODE, as CasADi SX."""
    if is_spatial(model_json):
        s = Spatial(model_json)
        fd = spatial_forward_dynamics(s, "reference", None)[0]
        q, v, t, p = s.q, s.v, s.t, s.p
        qdot = s.qdot
        nq, nv = s.q.shape[0], s.v.shape[0]
    else:
        s = Model(model_json)
        fd = forward_dynamics(s, "reference")[0]
        q, v, t, p = s.q, s.qd, s.t, s.p
        qdot = v
        nq, nv = s.nq, s.nq
    vdot = fd(q, v, t, p, ca.DM([0.0, 0.0]))[:nv]
    return ca.vertcat(q, v), ca.vertcat(qdot, vdot), t, p, s.params_vector({}), nq


def main(argv):
    if len(argv) != 1:
        print(__doc__)
        return 2
    with open(argv[0]) as f:
        data = json.load(f)
    y, ydot, t, p, p_values, nq = motion(data["model"])
    options = {
        "reltol": data.get("rtol", 1e-12),
        "abstol": data.get("atol", 1e-14),
        "linear_multistep_method": "adams",
        "nonlinear_solver_iteration": "functional",
        "max_num_steps": 200_000,
    }
    dae = {"x": y, "t": t, "p": p, "ode": ydot}
    solver = ca.integrator("reference", "cvodes", dae, 0.0, float(data["t_end"]), options)
    y0 = np.concatenate([np.asarray(data["q0"], dtype=float), np.asarray(data["v0"], dtype=float)])
    result = solver(x0=y0, p=p_values)
    q_end = np.array(result["xf"]).reshape(-1)[:nq]
    print("q_end " + " ".join(repr(float(x)) for x in q_end))
    stats = solver.stats()
    print(f"rhs_evaluations {stats.get('nfevals', 'unknown')}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

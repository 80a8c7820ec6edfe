"""Reference trajectories of driven mechanisms (DOF = 0) from CasADi's own integrator.

Usage (from tests/oracle):
    python -m mbd_oracle.reference SAMPLES_OR_MODEL.json T_END N OUT.csv

With the parameters at their defaults: a consistent q0 at t = 0 is found with CasADi's Newton
rootfinder from the model's initial guess, then q' = Phi_q(q, t)^-1 nu(q, t) is integrated with
CVODES at rtol = atol = 1e-12 and written at N + 1 equally spaced times in [0, T_END] as CSV
(header: t and the coordinate names; comment lines start with #).
"""

import json
import sys

import casadi as ca
import numpy as np

from .model import Model

RTOL = 1e-12
ATOL = 1e-12


def initial_guess(model, p):
    """The model's q0 expressions (the bodies' `at:`) evaluated at parameters p."""
    q0 = []
    for b in model.json["bodies"]:
        q0.extend(model.expr(e) for e in b["q0"])
    f = ca.Function("q0", [model.p], [ca.vertcat(*q0)])
    return np.array(f(p)).reshape(-1)


def reference(model_json, t_end, n):
    model = Model(model_json)
    if model.nc != model.nq:
        raise ValueError(f"{model.name}: reference trajectories need a driven mechanism (NQ = NC)")
    p = model.params_vector({})
    # Consistent q0 at t = 0.
    g = ca.Function("g", [model.q, model.p], [ca.substitute(model.phi, model.t, 0.0)])
    newton = ca.rootfinder("newton", "newton", g, {"abstol": 1e-14, "max_iter": 50})
    q0 = np.array(newton(initial_guess(model, p), p)).reshape(-1)
    # q' = Phi_q^-1 nu, through a linear solve inside the MX graph.
    q = ca.MX.sym("q", model.nq)
    t = ca.MX.sym("t")
    jac = ca.Function("J", [model.q, model.t, model.p], [model.jac])
    nu = ca.Function("nu", [model.q, model.t, model.p], [model.nu])
    qdot = ca.solve(jac(q, t, p), nu(q, t, p))
    times = [t_end * k / n for k in range(n + 1)]
    f = ca.integrator("F", "cvodes", {"x": q, "t": t, "ode": qdot}, 0.0, times[1:], {"reltol": RTOL, "abstol": ATOL, "max_num_steps": 100000})
    xf = np.array(f(x0=q0)["xf"])
    rows = [[0.0] + list(q0)] + [[times[k + 1]] + list(xf[:, k]) for k in range(n)]
    return model, rows


def main(argv):
    if len(argv) != 4:
        print(__doc__)
        return 2
    src, t_end, n, out = argv[0], float(argv[1]), int(argv[2]), argv[3]
    with open(src) as f:
        data = json.load(f)
    model_json = data.get("model", data)
    model, rows = reference(model_json, t_end, n)
    with open(out, "w") as f:
        f.write(f"# {model.name}: CasADi {ca.__version__} CVODES, rtol = atol = {RTOL:g}, parameters at their defaults\n")
        f.write(f"# made by: python -m mbd_oracle.reference <samples of {model.name}> {t_end:g} {n} {out}\n")
        f.write(",".join(["t"] + model.json["coordinates"]) + "\n")
        for r in rows:
            f.write(",".join(repr(float(v)) for v in r) + "\n")
    print(f"{model.name}: wrote {len(rows)} rows to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

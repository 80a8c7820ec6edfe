"""Compares mbd's generated functions with CasADi's, entry by entry.

Usage: python -m mbd_oracle.compare SAMPLES.json [SAMPLES.json ...]   (from tests/oracle)

A samples file is {"model": <MODEL_JSON>, "samples": [{"params": {name: value}, "t", "q", "qd",
"phi", "nu", "jacobian" (values in the order of model["jacobian_pattern"]), "gamma"}, ...]}.
A sample may also hold the dynamics: "mass" (the diagonal of M), "h", "h_q", "h_qd" (dense
NQ×NQ, row r = h_r) and "potential"; and a forward-dynamics solution: "qdd", "lambda" with the
Baumgarte parameters "alpha", "beta" it was computed with; and Coulomb friction at given loads:
"friction_lambda", "friction", "friction_q", "friction_qd". Each is compared when present.
Exit status 1 if any entry disagrees or a generated structural zero is wrong.
"""

import json
import sys

import numpy as np

from .dynamics import Dynamics, NoFixedPoint
from .model import Model

# Relative tolerance of the comparison.
RTOL = 1e-12
# Absolute floor, relative to the size of the function's values at the sample: mbd and CasADi
# evaluate the same sums of products in different orders, so they differ by rounding of a few ulps
# (2.2e-16) of the largest term. For these mechanisms the terms are within a small factor (< 100)
# of the largest output entry ||f||_inf (or of 1 when all outputs are tiny), so
# ATOL_SCALE * max(1, ||f||_inf) admits ~4500 ulps of the largest term: comfortably above
# rounding, and eight or more orders below any wrong term, which is O(1) of the term itself.
ATOL_SCALE = 1e-12

# The dynamics ("mass", "h", "h_q", "h_qd", "potential") use the same RTOL and ATOL_SCALE, with
# the floor scaled to max(1, ||f||_inf, ||sum_e |f_e| ||_inf), where f_e are the contributions
# of gravity and of each force element to f: terms of different elements may cancel in a sum (a
# spring holding a body against gravity), and the rounding of that sum is relative to the terms,
# not to the result.
DYNAMICS = ("mass", "h", "h_q", "h_qd", "potential")

# Forward dynamics ("qdd", "lambda"): the solution x = [q̈; λ] of K x = b. mbd and the oracle
# solve the same system, whose entries they evaluate independently to within the tolerances
# above (relative ε_in = 1e-12 of the largest entry at worst), and each solve adds a backward
# error of a few ulps. By the normwise perturbation bound, ||δx|| ≤ cond(K) (||δK||/||K|| +
# ||δb||/||b||) ||x|| / (1 − cond(K) ||δK||/||K||): so entries of x must agree to
# KKT_SCALE · cond₂(K) · max(1, ||x||_inf), KKT_SCALE = 2 ε_in (K and b) — plus RTOL of the
# entry itself. At cond₂(K) ≥ KKT_MAX_COND that bound is no check at all (≥ 1e-2 of ||x||): such
# a sample is reported as a note and not compared (redundant constraints, singular positions).
KKT_SCALE = 2e-12
KKT_MAX_COND = 1e10
# With Coulomb friction mbd iterates on λ (fixed point) and stops at a change of 1e-13 relative
# (the samples ask for it); the oracle solves the fixed point by Newton to 1e-14. mbd is then off
# by the stopping change times c/(1 − c), c < 1 the contraction: up to ~1e-12 relative for the
# slowest samples (c ≈ 0.9), in λ and, through the same solve, ~1e-12·cond(K) in q̈.
# FRICTION_SCALE = 1e-11 is added to KKT_SCALE for such mechanisms.
FRICTION_SCALE = 1e-11

# Coulomb friction at given λ ("friction", and its exact "friction_q", "friction_qd" at fixed λ,
# dense NQ×NQ), with the λ it was evaluated at ("friction_lambda"): compared like the dynamics,
# the floor relative to max(1, ||f||_inf, ||sum_e |f_e| ||_inf) over the friction joints e.
FRICTION = ("friction_lambda", "friction", "friction_q", "friction_qd")


class Failure(Exception):
    pass


def check_values(failures, worst, name, function, got, want, atol, where, k):
    """Compares arrays got (mbd) and want (CasADi) entry by entry against RTOL·max(|a|, |b|) +
    atol; appends a failure naming where(index) and sample k for each disagreeing entry; updates
    worst[function] with the largest error/bound."""
    got = np.asarray(got, dtype=float)
    want = np.asarray(want, dtype=float)
    if got.shape != want.shape:
        failures.append(f"{name}: {function} at sample {k} has shape {got.shape} in mbd, {want.shape} in CasADi")
        return
    err = np.abs(got - want)
    bound = RTOL * np.maximum(np.abs(got), np.abs(want)) + atol
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(bound > 0, err / bound, np.where(err > 0, np.inf, 0.0))
    ratio = np.where(np.isnan(ratio), np.inf, ratio)  # a NaN on either side fails
    if ratio.size:
        worst[function] = max(worst.get(function, 0.0), float(np.max(ratio)))
    for index in zip(*np.nonzero(~(ratio <= 1.0))):
        a, b = float(got[index]), float(want[index])
        failures.append(f"{name}: {where(index)} at sample {k}: mbd {a!r} vs CasADi {b!r} "
                        f"(|diff| {abs(a - b):.3e} > {float(bound[index]):.3e})")


def dynamics_floor(want, magnitude):
    """ATOL_SCALE · max(1, ||want||_inf, ||magnitude||_inf) (see DYNAMICS above)."""
    scale = max(1.0, float(np.max(np.abs(want))) if np.size(want) else 1.0,
                float(np.max(np.abs(magnitude))) if np.size(magnitude) else 1.0)
    return ATOL_SCALE * scale


def compare_dynamics(data, model, out, failures, worst):
    """Compares the samples' "mass", "h", "h_q", "h_qd", "potential" and, where present, "qdd" and
    "lambda" with the CasADi rebuild; appends to failures and updates worst."""
    samples = data["samples"]
    has_dynamics = [all(key in s for key in DYNAMICS) for s in samples]
    has_forward = [all(key in s for key in ("qdd", "lambda", "alpha", "beta")) for s in samples]
    name = model.name
    for k, s in enumerate(samples):
        partial = [key for key in DYNAMICS if key in s] if not has_dynamics[k] else []
        partial += [key for key in ("qdd", "lambda", "alpha", "beta") if key in s] if not has_forward[k] else []
        if partial:
            failures.append(f"{name}: sample {k} holds {partial} but not the rest of its group "
                            f"({list(DYNAMICS)} or ['qdd', 'lambda', 'alpha', 'beta']): nothing of it is compared")
    if not any(has_dynamics) and not any(has_forward):
        return
    cols = data["model"]["coordinates"]
    rows = data["model"]["constraint_rows"]
    dyn = Dynamics(model)
    nq = model.nq
    # Structure of ∂h/∂q and ∂h/∂q̇: CasADi's structural non-zeros, and, over the samples, whether
    # CasADi's value there is ever beyond the floor and whether mbd's is ever non-zero.
    structure = {}
    for function, expr in (("h_q", dyn.h_q), ("h_qd", dyn.h_qd)):
        sp = expr.sparsity()
        nz = np.zeros((nq, nq), dtype=bool)
        for r, c in zip(sp.row(), sp.get_col()):
            nz[r, c] = True
        structure[function] = {"casadi": nz, "casadi_seen": np.zeros((nq, nq), dtype=bool), "mbd_seen": np.zeros((nq, nq), dtype=bool)}
    coord_names = {
        "mass": lambda i: f"mass[{cols[i[0]]}]",
        "h": lambda i: f"h[{cols[i[0]]}]",
        "h_q": lambda i: f"h_q[{cols[i[0]]}][{cols[i[1]]}]",
        "h_qd": lambda i: f"h_qd[{cols[i[0]]}][{cols[i[1]]}]",
        "potential": lambda i: "potential",
    }
    skipped = []
    for k, s in enumerate(samples):
        p = model.params_vector(s["params"])
        args = (s["q"], s["qd"], s["t"], p)
        if has_dynamics[k]:
            mags = dyn.f_magnitudes(*args)
            want = {
                "mass": np.array(dyn.f_mass(*args)).reshape(-1),
                "h": np.array(dyn.f_h(*args)).reshape(-1),
                "h_q": np.array(dyn.f_h_q(*args)).reshape(nq, nq),
                "h_qd": np.array(dyn.f_h_qd(*args)).reshape(nq, nq),
                "potential": np.array(dyn.f_potential(*args)).reshape(-1),
            }
            magnitude = {
                "mass": want["mass"],
                "h": np.array(mags[0]), "h_q": np.array(mags[1]), "h_qd": np.array(mags[2]),
                "potential": np.array(mags[3]).reshape(-1),
            }
            for function in DYNAMICS:
                got = np.array(s[function], dtype=float).reshape(want[function].shape) if function != "potential" \
                    else np.array([s[function]], dtype=float)
                atol = dynamics_floor(want[function], magnitude[function])
                check_values(failures, worst, name, function, got, want[function], atol, coord_names[function], k)
                if function in structure:
                    st = structure[function]
                    st["casadi_seen"] |= np.abs(want[function]) > atol
                    st["mbd_seen"] |= got != 0.0
        if all(key in s for key in FRICTION):
            lam = np.array(s["friction_lambda"], dtype=float)
            want = [np.array(v) for v in dyn.f_friction(*args, lam)]
            mags = [np.array(v) for v in dyn.f_friction_magnitudes(*args, lam)]
            for function, w, mag in zip(FRICTION[1:], want, mags):
                w = w.reshape(-1) if function == "friction" else w.reshape(nq, nq)
                got = np.array(s[function], dtype=float).reshape(w.shape)
                where = (lambda i, f=function: f"{f}[{cols[i[0]]}]") if function == "friction" else \
                    (lambda i, f=function: f"{f}[{cols[i[0]]}][{cols[i[1]]}]")
                check_values(failures, worst, name, function, got, w, dynamics_floor(w, mag), where, k)
        elif any(key in s for key in FRICTION):
            failures.append(f"{name}: sample {k} holds part of {list(FRICTION)}: nothing of it is compared")
        if has_forward[k]:
            try:
                qdd, lam, cond = dyn.forward(*args, s["alpha"], s["beta"])
            except NoFixedPoint as e:
                failures.append(f"{name}: sample {k}: mbd's forward dynamics converged, but {e}")
                continue
            if not cond < KKT_MAX_COND:
                skipped.append((k, cond))
                continue
            x = np.concatenate([qdd, lam])
            scale = KKT_SCALE + (FRICTION_SCALE if dyn.has_friction else 0.0)
            atol = scale * cond * max(1.0, float(np.max(np.abs(x))) if x.size else 1.0)
            check_values(failures, worst, name, "qdd", np.array(s["qdd"], dtype=float), qdd, atol,
                         lambda i: f"qdd[{cols[i[0]]}] (alpha {s['alpha']}, beta {s['beta']}, cond {cond:.1e})", k)
            check_values(failures, worst, name, "lambda", np.array(s["lambda"], dtype=float), lam, atol,
                         lambda i: f"lambda[{rows[i[0]]}] (alpha {s['alpha']}, beta {s['beta']}, cond {cond:.1e})", k)
            worst["kkt_cond"] = max(worst.get("kkt_cond", 0.0), cond)
    for k, cond in skipped:
        out(f"note: {name}: forward dynamics at sample {k} not compared: cond(K) = {cond:.1e} >= {KKT_MAX_COND:.0e}")
    for function, st in structure.items():
        for r, c in zip(*np.nonzero(st["casadi_seen"] & ~st["mbd_seen"])):
            failures.append(f"{name}: {function}[{cols[r]}][{cols[c]}] is a structural zero in mbd (0.0 at every sample) but non-zero in CasADi")
        for r, c in zip(*np.nonzero(st["mbd_seen"] & ~st["casadi"])):
            out(f"note: {name}: {function}[{cols[r]}][{cols[c]}] is non-zero in mbd at some sample but a structural zero in CasADi")
        for r, c in zip(*np.nonzero(st["casadi"] & ~st["casadi_seen"])):
            out(f"note: {name}: {function}[{cols[r]}][{cols[c]}] is structurally non-zero in CasADi but within the floor at every sample")


def compare_model(data, out=print):
    """Compares one samples file's data; returns a list of failure messages (empty: passed)."""
    model = Model(data["model"])
    name = model.name
    rows = data["model"]["constraint_rows"]
    cols = data["model"]["coordinates"]
    pattern = [tuple(rc) for rc in data["model"]["jacobian_pattern"]]
    pattern_set = set(pattern)
    failures = []
    if len(rows) != model.nc:
        failures.append(f"{name}: mbd has {len(rows)} constraint rows, CasADi's rebuild has {model.nc}")
        return failures

    # Sparsity: CasADi's structural non-zeros against the generated pattern.
    casadi_nz = model.structural_jacobian()
    missing = casadi_nz - pattern_set  # generated structural zeros CasADi does not know to be zero
    extra = pattern_set - casadi_nz  # generated non-zeros CasADi knows are zero
    for r, c in sorted(extra):
        out(f"note: {name}: jacobian[{rows[r]}][{cols[c]}] is a structural non-zero in mbd but not in CasADi")

    worst = {"phi": 0.0, "nu": 0.0, "jacobian": 0.0, "gamma": 0.0}
    seen_nonzero_in_missing = set()
    for k, s in enumerate(data["samples"]):
        p = model.params_vector(s["params"])
        args = (s["q"], s["qd"], s["t"], p)
        ref = {
            "phi": np.array(model.f_phi(*args)).reshape(-1),
            "nu": np.array(model.f_nu(*args)).reshape(-1),
            "gamma": np.array(model.f_gamma(*args)).reshape(-1),
        }
        dense = np.array(model.f_jac(*args))
        ref["jacobian"] = np.array([dense[r, c] for r, c in pattern])
        for function in ("phi", "nu", "gamma", "jacobian"):
            want = ref[function]
            atol = ATOL_SCALE * max(1.0, float(np.max(np.abs(want))) if want.size else 1.0)
            if function == "jacobian":
                where = lambda i: f"jacobian[{rows[pattern[i[0]][0]]}][{cols[pattern[i[0]][1]]}]"  # noqa: E731
            else:
                where = lambda i, function=function: f"{function}[{rows[i[0]]}]"  # noqa: E731
            check_values(failures, worst, name, function, s[function], want, atol, where, k)
        jac_atol = ATOL_SCALE * max(1.0, float(np.max(np.abs(dense))) if dense.size else 1.0)
        for r, c in missing:
            if abs(dense[r, c]) > jac_atol:
                seen_nonzero_in_missing.add((r, c))
    for r, c in sorted(seen_nonzero_in_missing):
        failures.append(f"{name}: jacobian[{rows[r]}][{cols[c]}] is a structural zero in mbd but non-zero in CasADi")
    for r, c in sorted(missing - seen_nonzero_in_missing):
        out(f"note: {name}: jacobian[{rows[r]}][{cols[c]}] is structurally non-zero in CasADi but zero at every sample; mbd omits it")
    compare_dynamics(data, model, out, failures, worst)
    out(
        f"{name}: {len(data['samples'])} samples, {model.nc} rows x {model.nq} coordinates, "
        f"{len(pattern)} Jacobian non-zeros; worst error/bound: "
        + ", ".join(f"{f} {w:.2e}" for f, w in worst.items() if f != "kkt_cond")
        + (f"; largest cond(K) {worst['kkt_cond']:.1e}" if "kkt_cond" in worst else "")
        + (f"; {len(failures)} FAILURES" if failures else "; ok")
    )
    return failures


def main(argv):
    if not argv:
        print(__doc__)
        return 2
    failed = []
    for path in argv:
        with open(path) as f:
            data = json.load(f)
        failed += compare_model(data)
    for message in failed[:50]:
        print("FAIL:", message)
    if len(failed) > 50:
        print(f"... and {len(failed) - 50} more")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""Compares mbd's generated functions with CasADi's, entry by entry.

Usage: python -m mbd_oracle.compare SAMPLES.json [SAMPLES.json ...]   (from tests/oracle)

A samples file is {"model": <MODEL_JSON>, "samples": [{"params": {name: value}, "t", "q", "qd",
"phi", "nu", "jacobian" (values in the order of model["jacobian_pattern"]), "gamma"}, ...]}.
Exit status 1 if any entry disagrees or a generated structural zero is wrong.
"""

import json
import sys

import numpy as np

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


class Failure(Exception):
    pass


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
            got = np.array(s[function], dtype=float)
            want = ref[function]
            atol = ATOL_SCALE * max(1.0, float(np.max(np.abs(want))) if want.size else 1.0)
            for e, (a, b) in enumerate(zip(got, want)):
                err = abs(a - b)
                bound = RTOL * max(abs(a), abs(b)) + atol
                worst[function] = max(worst[function], err / bound if bound > 0 else 0.0)
                if not err <= bound:
                    if function == "jacobian":
                        r, c = pattern[e]
                        where = f"jacobian[{rows[r]}][{cols[c]}]"
                    else:
                        where = f"{function}[{rows[e]}]"
                    failures.append(f"{name}: {where} at sample {k}: mbd {a!r} vs CasADi {b!r} (|diff| {err:.3e} > {bound:.3e})")
        jac_atol = ATOL_SCALE * max(1.0, float(np.max(np.abs(dense))) if dense.size else 1.0)
        for r, c in missing:
            if abs(dense[r, c]) > jac_atol:
                seen_nonzero_in_missing.add((r, c))
    for r, c in sorted(seen_nonzero_in_missing):
        failures.append(f"{name}: jacobian[{rows[r]}][{cols[c]}] is a structural zero in mbd but non-zero in CasADi")
    for r, c in sorted(missing - seen_nonzero_in_missing):
        out(f"note: {name}: jacobian[{rows[r]}][{cols[c]}] is structurally non-zero in CasADi but zero at every sample; mbd omits it")
    out(
        f"{name}: {len(data['samples'])} samples, {model.nc} rows x {model.nq} coordinates, "
        f"{len(pattern)} Jacobian non-zeros; worst error/bound: "
        + ", ".join(f"{f} {w:.2e}" for f, w in worst.items())
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

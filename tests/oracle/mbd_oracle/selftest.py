"""Shows the oracle can fail: wrong values must be rejected, with the mechanism, function, row
and column named.

Usage: python -m mbd_oracle.selftest SAMPLES.json [SAMPLES.json ...]
       python -m mbd_oracle.selftest --spatial [MODEL.json ...]   (default: the spatial fixtures
       every_joint, every_force, every_friction of fixtures/spatial/)
       python -m mbd_oracle.selftest --largest SAMPLES.json [SAMPLES.json ...]

With --largest (any samples file; joint coordinates' among them), for every function the samples
hold — Φ, the Jacobian, ν, γ, M, h, ∂h/∂q, ∂h/∂v, V, q̈ — the entry of largest magnitude over
the first SAMPLES samples (q̈: in the best-conditioned sample) is put off by a relative 1e-9 (q̈:
1e-8, as below), and each must be rejected with the mechanism and the function named. Run it on
samples whose functions are well above the comparison's floor (a function that stays below
1e-3 everywhere moves by less than the floor).

With --spatial, each spatial model JSON gets fake "mbd" samples made from the oracle's own
values at 16 random states (unit Euler parameters) — fine for a self-test, which tests the
comparison's ability to fail — and the same perturbations below must be rejected, with the
velocity as the column ("h_v", "friction_v" for "h_qd", "friction_qd").

For each file: a Jacobian entry and a γ entry off by a relative 1e-9, a dropped structural
non-zero of the Jacobian; and, when the samples hold the dynamics, the largest h entry and the
largest ∂h/∂q̇ entry of a sample off by a relative 1e-9 and an ∂h/∂q̇ entry zeroed at every
sample (a structural non-zero mbd would have lost); with Coulomb friction, the largest friction
force and ∂f/∂q̇ entry of a sample off by a relative 1e-9. Every one must be rejected, naming
where. The self-test takes each file's first SAMPLES samples, which hold every perturbed one: it
shows that the comparison can fail and says where; the comparison itself (compare.py) checks all
of them.
Forward dynamics: the oracle's own q̈ and λ, written into the samples, must pass, and the largest
q̈ entry of the best-conditioned sample off by a relative 1e-8 must be rejected (the comparison's
resolution is 2e-12·cond(K)·||[q̈; λ]||∞,
which for the checked mechanisms, cond(K) ~ 1e1–1e3 and |λ| up to ~10 |q̈|, lies between 1e-11
and 1e-8 of the largest q̈).
"""

import copy
import json
import sys

import numpy as np

import os

from . import quat
from .compare import compare_model, layout_of
from .dynamics import NoFixedPoint
from .spatial import Spatial

# Samples per file the planar self-test perturbs and compares (each perturbation is a whole
# comparison; the spatial self-test makes 16 of its own).
SAMPLES = 32


def expect_rejection(data, what, needles):
    failures = compare_model(data, out=lambda *_: None)
    text = "\n".join(failures)
    if not failures:
        print(f"selftest: the oracle ACCEPTED {what}")
        return False
    missing = [n for n in needles if n not in text]
    if missing:
        print(f"selftest: the oracle rejected {what} but did not name {missing}:\n{text}")
        return False
    print(f"selftest: rejected {what}: {failures[0]}")
    return True


def largest(matrix):
    """(row, column) of the entry of largest magnitude."""
    a = np.abs(np.asarray(matrix, dtype=float))
    return tuple(int(i) for i in np.unravel_index(np.argmax(a), a.shape))


def dynamics_selftest(data):
    """The dynamics perturbations; True when every one is rejected and named."""
    model = data["model"]
    lay = layout_of(model)
    name, cols, h_qd = model["name"], lay.columns, lay.dynamics[3]
    ok = True
    # 4. The largest h entry of sample 7 off by a relative 1e-9. (The largest, because the floor is
    #    relative to ||h||_inf: a relative 1e-9 of an entry a million times smaller than the largest
    #    is below rounding of the largest terms, and not a claim the oracle makes.)
    bad = copy.deepcopy(data)
    s = bad["samples"][7]
    (r,) = largest(s["h"])
    s["h"][r] = s["h"][r] * (1 + 1e-9) if s["h"][r] != 0 else 1e-9
    ok &= expect_rejection(bad, f"an h entry off by 1e-9 (relative) at [{cols[r]}]", [name, "h[", cols[r], "sample 7"])

    # 5. The largest ∂h/∂q̇ (∂h/∂v) entry of sample 9 off by a relative 1e-9.
    bad = copy.deepcopy(data)
    s = bad["samples"][9]
    r, c = largest(s[h_qd])
    s[h_qd][r][c] = s[h_qd][r][c] * (1 + 1e-9) if s[h_qd][r][c] != 0 else 1e-9
    ok &= expect_rejection(bad, f"an {h_qd} entry off by 1e-9 (relative) at [{cols[r]}][{cols[c]}]",
                           [name, h_qd, cols[r], cols[c], "sample 9"])

    # 6. A structural non-zero of ∂h/∂q̇ lost: that entry 0.0 at every sample.
    if any(any(v != 0 for row in s[h_qd] for v in row) for s in data["samples"]):
        bad = copy.deepcopy(data)
        r, c = largest(data["samples"][9][h_qd])
        for s in bad["samples"]:
            s[h_qd][r][c] = 0.0
        ok &= expect_rejection(bad, f"a lost structural non-zero of {h_qd} at [{cols[r]}][{cols[c]}]",
                               [name, h_qd, "structural zero", cols[r], cols[c]])
    return ok


def friction_selftest(data):
    """The Coulomb friction perturbations (mechanisms that have it); True when rejected and named."""
    model = data["model"]
    lay = layout_of(model)
    name, cols, f_qd = model["name"], lay.columns, lay.friction[3]
    ok = True
    # 7. The largest friction force of sample 11 and the largest ∂f/∂q̇ entry of sample 13 off by a
    #    relative 1e-9 (the largest, for the reason given at 4).
    bad = copy.deepcopy(data)
    s = bad["samples"][11]
    (r,) = largest(s["friction"])
    s["friction"][r] *= 1 + 1e-9
    ok &= expect_rejection(bad, f"a friction entry off by 1e-9 (relative) at [{cols[r]}]", [name, "friction[", cols[r], "sample 11"])
    bad = copy.deepcopy(data)
    s = bad["samples"][13]
    r, c = largest(s[f_qd])
    s[f_qd][r][c] *= 1 + 1e-9
    ok &= expect_rejection(bad, f"a {f_qd} entry off by 1e-9 (relative) at [{cols[r]}][{cols[c]}]",
                           [name, f_qd, cols[r], cols[c], "sample 13"])
    return ok


def forward_selftest(data, alpha=5.0, beta=7.0):
    """The forward-dynamics comparison: the oracle's own solution passes, a perturbed one fails."""
    model = data["model"]
    lay = layout_of(model)
    name, cols = model["name"], lay.columns
    good = copy.deepcopy(data)
    conds = []
    for s in good["samples"]:
        for key in ("qdd", "lambda", "alpha", "beta"):
            s.pop(key, None)
        try:
            qdd, lam, cond = lay.dyn.forward(*lay.args(s), alpha, beta)
        except NoFixedPoint:
            conds.append(np.inf)  # friction without a fixed point at this state: no q̈ to write
            continue
        s.update({"qdd": list(qdd), "lambda": list(lam), "alpha": alpha, "beta": beta})
        conds.append(cond)
    failures = compare_model(good, out=lambda *_: None)
    if failures:
        print(f"selftest: the oracle REJECTED its own forward dynamics:\n" + "\n".join(failures[:10]))
        return False
    # The best-conditioned sample: the resolution there is what the comparison can claim.
    k = int(np.argmin(conds))
    bad = copy.deepcopy(good)
    s = bad["samples"][k]
    (r,) = largest(s["qdd"])
    s["qdd"][r] *= 1 + 1e-8
    return expect_rejection(bad, f"a qdd entry off by 1e-8 (relative) at [{cols[r]}]", [name, "qdd", cols[r], f"sample {k}"])


def main(argv):
    if not argv:
        print(__doc__)
        return 2
    if argv[0] == "--largest":
        ok = True
        for path in argv[1:]:
            with open(path) as f:
                data = json.load(f)
            data["samples"] = data["samples"][:SAMPLES]
            ok &= largest_selftest(data)
        return 0 if ok else 1
    if argv[0] == "--spatial":
        paths = argv[1:] or [os.path.join(FIXTURES, f"{n}.json") for n in ("every_joint", "every_force", "every_friction")]
        ok = True
        for path in paths:
            with open(path) as f:
                data = spatial_samples(json.load(f))
            print(f"selftest: {data['model']['name']}: {len(data['samples'])} fake samples from the oracle's own values")
            ok &= selftest(data)
        return 0 if ok else 1
    ok = True
    for path in argv:
        with open(path) as f:
            data = json.load(f)
        data["samples"] = data["samples"][:SAMPLES]
        ok &= selftest(data)
    return 0 if ok else 1


FIXTURES = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "fixtures", "spatial"))


def random_spatial_state(s, rng, q0, spread=0.5, turn=0.5):
    """A random state near q0: centres within ±spread, attitudes turned by up to `turn` rad about
    random axes (unit Euler parameters), velocities in ±3, t in [0, 2], parameters ±10 %."""
    q = np.array(q0, dtype=float)
    for k in range(len(s.bodies)):
        q[7 * k:7 * k + 3] += rng.uniform(-spread, spread, 3)
        p = quat.mul(q[7 * k + 3:7 * k + 7], quat.axis_angle(rng.normal(size=3), rng.uniform(0, turn)))
        q[7 * k + 3:7 * k + 7] = p / np.linalg.norm(p)
    v = rng.uniform(-3, 3, s.nv)
    t = float(rng.uniform(0, 2))
    p = [d * rng.uniform(0.9, 1.1) for d in s.params_vector({})]
    return q, v, t, p


def spatial_samples(model_json, n=16, seed=5):
    """Fake "mbd" samples of a spatial model from the oracle's own values (every key of a
    spatial sample; forward dynamics with random Baumgarte gains where it solves)."""
    s = Spatial(model_json)
    rng = np.random.default_rng(seed)
    q0, _ = s.initial_state()
    pattern = [tuple(rc) for rc in model_json["jacobian_pattern"]]
    samples = []
    for _ in range(n):
        q, v, t, p = random_spatial_state(s, rng, q0)
        args = (q, v, t, p)
        phi, jac, nu, gamma = (np.array(x) for x in s.f_kinematics(*args))
        nv = s.nv
        sample = {"q": q.tolist(), "v": v.tolist(), "t": t, "p": p, "phi": phi.reshape(-1).tolist(),
                  "jacobian": [float(jac[r, c]) for r, c in pattern], "nu": nu.reshape(-1).tolist(),
                  "gamma": gamma.reshape(-1).tolist(), "mass": np.array(s.f_mass(*args)).reshape(nv, nv).tolist(),
                  "h": np.array(s.f_h(*args)).reshape(-1).tolist(), "h_q": np.array(s.f_h_q(*args)).reshape(nv, nv).tolist(),
                  "h_v": np.array(s.f_h_v(*args)).reshape(nv, nv).tolist(), "potential": float(s.f_potential(*args))}
        lam = rng.uniform(-50, 50, s.nc)
        fr = [np.array(x) for x in s.f_friction(*args, lam)]
        sample.update({"friction_lambda": lam.tolist(), "friction": fr[0].reshape(-1).tolist(),
                       "friction_q": fr[1].reshape(nv, nv).tolist(), "friction_v": fr[2].reshape(nv, nv).tolist(),
                       "friction_slope": fr[3].reshape(nv, s.nc).tolist()})
        alpha, beta = float(rng.uniform(0, 10)), float(rng.uniform(0, 10))
        try:
            vdot, lam, _ = s.forward(*args, alpha, beta)
            sample.update({"qdd": vdot.tolist(), "lambda": lam.tolist(), "alpha": alpha, "beta": beta})
        except NoFixedPoint:
            pass
        samples.append(sample)
    return {"model": model_json, "samples": samples}


def largest_selftest(data):
    """For each function the samples hold, its entry of largest magnitude off by a relative 1e-9
    (q̈: 1e-8); True when every one is rejected with mechanism and function named."""
    name = data["model"]["name"]
    if compare_model(copy.deepcopy(data), out=lambda *_: None):
        print(f"selftest: the unperturbed samples of {name} do not pass; nothing to show")
        return False
    ok = True
    lay = layout_of(data["model"])

    def conditioning(s):
        return lay.model.forward(*lay.args(s), s["alpha"], s["beta"])[2]

    for function in ("phi", "jacobian", "nu", "gamma", "mass", "h", "h_q", "h_v", "potential", "qdd"):
        best = None
        holding = [(k, s) for k, s in enumerate(data["samples"]) if function in s]
        if function == "qdd" and holding:
            # q̈ in the best-conditioned sample, whose bound is the tightest
            holding = [min(holding, key=lambda ks: conditioning(ks[1]))]
        for k, s in holding:
            a = np.abs(np.asarray(s[function], dtype=float)).reshape(-1)
            if a.size and (best is None or a.max() > best[2]):
                best = (k, int(np.argmax(a)), float(a.max()))
        if best is None or best[2] == 0.0:
            continue
        k, i, _ = best
        bad = copy.deepcopy(data)
        flat = np.asarray(bad["samples"][k][function], dtype=float)
        shape = flat.shape
        flat = flat.reshape(-1)
        flat[i] *= 1 + (1e-8 if function == "qdd" else 1e-9)
        bad["samples"][k][function] = flat.reshape(shape).tolist() if shape else float(flat[0])
        ok &= expect_rejection(bad, f"the largest {function} entry off (sample {k})", [name, function, f"sample {k}"])
    return ok


def selftest(data):
    """All perturbations of one samples file; True when every one is rejected and named."""
    model = data["model"]
    name, rows, cols = model["name"], model["constraint_rows"], layout_of(model).columns
    ok = compare_model(copy.deepcopy(data), out=lambda *_: None) == []
    if not ok:
        print(f"selftest: the unperturbed samples of {name} do not pass; nothing to show")
        return False

    # 1. One Jacobian entry off by a relative 1e-9.
    bad = copy.deepcopy(data)
    e = len(model["jacobian_pattern"]) // 2
    r, c = model["jacobian_pattern"][e]
    v = bad["samples"][3]["jacobian"][e]
    bad["samples"][3]["jacobian"][e] = v * (1 + 1e-9) if v != 0 else 1e-9
    ok &= expect_rejection(bad, f"a Jacobian entry off by 1e-9 (relative) at [{rows[r]}][{cols[c]}]",
                           [name, "jacobian", rows[r], cols[c], "sample 3"])

    # 2. One gamma entry off by a relative 1e-9.
    bad = copy.deepcopy(data)
    row = len(rows) // 3
    v = bad["samples"][5]["gamma"][row]
    bad["samples"][5]["gamma"][row] = v * (1 + 1e-9) if v != 0 else 1e-9
    ok &= expect_rejection(bad, f"a gamma entry off by 1e-9 (relative) at [{rows[row]}]", [name, "gamma", rows[row], "sample 5"])

    # 3. A generated structural zero where CasADi has a non-zero: drop one pattern entry.
    bad = copy.deepcopy(data)
    r, c = bad["model"]["jacobian_pattern"].pop(0)
    for s in bad["samples"]:
        s["jacobian"].pop(0)
    ok &= expect_rejection(bad, f"a missing structural non-zero at [{rows[r]}][{cols[c]}]", [name, "structural zero", rows[r], cols[c]])

    if all("h" in s for s in data["samples"]):
        ok &= dynamics_selftest(data)
    if any(any(v != 0 for v in s.get("friction", [])) for s in data["samples"]):
        ok &= friction_selftest(data)
    ok &= forward_selftest(data)
    return ok


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""Compares mbd's generated functions with CasADi's, entry by entry.

Usage: python -m mbd_oracle.compare SAMPLES.json [SAMPLES.json ...]   (from tests/oracle)

A samples file is {"model": <MODEL_JSON>, "samples": [{"params": {name: value}, "t", "q", "qd",
"phi", "nu", "jacobian" (values in the order of model["jacobian_pattern"]), "gamma"}, ...]}.
A sample may also hold the dynamics: "mass" (the diagonal of M), "h", "h_q", "h_qd" (dense
NQ×NQ, row r = h_r) and "potential"; and a forward-dynamics solution: "qdd", "lambda" with the
Baumgarte parameters "alpha", "beta" it was computed with; and Coulomb friction at given loads:
"friction_lambda", "friction", "friction_q", "friction_qd"; and γ's derivatives "gamma_q",
"gamma_v" (dense NC×NQ; spatial: (∂γ/∂q) B and ∂γ/∂v, NC×NV). Each is compared when present.

A SPATIAL model ("dimension": 3, docs/formulation.md "Spatial bodies") is rebuilt by spatial.py
and compared by the same rules; its samples hold "q" (NQ, unit Euler parameters), "v" (NV),
"t", the parameters as "p" (values in model["params"] order, or a {name: value} mapping; "params"
is accepted too), "phi", "jacobian" (the non-zeros of D = Φ_q B in jacobian_pattern order), "nu",
"gamma", "mass" (dense NV×NV), "h", "h_q" (dense NV×NV, (∂h/∂q) B), "h_v" (dense NV×NV),
"potential"; optionally "friction_lambda", "friction", "friction_q" ((∂f/∂q) B), "friction_v",
and "qdd" (v̇, NV), "lambda", "alpha", "beta". Row, coordinate and velocity names must be the
spec's. A spatial model in JOINT coordinates (a "tree" in its JSON) is rebuilt by joint.py and
compared the same way, its samples' unit quaternions being the tree's.
Exit status 1 if any entry disagrees or a generated structural zero is wrong.
"""

import json
import sys

import numpy as np

from .dynamics import Dynamics, NoFixedPoint
from .model import Model
from .spatial import Spatial, is_spatial
from .joint import JointPlanar, JointSpatial, has_tree

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
# dense NQ×NQ, and its slope in the loads "friction_slope", ∂f/∂λ, NQ×NC), with the λ it was
# evaluated at ("friction_lambda"): compared like the dynamics, the floor relative to
# max(1, ||f||_inf, ||sum_e |f_e| ||_inf) over the friction joints e.
FRICTION = ("friction_lambda", "friction", "friction_q", "friction_qd", "friction_slope")


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



class PlanarLayout:
    """Planar samples: q̇ as "qd", ∂h/∂q̇ as "h_qd", M as its diagonal; columns are coordinates."""

    spatial = False
    velocity = "qd"
    dynamics = DYNAMICS
    friction = FRICTION

    def __init__(self, model_json):
        self.model = Model(model_json)
        self.columns = model_json["coordinates"]  # of the Jacobian, and of h and its derivatives
        self._dyn = None

    @property
    def dyn(self):
        if self._dyn is None:
            self._dyn = Dynamics(self.model)
        return self._dyn

    def args(self, s):
        return (s["q"], s["qd"], s["t"], self.model.params_vector(s["params"]))

    def structure(self):
        return {"h_q": self.dyn.h_q, "h_qd": self.dyn.h_qd}

    def dynamics_at(self, args):
        """(want, magnitude): CasADi's values of self.dynamics and the floors' magnitudes."""
        dyn, n = self.dyn, self.model.nq
        mags = dyn.f_magnitudes(*args)
        want = {"mass": np.array(dyn.f_mass(*args)).reshape(-1), "h": np.array(dyn.f_h(*args)).reshape(-1),
                "h_q": np.array(dyn.f_h_q(*args)).reshape(n, n), "h_qd": np.array(dyn.f_h_qd(*args)).reshape(n, n),
                "potential": np.array(dyn.f_potential(*args)).reshape(-1)}
        magnitude = {"mass": want["mass"], "h": np.array(mags[0]), "h_q": np.array(mags[1]), "h_qd": np.array(mags[2]),
                     "potential": np.array(mags[3]).reshape(-1)}
        return want, magnitude


class SpatialLayout:
    """Spatial samples: velocities as "v", ∂h/∂v as "h_v", dense M; columns are velocities."""

    spatial = True
    velocity = "v"
    dynamics = ("mass", "h", "h_q", "h_v", "potential")
    friction = ("friction_lambda", "friction", "friction_q", "friction_v", "friction_slope")

    def __init__(self, model_json):
        self.model = Spatial(model_json)
        self.dyn = self.model
        self.columns = model_json.get("velocities", self.model.velocity_names)

    def quaternions(self):
        """(where in q, whose) of each unit quaternion: every body's Euler parameters."""
        return [(7 * b + 3, f"{body}'s Euler parameters") for b, body in enumerate(self.model.bodies)]

    def args(self, s):
        p = s["p"] if "p" in s else s["params"]
        return (s["q"], s["v"], s["t"], self.model.params_vector(p))

    def structure(self):
        return {"h_q": self.model.h_q, "h_v": self.model.h_v}

    def dynamics_at(self, args):
        n = self.model.nv
        mass, h, h_q, h_v, potential, *mags = (np.array(x) for x in self.model.f_dynamics(*args))
        want = {"mass": mass.reshape(n, n), "h": h.reshape(-1), "h_q": h_q.reshape(n, n), "h_v": h_v.reshape(n, n),
                "potential": potential.reshape(-1)}
        magnitude = {"mass": want["mass"], "h": mags[0], "h_q": mags[1], "h_v": mags[2], "potential": mags[3].reshape(-1)}
        return want, magnitude

    def names_failures(self, data):
        """The model JSON's coordinate, velocity and row names against the spec's (the rebuild's)."""
        mj, m, failures = data["model"], self.model, []
        for key, want in (("coordinates", m.coordinate_names), ("velocities", m.velocity_names), ("constraint_rows", m.row_names)):
            got = mj.get(key)
            if got != want:
                diff = [f"{k}: {a!r} (spec: {b!r})" for k, (a, b) in enumerate(zip(got or [], want)) if a != b][:5]
                failures.append(f"{m.name}: model {key} differ from the spec's: {len(got or [])} names, the rebuild has "
                                f"{len(want)}; " + "; ".join(diff))
        return failures

    def sample_failures(self, k, s):
        """Sizes of q and v, and unit Euler parameters (the comparison holds only at |p| = 1)."""
        m = self.model
        if len(s["q"]) != m.nq or len(s[self.velocity]) != m.nv:
            return [f"{m.name}: sample {k} has {len(s['q'])} coordinates and {len(s[self.velocity])} velocities, "
                    f"the model {m.nq} and {m.nv}"]
        out = []
        for at, whose in self.quaternions():
            norm = float(np.linalg.norm(np.asarray(s["q"][at:at + 4], dtype=float)))
            if abs(norm - 1.0) > UNIT_TOL:
                out.append(f"{m.name}: sample {k}: {whose} have |p| = {norm!r}; samples use unit p "
                           f"(|p| − 1 within {UNIT_TOL:g})")
        return out


# Samples of spatial models use unit Euler parameters: D, γ, h_q B are independent of how A(p)
# is written off |p| = 1 only on it. A normalized p is within a few ulps of unit length.
UNIT_TOL = 1e-14


class SpatialJointLayout(SpatialLayout):
    """Spatial samples in joint coordinates (a model with a "tree", joint.py): as spatial ones,
    the unit quaternions being the tree's (ball joints', free bodies')."""

    def __init__(self, model_json):
        self.model = JointSpatial(model_json) if is_spatial(model_json) else JointPlanar(model_json)
        self.dyn = self.model
        self.columns = model_json.get("velocities", self.model.velocity_names)

    def quaternions(self):
        """The tree's unit quaternions: its ball joints' and free bodies' (none in the plane)."""
        return [(at, f"the quaternion at q[{at}]") for at in self.model.quaternions]


def layout_of(model_json):
    if has_tree(model_json):
        return SpatialJointLayout(model_json)
    return SpatialLayout(model_json) if is_spatial(model_json) else PlanarLayout(model_json)


def compare_gamma_derivatives(data, lay, failures, worst):
    """Compares "gamma_q" ((∂γ/∂q) B, dense NC×NV) and "gamma_v" (∂γ/∂v) where the samples hold
    them, with the floor of the Jacobian's: ATOL_SCALE · max(1, ||f||_inf) — γ's derivatives are
    sums of products of the same terms as γ, evaluated in different orders."""
    rows = data["model"]["constraint_rows"]
    cols = lay.columns
    for k, s in enumerate(data["samples"]):
        if "gamma_q" not in s:
            continue
        want = [np.array(x) for x in lay.model.f_gamma_derivatives(*lay.args(s))]
        for function, w in zip(("gamma_q", "gamma_v"), want):
            if w.size == 0:
                continue
            atol = ATOL_SCALE * max(1.0, float(np.max(np.abs(w))))
            where = lambda i, function=function: f"{function}[{rows[i[0]]}][{cols[i[1]]}]"  # noqa: E731
            check_values(failures, worst, lay.model.name, function, np.array(s[function]), w, atol, where, k)


def compare_dynamics(data, lay, out, failures, worst):
    """Compares the samples' dynamics (lay.dynamics: "mass", "h", "h_q", "h_qd" or "h_v",
    "potential"), Coulomb friction and, where present, "qdd" and "lambda" with the CasADi
    rebuild; appends to failures and updates worst."""
    samples = data["samples"]
    dynamics, friction = lay.dynamics, lay.friction
    has_dynamics = [all(key in s for key in dynamics) for s in samples]
    has_forward = [all(key in s for key in ("qdd", "lambda", "alpha", "beta")) for s in samples]
    model = lay.model
    name = model.name
    for k, s in enumerate(samples):
        partial = [key for key in dynamics if key in s] if not has_dynamics[k] else []
        partial += [key for key in ("qdd", "lambda", "alpha", "beta") if key in s] if not has_forward[k] else []
        if partial:
            failures.append(f"{name}: sample {k} holds {partial} but not the rest of its group "
                            f"({list(dynamics)} or ['qdd', 'lambda', 'alpha', 'beta']): nothing of it is compared")
    if not any(has_dynamics) and not any(has_forward):
        return
    cols = lay.columns
    rows = data["model"]["constraint_rows"]
    dyn = lay.dyn
    n = len(cols)
    # Structure of ∂h/∂q and ∂h/∂q̇ (∂h/∂v): CasADi's structural non-zeros, and, over the samples,
    # whether CasADi's value there is ever beyond the floor and whether mbd's is ever non-zero.
    structure = {}
    for function, expr in lay.structure().items():
        sp = expr.sparsity()
        nz = np.zeros((n, n), dtype=bool)
        for r, c in zip(sp.row(), sp.get_col()):
            nz[r, c] = True
        structure[function] = {"casadi": nz, "casadi_seen": np.zeros((n, n), dtype=bool), "mbd_seen": np.zeros((n, n), dtype=bool)}

    def where_of(function, shape):
        if function == "potential":
            return lambda i: "potential"
        if len(shape) == 1:
            return lambda i: f"{function}[{cols[i[0]]}]"
        if function == "friction_slope":
            return lambda i: f"{function}[{cols[i[0]]}][{rows[i[1]]}]"
        return lambda i: f"{function}[{cols[i[0]]}][{cols[i[1]]}]"

    skipped = []
    for k, s in enumerate(samples):
        args = lay.args(s)
        if has_dynamics[k]:
            want, magnitude = lay.dynamics_at(args)
            for function in dynamics:
                got = np.array(s[function], dtype=float).reshape(want[function].shape) if function != "potential" \
                    else np.array([s[function]], dtype=float)
                atol = dynamics_floor(want[function], magnitude[function])
                check_values(failures, worst, name, function, got, want[function], atol, where_of(function, want[function].shape), k)
                if function in structure:
                    st = structure[function]
                    st["casadi_seen"] |= np.abs(want[function]) > atol
                    st["mbd_seen"] |= got != 0.0
        if all(key in s for key in friction):
            lam = np.array(s["friction_lambda"], dtype=float)
            want = [np.array(v) for v in dyn.f_friction(*args, lam)]
            mags = [np.array(v) for v in dyn.f_friction_magnitudes(*args, lam)]
            for function, w, mag in zip(friction[1:], want, mags):
                w = w.reshape(-1) if function == "friction" else w.reshape(n, -1)
                got = np.array(s[function], dtype=float).reshape(w.shape)
                check_values(failures, worst, name, function, got, w, dynamics_floor(w, mag), where_of(function, w.shape), k)
        elif any(key in s for key in friction):
            failures.append(f"{name}: sample {k} holds part of {list(friction)}: nothing of it is compared")
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
    lay = layout_of(data["model"])
    model = lay.model
    name = model.name
    rows = data["model"]["constraint_rows"]
    cols = lay.columns
    pattern = [tuple(rc) for rc in data["model"]["jacobian_pattern"]]
    pattern_set = set(pattern)
    failures = []
    if len(rows) != model.nc:
        failures.append(f"{name}: mbd has {len(rows)} constraint rows, CasADi's rebuild has {model.nc}")
        return failures
    if lay.spatial:
        failures += lay.names_failures(data)
        for k, s in enumerate(data["samples"]):
            failures += lay.sample_failures(k, s)
        if failures:
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
        args = lay.args(s)
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
    compare_dynamics(data, lay, out, failures, worst)
    compare_gamma_derivatives(data, lay, failures, worst)
    columns = f"{model.nv} velocities" if lay.spatial else f"{model.nq} coordinates"
    out(
        f"{name}: {len(data['samples'])} samples, {model.nc} rows x {columns}, "
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

"""Shows the oracle can fail: wrong values must be rejected, with the mechanism, function, row
and column named.

Usage: python -m mbd_oracle.selftest SAMPLES.json
"""

import copy
import json
import sys

from .compare import compare_model


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


def main(argv):
    if len(argv) != 1:
        print(__doc__)
        return 2
    with open(argv[0]) as f:
        data = json.load(f)
    model = data["model"]
    name, rows, cols = model["name"], model["constraint_rows"], model["coordinates"]
    ok = compare_model(copy.deepcopy(data), out=lambda *_: None) == []
    if not ok:
        print("selftest: the unperturbed samples do not pass; nothing to show")
        return 1

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
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""Unit quaternions in NumPy (Hamilton product), for the spatial fixtures and the spatial
self-check. Rotations here are computed as the sandwich p ⊗ (0, v) ⊗ p*, NOT from the
polynomial A(p) of docs/formulation.md that spatial.py implements: the two are compared in
spatial_check.py, which makes this an independent way to move bodies.

A quaternion is an array (e0, e1, e2, e3) = (cos ½α, sin ½α n) for a rotation by α about n.
"""

import numpy as np


def mul(a, b):
    """The Hamilton product a ⊗ b."""
    a0, av = a[0], np.asarray(a[1:4])
    b0, bv = b[0], np.asarray(b[1:4])
    return np.concatenate([[a0 * b0 - av @ bv], a0 * bv + b0 * av + np.cross(av, bv)])


def conj(a):
    return np.concatenate([[a[0]], -np.asarray(a[1:4])])


def rotate(p, v):
    """p ⊗ (0, v) ⊗ p*: the vector v rotated by p (|p| = 1)."""
    return mul(mul(p, np.concatenate([[0.0], v])), conj(p))[1:4]


def matrix(p):
    """The rotation matrix whose columns are rotate(p, e_k)."""
    return np.column_stack([rotate(p, e) for e in np.eye(3)])


def axis_angle(axis, angle):
    n = np.asarray(axis, dtype=float)
    n = n / np.linalg.norm(n)
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * n])


def exp_body(omega, s):
    """The quaternion of a rotation by s|ω| about ω: p ⊗ exp_body(ω′, s) is the attitude after
    turning for a time s at the constant body-frame angular velocity ω′."""
    w = np.asarray(omega, dtype=float)
    n = np.linalg.norm(w)
    if n == 0.0:
        return np.array([1.0, 0.0, 0.0, 0.0])
    return np.concatenate([[np.cos(s * n / 2)], np.sin(s * n / 2) * w / n])


def from_matrix(r):
    """The unit quaternion (e0 ≥ 0) of a rotation matrix (Shepperd's method)."""
    r = np.asarray(r, dtype=float)
    tr = np.trace(r)
    k = int(np.argmax([tr, r[0, 0], r[1, 1], r[2, 2]]))
    if k == 0:
        e0 = 0.5 * np.sqrt(1 + tr)
        e = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]]) / (4 * e0)
        p = np.concatenate([[e0], e])
    else:
        i = k - 1
        j, l = (i + 1) % 3, (i + 2) % 3
        ei = 0.5 * np.sqrt(1 + 2 * r[i, i] - tr)
        p = np.zeros(4)
        p[1 + i] = ei
        p[0] = (r[l, j] - r[j, l]) / (4 * ei)
        p[1 + j] = (r[j, i] + r[i, j]) / (4 * ei)
        p[1 + l] = (r[l, i] + r[i, l]) / (4 * ei)
    if p[0] < 0:
        p = -p
    return p / np.linalg.norm(p)


def flow(q, v, s):
    """The exact solution at time s of q̇ = B(q) v with v held fixed, for bodies laid out as in
    docs/formulation.md (q: 7 per body, v: 6 per body, ω′ in the body frame): r(s) = r + s ṙ,
    p(s) = p ⊗ exp_body(ω′, s). (ṗ = ½ Lᵀ ω′ = ½ p ⊗ (0, ω′) is linear in p for constant ω′;
    this is its solution, and it stays on |p| = |p(0)|.) Unit p in, unit p out."""
    q = np.asarray(q, dtype=float)
    v = np.asarray(v, dtype=float)
    out = q.copy()
    for k in range(len(q) // 7):
        out[7 * k:7 * k + 3] = q[7 * k:7 * k + 3] + s * v[6 * k:6 * k + 3]
        out[7 * k + 3:7 * k + 7] = mul(q[7 * k + 3:7 * k + 7], exp_body(v[6 * k + 3:6 * k + 6], s))
    return out

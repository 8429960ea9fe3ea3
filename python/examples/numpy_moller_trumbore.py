"""'Your code': the Möller–Trumbore ray–triangle test (1997), vectorized with NumPy, as it is usually written:
an epsilon for "parallel", barycentric coordinates compared with 0 and 1, hits in front of the origin.
The tests beside it (test_numpy_examples.py) show raykernel's Hypothesis strategies finding where it is wrong.
"""

import numpy as np

EPSILON = 1e-9


def moller_trumbore(origins, directions, a, b, c, epsilon=EPSILON):
    """(hit, t) for each row: hit is a bool array, t the distance along the ray where hit (NaN elsewhere).
    |det| ≤ epsilon counts as parallel."""
    e1, e2 = b - a, c - a
    p = np.cross(directions, e2)
    det = np.einsum("ij,ij->i", e1, p)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        inv_det = 1.0 / det
        s = origins - a
        u = np.einsum("ij,ij->i", s, p) * inv_det
        q = np.cross(s, e1)
        v = np.einsum("ij,ij->i", directions, q) * inv_det
        t = np.einsum("ij,ij->i", e2, q) * inv_det
    hit = (np.abs(det) > epsilon) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0)
    return hit, np.where(hit, t, np.nan)

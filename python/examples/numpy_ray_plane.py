"""'Your code': the textbook ray–plane intersection, vectorized with NumPy.

    t = ((p − o)·n) / (d·n)

with an epsilon for "parallel", as it is usually written. The tests beside it (test_numpy_examples.py)
show raykernel's Hypothesis strategies finding where it is wrong.
"""

import numpy as np

from raykernel import Relation

EPSILON = 1e-12


def ray_plane(origins, directions, points, normals):
    """Relation codes (raykernel.Relation.*.code) and t for each row of the (n, 3) arrays."""
    den = np.einsum("ij,ij->i", directions, normals)
    num = np.einsum("ij,ij->i", points - origins, normals)
    parallel = np.abs(den) < EPSILON
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = np.where(parallel, np.nan, num / den)
    relation = np.where(
        parallel,
        np.where(np.abs(num) < EPSILON, Relation.IN_PLANE.code, Relation.PARALLEL.code),
        np.where(t >= 0, Relation.HIT.code, Relation.BEHIND.code),
    )
    return relation, t

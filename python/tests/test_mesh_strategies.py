"""raykernel.testing.hypothesis's mesh strategies keep their promises (closed, consistently oriented meshes with
dyadic vertices; rays exactly aimed at vertices, edges and faces), and raykernel answers them as promised:
certified == exact, a hit at t <= 1 under the closed rule, origins outside."""

from collections import Counter
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings

import raykernel as rk
from raykernel.testing.hypothesis import MESH_SHAPES, closed_meshes, mesh_queries

SETTINGS = settings(max_examples=60, deadline=None)


@SETTINGS
@given(closed_meshes(scales=("moderate", "tiny", "huge")))
def test_closed_meshes_are_closed_and_consistently_oriented(mesh):
    assert mesh.shape in MESH_SHAPES and np.isfinite(mesh.vertices).all()
    directed = Counter()
    for a, b, c in mesh.triangles.tolist():
        for e in ((a, b), (b, c), (c, a)):
            directed[e] += 1
    # Every directed edge once, and its reverse once: each edge shared by two triangles in opposite directions.
    assert all(n == 1 and directed[(b, a)] == 1 for (a, b), n in directed.items())
    # A point far outside is outside, and the mesh's own vertex is on its surface.
    m = rk.Mesh(mesh.vertices, mesh.triangles)
    far = mesh.vertices.max(axis=0) * 4 + np.abs(mesh.vertices).max()
    assert rk.inside(far, m) == rk.PointLocation.OUTSIDE
    assert rk.inside(mesh.vertices[0], m) == rk.PointLocation.ON_SURFACE


@SETTINGS
@given(mesh_queries(closed_meshes(scales=("moderate", "tiny", "huge"))))
def test_aimed_rays_hit_by_t_one_under_the_closed_rule_and_certified_is_exact(q):
    for k in range(len(q.origins)):
        for i in range(3):  # the aim is exact: origin + direction is the target, in rationals
            assert Fraction(q.origins[k, i]) + Fraction(q.directions[k, i]) == Fraction(q.targets[k, i])
    m = rk.Mesh(q.mesh.vertices, q.mesh.triangles)
    closed = rk.nearest_hit_batch(q.origins, q.directions, m, rule="closed")
    assert (closed.triangle >= 0).all() and (closed.t <= 1).all()
    for rule in ("owned", "closed"):
        certified = rk.nearest_hit_batch(q.origins, q.directions, m, rule=rule)
        exact = rk.nearest_hit_batch(q.origins, q.directions, m, rule=rule, path="exact")
        assert np.array_equal(certified.triangle, exact.triangle)
        assert np.array_equal(certified.t, exact.t, equal_nan=True)
    assert all(rk.inside(o, m) == rk.PointLocation.OUTSIDE for o in q.origins)


def test_mesh_strategies_refuse_unknown_kinds():
    with pytest.raises(ValueError, match="closed_meshes: unknown"):
        closed_meshes(["sphere"])
    with pytest.raises(ValueError, match="unknown or no scales"):
        closed_meshes(scales=("gigantic",))
    with pytest.raises(ValueError, match="mesh_queries: unknown"):
        mesh_queries(targets=["corner"])

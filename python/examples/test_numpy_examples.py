"""raykernel's Hypothesis strategies against NumPy ray code. The four tests of 'your code' FAIL, on purpose:
Hypothesis shrinks the counterexample and the assertion prints raykernel's reference report. The control
test runs raykernel itself through the same check and passes.

    /usr/bin/python3 -m pytest python/examples        # 4 failed, 1 passed
"""

import numpy as np
from hypothesis import given

import raykernel
from raykernel.testing import (
    assert_arrays_match_reference,
    assert_triangle_arrays_match_reference,
    assert_triangle_hit_matches_reference,
)
from raykernel.testing.hypothesis import hard_triangle_query_arrays, query_arrays, triangle_query_arrays

from numpy_moller_trumbore import moller_trumbore
from numpy_ray_plane import ray_plane


@given(query_arrays())
def test_numpy_ray_plane_matches_raykernel(q):
    relation, t = ray_plane(q.origins, q.directions, q.points, q.normals)
    assert_arrays_match_reference(q.origins, q.directions, q.points, q.normals, relation, t, max_t_ulps=4)


@given(triangle_query_arrays(["through-edge", "through-vertex", "inside"]))
def test_numpy_moller_trumbore_hits_edges_and_vertices(q):
    hit, t = moller_trumbore(q.origins, q.directions, q.a, q.b, q.c)
    for i, query in enumerate(q.queries):  # the closed rule: the triangle with its edges and vertices
        assert_triangle_hit_matches_reference(query.ray, query.triangle, hit[i], t[i], rule="closed", max_ulps=None)


@given(triangle_query_arrays(["through-edge", "through-vertex"]))
def test_numpy_moller_trumbore_without_epsilon_hits_edges_and_vertices(q):
    # No epsilon at all (only det == 0 is parallel): what is left is rounding, at exact edges and vertices.
    hit, t = moller_trumbore(q.origins, q.directions, q.a, q.b, q.c, epsilon=0.0)
    for i, query in enumerate(q.queries):
        assert_triangle_hit_matches_reference(query.ray, query.triangle, hit[i], t[i], rule="closed", max_ulps=None)


@given(hard_triangle_query_arrays(["tiny", "huge", "sliver", "needle", "wide-exponents"]))
def test_numpy_moller_trumbore_t_and_barycentric_within_4_ulps(q):
    # Where the exact answer is a hit, a hit with t and the barycentric coordinates within 4 ulps (closed rule).
    hit, t, barycentric = moller_trumbore(q.origins, q.directions, q.a, q.b, q.c, epsilon=0.0, with_barycentric=True)
    assert_triangle_arrays_match_reference(q.origins, q.directions, q.a, q.b, q.c, hit=hit, t=t,
                                           barycentric=np.where(hit[:, None], barycentric, np.nan),
                                           rule="closed", max_ulps=4)


@given(query_arrays())
def test_control_raykernel_passes_the_same_check(q):
    answers = raykernel.intersect_batch(q.origins, q.directions, q.points, q.normals)
    assert_arrays_match_reference(q.origins, q.directions, q.points, q.normals, answers.relation, answers.t,
                                  max_t_ulps=0, reference_path="exact")

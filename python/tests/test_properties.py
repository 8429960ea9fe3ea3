"""Hypothesis properties: the strategies keep their promises (checked in exact rationals, not with the code
under test), and the kernel's paths agree on what they generate, scalar and vectorized."""

import math
from fractions import Fraction

import numpy as np
from hypothesis import event, find, given
from hypothesis import strategies as st

import raykernel as rk
from raykernel._raykernel import testkit
from raykernel.testing import exact
from raykernel.testing.hypothesis import (
    QUERY_KINDS,
    TRIANGLE_QUERY_KINDS,
    arbitrary_queries,
    exact_degeneracies,
    hard_queries,
    plane_pairs,
    query_arrays,
    queries,
    rounding_ties,
    triangle_queries,
    triangle_query_arrays,
)


def same(a: float, b: float) -> bool:
    return float.hex(a) == float.hex(b) or (math.isnan(a) and math.isnan(b))


@given(hard_queries())
def test_certified_equals_exact_and_the_fraction_oracle(q):
    event(q.kind)
    certified, reference = rk.intersect(q.ray, q.plane), rk.intersect_exact(q.ray, q.plane)
    oracle = exact.exact_ray_plane(q.ray, q.plane)
    assert certified.relation is reference.relation is oracle.relation
    assert same(certified.t, reference.t) and same(certified.t, oracle.t)


@given(query_arrays())
def test_vectorized_equals_scalar(q):
    got = rk.intersect_batch(q.origins, q.directions, q.points, q.normals)
    for i in range(len(q.kinds)):
        x = rk.intersect(*q.query(i))
        assert got.relation[i] == x.relation.code and same(float(got.t[i]), x.t)


@given(rounding_ties())
def test_rounding_ties_are_ties_and_near_ties_are_near(q):
    answer = exact.exact_ray_plane(q.ray, q.plane)
    t = abs(answer.exact_t)
    below = Fraction(float(np.nextafter(abs(answer.t), 0.0)) if Fraction(abs(answer.t)) > t else abs(answer.t))
    above = Fraction(float(np.nextafter(float(below), math.inf)))
    halfway = (below + above) / 2
    if q.kind == "rounding-tie":
        assert t == halfway
    else:  # within 2^-20 of an ulp of the halfway point, and not on it
        assert t != halfway and abs(t - halfway) <= (above - below) * Fraction(1, 2**20)


@given(exact_degeneracies())
def test_exact_degeneracies_are_exact(q):
    answer = exact.exact_ray_plane(q.ray, q.plane)
    if q.kind in ("exact-parallel", "exact-in-plane"):
        assert answer.den == 0 and (answer.num == 0) == (q.kind == "exact-in-plane")
    else:
        assert answer.num == 0 and answer.den != 0


@given(plane_pairs())
def test_plane_pairs_keep_their_order_and_nearest_hit_finds_it(pp):
    event(pp.kind)
    t0, t1 = (exact.exact_ray_plane(pp.ray, plane).exact_t for plane in pp.planes)
    assert t0 > 0 and t1 > 0
    assert (t1 > t0) - (t1 < t0) == pp.order
    if pp.order != 0:
        assert abs(t1 - t0) < t0 * Fraction(1, 2**53)  # less than an ulp of t apart
    hit = rk.nearest_hit(pp.ray, pp.planes)
    assert hit.plane == pp.nearest and hit == rk.nearest_hit_exact(pp.ray, pp.planes)


@given(st.lists(plane_pairs(), min_size=1, max_size=8))
def test_nearest_hit_batch_on_plane_pairs(pairs):
    # Every ray against all the pairs' planes: the batch answers what nearest_hit answers, ray by ray.
    planes = rk.PlaneSet([plane for pp in pairs for plane in pp.planes])
    origins = np.array([pp.ray.origin for pp in pairs])
    directions = np.array([pp.ray.direction for pp in pairs])
    got = rk.nearest_hit_batch(origins, directions, planes)
    for i, pp in enumerate(pairs):
        want = rk.nearest_hit(pp.ray, planes)
        assert got.plane[i] == want.plane and same(float(got.t[i]), want.t)


@given(st.sampled_from(QUERY_KINDS), st.binary(max_size=300))
def test_fuzz_encoding_round_trips(kind, data):
    words = [int.from_bytes(data[k:k + 8].ljust(8, b"\0"), "little") for k in range(0, len(data), 8)]
    ray, plane, decoded_kind = testkit.decode_fuzz_query(testkit.encode_hard_query_fuzz_input(kind, words))
    assert decoded_kind == kind and (ray, plane) == testkit.make_query(kind, data.ljust(8 * len(words), b"\0"))
    raw = testkit.decode_fuzz_query(testkit.encode_raw_fuzz_input(ray, plane))
    assert raw[:2] == (ray, plane) and raw[2] is None


@given(arbitrary_queries(allow_invalid=True))
def test_invalid_input_is_rejected_exactly_when_validate_says_so(q):
    reason = rk.validate(q.ray, q.plane)
    try:
        x = rk.intersect(q.ray, q.plane)
    except rk.InvalidInput as e:
        assert reason is not None and str(e) == reason
    else:
        assert reason is None
        reference = rk.intersect_exact(q.ray, q.plane)
        assert x.relation is reference.relation and same(x.t, reference.t)


@given(triangle_queries())
def test_triangle_queries_keep_their_promises(q):
    event(q.kind)
    answer = exact.exact_ray_triangle(q.ray, q.triangle)
    if q.kind == "degenerate":
        assert answer.kind == "degenerate"
    else:
        assert answer.kind == "crossing"
    if q.location is not None:
        assert answer.location == q.location
    if q.exact_t is not None:
        assert answer.exact_t == q.exact_t
    if q.kind == "near-edge":  # one ulp from an edge point: the barycentric coordinate of that edge is tiny
        assert min(abs(u) for u in answer.barycentric) < Fraction(1, 2**20)


@given(triangle_query_arrays(TRIANGLE_QUERY_KINDS, max_size=4))
def test_triangle_arrays_hold_the_queries(q):
    for i, query in enumerate(q.queries):
        assert tuple(q.origins[i]) == query.ray.origin and tuple(q.c[i]) == query.triangle.c


def test_every_kind_is_reachable():
    for kind in QUERY_KINDS:
        assert find(queries(kind), lambda q: True).kind == kind
    for kind in TRIANGLE_QUERY_KINDS:
        assert find(triangle_queries([kind]), lambda q: True).kind == kind
    assert {find(hard_queries(), lambda q, k=k: q.kind == k).kind for k in QUERY_KINDS} == set(QUERY_KINDS)

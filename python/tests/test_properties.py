"""Hypothesis properties: the strategies keep their promises (checked in exact rationals, not with the code
under test), and the kernel's paths agree on what they generate, scalar and vectorized."""

import math
from fractions import Fraction

import numpy as np
from hypothesis import event, find, given
from hypothesis import strategies as st

import raykernel as rk
from raykernel._raykernel import testkit
from raykernel.testing import assert_triangle_matches_reference, exact
from raykernel.testing.hypothesis import (
    HARD_TRIANGLE_QUERY_KINDS,
    QUERY_KINDS,
    SPHERE_QUERY_KINDS,
    TRIANGLE_QUERY_KINDS,
    TRIANGLE_SCALES,
    hard_triangle_queries,
    hard_triangle_query_arrays,
    arbitrary_queries,
    exact_degeneracies,
    hard_queries,
    hard_sphere_queries,
    hard_sphere_query_arrays,
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
    if q.kind in ("near-edge", "near-vertex"):  # one ulp from an edge point or a vertex: a coordinate is tiny
        assert min(abs(u) for u in answer.barycentric) < Fraction(1, 2**20)


@given(triangle_queries())
def test_the_kernel_keeps_the_triangle_queries_promises(q):
    # The promises are the construction's (exact by the dyadic argument), the Fraction oracle shares no code with
    # the kernel: the kernel's certified and exact paths must both agree with them, under both rules.
    oracle = exact.exact_ray_triangle(q.ray, q.triangle)
    for rule in ("owned", "closed"):
        x = rk.intersect(q.ray, q.triangle, rule=rule)
        assert same_triangle(x, rk.intersect_exact(q.ray, q.triangle, rule=rule))
        if oracle.kind != "crossing":
            assert x.relation.value == oracle.kind and x.location is rk.TriangleLocation.NONE
            continue
        assert x.location.value == oracle.location
        assert x.relation.value == (oracle.owned if rule == "owned" else oracle.closed)
        assert same(x.t, exact.round_to_double(oracle.exact_t))
        assert all(same(u, exact.round_to_double(e)) for u, e in zip(x.barycentric, oracle.barycentric))
        if q.exact_t is not None:
            assert rk.intersect_exact_rational(q.ray, q.triangle, rule=rule).exact_t == q.exact_t


def same_triangle(x, y) -> bool:
    return (x.relation is y.relation and x.location is y.location and x.owned == y.owned and same(x.t, y.t)
            and all(same(a, b) for a, b in zip(x.barycentric, y.barycentric)))


@given(hard_triangle_queries(), st.sampled_from(["owned", "closed"]))
def test_certified_triangle_equals_exact_on_hard_queries(q, rule):
    event(q.kind)
    x = rk.intersect(q.ray, q.triangle, rule=rule)
    assert same_triangle(x, rk.intersect_exact(q.ray, q.triangle, rule=rule))
    assert tuple(rk.relation(q.ray, q.triangle, rule=rule)) == (x.relation, x.location, x.owned)
    assert_triangle_matches_reference(q.ray, q.triangle, x, rule=rule)  # the C++ toolkit's check, 0 ulps


@given(hard_triangle_query_arrays(max_size=8), st.sampled_from(["owned", "closed"]))
def test_vectorized_triangles_equal_scalar(q, rule):
    for path, scalar in (("certified", rk.intersect), ("exact", rk.intersect_exact)):
        arrays = rk.intersect_triangle_batch(q.origins, q.directions, q.a, q.b, q.c, rule=rule, path=path)
        for i, query in enumerate(q.queries):
            x = scalar(query.ray, query.triangle, rule=rule)
            assert arrays.relation[i] == x.relation.code and arrays.location[i] == x.location.code
            assert arrays.owned[i] == x.owned and same(arrays.t[i], x.t)
            assert all(same(arrays.barycentric[i, k], x.barycentric[k]) for k in range(3))
    classified = rk.relation_triangle_batch(q.origins, q.directions, q.a, q.b, q.c, rule=rule)
    assert (classified.relation == arrays.relation).all() and (classified.location == arrays.location).all()
    assert (classified.owned == arrays.owned).all()


@given(triangle_query_arrays(TRIANGLE_QUERY_KINDS, max_size=4))
def test_triangle_arrays_hold_the_queries(q):
    for i, query in enumerate(q.queries):
        assert tuple(q.origins[i]) == query.ray.origin and tuple(q.c[i]) == query.triangle.c


def test_every_kind_is_reachable():
    for kind in QUERY_KINDS:
        assert find(queries(kind), lambda q: True).kind == kind
    for kind in TRIANGLE_QUERY_KINDS:
        assert find(triangle_queries([kind]), lambda q: True).kind == kind
    for scale in TRIANGLE_SCALES:  # the extreme scales reach them: subnormal or huge coordinates
        q = find(triangle_queries(["through-edge"], scales=[scale]), lambda q: True)
        biggest = max(abs(x) for v in (q.ray.origin, *q.triangle) for x in v)
        assert {"moderate": 2.0**-70 < biggest < 2.0**90, "subnormal": 0 < biggest < 2.0**-980,
                "huge": biggest >= 2.0**900}[scale], (scale, q)
    for kind in HARD_TRIANGLE_QUERY_KINDS:
        assert find(hard_triangle_queries([kind]), lambda q: True).kind == kind
    for kind in SPHERE_QUERY_KINDS:
        assert find(hard_sphere_queries([kind]), lambda q: True).kind == kind
    assert {find(hard_queries(), lambda q, k=k: q.kind == k).kind for k in QUERY_KINDS} == set(QUERY_KINDS)


def same_sphere(x, y) -> bool:
    return x.origin is y.origin and x.relation is y.relation and same(x.t1, y.t1) and same(x.t2, y.t2)


@given(hard_sphere_queries())
def test_certified_sphere_equals_exact_and_the_fraction_oracle(q):
    event(q.kind)
    x = rk.intersect(q.ray, q.sphere)
    assert same_sphere(x, rk.intersect_exact(q.ray, q.sphere))
    assert tuple(rk.relation(q.ray, q.sphere)) == (x.origin, x.relation)
    oracle = exact.exact_ray_sphere(q.ray, q.sphere)  # no code shared with the kernel
    assert same_sphere(x, oracle)
    rational = rk.intersect_exact_rational(q.ray, q.sphere)
    assert (rational.u, rational.v) == (oracle.u, oracle.v)


def _exact_sqrt(v: Fraction):
    """√v when it is rational, else None."""
    p, q = math.isqrt(v.numerator), math.isqrt(v.denominator)
    return Fraction(p, q) if p * p == v.numerator and q * q == v.denominator else None


@given(hard_sphere_queries(["tangent", "on-surface", "rounding-tie"]))
def test_sphere_queries_keep_their_promises(q):
    # Checked in the Fraction oracle: tangent D = 0, an origin on the surface C = 0, and a root exactly halfway
    # between two doubles.
    event(q.kind)
    answer = exact.exact_ray_sphere(q.ray, q.sphere)
    if q.kind == "tangent":
        assert answer.d == 0 and answer.relation is rk.SphereRelation.TANGENT
    elif q.kind == "on-surface":
        assert answer.c == 0 and answer.origin is rk.SphereOrigin.ON_SURFACE
    else:
        s = _exact_sqrt(answer.v)
        assert s is not None and s > 0  # rational roots U ∓ √V

        def is_tie(root: Fraction) -> bool:
            nearest = float(root)  # correctly rounded
            return any(root == (Fraction(nearest) + Fraction(math.nextafter(nearest, side))) / 2
                       for side in (math.inf, -math.inf))

        assert is_tie(answer.u - s) or is_tie(answer.u + s)


@given(hard_sphere_query_arrays(max_size=8))
def test_vectorized_spheres_equal_scalar(q):
    for path, scalar in (("certified", rk.intersect), ("exact", rk.intersect_exact), ("naive", rk.intersect_naive)):
        arrays = rk.intersect_sphere_batch(q.origins, q.directions, q.centers, q.radii, path=path)
        assert arrays.valid.all()
        for i, query in enumerate(q.queries):
            x = scalar(query.ray, query.sphere)
            assert arrays.origin[i] == x.origin.code and arrays.relation[i] == x.relation.code
            assert same(arrays.t1[i], x.t1) and same(arrays.t2[i], x.t2)
            assert tuple(q.centers[i]) == query.sphere.center and q.radii[i] == query.sphere.radius


OCTAHEDRON = testkit.make_octahedron()  # |x| + |y| + |z| ≤ 1: vertices ±1 on the axes


@st.composite
def points_near_the_octahedron(draw):
    """A point of the octahedron's surface (dyadic x, y ≥ 0 with x + y ≤ 1, z = 1 − x − y, exact), its signs
    flipped to any of the 8 faces, and z then moved by up to 3 ulps: on a face, an edge or a vertex, or just
    inside or outside it, where a double evaluation of |x| + |y| + |z| rounds to 1."""
    bits = draw(st.integers(0, 30))
    scale = 2 ** bits
    x = draw(st.integers(0, scale)) / scale
    y = draw(st.integers(0, scale - int(x * scale))) / scale
    z = 1.0 - x - y  # exact: dyadics of at most 31 bits
    steps = draw(st.integers(-3, 3))
    for _ in range(abs(steps)):
        z = math.nextafter(z, math.inf if steps > 0 else -math.inf)
    signs = draw(st.tuples(*[st.sampled_from([1.0, -1.0])] * 3))
    return (signs[0] * x, signs[1] * y, signs[2] * z)


@given(points_near_the_octahedron())
def test_inside_equals_the_fraction_oracle_near_the_octahedron(p):
    total = sum(abs(Fraction(c)) for c in p)  # exact: the octahedron is |x| + |y| + |z| ≤ 1
    expected = rk.PointLocation.ON_SURFACE if total == 1 else rk.PointLocation.INSIDE if total < 1 else rk.PointLocation.OUTSIDE
    event(expected.value)
    assert rk.inside(p, OCTAHEDRON) is expected
    assert rk.inside_exact(p, OCTAHEDRON) is expected
    assert rk.inside_batch(np.array([p]), OCTAHEDRON).location[0] == expected.code

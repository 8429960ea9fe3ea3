"""Ray–sphere from Python (docs/contract.md §10): hand-derived answers (derivations in the comments), U and V
against the Fraction oracle, every root checked as correctly rounded at its midpoints, the batch against the
scalar calls, errors naming the field and the row, layouts, and the GIL released."""

import math
import struct
import sys
from decimal import Decimal, localcontext
from fractions import Fraction

import numpy as np
import pytest

import raykernel as rk
from raykernel._raykernel import testkit
from raykernel.testing import exact

from test_arrays import longest_pause_of_this_thread_while, same_bits

O, R = rk.SphereOrigin, rk.SphereRelation
X_AXIS = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0))
M = sys.float_info.max  # 2^1024 − 2^971
OVERFLOW = Fraction(2) ** 1024 - Fraction(2) ** 970  # halfway between M and 2^1024: from here on, ±inf


def same(a: float, b: float) -> bool:
    """The same double, the sign of a zero included (or both NaN)."""
    return float.hex(a) == float.hex(b) or (math.isnan(a) and math.isnan(b))


def answer(ray, sphere: rk.Sphere, origin, relation, t1: float, t2: float) -> rk.SphereIntersection:
    """Checks the certified and the exact paths, and relation(), against the hand-derived answer."""
    for f in (rk.intersect, rk.intersect_exact):
        x = f(ray, sphere)
        assert (x.origin, x.relation) == (origin, relation), f
        assert same(x.t1, t1) and same(x.t2, t2), (f, x)
    assert rk.relation(ray, sphere) == rk.SphereClassification(origin, relation)
    return x


def exact_roots(ray, sphere):
    x = rk.intersect_exact_rational(ray, sphere)
    return x.u, x.v


# Hand-derived cases. Throughout: f = o − c, A = d·d, B = d·f, C = f·f − r², D = B² − A·C, roots (−B ∓ √D)/A,
# U = −B/A, V = D/A².


def test_crossing_along_an_axis():
    # o = 0, d = (1, 0, 0), c = (5, 0, 0), r = 1: f = (−5, 0, 0), A = 1, B = −5, C = 25 − 1 = 24 > 0 (outside),
    # D = 25 − 24 = 1 > 0: roots 5 ∓ 1 = 4, 6. U = 5, V = 1.
    unit_at_5 = rk.Sphere((5.0, 0.0, 0.0), 1.0)
    answer(X_AXIS, unit_at_5, O.OUTSIDE, R.CROSS, 4.0, 6.0)
    assert exact_roots(X_AXIS, unit_at_5) == (5, 1)
    # d = (2, 0, 0): A = 4, B = −10, C = 24, D = 100 − 96 = 4: roots (10 ∓ 2)/4 = 2, 3. U = 10/4, V = 4/16.
    answer(((0, 0, 0), (2, 0, 0)), unit_at_5, O.OUTSIDE, R.CROSS, 2.0, 3.0)
    assert exact_roots(((0, 0, 0), (2, 0, 0)), unit_at_5) == (Fraction(5, 2), Fraction(1, 4))
    # The origin at the centre, r = 2: f = 0, B = 0, C = −4 < 0 (inside), D = 4: roots ∓2, U = 0, V = 4.
    answer(X_AXIS, rk.Sphere((0, 0, 0), 2), O.INSIDE, R.CROSS, -2.0, 2.0)
    assert exact_roots(X_AXIS, rk.Sphere((0, 0, 0), 2)) == (0, 4)


def test_tangent_exactly_and_an_ulp_off():
    # o = (0, 1, 0), d = (1, 0, 0), c = (5, 0, 0), r = 1: f = (−5, 1, 0), B = −5, C = 25 + 1 − 1 = 25,
    # D = 25 − 25 = 0: tangent at t0 = −B/A = 5 (t1 = t2 = 5). U = 5, V = 0.
    s = rk.Sphere((5.0, 0.0, 0.0), 1.0)
    answer(((0, 1, 0), (1, 0, 0)), s, O.OUTSIDE, R.TANGENT, 5.0, 5.0)
    assert exact_roots(((0, 1, 0), (1, 0, 0)), s) == (5, 0)
    # o_y = 1 + 2^-52: C = 25 + (1 + 2^-52)² − 1 > 25 = B², so D < 0: a miss, NaN roots, no U and V.
    off = ((0, 1 + 2.0**-52, 0), (1, 0, 0))
    answer(off, s, O.OUTSIDE, R.MISS, math.nan, math.nan)
    assert exact_roots(off, s) == (None, None)
    # o_y = 1 − 2^-53: D = 1 − (1 − 2^-53)² = 2^-52 − 2^-106, √D = 2^-26·√(1 − 2^-54) = 2^-26 − ε with
    # 0 < ε < 2^-80, far below half an ulp of 5 (2^-51): the roots round to 5 ∓ 2^-26, both doubles.
    answer(((0, 1 - 2.0**-53, 0), (1, 0, 0)), s, O.OUTSIDE, R.CROSS, 5 - 2.0**-26, 5 + 2.0**-26)


def test_origin_on_the_surface_gives_a_zero_root_with_its_sign():
    # o = (1, 0, 0), d = (1, 0, 0), c = 0, r = 1: f = (1, 0, 0), C = 1 − 1 = 0 (on the surface), B = 1, A = 1,
    # D = 1 − 0 = 1: roots −1 ∓ 1 = −2 and an exact 0, which is +0.
    unit = rk.Sphere((0, 0, 0), 1)
    x = answer(((1, 0, 0), (1, 0, 0)), unit, O.ON_SURFACE, R.CROSS, -2.0, 0.0)
    assert x.t2 == 0 and math.copysign(1.0, x.t2) == 1.0  # +0, not −0
    assert exact_roots(((1, 0, 0), (1, 0, 0)), unit) == (-1, 1)
    # d = (−1, 0, 0): B = −1, roots 1 ∓ 1 = +0 and 2.
    x = answer(((1, 0, 0), (-1, 0, 0)), unit, O.ON_SURFACE, R.CROSS, 0.0, 2.0)
    assert math.copysign(1.0, x.t1) == 1.0
    # d = (0, 1, 0): B = 0, C = 0, D = 0: tangent at +0.
    answer(((1, 0, 0), (0, 1, 0)), unit, O.ON_SURFACE, R.TANGENT, 0.0, 0.0)


def test_a_negative_root_that_rounds_to_zero_keeps_its_sign():
    # o = (2^-1074, 0, 0) = (ε, 0, 0), d = (4, 0, 0), c = (1, 0, 0), r = 1: f = (ε − 1, 0, 0), A = 16,
    # B = 4(ε − 1), C = (1 − ε)² − 1 = ε² − 2ε < 0 (inside), D = 16(1 − ε)² − 16(ε² − 2ε) = 16: roots
    # (4(1 − ε) ∓ 4)/16 = −ε/4 = −2^-1076 and 1/2 − 2^-1076. The first is below half the smallest subnormal
    # (2^-1075): it rounds to zero and keeps its sign, −0. The second is within a quarter ulp of 1/2: 0.5.
    x = answer(((2.0**-1074, 0, 0), (4, 0, 0)), rk.Sphere((1, 0, 0), 1), O.INSIDE, R.CROSS, -0.0, 0.5)
    assert x.t1 == 0 and math.copysign(1.0, x.t1) == -1.0


def test_roots_on_rounding_ties_go_to_the_even_neighbour():
    # c = (2^53, 0, 0), r = 3 along the x axis: B = −2^53, C = 2^106 − 9, D = 2^106 − (2^106 − 9) = 9: roots
    # 2^53 ∓ 3. 2^53 − 3 is a double (below 2^53 the doubles are the integers); 2^53 + 3 is odd, beyond 2^53 where
    # the doubles are the even integers: halfway between 2^53 + 2 (significand 1 + 2^-52, odd) and 2^53 + 4
    # (1 + 2^-51, even): the tie goes to 2^53 + 4.
    s = rk.Sphere((2.0**53, 0, 0), 3)
    answer(X_AXIS, s, O.OUTSIDE, R.CROSS, 2.0**53 - 3, 2.0**53 + 4)
    assert exact_roots(X_AXIS, s) == (2**53, 9)
    # r = 1: 2^53 + 1, halfway between 2^53 (even) and 2^53 + 2 (odd): 2^53.
    answer(X_AXIS, rk.Sphere((2.0**53, 0, 0), 1), O.OUTSIDE, R.CROSS, 2.0**53 - 1, 2.0**53)
    # The textbook formula rounds C = 2^106 − 9 to 2^106, so its discriminant h² − a·c is 0: tangent at 2^53.
    naive = rk.intersect_naive(X_AXIS, s)
    assert (naive.relation, naive.t1, naive.t2) == (R.TANGENT, 2.0**53, 2.0**53)


def test_irrational_roots_round_to_nearest():
    # o = 0, d = (1, 0, 0), c = (0, 1, 0), r = 2: f = (0, −1, 0), B = 0, C = 1 − 4 = −3 (inside), D = 3:
    # roots ∓√3, U = 0, V = 3. IEEE 754 square root is correctly rounded: RN(√3) = math.sqrt(3).
    s = rk.Sphere((0, 1, 0), 2)
    answer(X_AXIS, s, O.INSIDE, R.CROSS, -math.sqrt(3), math.sqrt(3))
    assert exact_roots(X_AXIS, s) == (0, 3)
    # o = (0, 1, 0), c = (5, 0, 0), r = 2: f = (−5, 1, 0), B = −5, C = 26 − 4 = 22, D = 25 − 22 = 3: roots 5 ∓ √3,
    # rounded here from 60-digit decimals (within 10^-58 of the roots; float() of a decimal string is
    # correctly rounded, and neither root is that close to a midpoint of doubles).
    with localcontext() as ctx:
        ctx.prec = 60
        low, high = (float(str(Decimal(5) + k * Decimal(3).sqrt())) for k in (-1, 1))
    assert (low, high) == (3.267949192431123, 6.732050807568878)
    answer(((0, 1, 0), (1, 0, 0)), rk.Sphere((5, 0, 0), 2), O.OUTSIDE, R.CROSS, low, high)


def test_roots_beyond_the_double_range_and_below_it():
    # c = (M, 0, 0), M = 2^1024 − 2^971 the largest double, r = 2^970, along x: roots M ∓ 2^970. M − 2^970 is
    # halfway between M − 2^971 (even significand) and M (odd): M − 2^971. M + 2^970 = 2^1024 − 2^970 is
    # halfway between M and 2^1024 (even, beyond the range): ties to even overflow to +inf.
    answer(X_AXIS, rk.Sphere((M, 0, 0), 2.0**970), O.OUTSIDE, R.CROSS, M - 2.0**971, math.inf)
    # c = (2^-1073, 0, 0), r = 2^-1074, d = (2, 0, 0): A = 4, B = −2^-1072, C = 2^-2146 − 2^-2148 = 3·2^-2148,
    # D = 2^-2144 − 12·2^-2148 = 2^-2146: roots (2^-1072 ∓ 2^-1073)/4 = 2^-1075 and 3·2^-1075. The first is
    # halfway between +0 and 2^-1074: +0 (even); the second between 2^-1074 and 2^-1073: 2^-1073 (even).
    answer(((0, 0, 0), (2, 0, 0)), rk.Sphere((2.0**-1073, 0, 0), 2.0**-1074), O.OUTSIDE, R.CROSS, 0.0, 2.0**-1073)


def test_a_miss():
    # o = (0, 2, 0), d = (1, 0, 0), c = (5, 0, 0), r = 1: f = (−5, 2, 0), B = −5, C = 25 + 4 − 1 = 28,
    # D = 25 − 28 = −3 < 0: a miss, NaN roots.
    ray, s = ((0, 2, 0), (1, 0, 0)), rk.Sphere((5, 0, 0), 1)
    answer(ray, s, O.OUTSIDE, R.MISS, math.nan, math.nan)
    assert rk.intersect_exact_rational(ray, s) == rk.ExactSphereIntersection(O.OUTSIDE, R.MISS, None, None)


def test_traced_naive_and_the_result_types():
    ray, s = X_AXIS, rk.Sphere(rk.Vec3(5, 0, 0), 1)
    x = rk.intersect(ray, s)
    assert isinstance(x, rk.SphereIntersection) and x == (O.OUTSIDE, R.CROSS, 4.0, 6.0)
    origin, relation, t1, t2 = x  # unpacks like a tuple
    assert origin == "outside" and relation == "cross" and str(relation) == "cross"
    traced = rk.intersect_traced(ray, s)
    assert isinstance(traced, rk.TracedSphereIntersection) and traced[:4] == x
    assert isinstance(traced.relation_stage, rk.Stage) and isinstance(traced.rounding_stage, rk.Stage)
    assert rk.intersect_naive(ray, s) == x  # the textbook formula is exact here: small integers
    exact_x = rk.intersect_exact_rational(ray, s)
    assert isinstance(exact_x.u, Fraction) and isinstance(exact_x.v, Fraction)
    # Any sequences inside a Sphere: a NumPy centre, a NumPy radius.
    assert rk.intersect(ray, rk.Sphere(np.array([5.0, 0, 0]), np.float32(1))) == x


def test_enums_are_str_valued_with_the_cpp_codes():
    assert [o.value for o in rk.SphereOrigin] == ["inside", "on-surface", "outside"]
    assert [r.value for r in rk.SphereRelation] == ["miss", "tangent", "cross"]
    for enum in (rk.SphereOrigin, rk.SphereRelation):
        assert [m.code for m in enum] == [0, 1, 2]
        assert all(enum.from_code(m.code) is m for m in enum)
    assert rk.SphereOrigin("on-surface") is rk.SphereOrigin.ON_SURFACE
    assert str(rk.SphereOrigin.ON_SURFACE) == "on-surface" and rk.SphereRelation.CROSS == "cross"


def test_only_a_sphere_is_a_sphere_and_triangle_options_are_refused():
    # A bare (center, radius) pair is a plane (point, normal): its radius is not a 3-vector.
    with pytest.raises(TypeError, match="^plane normal: expected a sequence of 3 numbers, got int$"):
        rk.intersect(X_AXIS, ((5, 0, 0), 1))
    with pytest.raises(ValueError, match="^rule: only triangles have rules, the second argument is a sphere$"):
        rk.intersect(X_AXIS, rk.Sphere((5, 0, 0), 1), rule="closed")
    with pytest.raises(ValueError, match=r"^t, barycentric: only for triangles \(a sphere's roots are always computed\)$"):
        rk.intersect_exact(X_AXIS, rk.Sphere((5, 0, 0), 1), t=False)
    with pytest.raises(ValueError, match="^rule: only triangles have rules, the second argument is a sphere$"):
        rk.relation(X_AXIS, rk.Sphere((5, 0, 0), 1), rule="owned")
    with pytest.raises(TypeError, match="^sphere radius: expected a number, got str$"):
        rk.intersect(X_AXIS, rk.Sphere((5, 0, 0), "1"))
    with pytest.raises(ValueError, match="^sphere center: expected a sequence of 3 numbers, got a sequence of 2 items$"):
        rk.intersect(X_AXIS, rk.Sphere((5, 0), 1))


@pytest.mark.parametrize(
    "ray, sphere, message",
    [
        (((math.nan, 0, 0), (1, 0, 0)), rk.Sphere((0, 0, 0), 1), "ray origin x is NaN"),
        (((0, 0, 0), (0, 0, 0)), rk.Sphere((0, 0, 0), 1), "ray direction is the zero vector"),
        (X_AXIS, rk.Sphere((0, math.inf, 0), 1), "sphere center y is \\+inf"),
        (X_AXIS, rk.Sphere((0, 0, 0), math.nan), "sphere radius is NaN"),
        (X_AXIS, rk.Sphere((0, 0, 0), -math.inf), "sphere radius is -inf"),
        (X_AXIS, rk.Sphere((0, 0, 0), 0.0), "sphere radius is not positive"),
        (X_AXIS, rk.Sphere((0, 0, 0), -0.0), "sphere radius is not positive"),
        (X_AXIS, rk.Sphere((0, 0, 0), -1), "sphere radius is not positive"),
    ],
)
def test_invalid_input_raises_naming_the_field(ray, sphere, message):
    for f in (rk.intersect, rk.relation, rk.intersect_exact, rk.intersect_exact_rational, rk.intersect_traced):
        with pytest.raises(rk.InvalidInput, match=f"^{message}$"):
            f(ray, sphere)
    assert rk.validate(ray, sphere).replace("+", "\\+") == message
    rk.intersect_naive(ray, sphere)  # the baseline never raises
    assert rk.validate(X_AXIS, rk.Sphere((0, 0, 0), 5e-324)) is None  # a subnormal radius is valid


# Hard queries (testkit/sphere_queries.hpp): seeded arrays of every kind.


@pytest.fixture(scope="module")
def hard_spheres():
    """2,400 hard ray–sphere queries, 200 of each testkit kind (seeded)."""
    kinds = list(testkit.SPHERE_QUERY_KINDS)
    o, d, c, r, kind = testkit.make_sphere_query_arrays(kinds, 200 * len(kinds), 7)
    assert set(np.unique(kind)) == set(range(len(kinds)))
    assert o.shape == d.shape == c.shape == (len(r), 3) and r.dtype == np.float64 and (r > 0).all()
    return o, d, c, r


def query(arrays, i):
    o, d, c, r = arrays
    return (tuple(o[i]), tuple(d[i])), rk.Sphere(tuple(c[i]), float(r[i]))


def side(u: Fraction, v: Fraction, upper: bool, m: Fraction) -> int:
    """The sign of root − m, exactly (raykernel.testing.exact.root_side: w = U − m against √V by w² against V)."""
    return exact.root_side(u, v, upper, Fraction(m))


def assert_correctly_rounded(x: float, u: Fraction, v: Fraction, upper: bool) -> None:
    """x is U ∓ √V rounded to nearest, ties to even, checked at the midpoints between x and its neighbours (an
    independent check of the kernel's rounding, and of raykernel.testing.exact's search)."""
    if math.isinf(x):  # the root at or beyond the overflow threshold on x's side
        assert side(u, v, upper, OVERFLOW) >= 0 if x > 0 else side(u, v, upper, -OVERFLOW) <= 0
        return
    if x == 0:  # |root| ≤ 2^-1075 (the midpoint of 0 and the smallest subnormal goes to the even 0); its sign kept
        half = Fraction(1, 2**1075)
        assert side(u, v, upper, half) <= 0 and side(u, v, upper, -half) >= 0
        at_zero = side(u, v, upper, 0)
        assert math.copysign(1.0, x) == (-1.0 if at_zero < 0 else 1.0)
        return
    even = struct.unpack("<Q", struct.pack("<d", x))[0] % 2 == 0

    def midpoint(neighbour: float) -> Fraction:
        if math.isinf(neighbour):
            return OVERFLOW if neighbour > 0 else -OVERFLOW
        return (Fraction(x) + Fraction(neighbour)) / 2

    below = side(u, v, upper, midpoint(math.nextafter(x, -math.inf)))
    above = side(u, v, upper, midpoint(math.nextafter(x, math.inf)))
    assert below > 0 or (below == 0 and even), (x, u, v, upper)
    assert above < 0 or (above == 0 and even), (x, u, v, upper)


def test_exact_roots_and_their_roundings_match_the_fraction_oracle(hard_spheres):
    # Every 4th query (12 kinds, 600 queries): U and V as the Fractions of the definitions, each root rounded as
    # its midpoints say, and the oracle's own rounding (a search over the doubles) the same.
    for i in range(0, len(hard_spheres[3]), 4):
        ray, s = query(hard_spheres, i)
        x, e = rk.intersect_exact_rational(ray, s), exact.exact_ray_sphere(ray, s)
        assert (x.origin, x.relation, x.u, x.v) == (e.origin, e.relation, e.u, e.v), (ray, s)
        got = rk.intersect(ray, s)
        assert same(got.t1, e.t1) and same(got.t2, e.t2), (ray, s, got, e)
        if x.relation is not R.MISS:
            assert_correctly_rounded(got.t1, x.u, x.v, False)
            assert_correctly_rounded(got.t2, x.u, x.v, True)


def test_the_midpoint_check_catches_a_wrong_rounding():
    u, v = Fraction(5), Fraction(3)  # 5 ∓ √3
    assert_correctly_rounded(3.267949192431123, u, v, False)
    for wrong in (math.nextafter(3.267949192431123, 0), math.nextafter(3.267949192431123, 4)):
        with pytest.raises(AssertionError):
            assert_correctly_rounded(wrong, u, v, False)
    with pytest.raises(AssertionError):  # the tie 2^53 + 3 goes to 2^53 + 4, not 2^53 + 2
        assert_correctly_rounded(2.0**53 + 2, Fraction(2**53), Fraction(9), True)
    with pytest.raises(AssertionError):  # −2^-1076 rounds to −0, not +0
        assert_correctly_rounded(0.0, Fraction(-1, 2**1076), Fraction(0), False)


def test_certified_equals_exact_and_the_batch_equals_the_scalar_calls(hard_spheres):
    o, d, c, r = hard_spheres
    got = rk.intersect_sphere_batch(o, d, c, r)
    exact_arrays = rk.intersect_sphere_batch(o, d, c, r, path="exact")
    for field in ("origin", "relation", "valid"):
        assert (getattr(got, field) == getattr(exact_arrays, field)).all(), field
    assert same_bits(got.t1, exact_arrays.t1) and same_bits(got.t2, exact_arrays.t2)
    assert got.valid.all()
    for i in range(len(r)):  # row by row against the scalar function
        x = rk.intersect(*query(hard_spheres, i))
        assert (got.origin[i], got.relation[i]) == (x.origin.code, x.relation.code), i
        assert same(float(got.t1[i]), x.t1) and same(float(got.t2[i]), x.t2), i
    naive = rk.intersect_sphere_batch(o, d, c, r, path="naive")
    assert naive.valid.all()
    caught = ((naive.relation != got.relation) | ~same_elementwise(naive.t1, got.t1)
              | ~same_elementwise(naive.t2, got.t2))
    assert caught.any()  # the hard queries do catch the textbook formula somewhere
    for i in np.flatnonzero(~caught)[:50]:
        assert naive.relation[i] == rk.intersect_naive(*query(hard_spheres, i)).relation.code
    assert list(got.relations()[:3]) == [R.from_code(k).value for k in got.relation[:3]]
    assert list(got.origins()[:3]) == [O.from_code(k).value for k in got.origin[:3]]


def same_elementwise(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (a.view(np.uint64) == b.view(np.uint64)) | (np.isnan(a) & np.isnan(b))


def test_layouts_and_one_sphere(hard_spheres):
    o, d, c, r = hard_spheres
    base = rk.intersect_sphere_batch(o, d, c, r)
    soa = [np.ascontiguousarray(x.T).T for x in (o, d, c)] + [r]  # column-contiguous
    strided = [np.repeat(x, 2, axis=0)[::2] for x in (o, d, c, r)]
    for arrays in (soa, strided, [x.tolist() for x in (o, d, c, r)]):
        other = rk.intersect_sphere_batch(*arrays)
        assert (other.relation == base.relation).all() and (other.origin == base.origin).all()
        assert same_bits(other.t1, base.t1) and same_bits(other.t2, base.t2)
    sphere = rk.Sphere((0.25, -0.5, 0.125), 0.75)
    for center, radius in ((np.array(sphere.center), sphere.radius), (list(sphere.center), np.float64(0.75)),
                           (sphere.center, np.array(0.75))):
        one = rk.intersect_sphere_batch(o, d, center, radius)
        for i in range(0, len(r), 97):
            x = rk.intersect((tuple(o[i]), tuple(d[i])), sphere)
            assert (one.origin[i], one.relation[i]) == (x.origin.code, x.relation.code)
            assert same(float(one.t1[i]), x.t1) and same(float(one.t2[i]), x.t2)
    integers = rk.intersect_sphere_batch(np.zeros((1, 3), np.int32), [[1, 0, 0]], [[5, 0, 0]], np.array([1], np.int8))
    assert (integers.t1[0], integers.t2[0]) == (4.0, 6.0)


def test_invalid_rows_raise_naming_the_row_or_are_masked(hard_spheres):
    o, d, c, r = (x[:50].copy() for x in hard_spheres)
    d[7] = 0
    r[12] = 0.0
    r[20] = -1.0
    c[30, 1] = np.nan
    with pytest.raises(rk.InvalidInput, match="^query 7: ray direction is the zero vector$"):
        rk.intersect_sphere_batch(o, d, c, r)
    fixed_d = d.copy()
    fixed_d[7] = (1, 0, 0)
    with pytest.raises(rk.InvalidInput, match="^query 12: sphere radius is not positive$"):
        rk.intersect_sphere_batch(o, fixed_d, c, r, path="exact")
    with pytest.raises(rk.InvalidInput, match="^query 30: sphere center y is NaN$"):
        rk.intersect_sphere_batch(o, fixed_d, c, np.abs(r) + 1)
    with pytest.raises(rk.InvalidInput, match="^ray 7: ray direction is the zero vector$"):
        rk.intersect_sphere_batch(o, d, (0, 0, 0), 1.0)
    with pytest.raises(rk.InvalidInput, match="^ray 0: sphere radius is not positive$"):
        rk.intersect_sphere_batch(o, d, (0, 0, 0), -1)
    for path in ("certified", "exact", "naive"):
        masked = rk.intersect_sphere_batch(o, d, c, r, errors="mask", path=path)
        assert list(np.flatnonzero(~masked.valid)) == [7, 12, 20, 30], path
        keep = masked.valid
        clean = rk.intersect_sphere_batch(o[keep], d[keep], c[keep], r[keep], path=path)
        assert (clean.relation == masked.relation[keep]).all() and same_bits(clean.t1, masked.t1[keep])
        if path != "naive":  # the naive path answers invalid rows too
            assert (masked.relation[~keep] == rk.INVALID_RELATION_CODE).all()
            assert (masked.origin[~keep] == rk.INVALID_RELATION_CODE).all()
            assert np.isnan(masked.t1[~keep]).all() and np.isnan(masked.t2[~keep]).all()
            assert list(masked.relations()[~keep]) == ["invalid"] * 4
            assert list(masked.origins()[~keep]) == ["invalid"] * 4


def test_malformed_arrays_name_the_argument(hard_spheres):
    o, d, c, r = (x[:50] for x in hard_spheres)
    with pytest.raises(ValueError, match="^radii has 3 rows, origins has 50$"):
        rk.intersect_sphere_batch(o, d, c, r[:3])
    with pytest.raises(ValueError, match="^centers has 3 rows, origins has 50$"):
        rk.intersect_sphere_batch(o, d, c[:3], r)
    with pytest.raises(ValueError, match="^centers, radii: give both as arrays of n rows"):
        rk.intersect_sphere_batch(o, d, (0, 0, 0), r)
    with pytest.raises(ValueError, match="^centers, radii: give both as arrays of n rows"):
        rk.intersect_sphere_batch(o, d, c, 1.0)
    with pytest.raises(ValueError, match=r"^radii: expected an array of shape \(n,\) or a number, got shape \(50, 1\)$"):
        rk.intersect_sphere_batch(o, d, c, r[:, None])
    with pytest.raises(TypeError, match="^radii: expected an array of shape .* got an array of dtype bool$"):
        rk.intersect_sphere_batch(o, d, c, r > 0)
    with pytest.raises(TypeError, match="^radii: expected .*, got a numpy.ma.MaskedArray"):
        rk.intersect_sphere_batch(o, d, c, np.ma.masked_array(r))
    with pytest.raises(ValueError, match="^path: expected 'certified', 'exact' or 'naive', got 'fast'$"):
        rk.intersect_sphere_batch(o, d, c, r, path="fast")
    with pytest.raises(ValueError, match="^errors: expected 'raise' or 'mask', got 'ignore'$"):
        rk.intersect_sphere_batch(o, d, c, r, errors="ignore")
    empty = rk.intersect_sphere_batch(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0))
    assert empty.t1.shape == (0,) and empty.valid.shape == (0,)


def test_testkit_sphere_queries_are_deterministic_and_named():
    for kind in testkit.SPHERE_QUERY_KINDS:
        words = bytes(range(256))
        ray, sphere = testkit.make_sphere_query(kind, words)
        assert isinstance(sphere, rk.Sphere) and isinstance(ray, rk.Ray)
        assert (ray, sphere) == testkit.make_sphere_query(kind, words)
        assert rk.validate(ray, sphere) is None
    with pytest.raises(ValueError, match="^unknown sphere query kind 'flat' \\(kinds: random, tangent, "):
        testkit.make_sphere_query("flat", b"")
    with pytest.raises(ValueError, match="^kinds: give at least one query kind$"):
        testkit.make_sphere_query_arrays([], 3, 1)


def test_threads_give_the_same_answers(hard_spheres):
    o, d, c, r = (np.tile(x, (2, 1)) if x.ndim == 2 else np.tile(x, 2) for x in hard_spheres)
    one = rk.intersect_sphere_batch(o, d, c, r, threads=1, path="exact")
    many = rk.intersect_sphere_batch(o, d, c, r, threads=4, path="exact")
    assert (one.relation == many.relation).all() and same_bits(one.t1, many.t1) and same_bits(one.t2, many.t2)


def test_the_gil_is_released_during_a_sphere_batch(hard_spheres):
    o, d, c, r = (np.tile(x, (8, 1)) if x.ndim == 2 else np.tile(x, 8) for x in hard_spheres)  # 19,200 exact queries
    longest, total = longest_pause_of_this_thread_while(
        lambda: rk.intersect_sphere_batch(o, d, c, r, path="exact", threads=1))
    assert total > 0.05, "the batch was too short to tell"
    assert longest < total / 4, f"this thread stopped for {longest:.3f} s of a {total:.3f} s batch"

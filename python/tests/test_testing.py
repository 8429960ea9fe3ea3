"""raykernel.testing: ulps, the reference checks and their reports, and the §6 triangle oracle by hand."""

import math
import sys
from fractions import Fraction

import numpy as np
import pytest

import raykernel as rk
from raykernel.testing import (
    assert_arrays_match_reference,
    assert_matches_reference,
    assert_triangle_hit_matches_reference,
    check_against_reference,
    check_triangle_hit_against_reference,
    ulp_difference,
    ulp_distance,
    ulp_distances,
)
from raykernel.testing.exact import exact_ray_triangle

TINY = 5e-324
BIG = sys.float_info.max


def test_ulp_distance_by_hand():
    assert ulp_distance(1.0, np.nextafter(1.0, 2.0)) == 1
    assert ulp_distance(-0.0, 0.0) == 1 and ulp_distance(0.0, 0.0) == 0
    assert ulp_distance(-TINY, TINY) == 3  # −tiny, −0, +0, +tiny
    assert ulp_distance(BIG, math.inf) == 1
    assert ulp_distance(1.0, math.nan) is None
    assert ulp_difference(1.0, 0.5) == -(2**52)  # [0.5, 1) holds 2^52 doubles
    assert ulp_difference(0.5, 1.0) == 2**52


def test_ulp_distances_is_ulp_distance_elementwise():
    rng = np.random.default_rng(5)
    special = [0.0, -0.0, TINY, -TINY, BIG, -BIG, math.inf, -math.inf, 1.0, -1.0, 2.2250738585072014e-308]
    a = np.concatenate([special * 3, rng.standard_normal(300) * 10.0 ** rng.integers(-300, 300, 300)])
    b = np.concatenate([np.repeat(special, 3)[: len(special) * 3], np.nextafter(a[len(special) * 3:], rng.choice([-np.inf, np.inf], 300))])
    got = ulp_distances(a, b)
    assert [int(x) for x in got] == [ulp_distance(float(x), float(y)) for x, y in zip(a, b)]
    assert ulp_distances(np.array([1.0]), np.array([math.nan]))[0] == np.iinfo(np.uint64).max


def test_check_against_reference_reports_like_the_cpp_check():
    ray, plane = ((0, 0, 0), (10, 0, 0)), ((1, 0, 0), (1, 0, 0))  # t = 1/10
    good = check_against_reference(ray, plane, "hit", 0.1)
    assert good.passed and good.t_ulps == 0 and good.exact_t == Fraction(1, 10)
    bad = check_against_reference(ray, plane, rk.Relation.HIT, 0.10000000000000003, max_t_ulps=1)
    assert not bad and bad.t_ulps == 2 and bad.t_direction == 1
    lines = bad.report.splitlines()
    assert lines[0] == "raykernel reference check FAILED: t is 2 ulps above the correctly rounded t (tolerance 1 ulp)"
    assert lines[2] == ("  replay    echo '0x0p+0 0x0p+0 0x0p+0 0x1.4p+3 0x0p+0 0x0p+0 0x1p+0 0x0p+0 0x0p+0 0x1p+0 0x0p+0 "
                        "0x0p+0' | raykernel classify --exact-t --hex")
    assert "exact     t = num/den = 1/10, num = 1, den = 10" in bad.report
    with pytest.raises(AssertionError, match="relation is parallel, expected hit"):
        assert_matches_reference(ray, plane, "parallel", math.nan)
    with pytest.raises(ValueError, match="ray direction is the zero vector"):
        check_against_reference(((0, 0, 0), (0, 0, 0)), plane, "hit", 0.0)


def test_assert_arrays_match_reference_names_the_first_wrong_row():
    o = np.zeros((6, 3))
    d = np.tile([10.0, 0, 0], (6, 1))
    p = np.array([[k + 1.0, 0, 0] for k in range(6)])
    n = np.tile([1.0, 0, 0], (6, 1))
    answers = rk.intersect_batch(o, d, p, n)
    assert_arrays_match_reference(o, d, p, n, answers.relation, answers.t)  # exact answers pass
    assert_arrays_match_reference(o, d, p, n, answers.relations(), answers.t)  # relation names work too
    t = answers.t.copy()
    t[3] = np.nextafter(t[3], 1.0)  # one ulp off: passes with a tolerance of 1, fails with 0
    t[5] = np.nextafter(np.nextafter(t[5], 0.0), 0.0)
    assert_arrays_match_reference(o, d, p, n, answers.relation, t, max_t_ulps=2)
    with pytest.raises(AssertionError) as failure:
        assert_arrays_match_reference(o, d, p, n, answers.relation, t, max_t_ulps=0)
    message = str(failure.value)
    assert "2 of 6 rows differ from the exact answer; row 3:" in message
    assert "t is 1 ulp above the correctly rounded t (tolerance 0 ulps)" in message
    relation = answers.relation.copy()
    relation[4] = rk.Relation.BEHIND.code
    with pytest.raises(AssertionError, match="row 4:\nraykernel reference check FAILED: relation is behind, expected hit"):
        assert_arrays_match_reference(o, d, p, n, relation, answers.t)


# The triangle a = 0, b = e_x, c = e_y: N = (b − a) × (c − a) = e_z. A ray going down, d = −e_z, from
# (x, y, 1): den = d·N = −1, num = (a − o)·N = −1, t = 1. π(p, q) = d·((p − o) × (q − o)) = −(the z of the
# cross product) = −((p − o)_x (q − o)_y − (p − o)_y (q − o)_x); the barycentric coordinates (πa, πb, πc)/den
# are those of (x, y) in the triangle: (1 − x − y, x, y).
A, B, C = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)


def down_from(x, y):
    return ((x, y, 1.0), (0.0, 0.0, -1.0))


@pytest.mark.parametrize(
    "x, y, location, barycentric",
    [
        (0.25, 0.25, "inside", (Fraction(1, 2), Fraction(1, 4), Fraction(1, 4))),
        (0.5, 0.0, "edge-ab", (Fraction(1, 2), Fraction(1, 2), 0)),  # y = 0: πc = 0
        (0.5, 0.5, "edge-bc", (0, Fraction(1, 2), Fraction(1, 2))),  # x + y = 1: πa = 0
        (0.0, 0.5, "edge-ca", (Fraction(1, 2), 0, Fraction(1, 2))),  # x = 0: πb = 0
        (0.0, 0.0, "vertex-a", (1, 0, 0)),
        (1.0, 0.0, "vertex-b", (0, 1, 0)),
        (0.0, 1.0, "vertex-c", (0, 0, 1)),
        (0.75, 0.75, "outside", (Fraction(-1, 2), Fraction(3, 4), Fraction(3, 4))),
    ],
)
def test_triangle_locations_by_hand(x, y, location, barycentric):
    answer = exact_ray_triangle(down_from(x, y), (A, B, C))
    assert answer.kind == "crossing" and answer.location == location
    assert answer.barycentric == tuple(Fraction(v) for v in barycentric)
    assert answer.exact_t == 1 and answer.t == 1.0
    assert answer.closed == ("miss" if location == "outside" else "hit")


def test_triangle_degenerate_parallel_coplanar_behind_by_hand():
    assert exact_ray_triangle(down_from(0.1, 0.1), (A, B, (2.0, 0.0, 0.0))).kind == "degenerate"  # collinear
    assert exact_ray_triangle(down_from(0.1, 0.1), (A, A, C)).kind == "degenerate"  # repeated vertex
    # d = e_x lies in the plane z = 0's direction: den = 0; from z = 1, num = −1 ≠ 0: parallel; from z = 0: coplanar.
    assert exact_ray_triangle(((0.1, 0.1, 1.0), (1.0, 0.0, 0.0)), (A, B, C)).kind == "parallel"
    assert exact_ray_triangle(((0.1, 0.1, 0.0), (1.0, 0.0, 0.0)), (A, B, C)).kind == "coplanar"
    # Going up from z = 1: den = +1, num = −1, t = −1: behind under both rules.
    behind = exact_ray_triangle(((0.25, 0.25, 1.0), (0.0, 0.0, 1.0)), (A, B, C))
    assert (behind.location, behind.closed, behind.owned, behind.t) == ("inside", "behind", "behind", -1.0)


def test_owned_rule_counts_a_shared_edge_once():
    # The square (0,0)-(1,0)-(1,1)-(0,1) as T1 = (p0, p1, p2) and T2 = (p0, p2, p3), both with N = e_z, sharing
    # the diagonal p0–p2. A ray down through (1/2, 1/2) lies on it: den = −1 for both.
    # T1: its edge c→a is p2→p0, π(c, a) = 0, replaced by the first nonzero component of d × (a − c) =
    #   (0, 0, −1) × (−1, −1, 0) = (−1, 1, 0): −1 = sign(den): T1 owns the hit.
    # T2: its edge a→b is p0→p2, π(a, b) = 0, replaced by d × (b − a) = (0, 0, −1) × (1, 1, 0) = (1, −1, 0):
    #   +1 ≠ sign(den): T2 does not. Under the closed rule both hit (the double count watertight code avoids).
    p0, p1, p2, p3 = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)
    ray = down_from(0.5, 0.5)
    t1, t2 = exact_ray_triangle(ray, (p0, p1, p2)), exact_ray_triangle(ray, (p0, p2, p3))
    assert (t1.location, t1.closed, t1.owned) == ("edge-ca", "hit", "hit")
    assert (t2.location, t2.closed, t2.owned) == ("edge-ab", "hit", "miss")


def test_triangle_reference_check_reports():
    ray = down_from(0.5, 0.0)  # through the edge ab at t = 1
    ok = check_triangle_hit_against_reference(ray, (A, B, C), True, 1.0, rule="closed")
    assert ok.passed and ok.t_ulps == 0
    missed = check_triangle_hit_against_reference(ray, (A, B, C), False, math.nan, rule="closed")
    assert not missed
    lines = missed.report.splitlines()
    assert lines[0] == "raykernel reference check FAILED: miss, expected hit (tolerance 0 ulps)"
    assert lines[2].endswith("| raykernel triangle --rule=closed --exact")
    assert "(edge-ab, hit under the closed rule)" in lines[3]
    off = check_triangle_hit_against_reference(ray, (A, B, C), True, np.nextafter(1.0, 0.0), rule="closed")
    assert not off and off.t_ulps == 1 and "t is 1 ulp below the correctly rounded t" in off.report
    assert check_triangle_hit_against_reference(ray, (A, B, C), True, 0.5, rule="closed", max_ulps=None).passed
    assert check_triangle_hit_against_reference(ray, (A, B, C), True, np.nextafter(1.0, 0.0), rule="closed",
                                                max_ulps=1).passed
    with pytest.raises(AssertionError, match="hit, expected miss"):
        assert_triangle_hit_matches_reference(down_from(0.75, 0.75), (A, B, C), True, 1.0)
    with pytest.raises(ValueError, match="rule"):
        check_triangle_hit_against_reference(ray, (A, B, C), True, 1.0, rule="open")


def test_the_triangle_checks_share_names_and_defaults():
    """Every triangle reference check takes ``rule`` (default "owned", as ``intersect``) and ``max_ulps`` (default 0:
    the same bits), keyword-only; the hit check's old ``max_t_ulps`` still works, with a DeprecationWarning."""
    import inspect

    from raykernel.testing import (assert_triangle_arrays_match_reference, assert_triangle_matches_reference,
                                   check_triangle_against_reference)

    checks = [check_triangle_hit_against_reference, assert_triangle_hit_matches_reference,
              check_triangle_against_reference, assert_triangle_matches_reference,
              assert_triangle_arrays_match_reference]
    for f in checks:
        params = inspect.signature(f).parameters
        for name, default in (("rule", "owned"), ("max_ulps", 0)):
            assert params[name].default == default, (f.__name__, name)
            assert params[name].kind is inspect.Parameter.KEYWORD_ONLY, (f.__name__, name)
    # The owned default decides: a lone triangle's edge ab (here not owned) is hit only under the closed rule.
    ray = down_from(0.5, 0.0)
    owned = check_triangle_hit_against_reference(ray, (A, B, C), True, 1.0)
    closed = check_triangle_hit_against_reference(ray, (A, B, C), True, 1.0, rule="closed")
    assert owned.rule == "owned" and closed.passed and owned.passed == (rk.intersect(ray, (A, B, C)).relation == "hit")
    with pytest.warns(DeprecationWarning, match="max_t_ulps is now max_ulps"):
        old = check_triangle_hit_against_reference(ray, (A, B, C), True, np.nextafter(1.0, 0.0), rule="closed",
                                                   max_t_ulps=1)
    assert old.passed and old.max_ulps == 1
    with pytest.raises(TypeError, match="give max_ulps only"):
        check_triangle_hit_against_reference(ray, (A, B, C), True, 1.0, max_ulps=2, max_t_ulps=1)

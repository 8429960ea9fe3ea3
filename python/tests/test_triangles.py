"""Ray–triangle from Python (docs/contract.md §6): hand-derived answers (derivations in the comments), the two
rules on a shared edge, options, errors naming the field and the row, layouts, and the GIL released."""

from fractions import Fraction

import numpy as np
import pytest

import raykernel as rk
from raykernel._raykernel import testkit

from test_arrays import longest_pause_of_this_thread_while, same_bits

R, L = rk.TriangleRelation, rk.TriangleLocation

# The unit right triangle in z = 0: a = 0, b = x, c = y. N = (b − a) × (c − a) = x × y = (0, 0, 1).
A, B, C = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)
UNIT = rk.Triangle(A, B, C)


def test_inside_hand_derived():
    # o = (1/4, 1/4, −1), d = (0, 0, 1): den = d·N = 1, num = (a − o)·N = 1, t = 1. The line meets z = 0 at
    # p = (1/4, 1/4, 0) = a + (1/4)(b − a) + (1/4)(c − a): barycentric (1/2, 1/4, 1/4), all positive: inside.
    x = rk.intersect(((0.25, 0.25, -1), (0, 0, 1)), UNIT)
    assert x == rk.TriangleIntersection(R.HIT, L.INSIDE, True, 1.0, rk.Barycentric(0.5, 0.25, 0.25))
    # The origin beyond the plane (z = +1, same d): num = −1, t = −1, behind under both rules.
    behind = rk.intersect(((0.25, 0.25, 1), (0, 0, 1)), UNIT, rule="closed")
    assert (behind.relation, behind.t) == (R.BEHIND, -1.0)
    # (2, 2, −1): barycentric (−3, 2, 2), πa < 0 against den > 0: outside, a miss under both rules.
    out = rk.relation(((2, 2, -1), (0, 0, 1)), UNIT, rule="closed")
    assert out == rk.TriangleClassification(R.MISS, L.OUTSIDE, False)


def test_edge_t_and_barycentric_rounded_from_the_exact_rationals():
    # o = (1/2, 0, −1), d = (0, 0, 3): den = 3, num = 1, t = 1/3 exactly (not a double: RN(1/3) =
    # 0x1.5555555555555p-2). The crossing (1/2, 0, 0) is the midpoint of ab: πc = π(a, b) = 0, barycentric
    # (1/2, 1/2, 0): edge-ab. Owned: πc takes the sign of the first nonzero component of d × (b − a) =
    # (0, 0, 3) × (1, 0, 0) = (0, 3, 0), positive like den: the owned rule lets it through.
    ray = ((0.5, 0, -1), (0, 0, 3))
    exact = rk.intersect_exact_rational(ray, UNIT)
    assert (exact.den, exact.num, exact.pi) == (3, 1, (Fraction(3, 2), Fraction(3, 2), 0))
    assert exact.exact_t == Fraction(1, 3) and exact.exact_barycentric == (Fraction(1, 2), Fraction(1, 2), 0)
    x = rk.intersect(ray, UNIT)
    assert (x.relation, x.location, x.owned) == (R.HIT, L.EDGE_AB, True)
    assert x.t.hex() == "0x1.5555555555555p-2" and x.barycentric == (0.5, 0.5, 0.0)
    assert x == rk.intersect_exact(ray, UNIT) == exact[:5]


def test_a_shared_edge_belongs_to_one_triangle_under_the_owned_rule_and_to_both_closed():
    # The neighbour across ab, consistently oriented: (b, a, (0, −1, 0)), N = (a − b) × ((0, −1, 0) − b) =
    # (−1, 0, 0) × (−1, −1, 0) = (0, 0, 1): the same den. For it the edge is b → a and its zero π takes the sign
    # of d × (a − b) = (0, −3, 0): negative, against den's — not owned. So exactly one of the two owns the ray.
    ray = ((0.5, 0, -1), (0, 0, 3))
    neighbour = (B, A, (0.0, -1.0, 0.0))
    first, second = rk.intersect(ray, UNIT), rk.intersect(ray, neighbour)
    assert (first.relation, second.relation) == (R.HIT, R.MISS)
    assert second.location is L.EDGE_AB and not second.owned
    closed = [rk.intersect(ray, t, rule="closed").relation for t in (UNIT, neighbour)]
    assert closed == [R.HIT, R.HIT]
    assert rk.intersect(ray, neighbour, rule=rk.TriangleRule.CLOSED).relation is R.HIT


def test_vertex_degenerate_parallel_coplanar():
    # Through a: o = (0, 0, −2), d = (0, 0, 1): πb = πc = 0, barycentric (1, 0, 0), t = 2.
    x = rk.intersect(((0, 0, -2), (0, 0, 1)), UNIT, rule="closed")
    assert (x.relation, x.location, x.t, x.barycentric) == (R.HIT, L.VERTEX_A, 2.0, (1.0, 0.0, 0.0))
    # c = 2b − a: collinear, N = 0: degenerate, never hit, nothing rounded.
    d = rk.intersect(((0, 0, -1), (0, 0, 1)), (A, B, (2.0, 0.0, 0.0)))
    assert (d.relation, d.location, d.owned) == (R.DEGENERATE, L.NONE, False) and np.isnan(d.t)
    # d = (1, 0, 0) lies in z = 0: den = 0. From z = −1: num = 1 ≠ 0, parallel; from z = 0: num = 0, coplanar.
    assert rk.relation(((0, 0, -1), (1, 0, 0)), UNIT).relation is R.PARALLEL
    assert rk.relation(((-1, 0.5, 0), (1, 0, 0)), UNIT, rule="closed").relation is R.COPLANAR


def test_options_skip_the_roundings():
    x = rk.intersect(((0.5, 0, -1), (0, 0, 3)), UNIT, t=False, barycentric=False)
    assert x.relation is R.HIT and np.isnan(x.t) and all(np.isnan(x.barycentric))
    traced = rk.intersect_traced(((0.5, 0, -1), (0, 0, 3)), UNIT)
    assert traced[:5] == rk.intersect(((0.5, 0, -1), (0, 0, 3)), UNIT)
    assert isinstance(traced.relation_stage, rk.Stage) and isinstance(traced.rounding_stage, rk.Stage)


def test_naive_is_moller_trumbore():
    # Möller–Trumbore on the hand case: u = 1/4, v = 1/4, t = 1 (exact in doubles here).
    x = rk.intersect_naive(((0.25, 0.25, -1), (0, 0, 1)), UNIT)
    assert (x.relation, x.t, x.barycentric) == (R.HIT, 1.0, (0.5, 0.25, 0.25))


def test_errors_name_the_field():
    with pytest.raises(rk.InvalidInput, match="^ray direction is the zero vector$"):
        rk.intersect(((0, 0, 0), (0, 0, 0)), UNIT)
    with pytest.raises(ValueError, match="^triangle vertex b z is NaN$"):
        rk.intersect(((0, 0, -1), (0, 0, 1)), (A, (1, 0, float("nan")), C))
    assert rk.validate(((0, 0, -1), (0, 0, 1)), (A, B, (0, float("inf"), 0))) is not None
    assert rk.validate(((0, 0, -1), (0, 0, 1)), (A, B, B)) is None  # degenerate is valid
    with pytest.raises(ValueError, match="^triangle c: expected a sequence of 3 numbers, got a sequence of 2 items$"):
        rk.intersect(((0, 0, -1), (0, 0, 1)), (A, B, (0, 1)))
    with pytest.raises(ValueError, match="^rule: expected 'owned' or 'closed', got 'open'$"):
        rk.intersect(((0, 0, -1), (0, 0, 1)), UNIT, rule="open")
    with pytest.raises(ValueError, match="^rule: only triangles have rules"):
        rk.intersect(((0, 0, -1), (0, 0, 1)), ((0, 0, 0), (0, 0, 1)), rule="owned")


@pytest.fixture(scope="module")
def hard_triangles():
    """3,200 hard ray–triangle queries, 200 of each testkit kind (seeded)."""
    kinds = list(testkit.TRIANGLE_QUERY_KINDS)
    o, d, a, b, c, kind = testkit.make_triangle_query_arrays(kinds, 200 * len(kinds), 5)
    assert set(np.unique(kind)) == set(range(len(kinds)))
    return o, d, a, b, c


@pytest.mark.parametrize("rule", ["owned", "closed"])
def test_batch_equals_scalar_and_certified_equals_exact(hard_triangles, rule):
    o, d, a, b, c = hard_triangles
    got = rk.intersect_triangle_batch(o, d, a, b, c, rule=rule)
    exact = rk.intersect_triangle_batch(o, d, a, b, c, rule=rule, path="exact")
    for field in ("relation", "location", "owned", "valid"):
        assert (getattr(got, field) == getattr(exact, field)).all(), field
    assert same_bits(got.t, exact.t) and same_bits(got.barycentric, exact.barycentric)
    for i in range(0, len(o), 97):  # a sample against the scalar function
        x = rk.intersect((o[i], d[i]), (a[i], b[i], c[i]), rule=rule)
        assert (got.relation[i], got.location[i], bool(got.owned[i])) == (x.relation.code, x.location.code, x.owned)
        assert same_bits(got.t[i], x.t) and same_bits(got.barycentric[i], x.barycentric)
    classified = rk.relation_triangle_batch(o, d, a, b, c, rule=rule)
    assert (classified.relation == got.relation).all() and (classified.owned == got.owned).all()
    assert (rk.relation_triangle_batch(o, d, a, b, c, rule=rule, path="exact").location == got.location).all()
    naive = rk.intersect_triangle_batch(o, d, a, b, c, path="naive")
    assert (naive.relation != got.relation).any()  # the hard queries do catch Möller–Trumbore somewhere
    assert list(got.relations()[:1]) == [x.value for x in [rk.TriangleRelation.from_code(got.relation[0])]]


def test_layouts_and_one_triangle(hard_triangles):
    o, d, a, b, c = hard_triangles
    base = rk.intersect_triangle_batch(o, d, a, b, c)
    soa = [np.ascontiguousarray(x.T).T for x in (o, d, a, b, c)]  # column-contiguous
    strided = [np.repeat(x, 2, axis=0)[::2] for x in (o, d, a, b, c)]
    for arrays in (soa, strided):
        other = rk.intersect_triangle_batch(*arrays)
        assert (other.relation == base.relation).all() and same_bits(other.t, base.t)
    one = rk.intersect_triangle_batch(o, d, np.array(A), np.array(B), np.array(C), rule="closed")
    for i in range(0, len(o), 211):
        x = rk.intersect((o[i], d[i]), UNIT, rule="closed")
        assert one.relation[i] == x.relation.code and same_bits(one.t[i], x.t)


def test_invalid_rows_raise_naming_the_row_or_are_masked(hard_triangles):
    o, d, a, b, c = (x[:50].copy() for x in hard_triangles)
    d[7] = 0
    c[12, 1] = np.nan
    with pytest.raises(rk.InvalidInput, match="^query 7: ray direction is the zero vector$"):
        rk.intersect_triangle_batch(o, d, a, b, c)
    with pytest.raises(ValueError, match="^query 7: "):
        rk.relation_triangle_batch(o, d, a, b, c, path="exact")
    with pytest.raises(rk.InvalidInput, match="^ray 7: ray direction is the zero vector$"):
        rk.intersect_triangle_batch(o, d, np.array(A), np.array(B), np.array(C))
    masked = rk.intersect_triangle_batch(o, d, a, b, c, errors="mask")
    assert list(np.flatnonzero(~masked.valid)) == [7, 12]
    assert (masked.relation[[7, 12]] == rk.INVALID_RELATION_CODE).all() and np.isnan(masked.t[[7, 12]]).all()
    assert list(masked.relations()[[7, 12]]) == ["invalid", "invalid"]
    keep = masked.valid
    clean = rk.intersect_triangle_batch(o[keep], d[keep], a[keep], b[keep], c[keep])
    assert (clean.relation == masked.relation[keep]).all() and same_bits(clean.t, masked.t[keep])
    with pytest.raises(ValueError, match="^b has 3 rows, origins has 50$"):
        rk.intersect_triangle_batch(o, d, a, b[:3], c)
    with pytest.raises(ValueError, match="^a, b, c: give all three"):
        rk.intersect_triangle_batch(o, d, np.array(A), b, c)
    with pytest.raises(ValueError, match="^path: expected 'certified' or 'exact', got 'naive'$"):
        rk.relation_triangle_batch(o, d, a, b, c, path="naive")


def test_threads_give_the_same_answers(hard_triangles):
    o, d, a, b, c = (np.tile(x, (4, 1)) for x in hard_triangles)
    one = rk.intersect_triangle_batch(o, d, a, b, c, threads=1, path="exact")
    many = rk.intersect_triangle_batch(o, d, a, b, c, threads=4, path="exact")
    assert (one.relation == many.relation).all() and same_bits(one.barycentric, many.barycentric)


def test_the_gil_is_released_during_a_triangle_batch(hard_triangles):
    o, d, a, b, c = (np.tile(x, (8, 1)) for x in hard_triangles)  # 25,600 exact queries
    longest, total = longest_pause_of_this_thread_while(
        lambda: rk.intersect_triangle_batch(o, d, a, b, c, path="exact", threads=1))
    assert total > 0.05, "the batch was too short to tell"
    assert longest < total / 4, f"this thread stopped for {longest:.3f} s of a {total:.3f} s batch"

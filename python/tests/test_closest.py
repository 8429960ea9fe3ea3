"""The exact closest point from Python (docs/contract.md §11): closest_point, closest_point_exact and
closest_point_batch against an independent oracle in Python's Fractions (the projection onto the plane when it
falls inside the triangle, else the nearest of the three segments), hand-derived cases, the batch against the
scalar form, the signed distance, bad rows."""
import math
from fractions import Fraction

import numpy as np
import pytest

import raykernel as rk


def _sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _segment(p, s0, s1):
    e = _sub(s1, s0)
    l2 = _dot(e, e)
    t = Fraction(0)
    if l2 > 0:
        t = min(max(_dot(_sub(p, s0), e) / l2, Fraction(0)), Fraction(1))
    q = tuple(s + t * x for s, x in zip(s0, e))
    r = _sub(p, q)
    return _dot(r, r), q


def _triangle(p, a, b, c):
    n = _cross(_sub(b, a), _sub(c, a))
    n2 = _dot(n, n)
    if n2 > 0:
        s = _dot(_sub(p, a), n) / n2
        q = tuple(x - s * y for x, y in zip(p, n))
        side = lambda u, v: _dot(_cross(_sub(v, u), _sub(q, u)), n)  # noqa: E731
        if side(a, b) >= 0 and side(b, c) >= 0 and side(c, a) >= 0:
            r = _sub(p, q)
            return _dot(r, r), q
    return min(_segment(p, a, b), _segment(p, b, c), _segment(p, c, a), key=lambda m: m[0])


def _oracle(point, vertices, triangles):
    p = tuple(Fraction(x) for x in point)
    best = None
    for k, t in enumerate(triangles):
        a, b, c = (tuple(Fraction(float(x)) for x in vertices[i]) for i in t)
        d2, q = _triangle(p, a, b, c)
        if best is None or d2 < best[1]:
            best = (k, d2, q)
    return best


def _octahedron_and_friends():
    v = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1],
                  [3, 3, 3], [3, 3, 3], [5, 5, 5], [0.1, 0.2, 0.3]], dtype=np.float64)
    t = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5],
                  [6, 7, 8],  # degenerate: a segment
                  [0, 2, 4], [9, 9, 9]], dtype=np.int64)  # a copy (ties), a point
    return v, t


def test_agrees_with_the_independent_oracle():
    v, t = _octahedron_and_friends()
    mesh = rk.Mesh(v, t)
    rng = np.random.default_rng(5)
    points = np.concatenate([rng.integers(-24, 25, size=(150, 3)) / 8.0, v, rng.normal(size=(50, 3))])
    for point in points:
        k, d2, q = _oracle(point, v, t)
        for got in (rk.closest_point(point, mesh), rk.closest_point_exact(point, mesh)):
            assert got.triangle == k, point
            assert got.squared_distance_exact == d2, point
            assert got.point == rk.Vec3(*(float(x) for x in q)), point  # float(Fraction) rounds to nearest
            assert got.squared_distance == float(d2)
            # RN(√d2): the exact square root lies within half an ulp, checked in Fractions at the midpoints
            s = got.distance
            hi = (Fraction(s) + Fraction(math.nextafter(s, math.inf))) / 2
            lo = (Fraction(s) + Fraction(math.nextafter(s, 0))) / 2 if s > 0 else Fraction(0)
            assert lo * lo <= d2 <= hi * hi, point


def test_hand_derived():
    mesh = rk.Mesh([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2]])
    c = rk.closest_point((0, 0, 0), mesh)  # the centroid, d² = 1/3
    assert c.feature is rk.ClosestFeature.FACE
    assert c.point == rk.Vec3(1 / 3, 1 / 3, 1 / 3)
    assert c.squared_distance_exact == Fraction(1, 3)
    assert c.distance == float.fromhex("0x1.279a74590331cp-1")  # √(1/3) = 0.57735026918962576…
    # (2, 2, −1): the plane's foot (4/3, 4/3, −5/3) is outside; edge ab gives (1/2, 1/2, 0) at d² = 9/4 + 9/4 + 1,
    # bc and ca their ends b and a at d² = 6.
    c = rk.closest_point((2, 2, -1), mesh)
    assert (c.feature, c.corner) == (rk.ClosestFeature.EDGE, 0)
    assert c.point == rk.Vec3(0.5, 0.5, 0.0)
    assert c.squared_distance_exact == Fraction(9, 4) + Fraction(9, 4) + 1


def test_batch_is_the_scalar_form_and_signed_follows_inside():
    v, t = _octahedron_and_friends()
    mesh = rk.Mesh(v[:6], t[:8])  # the closed octahedron
    rng = np.random.default_rng(9)
    points = rng.integers(-16, 17, size=(300, 3)) / 8.0
    got = rk.closest_point_batch(points, mesh, signed=True, threads=2)
    for i, p in enumerate(points):
        c = rk.closest_point(p, mesh)
        assert got.triangle[i] == c.triangle
        assert rk.ClosestFeature.from_code(got.feature[i]) is c.feature
        assert tuple(got.point[i]) == tuple(c.point)
        assert got.distance[i] == c.distance
        where = rk.inside(p, mesh)
        expected = 0.0 if where is rk.PointLocation.ON_SURFACE else (-c.distance if where is rk.PointLocation.INSIDE
                                                                     else c.distance)
        assert got.signed_distance[i] == expected
    assert got.valid.all()
    assert set(got.features()) <= {"vertex", "edge", "face"}


def test_bad_rows_are_named_or_masked():
    v, t = _octahedron_and_friends()
    mesh = rk.Mesh(v, t)
    points = np.array([[0, 0, 2], [0, np.nan, 0], [0, 0, 3]])
    with pytest.raises(ValueError, match="point 1: y is not finite"):
        rk.closest_point_batch(points, mesh)
    got = rk.closest_point_batch(points, mesh, errors="mask")
    assert got.valid.tolist() == [True, False, True]
    assert got.triangle[1] == -1 and math.isnan(got.distance[1])
    assert got.distance[0] == 1.0 and got.distance[2] == 2.0
    with pytest.raises(ValueError, match="no triangles"):
        rk.closest_point((0, 0, 0), rk.Mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)))

"""Nearest hits and PlaneSet: hand-derived answers, ties, errors."""

import math

import numpy as np
import pytest

import raykernel as rk

# The README's nearest example. Ray o = 0, d = e_x.
#   plane 0: point (0, 0, 5), normal e_z: den = d·n = 0 → parallel, never hit;
#   plane 1: point (1, 1, 0), normal (1, −2^-60, 0): num = (p − o)·n = 1 − 2^-60, den = 1 → t = 1 − 2^-60;
#   plane 2: point (1, 0, 0), normal e_x: t = 1.
# Plane 1 is nearer by 2^-60, less than an ulp of 1: both t round to 1.0.
RAY = ((0, 0, 0), (1, 0, 0))
PLANES = [((0, 0, 5), (0, 0, 1)), ((1, 1, 0), (1, -(2.0**-60), 0)), ((1, 0, 0), (1, 0, 0))]


@pytest.mark.parametrize("f", [rk.nearest_hit, rk.nearest_hit_exact])
def test_nearest_orders_below_an_ulp(f):
    assert f(RAY, PLANES) == rk.NearestHit(1, 1.0)
    assert f(RAY, rk.PlaneSet(PLANES)) == (1, 1.0)
    # Without plane 1, plane 2 wins; a ray pointing away (d = −e_x) has both behind: a miss.
    assert f(RAY, [PLANES[0], PLANES[2]]) == (1, 1.0)
    assert f(((0, 0, 0), (-1, 0, 0)), PLANES) is None
    assert f(RAY, []) is None


def test_naive_cannot_see_the_difference():
    # Both t round to 1.0; the loop keeps the first strictly smaller rounded t: plane 1 (its t is the first 1.0).
    assert rk.nearest_hit_naive(RAY, PLANES) == (1, 1.0)
    # Listed the other way round, the naive loop picks the farther plane; the exact comparison does not.
    reordered = [PLANES[2], PLANES[1]]
    assert rk.nearest_hit_naive(RAY, reordered) == (0, 1.0)
    assert rk.nearest_hit(RAY, reordered) == (1, 1.0)


def test_exact_ties_go_to_the_smaller_index():
    # The same plane twice, the second with its normal scaled by −4: equal exact t (= 2), tie → index 0.
    planes = [((2, 0, 0), (1, 0, 0)), ((2, 7, -3), (-4, 0, 0))]
    assert rk.nearest_hit(RAY, planes) == (0, 2.0)
    assert rk.nearest_hit(RAY, planes[::-1]) == (0, 2.0)


def test_plane_set():
    s = rk.PlaneSet(PLANES)
    assert len(s) == 3 and s[1] == rk.Plane((1, 1, 0), (1, -(2.0**-60), 0)) and s[-1] == s[2]
    points, normals = s.points, s.normals
    assert points.shape == normals.shape == (3, 3) and normals[1, 1] == -(2.0**-60)
    t = rk.PlaneSet(points, normals)
    assert [t[k] for k in range(3)] == [s[k] for k in range(3)]
    assert repr(s) == "PlaneSet(3 planes)"
    with pytest.raises(IndexError):
        s[3]


def test_plane_errors_name_the_plane():
    bad = PLANES + [((0, 0, 0), (0, 0, 0))]
    with pytest.raises(rk.InvalidInput, match="^plane 3: plane normal is the zero vector$"):
        rk.PlaneSet(bad)
    with pytest.raises(rk.InvalidInput, match="^plane 3: plane normal is the zero vector$"):
        rk.nearest_hit(RAY, bad)
    with pytest.raises(rk.InvalidInput, match="^plane 1: plane point x is NaN$"):
        rk.PlaneSet(np.array([[0, 0, 0], [math.nan, 0, 0]]), np.ones((2, 3)))
    with pytest.raises(ValueError, match="^plane 2 normal: expected a sequence of 3 numbers"):
        rk.nearest_hit(RAY, PLANES[:2] + [((0, 0, 0), (1, 0))])
    with pytest.raises(rk.InvalidInput, match="^ray direction is the zero vector$"):
        rk.nearest_hit(((0, 0, 0), (0, 0, 0)), PLANES)
    with pytest.raises(ValueError, match="normals has 2 rows, points has 3"):
        rk.PlaneSet(np.zeros((3, 3)), np.ones((2, 3)))

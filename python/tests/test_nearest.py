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


def test_plane_set_sets_coinciding_planes_aside():
    # Plane 1 is plane 0 (x = 2) with another point on it and its normal scaled by −4; plane 2 is x = 3. Exact
    # coincidence: plane 1 can never win (same t as plane 0 for every ray, ties to the smaller index).
    s = rk.PlaneSet([((2, 0, 0), (1, 0, 0)), ((2, 7, -3), (-4, 0, 0)), ((3, 0, 0), (1, 0, 0))])
    assert s.candidates.tolist() == [0, 2]
    assert rk.nearest_hit(RAY, s) == rk.nearest_hit_exact(RAY, s) == (0, 2.0)
    near = rk.PlaneSet([((2, 0, 0), (1, 0, 0)), ((2, 2.0**-60, 0), (1, 1e-300, 0))])  # not exactly the same plane
    assert near.candidates.tolist() == [0, 1]


def test_plane_scenes_take_an_interval():
    """docs/contract.md §8 on planes: x = 1, 2, 3 and a second x = 2 (index 3); along (3, 0, 0) t = 1/3, 2/3, 1 —
    1/3 is not a double and RN(1/3) < 1/3, so a bound at RN(1/3) is below the exact t."""
    planes = rk.PlaneSet([((1, 0, 0), (1, 0, 0)), ((2, 0, 0), (1, 0, 0)), ((3, 0, 0), (-1, 0, 0)),
                          ((2, 5, 7), (2, 0, 0))])
    x, x3 = ((0, 0, 0), (1, 0, 0)), ((0, 0, 0), (3, 0, 0))
    third = 1 / 3
    assert rk.nearest_hit(x, planes, t_min=1.5) == rk.NearestHit(1, 2.0)
    assert rk.nearest_hit(x, planes, t_min=2.0, t_max=2.0) == rk.NearestHit(1, 2.0)  # the tie: the smaller index
    assert rk.nearest_hit(x, planes, t_min=2.5, t_max=2.75) is None
    assert rk.nearest_hit(x3, planes, t_min=third) == rk.NearestHit(0, third)
    assert rk.nearest_hit(x3, planes, t_max=third) is None
    assert rk.nearest_hit(x3, planes, t_min=math.nextafter(third, 1)).plane == 1
    assert rk.nearest_hit_exact(x3, planes, t_min=math.nextafter(third, 1)).plane == 1
    with pytest.raises(ValueError, match="whole ray"):
        rk.nearest_hit_naive(x, planes, t_min=1.0)
    # Per-ray intervals in the batch: each row the scalar answer, certified == exact.
    rng = np.random.default_rng(12)
    n = 2000
    o = rng.integers(-8, 9, size=(n, 3)) / 4.0
    d = rng.integers(-4, 5, size=(n, 3)) / 2.0
    d[np.all(d == 0, axis=1)] = (1.0, 0.0, 0.0)
    points = rng.integers(-8, 9, size=(30, 3)) / 4.0
    normals = rng.integers(-2, 3, size=(30, 3)).astype(float)
    normals[np.all(normals == 0, axis=1)] = (0.0, 0.0, 1.0)
    scene = rk.PlaneSet(points, normals)
    whole = rk.nearest_hit_batch(o, d, scene)
    t_min = np.where(whole.plane >= 0, np.nan_to_num(whole.t, nan=0.0), 0.0)  # on the nearest t exactly: closed
    t_min[::3] = np.nextafter(t_min[::3], np.inf)                            # an ulp past it: another plane
    got = rk.nearest_hit_batch(o, d, scene, t_min=t_min)
    exact = rk.nearest_hit_batch(o, d, scene, t_min=t_min, path="exact")
    assert np.array_equal(got.plane, exact.plane) and np.array_equal(got.t, exact.t, equal_nan=True)
    assert ((got.plane != whole.plane) & (whole.plane >= 0)).sum() > 50
    for i in range(0, n, 71):
        one = rk.nearest_hit((o[i], d[i]), scene, t_min=t_min[i])
        assert (one.plane if one else -1) == got.plane[i]
    with pytest.raises(ValueError, match="stats: only for the whole ray"):
        rk.nearest_hit_batch(o, d, scene, t_min=t_min, stats=True)

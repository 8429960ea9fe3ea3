"""spawn and spawn_to (docs/contract.md §9) from Python: hand-derived origins, the formats, the errors, and the
guarantee checked with Fractions on generated hits."""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import raykernel as rk

FLOOR = ((0, 0, 0), (1, 0, 0), (0, 1, 0))  # z = 0, N = (0, 0, 1)


def test_a_hit_point_on_the_plane_moves_one_step_off_it():
    # P = (0.25, 0.25, 0) is a double on the plane: σ(P̂) = 0, so z moves one double up (or down).
    up = rk.spawn(((0.25, 0.25, 1), (0, 0, -1)), FLOOR, (0, 0, 1))
    assert up == rk.SpawnedOrigin(rk.Vec3(0.25, 0.25, 5e-324), 1)
    down = rk.spawn((0.25, 0.25, 0), FLOOR, (0, 0, -1))
    assert down.origin == (0.25, 0.25, -5e-324) and down.steps == 1
    assert isinstance(down.steps, int)
    # A shadow ray towards a point above: the same origin as leaving upwards.
    assert rk.spawn_to(((0.25, 0.25, 1), (0, 0, -1)), FLOOR, (3, 4, 5)) == up


def test_binary32_rounds_straight_from_the_exact_point():
    # The plane -x + 3z = 0 through (0, 0, 0), (3, 0, 1), (0, 1, 0); the ray down at x = 1 meets it at z = 1/3.
    # RN32(1/3) lies above the plane and the new ray leaves downwards: z moves one float down.
    triangle = ((0, 0, 0), (3, 0, 1), (0, 1, 0))
    o = rk.spawn(((1, 0.5, 1), (0, 0, -1)), triangle, (0, 0, -1), format="binary32")
    third = np.float32(1) / np.float32(3)
    assert Fraction(float(third)) > Fraction(1, 3)
    assert o.origin.z == float(np.nextafter(third, np.float32(-1)))
    assert (o.origin.x, o.origin.y, o.steps) == (1.0, 0.5, 1)
    # In binary64 the origin is on the side too (RN64(1/3) lies below 1/3): checked exactly.
    o64 = rk.spawn(((1, 0.5, 1), (0, 0, -1)), triangle, (0, 0, -1))
    assert side(o64.origin, triangle) == direction_side((0, 0, -1), triangle)


def test_invalid_input_names_the_reason():
    with pytest.raises(rk.InvalidInput, match="degenerate"):
        rk.spawn(((0, 0, 1), (0, 0, -1)), ((0, 0, 0), (1, 1, 1), (2, 2, 2)), (0, 0, 1))
    with pytest.raises(rk.InvalidInput, match="parallel"):
        rk.spawn(((0, 0, 1), (1, 0, 0)), FLOOR, (0, 0, 1))
    with pytest.raises(rk.InvalidInput, match="zero vector"):
        rk.spawn(((0, 0, 1), (0, 0, -1)), FLOOR, (0, 0, 0))
    with pytest.raises(rk.InvalidInput, match="plane"):
        rk.spawn_to(((0, 0, 1), (0, 0, -1)), FLOOR, (5, 5, 0))
    with pytest.raises(ValueError, match="binary64' or 'binary32"):
        rk.spawn(((0, 0, 1), (0, 0, -1)), FLOOR, (0, 0, 1), format="binary16")


def exact(v):
    return [Fraction(float(x)) for x in v]


def normal(triangle):
    a, b, c = (exact(v) for v in triangle)
    u = [b[k] - a[k] for k in range(3)]
    w = [c[k] - a[k] for k in range(3)]
    return [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]


def sign(x):
    return (x > 0) - (x < 0)


def side(point, triangle):
    a, n = exact(triangle[0]), normal(triangle)
    p = exact(point)
    return sign(sum((p[k] - a[k]) * n[k] for k in range(3)))


def direction_side(w, triangle):
    n = normal(triangle)
    return sign(sum(x * y for x, y in zip(exact(w), n)))


small = st.integers(-40, 40).map(lambda k: k / 8)
vec = st.tuples(small, small, small)


@settings(max_examples=300, deadline=None)
@given(vec, vec, vec, vec, vec, vec, st.sampled_from(["binary64", "binary32"]))
def test_the_origin_is_strictly_on_the_side(o, d, a, b, c, w, fmt):
    triangle = (a, b, c)
    n = normal(triangle)
    if all(x == 0 for x in n) or direction_side(w, triangle) == 0:
        return
    if sign(sum(x * y for x, y in zip(exact(d), n))) == 0:
        return
    origin, steps = rk.spawn((o, d), triangle, w, format=fmt)
    assert side(origin, triangle) == direction_side(w, triangle)
    if fmt == "binary32":
        assert all(float(np.float32(x)) == x for x in origin)
    assert steps >= 0


def test_spawn_from_a_sphere_hand_derived():
    # p = (1, 0, 0) on the unit sphere: outward along x the next double above 1 (k = 1); inward the double below 1;
    # from (2, 0, 0) inward, 2^52 + 1 steps down to 1 − 2^-53; a float renderer's origin: the float above 1.
    unit = rk.Sphere((0, 0, 0), 1)
    assert rk.spawn((1, 0, 0), unit, (1, 0, 0)) == ((1 + 2.0**-52, 0.0, 0.0), 1)
    assert rk.spawn((1, 0, 0), unit, (-1, 2, 3)) == ((1 - 2.0**-53, 0.0, 0.0), 1)
    assert rk.spawn((2, 0, 0), unit, (-1, 0, 0)) == ((1 - 2.0**-53, 0.0, 0.0), 2**52 + 1)
    assert rk.spawn((1, 0, 0), unit, (1, 0, 0), format="binary32") == ((1 + 2.0**-23, 0.0, 0.0), 1)
    with pytest.raises(ValueError, match="tangent"):
        rk.spawn((1, 0, 0), unit, (0, 1, 0))
    with pytest.raises(ValueError, match="hit point"):
        rk.spawn(((0, 0, 0), (1, 0, 0)), unit, (1, 0, 0))


def test_spawn_batches_are_the_scalar_forms():
    """spawn_batch and spawn_to_batch give, row by row, spawn's and spawn_to's answers (binary64 and binary32), and
    name or mask a bad row."""
    rng = np.random.default_rng(12)
    n = 300
    a = rng.integers(-8, 9, size=(n, 3)) / 4.0
    b = a + rng.integers(1, 9, size=(n, 3)) / 8.0 * np.array([1, 0, 0])
    c = a + rng.integers(1, 9, size=(n, 3)) / 8.0 * np.array([0, 1, 0.5])
    w1, w2 = rng.uniform(0.05, 0.9, size=(2, n))
    target = a + w1[:, None] * (b - a) + w2[:, None] * (c - a) * (1 - w1[:, None])  # a point in each triangle
    origins = target + rng.normal(size=(n, 3))
    directions = target - origins
    out = rng.normal(size=(n, 3))
    lights = rng.normal(size=(n, 3)) * 4
    for fmt in ("binary64", "binary32"):
        got = rk.spawn_batch(origins, directions, a, b, c, out, format=fmt, errors="mask")
        to = rk.spawn_to_batch(origins, directions, a, b, c, lights, format=fmt, errors="mask")
        assert got.valid.mean() > 0.9 and to.valid.mean() > 0.9  # rows w·N = 0 or q on the plane are rare
        for i in range(n):
            tri = (a[i], b[i], c[i])
            for batch, fn, v in ((got, rk.spawn, out[i]), (to, rk.spawn_to, lights[i])):
                try:
                    want = fn((origins[i], directions[i]), tri, v, format=fmt)
                except ValueError:
                    assert not batch.valid[i]
                    continue
                assert batch.valid[i]
                assert tuple(batch.origin[i]) == tuple(want.origin) and int(batch.steps[i]) == want.steps
    bad = directions.copy()
    bad[5] = 0
    with pytest.raises(ValueError, match=r"^row 5: "):
        rk.spawn_batch(origins, bad, a, b, c, out)

"""raykernel.SphereSet: spheres as a scene of nearest_hit, occluded and occluded_segment (docs/contract.md §8, §10),
scalar and batched. Hand-derived answers (roots that are integers, so every comparison is exact by hand), the
exact path as the oracle of the certified one on random scenes, and the batch forms equal to the scalar ones."""

import math
import pickle

import numpy as np
import pytest

import raykernel as rk

X = ((0, 0, 0), (1, 0, 0))  # the x axis from the origin


@pytest.fixture(scope="module")
def three():
    # Along X: sphere 0 has roots 4 and 6, sphere 1 roots 7 and 9, sphere 2 touches the axis at x = 5 (tangent root 5).
    return rk.SphereSet([[5, 0, 0], [8, 0, 0], [5, 0.5, 0]], [1, 1, 0.5])


def test_hand_derived_nearest_hits_and_intervals(three):
    assert rk.nearest_hit(X, three) == rk.SphereHit(0, 4.0)
    assert rk.nearest_hit(X, three, t_min=4.5) == rk.SphereHit(2, 5.0)        # the tangent root counts
    assert rk.nearest_hit(X, three, t_min=5.5) == rk.SphereHit(0, 6.0)        # the far root of sphere 0
    assert rk.nearest_hit(X, three, t_min=6.5) == rk.SphereHit(1, 7.0)
    assert rk.nearest_hit(X, three, t_max=3.999) is None
    assert rk.nearest_hit(X, three, t_min=4.0, t_max=4.0) == rk.SphereHit(0, 4.0)  # closed interval
    assert rk.nearest_hit(X, three, t_min=np.nextafter(9.0, 10.0)) is None
    # An exact tie goes to the smaller index: two copies of sphere 0.
    twins = rk.SphereSet([rk.Sphere((5, 0, 0), 1), rk.Sphere((5, 0, 0), 1)])
    assert rk.nearest_hit(X, twins) == rk.SphereHit(0, 4.0)
    # Irrational roots: (0, 0.5, 0) + t (1, 0, 0) passes 0.5 from sphere 0's centre, meeting it at 5 ∓ √0.75
    # (4.13...), before sphere 2, whose centre it goes through (roots 4.5 and 5.5). RN(5 − √0.75) by 60 digits.
    decimal = pytest.importorskip("decimal")
    decimal.getcontext().prec = 60
    want = float(decimal.Decimal(5) - decimal.Decimal("0.75").sqrt())
    assert rk.nearest_hit(((0, 0.5, 0), (1, 0, 0)), three) == rk.SphereHit(0, want)
    assert rk.nearest_hit(((0, 0.5, 0), (1, 0, 0)), three, t_min=4.2) == rk.SphereHit(2, 4.5)



def test_hand_derived_occlusion(three):
    assert rk.occluded(X, three) and not rk.occluded(X, three, t_max=3.5)
    assert rk.occluded(X, three, t_max=4.0)                  # a root on the bound blocks (closed)
    assert not rk.occluded(X, three, t_min=9.5)
    assert not rk.occluded(((0, 2, 0), (1, 0, 0)), three)    # passes above every sphere
    # Open segments: an end on a sphere does not count by itself.
    assert not rk.occluded_segment((0, 0, 0), (4, 0, 0), three)
    assert rk.occluded_segment((0, 0, 0), (4.5, 0, 0), three)
    assert not rk.occluded_segment((6, 0, 0), (7, 0, 0), three)  # from one sphere's surface to the next's
    assert rk.occluded_segment((6, 0, 0), (7, 0, 0), three, path="exact") is False


def test_invalid_input_is_named(three):
    with pytest.raises(ValueError, match="sphere 1: sphere radius is not positive"):
        rk.SphereSet([[0, 0, 0], [1, 1, 1]], [1.0, -2.0])
    with pytest.raises(ValueError, match="radii"):
        rk.SphereSet([[0, 0, 0]], [1.0, 2.0])
    with pytest.raises(ValueError, match="t_min is greater than t_max"):
        rk.nearest_hit(X, three, t_min=2, t_max=1)
    with pytest.raises(ValueError, match="rule: only meshes have rules, the scene is spheres"):
        rk.occluded(X, three, rule="closed")
    with pytest.raises(ValueError, match="endpoints are equal"):
        rk.occluded_segment((1, 1, 1), (1, 1, 1), three)
    with pytest.raises(TypeError, match="no form for a SphereSet"):
        rk.nearest_hit_naive(X, three)
    with pytest.raises(ValueError, match="the naive loop over planes takes the whole ray"):
        rk.nearest_hit_naive(X, [((1, 0, 0), (1, 0, 0))], t_max=2.0)
    with pytest.raises(TypeError, match="expected a raykernel.Mesh or a raykernel.SphereSet, got list"):
        rk.occluded(X, [1, 2, 3])


def test_the_set_reads_back_and_pickles(three):
    assert len(three) == 3 and three[2] == rk.Sphere((5.0, 0.5, 0.0), 0.5) and three[-1] == three[2]
    assert three.centers.shape == (3, 3) and list(three.radii) == [1.0, 1.0, 0.5]
    again = pickle.loads(pickle.dumps(three))
    assert np.array_equal(again.centers, three.centers) and np.array_equal(again.radii, three.radii)
    assert repr(rk.SphereSet([rk.Sphere((0, 0, 0), 1)])) == "SphereSet(1 sphere)"
    with pytest.raises(IndexError):
        three[3]


def random_scene(rng, m):
    # Centres and radii on a coarse dyadic grid, so that tangencies, shared roots and exact ties are frequent.
    centers = rng.integers(-8, 9, size=(m, 3)) / 4.0
    radii = rng.integers(1, 9, size=m) / 4.0
    return rk.SphereSet(centers, radii)


@pytest.mark.parametrize("m", [5, 40])  # below and above the BVH threshold (8 spheres)
def test_certified_is_the_exact_answer_on_random_scenes(m):
    rng = np.random.default_rng(10 + m)
    spheres = random_scene(rng, m)
    n = 3000
    o = rng.integers(-12, 13, size=(n, 3)) / 4.0
    d = rng.integers(-4, 5, size=(n, 3)) / 2.0
    d[np.all(d == 0, axis=1)] = (1.0, 0.0, 0.0)
    # Rays aimed exactly at a centre, or grazing a sphere along an axis: ties and tangent roots.
    k = np.arange(n // 3)
    d[k] = spheres.centers[k % m] - o[k]
    d[np.all(d == 0, axis=1)] = (0.0, 1.0, 0.0)
    t_min = rng.integers(0, 8, size=n) / 4.0
    t_max = t_min + rng.integers(0, 16, size=n) / 4.0
    t_max[::5] = np.inf
    cert = rk.nearest_hit_batch(o, d, spheres, t_min=t_min, t_max=t_max)
    exact = rk.nearest_hit_batch(o, d, spheres, t_min=t_min, t_max=t_max, path="exact")
    assert np.array_equal(cert.sphere, exact.sphere) and np.array_equal(cert.t, exact.t, equal_nan=True)
    assert (cert.sphere >= 0).sum() > n // 4  # the scene is hit often enough to mean something
    blocked = rk.occluded_batch(o, d, spheres, t_min=t_min, t_max=t_max)
    assert np.array_equal(blocked.occluded, cert.sphere >= 0)
    assert np.array_equal(blocked.occluded, rk.occluded_batch(o, d, spheres, t_min=t_min, t_max=t_max,
                                                              path="exact").occluded)
    for i in range(0, n, 97):  # the scalar forms give the batch's rows
        hit = rk.nearest_hit(((o[i]), (d[i])), spheres, t_min=t_min[i], t_max=t_max[i])
        assert (hit is None) == (cert.sphere[i] < 0)
        if hit is not None:
            assert hit == (cert.sphere[i], cert.t[i])
        assert rk.nearest_hit_exact((o[i], d[i]), spheres, t_min=t_min[i], t_max=t_max[i]) == hit
    q = o + d
    seg = rk.occluded_segment_batch(o, q, spheres)
    assert np.array_equal(seg.occluded, rk.occluded_segment_batch(o, q, spheres, path="exact").occluded)
    for i in range(0, n, 89):
        assert rk.occluded_segment(o[i], q[i], spheres) == seg.occluded[i]


def test_batch_errors_name_the_row_or_mask(three):
    o = np.zeros((4, 3))
    d = np.tile([1.0, 0.0, 0.0], (4, 1))
    d[2] = 0.0
    with pytest.raises(ValueError, match=r"^ray 2: "):
        rk.nearest_hit_batch(o, d, three)
    masked = rk.nearest_hit_batch(o, d, three, errors="mask")
    assert list(masked.valid) == [True, True, False, True] and list(masked.sphere) == [0, 0, -1, 0]
    assert math.isnan(masked.t[2])
    with pytest.raises(ValueError, match="stats: only for planes"):
        rk.nearest_hit_batch(o, d, three, stats=True)

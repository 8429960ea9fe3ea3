"""Rays with an interval, shadow rays, segments and all hits from Python over arrays (docs/contract.md §8):
all_hits, occluded_batch, occluded_segment_batch and crossings_batch against the scalar forms and the exact path,
with hand-derived cases on the octahedron |x| + |y| + |z| = 1, per-ray intervals, and bad rows."""
import numpy as np
import pytest

import raykernel as rk

OCTAHEDRON_V = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=np.float64)
OCTAHEDRON_T = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])


@pytest.fixture(scope="module")
def octahedron():
    return rk.Mesh(OCTAHEDRON_V, OCTAHEDRON_T)


def test_all_hits_hand_derived(octahedron):
    # From (−2, 1/4, 1/4) along +x: |x| + 1/2 ≤ 1 holds for x in [−1/2, 1/2], so the ray enters at t = 3/2 and
    # leaves at t = 5/2. With outward normals den = d·N is negative entering and positive leaving: crossings
    # −1 + 1 = 0.
    h = rk.all_hits(((-2, 0.25, 0.25), (1, 0, 0)), octahedron)
    assert [x.t for x in h.hits] == [1.5, 2.5]
    assert h.crossings == 0
    # The interval [0, 2] keeps only the entry: one crossing.
    h = rk.all_hits(((-2, 0.25, 0.25), (1, 0, 0)), octahedron, t_max=2.0)
    assert [x.t for x in h.hits] == [1.5] and h.crossings == -1
    # Exact agrees.
    assert rk.all_hits(((-2, 0.25, 0.25), (1, 0, 0)), octahedron, path="exact").crossings == 0


def test_batches_are_the_scalar_forms(octahedron):
    rng = np.random.default_rng(4)
    n = 400
    origins = rng.integers(-16, 17, size=(n, 3)) / 8.0
    directions = rng.integers(-4, 5, size=(n, 3)) / 4.0
    directions[np.all(directions == 0, axis=1)] = (1, 0, 0)
    t_max = rng.integers(0, 9, size=n) / 4.0
    occ = rk.occluded_batch(origins, directions, octahedron, t_max=t_max)
    occ_exact = rk.occluded_batch(origins, directions, octahedron, t_max=t_max, path="exact")
    cr = rk.crossings_batch(origins, directions, octahedron, t_max=t_max, threads=2)
    for i in range(n):
        ray = (origins[i], directions[i])
        assert occ.occluded[i] == rk.occluded(ray, octahedron, t_max=t_max[i])
        h = rk.all_hits(ray, octahedron, t_max=t_max[i])
        assert cr.hits[i] == len(h.hits) and cr.crossings[i] == h.crossings
    assert (occ.occluded == occ_exact.occluded).all()
    assert (occ.occluded == (cr.hits > 0)).all()
    # Rays from outside the octahedron's box to infinity: every crossing count is 0 (no leak).
    far = rk.crossings_batch(origins * 0 + (3, 0.125, 0.0625), directions, octahedron)
    assert (far.crossings == 0).all()


def test_segment_batch(octahedron):
    p = np.array([[-2, 0, 0], [-2, 0, 0], [0, 0, 0], [0.5, 0.5, 0]])
    q = np.array([[2, 0, 0], [-1.5, 0, 0], [0.25, 0, 0], [2, 2, 0]])
    got = rk.occluded_segment_batch(p, q, octahedron)
    # Through the mesh; short of it; inside it; from the surface point (½, ½, 0) outwards (the endpoint never counts).
    assert got.occluded.tolist() == [True, False, False, False]
    for i in range(len(p)):
        assert got.occluded[i] == rk.occluded_segment(p[i], q[i], octahedron)


def test_bad_rows(octahedron):
    o = np.array([[0, 0, 5], [0, 0, 5]], dtype=np.float64)
    d = np.array([[0, 0, -1], [0, 0, 0]], dtype=np.float64)
    with pytest.raises(ValueError, match="ray 1:"):
        rk.occluded_batch(o, d, octahedron)
    masked = rk.occluded_batch(o, d, octahedron, errors="mask")
    assert masked.valid.tolist() == [True, False] and masked.occluded.tolist() == [True, False]
    with pytest.raises(ValueError, match="ray 0: .*t_min"):
        rk.crossings_batch(o[:1], d[:1], octahedron, t_min=3.0, t_max=1.0)
    with pytest.raises(ValueError, match="segment 0:"):
        rk.occluded_segment_batch([[1, 1, 1]], [[1, 1, 1]], octahedron)
    with pytest.raises(ValueError):
        rk.occluded_batch(o, d[:1], octahedron)

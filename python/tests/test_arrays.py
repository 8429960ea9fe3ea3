"""The vectorized API: the same answers as the scalar one, bit for bit, for every memory layout; invalid rows;
errors; the GIL released."""

import threading
import time

import numpy as np
import pytest

import raykernel as rk
from raykernel._raykernel import testkit

KINDS = list(testkit.QUERY_KINDS)


def same_bits(a, b) -> bool:
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and bool((a.view(np.uint64) == b.view(np.uint64)).all())


def scalar_answers(f, o, d, p, n):
    out = [f((o[i], d[i]), (p[i], n[i])) for i in range(len(o))]
    return np.array([x.relation.code for x in out], dtype=np.uint8), np.array([x.t for x in out])


@pytest.fixture(scope="module")
def hard():
    """3,900 hard queries, 300 of each kind (make_query_arrays: testkit's constructions, seeded)."""
    o, d, p, n, kind = testkit.make_query_arrays(KINDS, 3900, 17)
    assert set(np.unique(kind)) == set(range(len(KINDS)))
    return o, d, p, n


@pytest.mark.parametrize("path, scalar", [("certified", rk.intersect), ("exact", rk.intersect_exact),
                                          ("naive", rk.intersect_naive)])
def test_batch_equals_scalar_bit_for_bit(hard, path, scalar):
    o, d, p, n = hard
    got = rk.intersect_batch(o, d, p, n, path=path)
    relation, t = scalar_answers(scalar, o, d, p, n)
    assert (got.relation == relation).all() and same_bits(got.t, t) and got.valid.all()
    assert got.relation.dtype == np.uint8 and got.t.dtype == np.float64 and got.valid.dtype == np.bool_


def test_certified_equals_exact_on_hard_queries(hard):
    c, e = rk.intersect_batch(*hard), rk.intersect_batch(*hard, path="exact")
    assert (c.relation == e.relation).all() and same_bits(c.t, e.t)


def test_every_layout_gives_the_same_answers(hard):
    o, d, p, n = (a[:1000] for a in hard)
    reference = rk.intersect_batch(o, d, p, n)
    layouts = {
        "fortran": lambda a: np.asfortranarray(a),
        "soa.T": lambda a: np.ascontiguousarray(a.T).T,  # a (3, n) structure of arrays, seen as (n, 3)
        "strided": lambda a: np.repeat(a, 2, axis=0)[::2],
        "lists": lambda a: a.tolist(),
    }
    for name, f in layouts.items():
        got = rk.intersect_batch(f(o), f(d), f(p), f(n))
        assert (got.relation == reference.relation).all() and same_bits(got.t, reference.t), name


def test_large_row_major_arrays_are_answered_in_chunks(hard):
    # More rows than one gathered chunk (2^16): row-major input goes through the batch API chunk by chunk.
    o, d, p, n = (np.tile(a, (45, 1)) for a in hard)  # 175,500 queries, C order
    assert not o.flags.f_contiguous
    row_major = rk.intersect_batch(o, d, p, n, stats=True)
    column_major = rk.intersect_batch(*(np.asfortranarray(a) for a in (o, d, p, n)), stats=True)
    assert (row_major.relation == column_major.relation).all() and same_bits(row_major.t, column_major.t)
    assert row_major.stats == column_major.stats
    tiled = rk.intersect_batch(*hard)
    assert same_bits(row_major.t, np.tile(tiled.t, 45))
    planes = rk.PlaneSet(hard[2][:3], hard[3][:3])
    a, b = rk.nearest_hit_batch(o, d, planes), rk.nearest_hit_batch(np.asfortranarray(o), np.asfortranarray(d), planes)
    assert (a.plane == b.plane).all() and same_bits(a.t, b.t)


def test_one_plane_against_many_rays(hard):
    o, d = hard[0][:500], hard[1][:500]
    plane = ((0.25, -1.5, 3.0), (1.0, 2.0**-40, -3.0))
    got = rk.intersect_batch(o, d, plane[0], plane[1])
    relation, t = scalar_answers(rk.intersect, o, d, [plane[0]] * 500, [plane[1]] * 500)
    assert (got.relation == relation).all() and same_bits(got.t, t)


def test_invalid_rows_raise_naming_the_row_or_are_masked(hard):
    o, d, p, n = (a[:50].copy() for a in hard)
    d[17] = 0.0
    n[30, 1] = np.nan
    for path in ("certified", "exact", "naive"):
        with pytest.raises(rk.InvalidInput, match="^query 17: ray direction is the zero vector$"):
            rk.intersect_batch(o, d, p, n, path=path)
        got = rk.intersect_batch(o, d, p, n, path=path, errors="mask")
        assert list(np.flatnonzero(~got.valid)) == [17, 30]
        assert (got.relation[[17, 30]] == rk.INVALID_RELATION_CODE).all() and np.isnan(got.t[[17, 30]]).all()
        keep = got.valid
        relation, t = scalar_answers(rk.intersect if path != "naive" else rk.intersect_naive,
                                     o[keep], d[keep], p[keep], n[keep])
        assert (got.relation[keep] == relation).all() and same_bits(got.t[keep], t)
        assert list(got.relations()[[0, 17]]) == [rk.Relation.from_code(got.relation[0]).value, "invalid"]
    with pytest.raises(rk.InvalidInput, match="^ray 17: ray direction is the zero vector$"):
        rk.intersect_batch(o, d, (0, 0, 0), (1, 0, 0))


def test_shapes_and_arguments_are_checked():
    z = np.zeros((4, 3))
    with pytest.raises(ValueError, match=r"^origins: expected an array of shape \(n, 3\), got shape \(4, 2\)$"):
        rk.intersect_batch(np.zeros((4, 2)), z, z, z)
    with pytest.raises(ValueError, match="^directions has 5 rows, origins has 4$"):
        rk.intersect_batch(z, np.zeros((5, 3)), z, z)
    with pytest.raises(ValueError, match="^points and normals: give both"):
        rk.intersect_batch(z, z, (0, 0, 0), z)
    with pytest.raises(TypeError, match="^normals: expected"):
        rk.intersect_batch(z, z, z, "abc")
    with pytest.raises(ValueError, match="^path: expected"):
        rk.intersect_batch(z, z, z, z, path="fast")
    with pytest.raises(ValueError, match="^errors: expected"):
        rk.intersect_batch(z, z, z, z, errors="ignore")
    with pytest.raises(ValueError, match="^stats: only the certified path"):
        rk.intersect_batch(z, z, z, z, path="exact", stats=True)
    empty = rk.intersect_batch(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)))
    assert empty.relation.shape == empty.t.shape == empty.valid.shape == (0,)


def test_threads_and_stats(hard):
    o, d, p, n = (np.tile(a, (10, 1)) for a in hard)  # 39,000 queries: enough to be split over threads
    one = rk.intersect_batch(o, d, p, n, threads=1, stats=True)
    many = rk.intersect_batch(o, d, p, n, threads=4, stats=True)
    assert (one.relation == many.relation).all() and same_bits(one.t, many.t)
    assert one.stats == many.stats
    assert sum(one.stats["relation"].values()) == len(o)
    assert set(one.stats["relation"]) == {"filter", "compensated", "expansion", "exact"}
    with_t = int(((one.relation == 0) | (one.relation == 1)).sum())
    assert sum(one.stats["t"].values()) == with_t


def test_nearest_hit_batch_equals_scalar(hard):
    o, d = hard[0][:400], hard[1][:400]
    planes = rk.PlaneSet(hard[2][:25], hard[3][:25])
    for path, scalar in (("certified", rk.nearest_hit), ("exact", rk.nearest_hit_exact), ("naive", rk.nearest_hit_naive)):
        got = rk.nearest_hit_batch(o, d, planes, path=path)
        want = [scalar((o[i], d[i]), planes) for i in range(len(o))]
        assert list(got.plane) == [-1 if h is None else h.plane for h in want], path
        assert same_bits(got.t, [np.nan if h is None else h.t for h in want]), path
    as_list = rk.nearest_hit_batch(o, d, [planes[k] for k in range(25)])
    assert as_list.plane.tolist() == rk.nearest_hit_batch(o, d, planes).plane.tolist()


def test_nearest_hit_batch_invalid_rays_and_planes(hard):
    o, d = hard[0][:40].copy(), hard[1][:40].copy()
    planes = rk.PlaneSet(hard[2][:5], hard[3][:5])
    o[9, 2] = np.inf
    with pytest.raises(rk.InvalidInput, match=r"^ray 9: ray origin z is \+inf$"):
        rk.nearest_hit_batch(o, d, planes)
    got = rk.nearest_hit_batch(o, d, planes, errors="mask", stats=True)
    assert list(np.flatnonzero(~got.valid)) == [9] and got.plane[9] == -1 and np.isnan(got.t[9])
    keep = np.flatnonzero(got.valid)
    want = [rk.nearest_hit((o[i], d[i]), planes) for i in keep]
    assert list(got.plane[keep]) == [-1 if h is None else h.plane for h in want]
    assert sum(got.stats["relation"].values()) == len(keep)
    with pytest.raises(rk.InvalidInput, match="^plane 1: plane normal is the zero vector$"):
        rk.nearest_hit_batch(o, d, [planes[0], ((0, 0, 0), (0, 0, 0))])


def longest_pause_of_this_thread_while(work) -> tuple:
    """Runs work() on another thread and spins here meanwhile: (the longest gap between two iterations of
    this thread's loop, counted from the start, and the total time). A call that holds the GIL stops this
    thread for its whole length."""
    done = threading.Event()

    def run():
        work()
        done.set()

    worker = threading.Thread(target=run)
    begin = last = time.perf_counter()
    longest = 0.0
    worker.start()
    while not done.is_set():
        now = time.perf_counter()
        longest, last = max(longest, now - last), now
    worker.join()
    end = time.perf_counter()
    return max(longest, end - last), end - begin


def test_the_gil_is_released_during_a_batch(hard):
    o, d, p, n = (np.tile(a, (20, 1)) for a in hard)  # 78,000 exact queries: a fraction of a second
    longest, total = longest_pause_of_this_thread_while(lambda: rk.intersect_batch(o, d, p, n, path="exact", threads=1))
    assert total > 0.05, "the batch was too short to tell"
    assert longest < total / 4, f"this thread stopped for {longest:.3f} s of a {total:.3f} s batch"
    # The check itself can fail: a builtin that holds the GIL (sum over a range, in C) stops this thread.
    longest, total = longest_pause_of_this_thread_while(lambda: sum(range(10**7)))
    assert longest > total / 2

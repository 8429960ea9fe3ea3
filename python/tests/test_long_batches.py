"""Long batches: Ctrl-C stops them (KeyboardInterrupt, raised once their threads have joined), and an optional
progress callback sees (done, total) as they go; an exception from the callback stops them too."""

import os
import pathlib
import signal
import threading
import time

import numpy as np
import pytest

import raykernel as rk

SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes"


@pytest.fixture(scope="module")
def long_batch():
    """Rays at the icosphere-3 mesh whose exact path (every triangle in rationals) takes many seconds."""
    mesh = rk.load_mesh(SCENES / "icosphere-3.ply")
    rng = np.random.default_rng(7)
    origins = rng.normal(size=(100_000, 3)) * 3
    return origins, -origins, mesh


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals go to the main thread")
def test_ctrl_c_stops_a_long_batch_soon(long_batch):
    origins, directions, mesh = long_batch
    fired = []

    def interrupt():
        fired.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(0.3, interrupt)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            rk.nearest_hit_batch(origins, directions, mesh, path="exact")
        stopped = time.monotonic()
    finally:
        timer.cancel()
    # The whole batch takes minutes (about 5 ms a row on 2 threads); it stops within a row or two of the signal
    # (measured: about 0.03 s). The bound is loose so that a loaded machine does not fail it.
    assert fired and stopped - fired[0] < 2.0


def test_progress_sees_every_row_and_its_exception_stops_the_batch(long_batch):
    origins, directions, mesh = long_batch
    seen = []
    n = 300  # about a second on the exact path
    answers = rk.nearest_hit_batch(origins[:n], directions[:n], mesh, path="exact",
                                   progress=lambda done, total: seen.append((done, total)))
    assert seen[-1] == (n, n) and all(total == n for _, total in seen)
    assert all(a <= b for (a, _), (b, _) in zip(seen, seen[1:])) and len(seen) >= 2
    # The answers are the batch's without a callback (the certified path's: the same, by the contract).
    plain = rk.nearest_hit_batch(origins[:n], directions[:n], mesh)
    assert np.array_equal(answers.triangle, plain.triangle) and np.array_equal(answers.t, plain.t, equal_nan=True)

    class Enough(Exception):
        pass

    def stop(done, total):
        raise Enough(f"{done} of {total}")

    start = time.monotonic()
    with pytest.raises(Enough):
        rk.inside_batch(origins, mesh, path="exact", progress=stop)
    assert time.monotonic() - start < 30  # the whole batch takes minutes

    with pytest.raises(TypeError, match="progress: expected None or a callable"):
        rk.intersect_sphere_batch(origins[:10], directions[:10], (0, 0, 0), 1.0, progress=3)


@pytest.mark.parametrize("call", ["intersect_batch", "relation_batch", "intersect_triangle_batch",
                                  "relation_triangle_batch", "intersect_sphere_batch", "nearest_hit_batch",
                                  "inside_batch"])
def test_every_batch_calls_progress_at_the_end(long_batch, call):
    """Every batch that answers rows one by one (all but the certified ray–plane batch, one vectorized call)."""
    origins, directions, mesh = long_batch
    n = 2_000
    o, d = origins[:n], directions[:n]
    arguments = {
        "intersect_batch": (o, d, (0, 0, 0), (0, 0, 1)),
        "relation_batch": (o, d, (0, 0, 0), (0, 0, 1)),
        "intersect_triangle_batch": (o, d, (0, 0, 0), (1, 0, 0), (0, 1, 0)),
        "relation_triangle_batch": (o, d, (0, 0, 0), (1, 0, 0), (0, 1, 0)),
        "intersect_sphere_batch": (o, d, (0, 0, 0), 1.0),
        "nearest_hit_batch": (o, d, mesh),
        "inside_batch": (o, mesh),
    }[call]
    seen = []
    path = "certified" if call in ("nearest_hit_batch", "inside_batch") else "exact"  # the mesh's exact path is slow
    getattr(rk, call)(*arguments, path=path, progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1] == (n, n)

#!/usr/bin/env python3
"""raykernel.dask on this machine: its overhead over the plain batch call, and its scaling over worker processes.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_dask.py [--rays 10000000] [--repeat 3]

The query is the exact nearest hit on scenes/icosphere-3.ply (rk.nearest_hit_batch, owned rule) for rays from
points around the mesh towards the centre, 10^6 rays per chunk. Each figure is the best of --repeat runs, in
wall time (run it alone: no build, test or other benchmark beside it):

  plain batch, 2 threads       rk.nearest_hit_batch(o, d, mesh): all cores, the baseline
  dask threaded, 2 threads     raykernel.dask.nearest_hit_batch on da.from_array(o) (no copy), computed with Dask's
                               threaded scheduler (2 threads, one chunk each at a time, threads=1 per chunk) by
                               raykernel.dask.compute (each chunk's answer written into place as it is done);
                               overhead = its time / the plain batch's − 1
  dask.compute, 2 threads      the same computed by dask.compute(*fields) (the chunks concatenated at the end)
  cluster, 1 process           a distributed.LocalCluster of 1 worker process (1 thread); the rays are generated
                               on the workers, one task per chunk, so no array crosses processes
  cluster, 2 processes         the same on 2 worker processes (1 thread each); scaling = 1 process / 2 processes

This is a measurement script, not a test: it prints a table (bench/README.md has the figures of one run).
"""

import argparse
import pathlib
import time

import dask
import dask.array as da
import numpy as np

import raykernel as rk
import raykernel.dask as rkd

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHUNK = 1_000_000  # 10 chunks of 10^7 rays: 5 per thread or worker


def best(repeat, run):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def _ray_block(block, seed):
    """The rays of one chunk, made where the chunk is computed: origins at distance ~3, directions to the centre."""
    rng = np.random.default_rng([seed, int(block[0])])
    origins = rng.normal(size=(CHUNK, 6))
    origins[:, :3] *= 3
    origins[:, 3:] = origins[:, 3:] * 0.2 - origins[:, :3]
    return origins


def rays(n, seed):
    """n rays as Dask arrays of CHUNK rows, each chunk one task (origins and directions made together, so that the
    query's inputs never cross processes)."""
    blocks = -(-n // CHUNK)
    both = da.map_blocks(_ray_block, da.arange(blocks, chunks=1), seed, dtype=np.float64, chunks=((CHUNK,) * blocks, (6,)),
                         new_axis=1)[:n]
    return both[:, :3], both[:, 3:]


def cluster_time(workers, mesh, n, repeat):
    import distributed

    with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        o, d = rays(n, 1)

        def run():
            hits = rkd.nearest_hit_batch(o, d, mesh)
            # A reduction per chunk, so that the answers stay on the workers (as an audit would: counts, sums).
            client.compute([(hits.triangle >= 0).sum(), da.nansum(hits.t)], sync=True)

        run()  # warm up: the workers import raykernel and receive the mesh
        return best(repeat, run)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rays", type=int, default=10_000_000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    n = args.rays
    mesh = rk.load_mesh(ROOT / "scenes" / "icosphere-3.ply")
    print(f"{n} rays, nearest hit on icosphere-3.ply ({len(mesh)} triangles), chunks of {CHUNK} rays, best of "
          f"{args.repeat}", flush=True)

    o, d = dask.compute(*rays(n, 1), scheduler="threads")
    plain = best(args.repeat, lambda: rk.nearest_hit_batch(o, d, mesh, threads=2))
    print(f"  plain batch, 2 threads      {plain:8.3f} s  {n / plain / 1e6:6.2f} M rays/s", flush=True)

    lazy_o = da.from_array(o, chunks=(CHUNK, 3))

    local = best(args.repeat, lambda: rkd.compute(rkd.nearest_hit_batch(lazy_o, d, mesh), scheduler="threads",
                                                  num_workers=2))
    print(f"  dask threaded, 2 threads    {local:8.3f} s  {n / local / 1e6:6.2f} M rays/s  overhead "
          f"{100 * (local / plain - 1):+.1f}%", flush=True)

    def concatenated():
        dask.compute(*[f for f in rkd.nearest_hit_batch(lazy_o, d, mesh) if f is not None], scheduler="threads",
                     num_workers=2)

    joined = best(args.repeat, concatenated)
    print(f"  dask.compute, 2 threads     {joined:8.3f} s  {n / joined / 1e6:6.2f} M rays/s  overhead "
          f"{100 * (joined / plain - 1):+.1f}%", flush=True)

    one = cluster_time(1, mesh, n, args.repeat)
    print(f"  cluster, 1 process          {one:8.3f} s  {n / one / 1e6:6.2f} M rays/s", flush=True)
    two = cluster_time(2, mesh, n, args.repeat)
    print(f"  cluster, 2 processes        {two:8.3f} s  {n / two / 1e6:6.2f} M rays/s  scaling {one / two:.2f}x",
          flush=True)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Vectorized throughput of raykernel's Python API against the C++ batch API, on the same kinds of queries.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_throughput.py [--cpp build/bin/raykernel_bench]

Workloads (2^20 queries each, as bench/workloads.hpp builds them): `random` (testkit's "random" kind, every
component uniform in [-1, 1]) and `degenerate` (testkit's near-parallel and near-coplanar kinds, half each).
Measured in queries per second, best of --repeat runs, counting time as Google Benchmark does by default: the
CPU time of the calling thread (so a loaded machine does not distort the numbers, and a batch split over
threads is counted by the share its calling thread runs, exactly as raykernel_bench counts the C++ batch):

  python batch (C order)   rk.intersect_batch on (n, 3) row-major arrays: the columns are gathered first
  python batch (F order)   the same arrays in column-major order (e.g. soa.T): read in place, no copy
  python batch, 1 thread   F order, threads=1: all the work on the calling thread
  C++ batch                raykernel_bench's intersect/batch_certified/<workload> (Google Benchmark, the same
                           intersect_batch over SoA vectors, all cores), run from this script when --cpp is given
  numpy naive              the textbook formula in NumPy (python/examples/numpy_ray_plane.py): no guarantee
  python scalar loop       rk.intersect called once per query from Python (2^14 queries), for the call overhead

This is a measurement script, not a test: it prints a table (and --json writes one).
"""

import argparse
import json
import pathlib
import subprocess
import sys
import time

import numpy as np

import raykernel as rk
from raykernel._raykernel import testkit

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "examples"))
from numpy_ray_plane import ray_plane  # noqa: E402

WORKLOADS = {"random": ["random"], "degenerate": ["near-parallel", "near-coplanar"]}


def best_rate(f, n: int, repeat: int) -> float:
    f()  # warm up (page faults, thread start)
    best = min(_timed(f) for _ in range(repeat))
    return n / best


def _timed(f) -> float:
    begin = time.thread_time()
    f()
    return time.thread_time() - begin


def cpp_rates(binary: str) -> dict:
    out = subprocess.run(
        [binary, "--benchmark_filter=^intersect/batch_certified/(random|degenerate)$", "--benchmark_format=json",
         "--benchmark_min_time=0.5"],
        capture_output=True, text=True, check=True).stdout
    return {b["name"].split("/")[-1]: b["items_per_second"] for b in json.loads(out)["benchmarks"]}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=1 << 20)
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--cpp", help="raykernel_bench binary for the C++ batch numbers")
    parser.add_argument("--json", help="write the results to this file")
    args = parser.parse_args()

    results = {}
    cpp = cpp_rates(args.cpp) if args.cpp else {}
    for name, kinds in WORKLOADS.items():
        o, d, p, n, _ = testkit.make_query_arrays(kinds, args.size, 1)
        of, df, pf, nf = (np.asfortranarray(a) for a in (o, d, p, n))
        expected = rk.intersect_batch(of, df, pf, nf)
        assert (rk.intersect_batch(o, d, p, n).t.view(np.uint64) == expected.t.view(np.uint64)).all()
        row = {
            "python batch (C order)": best_rate(lambda: rk.intersect_batch(o, d, p, n), args.size, args.repeat),
            "python batch (F order)": best_rate(lambda: rk.intersect_batch(of, df, pf, nf), args.size, args.repeat),
            "python batch, 1 thread": best_rate(lambda: rk.intersect_batch(of, df, pf, nf, threads=1), args.size,
                                                args.repeat),
            "numpy naive": best_rate(lambda: ray_plane(o, d, p, n), args.size, args.repeat),
        }
        if name in cpp:
            row["C++ batch"] = cpp[name]
        m = 1 << 14
        rays = [((tuple(o[i]), tuple(d[i])), (tuple(p[i]), tuple(n[i]))) for i in range(m)]
        row["python scalar loop"] = best_rate(lambda: [rk.intersect(r, pl) for r, pl in rays], m, 3)
        results[name] = row

    columns = list(WORKLOADS)
    labels = list(dict.fromkeys(k for row in results.values() for k in row))
    print(f"{'million queries/s':<26}" + "".join(f"{c:>14}" for c in columns))
    for label in labels:
        print(f"{label:<26}" + "".join(f"{results[c].get(label, float('nan')) / 1e6:>14.1f}" for c in columns))
    if cpp:
        for c in columns:
            ratio = results[c]["python batch (F order)"] / results[c]["C++ batch"]
            print(f"python (F order) / C++ batch on {c}: {ratio:.2f}")
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(results, indent=2))


if __name__ == "__main__":
    main()

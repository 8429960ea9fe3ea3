#!/usr/bin/env python3
"""Vectorized throughput of raykernel's Python API against the C++ batch API, on the same kinds of queries.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_throughput.py [--cpp build/bin/raykernel_bench]

Workloads (2^20 queries each, as bench/workloads.hpp builds them): `random` (testkit's "random" kind, every
component uniform in [-1, 1]) and `degenerate` (testkit's near-parallel and near-coplanar kinds, half each).
Measured in queries per second, best of --repeat runs. Ray–plane batches count wall time, as raykernel_bench
counts its batch benchmarks (…/real_time: a batch split over threads is counted by its elapsed time); the
one-thread rows, the NumPy code, the scalar loops and all the ray–triangle rows count the CPU time of the
calling thread, as Google Benchmark does by default for raykernel_bench's triangle/* loops (so a loaded
machine distorts them less):

  python batch (C order)   rk.intersect_batch on (n, 3) row-major arrays: the columns are gathered first
  python batch (F order)   the same arrays in column-major order (e.g. soa.T): read in place, no copy
  python batch, 1 thread   F order, threads=1: all the work on the calling thread
  C++ batch                raykernel_bench's intersect/batch_certified/<workload> (Google Benchmark, the same
                           intersect_batch over SoA vectors, all cores), run from this script when --cpp is given
  numpy naive              the textbook formula in NumPy (python/examples/numpy_ray_plane.py): no guarantee
  python scalar loop       rk.intersect called once per query from Python (2^14 queries), for the call overhead

Ray–triangle (--triangles; 2^18 queries each): `random` (testkit's "random" kind) and `degenerate` (through and
near vertices and edges, slivers, needles: the kinds of raykernel_bench's triangle/*/degenerate):

  python triangle batch (C order) / (F order) / 1 thread
                           rk.intersect_triangle_batch (owned rule, t and barycentric coordinates), as above
  python triangle relation, 1 thread
                           rk.relation_triangle_batch, threads=1: nothing rounded
  C++ scalar loop          raykernel_bench's triangle/certified/<workload> and triangle/relation/<workload>:
                           intersect / relation called in a C++ loop on one thread (the kernel has no
                           ray–triangle batch API; the Python batch runs the same loop, split over threads)
  numpy Moller-Trumbore    python/examples/numpy_moller_trumbore.py: no guarantee

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
from numpy_moller_trumbore import moller_trumbore  # noqa: E402
from numpy_ray_plane import ray_plane  # noqa: E402

WORKLOADS = {"random": ["random"], "degenerate": ["near-parallel", "near-coplanar"]}


def best_rate(f, n: int, repeat: int, clock=time.thread_time) -> float:
    f()  # warm up (page faults, thread start)
    best = min(_timed(f, clock) for _ in range(repeat))
    return n / best


def wall_rate(f, n: int, repeat: int) -> float:
    return best_rate(f, n, repeat, time.perf_counter)


def _timed(f, clock) -> float:
    begin = clock()
    f()
    return clock() - begin


def cpp_rates(binary: str) -> dict:
    out = subprocess.run(
        [binary, "--benchmark_filter=^intersect/batch_certified/(random|degenerate)/real_time$", "--benchmark_format=json",
         "--benchmark_min_time=0.5"],
        capture_output=True, text=True, check=True).stdout
    return {b["name"].split("/")[2]: b["items_per_second"] for b in json.loads(out)["benchmarks"]}


TRIANGLE_WORKLOADS = {
    "random": ["random"],
    "degenerate": ["through-vertex", "through-edge", "near-vertex", "near-edge", "sliver", "needle"],
}


def cpp_triangle_rates(binary: str) -> dict:
    out = subprocess.run(
        [binary, "--benchmark_filter=^triangle/(certified|relation)/(random|degenerate)$",
         "--benchmark_format=json", "--benchmark_min_time=0.5"],
        capture_output=True, text=True, check=True).stdout
    return {b["name"]: b["items_per_second"] for b in json.loads(out)["benchmarks"]}


def triangle_results(size: int, repeat: int, cpp_binary) -> dict:
    cpp = cpp_triangle_rates(cpp_binary) if cpp_binary else {}
    results = {}
    for name, kinds in TRIANGLE_WORKLOADS.items():
        o, d, a, b, c, _ = testkit.make_triangle_query_arrays(kinds, size, 1)
        fortran = [np.asfortranarray(x) for x in (o, d, a, b, c)]
        batch = rk.intersect_triangle_batch
        row = {
            "python triangle batch (C order)": best_rate(lambda: batch(o, d, a, b, c), size, repeat),
            "python triangle batch (F order)": best_rate(lambda: batch(*fortran), size, repeat),
            "python triangle batch, 1 thread": best_rate(lambda: batch(*fortran, threads=1), size, repeat),
            "python triangle relation, 1 thread": best_rate(
                lambda: rk.relation_triangle_batch(*fortran, threads=1), size, repeat),
            "numpy Moller-Trumbore": best_rate(lambda: moller_trumbore(o, d, a, b, c), size, repeat),
        }
        if f"triangle/certified/{name}" in cpp:
            row["C++ scalar loop (intersect)"] = cpp[f"triangle/certified/{name}"]
            row["C++ scalar loop (relation)"] = cpp[f"triangle/relation/{name}"]
        m = 1 << 13
        queries = [((tuple(o[i]), tuple(d[i])), (tuple(a[i]), tuple(b[i]), tuple(c[i]))) for i in range(m)]
        row["python scalar loop"] = best_rate(lambda: [rk.intersect(r, t) for r, t in queries], m, 3)
        results[name] = row
    return results


def print_table(results: dict) -> None:
    columns = list(results)
    labels = list(dict.fromkeys(k for row in results.values() for k in row))
    print(f"{'million queries/s':<36}" + "".join(f"{c:>14}" for c in columns))
    for label in labels:
        print(f"{label:<36}" + "".join(f"{results[c].get(label, float('nan')) / 1e6:>14.2f}" for c in columns))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=1 << 20)
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--cpp", help="raykernel_bench binary for the C++ batch numbers")
    parser.add_argument("--json", help="write the results to this file")
    parser.add_argument("--triangles", action="store_true", help="measure ray–triangle instead of ray–plane")
    args = parser.parse_args()

    if args.triangles:
        results = triangle_results(args.size if args.size != 1 << 20 else 1 << 18, args.repeat, args.cpp)
        print_table(results)
        for c, row in results.items():
            if "C++ scalar loop (intersect)" in row:
                print(f"python batch, 1 thread / C++ loop (intersect) on {c}: "
                      f"{row['python triangle batch, 1 thread'] / row['C++ scalar loop (intersect)']:.2f}; "
                      f"relation: {row['python triangle relation, 1 thread'] / row['C++ scalar loop (relation)']:.2f}")
        if args.json:
            pathlib.Path(args.json).write_text(json.dumps(results, indent=2))
        return

    results = {}
    cpp = cpp_rates(args.cpp) if args.cpp else {}
    for name, kinds in WORKLOADS.items():
        o, d, p, n, _ = testkit.make_query_arrays(kinds, args.size, 1)
        of, df, pf, nf = (np.asfortranarray(a) for a in (o, d, p, n))
        expected = rk.intersect_batch(of, df, pf, nf)
        assert (rk.intersect_batch(o, d, p, n).t.view(np.uint64) == expected.t.view(np.uint64)).all()
        row = {
            "python batch (C order)": wall_rate(lambda: rk.intersect_batch(o, d, p, n), args.size, args.repeat),
            "python batch (F order)": wall_rate(lambda: rk.intersect_batch(of, df, pf, nf), args.size, args.repeat),
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

#!/usr/bin/env python3
"""Runs raykernel_bench once and prints the tables of bench/README.md: ns per query for each path and workload,
the goal ratios (all from this one run on this one machine), and the certified path's fallback rates.

  bench/report.py [BUILD_DIR] [--min-time SECONDS] [--json FILE]     (python3 standard library only)

--json FILE reads a saved run (raykernel_bench --benchmark_format=json) instead of running the benchmarks.
"""
import json
import re
import os
import platform
import subprocess
import sys

FILTER = "^(intersect|relation|memory|nearest|render|triangle)/"


def run(build, min_time):
    cmd = [os.path.join(build, "bin", "raykernel_bench"), f"--benchmark_filter={FILTER}",
           f"--benchmark_min_time={min_time}", "--benchmark_repetitions=3", "--benchmark_format=json"]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def fmt(v):
    if v is None:
        return "—"
    return f"{v:.1f}" if v < 100 else f"{v:,.0f}"


def table(title, rows, columns, ns, name):
    print(title + "\n")
    print("| path | " + " | ".join(columns) + " |")
    print("|---|" + "---:|" * len(columns))
    for r in rows:
        cells = [fmt(ns.get(name(r, c))) for c in columns]
        if all(c == "—" for c in cells):
            continue
        print(f"| {r} | " + " | ".join(cells) + " |")
    print()


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    build = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build")
    min_time, saved = 1.0, None
    for i, a in enumerate(sys.argv):
        if a == "--min-time":
            min_time = float(sys.argv[i + 1])
        if a == "--json":
            saved = sys.argv[i + 1]
    data = json.load(open(saved)) if saved else run(build, min_time)
    ns, bench = {}, {}
    for b in data["benchmarks"]:
        if "items_per_second" in b and b.get("run_type") != "aggregate" or b.get("aggregate_name") == "median":
            # "intersect/batch_certified/random/real_time" is reported as "intersect/batch_certified/random";
            # with --benchmark_repetitions, the medians.
            name = re.sub(r"(/real_time|/threads:\d+|_median)+$", "", b["name"])
            ns[name] = 1e9 / b["items_per_second"]
            bench[name] = b
    ctx = data["context"]
    print(f"machine: {platform.processor() or ctx.get('host_name', '?')}, {ctx['num_cpus']} cores at "
          f"{ctx['mhz_per_cpu']} MHz, load average {ctx.get('load_avg', '?')}; {ctx['date']}\n")

    workloads = ["random", "random_l2", "wide", "degenerate", "render"]
    table("ns per query, intersection (lower is better):",
          ["naive", "naive_soa", "certified", "certified_scoped", "batch_certified", "exact", "cgal_epeck"], workloads, ns,
          lambda p, w: f"intersect/{p}/{w}")
    table("ns per query, relation only:", ["certified", "certified_scoped", "batch_certified", "cgal_epick"], workloads, ns,
          lambda p, w: f"relation/{p}/{w}")
    print(f"memory floor (reading the random workload's arrays on all threads): "
          f"{fmt(ns.get('memory/read/random'))} ns per query\n")
    table("nearest hit, ns per ray (prepared plane set):", ["naive", "certified", "exact"],
          ["demo4", "demo64", "random4", "random64"], ns, lambda p, s: f"nearest/{p}/{s}")
    table("render of the demo image (1 sample per pixel, 1 thread), ns per pixel; of scenes/octahedron.json "
          "(4 samples per pixel), ns per ray:", ["naive", "certified"], ["demo", "octahedron"],
          ns, lambda p, s: f"render/{p}/{s}")
    table("ray–triangle, ns per query:", ["naive", "relation", "relation_scoped", "certified", "certified_scoped", "exact",
                                         "cgal_epick", "cgal_epeck"],
          ["random", "degenerate"], ns, lambda p, w: f"triangle/{p}/{w}")

    def ratio(a, b):
        return ns[a] / ns[b] if a in ns and b in ns else None

    def throughput_ratio(a, b):  # how many times as many items per second a does as b
        return ns[b] / ns[a] if a in ns and b in ns else None

    # (a, b, limit, aim): a ≤ limit × b in ns per item; a negative limit means a's throughput ≥ |limit| × b's.
    goal_specs = [
        ("relation/certified/random_l2", "intersect/naive/random_l2", 1.3, ""),
        ("relation/certified/random_l2", "relation/cgal_epick/random_l2", -5, ""),
        ("intersect/certified/random_l2", "intersect/naive/random_l2", 4, " (aim 3×)"),
        ("intersect/batch_certified/random", "memory/read/random", 1.25, ""),
        ("intersect/batch_certified/random_l2", "intersect/naive_soa/random_l2", 3, ""),
        ("intersect/certified/degenerate", "intersect/naive/degenerate", 10, ""),
        ("nearest/certified/random64", "nearest/naive/random64", 2.5, ""),
        ("nearest/certified/demo64", "nearest/naive/demo64", 3, ""),
        ("render/certified/demo", "render/naive/demo", 2, ""),
        ("render/certified/octahedron", "render/naive/octahedron", 3, ""),
        ("triangle/relation/random", "triangle/naive/random", 2, ""),
        ("triangle/certified/random", "triangle/naive/random", 10, " (aim 6×)"),
    ]
    # The scalar goals again with the environment check hoisted out of the loop (DefaultFpEnvironment): what
    # the per-call stmxcsr/ldmxcsr costs, and what the goals measure without it.
    scalar = {"relation/certified": "relation/certified_scoped", "intersect/certified": "intersect/certified_scoped",
              "triangle/relation": "triangle/relation_scoped", "triangle/certified": "triangle/certified_scoped"}
    goal_specs += [(scalar[a.rsplit("/", 1)[0]] + "/" + a.rsplit("/", 1)[1], b, limit, aim)
                   for a, b, limit, aim in goal_specs if a.rsplit("/", 1)[0] in scalar]
    goals = []
    for a, b, limit, aim in goal_specs:
        if limit > 0:
            goals.append((f"{a} ≤ {limit:g} × {b}{aim}", ratio(a, b), lambda v, limit=limit: v <= limit))
        else:
            goals.append((f"{a} throughput ≥ {-limit:g} × {b}{aim}", throughput_ratio(a, b),
                          lambda v, limit=limit: v >= -limit))
    print("| goal | measured | met |")
    print("|---|---:|:---:|")
    for text, value, ok in goals:
        if value is not None:
            print(f"| {text} | {value:.2f} | {'yes' if ok(value) else 'no'} |")
    print()

    print("fallback rates of the certified path (fraction of the workload's queries whose relation / t each "
          "stage decided):\n")
    stages = ["filter", "compensated", "expansion", "exact"]
    print("| workload | " + " | ".join(f"rel {s}" for s in stages) + " | " +
          " | ".join(f"t {s}" for s in stages[1:]) + " |")
    print("|---|" + "---:|" * 7)
    for w in workloads:
        b = bench.get(f"intersect/certified/{w}")
        if not b:
            continue
        cells = [b.get(f"rel_{s}", 0) for s in stages] + [b.get(f"t_{s}", 0) for s in stages[1:]]
        print(f"| {w} | " + " | ".join(f"{c:.4g}" for c in cells) + " |")


if __name__ == "__main__":
    main()

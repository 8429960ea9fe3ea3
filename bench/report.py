#!/usr/bin/env python3
"""Runs raykernel_bench once and prints the table of bench/README.md: ns per query per path and workload,
the goal ratios of issue 6, and the fallback rates. All ratios come from one run on one machine.

  bench/report.py [BUILD_DIR] [--min-time SECONDS]      (python3 standard library only)
"""
import json
import os
import platform
import subprocess
import sys


def run(build, min_time):
    cmd = [os.path.join(build, "bin", "raykernel_bench"),
           "--benchmark_filter=^(intersect|nearest)/",
           f"--benchmark_min_time={min_time}",
           "--benchmark_format=json"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    build = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build")
    min_time = 1.0
    for i, a in enumerate(sys.argv):
        if a == "--min-time":
            min_time = float(sys.argv[i + 1])
    data = run(build, min_time)
    ns = {}
    counters = {}
    for b in data["benchmarks"]:
        if "items_per_second" not in b:
            continue
        ns[b["name"]] = 1e9 / b["items_per_second"]
        counters[b["name"]] = b
    ctx = data["context"]
    print(f"machine: {platform.processor() or ctx.get('host_name', '?')}, {ctx['num_cpus']} cores at "
          f"{ctx['mhz_per_cpu']} MHz, load average {ctx.get('load_avg', '?')}; {ctx['date']}\n")

    paths = ["naive", "certified", "batch_certified", "exact", "cgal_epick", "cgal_epeck"]
    workloads = ["random", "wide", "degenerate", "render"]
    print("ns per query (lower is better):\n")
    print("| path | " + " | ".join(workloads) + " |")
    print("|---|" + "---:|" * len(workloads))
    for p in paths:
        cells = []
        for w in workloads:
            v = ns.get(f"intersect/{p}/{w}")
            cells.append("—" if v is None else (f"{v:.1f}" if v < 100 else f"{v:.0f}"))
        print(f"| {p} | " + " | ".join(cells) + " |")
    print()
    print("| nearest hit, ns per ray | 4 planes | 64 planes |")
    print("|---|---:|---:|")
    for p in ["naive", "certified", "exact"]:
        cells = [ns.get(f"nearest/{p}/{k}") for k in (4, 64)]
        print(f"| {p} | " + " | ".join("—" if c is None else f"{c:.0f}" for c in cells) + " |")
    print()

    def ratio(a, b):
        return ns[a] / ns[b] if a in ns and b in ns else float("nan")

    goals = [
        ("certified/random ≤ 1.25 × naive/random", ratio("intersect/certified/random", "intersect/naive/random"), 1.25, "≤"),
        ("batch_certified/random throughput ≥ 2 × naive/random",
         ratio("intersect/naive/random", "intersect/batch_certified/random"), 2.0, "≥"),
        ("certified/degenerate ≤ 10 × naive/degenerate",
         ratio("intersect/certified/degenerate", "intersect/naive/degenerate"), 10.0, "≤"),
        ("certified ≥ 50 × cgal_epeck throughput (random)",
         ratio("intersect/cgal_epeck/random", "intersect/certified/random"), 50.0, "≥"),
        ("certified ≥ 1.5 × cgal_epick throughput (random)",
         ratio("intersect/cgal_epick/random", "intersect/certified/random"), 1.5, "≥"),
    ]
    print("| goal | measured | met |")
    print("|---|---:|:---:|")
    for name, value, target, sense in goals:
        met = value <= target if sense == "≤" else value >= target
        print(f"| {name} | {value:.2f} | {'yes' if met else 'no'} |")
    c = counters.get("intersect/certified/random", {})
    exact_rate = c.get("rel_exact", float("nan")) + c.get("t_exact", 0.0)
    print(f"| exact stage on random < 1e-7 | {exact_rate:.1e} (of {2**20} queries) | "
          f"{'yes' if exact_rate < 1e-7 else 'no'} |")
    print()
    print("fallback rates (fraction of queries whose relation / t each stage decided, certified path):\n")
    print("| workload | rel filter | rel compensated | rel expansion | rel exact | t compensated | t expansion | t exact |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for w in workloads:
        c = counters.get(f"intersect/certified/{w}")
        if not c:
            continue
        keys = ["rel_filter", "rel_compensated", "rel_expansion", "rel_exact", "t_compensated", "t_expansion", "t_exact"]
        print(f"| {w} | " + " | ".join(f"{c.get(k, 0):.4g}" for k in keys) + " |")


if __name__ == "__main__":
    main()

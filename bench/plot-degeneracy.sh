#!/usr/bin/env bash
# Plots the cost of one ray–plane query against how degenerate it is: queries whose ray makes the angle
# 2^-k with the plane, k = 0 .. 100, for the naive, certified and exact paths (bench/degeneracy.png).
#   bench/plot-degeneracy.sh [BUILD_DIR]        (needs gnuplot-nox and python3)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=$here/degeneracy.png
data=$(mktemp)
trap 'rm -f "$data" "$data.json"' EXIT

"$build/bin/raykernel_bench" --benchmark_filter='^sweep/' --benchmark_min_time=0.2 \
  --benchmark_format=json > "$data.json" 2> >(grep -v '^\*\*\*WARNING' >&2)
# One row per k: k, then ns per query for naive, certified, exact (JSON: the CSV reporter cannot mix
# benchmarks with and without counters).
python3 - "$data.json" > "$data" <<'PY'
import json, sys
ns = {}
for b in json.load(open(sys.argv[1]))["benchmarks"]:
    _, path, k = b["name"].split("/")
    ns.setdefault(int(k), {})[path] = 1e9 / b["items_per_second"]
for k in sorted(ns):
    print(k, ns[k]["naive"], ns[k]["certified"], ns[k]["exact"])
PY

gnuplot <<GNUPLOT
set terminal pngcairo size 1000,600 font "DejaVu Sans,11"
set output "$out"
set title "raykernel: cost of a ray–plane query vs. the angle between ray and plane"
set xlabel "k  (angle between ray and plane = 2^{-k})"
set ylabel "ns per query (log scale)"
set logscale y
set grid
set key top left
set xrange [0:100]
plot "$data" using 1:2 with linespoints lw 2 title "naive (plain doubles: wrong near parallel)", \
     "$data" using 1:3 with linespoints lw 2 title "certified (intersect)", \
     "$data" using 1:4 with linespoints lw 2 title "exact (intersect\\\\_exact)"
GNUPLOT
echo "wrote $out"

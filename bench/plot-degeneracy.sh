#!/usr/bin/env bash
# Plots the cost of one ray–plane query against how degenerate it is: queries whose ray makes the angle
# 2^-k with the plane, k = 0 .. 100, for the naive, certified and exact paths (bench/degeneracy.png).
#   bench/plot-degeneracy.sh [BUILD_DIR]        (needs gnuplot: apt-get install gnuplot-nox)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=$here/degeneracy.png
data=$(mktemp)
trap 'rm -f "$data" "$data.csv"' EXIT

"$build/bin/raykernel_bench" --benchmark_filter='^sweep/' --benchmark_min_time=0.2 \
  --benchmark_format=csv > "$data.csv" 2> >(grep -v '^\*\*\*WARNING' >&2)
# CSV: name,iterations,real_time,cpu_time,time_unit,bytes_per_second,items_per_second,...
# One row per k: k, then ns per query for naive, certified, exact.
awk -F, '/^"sweep\// {
    gsub(/"/, "", $1); split($1, part, "/"); path = part[2]; k = part[3];
    ns[k, path] = 1e9 / $7; ks[k] = 1
  }
  END { for (k in ks) printf "%d %g %g %g\n", k, ns[k, "naive"], ns[k, "certified"], ns[k, "exact"] }' \
  "$data.csv" | sort -n > "$data"

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

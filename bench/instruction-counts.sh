#!/usr/bin/env bash
# Instructions per call of the scalar entry points (bench/instruction_counts.cpp), counted by valgrind's
# callgrind: each entry is run with N and 2N calls and the difference divided by N (setup cancels). Also
# prints which multiversioned clone the dynamic loader picked under valgrind (callgrind names it).
#
#   bench/instruction-counts.sh [BUILD_DIR] [ENTRY...]     (default: build, every entry)
set -euo pipefail
build=${1:-build}
shift || true
program="$build/bin/raykernel_instruction_counts"
[ -x "$program" ] || { echo "instruction-counts: build the target raykernel_instruction_counts first ($program)" >&2; exit 2; }
entries=("$@")
if [ ${#entries[@]} -eq 0 ]; then
  entries=(plane/naive/random plane/certified/random plane/relation/random plane/naive/degenerate plane/certified/degenerate
           nearest/certified/random64 sphere/nearest/random64
           triangle/naive/random triangle/certified/random triangle/relation/random
           triangle/naive/degenerate triangle/certified/degenerate triangle/relation/degenerate)
fi
n=${INSTRUCTION_COUNT_CALLS:-20000}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
collected() {  # ENTRY COUNT -> total instructions
  valgrind --tool=callgrind --callgrind-out-file="$out/cg.$2" "$program" "$1" "$2" 2>"$out/log" >/dev/null
  sed -n 's/^==[0-9]*== Collected : \([0-9]*\)$/\1/p' "$out/log"
}
printf '%-32s %12s   %s\n' entry instructions "clone (callgrind)"
for e in "${entries[@]}"; do
  a=$(collected "$e" "$n")
  b=$(collected "$e" $((2 * n)))
  clone=$(grep -o '^c\?fn=.*\[clone \.\(arch_x86_64_v3\|fma\|default\)\]' "$out/cg.$((2 * n))" |
          sed 's/.*\[clone \.\(arch_x86_64_v3\|fma\|default\)\]$/\1/' | sort -u | tr '\n' ' ' || true)
  awk -v a="$a" -v b="$b" -v n="$n" -v e="$e" -v c="$clone" 'BEGIN { printf "%-32s %12.1f   %s\n", e, (b - a) / n, c }'
done

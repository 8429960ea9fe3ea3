#!/usr/bin/env bash
# Measures what the structure-aware input adds to fuzz_plane: runs it for SECONDS (default 60) in each
# configuration, from the seed corpus into a fresh scratch corpus, and prints execs/s, coverage and the
# stage table of each. Needs the fuzz build (fuzz/ci-run-fuzzers.sh, or cmake -C fuzz/clang-fuzz.cmake).
#
#   fuzz/tools/measure-structure.sh [SECONDS]
#
#   raw-only       RAYKERNEL_FUZZ_RAW_ONLY=1: plain bytes as 12 doubles, libFuzzer's mutations only
#   decoder        RAYKERNEL_FUZZ_PLAIN_MUTATOR=1: the selector byte and make_query's 13 kinds, no custom mutator
#   full           decoder and the geometric custom mutator (what CI runs)
#   full+vp        full with -use_value_profile=1
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-60}
build=${FUZZ_BUILD_DIR:-build-fuzz}
fuzzer="$build/fuzz/fuzz_plane"
[ -x "$fuzzer" ] || { echo "no $fuzzer: build the fuzz build first (fuzz/ci-run-fuzzers.sh)" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export ASAN_OPTIONS=${ASAN_OPTIONS:-malloc_context_size=0}
export RAYKERNEL_FUZZ_STATS=1

run() {
  local label=$1
  shift
  mkdir -p "$scratch/$label"
  echo "==== $label ($seconds s)"
  # shellcheck disable=SC2086  # EXTRA holds separate flags
  env "$@" "$fuzzer" "$scratch/$label" fuzz/corpus/plane -dict=fuzz/dict/plane.dict -max_len=256 \
    -max_total_time="$seconds" -print_final_stats=1 -seed=1 ${EXTRA:-} >"$scratch/$label.log" 2>&1
  grep -E '^#[0-9]+[[:space:]]+DONE' "$scratch/$label.log" | sed 's/^/final: /'
  grep -E '^stat::average_exec_per_sec' "$scratch/$label.log"
  sed -n '/==== raykernel fuzz stats/,$p' "$scratch/$label.log"
}

run raw-only RAYKERNEL_FUZZ_RAW_ONLY=1
run decoder RAYKERNEL_FUZZ_PLAIN_MUTATOR=1
run full RAYKERNEL_FUZZ_FULL=1
EXTRA=-use_value_profile=1 run full+vp RAYKERNEL_FUZZ_FULL=1

#!/usr/bin/env bash
# Builds the libFuzzer harnesses with clang-14, ASan and UBSan (the kernel included) in build-fuzz/, replays
# every saved input under the sanitizers, then runs each harness for a bounded time. Fails on any crash,
# sanitizer report, leak, timeout or disagreement; prints execs/s and the fraction of executions each
# certified stage decided. .ci/run calls it after the tests.
#
#   fuzz/ci-run-fuzzers.sh                        # CI: 10 s per harness (12 harnesses: 2 min of fuzzing)
#   FUZZ_SECONDS=3600 fuzz/ci-run-fuzzers.sh      # longer, locally
#   FUZZ_HARNESSES="plane nearest" fuzz/ci-run-fuzzers.sh
#
# The harnesses are those fuzz/CMakeLists.txt registers (the manifest $FUZZ_BUILD_DIR/fuzz/harnesses.txt):
# plane, triangle, sphere, spawn, batch, cli, nearest, nearest_cli, scene, mesh_reader, occlusion, closest.
#
# Environment: FUZZ_SECONDS (per harness, default 10: CI's budget is the whole .ci/run in 45 min on 2 cores),
# FUZZ_HARNESSES (default: all in the manifest), FUZZ_BUILD_DIR (default build-fuzz), FUZZ_BUILD_JOBS (default
# 2), FUZZ_EXTRA_ARGS (more libFuzzer flags), FUZZ_GCC_BUILD_DIR (default build, the README's build): when it
# has the replay programs, every input the fuzzers saved is replayed with them too, i.e. through the
# GCC-compiled kernel (its AVX2/AVX-512 batch loops).
# New inputs go to $FUZZ_BUILD_DIR/fuzz/work/<harness>/ (never into the source tree); failing inputs to
# $FUZZ_BUILD_DIR/fuzz/artifacts/<harness>/; full logs to $FUZZ_BUILD_DIR/fuzz/logs/. fuzz/README.md says
# how to reproduce a failure and turn it into a regression input.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=${FUZZ_SECONDS:-10}  # bounded so that .ci/run stays under 45 minutes on 2 cores
build=${FUZZ_BUILD_DIR:-build-fuzz}
jobs=${FUZZ_BUILD_JOBS:-2}
case "$build" in /*) ;; *) build="$root/$build" ;; esac
gcc_build=${FUZZ_GCC_BUILD_DIR:-build}
case "$gcc_build" in /*) ;; *) gcc_build="$root/$gcc_build" ;; esac

step() { printf '\n---- fuzz: %s\n' "$*"; }

step "configure and build (clang-14, -fsanitize=fuzzer-no-link,address,undefined) in $build"
mkdir -p "$build"
cmake -S . -B "$build" -G Ninja -C fuzz/clang-fuzz.cmake >"$build/fuzz-configure.log" 2>&1 || {
  cat "$build/fuzz-configure.log"
  exit 1
}
cmake --build "$build" -j"$jobs"

manifest="$build/fuzz/harnesses.txt"
out="$build/fuzz"
mkdir -p "$out/work" "$out/artifacts" "$out/logs"

# Sanitizer settings: every report is fatal; malloc_context_size=0 skips recording a stack trace per
# allocation (the harnesses allocate rationals constantly: about 1.5x the executions per second). To see
# allocation stacks when reproducing, run without ASAN_OPTIONS.
export ASAN_OPTIONS=${ASAN_OPTIONS:-malloc_context_size=0:detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export RAYKERNEL_FUZZ_STATS=1

declare -a names=() corpora=() options=()
while IFS=$'\t' read -r name corpus opts; do
  [ -n "$name" ] || continue
  if [ -n "${FUZZ_HARNESSES:-}" ] && [[ " $FUZZ_HARNESSES " != *" $name "* ]]; then continue; fi
  names+=("$name")
  corpora+=("$corpus")
  options+=("${opts//-dict=/-dict=$root/fuzz/}")
done <"$manifest"
if [ ${#names[@]} -eq 0 ]; then
  echo "fuzz: no harnesses selected (manifest $manifest, FUZZ_HARNESSES='${FUZZ_HARNESSES:-}')" >&2
  exit 1
fi

step "replay every saved input under the sanitizers"
for i in "${!names[@]}"; do
  "$out/fuzz_${names[i]}_replay" "${corpora[i]}"
done

failed=()
summary=()
for i in "${!names[@]}"; do
  name=${names[i]}
  step "fuzz_$name for $seconds s"
  work="$out/work/$name"
  artifacts="$out/artifacts/$name"
  log="$out/logs/$name.log"
  mkdir -p "$work" "$artifacts"
  status=0
  # shellcheck disable=SC2086  # options are separate flags
  "$out/fuzz_$name" "$work" "${corpora[i]}" ${options[i]} ${FUZZ_EXTRA_ARGS:-} \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" >"$log" 2>&1 || status=$?
  # The log without libFuzzer's per-input progress lines (and the new functions they reached) and its
  # recommended dictionary.
  grep -v -E '^#[0-9]+.*(NEW|REDUCE|pulse|RELOAD) |^[[:space:]]+NEW_FUNC' "$log" | sed '/Recommended dictionary/,/End of recommended dictionary/d'
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  if [ "$status" -ne 0 ]; then
    failed+=("$name")
    summary+=("$(printf '%-12s FAILED (exit %s) after %s executions; log %s' "$name" "$status" "${execs:-?}" "$log")")
    echo
    echo "fuzz_$name FAILED. Inputs it saved:"
    ls -l "$artifacts" || true
    for a in "$artifacts"/*; do
      [ -e "$a" ] || continue
      echo "  reproduce:  $out/fuzz_$name $a        (or: $out/fuzz_${name}_replay $a)"
    done
    echo "  then keep it: cp <input> fuzz/corpus/$name/regression-<what-it-broke>   (fuzz/README.md)"
  else
    summary+=("$(printf '%-12s ok: %s executions in %s s, %s execs/s' "$name" "${execs:-?}" "$seconds" "${rate:-?}")")
  fi
  # The same inputs through the GCC build, when there is one.
  gcc_replay="$gcc_build/fuzz/fuzz_${name}_replay"
  saved=$(find "$work" -type f | wc -l)
  if [ -x "$gcc_replay" ] && [ "$saved" -gt 0 ]; then
    echo "replaying the $saved saved inputs with the GCC build ($gcc_replay)"
    if ! "$gcc_replay" "$work" "${corpora[i]}" >"$out/logs/$name.gcc-replay.log" 2>&1; then
      cat "$out/logs/$name.gcc-replay.log"
      failed+=("$name(gcc-replay)")
      summary+=("$(printf '%-12s FAILED in the GCC replay; log %s' "$name" "$out/logs/$name.gcc-replay.log")")
    fi
  fi
done

step "summary"
printf '%s\n' "${summary[@]}"
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: FAILED: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: all harnesses passed"

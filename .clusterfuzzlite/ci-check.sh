#!/usr/bin/env bash
# Proves .clusterfuzzlite/build.sh on this machine, as ClusterFuzzLite would run it, and runs what it builds.
#
# Sets the variables ClusterFuzzLite's `compile` sets — $CC/$CXX (clang-14 here), $CFLAGS/$CXXFLAGS built from
# OSS-Fuzz's own flag sets (base-clang's -O1 -gline-tables-only ..., base-builder's SANITIZER_FLAGS_address
# AND SANITIZER_FLAGS_undefined in one build, COVERAGE_FLAGS, and -stdlib=libc++ for C++),
# $LIB_FUZZING_ENGINE=-fsanitize=fuzzer, and scratch $SRC/$WORK/$OUT — runs build.sh from the source tree
# (the Dockerfile's WORKDIR), then checks what it produced against fuzz/CMakeLists.txt's manifest (after
# check_config.py has checked the Dockerfile, project.yaml and the workflows, which cannot run here):
#   - every harness has its fuzzer, its seed corpus zip (all of fuzz/corpus/NAME/), its dict and options;
#   - the fuzzers depend on no shared library but the C/C++ runtime (ClusterFuzzLite's runner has no GMP,
#     MPFR or libpng);
#   - each fuzzer runs over its whole seed corpus and then fuzzes for FUZZ_SECONDS (default 2: the
#     fuzzing itself is fuzz/ci-run-fuzzers.sh's; this checks that the build runs) with its
#     dict and options, under the sanitizers with OSS-Fuzz's runtime options; any crash, sanitizer report,
#     leak or timeout fails the check.
# .ci/run calls it; it prints the time each part took. The scratch directory is build-cflite/ (kept for
# reproducing: build-cflite/out/fuzz_NAME <input>).
#
#   .clusterfuzzlite/ci-check.sh
#   FUZZ_SECONDS=60 CFLITE_HARNESSES="plane nearest" .clusterfuzzlite/ci-check.sh
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
start=$(date +%s)
step() { printf '\n---- cflite check: %s (%ds)\n' "$*" "$(( $(date +%s) - start ))"; }
fail() { printf 'cflite check: FAIL: %s\n' "$*" >&2; exit 1; }
seconds=${FUZZ_SECONDS:-2}  # bounded so that .ci/run stays under 45 minutes on 2 cores
scratch=${CFLITE_CHECK_DIR:-$root/build-cflite}
case "$scratch" in /*) ;; *) scratch=$root/$scratch ;; esac

step "the configuration (Dockerfile, project.yaml, workflows, the users' template)"
/usr/bin/python3 .clusterfuzzlite/check_config.py

export SRC=$scratch/src WORK=$scratch/work OUT=$scratch/out
rm -rf "$OUT" "$SRC"
mkdir -p "$SRC" "$WORK" "$OUT"
cp .clusterfuzzlite/build.sh "$SRC/build.sh"  # where the Dockerfile puts it

export CC=${CFLITE_CC:-clang-14} CXX=${CFLITE_CXX:-clang++-14}
# OSS-Fuzz's flags (infra/base-images/base-clang/Dockerfile: CFLAGS, CXXFLAGS_EXTRA; base-builder/Dockerfile:
# SANITIZER_FLAGS_address, SANITIZER_FLAGS_undefined, COVERAGE_FLAGS), composed as its `compile` script does.
base="-O1 -fno-omit-frame-pointer -gline-tables-only -DFUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION"
address="-fsanitize=address -fsanitize-address-use-after-scope"
ub_checks="array-bounds,bool,builtin,enum,float-divide-by-zero,function,integer-divide-by-zero,null,object-size,return,returns-nonnull-attribute,shift,signed-integer-overflow,unreachable,vla-bound,vptr"
undefined="-fsanitize=$ub_checks,unsigned-integer-overflow -fno-sanitize-recover=$ub_checks"
coverage="-fsanitize=fuzzer-no-link"
export CFLAGS="$base $address $undefined $coverage"
export CXXFLAGS="$CFLAGS -stdlib=libc++"
# Debian's libFuzzer (libclang-rt-14-dev) is built against libstdc++, OSS-Fuzz's against a private libc++:
# here the engine brings libstdc++ along for its own sake. So that this cannot hide our code needing
# libstdc++ too, the link traces the archive members it loads (LDFLAGS) and the check below fails if any
# comes from libgmpxx.a, whose (iostream) objects are built against libstdc++ and would not link with libc++.
export LIB_FUZZING_ENGINE="-fsanitize=fuzzer -l:libstdc++.so.6"  # (clang would turn -lstdc++ into -lc++)
export LDFLAGS="-Wl,--trace"
export RAYKERNEL_BUILD_JOBS=${RAYKERNEL_BUILD_JOBS:-2}
if ! echo '#include <vector>
int main() { return std::vector<int>(1).size() - 1; }' | "$CXX" -stdlib=libc++ -x c++ - -o "$WORK/libcxx-probe" 2> "$WORK/libcxx-probe.log"; then
  cat "$WORK/libcxx-probe.log"
  fail "$CXX cannot build with -stdlib=libc++ (Debian: libc++-14-dev libc++abi-14-dev, in .ci/install-deps)"
fi

step "build.sh with CC=$CC CXX=$CXX"
echo "CFLAGS=$CFLAGS"
echo "CXXFLAGS=$CXXFLAGS"
echo "LIB_FUZZING_ENGINE=$LIB_FUZZING_ENGINE LDFLAGS=$LDFLAGS"
build_start=$(date +%s)
(cd "$root" && nice -n 10 bash -eu "$SRC/build.sh") > "$WORK/build.log" 2>&1 || { tail -60 "$WORK/build.log"; fail "build.sh failed (log: $WORK/build.log)"; }
grep '^build.sh: ' "$WORK/build.log"
build_seconds=$(( $(date +%s) - build_start ))
if grep -q 'libgmpxx\.a(' "$WORK/build.log"; then
  grep 'libgmpxx\.a(' "$WORK/build.log" | sort -u
  fail "a fuzzer links objects of libgmpxx.a (gmpxx iostream operators, built against libstdc++): with ClusterFuzzLite's libc++ it would not link"
fi

step "what build.sh produced"
manifest=$WORK/raykernel-fuzz-build/fuzz/harnesses.txt
declare -a names=() corpora=()
while IFS=$'\t' read -r name corpus options; do
  [ -n "$name" ] || continue
  fuzzer=$OUT/fuzz_$name
  [ -x "$fuzzer" ] || fail "no $fuzzer"
  inputs=$(find "$corpus" -type f | wc -l)
  if [ "$inputs" -gt 0 ]; then
    zipped=$(unzip -Z1 "${fuzzer}_seed_corpus.zip" | grep -vc '/$' || true)
    [ "$zipped" = "$inputs" ] || fail "${fuzzer}_seed_corpus.zip has $zipped inputs, fuzz/corpus/$name has $inputs"
  fi
  case " $options " in *" -dict="*) [ -f "$fuzzer.dict" ] || fail "no $fuzzer.dict" ;; esac
  case " $options " in *" -max_len="*) grep -q '^max_len = ' "$fuzzer.options" || fail "no max_len in $fuzzer.options" ;; esac
  # Every shared library must be part of the C/C++ runtime: the runner image has nothing else.
  unexpected=$(ldd "$fuzzer" | awk '{print $1}' | grep -v -E '^(linux-vdso\.so|/lib64/ld-linux|libc\.so|libm\.so|libdl\.so|libpthread\.so|librt\.so|libgcc_s\.so|libstdc\+\+\.so|libc\+\+\.so|libc\+\+abi\.so|libunwind\.so|libatomic\.so)' || true)
  [ -z "$unexpected" ] || fail "fuzz_$name needs shared libraries the runner does not have: $unexpected"
  if [ -z "${CFLITE_HARNESSES:-}" ] || [[ " $CFLITE_HARNESSES " == *" $name "* ]]; then
    names+=("$name")
    corpora+=("$corpus")
  fi
  printf '%-18s %s\n' "fuzz_$name" "$(cd "$OUT" && ls -d "fuzz_$name" "fuzz_$name.dict" "fuzz_$name.options" \
    "fuzz_${name}_seed_corpus.zip" 2> /dev/null | tr '\n' ' ')"
done < "$manifest"
[ ${#names[@]} -gt 0 ] || fail "no harnesses to run"

# OSS-Fuzz's runtime options for the sanitizers (base-runner), every report fatal.
export ASAN_OPTIONS=${ASAN_OPTIONS:-alloc_dealloc_mismatch=0:allocator_may_return_null=1:detect_leaks=1:detect_stack_use_after_return=1:malloc_context_size=0:symbolize=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-silence_unsigned_overflow=1:print_stacktrace=1:halt_on_error=1:print_summary=1}

summary=()
for i in "${!names[@]}"; do
  name=${names[i]}
  fuzzer=$OUT/fuzz_$name
  step "fuzz_$name: the seed corpus, then $seconds s"
  corpus=$WORK/corpus/$name
  rm -rf "$corpus" "$WORK/artifacts/$name"
  mkdir -p "$corpus" "$WORK/artifacts/$name"
  if [ -f "${fuzzer}_seed_corpus.zip" ]; then unzip -q "${fuzzer}_seed_corpus.zip" -d "$corpus"; fi
  seeds=$(find "$corpus" -type f | wc -l)
  flags=()
  if [ -f "$fuzzer.dict" ]; then flags+=("-dict=$fuzzer.dict"); fi
  if [ -f "$fuzzer.options" ]; then  # [libfuzzer] key = value, as ClusterFuzz passes them
    while IFS= read -r line; do
      case $line in *=*) key=${line%%=*}; value=${line#*=}; flags+=("-${key// /}=${value# }") ;; esac
    done < <(sed -n '/^\[libfuzzer\]/,/^\[/p' "$fuzzer.options" | grep '=')
  fi
  log=$WORK/fuzz-$name.log
  status=0
  "$fuzzer" "${flags[@]}" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2560 -print_final_stats=1 \
    -artifact_prefix="$WORK/artifacts/$name/" "$corpus" > "$log" 2>&1 || status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  if [ "$status" -ne 0 ] || ! grep -q 'INITED' "$log"; then
    grep -v -E '^#[0-9]+.*(NEW|REDUCE|pulse|RELOAD) ' "$log" | tail -60
    ls -l "$WORK/artifacts/$name"
    fail "fuzz_$name (exit $status; log $log; reproduce: $fuzzer <input>)"
  fi
  summary+=("$(printf '%-18s ok: %s seeds, %s executions, %s execs/s, flags: %s' "fuzz_$name" "$seeds" "${execs:-?}" "${rate:-?}" "${flags[*]}")")
done

step "summary"
echo "build.sh: ${build_seconds} s"
printf '%s\n' "${summary[@]}"
echo "cflite check: build.sh works and every fuzzer ran its seed corpus and ${seconds} s of fuzzing"

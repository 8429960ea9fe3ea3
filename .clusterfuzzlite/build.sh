#!/bin/bash -eu
# ClusterFuzzLite (and OSS-Fuzz) build of raykernel's libFuzzer harnesses.
#
# Runs inside the image of .clusterfuzzlite/Dockerfile, from the source tree (its WORKDIR), with the variables
# ClusterFuzzLite sets: $CC, $CXX, $CFLAGS, $CXXFLAGS (optimization, sanitizer and coverage flags, and
# -stdlib=libc++), $LIB_FUZZING_ENGINE, $SRC, $WORK, $OUT. .clusterfuzzlite/ci-check.sh runs it the same way
# outside Docker, with clang-14, so that `.ci/run` proves it.
#
# The harnesses are the ones fuzz/CMakeLists.txt registers with raykernel_add_fuzzer: its manifest
# <build>/fuzz/harnesses.txt (NAME, CORPUS DIR, LIBFUZZER OPTIONS per line) is read here, so a harness added
# there (triangles, mesh readers) is built, seeded and configured here without any change to this script.
# For each harness NAME it writes to $OUT:
#   fuzz_NAME                    the fuzzer (static: GMP, MPFR, libpng and zlib linked in; the runner image
#                                has none of them)
#   fuzz_NAME_seed_corpus.zip    fuzz/corpus/NAME/ (the inputs the replay tests run in every ctest)
#   fuzz_NAME.dict               the -dict= of its FUZZ_OPTIONS (fuzz/dict/NAME.dict)
#   fuzz_NAME.options            its other FUZZ_OPTIONS (e.g. max_len), as a [libfuzzer] section
#
# Floating point: the certified kernel keeps -ffp-contract=off -fno-fast-math (kernel/CMakeLists.txt adds
# them after the flags given here), and this script refuses flags that would break IEEE semantics, then
# checks the compile commands of kernel/ afterwards. OSS-Fuzz's `undefined` sanitizer includes
# float-divide-by-zero, which reports a division by zero of doubles: that is defined by IEEE 754 (±inf or
# NaN; clang leaves it out of -fsanitize=undefined for that reason), and the kernel's branch-free fast path
# divides before it knows whether the quotient is needed, so it is turned off here.
set -o pipefail

src=${RAYKERNEL_SOURCE_DIR:-$PWD}
if ! grep -q '^project(raykernel ' "$src/CMakeLists.txt" 2>/dev/null; then
  echo "build.sh: run it from raykernel's source tree (the Dockerfile's WORKDIR), or set RAYKERNEL_SOURCE_DIR" >&2
  exit 1
fi
build=$WORK/raykernel-fuzz-build
jobs=${RAYKERNEL_BUILD_JOBS:-$(nproc)}

for flag in $CFLAGS $CXXFLAGS; do
  case $flag in
    -ffast-math | -Ofast | -funsafe-math-optimizations | -ffinite-math-only | -ffp-contract=fast | -ffp-model=fast)
      echo "build.sh: $flag breaks the IEEE-754 semantics raykernel's certified kernel is proved for" >&2
      exit 1 ;;
  esac
done
ieee="-fno-sanitize=float-divide-by-zero"
# Boost (CGAL's dependency; 1.71 in the Ubuntu 20.04 base image) derives from std::unary_function unless told
# the library lacks it, and recent libc++ removes it in C++17 and later.
boost="-DBOOST_NO_CXX98_FUNCTION_BASE"

# Static archives of the C libraries the kernel and the CLI link (the fuzzers must run without them).
static_lib() {
  local path
  path=$("$CXX" -print-file-name="$1")
  if [ "$path" = "$1" ] || [ ! -f "$path" ]; then
    echo "build.sh: $1 not found (the Dockerfile installs the -dev packages that ship it)" >&2
    exit 1
  fi
  echo "$path"
}
gmp=$(static_lib libgmp.a)
gmpxx=$(static_lib libgmpxx.a)
mpfr=$(static_lib libmpfr.a)
png=$(static_lib libpng16.a)
zlib=$(static_lib libz.a)

generator=()
if command -v ninja > /dev/null; then generator=(-G Ninja); fi

# A build type without flags of its own: the optimization and debug flags are ClusterFuzzLite's ($CFLAGS).
# Embree off: the fuzzers run where only $OUT is copied, and the CLI would link libembree3.so (its watertight
# baseline), which the runner image does not have.
cmake -S "$src" -B "$build" "${generator[@]}" \
  -DCMAKE_BUILD_TYPE=ClusterFuzzLite \
  -DCMAKE_C_COMPILER="$CC" -DCMAKE_CXX_COMPILER="$CXX" \
  -DCMAKE_C_FLAGS="$CFLAGS $ieee" -DCMAKE_CXX_FLAGS="$CXXFLAGS $ieee $boost" -DCMAKE_EXE_LINKER_FLAGS="${LDFLAGS:-}" \
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DRAYKERNEL_BUILD_FUZZERS=ON -DRAYKERNEL_FUZZING_ENGINE="$LIB_FUZZING_ENGINE" \
  -DRAYKERNEL_BUILD_CLI=ON -DRAYKERNEL_BUILD_TESTS=OFF -DRAYKERNEL_BUILD_BENCH=OFF -DRAYKERNEL_BUILD_PYTHON=OFF \
  -DRAYKERNEL_WITH_EMBREE=OFF \
  -DRAYKERNEL_GMP_LIBRARY="$gmp" -DRAYKERNEL_GMPXX_LIBRARY="$gmpxx" -DRAYKERNEL_MPFR_LIBRARY="$mpfr" \
  -DGMP_LIBRARY_RELEASE="$gmp" -DGMP_LIBRARY_DEBUG="$gmp" -DGMPXX_LIBRARIES="$gmpxx" -DMPFR_LIBRARIES="$mpfr" \
  -DPNG_LIBRARY="$png" -DZLIB_LIBRARY="$zlib"

manifest=$build/fuzz/harnesses.txt
names=()
while IFS=$'\t' read -r name _; do
  [ -n "$name" ] && names+=("$name")
done < "$manifest"
if [ ${#names[@]} -eq 0 ]; then
  echo "build.sh: no harnesses in $manifest" >&2
  exit 1
fi
targets=()
for name in "${names[@]}"; do targets+=("fuzz_$name"); done
cmake --build "$build" -j "$jobs" --target "${targets[@]}"

# The kernel's translation units must have been compiled with contraction off and without fast-math: the
# last -ffp-contract= must be "off", and no fast-math flag may come after the last -fno-fast-math.
python3 - "$build/compile_commands.json" "$src/kernel/" <<'PY'
import json, shlex, sys
commands, kernel = json.load(open(sys.argv[1])), sys.argv[2]
fast = {"-ffast-math", "-Ofast", "-funsafe-math-optimizations", "-ffinite-math-only"}
checked = 0
for entry in commands:
    if not entry["file"].startswith(kernel):
        continue
    words = shlex.split(entry["command"]) if "command" in entry else entry["arguments"]
    contract = [w for w in words if w.startswith("-ffp-contract=")]
    last_no_fast = max((i for i, w in enumerate(words) if w == "-fno-fast-math"), default=-1)
    if not contract or contract[-1] != "-ffp-contract=off" or last_no_fast < 0 or \
            any(w in fast for w in words[last_no_fast:]):
        sys.exit(f"build.sh: {entry['file']} is not compiled with -ffp-contract=off -fno-fast-math last")
    checked += 1
if checked == 0:
    sys.exit("build.sh: no kernel/ sources in compile_commands.json")
print(f"build.sh: {checked} kernel translation units compiled with -ffp-contract=off -fno-fast-math")
PY

while IFS=$'\t' read -r name corpus options; do
  [ -n "$name" ] || continue
  fuzzer=fuzz_$name
  cp "$build/fuzz/$fuzzer" "$OUT/$fuzzer"
  rm -f "$OUT/${fuzzer}_seed_corpus.zip" "$OUT/$fuzzer.options" "$OUT/$fuzzer.dict"
  if [ -d "$corpus" ] && [ -n "$(ls -A "$corpus")" ]; then
    (cd "$corpus" && zip -q -X -r "$OUT/${fuzzer}_seed_corpus.zip" .)
  fi
  libfuzzer_options=()
  for option in $options; do
    case $option in
      -dict=*) cp "$src/fuzz/${option#-dict=}" "$OUT/$fuzzer.dict" ;;
      -*=*) option=${option#-}; libfuzzer_options+=("${option%%=*} = ${option#*=}") ;;
    esac
  done
  if [ ${#libfuzzer_options[@]} -gt 0 ]; then
    printf '[libfuzzer]\n' > "$OUT/$fuzzer.options"
    printf '%s\n' "${libfuzzer_options[@]}" >> "$OUT/$fuzzer.options"
  fi
  echo "build.sh: $OUT/$fuzzer$( [ -f "$OUT/${fuzzer}_seed_corpus.zip" ] && echo " + seed corpus ($(ls "$corpus" | wc -l) inputs)")$( [ -f "$OUT/$fuzzer.dict" ] && echo " + dict")$( [ -f "$OUT/$fuzzer.options" ] && echo " + options")"
done < "$manifest"

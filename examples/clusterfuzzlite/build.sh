#!/bin/bash -eu
# ClusterFuzzLite build for YOUR project's fuzz harnesses that test your ray code against raykernel (a template:
# copy this directory's Dockerfile, build.sh and project.yaml into your repository's .clusterfuzzlite/, and a
# workflow such as ../../.github/workflows/cflite_pr.yml into .github/workflows/; edit the two lists below).
#
# It runs inside the Dockerfile's image with ClusterFuzzLite's $CC, $CXX, $CFLAGS, $CXXFLAGS,
# $LIB_FUZZING_ENGINE, $SRC, $WORK, $OUT, from your source tree (the Dockerfile's WORKDIR):
#   1. raykernel (kernel and testkit) is built from $SRC/raykernel with the same compiler and flags and
#      installed into $WORK/raykernel — it must use the same C++ standard library as your harness (OSS-Fuzz's
#      is libc++, a distribution's raykernel package libstdc++). With RAYKERNEL_PREFIX set, an installed
#      raykernel built with a compatible standard library is used instead (examples/ci-consumer.sh does that).
#   2. every harness is compiled with your sources and linked with raykernel's static libraries and static
#      GMP and MPFR (the fuzzers run in an image that has neither), into $OUT; a directory corpus/<harness>/
#      next to it, if there is one, becomes its seed corpus.

# --- your project -----------------------------------------------------------------------------------------
harnesses=(fuzz_my_intersect.cpp)   # files defining LLVMFuzzerTestOneInput: each becomes $OUT/<file name>
sources=(my_ray_code.cpp)           # your code under test, linked into every harness
# ------------------------------------------------------------------------------------------------------------

# Dividing doubles by zero is defined (IEEE 754) and raykernel's fast path relies on it; OSS-Fuzz's
# `undefined` sanitizer would report it. Boost (CGAL's dependency) must not use std::unary_function under libc++.
CFLAGS="$CFLAGS -fno-sanitize=float-divide-by-zero"
CXXFLAGS="$CXXFLAGS -fno-sanitize=float-divide-by-zero -DBOOST_NO_CXX98_FUNCTION_BASE"

static_lib() {  # the static archive of a C library (libgmp.a, ...), from the compiler's search path
  local path
  path=$("$CXX" -print-file-name="$1")
  [ "$path" != "$1" ] && [ -f "$path" ] || { echo "build.sh: $1 not found (install its -dev package)" >&2; exit 1; }
  echo "$path"
}
gmp=$(static_lib libgmp.a)
mpfr=$(static_lib libmpfr.a)

prefix=${RAYKERNEL_PREFIX:-}
if [ -z "$prefix" ]; then
  prefix=$WORK/raykernel
  generator=()
  if command -v ninja > /dev/null; then generator=(-G Ninja); fi
  cmake -S "${RAYKERNEL_SOURCE_DIR:-$SRC/raykernel}" -B "$WORK/raykernel-build" "${generator[@]}" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER="$CC" -DCMAKE_CXX_COMPILER="$CXX" \
    -DCMAKE_C_FLAGS="$CFLAGS" -DCMAKE_CXX_FLAGS="$CXXFLAGS" -DCMAKE_INSTALL_PREFIX="$prefix" \
    -DRAYKERNEL_BUILD_CLI=OFF -DRAYKERNEL_BUILD_TESTS=OFF -DRAYKERNEL_BUILD_BENCH=OFF -DRAYKERNEL_BUILD_PYTHON=OFF \
    -DRAYKERNEL_GMP_LIBRARY="$gmp" -DRAYKERNEL_GMPXX_LIBRARY="$(static_lib libgmpxx.a)" -DRAYKERNEL_MPFR_LIBRARY="$mpfr" \
    -DGMP_LIBRARY_RELEASE="$gmp" -DMPFR_LIBRARIES="$mpfr"
  cmake --build "$WORK/raykernel-build" -j "$(nproc)" --target raykernel raykernel_testkit
  cmake --install "$WORK/raykernel-build" > /dev/null
fi
libdir=$(dirname "$(find "$prefix" -name libraykernel.a | head -1)")
[ -f "$libdir/libraykernel_testkit.a" ] || { echo "build.sh: no raykernel libraries under $prefix" >&2; exit 1; }

for harness in "${harnesses[@]}"; do
  name=$(basename "$harness" .cpp)
  # shellcheck disable=SC2086  # the flags are words
  $CXX $CXXFLAGS -std=c++20 -I"$prefix/include" "$harness" "${sources[@]}" -o "$OUT/$name" \
    $LIB_FUZZING_ENGINE "$libdir/libraykernel_testkit.a" "$libdir/libraykernel.a" "$mpfr" "$gmp" -pthread
  if [ -d "corpus/$name" ] && [ -n "$(ls -A "corpus/$name")" ]; then
    (cd "corpus/$name" && zip -q -X -r "$OUT/${name}_seed_corpus.zip" .)
  fi
  echo "build.sh: $OUT/$name"
done

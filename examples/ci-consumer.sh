#!/usr/bin/env bash
# CI: raykernel as a dependency. Installs raykernel into a temporary prefix, MOVES the installed
# tree (it must be relocatable), then builds examples/ as a stand-alone project out of the source tree
# against that prefix only, runs the examples and checks what they must show:
#
#   - the installed CLI prints the project's version and answers a query;
#   - pkg-config --cflags --libs raykernel works, and a program built with those flags alone runs;
#   - intersect_basics (the library) prints the exact answers;
#   - my_ray_code_properties FAILS, for the right reason: RapidCheck falsifies the naive ray-plane code and
#     the naive nearest-hit loop, prints the shrunk counterexample with the reference check's report, and
#     the control property (raykernel::intersect, 0 ulps) passes; the counterexample's replay line, run
#     through the installed CLI, gives the report's expected answer;
#   - the fuzz harness (decode_fuzz_query + check_against_reference) finds the naive code's mismatch: with
#     libFuzzer when clang++-14 (or $RAYKERNEL_FUZZ_CXX) is available, then replays the saved crash input
#     with the plain replay program; without clang, the replay program on seeded random inputs;
#   - the ClusterFuzzLite template (examples/clusterfuzzlite/build.sh) builds the harness against the
#     installed package with ClusterFuzzLite's variables, and the fuzzer it writes runs and finds the mismatch.
#
# Reuses build/ (or $RAYKERNEL_BUILD_DIR) when it holds a CMake cache: re-configured, and only the installed
# targets rebuilt. Otherwise builds raykernel alone (no tests, no benchmarks) in the temporary directory.
# KEEP=1 keeps the temporary directory (it is always kept on failure).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
start=$(date +%s)
jobs=${RAYKERNEL_CI_JOBS:-2}
work=$(mktemp -d "${TMPDIR:-/tmp}/raykernel-consumer.XXXXXX")
cleanup() { if [ "${KEEP:-0}" = 1 ] || [ "${ok:-0}" != 1 ]; then echo "ci-consumer: kept $work"; else rm -rf "$work"; fi; }
trap cleanup EXIT

step() { printf '\n-- ci-consumer: %s (%ds)\n' "$*" "$(( $(date +%s) - start ))"; }
fail() { printf 'ci-consumer: FAIL: %s\n' "$*" >&2; exit 1; }
expect_in() {  # expect_in FILE FIXED-STRING...
  local file=$1; shift
  for s in "$@"; do grep -qF -- "$s" "$file" || { cat "$file"; fail "'$s' not in $(basename "$file")"; }; done
}

version=$(sed -n 's/^project(raykernel VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
[ -n "$version" ] || fail "no project(raykernel VERSION ...) in CMakeLists.txt"

step "build raykernel $version"
build=${RAYKERNEL_BUILD_DIR:-build}
if [ -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" > "$work/configure.log"  # picks up install rules added since it was configured
else
  build=$work/raykernel-build
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRAYKERNEL_BUILD_TESTS=OFF \
    -DRAYKERNEL_BUILD_BENCH=OFF > "$work/configure.log"
fi
targets=(raykernel raykernel_testkit)
if grep -q '^RAYKERNEL_BUILD_CLI:BOOL=ON' "$build/CMakeCache.txt"; then targets+=(raykernel_tool); fi
cmake --build "$build" -j "$jobs" --target "${targets[@]}"

step "install into a temporary prefix, then move it"
cmake --install "$build" --prefix "$work/staging" > "$work/install.log"
mv "$work/staging" "$work/prefix"
prefix=$work/prefix
config=$(find "$prefix" -name raykernel-config.cmake)
pc=$(find "$prefix" -name raykernel.pc)
[ -n "$config" ] && [ -f "$(dirname "$config")/raykernel-config-version.cmake" ] || fail "CMake package files not installed"
[ -n "$pc" ] || fail "raykernel.pc not installed"
[ -f "$(dirname "$pc")/raykernel-io.pc" ] || fail "raykernel-io.pc not installed"
for h in raykernel/raykernel.hpp raykernel/testkit/plane_queries.hpp raykernel/testkit/plane_rapidcheck.hpp \
         raykernel/testkit/plane_reference_check.hpp raykernel/testkit/plane_pairs.hpp raykernel/testkit/plane_fuzz_decoder.hpp; do
  [ -f "$prefix/include/$h" ] || fail "header $h not installed"
done
if grep -rlF -e "$root" -e "$work/staging" "$(dirname "$config")" "$(dirname "$pc")"; then
  fail "the installed package files above name the source, build or staging directory"
fi
echo "installed $(find "$prefix" -type f | wc -l) files; no build or install paths in the package files"

if [[ " ${targets[*]} " == *" raykernel_tool "* ]]; then
  step "installed CLI"
  [ -x "$prefix/bin/raykernel" ] || fail "the CLI was built but not installed as bin/raykernel"
  got=$("$prefix/bin/raykernel" --version)
  [ "$got" = "raykernel $version" ] || fail "raykernel --version printed '$got', expected 'raykernel $version'"
  got=$(echo "0 0 0 10 0 0 1 0 0 1 0 0" | "$prefix/bin/raykernel" classify --exact-t)
  [ "$got" = "hit 0.1 1/10" ] || fail "installed CLI answered '$got'"
  echo "$("$prefix/bin/raykernel" --version); classify: $got"
fi

step "pkg-config"
export PKG_CONFIG_PATH=$(dirname "$pc")
flags=$(pkg-config --cflags --libs raykernel)
echo "pkg-config --cflags --libs raykernel: $flags"
[ "$(pkg-config --modversion raykernel)" = "$version" ] || fail "pkg-config --modversion is not $version"
incdir=$(pkg-config --variable=includedir raykernel)
[ "$(realpath "$incdir")" = "$(realpath "$prefix/include")" ] || fail "pkg-config includedir $incdir is not under the moved prefix"
case " $flags " in *" -lraykernel "*) ;; *) fail "no -lraykernel in '$flags'" ;; esac
echo "pkg-config --libs raykernel-testkit: $(pkg-config --libs raykernel-testkit)"
# shellcheck disable=SC2086  # the flags are words
c++ -std=c++20 -O1 examples/intersect_basics.cpp $flags -o "$work/intersect_basics_pkgconfig"
"$work/intersect_basics_pkgconfig" > "$work/basics-pkgconfig.out"
expect_in "$work/basics-pkgconfig.out" "raykernel $version"
# Mesh files through raykernel-io (it requires raykernel): a program that reads an OBJ and casts a ray.
io_flags=$(pkg-config --cflags --libs raykernel-io)
echo "pkg-config --cflags --libs raykernel-io: $io_flags"
case " $io_flags " in *" -lraykernel_io "*) ;; *) fail "no -lraykernel_io in '$io_flags'" ;; esac
cat > "$work/read_mesh_app.cpp" <<'CPP'
#include <raykernel/io/mesh_file.hpp>
#include <raykernel/mesh_queries.hpp>
#include <cstdio>
int main(int, char** argv) {
  const raykernel::Mesh mesh = raykernel::io::read_mesh(argv[1]);
  const auto hit = raykernel::nearest_hit(raykernel::Ray{{0.25, 0.25, 1}, {0, 0, -1}}, mesh);
  std::printf("%zu triangles, %s\n", mesh.triangles.size(), hit ? "hit" : "miss");
}
CPP
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$work/one.obj"
# shellcheck disable=SC2086  # the flags are words
c++ -std=c++20 -O1 "$work/read_mesh_app.cpp" $io_flags -o "$work/read_mesh_app"
"$work/read_mesh_app" "$work/one.obj" > "$work/read-mesh.out"
expect_in "$work/read-mesh.out" "1 triangles, hit"

step "find_package(raykernel) from two sibling directories of one project"
# Imported targets are directory-scoped: each find_package must define what the link interface names.
mkdir -p "$work/siblings/a" "$work/siblings/b"
printf 'cmake_minimum_required(VERSION 3.20)\nproject(siblings LANGUAGES CXX)\nadd_subdirectory(a)\nadd_subdirectory(b)\n' \
  > "$work/siblings/CMakeLists.txt"
for d in a b; do
  printf 'find_package(raykernel CONFIG REQUIRED)\nadd_executable(app_%s main.cpp)\n%s\n' "$d" \
    "target_link_libraries(app_$d PRIVATE raykernel::raykernel)" > "$work/siblings/$d/CMakeLists.txt"
  printf '#include <raykernel/raykernel.hpp>\nint main() { return raykernel::version().empty(); }\n' > "$work/siblings/$d/main.cpp"
done
cmake -S "$work/siblings" -B "$work/siblings/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" > "$work/siblings.log"
cmake --build "$work/siblings/build" >> "$work/siblings.log"
"$work/siblings/build/a/app_a" && "$work/siblings/build/b/app_b" || fail "sibling consumers do not run"
echo "both link and run"

step "build examples/ out of the source tree against the installed package"
cp -r examples "$work/examples-src"  # nothing of the source tree is reachable from here
cmake -S "$work/examples-src" -B "$work/examples-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF > "$work/examples-configure.log"
expect_in "$work/examples-configure.log" "raykernel $version from $prefix/"
cmake --build "$work/examples-build" -j "$jobs"
ex=$work/examples-build

step "(c) intersect_basics"
"$ex/intersect_basics" | tee "$work/basics.out"
expect_in "$work/basics.out" "raykernel $version" \
  "intersect                    hit      t = 0x1.999999999999ap-4" \
  "intersect_exact              hit      t = 0x1.999999999999ap-4" \
  "intersect_exact_rational     t = 1/10" \
  "underflow: intersect         hit      t = 0x1p+0" \
  "underflow: intersect_naive   in-plane" \
  "zero direction               invalid_input:"

step "(a) my_ray_code_properties: must fail, with the shrunk counterexamples"
status=0
"$ex/my_ray_code_properties" > "$work/properties.out" 2>&1 || status=$?
sed -n '/Falsifiable/,/^\[  FAILED  \]/p' "$work/properties.out"
[ "$status" = 1 ] || { cat "$work/properties.out"; fail "my_ray_code_properties exited with $status, expected 1 (failed properties, no crash)"; }
expect_in "$work/properties.out" \
  "[  FAILED  ] MyRayCode.IntersectMatchesRaykernel (" \
  "[  FAILED  ] MyRayCode.NearestOrdersNearTies (" \
  "[       OK ] Raykernel.IntersectPassesTheReferenceCheck (" \
  "2 FAILED TESTS" \
  "raykernel reference check FAILED" \
  "my::nearest_hit chose plane" \
  "RC_PARAMS=\"reproduce="
[ "$(grep -c '^Falsifiable after [0-9]* tests' "$work/properties.out")" = 2 ] \
  || fail "expected two shrunk counterexamples"
grep -q 'std::tuple<raykernel::testkit::KindedQuery>:' "$work/properties.out" || fail "no counterexample query printed"
if [ -x "$prefix/bin/raykernel" ]; then
  # The report's replay line through the installed CLI: its answer is the report's "expected".
  replay=$(sed -n "s/^  replay    echo '\(.*\)' | raykernel classify --exact-t --hex$/\1/p" "$work/properties.out" | head -1)
  expected=$(sed -n 's/^  expected  \([a-z-]*\) *\(t = \([^ ]*\)\)\{0,1\}.*/\1 \3/p' "$work/properties.out" | head -1)
  cli=$(echo "$replay" | "$prefix/bin/raykernel" classify --exact-t --hex | awk '{print $1, $2}')
  [ "${cli% }" = "${expected% }" ] || fail "CLI on the counterexample: '$cli', report expected '$expected'"
  echo "counterexample through the installed CLI: $cli (the report's expected answer)"
fi

step "(b) fuzz harness"
"$ex/fuzz_my_intersect_replay" --random 2000 --seed 1 > "$work/replay-random.out" || status=$?
expect_in "$work/replay-random.out" "raykernel reference check FAILED" "2000 inputs, "
tail -1 "$work/replay-random.out"
fuzz_cxx=${RAYKERNEL_FUZZ_CXX:-$(command -v clang++-14 || true)}
if [ -n "$fuzz_cxx" ]; then
  CXX=$fuzz_cxx cmake -S "$work/examples-src" -B "$work/examples-fuzz" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$prefix" > "$work/fuzz-configure.log"
  expect_in "$work/fuzz-configure.log" "RAYKERNEL_EXAMPLES_HAVE_LIBFUZZER - Success"
  cmake --build "$work/examples-fuzz" -j "$jobs" --target fuzz_my_intersect
  mkdir -p "$work/fuzz/corpus"
  status=0
  (cd "$work/fuzz" && "$work/examples-fuzz/fuzz_my_intersect" -max_total_time=30 -seed=1 -print_final_stats=1 \
    corpus > fuzz.log 2>&1) || status=$?
  crash=$(find "$work/fuzz" -maxdepth 1 -name 'crash-*' | head -1)
  [ "$status" != 0 ] && [ -n "$crash" ] || { tail -30 "$work/fuzz/fuzz.log"; fail "libFuzzer found no mismatch in 30 s"; }
  expect_in "$work/fuzz/fuzz.log" "raykernel reference check FAILED"
  grep -E '^(raykernel reference check|  (expected|got) )' "$work/fuzz/fuzz.log" | head -3
  echo "libFuzzer saved $(basename "$crash"); replaying it without libFuzzer:"
  status=0
  "$ex/fuzz_my_intersect_replay" "$crash" > "$work/replay-crash.out" || status=$?
  [ "$status" = 1 ] || fail "the replay program did not reproduce the crash (exit $status)"
  expect_in "$work/replay-crash.out" "raykernel reference check FAILED" "1 inputs, 1 failed"
  tail -1 "$work/replay-crash.out"
else
  echo "no clang++-14: libFuzzer harness skipped (the replay program ran above)"
fi

step "ClusterFuzzLite template (examples/clusterfuzzlite/build.sh) against the installed package"
if [ -n "$fuzz_cxx" ]; then
  # The template's build.sh as ClusterFuzzLite runs it — from the project's tree, with its variables — but
  # with RAYKERNEL_PREFIX: the installed package instead of a raykernel built from source (the prefix is
  # built with libstdc++, so CXXFLAGS here do not ask for OSS-Fuzz's libc++).
  cf=$work/cflite
  mkdir -p "$cf/src" "$cf/work" "$cf/out"
  cp -r "$work/examples-src" "$cf/src/myproject"
  cp examples/clusterfuzzlite/build.sh "$cf/src/build.sh"
  cf_flags="-O1 -fno-omit-frame-pointer -gline-tables-only -fsanitize=address,undefined -fsanitize=fuzzer-no-link"
  (cd "$cf/src/myproject" && SRC=$cf/src WORK=$cf/work OUT=$cf/out CC=${fuzz_cxx/clang++/clang} CXX=$fuzz_cxx \
     CFLAGS="$cf_flags" CXXFLAGS="$cf_flags" LIB_FUZZING_ENGINE=-fsanitize=fuzzer RAYKERNEL_PREFIX=$prefix \
     bash -eu "$cf/src/build.sh") > "$cf/build.log" 2>&1 || { cat "$cf/build.log"; fail "the template's build.sh failed"; }
  grep '^build.sh: ' "$cf/build.log"
  unexpected=$(ldd "$cf/out/fuzz_my_intersect" | grep -E 'libgmp|libmpfr|libraykernel' || true)
  [ -z "$unexpected" ] || fail "the template's fuzzer links shared libraries the runner lacks: $unexpected"
  status=0
  (cd "$cf/work" && "$cf/out/fuzz_my_intersect" -max_total_time=30 -seed=1 > fuzz.log 2>&1) || status=$?
  [ "$status" != 0 ] && grep -q "raykernel reference check FAILED" "$cf/work/fuzz.log" \
    || { tail -30 "$cf/work/fuzz.log"; fail "the template's fuzzer found no mismatch in my::ray_plane in 30 s"; }
  echo "the template's fuzzer runs and finds my::ray_plane's mismatch: $(grep -m1 '^raykernel reference check' "$cf/work/fuzz.log")"
else
  echo "no clang++-14: the ClusterFuzzLite template was not built"
fi

ok=1
step "done: the consumer project built and ran against the installed package"

# Initial cache for the libFuzzer build (cmake -C): clang 14 with libFuzzer's coverage instrumentation, ASan
# and UBSan on every target — the kernel, raykernel::testkit and the CLI library included — and every
# sanitizer report fatal. The kernel keeps its own floating-point flags (-ffp-contract=off -fno-fast-math,
# kernel/CMakeLists.txt); the sanitizers do not change floating-point semantics.
#
#   cmake -S . -B build-fuzz -G Ninja -C fuzz/clang-fuzz.cmake && cmake --build build-fuzz -j2
#
# The certified cascade keeps its multiversioning (target_clones: an FMA clone and a portable clone, chosen
# by ifunc at load time), so the fuzzers run the code users run; ifunc works under ASan and UBSan here. With
# the environment variable FUZZ_NO_MULTIVERSION=1 at configure time the build defines
# RAYKERNEL_NO_MULTIVERSION instead (only the portable clone, std::fma through libm).
#
# Tests and benchmarks are off (the fuzz build needs the harnesses, the CLI library and the replay programs);
# the GCC build replays the corpora under ctest. Every entry is forced: this file defines the fuzz build.
set(CMAKE_CXX_COMPILER clang++-14 CACHE STRING "" FORCE)
set(CMAKE_BUILD_TYPE RelWithDebInfo CACHE STRING "" FORCE)
set(raykernel_fuzz_flags "-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer")
if("$ENV{FUZZ_NO_MULTIVERSION}" STREQUAL "1")
  string(APPEND raykernel_fuzz_flags " -DRAYKERNEL_NO_MULTIVERSION")
endif()
set(CMAKE_CXX_FLAGS "${raykernel_fuzz_flags}" CACHE STRING "" FORCE)
set(CMAKE_EXE_LINKER_FLAGS "-fsanitize=address,undefined" CACHE STRING "" FORCE)
set(RAYKERNEL_BUILD_FUZZERS ON CACHE BOOL "" FORCE)
set(RAYKERNEL_BUILD_TESTS OFF CACHE BOOL "" FORCE)
set(RAYKERNEL_BUILD_BENCH OFF CACHE BOOL "" FORCE)
set(RAYKERNEL_BUILD_CLI ON CACHE BOOL "" FORCE)
set(RAYKERNEL_BUILD_PYTHON OFF CACHE BOOL "" FORCE)  # a sanitized extension cannot be loaded by a plain python

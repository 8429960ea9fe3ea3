# raykernel_warnings: the warning flags of every target the project builds (kernel, testkit, CLI, tests,
# benchmarks, fuzz harnesses, proof checkers), in one place. Link it PRIVATE and inside $<BUILD_INTERFACE:...>
# so that installed targets do not export it:
#
#   target_link_libraries(TARGET PRIVATE $<BUILD_INTERFACE:raykernel_warnings>)
#
# Flags are given only for the compilers whose spelling they are (GCC, Clang, AppleClang); another compiler
# gets none rather than flags it rejects. Targets may add stricter flags of their own (the kernel adds
# -Wpedantic -Wconversion).
if(TARGET raykernel_warnings)
  return()
endif()
add_library(raykernel_warnings INTERFACE)
target_compile_options(raykernel_warnings INTERFACE
  "$<$<CXX_COMPILER_ID:GNU,Clang,AppleClang>:-Wall;-Wextra>"
  # GCC notes that passing 64-byte vectors changed ABI in GCC 4.6; raykernel's vector types only pass between
  # always-inline functions of one translation unit (kernel/src/core/lanes.hpp), so the note is noise.
  # clang says the same of 32-byte vectors passed where AVX is off (the portable clone): the same noise. Where
  # it would be a real mismatch (a call from a target_clones("fma") clone to a function without the target)
  # clang makes it an error that no flag silences, so the multiversioned functions call their always-inline
  # bodies with scalars and references only (kernel/src/triangle/ray_triangle_cascade.cpp).
  # The kernel combines bool comparisons with `&` on purpose (branch-free, both sides evaluated).
  "$<$<CXX_COMPILER_ID:GNU,Clang,AppleClang>:-Wno-psabi>"
  "$<$<CXX_COMPILER_ID:Clang,AppleClang>:-Wno-bitwise-instead-of-logical>")

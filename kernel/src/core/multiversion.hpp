// RAYKERNEL_MULTIVERSION: compile a function more than once — with AVX2 and FMA (GCC's "arch=x86-64-v3"),
// with the FMA instruction alone, and portably (std::fma then calls glibc's correctly rounded fma()) — and let
// the dynamic loader pick one when the program starts (GCC and clang ≥ 14 `target_clones`, an ifunc). Every
// clone computes the same bits: each lane of lanes.hpp performs the same IEEE operations whatever the vector
// width the target lowers it to, std::fma is one correctly rounded operation either way, and certified code is
// compiled with -ffp-contract=off (no clone contracts a product and a sum). The AVX2 clone exists for the
// four-lane code of the triangle and mesh paths: without AVX2 the 256-bit integer operations on Lanes4 masks
// (signs, selects, the screen's decisions) are lowered to one scalar operation per lane (bench/README.md,
// "AVX2 clones": 4,248 → 3,704 instructions per ray of the mesh nearest hit). clang (14, the fuzz build)
// keeps the two clones it accepts. Off where the attribute or ifunc is unavailable, or when
// RAYKERNEL_NO_MULTIVERSION is defined (the fuzz build: sanitizers and ifuncs do not mix).
//
// A multiversioned function must be noexcept: GCC 12 treats a target_clones function as nothrow and
// compiles its callers without cleanups for it, so an exception passing through one would skip
// destructors (tests/fp_environment_test.cpp caught that: the caller's floating-point environment was
// not restored after an invalid query). Validation, which throws, is done outside them.
#pragma once

#if !defined(RAYKERNEL_NO_MULTIVERSION) && defined(__x86_64__) && defined(__ELF__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#if defined(__clang__)
#define RAYKERNEL_MULTIVERSION __attribute__((target_clones("fma", "default")))
#else
#define RAYKERNEL_MULTIVERSION __attribute__((target_clones("arch=x86-64-v3", "fma", "default")))
#endif
#endif
#endif
#ifndef RAYKERNEL_MULTIVERSION
#define RAYKERNEL_MULTIVERSION
#endif

// RAYKERNEL_MULTIVERSION_FLATTEN: the same, with everything the function calls inlined into each clone (GCC's
// flatten), so that the FMA clone computes std::fma with the instruction in its callees too (the triangle
// cascade's stages). clang (14) does not combine flatten with target_clones; there it is RAYKERNEL_MULTIVERSION
// alone (the same bits: the callees call libm's fma).
#if defined(__clang__)
#define RAYKERNEL_MULTIVERSION_FLATTEN RAYKERNEL_MULTIVERSION
#else
#define RAYKERNEL_MULTIVERSION_FLATTEN [[gnu::flatten]] RAYKERNEL_MULTIVERSION
#endif

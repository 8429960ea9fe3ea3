// RAYKERNEL_MULTIVERSION: compile a function twice, with the FMA instruction and portably (std::fma then
// calls glibc's correctly rounded fma()), and let the dynamic loader pick one when the program starts (GCC
// and clang ≥ 14 `target_clones`, an ifunc). Both clones compute the same bits: std::fma is one correctly
// rounded operation either way. Off where the attribute or ifunc is unavailable, or when
// RAYKERNEL_NO_MULTIVERSION is defined (the fuzz build: sanitizers and ifuncs do not mix).
//
// A multiversioned function must be noexcept: GCC 12 treats a target_clones function as nothrow and
// compiles its callers without cleanups for it, so an exception passing through one would skip
// destructors (tests/fp_environment_test.cpp caught that: the caller's floating-point environment was
// not restored after an invalid query). Validation, which throws, is done outside them.
#pragma once

#if !defined(RAYKERNEL_NO_MULTIVERSION) && defined(__x86_64__) && defined(__ELF__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define RAYKERNEL_MULTIVERSION __attribute__((target_clones("fma", "default")))
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

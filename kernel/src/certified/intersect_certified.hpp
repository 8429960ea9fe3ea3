// The certified cascade's entry point, for inputs already validated.
#pragma once

#include <raykernel/raykernel.hpp>

// Multiversioning: an FMA clone and a portable clone, chosen at load time (see intersect_certified.cpp).
// Off where the attribute or ifunc is unavailable, or when RAYKERNEL_NO_MULTIVERSION is defined.
#if !defined(RAYKERNEL_NO_MULTIVERSION) && defined(__x86_64__) && defined(__ELF__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define RAYKERNEL_MULTIVERSION __attribute__((target_clones("fma", "default")))
#endif
#endif
#ifndef RAYKERNEL_MULTIVERSION
#define RAYKERNEL_MULTIVERSION
#endif

namespace raykernel::detail {

// intersect_traced in the default floating-point environment: the fast path (certified/fast_path.hpp),
// then, for what it does not certify, validation (throws invalid_input) and the full cascade.
[[nodiscard]] TracedIntersection intersect_certified(const Ray& ray, const Plane& plane);

}  // namespace raykernel::detail

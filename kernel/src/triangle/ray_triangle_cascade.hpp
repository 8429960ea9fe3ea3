// The certified ray–triangle path (ray_triangle_cascade.cpp), for the public entry points (triangle_api.cpp)
// and whatever else asks triangle queries (meshes):
//
//   fast_triangle_intersection, fast_triangle_relation   the fast paths on raw input: multiversioned
//                                                        (core/multiversion.hpp), noexcept, branch-free
//                                                        up to the decision; nothing when they do not certify
//   triangle_intersection_cascade, triangle_relation_cascade   everything else, for validated input
//
// The split is the one core/multiversion.hpp requires: the multiversioned functions never throw, and
// validation (which throws) happens between the two, in the caller. Every function assumes the default
// floating-point environment (fp_environment.hpp), which the public entry points install.
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/triangle.hpp>

#include <optional>

namespace raykernel::detail {

struct TracedTriangleClassification {
  TriangleClassification classification;
  Stage stage;
};

// The answer when the fast path certifies it: the signs of den and the three π (and of num for a line
// through the triangle) from stage 1 or stage 2's first evaluation, and — when asked for — t and the
// barycentric coordinates rounded by round_quotient over one divisor. Nothing otherwise (then the input may
// also be invalid: a certified sign implies valid input, see ray_triangle_cascade.cpp).
[[nodiscard]] std::optional<TracedTriangleIntersection> fast_triangle_intersection(
    const Ray& ray, const Triangle& triangle, const TriangleOptions& options) noexcept;
// The same; when it certifies nothing after evaluating stage 2 (t or barycentrics asked), it leaves stage 2's five
// values there (ray_triangle_stages.hpp) for the cascade, which then does not evaluate them again.
struct TriangleStage2Handover;
[[nodiscard]] std::optional<TracedTriangleIntersection> fast_triangle_intersection(
    const Ray& ray, const Triangle& triangle, const TriangleOptions& options, TriangleStage2Handover& stage2) noexcept;
[[nodiscard]] std::optional<TracedTriangleClassification> fast_triangle_relation(const Ray& ray,
                                                                                 const Triangle& triangle,
                                                                                 TriangleRule rule) noexcept;
// The same, and for a line through the triangle (relation hit or behind, whether certified or not) the stage-1
// values of num and den it read (ray_triangle_stages.hpp): a nearest hit compares them without recomputing.
struct TriangleQuotientStage1;
[[nodiscard]] std::optional<TracedTriangleClassification> fast_triangle_relation(const Ray& ray,
                                                                                 const Triangle& triangle,
                                                                                 TriangleRule rule,
                                                                                 TriangleQuotientStage1& values) noexcept;

// The whole cascade, each sign and each quotient escalated on its own (filter, compensated, expansion,
// exact). Requires valid input (validation.hpp).
[[nodiscard]] TracedTriangleIntersection triangle_intersection_cascade(const Ray& ray, const Triangle& triangle,
                                                                       const TriangleOptions& options);
// The same, from the stage-2 values the fast path left (bit for bit the ones the cascade would evaluate).
[[nodiscard]] TracedTriangleIntersection triangle_intersection_cascade(const Ray& ray, const Triangle& triangle,
                                                                       const TriangleOptions& options,
                                                                       const TriangleStage2Handover& stage2);
[[nodiscard]] TracedTriangleClassification triangle_relation_cascade(const Ray& ray, const Triangle& triangle,
                                                                     TriangleRule rule);

}  // namespace raykernel::detail

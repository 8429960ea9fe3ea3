// Constructors of hard ray–triangle queries: the inputs where floating-point ray–triangle code goes wrong.
//
// Each kind aims at one weakness: rays through vertices and edges exactly (where watertightness is decided),
// an ulp or a few beside them, sliver and needle triangles, degenerate triangles, rays parallel to or in the
// triangle's plane, origins on the triangle, rounding ties of t, and tiny (subnormal products), huge
// (overflowing products) and wide scales. Where a construction promises an exact property (a ray through a
// vertex, a zero den), every coordinate is an integer times a power of two chosen so that the differences
// and the stated combinations are exact doubles; tests/triangle_queries_test.cpp checks each promise with
// exact rationals. A construction draws its randomness from a BitSource (hard_queries.hpp), so the same
// construction serves a seeded SplitMix64, RapidCheck (every word a shrinkable value) and fuzzer bytes.
// Queries are always valid input (finite, nonzero direction); degenerate triangles are valid input.
#pragma once

#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/triangle.hpp>

#include <array>
#include <cstdint>
#include <string_view>

namespace raykernel::testkit {

struct TriangleQuery {
  Ray ray;
  Triangle triangle;
};

enum class TriangleQueryKind : std::uint8_t {
  random,              // every component uniform in [-1, 1]
  through_vertex,      // the ray's line passes exactly through a vertex (two π are 0)
  through_edge,        // ... exactly through a point of an edge with a dyadic weight (one π is 0)
  through_interior,    // ... exactly through a point with dyadic barycentric coordinates
  near_vertex,         // through a vertex, then one component of o or d moved by 1–4 ulps
  near_edge,           // through an edge point, then moved by 1–4 ulps
  origin_on_triangle,  // the origin exactly on the triangle (or its plane): t = 0
  sliver,              // a vertex within an ulp or a few of the opposite edge (N tiny)
  needle,              // two vertices a few ulps apart
  degenerate,          // collinear (c = a + k(b − a)) or repeated vertices: N = 0 exactly
  parallel,            // d exactly in the plane (den = 0), origin off the plane
  coplanar,            // d and the origin exactly in the plane
  rounding_tie,        // t exactly halfway between two adjacent doubles (or 2^-20..2^-60 ulps from it)
  wide_exponents,      // components ±(1 + f)·2^e, e uniform in [-300, 300]
  tiny,                // a vertex/edge construction scaled into the subnormal range: every product underflows
  huge,                // the same scaled to 2^900..2^1019: products overflow
  above_power_of_two,  // t or a barycentric coordinate in (2^e + ulp/4, 2^e + ulp/2): rounds down to 2^e
};
inline constexpr int triangle_query_kind_count = 17;
inline constexpr std::array<TriangleQueryKind, triangle_query_kind_count> all_triangle_query_kinds = {
    TriangleQueryKind::random,           TriangleQueryKind::through_vertex, TriangleQueryKind::through_edge,
    TriangleQueryKind::through_interior, TriangleQueryKind::near_vertex,    TriangleQueryKind::near_edge,
    TriangleQueryKind::origin_on_triangle, TriangleQueryKind::sliver,       TriangleQueryKind::needle,
    TriangleQueryKind::degenerate,       TriangleQueryKind::parallel,       TriangleQueryKind::coplanar,
    TriangleQueryKind::rounding_tie,     TriangleQueryKind::wide_exponents, TriangleQueryKind::tiny,
    TriangleQueryKind::huge,             TriangleQueryKind::above_power_of_two};

[[nodiscard]] std::string_view to_string(TriangleQueryKind kind) noexcept;

// A query of the given kind. Deterministic in the words drawn. After the construction, the axes are permuted
// and reflected and the vertices relabelled (a cyclic shift, or a reversal of the orientation), all exactly,
// so that no kind favours an axis or a vertex.
[[nodiscard]] TriangleQuery make_triangle_query(TriangleQueryKind kind, const BitSource& bits);

// The query as one line of `raykernel triangle` input: 15 hexadecimal floats.
[[nodiscard]] std::string triangle_line(const TriangleQuery& query);

}  // namespace raykernel::testkit

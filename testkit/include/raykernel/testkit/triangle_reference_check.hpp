// The reference check for ray–triangle code: is a user's answer to one query the exact answer of
// docs/contract.md §6, and if not, how far off? Give it the query, the rule your code implements, and what your
// code answered; it computes the exact answer with `intersect_exact_rational`, compares relation, location and
// owned flag, measures t and each barycentric coordinate in ulps, and writes a report that reproduces the query:
//
//   const raykernel::testkit::TriangleReferenceCheck c = raykernel::testkit::check_against_reference(
//       query, my_intersect(query.ray, query.triangle), raykernel::TriangleRule::closed, /*max_ulps=*/4);
//   if (!c.passed()) std::cerr << c.report();
//
//   raykernel triangle reference check FAILED: relation is miss, expected hit (closed rule)
//     query     o = (...)  d = (...)  a = (...)  b = (...)  c = (...)
//     replay    echo '...' | raykernel triangle --rule=closed --exact --hex
//     expected  hit  edge-bc    t = 0x1p+0 (1)   u = (0x0p+0, 0x1p-1, 0x1p-1)
//     got       miss edge-bc    t = 0x1p+0 (1)   u = (0x0p+0, 0x1p-1, 0x1p-1)
//     exact     t = 1/1, u = (0/1, 1/2, 1/2), den = 1/1
//     errors    t 0 ulps, ua 0, ub 0, uc 0 (tolerance 4)
//
// Which fields are judged: the relation always; the location and the owned flag only when `check_location`
// (a Möller–Trumbore-style test computes no owned flag of its own, say); t and the coordinates when the exact
// den ≠ 0 and the answer's value is not NaN (NaN means "not computed", and is reported, not judged).
#pragma once

#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/triangle.hpp>

#include <array>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>

namespace raykernel::testkit {

struct TriangleReferenceCheck {
  TriangleQuery query;
  TriangleRule rule = TriangleRule::owned;
  TriangleIntersection expected{};  // the exact answer under `rule`
  TriangleIntersection got{};
  ExactTriangleIntersection exact;  // the exact rationals (den, num, π's, t and coordinates when den ≠ 0)
  std::uint64_t max_ulps = 0;
  bool check_location = true;

  bool relation_matches = false;
  bool location_matches = true;  // (true when not checked)
  bool owned_matches = true;
  // ulps of t, ua, ub, uc (reference_check.hpp's ulp_distance): nothing when not compared (den = 0, or the
  // answer's value NaN).
  std::array<std::optional<std::uint64_t>, 4> ulps{};

  [[nodiscard]] bool values_match() const noexcept {
    for (const auto& u : ulps)
      if (u && *u > max_ulps) return false;
    return true;
  }
  [[nodiscard]] bool passed() const noexcept {
    return relation_matches && location_matches && owned_matches && values_match();
  }
  [[nodiscard]] std::string report() const;
};

// Compares `got` with the exact answer under `rule`. Throws raykernel::invalid_input for invalid input.
[[nodiscard]] TriangleReferenceCheck check_against_reference(const TriangleQuery& query, const TriangleIntersection& got,
                                                             TriangleRule rule = TriangleRule::owned,
                                                             std::uint64_t max_ulps = 0, bool check_location = true);

// "o = (...)  d = (...)  a = (...)  b = (...)  c = (...)", components as hexadecimal floats.
[[nodiscard]] std::string to_string(const TriangleQuery& query);

std::ostream& operator<<(std::ostream& os, const TriangleReferenceCheck& check);

}  // namespace raykernel::testkit

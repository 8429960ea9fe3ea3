// The reference check: is a user's answer to one ray–plane query the exact answer, and if not, how far off?
//
// raykernel is meant to be the reference other ray code is tested against. This header turns that into one
// call: give it the query and what your code answered (a relation and a t), and it computes the exact
// answer with `intersect_exact_rational` (exact rationals, correctly rounded t; docs/contract.md §1), compares
// the relation, measures t's error in ulps, and writes a report that reproduces the query exactly:
//
//   const raykernel::testkit::ReferenceCheck c =
//       raykernel::testkit::check_against_reference(query, my_intersect(query.ray, query.plane));
//   if (!c.passed()) std::cerr << c.report();
//
//   raykernel reference check FAILED: t is 2 ulps above the correctly rounded t (tolerance 1 ulp)
//     query     o = (0x0p+0, 0x0p+0, 0x0p+0)  d = (0x1.4p+3, 0x0p+0, 0x0p+0)  p = (0x1p+0, ...)  n = (0x1p+0, ...)
//     replay    echo '0x0p+0 0x0p+0 0x0p+0 0x1.4p+3 0x0p+0 0x0p+0 0x1p+0 ...' | raykernel classify --exact-t --hex
//     expected  hit t = 0x1.999999999999ap-4 (0.1)
//     got       hit t = 0x1.999999999999cp-4 (0.10000000000000003)
//     exact     t = num/den = 1/10, num = 1, den = 10
//     t error   2 ulps above (tolerance 1)
//
// Inside a RapidCheck property, `RAYKERNEL_RC_ASSERT_MATCHES_REFERENCE` (raykernel/testkit/plane_rapidcheck.hpp) fails
// the case with this report, so the shrunk counterexample is printed with it.
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>

namespace raykernel::testkit {

// The distance between two doubles in units in the last place: the number of steps from a to b through
// the representable doubles in increasing order,
//
//     -inf < -DBL_MAX < ... < -DBL_TRUE_MIN < -0 < +0 < DBL_TRUE_MIN < ... < DBL_MAX < +inf,
//
// so that nextafter moves one step (std::nextafter(DBL_MAX, inf) is inf: one step), and -0 and +0 count as
// two adjacent values, one step apart (the contract distinguishes them: -0 is a behind t that underflowed).
// Consequently the distance is 0 exactly when a and b have the same bits, and is symmetric. Examples:
// (1, nextafter(1, 2)) → 1; (-0, +0) → 1; (-DBL_TRUE_MIN, DBL_TRUE_MIN) → 3; (DBL_MAX, inf) → 1;
// (-inf, inf) → 2·0x7ff0000000000000 + 1. Nothing when either is NaN (NaN has no place in the order).
[[nodiscard]] std::optional<std::uint64_t> ulp_distance(double a, double b) noexcept;

// The signed counterpart: ulp_distance(a, b) with the sign of b − a in the order above (negative when b
// lies below a), saturated to ±INT64_MAX (only reachable between values of opposite signs more than 2^62
// ulps apart). Nothing when either is NaN.
[[nodiscard]] std::optional<std::int64_t> ulp_difference(double a, double b) noexcept;

// The outcome of comparing one answer with the exact one.
struct ReferenceCheck {
  Query query;                      // the query, as given
  Intersection expected;            // the exact answer (docs/contract.md §1), as intersect_exact computes it
  Intersection got;                 // the answer under test
  Rational exact_num;               // num = (p − o)·n, exactly, in lowest terms
  Rational exact_den;               // den = d·n, exactly
  std::optional<Rational> exact_t;  // num/den in lowest terms, for hit and behind
  std::uint64_t max_t_ulps = 0;     // the tolerance t was checked with

  // The relations are the same.
  bool relation_matches = false;
  // t is compared only when the exact relation is hit or behind (for parallel and in-plane, t is NaN and
  // whatever the code under test put there is shown in the report, not judged). Then
  // t_ulps = ulp_distance(expected.t, got.t): nothing when got.t is NaN, 0 when the bits are the same.
  bool t_compared = false;
  std::optional<std::uint64_t> t_ulps;
  // The sign of got.t − expected.t in the order of ulp_distance (−1 below, 0 same bits, +1 above), when
  // t_ulps is set.
  int t_direction = 0;

  // t passes: not compared, or got.t within max_t_ulps of expected.t (0: the same bits).
  [[nodiscard]] bool t_matches() const noexcept { return !t_compared || (t_ulps.has_value() && *t_ulps <= max_t_ulps); }
  // The answer under test is acceptable: the relation is right and t_matches().
  [[nodiscard]] bool passed() const noexcept { return relation_matches && t_matches(); }

  // A multi-line, human-readable report (it ends with a newline): verdict, the query in hexadecimal
  // floats (exact), a command line that replays it through the raykernel CLI, expected and got (relation,
  // t as a hexadecimal float and in shortest round-trip decimal), the exact t as P/Q (in full) with num and
  // den (integers of more than 56 digits elided in the middle; exact_num and exact_den hold them in full),
  // and the ulp distance of t.
  [[nodiscard]] std::string report() const;
};

// Compares `got` with the exact answer to `query`. `max_t_ulps` is the accepted error of t (0: t must be
// the correctly rounded one, bit for bit). Throws raykernel::invalid_input when the query is not valid
// input (a NaN or infinite component, a zero direction or normal): there is no answer to compare with.
[[nodiscard]] ReferenceCheck check_against_reference(const Query& query, const Intersection& got,
                                                     std::uint64_t max_t_ulps = 0);
[[nodiscard]] ReferenceCheck check_against_reference(const Query& query, Relation relation, double t,
                                                     std::uint64_t max_t_ulps = 0);

// Formatting used by the report, for users' own messages.
// A double as a hexadecimal float ("0x1.8p+1", "-0x0p+0", "inf", "nan"): exact, and read back by strtod.
[[nodiscard]] std::string hex_string(double x);
// A double in the shortest decimal that reads back to the same double ("0.1", "-0", "inf").
[[nodiscard]] std::string shortest_decimal(double x);
// "o = (x, y, z)  d = (...)  p = (...)  n = (...)", components as hexadecimal floats.
[[nodiscard]] std::string to_string(const Query& query);
// The query as one line of `raykernel classify` input: "ox oy oz dx dy dz px py pz nx ny nz" in hex floats.
[[nodiscard]] std::string classify_line(const Query& query);

std::ostream& operator<<(std::ostream& os, const ReferenceCheck& check);

}  // namespace raykernel::testkit

// Constructors of hard ray–plane queries: the inputs where floating-point ray code goes wrong.
//
// Each kind aims at one weakness (near-parallel rays, origins a few ulps from the plane, exact
// degeneracies, rounding ties, extreme exponents). A constructor draws its randomness from a BitSource, so
// the same construction serves a seeded PRNG (demo, benchmarks), RapidCheck (each draw is a shrinkable
// value: see tests/plane_properties_test.cpp) and fuzzer bytes (fuzz/). Queries are always valid input: finite
// components, nonzero direction and normal.
#pragma once

#include <raykernel/raykernel.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <string_view>

namespace raykernel::testkit {

struct Query {
  Ray ray;
  Plane plane;
};

enum class QueryKind : std::uint8_t {
  random,            // every component uniform in [-1, 1]
  wide_exponents,    // components ±(1 + f)·2^e with e uniform in [-300, 300]
  near_parallel,     // direction projected onto the plane in doubles, then nudged a few ulps: d·n tiny
  near_coplanar,     // origin moved within the plane in doubles, then nudged a few ulps: (p − o)·n tiny
  exact_parallel,    // integer vectors times powers of two with d·n = 0 exactly, origin off the plane
  exact_in_plane,    // d·n = 0 and (p − o)·n = 0 exactly
  origin_on_plane,   // (p − o)·n = 0 exactly, d·n ≠ 0: t = 0
  rounding_tie,      // num/den exactly halfway between two adjacent doubles
  near_tie,          // num/den within 2^-20 .. 2^-60 ulps of a halfway point
  subnormal,         // components between 2^-1074 and 2^-400: products underflow, exact values do not
  huge_products,     // components up to 2^1023: products and differences overflow binary64
  t_overflow,        // |num/den| near or beyond the largest double (2^900 .. 2^1120)
  t_underflow,       // |num/den| in or below the subnormal range
  above_power_of_two,  // |num/den| in (2^e + ulp/4, 2^e + ulp/2): rounds down to 2^e, where the gap below is half
};
inline constexpr int query_kind_count = 14;
inline constexpr std::array<QueryKind, query_kind_count> all_query_kinds = {
    QueryKind::random,         QueryKind::wide_exponents, QueryKind::near_parallel, QueryKind::near_coplanar,
    QueryKind::exact_parallel, QueryKind::exact_in_plane, QueryKind::origin_on_plane, QueryKind::rounding_tie,
    QueryKind::near_tie,       QueryKind::subnormal,      QueryKind::huge_products,  QueryKind::t_overflow,
    QueryKind::t_underflow,    QueryKind::above_power_of_two};

[[nodiscard]] std::string_view to_string(QueryKind kind) noexcept;

// A source of uniformly random 64-bit words.
using BitSource = std::function<std::uint64_t()>;

// A query of the given kind. Deterministic in the words drawn: the same words give the same query.
[[nodiscard]] Query make_query(QueryKind kind, const BitSource& bits);

// SplitMix64 (Steele, Lea, Flood 2014): a small, fast, seedable generator for reproducible streams.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
  std::uint64_t operator()() noexcept {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_;
};

}  // namespace raykernel::testkit

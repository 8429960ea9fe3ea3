// Constructors of hard ray–sphere queries (docs/contract.md §10): the inputs where floating-point ray–sphere
// code goes wrong.
//
// Each kind aims at one weakness: lines exactly tangent (D = 0) and an ulp or a few beside, origins exactly on
// the sphere (C = 0: a root at 0) and a few ulps off, roots that are rounding ties, far-away spheres where
// |o − c|² − r² cancels, wide exponents, tiny and huge directions (roots scaled by 2^±500), and constructions
// scaled into the range where products underflow or overflow, and ties broken by a subnormal coordinate. Where a construction promises an exact property
// (D = 0, C = 0, a tie), every coordinate is an integer times a power of two, so the doubles hold it exactly;
// tests/sphere_test.cpp checks each promise with exact rationals. A construction draws its randomness from a
// BitSource (plane_queries.hpp), so the same construction serves a seeded SplitMix64, RapidCheck and fuzzer
// bytes. Queries are always valid input (finite, nonzero direction, positive radius).
#pragma once

#include <raykernel/sphere.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace raykernel::testkit {

struct SphereQuery {
  Ray ray;
  Sphere sphere;
};

enum class SphereQueryKind : std::uint8_t {
  random,          // every component uniform in [-1, 1], the radius in (0, 1]
  tangent,         // the line exactly tangent: D = 0 (a Pythagorean offset from the centre)
  near_tangent,    // tangent, then the radius or one component of o or d moved by 1–4 ulps
  on_surface,      // the origin exactly on the sphere: C = 0, a root exactly 0
  near_surface,    // on the surface, then one component of o or the radius moved by 1–4 ulps: a root near 0
  rounding_tie,    // a root exactly halfway between two adjacent doubles
  far_cancel,      // |o − c| up to 2^50 times the radius' last bits: C = |o − c|² − r² cancels
  wide_exponents,  // components ±(1 + f)·2^e, e uniform in [-150, 150]
  tiny_direction,  // a tangent or crossing construction with d scaled by 2^-600..2^-400: roots near 2^500
  huge_direction,  // ... d scaled by 2^400..2^600: roots near 2^-500
  tiny,            // a tangent or on-surface construction scaled to 2^-1000..2^-900: products underflow
  huge,            // ... scaled to 2^900..2^980: products overflow
  subnormal_offset,  // roots on rounding ties, then one subnormal coordinate (origin or centre): the ties broken by less than any
                     // double, through a square or a product that underflows in binary64
};
inline constexpr int sphere_query_kind_count = 13;
inline constexpr std::array<SphereQueryKind, sphere_query_kind_count> all_sphere_query_kinds = {
    SphereQueryKind::random,         SphereQueryKind::tangent,        SphereQueryKind::near_tangent,
    SphereQueryKind::on_surface,     SphereQueryKind::near_surface,   SphereQueryKind::rounding_tie,
    SphereQueryKind::far_cancel,     SphereQueryKind::wide_exponents, SphereQueryKind::tiny_direction,
    SphereQueryKind::huge_direction, SphereQueryKind::tiny,           SphereQueryKind::huge,
    SphereQueryKind::subnormal_offset};

[[nodiscard]] std::string_view to_string(SphereQueryKind kind) noexcept;

// A query of the given kind. Deterministic in the words drawn. After the construction the axes are permuted
// and reflected, exactly, so that no kind favours an axis.
[[nodiscard]] SphereQuery make_sphere_query(SphereQueryKind kind, const BitSource& bits);

// The query as one line of `raykernel sphere` input: 10 hexadecimal floats.
[[nodiscard]] std::string sphere_line(const SphereQuery& query);

}  // namespace raykernel::testkit

// fuzz_plane: one ray–plane query per input, answered by raykernel's certified path (`intersect`,
// `intersect_traced`), its exact reference (`intersect_exact`, `intersect_exact_rational`) and an oracle
// that shares no code with either: CGAL's Epeck kernel constructing the intersection point of a Ray_3 and a
// Plane_3 (CGAL::intersection), t recovered from that point exactly.
//
// Input: the layout of raykernel/testkit/plane_fuzz_decoder.hpp. Byte 0 < 0x80: 12 raw doubles (every bit
// pattern: subnormals, signed zeros, NaN, ±inf, every exponent); byte 0 ≥ 0x80: a hard query of one of the
// 13 kinds of raykernel::testkit::make_query, built from the remaining bytes. A custom mutator (below)
// also applies geometric mutations to raw inputs (nudging by ulps, projecting onto the plane, ...).
//
// Checked for every input:
//   - validity: `validate` rejects exactly the inputs with a non-finite component or a zero direction or
//     normal, decided here from the bits; then `intersect`, `intersect_traced`, `intersect_exact` and
//     `intersect_exact_rational` all throw invalid_input with validate's reason;
//   - valid input: relation, the bits of t, and the exact rational t agree between the certified path, the
//     exact path and the CGAL oracle; t is the oracle's exact t rounded by round_rational_to_double, and
//     that rounding is verified independently (exact comparisons with the neighbouring doubles); CGAL's
//     do_intersect agrees; the stages reported are consistent.
#include "fuzz_exact.hpp"
#include "fuzz_support.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_fuzz_decoder.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gmpxx.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using raykernel::Intersection;
using raykernel::Plane;
using raykernel::Ray;
using raykernel::Relation;
using raykernel::Vec3;
using raykernel::fuzz::bits;
using raykernel::fuzz::check;
using raykernel::fuzz::exact_of;
using raykernel::fuzz::is_round_to_nearest_even;
using K = CGAL::Exact_predicates_exact_constructions_kernel;

// ---- The oracle ------------------------------------------------------------------------------------------

// CGAL's exact number type (mpq_class, boost::multiprecision's gmp_rational or CGAL::Gmpq, depending on
// the configuration) as an mpq_class, exactly.
template <class T>
mpq_class to_mpq(const T& x) {
  if constexpr (std::is_same_v<T, mpq_class>) {
    return x;
  } else if constexpr (requires { mpq_class(x.backend().data()); }) {
    return mpq_class(x.backend().data());
  } else if constexpr (requires { mpq_class(x.mpq()); }) {
    return mpq_class(x.mpq());
  } else {
    std::ostringstream s;
    s << x;
    mpq_class q(s.str());
    q.canonicalize();
    return q;
  }
}

struct OracleAnswer {
  Relation relation;
  std::optional<mpq_class> t;  // hit and behind
};

// t with x = o + t·d: t = (x − o)·d / (d·d), exactly; also checks that x is that point of the line and lies
// on the plane, so that a wrong construction cannot go unnoticed.
mpq_class t_of_point(const K::Point_3& x, const Ray& r, const Plane& pl) {
  const mpq_class xs[3] = {to_mpq(CGAL::exact(x.x())), to_mpq(CGAL::exact(x.y())), to_mpq(CGAL::exact(x.z()))};
  const mpq_class o[3] = {exact_of(r.origin.x), exact_of(r.origin.y), exact_of(r.origin.z)};
  const mpq_class d[3] = {exact_of(r.direction.x), exact_of(r.direction.y), exact_of(r.direction.z)};
  const mpq_class p[3] = {exact_of(pl.point.x), exact_of(pl.point.y), exact_of(pl.point.z)};
  const mpq_class n[3] = {exact_of(pl.normal.x), exact_of(pl.normal.y), exact_of(pl.normal.z)};
  mpq_class xo_d = 0, dd = 0, on_plane = 0;
  for (int i = 0; i < 3; ++i) {
    xo_d += (xs[i] - o[i]) * d[i];
    dd += d[i] * d[i];
    on_plane += (xs[i] - p[i]) * n[i];
  }
  const mpq_class t = xo_d / dd;
  for (int i = 0; i < 3; ++i) {
    check(xs[i] == o[i] + t * d[i], "oracle: CGAL's intersection point lies on the ray's line");
  }
  check(on_plane == 0, "oracle: CGAL's intersection point lies on the plane");
  return t;
}

// The contract's answer by CGAL's constructions: Ray_3 ∩ Plane_3 is a point (hit), the ray (in-plane) or
// empty (behind or parallel); the supporting line tells those two apart (a point behind the origin, or
// nothing).
OracleAnswer cgal_oracle(const Ray& r, const Plane& pl) {
  const K::Point_3 o(r.origin.x, r.origin.y, r.origin.z);
  const K::Vector_3 d(r.direction.x, r.direction.y, r.direction.z);
  const K::Point_3 p(pl.point.x, pl.point.y, pl.point.z);
  const K::Vector_3 n(pl.normal.x, pl.normal.y, pl.normal.z);
  const K::Ray_3 ray(o, d);
  const K::Plane_3 plane(p, n);  // a, b, c = n and d = −n·p, computed exactly in Epeck

  const auto on_ray = CGAL::intersection(ray, plane);
  const bool do_intersect = CGAL::do_intersect(ray, plane);
  check(do_intersect == static_cast<bool>(on_ray), "oracle: CGAL's do_intersect agrees with its intersection");
  if (on_ray) {
    if (const K::Point_3* x = boost::get<K::Point_3>(&*on_ray)) {
      mpq_class t = t_of_point(*x, r, pl);
      check(t >= 0, "oracle: a point of the ray has t >= 0");
      return {Relation::hit, std::move(t)};
    }
    check(boost::get<K::Ray_3>(&*on_ray) != nullptr, "oracle: Ray_3 ∩ Plane_3 is a point or the ray");
    return {Relation::in_plane, std::nullopt};
  }
  const auto on_line = CGAL::intersection(ray.supporting_line(), plane);
  if (!on_line) return {Relation::parallel, std::nullopt};
  const K::Point_3* x = boost::get<K::Point_3>(&*on_line);
  check(x != nullptr, "oracle: a line in the plane contains the ray, so Ray_3 ∩ Plane_3 was not empty");
  mpq_class t = t_of_point(*x, r, pl);
  check(t < 0, "oracle: a point of the line that is not on the ray has t < 0");
  return {Relation::behind, std::move(t)};
}

// ---- Checks independent of the kernel: validity from the bits, rounding verified in rationals ------------

bool invalid_by_bits(const Ray& r, const Plane& p) {
  return raykernel::fuzz::ray_invalid_by_bits(r) || raykernel::fuzz::plane_invalid_by_bits(p);
}

std::string relation_name(Relation r) { return std::string(raykernel::to_string(r)); }

// ---- The current input, for failure reports and statistics ---------------------------------------------

struct Current {
  raykernel::testkit::FuzzQuery decoded;
  std::size_t size = 0;
};
Current current;

std::string describe_current() {
  const auto& q = current.decoded.query;
  const std::string mode = current.decoded.kind
                               ? std::string("hard query ").append(raykernel::testkit::to_string(*current.decoded.kind))
                               : std::string("raw doubles");
  std::string s = "input: " + std::to_string(current.size) + " bytes, mode " + mode +
                  "\nquery (ox oy oz dx dy dz px py pz nx ny nz, hex floats; a raykernel classify line):\n";
  for (const Vec3& v : {q.ray.origin, q.ray.direction, q.plane.point, q.plane.normal}) {
    for (double c : {v.x, v.y, v.z}) s += raykernel::fuzz::hex(c) + " ";
  }
  s += "\nbit patterns:";
  for (const Vec3& v : {q.ray.origin, q.ray.direction, q.plane.point, q.plane.normal}) {
    for (double c : {v.x, v.y, v.z}) s.append(" ").append(raykernel::fuzz::bits_of(c));
  }
  return s;
}

// Per decoder mode: raw, then the 13 kinds.
raykernel::fuzz::StageCounts stats_by_mode[1 + raykernel::testkit::query_kind_count];
std::size_t mode_index(const raykernel::testkit::FuzzQuery& f) {
  if (!f.kind) return 0;
  for (std::size_t k = 0; k < raykernel::testkit::all_query_kinds.size(); ++k) {
    if (raykernel::testkit::all_query_kinds[k] == *f.kind) return 1 + k;
  }
  return 0;
}

void print_stats() {
  std::vector<std::pair<std::string, raykernel::fuzz::StageCounts>> rows;
  rows.emplace_back("raw", stats_by_mode[0]);
  for (std::size_t k = 0; k < raykernel::testkit::all_query_kinds.size(); ++k) {
    const raykernel::testkit::QueryKind kind = raykernel::testkit::all_query_kinds[k];
    rows.emplace_back(std::string(raykernel::testkit::to_string(kind)), stats_by_mode[1 + k]);
  }
  std::fputs(raykernel::fuzz::format_stage_table("classify", rows).c_str(), stderr);
}

// Runs `f`, which must throw invalid_input with message `reason`.
template <class F>
void expect_rejected(F&& f, const std::string& reason, const char* what) {
  try {
    (void)f();
  } catch (const raykernel::invalid_input& e) {
    check(reason == e.what(), [&] {
      return std::string(what) + " throws invalid_input with validate's reason (got '" + e.what() +
             "', validate says '" + reason + "')";
    });
    return;
  }
  check(false, [&] { return std::string(what) + " throws invalid_input on invalid input"; });
}

void check_query(const Ray& ray, const Plane& plane, raykernel::fuzz::StageCounts& stats) {
  // The baseline has no precondition: it must merely not misbehave (the sanitizers watch it).
  (void)raykernel::intersect_naive(ray, plane);

  const std::optional<std::string> reason = raykernel::validate(ray, plane);
  const bool invalid = invalid_by_bits(ray, plane);
  check(reason.has_value() == invalid, invalid ? "validate rejects a non-finite component or a zero direction/normal"
                                               : "validate accepts finite input with nonzero direction and normal");
  if (invalid) {
    check(!reason->empty(), "validate's reason is not empty");
    expect_rejected([&] { return raykernel::intersect(ray, plane); }, *reason, "intersect");
    expect_rejected([&] { return raykernel::intersect_traced(ray, plane); }, *reason, "intersect_traced");
    expect_rejected([&] { return raykernel::intersect_exact(ray, plane); }, *reason, "intersect_exact");
    expect_rejected([&] { return raykernel::intersect_exact_rational(ray, plane); }, *reason,
                    "intersect_exact_rational");
    stats.add_invalid();
    return;
  }

  const raykernel::TracedIntersection traced = raykernel::intersect_traced(ray, plane);
  const Intersection certified = traced.intersection;
  const Intersection plain = raykernel::intersect(ray, plane);
  const Intersection exact = raykernel::intersect_exact(ray, plane);
  const raykernel::ExactIntersection rational = raykernel::intersect_exact_rational(ray, plane);
  check(raykernel::floating_point_environment_is_default(), "the floating-point environment is left as it was");
  const OracleAnswer oracle = cgal_oracle(ray, plane);
  check(raykernel::floating_point_environment_is_default(), "CGAL leaves the floating-point environment as it was");
  stats.add(traced);

  auto relations = [&] {
    return "relations agree: certified " + relation_name(certified.relation) + ", intersect " +
           relation_name(plain.relation) + ", exact " + relation_name(exact.relation) + ", exact_rational " +
           relation_name(rational.intersection.relation) + ", CGAL " + relation_name(oracle.relation);
  };
  check(certified.relation == oracle.relation && plain.relation == oracle.relation &&
            exact.relation == oracle.relation && rational.intersection.relation == oracle.relation,
        relations);

  const bool has_t = oracle.relation == Relation::hit || oracle.relation == Relation::behind;
  if (!has_t) {
    check(std::isnan(certified.t) && std::isnan(plain.t) && std::isnan(exact.t) && std::isnan(rational.intersection.t),
          "t is NaN for parallel and in-plane");
    check(!rational.t.has_value(), "no exact t for parallel and in-plane");
    check(traced.t_stage == traced.relation_stage, "t_stage == relation_stage when there is no t");
    return;
  }

  const mpq_class& t = *oracle.t;
  check(rational.t.has_value(), "intersect_exact_rational gives an exact t for hit and behind");
  const std::string numerator = t.get_num().get_str(), denominator = t.get_den().get_str();
  check(rational.t->numerator == numerator && rational.t->denominator == denominator,
        [&] { return "the exact t agrees with CGAL's: kernel " + rational.t->str() + ", CGAL " + t.get_str(); });
  const double rounded = raykernel::round_rational_to_double(numerator, denominator);
  check(is_round_to_nearest_even(t, rounded), [&] {
    return "round_rational_to_double(" + t.get_str() + ") = " + raykernel::fuzz::hex(rounded) +
           " is RN(t), ties to even";
  });
  check(bits(certified.t) == bits(rounded) && bits(plain.t) == bits(rounded) && bits(exact.t) == bits(rounded) &&
            bits(rational.intersection.t) == bits(rounded),
        [&] {
          using raykernel::fuzz::hex;
          return "the bits of t agree: certified " + hex(certified.t) + ", intersect " + hex(plain.t) + ", exact " +
                 hex(exact.t) + ", exact_rational " + hex(rational.intersection.t) + ", RN(CGAL's t = " + t.get_str() +
                 ") " + hex(rounded);
        });
  if (t == 0) check(traced.t_stage == traced.relation_stage, "t_stage == relation_stage when t = 0 exactly");
}

// ---- The custom mutator ----------------------------------------------------------------------------------

// Geometric mutations of raw inputs. libFuzzer's byte mutations keep a random query random: a direction a few
// ulps from the plane essentially never appears. These move a raw query toward the degenerate
// cases — onto the plane, parallel to it, onto exact small integers, to extreme exponents — and still leave
// the bytes to libFuzzer's own mutations a quarter of the time.
//
// Two switches measure what the structure adds (fuzz/README.md, "Measurements"):
//   RAYKERNEL_FUZZ_PLAIN_MUTATOR=1  libFuzzer's byte mutations only (the decoder's modes stay);
//   RAYKERNEL_FUZZ_RAW_ONLY=1       no structure at all: every input is read as raw doubles after byte 0
//                                   (the hard-query mode is off) and the mutations are libFuzzer's.
bool environment_flag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' && std::string_view(v) != "0";
}
bool raw_only_requested() {
  static const bool raw_only = environment_flag("RAYKERNEL_FUZZ_RAW_ONLY");
  return raw_only;
}
bool plain_mutator_requested() {
  static const bool plain = environment_flag("RAYKERNEL_FUZZ_PLAIN_MUTATOR") || raw_only_requested();
  return plain;
}

double& component(Vec3& v, std::uint64_t i) { return i % 3 == 0 ? v.x : (i % 3 == 1 ? v.y : v.z); }
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 axpy(double s, const Vec3& x, const Vec3& y) { return {s * x.x + y.x, s * x.y + y.y, s * x.z + y.z}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

void mutate_query(raykernel::testkit::Query& q, raykernel::testkit::SplitMix64& rng) {
  Vec3* vectors[4] = {&q.ray.origin, &q.ray.direction, &q.plane.point, &q.plane.normal};
  Vec3& o = q.ray.origin;
  Vec3& d = q.ray.direction;
  Vec3& p = q.plane.point;
  Vec3& n = q.plane.normal;
  const std::uint64_t r = rng();
  const std::uint64_t which = rng();
  switch (r % 10) {
    case 0: {  // nudge one component by 1..8 ulps either way
      double& c = component(*vectors[which % 4], which >> 8);
      const int steps = 1 + static_cast<int>((which >> 16) % 8);
      for (int k = 0; k < steps; ++k) c = std::nextafter(c, (which >> 24) & 1 ? HUGE_VAL : -HUGE_VAL);
      break;
    }
    case 1:  // d projected onto the plane in doubles: d·n a few rounding errors from zero
      if (dot(n, n) != 0) d = axpy(-(dot(d, n) / dot(n, n)), n, d);
      break;
    case 2:  // o moved onto the plane in doubles: (p − o)·n a few rounding errors from zero
      if (dot(n, n) != 0) o = axpy(dot(Vec3{p.x - o.x, p.y - o.y, p.z - o.z}, n) / dot(n, n), n, o);
      break;
    case 3: {  // d = n × w: exactly orthogonal when the products are exact (small integers), else nearly
      const Vec3 w = *vectors[which % 4];
      d = cross(n, w);
      break;
    }
    case 4:  // origin on the plane exactly, or one coordinate shared
      if ((which & 3) == 0)
        o = p;
      else
        component(o, which >> 2) = component(p, which >> 2);
      break;
    case 5: {  // scale a vector by 2^k, k in [-1100, 1100]: every exponent range, exactly when no under/overflow
      const int k = static_cast<int>((which >> 8) % 2201) - 1100;
      Vec3& v = *vectors[which % 4];
      v = {std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
      break;
    }
    case 6: {  // a special value in one component
      // clang-format off
      static const double special[] = {
          0.0, -0.0, 1.0, -1.0, 2.0, 0.5, 3.0, DBL_MIN, -DBL_MIN, DBL_TRUE_MIN, -DBL_TRUE_MIN, DBL_MAX, -DBL_MAX,
          0x1p-537, 0x1p511, 0x1p-1022 - 0x1p-1074, HUGE_VAL, -HUGE_VAL, std::numeric_limits<double>::quiet_NaN(),
          DBL_EPSILON, 1.0 + DBL_EPSILON, 1.0 - DBL_EPSILON / 2};
      // clang-format on
      component(*vectors[which % 4], which >> 8) = special[(which >> 16) % (sizeof special / sizeof special[0])];
      break;
    }
    case 7:  // small integers: exact arithmetic everywhere, so exact degeneracies become likely
      for (Vec3* v : vectors) {
        for (std::uint64_t i = 0; i < 3; ++i) {
          const std::uint64_t bits_i = rng();
          component(*v, i) = static_cast<double>(static_cast<int>(bits_i % 9) - 4);
        }
      }
      break;
    case 8: {  // copy one vector over another (d = n, p = o, ...) or negate one
      Vec3& to = *vectors[which % 4];
      const Vec3& from = *vectors[(which >> 2) % 4];
      if (&to == &from)
        to = {-to.x, -to.y, -to.z};
      else
        to = from;
      break;
    }
    default: {  // a random component, uniform over all bit patterns
      component(*vectors[which % 4], which >> 8) = std::bit_cast<double>(rng());
      break;
    }
  }
}

}  // namespace

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size)
    __attribute__((weak));

// Raw inputs: a quarter of the time libFuzzer's byte mutations, rarely a switch to the hard-query mode
// (the same bytes read as make_query's words), otherwise 1–3 geometric mutations. Hard-query inputs: mostly
// libFuzzer's mutations of the words (the kind kept), sometimes another kind, and sometimes the query is
// made concrete as a raw input and mutated geometrically (a near tie nudged by an ulp, ...).
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  namespace rt = raykernel::testkit;
  auto byte_mutation = [&](std::size_t skip) {
    if (LLVMFuzzerMutate == nullptr || size < skip || max_size <= skip) return size;
    return skip + LLVMFuzzerMutate(data + skip, size - skip, max_size - skip);
  };
  if (plain_mutator_requested() || max_size < rt::raw_fuzz_input_size) return byte_mutation(0);
  rt::SplitMix64 rng(seed);
  const std::uint64_t choice = rng() % 16;
  auto switch_kind = [&] {
    if (size == 0) return byte_mutation(0);
    data[0] = static_cast<std::uint8_t>(rt::hard_query_selector + rng() % rt::query_kind_count);
    return size;
  };
  const bool raw = size == 0 || data[0] < rt::hard_query_selector;
  if (raw && choice < 4) return byte_mutation(0);
  if (raw && choice == 4) return switch_kind();
  if (!raw && choice < 2) return byte_mutation(0);
  if (!raw && choice < 4) return switch_kind();
  if (!raw && choice >= 7) return byte_mutation(1);

  rt::Query q = rt::decode_fuzz_query({data, size}).query;
  const int rounds = 1 + static_cast<int>(rng() % 3);
  for (int k = 0; k < rounds; ++k) mutate_query(q, rng);
  const std::vector<std::uint8_t> bytes = rt::encode_raw_fuzz_input(q.ray, q.plane);
  std::memcpy(data, bytes.data(), bytes.size());
  return bytes.size();
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("classify");
    raykernel::fuzz::set_input_describer(describe_current);
    raykernel::fuzz::print_at_exit(print_stats);
    return true;
  }();
  (void)initialized;
  const std::span<const std::uint8_t> bytes(data, size);
  current.decoded =
      raw_only_requested()
          ? raykernel::testkit::FuzzQuery{raykernel::testkit::decode_raw_doubles(bytes.subspan(size ? 1 : 0)), {}}
          : raykernel::testkit::decode_fuzz_query(bytes);
  current.size = size;
  if (!current.decoded.kind && !raw_only_requested()) {
    // The decoder's promise: the encoder inverts it (the input, zero-padded to 97 bytes, extra bytes cut).
    const std::vector<std::uint8_t> encoded =
        raykernel::testkit::encode_raw_fuzz_input(current.decoded.query.ray, current.decoded.query.plane);
    for (std::size_t k = 1; k < encoded.size(); ++k) {
      check(encoded[k] == (k < size ? data[k] : 0), "encode_raw_fuzz_input inverts decode_fuzz_query");
    }
  }
  check_query(current.decoded.query.ray, current.decoded.query.plane, stats_by_mode[mode_index(current.decoded)]);
  return 0;
}

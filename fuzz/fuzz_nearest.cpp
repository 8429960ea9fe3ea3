// fuzz_nearest: a ray and a handful of planes, answered by raykernel's certified nearest hit (`nearest_hit`,
// `nearest_hit_traced`, `nearest_hit_batch`) and its exact reference (`nearest_hit_exact`), against a
// brute-force search written here in GMP rationals (docs/contract.md §4).
//
// Input (structure-aware, so that near ties between planes are the common case; layout below, and in
// fuzz/README.md): record 0 (97 bytes) gives the ray and its first planes — a raw query or a hard query of
// raykernel::testkit::decode_fuzz_query, or a near-tie pair of make_plane_pair_near_tie; every further
// record (49 bytes) adds planes — raw bit patterns, the plane of a hard query, or a plane derived from the
// ray and the planes so far: a coincident copy (normal scaled by ±2^k, or negated), a copy nudged by ulps,
// a parallel offset, planes through a common point of the ray or through a plane's point, planes through the
// origin, containing the ray's direction, or behind it, small-integer planes.
//
// Checked for every input:
//   - validity: the ray and each plane are invalid exactly when the bits say so (validate_ray,
//     validate_plane); then nearest_hit, nearest_hit_traced and nearest_hit_exact throw invalid_input naming
//     the ray's reason, or "plane K: REASON" for the first invalid plane K; with no planes at all,
//     nearest_hit is a miss or throws the ray's reason; nearest_hit_batch throws "plane K:
//     REASON" for an invalid plane, else "query I: REASON" for the first invalid ray I;
//   - valid input: the oracle — num = (p − o)·n and den = d·n exactly (GMP rationals from the doubles'
//     exact values), hit iff den ≠ 0 and num/den ≥ 0, the smallest exact t, ties to the smallest index — and
//     nearest_hit, nearest_hit_traced and nearest_hit_exact give the same plane, with t = the oracle's t
//     rounded to nearest (verified by exact comparison with the neighbouring doubles, and equal to
//     round_rational_to_double) and equal to intersect's t for that plane; the same for the reversed ray
//     (o, −d), whose exact t are the negated ones; nearest_hit_batch gives nearest_hit's answer for the ray,
//     the reversed ray and the ray moved to o + d; each plane's relation (intersect_traced) is the oracle's;
//   - the trace adds up: one comparison per hit plane after the first (planes coinciding with an earlier
//     one set aside, as PlaneSet does: checked independently), comparison_stage the slowest stage
//     that decided one, relation_stage the slowest of the planes' (intersect_traced's) relation stages,
//     t_stage filter on a miss, the winner's relation stage when t = 0 exactly, past the filter otherwise.
#include "fuzz_exact.hpp"
#include "fuzz_support.hpp"

#include <raykernel/batch.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_fuzz_decoder.hpp>
#include <raykernel/testkit/plane_pairs.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace {

using raykernel::NearestHit;
using raykernel::Plane;
using raykernel::Ray;
using raykernel::Relation;
using raykernel::Stage;
using raykernel::Vec3;
using raykernel::fuzz::bits;
using raykernel::fuzz::check;
using raykernel::fuzz::exact_of;
namespace rt = raykernel::testkit;

// ---- The input ---------------------------------------------------------------------------------------------

constexpr std::size_t first_record_size = rt::raw_fuzz_input_size;  // 97: a classify input
constexpr std::size_t plane_record_size = 49;                       // a tag byte and 6 words
constexpr std::size_t max_plane_records = 63;                       // at most 2 + 63 planes

// Record 0, by its first byte: below 0xC0 a decode_fuzz_query input (raw < 0x80, hard query 0x80..0xBF),
// from 0xC0 a near-tie pair of kind (byte − 0xC0) mod 4.
constexpr std::uint8_t pair_selector = 0xC0;
// Records 1.., by their first byte: 0x00..0x3F a raw plane, 0x40..0x7F the plane of a hard query of kind
// (byte − 0x40) mod 13, 0x80..0xFF the derived plane (byte >> 4) & 7 (DerivedPlane).
constexpr std::uint8_t hard_plane_selector = 0x40;
constexpr std::uint8_t derived_plane_selector = 0x80;

enum class DerivedPlane : std::uint8_t {
  coincident,          // plane K with its normal scaled by ±2^e, e in [−10, 10]: an exact tie with K
  negated,             // plane K with its normal negated, through another plane's point when that point
                       // lies on K exactly: an exact tie
  nudged,              // plane K with one component moved by 1..8 ulps: t a few ulps (or less) from K's
  parallel_offset,     // plane K's point moved along its normal by ±2^-e·n, e in [20, 79]: a near tie
  through_ray_point,   // a plane through o + τ·d (in doubles), τ = K's rounded t or m·2^e: planes made from
                       // the same τ meet the ray at (nearly) the same point
  pivot_about_point,   // plane K turned about its point: n + c·(d × axis), c = ±2^e, e in [−30, 30]; an exact
                       // tie when K's point is on the ray (pivot pairs, origin-on-plane queries)
  special_relation,    // through the origin (t = 0), containing d (parallel, in-plane), K reflected through
                       // the origin (behind), or K's normal through o + d
  small_integers,      // small integers times a power of two: exact degeneracies with integral rays
};
constexpr int derived_plane_count = 8;
const char* const derived_plane_names[derived_plane_count] = {
    "coincident", "negated", "nudged", "parallel-offset", "through-ray-point", "pivot-about-point",
    "special-relation", "small-integers"};

// The words of a record: its bytes 8 at a time, little-endian, the last word zero-padded; then, for
// constructions that draw more words than the record holds (a near-tie pair draws about 26), a SplitMix64
// stream seeded from the record's bytes, so that every byte still changes the construction.
rt::BitSource record_words(std::span<const std::uint8_t> bytes) {
  std::uint64_t seed = 0xcbf29ce484222325ULL;  // FNV-1a
  for (std::uint8_t b : bytes) seed = (seed ^ b) * 0x100000001b3ULL;
  struct State {
    std::span<const std::uint8_t> bytes;
    std::size_t offset;
    rt::SplitMix64 tail;
  };
  auto state = std::make_shared<State>(State{bytes, 0, rt::SplitMix64(seed)});
  return [state] {
    if (state->offset >= state->bytes.size()) return state->tail();
    std::uint64_t w = 0;
    for (std::size_t k = 0; k < 8 && state->offset + k < state->bytes.size(); ++k)
      w |= std::uint64_t{state->bytes[state->offset + k]} << (8 * k);
    state->offset += 8;
    return w;
  };
}

double& component(Vec3& v, std::uint64_t i) { return i % 3 == 0 ? v.x : (i % 3 == 1 ? v.y : v.z); }
Vec3 add(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 scaled(double s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
bool is_zero(const Vec3& v) { return v.x == 0 && v.y == 0 && v.z == 0; }
// Three small integers in [−r, r] from the bytes of a word.
Vec3 small_vector(std::uint64_t w, int r) {
  auto c = [&](int i) { return static_cast<double>(static_cast<int>((w >> (8 * i)) & 0xff) % (2 * r + 1) - r); };
  return {c(0), c(1), c(2)};
}

// Whether point q lies exactly on plane p.
bool on_plane_exactly(const Vec3& q, const Plane& p) {
  const Vec3& a = p.point;
  const Vec3& n = p.normal;
  if (!raykernel::fuzz::finite_vector_by_bits(q) || raykernel::fuzz::plane_invalid_by_bits(p)) return false;
  const mpq_class s = (exact_of(q.x) - exact_of(a.x)) * exact_of(n.x) + (exact_of(q.y) - exact_of(a.y)) * exact_of(n.y) +
                      (exact_of(q.z) - exact_of(a.z)) * exact_of(n.z);
  return sgn(s) == 0;
}

Plane derived_plane(DerivedPlane op, const rt::BitSource& words, const Ray& ray, const std::vector<Plane>& planes) {
  const std::uint64_t w0 = words(), w1 = words(), w2 = words(), w3 = words();
  const Plane& base = planes[w0 % planes.size()];
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  Plane p = base;
  switch (op) {
    case DerivedPlane::coincident: {
      const double s = std::ldexp((w1 >> 8) & 1 ? -1.0 : 1.0, static_cast<int>(w1 % 21) - 10);
      p.normal = scaled(s, base.normal);
      break;
    }
    case DerivedPlane::negated: {
      p.normal = scaled(-1.0, base.normal);
      const Plane& other = planes[w1 % planes.size()];
      if (on_plane_exactly(other.point, base)) p.point = other.point;
      break;
    }
    case DerivedPlane::nudged: {
      double& c = (w1 & 1) ? component(p.normal, w1 >> 1) : component(p.point, w1 >> 1);
      const int steps = 1 + static_cast<int>((w1 >> 8) % 8);
      for (int k = 0; k < steps; ++k) c = std::nextafter(c, (w1 >> 16) & 1 ? HUGE_VAL : -HUGE_VAL);
      break;
    }
    case DerivedPlane::parallel_offset: {
      const double s = std::ldexp((w1 >> 8) & 1 ? -1.0 : 1.0, -20 - static_cast<int>(w1 % 60));
      p.point = add(base.point, scaled(s, base.normal));
      break;
    }
    case DerivedPlane::through_ray_point: {
      double tau = std::ldexp(static_cast<double>(1 + w1 % 7), static_cast<int>((w1 >> 8) % 41) - 20);
      if ((w1 >> 16) & 1) {
        if (!raykernel::validate(ray, base)) {
          const raykernel::Intersection x = raykernel::intersect(ray, base);
          if (x.relation == Relation::hit || x.relation == Relation::behind) tau = x.t;
        }
      }
      p.point = add(o, scaled(tau, d));
      const Vec3 n = small_vector(w2, 4);
      p.normal = is_zero(n) ? base.normal : n;
      break;
    }
    case DerivedPlane::pivot_about_point: {
      Vec3 axis{0, 0, 0};
      component(axis, w1) = 1;
      const double c = std::ldexp((w1 >> 8) & 1 ? -1.0 : 1.0, static_cast<int>(w2 % 61) - 30);
      p.normal = add(base.normal, scaled(c, cross(d, axis)));
      break;
    }
    case DerivedPlane::special_relation: {
      const Vec3 n = small_vector(w2, 4);
      switch (w1 % 4) {
        case 0:  // through the origin: t = 0 (or in-plane)
          p.point = o;
          p.normal = is_zero(n) ? base.normal : n;
          break;
        case 1:  // containing the direction (exactly when the products are exact): parallel or in-plane
          p.point = (w1 >> 8) & 1 ? o : base.point;
          p.normal = cross(d, is_zero(n) ? base.normal : n);
          break;
        case 2:  // plane K reflected through the origin: t = −t_K, behind when K is hit
          p.point = add(scaled(2.0, o), scaled(-1.0, base.point));
          break;
        default:  // K's normal through o + d: t = 1, exactly when o + d is exact
          p.point = add(o, d);
          break;
      }
      break;
    }
    case DerivedPlane::small_integers: {
      const int e = static_cast<int>(w3 % 21) - 10;
      const Vec3 q = small_vector(w1, 8);
      p.point = {std::ldexp(q.x, e), std::ldexp(q.y, e), std::ldexp(q.z, e)};
      p.normal = small_vector(w2, 4);
      break;
    }
  }
  return p;
}

// Where the ray and the first planes came from, for the statistics: raw, the 13 hard kinds, the 4 pairs.
constexpr std::size_t mode_count = 1 + rt::query_kind_count + rt::plane_tie_kind_count;
std::string mode_name(std::size_t mode) {
  if (mode == 0) return "raw";
  if (mode <= rt::query_kind_count) return std::string(rt::to_string(rt::all_query_kinds[mode - 1]));
  return "pair " + std::string(rt::to_string(rt::all_plane_tie_kinds[mode - 1 - rt::query_kind_count]));
}

struct Decoded {
  Ray ray{};
  std::vector<Plane> planes;
  std::vector<std::string> origin;  // per plane: the record that made it
  std::size_t mode = 0;
  std::array<std::uint32_t, derived_plane_count> derived{};  // how many planes each derived kind made
};

// RAYKERNEL_FUZZ_RAW_ONLY=1: no structure — every record is raw doubles whatever its first byte (record 0 the
// ray and plane 0, the others a plane), to measure what the structure adds (fuzz/README.md, "Measurements").
bool raw_only_requested() {
  static const bool raw_only = [] {
    const char* v = std::getenv("RAYKERNEL_FUZZ_RAW_ONLY");
    return v != nullptr && *v != '\0' && std::string_view(v) != "0";
  }();
  return raw_only;
}

Decoded decode(std::span<const std::uint8_t> bytes) {
  Decoded in;
  const std::span<const std::uint8_t> first = bytes.subspan(0, std::min(bytes.size(), first_record_size));
  if (raw_only_requested()) {
    const rt::Query q = rt::decode_raw_doubles(first.subspan(first.empty() ? 0 : 1));
    in.ray = q.ray;
    in.planes = {q.plane};
    in.origin = {"record 0 (raw)"};
  } else if (!first.empty() && first[0] >= pair_selector) {
    const auto kind = rt::all_plane_tie_kinds[static_cast<std::size_t>(first[0] - pair_selector) % rt::plane_tie_kind_count];
    const rt::PlanePair pair = rt::make_plane_pair_near_tie(kind, record_words(first.subspan(1)));
    in.ray = pair.ray;
    in.planes = {pair.planes[0], pair.planes[1]};
    in.mode = 1 + rt::query_kind_count + static_cast<std::size_t>(kind);
    const std::string name = "record 0 (pair " + std::string(rt::to_string(kind)) + ")";
    in.origin = {name, name};
  } else {
    const rt::FuzzQuery f = rt::decode_fuzz_query(first);
    in.ray = f.query.ray;
    in.planes = {f.query.plane};
    in.mode = f.kind ? 1 + static_cast<std::size_t>(*f.kind) : 0;
    in.origin = {"record 0 (" + (f.kind ? std::string(rt::to_string(*f.kind)) : std::string("raw")) + ")"};
  }
  std::size_t record = 1;
  for (std::size_t offset = first_record_size; offset < bytes.size() && record <= max_plane_records;
       offset += plane_record_size, ++record) {
    const std::span<const std::uint8_t> r = bytes.subspan(offset, std::min(plane_record_size, bytes.size() - offset));
    const std::uint8_t tag = r[0];
    const rt::BitSource words = record_words(r.subspan(1));
    const std::string where = "record " + std::to_string(record);
    if (tag < hard_plane_selector || raw_only_requested()) {
      double c[6];
      for (double& x : c) x = std::bit_cast<double>(words());
      in.planes.push_back({{c[0], c[1], c[2]}, {c[3], c[4], c[5]}});
      in.origin.push_back(where + " (raw)");
    } else if (tag < derived_plane_selector) {
      const rt::QueryKind kind = rt::all_query_kinds[static_cast<std::size_t>(tag - hard_plane_selector) % rt::query_kind_count];
      in.planes.push_back(rt::make_query(kind, rt::bit_source_from_bytes(r.subspan(1))).plane);
      in.origin.push_back(where + " (plane of a " + std::string(rt::to_string(kind)) + " query)");
    } else {
      const auto op = static_cast<DerivedPlane>((tag >> 4) & 7);
      in.planes.push_back(derived_plane(op, words, in.ray, in.planes));
      in.origin.push_back(where + " (" + derived_plane_names[static_cast<int>(op)] + ")");
      ++in.derived[static_cast<std::size_t>(op)];
    }
  }
  return in;
}

// ---- The oracle --------------------------------------------------------------------------------------------

// num = (p − o)·n and den = d·n of each plane, exactly.
struct ExactPlane {
  mpq_class num, den;
};

std::vector<ExactPlane> exact_planes(const Ray& ray, const std::vector<Plane>& planes) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  const mpq_class ox = exact_of(o.x), oy = exact_of(o.y), oz = exact_of(o.z);
  const mpq_class dx = exact_of(d.x), dy = exact_of(d.y), dz = exact_of(d.z);
  std::vector<ExactPlane> out;
  out.reserve(planes.size());
  for (const Plane& p : planes) {
    const mpq_class nx = exact_of(p.normal.x), ny = exact_of(p.normal.y), nz = exact_of(p.normal.z);
    out.push_back({(exact_of(p.point.x) - ox) * nx + (exact_of(p.point.y) - oy) * ny + (exact_of(p.point.z) - oz) * nz,
                   dx * nx + dy * ny + dz * nz});
  }
  return out;
}

// Whether plane j describes the same point set as an earlier plane i: n_i × n_j = 0 and (p_j − p_i)·n_i = 0,
// exactly. Such a plane has the same t as plane i along every ray, so a PlaneSet sets it aside.
std::vector<bool> coincident_with_earlier(const std::vector<Plane>& planes) {
  std::vector<bool> out(planes.size(), false);
  for (std::size_t j = 0; j < planes.size(); ++j) {
    const mpq_class nj[3] = {exact_of(planes[j].normal.x), exact_of(planes[j].normal.y), exact_of(planes[j].normal.z)};
    const mpq_class pj[3] = {exact_of(planes[j].point.x), exact_of(planes[j].point.y), exact_of(planes[j].point.z)};
    for (std::size_t i = 0; i < j && !out[j]; ++i) {
      const mpq_class ni[3] = {exact_of(planes[i].normal.x), exact_of(planes[i].normal.y), exact_of(planes[i].normal.z)};
      const mpq_class pi[3] = {exact_of(planes[i].point.x), exact_of(planes[i].point.y), exact_of(planes[i].point.z)};
      const bool parallel = ni[1] * nj[2] == ni[2] * nj[1] && ni[2] * nj[0] == ni[0] * nj[2] && ni[0] * nj[1] == ni[1] * nj[0];
      out[j] = parallel && (pj[0] - pi[0]) * ni[0] + (pj[1] - pi[1]) * ni[1] + (pj[2] - pi[2]) * ni[2] == 0;
    }
  }
  return out;
}

// docs/contract.md §1's relation from the exact signs; for the reversed ray (o, −d) den changes sign.
Relation oracle_relation(const ExactPlane& e, bool reversed) {
  const int num = sgn(e.num), den = reversed ? -sgn(e.den) : sgn(e.den);
  if (den == 0) return num == 0 ? Relation::in_plane : Relation::parallel;
  return num == 0 || num == den ? Relation::hit : Relation::behind;
}

struct OracleAnswer {
  std::optional<std::size_t> plane;  // the winner
  mpq_class t;                       // its exact t
  std::size_t hits = 0;              // planes hit
  std::size_t tied = 0;              // planes hit at exactly t
  std::optional<mpq_class> runner_up;  // the smallest exact t > t among the planes hit
};

// The brute-force search of docs/contract.md §4: every plane hit, the smallest exact t, ties to the smallest index.
OracleAnswer brute_force(const std::vector<ExactPlane>& planes, bool reversed) {
  OracleAnswer a;
  std::vector<std::pair<std::size_t, mpq_class>> hit;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    if (oracle_relation(planes[k], reversed) != Relation::hit) continue;
    mpq_class t = planes[k].num / planes[k].den;
    if (reversed) t = -t;
    if (!a.plane || t < a.t) {
      a.plane = k;
      a.t = t;
    }
    hit.emplace_back(k, std::move(t));
  }
  a.hits = hit.size();
  for (const auto& [k, t] : hit) {
    if (t == a.t) ++a.tied;
    else if (!a.runner_up || t < *a.runner_up) a.runner_up = t;
  }
  return a;
}

// ---- Statistics --------------------------------------------------------------------------------------------

struct NearestStats {
  std::uint64_t executions = 0, invalid = 0, misses = 0, planes = 0;
  std::uint64_t compared = 0;  // executions with at least one comparison of two t values (≥ 2 planes hit)
  std::uint64_t exact_tie = 0;  // ... whose smallest t is shared by two planes or more
  std::uint64_t sub_ulp = 0;    // ... whose runner-up t is less than an ulp of the winner's (normal) t away
  std::array<std::uint64_t, 4> comparison_deepest{};  // executions with a comparison, by its slowest stage
  std::array<std::uint64_t, 4> comparisons{};         // comparisons, by the stage that decided them
  std::array<std::uint64_t, 4> relation_deepest{};    // valid executions, by relation_stage
  std::array<std::uint64_t, 4> t_stage{};             // executions with a hit, by t_stage
};
NearestStats stats_by_mode[mode_count];
std::array<std::uint64_t, derived_plane_count> derived_planes{};
std::uint64_t comparisons_reversed_deepest[4] = {};

void print_stats() {
  using raykernel::fuzz::percent_text;
  using raykernel::fuzz::shares_text;
  std::string out =
      "==== raykernel fuzz stats: nearest (percentages)\n"
      "  invalid: of executions; miss, >=2 hit: of valid executions (>=2 hit: two t values were compared)\n"
      "  tie: the smallest t is shared exactly; <ulp: the runner-up t is less than an ulp of the winner's t away,\n"
      "    the winner's t a normal double (of >=2 hit)\n"
      "  comparison stage: the slowest stage one comparison needed, of executions with >=2 hits\n"
      "  comparisons: every comparison by the stage that decided it\n"
      "  relation stage: the slowest stage a plane's relation needed; t stage: the winner's t, hits only\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-24s %9s %6s %6s %6s %6s %6s %5s |%-28s |%-28s |%-28s |%-28s |\n", "mode", "execs",
                "inval", "miss", ">=2hit", "tie", "<ulp", "pl/ex", " comparison stage", " comparisons", " relation stage",
                " t stage");
  out += line;
  std::snprintf(line, sizeof line, "%-24s %9s %6s %6s %6s %6s %6s %5s |%s |%s |%s |%s |\n", "", "", "", "", "", "", "", "",
                "   filt   comp   expa  exact", "   filt   comp   expa  exact", "   filt   comp   expa  exact",
                "   filt   comp   expa  exact");
  out += line;
  NearestStats all;
  auto row = [&](const std::string& name, const NearestStats& s) {
    const std::uint64_t valid = s.executions - s.invalid;
    char per[16];
    std::snprintf(per, sizeof per, "%5.1f", valid ? static_cast<double>(s.planes) / static_cast<double>(valid) : 0.0);
    std::snprintf(line, sizeof line, "%-24s %9llu %s %s %s %s %s %s |%s |%s |%s |%s |\n", name.c_str(),
                  static_cast<unsigned long long>(s.executions), percent_text(s.invalid, s.executions).c_str(),
                  percent_text(s.misses, valid).c_str(), percent_text(s.compared, valid).c_str(),
                  percent_text(s.exact_tie, s.compared).c_str(), percent_text(s.sub_ulp, s.compared).c_str(), per,
                  shares_text(s.comparison_deepest).c_str(), shares_text(s.comparisons).c_str(), shares_text(s.relation_deepest).c_str(),
                  shares_text(s.t_stage).c_str());
    out += line;
  };
  for (std::size_t m = 0; m < mode_count; ++m) {
    const NearestStats& s = stats_by_mode[m];
    if (s.executions == 0) continue;
    row(mode_name(m), s);
    all.executions += s.executions, all.invalid += s.invalid, all.misses += s.misses, all.planes += s.planes;
    all.compared += s.compared, all.exact_tie += s.exact_tie, all.sub_ulp += s.sub_ulp;
    for (std::size_t k = 0; k < 4; ++k) {
      all.comparison_deepest[k] += s.comparison_deepest[k];
      all.comparisons[k] += s.comparisons[k];
      all.relation_deepest[k] += s.relation_deepest[k];
      all.t_stage[k] += s.t_stage[k];
    }
  }
  row("all", all);
  out += "  derived planes made:";
  for (int k = 0; k < derived_plane_count; ++k)
    out += std::string(" ") + derived_plane_names[k] + " " + std::to_string(derived_planes[static_cast<std::size_t>(k)]);
  out += "\n  reversed ray (o, -d), executions with a comparison, by the slowest comparison stage:";
  std::array<std::uint64_t, 4> reversed{};
  for (std::size_t k = 0; k < 4; ++k) reversed[k] = comparisons_reversed_deepest[k];
  out += shares_text(reversed) + "\n";
  std::fputs(out.c_str(), stderr);
}

// ---- The checks --------------------------------------------------------------------------------------------

const Decoded* current = nullptr;
std::size_t current_size = 0;

std::string vec_text(const Vec3& v) {
  using raykernel::fuzz::hex;
  return hex(v.x) + " " + hex(v.y) + " " + hex(v.z);
}

std::string describe_current() {
  if (current == nullptr) return "";
  std::string s = "input: " + std::to_string(current_size) + " bytes, mode " + mode_name(current->mode) + "\n";
  s += "ray (a raykernel nearest rays line, hex floats): " + vec_text(current->ray.origin) + " " +
       vec_text(current->ray.direction) + "\n";
  s += "planes (a planes file):\n";
  for (std::size_t k = 0; k < current->planes.size(); ++k) {
    s += vec_text(current->planes[k].point) + " " + vec_text(current->planes[k].normal) + "   # plane " +
         std::to_string(k) + ", " + current->origin[k] + "\n";
  }
  return s;
}

// The same plane and the same bits of t (so +0 and −0 differ), or both misses.
bool same_answer(const std::optional<NearestHit>& a, const std::optional<NearestHit>& b) {
  return a.has_value() == b.has_value() && (!a || (a->plane == b->plane && bits(a->t) == bits(b->t)));
}

std::string answer_text(const std::optional<NearestHit>& h) {
  return h ? "hit " + std::to_string(h->plane) + " " + raykernel::fuzz::hex(h->t) : std::string("miss");
}

// Runs `f`, which must throw invalid_input with message `expected`.
template <class F>
void expect_rejected(F&& f, const std::string& expected, const char* what) {
  try {
    (void)f();
  } catch (const raykernel::invalid_input& e) {
    check(expected == e.what(), [&] {
      return std::string(what) + " throws invalid_input '" + expected + "', got '" + e.what() + "'";
    });
    return;
  }
  check(false, [&] { return std::string(what) + " throws invalid_input '" + expected + "'"; });
}

// Checks `got` (named `what`) against the oracle's answer.
void check_against_oracle(const std::optional<NearestHit>& got, const OracleAnswer& want, const char* what) {
  if (!want.plane) {
    check(!got, [&] { return std::string(what) + " is a miss (no plane is hit), got " + answer_text(got); });
    return;
  }
  check(got && got->plane == *want.plane, [&] {
    return std::string(what) + " picks plane " + std::to_string(*want.plane) + " (exact t " + want.t.get_str() +
           ", " + std::to_string(want.tied) + " plane(s) at that t), got " + answer_text(got);
  });
  check(raykernel::fuzz::is_round_to_nearest_even(want.t, got->t), [&] {
    return std::string(what) + ": t = " + raykernel::fuzz::hex(got->t) + " is the exact t " + want.t.get_str() +
           " rounded to nearest, ties to even";
  });
}

void check_batch(const std::vector<Ray>& rays, const std::vector<Plane>& planes) {
  std::vector<double> c[6];
  for (const Ray& r : rays) {
    c[0].push_back(r.origin.x), c[1].push_back(r.origin.y), c[2].push_back(r.origin.z);
    c[3].push_back(r.direction.x), c[4].push_back(r.direction.y), c[5].push_back(r.direction.z);
  }
  const raykernel::RayBatch batch{c[0], c[1], c[2], c[3], c[4], c[5]};
  std::vector<std::optional<NearestHit>> out(rays.size());
  std::optional<std::string> expected_error;
  for (std::size_t k = 0; k < planes.size() && !expected_error; ++k) {
    if (raykernel::fuzz::plane_invalid_by_bits(planes[k]))
      expected_error = "plane " + std::to_string(k) + ": " + raykernel::validate(planes[k]).value_or("?");
  }
  for (std::size_t i = 0; i < rays.size() && !expected_error; ++i) {
    if (raykernel::fuzz::ray_invalid_by_bits(rays[i]))
      expected_error = "ray " + std::to_string(i) + ": " + raykernel::validate(rays[i]).value_or("?");
  }
  if (expected_error) {
    expect_rejected([&] { raykernel::nearest_hit_batch(batch, planes, out, {.threads = 1}); return 0; },
                    *expected_error, "nearest_hit_batch");
    return;
  }
  raykernel::BatchStats batch_stats;
  raykernel::nearest_hit_batch(batch, planes, out, {.threads = 1, .stats = &batch_stats});
  std::uint64_t hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const std::optional<NearestHit> want = raykernel::nearest_hit(rays[i], planes);
    hits += want ? 1 : 0;
    check(same_answer(out[i], want), [&] {
      return "nearest_hit_batch: ray " + std::to_string(i) + " gets nearest_hit's answer " + answer_text(want) +
             ", got " + answer_text(out[i]);
    });
  }
  std::uint64_t relation_sum = 0, t_sum = 0;
  for (std::size_t k = 0; k < 4; ++k) relation_sum += batch_stats.relation_stage[k], t_sum += batch_stats.t_stage[k];
  check(relation_sum == rays.size() && t_sum == hits,
        "nearest_hit_batch's stats count one relation stage per ray and one t stage per hit");
}

void check_input(const Decoded& in) {
  const Ray& ray = in.ray;
  const std::vector<Plane>& planes = in.planes;
  NearestStats& stats = stats_by_mode[in.mode];
  ++stats.executions;
  for (std::size_t k = 0; k < derived_plane_count; ++k) derived_planes[k] += in.derived[k];

  // The baseline has no precondition: it must merely not misbehave (the sanitizers watch it).
  (void)raykernel::nearest_hit_naive(ray, planes);

  const Ray reversed{ray.origin, {-ray.direction.x, -ray.direction.y, -ray.direction.z}};
  const Ray moved{add(ray.origin, ray.direction), ray.direction};
  check_batch({ray, reversed, moved}, planes);

  // Validity, decided from the bits, and the message each entry point must throw.
  const bool ray_invalid = raykernel::fuzz::ray_invalid_by_bits(ray);
  const std::optional<std::string> ray_reason = raykernel::validate(ray);
  check(ray_reason.has_value() == ray_invalid, ray_invalid ? "validate_ray rejects a non-finite component or a zero direction"
                                                           : "validate_ray accepts a finite ray with a nonzero direction");
  std::optional<std::string> expected_error;
  if (ray_invalid) {
    check(!ray_reason->empty(), "validate_ray's reason is not empty");
    expected_error = *ray_reason;
  }
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const bool invalid = raykernel::fuzz::plane_invalid_by_bits(planes[k]);
    const std::optional<std::string> reason = raykernel::validate(planes[k]);
    check(reason.has_value() == invalid, [&] {
      return "validate_plane " + std::string(invalid ? "rejects" : "accepts") + " plane " + std::to_string(k);
    });
    if (invalid && !expected_error) {
      check(!reason->empty(), "validate_plane's reason is not empty");
      expected_error = "plane " + std::to_string(k) + ": " + *reason;
    }
  }
  // No planes at all: a miss, or the ray's reason.
  if (ray_invalid) {
    expect_rejected([&] { return raykernel::nearest_hit(ray, {}); }, *ray_reason, "nearest_hit with no planes");
  } else {
    check(!raykernel::nearest_hit(ray, {}).has_value(), "nearest_hit with no planes is a miss");
  }
  if (expected_error) {
    expect_rejected([&] { return raykernel::nearest_hit(ray, planes); }, *expected_error, "nearest_hit");
    expect_rejected([&] { return raykernel::nearest_hit_traced(ray, planes); }, *expected_error, "nearest_hit_traced");
    expect_rejected([&] { return raykernel::nearest_hit_exact(ray, planes); }, *expected_error, "nearest_hit_exact");
    ++stats.invalid;
    return;
  }

  // The oracle, and each plane's relation by the one-query path.
  const std::vector<ExactPlane> exact = exact_planes(ray, planes);
  const OracleAnswer want = brute_force(exact, false);
  // The prepared set sets aside exactly the planes that coincide with an earlier one.
  const std::vector<bool> coincident = coincident_with_earlier(planes);
  {
    std::vector<std::uint32_t> expected_candidates;
    for (std::size_t k = 0; k < planes.size(); ++k)
      if (!coincident[k]) expected_candidates.push_back(static_cast<std::uint32_t>(k));
    const raykernel::PlaneSet set(planes);
    check(std::equal(set.candidates().begin(), set.candidates().end(), expected_candidates.begin(),
                     expected_candidates.end()),
          "PlaneSet's candidates are the planes that do not coincide with an earlier one");
  }
  std::size_t candidate_hits = 0;
  Stage slowest_relation = Stage::filter;
  std::vector<raykernel::TracedIntersection> single;
  single.reserve(planes.size());
  for (std::size_t k = 0; k < planes.size(); ++k) {
    single.push_back(raykernel::intersect_traced(ray, planes[k]));
    check(single[k].intersection.relation == oracle_relation(exact[k], false), [&] {
      return "intersect_traced's relation for plane " + std::to_string(k) + " is the exact one: got " +
             std::string(raykernel::to_string(single[k].intersection.relation)) + ", num " + exact[k].num.get_str() +
             ", den " + exact[k].den.get_str();
    });
    if (coincident[k]) continue;
    slowest_relation = std::max(slowest_relation, single[k].relation_stage);
    candidate_hits += single[k].intersection.relation == Relation::hit;
  }

  const raykernel::TracedNearestHit traced = raykernel::nearest_hit_traced(ray, planes);
  check_against_oracle(traced.hit, want, "nearest_hit_traced");
  const std::optional<NearestHit> plain = raykernel::nearest_hit(ray, planes);
  check(same_answer(plain, traced.hit),
        [&] { return "nearest_hit agrees with nearest_hit_traced: " + answer_text(plain) + " vs " + answer_text(traced.hit); });
  const std::optional<NearestHit> reference = raykernel::nearest_hit_exact(ray, planes);
  check_against_oracle(reference, want, "nearest_hit_exact");
  check(same_answer(reference, traced.hit), [&] {
    return "nearest_hit_exact agrees with nearest_hit_traced: " + answer_text(reference) + " vs " + answer_text(traced.hit);
  });
  check(raykernel::floating_point_environment_is_default(), "the floating-point environment is left as it was");
  if (want.plane) {
    const double rounded = raykernel::round_rational_to_double(want.t.get_num().get_str(), want.t.get_den().get_str());
    check(bits(traced.hit->t) == bits(rounded), [&] {
      return "t = " + raykernel::fuzz::hex(traced.hit->t) + " is round_rational_to_double(" + want.t.get_str() +
             ") = " + raykernel::fuzz::hex(rounded);
    });
    const raykernel::Intersection& one = single[*want.plane].intersection;
    check(bits(one.t) == bits(traced.hit->t), [&] {
      return "t = " + raykernel::fuzz::hex(traced.hit->t) + " is intersect's t for the winning plane, " +
             raykernel::fuzz::hex(one.t);
    });
  }

  // The reversed ray: every exact t negated.
  const OracleAnswer want_reversed = brute_force(exact, true);
  const raykernel::TracedNearestHit traced_reversed = raykernel::nearest_hit_traced(reversed, planes);
  check_against_oracle(traced_reversed.hit, want_reversed, "nearest_hit_traced (reversed ray o, -d)");

  // The trace adds up.
  std::uint32_t comparisons = 0;
  Stage slowest_comparison = Stage::filter;
  for (std::size_t k = 0; k < 4; ++k) {
    comparisons += traced.comparisons[k];
    if (traced.comparisons[k] != 0) slowest_comparison = static_cast<Stage>(k);
  }
  check(comparisons == (candidate_hits == 0 ? 0 : candidate_hits - 1), [&] {
    return "one comparison per hit plane after the first, coincident planes set aside: " +
           std::to_string(candidate_hits) + " planes hit, " + std::to_string(comparisons) + " comparisons";
  });
  check(traced.comparison_stage == slowest_comparison, "comparison_stage is the slowest stage that decided a comparison");
  check(traced.relation_stage == slowest_relation, [&] {
    return "relation_stage " + std::string(raykernel::to_string(traced.relation_stage)) +
           " is the slowest of the planes' relation stages (intersect_traced), " +
           std::string(raykernel::to_string(slowest_relation));
  });
  if (!want.plane) {
    check(traced.t_stage == Stage::filter, "t_stage is filter on a miss");
  } else if (sgn(want.t) == 0) {
    check(traced.t_stage == single[*want.plane].relation_stage, "t_stage is the winner's relation stage when t = 0");
  } else {
    check(traced.t_stage != Stage::filter, "rounding a nonzero t starts past the filter");
  }

  // Statistics.
  std::uint32_t reversed_comparisons = 0;
  for (std::uint32_t n : traced_reversed.comparisons) reversed_comparisons += n;
  if (reversed_comparisons > 0) ++comparisons_reversed_deepest[static_cast<std::size_t>(traced_reversed.comparison_stage)];
  stats.planes += planes.size();
  ++stats.relation_deepest[static_cast<std::size_t>(traced.relation_stage)];
  if (!want.plane) {
    ++stats.misses;
    return;
  }
  ++stats.t_stage[static_cast<std::size_t>(traced.t_stage)];
  for (std::size_t k = 0; k < 4; ++k) stats.comparisons[k] += traced.comparisons[k];
  if (comparisons > 0) {
    ++stats.compared;
    ++stats.comparison_deepest[static_cast<std::size_t>(traced.comparison_stage)];
    if (want.tied > 1) ++stats.exact_tie;
    const double t = traced.hit->t;
    if (want.runner_up && std::isnormal(t)) {  // not t rounded to 0 or to ±inf, or subnormal: a real near tie
      const mpq_class ulp = exact_of(std::nextafter(std::fabs(t), HUGE_VAL)) - exact_of(std::fabs(t));
      if (*want.runner_up - want.t < ulp) ++stats.sub_ulp;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("nearest");
    raykernel::fuzz::set_input_describer(describe_current);
    raykernel::fuzz::print_at_exit(print_stats);
    return true;
  }();
  (void)initialized;
  const Decoded decoded = decode({data, size});
  current = &decoded;
  current_size = size;
  check_input(decoded);
  current = nullptr;
  return 0;
}

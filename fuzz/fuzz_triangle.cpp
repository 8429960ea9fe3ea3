// fuzz_triangle: one ray–triangle query per input (docs/contract.md §6), answered by raykernel's certified path
// (`intersect`, `intersect_traced`, `relation`) under both rules, its exact reference (`intersect_exact`,
// `intersect_exact_rational`) and an oracle that shares no code with either: CGAL's Epeck kernel
// (Ray_3/Triangle_3 intersection, orientation predicates) and GMP rationals straight from the definitions.
//
// Input: the layout of raykernel/testkit/triangle_fuzz_decoder.hpp. Byte 0 < 0x80: 15 raw doubles (every bit
// pattern); byte 0 ≥ 0x80: a hard query of one of the 16 kinds of raykernel::testkit::make_triangle_query. A
// custom mutator moves raw queries toward degeneracies (aiming at vertices and edge midpoints, nudging by ulps,
// collapsing the triangle, scaling by powers of two).
//
// Checked for every input:
//   - validity: `validate` rejects exactly the inputs with a non-finite component or a zero direction (decided
//     here from the bits), and then every entry point throws invalid_input with validate's reason;
//   - valid input: certified == exact bit for bit (relation, location, owned flag, t, the three coordinates)
//     under both rules, `relation` agrees; the exact rationals equal GMP's from the definitions; the sign of
//     den, num and each π equals CGAL's orientation predicate; the location and owned flag follow from those
//     signs and the tie-break vectors as §6 words it; a closed-rule hit or behind is a CGAL intersection point
//     of the ray or its line with the triangle, at the exact t and at the exact barycentric combination; a
//     closed-rule miss, a parallel line and a degenerate triangle have no CGAL intersection where §6 says so;
//     every rounding is verified (exact comparisons with the neighbouring doubles).
#include "fuzz_exact.hpp"
#include "fuzz_support.hpp"

#include <raykernel/testkit/triangle_fuzz_decoder.hpp>
#include <raykernel/triangle.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gmpxx.h>

#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace {

using raykernel::Ray;
using raykernel::Triangle;
using raykernel::TriangleIntersection;
using raykernel::TriangleLocation;
using raykernel::TriangleRelation;
using raykernel::TriangleRule;
using raykernel::Vec3;
using raykernel::fuzz::bits;
using raykernel::fuzz::check;
using raykernel::fuzz::exact_of;
using raykernel::fuzz::is_round_to_nearest_even;
using K = CGAL::Exact_predicates_exact_constructions_kernel;
namespace rt = raykernel::testkit;

// ---- The oracle: GMP from the definitions, and CGAL ------------------------------------------------------------

struct Q3 {
  mpq_class x, y, z;
};
Q3 q3(const Vec3& v) { return {exact_of(v.x), exact_of(v.y), exact_of(v.z)}; }
Q3 operator-(const Q3& a, const Q3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Q3 cross(const Q3& a, const Q3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
mpq_class dot(const Q3& a, const Q3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

mpq_class rational_of(const raykernel::Rational& r) {
  mpq_class q(mpz_class(r.numerator), mpz_class(r.denominator));
  q.canonicalize();
  return q;
}

template <class T>
mpq_class to_mpq(const T& x) {
  if constexpr (std::is_same_v<T, mpq_class>) {
    return x;
  } else if constexpr (requires { mpq_class(x.backend().data()); }) {
    return mpq_class(x.backend().data());
  } else {
    std::ostringstream s;
    s << x;
    mpq_class q(s.str());
    q.canonicalize();
    return q;
  }
}
Q3 q3(const K::Point_3& p) {
  return {to_mpq(CGAL::exact(p.x())), to_mpq(CGAL::exact(p.y())), to_mpq(CGAL::exact(p.z()))};
}

int sign_of(CGAL::Orientation o) { return o == CGAL::POSITIVE ? 1 : (o == CGAL::NEGATIVE ? -1 : 0); }

// ---- The current input -------------------------------------------------------------------------------------------

struct Current {
  rt::FuzzTriangleQuery decoded;
  std::size_t size = 0;
};
Current current;

std::string describe_current() {
  const std::string mode = current.decoded.kind ? "hard query " + std::string(rt::to_string(*current.decoded.kind))
                                                : std::string("raw doubles");
  return "input: " + std::to_string(current.size) + " bytes, mode " + mode +
         "\nquery (a raykernel triangle line, hex floats):\n" + rt::triangle_line(current.decoded.query);
}

// Per decoder mode (raw, then the kinds): executions, invalid, relations, stages.
struct ModeCounts {
  std::uint64_t executions = 0, invalid = 0;
  std::array<std::uint64_t, 4> relation{};        // hit, behind, miss, den = 0 (owned rule)
  std::array<std::uint64_t, 4> relation_stage{};  // by Stage
  std::array<std::uint64_t, 4> rounding_stage{};  // by Stage, den ≠ 0
};
ModeCounts counts_by_mode[1 + rt::triangle_query_kind_count];

std::size_t mode_index(const rt::FuzzTriangleQuery& f) {
  if (!f.kind) return 0;
  for (std::size_t k = 0; k < rt::all_triangle_query_kinds.size(); ++k)
    if (rt::all_triangle_query_kinds[k] == *f.kind) return 1 + k;
  return 0;
}

void print_stats() {
  using raykernel::fuzz::percent_text;
  using raykernel::fuzz::shares_text;
  std::string out = "==== raykernel fuzz stats: triangle (percentages)\n";
  out += "  relation (owned rule): hit, behind, miss, den = 0; stages: filter, compensated, expansion, exact\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-20s %10s %7s |%-28s |%-28s |%-28s |\n", "mode", "execs", "invalid",
                " relation", " relation stage", " rounding stage (den != 0)");
  out += line;
  ModeCounts total;
  auto row = [&](const std::string& name, const ModeCounts& c) {
    std::snprintf(line, sizeof line, "%-20s %10llu %7s |%s |%s |%s |\n", name.c_str(),
                  static_cast<unsigned long long>(c.executions), percent_text(c.invalid, c.executions).c_str(),
                  shares_text(c.relation).c_str(), shares_text(c.relation_stage).c_str(),
                  shares_text(c.rounding_stage).c_str());
    out += line;
  };
  for (std::size_t m = 0; m <= rt::all_triangle_query_kinds.size(); ++m) {
    const ModeCounts& c = counts_by_mode[m];
    if (c.executions == 0) continue;
    row(m == 0 ? "raw" : std::string(rt::to_string(rt::all_triangle_query_kinds[m - 1])), c);
    total.executions += c.executions;
    total.invalid += c.invalid;
    for (std::size_t k = 0; k < 4; ++k) {
      total.relation[k] += c.relation[k];
      total.relation_stage[k] += c.relation_stage[k];
      total.rounding_stage[k] += c.rounding_stage[k];
    }
  }
  row("all", total);
  std::fputs(out.c_str(), stderr);
}

template <class F>
void expect_rejected(F&& f, const std::string& reason, const char* what) {
  try {
    (void)f();
  } catch (const raykernel::invalid_input& e) {
    check(reason == e.what(), [&] {
      return std::string(what) + " throws invalid_input with validate's reason (got '" + e.what() + "', validate says '" +
             reason + "')";
    });
    return;
  }
  check(false, [&] { return std::string(what) + " throws invalid_input on invalid input"; });
}

bool same_value(double a, double b) { return bits(a) == bits(b) || (std::isnan(a) && std::isnan(b)); }

std::string answer_text(const TriangleIntersection& x) {
  using raykernel::fuzz::hex;
  return std::string(raykernel::to_string(x.relation)) + " " + std::string(raykernel::to_string(x.location)) +
         (x.owned ? " owned" : "") + " t=" + hex(x.t) + " u=(" + hex(x.barycentric[0]) + ", " + hex(x.barycentric[1]) +
         ", " + hex(x.barycentric[2]) + ")";
}

// The location of §6 from exact signs, written here again.
TriangleLocation location_of(int sa, int sb, int sc, int sden) {
  if (sa == -sden || sb == -sden || sc == -sden) return TriangleLocation::outside;
  if (sb == 0 && sc == 0) return TriangleLocation::vertex_a;
  if (sc == 0 && sa == 0) return TriangleLocation::vertex_b;
  if (sa == 0 && sb == 0) return TriangleLocation::vertex_c;
  if (sc == 0) return TriangleLocation::edge_ab;
  if (sa == 0) return TriangleLocation::edge_bc;
  if (sb == 0) return TriangleLocation::edge_ca;
  return TriangleLocation::inside;
}

int owned_sign(int s, const Q3& d, const Q3& p, const Q3& q) {
  if (s != 0) return s;
  const Q3 t = cross(d, q - p);
  return sgn(t.x) != 0 ? sgn(t.x) : (sgn(t.y) != 0 ? sgn(t.y) : sgn(t.z));
}

void check_query(const Ray& ray, const Triangle& tri, ModeCounts& stats) {
  ++stats.executions;
  (void)raykernel::intersect_naive(ray, tri);  // no precondition: the sanitizers watch it

  const std::optional<std::string> reason = raykernel::validate(ray, tri);
  const bool invalid = raykernel::fuzz::ray_invalid_by_bits(ray) || !raykernel::fuzz::finite_vector_by_bits(tri.a) ||
                       !raykernel::fuzz::finite_vector_by_bits(tri.b) || !raykernel::fuzz::finite_vector_by_bits(tri.c);
  check(reason.has_value() == invalid, invalid ? "validate rejects a non-finite component or a zero direction"
                                               : "validate accepts finite input with a nonzero direction");
  if (invalid) {
    ++stats.invalid;
    expect_rejected([&] { return raykernel::intersect(ray, tri); }, *reason, "intersect");
    expect_rejected([&] { return raykernel::relation(ray, tri); }, *reason, "relation");
    expect_rejected([&] { return raykernel::intersect_exact(ray, tri); }, *reason, "intersect_exact");
    expect_rejected([&] { return raykernel::intersect_exact_rational(ray, tri); }, *reason, "intersect_exact_rational");
    return;
  }

  // Certified == exact under both rules; relation() agrees.
  const raykernel::ExactTriangleIntersection x = raykernel::intersect_exact_rational(ray, tri, TriangleRule::owned);
  for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
    const raykernel::TracedTriangleIntersection traced = raykernel::intersect_traced(ray, tri, {rule, true, true});
    const TriangleIntersection& c = traced.intersection;
    // The owned rule's exact answer is x's (computed once: the exact stage is the slow part of this harness).
    const TriangleIntersection e =
        rule == TriangleRule::owned ? x.intersection : raykernel::intersect_exact(ray, tri, {rule, true, true});
    check(c.relation == e.relation && c.location == e.location && c.owned == e.owned && same_value(c.t, e.t) &&
              same_value(c.barycentric[0], e.barycentric[0]) && same_value(c.barycentric[1], e.barycentric[1]) &&
              same_value(c.barycentric[2], e.barycentric[2]),
          [&] {
            return std::string("certified == exact (") + std::string(raykernel::to_string(rule)) +
                   " rule): certified " + answer_text(c) + ", exact " + answer_text(e);
          });
    const raykernel::TriangleClassification r = raykernel::relation(ray, tri, rule);
    check(r.relation == e.relation && r.location == e.location && r.owned == e.owned,
          "relation() agrees with intersect_exact");
    if (rule == TriangleRule::owned) {
      const int rel = e.relation == TriangleRelation::hit ? 0 : e.relation == TriangleRelation::behind ? 1
                      : e.relation == TriangleRelation::miss ? 2 : 3;
      ++stats.relation[static_cast<std::size_t>(rel)];
      ++stats.relation_stage[static_cast<std::size_t>(traced.relation_stage)];
      if (rel < 3) ++stats.rounding_stage[static_cast<std::size_t>(traced.rounding_stage)];
    }
  }

  // The exact values from the definitions.
  const Q3 o = q3(ray.origin), d = q3(ray.direction), a = q3(tri.a), b = q3(tri.b), c = q3(tri.c);
  const Q3 n = cross(b - a, c - a);
  const mpq_class den = dot(d, n), num = dot(a - o, n);
  const mpq_class pa = dot(d, cross(b - o, c - o)), pb = dot(d, cross(c - o, a - o)), pc = dot(d, cross(a - o, b - o));
  check(rational_of(x.den) == den && rational_of(x.num) == num && rational_of(x.pi_a) == pa &&
            rational_of(x.pi_b) == pb && rational_of(x.pi_c) == pc,
        "the exact den, num and π's are the definitions' values");

  // CGAL's orientation predicates give the same signs.
  const K::Point_3 O(ray.origin.x, ray.origin.y, ray.origin.z), A(tri.a.x, tri.a.y, tri.a.z),
      B(tri.b.x, tri.b.y, tri.b.z), C(tri.c.x, tri.c.y, tri.c.z);
  const K::Vector_3 D(ray.direction.x, ray.direction.y, ray.direction.z);
  const K::Point_3 OD = O + D;
  check(sign_of(CGAL::orientation(O, B, C, OD)) == sgn(pa) && sign_of(CGAL::orientation(O, C, A, OD)) == sgn(pb) &&
            sign_of(CGAL::orientation(O, A, B, OD)) == sgn(pc),
        "sign(π(p, q)) == CGAL::orientation(o, p, q, o + d)");
  check(sign_of(CGAL::orientation(A, B, C, A + D)) == sgn(den), "sign(den) == CGAL::orientation(a, b, c, a + d)");
  check(sign_of(CGAL::orientation(A, B, C, O)) == -sgn(num), "sign(num) == −CGAL::orientation(a, b, c, o)");

  const TriangleIntersection& owned_answer = x.intersection;
  const bool degenerate = sgn(n.x) == 0 && sgn(n.y) == 0 && sgn(n.z) == 0;
  const K::Triangle_3 triangle(A, B, C);
  check(triangle.is_degenerate() == degenerate, "CGAL's is_degenerate agrees with N = 0");
  if (sgn(den) == 0) {
    const TriangleRelation want = degenerate ? TriangleRelation::degenerate
                                  : sgn(num) == 0 ? TriangleRelation::coplanar : TriangleRelation::parallel;
    check(owned_answer.relation == want, "den = 0: degenerate, coplanar or parallel as N and num say");
    check(!x.t.has_value() && std::isnan(owned_answer.t), "no t when den = 0");
    if (want == TriangleRelation::parallel)
      check(!CGAL::do_intersect(K::Line_3(O, D), triangle), "CGAL: a parallel line does not meet the triangle");
    return;
  }

  // The location and the owned flag from the signs and the tie-breaks, as §6 words them.
  const int s = sgn(den);
  const TriangleLocation loc = location_of(sgn(pa), sgn(pb), sgn(pc), s);
  const bool owned = owned_sign(sgn(pa), d, b, c) == s && owned_sign(sgn(pb), d, c, a) == s &&
                     owned_sign(sgn(pc), d, a, b) == s;
  check(owned_answer.location == loc && owned_answer.owned == owned, "location and owned flag as §6 defines them");

  // The roundings.
  const mpq_class t = num / den;
  const mpq_class u[3] = {pa / den, pb / den, pc / den};
  check(x.t.has_value() && rational_of(*x.t) == t, "the exact t is num/den");
  check(is_round_to_nearest_even(t, owned_answer.t), "t is RN(num/den)");
  for (std::size_t k = 0; k < 3; ++k) {
    check(rational_of((*x.barycentric)[k]) == u[k], "the exact barycentric coordinate is π/den");
    check(is_round_to_nearest_even(u[k], owned_answer.barycentric[k]), "each coordinate is RN(π/den)");
  }

  // CGAL: the closed rule's hits and behinds are where CGAL's line meets the triangle.
  const bool closed_through = loc != TriangleLocation::outside;
  const auto on_line = CGAL::intersection(K::Line_3(O, D), triangle);
  check(static_cast<bool>(on_line) == closed_through, [&] {
    return std::string("CGAL: the line meets the triangle exactly when the location is not outside (location ") +
           std::string(raykernel::to_string(loc)) + ")";
  });
  if (on_line) {
    const K::Point_3* p = boost::get<K::Point_3>(&*on_line);
    check(p != nullptr, "CGAL: a line crossing the plane meets the triangle in a point");
    const Q3 x3 = q3(*p);
    const Q3 at_t = {o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
    check(x3.x == at_t.x && x3.y == at_t.y && x3.z == at_t.z, "CGAL's point is o + t·d at the exact t");
    const Q3 combination = {u[0] * a.x + u[1] * b.x + u[2] * c.x, u[0] * a.y + u[1] * b.y + u[2] * c.y,
                            u[0] * a.z + u[1] * b.z + u[2] * c.z};
    check(x3.x == combination.x && x3.y == combination.y && x3.z == combination.z,
          "CGAL's point is the barycentric combination ua·a + ub·b + uc·c");
    check(CGAL::do_intersect(K::Ray_3(O, D), triangle) == (t >= 0), "CGAL's ray meets the triangle iff t ≥ 0");
  }
}

// ---- The custom mutator ---------------------------------------------------------------------------------------

bool environment_flag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' && std::string_view(v) != "0";
}

double& component(Vec3& v, std::uint64_t i) { return i % 3 == 0 ? v.x : (i % 3 == 1 ? v.y : v.z); }

void mutate_query(rt::TriangleQuery& q, rt::SplitMix64& rng) {
  Vec3* vectors[5] = {&q.ray.origin, &q.ray.direction, &q.triangle.a, &q.triangle.b, &q.triangle.c};
  Vec3* vertices[3] = {&q.triangle.a, &q.triangle.b, &q.triangle.c};
  Vec3& o = q.ray.origin;
  Vec3& d = q.ray.direction;
  const std::uint64_t which = rng();
  switch (rng() % 9) {
    case 0: {  // nudge one component by 1..8 ulps
      double& c = component(*vectors[which % 5], which >> 8);
      for (int k = 0, n = 1 + static_cast<int>((which >> 16) % 8); k < n; ++k)
        c = std::nextafter(c, (which >> 24) & 1 ? HUGE_VAL : -HUGE_VAL);
      break;
    }
    case 1: {  // aim at a vertex: d = v − o (exact when the difference is)
      const Vec3& v = *vertices[which % 3];
      d = {v.x - o.x, v.y - o.y, v.z - o.z};
      break;
    }
    case 2: {  // aim at an edge midpoint
      const Vec3 &p = *vertices[which % 3], &r = *vertices[(which + 1) % 3];
      d = {(p.x + r.x) / 2 - o.x, (p.y + r.y) / 2 - o.y, (p.z + r.z) / 2 - o.z};
      break;
    }
    case 3:  // collapse: a vertex onto another, or onto the midpoint of the other two
      if ((which >> 4) & 1) {
        *vertices[which % 3] = *vertices[(which + 1) % 3];
      } else {
        const Vec3 &p = *vertices[(which + 1) % 3], &r = *vertices[(which + 2) % 3];
        *vertices[which % 3] = {(p.x + r.x) / 2, (p.y + r.y) / 2, (p.z + r.z) / 2};
      }
      break;
    case 4: {  // d along an edge (in the plane), or o onto a vertex
      const Vec3 &p = *vertices[which % 3], &r = *vertices[(which + 1) % 3];
      if ((which >> 4) & 1)
        d = {r.x - p.x, r.y - p.y, r.z - p.z};
      else
        o = p;
      break;
    }
    case 5: {  // scale a vector by 2^k
      const int k = static_cast<int>((which >> 8) % 2201) - 1100;
      Vec3& v = *vectors[which % 5];
      v = {std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
      break;
    }
    case 6: {  // small integers everywhere: exact degeneracies become likely
      for (Vec3* v : vectors)
        for (std::uint64_t i = 0; i < 3; ++i) component(*v, i) = static_cast<double>(static_cast<int>(rng() % 7) - 3);
      break;
    }
    case 7: {  // a special value
      static const double special[] = {0.0, -0.0, 1.0, -1.0, 0.5, DBL_MIN, DBL_TRUE_MIN, DBL_MAX, 0x1p-537, 0x1p511,
                                       HUGE_VAL, std::numeric_limits<double>::quiet_NaN(), DBL_EPSILON};
      component(*vectors[which % 5], which >> 8) = special[(which >> 16) % (sizeof special / sizeof special[0])];
      break;
    }
    default:  // a random bit pattern
      component(*vectors[which % 5], which >> 8) = std::bit_cast<double>(rng());
      break;
  }
}

}  // namespace

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size)
    __attribute__((weak));

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  auto byte_mutation = [&](std::size_t skip) {
    if (LLVMFuzzerMutate == nullptr || size < skip || max_size <= skip) return size;
    return skip + LLVMFuzzerMutate(data + skip, size - skip, max_size - skip);
  };
  if (environment_flag("RAYKERNEL_FUZZ_PLAIN_MUTATOR") || max_size < rt::raw_triangle_fuzz_input_size)
    return byte_mutation(0);
  rt::SplitMix64 rng(seed);
  const std::uint64_t choice = rng() % 16;
  const bool raw = size == 0 || data[0] < rt::hard_query_selector;
  if (choice < 4) return byte_mutation(raw ? 0 : 1);
  if (choice == 4 && size > 0) {
    data[0] = static_cast<std::uint8_t>(rt::hard_query_selector + rng() % rt::triangle_query_kind_count);
    return size;
  }
  if (!raw && choice >= 10) return byte_mutation(1);
  rt::TriangleQuery q = rt::decode_fuzz_triangle_query({data, size}).query;
  for (int k = 0, rounds = 1 + static_cast<int>(rng() % 3); k < rounds; ++k) mutate_query(q, rng);
  const std::vector<std::uint8_t> bytes = rt::encode_raw_fuzz_input(q);
  std::memcpy(data, bytes.data(), bytes.size());
  return bytes.size();
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("triangle");
    raykernel::fuzz::set_input_describer(describe_current);
    raykernel::fuzz::print_at_exit(print_stats);
    return true;
  }();
  (void)initialized;
  current.decoded = rt::decode_fuzz_triangle_query({data, size});
  current.size = size;
  check_query(current.decoded.query.ray, current.decoded.query.triangle, counts_by_mode[mode_index(current.decoded)]);
  return 0;
}

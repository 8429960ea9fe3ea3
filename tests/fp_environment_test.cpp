// The floating-point environment the guarantees rest on (README, "Floating-point assumptions"):
// no FMA contraction in the kernel's build, round-to-nearest, no flush-to-zero. The kernel's own build is
// probed; a deliberately contracting build of the same expression shows the probe can tell; and the run-time
// check is exercised by switching the rounding mode and flush-to-zero on and off.
#include "core/absolute_terms.hpp"
#include "core/error_bounds.hpp"
#include "core/fp_probe.hpp"
#include "support/entry_points.hpp"
#include "support/oracle.hpp"

#include <raykernel/fp_environment.hpp>
#include <raykernel/mesh_queries.hpp>
#include <raykernel/occlusion.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/meshes.hpp>
#include <raykernel/testkit/sphere_queries.hpp>
#include <raykernel/testkit/triangle_queries.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cfenv>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace raykernel::test_support {
double contracting_probe(double a, double c) noexcept;
}

namespace raykernel {
namespace {

// a = 1 + 2^-30, c = 1 + 2^-29: a·a = 1 + 2^-29 + 2^-60 exactly, which rounds to c, so the separately
// rounded a·a − c is 0; fused, it is the exact 2^-60.
constexpr double probe_a = 1 + 0x1p-30;
constexpr double probe_c = 1 + 0x1p-29;

TEST(FpEnvironment, KernelBuildDoesNotContractIntoFma) {
  EXPECT_EQ(detail::contraction_probe(probe_a, probe_c), 0.0)
      << "the kernel was compiled with FMA contraction: its error bounds no longer apply";
}

TEST(FpEnvironment, ProbeDetectsAContractingBuild) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (!__builtin_cpu_supports("fma")) GTEST_SKIP() << "no FMA unit: the positive control cannot run";
#endif
  EXPECT_EQ(test_support::contracting_probe(probe_a, probe_c), 0x1p-60);
}

// ---- The caller's environment ----------------------------------------------------------------------------
//
// Every public entry point, run on subnormal-heavy hard queries (ray–plane and ray–triangle) in each
// non-default environment a caller can leave (set here by hand), must give the answers it gives in the
// default environment, bit for bit, and leave the environment exactly as it found it
// (tests/support/entry_points.hpp). Before this was
// fixed, DAZ made `intersect` throw "plane normal is the zero vector" for the normal (2^-1070, 0, 0) and FTZ
// made it answer t = 0 for t = 2^-1070 (the first two queries of the list).

const std::vector<testkit::Query>& queries() {
  static const std::vector<testkit::Query> q = test_support::environment_test_queries(3000, 0xe5e5);
  return q;
}
const std::vector<testkit::TriangleQuery>& triangle_queries() {
  static const std::vector<testkit::TriangleQuery> q = test_support::environment_test_triangle_queries(3000, 0x7e5e5);
  return q;
}
test_support::EntryPointAnswers answers_here() {
  return test_support::answers_of_every_entry_point(queries(), triangle_queries(), 7);
}
const test_support::EntryPointAnswers& default_answers() {
  static const test_support::EntryPointAnswers a = answers_here();
  return a;
}

void expect_same_answers(const test_support::EntryPointAnswers& got, const std::string& mode) {
  const test_support::EntryPointAnswers& want = default_answers();
  ASSERT_EQ(got.names, want.names);
  for (std::size_t k = 0; k < want.names.size(); ++k) {
    int reported = 0;
    for (std::size_t i = 0; i < want.answers[k].size() && reported < 3; ++i) {
      if (got.answers[k][i] == want.answers[k][i]) continue;
      ++reported;
      ADD_FAILURE() << mode << ": " << want.names[k] << ", query " << i << " ("
                    << test_support::query_text(want, k, i, queries(), triangle_queries()) << "):\n  default: " << want.answers[k][i]
                    << "\n  here:    " << got.answers[k][i];
    }
  }
}

TEST(FpEnvironment, DefaultEnvironmentIsRecognized) { EXPECT_TRUE(floating_point_environment_is_default()); }

TEST(FpEnvironment, TheDazAndFtzCasesHaveTheirContractAnswers) {
  // Hand-derived: d·n = 2^-1070 > 0, (p − o)·n = 5·2^-1070, t = 5; and num = 2^-1070, den = 1, t = 2^-1070.
  const test_support::EntryPointAnswers& a = default_answers();
  EXPECT_EQ(a.answers[0][0], "hit " + test_support::bits_of(5.0));
  EXPECT_EQ(a.answers[0][1], "hit " + test_support::bits_of(0x1p-1070));
  // The subnormal triangle (entry_points.hpp): hit inside at t = 1, coordinates (1/2, 1/4, 1/4); the ray
  // passes through the triangle's interior, so the owned rule agrees.
  const auto k = static_cast<std::size_t>(
      std::find(a.names.begin(), a.names.end(), "triangle intersect") - a.names.begin());
  ASSERT_LT(k, a.names.size());
  EXPECT_EQ(a.answers[k][0], "hit inside owned " + test_support::bits_of(1.0) + " " + test_support::bits_of(0.5) +
                                 " " + test_support::bits_of(0.25) + " " + test_support::bits_of(0.25));
}

TEST(FpEnvironment, DirectedRoundingChangesNothing) {
  (void)default_answers();  // the queries and the reference, computed in the default environment first
  for (int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    ASSERT_EQ(std::fesetround(mode), 0);
    const bool recognized = !floating_point_environment_is_default();
    const test_support::EntryPointAnswers got = answers_here();
    const int after = std::fegetround();
    std::fesetround(FE_TONEAREST);
    EXPECT_TRUE(recognized) << "mode " << mode;
    EXPECT_EQ(after, mode);
    expect_same_answers(got, "rounding mode " + std::to_string(mode));
  }
}

#if defined(__x86_64__)
// MXCSR: DAZ bit 6, FTZ bit 15; exception masks bits 7–12 (invalid, denormal, divide-by-zero, overflow,
// underflow, precision); flags bits 0–5.
void expect_same_answers_with_mxcsr(unsigned mxcsr, const std::string& mode) {
  (void)default_answers();  // the queries and the reference, computed in the default environment first
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(mxcsr);
  const bool recognized = !floating_point_environment_is_default();
  const test_support::EntryPointAnswers got = answers_here();
  const unsigned after = _mm_getcsr();
  _mm_setcsr(saved);
  EXPECT_EQ(recognized, (mxcsr & 0xFFC0u) != 0x1F80u) << mode;
  EXPECT_EQ(after, mxcsr) << mode << ": the environment was not restored exactly";
  expect_same_answers(got, mode);
}

TEST(FpEnvironment, FlushToZeroAndDenormalsAreZeroChangeNothing) {
  expect_same_answers_with_mxcsr(0x1F80u | 0x8000u, "FTZ");
  expect_same_answers_with_mxcsr(0x1F80u | 0x0040u, "DAZ");
  expect_same_answers_with_mxcsr(0x1F80u | 0x8040u, "FTZ+DAZ (what -ffast-math sets)");
}

TEST(FpEnvironment, UnmaskedExceptionsNeitherTrapNorChangeAnything) {
  // Each exception unmasked alone, then all of them: the fast paths divide by zero, form inf − inf or
  // touch subnormals on some of these queries, which must not trap.
  const char* names[6] = {"invalid", "denormal", "divide-by-zero", "overflow", "underflow", "precision"};
  for (int bit = 0; bit < 6; ++bit)
    expect_same_answers_with_mxcsr(0x1F80u & ~(0x80u << bit), std::string("trap on ") + names[bit]);
  expect_same_answers_with_mxcsr(0x0000u, "every trap enabled");
}

TEST(FpEnvironment, StickyFlagsAreKeptExactly) {
  // All six flags already raised by the caller, default control bits: still the default environment, and
  // the flags stay exactly as they were (the library's own inexact results do not clear or add any).
  expect_same_answers_with_mxcsr(0x1F80u | 0x3Fu, "all flags raised");
}

// ---- DefaultFpEnvironment: the check hoisted out of a loop ----------------------------------------------

// Whatever the thread's environment, a DefaultFpEnvironment scope installs the default one (so every entry
// point inside answers as in the default environment), nested scopes change nothing, and the end of the
// outermost scope restores the environment of its start exactly (control bits and flags).
TEST(FpEnvironment, ScopeInstallsTheDefaultAndRestoresTheCallersExactly) {
  (void)default_answers();
  const unsigned saved = _mm_getcsr();
  const std::pair<unsigned, const char*> cases[] = {
      {0x1F80u | 0x8040u, "FTZ+DAZ"}, {0x1F80u | 0x4000u, "round upward"}, {0x0000u, "every trap enabled"},
      {0x1F80u | 0x3Fu, "all flags raised"}, {0x1F80u, "default"}};
  for (const auto& [mxcsr, mode] : cases) {
    _mm_setcsr(mxcsr);
    unsigned inside = 0, nested = 0;
    test_support::EntryPointAnswers got;
    {
      const DefaultFpEnvironment outer;
      inside = _mm_getcsr();
      {
        const DefaultFpEnvironment inner;
        nested = _mm_getcsr();
        test_support::environment_compared = 0xFFC0u;  // the calls keep the flags they raise (below)
        got = answers_here();
        test_support::environment_compared = ~std::uint64_t{0};
      }
      EXPECT_EQ(_mm_getcsr() & 0xFFC0u, 0x1F80u) << mode << ": the inner scope's end changed the control bits";
    }
    const unsigned after = _mm_getcsr();
    _mm_setcsr(saved);
    EXPECT_EQ(inside & 0xFFC0u, 0x1F80u) << mode << ": the scope did not install the default environment";
    EXPECT_EQ(nested, inside) << mode << ": a nested scope changed the environment";
    EXPECT_EQ(after, mxcsr) << mode << ": the environment was not restored exactly";
    expect_same_answers(got, std::string("inside a DefaultFpEnvironment entered with ") + mode);
  }
}

// Inside a scope the entry points skip their own save and restore: the inexact flag a computation raises
// stays raised until the scope ends (an unscoped call clears it on return), and the scope's end clears it.
TEST(FpEnvironment, EntryPointsInsideAScopeDoNotSaveAndRestore) {
  // Hand-derived: d·n = 3, (p − o)·n = 1, t = 1/3 (inexact); the expected value is folded at compile time,
  // so that no division of the test's own raises the flag.
  const Ray ray{{0, 0, 0}, {3, 0, 0}};
  const Plane plane{{1, 0, 0}, {1, 0, 0}};
  constexpr double third = 1.0 / 3.0;
  constexpr unsigned inexact = 0x20u;
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(0x1F80u);
  ASSERT_EQ(intersect(ray, plane).t, third);
  const unsigned unscoped = _mm_getcsr();
  unsigned scoped = 0;
  {
    const DefaultFpEnvironment env;
    EXPECT_EQ(intersect(ray, plane).t, third);
    scoped = _mm_getcsr();
  }
  const unsigned after = _mm_getcsr();
  _mm_setcsr(saved);
  EXPECT_EQ(unscoped & inexact, 0u) << "an unscoped call left its inexact flag raised";
  EXPECT_EQ(scoped & inexact, inexact) << "inside a scope, the call still restored the flags (no check was skipped)";
  EXPECT_EQ(after, 0x1F80u) << "the scope's end did not restore the flags";
}

// ---- No flag but inexact on ordinary queries ----------------------------------------------------------------
//
// A sticky flag that a call raises and the caller's flags do not hold is cleared again on return, and raising
// it costs a microcode assist: the error bounds' subnormal absolute terms as operands (the denormal-operand
// flag, DE) cost every call about 90 ns on the degenerate plane workload before core/absolute_terms.hpp
// (bench/README.md). So on ordinary queries — random ones, and rays through vertices and edges — every certified
// path raises inexact at most: checked per call inside a scope (which skips the per-call save and restore),
// the flags cleared before each. (Stage 3 and the exact stage, and inputs near the subnormal range, may raise
// underflow and denormal: their own arithmetic is on tiny values.)
constexpr unsigned mxcsr_flags = 0x3Fu, inexact_flag = 0x20u;

std::string hex(unsigned x) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%02x", x);
  return buffer;
}

template <class F>
unsigned flags_raised_by(F&& f) {
  _mm_setcsr(0x1F80u);
  f();
  return _mm_getcsr() & mxcsr_flags;
}

TEST(FpEnvironment, OrdinaryQueriesRaiseNoFlagButInexact) {
  const unsigned saved = _mm_getcsr();
  testkit::SplitMix64 rng(0xf1a6);
  const testkit::BitSource bits = [&rng] { return rng(); };
  const PreparedMesh mesh(testkit::make_icosphere(2));
  std::vector<std::string> failures;
  auto expect_only_inexact = [&](const char* what, int query, unsigned raised) {
    if ((raised & ~inexact_flag) != 0 && failures.size() < 10)
      failures.push_back(std::string(what) + ", query " + std::to_string(query) + ": flags 0x" + hex(raised));
  };
  {
    const DefaultFpEnvironment env;
    for (int i = 0; i < 400; ++i) {
      const testkit::Query q = testkit::make_query(testkit::QueryKind::random, bits);
      expect_only_inexact("plane relation", i, flags_raised_by([&] { (void)relation(q.ray, q.plane); }));
      expect_only_inexact("plane intersect", i, flags_raised_by([&] { (void)intersect(q.ray, q.plane); }));
      for (const auto kind : {testkit::TriangleQueryKind::random, testkit::TriangleQueryKind::through_vertex,
                              testkit::TriangleQueryKind::through_edge}) {
        const testkit::TriangleQuery t = testkit::make_triangle_query(kind, bits);
        expect_only_inexact("triangle relation", i, flags_raised_by([&] { (void)relation(t.ray, t.triangle); }));
        expect_only_inexact("triangle intersect", i, flags_raised_by([&] { (void)intersect(t.ray, t.triangle); }));
      }
      const testkit::SphereQuery s = testkit::make_sphere_query(testkit::SphereQueryKind::random, bits);
      expect_only_inexact("sphere relation", i, flags_raised_by([&] { (void)relation(s.ray, s.sphere); }));
      expect_only_inexact("sphere intersect", i, flags_raised_by([&] { (void)intersect(s.ray, s.sphere); }));
      // A ray from outside the icosphere (radius about 1) towards a random point near its centre.
      const testkit::Query r = testkit::make_query(testkit::QueryKind::random, bits);
      const Vec3 origin{3 * r.ray.origin.x + 3, 3 * r.ray.origin.y, 3 * r.ray.origin.z};
      const Ray ray{origin, {r.plane.point.x / 2 - origin.x, r.plane.point.y / 2 - origin.y, r.plane.point.z / 2 - origin.z}};
      expect_only_inexact("mesh nearest_hit", i, flags_raised_by([&] { (void)nearest_hit(ray, mesh); }));
      expect_only_inexact("mesh occluded", i, flags_raised_by([&] { (void)occluded(ray, mesh); }));
      expect_only_inexact("mesh inside", i, flags_raised_by([&] { (void)inside(r.plane.point, mesh); }));
    }
  }
  _mm_setcsr(saved);
  for (const std::string& f : failures) ADD_FAILURE() << f << " (0x02 denormal operand, 0x08 overflow, 0x10 underflow)";
}
#endif

// ---- The absolute terms without a subnormal operand -------------------------------------------------------
//
// core/absolute_terms.hpp forms X ⊕ M (each error bound's absolute constant M) and X ⊕ A (the determinants'
// dynamic term) from normal operands; its bits must be the sums', which is what the proofs and the twins' models
// compute: checked on values around the thresholds 2^-1000 and 2^-968, around 2^-1022, signed zeros, subnormals,
// the largest doubles, ±inf, NaN and random bit patterns, for one value and per lane.
std::uint64_t bits_of(double x) { return std::bit_cast<std::uint64_t>(x); }

std::vector<double> absolute_term_operands() {
  std::vector<double> v{0.0, -0.0, 0x1p-1074, 0x1p-1073, 3 * 0x1p-1074, 0x1p-1022, 0x1p-1021, 0x1p-1000, 0x1p-968,
                        0x1p-1060, 1.0, 1e-300, 1e300, 1.7976931348623157e308, HUGE_VAL, -HUGE_VAL, std::nan("")};
  for (const double t : {0x1p-1000, 0x1p-968, 0x1p-1022, 0x1p-1020, 0x1p-1019})
    for (int k = 1; k <= 4; ++k) {
      double up = t, down = t;
      for (int j = 0; j < k; ++j) {
        up = std::nextafter(up, HUGE_VAL);
        down = std::nextafter(down, 0.0);
      }
      v.insert(v.end(), {up, down, -up, -down});
    }
  std::mt19937_64 rng(0xab5);
  for (int k = 0; k < 20000; ++k) {
    const int e = static_cast<int>(rng() % 130) - 1080;  // 2^-1080 .. 2^-950: the subnormals and the thresholds
    const double x = std::ldexp(static_cast<double>(rng() >> 11), e - 53);
    v.push_back(rng() % 2 ? x : -x);
    v.push_back(std::bit_cast<double>(rng()));
  }
  return v;
}

void expect_constant_term(const std::vector<double>& xs, detail::AbsoluteConstant c) {
  const double M = c.m;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const volatile double m = M;  // the sum itself, at run time
    const double want = xs[k] + m;
    const double got = detail::plus_absolute(xs[k], c);
    if (std::isnan(want)) EXPECT_TRUE(std::isnan(got));
    else ASSERT_EQ(bits_of(got), bits_of(want)) << std::hexfloat << xs[k] << " + " << M;
    const detail::Lanes4 x4{xs[k], xs[(k + 1) % xs.size()], xs[(k + 7) % xs.size()], -xs[k]};
    const detail::Lanes4 got4 = detail::plus_absolute(x4, c);
    for (int i = 0; i < 4; ++i) {
      const double w = x4[i] + m;
      if (std::isnan(w)) EXPECT_TRUE(std::isnan(got4[i]));
      else ASSERT_EQ(bits_of(got4[i]), bits_of(w)) << std::hexfloat << x4[i] << " + " << M << " (lane " << i << ")";
    }
  }
}

TEST(AbsoluteTerms, ConstantTermsAreTheSums) {
  const std::vector<double> xs = absolute_term_operands();
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::filter_absolute));
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::compensated_absolute));
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::refined_absolute));
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::tail_sum_absolute));
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::compare_absolute));
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::sphere_filter_c_absolute));
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::sphere_filter_d_absolute));
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::sphere_boundary_q_absolute));
  expect_constant_term(xs, detail::absolute_constant(detail::bounds::sphere_boundary_slope_absolute));
  expect_constant_term(xs, detail::absolute_constant(0x1p-1056));  // the largest the helper accepts
}

TEST(AbsoluteTerms, DynamicTermsAreTheSums) {
  const std::vector<double> xs = absolute_term_operands();
  std::vector<double> as{0x1p-1069, 0x1p-1070 + 0x1p-1069, 0x1p-1023, std::nextafter(0x1p-1022, 0.0), 0x1p-1022,
                         0x1p-1000, 1.0, 0.0, HUGE_VAL, std::nan("")};
  std::mt19937_64 rng(0xd1a);
  for (int k = 0; k < 200; ++k) as.push_back(std::bit_cast<double>(rng() >> 1));  // every a ≥ 0 (sign bit clear)
  for (const double a : as) {
    for (std::size_t k = 0; k < xs.size(); k += 3) {
      const volatile double va = a;
      const double want = xs[k] + va;
      const double got = detail::plus_absolute_term(xs[k], a);
      if (std::isnan(want)) EXPECT_TRUE(std::isnan(got));
      else ASSERT_EQ(bits_of(got), bits_of(want)) << std::hexfloat << xs[k] << " + " << a;
      const detail::Lanes4 x4{xs[k], -xs[k], xs[(k + 5) % xs.size()], 0.0};
      const detail::Lanes4 a4{a, a, as[k % as.size()], a};
      const detail::Lanes4 got4 = detail::plus_absolute_term(x4, a4);
      for (int i = 0; i < 4; ++i) {
        const double w = x4[i] + a4[i];
        if (std::isnan(w)) EXPECT_TRUE(std::isnan(got4[i]));
        else ASSERT_EQ(bits_of(got4[i]), bits_of(w)) << std::hexfloat << x4[i] << " + " << a4[i] << " (lane " << i << ")";
      }
    }
  }
}

}  // namespace
}  // namespace raykernel

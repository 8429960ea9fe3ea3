// The floating-point environment the guarantees rest on (README, "Floating-point assumptions"):
// no FMA contraction in the kernel's build, round-to-nearest, no flush-to-zero. The kernel's own build is
// probed; a deliberately contracting build of the same expression shows the probe can tell; and the run-time
// check is exercised by switching the rounding mode and flush-to-zero on and off.
#include "fp_probe.hpp"
#include "support/oracle.hpp"

#include <raykernel/raykernel.hpp>

#include <gtest/gtest.h>

#include <cfenv>
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

// A near tie: num = 2^53 + 1 + 2^-27, den = 2^53, t = 1 + 2^-53 + 2^-80 → RN is 1 + 2^-52 (hand-derived in
// contract_test.cpp). Under a directed rounding mode the certified stages' bounds do not hold, so
// `intersect` must notice and still give the round-to-nearest answer.
const Ray near_tie_ray{{-1, 0, 0}, {0x1p53, 0, 0}};
const Plane near_tie_plane{{0x1p53, 0x1p-27, 0}, {1, 1, 0}};

TEST(FpEnvironment, DefaultEnvironmentIsRecognized) { EXPECT_TRUE(floating_point_environment_is_default()); }

TEST(FpEnvironment, DirectedRoundingFallsBackToTheExactStage) {
  for (int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    ASSERT_EQ(std::fesetround(mode), 0);
    const bool recognized = !floating_point_environment_is_default();
    const TracedIntersection r = intersect_traced(near_tie_ray, near_tie_plane);
    std::fesetround(FE_TONEAREST);
    EXPECT_TRUE(recognized) << "mode " << mode;
    EXPECT_EQ(r.relation_stage, Stage::exact);
    EXPECT_EQ(r.intersection.t, 0x1.0000000000001p+0);
  }
}

#if defined(__x86_64__)
TEST(FpEnvironment, FlushToZeroFallsBackToTheExactStage) {
  // FTZ (bit 15) and DAZ (bit 6), as -ffast-math's startup code sets them. Products of 2^-600 underflow;
  // with DAZ a subnormal input would read as zero. The answer (t = 1, hand-derived in contract_test.cpp)
  // must not change.
  const Ray r{{0, 0, 0}, {0x1p-600, 0, 0}};
  const Plane p{{0x1p-600, 0, 0}, {0x1p-600, 0, 0}};
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(saved | 0x8040u);
  const bool recognized = !floating_point_environment_is_default();
  const TracedIntersection got = intersect_traced(r, p);
  _mm_setcsr(saved);
  EXPECT_TRUE(recognized);
  EXPECT_EQ(got.relation_stage, Stage::exact);
  EXPECT_EQ(got.intersection.relation, Relation::hit);
  EXPECT_EQ(got.intersection.t, 1.0);
}

TEST(FpEnvironment, UnmaskedExceptionsFallBackToTheExactStage) {
  // A parallel ray: the branch-free fast path would divide by d·n = 0 on the way to discarding the
  // quotient; with division-by-zero and invalid-operation traps enabled that must not happen.
  const Ray r{{0, 0, 0}, {1, 0, 0}};
  const Plane p{{0, 0, 5}, {0, 0, 1}};
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(saved & ~0x0280u);  // unmask ZM (bit 9) and IM (bit 7)
  const bool recognized = !floating_point_environment_is_default();
  const TracedIntersection got = intersect_traced(r, p);
  _mm_setcsr(saved);
  EXPECT_TRUE(recognized);
  EXPECT_EQ(got.relation_stage, Stage::exact);
  EXPECT_EQ(got.intersection.relation, Relation::parallel);
}
#endif

}  // namespace
}  // namespace raykernel

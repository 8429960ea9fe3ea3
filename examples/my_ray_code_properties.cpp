// Example (a): RapidCheck properties of your ray code, with raykernel as the reference.
//
// MyRayCode.IntersectMatchesRaykernel and MyRayCode.NearestOrdersNearTies are EXPECTED TO FAIL: the code in
// my_ray_code.cpp is the usual floating-point formula, and raykernel's generators find inputs where it is
// wrong. RapidCheck shrinks the failing input and prints it (every double as a hex float) with the
// reference check's report; RC_PARAMS="seed=N" (the seed is printed) replays the same run.
// Raykernel.IntersectPassesTheReferenceCheck is the control: raykernel::intersect passes with 0 ulps.
#include "my_ray_code.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_rapidcheck.hpp>  // gen_hard_query, gen_plane_pair_near_tie, the reference check

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstddef>
#include <string>

using raykernel::testkit::KindedQuery;
using raykernel::testkit::PlanePair;

// Your code's answer must be the exact relation, with t within 4 ulps of the correctly rounded t. The
// report (on failure) shows the query, a replay command for the raykernel CLI, expected and got, the exact
// t as P/Q and the ulp distance.
RC_GTEST_PROP(MyRayCode, IntersectMatchesRaykernel, (const KindedQuery& k)) {
  RC_TAG(raykernel::testkit::to_string(k.kind));  // the histogram of kinds tested, printed on success
  RAYKERNEL_RC_ASSERT_MATCHES_REFERENCE(k.query, my::ray_plane(k.query.ray, k.query.plane), 4);
}

// Nearest hit among two planes whose exact t tie or differ by less than an ulp: the construction knows the
// exact winner (smallest exact t, ties to the smaller index).
RC_GTEST_PROP(MyRayCode, NearestOrdersNearTies, (const PlanePair& pp)) {
  const int mine = my::nearest_hit(pp.ray, pp.planes);
  if (mine != pp.nearest()) {
    std::string message = "my::nearest_hit chose plane " + std::to_string(mine) + ", the exact nearest is plane " +
                          std::to_string(pp.nearest()) + " (" + std::string(raykernel::testkit::to_string(pp.kind)) +
                          ")\n";
    for (std::size_t i = 0; i < pp.planes.size(); ++i) {
      const raykernel::ExactIntersection exact = raykernel::intersect_exact_rational(pp.ray, pp.planes[i]);
      const raykernel::Intersection got = my::ray_plane(pp.ray, pp.planes[i]);
      message += "  plane " + std::to_string(i) + ": exact t = " + (exact.t ? exact.t->str() : "-") + ", rounded " +
                 raykernel::testkit::hex_string(exact.intersection.t) +
                 "; my t = " + raykernel::testkit::hex_string(got.t) + "\n";
    }
    RC_FAIL(message);
  }
}

// The control: raykernel's certified path is the exact answer, bit for bit.
RC_GTEST_PROP(Raykernel, IntersectPassesTheReferenceCheck, (const KindedQuery& k)) {
  RAYKERNEL_RC_ASSERT_MATCHES_REFERENCE(k.query, raykernel::intersect(k.query.ray, k.query.plane), 0);
}

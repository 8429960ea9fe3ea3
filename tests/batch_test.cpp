// The batch API gives `intersect`'s answers bit for bit: over every kind of hard query, through each
// instruction-set variant of the fast loop this CPU can run, split over threads or not, many rays against
// one plane or pairwise, with invalid queries reported or thrown.
#include "plane/fast_loop.hpp"
#include "support/oracle.hpp"

#include <raykernel/batch.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace raykernel {
namespace {

using testkit::Query;
using testkit::QueryKind;

// A structure-of-arrays copy of a list of queries.
struct SoA {
  std::vector<double> ox, oy, oz, dx, dy, dz, px, py, pz, nx, ny, nz;
  explicit SoA(const std::vector<Query>& q) {
    for (const Query& x : q) {
      ox.push_back(x.ray.origin.x), oy.push_back(x.ray.origin.y), oz.push_back(x.ray.origin.z);
      dx.push_back(x.ray.direction.x), dy.push_back(x.ray.direction.y), dz.push_back(x.ray.direction.z);
      px.push_back(x.plane.point.x), py.push_back(x.plane.point.y), pz.push_back(x.plane.point.z);
      nx.push_back(x.plane.normal.x), ny.push_back(x.plane.normal.y), nz.push_back(x.plane.normal.z);
    }
  }
  RayBatch rays() const { return {ox, oy, oz, dx, dy, dz}; }
  PlaneBatch planes() const { return {px, py, pz, nx, ny, nz}; }
};

std::vector<Query> queries_of_every_kind(std::size_t per_kind, std::uint64_t seed) {
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<Query> out;
  for (QueryKind kind : testkit::all_query_kinds)
    for (std::size_t i = 0; i < per_kind; ++i) out.push_back(testkit::make_query(kind, bits));
  // Interleave kinds so that every group of eight lanes mixes easy and hard queries.
  std::vector<Query> mixed(out.size());
  const std::size_t kinds = testkit::all_query_kinds.size();
  for (std::size_t i = 0; i < out.size(); ++i) mixed[(i % kinds) * per_kind + i / kinds] = out[i];
  return mixed;
}

void expect_matches_scalar(const std::vector<Query>& q, const std::vector<Relation>& relation,
                           const std::vector<double>& t) {
  for (std::size_t i = 0; i < q.size(); ++i) {
    const Intersection want = intersect(q[i].ray, q[i].plane);
    ASSERT_TRUE(test_support::same_answer({relation[i], t[i]}, want))
        << "query " << i << ": batch " << test_support::describe({relation[i], t[i]}) << ", intersect " << test_support::describe(want);
  }
}

TEST(Batch, PairwiseMatchesIntersectOnEveryKind) {
  const std::vector<Query> q = queries_of_every_kind(400, 11);
  const SoA soa(q);
  std::vector<Relation> relation(q.size());
  std::vector<double> t(q.size());
  BatchStats stats;
  intersect_batch(soa.rays(), soa.planes(), {relation, t}, {.threads = 1, .stats = &stats});
  expect_matches_scalar(q, relation, t);
  std::uint64_t counted = 0;
  for (auto n : stats.relation_stage) counted += n;
  EXPECT_EQ(counted, q.size());
  EXPECT_GT(stats.relation_stage[static_cast<int>(Stage::filter)], 0u);
  EXPECT_GT(stats.relation_stage[static_cast<int>(Stage::exact)], 0u);  // subnormal and huge kinds
}

TEST(Batch, ThreadsGiveTheSameAnswers) {
  const std::vector<Query> q = queries_of_every_kind(5000, 12);  // 65,000 queries: split over threads
  const SoA soa(q);
  std::vector<Relation> r1(q.size()), r4(q.size());
  std::vector<double> t1(q.size()), t4(q.size());
  intersect_batch(soa.rays(), soa.planes(), {r1, t1}, {.threads = 1});
  intersect_batch(soa.rays(), soa.planes(), {r4, t4}, {.threads = 4});
  for (std::size_t i = 0; i < q.size(); ++i)
    ASSERT_TRUE(test_support::same_answer({r1[i], t1[i]}, {r4[i], t4[i]})) << i;
  expect_matches_scalar(q, r4, t4);
}

TEST(Batch, ManyRaysAgainstOnePlane) {
  std::vector<Query> q = queries_of_every_kind(200, 13);
  const Plane plane = q[5].plane;
  for (Query& x : q) x.plane = plane;
  const SoA soa(q);
  std::vector<Relation> relation(q.size());
  std::vector<double> t(q.size());
  intersect_batch(soa.rays(), plane, {relation, t});
  expect_matches_scalar(q, relation, t);
}

// Each instruction-set variant of the fast loop that this CPU can run: whatever it certifies is the scalar
// fast path's answer, lane for lane.
TEST(Batch, EveryInstructionSetVariantAgreesWithTheScalarFastPath) {
  const std::vector<Query> q = queries_of_every_kind(300, 14);
  const SoA soa(q);
  const batch_kernel::RayArrays rays{soa.ox.data(), soa.oy.data(), soa.oz.data(),
                                     soa.dx.data(), soa.dy.data(), soa.dz.data()};
  const batch_kernel::PlaneArrays planes{soa.px.data(), soa.py.data(), soa.pz.data(),
                                         soa.nx.data(), soa.ny.data(), soa.nz.data()};
  struct Variant {
    const char* name;
    batch_kernel::LoopFunction loop;
    bool available;
  };
  std::vector<Variant> variants = {{"portable", batch_kernel::portable::pairwise, true}};
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __builtin_cpu_init();
  variants.push_back({"avx2", batch_kernel::avx2::pairwise, __builtin_cpu_supports("x86-64-v3") != 0});
  variants.push_back({"avx512", batch_kernel::avx512::pairwise, __builtin_cpu_supports("x86-64-v4") != 0});
#endif
  for (const Variant& v : variants) {
    if (!v.available) continue;
    SCOPED_TRACE(v.name);
    std::vector<Relation> relation(q.size());
    std::vector<double> t(q.size());
    std::vector<std::uint8_t> outcome(q.size());
    v.loop(rays, planes, 0, q.size(), relation.data(), t.data(), outcome.data());
    std::size_t certified = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      const double o[3] = {soa.ox[i], soa.oy[i], soa.oz[i]}, d[3] = {soa.dx[i], soa.dy[i], soa.dz[i]};
      const double p[3] = {soa.px[i], soa.py[i], soa.pz[i]}, n[3] = {soa.nx[i], soa.ny[i], soa.nz[i]};
      const detail::FastAnswer a = detail::fast_answer(detail::ray_plane_terms(o, d, p, n));
      const bool scalar_certified = a.certain;
      ASSERT_EQ((outcome[i] & batch_kernel::certified_by_fast_path) != 0, scalar_certified) << i;
      if (!scalar_certified) continue;
      ++certified;
      ASSERT_TRUE(test_support::same_bits(t[i], a.t)) << i;
      ASSERT_EQ(relation[i], a.behind ? Relation::behind : Relation::hit) << i;
      ASSERT_TRUE(test_support::same_answer({relation[i], t[i]}, intersect(q[i].ray, q[i].plane))) << i;
    }
    EXPECT_GT(certified, q.size() / 8);  // the easy kinds; the hard ones go on to the cascade
  }
}

TEST(Batch, InvalidQueriesAreReportedOrThrownWithTheirIndex) {
  std::vector<Query> q = queries_of_every_kind(10, 15);
  q[7].ray.direction = {0, 0, 0};
  q[40].plane.normal.y = std::numeric_limits<double>::quiet_NaN();
  const SoA soa(q);
  std::vector<Relation> relation(q.size());
  std::vector<double> t(q.size());
  std::unique_ptr<bool[]> valid(new bool[q.size()]);
  intersect_batch(soa.rays(), soa.planes(), {relation, t, std::span<bool>(valid.get(), q.size())});
  for (std::size_t i = 0; i < q.size(); ++i) {
    EXPECT_EQ(valid[i], i != 7 && i != 40) << i;
    if (valid[i]) {
      ASSERT_TRUE(test_support::same_answer({relation[i], t[i]}, intersect(q[i].ray, q[i].plane))) << i;
    }
  }
  try {
    intersect_batch(soa.rays(), soa.planes(), {relation, t});
    ADD_FAILURE() << "no exception";
  } catch (const invalid_input& e) {
    EXPECT_EQ(std::string(e.what()), "query 7: ray direction is the zero vector");
  }
}

TEST(Batch, MismatchedSpansAreAnError) {
  const std::vector<Query> q = queries_of_every_kind(2, 16);
  const SoA soa(q);
  std::vector<Relation> relation(q.size() - 1);
  std::vector<double> t(q.size());
  EXPECT_THROW(intersect_batch(soa.rays(), soa.planes(), {relation, t}), std::invalid_argument);
}

TEST(Batch, NearestHitBatchMatchesNearestHit) {
  const std::vector<Query> q = queries_of_every_kind(30, 17);
  std::vector<Plane> planes;
  for (std::size_t i = 0; i < 24; ++i) planes.push_back(q[i * 7 % q.size()].plane);
  planes.push_back(planes[3]);  // a duplicate: exact ties
  const SoA soa(q);
  std::vector<std::optional<NearestHit>> hits(q.size());
  nearest_hit_batch(soa.rays(), planes, hits, {.threads = 2});
  for (std::size_t i = 0; i < q.size(); ++i) ASSERT_EQ(hits[i], nearest_hit(q[i].ray, planes)) << i;
}

}  // namespace
}  // namespace raykernel

// raykernel_instruction_counts ENTRY COUNT: calls one entry point COUNT times, cycling through a buffer of 4096
// queries generated first (the benchmarks' L2 workloads), so that an instruction counter run twice with two
// counts gives the instructions per call as the difference (setup cancels):
//
//   bench/instruction-counts.sh build        # valgrind --tool=callgrind, every entry point, per call
//
// Entries: mesh/{nearest,occluded}/{icosphere,cube,terrain}-100k (per ray, bench/mesh_bench.cpp's rays), plane/{naive,certified,relation}/random, plane/{naive,certified}/degenerate, sphere/nearest/random64 (per ray, 64
// spheres, a SphereSet), nearest/certified/random64 (per ray, 64 planes, a
// PlaneSet), triangle/{naive,certified,relation}/{random,degenerate}, and per kind of the degenerate mix
// triangle/{naive,certified,relation}/{through-vertex,through-edge,near-vertex,near-edge,sliver,needle}. Hardware counters do not work on this
// VM and timings are shared with other jobs; instruction counts are exact and repeatable.
#include <raykernel/mesh_queries.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/occlusion.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/meshes.hpp>
#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/sphere_queries.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/triangle.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <utility>
#include <string>
#include <vector>

namespace {

using namespace raykernel;

constexpr std::size_t buffer_size = 4096;

// Seeds and kinds as bench/workloads.cpp (random) and bench/ray_triangle_bench.cpp (random, degenerate).
std::vector<testkit::Query> plane_queries() {
  testkit::SplitMix64 rng(1);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<testkit::Query> q(buffer_size);
  for (auto& x : q) x = testkit::make_query(testkit::QueryKind::random, bits);
  return q;
}

// bench/workloads.cpp's degenerate mix: near-parallel and near-coplanar alternately, seed 3.
std::vector<testkit::Query> plane_degenerate_queries() {
  testkit::SplitMix64 rng(3);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<testkit::Query> q(buffer_size);
  for (std::size_t i = 0; i < q.size(); ++i)
    q[i] = testkit::make_query(i % 2 == 0 ? testkit::QueryKind::near_parallel : testkit::QueryKind::near_coplanar, bits);
  return q;
}

std::vector<testkit::TriangleQuery> triangle_queries(std::initializer_list<testkit::TriangleQueryKind> kinds,
                                                     std::uint64_t seed) {
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  const std::vector<testkit::TriangleQueryKind> k(kinds);
  std::vector<testkit::TriangleQuery> q(buffer_size);
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = testkit::make_triangle_query(k[i % k.size()], bits);
  return q;
}

// Keeps results alive without a store per call the compiler could not drop anyway.
volatile double sink;

template <class Query, class F>
void run(const std::vector<Query>& queries, std::size_t count, F f) {
  double acc = 0;
  for (std::size_t i = 0; i < count; ++i) acc += f(queries[i % queries.size()]);
  sink = acc;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: raykernel_instruction_counts ENTRY COUNT\n");
    return 2;
  }
  const std::string entry = argv[1];
  const std::size_t count = std::strtoull(argv[2], nullptr, 10);
  using testkit::TriangleQueryKind;
  const std::map<std::string, std::function<void()>> entries = {
      {"plane/naive/random", [&] { run(plane_queries(), count, [](const testkit::Query& q) { return intersect_naive(q.ray, q.plane).t; }); }},
      {"plane/certified/random", [&] { run(plane_queries(), count, [](const testkit::Query& q) { return intersect(q.ray, q.plane).t; }); }},
      {"plane/naive/degenerate", [&] {
         run(plane_degenerate_queries(), count, [](const testkit::Query& q) { return intersect_naive(q.ray, q.plane).t; });
       }},
      {"plane/certified/degenerate", [&] {
         run(plane_degenerate_queries(), count, [](const testkit::Query& q) { return intersect(q.ray, q.plane).t; });
       }},
      {"plane/relation/random", [&] {
         run(plane_queries(), count, [](const testkit::Query& q) { return static_cast<double>(relation(q.ray, q.plane)); });
       }},
      {"nearest/certified/random64", [&] {
         const std::vector<testkit::Query> q = plane_queries();
         std::vector<Plane> planes;
         for (std::size_t i = 0; i < 64; ++i) planes.push_back(q[i].plane);
         const PlaneSet set(planes);
         run(q, count, [&set](const testkit::Query& x) {
           const std::optional<NearestHit> h = nearest_hit(x.ray, set);
           return h ? h->t : -1.0;
         });
       }},
      {"sphere/nearest/random64", [&] {  // per ray, 64 random spheres (a SphereSet), the rays of the same kind
         testkit::SplitMix64 rng(10);
         const testkit::BitSource bits = [&rng] { return rng(); };
         std::vector<testkit::SphereQuery> q(buffer_size);
         for (auto& x : q) x = testkit::make_sphere_query(testkit::SphereQueryKind::random, bits);
         std::vector<Sphere> spheres;
         for (std::size_t i = 0; i < 64; ++i) spheres.push_back(q[i].sphere);
         const SphereSet set(spheres);
         run(q, count, [&set](const testkit::SphereQuery& x) {
           const std::optional<SphereHit> h = nearest_hit(x.ray, RayInterval{}, set);
           return h ? h->t : -1.0;
         });
       }},
  };
  // Per ray on a 100k mesh of bench/mesh_bench.cpp (the same mesh and rays): the exact nearest hit and the
  // any-hit query.
  for (const auto& [name, make] : std::initializer_list<std::pair<const char*, Mesh (*)()>>{
           {"icosphere-100k", [] { return testkit::make_icosphere(6); }},
           {"cube-100k", [] { return testkit::make_subdivided_cube(91); }},
           {"terrain-100k", [] { return testkit::make_terrain(158); }}}) {
    const bool nearest = entry == std::string("mesh/nearest/") + name;
    if (!nearest && entry != std::string("mesh/occluded/") + name) continue;
    const Mesh m = make();
    const PreparedMesh prepared(m);
    run(testkit::benchmark_rays(m, buffer_size), count, [&](const Ray& r) {
      if (!nearest) return occluded(r, prepared) ? 1.0 : 0.0;
      const auto hit = nearest_hit(r, prepared);
      return hit ? hit->intersection.t : -1.0;
    });
    return 0;
  }
  auto triangle = [&](const char* name, std::initializer_list<TriangleQueryKind> kinds, std::uint64_t seed) {
    const std::string w = name;
    if (entry == "triangle/naive/" + w)
      run(triangle_queries(kinds, seed), count,
          [](const testkit::TriangleQuery& q) { return intersect_naive(q.ray, q.triangle).t; });
    else if (entry == "triangle/certified/" + w)
      run(triangle_queries(kinds, seed), count,
          [](const testkit::TriangleQuery& q) { return intersect(q.ray, q.triangle).t; });
    else if (entry == "triangle/relation/" + w)
      run(triangle_queries(kinds, seed), count, [](const testkit::TriangleQuery& q) {
        return static_cast<double>(relation(q.ray, q.triangle).relation);
      });
    else
      return false;
    return true;
  };
  if (const auto it = entries.find(entry); it != entries.end()) {
    it->second();
    return 0;
  }
  if (triangle("random", {TriangleQueryKind::random}, 14)) return 0;
  if (triangle("degenerate",
               {TriangleQueryKind::through_vertex, TriangleQueryKind::through_edge, TriangleQueryKind::near_vertex,
                TriangleQueryKind::near_edge, TriangleQueryKind::sliver, TriangleQueryKind::needle},
               15))
    return 0;
  // Each kind of the degenerate mix alone (bench/ray_triangle_bench.cpp's per-kind rows, seed 16).
  for (TriangleQueryKind kind : {TriangleQueryKind::through_vertex, TriangleQueryKind::through_edge,
                                 TriangleQueryKind::near_vertex, TriangleQueryKind::near_edge, TriangleQueryKind::sliver,
                                 TriangleQueryKind::needle})
    if (triangle(std::string(testkit::to_string(kind)).c_str(), {kind}, 16)) return 0;
  std::fprintf(stderr, "raykernel_instruction_counts: unknown entry '%s'\n", entry.c_str());
  return 2;
}

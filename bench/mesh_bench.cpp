// raykernel_mesh_bench: meshes at scale — readers, BVH build and traversal, and the baselines people use.
//
//   io/read_{obj,off,ply_ascii,ply_binary,stl_binary}/icosphere-1M   MB/s and triangles/s of read_mesh on a
//                                                                   ~10^6-triangle file made in memory
//   mesh/bvh_build/<mesh>, mesh/{embree,embree_robust}_build/<mesh>   build times on 1 and 2 threads, and
//                                   memory per triangle
//   mesh/bvh_traverse/<mesh>        rays/s of the certified BVH walk alone: every leaf whose box the ray may
//                                   meet (no bound), counting candidate triangles — the cost floor of the
//                                   exact nearest hit to come
//   mesh/certified/<mesh>           rays/s of nearest_hit(ray, PreparedMesh): the exact nearest hit (owned rule) —
//                                   the brute-force answer of docs/contract.md §7 — through the BVH
//   inside/certified/<mesh>         points/s of inside(point, PreparedMesh), exact
//   mesh/naive/<mesh>               rays/s of a nearest hit through the same BVH with Möller–Trumbore in
//                                   doubles (no guarantee), pruning by its t
//   mesh/{embree,embree_robust}/<mesh>   rays/s of rtcIntersect1 in Embree's default and robust modes (float
//                                   mesh and rays: Embree's answers are for the float data)
//   mesh/warm/{certified,embree_robust}/<mesh>   the certified nearest hit and rtcIntersect1 (robust) on the
//                                   first 16 rays only, cycled: what they read stays in the caches, so the
//                                   difference from the rows above is the time spent waiting for memory
//   mesh/embree_robust_packet8/<mesh>    rtcIntersect8
//   mesh/embree_robust_medium[_build]/<mesh>   Embree robust built without spatial splits (BUILD_QUALITY_MEDIUM;
//                                   the rows above use HIGH)
//   mesh/cgal_aabb/<mesh>           rays/s of CGAL's AABB_tree::first_intersected_primitive (Epick)
//   inside/cgal/<mesh>              points/s of CGAL's Side_of_triangle_mesh
//   closest/{certified,naive,cgal}/<mesh>   points/s of closest_point(point, PreparedMesh) (exact: the point, the
//                                   exact squared distance, the distance correctly rounded), closest_point_naive
//                                   (Ericson's algorithm in doubles through the same BVH) and CGAL's
//                                   AABB_tree::closest_point_and_primitive (Epick) with √ of its squared distance;
//                                   counters on the naive and CGAL rows, over the first 4,096 points: the share
//                                   whose distance differs from the correctly rounded exact one (wrong_pct), the
//                                   largest difference in ulps (max_ulps), and the share naming another triangle
//                                   at a different exact distance (other_triangle_pct)
//   ties/{certified,naive}/<mesh>   nearest_hit(ray, PreparedMesh) and nearest_hit_naive (the BVH with
//                                   Möller–Trumbore, the baseline) on meshes where one ray meets many triangles at
//                                   one exact t or crosses many boxes: duplicates-100k (10^5 copies of one
//                                   triangle, vertex orders rotated and reversed), fan-1M (a convex 10^6-gon on the
//                                   unit circle fanned from its first vertex: slivers whose boxes all hold that
//                                   vertex), overlapping-fan-1M and overlapping-fan-tilted-100k (the fan of a
//                                   polygon winding over itself, v0 = 0, vi = (i, ±1), in the plane z = 0 or
//                                   z = x + 2y: every ray hits every triangle at one exact t); counters: candidate
//                                   triangles, hits, near ties (not ordered by the filter) and those ordered in
//                                   rationals, per ray
// Meshes (testkit, exact dyadic vertices): icosphere, subdivided cube and terrain at ~10^3, ~10^5 and
// ~10^6 triangles. Rays: 2^16 per mesh, from a sphere around it towards random points of its box (fixed
// seed). Every ray benchmark runs on 1 thread and on all threads (items_per_second is the total).
// bench/README.md has the command and the numbers.
#include "cgal_mesh_baselines.hpp"

#include <raykernel/bvh.hpp>
#include <raykernel/closest_point.hpp>
#include <raykernel/mesh_queries.hpp>
#include <raykernel/occlusion.hpp>
#include <raykernel/io/mesh_file.hpp>
#include <raykernel/testkit/meshes.hpp>

#ifdef RAYKERNEL_HAVE_EMBREE
#include "embree_scene.hpp"
#endif

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace raykernel::bench {
namespace {

struct MeshSpec {
  std::string name;
  std::function<Mesh()> make;
};

const std::vector<MeshSpec>& mesh_specs() {
  static const std::vector<MeshSpec> specs = {
      {"icosphere-1k", [] { return testkit::make_icosphere(3); }},         // 1,280 triangles
      {"cube-1k", [] { return testkit::make_subdivided_cube(9); }},         // 972
      {"terrain-1k", [] { return testkit::make_terrain(16); }},             // 1,152
      {"icosphere-100k", [] { return testkit::make_icosphere(6); }},       // 81,920
      {"cube-100k", [] { return testkit::make_subdivided_cube(91); }},      // 99,372
      {"terrain-100k", [] { return testkit::make_terrain(158); }},          // 101,120
      {"icosphere-1M", [] { return testkit::make_icosphere(8); }},         // 1,310,720
      {"cube-1M", [] { return testkit::make_subdivided_cube(289); }},       // 1,002,252
      {"terrain-1M", [] { return testkit::make_terrain(500); }},            // 1,004,000
  };
  return specs;
}

// Everything one mesh's benchmarks need, built on first use (under a lock: the threads of a benchmark all
// ask). One mesh at a time is kept.
struct Fixture {
  std::string name;
  Mesh mesh;
  std::vector<Ray> rays;
  std::vector<Vec3> points;
  std::unique_ptr<MeshBvh> bvh;
  std::unique_ptr<PreparedMesh> prepared;
  double inside_grid_seconds = -1;  // the first inside call on `prepared` (it builds the point-location grid)
  std::unique_ptr<CgalMeshQueries> cgal;
#ifdef RAYKERNEL_HAVE_EMBREE
  std::unique_ptr<baseline::EmbreeScene> embree[2];
  std::unique_ptr<baseline::EmbreeScene> embree_medium;  // robust, RTC_BUILD_QUALITY_MEDIUM (no spatial splits)
#endif
};

std::mutex fixture_mutex;
std::unique_ptr<Fixture> current;

Fixture& fixture(const std::string& name) {
  if (current && current->name == name) return *current;
  current.reset();
  auto f = std::make_unique<Fixture>();
  f->name = name;
  for (const MeshSpec& s : mesh_specs())
    if (s.name == name) f->mesh = s.make();
  f->rays = testkit::benchmark_rays(f->mesh, std::size_t{1} << 16, &f->points);
  current = std::move(f);
  return *current;
}

template <class Part, class Make>
const Part& part(std::unique_ptr<Part>& slot, Make&& make) {
  if (!slot) slot = make();
  return *slot;
}

// Points per second of `query` over the fixture's points (uniform in the mesh's box), after `prepare`.
template <class Prepare, class Query>
void point_benchmark(benchmark::State& state, const std::string& m, Prepare&& prepare, Query&& query) {
  Fixture* f;
  {
    std::lock_guard lock(fixture_mutex);
    f = &fixture(m);
    prepare(*f);
  }
  std::size_t i = static_cast<std::size_t>(state.thread_index()) * 7919 % f->points.size();
  double sum = 0;
  for (auto _ : state) {
    sum += query(*f, f->points[i]);
    if (++i == f->points.size()) i = 0;
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

// How a baseline's distances compare with the exact ones (closest_point), over the first 4,096 points: counters.
template <class Baseline>
void closest_accuracy(benchmark::State& state, Fixture& f, Baseline&& baseline) {
  part(f.prepared, [&] { return std::make_unique<PreparedMesh>(f.mesh); });
  const std::size_t n = std::min<std::size_t>(4096, f.points.size());
  std::uint64_t wrong = 0, other = 0;
  double max_ulps = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const ClosestPoint exact = closest_point(f.points[i], *f.prepared);
    const auto [triangle, distance] = baseline(f, f.points[i]);
    if (distance != exact.distance) {
      ++wrong;
      max_ulps = std::max(max_ulps, std::fabs(distance - exact.distance) /
                                        (std::nextafter(exact.distance, INFINITY) - exact.distance));
    }
    if (triangle != exact.triangle) {  // another triangle: wrong unless it is at the same exact distance
      const Triangle t = f.mesh.triangle(triangle);
      const Mesh one{{t.a, t.b, t.c}, {{0, 1, 2}}};
      if (closest_point_exact(f.points[i], one).squared_distance_exact.str() != exact.squared_distance_exact.str()) ++other;
    }
  }
  state.counters["wrong_pct"] = 100.0 * static_cast<double>(wrong) / static_cast<double>(n);
  state.counters["max_ulps"] = max_ulps;
  state.counters["other_triangle_pct"] = 100.0 * static_cast<double>(other) / static_cast<double>(n);
}

// Möller–Trumbore in doubles (the baseline users compare; to be replaced by intersect_naive(Ray, Triangle)
// when it lands): t of a hit, or nothing.
std::optional<double> moller_trumbore(const Ray& r, const Triangle& tri) {
  const Vec3 e1{tri.b.x - tri.a.x, tri.b.y - tri.a.y, tri.b.z - tri.a.z}, e2{tri.c.x - tri.a.x, tri.c.y - tri.a.y, tri.c.z - tri.a.z};
  const Vec3& d = r.direction;
  const Vec3 p{d.y * e2.z - d.z * e2.y, d.z * e2.x - d.x * e2.z, d.x * e2.y - d.y * e2.x};
  const double det = e1.x * p.x + e1.y * p.y + e1.z * p.z;
  if (det == 0) return std::nullopt;
  const double inv = 1 / det;
  const Vec3 s{r.origin.x - tri.a.x, r.origin.y - tri.a.y, r.origin.z - tri.a.z};
  const double u = (s.x * p.x + s.y * p.y + s.z * p.z) * inv;
  if (u < 0 || u > 1) return std::nullopt;
  const Vec3 q{s.y * e1.z - s.z * e1.y, s.z * e1.x - s.x * e1.z, s.x * e1.y - s.y * e1.x};
  const double v = (d.x * q.x + d.y * q.y + d.z * q.z) * inv;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = (e2.x * q.x + e2.y * q.y + e2.z * q.z) * inv;
  if (t < 0) return std::nullopt;
  return t;
}

constexpr std::size_t warm_rays = 16;  // the warm rows' rays (mesh/warm/...)

void set_rate(benchmark::State& state, std::int64_t per_iteration) {
  state.SetItemsProcessed(state.iterations() * per_iteration);
}

// A ray benchmark: `query(fixture, ray)` for ray after ray, each thread starting elsewhere in the list; with
// `rays`, only the list's first `rays` rays, cycled (the warm rows: what they read stays in the caches).
template <class Prepare, class Query>
void ray_benchmark(benchmark::State& state, const std::string& mesh, Prepare prepare, Query query,
                   std::size_t rays = 0) {
  Fixture* f;
  {
    std::lock_guard lock(fixture_mutex);
    f = &fixture(mesh);
    prepare(*f);
  }
  const std::size_t n = rays != 0 ? std::min(rays, f->rays.size()) : f->rays.size();
  std::size_t i = static_cast<std::size_t>(state.thread_index()) * 7919 % n;
  std::uint64_t sink = 0;
  for (auto _ : state) {
    sink += query(*f, f->rays[i]);
    if (++i == n) i = 0;
  }
  benchmark::DoNotOptimize(sink);
  set_rate(state, 1);
}

// What a nearest hit touches, over the first 4,096 rays: candidate triangles per ray (nearest_hit_traced), nodes
// per ray of the walk pruned by the winner's t (the search's bound only comes down to it, so this is a lower
// bound of the nodes it tests), and the bytes those read (256 per node; 72 per candidate's triangle, 4 for its
// index).
void walk_counters(benchmark::State& state, const std::string& mesh) {
  std::lock_guard lock(fixture_mutex);
  Fixture& f = fixture(mesh);
  const std::size_t rays = std::min<std::size_t>(4096, f.rays.size());
  double candidates = 0, nodes = 0;
  for (std::size_t i = 0; i < rays; ++i) {
    const TracedMeshHit traced = nearest_hit_traced(f.rays[i], *f.prepared);
    candidates += static_cast<double>(traced.candidates);
    const double bound = traced.hit ? std::nextafter(traced.hit->intersection.t, std::numeric_limits<double>::infinity())
                                    : std::numeric_limits<double>::infinity();
    BvhRayTraversal walk(f.prepared->bvh(), f.rays[i]);
    while (walk.next(bound)) {
    }
    nodes += static_cast<double>(walk.boxes_tested()) / BvhNode::width;
  }
  const auto n = static_cast<double>(rays);
  state.counters["candidates_per_ray"] = candidates / n;
  state.counters["nodes_per_ray"] = nodes / n;
  state.counters["bytes_per_ray"] = (nodes * sizeof(BvhNode) + candidates * (sizeof(Triangle) + 4)) / n;
}

#ifdef RAYKERNEL_HAVE_EMBREE
// An Embree scene's build on state.range(0) threads, and what its device then holds per triangle (its memory
// monitor's sum: the float vertex and index buffers, the BVH and its leaves).
void embree_build(benchmark::State& state, const std::string& mesh_name, baseline::EmbreeScene::Mode mode,
                  baseline::EmbreeScene::Quality quality) {
  const Mesh* mesh;
  {
    std::lock_guard lock(fixture_mutex);
    mesh = &fixture(mesh_name).mesh;
  }
  const auto threads = static_cast<unsigned>(state.range(0));
  std::size_t bytes = 0;
  for (auto _ : state) {
    const baseline::EmbreeScene scene(*mesh, mode, threads, false, quality);
    bytes = scene.device_bytes();
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["device_bytes_per_triangle"] = static_cast<double>(bytes) / static_cast<double>(mesh->triangles.size());
}
#endif

void threads(benchmark::internal::Benchmark* b) {
  const int all = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  b->Threads(1);
  if (all > 1) b->Threads(all);
  b->UseRealTime();
}

// ---- ties and slivers ---------------------------------------------------------------------------

struct TieSpec {
  std::string name;
  std::function<Mesh()> make;
  std::function<Ray(std::mt19937_64&)> ray;  // a ray of the workload
};


// Downwards (with a small tilt) through a point of the region 0 < x ≤ 1/2, |y| < x·2^-21 that every triangle of
// an overlapping fan of at most 2^20 vertices contains.
Ray ray_through_fan_core(std::mt19937_64& rng, bool tilted) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double x = 0.5 * (0.25 + 0.75 * unit(rng)), y = x * std::ldexp(2 * unit(rng) - 1, -22);
  const double z = tilted ? x + 2 * y : 0;
  const Vec3 o{x + std::ldexp(unit(rng) - 0.5, -30), y, z + 8};
  return {o, {x - o.x, y - o.y, z - o.z}};
}

const std::vector<TieSpec>& tie_specs() {
  static const std::vector<TieSpec> specs = {
      {"duplicates-100k",
       [] {
         Mesh m;
         m.vertices = {{-1, -1, 1}, {3, -1, 1.5}, {-1, 3, 2}};
         const std::array<std::array<std::uint32_t, 3>, 4> orders{{{0, 1, 2}, {1, 2, 0}, {2, 1, 0}, {0, 2, 1}}};
         for (std::uint32_t k = 0; k < 100000; ++k) m.triangles.push_back(orders[k % 4]);
         return m;
       },
       [](std::mt19937_64& rng) {  // from above towards a point inside the triangle
         std::uniform_real_distribution<double> unit(0.0, 1.0);
         const double u = unit(rng), v = unit(rng) * (1 - u);
         const Vec3 target{-1 + 4 * u, -1 + 4 * v, 1 + 0.5 * u + v};  // a + u(b − a) + v(c − a)
         const Vec3 o{unit(rng) - 0.5, unit(rng) - 0.5, 6};
         return Ray{o, {target.x - o.x, target.y - o.y, target.z - o.z}};
       }},
      {"fan-1M",
       [] {
         Mesh m;
         constexpr std::uint32_t n = 1000000;
         for (std::uint32_t i = 0; i < n; ++i) {
           const double a = 2 * M_PI * i / n;
           m.vertices.push_back({std::cos(a), std::sin(a), 0});
         }
         for (std::uint32_t i = 1; i + 1 < n; ++i) m.triangles.push_back({0, i, i + 1});
         return m;
       },
       [](std::mt19937_64& rng) {  // from above towards a point within radius 0.9
         std::uniform_real_distribution<double> unit(0.0, 1.0);
         const double r = 0.9 * std::sqrt(unit(rng)), a = 2 * M_PI * unit(rng);
         const Vec3 target{r * std::cos(a), r * std::sin(a), 0};
         const Vec3 o{target.x + 0.5 * (unit(rng) - 0.5), target.y + 0.5 * (unit(rng) - 0.5), 2};
         return Ray{o, {target.x - o.x, target.y - o.y, -o.z}};
       }},
      {"overlapping-fan-1M", [] { return testkit::make_overlapping_fan(1000000, false); },
       [](std::mt19937_64& rng) { return ray_through_fan_core(rng, false); }},
      {"overlapping-fan-tilted-100k", [] { return testkit::make_overlapping_fan(100000, true); },
       [](std::mt19937_64& rng) { return ray_through_fan_core(rng, true); }},
  };
  return specs;
}

struct TieFixture {
  std::string name;
  std::unique_ptr<PreparedMesh> prepared;
  std::vector<Ray> rays;
  TracedMeshHit totals;  // summed over the rays
};
std::unique_ptr<TieFixture> current_ties;

TieFixture& tie_fixture(const std::string& name) {
  if (current_ties && current_ties->name == name) return *current_ties;
  current_ties.reset();
  auto f = std::make_unique<TieFixture>();
  f->name = name;
  for (const TieSpec& s : tie_specs()) {
    if (s.name != name) continue;
    f->prepared = std::make_unique<PreparedMesh>(s.make());
    std::mt19937_64 rng(25);
    for (int i = 0; i < 64; ++i) f->rays.push_back(s.ray(rng));
  }
  // What the certified path does for these rays (and a check that it answers as the brute force would: every
  // ray hits; the rational reference is too slow at this size).
  for (const Ray& r : f->rays) {
    const TracedMeshHit t = nearest_hit_traced(r, *f->prepared);
    if (!t.hit) throw std::logic_error("ties benchmark: a ray of " + name + " misses");
    f->totals.candidates += t.candidates;
    f->totals.hits += t.hits;
    f->totals.ties += t.ties;
    f->totals.ties_without_arithmetic += t.ties_without_arithmetic;
    for (int s = 0; s < stage_count; ++s) f->totals.comparisons[static_cast<std::size_t>(s)] += t.comparisons[static_cast<std::size_t>(s)];
  }
  current_ties = std::move(f);
  return *current_ties;
}

void register_ties() {
  for (const TieSpec& spec : tie_specs()) {
    const std::string m = spec.name;
    for (const bool certified : {true, false}) {
      benchmark::RegisterBenchmark(("ties/" + std::string(certified ? "certified/" : "naive/") + m).c_str(),
                                   [m, certified](benchmark::State& state) {
                                     TieFixture* f;
                                     {
                                       std::lock_guard lock(fixture_mutex);
                                       f = &tie_fixture(m);
                                     }
                                     std::size_t i = 0;
                                     std::uint64_t sink = 0;
                                     for (auto _ : state) {
                                       const auto hit = certified ? nearest_hit(f->rays[i], *f->prepared)
                                                                  : nearest_hit_naive(f->rays[i], *f->prepared);
                                       sink += hit ? hit->triangle : 0;
                                       if (++i == f->rays.size()) i = 0;
                                     }
                                     benchmark::DoNotOptimize(sink);
                                     set_rate(state, 1);
                                     const double rays = static_cast<double>(f->rays.size());
                                     state.counters["candidates"] = static_cast<double>(f->totals.candidates) / rays;
                                     state.counters["hits"] = static_cast<double>(f->totals.hits) / rays;
                                     state.counters["ties"] = static_cast<double>(f->totals.ties) / rays;
                                     state.counters["ties_exact"] =
                                         static_cast<double>(f->totals.comparisons[static_cast<std::size_t>(Stage::exact)]) / rays;
                                   })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

void register_all() {
  register_ties();

  // Readers, on the 10^6 icosphere written in each format.
  for (auto [label, format, encoding] :
       {std::tuple{"obj", io::MeshFormat::obj, io::MeshEncoding::ascii}, {"off", io::MeshFormat::off, io::MeshEncoding::ascii},
        {"ply_ascii", io::MeshFormat::ply, io::MeshEncoding::ascii},
        {"ply_binary", io::MeshFormat::ply, io::MeshEncoding::binary_little_endian},
        {"stl_binary", io::MeshFormat::stl, io::MeshEncoding::binary_little_endian},
        {"stl_ascii", io::MeshFormat::stl, io::MeshEncoding::ascii}}) {
    benchmark::RegisterBenchmark(("io/read_" + std::string(label) + "/icosphere-1M").c_str(),
                                 [format = format, encoding = encoding](benchmark::State& state) {
                                   // icosphere vertices (multiples of 2^-30 in [-1, 1]) are floats too, as STL needs
                                   const Mesh mesh = testkit::make_icosphere(8, 23);
                                   const std::string bytes = io::write_mesh(mesh, format, encoding);
                                   std::size_t triangles = 0;
                                   for (auto _ : state) triangles = io::read_mesh(bytes, "bench", format).triangles.size();
                                   state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(bytes.size()));
                                   state.counters["triangles/s"] = benchmark::Counter(static_cast<double>(triangles),
                                                                                      benchmark::Counter::kIsIterationInvariantRate);
                                 })
        ->Unit(benchmark::kMillisecond)
        ->MinTime(2);
  }

  for (const MeshSpec& spec : mesh_specs()) {
    const std::string m = spec.name;
    benchmark::RegisterBenchmark(("mesh/bvh_build/" + m).c_str(), [m](benchmark::State& state) {
      const Mesh* mesh;
      {
        std::lock_guard lock(fixture_mutex);
        mesh = &fixture(m).mesh;
      }
      const BvhBuildOptions options{.threads = static_cast<unsigned>(state.range(0))};
      std::size_t bytes = 0;
      for (auto _ : state) {
        const MeshBvh bvh(*mesh, options);
        bytes = bvh.nodes().size_bytes() + bvh.triangle_order().size_bytes();
        benchmark::DoNotOptimize(bvh.nodes().size());
      }
      const auto triangles = static_cast<double>(mesh->triangles.size());
      state.counters["triangles"] = triangles;
      // Memory: the hierarchy (nodes and the triangle order), and the prepared mesh's copy of the triangles in
      // leaf order (9 doubles each) that the queries read beside it.
      state.counters["bvh_bytes_per_triangle"] = static_cast<double>(bytes) / triangles;
      state.counters["prepared_bytes_per_triangle"] = static_cast<double>(bytes + mesh->triangles.size() * sizeof(Triangle)) / triangles;
    })->Unit(benchmark::kMillisecond)->MinTime(1)->ArgName("threads")->Arg(1)->Arg(2);

    benchmark::RegisterBenchmark(("mesh/bvh_traverse/" + m).c_str(), [m](benchmark::State& state) {
      ray_benchmark(
          state, m, [](Fixture& f) { part(f.bvh, [&] { return std::make_unique<MeshBvh>(f.mesh); }); },
          [](Fixture& f, const Ray& r) {
            std::uint64_t candidates = 0;
            BvhRayTraversal walk(*f.bvh, r);
            while (const auto leaf = walk.next()) candidates += leaf->triangles.size();
            return candidates;
          });
    })->Apply(threads);

    // mesh/certified over every ray; mesh/warm/certified over the first 16 only, cycled, so that the nodes and
    // triangles they read stay in the caches (about 40 KB): the arithmetic's time without the memory's, against
    // Embree's warm row below.
    for (const std::size_t rays : {std::size_t{0}, warm_rays}) {
      const std::string name = (rays == 0 ? "mesh/certified/" : "mesh/warm/certified/") + m;
      benchmark::RegisterBenchmark(name.c_str(), [m, rays](benchmark::State& state) {
        ray_benchmark(
            state, m, [](Fixture& f) { part(f.prepared, [&] { return std::make_unique<PreparedMesh>(f.mesh); }); },
            [](Fixture& f, const Ray& r) {
              const auto hit = nearest_hit(r, *f.prepared);
              return hit ? std::uint64_t{hit->triangle} : 0;
            },
            rays);
        if (rays == 0 && state.threads() == 1) walk_counters(state, m);
      })->Apply(threads);
    }

    // Any-hit (shadow rays): raykernel's occluded (owned rule, stops at the first blocker) against Embree's
    // rtcOccluded1 below; the same rays as the nearest-hit rows.
    benchmark::RegisterBenchmark(("mesh/occluded/certified/" + m).c_str(), [m](benchmark::State& state) {
      ray_benchmark(
          state, m, [](Fixture& f) { part(f.prepared, [&] { return std::make_unique<PreparedMesh>(f.mesh); }); },
          [](Fixture& f, const Ray& r) { return std::uint64_t{occluded(r, *f.prepared)}; });
    })->Apply(threads);

    benchmark::RegisterBenchmark(("inside/certified/" + m).c_str(), [m](benchmark::State& state) {
      Fixture* f;
      {
        std::lock_guard lock(fixture_mutex);
        f = &fixture(m);
        part(f->prepared, [&] { return std::make_unique<PreparedMesh>(f->mesh); });
        // The point-location grid is built by a prepared mesh's first inside call: here, timed, outside the loop
        // (as CGAL's tree is built by Side_of_triangle_mesh's constructor, outside its loop).
        if (f->inside_grid_seconds < 0) {
          const auto start = std::chrono::steady_clock::now();
          benchmark::DoNotOptimize(inside(f->points[0], *f->prepared));
          f->inside_grid_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
      }
      state.counters["grid_build_ms"] = benchmark::Counter(1e3 * f->inside_grid_seconds, benchmark::Counter::kAvgThreads);
      std::size_t i = static_cast<std::size_t>(state.thread_index()) * 7919 % f->points.size();
      std::int64_t sum = 0;
      for (auto _ : state) {
        sum += static_cast<int>(inside(f->points[i], *f->prepared));
        if (++i == f->points.size()) i = 0;
      }
      benchmark::DoNotOptimize(sum);
      set_rate(state, 1);
    })->Apply(threads);

    benchmark::RegisterBenchmark(("mesh/naive/" + m).c_str(), [m](benchmark::State& state) {
      ray_benchmark(
          state, m, [](Fixture& f) { part(f.bvh, [&] { return std::make_unique<MeshBvh>(f.mesh); }); },
          [](Fixture& f, const Ray& r) {
            double best = std::numeric_limits<double>::infinity();
            std::uint64_t best_k = ~0ull;
            BvhRayTraversal walk(*f.bvh, r);
            // Pruning by a naive t is not certified (it may be off by rounding); this is the baseline.
            while (const auto leaf = walk.next(best))
              for (std::uint32_t k : leaf->triangles)
                if (const auto t = moller_trumbore(r, f.mesh.triangle(k)); t && (*t < best || (*t == best && k < best_k))) {
                  best = *t;
                  best_k = k;
                }
            return best_k;
          });
    })->Apply(threads);

#ifdef RAYKERNEL_HAVE_EMBREE
    for (int robust = 0; robust < 2; ++robust) {
      const std::string mode = robust ? "embree_robust" : "embree";
      benchmark::RegisterBenchmark(("mesh/" + mode + "_build/" + m).c_str(), [m, robust](benchmark::State& state) {
        embree_build(state, m, robust ? baseline::EmbreeScene::Mode::robust : baseline::EmbreeScene::Mode::fast,
                     baseline::EmbreeScene::Quality::high);
      })->Unit(benchmark::kMillisecond)->MinTime(1)->ArgName("threads")->Arg(1)->Arg(2);
      benchmark::RegisterBenchmark(("mesh/" + mode + "/" + m).c_str(), [m, robust](benchmark::State& state) {
        ray_benchmark(
            state, m,
            [robust](Fixture& f) {
              part(f.embree[robust], [&] {
                auto s = std::make_unique<baseline::EmbreeScene>(f.mesh, robust ? baseline::EmbreeScene::Mode::robust
                                                                                 : baseline::EmbreeScene::Mode::fast);
                return s;
              });
            },
            [robust](Fixture& f, const Ray& r) {
              const auto hit = f.embree[robust]->intersect(r);
              return hit ? std::uint64_t{hit->triangle} : 0;
            });
        std::lock_guard lock(fixture_mutex);
        state.counters["coords_changed_by_float"] =
            benchmark::Counter(static_cast<double>(current->embree[robust]->conversion().inexact), benchmark::Counter::kAvgThreads);
      })->Apply(threads);
    }
    benchmark::RegisterBenchmark(("mesh/warm/embree_robust/" + m).c_str(), [m](benchmark::State& state) {
      ray_benchmark(
          state, m,
          [](Fixture& f) {
            part(f.embree[1], [&] {
              return std::make_unique<baseline::EmbreeScene>(f.mesh, baseline::EmbreeScene::Mode::robust);
            });
          },
          [](Fixture& f, const Ray& r) {
            const auto hit = f.embree[1]->intersect(r);
            return hit ? std::uint64_t{hit->triangle} : 0;
          },
          warm_rays);
    })->Apply(threads);
    for (int robust = 0; robust < 2; ++robust) {
      const std::string mode = robust ? "embree_robust" : "embree";
      benchmark::RegisterBenchmark(("mesh/occluded/" + mode + "/" + m).c_str(), [m, robust](benchmark::State& state) {
        ray_benchmark(
            state, m,
            [robust](Fixture& f) {
              part(f.embree[robust], [&] {
                return std::make_unique<baseline::EmbreeScene>(f.mesh, robust ? baseline::EmbreeScene::Mode::robust
                                                                              : baseline::EmbreeScene::Mode::fast);
              });
            },
            [robust](Fixture& f, const Ray& r) { return std::uint64_t{f.embree[robust]->occluded(r)}; });
      })->Apply(threads);
    }
    benchmark::RegisterBenchmark(("mesh/embree_robust_packet8/" + m).c_str(), [m](benchmark::State& state) {
      Fixture* f;
      {
        std::lock_guard lock(fixture_mutex);
        f = &fixture(m);
        part(f->embree[1], [&] { return std::make_unique<baseline::EmbreeScene>(f->mesh, baseline::EmbreeScene::Mode::robust); });
      }
      std::optional<baseline::EmbreeScene::Hit> hits[8];
      std::size_t i = static_cast<std::size_t>(state.thread_index()) * 7912 % f->rays.size();
      for (auto _ : state) {
        f->embree[1]->intersect8(std::span(f->rays).subspan(i, 8), hits);
        benchmark::DoNotOptimize(hits);
        i = (i + 8) % f->rays.size();
      }
      set_rate(state, 8);
    })->Apply(threads);
    // Embree robust without spatial splits (RTC_BUILD_QUALITY_MEDIUM, Embree's default quality; the rows above
    // use HIGH): what the splits gain in query speed and cost in build time.
    benchmark::RegisterBenchmark(("mesh/embree_robust_medium_build/" + m).c_str(), [m](benchmark::State& state) {
      embree_build(state, m, baseline::EmbreeScene::Mode::robust, baseline::EmbreeScene::Quality::medium);
    })->Unit(benchmark::kMillisecond)->MinTime(1)->ArgName("threads")->Arg(1)->Arg(2);
    benchmark::RegisterBenchmark(("mesh/embree_robust_medium/" + m).c_str(), [m](benchmark::State& state) {
      ray_benchmark(
          state, m,
          [](Fixture& f) {
            part(f.embree_medium, [&] {
              return std::make_unique<baseline::EmbreeScene>(f.mesh, baseline::EmbreeScene::Mode::robust, 0, false,
                                                             baseline::EmbreeScene::Quality::medium);
            });
          },
          [](Fixture& f, const Ray& r) {
            const auto hit = f.embree_medium->intersect(r);
            return hit ? std::uint64_t{hit->triangle} : 0;
          });
    })->Apply(threads);
#endif

    benchmark::RegisterBenchmark(("mesh/cgal_aabb/" + m).c_str(), [m](benchmark::State& state) {
      ray_benchmark(
          state, m, [](Fixture& f) { part(f.cgal, [&] { return std::make_unique<CgalMeshQueries>(f.mesh); }); },
          [](Fixture& f, const Ray& r) {
            const auto hit = f.cgal->first_hit(r);
            return hit ? std::uint64_t{*hit} : 0;
          });
    })->Apply(threads);

    benchmark::RegisterBenchmark(("closest/certified/" + m).c_str(), [m](benchmark::State& state) {
      point_benchmark(state, m, [](Fixture& f) { part(f.prepared, [&] { return std::make_unique<PreparedMesh>(f.mesh); }); },
                      [](Fixture& f, const Vec3& p) { return closest_point(p, *f.prepared).distance; });
    })->Apply(threads);
    benchmark::RegisterBenchmark(("closest/naive/" + m).c_str(), [m](benchmark::State& state) {
      point_benchmark(state, m, [](Fixture& f) { part(f.prepared, [&] { return std::make_unique<PreparedMesh>(f.mesh); }); },
                      [](Fixture& f, const Vec3& p) { return closest_point_naive(p, *f.prepared).distance; });
      if (state.thread_index() == 0)
        closest_accuracy(state, fixture(m), [](Fixture& f, const Vec3& p) {
          const ClosestPoint c = closest_point_naive(p, *f.prepared);
          return std::pair{c.triangle, c.distance};
        });
    })->Apply(threads);
    benchmark::RegisterBenchmark(("closest/cgal/" + m).c_str(), [m](benchmark::State& state) {
      point_benchmark(state, m, [](Fixture& f) { part(f.cgal, [&] { return std::make_unique<CgalMeshQueries>(f.mesh); }); },
                      [](Fixture& f, const Vec3& p) { return f.cgal->closest(p).distance; });
      closest_accuracy(state, fixture(m), [](Fixture& f, const Vec3& p) {
        const CgalMeshQueries::Closest c = f.cgal->closest(p);
        return std::pair{c.triangle, c.distance};
      });
    });  // 1 thread: the tree's distance-query accelerator is built lazily

    benchmark::RegisterBenchmark(("inside/cgal/" + m).c_str(), [m](benchmark::State& state) {
      Fixture* f;
      {
        std::lock_guard lock(fixture_mutex);
        f = &fixture(m);
        part(f->cgal, [&] { return std::make_unique<CgalMeshQueries>(f->mesh); });
      }
      std::size_t i = 0;
      std::int64_t sum = 0;
      for (auto _ : state) {
        sum += f->cgal->side(f->points[i]);
        if (++i == f->points.size()) i = 0;
      }
      benchmark::DoNotOptimize(sum);
      set_rate(state, 1);
    });  // Side_of_triangle_mesh is not thread-safe: 1 thread
  }
}

}  // namespace
}  // namespace raykernel::bench

int main(int argc, char** argv) {
  raykernel::bench::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// The benchmark workloads: buffers of ray–plane queries generated before timing, larger than the caches
// (the timed loops rotate through them), each checked once (certified == exact) before it is timed.
#pragma once

#include <raykernel/batch.hpp>
#include <raykernel/camera.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace raykernel::bench {

using testkit::Query;

// 1 Mi queries × 96 bytes = 96 MiB: well beyond the last-level cache. random_l2 has 2^12 queries
// (384 KiB), which stay in the L2 cache.
inline constexpr std::size_t workload_size = std::size_t{1} << 20;
inline constexpr std::size_t l2_workload_size = std::size_t{1} << 12;

enum class Workload { random, random_l2, wide, degenerate, render };

[[nodiscard]] std::string to_string(Workload w);

// The queries of a workload (deterministic: seeded by the workload).
//   random      every component uniform in [-1, 1]
//   random_l2   the first 2^12 queries of random
//   wide        components ±(1 + f)·2^e, e uniform in [-300, 300]
//   degenerate  half near-parallel, half near-coplanar (raykernel::testkit), interleaved: built so that
//               plain binary64 is unsure of the sign of d·n or (p − o)·n
//   render      the demo scene's camera rays (pixel centres, `raykernel render`) against each of its planes
[[nodiscard]] const std::vector<Query>& workload(Workload w);

// A workload in structure-of-arrays layout, for the batch API.
struct SoA {
  std::vector<double> ox, oy, oz, dx, dy, dz, px, py, pz, nx, ny, nz;
  [[nodiscard]] RayBatch rays() const { return {ox, oy, oz, dx, dy, dz}; }
  [[nodiscard]] PlaneBatch planes() const { return {px, py, pz, nx, ny, nz}; }
};
[[nodiscard]] const SoA& workload_soa(Workload w);

// The seed's formula over the arrays (naive_soa.cpp): a loop the compiler vectorizes, cloned for AVX-512,
// AVX2 and generic x86-64 — the baseline a SIMD batch is compared with.
void naive_soa(const SoA& soa, Relation* relation, double* t) noexcept;

// Reads every array of the workload once, split over `threads` threads (the sum of all doubles, so that
// nothing is optimized away): the memory floor for a streaming pass over the same bytes.
[[nodiscard]] double read_all(const SoA& soa, unsigned threads);

// Rays against a set of planes, for nearest/<path>/<name>:
//   demo4, demo64      the demo camera's rays (pixel centres) against 4 or 64 planes (the demo's, repeated
//                      with small offsets when more are asked for)
//   random4, random64  2^12 random rays (components uniform in [-1, 1]) against 4 or 64 random planes
// `prepared` is the PlaneSet of `planes`, built before timing.
struct NearestWorkload {
  std::vector<Ray> rays;
  std::vector<Plane> planes;
  PlaneSet prepared;
};
[[nodiscard]] const NearestWorkload& nearest_workload(const std::string& name);

// The demo scene rendered at one sample per pixel (render/<path>/demo): for each pixel its camera ray, the
// nearest plane (certified over a prepared set, or the naive loop) and its shading, on one thread.
class DemoRender {
 public:
  DemoRender();
  [[nodiscard]] double render_once(bool certified) const;  // the sum of the shaded values
  [[nodiscard]] std::size_t pixels() const noexcept { return std::size_t{camera_.image.width} * camera_.image.height; }

 private:
  Camera camera_;
  std::vector<Plane> planes_;
  PlaneSet prepared_;
};
[[nodiscard]] const DemoRender& demo_render();

// scenes/octahedron.json rendered as `raykernel render` does (render/<path>/octahedron): 400 × 400 pixels, 4
// stratified samples each, for each sample its camera ray, the nearest surface among the floor and the mesh's
// triangles and its shading, on one thread. Certified: the scene's one query (nearest_hit(ray, NearestScene),
// t rounded once for the winner); naive: nearest_hit_naive on the planes and on the mesh (Möller–Trumbore
// through the BVH), the smaller t winning, a plane on equal t — the CLI's two passes (cli/rendering/render.cpp).
class SceneRender {
 public:
  explicit SceneRender(const std::string& path);
  [[nodiscard]] double render_once(bool certified) const;  // the sum of the shaded values
  [[nodiscard]] std::size_t rays() const noexcept;

 private:
  struct Loaded;
  std::shared_ptr<const Loaded> scene_;
};
[[nodiscard]] const SceneRender& octahedron_render();

// Queries whose direction makes the angle 2^-k with the plane (k = 0 .. 100), for the degeneracy sweep.
[[nodiscard]] const std::vector<Query>& angle_sweep(int k);

}  // namespace raykernel::bench

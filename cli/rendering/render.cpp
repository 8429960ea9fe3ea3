// The ray caster behind `raykernel render`: the certified pass (the image, and each pixel's slowest stage),
// the naive pass (the same rays through nearest_hit_naive), and their statistics. Colour is colour.hpp,
// shading shading.hpp, threads parallel_rows.hpp, the diagnostic images and legends diagnostic_images.hpp,
// and the printed summary render_summary.hpp.
#include "rendering/render.hpp"

#include "rendering/colour.hpp"
#include "rendering/diagnostic_images.hpp"
#include "rendering/parallel_rows.hpp"

#include <raykernel/parallel.hpp>
#include "rendering/shading.hpp"

#include <raykernel/camera.hpp>
#include <raykernel/fp_environment.hpp>
#include <raykernel/mesh_queries.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/nearest_scene.hpp>
#include <raykernel/sphere.hpp>

#include <algorithm>
#include <chrono>
#include <vector>

namespace raykernel::cli {
namespace {

using Clock = std::chrono::steady_clock;

// What both passes share: the scene, its planes (as given, for the naive loop) and its surfaces prepared once
// for the certified nearest hit (the planes, and the scene's meshes in one), the shader and the thread count.
struct Pass {
  const Scene& scene;
  const std::vector<Plane>& geometry;
  const NearestScene& surfaces;
  const PreparedMesh* mesh;  // the scene's meshes in one, or null when it has none
  const std::vector<Sphere>& spheres;  // as given, for the naive loop
  const Shader& shader;
  unsigned threads;
  const std::function<void(double)>& progress;

  [[nodiscard]] std::uint32_t width() const noexcept { return scene.image.width; }
  [[nodiscard]] std::uint32_t height() const noexcept { return scene.image.height; }
  [[nodiscard]] std::uint32_t samples() const noexcept { return scene.samples_per_pixel; }
  // The index of sample s of pixel i in image row `row`, over all rays of the image.
  [[nodiscard]] std::size_t ray_index(std::uint32_t row, std::uint32_t i, std::uint32_t s) const noexcept {
    return (std::size_t{row} * width() + i) * samples() + s;
  }
  // Runs `pixel_job(row, i, j, samples)` for every pixel, rows in parallel: row `row` of the image is
  // j = height − 1 − row (j counts from the bottom), `samples` the pixel's sample positions. Each row runs in
  // one DefaultFpEnvironment scope: the library's environment check once per row, not once per call (the
  // render changes no floating-point environment).
  template <class PixelJob>
  unsigned for_each_pixel(PixelJob pixel_job) const {
    return for_each_row(height(), threads, progress, [&](std::uint32_t row) {
      const DefaultFpEnvironment environment;
      const std::uint32_t j = height() - 1 - row;
      for (std::uint32_t i = 0; i < width(); ++i) pixel_job(row, i, j, stratified_samples(samples(), scene.seed, i, j));
    });
  }
};

// A ray's winner as the passes record it: plane k is k, triangle m of the scene's mesh is (number of
// planes) + m, sphere k is (number of planes) + (number of triangles) + k, a miss −1.
std::int64_t triangle_winner(const Pass& pass, std::uint32_t triangle) noexcept {
  return static_cast<std::int64_t>(pass.geometry.size()) + triangle;
}
std::int64_t sphere_winner(const Pass& pass, std::size_t sphere) noexcept {
  return static_cast<std::int64_t>(pass.geometry.size() + pass.scene.mesh.triangles.size() + sphere);
}

// The textbook nearest sphere (Ray Tracing in One Weekend's loop): intersect_naive for each sphere, its smaller
// computed root at or beyond 0 (else the larger), the smallest computed t winning.
struct NaiveSphereHit {
  std::size_t sphere;
  double t;
};
std::optional<NaiveSphereHit> nearest_sphere_naive(const Ray& ray, const std::vector<Sphere>& spheres) noexcept {
  std::optional<NaiveSphereHit> best;
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const SphereIntersection r = intersect_naive(ray, spheres[k]);
    if (r.relation == SphereRelation::miss) continue;
    const double t = r.t1 >= 0 ? r.t1 : r.t2;
    if (!(t >= 0)) continue;
    if (!best || t < best->t) best = NaiveSphereHit{k, t};
  }
  return best;
}

// The certified pass: the image, each pixel's slowest stage, each ray's winner (plane index, or −1 for a
// miss) when `keep_winners`, and the counts of `stats`.
struct CertifiedPass {
  std::vector<std::uint8_t> pixel_stage;
  std::vector<std::int64_t> winners;
};

CertifiedPass certified_pass(const Pass& pass, bool keep_winners, Image& image, RenderStats& stats) {
  const std::uint32_t width = pass.width(), height = pass.height(), spp = pass.samples();
  CertifiedPass out{std::vector<std::uint8_t>(stats.pixels, 0), std::vector<std::int64_t>(keep_winners ? stats.rays : 0)};
  struct RowTally {
    std::uint64_t hits = 0;
    std::array<std::uint64_t, stage_count> rays{}, comparisons{};
  };
  std::vector<RowTally> tally(height);

  const auto start = Clock::now();
  stats.threads_ran = pass.for_each_pixel([&](std::uint32_t row, std::uint32_t i, std::uint32_t j, const std::vector<PixelSample>& samples) {
    Linear sum;
    Stage slowest = Stage::filter;
    RowTally& t = tally[row];
    for (std::uint32_t s = 0; s < spp; ++s) {
      const Ray ray = pass.scene.camera.ray(i, j, samples[s]);
      // The exact nearest of the planes and the mesh's triangles (a plane wins an exact tie), t rounded once.
      const TracedSceneHit traced = nearest_hit_traced(ray, pass.surfaces);
      std::int64_t winner = -1;
      if (traced.hit && traced.hit->kind == SurfaceKind::sphere) {
        sum += pass.shader.shade_sphere(ray, traced.hit->index, traced.hit->t);
        winner = sphere_winner(pass, traced.hit->index);
      } else if (traced.hit && traced.hit->kind == SurfaceKind::triangle) {
        const auto triangle = static_cast<std::uint32_t>(traced.hit->index);
        sum += pass.shader.shade_triangle(ray, triangle, traced.hit->t);
        winner = triangle_winner(pass, triangle);
      } else {
        std::optional<NearestHit> plane;
        if (traced.hit) plane = NearestHit{traced.hit->index, traced.hit->t};
        sum += pass.shader.shade(ray, plane);
        if (plane) winner = static_cast<std::int64_t>(plane->plane);
      }
      const Stage stage = slowest_stage(traced);
      slowest = std::max(slowest, stage);
      ++t.rays[static_cast<std::size_t>(stage)];
      for (std::size_t k = 0; k < stage_count; ++k) t.comparisons[k] += traced.comparisons[k];
      if (winner >= 0) ++t.hits;
      if (keep_winners) out.winners[pass.ray_index(row, i, s)] = winner;
    }
    store(image.pixel(i, row), sum * (1.0 / spp));
    out.pixel_stage[std::size_t{row} * width + i] = static_cast<std::uint8_t>(slowest);
  });
  stats.seconds = std::chrono::duration<double>(Clock::now() - start).count();

  for (const RowTally& t : tally) {
    stats.hit_rays += t.hits;
    for (std::size_t k = 0; k < stage_count; ++k) {
      stats.rays_by_stage[k] += t.rays[k];
      stats.comparisons_by_stage[k] += t.comparisons[k];
    }
  }
  for (std::uint8_t s : out.pixel_stage) ++stats.pixels_by_stage[s];
  return out;
}

// The naive pass: the same rays through the textbook loop in plain doubles, compared with the certified
// winners. Returns, row-major, 1 for each pixel with a ray whose naive answer differs; draws the naive
// render into `naive_image` when given. It shades every pixel either way, so that its time (the report's
// "naive loop") is the certified pass's work with the naive nearest hit in place of the certified one.
std::vector<std::uint8_t> naive_pass(const Pass& pass, const std::vector<std::int64_t>& winners, Image* naive_image,
                                     RenderStats& stats) {
  const std::uint32_t width = pass.width(), height = pass.height(), spp = pass.samples();
  std::vector<std::uint8_t> differs(stats.pixels, 0);
  std::vector<std::uint64_t> rays_differ(height, 0);

  const auto start = Clock::now();
  pass.for_each_pixel([&](std::uint32_t row, std::uint32_t i, std::uint32_t j, const std::vector<PixelSample>& samples) {
    Linear sum;
    for (std::uint32_t s = 0; s < spp; ++s) {
      const Ray ray = pass.scene.camera.ray(i, j, samples[s]);
      const std::optional<NearestHit> naive = nearest_hit_naive(ray, pass.geometry);
      // Möller–Trumbore for the meshes; the smaller computed t wins, a plane on equal t.
      std::optional<MeshHit> naive_mesh;
      if (pass.mesh != nullptr) naive_mesh = nearest_hit_naive(ray, *pass.mesh);
      if (naive_mesh && naive && !(naive_mesh->intersection.t < naive->t)) naive_mesh.reset();
      // The textbook spheres last: a sphere wins only with a strictly smaller computed t.
      std::optional<NaiveSphereHit> naive_sphere;
      if (!pass.spheres.empty()) naive_sphere = nearest_sphere_naive(ray, pass.spheres);
      if (naive_sphere && naive_mesh && !(naive_sphere->t < naive_mesh->intersection.t)) naive_sphere.reset();
      if (naive_sphere && naive && !naive_mesh && !(naive_sphere->t < naive->t)) naive_sphere.reset();
      const std::int64_t picked = naive_sphere ? sphere_winner(pass, naive_sphere->sphere)
                                  : naive_mesh ? triangle_winner(pass, naive_mesh->triangle)
                                  : naive      ? static_cast<std::int64_t>(naive->plane)
                                               : -1;
      if (picked != winners[pass.ray_index(row, i, s)]) {
        differs[std::size_t{row} * width + i] = 1;
        ++rays_differ[row];
      }
      sum += naive_sphere ? pass.shader.shade_sphere(ray, naive_sphere->sphere, naive_sphere->t)
             : naive_mesh ? pass.shader.shade_triangle(ray, naive_mesh->triangle, naive_mesh->intersection.t)
                          : pass.shader.shade(ray, naive);
    }
    if (naive_image) store(naive_image->pixel(i, row), sum * (1.0 / spp));
  });
  stats.naive_compared = true;
  stats.naive_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  for (std::uint64_t r : rays_differ) stats.naive_rays_differ += r;
  for (std::uint8_t d : differs) stats.naive_pixels_differ += d;
  return differs;
}

}  // namespace

RenderResult render_scene(const Scene& scene, const RenderOptions& options) {
  const std::vector<Plane> geometry = scene.geometry();
  const PlaneSet prepared(geometry);  // validated once, coincident planes set aside once
  std::optional<PreparedMesh> mesh;  // validated once, its BVH built once
  if (!scene.mesh.triangles.empty()) mesh.emplace(scene.mesh);
  const std::vector<Sphere> spheres = scene.sphere_geometry();
  const SphereSet prepared_spheres(spheres);  // validated once
  const Shader shader(scene);
  const NearestScene surfaces{&prepared, mesh ? &*mesh : nullptr, TriangleRule::owned, &prepared_spheres};
  const Pass pass{scene,  geometry, surfaces, mesh ? &*mesh : nullptr, spheres, shader, thread_count(options.threads),
                  options.progress};

  RenderResult result;
  RenderStats& stats = result.stats;
  stats.pixels = std::uint64_t{scene.image.width} * scene.image.height;
  stats.rays = stats.pixels * scene.samples_per_pixel;
  stats.threads = pass.threads;
  result.image = Image(scene.image.width, scene.image.height);

  const bool naive = options.compare_naive || options.naive_image;
  const CertifiedPass certified = certified_pass(pass, naive, result.image, stats);
  if (options.stage_image) result.stages = stage_image(result.image, certified.pixel_stage, stats, options.legend);
  if (naive) {
    if (options.naive_image) result.naive = Image(scene.image.width, scene.image.height);
    const std::vector<std::uint8_t> differs =
        naive_pass(pass, certified.winners, options.naive_image ? &result.naive : nullptr, stats);
    if (options.compare_naive)
      result.naive_difference = naive_difference_image(result.image, differs, stats, options.legend);
  }
  return result;
}

}  // namespace raykernel::cli

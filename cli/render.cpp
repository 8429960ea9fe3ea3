// The ray caster behind `raykernel render`.
#include "render.hpp"

#include "legend.hpp"

#include <raykernel/camera.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/transform.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace raykernel::cli {
namespace {

// ---- Colour ----------------------------------------------------------------------------------------------

struct Linear {
  double r = 0, g = 0, b = 0;
  Linear& operator+=(const Linear& o) noexcept {
    r += o.r, g += o.g, b += o.b;
    return *this;
  }
};
Linear operator*(const Linear& c, double k) noexcept { return {c.r * k, c.g * k, c.b * k}; }
Linear operator+(const Linear& a, const Linear& b) noexcept { return {a.r + b.r, a.g + b.g, a.b + b.b}; }

// sRGB transfer function (IEC 61966-2-1): scene colours are display values, shading and averaging happen in
// linear light.
double srgb_to_linear(double c) noexcept { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double c) noexcept {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}
Linear linear(const Rgb& c) noexcept { return {srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b)}; }
std::uint8_t to_byte(double display) noexcept {
  return static_cast<std::uint8_t>(std::lround(std::clamp(display, 0.0, 1.0) * 255));
}
void store(std::uint8_t* px, const Linear& c) noexcept {
  px[0] = to_byte(linear_to_srgb(c.r));
  px[1] = to_byte(linear_to_srgb(c.g));
  px[2] = to_byte(linear_to_srgb(c.b));
}
// A grey version of a pixel, for the background of the diagnostic images: dimmed so markers stand out.
void store_grey(std::uint8_t* px, const std::uint8_t* from) noexcept {
  const double luma = (0.2126 * from[0] + 0.7152 * from[1] + 0.0722 * from[2]) / 255;
  const std::uint8_t g = to_byte(0.18 + 0.5 * luma);
  px[0] = px[1] = px[2] = g;
}

// ---- Scene, prepared for shading -------------------------------------------------------------------------

struct PreparedPlane {
  Vec3 unit_normal;
  Vec3 u, v;  // checker axes in the plane
  Linear color[2];
  double checker_size = 0;  // 0: solid colour
};

double dot(const Vec3& a, const Vec3& b) noexcept { return a.x * b.x + a.y * b.y + a.z * b.z; }

PreparedPlane prepare(const ScenePlane& sp) {
  PreparedPlane p;
  p.unit_normal = normalized(sp.plane.normal);
  p.color[0] = p.color[1] = linear(sp.color);
  if (sp.checker) {
    const Vec3& n = p.unit_normal;
    const Vec3& a = sp.checker->u_axis;
    const double k = dot(a, n);
    p.u = normalized({a.x - k * n.x, a.y - k * n.y, a.z - k * n.z});
    p.v = {n.y * p.u.z - n.z * p.u.y, n.z * p.u.x - n.x * p.u.z, n.x * p.u.y - n.y * p.u.x};
    p.color[0] = linear(sp.checker->colors[0]);
    p.color[1] = linear(sp.checker->colors[1]);
    p.checker_size = sp.checker->size;
  }
  return p;
}

struct Shader {
  const Scene& scene;
  std::vector<PreparedPlane> planes;
  Linear horizon, zenith;

  explicit Shader(const Scene& s) : scene(s), horizon(linear(s.background.horizon)), zenith(linear(s.background.zenith)) {
    for (const ScenePlane& p : s.planes) planes.push_back(prepare(p));
  }

  [[nodiscard]] Linear sky(const Vec3& unit_direction) const noexcept {
    const double elevation = std::clamp(unit_direction.y, 0.0, 1.0);
    const double k = std::sqrt(elevation);
    return horizon * (1 - k) + zenith * k;
  }

  // Colour by plane (or its checker square), darkened at grazing angles, faded into the horizon colour
  // with distance.
  [[nodiscard]] Linear shade(const Ray& ray, const std::optional<NearestHit>& hit) const noexcept {
    const Vec3& d = ray.direction;
    const double length = std::sqrt(dot(d, d));
    const Vec3 unit{d.x / length, d.y / length, d.z / length};
    if (!hit || !std::isfinite(hit->t)) return sky(unit);
    const PreparedPlane& p = planes[hit->plane];
    const double t = hit->t;
    Linear base = p.color[0];
    if (p.checker_size > 0) {
      const Vec3 x{ray.origin.x + t * d.x - scene.planes[hit->plane].plane.point.x,
                   ray.origin.y + t * d.y - scene.planes[hit->plane].plane.point.y,
                   ray.origin.z + t * d.z - scene.planes[hit->plane].plane.point.z};
      const double a = std::floor(dot(x, p.u) / p.checker_size), b = std::floor(dot(x, p.v) / p.checker_size);
      const double parity = std::fabs(std::fmod(a + b, 2.0));
      if (std::isfinite(parity) && parity == 1) base = p.color[1];
    }
    const double facing = std::fabs(dot(unit, p.unit_normal));  // cos of the angle to the normal
    Linear c = base * (0.22 + 0.78 * facing);
    if (scene.fog_distance > 0) {
      const double visible = std::exp2(-(t * length) / scene.fog_distance);
      c = c * visible + horizon * (1 - visible);
    }
    return c;
  }
};

// ---- Parallel rows -----------------------------------------------------------------------------------

// Runs `row_job(row)` for every row on `threads` threads (rows handed out one at a time, so uneven rows
// balance), calling `progress` from this thread about every 100 ms. Rethrows the first exception.
template <class RowJob>
void for_each_row(std::uint32_t rows, unsigned threads, const std::function<void(double)>& progress, RowJob row_job) {
  std::atomic<std::uint32_t> next{0}, done{0};
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished;
  auto worker = [&] {
    for (std::uint32_t row; (row = next.fetch_add(1)) < rows;) {
      try {
        row_job(row);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        next = rows;  // stop handing out rows
      }
      if (done.fetch_add(1) + 1 == rows) {
        const std::lock_guard<std::mutex> lock(mutex);
        finished.notify_all();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned k = 0; k < threads; ++k) pool.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (done.load() < rows && !failure) {
      finished.wait_for(lock, std::chrono::milliseconds(100));
      if (progress) progress(static_cast<double>(done.load()) / rows);
    }
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  if (progress) progress(1.0);
}

using Clock = std::chrono::steady_clock;

std::string with_thousands(std::uint64_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace

RenderResult render_scene(const Scene& scene, const RenderOptions& options) {
  const std::uint32_t width = scene.image.width, height = scene.image.height, spp = scene.samples_per_pixel;
  const std::vector<Plane> geometry = scene.geometry();
  const PlaneSet prepared(geometry);  // validated once, coincident planes set aside once
  const Shader shader(scene);
  const unsigned threads = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());

  RenderResult result;
  RenderStats& stats = result.stats;
  stats.pixels = std::uint64_t{width} * height;
  stats.rays = stats.pixels * spp;
  stats.threads = threads;
  result.image = Image(width, height);
  std::vector<std::uint8_t> pixel_stage(stats.pixels, 0);
  const bool keep_winners = options.compare_naive || options.naive_image;
  // The certified winner of every ray (plane index, or −1 for a miss), for the naive pass.
  std::vector<std::int32_t> winners(keep_winners ? stats.rays : 0);

  struct RowTally {
    std::uint64_t hits = 0;
    std::array<std::uint64_t, stage_count> rays{}, comparisons{};
  };
  std::vector<RowTally> tally(height);

  // Pass 1: the certified render. Row r of the image is j = height − 1 − r (j counts from the bottom).
  const auto start = Clock::now();
  for_each_row(height, threads, options.progress, [&](std::uint32_t row) {
    const std::uint32_t j = height - 1 - row;
    RowTally& t = tally[row];
    for (std::uint32_t i = 0; i < width; ++i) {
      Linear sum;
      Stage slowest = Stage::filter;
      const std::vector<PixelSample> samples = stratified_samples(spp, scene.seed, i, j);
      for (std::uint32_t s = 0; s < spp; ++s) {
        const Ray ray = scene.camera.ray(i, j, samples[s]);
        const TracedNearestHit traced = nearest_hit_traced(ray, prepared);
        sum += shader.shade(ray, traced.hit);
        const Stage stage = slowest_stage(traced);
        slowest = std::max(slowest, stage);
        ++t.rays[static_cast<std::size_t>(stage)];
        for (std::size_t k = 0; k < stage_count; ++k) t.comparisons[k] += traced.comparisons[k];
        if (traced.hit) ++t.hits;
        if (keep_winners)
          winners[(std::size_t{row} * width + i) * spp + s] = traced.hit ? static_cast<std::int32_t>(traced.hit->plane) : -1;
      }
      store(result.image.pixel(i, row), sum * (1.0 / spp));
      pixel_stage[std::size_t{row} * width + i] = static_cast<std::uint8_t>(slowest);
    }
  });
  stats.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  for (const RowTally& t : tally) {
    stats.hit_rays += t.hits;
    for (std::size_t k = 0; k < stage_count; ++k) {
      stats.rays_by_stage[k] += t.rays[k];
      stats.comparisons_by_stage[k] += t.comparisons[k];
    }
  }
  for (std::uint8_t s : pixel_stage) ++stats.pixels_by_stage[s];

  if (options.stage_image) {
    result.stages = Image(width, height);
    for (std::uint32_t row = 0; row < height; ++row)
      for (std::uint32_t i = 0; i < width; ++i) {
        std::uint8_t* px = result.stages.pixel(i, row);
        const std::uint8_t s = pixel_stage[std::size_t{row} * width + i];
        if (s == static_cast<std::uint8_t>(Stage::filter)) {
          store_grey(px, result.image.pixel(i, row));
        } else {
          std::copy(stage_marker_colors[s].begin(), stage_marker_colors[s].end(), px);
        }
      }
    if (options.legend) {
      std::vector<LegendItem> legend = {{std::nullopt, "past the filter:"}};
      const char* names[stage_count] = {"filter", "compensated", "expansion", "exact"};
      for (std::size_t k = 1; k < stage_count; ++k)
        legend.push_back({stage_marker_colors[k], std::string(names[k]) + " " + with_thousands(stats.pixels_by_stage[k])});
      (void)draw_legend(result.stages, legend);
    }
  }

  if (keep_winners) {
    // Pass 2: the same rays through the seed's loop in plain doubles.
    std::vector<std::uint8_t> differs(stats.pixels, 0);
    std::vector<std::uint64_t> rays_differ(height, 0);
    if (options.naive_image) result.naive = Image(width, height);
    const auto naive_start = Clock::now();
    for_each_row(height, threads, options.progress, [&](std::uint32_t row) {
      const std::uint32_t j = height - 1 - row;
      for (std::uint32_t i = 0; i < width; ++i) {
        Linear sum;
        const std::vector<PixelSample> samples = stratified_samples(spp, scene.seed, i, j);
        for (std::uint32_t s = 0; s < spp; ++s) {
          const Ray ray = scene.camera.ray(i, j, samples[s]);
          const std::optional<NearestHit> naive = nearest_hit_naive(ray, geometry);
          const std::int32_t picked = naive ? static_cast<std::int32_t>(naive->plane) : -1;
          if (picked != winners[(std::size_t{row} * width + i) * spp + s]) {
            differs[std::size_t{row} * width + i] = 1;
            ++rays_differ[row];
          }
          if (options.naive_image) sum += shader.shade(ray, naive);
        }
        if (options.naive_image) store(result.naive.pixel(i, row), sum * (1.0 / spp));
      }
    });
    stats.naive_compared = true;
    stats.naive_seconds = std::chrono::duration<double>(Clock::now() - naive_start).count();
    for (std::uint64_t r : rays_differ) stats.naive_rays_differ += r;
    for (std::uint8_t d : differs) stats.naive_pixels_differ += d;
    if (options.compare_naive) {
      result.naive_difference = Image(width, height);
      for (std::uint32_t row = 0; row < height; ++row)
        for (std::uint32_t i = 0; i < width; ++i) {
          std::uint8_t* px = result.naive_difference.pixel(i, row);
          if (differs[std::size_t{row} * width + i]) std::copy(naive_difference_color.begin(), naive_difference_color.end(), px);
          else store_grey(px, result.image.pixel(i, row));
        }
      if (options.legend) {
        char percent[32];
        std::snprintf(percent, sizeof percent, "%.2f%%", 100.0 * static_cast<double>(stats.naive_pixels_differ) /
                                                             static_cast<double>(stats.pixels));
        (void)draw_legend(result.naive_difference,
                          {{naive_difference_color, "plain doubles pick another plane: " +
                                                        with_thousands(stats.naive_pixels_differ) + " pixels (" + percent + ")"}});
      }
    }
  }
  return result;
}

}  // namespace raykernel::cli

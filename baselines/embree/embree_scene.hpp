// raykernel's Embree baseline: a raykernel::Mesh as an Embree 3 scene, in Embree's default mode or its
// robust mode (RTC_SCENE_FLAG_ROBUST), for the benchmarks and the `watertight` comparison.
//
// Embree stores and computes in float. Building the scene converts every vertex coordinate to the nearest
// float, and every query converts the ray; `conversion()` says how many coordinates that changed and by how
// much. Wherever Embree's answers are shown, say that they are answers for the float mesh and the float ray,
// not for the doubles raykernel answers for. Not part of the installed library (an internal target,
// raykernel_embree_baseline, built when RAYKERNEL_WITH_EMBREE is on).
#pragma once

#include <raykernel/mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace raykernel::baseline {

// What converting doubles to floats did.
struct FloatConversion {
  std::size_t coordinates = 0;  // converted
  std::size_t inexact = 0;      // changed by the conversion
  std::size_t underflowed = 0;  // nonzero doubles that became 0 or a subnormal float
  double max_relative_change = 0;  // max |float − double| / |double| over the nonzero coordinates
};

class EmbreeScene {
 public:
  enum class Mode { fast, robust };  // Embree's default, or RTC_SCENE_FLAG_ROBUST
  // RTC_BUILD_QUALITY_HIGH (spatial splits: triangles may be referenced by several leaves), or MEDIUM (Embree's
  // default for static scenes: binned SAH, each triangle in one leaf).
  enum class Quality { high, medium };

  // Builds the scene (one triangle geometry, the mesh's triangles in order: primID = triangle index).
  // Throws std::invalid_argument when validate(mesh) fails or a coordinate is beyond the float range, and
  // std::runtime_error when Embree reports an error. `threads` = 0: Embree's default (all cores).
  // `collect_all_hits`: install an intersection filter so that all_hits() can list every hit Embree's
  // traversal reports (it costs the other queries a callback per candidate hit).
  EmbreeScene(const Mesh& mesh, Mode mode, unsigned threads = 0, bool collect_all_hits = false,
              Quality quality = Quality::high);
  ~EmbreeScene();
  EmbreeScene(EmbreeScene&&) noexcept;
  EmbreeScene& operator=(EmbreeScene&&) noexcept;

  [[nodiscard]] Mode mode() const noexcept;
  [[nodiscard]] const FloatConversion& conversion() const noexcept;
  // The bytes the device holds after the build (its memory monitor's sum: the scene's vertex and index
  // buffers, the BVH and its leaves).
  [[nodiscard]] std::size_t device_bytes() const noexcept;

  // Embree's nearest hit (rtcIntersect1) of the ray converted to float, for t in [0, t_max]: the triangle
  // index and Embree's float t, or nothing. Thread-safe.
  struct Hit {
    std::uint32_t triangle;
    float t;
  };
  [[nodiscard]] std::optional<Hit> intersect(const Ray& ray, float t_max = 1e38f) const;
  // Every hit Embree's rtcIntersect1 traversal reports along the float ray for t in [0, t_max], in the order
  // reported (an intersection filter records each and rejects it, so that the traversal goes on): how Embree
  // would count crossings. Needs a scene built with collect_all_hits (throws std::logic_error otherwise).
  // Thread-safe.
  [[nodiscard]] std::vector<Hit> all_hits(const Ray& ray, float t_max = 1e38f) const;
  // The float mesh Embree intersects, as doubles (each coordinate the float it was rounded to).
  [[nodiscard]] Mesh float_mesh() const;
  // rtcOccluded1: whether Embree finds any hit with t in [0, t_max].
  [[nodiscard]] bool occluded(const Ray& ray, float t_max = 1e38f) const;
  // rtcIntersect8 over up to 8 rays at once: hits[i] for rays[i]. Thread-safe.
  void intersect8(std::span<const Ray> rays, std::span<std::optional<Hit>> hits) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// How converting one ray's origin and direction to float changes them (added to `into`).
void count_float_conversion(const Ray& ray, FloatConversion& into);

// The ray Embree intersects: each component rounded to the nearest float (as doubles).
[[nodiscard]] Ray float_ray(const Ray& ray);

}  // namespace raykernel::baseline

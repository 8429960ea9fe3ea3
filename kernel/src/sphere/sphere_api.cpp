// The public ray–sphere entry points (raykernel/sphere.hpp), as the triangle's: the default floating-point
// environment for the call (core/fp_environment.hpp), validation at the boundary (core/validation.hpp), then the
// certified cascade (ray_sphere_cascade.hpp) or the exact reference (exact_sphere.hpp). The textbook formula
// runs in the caller's environment, as the baseline it is.
#include <raykernel/occlusion.hpp>
#include <raykernel/sphere.hpp>

#include <raykernel/bvh.hpp>

#include "core/eft.hpp"
#include "core/fp_environment.hpp"
#include "core/validation.hpp"
#include "sphere/exact_sphere.hpp"
#include "sphere/ray_sphere_cascade.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace raykernel {
namespace {

void throw_if_invalid(const Ray& ray, const Sphere& sphere) {
  if (detail::is_valid(ray) & detail::is_valid(sphere)) [[likely]]
    return;
  throw invalid_input(*validate(ray, sphere));
}

}  // namespace

TracedSphereIntersection intersect_traced(const Ray& ray, const Sphere& sphere) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid(ray, sphere);
    return detail::sphere_intersection_cascade(ray, sphere);
  });
}

// The answer written in place: the cascade stores origin and relation byte by byte, and a copy of the whole
// struct read them back in one wide load, which store forwarding cannot serve (measured: 18% of the call).
SphereIntersection intersect(const Ray& ray, const Sphere& sphere) {
  SphereIntersection r;
  detail::in_default_fp_environment([&] {
    if (detail::sphere_intersection_filtered(ray, sphere, r)) [[likely]]
      return;
    throw_if_invalid(ray, sphere);
    detail::sphere_intersection_after_filter(ray, sphere, r);
  });
  return r;
}

namespace {
// The relation with the environment installed, the fast path tried first.
[[gnu::noinline]] SphereClassification relation_in_environment(const Ray& ray, const Sphere& sphere) {
  return detail::in_default_fp_environment([&] {
    if (const std::optional<SphereClassification> c = detail::fast_sphere_relation(ray, sphere)) [[likely]]
      return *c;
    throw_if_invalid(ray, sphere);
    return detail::sphere_relation_cascade(ray, sphere).classification;
  });
}
}  // namespace

// Inside a DefaultFpEnvironment scope the fast path answers with nothing on the stack (the rest, out of line, is a
// tail call: measured 20% of the call's time when it shared this frame).
SphereClassification relation(const Ray& ray, const Sphere& sphere) {
  if (detail::default_environment_scopes > 0) [[likely]] {
    const std::uint32_t p = detail::fast_sphere_relation_packed(ray, sphere);
    if ((p & detail::fast_sphere_relation_certain) != 0) [[likely]]
      return detail::unpack_sphere_classification(p);
  }
  return relation_in_environment(ray, sphere);
}

SphereIntersection intersect_exact(const Ray& ray, const Sphere& sphere) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid(ray, sphere);
    return detail::exact::intersect_sphere(ray, sphere);
  });
}

ExactSphereIntersection intersect_exact_rational(const Ray& ray, const Sphere& sphere) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid(ray, sphere);
    return detail::exact::intersect_sphere_rational(ray, sphere);
  });
}

namespace {

// [c − r, c + r] rounded outwards on each axis: RN of the sum, moved one double out when TwoSum says it rounded
// inwards; nothing when a bound overflows.
std::optional<Box3> sphere_box(const Sphere& s) {
  const double c[3] = {s.center.x, s.center.y, s.center.z};
  double lo[3], hi[3];
  for (int i = 0; i < 3; ++i) {
    const detail::DD<double> l = detail::two_sum(c[i], -s.radius), h = detail::two_sum(c[i], s.radius);
    lo[i] = l.lo < 0 ? std::nextafter(l.hi, -std::numeric_limits<double>::infinity()) : l.hi;
    hi[i] = h.lo > 0 ? std::nextafter(h.hi, std::numeric_limits<double>::infinity()) : h.hi;
    if (!std::isfinite(lo[i]) || !std::isfinite(hi[i]) || !std::isfinite(l.lo) || !std::isfinite(h.lo))
      return std::nullopt;
  }
  return Box3{{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
}

}  // namespace

SphereSet::SphereSet(std::span<const Sphere> spheres) : spheres_(spheres.begin(), spheres.end()) {
  for (std::size_t k = 0; k < spheres_.size(); ++k)
    if (!detail::is_valid(spheres_[k])) throw invalid_input("sphere " + std::to_string(k) + ": " + *validate(spheres_[k]));
  if (spheres_.size() < bvh_min_spheres) return;
  detail::in_default_fp_environment([&] {  // the boxes' roundings assume round-to-nearest
    std::vector<Box3> boxes;
    boxes.reserve(spheres_.size());
    for (const Sphere& sphere : spheres_) {
      const std::optional<Box3> box = sphere_box(sphere);
      if (!box) return;  // a sphere beyond the doubles: the set is searched in order
      boxes.push_back(*box);
    }
    bvh_ = std::make_shared<const MeshBvh>(boxes);
  });
}

std::optional<double> nearest_root(const Ray& ray, const RayInterval& interval, const Sphere& sphere) {
  return detail::in_default_fp_environment([&]() -> std::optional<double> {
    throw_if_invalid(ray, sphere);
    detail::throw_if_invalid_interval(interval);
    const TracedSphereIntersection r = detail::sphere_intersection_cascade(ray, sphere);
    const std::optional<detail::SphereRootHit> hit = detail::sphere_hit_in_interval(ray, sphere, r.intersection, interval);
    if (!hit) return std::nullopt;
    return hit->t;
  });
}

bool occluded(const Ray& ray, const RayInterval& interval, const SphereSet& spheres) {
  return detail::in_default_fp_environment([&] {
    if (!detail::is_valid(ray)) [[unlikely]]
      throw invalid_input(*validate(ray));
    detail::throw_if_invalid_interval(interval);
    const auto blocks = [&](const Sphere& sphere) {
      return detail::sphere_hit_in_interval(ray, sphere, detail::sphere_intersection_cascade(ray, sphere).intersection,
                                            interval)
          .has_value();
    };
    const std::span<const Sphere> list = spheres.spheres();
    if (const MeshBvh* bvh = spheres.bvh()) {
      // Every sphere with a root in [t_min, t_max] has its box met there: its leaf is returned (bvh.hpp).
      BvhRayTraversal walk(*bvh, ray, interval.t_min, interval.t_max);
      while (const std::optional<BvhLeaf> leaf = walk.next(interval.t_max))
        for (const std::uint32_t k : leaf->triangles)
          if (blocks(list[k])) return true;
      return false;
    }
    for (const Sphere& sphere : list)
      if (blocks(sphere)) return true;
    return false;
  });
}

namespace {

void throw_if_invalid_segment(const Vec3& p, const Vec3& q) {
  if (const auto reason = validate_segment(p, q)) [[unlikely]]
    throw invalid_input(*reason);
}

}  // namespace

bool segment_meets(const Vec3& p, const Vec3& q, const Sphere& sphere) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid_segment(p, q);
    if (!detail::is_valid(sphere)) [[unlikely]]
      throw invalid_input(*validate(sphere));
    return detail::segment_meets_sphere(p, q, sphere);
  });
}

bool segment_meets_exact(const Vec3& p, const Vec3& q, const Sphere& sphere) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid_segment(p, q);
    if (!detail::is_valid(sphere)) [[unlikely]]
      throw invalid_input(*validate(sphere));
    return detail::exact::segment_meets_sphere(p, q, sphere);
  });
}

bool occluded(const Vec3& p, const Vec3& q, const SphereSet& spheres) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid_segment(p, q);
    const std::span<const Sphere> list = spheres.spheres();
    const auto meets = [&](const Sphere& sphere) { return detail::segment_meets_sphere(p, q, sphere); };
    if (const MeshBvh* bvh = spheres.bvh()) {
      // The segment lies in the box of its ends: a sphere it meets has a point there, so its leaf overlaps it.
      const Box3 box{{std::fmin(p.x, q.x), std::fmin(p.y, q.y), std::fmin(p.z, q.z)},
                     {std::fmax(p.x, q.x), std::fmax(p.y, q.y), std::fmax(p.z, q.z)}};
      return any_leaf_overlapping(*bvh, box, [&](std::span<const std::uint32_t> leaf) {
        return std::any_of(leaf.begin(), leaf.end(), [&](std::uint32_t k) { return meets(list[k]); });
      });
    }
    return std::any_of(list.begin(), list.end(), meets);
  });
}

// The textbook quadratic ("Ray Tracing in One Weekend", with the half b): no guard against cancellation.
SphereIntersection intersect_naive(const Ray& ray, const Sphere& sphere) noexcept {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  const Vec3& c = sphere.center;
  const double fx = o.x - c.x, fy = o.y - c.y, fz = o.z - c.z;
  const double a = d.x * d.x + d.y * d.y + d.z * d.z;
  const double h = d.x * fx + d.y * fy + d.z * fz;
  const double cc = fx * fx + fy * fy + fz * fz - sphere.radius * sphere.radius;
  const double disc = h * h - a * cc;
  const SphereOrigin origin = cc < 0 ? SphereOrigin::inside : cc == 0 ? SphereOrigin::on_surface : SphereOrigin::outside;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (disc < 0) return {origin, SphereRelation::miss, nan, nan};
  if (disc == 0) return {origin, SphereRelation::tangent, -h / a, -h / a};
  const double root = std::sqrt(disc);
  return {origin, SphereRelation::cross, (-h - root) / a, (-h + root) / a};
}

std::string_view to_string(SphereOrigin origin) noexcept {
  switch (origin) {
    case SphereOrigin::inside: return "inside";
    case SphereOrigin::on_surface: return "on-surface";
    case SphereOrigin::outside: return "outside";
  }
  return "?";
}

std::string_view to_string(SphereRelation relation) noexcept {
  switch (relation) {
    case SphereRelation::miss: return "miss";
    case SphereRelation::tangent: return "tangent";
    case SphereRelation::cross: return "cross";
  }
  return "?";
}

}  // namespace raykernel

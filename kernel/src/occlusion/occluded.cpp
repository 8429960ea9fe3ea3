// occluded (docs/contract.md §8): any-hit queries on a mesh — a ray in its interval, and the open segment between
// two points — and their references in rationals.
//
// A ray: the BVH walk of the nearest-hit module (mesh/bvh_walk.hpp) from t_min to t_max, a leaf's certain misses
// set aside four triangles at a time (LeafScreen), each other triangle classified by the nearest-hit
// module's candidate (nearest/triangle_candidate.hpp: the certified cascade, every sign exact)
// and a hit's exact t placed against the bounds by within_interval (nearest/interval_bound.hpp); the first
// triangle that passes answers. A segment: its direction q − p is not rounded, so no ray walk applies; the walk
// descends into every box that overlaps the segment's bounding box (exact comparisons of doubles: a box holds its
// triangles' vertices exactly, so a triangle meeting the segment meets that box), and each triangle of those
// leaves is decided by occlusion/segment_triangle.hpp.
#include <raykernel/occlusion.hpp>

#include "core/fp_environment.hpp"
#include "core/multiversion.hpp"
#include "core/validation.hpp"
#include "mesh/exact_mesh.hpp"
#include "mesh/bvh_walk.hpp"
#include "nearest/interval_bound.hpp"
#include "nearest/triangle_candidate.hpp"
#include "occlusion/exact_occlusion.hpp"
#include "occlusion/segment_triangle.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace raykernel {
namespace {

void throw_if_invalid(const Ray& ray) {
  if (detail::is_valid(ray)) [[likely]]
    return;
  throw invalid_input(*validate(ray));
}

void throw_if_invalid_segment(const Vec3& p, const Vec3& q) {
  if (const auto reason = validate_segment(p, q)) throw invalid_input(*reason);
}

// Whether some triangle passes `rule` at an exact t in `interval` (valid ray and interval, default environment).
RAYKERNEL_MULTIVERSION
bool ray_blocked(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh, TriangleRule rule) noexcept {
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty()) return false;
  const bool whole_ray = interval.t_min == 0 && interval.t_max == std::numeric_limits<double>::infinity();
  detail::BvhWalk walk;
  mesh_detail::start_walk(walk, bvh, ray, interval.t_min, interval.t_max, mesh.leaf_triangles());
  const auto next_leaf = mesh_detail::bvh_walk_functions().next_leaf;
  const std::span<const Triangle> triangles = mesh.leaf_triangles();
  detail::TriangleCandidate c;
  BvhLeaf leaf;
  while (next_leaf(walk, std::numeric_limits<double>::infinity(), leaf)) {
    detail::LeafScreen screen(ray, triangles, leaf.position, leaf.triangles.size());
    for (std::size_t n = 0; n < leaf.triangles.size(); ++n) {
      if (screen.certainly_missed(n)) continue;
      const auto position = static_cast<std::uint32_t>(leaf.position + n);
      c.classify_screened(ray, triangles[position], 0, position, rule, screen, n);  // which triangle does not matter: no index read
      if (c.classification.relation != TriangleRelation::hit) continue;
      if (whole_ray || detail::within_interval(ray, c, interval)) return true;
    }
  }
  return false;
}

// Whether the closed boxes [lo, hi] and `box` overlap, exactly (comparisons of doubles; the empty slots of a node,
// lo = +inf and hi = −inf, overlap nothing).
bool overlaps(const Vec3& lo, const Vec3& hi, const Box3& box) noexcept {
  return box.lo.x <= hi.x && lo.x <= box.hi.x && box.lo.y <= hi.y && lo.y <= box.hi.y && box.lo.z <= hi.z &&
         lo.z <= box.hi.z;
}

// Whether some triangle meets the open segment from p to q under `rule` (valid input, default environment).
bool segment_blocked(const Vec3& p, const Vec3& q, const PreparedMesh& mesh, TriangleRule rule) {
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty()) return false;
  const Vec3 lo{std::min(p.x, q.x), std::min(p.y, q.y), std::min(p.z, q.z)};
  const Vec3 hi{std::max(p.x, q.x), std::max(p.y, q.y), std::max(p.z, q.z)};
  const std::span<const BvhNode> nodes = bvh.nodes();
  const std::span<const Triangle> triangles = mesh.leaf_triangles();
  std::array<std::uint32_t, (BvhNode::width - 1) * MeshBvh::max_depth + 2> stack;
  std::size_t size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const BvhNode& node = nodes[stack[--size]];
    for (int s = 0; s < BvhNode::width && !node.empty_slot(s); ++s) {
      if (!overlaps(lo, hi, node.box(s))) continue;
      const auto slot = static_cast<std::size_t>(s);
      if (!node.is_leaf(s)) {
        stack[size++] = node.first[slot];
        continue;
      }
      for (std::uint32_t n = 0; n < node.count[slot]; ++n) {
        const Triangle& t = triangles[node.first[slot] + n];
        if (!overlaps(lo, hi, Box3{{std::min({t.a.x, t.b.x, t.c.x}), std::min({t.a.y, t.b.y, t.c.y}),
                                    std::min({t.a.z, t.b.z, t.c.z})},
                                   {std::max({t.a.x, t.b.x, t.c.x}), std::max({t.a.y, t.b.y, t.c.y}),
                                    std::max({t.a.z, t.b.z, t.c.z})}}))
          continue;
        if (detail::segment_meets_triangle(p, q, t, rule)) return true;
      }
    }
  }
  return false;
}

// Every hit in the interval (each triangle once: the walk returns each leaf once, a triangle is in one leaf), then
// sorted by the certified comparison of exact t, ties by index; each one's t and coordinates rounded.
MeshHits all_hits_in(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh, TriangleRule rule) {
  MeshHits answer;
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty()) return answer;
  detail::BvhWalk walk;
  mesh_detail::start_walk(walk, bvh, ray, interval.t_min, interval.t_max, mesh.leaf_triangles());
  const auto next_leaf = mesh_detail::bvh_walk_functions().next_leaf;
  const std::span<const Triangle> triangles = mesh.leaf_triangles();
  // Closed-rule hits include the owned ones (an owned crossing's location is not outside): classified under the
  // closed rule when the list asks for it, the owned flag then says which cross.
  std::vector<detail::TriangleCandidate> found;
  BvhLeaf leaf;
  detail::TriangleCandidate c;
  while (next_leaf(walk, std::numeric_limits<double>::infinity(), leaf)) {
    detail::LeafScreen screen(ray, triangles, leaf.position, leaf.triangles.size());
    for (std::size_t n = 0; n < leaf.triangles.size(); ++n) {
      if (screen.certainly_missed(n)) continue;
      const auto position = static_cast<std::uint32_t>(leaf.position + n);
      c.classify_screened(ray, triangles[position], leaf.triangles[n], position, rule, screen, n);
      if (c.classification.relation != TriangleRelation::hit || !detail::within_interval(ray, c, interval)) continue;
      if (c.classification.owned) answer.crossings += c.den_sign == detail::Sign::positive ? 1 : -1;
      found.push_back(c);
    }
  }
  std::vector<std::size_t> order(found.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const int s = detail::compare_candidates(ray, found[a], found[b]).sign;
    return s < 0 || (s == 0 && found[a].index < found[b].index);
  });
  answer.hits.reserve(found.size());
  for (const std::size_t k : order) {
    detail::TriangleCandidate& h = found[k];
    const TriangleClassification& x = h.classification;
    const double t = h.round_t();
    answer.hits.push_back(MeshHit{static_cast<std::uint32_t>(h.index),
                                  {x.relation, x.location, x.owned, t,
                                   detail::triangle_barycentric(ray, *h.triangle, rule)}});
  }
  return answer;
}

}  // namespace

MeshHits all_hits(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  return detail::in_default_fp_environment([&] { return all_hits_in(ray, interval, mesh, rule); });
}

// Every triangle in rationals: the hits of intersect_exact_rational in the interval (rational t against the bounds'
// rationals), sorted by rational t then index; the owned crossings from each triangle's owned flag and the sign
// of its rational den.
MeshHits all_hits_exact(const Ray& ray, const RayInterval& interval, const Mesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  if (const auto problem = validate(mesh)) throw invalid_input("mesh: " + *problem);
  struct Found {
    MeshHit hit;
    Rational t;
  };
  std::vector<Found> found;
  MeshHits answer;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const ExactTriangleIntersection e = intersect_exact_rational(ray, mesh.triangle(k), rule);
    if (e.intersection.relation != TriangleRelation::hit) continue;
    if (!detail::exact::rational_in_interval(*e.t, interval)) continue;
    if (e.intersection.owned) answer.crossings += e.den.numerator.starts_with("-") ? -1 : 1;
    found.push_back({MeshHit{static_cast<std::uint32_t>(k), e.intersection}, *e.t});
  }
  std::stable_sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
    return detail::exact::compare_rationals(a.t, b.t) < 0;  // stable: ties keep the index order
  });
  for (const Found& f : found) answer.hits.push_back(f.hit);
  return answer;
}

bool occluded(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule) {
  return occluded(ray, RayInterval{}, mesh, rule);
}

bool occluded(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  return detail::in_default_fp_environment([&] { return ray_blocked(ray, interval, mesh, rule); });
}

bool occluded(const Vec3& p, const Vec3& q, const PreparedMesh& mesh, TriangleRule rule) {
  throw_if_invalid_segment(p, q);
  return detail::in_default_fp_environment([&] { return segment_blocked(p, q, mesh, rule); });
}

bool segment_meets(const Vec3& p, const Vec3& q, const Triangle& triangle, TriangleRule rule) {
  throw_if_invalid_segment(p, q);
  if (!detail::is_valid(triangle)) throw invalid_input(*validate(Ray{p, {1, 0, 0}}, triangle));
  return detail::in_default_fp_environment([&] { return detail::segment_meets_triangle(p, q, triangle, rule); });
}

bool occluded_exact(const Ray& ray, const RayInterval& interval, const Mesh& mesh, TriangleRule rule) {
  return nearest_hit_exact(ray, interval, mesh, rule).has_value();
}

bool occluded_exact(const Vec3& p, const Vec3& q, const Mesh& mesh, TriangleRule rule) {
  throw_if_invalid_segment(p, q);
  if (const auto problem = validate(mesh)) throw invalid_input("mesh: " + *problem);
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
    if (detail::exact::segment_meets_triangle(p, q, mesh.triangle(k), rule)) return true;
  return false;
}

bool segment_meets_exact(const Vec3& p, const Vec3& q, const Triangle& triangle, TriangleRule rule) {
  throw_if_invalid_segment(p, q);
  if (!detail::is_valid(triangle)) throw invalid_input(*validate(Ray{p, {1, 0, 0}}, triangle));
  return detail::exact::segment_meets_triangle(p, q, triangle, rule);
}

}  // namespace raykernel

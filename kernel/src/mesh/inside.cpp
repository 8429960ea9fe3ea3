// inside(point, mesh) (docs/contract.md §7): on the surface, else the exact winding number by the owned crossings
// of an axis-aligned ray from the point, through the BVH — or, for most points of a closed mesh, the number of the
// point's cell in the point-location grid (inside_grid.hpp), which is the walk's.
//
// For the ray o + t·s·e_k every value that decides a crossing is a planar orientation in the other two axes
// (orient/orient_predicates.hpp), so a crossing costs a few 2×2 determinants, filtered; the owned rule itself is
// docs/contract.md §6's, decided by the same code as every ray–triangle query (detail::classify_triangle of
// ray_triangle_formula.hpp) from these signs.
#include <raykernel/mesh_queries.hpp>

#include "core/fp_requirements.hpp"
#include "mesh/exact_mesh.hpp"
#include "mesh/inside_grid.hpp"
#include "core/fp_environment.hpp"
#include "mesh/bvh_walk.hpp"
#include "orient/orient_predicates.hpp"
#include "triangle/ray_triangle_formula.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace raykernel {
namespace {

using mesh_detail::coordinate;

void throw_if_invalid(const Vec3& p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    throw invalid_input(std::string("point ") + (!std::isfinite(p.x) ? "x" : !std::isfinite(p.y) ? "y" : "z") +
                        " is not finite");
}

// The ray from the point along s·e_k, and the plane of the other two axes (i, j) = (k + 1, k + 2) mod 3.
struct AxisRay {
  Vec3 origin;
  int k, i, j;
  int s;  // +1 or −1
};

AxisRay axis_ray(const Vec3& origin, const Vec3& direction) {
  const int k = direction.x != 0 ? 0 : (direction.y != 0 ? 1 : 2);
  const double c = coordinate(direction, k);
  return {origin, k, (k + 1) % 3, (k + 2) % 3, c > 0 ? 1 : -1};
}

bool outside_box(const Vec3& p, const Box3& b) {
  return p.x < b.lo.x || p.x > b.hi.x || p.y < b.lo.y || p.y > b.hi.y || p.z < b.lo.z || p.z > b.hi.z;
}

// What one triangle contributes: the point is on it, or the owned crossing's sign of den (0 for none).
struct Crossing {
  bool on_surface;
  int sign;
};

Crossing crossing(const AxisRay& r, const Triangle& tri) {
  const Vec3& p = r.origin;
  const double pi = coordinate(p, r.i), pj = coordinate(p, r.j), pk = coordinate(p, r.k);
  auto range = [&](int axis, double& lo, double& hi) {
    const double a = coordinate(tri.a, axis), b = coordinate(tri.b, axis), c = coordinate(tri.c, axis);
    lo = std::min({a, b, c}), hi = std::max({a, b, c});
  };
  double lo_i, hi_i, lo_j, hi_j, lo_k, hi_k;
  range(r.i, lo_i, hi_i);
  range(r.j, lo_j, hi_j);
  // The line meets the closed triangle only where it meets the triangle's bounding box (exact comparisons).
  if (pi < lo_i || pi > hi_i || pj < lo_j || pj > hi_j) return {false, 0};
  range(r.k, lo_k, hi_k);
  if (r.s > 0 ? hi_k < pk : lo_k > pk) return {false, 0};  // the whole triangle behind the origin
  const bool origin_in_box = lo_k <= pk && pk <= hi_k;
  // On the triangle only if coplanar: the filtered orientation rules most triangles out; for a coplanar point
  // (exact expansions decide that zero: a point in the plane of a flat mesh meets it in every triangle whose box
  // holds it) the on-triangle test with filtered planar orientations — exact::point_on_triangle's signs.
  const int snum = origin_in_box ? mesh_detail::orient3d_sign(p, tri.a, tri.b, tri.c) : 0;
  if (origin_in_box && snum == 0 && mesh_detail::coplanar_point_on_triangle(p, tri)) return {true, 0};

  // den = d·N = s·orient2d(b, c, a); π(q, w) = s·orient2d(q, w, o); the tie-break vector d × (w − q) has the
  // components s·(e_k × (w − q)): 0 on axis k, −s(w_j − q_j) on axis i, s(w_i − q_i) on axis j.
  const int sden = r.s * mesh_detail::orient2d_sign(tri.b, tri.c, tri.a, r.i, r.j);
  if (sden == 0) return {false, 0};  // parallel, coplanar or degenerate: never crossed
  const Vec3* edge[3][2] = {{&tri.b, &tri.c}, {&tri.c, &tri.a}, {&tri.a, &tri.b}};
  auto pi_sign = [&](int e) { return r.s * mesh_detail::orient2d_sign(*edge[e][0], *edge[e][1], p, r.i, r.j); };
  auto tie_break_signs = [&](int e) {
    const Vec3 &q = *edge[e][0], &w = *edge[e][1];
    auto cmp = [](double x, double y) { return (x > y) - (x < y); };  // sign(x − y), exactly
    std::array<int, 3> t{};
    t[static_cast<std::size_t>(r.i)] = -r.s * cmp(coordinate(w, r.j), coordinate(q, r.j));
    t[static_cast<std::size_t>(r.j)] = r.s * cmp(coordinate(w, r.i), coordinate(q, r.i));
    return t;
  };
  // t > 0 exactly when the crossing point lies beyond the origin along the ray: certain when the whole triangle
  // does; else the sign of num = det(a − o, b − o, c − o), exactly. (t = 0 cannot happen: the origin would lie on
  // the closed triangle, which was ruled out.)
  auto num_sign = [&] { return origin_in_box ? snum : sden; };
  const TriangleClassification c = detail::classify_triangle(
      TriangleRule::owned, [&] { return sden; }, pi_sign, tie_break_signs, num_sign, [] { return true; });
  return {false, c.relation == TriangleRelation::hit ? sden : 0};
}

// The winding number by the walk, or nothing on the surface; in the default floating-point environment.
std::optional<std::int64_t> walk_winding(const Vec3& point, const PreparedMesh& mesh) {
  const MeshBvh& bvh = mesh.bvh();
  const AxisRay r = axis_ray(point, inside_ray_direction(point, bvh.bounds()));
  Vec3 direction{0, 0, 0};
  (r.k == 0 ? direction.x : r.k == 1 ? direction.y : direction.z) = r.s;
  detail::BvhWalk walk;
  mesh_detail::start_walk(walk, bvh, {point, direction}, 0, std::numeric_limits<double>::infinity(),
                          mesh.leaf_triangles());
  const auto next_leaf = mesh_detail::bvh_walk_functions().next_leaf;
  const std::span<const Triangle> triangles = mesh.leaf_triangles();
  std::int64_t count = 0;
  // A triangle with the previous one's vertices in the same order (copies) contributes the same (a function of
  // the exact inputs): its crossing is reused.
  const Triangle* previous = nullptr;
  Crossing c{false, 0};
  auto same = [](const Vec3& u, const Vec3& v) { return u.x == v.x && u.y == v.y && u.z == v.z; };
  BvhLeaf leaf;
  while (next_leaf(walk, std::numeric_limits<double>::infinity(), leaf)) {
    for (std::size_t n = 0; n < leaf.triangles.size(); ++n) {
      const Triangle& tri = triangles[leaf.position + n];
      if (previous == nullptr || !same(tri.a, previous->a) || !same(tri.b, previous->b) || !same(tri.c, previous->c)) {
        c = crossing(r, tri);
        previous = &tri;
      }
      if (c.on_surface) return std::nullopt;
      count += c.sign;
    }
  }
  return count;
}

}  // namespace

namespace mesh_detail {
struct InsideGridAccess {
  // The mesh's grid, built by the first call (in the default environment, installed by the caller); nothing for
  // a default-constructed PreparedMesh.
  static const InsideGrid* grid(const PreparedMesh& mesh) {
    InsideGridCache* cache = mesh.inside_grid_.get();
    if (cache == nullptr) return nullptr;
    std::call_once(cache->once, [&] {
      // (the grid's cells lie in the mesh's box, so the walk applies to their points directly)
      cache->grid = InsideGrid::build(mesh, [&](const Vec3& p) { return walk_winding(p, mesh); }, {});
    });
    return &cache->grid;
  }
};
}  // namespace mesh_detail

namespace {

// The winding number, or nothing on the surface; in the default floating-point environment. A point of a free
// cell of a closed mesh's grid has its cell's number (inside_grid.hpp; built on the first call that asks for it,
// `use_grid`); every other point is walked.
std::optional<std::int64_t> winding(const Vec3& point, const PreparedMesh& mesh, bool use_grid) {
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty() || outside_box(point, bvh.bounds())) return 0;  // no triangle can be on or around it
  if (use_grid)
    if (const mesh_detail::InsideGrid* grid = mesh_detail::InsideGridAccess::grid(mesh))
      if (const auto w = grid->lookup(point)) return w;
  return walk_winding(point, mesh);
}

PointLocation location_of(const std::optional<std::int64_t>& w) {
  if (!w) return PointLocation::on_surface;
  return *w != 0 ? PointLocation::inside : PointLocation::outside;
}

}  // namespace

std::string_view to_string(PointLocation location) noexcept {
  switch (location) {
    case PointLocation::outside: return "outside";
    case PointLocation::inside: return "inside";
    case PointLocation::on_surface: return "on-surface";
  }
  return "?";
}

Vec3 inside_ray_direction(const Vec3& point, const Box3& bounds) noexcept {
  return detail::in_default_fp_environment([&] {
    const double distance[6] = {bounds.hi.x - point.x, point.x - bounds.lo.x, bounds.hi.y - point.y,
                                point.y - bounds.lo.y, bounds.hi.z - point.z, point.z - bounds.lo.z};
    int best = 0;
    for (int n = 1; n < 6; ++n)
      if (distance[n] < distance[best]) best = n;
    Vec3 d{0, 0, 0};
    const double s = best % 2 == 0 ? 1.0 : -1.0;
    (best / 2 == 0 ? d.x : best / 2 == 1 ? d.y : d.z) = s;
    return d;
  });
}

std::optional<std::int64_t> winding_number(const Vec3& point, const PreparedMesh& mesh) {
  throw_if_invalid(point);
  return detail::in_default_fp_environment([&] { return winding(point, mesh, true); });
}

PointLocation inside(const Vec3& point, const PreparedMesh& mesh) { return location_of(winding_number(point, mesh)); }

PointLocation inside(const Vec3& point, const Mesh& mesh) {
  throw_if_invalid(point);
  const PreparedMesh prepared(mesh);
  // One point: the walk alone (a grid would cost more than it saves).
  return location_of(detail::in_default_fp_environment([&] { return winding(point, prepared, false); }));
}

bool point_on_triangle(const Vec3& point, const Triangle& triangle) {
  throw_if_invalid(point);
  for (const Vec3* v : {&triangle.a, &triangle.b, &triangle.c})
    if (!std::isfinite(v->x) || !std::isfinite(v->y) || !std::isfinite(v->z)) throw invalid_input("triangle vertex is not finite");
  return detail::exact::point_on_triangle(point, triangle);  // exact rationals: no floating-point operation
}

PointLocation inside_exact(const Vec3& point, const Mesh& mesh) {
  throw_if_invalid(point);
  if (const auto problem = validate(mesh)) throw invalid_input("mesh: " + *problem);
  if (mesh.triangles.empty()) return PointLocation::outside;
  Box3 bounds{mesh.triangle(0).a, mesh.triangle(0).a};
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const Triangle t = mesh.triangle(k);
    for (const Vec3* v : {&t.a, &t.b, &t.c}) {
      bounds.lo = {std::min(bounds.lo.x, v->x), std::min(bounds.lo.y, v->y), std::min(bounds.lo.z, v->z)};
      bounds.hi = {std::max(bounds.hi.x, v->x), std::max(bounds.hi.y, v->y), std::max(bounds.hi.z, v->z)};
    }
  }
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
    if (detail::exact::point_on_triangle(point, mesh.triangle(k))) return PointLocation::on_surface;
  if (outside_box(point, bounds)) return PointLocation::outside;
  const Ray ray{point, inside_ray_direction(point, bounds)};
  std::int64_t count = 0;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const ExactTriangleIntersection e = intersect_exact_rational(ray, mesh.triangle(k), TriangleRule::owned);
    if (e.intersection.relation != TriangleRelation::hit) continue;
    count += e.den.numerator.starts_with('-') ? -1 : 1;  // hit: den ≠ 0; lowest terms, the sign on the numerator
  }
  return count != 0 ? PointLocation::inside : PointLocation::outside;
}

}  // namespace raykernel

// CGAL's own mesh queries, as baselines: the AABB tree's first intersection along a ray and closest point, and
// Side_of_triangle_mesh (inside/outside), both with Epick (filtered predicates on doubles; constructions
// rounded). The CGAL structures are built before timing. CGAL stays in cgal_mesh_baselines.cpp.
#pragma once

#include <raykernel/mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

namespace raykernel::bench {

class CgalMeshQueries {
 public:
  // The mesh as a CGAL::Surface_mesh (faces in the mesh's order) with an AABB tree over its faces. Side
  // queries need a closed mesh.
  explicit CgalMeshQueries(const Mesh& mesh);
  ~CgalMeshQueries();
  // AABB_tree::first_intersected_primitive(Ray_3(o, o + d)): the index of the first triangle hit, if any.
  // (Epick's Ray_3 stores o + d rounded.)
  [[nodiscard]] std::optional<std::uint32_t> first_hit(const Ray& ray) const;
  // Side_of_triangle_mesh: 1 inside, 0 on the boundary, -1 outside.
  [[nodiscard]] int side(const Vec3& point) const;
  // AABB_tree::closest_point_and_primitive: the closest point CGAL computes (Epick: constructed in doubles), the
  // triangle it lies on, and the distance √(squared_distance(p, q)) in doubles, as CGAL users compute it.
  struct Closest {
    Vec3 point;
    std::uint32_t triangle;
    double distance;
  };
  [[nodiscard]] Closest closest(const Vec3& point) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raykernel::bench

// CgalMeshQueries: CGAL's AABB tree and Side_of_triangle_mesh over a raykernel::Mesh (Epick).
#include "cgal_mesh_baselines.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace raykernel::bench {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
using Side = CGAL::Side_of_triangle_mesh<SurfaceMesh, K>;
}  // namespace

struct CgalMeshQueries::Impl {
  SurfaceMesh mesh;
  std::unique_ptr<Tree> tree;
  std::unique_ptr<Side> side;
};

CgalMeshQueries::CgalMeshQueries(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) v.push_back(impl_->mesh.add_vertex(K::Point_3(p.x, p.y, p.z)));
  for (const auto& t : mesh.triangles) {
    const auto f = impl_->mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
    if (f == SurfaceMesh::null_face()) throw std::invalid_argument("CgalMeshQueries: the mesh is not a manifold Surface_mesh");
  }
  impl_->tree = std::make_unique<Tree>(faces(impl_->mesh).first, faces(impl_->mesh).second, impl_->mesh);
  impl_->tree->build();
  impl_->tree->accelerate_distance_queries();  // before timing, as a user would
  impl_->side = std::make_unique<Side>(impl_->mesh);
  (void)(*impl_->side)(K::Point_3(0, 0, 0));  // builds Side_of_triangle_mesh's own tree before timing
}

CgalMeshQueries::~CgalMeshQueries() = default;

std::optional<std::uint32_t> CgalMeshQueries::first_hit(const Ray& r) const {
  const K::Point_3 o(r.origin.x, r.origin.y, r.origin.z);
  const K::Ray_3 ray(o, K::Vector_3(r.direction.x, r.direction.y, r.direction.z));
  const auto hit = impl_->tree->first_intersected_primitive(ray);
  if (!hit) return std::nullopt;
  return static_cast<std::uint32_t>(static_cast<std::size_t>(*hit));
}

CgalMeshQueries::Closest CgalMeshQueries::closest(const Vec3& p) const {
  const K::Point_3 query(p.x, p.y, p.z);
  const auto [q, face] = impl_->tree->closest_point_and_primitive(query);
  return {{q.x(), q.y(), q.z()}, static_cast<std::uint32_t>(static_cast<std::size_t>(face)),
          std::sqrt(CGAL::to_double(CGAL::squared_distance(query, q)))};
}

int CgalMeshQueries::side(const Vec3& p) const {
  switch ((*impl_->side)(K::Point_3(p.x, p.y, p.z))) {
    case CGAL::ON_BOUNDED_SIDE: return 1;
    case CGAL::ON_BOUNDARY: return 0;
    default: return -1;
  }
}

}  // namespace raykernel::bench

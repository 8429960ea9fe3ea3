// PreparedMesh (raykernel/mesh_queries.hpp): a mesh validated once, its BVH, its triangles in leaf order, and
// the place of inside's point-location grid (built by the first inside call, inside.cpp).
#include <raykernel/mesh_queries.hpp>

#include "mesh/inside_grid.hpp"

#include <utility>

namespace raykernel {

PreparedMesh::PreparedMesh(Mesh mesh, const BvhBuildOptions& options)
    : mesh_(std::move(mesh)), bvh_(mesh_, options), inside_grid_(std::make_shared<mesh_detail::InsideGridCache>()) {  // MeshBvh validates (invalid_input "mesh: ...")
  leaf_triangles_.reserve(bvh_.triangle_order().size());
  for (const std::uint32_t k : bvh_.triangle_order()) leaf_triangles_.push_back(mesh_.triangle(k));
}

}  // namespace raykernel

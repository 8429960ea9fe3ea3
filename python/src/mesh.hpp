// raykernel.Mesh: a triangle mesh (docs/contract.md §7) read from Python or from a file, validated once, with its
// BVH built once, and the mesh's nearest hit through that BVH.
//
// The kernel on main has meshes, their readers and the BVH, but not yet a mesh nearest-hit entry point (issue
// 15); nearest_hit here is the §7 answer built from the kernel's pieces — the BVH walk, the certified
// ray–triangle `intersect`, and exact rationals to order two hits whose rounded t are equal. When the kernel
// gains nearest_hit(Ray, PreparedMesh), nearest_hit() below calls it and nothing in the Python API changes.
// inside(point, mesh) is on branch mesh2 (PreparedMesh, mesh_queries.hpp), not on main: see the marked place
// in bind_mesh.cpp.
#pragma once

#include "convert.hpp"

#include <raykernel/bvh.hpp>
#include <raykernel/mesh.hpp>
#include <raykernel/triangle.hpp>

#include <cstddef>
#include <optional>
#include <string>

namespace raykernel::python {

class PythonMesh {
 public:
  // Throws InvalidInput naming the first bad vertex or triangle (validate(const Mesh&)).
  explicit PythonMesh(Mesh mesh);

  [[nodiscard]] const Mesh& mesh() const noexcept { return mesh_; }
  [[nodiscard]] const MeshBvh& bvh() const noexcept { return bvh_; }

 private:
  Mesh mesh_;
  MeshBvh bvh_;
};

// The nearest hit of docs/contract.md §7: among the triangles the ray hits under `rule` (t ≥ 0), the one with
// the smallest exact t, ties to the smallest index; its intersection (t and barycentric coordinates rounded
// as in §6).
struct MeshHit {
  std::size_t triangle;
  TriangleIntersection intersection;
};

// Through the BVH, certified. The ray must be valid (throws InvalidInput otherwise). Thread-safe.
[[nodiscard]] std::optional<MeshHit> nearest_hit(const Ray& ray, const PythonMesh& mesh, TriangleRule rule);
// The reference: every triangle by intersect_exact, the order of t exactly. Slow and obviously right.
[[nodiscard]] std::optional<MeshHit> nearest_hit_exact(const Ray& ray, const Mesh& mesh, TriangleRule rule);

// The Python forms (bind_mesh.cpp), called by nearest_hit / nearest_hit_exact / nearest_hit_batch when their
// scene is a Mesh: a MeshHit NamedTuple or None; MeshHitArrays. `rule` is None (owned) or a rule.
[[nodiscard]] py::object nearest_hit_mesh(py::handle ray, const PythonMesh& mesh, py::handle rule, bool exact);
[[nodiscard]] py::object nearest_hit_mesh_batch(py::handle origins, py::handle directions, const PythonMesh& mesh,
                                                py::handle rule, const std::string& path, const std::string& errors,
                                                std::optional<unsigned> threads);

}  // namespace raykernel::python

// raykernel.Mesh: a triangle mesh (docs/contract.md §7) read from Python or from a file, prepared once (validated,
// its BVH built: the kernel's PreparedMesh), and the Python forms of the kernel's mesh queries
// (<raykernel/mesh_queries.hpp>): nearest_hit / nearest_hit_exact / nearest_hit_naive and inside / inside_exact.
// Every answer is the kernel's; this file and bind_mesh.cpp only convert values and spread arrays over threads.
#pragma once

#include "convert.hpp"

#include <raykernel/mesh.hpp>
#include <raykernel/mesh_queries.hpp>

#include <optional>
#include <string>

namespace raykernel::python {

class PythonMesh {
 public:
  // Throws invalid_input (ValueError) naming the first bad vertex or triangle (validate(const Mesh&)).
  explicit PythonMesh(Mesh mesh) : prepared_(std::move(mesh)) {}

  [[nodiscard]] const PreparedMesh& prepared() const noexcept { return prepared_; }
  [[nodiscard]] const Mesh& mesh() const noexcept { return prepared_.mesh(); }

 private:
  PreparedMesh prepared_;
};

// A mesh hit as the MeshHit NamedTuple, or None (bind_mesh.cpp).
[[nodiscard]] py::object to_python(const std::optional<MeshHit>& hit);

// Which kernel query answers a mesh nearest hit from Python.
enum class MeshPath { certified, exact, naive };

// The Python forms (bind_mesh.cpp), called by nearest_hit / nearest_hit_exact / nearest_hit_naive /
// nearest_hit_batch when their scene is a Mesh: a MeshHit NamedTuple or None; MeshHitArrays. `rule` is None
// (owned) or a rule; the naive path has none (Möller–Trumbore decides its own edges).
[[nodiscard]] py::object nearest_hit_mesh(py::handle ray, const PythonMesh& mesh, py::handle rule, MeshPath path);
[[nodiscard]] py::object nearest_hit_mesh_batch(py::handle origins, py::handle directions, const PythonMesh& mesh,
                                                py::handle rule, const std::string& path, const std::string& errors,
                                                std::optional<unsigned> threads);

}  // namespace raykernel::python

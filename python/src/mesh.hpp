// raykernel.Mesh: a triangle mesh (docs/contract.md §7) read from Python or from a file, prepared once (validated,
// its BVH built: the kernel's PreparedMesh), and the Python forms of the kernel's mesh queries
// (<raykernel/mesh_queries.hpp>): nearest_hit / nearest_hit_exact / nearest_hit_naive and inside / inside_exact.
// Every answer is the kernel's; this file and bind_mesh.cpp only convert values and spread arrays over threads.
#pragma once

#include "batch_support.hpp"
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

// The Mesh a scene argument holds; TypeError otherwise ("scene: expected <wanted>, got list").
[[nodiscard]] const PythonMesh& mesh_from(py::handle scene, const char* wanted);

// A mesh hit as the MeshHit NamedTuple, or None (bind_mesh.cpp).
[[nodiscard]] py::object to_python(const std::optional<MeshHit>& hit);

// The Python forms (bind_mesh.cpp), called by nearest_hit / nearest_hit_exact / nearest_hit_naive /
// nearest_hit_batch when their scene is a Mesh, on `path` (certified, exact or naive) within [t_min, t_max] (per
// ray in the batch: one number or one per ray): a MeshHit NamedTuple or None; MeshHitArrays. `rule` is None
// (owned) or a rule; the naive path has none (Möller–Trumbore decides its own edges).
[[nodiscard]] py::object nearest_hit_mesh(py::handle ray, const PythonMesh& mesh, double t_min, double t_max,
                                          py::handle rule, Path path);
[[nodiscard]] py::object nearest_hit_mesh_batch(py::handle origins, py::handle directions, const PythonMesh& mesh,
                                                py::handle t_min, py::handle t_max, py::handle rule,
                                                const std::string& path, const std::string& errors,
                                                std::optional<unsigned> threads);

}  // namespace raykernel::python

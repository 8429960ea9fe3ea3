// raykernel/mesh.hpp: a triangle mesh as the file states it (docs/contract.md §7).
//
// Vertices are doubles, taken exactly as given; triangles are triples of vertex indices counted from 0.
// Nothing is welded, moved or dropped: two triangles share a vertex exactly when they hold the same index,
// or, for the owned rule's watertightness (§6), when their vertices are the same doubles.
#pragma once

#include <raykernel/raykernel.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace raykernel {

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into `vertices`

  // Triangle k with its vertices in the stored order. Requires k < triangles.size() and valid indices.
  [[nodiscard]] Triangle triangle(std::size_t k) const noexcept {
    const std::array<std::uint32_t, 3>& t = triangles[k];
    return {vertices[t[0]], vertices[t[1]], vertices[t[2]]};
  }
};

// Why `mesh` is not valid input for the mesh queries (docs/contract.md §7), or nothing when it is: the first
// vertex with a coordinate that is NaN or infinite ("vertex 7: y is not finite"), or the first triangle with
// a vertex index out of range ("triangle 3: vertex index 12 is out of range (10 vertices)"). Degenerate
// triangles are valid. Every mesh the readers of <raykernel/io/mesh_file.hpp> return is valid.
[[nodiscard]] std::optional<std::string> validate(const Mesh& mesh);

}  // namespace raykernel

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

}  // namespace raykernel

// A small picture of a mesh for the mesh commands' diagnostic images (`watertight --png`, `spawn-audit --png`):
// an orthographic view along (−1, −0.8, −0.6) framing the mesh's box, Lambert shading of the nearest owned hit,
// and round marks at points of the mesh.
#pragma once

#include "rendering/png_image.hpp"

#include <raykernel/mesh_queries.hpp>

#include <array>
#include <cstdint>

namespace raykernel::cli {

struct MeshView {
  Vec3 centre, right, up, forward;
  double scale;
  std::uint32_t size;
  // The pixel coordinates (x, y) of a point.
  [[nodiscard]] std::array<double, 2> project(const Vec3& p) const;
};

// The view of the mesh's bounding box, `size` pixels square.
[[nodiscard]] MeshView view_of(const PreparedMesh& mesh, std::uint32_t size);
[[nodiscard]] Image render_mesh(const PreparedMesh& mesh, const MeshView& view);
// A filled disc of `radius` pixels at `at` (clipped to the image).
void mark(Image& image, const std::array<double, 2>& at, const std::array<std::uint8_t, 3>& colour, int radius);

}  // namespace raykernel::cli

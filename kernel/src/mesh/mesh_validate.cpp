// validate(const Mesh&) of <raykernel/mesh.hpp>.
#include <raykernel/mesh.hpp>

#include <cmath>

namespace raykernel {

std::optional<std::string> validate(const Mesh& mesh) {
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    const char* axis = !std::isfinite(v.x) ? "x" : !std::isfinite(v.y) ? "y" : !std::isfinite(v.z) ? "z" : nullptr;
    if (axis != nullptr) return "vertex " + std::to_string(i) + ": " + axis + " is not finite";
  }
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
    for (const std::uint32_t index : mesh.triangles[k])
      if (index >= mesh.vertices.size())
        return "triangle " + std::to_string(k) + ": vertex index " + std::to_string(index) + " is out of range (" +
               std::to_string(mesh.vertices.size()) + " vertices)";
  return std::nullopt;
}

}  // namespace raykernel

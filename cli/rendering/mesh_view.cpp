#include "rendering/mesh_view.hpp"

#include <algorithm>
#include <cmath>

namespace raykernel::cli {
namespace {

Vec3 normalized(Vec3 v) {
  const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / n, v.y / n, v.z / n};
}
Vec3 cross(const Vec3& a, const Vec3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

}  // namespace

std::array<double, 2> MeshView::project(const Vec3& p) const {
  const Vec3 q{p.x - centre.x, p.y - centre.y, p.z - centre.z};
  return {(q.x * right.x + q.y * right.y + q.z * right.z) / scale * size / 2 + size / 2.0,
          size / 2.0 - (q.x * up.x + q.y * up.y + q.z * up.z) / scale * size / 2};
}

MeshView view_of(const PreparedMesh& mesh, std::uint32_t size) {
  const Box3& b = mesh.bvh().bounds();
  MeshView v;
  v.centre = {(b.lo.x + b.hi.x) / 2, (b.lo.y + b.hi.y) / 2, (b.lo.z + b.hi.z) / 2};
  v.forward = normalized({-1, -0.8, -0.6});
  v.right = normalized(cross(v.forward, {0, 0, 1}));
  v.up = cross(v.right, v.forward);
  v.scale = 0.9 * std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z});
  v.size = size;
  return v;
}

Image render_mesh(const PreparedMesh& mesh, const MeshView& v) {
  Image image(v.size, v.size);
  const Vec3 light = normalized({0.3, 0.5, 1});
  for (std::uint32_t row = 0; row < v.size; ++row)
    for (std::uint32_t x = 0; x < v.size; ++x) {
      const double u = ((x + 0.5) - v.size / 2.0) / (v.size / 2.0) * v.scale,
                   w = (v.size / 2.0 - (row + 0.5)) / (v.size / 2.0) * v.scale;
      const Vec3 o{v.centre.x + u * v.right.x + w * v.up.x - 4 * v.scale * v.forward.x,
                   v.centre.y + u * v.right.y + w * v.up.y - 4 * v.scale * v.forward.y,
                   v.centre.z + u * v.right.z + w * v.up.z - 4 * v.scale * v.forward.z};
      std::uint8_t* p = image.pixel(x, row);
      p[0] = p[1] = p[2] = 255;
      if (const auto hit = nearest_hit({o, v.forward}, mesh)) {
        const Triangle t = mesh.mesh().triangle(hit->triangle);
        const Vec3 n = normalized(cross({t.b.x - t.a.x, t.b.y - t.a.y, t.b.z - t.a.z}, {t.c.x - t.a.x, t.c.y - t.a.y, t.c.z - t.a.z}));
        const double shade = 0.25 + 0.6 * std::fabs(n.x * light.x + n.y * light.y + n.z * light.z);
        p[0] = p[1] = p[2] = static_cast<std::uint8_t>(255 * shade);
      }
    }
  return image;
}

void mark(Image& image, const std::array<double, 2>& at, const std::array<std::uint8_t, 3>& colour, int radius) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      if (dx * dx + dy * dy > radius * radius) continue;
      const double x = at[0] + dx, y = at[1] + dy;
      if (!(x >= 0 && y >= 0 && x < image.width && y < image.height)) continue;
      std::uint8_t* p = image.pixel(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
      p[0] = colour[0], p[1] = colour[1], p[2] = colour[2];
    }
}

}  // namespace raykernel::cli

// The closed test meshes of <raykernel/testkit/meshes.hpp>.
#include <raykernel/testkit/meshes.hpp>

#include <raykernel/bvh.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace raykernel::testkit {
namespace {

using Index = std::uint32_t;

Index add_vertex(Mesh& mesh, const Vec3& v) {
  mesh.vertices.push_back(v);
  return static_cast<Index>(mesh.vertices.size() - 1);
}

double round_to_grid(double x, int bits) { return std::ldexp(std::nearbyint(std::ldexp(x, bits)), -bits); }

Vec3 normalized_on_grid(double x, double y, double z, int bits) {
  const double r = std::sqrt(x * x + y * y + z * z);
  return {round_to_grid(x / r, bits), round_to_grid(y / r, bits), round_to_grid(z / r, bits)};
}

// a + b exactly, or nothing.
std::optional<double> exact_sum(double a, double b) {
  const double s = a + b;
  const double bv = s - a, av = s - bv;
  if ((a - av) + (b - bv) != 0) return std::nullopt;
  return s;
}

}  // namespace

Mesh make_octahedron(double radius) {
  Mesh mesh;
  // 0: +x, 1: −x, 2: +y, 3: −y, 4: +z, 5: −z
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {radius, -radius}) {
      Vec3 v{0, 0, 0};
      (axis == 0 ? v.x : axis == 1 ? v.y : v.z) = s;
      add_vertex(mesh, v);
    }
  // The face of octant (sx, sy, sz) is (X, Y, Z) with outward normal (sx, sy, sz)·(1,1,1) when
  // sx·sy·sz > 0; an odd number of negative signs reverses the orientation, so two vertices swap.
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy)
      for (int sz = 0; sz < 2; ++sz) {
        const Index x = static_cast<Index>(sx), y = static_cast<Index>(2 + sy), z = static_cast<Index>(4 + sz);
        if ((sx + sy + sz) % 2 == 0) mesh.triangles.push_back({x, y, z});
        else mesh.triangles.push_back({x, z, y});
      }
  return mesh;
}

Mesh make_subdivided_cube(int n, double half_size) {
  if (n < 1) throw std::invalid_argument("make_subdivided_cube: n must be at least 1");
  Mesh mesh;
  std::map<std::array<int, 3>, Index> index;  // lattice point (i, j, k) ∈ [0, n]^3 on the surface
  const double step = 2 * half_size / n;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, inserted] = index.try_emplace(p, 0);
    if (inserted) it->second = add_vertex(mesh, {-half_size + p[0] * step, -half_size + p[1] * step, -half_size + p[2] * step});
    return it->second;
  };
  // Face with outward normal sign·e_axis; (u, v) chosen so that e_u × e_v = e_axis.
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int sign : {1, -1}) {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto corner = [&](int di, int dj) {
            std::array<int, 3> p{};
            p[axis] = sign > 0 ? n : 0;
            p[u] = i + di;
            p[v] = j + dj;
            return vertex(p);
          };
          const Index p00 = corner(0, 0), p10 = corner(1, 0), p11 = corner(1, 1), p01 = corner(0, 1);
          if (sign > 0) {
            mesh.triangles.push_back({p00, p10, p11});
            mesh.triangles.push_back({p00, p11, p01});
          } else {
            mesh.triangles.push_back({p00, p11, p10});
            mesh.triangles.push_back({p00, p01, p11});
          }
        }
    }
  }
  return mesh;
}

Mesh make_icosphere(int level, int grid_bits) {
  if (level < 0 || level > 10) throw std::invalid_argument("make_icosphere: level must be in [0, 10]");
  if (grid_bits < 8 || grid_bits > 40) throw std::invalid_argument("make_icosphere: grid_bits must be in [8, 40]");
  const double phi = (1 + std::sqrt(5.0)) / 2;
  // Directions before projection, kept exact for the midpoints (the rounded vertices are stored).
  std::vector<std::array<double, 3>> direction = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                                  {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                                  {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  std::vector<std::array<Index, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& d : direction) {  // onto the unit sphere (unrounded) so midpoints are taken between sphere points
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double& c : d) c /= r;
  }
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<Index, Index>, Index> midpoint;
    auto middle = [&](Index a, Index b) {
      const std::pair<Index, Index> key = a < b ? std::pair{a, b} : std::pair{b, a};
      auto [it, inserted] = midpoint.try_emplace(key, 0);
      if (inserted) {
        std::array<double, 3> m;
        for (int i = 0; i < 3; ++i) m[i] = direction[a][i] + direction[b][i];
        const double r = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
        for (double& c : m) c /= r;
        direction.push_back(m);
        it->second = static_cast<Index>(direction.size() - 1);
      }
      return it->second;
    };
    std::vector<std::array<Index, 3>> next;
    next.reserve(faces.size() * 4);
    for (const auto& f : faces) {
      const Index ab = middle(f[0], f[1]), bc = middle(f[1], f[2]), ca = middle(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    faces = std::move(next);
  }
  Mesh mesh;
  mesh.vertices.reserve(direction.size());
  for (const auto& d : direction) mesh.vertices.push_back(normalized_on_grid(d[0], d[1], d[2], grid_bits));
  mesh.triangles = std::move(faces);
  return mesh;
}

Mesh make_terrain(int n, std::uint64_t seed) {
  if (n < 1) throw std::invalid_argument("make_terrain: n must be at least 1");
  Mesh mesh;
  const double phase = static_cast<double>(seed % 1000) / 1000 * 6.283185307179586;
  auto height = [&](int i, int j) {
    const double x = static_cast<double>(i) / n, y = static_cast<double>(j) / n;
    const double h = 0.75 + 0.15 * std::sin(6.1 * x + phase) * std::cos(4.3 * y - phase) + 0.08 * std::sin(17.0 * x * y + 2 * phase);
    return round_to_grid(h, 20);
  };
  const std::size_t side = static_cast<std::size_t>(n) + 1;
  auto top = [&](int i, int j) { return static_cast<Index>(static_cast<std::size_t>(i) * side + static_cast<std::size_t>(j)); };
  auto bottom = [&](int i, int j) { return static_cast<Index>(side * side + static_cast<std::size_t>(i) * side + static_cast<std::size_t>(j)); };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) add_vertex(mesh, {static_cast<double>(i) / n, static_cast<double>(j) / n, height(i, j)});
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) add_vertex(mesh, {static_cast<double>(i) / n, static_cast<double>(j) / n, 0.0});
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      // Top, normal +z: (x, y) counter-clockwise seen from above. Bottom, normal −z: reversed.
      mesh.triangles.push_back({top(i, j), top(i + 1, j), top(i + 1, j + 1)});
      mesh.triangles.push_back({top(i, j), top(i + 1, j + 1), top(i, j + 1)});
      mesh.triangles.push_back({bottom(i, j), bottom(i + 1, j + 1), bottom(i + 1, j)});
      mesh.triangles.push_back({bottom(i, j), bottom(i, j + 1), bottom(i + 1, j + 1)});
    }
  // Walls: each boundary step (p → q) of the top, walked counter-clockwise seen from above, with the
  // bottom below it; outward normal to the right of the walk.
  auto wall = [&](Index top_p, Index top_q, Index bottom_p, Index bottom_q) {
    mesh.triangles.push_back({bottom_p, bottom_q, top_q});
    mesh.triangles.push_back({bottom_p, top_q, top_p});
  };
  for (int k = 0; k < n; ++k) {
    wall(top(k, 0), top(k + 1, 0), bottom(k, 0), bottom(k + 1, 0));          // y = 0, walking +x
    wall(top(n, k), top(n, k + 1), bottom(n, k), bottom(n, k + 1));          // x = 1, walking +y
    wall(top(k + 1, n), top(k, n), bottom(k + 1, n), bottom(k, n));          // y = 1, walking −x
    wall(top(0, k + 1), top(0, k), bottom(0, k + 1), bottom(0, k));          // x = 0, walking −y
  }
  return mesh;
}

std::optional<Vec3> edge_point(const Vec3& a, const Vec3& b, std::int64_t k, int bits) {
  auto component = [&](double p, double q) -> std::optional<double> {
    const std::optional<double> diff = exact_sum(q, -p);
    if (!diff) return std::nullopt;
    const double kd = static_cast<double>(k);
    if (static_cast<std::int64_t>(kd) != k) return std::nullopt;
    const double scaled = kd * *diff;
    if (std::fma(kd, *diff, -scaled) != 0 || !std::isfinite(scaled)) return std::nullopt;
    const double w = std::ldexp(scaled, -bits);
    if (std::ldexp(w, bits) != scaled) return std::nullopt;  // underflow lost bits
    return exact_sum(p, w);
  };
  const auto x = component(a.x, b.x), y = component(a.y, b.y), z = component(a.z, b.z);
  if (!x || !y || !z) return std::nullopt;
  return Vec3{*x, *y, *z};
}

Mesh make_overlapping_fan(std::uint32_t n, bool tilted) {
  Mesh m;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double x = i, y = i == 0 ? 0 : (i % 2 == 1 ? 1 : -1);
    m.vertices.push_back({x, y, tilted ? x + 2 * y : 0});
  }
  for (std::uint32_t i = 1; i + 1 < n; ++i) m.triangles.push_back({0, i, i + 1});
  return m;
}

std::vector<Ray> benchmark_rays(const Mesh& mesh, std::size_t count, std::vector<Vec3>* points) {
  Box3 box{mesh.vertices.at(0), mesh.vertices.at(0)};
  for (const Vec3& v : mesh.vertices) {
    box.lo = {std::min(box.lo.x, v.x), std::min(box.lo.y, v.y), std::min(box.lo.z, v.z)};
    box.hi = {std::max(box.hi.x, v.x), std::max(box.hi.y, v.y), std::max(box.hi.z, v.z)};
  }
  const Vec3 c{(box.lo.x + box.hi.x) / 2, (box.lo.y + box.hi.y) / 2, (box.lo.z + box.hi.z) / 2};
  const Vec3 e{box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z};
  const double radius = std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z);
  std::mt19937_64 rng(15);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  std::vector<Ray> rays;
  rays.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    Vec3 u{normal(rng), normal(rng), normal(rng)};
    const double n = std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
    const Vec3 o{c.x + radius * u.x / n, c.y + radius * u.y / n, c.z + radius * u.z / n};
    const Vec3 target{c.x + e.x * unit(rng), c.y + e.y * unit(rng), c.z + e.z * unit(rng)};
    rays.push_back({o, {target.x - o.x, target.y - o.y, target.z - o.z}});
    const Vec3 point{c.x + e.x * unit(rng), c.y + e.y * unit(rng), c.z + e.z * unit(rng)};
    if (points != nullptr) points->push_back(point);
  }
  return rays;
}

}  // namespace raykernel::testkit

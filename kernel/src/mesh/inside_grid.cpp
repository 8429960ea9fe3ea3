// InsideGrid (inside_grid.hpp): the closedness test, the grid's exact cell bounds, the free cells, their
// components and each component's winding number.
#include "mesh/inside_grid.hpp"

#include "orient/orient_predicates.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace raykernel::mesh_detail {
namespace {

// At most `max_cells` cells, `max_per_axis` along an axis.
constexpr double max_cells = 1 << 22;
constexpr double max_per_axis = 1024;

}  // namespace

bool InsideGrid::closed(const Mesh& mesh) {
  // Each vertex's position as a number, equal for equal (x, y, z) (== on doubles, so −0 and +0 are one position,
  // as they are one point): an open-addressing table of the first vertex at each position.
  const std::size_t v = mesh.vertices.size();
  std::size_t size = 16;
  while (size < 2 * v) size *= 2;
  constexpr std::uint32_t none = ~0u;
  std::vector<std::uint32_t> first_at(size, none), position(v);
  std::uint32_t positions = 0;
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x == 0 ? 0.0 : x); };
  for (std::uint32_t k = 0; k < v; ++k) {
    const Vec3& p = mesh.vertices[k];
    std::uint64_t h = bits(p.x) * 0x9E3779B97F4A7C15ull ^ bits(p.y) * 0xC2B2AE3D27D4EB4Full ^ bits(p.z) * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    for (std::size_t i = h & (size - 1);; i = (i + 1) & (size - 1)) {
      if (first_at[i] == none) {
        first_at[i] = k;
        position[k] = positions++;
        break;
      }
      const Vec3& q = mesh.vertices[first_at[i]];
      if (p.x == q.x && p.y == q.y && p.z == q.z) {
        position[k] = position[first_at[i]];
        break;
      }
    }
  }
  // The edges of every triangle's boundary a→b, b→c, c→a between positions p ≠ q, grouped by their smaller end
  // (a counting sort): for each pair, as many from p to q as from q to p.
  std::vector<std::uint32_t> start(positions + 1, 0);
  const auto for_each_edge = [&](const auto& f) {
    for (const auto& t : mesh.triangles)
      for (std::size_t e = 0; e < 3; ++e) {
        const std::uint32_t p = position[t[e]], q = position[t[(e + 1) % 3]];
        if (p != q) f(std::min(p, q), std::uint64_t{std::max(p, q)} << 1 | (p < q ? 0u : 1u));
      }
  };
  for_each_edge([&](std::uint32_t low, std::uint64_t) { ++start[low + 1]; });
  for (std::size_t k = 0; k < positions; ++k) start[k + 1] += start[k];
  std::vector<std::uint64_t> other(start[positions]);  // the other end (times 2) and the direction bit
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for_each_edge([&](std::uint32_t low, std::uint64_t entry) { other[fill[low]++] = entry; });
  for (std::size_t k = 0; k < positions; ++k) {
    const auto first = other.begin() + start[k], last = other.begin() + start[k + 1];
    std::sort(first, last);
    for (auto i = first; i != last;) {  // a run of one pair: directions 0 first, then 1, as many of each
      auto j = i;
      while (j != last && (*j >> 1) == (*i >> 1)) ++j;
      const auto backward = std::count_if(i, j, [](std::uint64_t x) { return (x & 1) != 0; });
      if (2 * backward != j - i) return false;
      i = j;
    }
  }
  return true;
}

std::uint32_t InsideGrid::guess(int axis, double x) const noexcept {
  const auto a = static_cast<std::size_t>(axis);
  const double t = (x - origin_[a]) * inverse_step_[a];
  if (!(t >= 1)) return 0;  // also NaN
  if (t >= static_cast<double>(n_[a] - 1)) return n_[a] - 1;
  return static_cast<std::uint32_t>(t);
}

// The last cell whose lower bound is ≤ x (x ≥ the box's lower face): exact comparisons from the guess.
std::uint32_t InsideGrid::last_starting_at_or_before(int axis, double x) const noexcept {
  const auto& p = plane_[static_cast<std::size_t>(axis)];
  const std::uint32_t n = n_[static_cast<std::size_t>(axis)];
  std::uint32_t k = guess(axis, x);
  while (k > 0 && p[k] > x) --k;
  while (k + 1 < n && p[k + 1] <= x) ++k;
  return k;
}

// The first cell whose upper bound is ≥ x (x ≤ the box's upper face).
std::uint32_t InsideGrid::first_ending_at_or_after(int axis, double x) const noexcept {
  const auto& p = plane_[static_cast<std::size_t>(axis)];
  const std::uint32_t n = n_[static_cast<std::size_t>(axis)];
  std::uint32_t k = guess(axis, x);
  while (k > 0 && p[k] >= x) --k;
  while (k + 1 < n && p[k + 1] < x) ++k;
  return k;
}

InsideGrid InsideGrid::build(const PreparedMesh& prepared, const Winding& winding, const Options& options) {
  InsideGrid g;
  const Mesh& mesh = prepared.mesh();
  const Box3& box = prepared.bvh().bounds();
  if (mesh.triangles.size() < options.min_triangles || !closed(mesh)) return g;
  const double lo[3] = {box.lo.x, box.lo.y, box.lo.z}, hi[3] = {box.hi.x, box.hi.y, box.hi.z};
  double extent[3], largest = 0;
  for (int a = 0; a < 3; ++a) {
    extent[a] = hi[a] - lo[a];
    if (!std::isfinite(extent[a])) return g;  // beyond the double range: walk every point
    largest = std::max(largest, extent[a]);
  }
  if (largest == 0) return g;
  // Cells about cubes, about triangles/triangles_per_cell of them in all.
  const double target =
      std::clamp(static_cast<double>(mesh.triangles.size()) / options.triangles_per_cell, 1.0, max_cells);
  double volume_share = 1;  // the product of extent/largest over the axes of positive extent
  int dims = 0;
  for (double e : extent)
    if (e > 0) volume_share *= e / largest, ++dims;
  const double per_largest = std::pow(target / volume_share, 1.0 / dims);
  std::size_t cells = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    const double count = extent[a] > 0 ? std::ceil(per_largest * extent[a] / largest) : 1;
    g.n_[a] = static_cast<std::uint32_t>(std::clamp(count, 1.0, max_per_axis));
    cells *= g.n_[a];
    auto& p = g.plane_[a];
    p.resize(g.n_[a] + 1);
    p[0] = lo[a];
    for (std::uint32_t k = 1; k < g.n_[a]; ++k)
      p[k] = std::min(hi[a], std::max(p[k - 1], lo[a] + extent[a] * (static_cast<double>(k) / g.n_[a])));
    p[g.n_[a]] = hi[a];
    g.origin_[a] = lo[a];
    g.inverse_step_[a] = extent[a] > 0 ? g.n_[a] / extent[a] : 0;
  }
  const std::size_t nx = g.n_[0], ny = g.n_[1];
  const auto index = [&](std::size_t i, std::size_t j, std::size_t k) { return (k * ny + j) * nx + i; };

  // Mark every cell some triangle's box meets (0: such a cell; 1: free until marked).
  std::vector<std::int32_t> cell(cells, 1);
  const std::size_t budget = 16 * cells + 8 * mesh.triangles.size();
  std::size_t marked = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle tri = mesh.triangle(t);
    std::uint32_t from[3], to[3];
    for (int a = 0; a < 3; ++a) {
      const double u = coordinate(tri.a, a), v = coordinate(tri.b, a), w = coordinate(tri.c, a);
      from[a] = g.first_ending_at_or_after(a, std::min({u, v, w}));
      to[a] = g.last_starting_at_or_before(a, std::max({u, v, w}));
    }
    marked += std::size_t{to[0] - from[0] + 1} * (to[1] - from[1] + 1) * (to[2] - from[2] + 1);
    if (marked > budget) return InsideGrid{};  // huge triangles over a fine grid: not worth it
    for (std::uint32_t k = from[2]; k <= to[2]; ++k)
      for (std::uint32_t j = from[1]; j <= to[1]; ++j)
        for (std::uint32_t i = from[0]; i <= to[0]; ++i) cell[index(i, j, k)] = 0;
  }

  // Components of free cells sharing a face; each one's winding number from a point of its first cell.
  std::vector<std::uint32_t> stack;
  for (std::size_t start = 0; start < cells; ++start) {
    if (cell[start] != 1) continue;
    const std::size_t i0 = start % nx, j0 = start / nx % ny, k0 = start / nx / ny;
    const std::size_t at[3] = {i0, j0, k0};
    Vec3 centre{};
    for (int a = 0; a < 3; ++a) {
      const auto& p = g.plane_[static_cast<std::size_t>(a)];
      const double l = p[at[a]], h = p[at[a] + 1];
      const double m = std::clamp(0.5 * l + 0.5 * h, l, h);  // in the closed cell whatever the rounding
      (a == 0 ? centre.x : a == 1 ? centre.y : centre.z) = m;
    }
    const std::optional<std::int64_t> w = winding(centre);
    if (!w) return InsideGrid{};  // cannot happen (a free cell holds no point of the surface): walk instead
    const auto component = static_cast<std::int32_t>(g.winding_.size()) + 2;
    g.winding_.push_back(*w);
    cell[start] = component;
    stack.push_back(static_cast<std::uint32_t>(start));
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      const std::size_t i = c % nx, j = c / nx % ny, k = c / nx / ny;
      const auto visit = [&](std::size_t n) {
        if (cell[n] == 1) cell[n] = component, stack.push_back(static_cast<std::uint32_t>(n));
      };
      if (i > 0) visit(c - 1);
      if (i + 1 < nx) visit(c + 1);
      if (j > 0) visit(c - nx);
      if (j + 1 < ny) visit(c + nx);
      if (k > 0) visit(c - nx * ny);
      if (k + 1 < g.n_[2]) visit(c + nx * ny);
    }
  }
  // Stored: the component's index, −1 for a cell some triangle's box meets.
  for (auto& c : cell) c -= 2;
  g.cell_ = std::move(cell);
  return g;
}

std::optional<std::int64_t> InsideGrid::lookup(const Vec3& point) const noexcept {
  if (cell_.empty()) return std::nullopt;
  const std::size_t i = last_starting_at_or_before(0, point.x), j = last_starting_at_or_before(1, point.y),
                    k = last_starting_at_or_before(2, point.z);
  const std::int32_t c = cell_[(k * n_[1] + j) * n_[0] + i];
  if (c < 0) return std::nullopt;
  return winding_[static_cast<std::size_t>(c)];
}

double InsideGrid::free_share() const noexcept {
  if (cell_.empty()) return 0;
  return static_cast<double>(std::count_if(cell_.begin(), cell_.end(), [](std::int32_t c) { return c >= 0; })) /
         static_cast<double>(cell_.size());
}

}  // namespace raykernel::mesh_detail

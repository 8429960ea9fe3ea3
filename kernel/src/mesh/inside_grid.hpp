// The point-location grid of `inside` (inside.cpp): for a closed mesh, the winding number of every cell of a
// grid over the bounding box that no triangle comes near, so that most points are answered without a walk.
//
// Why it is exact. A cell is a closed box [x_i, x_i+1] × [y_j, y_j+1] × [z_k, z_k+1] whose bounds are doubles;
// it is *free* when no triangle's box (the exact min/max of its vertex doubles) meets it, decided by exact
// comparisons of doubles. A free cell holds no point of the surface, and neither does the union of two free
// cells that share a face, which is connected: so the winding number of the mesh — the signed count of owned
// crossings of any ray, for a closed mesh (docs/contract.md §7, raykernel/mesh_queries.hpp) — is one integer on
// each connected set of free cells (a component). The grid stores it, computed once per component by the
// exact walk from a point of one of its cells. A point in a free cell is therefore answered with its
// component's number, which is the number the walk would give it; a point in any other cell goes to the walk.
//
// When the grid is used at all: only for a closed mesh, in the sense under which the count does not depend on
// the ray: every edge between two vertex positions (compared as doubles) is traversed as often from one end as
// from the other by the triangles' boundaries (degenerate triangles included; an edge whose ends are the same
// position counts for nothing). For any other mesh (an open or inconsistently oriented one) the answer depends
// on the direction of the ray, which differs from point to point, so every point is walked.
#pragma once

#include <raykernel/mesh_queries.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

namespace raykernel::mesh_detail {

class InsideGrid {
 public:
  // The exact winding number of a point off the surface (the walk).
  using Winding = std::function<std::optional<std::int64_t>(const Vec3&)>;

  // The grid of `mesh` (the default environment is installed by the caller), or an unusable one when the mesh
  // is not closed, has too few triangles for a grid to pay, or its triangles' boxes would cost too much to
  // mark.
  struct Options {
    // Below this many triangles every point is walked (a walk over a small mesh costs about what a grid saves).
    std::size_t min_triangles = 1024;
    // About one cell per this many triangles (at most 2^22 cells, 1024 along an axis).
    double triangles_per_cell = 4;
  };
  static InsideGrid build(const PreparedMesh& mesh, const Winding& winding, const Options& options);

  // The winding number of a point of the mesh's bounding box that lies in a free cell; nothing otherwise
  // (and always nothing for an unusable grid).
  [[nodiscard]] std::optional<std::int64_t> lookup(const Vec3& point) const noexcept;

  [[nodiscard]] bool usable() const noexcept { return !cell_.empty(); }
  // The share of free cells, and the number of components (for the benchmarks' counters).
  [[nodiscard]] double free_share() const noexcept;
  [[nodiscard]] std::size_t components() const noexcept { return winding_.size(); }

  // The closedness test above, on its own (exact: vertex positions compared as doubles).
  [[nodiscard]] static bool closed(const Mesh& mesh);
  // Axis a's cell bounds (n_a + 1 non-decreasing doubles), for tests that aim at them.
  [[nodiscard]] const std::vector<double>& planes(int axis) const noexcept { return plane_[static_cast<std::size_t>(axis)]; }

 private:
  // Axis a: cells 0 … n_a − 1, cell i spans [plane_[a][i], plane_[a][i + 1]] (non-decreasing doubles, the
  // bounding box's faces first and last).
  std::array<std::vector<double>, 3> plane_;
  std::array<std::uint32_t, 3> n_{};
  std::array<double, 3> origin_{}, inverse_step_{};  // a first guess of the cell (then corrected exactly)
  std::vector<std::int32_t> cell_;                    // component of each free cell, −1 for the others
  std::vector<std::int64_t> winding_;                 // per component

  [[nodiscard]] std::uint32_t last_starting_at_or_before(int axis, double x) const noexcept;
  [[nodiscard]] std::uint32_t first_ending_at_or_after(int axis, double x) const noexcept;
  [[nodiscard]] std::uint32_t guess(int axis, double x) const noexcept;
};

// PreparedMesh's slot for the grid: built once, by the first inside() (or winding_number()) on the mesh.
struct InsideGridCache {
  std::once_flag once;
  InsideGrid grid;
};

}  // namespace raykernel::mesh_detail

// raykernel/bvh.hpp: a bounding volume hierarchy over a mesh's triangles, and a ray traversal that never
// misses a box the exact ray meets.
//
// The hierarchy is built once per mesh (binned surface-area heuristic, deterministic) and stored flat:
// each node's box is the exact min/max of its triangles' vertex doubles, so it contains them exactly. The
// traversal asks, for each box, whether the ray o + t·d, t in [t_min, t_max], may meet it. Its answer is
// conservative in one direction only: a box the exact ray meets is never rejected, and the lower bound it
// reports for the box's exact entry t is never above that t (kernel/src/mesh/ray_box.hpp has the argument,
// step by step, with overflow, underflow, zero and tiny direction components). A box may be reported that
// the exact ray just misses; the exact primitive test decides those.
//
// Leaves come nearest box first (each inner node's nearer child first; a deferred child is skipped when
// popped if its entry bound already exceeds the caller's bound), so a nearest-hit search can prune: the
// caller passes to next() an upper bound of the best exact t found so far, and a box is skipped only when
// its certified entry lower bound is strictly greater, i.e. when its exact entry t is provably greater
// than the best exact t — so ties between equal exact t values (broken by triangle index, docs/contract.md
// §7) are never lost.
#pragma once

#include <raykernel/mesh.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace raykernel {

// The box [lo.x, hi.x] × [lo.y, hi.y] × [lo.z, hi.z] (closed).
struct Box3 {
  Vec3 lo, hi;
};

// One node of the flattened hierarchy, in depth-first order: an inner node's first child is the next node.
struct BvhNode {
  Box3 bounds;          // exact: min/max of the vertex doubles of every triangle below
  std::uint32_t first;  // leaf: first position in MeshBvh::triangle_order(); inner: index of the second child
  std::uint32_t count;  // leaf: number of triangles (≥ 1); inner: 0
  std::uint8_t axis;    // inner: the axis its children were split along
};

struct BvhBuildOptions {
  std::uint32_t max_leaf_size = 4;  // a node with more triangles is split when the heuristic says so...
  std::uint32_t max_leaf_size_hard = 16;  // ...and always above this (unless all centroids coincide)
  std::uint32_t bins = 32;          // candidate split planes per axis: bins − 1
};

class MeshBvh {
 public:
  MeshBvh() = default;
  // Builds the hierarchy over every triangle of `mesh` (degenerate ones included). Throws invalid_input when
  // validate(mesh) fails. Deterministic: the same mesh gives the same nodes. The mesh is not referenced
  // afterwards.
  explicit MeshBvh(const Mesh& mesh, const BvhBuildOptions& options = {});

  [[nodiscard]] std::span<const BvhNode> nodes() const noexcept { return nodes_; }
  // Leaf ranges index this: the mesh's triangle indices, grouped by leaf.
  [[nodiscard]] std::span<const std::uint32_t> triangle_order() const noexcept { return order_; }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return order_.size(); }
  [[nodiscard]] int depth() const noexcept { return depth_; }
  // max(|lo_i|, |hi_i|) of the root box per axis: the overflow guard of the traversal uses it.
  [[nodiscard]] const std::array<double, 3>& magnitude() const noexcept { return magnitude_; }

  static constexpr int max_depth = 64;

 private:
  std::vector<BvhNode> nodes_;
  std::vector<std::uint32_t> order_;
  std::array<double, 3> magnitude_{};
  int depth_ = 0;
};

// A leaf the ray may meet: its triangles (indices into the mesh), and a lower bound of the exact t at which
// the ray enters the leaf's box within [t_min, t_max] (≥ t_min).
struct BvhLeaf {
  std::span<const std::uint32_t> triangles;
  double entry_lower_bound;
};

// One ray's walk through a MeshBvh, leaf by leaf, nearest first.
//
//   BvhRayTraversal walk(bvh, ray);
//   double best = inf;                        // ≥ the best exact t found so far
//   while (auto leaf = walk.next(best))
//     for (std::uint32_t k : leaf->triangles) ...   // test triangle k exactly; lower `best` on a hit
//
// Guarantee: every leaf whose box the exact ray meets at some t in [t_min, min(t_max, t_upper)] — t_upper
// the value passed to next() at the time the leaf's box or an ancestor's was tested — is returned. Hence
// every triangle the exact ray meets at such a t is in a returned leaf. The bvh must outlive the walk.
class BvhRayTraversal {
 public:
  // The ray must be valid (finite origin and direction, direction ≠ 0) and 0 ≤ t_min ≤ t_max (t_max may be
  // +inf); otherwise throws invalid_input. For a whole line, walk (o, d) and (o, −d).
  BvhRayTraversal(const MeshBvh& bvh, const Ray& ray, double t_min = 0,
                  double t_max = std::numeric_limits<double>::infinity());

  // The next leaf, or nothing when every box left is missed or starts beyond t_upper (not NaN): boxes
  // whose certified entry lower bound is > t_upper are skipped.
  [[nodiscard]] std::optional<BvhLeaf> next(double t_upper = std::numeric_limits<double>::infinity());

  [[nodiscard]] std::uint64_t boxes_tested() const noexcept { return boxes_tested_; }

  // The per-ray set-up of the box test (kernel/src/mesh/ray_box.hpp), exposed for tests: for each axis the
  // origin, RN(1/d) (±inf for d = ±0, NaN when the axis is left out of the test) and whether the ray
  // enters through the box's upper face (d negative, or −0).
  struct Slabs {
    std::array<double, 3> origin;
    std::array<double, 3> inverse_direction;
    std::array<bool, 3> enters_at_hi;
  };
  [[nodiscard]] const Slabs& slabs() const noexcept { return slabs_; }

 private:
  struct Pending {
    std::uint32_t node;
    double entry;
  };
  const MeshBvh* bvh_;
  Slabs slabs_;
  double t_min_, t_max_;
  std::array<Pending, MeshBvh::max_depth + 2> stack_;
  int stack_size_ = 0;
  std::uint64_t boxes_tested_ = 0;
};

// The certified ray–box test on its own (kernel/src/mesh/ray_box.hpp): whether the ray may meet `box` at
// some t in [t_min, t_max], and then a lower bound of the exact entry t. `magnitude` bounds |coordinate| of
// every box that will be tested, per axis (the overflow guard). For tests and for callers with their own
// boxes. The ray must be valid and 0 ≤ t_min ≤ t_max.
[[nodiscard]] BvhRayTraversal::Slabs ray_box_slabs(const Ray& ray, const std::array<double, 3>& magnitude);
[[nodiscard]] std::optional<double> ray_box_entry(const BvhRayTraversal::Slabs& slabs, const Box3& box, double t_min,
                                                  double t_max) noexcept;

}  // namespace raykernel

// raykernel/bvh.hpp: a bounding volume hierarchy over a mesh's triangles, and a ray traversal that never
// misses a box the exact ray meets.
//
// The hierarchy is built once per mesh (binned surface-area heuristic, deterministic, then collapsed to eight
// children per node) and stored flat: each child's box is the exact min/max of its triangles' vertex
// doubles rounded outward to binary32, so it contains them exactly. The traversal asks, for each box, whether the ray o + t·d, t in
// [t_min, t_max], may meet it. Its answer is conservative in one direction only: a box the exact ray meets is
// never rejected, and the lower bound it reports for the box's exact entry t is never above that t
// (kernel/src/box/ray_box.hpp has the argument, step by step, with overflow, underflow, zero and tiny
// direction components). A box may be reported that the exact ray just misses; the exact primitive test
// decides those. The eight children of a node are tested in one vector pass (AVX2 or AVX-512 where the CPU has
// it), each lane performing exactly the scalar test's operations on its box converted to double, so the argument (and proofs/box/RayBox.v) covers every
// lane; the differential runner checks each lane of every instruction set's pass, and the scalar test, bit for
// bit against their Coq twins (proofs/box/RayBoxTwins.v, `ray_box_entry_twin_sound`, `ray_box_entries8_twin_sound`).
//
// Leaves come nearest box first (each node's children in the order of their entry bounds; a deferred child is
// skipped when popped if its entry bound already exceeds the caller's bound), so a nearest-hit search can
// prune: the caller passes to next() an upper bound of the best exact t found so far, and a box is skipped
// only when its certified entry lower bound is strictly greater, i.e. when its exact entry t is provably
// greater than the best exact t — so ties between equal exact t values (broken by triangle index,
// docs/contract.md §7) are never lost.
#pragma once

#include <raykernel/large_vector.hpp>
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

// One node of the flattened hierarchy: up to eight children, their boxes side by side (structure of arrays,
// one 32-byte row per face, so that one vector load reads a face of all eight boxes), then what each child is.
// 256 bytes, aligned to cache lines. The boxes are binary32, rounded outward from the exact double boxes (lo
// down, hi up), so each contains its primitives exactly; the ray–box test converts them back to double exactly (proofs/box/RayBox.v, `slab_sound_outward`).
struct alignas(64) BvhNode {
  static constexpr int width = 8;
  // bounds[f][s]: face f of child s's box, f = 0, 1, 2 for lo.x, lo.y, lo.z and 3, 4, 5 for hi.x, hi.y, hi.z.
  // Slots s ≥ children() hold the empty box (lo = +inf, hi = −inf) and first = count = 0.
  std::array<std::array<float, width>, 6> bounds;
  std::array<std::uint32_t, width> first;  // leaf child: first position in MeshBvh::triangle_order(); inner: node index (≥ 1)
  std::array<std::uint32_t, width> count;  // leaf child: number of triangles (≥ 1); inner child: 0

  // The slot holds no child (the root, node 0, is nobody's child, so an inner child has first ≥ 1).
  [[nodiscard]] bool empty_slot(int slot) const noexcept {
    const auto s = static_cast<std::size_t>(slot);
    return (first[s] | count[s]) == 0;
  }
  // Slots in use, 1 to width: the children fill the first slots.
  [[nodiscard]] int children() const noexcept {
    int n = 0;
    while (n < width && !empty_slot(n)) ++n;
    return n;
  }
  // Child `slot`'s box, in doubles (exactly the stored binary32 bounds): it contains the exact box.
  [[nodiscard]] Box3 box(int slot) const noexcept {
    const auto s = static_cast<std::size_t>(slot);
    return {{bounds[0][s], bounds[1][s], bounds[2][s]}, {bounds[3][s], bounds[4][s], bounds[5][s]}};
  }
  [[nodiscard]] bool is_leaf(int slot) const noexcept { return count[static_cast<std::size_t>(slot)] > 0; }
};
static_assert(sizeof(BvhNode) == 256);

struct BvhBuildOptions {
  std::uint32_t max_leaf_size = 4;  // a node with more triangles is split when the heuristic says so...
  std::uint32_t max_leaf_size_hard = 16;  // ...and always above this (unless all centroids coincide)
  std::uint32_t bins = 32;          // candidate split planes per axis: bins − 1
  unsigned threads = 0;             // the build's threads (0: every core); the nodes are the same for any count
};

class MeshBvh {
 public:
  MeshBvh() = default;
  // Builds the hierarchy over every triangle of `mesh` (degenerate ones included). Throws invalid_input when
  // validate(mesh) fails. Deterministic: the same mesh gives the same nodes. The mesh is not referenced
  // afterwards.
  explicit MeshBvh(const Mesh& mesh, const BvhBuildOptions& options = {});
  // The same hierarchy over any primitives, given by their boxes (each must contain its primitive exactly and
  // be finite, lo ≤ hi; a sphere set's, SphereSet): leaf ranges then index `boxes`. Throws invalid_input for a
  // box that is not finite or is inverted.
  explicit MeshBvh(std::span<const Box3> boxes, const BvhBuildOptions& options = {});

  // The nodes; the root is nodes()[0] (none for a mesh without triangles).
  [[nodiscard]] std::span<const BvhNode> nodes() const noexcept { return nodes_; }
  // Leaf ranges index this: the mesh's triangle indices, grouped by leaf.
  [[nodiscard]] std::span<const std::uint32_t> triangle_order() const noexcept { return order_; }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return order_.size(); }
  // The exact min/max of every vertex of every triangle (the empty box for no triangles).
  [[nodiscard]] const Box3& bounds() const noexcept { return bounds_; }
  // Nodes on the longest path from the root to a leaf (0 without triangles), at most max_depth.
  [[nodiscard]] int depth() const noexcept { return depth_; }
  // max(|lo_i|, |hi_i|) of the root box rounded outward to binary32, per axis (so it bounds every node's box;
  // +inf beyond the binary32 range): the overflow guard of the traversal uses it.
  [[nodiscard]] const std::array<double, 3>& magnitude() const noexcept { return magnitude_; }

  static constexpr int max_depth = 64;

 private:
  // The build over n primitives, primitive k's box (exact, finite, lo ≤ hi) given by box_of(source, k).
  using BoxSource = Box3 (*)(const void* source, std::size_t k);
  void build(std::size_t n, BoxSource box_of, const void* source, const BvhBuildOptions& options);

  detail::LargeVector<BvhNode> nodes_;
  detail::LargeVector<std::uint32_t> order_;
  Box3 bounds_{};
  std::array<double, 3> magnitude_{};
  int depth_ = 0;
};

// A leaf the ray may meet: its triangles (indices into the mesh), where they start in triangle_order(), and a
// lower bound of the exact t at which the ray enters the leaf's box within [t_min, t_max] (≥ t_min).
struct BvhLeaf {
  std::span<const std::uint32_t> triangles;
  double entry_lower_bound;
  std::uint32_t position;  // triangles[0] is triangle_order()[position]
};

namespace detail {
// The state of one ray's walk (BvhRayTraversal's, and the mesh queries'); internal.
struct BvhWalk {
  struct Pending {
    std::uint32_t first, count;  // a child: node index (count 0) or leaf range
    double entry;
  };
  const MeshBvh* bvh = nullptr;
  // The per-ray set-up of the box test (ray_box.hpp): origin, RN(1/d) (±inf for d = ±0, NaN for an axis left
  // out), and per axis the rows of BvhNode::bounds holding the near and the far face.
  std::array<double, 3> origin{}, inverse_direction{};
  std::array<std::uint8_t, 3> near_face{}, far_face{};
  double t_min = 0, t_max = 0;
  // The caller's primitives in leaf order (a PreparedMesh's leaf_triangles()), and their size in bytes: the walk
  // prefetches a deferred leaf's when it defers it. Null: nothing to prefetch.
  const unsigned char* leaf_data = nullptr;
  std::uint32_t leaf_stride = 0;
  std::uint64_t boxes_tested = 0;
  int stack_size = 0;
  std::array<Pending, (BvhNode::width - 1) * MeshBvh::max_depth + 2> stack;
};
}  // namespace detail

// One ray's walk through a MeshBvh, leaf by leaf, nearest first.
//
//   BvhRayTraversal walk(bvh, ray);
//   double best = inf;                        // ≥ the best exact t found so far
//   while (auto leaf = walk.next(best))
//     for (std::uint32_t k : leaf->triangles) ...   // test triangle k exactly; lower `best` on a hit
//
// Guarantee: every leaf whose box the exact ray meets at some t in [t_min, min(t_max, t_upper)] — t_upper
// the value passed to next() at the time the leaf's box or an ancestor's was tested — is returned. Hence
// every triangle the exact ray meets at such a t is in a returned leaf. The bvh must outlive the walk. The
// box tests run in the default floating-point environment whatever the caller's (each call installs it).
class BvhRayTraversal {
 public:
  // The ray must be valid (finite origin and direction, direction ≠ 0) and 0 ≤ t_min ≤ t_max (t_max may be
  // +inf); otherwise throws invalid_input. For a whole line, walk (o, d) and (o, −d).
  BvhRayTraversal(const MeshBvh& bvh, const Ray& ray, double t_min = 0,
                  double t_max = std::numeric_limits<double>::infinity());

  // The next leaf, or nothing when every box left is missed or starts beyond t_upper (not NaN): boxes
  // whose certified entry lower bound is > t_upper are skipped.
  [[nodiscard]] std::optional<BvhLeaf> next(double t_upper = std::numeric_limits<double>::infinity());

  [[nodiscard]] std::uint64_t boxes_tested() const noexcept { return walk_.boxes_tested; }

  // The per-ray set-up of the box test (kernel/src/box/ray_box.hpp), exposed for tests: for each axis the
  // origin, RN(1/d) (±inf for d = ±0, NaN when the axis is left out of the test) and whether the ray
  // enters through the box's upper face (d negative, or −0).
  struct Slabs {
    std::array<double, 3> origin;
    std::array<double, 3> inverse_direction;
    std::array<bool, 3> enters_at_hi;
  };
  [[nodiscard]] Slabs slabs() const noexcept;

 private:
  detail::BvhWalk walk_;
};

// The certified ray–box test on its own (kernel/src/box/ray_box.hpp): whether the ray may meet `box` at
// some t in [t_min, t_max], and then a lower bound of the exact entry t. `magnitude` bounds |coordinate| of
// every box that will be tested, per axis (the overflow guard). For tests and for callers with their own
// boxes. The ray must be valid and 0 ≤ t_min ≤ t_max.
[[nodiscard]] BvhRayTraversal::Slabs ray_box_slabs(const Ray& ray, const std::array<double, 3>& magnitude);
[[nodiscard]] std::optional<double> ray_box_entry(const BvhRayTraversal::Slabs& slabs, const Box3& box, double t_min,
                                                  double t_max) noexcept;

// The same test on the eight children of `node` at once, as the traversal runs it (one vector pass where the
// CPU has AVX2; each lane the scalar test's operations on its box converted to double): bit s of the result is set when child s may be met,
// and entries[s] is then its entry bound. For tests.
[[nodiscard]] unsigned ray_box_entries(const BvhRayTraversal::Slabs& slabs, const BvhNode& node, double t_min,
                                       double t_max, std::array<double, BvhNode::width>& entries) noexcept;

// Whether the closed boxes a and b share a point: six comparisons of doubles, exact (an empty box shares none).
[[nodiscard]] inline bool boxes_overlap(const Box3& a, const Box3& b) noexcept {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}

// Calls visit(primitives) — the indices of one leaf (into the mesh's triangles, or a SphereSet's spheres) — for
// each leaf whose box overlaps `box`, depth first, until visit returns true; returns whether it did. Exact: a
// primitive with a point in `box` is in a leaf whose box overlaps it (each box contains its primitives exactly), so
// that leaf is visited. The query of anything bounded by a box: an open segment by the box of its two ends.
template <class Visit>
bool any_leaf_overlapping(const MeshBvh& bvh, const Box3& box, Visit&& visit) {
  const std::span<const BvhNode> nodes = bvh.nodes();
  if (nodes.empty() || !boxes_overlap(bvh.bounds(), box)) return false;
  std::array<std::uint32_t, (BvhNode::width - 1) * MeshBvh::max_depth + 2> stack;
  int size = 0;
  stack[static_cast<std::size_t>(size++)] = 0;
  while (size > 0) {
    const BvhNode& node = nodes[stack[static_cast<std::size_t>(--size)]];
    for (int s = 0; s < BvhNode::width && !node.empty_slot(s); ++s) {
      if (!boxes_overlap(node.box(s), box)) continue;
      const auto slot = static_cast<std::size_t>(s);
      if (node.is_leaf(s)) {
        if (visit(bvh.triangle_order().subspan(node.first[slot], node.count[slot]))) return true;
      } else {
        stack[static_cast<std::size_t>(size++)] = node.first[slot];
      }
    }
  }
  return false;
}

}  // namespace raykernel

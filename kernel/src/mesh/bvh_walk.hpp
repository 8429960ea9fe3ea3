// The BVH walk: the next leaf of one ray's nearest-first traversal (BvhRayTraversal::next and the mesh
// queries). Written once here and compiled per instruction set in bvh_walk_<isa>.cpp (AVX-512: the eight
// child boxes of a node in one zmm pass per face row; AVX2: two passes of four lanes (ymm); portable: four of
// two (xmm) — box/ray_box.hpp, ray_box_entries8), chosen at run time by bvh.cpp — as the batch loops are
// (plane/fast_loop.hpp), and for the same reason separate translation units: everything here is always
// inlined into the per-ISA entry point, so those objects define no other symbol (tests/check_isa_objects.cmake
// checks it) and no AVX2 copy of a shared inline function can be picked by the linker for other callers.
#pragma once

#include "box/ray_box.hpp"

#include <raykernel/bvh.hpp>

#include <algorithm>
#include <cstdint>
#include <span>

namespace raykernel::mesh_detail {

// All four cache lines of a node (256 bytes, aligned to 64).
[[gnu::always_inline]] inline void prefetch_node(const BvhNode& node) noexcept {
  const char* p = reinterpret_cast<const char*>(&node);
  for (int line = 0; line < 4; ++line) __builtin_prefetch(p + 64 * line);
}

// The first cache lines (up to four) of a deferred leaf's primitives, when the caller gave them (BvhWalk::leaf_data).
[[gnu::always_inline]] inline void prefetch_leaf(const detail::BvhWalk& w, std::uint32_t first, std::uint32_t count) noexcept {
  __builtin_prefetch(w.bvh->triangle_order().data() + first);  // the leaf's mesh indices
  if (w.leaf_data == nullptr) return;
  const unsigned char* p = w.leaf_data + static_cast<std::size_t>(first) * w.leaf_stride;
  const std::size_t bytes = std::min<std::size_t>(static_cast<std::size_t>(count) * w.leaf_stride, 256);
  for (std::size_t offset = 0; offset < bytes; offset += 64) __builtin_prefetch(p + offset);
}

// The next leaf whose box the ray may meet in [t_min, min(t_max, t_upper)], nearest entry bound first among
// the children of each node; false when there is none. On a node, the children the test accepts are ordered
// by their entry bounds (ties by slot), the nearest is descended into and the others pushed, farthest first,
// so that the nearest deferred one is popped next; a popped child whose entry bound exceeds the bound of the
// time is skipped.
[[gnu::always_inline]] inline bool walk_next(detail::BvhWalk& w, double t_upper, BvhLeaf& leaf) noexcept {
  using Pending = detail::BvhWalk::Pending;
  const double t1 = t_upper < w.t_max ? t_upper : w.t_max;
  const BvhNode* const nodes = w.bvh->nodes().data();
  while (w.stack_size > 0) {
    Pending current = w.stack[static_cast<std::size_t>(--w.stack_size)];
    if (current.entry > t1) continue;  // the box starts beyond the caller's bound: skip it
    while (current.count == 0) {
      const BvhNode& node = nodes[current.first];
      // The children's ids are on the node's last cache line, read only after the box test: fetch them now,
      // beside the box rows, rather than after.
      __builtin_prefetch(&node.first);
      detail::Lanes8 entry;
      unsigned met = ray_box_entries8(w, node, w.t_min, t1, entry);
      w.boxes_tested += BvhNode::width;
      if (met == 0) goto next_pending;
      // The accepted children by entry bound, nearest last (insertion into at most eight); an accepted empty
      // slot (only when every axis is left out of the test) is skipped.
      Pending order[BvhNode::width];
      int n = 0;
      for (; met != 0; met &= met - 1) {
        const auto slot = static_cast<std::size_t>(__builtin_ctz(met));
        const Pending p{node.first[slot], node.count[slot], entry[slot]};
        if ((p.first | p.count) == 0) continue;
        int i = n++;
        for (; i > 0 && order[i - 1].entry < p.entry; --i) order[i] = order[i - 1];
        order[i] = p;
      }
      if (n == 0) goto next_pending;
      for (int i = 0; i + 1 < n; ++i) {
        w.stack[static_cast<std::size_t>(w.stack_size++)] = order[i];
        if (order[i].count == 0) prefetch_node(nodes[order[i].first]);
        else prefetch_leaf(w, order[i].first, order[i].count);
      }
      current = order[n - 1];
    }
    leaf.triangles = w.bvh->triangle_order().subspan(current.first, current.count);
    leaf.entry_lower_bound = current.entry;
    leaf.position = current.first;
    return true;
  next_pending:;
  }
  return false;
}

// The entry points, one per instruction set (defined in bvh_walk_<isa>.cpp).
#define RAYKERNEL_DECLARE_BVH_WALK(isa)                                                                      \
  namespace isa {                                                                                           \
  bool next_leaf(detail::BvhWalk& walk, double t_upper, BvhLeaf& leaf) noexcept;                            \
  unsigned node_entries(const detail::BvhWalk& walk, const BvhNode& node, double t_min, double t_max,        \
                        double* entries) noexcept;                                                          \
  }
RAYKERNEL_DECLARE_BVH_WALK(portable)
RAYKERNEL_DECLARE_BVH_WALK(avx2)
RAYKERNEL_DECLARE_BVH_WALK(avx512)
#undef RAYKERNEL_DECLARE_BVH_WALK

#define RAYKERNEL_DEFINE_BVH_WALK(isa)                                                                        \
  bool raykernel::mesh_detail::isa::next_leaf(detail::BvhWalk& walk, double t_upper, BvhLeaf& leaf) noexcept { \
    return walk_next(walk, t_upper, leaf);                                                                     \
  }                                                                                                            \
  unsigned raykernel::mesh_detail::isa::node_entries(const detail::BvhWalk& walk, const BvhNode& node,         \
                                                     double t_min, double t_max, double* entries) noexcept {   \
    detail::Lanes8 e;                                                                                          \
    unsigned met = ray_box_entries8(walk, node, t_min, t_max, e);                                              \
    for (int s = 0; s < BvhNode::width; ++s) {                                                                 \
      entries[s] = e[s];                                                                                       \
      if (node.empty_slot(s)) met &= ~(1u << s);                                                               \
    }                                                                                                          \
    return met;                                                                                                \
  }

// The walk's functions for the CPU running the program (chosen once).
struct BvhWalkFunctions {
  bool (*next_leaf)(detail::BvhWalk&, double, BvhLeaf&) noexcept;
  unsigned (*node_entries)(const detail::BvhWalk&, const BvhNode&, double, double, double*) noexcept;
};
[[nodiscard]] const BvhWalkFunctions& bvh_walk_functions() noexcept;

// The walk's start: the ray's set-up and the root on the stack (nothing for an empty hierarchy). The ray must
// be valid and 0 ≤ t_min ≤ t_max.
void start_walk(detail::BvhWalk& w, const MeshBvh& bvh, const Ray& ray, double t_min, double t_max) noexcept;
// The same over a mesh's triangles in leaf order (PreparedMesh::leaf_triangles()), which the walk prefetches.
inline void start_walk(detail::BvhWalk& w, const MeshBvh& bvh, const Ray& ray, double t_min, double t_max,
                       std::span<const Triangle> leaf_triangles) noexcept {
  start_walk(w, bvh, ray, t_min, t_max);
  w.leaf_data = reinterpret_cast<const unsigned char*>(leaf_triangles.data());
  w.leaf_stride = sizeof(Triangle);
}

}  // namespace raykernel::mesh_detail

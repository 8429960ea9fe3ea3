// MeshBvh (binned SAH build of a binary hierarchy, collapsed to four children per node) and
// BvhRayTraversal (nearest-first walk with the certified box test of ray_box.hpp, bvh_walk.hpp).
#include "core/fp_requirements.hpp"
#include "core/fp_environment.hpp"
#include "mesh/bvh_walk.hpp"
#include "box/ray_box.hpp"

#include <raykernel/bvh.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace raykernel {
namespace {

struct Item {  // one triangle during the build
  Box3 box;
  std::array<double, 3> centroid;  // the box centre, scaled by 2^-e (only the split choice uses it)
};

Box3 empty_box() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

void grow(Box3& b, const Box3& o) {
  b.lo = {std::min(b.lo.x, o.lo.x), std::min(b.lo.y, o.lo.y), std::min(b.lo.z, o.lo.z)};
  b.hi = {std::max(b.hi.x, o.hi.x), std::max(b.hi.y, o.hi.y), std::max(b.hi.z, o.hi.z)};
}

// Surface area of a box (half of it), in the scaled coordinates; only compared, never certified.
double half_area(const Box3& b, double scale) {
  if (b.lo.x > b.hi.x) return 0;
  const double ex = (b.hi.x * scale - b.lo.x * scale), ey = (b.hi.y * scale - b.lo.y * scale),
               ez = (b.hi.z * scale - b.lo.z * scale);
  return ex * ey + ey * ez + ez * ex;
}

// A node of the binary hierarchy the build makes first (depth-first: an inner node's first child is the next
// node).
struct BinaryNode {
  Box3 bounds;          // exact: min/max of the vertex doubles of every triangle below
  std::uint32_t first;  // leaf: first position in the triangle order; inner: index of the second child
  std::uint32_t count;  // leaf: number of triangles (≥ 1); inner: 0
};

class Builder {
 public:
  Builder(std::vector<Item> items, const BvhBuildOptions& options, double scale, std::vector<BinaryNode>& nodes,
          std::vector<std::uint32_t>& order)
      : items_(std::move(items)), options_(options), scale_(scale), nodes_(nodes), order_(order) {}

  int build(std::uint32_t begin, std::uint32_t end, int depth) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    Box3 bounds = empty_box();
    Box3 centroid_bounds = empty_box();
    for (std::uint32_t i = begin; i < end; ++i) {
      const Item& it = items_[order_[i]];
      grow(bounds, it.box);
      const Box3 c{{it.centroid[0], it.centroid[1], it.centroid[2]}, {it.centroid[0], it.centroid[1], it.centroid[2]}};
      grow(centroid_bounds, c);
    }
    const std::uint32_t n = end - begin;
    auto make_leaf = [&] {
      nodes_[index] = {bounds, begin, n};
      return depth;
    };
    if (n <= 1 || depth >= MeshBvh::max_depth) return make_leaf();
    const std::uint32_t mid = split(begin, end, bounds, centroid_bounds);
    if (mid == begin || mid == end) return make_leaf();
    const int left_depth = build(begin, mid, depth + 1);
    const auto right = static_cast<std::uint32_t>(nodes_.size());
    const int right_depth = build(mid, end, depth + 1);
    nodes_[index] = {bounds, right, 0};
    return std::max(left_depth, right_depth);
  }

 private:
  // Partitions [begin, end) by the cheapest binned SAH split; returns the split position, or begin/end for
  // "make a leaf".
  std::uint32_t split(std::uint32_t begin, std::uint32_t end, const Box3& bounds, const Box3& cb) {
    const std::uint32_t n = end - begin;
    const std::uint32_t bins = std::max<std::uint32_t>(2, options_.bins);
    const double lo[3] = {cb.lo.x, cb.lo.y, cb.lo.z}, hi[3] = {cb.hi.x, cb.hi.y, cb.hi.z};
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1;
    std::uint32_t best_bin = 0;
    std::vector<Box3> bin_box(bins);
    std::vector<std::uint32_t> bin_count(bins);
    std::vector<double> right_area(bins);
    std::vector<std::uint32_t> right_count(bins);
    for (int axis = 0; axis < 3; ++axis) {
      const double extent = hi[axis] - lo[axis];
      if (!(extent > 0)) continue;
      const double factor = bins / extent;
      std::fill(bin_box.begin(), bin_box.end(), empty_box());
      std::fill(bin_count.begin(), bin_count.end(), 0);
      for (std::uint32_t i = begin; i < end; ++i) {
        const Item& it = items_[order_[i]];
        const std::uint32_t b = bin_of(it.centroid[static_cast<std::size_t>(axis)], lo[axis], factor, bins);
        grow(bin_box[b], it.box);
        ++bin_count[b];
      }
      Box3 acc = empty_box();
      std::uint32_t count = 0;
      for (std::uint32_t b = bins - 1; b > 0; --b) {
        grow(acc, bin_box[b]);
        count += bin_count[b];
        right_area[b] = half_area(acc, scale_);
        right_count[b] = count;
      }
      acc = empty_box();
      count = 0;
      for (std::uint32_t b = 0; b + 1 < bins; ++b) {
        grow(acc, bin_box[b]);
        count += bin_count[b];
        if (count == 0 || right_count[b + 1] == 0) continue;
        const double cost = half_area(acc, scale_) * count + right_area[b + 1] * right_count[b + 1];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    const double parent_area = half_area(bounds, scale_);
    if (best_axis < 0) {
      // Every centroid coincides: split by position only when the leaf would be too large.
      if (n <= options_.max_leaf_size_hard) return begin;
      return begin + n / 2;
    }
    // SAH: traversal cost 1 against intersection cost 1 per triangle, relative to the parent's area.
    const double split_cost = 1 + (parent_area > 0 ? best_cost / parent_area : best_cost);
    if (n <= options_.max_leaf_size || (n <= options_.max_leaf_size_hard && split_cost >= n)) return begin;
    const double factor = bins / (hi[best_axis] - lo[best_axis]);
    const auto mid = std::partition(order_.begin() + begin, order_.begin() + end, [&](std::uint32_t k) {
      return bin_of(items_[k].centroid[static_cast<std::size_t>(best_axis)], lo[best_axis], factor, bins) <= best_bin;
    });
    return static_cast<std::uint32_t>(mid - order_.begin());
  }

  // The bin of a centroid: x = (c − lo)·factor clamped to [0, bins − 1] before it is converted (x may be +inf
  // or NaN when the extent is subnormal or the difference overflows; converting those is undefined).
  static std::uint32_t bin_of(double c, double lo, double factor, std::uint32_t bins) {
    const double x = (c - lo) * factor;
    if (!(x > 0)) return 0;
    if (!(x < static_cast<double>(bins))) return bins - 1;
    return static_cast<std::uint32_t>(x);
  }

  std::vector<Item> items_;
  const BvhBuildOptions& options_;
  double scale_;
  std::vector<BinaryNode>& nodes_;
  std::vector<std::uint32_t>& order_;
};

// The binary hierarchy collapsed to nodes of up to four children: a node's children are its binary
// children, with the inner one of largest surface area replaced by its own two children while fewer than
// four. Nodes in depth-first order, each parent before its children.
class Collapser {
 public:
  Collapser(const std::vector<BinaryNode>& binary, double scale, std::vector<BvhNode>& wide)
      : binary_(binary), scale_(scale), wide_(wide) {}

  // The wide node for binary node `b` (inner), and its children's; returns the depth below it (1 for a node
  // whose children are all leaves).
  int collapse(std::uint32_t b, std::uint32_t& index) {
    std::uint32_t slot_node[BvhNode::width];
    int n = 0;
    slot_node[n++] = b + 1;
    slot_node[n++] = binary_[b].first;
    while (n < BvhNode::width) {
      int widest = -1;
      double widest_area = -1;
      for (int i = 0; i < n; ++i) {
        const BinaryNode& c = binary_[slot_node[i]];
        if (c.count > 0) continue;
        const double area = half_area(c.bounds, scale_);
        if (area > widest_area) widest = i, widest_area = area;
      }
      if (widest < 0) break;
      const std::uint32_t opened = slot_node[widest];
      slot_node[widest] = opened + 1;
      slot_node[n++] = binary_[opened].first;
    }
    index = static_cast<std::uint32_t>(wide_.size());
    wide_.push_back(empty_node());
    int depth = 1;
    for (int i = 0; i < n; ++i) {
      const BinaryNode& c = binary_[slot_node[i]];
      std::uint32_t first = c.first, count = c.count;
      if (c.count == 0) depth = std::max(depth, 1 + collapse(slot_node[i], first));
      set_slot(wide_[index], i, c.bounds, first, count);
    }
    wide_[index].children = static_cast<std::uint32_t>(n);
    return depth;
  }

  static BvhNode empty_node() {
    BvhNode node{};
    const Box3 empty = empty_box();
    for (int s = 0; s < BvhNode::width; ++s) set_slot(node, s, empty, 0, 0);
    node.children = 0;
    return node;
  }

  static void set_slot(BvhNode& node, int slot, const Box3& b, std::uint32_t first, std::uint32_t count) {
    const auto s = static_cast<std::size_t>(slot);
    node.bounds[0][s] = b.lo.x, node.bounds[1][s] = b.lo.y, node.bounds[2][s] = b.lo.z;
    node.bounds[3][s] = b.hi.x, node.bounds[4][s] = b.hi.y, node.bounds[5][s] = b.hi.z;
    node.first[s] = first;
    node.count[s] = count;
  }

 private:
  const std::vector<BinaryNode>& binary_;
  double scale_;
  std::vector<BvhNode>& wide_;
};

}  // namespace

MeshBvh::MeshBvh(const Mesh& mesh, const BvhBuildOptions& options) {
  if (const auto problem = validate(mesh)) throw invalid_input("mesh: " + *problem);
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max())
    throw invalid_input("mesh: more than 2^32 - 1 triangles");
  std::vector<Box3> boxes(mesh.triangles.size());
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const Triangle t = mesh.triangle(k);
    Box3 b{t.a, t.a};
    grow(b, {t.b, t.b});
    grow(b, {t.c, t.c});
    boxes[k] = b;
  }
  build(std::move(boxes), options);
}

MeshBvh::MeshBvh(std::span<const Box3> boxes, const BvhBuildOptions& options) {
  if (boxes.size() > std::numeric_limits<std::uint32_t>::max()) throw invalid_input("bvh: more than 2^32 - 1 boxes");
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const Box3& b = boxes[k];
    const double c[6] = {b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z};
    for (double x : c)
      if (!std::isfinite(x)) throw invalid_input("bvh: box " + std::to_string(k) + " is not finite");
    if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z))
      throw invalid_input("bvh: box " + std::to_string(k) + " has lo above hi");
  }
  build(std::vector<Box3>(boxes.begin(), boxes.end()), options);
}

void MeshBvh::build(std::vector<Box3> boxes, const BvhBuildOptions& options) {
  bounds_ = empty_box();
  const std::size_t n = boxes.size();
  if (n == 0) return;
  // The scale 2^-e with 2^e above every |coordinate|: centroids and areas in scaled coordinates cannot
  // overflow (they steer the split choice only).
  double largest = 0;
  for (const Box3& b : boxes)
    largest = std::max({largest, std::fabs(b.lo.x), std::fabs(b.lo.y), std::fabs(b.lo.z), std::fabs(b.hi.x),
                        std::fabs(b.hi.y), std::fabs(b.hi.z)});
  int e = 0;
  (void)std::frexp(largest, &e);
  const double scale = std::ldexp(1.0, -e);
  std::vector<Item> items(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Box3& b = boxes[k];
    items[k].box = b;
    items[k].centroid = {b.lo.x * scale * 0.5 + b.hi.x * scale * 0.5, b.lo.y * scale * 0.5 + b.hi.y * scale * 0.5,
                         b.lo.z * scale * 0.5 + b.hi.z * scale * 0.5};
  }
  order_.resize(n);
  for (std::size_t k = 0; k < n; ++k) order_[k] = static_cast<std::uint32_t>(k);
  std::vector<BinaryNode> binary;
  binary.reserve(2 * n / std::max<std::uint32_t>(1, options.max_leaf_size) + 1);
  Builder builder(std::move(items), options, scale, binary, order_);
  const int binary_depth = builder.build(0, static_cast<std::uint32_t>(n), 0);
  bounds_ = binary[0].bounds;
  nodes_.reserve(binary.size() / 2 + 1);
  if (binary[0].count > 0) {  // the whole mesh is one leaf: a root with one child
    nodes_.push_back(Collapser::empty_node());
    Collapser::set_slot(nodes_[0], 0, binary[0].bounds, binary[0].first, binary[0].count);
    nodes_[0].children = 1;
    depth_ = 1;
  } else {
    std::uint32_t root = 0;
    depth_ = Collapser(binary, scale, nodes_).collapse(0, root);
  }
  (void)binary_depth;  // ≥ depth_ − 1; the wide depth is what bounds the walk's stack
  nodes_.shrink_to_fit();
  const Box3& root = bounds_;
  magnitude_ = {std::max(std::fabs(root.lo.x), std::fabs(root.hi.x)), std::max(std::fabs(root.lo.y), std::fabs(root.hi.y)),
                std::max(std::fabs(root.lo.z), std::fabs(root.hi.z))};
}

namespace mesh_detail {

const BvhWalkFunctions& bvh_walk_functions() noexcept {
  static const BvhWalkFunctions functions = [] {
#if defined(RAYKERNEL_BVH_WALK_AVX2)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v3")) return BvhWalkFunctions{avx2::next_leaf, avx2::node_entries};
#endif
    return BvhWalkFunctions{portable::next_leaf, portable::node_entries};
  }();
  return functions;
}

void start_walk(detail::BvhWalk& w, const MeshBvh& bvh, const Ray& ray, double t_min, double t_max) noexcept {
  w.bvh = &bvh;
  w.t_min = t_min;
  w.t_max = t_max;
  set_walk_ray(w, make_slabs(ray, bvh.magnitude()));
  w.stack_size = 0;
  w.boxes_tested = 0;
  if (!bvh.nodes().empty()) w.stack[static_cast<std::size_t>(w.stack_size++)] = {0, 0, t_min};
}

}  // namespace mesh_detail

BvhRayTraversal::Slabs ray_box_slabs(const Ray& ray, const std::array<double, 3>& magnitude) {
  return detail::in_default_fp_environment([&] { return mesh_detail::make_slabs(ray, magnitude); });
}

std::optional<double> ray_box_entry(const BvhRayTraversal::Slabs& slabs, const Box3& box, double t_min, double t_max) noexcept {
  return detail::in_default_fp_environment([&]() -> std::optional<double> {
    double entry = 0;
    if (mesh_detail::ray_box_entry(slabs, box, t_min, t_max, entry)) return entry;
    return std::nullopt;
  });
}

unsigned ray_box_entries(const BvhRayTraversal::Slabs& slabs, const BvhNode& node, double t_min, double t_max,
                         std::array<double, BvhNode::width>& entries) noexcept {
  return detail::in_default_fp_environment([&] {
    detail::BvhWalk w;
    mesh_detail::set_walk_ray(w, slabs);
    return mesh_detail::bvh_walk_functions().node_entries(w, node, t_min, t_max, entries.data());
  });
}

BvhRayTraversal::BvhRayTraversal(const MeshBvh& bvh, const Ray& ray, double t_min, double t_max) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.z)) throw invalid_input("ray origin is not finite");
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z)) throw invalid_input("ray direction is not finite");
  if (d.x == 0 && d.y == 0 && d.z == 0) throw invalid_input("ray direction is zero");
  if (!(t_min >= 0 && t_min <= t_max)) throw invalid_input("ray range: need 0 <= t_min <= t_max");
  detail::in_default_fp_environment([&] { mesh_detail::start_walk(walk_, bvh, ray, t_min, t_max); });
}

std::optional<BvhLeaf> BvhRayTraversal::next(double t_upper) {
  return detail::in_default_fp_environment([&]() -> std::optional<BvhLeaf> {
    BvhLeaf leaf;
    if (mesh_detail::bvh_walk_functions().next_leaf(walk_, t_upper, leaf)) return leaf;
    return std::nullopt;
  });
}

BvhRayTraversal::Slabs BvhRayTraversal::slabs() const noexcept {
  Slabs s{};
  for (std::size_t k = 0; k < 3; ++k) {
    s.origin[k] = walk_.origin[k];
    s.inverse_direction[k] = walk_.inverse_direction[k];
    s.enters_at_hi[k] = walk_.near_face[k] != k;
  }
  return s;
}

}  // namespace raykernel

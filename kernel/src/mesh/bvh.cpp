// MeshBvh (binned SAH build) and BvhRayTraversal (nearest-first walk with the certified box test of
// ray_box.hpp).
#include "mesh/ray_box.hpp"

#include <raykernel/bvh.hpp>

#include <algorithm>
#include <utility>
#include <cmath>

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

class Builder {
 public:
  Builder(std::vector<Item> items, const BvhBuildOptions& options, double scale, std::vector<BvhNode>& nodes,
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
      nodes_[index] = {bounds, begin, n, 0};
      return depth;
    };
    if (n <= 1 || depth >= MeshBvh::max_depth) return make_leaf();
    const auto [mid, axis] = split(begin, end, bounds, centroid_bounds);
    if (mid == begin || mid == end) return make_leaf();
    const int left_depth = build(begin, mid, depth + 1);
    const auto right = static_cast<std::uint32_t>(nodes_.size());
    const int right_depth = build(mid, end, depth + 1);
    nodes_[index] = {bounds, right, 0, axis};
    return std::max(left_depth, right_depth);
  }

 private:
  // Partitions [begin, end) by the cheapest binned SAH split; returns the split position, or begin/end for
  // "make a leaf".
  std::pair<std::uint32_t, std::uint8_t> split(std::uint32_t begin, std::uint32_t end, const Box3& bounds, const Box3& cb) {
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
      if (n <= options_.max_leaf_size_hard) return {begin, 0};
      return {begin + n / 2, 0};
    }
    // SAH: traversal cost 1 against intersection cost 1 per triangle, relative to the parent's area.
    const double split_cost = 1 + (parent_area > 0 ? best_cost / parent_area : best_cost);
    if (n <= options_.max_leaf_size || (n <= options_.max_leaf_size_hard && split_cost >= n)) return {begin, 0};
    const double factor = bins / (hi[best_axis] - lo[best_axis]);
    const auto mid = std::partition(order_.begin() + begin, order_.begin() + end, [&](std::uint32_t k) {
      return bin_of(items_[k].centroid[static_cast<std::size_t>(best_axis)], lo[best_axis], factor, bins) <= best_bin;
    });
    return {static_cast<std::uint32_t>(mid - order_.begin()), static_cast<std::uint8_t>(best_axis)};
  }

  static std::uint32_t bin_of(double c, double lo, double factor, std::uint32_t bins) {
    const double x = (c - lo) * factor;
    if (!(x > 0)) return 0;
    return std::min(bins - 1, static_cast<std::uint32_t>(x));
  }

  std::vector<Item> items_;
  const BvhBuildOptions& options_;
  double scale_;
  std::vector<BvhNode>& nodes_;
  std::vector<std::uint32_t>& order_;
};

}  // namespace

MeshBvh::MeshBvh(const Mesh& mesh, const BvhBuildOptions& options) {
  if (const auto problem = validate(mesh)) throw invalid_input("mesh: " + *problem);
  const std::size_t n = mesh.triangles.size();
  if (n == 0) return;
  // The scale 2^-e with 2^e above every |coordinate|: centroids and areas in scaled coordinates cannot
  // overflow (they steer the split choice only).
  double largest = 0;
  for (const Vec3& v : mesh.vertices) largest = std::max({largest, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  int e = 0;
  (void)std::frexp(largest, &e);
  const double scale = std::ldexp(1.0, -e);
  std::vector<Item> items(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Triangle t = mesh.triangle(k);
    Box3 b{t.a, t.a};
    grow(b, {t.b, t.b});
    grow(b, {t.c, t.c});
    items[k].box = b;
    items[k].centroid = {b.lo.x * scale * 0.5 + b.hi.x * scale * 0.5, b.lo.y * scale * 0.5 + b.hi.y * scale * 0.5,
                         b.lo.z * scale * 0.5 + b.hi.z * scale * 0.5};
  }
  order_.resize(n);
  for (std::size_t k = 0; k < n; ++k) order_[k] = static_cast<std::uint32_t>(k);
  nodes_.reserve(2 * n / std::max<std::uint32_t>(1, options.max_leaf_size) + 1);
  Builder builder(std::move(items), options, scale, nodes_, order_);
  depth_ = builder.build(0, static_cast<std::uint32_t>(n), 0);
  nodes_.shrink_to_fit();
  const Box3& root = nodes_[0].bounds;
  magnitude_ = {std::max(std::fabs(root.lo.x), std::fabs(root.hi.x)), std::max(std::fabs(root.lo.y), std::fabs(root.hi.y)),
                std::max(std::fabs(root.lo.z), std::fabs(root.hi.z))};
}

BvhRayTraversal::Slabs ray_box_slabs(const Ray& ray, const std::array<double, 3>& magnitude) {
  return mesh_detail::make_slabs(ray, magnitude);
}

std::optional<double> ray_box_entry(const BvhRayTraversal::Slabs& slabs, const Box3& box, double t_min, double t_max) noexcept {
  double entry = 0;
  if (mesh_detail::ray_box_entry(slabs, box, t_min, t_max, entry)) return entry;
  return std::nullopt;
}

BvhRayTraversal::BvhRayTraversal(const MeshBvh& bvh, const Ray& ray, double t_min, double t_max)
    : bvh_(&bvh), t_min_(t_min), t_max_(t_max) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.z)) throw invalid_input("ray origin is not finite");
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z)) throw invalid_input("ray direction is not finite");
  if (d.x == 0 && d.y == 0 && d.z == 0) throw invalid_input("ray direction is zero");
  if (!(t_min >= 0 && t_min <= t_max)) throw invalid_input("ray range: need 0 <= t_min <= t_max");
  slabs_ = mesh_detail::make_slabs(ray, bvh.magnitude());
  if (bvh.nodes().empty()) return;
  double entry = 0;
  ++boxes_tested_;
  if (mesh_detail::ray_box_entry(slabs_, bvh.nodes()[0].bounds, t_min_, t_max_, entry)) stack_[stack_size_++] = {0, entry};
}

std::optional<BvhLeaf> BvhRayTraversal::next(double t_upper) {
  const double t1 = std::min(t_max_, t_upper);
  const std::span<const BvhNode> nodes = bvh_->nodes();
  while (stack_size_ > 0) {
    Pending current = stack_[--stack_size_];
    if (current.entry > t1) continue;  // the box starts beyond the caller's bound: skip it
    while (true) {
      const BvhNode& node = nodes[current.node];
      if (node.count > 0) return BvhLeaf{bvh_->triangle_order().subspan(node.first, node.count), current.entry};
      const std::uint32_t left = current.node + 1, right = node.first;
      double e_left = 0, e_right = 0;
      boxes_tested_ += 2;
      const bool hit_left = mesh_detail::ray_box_entry(slabs_, nodes[left].bounds, t_min_, t1, e_left);
      const bool hit_right = mesh_detail::ray_box_entry(slabs_, nodes[right].bounds, t_min_, t1, e_right);
      if (hit_left && hit_right) {
        const bool left_first = e_left <= e_right;
        stack_[stack_size_++] = left_first ? Pending{right, e_right} : Pending{left, e_left};
        current = left_first ? Pending{left, e_left} : Pending{right, e_right};
      } else if (hit_left) {
        current = {left, e_left};
      } else if (hit_right) {
        current = {right, e_right};
      } else {
        break;
      }
      // The next node's children are tested next: fetch the far one (the near one is adjacent).
      const BvhNode& next_node = nodes[current.node];
      if (next_node.count == 0) __builtin_prefetch(&nodes[next_node.first]);
    }
  }
  return std::nullopt;
}

}  // namespace raykernel

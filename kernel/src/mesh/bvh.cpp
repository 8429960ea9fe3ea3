// MeshBvh (binned SAH build of a binary hierarchy on every core, collapsed to eight children per node, boxes
// rounded outward to binary32) and BvhRayTraversal (nearest-first walk with the certified box test of
// ray_box.hpp, bvh_walk.hpp).
#include "core/fp_requirements.hpp"
#include "core/fp_environment.hpp"
#include "mesh/bvh_walk.hpp"
#include "box/ray_box.hpp"

#include <raykernel/bvh.hpp>
#include <raykernel/parallel.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>
#include <utility>

namespace raykernel {
namespace {

Box3 empty_box() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

void grow(Box3& b, const Box3& o) {
  b.lo = {std::min(b.lo.x, o.lo.x), std::min(b.lo.y, o.lo.y), std::min(b.lo.z, o.lo.z)};
  b.hi = {std::max(b.hi.x, o.hi.x), std::max(b.hi.y, o.hi.y), std::max(b.hi.z, o.hi.z)};
}

// The largest binary32 ≤ x and the smallest ≥ x, for finite x, in the default floating-point environment
// (MeshBvh::build runs in it): RN32(x) is within one binary32 step of x, so one step towards x from a rounding
// on the wrong side lands on the right side (±inf beyond the binary32 range: RN32 gives ±inf only there, and
// a step from it gives ±FLT_MAX, beyond which x then lies).
float round_down(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float round_up(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// A box in binary32 (the build's: each primitive's box rounded outward, and their min/max). Rounding down and
// up are monotone, so the min/max of rounded boxes is the rounded min/max: a node's FloatBox is its exact box
// rounded outward, what BvhNode stores.
struct FloatBox {
  std::array<float, 3> lo, hi;
};

FloatBox empty_float_box() {
  constexpr float inf = std::numeric_limits<float>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

FloatBox outward(const Box3& b) {
  return {{round_down(b.lo.x), round_down(b.lo.y), round_down(b.lo.z)}, {round_up(b.hi.x), round_up(b.hi.y), round_up(b.hi.z)}};
}

// Surface area of a box (half of it), in the scaled coordinates; only compared, never certified (beyond the
// binary32 range it is inf or NaN, which no comparison prefers).
double half_area(const FloatBox& b, double scale) {
  if (b.lo[0] > b.hi[0]) return 0;
  const double ex = (b.hi[0] * scale - b.lo[0] * scale), ey = (b.hi[1] * scale - b.lo[1] * scale),
               ez = (b.hi[2] * scale - b.lo[2] * scale);
  return ex * ey + ey * ez + ez * ex;
}

// The build's vectors: a box's three lower or upper bounds in lanes 0–2 (GCC vector extensions: SSE on x86-64,
// the same operations elsewhere).
using F4 = float __attribute__((vector_size(16)));
using I4 = std::int32_t __attribute__((vector_size(16)));

[[gnu::always_inline]] inline F4 min4(F4 a, F4 b) { return a < b ? a : b; }
[[gnu::always_inline]] inline F4 max4(F4 a, F4 b) { return a > b ? a : b; }

// One primitive during the build: its box rounded outward to binary32, and its index (in the bits of hi's lane 3).
// The build partitions these in place (32 bytes each), so each node's primitives lie side by side.
struct Ref {
  F4 lo;  // lo.x, lo.y, lo.z, 0
  F4 hi;  // hi.x, hi.y, hi.z, the index's bits
  [[nodiscard]] std::uint32_t index() const { return static_cast<std::uint32_t>(std::bit_cast<I4>(hi)[3]); }
  [[nodiscard]] F4 upper() const { return std::bit_cast<F4>(std::bit_cast<I4>(hi) & I4{-1, -1, -1, 0}); }
  // The box's centre (only the split choice uses it): ±inf when the box reaches beyond the binary32 range on one
  // side, 0 when on both (never NaN, whose min/max would depend on the order the bins are added up in).
  [[nodiscard]] F4 centroid() const {
    const F4 c = lo * 0.5f + upper() * 0.5f;
    return c == c ? c : F4{};
  }
};

Ref make_ref(const FloatBox& b, std::uint32_t index) {
  Ref r;
  r.lo = F4{b.lo[0], b.lo[1], b.lo[2], 0};
  r.hi = F4{b.hi[0], b.hi[1], b.hi[2], 0};
  r.hi = std::bit_cast<F4>(std::bit_cast<I4>(r.hi) | I4{0, 0, 0, static_cast<std::int32_t>(index)});
  return r;
}

// A node's bounds and its centroids' bounds (lanes 0–2).
struct Bounds {
  F4 lo, hi, clo, chi;
  static Bounds empty() {
    constexpr float inf = std::numeric_limits<float>::infinity();
    return {F4{inf, inf, inf, inf}, F4{-inf, -inf, -inf, -inf}, F4{inf, inf, inf, inf}, F4{-inf, -inf, -inf, -inf}};
  }
  void grow(const Bounds& o) {
    lo = min4(lo, o.lo), hi = max4(hi, o.hi), clo = min4(clo, o.clo), chi = max4(chi, o.chi);
  }
  // One primitive's box [rlo, rhi] and centroid c.
  void add(F4 rlo, F4 rhi, F4 c) { lo = min4(lo, rlo), hi = max4(hi, rhi), clo = min4(clo, c), chi = max4(chi, c); }
  [[nodiscard]] FloatBox box() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
};

// Surface area of a box (half of it), in the scaled coordinates; only compared, never certified.
double half_area(const Bounds& b, double scale) { return half_area(b.box(), scale); }

// A node of the binary hierarchy the build makes first (depth-first: an inner node's first child is the next
// node).
struct BinaryNode {
  FloatBox bounds;      // the exact min/max of the vertex doubles of every triangle below, rounded outward
  std::uint32_t first;  // leaf: first position in the triangle order; inner: index of the second child
  std::uint32_t count;  // leaf: number of triangles (≥ 1); inner: 0
};

// A split: the position (begin: "make a leaf"), and the two sides' bounds when the bins gave them.
struct Split {
  std::uint32_t mid;
  bool bounded;
  Bounds left, right;
  static Split at(std::uint32_t mid) {
    Split s;
    s.mid = mid;
    s.bounded = false;
    return s;
  }
};

// The binned SAH build of the subtree over refs[begin, end) into `nodes` (appended depth-first; inner nodes'
// `first` index `nodes`). One Builder per thread: the bins are its scratch space. Each node's bounds come from
// its parent's bins (the union of the bins on its side), so the primitives are read once per level, to bin
// them on all three axes at once.
class Builder {
 public:
  // `parallel`: bin large nodes on two threads (the top levels' builder only: the subtrees' builders already run
  // one per thread).
  Builder(std::vector<Ref>& refs, const BvhBuildOptions& options, double scale, std::vector<BinaryNode>& nodes,
          bool parallel = false)
      : refs_(refs), options_(options), scale_(scale), nodes_(nodes), parallel_(parallel), bins_(std::clamp<std::uint32_t>(options.bins, 2, 1u << 20)),
        bins_data_(3 * static_cast<std::size_t>(bins_)), right_area_(bins_), right_count_(bins_) {}

  // The bounds of refs[begin, end) (one pass over them).
  [[nodiscard]] Bounds measure(std::uint32_t begin, std::uint32_t end) const {
    Bounds b = Bounds::empty();
    for (std::uint32_t i = begin; i < end; ++i) {
      const Ref& r = refs_[i];
      b.add(r.lo, r.upper(), r.centroid());
    }
    return b;
  }

  // Returns the depth of the subtree's deepest leaf.
  int build(std::uint32_t begin, std::uint32_t end, int depth, const Bounds& bounds) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    const Split s = split_or_leaf(begin, end, depth, bounds);
    if (s.mid == begin) {
      nodes_[index] = {bounds.box(), begin, end - begin};
      return depth;
    }
    const int left_depth = build(begin, s.mid, depth + 1, s.bounded ? s.left : measure(begin, s.mid));
    const auto right = static_cast<std::uint32_t>(nodes_.size());
    const int right_depth = build(s.mid, end, depth + 1, s.bounded ? s.right : measure(s.mid, end));
    nodes_[index] = {bounds.box(), right, 0};
    return std::max(left_depth, right_depth);
  }

  Split split_or_leaf(std::uint32_t begin, std::uint32_t end, int depth, const Bounds& bounds) {
    // A node of at most max_leaf_size (and max_leaf_size_hard) primitives is a leaf whatever the bins say:
    // the split below would decide so after binning them.
    if (end - begin <= std::max<std::uint32_t>(1, std::min(options_.max_leaf_size, options_.max_leaf_size_hard)) ||
        depth >= MeshBvh::max_depth)
      return Split::at(begin);
    Split s = split(begin, end, bounds);
    if (s.mid == end) s.mid = begin;
    return s;
  }

 private:
  // A bin: the bounds of its primitives' boxes (lanes 0–2) and their number. (The centroids' bounds of the two
  // sides are gathered by the partition, which reads every centroid anyway.)
  struct Bin {
    F4 lo, hi;
    std::uint32_t count;
    static Bin empty() {
      constexpr float inf = std::numeric_limits<float>::infinity();
      return {F4{inf, inf, inf, inf}, F4{-inf, -inf, -inf, -inf}, 0};
    }
    void grow(const Bin& o) { lo = min4(lo, o.lo), hi = max4(hi, o.hi), count += o.count; }
    [[nodiscard]] FloatBox box() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
  };

  // The bins of a centroid on the three axes: x = (c − lo)·factor clamped to [0, bins − 1] before it is
  // converted (x may be ±inf or NaN when an extent is tiny or a centroid infinite; the clamp sends NaN to 0).
  [[gnu::always_inline]] static I4 bins_of(F4 c, F4 lo, F4 factor, F4 top) {
    F4 x = (c - lo) * factor;
    x = x > F4{} ? x : F4{};
    x = x < top ? x : top;
    return __builtin_convertvector(x, I4);
  }

  static constexpr std::uint32_t parallel_binning_from = 1u << 16;

  // Bins refs[begin, end) on the three axes: bins[axis·count + bin] (count bins per axis).
  void bin_range(std::uint32_t begin, std::uint32_t end, std::uint32_t count, F4 lo, F4 factor, F4 top, Bin* bins) const {
    for (std::uint32_t i = begin; i < end; ++i) {
      const Ref& r = refs_[i];
      const F4 rlo = r.lo, rhi = r.upper();
      const I4 b = bins_of(r.centroid(), lo, factor, top);
      for (int axis = 0; axis < 3; ++axis) {
        Bin& bin = bins[static_cast<std::size_t>(axis) * count + static_cast<std::uint32_t>(b[axis])];
        bin.lo = min4(bin.lo, rlo), bin.hi = max4(bin.hi, rhi);
        ++bin.count;
      }
    }
  }

  // into[b] ∪= from[b] for the first `all` bins (unions and sums: the same bins as binning both parts' refs).
  static void merge(Bin* into, const Bin* from, std::size_t all) {
    for (std::size_t b = 0; b < all; ++b) {
      into[b].grow(from[b]);
    }
  }

  // Partitions [begin, end) by the cheapest binned SAH split; returns the split position (begin or end for
  // "make a leaf") and the two sides' bounds. The three axes are binned in one pass over the primitives.
  Split split(std::uint32_t begin, std::uint32_t end, const Bounds& bounds) {
    const std::uint32_t n = end - begin;
    // No more bins than primitives (at least 8): a small node's split costs its bins' clearing and sweeps, not
    // its primitives, and more bins than centroids add few distinct partitions.
    const std::uint32_t bins = std::min(bins_, std::max<std::uint32_t>(8, n));
    const F4 lo = bounds.clo, extent = bounds.chi - bounds.clo;
    F4 factor{};
    bool split_axis[3];
    for (int axis = 0; axis < 3; ++axis) {
      split_axis[axis] = extent[axis] > 0 && extent[axis] <= std::numeric_limits<float>::max();
      if (split_axis[axis]) factor[axis] = static_cast<float>(bins) / extent[axis];
    }
    const F4 top = F4{} + static_cast<float>(bins - 1);
    Bin* const per_axis[3] = {&bins_data_[0], &bins_data_[bins], &bins_data_[2 * static_cast<std::size_t>(bins)]};
    const std::size_t all = 3 * static_cast<std::size_t>(bins);
    std::fill_n(bins_data_.begin(), all, Bin::empty());
    if (parallel_ && n >= parallel_binning_from && thread_count(options_.threads) >= 2) {
      // A large node (the top levels, which run before the subtrees are handed out): its two halves binned on
      // two threads, the second into its own bins, then added up (unions and sums: the same bins).
      std::vector<Bin> second(all, Bin::empty());
      const std::uint32_t half = begin + n / 2;
      run_parts(2, 2, [&](std::size_t k) {
        detail::in_default_fp_environment([&] {
          if (k == 0) bin_range(begin, half, bins, lo, factor, top, bins_data_.data());
          else bin_range(half, end, bins, lo, factor, top, second.data());
        });
      });
      merge(bins_data_.data(), second.data(), all);
    } else {
      bin_range(begin, end, bins, lo, factor, top, bins_data_.data());
    }
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1;
    std::uint32_t best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (!split_axis[axis]) continue;
      const Bin* bin = per_axis[axis];
      Bin acc = Bin::empty();
      for (std::uint32_t b = bins - 1; b > 0; --b) {
        acc.grow(bin[b]);
        right_area_[b] = half_area(acc.box(), scale_);
        right_count_[b] = acc.count;
      }
      acc = Bin::empty();
      for (std::uint32_t b = 0; b + 1 < bins; ++b) {
        acc.grow(bin[b]);
        const std::uint32_t count = acc.count;
        if (count == 0 || right_count_[b + 1] == 0) continue;
        const double cost = half_area(acc.box(), scale_) * count + right_area_[b + 1] * right_count_[b + 1];
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
      if (n <= options_.max_leaf_size_hard) return Split::at(begin);
      return Split::at(begin + n / 2);
    }
    // SAH: traversal cost 1 against intersection cost 1 per triangle, relative to the parent's area.
    const double split_cost = 1 + (parent_area > 0 ? best_cost / parent_area : best_cost);
    if (n <= options_.max_leaf_size || (n <= options_.max_leaf_size_hard && split_cost >= n)) return Split::at(begin);
    Split s = Split::at(0);
    s.bounded = true;
    s.left = s.right = Bounds::empty();
    Bin side[2] = {Bin::empty(), Bin::empty()};
    for (std::uint32_t b = 0; b < bins; ++b) side[b <= best_bin ? 0 : 1].grow(per_axis[best_axis][b]);
    const auto axis = static_cast<std::size_t>(best_axis);
    // (the predicate is applied once to each ref: it gathers each side's centroid bounds too)
    const auto mid = std::partition(refs_.begin() + begin, refs_.begin() + end, [&](const Ref& r) {
      const F4 c = r.centroid();
      const bool left = static_cast<std::uint32_t>(bins_of(c, lo, factor, top)[axis]) <= best_bin;
      Bounds& b = left ? s.left : s.right;
      b.clo = min4(b.clo, c), b.chi = max4(b.chi, c);
      return left;
    });
    s.left.lo = side[0].lo, s.left.hi = side[0].hi;
    s.right.lo = side[1].lo, s.right.hi = side[1].hi;
    s.mid = static_cast<std::uint32_t>(mid - refs_.begin());
    return s;
  }

  std::vector<Ref>& refs_;
  const BvhBuildOptions& options_;
  double scale_;
  std::vector<BinaryNode>& nodes_;
  bool parallel_;
  std::uint32_t bins_;
  std::vector<Bin> bins_data_;
  std::vector<double> right_area_;
  std::vector<std::uint32_t> right_count_;
};

// The binary hierarchy over every ref, on up to options.threads threads: the top levels' splits on this thread
// (a tree of Top entries), the subtrees below them as tasks handed out to the threads, each built into its own
// list, then everything joined in depth-first order with the inner nodes' indices moved — the nodes one thread
// builds, bit for bit (deterministic whatever the thread count).
class ParallelBuild {
 public:
  ParallelBuild(std::vector<Ref>& refs, const BvhBuildOptions& options, double scale)
      : refs_(refs), options_(options), scale_(scale) {}

  std::vector<BinaryNode> run() {
    const auto n = static_cast<std::uint32_t>(refs_.size());
    const unsigned threads = thread_count(options_.threads);
    // Eight subtrees for two threads: the SAH's splits are uneven, and run_parts hands the next one to whichever
    // thread is free.
    const int levels = threads < 2 || n < parallel_from ? 0 : 3;
    const int root = top(0, n, 0, levels, Builder(refs_, options_, scale_, unused_).measure(0, n));
    std::vector<std::vector<BinaryNode>> built(tasks_.size());
    run_parts(tasks_.size(), threads, [&](std::size_t k) {
      detail::in_default_fp_environment([&] {
        const Task& t = tasks_[k];
        std::vector<BinaryNode> nodes;
        nodes.reserve(2 * (t.end - t.begin) / std::max<std::uint32_t>(1, options_.max_leaf_size) + 1);
        Builder(refs_, options_, scale_, nodes).build(t.begin, t.end, t.depth, t.bounds);
        built[k] = std::move(nodes);
      });
    });
    std::size_t total = tops_.size();
    for (const auto& b : built) total += b.size();
    std::vector<BinaryNode> nodes;
    nodes.reserve(total);
    join(root, built, nodes);
    return nodes;
  }

 private:
  static constexpr std::uint32_t parallel_from = 1u << 14;
  struct Task {
    std::uint32_t begin, end;
    int depth;
    Bounds bounds;
  };
  struct Top {
    BinaryNode node;  // a leaf, or an inner node whose children are tops `left` and `right`
    int left = -1, right = -1;
    int task = -1;    // or the subtree of tasks_[task]
  };

  int top(std::uint32_t begin, std::uint32_t end, int depth, int levels, const Bounds& bounds) {
    const int index = static_cast<int>(tops_.size());
    tops_.emplace_back();
    if (depth >= levels) {
      tops_[static_cast<std::size_t>(index)].task = static_cast<int>(tasks_.size());
      tasks_.push_back({begin, end, depth, bounds});
      return index;
    }
    Builder builder(refs_, options_, scale_, unused_, true);
    const Split s = builder.split_or_leaf(begin, end, depth, bounds);
    if (s.mid == begin) {
      tops_[static_cast<std::size_t>(index)].node = {bounds.box(), begin, end - begin};
      return index;
    }
    const int left = top(begin, s.mid, depth + 1, levels, s.bounded ? s.left : builder.measure(begin, s.mid));
    const int right = top(s.mid, end, depth + 1, levels, s.bounded ? s.right : builder.measure(s.mid, end));
    Top& t = tops_[static_cast<std::size_t>(index)];
    t.node = {bounds.box(), 0, 0};
    t.left = left;
    t.right = right;
    return index;
  }

  void join(int index, const std::vector<std::vector<BinaryNode>>& built, std::vector<BinaryNode>& nodes) const {
    const Top& t = tops_[static_cast<std::size_t>(index)];
    if (t.task >= 0) {
      const auto offset = static_cast<std::uint32_t>(nodes.size());
      for (BinaryNode node : built[static_cast<std::size_t>(t.task)]) {
        if (node.count == 0) node.first += offset;
        nodes.push_back(node);
      }
      return;
    }
    const std::size_t at = nodes.size();
    nodes.push_back(t.node);
    if (t.node.count > 0) return;
    join(t.left, built, nodes);
    nodes[at].first = static_cast<std::uint32_t>(nodes.size());
    join(t.right, built, nodes);
  }

  std::vector<Ref>& refs_;
  const BvhBuildOptions& options_;
  double scale_;
  std::vector<BinaryNode> unused_;  // the top levels' builders append nothing
  std::vector<Top> tops_;
  std::vector<Task> tasks_;
};

// The binary hierarchy collapsed to nodes of up to eight children: a node's children are its binary
// children, with the inner one of largest surface area replaced by its own two children while fewer than
// eight. Nodes in depth-first order, each parent before its children. Without `wide`, the same walk only
// counts the nodes (nodes()), so that the storage is reserved exactly.
class Collapser {
 public:
  Collapser(const std::vector<BinaryNode>& binary, double scale, detail::LargeVector<BvhNode>* wide)
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
    index = nodes_++;
    if (wide_ != nullptr) wide_->push_back(empty_node());
    int depth = 1;
    for (int i = 0; i < n; ++i) {
      const BinaryNode& c = binary_[slot_node[i]];
      std::uint32_t first = c.first, count = c.count;
      if (c.count == 0) depth = std::max(depth, 1 + collapse(slot_node[i], first));
      if (wide_ != nullptr) set_slot((*wide_)[index], i, c.bounds, first, count);
    }
    return depth;
  }

  static BvhNode empty_node() {
    BvhNode node{};
    const FloatBox empty = empty_float_box();
    for (int s = 0; s < BvhNode::width; ++s) set_slot(node, s, empty, 0, 0);
    return node;
  }

  static void set_slot(BvhNode& node, int slot, const FloatBox& b, std::uint32_t first, std::uint32_t count) {
    const auto s = static_cast<std::size_t>(slot);
    for (std::size_t k = 0; k < 3; ++k) node.bounds[k][s] = b.lo[k], node.bounds[k + 3][s] = b.hi[k];
    node.first[s] = first;
    node.count[s] = count;
  }

 private:
  const std::vector<BinaryNode>& binary_;
  double scale_;
  detail::LargeVector<BvhNode>* wide_;
  std::uint32_t nodes_ = 0;

 public:
  [[nodiscard]] std::uint32_t nodes() const noexcept { return nodes_; }
};

}  // namespace

MeshBvh::MeshBvh(const Mesh& mesh, const BvhBuildOptions& options) {
  if (const auto problem = validate(mesh)) throw invalid_input("mesh: " + *problem);
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max())
    throw invalid_input("mesh: more than 2^32 - 1 triangles");
  const BoxSource triangle_box = [](const void* source, std::size_t k) {
    const Triangle t = static_cast<const Mesh*>(source)->triangle(k);
    Box3 b{t.a, t.a};
    grow(b, {t.b, t.b});
    grow(b, {t.c, t.c});
    return b;
  };
  detail::in_default_fp_environment([&] { build(mesh.triangles.size(), triangle_box, &mesh, options); });
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
  const BoxSource stored = [](const void* source, std::size_t k) { return static_cast<const Box3*>(source)[k]; };
  detail::in_default_fp_environment([&] { build(boxes.size(), stored, boxes.data(), options); });
}

void MeshBvh::build(std::size_t n, BoxSource box_of, const void* source, const BvhBuildOptions& options) {
  bounds_ = empty_box();
  if (n == 0) return;
  // The refs, in parts on every thread (each part's exact bounds, then their union).
  std::vector<Ref> refs(n);
  constexpr std::size_t part_size = std::size_t{1} << 16;
  const std::size_t parts = (n + part_size - 1) / part_size;
  std::vector<Box3> part_bounds(parts, empty_box());
  const auto in_parts = [&](const auto& body) {
    run_parts(parts, options.threads, [&](std::size_t p) {
      detail::in_default_fp_environment([&] { body(p, p * part_size, std::min(n, (p + 1) * part_size)); });
    });
  };
  in_parts([&](std::size_t p, std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to; ++k) {
      const Box3 b = box_of(source, k);
      grow(part_bounds[p], b);
      refs[k] = make_ref(outward(b), static_cast<std::uint32_t>(k));
    }
  });
  for (const Box3& b : part_bounds) grow(bounds_, b);
  // The scale 2^-e with 2^e above every |coordinate|: areas in scaled coordinates cannot overflow (they steer the
  // split choice only).
  const double largest = std::max({std::fabs(bounds_.lo.x), std::fabs(bounds_.lo.y), std::fabs(bounds_.lo.z),
                                   std::fabs(bounds_.hi.x), std::fabs(bounds_.hi.y), std::fabs(bounds_.hi.z)});
  int e = 0;
  (void)std::frexp(largest, &e);
  const double scale = std::ldexp(1.0, -e);
  const std::vector<BinaryNode> binary = ParallelBuild(refs, options, scale).run();
  order_.resize(n);
  in_parts([&](std::size_t, std::size_t from, std::size_t to) {
    for (std::size_t k = from; k < to; ++k) order_[k] = refs[k].index();
  });
  std::vector<Ref>().swap(refs);
  if (binary[0].count > 0) {  // the whole mesh is one leaf: a root with one child
    nodes_.push_back(Collapser::empty_node());
    Collapser::set_slot(nodes_[0], 0, binary[0].bounds, binary[0].first, binary[0].count);
    depth_ = 1;
  } else {
    std::uint32_t root = 0;
    Collapser counter(binary, scale, nullptr);
    (void)counter.collapse(0, root);
    nodes_.reserve(counter.nodes());
    depth_ = Collapser(binary, scale, &nodes_).collapse(0, root);
  }
  // The guard's magnitude bounds every stored (binary32, outward) box: the root's, rounded outward, contains them
  // all (rounding down and up are monotone).
  const FloatBox root = outward(bounds_);
  for (std::size_t k = 0; k < 3; ++k)
    magnitude_[k] = std::max(std::fabs(static_cast<double>(root.lo[k])), std::fabs(static_cast<double>(root.hi[k])));
}

namespace mesh_detail {

const BvhWalkFunctions& bvh_walk_functions() noexcept {
  static const BvhWalkFunctions functions = [] {
#if defined(RAYKERNEL_BVH_WALK_AVX2)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v4")) return BvhWalkFunctions{avx512::next_leaf, avx512::node_entries};
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
  w.leaf_data = nullptr;
  w.leaf_stride = 0;
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

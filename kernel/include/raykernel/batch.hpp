// Batches of ray–plane queries in structure-of-arrays layout: the same certified answers as `intersect`,
// bit for bit, at SIMD speed.
//
// The first two stages of the cascade (the binary64 filter and the double-double stage with round_quotient)
// run as one branch-free loop over the batch, which the compiler vectorizes (AVX-512 or AVX2 with FMA,
// chosen when the program loads; a portable scalar loop elsewhere). The queries that loop cannot certify —
// near-degenerate ones, exact degeneracies, invalid input — then go through `intersect`'s full cascade one
// by one. Large batches are split over threads.
#pragma once

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

namespace raykernel {

// n rays: ray i is origin (ox[i], oy[i], oz[i]), direction (dx[i], dy[i], dz[i]). All spans have size n.
struct RayBatch {
  std::span<const double> ox, oy, oz, dx, dy, dz;
  [[nodiscard]] std::size_t size() const noexcept { return ox.size(); }
};

// n planes: plane i is point (px[i], py[i], pz[i]), normal (nx[i], ny[i], nz[i]). All spans have size n.
struct PlaneBatch {
  std::span<const double> px, py, pz, nx, ny, nz;
  [[nodiscard]] std::size_t size() const noexcept { return px.size(); }
};

// Where the answers go: relation[i] and t[i] as `intersect` would return them (t is NaN for parallel
// and in-plane). `valid`, if not empty, receives whether query i was valid input; with it, invalid queries
// do not throw (their relation and t are unspecified). All non-empty spans have the batch's size.
struct IntersectionBatch {
  std::span<Relation> relation;
  std::span<double> t;
  std::span<bool> valid = {};
};

// Where relation_batch's answers go: relation[i] as `relation` would return it; `valid` as above.
struct RelationBatch {
  std::span<Relation> relation;
  std::span<bool> valid = {};
};

// Which stages answered the batch: relation_stage[s] and t_stage[s] count queries (t_stage over those
// with a t, hit or behind), as intersect_traced reports them.
struct BatchStats {
  std::array<std::uint64_t, stage_count> relation_stage{};
  std::array<std::uint64_t, stage_count> t_stage{};
};

struct BatchOptions {
  unsigned threads = 0;           // 0: as many as the hardware has, for batches large enough to gain; at most
                                  // max_threads (<raykernel/parallel.hpp>: threads the system refuses are no error)
  BatchStats* stats = nullptr;    // filled in when not null
};

// Query i is (ray i, plane i). Without `out.valid`, throws invalid_input for the first invalid query,
// naming its index ("query 17: ray direction is the zero vector"); the answers of the others may then be
// incomplete. Throws std::invalid_argument when the spans' sizes differ.
void intersect_batch(const RayBatch& rays, const PlaneBatch& planes, IntersectionBatch out, BatchOptions options = {});

// Query i is (ray i, plane): many rays against one plane. Same contract.
void intersect_batch(const RayBatch& rays, const Plane& plane, IntersectionBatch out, BatchOptions options = {});

// The relation alone (`relation`) for each query i = (ray i, plane i), or (ray i, plane): the binary64
// filter as one vectorized loop, the cascade for the rest. Same contract as intersect_batch (stats count
// relation stages only).
void relation_batch(const RayBatch& rays, const PlaneBatch& planes, RelationBatch out, BatchOptions options = {});
void relation_batch(const RayBatch& rays, const Plane& plane, RelationBatch out, BatchOptions options = {});

// Many rays against a set of planes: out[i] = nearest_hit(ray i, planes), rays spread over threads. Throws
// invalid_input for the first invalid ray, naming it ("ray 17: ray direction is the zero vector"); the span
// form also for an invalid plane ("plane 3: ..."), checked first.
void nearest_hit_batch(const RayBatch& rays, const PlaneSet& planes, std::span<std::optional<NearestHit>> out,
                       BatchOptions options = {});
void nearest_hit_batch(const RayBatch& rays, std::span<const Plane> planes, std::span<std::optional<NearestHit>> out,
                       BatchOptions options = {});

}  // namespace raykernel

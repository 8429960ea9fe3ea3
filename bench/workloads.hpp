// The benchmark workloads: buffers of ray–plane queries generated before timing, larger than the caches
// (the timed loops rotate through them), each checked once (certified == exact) before it is timed.
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/hard_queries.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace raykernel::bench {

using testkit::Query;

// 1 Mi queries × 96 bytes = 96 MiB: well beyond the last-level cache.
inline constexpr std::size_t workload_size = std::size_t{1} << 20;

enum class Workload { random, wide, degenerate, render };

[[nodiscard]] std::string to_string(Workload w);

// The queries of a workload (deterministic: seeded by the workload).
//   random      every component uniform in [-1, 1]
//   wide        components ±(1 + f)·2^e, e uniform in [-300, 300]
//   degenerate  half near-parallel, half near-coplanar (raykernel::testkit), interleaved: built so that
//               plain binary64 is unsure of the sign of d·n or (p − o)·n
//   render      the demo scene's camera rays (pixel centres, `raykernel render`) against each of its planes
[[nodiscard]] const std::vector<Query>& workload(Workload w);

// A workload in structure-of-arrays layout, for the batch API.
struct SoA {
  std::vector<double> ox, oy, oz, dx, dy, dz, px, py, pz, nx, ny, nz;
};
[[nodiscard]] const SoA& workload_soa(Workload w);

// Rays of the demo scene's camera (pixel centres) and the scene's planes, for nearest/<path>/<planes>:
// `plane_count` planes (the demo's, repeated with small offsets when more are asked for).
struct NearestWorkload {
  std::vector<Ray> rays;
  std::vector<Plane> planes;
};
[[nodiscard]] const NearestWorkload& nearest_workload(std::size_t plane_count);

// Queries whose direction makes the angle 2^-k with the plane (k = 0 .. 100), for the degeneracy sweep.
[[nodiscard]] const std::vector<Query>& angle_sweep(int k);

}  // namespace raykernel::bench

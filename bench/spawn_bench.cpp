// spawn/<method>: the origin of a secondary ray at random hits (docs/contract.md §9), raykernel's `spawn` against
// the offset methods renderers use (baselines/offsets): pbrt-v4's OffsetRayOrigin, Ray Tracing Gems as Cycles
// ships it, and the bare rounded hit point (what Ray Tracing in One Weekend starts from). One call per item, the
// same 4,096 hits cycled: triangles with binary32 vertices in [−1, 1]^3 hit by rays from a sphere of radius 4,
// mirror directions.
#include "offset_methods.hpp"

#include <raykernel/fp_environment.hpp>
#include <raykernel/spawn.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

namespace raykernel::bench {
namespace {

struct SpawnCase {
  Ray primary;
  Triangle triangle;
  baseline::OffsetHit hit;
};

const std::vector<SpawnCase>& spawn_cases() {
  static const std::vector<SpawnCase> cases = [] {
    std::vector<SpawnCase> out;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto f = [&] { return static_cast<double>(static_cast<float>(u(rng))); };
    while (out.size() < 4096) {
      const Triangle t{{f(), f(), f()}, {f(), f(), f()}, {f(), f(), f()}};
      const double b1 = (u(rng) + 1) / 4, b2 = (u(rng) + 1) / 4;
      const Vec3 target{t.a.x + b1 * (t.b.x - t.a.x) + b2 * (t.c.x - t.a.x), t.a.y + b1 * (t.b.y - t.a.y) + b2 * (t.c.y - t.a.y),
                        t.a.z + b1 * (t.b.z - t.a.z) + b2 * (t.c.z - t.a.z)};
      const Vec3 origin{4 * u(rng), 4 * u(rng), 4};
      const Ray ray{origin, {target.x - origin.x, target.y - origin.y, target.z - origin.z}};
      const TriangleIntersection x = intersect(ray, t, {TriangleRule::closed, true, true});
      if (x.relation != TriangleRelation::hit) continue;
      const Vec3 e1{t.b.x - t.a.x, t.b.y - t.a.y, t.b.z - t.a.z}, e2{t.c.x - t.a.x, t.c.y - t.a.y, t.c.z - t.a.z};
      Vec3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
      const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
      n = {n.x / len, n.y / len, n.z / len};
      const double dn = ray.direction.x * n.x + ray.direction.y * n.y + ray.direction.z * n.z;
      const Vec3 w{static_cast<float>(ray.direction.x - 2 * dn * n.x), static_cast<float>(ray.direction.y - 2 * dn * n.y),
                   static_cast<float>(ray.direction.z - 2 * dn * n.z)};
      if (direction_side(w, t) == 0) continue;
      baseline::OffsetHit h{};
      const HitPoint p = HitPoint::crossing(ray);
      h.p64 = rounded_hit_point(p, t, OriginFormat::binary64);
      h.p32 = rounded_hit_point(p, t, OriginFormat::binary32);
      h.triangle = t;
      h.barycentric = {x.barycentric.a, x.barycentric.b, x.barycentric.c};
      h.primary_origin = origin;
      h.primary_t = x.t;
      h.direction = w;
      out.push_back({ray, t, h});
    }
    return out;
  }();
  return cases;
}

template <class F>
void cycle(benchmark::State& state, F&& call) {
  const std::vector<SpawnCase>& cases = spawn_cases();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(call(cases[i]));
    if (++i == cases.size()) i = 0;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void spawn_binary64(benchmark::State& s) {
  cycle(s, [](const SpawnCase& c) { return spawn(HitPoint::crossing(c.primary), c.triangle, c.hit.direction); });
}
void spawn_binary32(benchmark::State& s) {
  cycle(s, [](const SpawnCase& c) {
    return spawn(HitPoint::crossing(c.primary), c.triangle, c.hit.direction, OriginFormat::binary32);
  });
}
// The same calls inside one DefaultFpEnvironment scope (as the plane's, the triangle's and the sphere's
// *_scoped): how a renderer spawning many rays on one thread calls it, the per-call environment check hoisted out.
void spawn_binary64_scoped(benchmark::State& s) {
  const DefaultFpEnvironment env;
  cycle(s, [](const SpawnCase& c) { return spawn(HitPoint::crossing(c.primary), c.triangle, c.hit.direction); });
}
void spawn_binary32_scoped(benchmark::State& s) {
  const DefaultFpEnvironment env;
  cycle(s, [](const SpawnCase& c) {
    return spawn(HitPoint::crossing(c.primary), c.triangle, c.hit.direction, OriginFormat::binary32);
  });
}
void spawn_exact_binary64(benchmark::State& s) {
  cycle(s, [](const SpawnCase& c) { return spawn_exact(HitPoint::crossing(c.primary), c.triangle, c.hit.direction); });
}
void pbrt(benchmark::State& s) {
  cycle(s, [](const SpawnCase& c) { return baseline::offset_ray(baseline::OffsetMethod::pbrt_v4, c.hit); });
}
void rtgems(benchmark::State& s) {
  cycle(s, [](const SpawnCase& c) { return baseline::offset_ray(baseline::OffsetMethod::ray_tracing_gems, c.hit); });
}

BENCHMARK(spawn_binary64)->Name("spawn/certified/binary64");
BENCHMARK(spawn_binary32)->Name("spawn/certified/binary32");
BENCHMARK(spawn_binary64_scoped)->Name("spawn/certified/binary64_scoped");
BENCHMARK(spawn_binary32_scoped)->Name("spawn/certified/binary32_scoped");
BENCHMARK(spawn_exact_binary64)->Name("spawn/exact/binary64");
BENCHMARK(pbrt)->Name("spawn/pbrt");
BENCHMARK(rtgems)->Name("spawn/rtgems");

}  // namespace
}  // namespace raykernel::bench

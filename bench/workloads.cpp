#include "workloads.hpp"

#include "scenes/scene.hpp"

#include <raykernel/fp_environment.hpp>
#include <raykernel/mesh_queries.hpp>
#include <raykernel/nearest_scene.hpp>
#include <raykernel/parallel.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace raykernel::bench {
namespace {

using testkit::QueryKind;
using testkit::SplitMix64;

std::vector<Query> generate(QueryKind kind, std::uint64_t seed, std::size_t count) {
  SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<Query> out(count);
  for (auto& q : out) q = testkit::make_query(kind, bits);
  return out;
}

std::vector<Query> degenerate_mix(std::size_t count) {
  SplitMix64 rng(3);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<Query> out(count);
  for (std::size_t i = 0; i < count; ++i)
    out[i] = testkit::make_query(i % 2 == 0 ? QueryKind::near_parallel : QueryKind::near_coplanar, bits);
  return out;
}

// d = (n2·s, −n1·s, 2^-k·c) against n = (n1, n2, n3): the first two terms of d·n cancel exactly (20-bit
// integers: every product is exact), so d·n = 2^-k·c·n3 exactly and the angle between ray and plane is
// about 2^-k. Axes are then shuffled so that the tiny component is not always z.
std::vector<Query> sweep(int k, std::size_t count) {
  SplitMix64 rng(1000 + static_cast<std::uint64_t>(k));
  auto integer = [&rng] { return static_cast<double>(static_cast<std::int64_t>(rng() % (1u << 20)) - (1 << 19)) + 0.5; };
  auto unit = [&rng] { return static_cast<double>(static_cast<std::int64_t>(rng() >> 11) - (std::int64_t{1} << 52)) * 0x1p-52; };
  std::vector<Query> out(count);
  for (auto& q : out) {
    const double n1 = integer(), n2 = integer(), n3 = integer(), s = integer();
    const double d[3] = {n2 * s, -n1 * s, std::ldexp(integer(), -k) * std::ldexp(1.0, 19)};
    const double n[3] = {n1, n2, n3};
    const double o[3] = {unit(), unit(), unit()};
    const double p[3] = {unit(), unit(), unit()};
    const int r = static_cast<int>(rng() % 3);  // rotate axes
    auto at = [r](const double* v, int i) { return v[(i + r) % 3]; };
    q = {{{at(o, 0), at(o, 1), at(o, 2)}, {at(d, 0), at(d, 1), at(d, 2)}},
         {{at(p, 0), at(p, 1), at(p, 2)}, {at(n, 0), at(n, 1), at(n, 2)}}};
  }
  return out;
}

// Certified == exact on every query of the buffer (on the first 2^16 for the exact path's sake: it takes
// microseconds per query). A mismatch is a bug: abort before anything is timed.
void check(const std::vector<Query>& queries, const std::string& name) {
  const std::size_t n = queries.size() < (std::size_t{1} << 16) ? queries.size() : (std::size_t{1} << 16);
  for (std::size_t i = 0; i < n; ++i) {
    const Intersection a = intersect(queries[i].ray, queries[i].plane);
    const Intersection b = intersect_exact(queries[i].ray, queries[i].plane);
    const bool t_matters = a.relation == Relation::hit || a.relation == Relation::behind;
    if (a.relation != b.relation || (t_matters && std::memcmp(&a.t, &b.t, sizeof a.t) != 0)) {
      std::fprintf(stderr, "raykernel_bench: certified != exact on %s query %zu\n", name.c_str(), i);
      std::abort();
    }
  }
}

// The demo scene's camera rays through pixel centres (every pixel of the 960×540 image).
std::vector<Ray> demo_camera_rays() {
  const cli::SceneParse parsed = cli::parse_scene(cli::demo_scene_json());
  if (!parsed.scene) {
    std::fprintf(stderr, "raykernel_bench: the demo scene does not parse: %s\n", parsed.error.str().c_str());
    std::abort();
  }
  const cli::Scene& scene = *parsed.scene;
  std::vector<Ray> rays;
  for (std::uint32_t j = 0; j < scene.image.height; ++j)
    for (std::uint32_t i = 0; i < scene.image.width; ++i) rays.push_back(scene.camera.ray(i, j));
  return rays;
}

std::vector<Plane> demo_planes() { return cli::parse_scene(cli::demo_scene_json()).scene->geometry(); }

// Every (ray, plane) pair of the demo render, ray-major, cut to workload_size queries.
std::vector<Query> render_pairs() {
  const std::vector<Ray> rays = demo_camera_rays();
  const std::vector<Plane> planes = demo_planes();
  std::vector<Query> out;
  out.reserve(workload_size);
  for (const Ray& r : rays)
    for (const Plane& p : planes)
      if (out.size() < workload_size) out.push_back({r, p});
  return out;
}

// A value built once per key, on first use, under a lock (benchmarks register before they run).
template <class Key, class Value, class Make>
const Value& cached(Key key, Make make) {
  static std::mutex mutex;
  static std::map<Key, Value> cache;
  const std::lock_guard lock(mutex);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, make()).first;
  return it->second;
}

}  // namespace

std::string to_string(Workload w) {
  switch (w) {
    case Workload::random: return "random";
    case Workload::random_l2: return "random_l2";
    case Workload::wide: return "wide";
    case Workload::degenerate: return "degenerate";
    case Workload::render: return "render";
  }
  return "?";
}

const std::vector<Query>& workload(Workload w) {
  return cached<Workload, std::vector<Query>>(w, [w] {
    std::vector<Query> q;
    switch (w) {
      case Workload::random: q = generate(QueryKind::random, 1, workload_size); break;
      case Workload::random_l2: q = generate(QueryKind::random, 1, l2_workload_size); break;
      case Workload::wide: q = generate(QueryKind::wide_exponents, 2, workload_size); break;
      case Workload::degenerate: q = degenerate_mix(workload_size); break;
      case Workload::render: q = render_pairs(); break;
    }
    check(q, to_string(w));
    return q;
  });
}

const SoA& workload_soa(Workload w) {
  const std::vector<Query>& q = workload(w);
  return cached<Workload, SoA>(w, [&q] {
    SoA s;
    for (const Query& x : q) {
      s.ox.push_back(x.ray.origin.x), s.oy.push_back(x.ray.origin.y), s.oz.push_back(x.ray.origin.z);
      s.dx.push_back(x.ray.direction.x), s.dy.push_back(x.ray.direction.y), s.dz.push_back(x.ray.direction.z);
      s.px.push_back(x.plane.point.x), s.py.push_back(x.plane.point.y), s.pz.push_back(x.plane.point.z);
      s.nx.push_back(x.plane.normal.x), s.ny.push_back(x.plane.normal.y), s.nz.push_back(x.plane.normal.z);
    }
    return s;
  });
}

const NearestWorkload& nearest_workload(const std::string& name) {
  return cached<std::string, NearestWorkload>(name, [&name] {
    std::vector<Ray> rays;
    std::vector<Plane> planes;
    const std::size_t plane_count = name.ends_with("64") ? 64 : 4;
    if (name.starts_with("demo")) {
      rays = demo_camera_rays();
      const std::vector<Plane> base = demo_planes();
      // More planes than the demo has: copies moved along their normals by small dyadic steps (parallel
      // layers, as in a scene with thin slabs), so that the nearest hit keeps changing with the count.
      for (std::size_t k = 0; k < plane_count; ++k) {
        Plane p = base[k % base.size()];
        const double step = std::ldexp(static_cast<double>(k / base.size()), -4);
        p.point = {p.point.x + step * p.normal.x, p.point.y + step * p.normal.y, p.point.z + step * p.normal.z};
        planes.push_back(p);
      }
    } else {
      for (const Query& q : generate(QueryKind::random, 11, l2_workload_size)) rays.push_back(q.ray);
      for (const Query& q : generate(QueryKind::random, 12, plane_count)) planes.push_back(q.plane);
    }
    PlaneSet prepared(planes);
    return NearestWorkload{std::move(rays), std::move(planes), std::move(prepared)};
  });
}

double read_all(const SoA& soa, unsigned threads) {
  const std::vector<double>* arrays[12] = {&soa.ox, &soa.oy, &soa.oz, &soa.dx, &soa.dy, &soa.dz,
                                           &soa.px, &soa.py, &soa.pz, &soa.nx, &soa.ny, &soa.nz};
  const std::size_t n = soa.ox.size();
  std::vector<double> sums(threads, 0.0);
  auto part = [&](std::size_t k) {
    const std::size_t begin = n * k / threads, end = n * (k + 1) / threads;
    double s[4] = {0, 0, 0, 0};
    for (const std::vector<double>* a : arrays)
      for (std::size_t i = begin; i < end; ++i) s[i % 4] += (*a)[i];
    sums[k] = (s[0] + s[1]) + (s[2] + s[3]);
  };
  run_parts(threads, threads, part);  // the library's own pool: the memory-bandwidth floor of its batches
  double total = 0;
  for (double x : sums) total += x;
  return total;
}

DemoRender::DemoRender()
    : camera_(cli::parse_scene(cli::demo_scene_json()).scene->camera),
      planes_(demo_planes()),
      prepared_(planes_) {}

// Lambert shading against the ray, |d·n| / (|d|·|n|), the same work for both paths.
double DemoRender::render_once(bool certified) const {
  double total = 0;
  for (std::uint32_t j = 0; j < camera_.image.height; ++j)
    for (std::uint32_t i = 0; i < camera_.image.width; ++i) {
      const Ray ray = camera_.ray(i, j);
      const std::optional<NearestHit> hit = certified ? nearest_hit(ray, prepared_) : nearest_hit_naive(ray, planes_);
      if (!hit) continue;
      const Vec3& n = planes_[hit->plane].normal;
      const Vec3& d = ray.direction;
      const double dn = d.x * n.x + d.y * n.y + d.z * n.z;
      total += std::fabs(dn) / std::sqrt((d.x * d.x + d.y * d.y + d.z * d.z) * (n.x * n.x + n.y * n.y + n.z * n.z));
    }
  return total;
}

const DemoRender& demo_render() {
  static const DemoRender render;
  return render;
}

struct SceneRender::Loaded {
  cli::Scene scene;
  std::vector<Plane> planes;
  std::unique_ptr<PlaneSet> prepared;
  std::unique_ptr<PreparedMesh> mesh;
};

SceneRender::SceneRender(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw std::runtime_error("cannot open " + path);
  std::string text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) text.append(buffer, n);
  std::fclose(f);
  cli::SceneParse parsed = cli::parse_scene(text);
  if (!parsed.scene) throw std::runtime_error(path + ": " + parsed.error.str());
  auto loaded = std::make_shared<Loaded>();
  loaded->scene = std::move(*parsed.scene);
  if (const auto error = cli::load_scene_meshes(loaded->scene, std::filesystem::path(path).parent_path()))
    throw std::runtime_error(path + ": " + error->str());
  loaded->planes = loaded->scene.geometry();
  loaded->prepared = std::make_unique<PlaneSet>(loaded->planes);
  loaded->mesh = std::make_unique<PreparedMesh>(loaded->scene.mesh);
  scene_ = std::move(loaded);
}

std::size_t SceneRender::rays() const noexcept {
  const cli::Scene& s = scene_->scene;
  return std::size_t{s.image.width} * s.image.height * s.samples_per_pixel;
}

// Lambert shading against the ray, |d·n| / (|d|·|n|), with the plane's normal or the triangle's (b − a) × (c − a):
// the same work for both paths.
double SceneRender::render_once(bool certified) const {
  const Loaded& l = *scene_;
  const cli::Scene& scene = l.scene;
  const NearestScene surfaces{l.prepared.get(), l.mesh.get(), TriangleRule::owned};
  const DefaultFpEnvironment environment;  // as the CLI's rows
  double total = 0;
  for (std::uint32_t j = 0; j < scene.image.height; ++j)
    for (std::uint32_t i = 0; i < scene.image.width; ++i)
      for (const PixelSample& sample : stratified_samples(scene.samples_per_pixel, scene.seed, i, j)) {
        const Ray ray = scene.camera.ray(i, j, sample);
        std::optional<SurfaceKind> kind;
        std::size_t index = 0;
        if (certified) {
          if (const std::optional<SurfaceHit> hit = nearest_hit(ray, surfaces)) kind = hit->kind, index = hit->index;
        } else {
          const std::optional<NearestHit> plane = nearest_hit_naive(ray, l.planes);
          const std::optional<MeshHit> triangle = nearest_hit_naive(ray, *l.mesh);
          if (triangle && !(plane && !(triangle->intersection.t < plane->t))) {
            kind = SurfaceKind::triangle, index = triangle->triangle;
          } else if (plane) {
            kind = SurfaceKind::plane, index = plane->plane;
          }
        }
        if (!kind) continue;
        Vec3 n;
        if (*kind == SurfaceKind::plane) {
          n = l.planes[index].normal;
        } else {
          const Triangle t = scene.mesh.triangle(index);
          const Vec3 e1{t.b.x - t.a.x, t.b.y - t.a.y, t.b.z - t.a.z}, e2{t.c.x - t.a.x, t.c.y - t.a.y, t.c.z - t.a.z};
          n = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
        }
        const Vec3& d = ray.direction;
        const double dn = d.x * n.x + d.y * n.y + d.z * n.z;
        total += std::fabs(dn) / std::sqrt((d.x * d.x + d.y * d.y + d.z * d.z) * (n.x * n.x + n.y * n.y + n.z * n.z));
      }
  return total;
}

const SceneRender& octahedron_render() {
  static const SceneRender render(std::string(RAYKERNEL_SCENES_DIR) + "/octahedron.json");
  return render;
}

const std::vector<Query>& angle_sweep(int k) {
  return cached<int, std::vector<Query>>(k, [k] {
    std::vector<Query> q = sweep(k, std::size_t{1} << 16);
    check(q, "angle 2^-" + std::to_string(k));
    return q;
  });
}

}  // namespace raykernel::bench

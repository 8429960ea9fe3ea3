// raykernel spawn-audit MESH [--hits N] [--seed S] [--scale-exponent E] [--png OUT]: how the ways renderers
// start a secondary ray at a hit point fare against the exact answer, on a mesh.
//
// Seeded primary rays from a sphere around the mesh find their nearest hits (exact: nearest_hit, owned rule).
// At each hit three new directions leave it (a mirror reflection, a direction uniform over both hemispheres,
// and a grazing one within 2^-20 rad of the surface); each method of baselines/offsets (pbrt-v4, Ray Tracing
// Gems as Cycles ships it, Mitsuba 3, Embree's path tracer tutorial, Ray Tracing in One Weekend) and raykernel's
// `spawn` in binary32 and binary64 gives the new ray's origin (and its interval's start), from the same hit.
// Each is then checked exactly (<raykernel/spawn.hpp>'s ground truth, GMP rationals):
//   no-origin          the method gave no finite origin (an overflow or a NaN in its arithmetic; for spawn: no
//                      value of the format on the side, beyond its range);
//   self-hits          the new ray meets the triangle it leaves, with t in its own interval (closed rule);
//   behind, on-plane   the origin is on the other side of the triangle's plane than the direction leaves to,
//                      or on the plane itself (σ = −s or σ = 0: not strictly on side s);
//   first-hit-differs  the first triangles the new ray meets (closed rule, its own interval) are not those the
//                      exact ray from the exact hit point P meets first (t > 0, the source triangle left out):
//                      a surface skipped (light leaks through a near surface) or one that is not there;
//   offset             how far the origin is from P rounded to the method's format, in values of that format
//                      (ulps) along the axis that moved most: the median and the largest.
// The mesh's vertices are rounded to binary32 first (so that every method, in float or double, sees the same
// surface), then scaled by 2^E (exactly); the directions are binary32 values too.
#include "commands/commands.hpp"
#include "commands/mesh_file.hpp"
#include "common/exit_status.hpp"
#include "common/io.hpp"
#include "common/limits.hpp"
#include "common/options.hpp"
#include "common/text_format.hpp"
#include "common/text_input.hpp"
#include "rendering/legend.hpp"
#include "rendering/mesh_view.hpp"
#include "rendering/png_image.hpp"

#include "offset_methods.hpp"

#include <raykernel/mesh_queries.hpp>
#include <raykernel/parallel.hpp>
#include <raykernel/spawn.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <atomic>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel spawn-audit FILE [--hits N] [--seed S] [--scale-exponent E] [--png OUT]

Checks exactly how the ways renderers start a secondary ray at a hit point fare on the triangle
mesh in FILE (OBJ, PLY, STL, OFF or glTF): seeded primary rays find their exact nearest hits; at each hit
a mirror, a random (both hemispheres) and a grazing (within 2^-20 rad of the surface) direction
leave it; each method gives the new ray's origin (and where its interval starts):
  pbrt-v4          OffsetRayOrigin with the triangle's pError (float)
  rtgems-cycles    Ray Tracing Gems ch. 6 as Cycles ships it (float bits moved along the normal)
  mitsuba3         (1 + max|p|) * 1500 * 2^-24 along the normal (float)
  embree-tutorial  Embree's path tracer: eps = 32 FLT_EPSILON max(|p_i|, |org|, tfar), tnear = eps
  one-weekend      Ray Tracing in One Weekend: the hit point, t > 0.001 (double)
  raykernel-32/64  raykernel spawn in binary32 and binary64 (t >= 0)
and every new ray is checked exactly (GMP rationals):
  no-origin          the method gave no finite origin (an overflow or NaN in its arithmetic)
  self-hits          it meets the triangle it leaves, with t in its own interval
  behind, on-plane   its origin is on the other side of the plane, or on it
  first-hit-differs  its first hit is not the exact ray's from the exact hit point (source left out)
  offset             the origin's distance from the rounded hit point, in ulps of its format
The vertices are rounded to binary32 first (every method sees the same surface), then scaled by
2^E exactly.
)";

constexpr const char* help_after = R"(exit status: 0 done, 2 usage or I/O error or a file that is not a mesh
)";

struct Arguments {
  std::optional<std::string> mesh_path;
  std::string png_path;
  std::uint64_t hits = 200, seed = 1;
  std::int64_t scale_exponent = 0;
  unsigned threads = 0;
};

CommandLine command_line(Arguments& a) {
  return {.command = "spawn-audit",
          .options = {{"--hits", integer(a.hits, 1, 1000000), "number of primary hits (default 200)"},
                      {"--seed", integer(a.seed, 0, UINT64_MAX, "S"), "random seed (default 1)"},
                      {"--scale-exponent", signed_integer(a.scale_exponent, -100, 100, "E"),
                       "scale the mesh by 2^E after rounding it to binary32 (default 0)"},
                      {"--threads", integer(a.threads, 1, limits::max_threads), "worker threads (default: every core)"},
                      {"--png", file(a.png_path, "OUT"),
                       "write one panel per method: the mesh, and the hits where the method failed marked (red: "
                       "self-hit, orange: behind or on the plane, blue: first hit differs)"}},
          .operand = Operand{.metavar = "FILE", .what = "mesh file", .destination = &a.mesh_path},
          .help_before = help_before,
          .help_after = help_after};
}

// ---- The methods ---------------------------------------------------------------------------------------------

constexpr std::size_t method_count = baseline::offset_methods.size() + 2;  // + raykernel binary32, binary64

std::string method_name(std::size_t m) {
  if (m < baseline::offset_methods.size()) return std::string(baseline::name(baseline::offset_methods[m]));
  return m == baseline::offset_methods.size() ? "raykernel-32" : "raykernel-64";
}
bool method_binary32(std::size_t m) {
  if (m < baseline::offset_methods.size()) return baseline::is_binary32(baseline::offset_methods[m]);
  return m == baseline::offset_methods.size();
}

// The ordinal of a value among the finite values of its format (as spawn counts steps), for the offset in ulps.
std::int64_t ordinal(double x, bool binary32) {
  if (binary32) {
    const auto bits = std::bit_cast<std::uint32_t>(static_cast<float>(x));
    const std::int64_t magnitude = bits & 0x7fffffffu;
    return (bits >> 31) != 0 ? -magnitude : magnitude;
  }
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto magnitude = static_cast<std::int64_t>(bits & 0x7fffffffffffffffu);
  return (bits >> 63) != 0 ? -magnitude : magnitude;
}
std::uint64_t offset_ulps(const Vec3& origin, const Vec3& rounded, bool binary32) {
  const double o[3] = {origin.x, origin.y, origin.z}, r[3] = {rounded.x, rounded.y, rounded.z};
  std::uint64_t most = 0;
  for (int i = 0; i < 3; ++i) {
    const std::int64_t a = ordinal(o[i], binary32), b = ordinal(r[i], binary32);
    most = std::max(most, a > b ? static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b)
                                : static_cast<std::uint64_t>(b) - static_cast<std::uint64_t>(a));
  }
  return most;
}

struct Tally {
  std::uint64_t rays = 0, no_origin = 0, self_hits = 0, behind = 0, on_plane = 0, differs = 0;
  std::vector<std::uint64_t> ulps;
};

// ---- Directions and sampling ---------------------------------------------------------------------------------

Vec3 to_binary32(const Vec3& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(const Vec3& a, const Vec3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec3 scaled(const Vec3& v, double s) { return {v.x * s, v.y * s, v.z * s}; }
Vec3 plus(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 minus(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 unit(const Vec3& v) { return scaled(v, 1 / std::sqrt(dot(v, v))); }

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const Vec3 v{g(rng), g(rng), g(rng)};
    if (dot(v, v) > 1e-12) return unit(v);
  }
}

enum Kind { mirror, random_direction, grazing, kind_count };
constexpr const char* kind_names[kind_count] = {"mirror", "random", "grazing"};

Vec3 outgoing(Kind kind, const Vec3& d, const Vec3& n, std::mt19937_64& rng) {
  switch (kind) {
    case mirror: return unit(minus(unit(d), scaled(n, 2 * dot(unit(d), n))));
    case random_direction: return random_unit(rng);
    case grazing: {
      const Vec3 tangent = unit(cross(n, random_unit(rng)));
      const double angle = std::ldexp(std::uniform_real_distribution<double>(0x1p-10, 1)(rng), -20);
      const double side = std::uniform_int_distribution<int>(0, 1)(rng) == 0 ? -1 : 1;
      return plus(scaled(tangent, std::cos(angle)), scaled(n, side * std::sin(angle)));
    }
    case kind_count: break;
  }
  return n;
}

struct Mark {
  Vec3 at;
  std::size_t method;
  int what;  // 0 self-hit, 1 wrong side, 2 first hit differs
};

}  // namespace

OwnedCommandLine spawn_audit_command_line() { return owned_command_line(command_line); }

int run_spawn_audit(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;
  if (!arguments.mesh_path) {
    std::cerr << "raykernel spawn-audit: a mesh FILE is required (see raykernel spawn-audit --help)\n";
    return exit_usage;
  }
  const std::string& mesh_path = *arguments.mesh_path;
  std::optional<Mesh> read = read_mesh_file("spawn-audit", mesh_path, std::cerr);
  if (!read) return exit_usage;
  if (read->triangles.empty()) {
    std::cerr << "raykernel: " << printable(mesh_path) << ": the mesh has no triangles\n";
    return exit_usage;
  }
  // Vertices to binary32, then scaled by 2^E exactly.
  std::uint64_t changed = 0;
  for (std::size_t n = 0; n < read->vertices.size(); ++n) {
    double* c = &read->vertices[n].x;
    for (int k = 0; k < 3; ++k) {
      const double f = static_cast<float>(c[k]);
      changed += f != c[k];
      const double s = std::ldexp(f, static_cast<int>(arguments.scale_exponent));
      if (!std::isfinite(static_cast<float>(s)) || static_cast<float>(s) != s ||
          (f != 0 && std::fabs(s) < 0x1p-126)) {
        std::cerr << "raykernel: " << printable(mesh_path) << ": vertex " << n + 1 << ": " << "xyz"[k] << " = "
                  << format_shortest(c[k]) << " rounded to binary32 and scaled by 2^" << arguments.scale_exponent
                  << " leaves the normal binary32 range (the audit's float methods need it)\n";
        return exit_usage;
      }
      c[k] = s;
    }
  }
  const PreparedMesh prepared = prepare_mesh(std::move(*read), mesh_path);
  const Mesh& mesh = prepared.mesh();
  const Box3& box = prepared.bvh().bounds();
  const Vec3 centre = scaled(plus(box.lo, box.hi), 0.5);
  const double radius = 2 * std::sqrt(dot(minus(box.hi, box.lo), minus(box.hi, box.lo))) + 1e-300;

  // The samples, drawn in order from the seed: each hit and its new directions.
  struct Sample {
    Ray primary;
    std::uint32_t source;
    baseline::OffsetHit hit;
    std::vector<Vec3> directions;
  };
  std::mt19937_64 rng(arguments.seed);
  std::array<std::uint64_t, kind_count> by_kind{};
  std::uint64_t attempts = 0, skipped_directions = 0;
  std::vector<Sample> samples;
  const std::uint64_t max_attempts = 50 * arguments.hits + 1000;
  while (samples.size() < arguments.hits && attempts < max_attempts) {
    ++attempts;
    const std::uint32_t k = std::uniform_int_distribution<std::uint32_t>(
        0, static_cast<std::uint32_t>(mesh.triangles.size() - 1))(rng);
    const Triangle aim = mesh.triangle(k);
    double u = std::uniform_real_distribution<double>(0, 1)(rng), v = std::uniform_real_distribution<double>(0, 1)(rng);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Vec3 target = plus(aim.a, plus(scaled(minus(aim.b, aim.a), u), scaled(minus(aim.c, aim.a), v)));
    const Vec3 origin = plus(centre, scaled(random_unit(rng), radius));
    const Ray primary{origin, minus(target, origin)};
    if (validate(primary)) continue;  // a zero direction (the target at the origin)
    const std::optional<MeshHit> hit = nearest_hit(primary, prepared);
    if (!hit) continue;
    Sample sample{primary, hit->triangle, {}, {}};
    const Triangle tri = mesh.triangle(sample.source);
    const TriangleIntersection x =
        intersect(primary, tri, TriangleOptions{.rule = TriangleRule::closed, .t = true, .barycentric = true});
    const HitPoint at_p = HitPoint::crossing(primary);
    baseline::OffsetHit& in = sample.hit;
    try {
      in.p64 = rounded_hit_point(at_p, tri, OriginFormat::binary64);
      in.p32 = rounded_hit_point(at_p, tri, OriginFormat::binary32);
    } catch (const invalid_input&) {
      continue;
    }
    in.triangle = tri;
    in.barycentric = {x.barycentric.a, x.barycentric.b, x.barycentric.c};
    in.primary_origin = origin;
    in.primary_t = x.t;
    const Vec3 normal = unit(cross(minus(tri.b, tri.a), minus(tri.c, tri.a)));
    for (int kind = 0; kind < kind_count; ++kind) {
      const Vec3 w = to_binary32(outgoing(static_cast<Kind>(kind), primary.direction, normal, rng));
      if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z) || (w.x == 0 && w.y == 0 && w.z == 0) ||
          direction_side(w, tri) == 0) {
        ++skipped_directions;
        continue;
      }
      ++by_kind[static_cast<std::size_t>(kind)];
      sample.directions.push_back(w);
    }
    samples.push_back(std::move(sample));
  }

  // Each sample checked exactly, on every thread; the results kept per sample, then summed in order.
  struct Check {
    bool ran = false, no_origin = false, self = false, behind = false, on_plane = false, differs = false;
    std::uint64_t ulps = 0;
  };
  struct Result {
    std::vector<std::array<Check, method_count>> checks;  // per direction
    std::uint64_t no_reference_hit = 0;
  };
  std::vector<Result> results(samples.size());
  const bool show_progress = isatty(STDERR_FILENO);
  std::atomic<std::uint64_t> done{0};
  std::mutex progress;
  run_parts(samples.size(), thread_count(arguments.threads), [&](std::size_t n) {
    const Sample& sample = samples[n];
    const Triangle tri = mesh.triangle(sample.source);
    const HitPoint at_p = HitPoint::crossing(sample.primary);
    Result& result = results[n];
    for (const Vec3& w : sample.directions) {
      baseline::OffsetHit in = sample.hit;
      in.direction = w;
      const int side = direction_side(w, tri);
      const std::vector<std::uint32_t> reference =
          first_hits_exact(at_p, tri, w, mesh, SecondaryInterval{0, false}, sample.source);
      result.no_reference_hit += reference.empty();
      std::array<Check, method_count>& checks = result.checks.emplace_back();
      for (std::size_t m = 0; m < method_count; ++m) {
        baseline::OffsetRay ray{};
        if (m < baseline::offset_methods.size()) {
          ray = baseline::offset_ray(baseline::offset_methods[m], in);
        } else {
          try {
            const OriginFormat f = method_binary32(m) ? OriginFormat::binary32 : OriginFormat::binary64;
            ray = {spawn(at_p, tri, w, f).origin, 0, true};
          } catch (const invalid_input&) {
            checks[m] = {.ran = true, .no_origin = true};  // no origin on the side in the format (beyond its range)
            continue;
          }
        }
        if (!std::isfinite(ray.origin.x) || !std::isfinite(ray.origin.y) || !std::isfinite(ray.origin.z)) {
          checks[m] = {.ran = true, .no_origin = true};  // an overflow or a NaN in the method's arithmetic
          continue;
        }
        const SecondaryInterval interval{ray.t_min, ray.t_min_included};
        const HitPoint from = HitPoint::at(ray.origin);
        const std::vector<std::uint32_t> first = first_hits_exact(from, tri, w, mesh, interval);
        bool agree = first.empty() && reference.empty();
        for (std::uint32_t f : first) agree = agree || std::binary_search(reference.begin(), reference.end(), f);
        const int sigma = plane_side(ray.origin, tri);
        checks[m] = {true, false, hits_exact(from, tri, w, tri, interval), sigma == -side, sigma == 0, !agree,
                     offset_ulps(ray.origin, method_binary32(m) ? in.p32 : in.p64, method_binary32(m))};
      }
    }
    const std::uint64_t finished = ++done;
    if (show_progress) {
      const std::lock_guard<std::mutex> lock(progress);
      std::cerr << "\rspawn-audit: " << finished << " of " << samples.size() << " hits checked" << std::flush;
    }
  });
  if (show_progress) std::cerr << '\n';

  std::array<Tally, method_count> tally{};
  std::uint64_t no_reference_hit = 0;
  std::vector<Mark> marks;
  std::vector<Vec3> hit_points;
  for (std::size_t n = 0; n < samples.size(); ++n) {
    hit_points.push_back(samples[n].hit.p64);
    no_reference_hit += results[n].no_reference_hit;
    for (const auto& checks : results[n].checks)
      for (std::size_t m = 0; m < method_count; ++m) {
        const Check& c = checks[m];
        if (!c.ran) continue;
        Tally& t = tally[m];
        ++t.rays;
        if (c.no_origin) {
          ++t.no_origin;
          continue;
        }
        t.self_hits += c.self;
        t.behind += c.behind;
        t.on_plane += c.on_plane;
        t.differs += c.differs;
        t.ulps.push_back(c.ulps);
        if (c.self || c.behind || c.on_plane || c.differs)
          marks.push_back({samples[n].hit.p64, m, c.self ? 0 : (c.behind || c.on_plane) ? 1 : 2});
      }
  }
  const std::uint64_t hits = samples.size();

  const std::uint64_t directions = by_kind[0] + by_kind[1] + by_kind[2];
  std::cout << "mesh " << printable(mesh_path) << ": " << mesh.triangles.size() << " triangles, vertices rounded to binary32 ("
            << changed << " coordinates changed), scaled by 2^" << arguments.scale_exponent << "\n";
  std::cout << "hits: " << hits << " (seed " << arguments.seed << ", " << attempts << " primary rays); new rays: " << directions
            << " (" << by_kind[mirror] << " mirror, " << by_kind[random_direction] << " random, " << by_kind[grazing]
            << " grazing; " << skipped_directions << " parallel to the surface left out); the exact ray from P meets nothing for "
            << no_reference_hit << "\n";
  std::cout << std::left << std::setw(17) << "method" << std::setw(10) << "format" << std::right << std::setw(7) << "rays"
            << std::setw(11) << "no-origin" << std::setw(11) << "self-hits" << std::setw(8) << "behind" << std::setw(10) << "on-plane" << std::setw(19)
            << "first-hit-differs"
            << std::setw(15) << "offset-median" << std::setw(12) << "offset-max" << '\n';
  for (std::size_t m = 0; m < method_count; ++m) {
    Tally& t = tally[m];
    std::sort(t.ulps.begin(), t.ulps.end());
    const std::uint64_t median = t.ulps.empty() ? 0 : t.ulps[t.ulps.size() / 2];
    const std::uint64_t most = t.ulps.empty() ? 0 : t.ulps.back();
    std::cout << std::left << std::setw(17) << method_name(m) << std::setw(10) << (method_binary32(m) ? "binary32" : "binary64")
              << std::right << std::setw(7) << t.rays << std::setw(11) << t.no_origin << std::setw(11) << t.self_hits << std::setw(8) << t.behind << std::setw(10) << t.on_plane
              << std::setw(19) << t.differs << std::setw(15) << median << std::setw(12) << most << '\n';
  }

  if (!arguments.png_path.empty()) {
    constexpr std::uint32_t panel = 320;
    constexpr std::uint32_t columns = 4, rows = (method_count + columns - 1) / columns;
    const MeshView view = view_of(prepared, panel);
    const Image base = render_mesh(prepared, view);
    Image image(panel * columns, panel * rows);
    std::fill(image.rgb.begin(), image.rgb.end(), std::uint8_t{255});
    constexpr std::array<std::array<std::uint8_t, 3>, 3> colours = {{{220, 20, 20}, {255, 150, 0}, {40, 80, 255}}};
    for (std::size_t m = 0; m < method_count; ++m) {
      Image p = base;
      for (const Vec3& h : hit_points) mark(p, view.project(h), {150, 150, 150}, 1);
      for (int what = 2; what >= 0; --what)  // self-hits drawn last, on top
        for (const Mark& k : marks)
          if (k.method == m && k.what == what) mark(p, view.project(k.at), colours[static_cast<std::size_t>(what)], 3);
      const Tally& t = tally[m];
      std::vector<LegendItem> legend = {{std::nullopt, method_name(m)},
                                        {colours[0], std::to_string(t.self_hits) + " self"},
                                        {colours[1], std::to_string(t.behind + t.on_plane) + " side"},
                                        {colours[2], std::to_string(t.differs) + " differ"}};
      draw_legend(p, legend);
      const std::uint32_t x0 = static_cast<std::uint32_t>(m % columns) * panel, y0 = static_cast<std::uint32_t>(m / columns) * panel;
      for (std::uint32_t y = 0; y < panel; ++y)
        std::copy(p.pixel(0, y), p.pixel(0, y) + 3 * panel, image.pixel(x0, y0 + y));
    }
    if (const auto error = write_png(arguments.png_path, image)) {
      std::cerr << "raykernel spawn-audit: " << printable(*error) << '\n';
      return exit_usage;
    }
  }
  return finish_standard_output(exit_ok);
}

}  // namespace raykernel::cli

// raykernel watertight FILE [--rays N] [--seed S] [--png OUT]: random lines through a mesh, and how many hits
// each way of intersecting counts along them — raykernel's owned rule, the closed rule, Möller–Trumbore in
// doubles, Embree's default and robust modes (when built with Embree) — against the line's exact crossings.
//
// The reference is the owned rule's count, computed exactly: its hits are the crossings of the line moved by an
// infinitesimal (ε, ε², ε³) (docs/contract.md §6), a line in general position, so each one is a true crossing of
// the surface and none is counted twice. A way of counting then
//   leaks       on a line where it counts an odd number of hits (on a closed mesh every line leaves as often as
//               it enters, so an odd count is a hole or a double count) — for the owned rule itself this is the
//               independent check, with `unbalanced` (the signed count, +1 for each den > 0, must be 0);
//   double hits on a line where it counts more hits than the owned rule's exact crossings;
//   misses      on a line where it counts fewer; `missed vertices` are such lines aimed exactly at a vertex.
// Every line starts outside the mesh's bounding box (so the ray is the whole line's part that meets the mesh).
// Half the lines are aimed exactly (the direction target − origin computed without rounding; the target is then
// at t = 1) at a vertex, an edge point or a face point, the others at the same kind of target moved off by a few
// ulps, or at random points of the box.
#include "commands/commands.hpp"
#include "commands/mesh_file.hpp"
#include "common/exit_status.hpp"
#include "common/io.hpp"
#include "common/options.hpp"
#include "common/text_format.hpp"
#include "rendering/mesh_view.hpp"
#include "rendering/png_image.hpp"

#include <raykernel/mesh_queries.hpp>

#ifdef RAYKERNEL_HAVE_EMBREE
#include "embree_scene.hpp"
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel watertight FILE [--rays N] [--seed S] [--png OUT]

Shoots N random lines through the triangle mesh in FILE (OBJ, PLY, STL, OFF or glTF) and counts, for
raykernel's owned rule, the closed rule, Moller-Trumbore in doubles and Embree (default and
robust modes, when raykernel was built with Embree; Embree intersects the mesh and the lines
rounded to float), on how many lines each
  leaks            counts an odd number of hits (on a closed mesh),
  double-hits      counts more hits than the line's exact crossings,
  misses           counts fewer hits than the exact crossings,
  missed-vertices  misses, on a line aimed exactly at a vertex.
The exact crossings are the owned rule's hits, decided exactly: the crossings of the line moved
by an infinitesimal (e, e^2, e^3), each a true crossing counted once. The owned rule's own checks
are its parity (leaks) and its balance (unbalanced: entries minus exits is not 0). Half the
lines are aimed exactly at vertices, edge points and face points; the others near them, or at
random.
)";

constexpr const char* help_after = R"(exit status: 0 done, 2 usage or I/O error or a file that is not a mesh
)";

// The most lines one run shoots (--rays).
constexpr std::uint64_t max_rays = 100'000'000;

enum class Target { vertex, edge, face, random };

struct Line {
  Ray ray;
  Vec3 target;
  Target kind;
  bool exact;  // target = origin + direction exactly (t = 1)
};

// Whether a − b is computed exactly (TwoSum's error term is 0).
bool exact_difference(double a, double b) {
  const double s = a - b, bb = s - a;
  return (a - (s - bb)) + (-b - bb) == 0 && std::isfinite(s);
}

struct Generator {
  const Mesh& mesh;
  Box3 box;
  std::mt19937_64 rng;

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  std::uint64_t below(std::uint64_t n) { return std::uniform_int_distribution<std::uint64_t>(0, n - 1)(rng); }

  // A point on the grid of 1/64ths of the box enlarged threefold, on one of its faces: outside the box.
  Vec3 origin() {
    const Vec3 c{(box.lo.x + box.hi.x) / 2, (box.lo.y + box.hi.y) / 2, (box.lo.z + box.hi.z) / 2};
    const double e = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z, 0x1p-900});
    const double half = std::exp2(std::ceil(std::log2(e)));  // a power of two ≥ the extent
    auto grid = [&] { return static_cast<double>(static_cast<std::int64_t>(below(129)) - 64) / 64 * 2 * half; };
    std::array<double, 3> o{grid(), grid(), grid()};
    o[below(3)] = (below(2) ? 2 : -2) * half;
    return {c.x + o[0], c.y + o[1], c.z + o[2]};
  }

  Vec3 target(Target kind) {
    if (kind == Target::random)
      return {uniform(box.lo.x, box.hi.x), uniform(box.lo.y, box.hi.y), uniform(box.lo.z, box.hi.z)};
    const Triangle t = mesh.triangle(below(mesh.triangles.size()));
    const Vec3 v[3] = {t.a, t.b, t.c};
    if (kind == Target::vertex) return v[below(3)];
    // a + w(b − a) with w = k/16, computed in doubles (exact on dyadic meshes; the aim is checked anyway).
    auto lerp = [](const Vec3& a, const Vec3& b, double w) {
      return Vec3{a.x + w * (b.x - a.x), a.y + w * (b.y - a.y), a.z + w * (b.z - a.z)};
    };
    const Vec3 p = lerp(v[below(3)], v[below(3)], static_cast<double>(1 + below(15)) / 16);
    return kind == Target::edge ? lerp(t.a, t.b, static_cast<double>(1 + below(15)) / 16)
                                : lerp(p, t.c, static_cast<double>(1 + below(15)) / 16);
  }

  Line next() {
    const Target kind = static_cast<Target>(below(4));
    const bool aim_exactly = below(2) == 0 && kind != Target::random;
    Vec3 p = target(kind);
    const Vec3 o = origin();
    if (!aim_exactly && kind != Target::random) {  // a few ulps off the target
      auto nudge = [&](double x) {
        for (std::uint64_t n = below(4); n > 0; --n) x = std::nextafter(x, below(2) ? INFINITY : -INFINITY);
        return x;
      };
      p = {nudge(p.x), nudge(p.y), nudge(p.z)};
    }
    Vec3 d{p.x - o.x, p.y - o.y, p.z - o.z};
    if (d.x == 0 && d.y == 0 && d.z == 0) d = {1, 0, 0};
    const bool exact = exact_difference(p.x, o.x) && exact_difference(p.y, o.y) && exact_difference(p.z, o.z);
    return {{o, d}, p, kind, exact && aim_exactly};
  }
};

enum Method { owned, closed, moller_trumbore, embree_default, embree_robust, method_count };
constexpr const char* method_names[method_count] = {"owned (raykernel)", "closed (raykernel)", "Moller-Trumbore",
                                                    "Embree", "Embree robust"};

struct Tally {
  std::uint64_t leaks = 0, double_hits = 0, misses = 0, missed_vertices = 0;
};

// The signed count of the owned hits (+1 where den > 0, −1 where den < 0, exactly): 0 on a closed mesh.
std::int64_t signed_count(const Ray& ray, const Mesh& mesh, const std::vector<std::uint32_t>& owned_hits) {
  std::int64_t sum = 0;
  for (std::uint32_t k : owned_hits)
    sum += intersect_exact_rational(ray, mesh.triangle(k), TriangleRule::owned).den.numerator.starts_with('-') ? -1 : 1;
  return sum;
}

// Whether every directed edge (by vertex coordinates) is matched by exactly one reversed edge.
bool is_closed(const Mesh& mesh) {
  auto key = [&](std::uint32_t i) {
    const Vec3& v = mesh.vertices[i];
    return std::array<std::uint64_t, 3>{std::bit_cast<std::uint64_t>(v.x + 0.0), std::bit_cast<std::uint64_t>(v.y + 0.0),
                                        std::bit_cast<std::uint64_t>(v.z + 0.0)};
  };
  std::map<std::pair<std::array<std::uint64_t, 3>, std::array<std::uint64_t, 3>>, int> edges;
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{key(t[static_cast<std::size_t>(e)]), key(t[static_cast<std::size_t>((e + 1) % 3)])}];
  if (mesh.triangles.empty()) return false;
  for (const auto& [edge, count] : edges) {
    const auto reverse = edges.find({edge.second, edge.first});
    if (count != 1 || reverse == edges.end() || reverse->second != 1) return false;
  }
  return true;
}

// What the command line says.
struct Arguments {
  std::optional<std::string> mesh_path;
  std::string png_path;
  std::uint64_t rays = 10000, seed = 1;
};

CommandLine command_line(Arguments& a) {
  return {.command = "watertight",
          .options = {{"--rays", integer(a.rays, 1, max_rays), "number of lines (default 10000)"},
                      {"--seed", integer(a.seed, 0, UINT64_MAX, "S"), "random seed (default 1)"},
                      {"--png", file(a.png_path, "OUT"),
                       "write a render of the mesh with the lines' targets marked where a method leaked (red: "
                       "Moller-Trumbore, orange: Embree, magenta: Embree robust, blue: closed rule, green: owned "
                       "rule)"}},
          .operand = Operand{.metavar = "FILE", .what = "mesh file", .destination = &a.mesh_path},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

OwnedCommandLine watertight_command_line() { return owned_command_line(command_line); }

int run_watertight(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;
  if (!arguments.mesh_path) {
    std::cerr << "raykernel watertight: a mesh FILE is required (see raykernel watertight --help)\n";
    return exit_usage;
  }
  const std::string& mesh_path = *arguments.mesh_path;
  const std::string& png_path = arguments.png_path;
  const std::uint64_t rays = arguments.rays, seed = arguments.seed;
  std::optional<Mesh> read = read_mesh_file("watertight", mesh_path, std::cerr);
  if (!read) return exit_usage;
  if (read->triangles.empty()) {
    std::cerr << "raykernel: " << printable(mesh_path) << ": the mesh has no triangles\n";
    return exit_usage;
  }
  const PreparedMesh prepared = prepare_mesh(std::move(*read), mesh_path);
  const Mesh& mesh = prepared.mesh();
  const bool closed_mesh = is_closed(mesh);

  bool have_embree = false;
#ifdef RAYKERNEL_HAVE_EMBREE
  std::unique_ptr<baseline::EmbreeScene> embree[2];
  try {
    embree[0] = std::make_unique<baseline::EmbreeScene>(mesh, baseline::EmbreeScene::Mode::fast, 0, true);
    embree[1] = std::make_unique<baseline::EmbreeScene>(mesh, baseline::EmbreeScene::Mode::robust, 0, true);
    have_embree = true;
  } catch (const std::exception& e) {
    std::cerr << "raykernel watertight: Embree left out: " << printable(e.what()) << '\n';
  }
#endif

  Generator generator{mesh, prepared.bvh().bounds(), std::mt19937_64(seed)};
  std::array<Tally, method_count> tally{};
  std::array<std::uint64_t, 4> by_kind{};
  std::uint64_t aimed_exactly = 0, crossings_total = 0, unbalanced = 0;
  std::vector<std::pair<Vec3, int>> marks;  // target, method that leaked
  std::vector<std::uint32_t> owned_hits;
  for (std::uint64_t n = 0; n < rays; ++n) {
    const Line line = generator.next();
    ++by_kind[static_cast<std::size_t>(line.kind)];
    aimed_exactly += line.exact;
    std::array<std::uint64_t, method_count> hits{};
    owned_hits.clear();
    BvhRayTraversal walk(prepared.bvh(), line.ray);
    const std::span<const Triangle> triangles = prepared.leaf_triangles();
    while (const auto leaf = walk.next()) {
      for (std::size_t i = 0; i < leaf->triangles.size(); ++i) {
        const Triangle& t = triangles[leaf->position + i];
        const TriangleClassification c = relation(line.ray, t, TriangleRule::closed);
        if (c.relation == TriangleRelation::hit) {
          ++hits[closed];
          if (c.owned) {
            ++hits[owned];
            owned_hits.push_back(leaf->triangles[i]);
          }
        }
        if (intersect_naive(line.ray, t).relation == TriangleRelation::hit) ++hits[moller_trumbore];
      }
    }
#ifdef RAYKERNEL_HAVE_EMBREE
    if (have_embree)
      for (int m = 0; m < 2; ++m) hits[embree_default + m] = embree[m]->all_hits(line.ray).size();
#endif
    const std::uint64_t crossings = hits[owned];
    crossings_total += crossings;
    unbalanced += closed_mesh && signed_count(line.ray, mesh, owned_hits) != 0;
    for (int m = 0; m < method_count; ++m) {
      if ((m == embree_default || m == embree_robust) && !have_embree) continue;
      Tally& t = tally[static_cast<std::size_t>(m)];
      const std::uint64_t h = hits[static_cast<std::size_t>(m)];
      const bool leak = closed_mesh && h % 2 == 1;
      t.leaks += leak;
      if (h > crossings) ++t.double_hits;
      if (h < crossings) {
        ++t.misses;
        if (line.kind == Target::vertex && line.exact) ++t.missed_vertices;
      }
      if (leak && !png_path.empty()) marks.push_back({line.target, m});
    }
  }

  std::cout << "mesh " << printable(mesh_path) << ": " << mesh.triangles.size() << " triangles, " << mesh.vertices.size()
            << " vertices, " << (closed_mesh ? "closed" : "not closed (leaks not counted)") << "\n";
  std::cout << "lines: " << rays << " (seed " << seed << "), aimed at " << by_kind[0] << " vertices, " << by_kind[1]
            << " edge points, " << by_kind[2] << " face points, " << by_kind[3] << " random points; " << aimed_exactly
            << " aimed exactly; " << crossings_total << " exact crossings (owned rule)\n";
  std::cout << std::left << std::setw(20) << "method" << std::right << std::setw(10) << "leaks" << std::setw(13)
            << "double-hits" << std::setw(10) << "misses" << std::setw(17) << "missed-vertices" << '\n';
  for (int m = 0; m < method_count; ++m) {
    const Tally& t = tally[static_cast<std::size_t>(m)];
    std::cout << std::left << std::setw(20) << method_names[m] << std::right;
    if ((m == embree_default || m == embree_robust) && !have_embree) {
      std::cout << "  (not built with Embree)\n";
      continue;
    }
    if (m == owned) {  // the reference: only its parity and balance are checks
      std::cout << std::setw(10) << t.leaks << std::setw(13) << "(reference)" << std::setw(10) << "" << std::setw(17) << ""
                << "  unbalanced " << unbalanced << '\n';
      continue;
    }
    std::cout << std::setw(10) << t.leaks << std::setw(13) << t.double_hits << std::setw(10) << t.misses << std::setw(17)
              << t.missed_vertices << '\n';
  }

  if (!png_path.empty()) {
    const MeshView v = view_of(prepared, 512);
    Image image = render_mesh(prepared, v);
    constexpr std::array<std::array<std::uint8_t, 3>, method_count> colours = {
        {{0, 170, 0}, {40, 80, 255}, {230, 20, 20}, {255, 150, 0}, {220, 0, 220}}};
    for (const auto& [target, m] : marks) mark(image, v.project(target), colours[static_cast<std::size_t>(m)], 3);
    if (const auto error = write_png(png_path, image)) {
      std::cerr << "raykernel watertight: " << printable(*error) << '\n';
      return exit_usage;
    }
  }
  return finish_standard_output(exit_ok);
}

}  // namespace raykernel::cli

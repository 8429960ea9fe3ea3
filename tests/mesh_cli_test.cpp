// `raykernel nearest --mesh` and `raykernel inside` (docs/contract.md §7, with §3's and §4's line rules): hand-derived
// answers on an octahedron file through the real binary, in every mesh format; the stream code's paths against
// each other; files that are not meshes (exit 2, "raykernel: FILE:LINE: REASON", nothing on stdout); usage errors.
#include "commands/mesh_nearest.hpp"
#include "rendering/png_image.hpp"

#include <raykernel/io/mesh_file.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <vector>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace raykernel::cli {
namespace {

const std::string cli = RAYKERNEL_CLI_PATH;

struct CliRun {
  int status;
  std::string out, err;
};

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/mesh_cli_" + std::to_string(getpid()) + "_" + name;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  ASSERT_TRUE(f.good());
}

CliRun run(const std::string& args, const std::string& stdin_text = "") {
  const std::string in = temp_path("stdin.txt"), err = temp_path("stderr.txt");
  write_file(in, stdin_text);
  CliRun r{};
  FILE* p = popen((cli + " " + args + " < " + in + " 2> " + err).c_str(), "r");
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
  const int status = pclose(p);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err);
  std::stringstream s;
  s << e.rdbuf();
  r.err = s.str();
  return r;
}

// The octahedron |x| + |y| + |z| = 1, outward normals. Triangle 0 is the face x + y + z = 1; triangles 0–3 hold
// the top vertex (0, 0, 1) (vertex 5); triangle 4 ("f 3 1 6": (0,1,0), (1,0,0), (0,0,−1)) is the face
// x + y − z = 1.
const std::string octahedron_obj = R"(# octahedron
v 1 0 0
v -1 0 0
v 0 1 0
v 0 -1 0
v 0 0 1
v 0 0 -1
f 1 3 5
f 3 2 5
f 2 4 5
f 4 1 5
f 3 1 6
f 2 3 6
f 4 2 6
f 1 4 6
)";

// Rays and their answers, derived by hand:
//   (0,0,0) + t(1,1,1) meets x + y + z = 1 at t = 1/3 (triangle 0; RN(1/3) prints as 0.3333333333333333);
//   (0.25,0.25,−5) + t(0,0,1) meets x + y − z = 1 at z = −0.5, t = 4.5 (triangle 4);
//   (2,2,2) + t(1,0,0) passes outside; (0,0,0) + t(0,0,0) is invalid; "1 2 x" is not a number.
const std::string rays = "0 0 0 1 1 1\n0.25 0.25 -5 0 0 1\n\n# comment\n2 2 2 1 0 0\n0 0 0 0 0 0\n1 2 x 0 0 1\n";
const std::string expected_rays =
    "hit 0 0.3333333333333333\nhit 4 4.5\nmiss\ninvalid ray direction is the zero vector\ninvalid field 3: 'x' is not a number\n";

TEST(MeshCli, NearestOnEveryFormat) {
  const Mesh mesh = io::read_mesh(octahedron_obj, "octahedron.obj", io::MeshFormat::obj);
  struct Format {
    const char* name;
    std::string bytes;
  };
  const Format formats[] = {
      {"oct.obj", octahedron_obj},
      {"oct.off", io::write_mesh(mesh, io::MeshFormat::off)},
      {"oct.ply", io::write_mesh(mesh, io::MeshFormat::ply, io::MeshEncoding::binary_big_endian)},
      {"oct-ascii.ply", io::write_mesh(mesh, io::MeshFormat::ply)},
      {"oct.stl", io::write_mesh(mesh, io::MeshFormat::stl, io::MeshEncoding::binary_little_endian)},
  };
  for (const Format& f : formats) {
    const std::string path = temp_path(f.name);
    write_file(path, f.bytes);
    const CliRun r = run("nearest --mesh " + path, rays);
    EXPECT_EQ(r.status, 1) << f.name;  // some ray lines invalid
    EXPECT_EQ(r.out, expected_rays) << f.name;
    EXPECT_NE(r.err.find("raykernel: line 6: ray direction is the zero vector"), std::string::npos) << r.err;
  }
}

TEST(MeshCli, NearestRules) {
  const std::string path = temp_path("oct.obj");
  write_file(path, octahedron_obj);
  // Down the z axis onto the top vertex at t = 4: closed, every triangle around it is hit and the smallest index
  // (0) wins; owned, exactly one of the four owns it.
  CliRun r = run("nearest --rule=closed --mesh=" + path + " --exact-t", "0 0 5 0 0 -1\n");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, "hit 0 4 4/1\n");
  r = run("nearest --mesh " + path + " --rule owned", "0 0 5 0 0 -1\n");
  EXPECT_EQ(r.status, 0);
  EXPECT_TRUE(r.out == "hit 0 4\n" || r.out == "hit 1 4\n" || r.out == "hit 2 4\n" || r.out == "hit 3 4\n") << r.out;
  r = run("nearest --mesh " + path + " --hex", "0 0 0 1 1 1\n");
  EXPECT_EQ(r.out, "hit 0 0x1.5555555555555p-2\n");
  r = run("nearest --mesh " + path + " --stats -", "0 0 0 1 1 1\n");
  EXPECT_NE(r.err.find("1 rays: 1 hit, 0 miss, 0 invalid"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("near ties (two t the filter could not order): 0 "), std::string::npos) << r.err;
  // Closed, through the top vertex: the four triangles around it tie at t = 4, settled from the vertices (one
  // crossing point) without arithmetic.
  r = run("nearest --rule=closed --mesh " + path + " --stats -", "0 0 5 0 0 -1\n");
  EXPECT_EQ(r.out, "hit 0 4\n");
  EXPECT_NE(r.err.find("near ties (two t the filter could not order): 3 (settled from the vertices 3; compared by: "
                       "filter 0, compensated 0, expansion 0, exact 0)"),
            std::string::npos)
      << r.err;
  r = run("nearest --mesh " + path + " --path=naive --stats -", "0 0 0 1 1 1\n");
  EXPECT_NE(r.err.find("path naive: no stages"), std::string::npos) << r.err;
}

TEST(MeshCli, Inside) {
  const std::string path = temp_path("oct.obj");
  write_file(path, octahedron_obj);
  // (0,0,0): inside; (0.5,0.5,0): on the edge (1,0,0)–(0,1,0); (0.5,0.25,0.25): on face 0; (0.5,0.5,0.25):
  // |x|+|y|+|z| = 5/4, outside; (0,0,0.5): inside, its axis ray runs through the top vertex.
  const CliRun r = run("inside --mesh " + path, "0 0 0\n0.5 0.5 0\n0.5 0.25 0.25\n0.5 0.5 0.25\n0 0 0.5\n1 1\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "inside\non-surface\non-surface\noutside\ninside\ninvalid expected 3 numbers, found 2\n");
  const CliRun ok = run("inside --mesh " + path + " --stats", "0 0 0\n");
  EXPECT_EQ(ok.status, 0);
  EXPECT_EQ(ok.out, "inside\n");
}

TEST(MeshCli, Closest) {
  const std::string path = temp_path("oct-closest.obj");
  write_file(path, octahedron_obj);
  // (2,0,0): the vertex (1,0,0), vertex a of triangle 0 (f 1 3 5), d² = 1. (0,0,0): every face at 1/√3, the foot
  // on triangle 0 is (1/3,1/3,1/3), d² = 1/3, √(1/3) = 0.57735026918962576… rounds to 0.5773502691896257, inside.
  // (1,1,0): the midpoint (1/2,1/2,0) of edge ab of triangle 0 (shared with triangle 4), d² = 1/2, √(1/2) rounds
  // to 0.7071067811865476.
  const CliRun r = run("closest --signed --mesh " + path, "2 0 0\n0 0 0\n1 1 0\n1 1\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out,
            "0 vertex 0 1 0 0 1 1 1 1/1\n"
            "0 face 0 0.3333333333333333 0.3333333333333333 0.3333333333333333 0.3333333333333333 "
            "0.5773502691896257 -0.5773502691896257 1/3\n"
            "0 edge 0 0.5 0.5 0 0.5 0.7071067811865476 0.7071067811865476 1/2\n"
            "invalid expected 3 numbers, found 2\n");
  const CliRun plain = run("closest --mesh " + path + " --stats", "2 0 0\n");
  EXPECT_EQ(plain.status, 0);
  EXPECT_EQ(plain.out, "0 vertex 0 1 0 0 1 1 1/1\n");
  EXPECT_NE(plain.err.find("1 points: 1 at a vertex, 0 on an edge, 0 on a face, 0 invalid"), std::string::npos) << plain.err;
  const std::string empty = temp_path("empty.obj");
  write_file(empty, "v 0 0 0\n");
  const CliRun none = run("closest --mesh " + empty, "0 0 0\n");
  EXPECT_EQ(none.status, 2);
  EXPECT_EQ(none.out, "");
  EXPECT_NE(none.err.find("no triangles"), std::string::npos) << none.err;
}

TEST(MeshCli, FilesThatAreNotMeshes) {
  struct Bad {
    const char* name;
    const char* text;
    const char* message;  // after "raykernel: PATH"
  };
  const Bad bad[] = {
      {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", ":4: "},
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", ":2: "},
      {"short.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", ":3: "},
      // Regression: aborted (SIGABRT) with three vertices, loaded as triangle [0, 1, 3] with a fourth after.
      {"int64-min.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n", ":4: relative vertex index"},
      {"int64-min-then-vertex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\nv 0 0 1\n", ":4: relative vertex index"},
      {"count.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", ""},
      {"unknown.xyz", "hello\n", ""},
      {"empty.stl", "", ""},
  };
  for (const Bad& b : bad) {
    const std::string path = temp_path(b.name);
    write_file(path, b.text);
    for (const char* command : {"nearest --mesh ", "inside --mesh ", "watertight "}) {
      const CliRun r = run(command + path + (std::string_view(command) == "watertight " ? " --rays 10" : ""), "0 0 0 1 0 0\n");
      EXPECT_EQ(r.status, 2) << b.name;
      EXPECT_EQ(r.out, "") << b.name;
      EXPECT_EQ(r.err.rfind("raykernel: " + path + b.message, 0), 0u) << b.name << ": " << r.err;
    }
  }
  const CliRun missing = run("inside --mesh " + temp_path("does-not-exist.obj"), "0 0 0\n");
  EXPECT_EQ(missing.status, 2);
  EXPECT_EQ(missing.out, "");
  EXPECT_NE(missing.err.find("does-not-exist.obj"), std::string::npos);
}

// Regression: every std::bad_alloc becomes "not enough memory for WHAT", exit 2 — never std::terminate. A mesh
// of 150,000 vertices (5 MB of OBJ) under address-space limits from too small to enough: each run answers
// or says which file it could not hold, and at least one run runs out.
TEST(MeshCli, RunningOutOfMemoryIsAMessageNamingTheFileNeverACrash) {
  const std::string path = temp_path("big.obj");
  {
    std::ofstream f(path, std::ios::binary);
    const int n = 150000;
    for (int i = 0; i < n; ++i) f << "v " << i << ' ' << i * 7 % 1000 << ' ' << i * 13 % 1000 << '\n';
    for (int i = 1; i + 2 <= n; ++i) f << "f " << i << ' ' << i + 1 << ' ' << i + 2 << '\n';
  }
  int out_of_memory = 0, answered = 0;
  for (int limit_kb = 40000; limit_kb <= 240000; limit_kb += 20000) {
    const std::string err = temp_path("oom-err.txt"), out = temp_path("oom-out.txt");
    const int status = std::system(("(ulimit -v " + std::to_string(limit_kb) + " && echo '0 0 -1 0 0 1' | " + cli +
                                    " nearest --mesh " + path + " > " + out + " 2> " + err + ")").c_str());
    std::ifstream e(err), o(out);
    std::stringstream es, os;
    es << e.rdbuf();
    os << o.rdbuf();
    ASSERT_TRUE(WIFEXITED(status)) << limit_kb << " KB: " << es.str();
    const int code = WEXITSTATUS(status);
    if (code == 127) continue;  // too small to load the program's shared libraries at all
    if (code == 0) {
      EXPECT_EQ(os.str(), "miss\n") << limit_kb << " KB";
      ++answered;
      continue;
    }
    EXPECT_EQ(code, 2) << limit_kb << " KB: " << es.str();
    EXPECT_NE(es.str().find("not enough memory for "), std::string::npos) << limit_kb << " KB: " << es.str();
    EXPECT_NE(es.str().find(path), std::string::npos) << limit_kb << " KB: " << es.str();
    EXPECT_EQ(os.str(), "") << limit_kb << " KB";
    ++out_of_memory;
  }
  EXPECT_GT(out_of_memory, 0);
  EXPECT_GT(answered, 0);
}

TEST(MeshCli, UsageErrors) {
  const std::string path = temp_path("oct.obj");
  write_file(path, octahedron_obj);
  for (const std::string& args : {"nearest --mesh " + path + " --planes " + path, "nearest --rule=closed --planes " + path,
                                 "nearest --mesh " + path + " --rule=open", std::string("nearest --mesh"), std::string("inside"),
                                 "inside --mesh " + path + " --mesh " + path, "inside --mesh " + path + " --bogus"}) {
    const CliRun r = run(args, "0 0 0\n");
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(r.out, "") << args;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  EXPECT_EQ(run("inside --help").status, 0);
}

// Each output row: the method's name, then leaks, double-hits, misses, missed-vertices.
std::vector<std::string> row(const std::string& out, const std::string& method) {
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line))
    if (line.starts_with(method)) {
      std::istringstream words(line.substr(method.size()));
      std::vector<std::string> w;
      for (std::string x; words >> x;) w.push_back(x);
      return w;
    }
  return {};
}

// spawn-audit on the octahedron: raykernel's origins, binary32 and binary64, never self-hit, are always on the
// side the new ray leaves towards and meet first what the exact ray from the exact hit point meets; Ray Tracing
// in One Weekend's origin, the rounded hit point, lies on the wrong side (or on the plane) for about half the
// rays. The picture has one 320-pixel panel per method, four to a row.
TEST(MeshCli, SpawnAudit) {
  const std::string path = temp_path("oct-audit.obj"), png = temp_path("spawn-audit.png");
  write_file(path, octahedron_obj);
  const CliRun r = run("spawn-audit " + path + " --hits 20 --seed 3 --png " + png);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("hits: 20 "), std::string::npos) << r.out;
  for (const char* m : {"raykernel-32", "raykernel-64"}) {
    const auto cells = row(r.out, m);
    ASSERT_EQ(cells.size(), 9u) << r.out;
    EXPECT_EQ(cells[1], "60") << r.out;  // 20 hits, 3 directions each
    EXPECT_EQ(cells[2], "0") << r.out;   // no origin
    EXPECT_EQ(cells[3], "0") << r.out;   // self-hits
    EXPECT_EQ(cells[4], "0") << r.out;   // behind
    EXPECT_EQ(cells[5], "0") << r.out;   // on the plane
    EXPECT_EQ(cells[6], "0") << r.out;   // first hit differs
  }
  const auto weekend = row(r.out, "one-weekend");
  ASSERT_EQ(weekend.size(), 9u) << r.out;
  EXPECT_GT(std::stoi(weekend[4]) + std::stoi(weekend[5]), 10) << r.out;
  const std::optional<cli::Image> image = cli::read_png(png);
  ASSERT_TRUE(image.has_value());
  EXPECT_EQ(image->width, 4u * 320);
  EXPECT_EQ(image->height, 2u * 320);
  EXPECT_EQ(run("spawn-audit " + path + " --hits 0").status, 2);
  EXPECT_EQ(run("spawn-audit " + path + " --scale-exponent 200").status, 2);
  EXPECT_EQ(run("spawn-audit " + temp_path("does-not-exist.obj")).status, 2);
  EXPECT_EQ(run("spawn-audit").status, 2);
}

// On the closed octahedron the owned rule never leaks and its crossings balance (docs/contract.md §6);
// the closed rule leaks on lines through vertices: a line entering at the top vertex (0, 0, 1) meets the four
// triangles around it and leaves through one face, 5 hits.
TEST(MeshCli, Watertight) {
  const std::string path = temp_path("oct.obj"), png = temp_path("watertight.png");
  write_file(path, octahedron_obj);
  const CliRun r = run("watertight " + path + " --rays 400 --seed 7 --png " + png);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("8 triangles, 6 vertices, closed"), std::string::npos) << r.out;
  EXPECT_EQ(row(r.out, "owned (raykernel)"), (std::vector<std::string>{"0", "(reference)", "unbalanced", "0"})) << r.out;
  const auto closed = row(r.out, "closed (raykernel)");
  ASSERT_EQ(closed.size(), 4u) << r.out;
  EXPECT_GT(std::stoi(closed[0]), 0) << r.out;
  EXPECT_EQ(closed[2], "0");  // the closed rule never misses an owned crossing (the owned points are closed ones)
  std::ifstream f(png, std::ios::binary);
  EXPECT_TRUE(f.good());
  // Both spellings of a value, as every command takes them (watertight alone refused --rays=N).
  const CliRun attached = run("watertight --rays=40 --seed=7 " + path);
  EXPECT_EQ(attached.status, 0) << attached.err;
  EXPECT_NE(attached.out.find("lines: 40 (seed 7)"), std::string::npos) << attached.out;
  EXPECT_EQ(run("watertight " + path + " --rays 0").status, 2);
  EXPECT_EQ(run("watertight " + path + " --rays x").status, 2);
  EXPECT_EQ(run("watertight").status, 2);
  EXPECT_EQ(run("watertight " + temp_path("does-not-exist.obj")).status, 2);
}

// The three paths of the stream code on the hand-derived rays: the certified one and the exact brute force agree
// (the certified one is the contract's); Möller–Trumbore agrees on these easy rays.
TEST(MeshCli, StreamPaths) {
  const PreparedMesh mesh(io::read_mesh(octahedron_obj, "octahedron.obj", io::MeshFormat::obj));
  for (const Method method : {Method::certified, Method::exact, Method::naive}) {
    std::istringstream in(rays);
    std::ostringstream out, err;
    MeshNearestCounts counts;
    EXPECT_EQ(mesh_nearest_stream(in, out, err, mesh, {.method = method}, counts), exit_invalid_line);
    EXPECT_EQ(out.str(), expected_rays);
    EXPECT_EQ(counts.hits, 2u);
    EXPECT_EQ(counts.misses, 1u);
    EXPECT_EQ(counts.invalid, 2u);
  }
}

// docs/contract.md §8 through the binary, answers derived by hand on the octahedron above: (2,0,0) + t(−1,0,0) meets
// the vertex (1,0,0) at t = 1 (triangles 0, 3, 4, 7 hold it) and leaves through (−1,0,0) at t = 3 (triangles 1, 2,
// 5, 6); the owned rule gives each vertex to exactly one of its triangles. Entering, d·N < 0 for every outward
// normal there (N_x > 0): −1; leaving, +1.
TEST(MeshCli, OccludedRaysWithIntervalsAndSegments) {
  const std::string path = temp_path("occ.obj");
  write_file(path, octahedron_obj);
  const CliRun r = run("occluded --mesh " + path,
                       "2 0 0 -1 0 0\n2 0 0 -1 0 0 0 1\n2 0 0 -1 0 0 0 0x1.fffffffffffffp-1\n"
                       "2 0 0 -1 0 0 1.5 infinity\n2 0 0 -1 0 0 0x1.8000000000001p+1 INF\n"
                       "2 0 0 -1 0 0 2 1\n2 0 0 -1 0 0 inf inf\n2 0 0 -1 0 0 0\n2 0 0 -1 0 0 0 1e400\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out,
            "occluded\noccluded\nclear\noccluded\nclear\n"
            "invalid t_min is greater than t_max\ninvalid field 7 (t_min): 'inf' is not finite\n"
            "invalid expected 6 or 8 numbers, found 7\ninvalid field 8 (t_max): '1e400' overflows the double range\n");
  EXPECT_NE(r.err.find("raykernel: line 6: t_min is greater than t_max"), std::string::npos) << r.err;
  // Segments: through the vertex (1,0,0); ending exactly on the face x + y + z = 1; an ulp beyond it; p = q.
  const CliRun s = run("occluded --segment --mesh " + path,
                       "0 0 0 2 0 0\n0 0 0 0.25 0.25 0.5\n0 0 0 0.25 0.25 0x1.0000000000001p-1\n1 1 1 1 1 1\n");
  EXPECT_EQ(s.status, 1);
  EXPECT_EQ(s.out, "occluded\nclear\noccluded\ninvalid segment endpoints are equal (p = q)\n");
  EXPECT_EQ(run("occluded --segment --rule=closed --mesh " + path, "0 0 0 0.25 0.25 0.5\n").out, "clear\n");
  // Usage: --mesh is required (exit 2, nothing on stdout).
  const CliRun u = run("occluded", "0 0 0 1 0 0\n");
  EXPECT_EQ(u.status, 2);
  EXPECT_EQ(u.out, "");
  EXPECT_NE(u.err.find("--mesh FILE is required"), std::string::npos);
  auto one_of = [](const std::string& k, std::initializer_list<const char*> ks) {
    for (const char* x : ks)
      if (k == x) return true;
    return false;
  };
  // nearest --mesh with an interval: the exit vertex at t = 3 when the entry is excluded.
  std::istringstream n(run("nearest --mesh " + path, "2 0 0 -1 0 0 1.5 inf\n2 0 0 -1 0 0 3.5 inf\n").out);
  std::string word, k, t;
  n >> word >> k >> t;
  EXPECT_EQ(word, "hit");
  EXPECT_TRUE(one_of(k, {"1", "2", "5", "6"})) << k;
  EXPECT_EQ(t, "3");
  n >> word;
  EXPECT_EQ(word, "miss");
  // hits: both vertices in order, the signed count −1 + 1 = 0; in [0, 2] the entry alone, −1.
  const CliRun h = run("hits --mesh " + path, "2 0 0 -1 0 0\n2 0 0 -1 0 0 0 2\n");
  EXPECT_EQ(h.status, 0);
  std::istringstream lines(h.out);
  std::string hits, count, crossings, c, k1, t1, k2, t2;
  lines >> hits >> count >> crossings >> c >> k1 >> t1 >> k2 >> t2;
  EXPECT_EQ(hits + " " + count + " " + crossings + " " + c, "hits 2 crossings 0");
  EXPECT_TRUE(one_of(k1, {"0", "3", "4", "7"})) << k1;
  EXPECT_TRUE(one_of(k2, {"1", "2", "5", "6"})) << k2;
  EXPECT_EQ(t1 + " " + t2, "1 3");
  lines >> hits >> count >> crossings >> c >> k1 >> t1;
  EXPECT_EQ(hits + " " + count + " " + crossings + " " + c + " " + t1, "hits 1 crossings -1 1");
  EXPECT_TRUE(one_of(k1, {"0", "3", "4", "7"})) << k1;
}

}  // namespace
}  // namespace raykernel::cli

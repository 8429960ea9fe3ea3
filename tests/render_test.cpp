// The `nearest` and `render` commands: nearest on streams and through the binary (docs/contract.md §4 and the
// sample cases), scene files (every kind of error, with its JSON Pointer), rendering (hand-derived
// pixels, supersampling, determinism across thread counts, the demo's stage and naive-difference counts),
// PNG output, and the binary's usage errors.
#include "commands/plane_nearest.hpp"
#include "rendering/png_image.hpp"
#include "rendering/render.hpp"
#include "scenes/scene.hpp"
#include "support/answer_lines.hpp"

#include <raykernel/io/mesh_file.hpp>

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace raykernel::cli {
namespace {

const std::string cli = RAYKERNEL_CLI_PATH;
const std::string cases = RAYKERNEL_CASES_DIR;
const std::string scenes = RAYKERNEL_SCENES_DIR;

struct CliRun {
  int status;
  std::string out, err;
};

// Per process: ctest runs each test case as its own process, in parallel.
std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/raykernel_render_test_" + std::to_string(getpid()) + "_" + name;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}
std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs the binary (in directory `dir` when given) with stdin from `stdin_text`.
CliRun run(const std::string& args, const std::string& stdin_text = "", const std::string& dir = "") {
  const std::string in = temp_path("stdin.txt"), err = temp_path("stderr.txt");
  write_file(in, stdin_text);
  const std::string command = (dir.empty() ? "" : "cd '" + dir + "' && ") + cli + " " + args + " < " + in + " 2> " + err;
  CliRun r{};
  FILE* p = popen(command.c_str(), "r");
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
  const int status = pclose(p);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_file(err);
  return r;
}

// ---- nearest ---------------------------------------------------------------------------------------------

std::vector<std::string> lines_of(const std::string& text) {
  std::istringstream s(text);
  std::vector<std::string> lines;
  for (std::string l; std::getline(s, l);) lines.push_back(l);
  return lines;
}

TEST(Nearest, ContractSampleOnStreams) {
  std::ifstream planes_file(cases + "/nearest-sample/planes.txt");
  const PlanesFile planes = read_planes(planes_file);
  ASSERT_TRUE(planes.ok()) << planes.error;
  ASSERT_EQ(planes.items.size(), 51u);
  const auto expected = test_support::read_lines(cases + "/nearest-sample/expected.txt");
  for (Method method : {Method::certified, Method::exact}) {
    std::ifstream rays(cases + "/nearest-sample/rays.txt");
    std::ostringstream out, err;
    NearestOptions options;
    options.method = method;
    NearestCounts counts;
    EXPECT_EQ(nearest_stream(rays, out, err, planes.items, options, counts), exit_ok);
    const auto got = lines_of(out.str());
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i)
      EXPECT_TRUE(test_support::same_nearest_answer(got[i], expected[i])) << "ray " << i + 1 << "\n  got:  " << got[i]
                                                                  << "\n  want: " << expected[i];
    EXPECT_EQ(err.str(), "");
  }
}

TEST(Nearest, ContractSampleThroughTheBinary) {
  const CliRun r = run("nearest --planes " + cases + "/nearest-sample/planes.txt " + cases + "/nearest-sample/rays.txt");
  EXPECT_EQ(r.status, 0);
  const auto got = lines_of(r.out);
  const auto expected = test_support::read_lines(cases + "/nearest-sample/expected.txt");
  ASSERT_EQ(got.size(), expected.size());
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < got.size(); ++i) wrong += !test_support::same_nearest_answer(got[i], expected[i]);
  EXPECT_EQ(wrong, 0u);
}

TEST(Nearest, HandDerivedAnswersAndInvalidRays) {
  // Planes: 0: z = 5; 1: z = 3 (normal −z); 2: x = 1. Ray 1 (+z from 0): hit 1 at t = 3. Ray 2 (−z from 0):
  // every plane behind or parallel: miss. Ray 3 (+x from 0): plane 2 at t = 1 (z planes parallel).
  // Ray 4 (+z scaled by 10): t = 0.3, exact 3/10. Line 6 is invalid (zero direction), line 7 too (5 numbers).
  const std::vector<Plane> planes = {{{0, 0, 5}, {0, 0, 1}}, {{0, 0, 3}, {0, 0, -1}}, {{1, 0, 0}, {1, 0, 0}}};
  std::istringstream rays("0 0 0 0 0 1\n0 0 0 0 0 -1\n# a comment\n0 0 0 1 0 0\n0 0 0 0 0 10\n\n0 0 0 0 0 0\n1 2 3 4 5\n");
  std::ostringstream out, err;
  NearestOptions options;
  options.exact_t = true;
  NearestCounts counts;
  EXPECT_EQ(nearest_stream(rays, out, err, planes, options, counts), exit_invalid_line);
  EXPECT_EQ(out.str(),
            "hit 1 3 3/1\nmiss\nhit 2 1 1/1\nhit 1 0.3 3/10\ninvalid ray direction is the zero vector\n"
            "invalid expected 6 numbers, found 5\n");
  EXPECT_EQ(err.str(), "raykernel: line 7: ray direction is the zero vector\nraykernel: line 8: expected 6 numbers, found 5\n");
  EXPECT_EQ(counts.hits, 3u);
  EXPECT_EQ(counts.misses, 1u);
  EXPECT_EQ(counts.invalid, 2u);
}

TEST(Nearest, SubUlpOrderAndTiesOnEveryPath) {
  // Plane 0: x = 1 (t = 1); plane 1: point (1, 1, 0), normal (1, −2^-60, 0): t = 1 − 2^-60, nearer, and
  // both round to 1. Certified and exact answer plane 1; the naive loop sees two t = 1 and keeps plane 0.
  const std::vector<Plane> planes = {{{1, 0, 0}, {1, 0, 0}}, {{1, 1, 0}, {1, -0x1p-60, 0}}};
  auto answer = [&](Method method) {
    std::istringstream rays("0 0 0 1 0 0\n");
    std::ostringstream out, err;
    NearestOptions options;
    options.method = method;
    options.hex = true;
    NearestCounts counts;
    (void)nearest_stream(rays, out, err, planes, options, counts);
    return out.str();
  };
  EXPECT_EQ(answer(Method::certified), "hit 1 0x1p+0\n");
  EXPECT_EQ(answer(Method::exact), "hit 1 0x1p+0\n");
  EXPECT_EQ(answer(Method::naive), "hit 0 0x1p+0\n");
}

TEST(Nearest, InvalidPlaneLinesAreReportedWithFileAndLine) {
  std::istringstream zero_normal("# planes\n0 0 5 0 0 1\n\n1 2 3 0 -0 0\n");
  const PlanesFile f = read_planes(zero_normal);
  EXPECT_FALSE(f.ok());
  EXPECT_EQ(f.error_line, 4u);
  EXPECT_EQ(f.error, "plane normal is the zero vector");
  std::istringstream bad_token("0 0 5 0 0 1 7\n");
  EXPECT_EQ(read_planes(bad_token).error, "expected 6 numbers, found 7; the extra ones start at token 7, column 13: '7'");

  const std::string path = temp_path("planes.txt");
  write_file(path, "0 0 5 0 0 1\n0 0 nan 0 0 1\n");
  const CliRun r = run("nearest --planes " + path, "0 0 0 0 0 1\n");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "") << "nothing on stdout when a plane line is invalid";
  EXPECT_EQ(r.err, "raykernel: " + path + ":2: field 3: 'nan' is not finite\n");
}

TEST(Nearest, PlanesAndRaysFilesMayStartWithAByteOrderMark) {
  const std::string planes = temp_path("bom-planes.txt");
  write_file(planes, "\xEF\xBB\xBF" "0 0 5 0 0 1\n");
  const CliRun r = run("nearest --planes " + planes, "\xEF\xBB\xBF" "0 0 0 0 0 1\n");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "hit 0 5\n");
}

TEST(Nearest, APlaneNumberThatRoundsToZeroIsAnInvalidPlaneLine) {
  // Read as doubles the normal would be (0, 0, 0): the line is invalid because 1e-400 is not 0.
  std::istringstream text("0 0 5 0 0 1\n0 0 5 0 0 1e-400\n");
  const PlanesFile f = read_planes(text);
  EXPECT_EQ(f.error_line, 2u);
  EXPECT_EQ(f.error,
            "field 6: '1e-400' is nonzero but rounds to zero when read (its magnitude is at most 2^-1075, half the "
            "smallest subnormal)");
}

TEST(Nearest, UsageErrors) {
  EXPECT_EQ(run("nearest", "0 0 0 0 0 1\n").status, 2);  // no --planes
  EXPECT_EQ(run("nearest --planes /nonexistent/planes.txt", "").status, 2);
  const std::string path = temp_path("one-plane.txt");
  write_file(path, "0 0 5 0 0 1\n");
  EXPECT_EQ(run("nearest --planes " + path + " /nonexistent/rays.txt").status, 2);
  EXPECT_EQ(run("nearest --planes " + path + " --bogus").status, 2);
  EXPECT_EQ(run("nearest --planes " + path + " --path=fast").status, 2);
  EXPECT_EQ(run("nearest --planes " + path + " a b").status, 2);
  const CliRun ok = run("nearest --planes=" + path + " -", "0 0 0 0 0 1\n0 0 0 0 0 0\n");
  EXPECT_EQ(ok.status, 1);
  EXPECT_EQ(ok.out, "hit 0 5\ninvalid ray direction is the zero vector\n");
  const CliRun stats = run("nearest --stats --planes " + path, "0 0 0 0 0 1\n");
  EXPECT_NE(stats.err.find("comparisons of two t"), std::string::npos) << stats.err;
}

TEST(Commands, EveryCommandAnswersHelpAndIsListed) {
  for (const char* sub : {"nearest --help", "render --help"}) {
    const CliRun help = run(sub);
    EXPECT_EQ(help.status, 0) << sub;
    EXPECT_NE(help.out.find("usage: raykernel"), std::string::npos) << sub;
  }
  const CliRun overview = run("");
  EXPECT_NE(overview.out.find("nearest --planes FILE"), std::string::npos);
  EXPECT_NE(overview.out.find("render [SCENE.json]"), std::string::npos);
}

// ---- Scenes ----------------------------------------------------------------------------------------------

TEST(Scene, TheDemoIsValidAndIsScenesDemoJsonByteForByte) {
  const SceneParse demo = parse_scene(demo_scene_json());
  ASSERT_TRUE(demo.scene) << demo.error.str();
  EXPECT_EQ(demo.scene->image.width, 960u);
  EXPECT_EQ(demo.scene->image.height, 540u);
  EXPECT_EQ(demo.scene->samples_per_pixel, 4u);
  EXPECT_EQ(demo.scene->planes.size(), 6u);
  EXPECT_EQ(read_file(scenes + "/demo.json"), std::string(demo_scene_json()));
}

TEST(Scene, EveryExampleSceneIsValid) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(scenes)) {
    if (entry.path().extension() != ".json") continue;
    const SceneParse s = parse_scene(read_file(entry.path().string()));
    EXPECT_TRUE(s.scene) << entry.path() << ": " << s.error.str();
    ++count;
  }
  EXPECT_GE(count, 3);
}

// A minimal valid scene with `planes` substituted, for the error tests.
std::string scene_with(const std::string& image, const std::string& camera, const std::string& planes) {
  return "{\"image\": " + image + ",\n \"camera\": " + camera + ",\n \"planes\": " + planes + "}";
}
const std::string good_image = R"({"width": 4, "height": 2})";
const std::string good_camera = R"({"eye": [0, 1, 5], "target": [0, 0, 0], "up": [0, 1, 0], "perspective": {"fov_degrees": 60}})";
const std::string good_planes = R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [0.5, 0.5, 0.5]}])";

std::string error_of(const std::string& text) {
  const SceneParse s = parse_scene(text);
  if (s.scene) return "(valid)";
  return s.error.str();
}

TEST(Scene, ErrorsNameTheJsonPointerAndTheReason) {
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, good_planes)), "(valid)");
  // Missing and unknown fields.
  EXPECT_EQ(error_of(R"({"image": {"width": 4, "height": 2}, "planes": []})"), "/camera: missing field");
  EXPECT_EQ(error_of(R"({"camera": {"eye": [0, 1, 5]}, "planes": []})"), "/camera/target: missing field");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "colour": [1, 0, 0]}])")),
            "/planes/0/colour: unknown field (expected one of: name, point, normal, color, checker)");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [0, 0, 0], "color": [0, 1, 0]}])")),
            "/planes/0/normal: missing field");
  // Mistyped fields.
  EXPECT_EQ(error_of(scene_with(R"({"width": "640", "height": 2})", good_camera, good_planes)),
            "/image/width: expected an integer, found a string");
  EXPECT_EQ(error_of(scene_with(R"({"width": 640.5, "height": 2})", good_camera, good_planes)),
            "/image/width: expected an integer, found a number with a fraction");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"({"point": [0, 0, 0]})")),
            "/planes: expected an array of planes, found an object");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [0, 0], "normal": [0, 1, 0], "color": [1, 0, 0]}])")),
            "/planes/0/point: expected an array of 3 numbers, found an array of 2");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [0, null, 0], "normal": [0, 1, 0], "color": [1, 0, 0]}])")),
            "/planes/0/point/1: expected a number, found a null");
  EXPECT_EQ(error_of("[1, 2]"), "expected an object, found an array");
  // Values out of range.
  EXPECT_EQ(error_of(scene_with(R"({"width": 0, "height": 2})", good_camera, good_planes)), "/image/width: must be positive");
  EXPECT_EQ(error_of(scene_with(R"({"width": 4, "height": -3})", good_camera, good_planes)), "/image/height: must be positive");
  EXPECT_EQ(error_of(scene_with(R"({"width": 4, "height": 2, "samples_per_pixel": 0})", good_camera, good_planes)),
            "/image/samples_per_pixel: must be positive");
  EXPECT_EQ(error_of(scene_with(R"({"width": 100000, "height": 2})", good_camera, good_planes)),
            "/image/width: out of range (at most 16384)");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 1.5, 0]}])")),
            "/planes/0/color/1: colour component outside [0, 1]");
  EXPECT_EQ(error_of(scene_with(good_image, R"({"eye": [0, 1, 5], "target": [0, 0, 0], "up": [0, 1, 0], "perspective": {"fov_degrees": 180}})",
                                good_planes)),
            "/camera/perspective/fov_degrees: must be in (0, 180)");
  // Zero vectors and degenerate cameras.
  EXPECT_EQ(error_of(scene_with(good_image, good_camera,
                                R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 0, 0]},
                                    {"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 0, 0]},
                                    {"point": [0, 0, 0], "normal": [0, -0.0, 0], "color": [1, 0, 0]}])")),
            "/planes/2/normal: zero vector");
  EXPECT_EQ(error_of(scene_with(good_image, R"({"eye": [1, 2, 3], "target": [1, 2, 3], "up": [0, 1, 0], "perspective": {"fov_degrees": 60}})",
                                good_planes)),
            "/camera/target: same point as eye");
  EXPECT_EQ(error_of(scene_with(good_image, R"({"eye": [0, 5, 0], "target": [0, 0, 0], "up": [0, 1, 0], "perspective": {"fov_degrees": 60}})",
                                good_planes)),
            "/camera/up: parallel to the view direction (eye to target)");
  EXPECT_EQ(error_of(scene_with(good_image, R"({"eye": [0, 5, 0], "target": [0, 0, 0]})", good_planes)),
            "/camera: the default up vector [0, 1, 0] is parallel to the view direction (eye to target): give \"up\"");
  // Exclusive choices.
  EXPECT_EQ(error_of(scene_with(good_image, good_camera,
                                R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 0, 0], "checker": {"colors": [[0, 0, 0], [1, 1, 1]], "size": 1}}])")),
            "/planes/0: give either color or checker, not both");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera,
                                R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "checker": {"colors": [[0, 0, 0], [1, 1, 1], [1, 0, 0]], "size": 1}}])")),
            "/planes/0/checker/colors: expected an array of 2 colours, found an array of 3");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera,
                                R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "checker": {"colors": [[0, 0, 0], [1, 1, 1]], "size": 1, "u_axis": [0, 2, 0]}}])")),
            "/planes/0/checker/u_axis: parallel to the plane's normal");
}

// Regressions found by the scene fuzzer (fuzz/corpus/scene/regression-*): cameras whose image rays overflow
// or whose window underflows to nothing were accepted, and the render then failed without a pointer. Each
// is now rejected under /camera. Hand-derived: right − left = 2e308 overflows; tan(89.5°)·1e307 ≈ 1.1e309
// overflows; tan(0.5°)·5e-324 rounds to 0 (an empty window); eye x + window x = 1.7e308 + 1e308 overflows.
TEST(SceneRegression, CameraWhoseImageRaysAreNotFiniteIsRejectedUnderCamera) {
  const char* cameras[] = {
      R"("orthographic": {"window": {"left": -1e308, "right": 1e308, "bottom": -1, "top": 1}})",
      R"("perspective": {"fov_degrees": 179, "near": 1e307})",
      R"("perspective": {"fov_degrees": 1, "near": 5e-324})",
  };
  for (const char* camera : cameras) {
    const std::string text = std::string(R"({"image": {"width": 1, "height": 1}, "camera": {"eye": [0, 0, 0], )") +
                             R"("target": [0, 0, -1], "up": [0, 1, 0], )" + camera + R"(}, "planes": []})";
    const SceneParse s = parse_scene(text);
    ASSERT_FALSE(s.scene.has_value()) << camera;
    EXPECT_EQ(s.error.pointer.rfind("/camera", 0), 0u) << camera << ": " << s.error.str();
  }
  const SceneParse far = parse_scene(
      R"({"image": {"width": 1, "height": 1}, "camera": {"eye": [1.7e308, 0, 0], "target": [1.7e308, 0, -1], )"
      R"("up": [0, 1, 0], "orthographic": {"window": {"left": 1e308, "right": 1.1e308, "bottom": -1, "top": 1}}},)"
      R"( "planes": []})");
  ASSERT_FALSE(far.scene.has_value());
  EXPECT_EQ(far.error.pointer, "/camera") << far.error.str();
}

TEST(SceneRegression, TargetTooFarFromTheEyeIsTheTargetsFault) {
  // target − eye = −1e308 − 1e308 overflows: reported at /camera/target, not as an up vector problem.
  const SceneParse s = parse_scene(
      R"({"image": {"width": 1, "height": 1}, "camera": {"eye": [1e308, 0, 0], "target": [-1e308, 0, 0], )"
      R"("up": [0, 1, 0], "perspective": {"fov_degrees": 60, "near": 0.1}}, "planes": []})");
  ASSERT_FALSE(s.scene.has_value());
  EXPECT_EQ(s.error.pointer, "/camera/target");
  EXPECT_NE(s.error.message.find("overflows"), std::string::npos) << s.error.str();
}

TEST(Scene, NonFiniteNumbersAreLocated) {
  // JSON has no NaN or infinity; 1e999 overflows the double range, which nlohmann reports without a
  // location: the scene parser adds the pointer and the line and column.
  const std::string text = scene_with(good_image, good_camera,
                                      "[{\"point\": [0, 0, 0], \"normal\": [0, 1e999, 0], \"color\": [1, 0, 0]}]");
  EXPECT_EQ(error_of(text), "/planes/0/normal/1: number outside the double range (not finite), at line 3, column 48");
  EXPECT_EQ(error_of("{\"fog\": {\"distance\": -1e400}}"), "/fog/distance: number outside the double range (not finite), at line 1, column 22");
}

TEST(Scene, BadJsonGivesLineAndColumn) {
  EXPECT_EQ(error_of("{\"image\": {\"width\": 4,\n \"height\": 2,}}"),
            "invalid JSON: parse error at line 2, column 14: syntax error while parsing object key - unexpected '}'; "
            "expected string literal");
  EXPECT_EQ(error_of(""), "invalid JSON: parse error at line 1, column 1: syntax error while parsing value - unexpected end "
                          "of input; expected '[', '{', or a literal");
  EXPECT_EQ(error_of("{\"a\": NaN}").substr(0, 40), "invalid JSON: parse error at line 1, col");
}

// Regression: 2·10^7 nested arrays (40 MB) aborted with an uncaught std::bad_alloc, 10^7 took 2.2 GB; a syntax
// error under 10^6 levels took 48 s to locate (the pointer copied at every level). Nesting is limited, and the
// error names the first array too deep by its pointer.
TEST(Scene, NestingDeeperThanTheLimitIsAnErrorAtItsPointer) {
  std::string p64;
  for (int k = 0; k < 64; ++k) p64 += "/0";
  EXPECT_EQ(error_of(std::string(100, '[')), p64 + ": arrays and objects nested deeper than 64 levels");
  EXPECT_EQ(error_of(std::string(10'000'000, '[')), p64 + ": arrays and objects nested deeper than 64 levels");
  std::string objects, pa;
  for (int k = 0; k < 70; ++k) objects += "{\"a~/\": ";
  for (int k = 0; k < 64; ++k) pa += "/a~0~1";
  EXPECT_EQ(error_of(objects), pa + ": arrays and objects nested deeper than 64 levels");
  // 64 levels are fine for the parser (the scene's own checks then speak).
  EXPECT_EQ(error_of(std::string(64, '[') + std::string(64, ']')), "expected an object, found an array");
}

TEST(Scene, AMinimalSceneTakesTheDefaults) {
  // A camera (eye and target) and planes (point and normal) only.
  const SceneParse s = parse_scene(R"({"camera": {"eye": [0, 2, 6], "target": [0, 0, 0]},
                                       "planes": [{"point": [0, 0, 0], "normal": [0, 1, 0]},
                                                  {"point": [0, 0, -4], "normal": [0, 0, 1]}]})");
  ASSERT_TRUE(s.scene) << s.error.str();
  EXPECT_EQ(s.scene->image.width, 960u);
  EXPECT_EQ(s.scene->image.height, 540u);
  EXPECT_EQ(s.scene->samples_per_pixel, 1u);
  EXPECT_EQ(s.scene->seed, 1u);
  EXPECT_EQ(s.scene->camera.projection, Projection::perspective);
  EXPECT_EQ(s.scene->camera.start, RayStart::near_plane);
  // fov 60° vertical at near 0.1: top = 0.1·tan(30°) = 0.0577..., right = top · 960/540.
  const NearPlaneWindow& w = s.scene->camera.window;
  EXPECT_EQ(w.near, 0.1);
  EXPECT_NEAR(w.top, 0.1 * std::tan(M_PI / 6), 1e-15);
  EXPECT_NEAR(w.right, w.top * 960 / 540, 1e-15);
  // Up is +y: the image's top row looks higher than its bottom row.
  EXPECT_GT(s.scene->camera.ray(480, 539).direction.y, s.scene->camera.ray(480, 0).direction.y);
  // Planes without a colour take the palette's first two, distinct.
  const Rgb a = s.scene->planes[0].color, b = s.scene->planes[1].color;
  EXPECT_FALSE(a.r == b.r && a.g == b.g && a.b == b.b);
  EXPECT_EQ(s.scene->background.horizon.r, scene_defaults::background.horizon.r);
}

TEST(Scene, DuplicateKeysAreErrorsWithTheirPointer) {
  // nlohmann-json's DOM would keep one of the two silently.
  EXPECT_EQ(error_of(R"({"camera": {"eye": [0, 1, 5], "target": [0, 0, 0]}, "fog": {"distance": 1, "distance": -1},
                         "planes": []})"),
            "/fog/distance: duplicate key: this member appears more than once in its object");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera,
                                R"([{"point": [0, 0, 0], "normal": [0, 1, 0]}, {"name": "a", "point": [0, 0, 0], "normal": [0, 1, 0], "name": "b"}])")),
            "/planes/1/name: duplicate key: this member appears more than once in its object");
  EXPECT_EQ(error_of(R"({"planes": [], "camera": {"eye": [0, 1, 5], "target": [0, 0, 0]}, "planes": []})"),
            "/planes: duplicate key: this member appears more than once in its object");
  // The same key in two objects is fine; a syntax error later in the text is still the error reported.
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [0, 0, 0], "normal": [0, 1, 0]}, {"point": [0, 0, 1], "normal": [0, 1, 0]}])")),
            "(valid)");
  EXPECT_EQ(error_of(R"({"a": 1, "a": 2, )").substr(0, 13), "invalid JSON:");
}

TEST(Scene, IntegersMayBeWrittenWithAnExponentAndTooLargeIsOutOfRange) {
  // 1e2 and 9.6e1 are the integers 100 and 96; 2.5e1 is 25; 1.5 is not an integer.
  SceneParse s = parse_scene(scene_with(R"({"width": 1e2, "height": 9.6e1, "samples_per_pixel": 2.5e1, "seed": 1.0e0})",
                                        good_camera, good_planes));
  ASSERT_TRUE(s.scene) << s.error.str();
  EXPECT_EQ(s.scene->image.width, 100u);
  EXPECT_EQ(s.scene->image.height, 96u);
  EXPECT_EQ(s.scene->samples_per_pixel, 25u);
  // 2^64 − 1 is the largest seed, written in any form; 2^64 = 18446744073709551616 is out of range.
  s = parse_scene(scene_with(R"({"seed": 1.8446744073709551615e19})", good_camera, good_planes));
  ASSERT_TRUE(s.scene) << s.error.str();
  EXPECT_EQ(s.scene->seed, 18446744073709551615u);
  for (const char* too_large : {"18446744073709551616", "1.8446744073709551616e19", "1e30"})
    EXPECT_EQ(error_of(scene_with(std::string(R"({"seed": )") + too_large + "}", good_camera, good_planes)),
              "/image/seed: out of range (at most 18446744073709551615)")
        << too_large;
  EXPECT_EQ(error_of(scene_with(R"({"width": 1.5})", good_camera, good_planes)),
            "/image/width: expected an integer, found a number with a fraction");
  // A text with a fraction that rounds to an integral double is still not an integer.
  EXPECT_EQ(error_of(scene_with(R"({"width": 100.00000000000000001})", good_camera, good_planes)),
            "/image/width: expected an integer, found a number with a fraction");
  EXPECT_EQ(error_of(scene_with(R"({"width": -1e2})", good_camera, good_planes)), "/image/width: must be positive");
  EXPECT_EQ(error_of(scene_with(R"({"seed": -0.0})", good_camera, good_planes)), "(valid)");
}

TEST(Scene, ANumberThatRoundsToZeroIsAnError) {
  // Without the check, the normal (0, 1e-400, 0) would be read as the zero vector.
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [0, 0, 0], "normal": [0, 1e-400, 0]}])")),
            "/planes/0/normal/1: '1e-400' is nonzero but rounds to zero when read (its magnitude is at most 2^-1075, "
            "half the smallest subnormal)");
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [-2e-324, 0, 0], "normal": [0, 1, 0]}])")),
            "/planes/0/point/0: '-2e-324' is nonzero but rounds to zero when read (its magnitude is at most "
            "2^-1075, half the smallest subnormal)");
  // A subnormal and a zero written with an exponent are fine.
  EXPECT_EQ(error_of(scene_with(good_image, good_camera, R"([{"point": [0e-400, 0, 0], "normal": [0, 4e-324, 0]}])")),
            "(valid)");
}

TEST(Scene, PerspectiveRaysStartAtTheNearPlaneOrAtTheEye) {
  const std::string camera = R"({"eye": [0, 0, 5], "target": [0, 0, 0], "perspective": {"fov_degrees": 90, "near": 2)";
  const SceneParse near = parse_scene(scene_with(good_image, camera + "}}", good_planes));
  const SceneParse eye = parse_scene(scene_with(good_image, camera + R"(, "ray_start": "eye"}})", good_planes));
  ASSERT_TRUE(near.scene && eye.scene);
  // The camera looks down −z from (0, 0, 5); a pixel-centre ray starts on the near plane z = 5 − 2 = 3, or
  // at the eye, with the same direction.
  const Ray from_near = near.scene->camera.ray(1, 1), from_eye = eye.scene->camera.ray(1, 1);
  EXPECT_EQ(from_near.origin.z, 3);
  EXPECT_EQ(from_eye.origin.x, 0);
  EXPECT_EQ(from_eye.origin.y, 0);
  EXPECT_EQ(from_eye.origin.z, 5);
  EXPECT_EQ(from_near.direction.x, from_eye.direction.x);
  EXPECT_EQ(from_near.direction.z, from_eye.direction.z);
  EXPECT_EQ(error_of(scene_with(good_image, camera + R"(, "ray_start": "pupil"}})", good_planes)),
            "/camera/perspective/ray_start: expected \"near_plane\" or \"eye\", found 'pupil'");
}

TEST(Scene, OverridesKeepTheAspectOfAFieldOfViewCamera) {
  SceneOverrides o;
  o.width = 200;
  o.height = 100;
  o.samples_per_pixel = 9;
  const SceneParse s = parse_scene(scene_with(good_image, good_camera, good_planes), o);
  ASSERT_TRUE(s.scene);
  EXPECT_EQ(s.scene->image.width, 200u);
  EXPECT_EQ(s.scene->samples_per_pixel, 9u);
  const NearPlaneWindow& w = s.scene->camera.window;
  EXPECT_EQ(w.right - w.left, 2 * (w.top - w.bottom));  // aspect 2, from the overridden size
}

// ---- Rendering -------------------------------------------------------------------------------------------

// Looking straight down from (0, 5, 0) through an orthographic 2 × 2 window: camera x is world x.
std::string top_down(const std::string& image, const std::string& planes) {
  return scene_with(image, R"({"eye": [0, 5, 0], "target": [0, 0, 0], "up": [0, 0, -1], "orthographic": {"window": {"left": -1, "right": 1, "bottom": -1, "top": 1}}})",
                    planes);
}

Scene parsed(const std::string& text) {
  SceneParse s = parse_scene(text);
  EXPECT_TRUE(s.scene) << s.error.str();
  return *s.scene;
}

TEST(Render, CoincidentPlanesShowTheFirstOne) {
  // A red floor and a blue floor that is the same plane (point moved within it, normal ×3): every ray is an
  // exact tie, so every pixel is the first plane's colour. Facing the rays head-on, the shading factor is
  // 0.22 + 0.78·1 = 1, so pure red stays (255, 0, 0).
  const std::string red = R"({"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 0, 0]})";
  const std::string blue = R"({"point": [3, 0, -7], "normal": [0, 3, 0], "color": [0, 0, 1]})";
  RenderOptions options;
  options.stage_image = true;
  options.compare_naive = true;
  const RenderResult r = render_scene(parsed(top_down(R"({"width": 4, "height": 3})", "[" + red + ", " + blue + "]")), options);
  for (std::uint32_t row = 0; row < 3; ++row)
    for (std::uint32_t x = 0; x < 4; ++x) {
      const std::uint8_t* px = r.image.pixel(x, row);
      EXPECT_EQ(px[0], 255);
      EXPECT_EQ(px[1], 0);
      EXPECT_EQ(px[2], 0);
    }
  // The blue floor coincides with the red one, so the prepared plane set sets it aside once (exactly,
  // before any ray): no pixel needs a comparison, let alone a slower stage.
  EXPECT_EQ(r.stats.pixels_by_stage[static_cast<std::size_t>(Stage::filter)], 12u);
  EXPECT_EQ(r.stats.rays, 12u);
  const RenderResult swapped = render_scene(parsed(top_down(R"({"width": 4, "height": 3})", "[" + blue + ", " + red + "]")), {});
  EXPECT_EQ(swapped.image.pixel(2, 1)[2], 255);  // blue first: blue wins
  EXPECT_EQ(swapped.image.pixel(2, 1)[0], 0);
}

TEST(Render, SupersamplesAverageInLinearLight) {
  // One pixel over x ∈ [−1, 1]: a red floor y = 0, and a blue plane through the origin tilted by 2^-20
  // (normal (2^-20, 1, 0)), above the floor exactly where x < 0. With 16 n-rooks samples, exactly 8 have
  // x < 0 (one per column stratum): the average is (0.5, 0, 0.5) in linear light (the tilt changes the
  // shading by about 1e-12), and sRGB(0.5) = 1.055·0.5^(1/2.4) − 0.055 = 0.73536, i.e. byte 188.
  const std::string planes = R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 0, 0]},
                                 {"point": [0, 0, 0], "normal": [9.5367431640625e-07, 1, 0], "color": [0, 0, 1]}])";
  const RenderResult r = render_scene(parsed(top_down(R"({"width": 1, "height": 1, "samples_per_pixel": 16})", planes)), {});
  EXPECT_EQ(r.image.pixel(0, 0)[0], 188);
  EXPECT_EQ(r.image.pixel(0, 0)[1], 0);
  EXPECT_EQ(r.image.pixel(0, 0)[2], 188);
  // With one sample (the centre, x = 0 on the seam: both planes pass through the origin, t ties) the first
  // plane, red, wins.
  const RenderResult centre = render_scene(parsed(top_down(R"({"width": 1, "height": 1})", planes)), {});
  EXPECT_EQ(centre.image.pixel(0, 0)[0], 255);
  EXPECT_EQ(centre.image.pixel(0, 0)[2], 0);
}

TEST(Render, MissesShowTheBackgroundAndRowsGoTopDown) {
  // Perspective camera looking at the horizon over a floor: the top row sees sky, the bottom row floor.
  const std::string text = R"({"image": {"width": 3, "height": 8},
     "camera": {"eye": [0, 1, 0], "target": [0, 1, -10], "up": [0, 1, 0], "perspective": {"fov_degrees": 90}},
     "background": [0, 1, 0],
     "planes": [{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 0, 0]}]})";
  const RenderResult r = render_scene(parsed(text), {});
  EXPECT_EQ(r.image.pixel(1, 0)[1], 255);  // sky: pure green background
  EXPECT_EQ(r.image.pixel(1, 0)[0], 0);
  EXPECT_GT(r.image.pixel(1, 7)[0], 100);  // floor: red, darkened at the grazing angle
  EXPECT_EQ(r.image.pixel(1, 7)[1], 0);
  EXPECT_EQ(r.stats.hit_rays, 12u);  // the lower half of 3 × 8
}

TEST(Render, ThreadCountDoesNotChangeTheImage) {
  SceneOverrides o;
  o.width = 64;
  o.height = 36;
  o.samples_per_pixel = 2;
  const SceneParse demo = parse_scene(demo_scene_json(), o);
  ASSERT_TRUE(demo.scene);
  RenderOptions one, three;
  one.threads = 1;
  three.threads = 3;
  one.stage_image = three.stage_image = true;
  const RenderResult a = render_scene(*demo.scene, one), b = render_scene(*demo.scene, three);
  EXPECT_EQ(a.image.rgb, b.image.rgb);
  EXPECT_EQ(a.stages.rgb, b.stages.rgb);
  EXPECT_EQ(a.stats.pixels_by_stage, b.stats.pixels_by_stage);
}

TEST(Render, TheDemoNeedsSlowerStagesAndFoolsThePlainDoubles) {
  // At a quarter of the demo's size, one sample per pixel: the shallow angles need the compensated stage,
  // the coincident walls none (the prepared plane set sets the second wall aside), and the naive loop
  // picks another plane on the coincident wall, along the pool's edge and along the seam of the two right
  // walls.
  SceneOverrides o;
  o.width = 240;
  o.height = 135;
  o.samples_per_pixel = 1;
  const SceneParse demo = parse_scene(demo_scene_json(), o);
  ASSERT_TRUE(demo.scene);
  RenderOptions options;
  options.stage_image = options.compare_naive = options.naive_image = true;
  const RenderResult r = render_scene(*demo.scene, options);
  const RenderStats& s = r.stats;
  EXPECT_GT(s.pixels_by_stage[static_cast<std::size_t>(Stage::filter)], s.pixels / 3);
  EXPECT_GT(s.pixels_by_stage[static_cast<std::size_t>(Stage::compensated)], 500u);
  EXPECT_EQ(s.pixels_by_stage[static_cast<std::size_t>(Stage::expansion)], 0u);
  EXPECT_GT(s.naive_pixels_differ, 500u);
  EXPECT_EQ(s.naive_rays_differ, s.naive_pixels_differ);  // one ray per pixel
  std::uint64_t magenta = 0;
  for (std::size_t k = 0; k < r.naive_difference.rgb.size(); k += 3)
    magenta += r.naive_difference.rgb[k] == 255 && r.naive_difference.rgb[k + 1] == 0 && r.naive_difference.rgb[k + 2] == 255;
  EXPECT_EQ(magenta, s.naive_pixels_differ);
  EXPECT_NE(r.naive.rgb, r.image.rgb);
}

TEST(Png, WritesAndReadsBack) {
  Image image(3, 2);
  for (std::size_t k = 0; k < image.rgb.size(); ++k) image.rgb[k] = static_cast<std::uint8_t>(k * 13);
  const std::string path = temp_path("roundtrip.png");
  ASSERT_EQ(write_png(path, image), std::nullopt);
  const std::optional<Image> back = read_png(path);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->width, 3u);
  EXPECT_EQ(back->height, 2u);
  EXPECT_EQ(back->rgb, image.rgb);
  const std::optional<std::string> error = write_png("/nonexistent/dir/x.png", image);
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("cannot create '/nonexistent/dir/x.png'"), std::string::npos) << *error;
}

// ---- The render command ----------------------------------------------------------------------------------

TEST(RenderCommand, BrokenScenesExitWithTwoAndNameFileAndPointer) {
  const std::string path = temp_path("broken.json");
  const std::string out = temp_path("never-written.png");
  std::filesystem::remove(out);
  write_file(path, scene_with(good_image, good_camera,
                              R"([{"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 0, 0]},
                                  {"point": [0, 0, 0], "normal": [0, 1, 0], "color": [1, 0, 0]},
                                  {"point": [0, 0, 0], "normal": [0, 0, 0], "color": [1, 0, 0]}])"));
  CliRun r = run("render " + path + " -o " + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "raykernel: " + path + ": /planes/2/normal: zero vector\n");
  EXPECT_EQ(r.out, "");
  EXPECT_FALSE(std::filesystem::exists(out));
  write_file(path, "{\"image\": ");
  r = run("render " + path + " -o " + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("raykernel: " + path + ": invalid JSON: parse error at line 1, column 11", 0), 0u) << r.err;
  r = run("render /nonexistent/scene.json -o " + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "raykernel render: cannot open scene file '/nonexistent/scene.json': No such file or directory\n");
  // A directory is not a JSON syntax error.
  r = run("render " + scenes + " -o " + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "raykernel render: cannot open scene file '" + scenes + "': Is a directory\n");
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(RenderCommand, UsageErrors) {
  EXPECT_EQ(run("render --bogus").status, 2);
  EXPECT_EQ(run("render --width 0").status, 2);
  EXPECT_EQ(run("render --samples x").status, 2);
  EXPECT_EQ(run("render a.json b.json").status, 2);
  EXPECT_EQ(run("render -o").status, 2);
  const CliRun unwritable = run("render --width 8 --height 8 -o /nonexistent/dir/out.png");
  EXPECT_EQ(unwritable.status, 2);
  EXPECT_NE(unwritable.err.find("cannot create"), std::string::npos) << unwritable.err;
}

TEST(RenderCommand, WritesTheImagesAndPrintsTheCounts) {
  const std::string out = temp_path("small.png");
  const CliRun r = run("render --width 96 --height 54 --samples 1 --no-progress -o " + out + " --show-stages --compare-naive");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const char* suffix : {".png", "-stages.png", "-naive-diff.png"}) {
    const std::optional<Image> image = read_png(temp_path("small") + suffix);
    ASSERT_TRUE(image) << suffix;
    EXPECT_EQ(image->width, 96u);
    EXPECT_EQ(image->height, 54u);
  }
  for (const char* text : {"96x54, 1 sample per pixel, 6 planes", "rays/s", "pixels by the slowest stage they needed: filter",
                           "naive loop", "picks another surface than the exact answer at", "-stages.png", "-naive-diff.png"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << " in:\n" << r.out;
}

TEST(RenderCommand, WithoutArgumentsRendersTheDemoToRenderPng) {
  // The README's first command: `raykernel render` alone writes the demo, 960 × 540, to render.png.
  const std::string dir = temp_path("cwd");
  std::filesystem::create_directories(dir);
  std::filesystem::remove(dir + "/render.png");
  const CliRun r = run("render", "", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::optional<Image> image = read_png(dir + "/render.png");
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 960u);
  EXPECT_EQ(image->height, 540u);
  EXPECT_NE(r.out.find("demo scene"), std::string::npos) << r.out;
}

const std::string minimal_scene = R"({"camera": {"eye": [0, 2, 6], "target": [0, 0, 0]},
 "planes": [{"point": [0, 0, 0], "normal": [0, 1, 0]}]})";

TEST(RenderCommand, AMinimalSceneRendersAndOptionsOverrideTheScene) {
  const std::string scene = temp_path("minimal.json"), out = temp_path("minimal.png");
  write_file(scene, minimal_scene);
  CliRun r = run("render " + scene + " --width 16 --height 8 --samples 2 --no-progress -o " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  std::optional<Image> image = read_png(out);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 16u);
  EXPECT_EQ(image->height, 8u);
  // One plane and one thread: singular; the header names the scene file.
  r = run("render " + scene + " --width 4 --height 2 --threads 1 --no-progress -o " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("raykernel render: " + scene + ", 4x2, 1 sample per pixel, 1 plane, 1 thread\n", 0), 0u) << r.out;
  // The scene's own values are overridden, not only missing ones.
  write_file(scene, R"({"image": {"width": 3, "height": 3, "samples_per_pixel": 7}, )" + minimal_scene.substr(1));
  r = run("render " + scene + " --width 5 --height 4 --samples 3 --no-progress -o " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("5x4, 3 samples per pixel"), std::string::npos) << r.out;
}

TEST(RenderCommand, PrintsItsHeaderBeforeRendering) {
  // The header comes first: when the image then cannot be written, it has already been printed.
  CliRun r = run("render --width 8 --height 8 --no-progress -o /nonexistent/dir/out.png");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out.rfind("raykernel render: demo scene, 8x8, 4 samples per pixel, 6 planes, ", 0), 0u) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "the header alone: " << r.out;
  // And when standard output cannot be written, nothing is rendered.
  const std::string out = temp_path("never.png");
  std::filesystem::remove(out);
  const int status = std::system((cli + " render --width 8 --height 8 --no-progress -o " + out + " > /dev/full 2> /dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(RenderCommand, RaysPerSecondUseAUnitThatShowsThem) {
  // A 1×1 render takes microseconds: its rate is shown in k or M rays/s with 3 significant digits, never as
  // "0.00 million".
  const std::string out = temp_path("one-pixel.png");
  const CliRun r = run("render --width 1 --height 1 --samples 1 --no-progress -o " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::size_t rays = r.out.find("rays/s");
  ASSERT_NE(rays, std::string::npos) << r.out;
  const std::size_t start = r.out.rfind(", ", rays) + 2;
  const std::string shown = r.out.substr(start, rays - start);  // "123 k " or "1.23 M " or "812 "
  EXPECT_EQ(shown.find("million"), std::string::npos) << shown;
  EXPECT_NE(shown[0], '0') << shown;
  EXPECT_NE(r.out.find("1 ray in "), std::string::npos) << r.out;
}

TEST(RenderCommand, DashWritesThePngToStandardOutput) {
  const std::string dir = temp_path("dash-output");
  std::filesystem::create_directories(dir);
  const CliRun r = run("render --width 6 --height 4 --samples 1 --no-progress -o -", "", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_GT(r.out.size(), 8u);
  EXPECT_EQ(r.out.substr(0, 8), "\x89PNG\r\n\x1a\n");
  const std::string copy = temp_path("from-stdout.png");
  write_file(copy, r.out);
  const std::optional<Image> image = read_png(copy);
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 6u);
  EXPECT_EQ(image->height, 4u);
  // The report goes to standard error instead, and names standard output.
  EXPECT_NE(r.err.find("wrote standard output: 24 rays"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "no file named -";
  // A derived name needs a file to derive it from.
  EXPECT_EQ(run("render -o - --show-stages").status, 2);
}

TEST(RenderCommand, TwoOutputsWithTheSamePathAreRefused) {
  const std::string dir = temp_path("same");
  std::filesystem::create_directories(dir);
  for (const std::string& args : {std::string("-o a.png --show-stages=a.png"), std::string("-o a.png --compare-naive=./a.png"),
                                  std::string("-o x.png --show-stages=y.png --naive-image=sub/../y.png"),
                                  std::string("-o a.png --show-stages --compare-naive=a-stages.png"),
                                  std::string("-o - --show-stages=-")}) {
    const CliRun r = run("render --width 4 --height 4 --no-progress " + args, "", dir);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.err.find("name the same file"), std::string::npos) << args << ": " << r.err;
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "nothing is written";
  // Regression: compared as opened, not as spelled: /dev/stdout is standard output (two PNGs on one stream
  // exited 0), and a hard link or a symbolic link to an existing file is that file.
  const CliRun r = run("render --width 4 --height 4 --no-progress -o - --show-stages=/dev/stdout", "", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("name the same file"), std::string::npos) << r.err;
  write_file(dir + "/a.png", "old");
  std::filesystem::create_hard_link(dir + "/a.png", dir + "/hard.png");
  std::filesystem::create_symlink("a.png", dir + "/soft.png");
  for (const std::string& other : {std::string("hard.png"), std::string("soft.png")}) {
    const CliRun link = run("render --width 4 --height 4 --no-progress -o a.png --show-stages=" + other, "", dir);
    EXPECT_EQ(link.status, 2) << other;
    EXPECT_NE(link.err.find("name the same file"), std::string::npos) << other << ": " << link.err;
  }
  EXPECT_EQ(read_file(dir + "/a.png"), "old");
  // /dev/null takes any number of outputs.
  EXPECT_EQ(run("render --width 4 --height 4 --no-progress -o /dev/null --show-stages=/dev/null", "", dir).status, 0);
}

// Regression: `render --threads 500` under `ulimit -v 4000000` and `--threads 100` under a process limit of 64
// ended in std::terminate (a std::thread destroyed while joinable when the next one failed to start). Threads
// the system refuses are no error: the render completes on those that started, the same image.
TEST(RenderCommand, ThreadsTheSystemRefusesAreNoError) {
  const std::string dir = temp_path("few-threads");
  std::filesystem::create_directories(dir);
  // 256 threads need 2 GB of stacks: under a 600 MB address-space limit most cannot start.
  const int limited = std::system(("ulimit -s 8192 && ulimit -v 600000 && cd '" + dir + "' && " + cli +
                                   " render --width 32 --height 16 --no-progress --threads 256 -o limited.png > out.txt 2> err.txt")
                                      .c_str());
  ASSERT_TRUE(WIFEXITED(limited)) << read_file(dir + "/err.txt");
  EXPECT_EQ(WEXITSTATUS(limited), 0) << read_file(dir + "/err.txt");
  const std::string report = read_file(dir + "/out.txt");
  EXPECT_NE(report.find("the system started "), std::string::npos) << "the limit did refuse threads: " << report;
  EXPECT_NE(report.find(" of the 256 threads asked for; they rendered every row"), std::string::npos) << report;
  const CliRun free = run("render --width 32 --height 16 --no-progress --threads 1 -o free.png", "", dir);
  ASSERT_EQ(free.status, 0) << free.err;
  EXPECT_EQ(read_file(dir + "/limited.png"), read_file(dir + "/free.png"));
  // More than raykernel::max_threads is a usage error naming the limit.
  const CliRun many = run("render --threads 257");
  EXPECT_EQ(many.status, 2);
  EXPECT_EQ(many.err, "raykernel render: bad value for --threads: '257' (an integer from 1 to 256)\n");
}

TEST(RenderCommand, DerivedNamesReplaceAPngExtensionInAnyCase) {
  const std::string dir = temp_path("upper");
  std::filesystem::create_directories(dir);
  const CliRun r = run("render --width 4 --height 4 --no-progress -o OUT.PNG --show-stages --compare-naive --naive-image", "", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* name : {"OUT.PNG", "OUT-stages.png", "OUT-naive-diff.png", "OUT-naive.png"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + name)) << name;
}

TEST(RenderCommand, DoubleDashEndsTheOptions) {
  const std::string dir = temp_path("dash-scene");
  std::filesystem::create_directories(dir);
  write_file(dir + "/-scene.json", minimal_scene);
  CliRun r = run("render --width 4 --height 2 --no-progress -o out.png -- -scene.json", "", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("raykernel render: -scene.json, 4x2"), std::string::npos) << r.out;
  r = run("render --width 4 --height 2 -scene.json", "", dir);
  EXPECT_EQ(r.status, 2);
}

TEST(RenderCommand, HelpSaysHowThePerspectiveCameraWorks) {
  const CliRun r = run("render --help");
  for (const char* text : {"fov_degrees is the VERTICAL field of view", "Rays start on the near plane",
                           "\"ray_start\": \"eye\" starts every ray", "clipped", "-o, --output FILE", "end of options"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text;
}

TEST(RenderCommand, PrintsTheDemoScene) {
  const CliRun r = run("render --print-demo-scene");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out, std::string(demo_scene_json()));
}


// ---- meshes in scenes ------------------------------------------------------------------------------------

// A scene parsed with overrides and its meshes loaded from scenes/ (as `raykernel render` does for a scene
// file there).
Scene parsed_with_meshes(const std::string& text, const SceneOverrides& overrides) {
  SceneParse s = parse_scene(text, overrides);
  EXPECT_TRUE(s.scene) << s.error.str();
  if (!s.scene) return {};
  const std::optional<SceneError> error = load_scene_meshes(*s.scene, scenes);
  EXPECT_FALSE(error) << error->str();
  return *s.scene;
}

// Bytes within 1 of the hand-computed sRGB values (the colour pipeline's pow may differ in the last bit).
void expect_pixel(const Image& image, std::uint32_t x, std::uint32_t row, int r, int g, int b) {
  const std::uint8_t* px = image.pixel(x, row);
  EXPECT_NEAR(px[0], r, 1) << "pixel (" << x << ", " << row << ")";
  EXPECT_NEAR(px[1], g, 1) << "pixel (" << x << ", " << row << ")";
  EXPECT_NEAR(px[2], b, 1) << "pixel (" << x << ", " << row << ")";
}

// scenes/octahedron.json: the octahedron |x| + |y| + |z − 1| ≤ 2 (octahedron.off scaled by 2, raised by 1) over
// the floor z = −2, seen down −z by an orthographic camera at z = 10 with the window [−3, 3]². At 5 × 5 with one
// sample, pixel centres are at x, y ∈ {−2.4, −1.2, 0, 1.2, 2.4} (rows from the top: row 0 is y = 2.4).
//   - The mesh covers |x| + |y| < 2: pixels (2, 2) (the apex (0, 0, 3): t = 10 − 3 = 7 against the floor's 12),
//     (1, 2), (3, 2), (2, 1), (2, 3). Every top facet has normal ±(1, 1, 1) up to signs, facing the ray at
//     cos = 1/√3, so the colour (0.9, 0.3, 0.2) is lit by 0.22 + 0.78/√3 = 0.67033: in linear light
//     0.9 → 0.7874·0.6703, 0.3 → 0.07324·0.6703, 0.2 → 0.03310·0.6703, in sRGB bytes (192, 63, 41).
//   - The other pixels see the floor face-on (lit by 1): its colour (0.2, 0.4, 0.8) → bytes (51, 102, 204).
TEST(RenderMesh, TheOctahedronSceneShowsTheMeshNearerThanTheFloor) {
  const Scene scene = parsed_with_meshes(read_file(scenes + "/octahedron.json"), {5, 5, 1});
  ASSERT_EQ(scene.mesh.triangles.size(), 8u);
  ASSERT_EQ(scene.mesh.vertices.size(), 6u);
  EXPECT_EQ(scene.mesh.vertices[4].z, 3);   // the apex 1·2 + 1
  EXPECT_EQ(scene.mesh.vertices[0].x, 2);
  EXPECT_EQ(scene.mesh.vertices[5].z, -1);
  RenderOptions options;
  options.compare_naive = true;
  const RenderResult r = render_scene(scene, options);
  for (const auto& [x, row] : {std::pair{2u, 2u}, {1u, 2u}, {3u, 2u}, {2u, 1u}, {2u, 3u}}) expect_pixel(r.image, x, row, 192, 63, 41);
  for (const auto& [x, row] : {std::pair{0u, 0u}, {1u, 1u}, {3u, 3u}, {4u, 4u}, {0u, 2u}, {4u, 2u}})
    expect_pixel(r.image, x, row, 51, 102, 204);
  EXPECT_EQ(r.stats.hit_rays, 25u);  // every ray meets the floor or the mesh
  // Nothing here is close, except the rays on the axes x = 0 and y = 0 (column 2, row 2): they meet the mesh on
  // an edge between two facets, or (the centre) at the apex shared by four. The owned rule gives such a ray to
  // exactly one of them; Möller–Trumbore in doubles (barycentric coordinates 0, computed exactly here) to every
  // one and keeps the first, which may be another triangle than the owned one. So only pixels on the axes may
  // differ (and their colour does not: the facets shade alike).
  EXPECT_LE(r.stats.naive_pixels_differ, 5u);
  for (std::uint32_t row = 0; row < 5; ++row)
    for (std::uint32_t x = 0; x < 5; ++x) {
      if (x == 2 || row == 2) continue;
      const std::uint8_t* px = r.naive_difference.pixel(x, row);
      EXPECT_FALSE(px[0] == 255 && px[1] == 0 && px[2] == 255) << "pixel (" << x << ", " << row << ")";
    }
}

// The plane x + y + z = 3 holds the octahedron's facet (2, 0, 1), (0, 2, 1), (0, 0, 3) exactly. At 10 × 10 pixel
// centres are at ±0.3, ±0.9, ...; pixel (6, 3) is (0.9, 0.9), inside that facet (0.9 + 0.9 < 2), where the plane
// and the facet meet the ray at the same point: the same exact t, a tie that a plane wins (README "raykernel
// render"). Lowered by 2^-20 (x + y + z = 3 − 2^-20), the plane is behind the facet there and the mesh shows.
// Elsewhere the plane z = 3 − x − y is at or above the octahedron's top z = 3 − |x| − |y|, so it shows: e.g.
// pixel (3, 3) at (−0.9, 0.9).
TEST(RenderMesh, APlaneWinsAnExactTieWithATriangle) {
  const std::string meshes =
      R"([{"file": "octahedron.off", "transform": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 1, 0, 0, 0, 1], "color": [0.9, 0.3, 0.2]}])";
  const std::string camera = R"({"eye": [0, 0, 10], "target": [0, 0, 0], "up": [0, 1, 0], "orthographic": {"height": 6}})";
  const auto scene_text = [&](const std::string& point) {
    return R"({"image": {"width": 10, "height": 10}, "camera": )" + camera + R"(, "planes": [{"point": )" + point +
           R"(, "normal": [1, 1, 1], "color": [0.2, 0.4, 0.8]}], "meshes": )" + meshes + "}";
  };
  // The plane's facing is 1/√3 as the facet's: (0.2, 0.4, 0.8) lit by 0.67033 is, in sRGB bytes, (41, 84, 170).
  const RenderResult tie = render_scene(parsed_with_meshes(scene_text("[0, 0, 3]"), {}), {});
  expect_pixel(tie.image, 6, 3, 41, 84, 170);
  expect_pixel(tie.image, 3, 3, 41, 84, 170);
  const RenderResult lowered = render_scene(parsed_with_meshes(scene_text("[0, 0, 2.9999990463256836]"), {}), {});
  expect_pixel(lowered.image, 6, 3, 192, 63, 41);
  expect_pixel(lowered.image, 3, 3, 41, 84, 170);
}

TEST(RenderMesh, BadMeshReferencesAreErrorsWithTheirPointer) {
  const std::string camera = R"({"eye": [0, 0, 10], "target": [0, 0, 0], "orthographic": {"height": 6}})";
  const auto load_error = [&](const std::string& meshes) -> std::string {
    SceneParse s = parse_scene(R"({"camera": )" + camera + R"(, "planes": [], "meshes": )" + meshes + "}");
    if (!s.scene) return s.error.str();
    const std::optional<SceneError> e = load_scene_meshes(*s.scene, scenes);
    return e ? e->str() : "(valid)";
  };
  EXPECT_EQ(load_error(R"({"file": "octahedron.off"})"), "/meshes: expected an array of meshes, found an object");
  EXPECT_EQ(load_error(R"([{"name": "x"}])"), "/meshes/0/name: unknown field (expected one of: file, transform, rounding, color)");
  EXPECT_EQ(load_error(R"([{"transform": []}])"), "/meshes/0/file: missing field");
  EXPECT_EQ(load_error(R"([{"file": 3}])"), "/meshes/0/file: expected a file name (a non-empty string), found an integer");
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "transform": [1, 0, 0]}])"),
            "/meshes/0/transform: expected 16 numbers (a row-major 4x4 matrix), found an array of 3");
  // A rotation (about z by 90°: exact here, but not in general) and a scale by 3 would round vertices: refused.
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "transform": [0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])")
                .rfind("/meshes/0/transform/0: only scalings by powers of two", 0),
            0u);
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "transform": [3, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])")
                .rfind("/meshes/0/transform/0: only scalings by powers of two", 0),
            0u);
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "transform": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1]}])"),
            "/meshes/0/transform: the bottom row must be 0 0 0 1 (an affine transform)");
  // Translating x by 2^-60: 1 + 2^-60 is not a double, so vertex 0 (1, 0, 0) would be rounded.
  const std::string inexact = load_error(
      R"([{"file": "octahedron.off", "transform": [1, 0, 0, 8.673617379884035e-19, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])");
  EXPECT_EQ(inexact.rfind("/meshes/0/transform: the image of vertex 0 of ", 0), 0u) << inexact;
  // A scale by 2^-1074 is exact on these coordinates (0 and ±1 become 0 and ±2^-1074, subnormal but exact), but
  // a scale by 2^1023 plus a translation by 2^1023 takes x = 1 to 2^1024: overflow.
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "transform": [4.9406564584124654e-324, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])"),
            "(valid)");
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "transform": [8.98846567431158e307, 0, 0, 8.98846567431158e307, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])")
                .rfind("/meshes/0/transform: the image of vertex 0 of ", 0),
            0u);
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "rounding": "round"}])"),
            "/meshes/0/rounding: expected \"exact\" or \"nearest\", found a string");
  // "rounding": "nearest": any affine matrix, the images correctly rounded; x = max + max·1 rounds beyond the doubles.
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "rounding": "nearest", "transform": [0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])"),
            "(valid)");
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off", "rounding": "nearest", "transform": [1.7976931348623157e308, 0, 0, 1.7976931348623157e308, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])")
                .rfind("/meshes/0/transform: the image of vertex 0 of ", 0),
            0u);
  // A file that is not there, or not a mesh: the reader's reason, naming the file.
  const std::string missing = load_error(R"([{"file": "no-such-mesh.off"}])");
  EXPECT_EQ(missing.rfind("/meshes/0/file: ", 0), 0u) << missing;
  EXPECT_NE(missing.find("no-such-mesh.off"), std::string::npos) << missing;
  const std::string not_a_mesh = load_error(R"([{"file": "demo.json"}, {"file": "octahedron.off"}])");
  EXPECT_EQ(not_a_mesh.rfind("/meshes/0/file: ", 0), 0u) << not_a_mesh;
  EXPECT_NE(not_a_mesh.find("demo.json"), std::string::npos) << not_a_mesh;
  // A device is never read (/dev/zero would never end).
  EXPECT_EQ(load_error(R"([{"file": "/dev/zero"}])"), "/meshes/0/file: /dev/zero: not a regular file");
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off"}, {"file": "octahedron.off", "color": [0, 0, 1]}])"), "(valid)");
  // Regression: a NUL in the name was cut off by the system's calls and octahedron.off was read instead.
  EXPECT_EQ(load_error(R"([{"file": "octahedron.off\u0000x"}])"),
            "/meshes/0/file: the file name contains a NUL character (\\u0000), which no file name can hold");
  // Regression: a mesh file whose face index overflows when negated names its file and line (render exited 2
  // with neither).
  const std::string bad_obj = temp_path("int64-min.obj");
  write_file(bad_obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\nv 0 0 1\n");
  EXPECT_EQ(load_error(R"([{"file": ")" + bad_obj + R"("}])"),
            "/meshes/0/file: " + bad_obj + ":4: relative vertex index -9223372036854775808 is out of range (3 vertices so far)");
}

// "rounding": "nearest": each image coordinate is row·v + t exactly, rounded once. Vertex 0 = (1 + 2^-52, 1 + 2^-51,
// 0) under the row (1 + 2^-52, −1, 0, 0): (1 + 2^-52)² − (1 + 2^-51) = 2^-104 exactly (a double), where the
// textbook evaluation rounds the product to 1 + 2^-51 first and gives 0. A rotation by 90° about z moves the
// octahedron's vertices exactly; shared vertices are one vertex, rounded once.
TEST(RenderMesh, NearestRoundingGivesTheCorrectlyRoundedImages) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / ("raykernel-round-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "sliver.off") << "OFF\n3 1 0\n1.0000000000000002 1.0000000000000004 0\n0 0 0\n0 0 1\n3 0 1 2\n";
  const auto loaded = [&](const std::string& meshes) {
    SceneParse s = parse_scene(R"({"camera": {"eye": [0, 0, 10], "target": [0, 0, 0]}, "planes": [], "meshes": )" + meshes + "}");
    EXPECT_TRUE(s.scene.has_value()) << s.error.str();
    const std::optional<SceneError> e = load_scene_meshes(*s.scene, folder);
    EXPECT_FALSE(e.has_value()) << e->str();
    return s.scene->mesh;
  };
  const Mesh m = loaded(R"([{"file": "sliver.off", "rounding": "nearest", "transform": [1.0000000000000002, -1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}])");
  ASSERT_EQ(m.vertices.size(), 3u);
  EXPECT_EQ(m.vertices[0].x, 0x1p-104);
  EXPECT_EQ(m.vertices[0].y, 1 + 0x1p-51);
  EXPECT_EQ(m.vertices[1].x, 0.0);
  std::filesystem::remove_all(folder);
  SceneParse s = parse_scene(R"({"camera": {"eye": [0, 0, 10], "target": [0, 0, 0]}, "planes": [], "meshes": [{"file": "octahedron.off", "rounding": "nearest", "transform": [0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}]})");
  ASSERT_TRUE(s.scene.has_value());
  ASSERT_FALSE(load_scene_meshes(*s.scene, scenes).has_value());
  const Mesh octahedron = io::read_mesh(std::filesystem::path(scenes) / "octahedron.off");
  ASSERT_EQ(s.scene->mesh.vertices.size(), octahedron.vertices.size());
  for (std::size_t v = 0; v < octahedron.vertices.size(); ++v) {  // (x, y, z) → (−y, x, z)
    EXPECT_EQ(s.scene->mesh.vertices[v].x, -octahedron.vertices[v].y);
    EXPECT_EQ(s.scene->mesh.vertices[v].y, octahedron.vertices[v].x);
    EXPECT_EQ(s.scene->mesh.vertices[v].z, octahedron.vertices[v].z);
  }
  EXPECT_EQ(s.scene->mesh.triangles, octahedron.triangles);
}

TEST(RenderMesh, TheCommandRendersMeshesAndReportsBadOnesWithExitTwo) {
  const std::string out = temp_path("octahedron.png");
  CliRun r = run("render " + scenes + "/octahedron.json --width 8 --height 8 --samples 1 --no-progress -o " + out +
                 " --compare-naive=" + temp_path("octahedron-naive-diff.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("1 plane, 1 mesh (8 triangles)"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(out));
  // The mesh file is relative to the scene file's directory, not to the working directory.
  const std::string dir = temp_path("mesh-scene");
  std::filesystem::create_directories(dir + "/sub");
  write_file(dir + "/sub/scene.json",
             R"({"camera": {"eye": [0, 0, 10], "target": [0, 0, 0]}, "planes": [], "meshes": [{"file": "missing.obj"}]})");
  r = run("render sub/scene.json --width 4 --height 4 --no-progress -o out.png", "", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("raykernel: sub/scene.json: /meshes/0/file: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("sub/missing.obj"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.png"));
}

// Spheres in scenes: errors name their pointer; "planes" may be left out only when spheres are given.
TEST(RenderSphere, SceneSpheresAreValidatedWithTheirPointer) {
  const std::string camera = R"({"eye": [0, 1, 5], "target": [0, 0, 0]})";
  EXPECT_EQ(error_of(R"({"camera": )" + camera + R"(, "spheres": [{"center": [0, 0, 0], "radius": 1}]})"), "(valid)");
  EXPECT_EQ(error_of(R"({"camera": )" + camera + "}"), "/planes: missing field");
  EXPECT_EQ(error_of(R"({"camera": )" + camera + R"(, "spheres": [{"center": [0, 0, 0], "radius": 0}]})"),
            "/spheres/0/radius: must be positive");
  EXPECT_EQ(error_of(R"({"camera": )" + camera + R"(, "spheres": [{"center": [0, 0], "radius": 1}]})").substr(0, 19),
            "/spheres/0/center: ");
  EXPECT_EQ(error_of(R"({"camera": )" + camera + R"(, "spheres": [{"center": [0, 0, 0]}]})"),
            "/spheres/0/radius: missing field");
  EXPECT_EQ(error_of(R"({"camera": )" + camera + R"(, "spheres": [{"centre": [0, 0, 0], "radius": 1}]})"),
            "/spheres/0/centre: unknown field (expected one of: name, center, radius, color)");
  EXPECT_EQ(error_of(R"({"camera": )" + camera + R"(, "spheres": {}})"), "/spheres: expected an array of spheres, found an object");
}

// Twins: a red unit sphere and a blue one with the same centre and a radius one ulp larger (listed second). Every
// ray that meets them meets the blue one first (its roots enclose the red one's), so every pixel showing them is
// blue; seen from straight above (orthographic, every ray along −z), the centre pixels all hit. Plain doubles
// compute the same t for the two on some rays and then keep the first listed: the naive loop differs there.
TEST(RenderSphere, TwinsShowTheOuterSphereAndFoolThePlainDoubles) {
  const std::string text = R"({"image": {"width": 8, "height": 8},
    "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "up": [0, 1, 0], "orthographic": {"height": 1}},
    "spheres": [{"center": [0, 0, 0], "radius": 1, "color": [1, 0, 0]},
                {"center": [0, 0, 0], "radius": 1.0000000000000002, "color": [0, 0, 1]}]})";
  RenderOptions options;
  options.compare_naive = true;
  const RenderResult r = render_scene(parsed(text), options);
  EXPECT_EQ(r.stats.hit_rays, 64u);
  for (std::uint32_t row = 0; row < 8; ++row)
    for (std::uint32_t x = 0; x < 8; ++x) {
      const std::uint8_t* px = r.image.pixel(x, row);
      EXPECT_EQ(px[0], 0) << x << " " << row;
      EXPECT_GT(px[2], 0) << x << " " << row;
    }
  EXPECT_GT(r.stats.naive_rays_differ, 0u);
}

}  // namespace
}  // namespace raykernel::cli

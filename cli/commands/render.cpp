// raykernel render: a scene of planes to PNG, with the stage and naive-difference images.
#include "commands/commands.hpp"
#include "common/exit_status.hpp"
#include "common/failure.hpp"
#include "common/io.hpp"
#include "common/limits.hpp"
#include "common/options.hpp"
#include "common/stream_command.hpp"
#include "common/text_format.hpp"
#include "rendering/render.hpp"
#include "rendering/render_summary.hpp"
#include "scenes/scene.hpp"

#include <raykernel/parallel.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel render [options] [--] [SCENE.json|-]

Renders a scene of infinite planes, meshes and spheres by ray casting: for every pixel and sample,
the surface the ray hits first, decided exactly (the same nearest_hit as `raykernel nearest`),
coloured by plane, checker, mesh or sphere, darkened at grazing angles and faded with distance. Without SCENE.json it renders the
built-in demo scene (planes meeting at shallow angles, a far checkered floor, coincident planes);
with - it reads the scene from standard input.
Rows are rendered in parallel on every core. Prints what it renders before it starts, then the
render time, rays per second and how many pixels needed which stage.
)";

constexpr const char* help_after = R"(Two outputs may not be the same file.

Scene file (JSON; unknown fields and keys given twice are errors; examples in scenes/). Only
"camera" (eye, target) and "planes" (point, normal) are required ("planes" may be left out when
"spheres" are given); the defaults are shown:
  {"image":  {"width": 960, "height": 540, "samples_per_pixel": 1, "seed": 1},
   "camera": {"eye": [x,y,z], "target": [x,y,z], "up": [0,1,0],
              "perspective": {"fov_degrees": 60, "near": 0.1, "ray_start": "near_plane"}
                 or {"window": {"left": l, "right": r, "bottom": b, "top": t}, "near": n}
              or "orthographic": {"height": h} or {"window": {...}, "near": n}},
   "background": [r,g,b] or {"horizon": [r,g,b], "zenith": [r,g,b]},
   "fog": {"distance": D},         (half of a colour fades away every D units; default none)
   "planes": [{"name": "floor", "point": [x,y,z], "normal": [x,y,z],
               "color": [r,g,b]  or  "checker": {"colors": [[r,g,b], [r,g,b]], "size": s,
                                                 "u_axis": [x,y,z] (optional)}}, ...],
   "meshes": [{"file": "PATH" (OBJ/PLY/STL/OFF, relative to the scene file's directory),
               "transform": [16 numbers, row-major; only ±2^k scales and translations, applied exactly],
               "color": [r,g,b]}, ...],
   "spheres": [{"name": "ball", "center": [x,y,z], "radius": r (positive), "color": [r,g,b]}, ...],
   "description": "..."}
Integers may be written as any JSON number with an integer value (1e3). Colours are display
(sRGB) values in [0, 1]; a plane without a colour gets one from a built-in palette. Planes are
numbered from 0 in file order; on an exact tie the smaller number wins.
A plane wins an exact tie with a mesh triangle, a triangle with a sphere; within a kind the smaller
index (docs/contract.md §7, §10). A sphere is hit at its smallest root t >= 0.

Perspective cameras: fov_degrees is the VERTICAL field of view (the horizontal one follows from
the image's aspect ratio). Rays start on the near plane, at distance near in front of the eye
(z = -near in camera space), not at the eye: anything closer to the eye than the near plane is
clipped. A near-plane window grows as near * tan(fov/2), and rays at the image's edges start up to
near / cos(angle off the view axis) from the eye, so with a wide field of view a floor or wall
close to the camera is visibly cut away towards the sides. "ray_start": "eye" starts every ray
at the eye instead (same directions; nothing is clipped); a smaller near clips less.

exit status: 0 rendered; 2 usage error, unreadable or invalid scene (reported as
raykernel: FILE: /json/pointer: REASON), an image that cannot be written, or standard output
that cannot be written
)";

// OUTPUT with its ".png" (any case) replaced by `suffix` ("render.png", "OUT.PNG" → "render-stages.png",
// "OUT-stages.png"); OUTPUT without .png gets the suffix appended.
std::string sibling(const std::string& output, const std::string& suffix) {
  std::string stem = output;
  if (stem.size() > 4) {
    std::string extension = stem.substr(stem.size() - 4);
    for (char& c : extension) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    if (extension == ".png") stem.resize(stem.size() - 4);
  }
  return stem + suffix;
}

// The file an output path names when it exists ("-": standard output), as the system identifies it: its
// device and inode, after symbolic links (/dev/stdout, /proc/self/fd/1, a link, a hard link all show it).
std::optional<std::pair<dev_t, ino_t>> file_identity(const std::string& path) {
  struct stat status {};
  const int r = path == "-" ? ::fstat(STDOUT_FILENO, &status) : ::stat(path.c_str(), &status);
  if (r != 0) return std::nullopt;
  return std::pair{status.st_dev, status.st_ino};
}

// Whether two outputs would write to one file: the same existing file (compared as opened, not as spelled:
// "-o - --show-stages=/dev/stdout" is one stream), else the same path once made absolute, normalized and
// with symbolic links of existing directories resolved ("out.png", "./out.png" and "dir/../out.png" are
// one). /dev/null may take any number of outputs.
bool same_file(const std::string& a, const std::string& b) {
  const auto ia = file_identity(a), ib = file_identity(b);
  if (ia && ib) return *ia == *ib && ia != file_identity("/dev/null");
  if (a == "-" || b == "-") return a == b;
  std::error_code ea, eb;
  const std::filesystem::path pa = std::filesystem::weakly_canonical(std::filesystem::absolute(a, ea), ea);
  const std::filesystem::path pb = std::filesystem::weakly_canonical(std::filesystem::absolute(b, eb), eb);
  if (ea || eb) return std::filesystem::path(a).lexically_normal() == std::filesystem::path(b).lexically_normal();
  return pa == pb;
}

// A one-line progress bar on stderr, redrawn in place; it appears only once a render has taken 0.3 s.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled, std::string label) : enabled_(enabled), label_(std::move(label)) {}
  void operator()(double fraction) {
    if (!enabled_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (!shown_ && (elapsed < 0.3 || fraction >= 1)) return;
    shown_ = true;
    constexpr int width = 40;
    const int filled = static_cast<int>(fraction * width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.append(static_cast<std::size_t>(width - filled), '.');
    std::fprintf(stderr, "\r%s [%s] %3d%%  %.1f s", label_.c_str(), bar.c_str(), static_cast<int>(fraction * 100), elapsed);
    std::fflush(stderr);
  }
  // Erases the bar, so that the report after the render starts on a clean line.
  void finish() {
    if (shown_) std::fprintf(stderr, "\r%*s\r", 80, "");
    shown_ = false;
    enabled_ = false;
  }
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

 private:
  bool enabled_;
  bool shown_ = false;
  std::string label_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// What the command line says.
struct Arguments {
  std::optional<std::string> scene_path, stages_path, naive_diff_path, naive_image_path;
  std::string output = "render.png";
  SceneOverrides overrides;
  unsigned threads = 0;
  int progress_mode = -1;  // −1: on a terminal
  bool print_demo_scene = false;
};

CommandLine command_line(Arguments& a) {
  return {
      .command = "render",
      .options =
          {{"--output", "-o", file(a.output, "FILE", "a file name, or - for standard output"),
            "the PNG to write (default render.png; - writes it to standard output, and the report then "
            "goes to standard error)"},
           {"--show-stages", optional_file(a.stages_path),
            "also write an image marking the pixels where the certified path needed a slower stage than "
            "the binary64 filter: yellow compensated (double-double), orange expansion (exact "
            "expansions), crimson exact (rationals) (default FILE: OUTPUT with -stages.png for its .png)"},
           {"--compare-naive", optional_file(a.naive_diff_path),
            "also run the textbook loop in plain doubles on the same rays and write an image marking in "
            "magenta the pixels where it picks another surface than the exact answer, with the counts "
            "(default FILE: OUTPUT with -naive-diff.png)"},
           {"--naive-image", optional_file(a.naive_image_path),
            "also write the scene as the plain-double loop renders it (default FILE: OUTPUT with "
            "-naive.png)"},
           {"--width", integer(a.overrides.width, 1, limits::max_image_side), "override the scene's image width"},
           {"--height", integer(a.overrides.height, 1, limits::max_image_side), "override the scene's image height"},
           {"--samples", integer(a.overrides.samples_per_pixel, 1, limits::max_samples_per_pixel),
            "override the samples per pixel (stratified, reproducible)"},
           {"--threads", integer(a.threads, 1, limits::max_threads), "worker threads (default: every core)"},
           {"--progress", flag(a.progress_mode, 1), "force the progress bar"},
           {"--no-progress", flag(a.progress_mode, 0), "suppress the progress bar (default: shown on a terminal)"},
           {"--print-demo-scene", action(a.print_demo_scene),
            "print the demo scene's JSON (a starting point for your own) and exit"}},
      .operand = Operand{.metavar = "SCENE.json", .what = "scene file", .destination = &a.scene_path},
      .help_before = help_before,
      .help_after = help_after};
}

}  // namespace

OwnedCommandLine render_command_line() { return owned_command_line(command_line); }

int run_render(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;
  if (arguments.print_demo_scene) {
    std::cout << demo_scene_json();
    return finish_standard_output(exit_ok);
  }

  // The outputs: derived names, then no two the same.
  struct Output {
    const char* option;
    std::optional<std::string>* path;
    const char* suffix;
  };
  std::optional<std::string> main_output = arguments.output;
  const Output outputs[] = {{"--output", &main_output, ""},
                            {"--show-stages", &arguments.stages_path, "-stages.png"},
                            {"--compare-naive", &arguments.naive_diff_path, "-naive-diff.png"},
                            {"--naive-image", &arguments.naive_image_path, "-naive.png"}};
  for (const Output& o : outputs) {
    if (!o.path->has_value() || !(*o.path)->empty()) continue;
    if (arguments.output == "-") {
      std::cerr << "raykernel render: " << o.option << " needs =FILE when the image goes to standard output\n";
      return exit_usage;
    }
    *o.path = sibling(arguments.output, o.suffix);
  }
  for (std::size_t x = 0; x < std::size(outputs); ++x)
    for (std::size_t y = x + 1; y < std::size(outputs); ++y)
      if (outputs[x].path->has_value() && outputs[y].path->has_value() && same_file(**outputs[x].path, **outputs[y].path)) {
        std::cerr << "raykernel render: " << outputs[x].option << " and " << outputs[y].option << " name the same file "
                  << quote(**outputs[y].path, (*outputs[y].path)->size()) << "\n";
        return exit_usage;
      }
  bool image_to_standard_output = false;
  for (const Output& o : outputs) image_to_standard_output |= o.path->has_value() && **o.path == "-";
  // The report goes where the image does not.
  std::ostream& report = image_to_standard_output ? std::cerr : std::cout;

  // The scene.
  const std::optional<std::string>& scene_path = arguments.scene_path;
  std::string text;
  std::string scene_name = "demo scene";
  if (scene_path) {
    const Doing doing("reading the scene file " + quote(*scene_path, limits::quoted_token_bytes));
    Input input(*scene_path);
    if (!check_opened("render", "scene file", *scene_path, input)) return exit_usage;
    char chunk[1 << 16];
    while (input.stream().read(chunk, sizeof chunk) || input.stream().gcount() > 0) {
      text.append(chunk, static_cast<std::size_t>(input.stream().gcount()));
      if (text.size() > limits::max_scene_bytes) {
        std::cerr << "raykernel render: scene file " << input_name(*scene_path) << " is larger than "
                  << with_thousands(limits::max_scene_bytes) << " bytes, the largest scene raykernel reads\n";
        return exit_usage;
      }
    }
    if (const std::string error = input.read_error(); !error.empty()) {
      std::cerr << "raykernel render: I/O error reading scene file " << input_name(*scene_path) << ": " << error << '\n';
      return exit_usage;
    }
    scene_name = *scene_path == "-" ? "standard input" : *scene_path;
  } else {
    text = demo_scene_json();
  }
  const Doing doing("the scene " + (scene_path ? quote(scene_name, limits::quoted_token_bytes) : std::string("(the built-in demo)")));
  SceneParse parsed = parse_scene(text, arguments.overrides);
  if (!parsed.scene) {
    std::cerr << "raykernel: " << (scene_path ? printable(scene_name) : "built-in demo scene") << ": " << parsed.error.str()
              << '\n';
    return exit_usage;
  }
  // Mesh files are relative to the scene file's directory (the working directory for standard input).
  const std::filesystem::path scene_directory =
      scene_path && *scene_path != "-" ? std::filesystem::path(*scene_path).parent_path() : std::filesystem::path();
  if (const std::optional<SceneError> error = load_scene_meshes(*parsed.scene, scene_directory)) {
    std::cerr << "raykernel: " << (scene_path ? printable(scene_name) : "built-in demo scene") << ": " << error->str()
              << '\n';
    return exit_usage;
  }
  const Scene& scene = *parsed.scene;

  RenderOptions options;
  options.threads = thread_count(arguments.threads);
  options.stage_image = arguments.stages_path.has_value();
  options.compare_naive = arguments.naive_diff_path.has_value();
  options.naive_image = arguments.naive_image_path.has_value();
  options.legend = true;
  // Say what is about to happen before it takes its time (and stop now if nobody can read it).
  report << render_header(scene_name, scene, options.threads);
  report.flush();
  if (!image_to_standard_output && !flush_standard_output()) return exit_usage;

  const bool show_progress = arguments.progress_mode == 1 || (arguments.progress_mode == -1 && isatty(STDERR_FILENO));
  ProgressBar bar(show_progress, "raykernel render");
  options.progress = [&bar](double fraction) { bar(fraction); };
  RenderResult result;
  try {
    result = render_scene(scene, options);
  } catch (const std::exception& e) {
    std::cerr << "raykernel render: " << e.what() << '\n';
    return exit_usage;
  }
  bar.finish();

  auto write = [](const std::string& path, const Image& image) {
    if (path == "-") {
      std::string error;
      const std::vector<std::uint8_t> bytes = encode_png(image, error);
      if (!error.empty()) {
        std::cerr << "raykernel render: " << error << '\n';
        return false;
      }
      std::cout.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
      return flush_standard_output();
    }
    if (const std::optional<std::string> error = write_png(path, image)) {
      std::cerr << "raykernel render: " << *error << '\n';
      return false;
    }
    return true;
  };
  const RenderStats& s = result.stats;
  if (!write(arguments.output, result.image)) return exit_usage;
  report << render_statistics(arguments.output, s);
  if (arguments.stages_path) {
    if (!write(*arguments.stages_path, result.stages)) return exit_usage;
    report << stage_image_line(*arguments.stages_path, s);
  }
  if (s.naive_compared) report << naive_comparison_line(s);
  if (arguments.naive_diff_path) {
    if (!write(*arguments.naive_diff_path, result.naive_difference)) return exit_usage;
    report << naive_difference_line(*arguments.naive_diff_path);
  }
  if (arguments.naive_image_path) {
    if (!write(*arguments.naive_image_path, result.naive)) return exit_usage;
    report << naive_image_line(*arguments.naive_image_path);
  }
  return finish_standard_output(exit_ok);
}

}  // namespace raykernel::cli

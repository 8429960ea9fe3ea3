// raykernel render: a scene of planes to PNG, with the stage and naive-difference images.
#include "commands.hpp"
#include "render.hpp"
#include "scene.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

namespace raykernel::cli {
namespace {

constexpr const char* render_help = R"(usage: raykernel render [SCENE.json] [options]

Renders a scene of infinite planes by ray casting: for every pixel and sample, the plane the ray
hits first, decided exactly (the same nearest_hit as `raykernel nearest`), coloured by plane or
checker, darkened at grazing angles and faded with distance. Without SCENE.json it renders the
built-in demo scene (planes meeting at shallow angles, a far checkered floor, coincident planes).
Rows are rendered in parallel on every core. Prints the render time, rays per second and how
many pixels needed which stage.

options:
  -o, --output FILE          the PNG to write (default render.png)
  --show-stages[=FILE]       also write an image marking the pixels where the certified path needed
                             a slower stage than the binary64 filter: yellow compensated (double-
                             double), orange expansion (exact expansions), crimson exact (rationals)
                             (default FILE: OUTPUT with -stages.png)
  --compare-naive[=FILE]     also run the seed's loop in plain doubles on the same rays and write an
                             image marking in magenta the pixels where it picks another plane than the
                             exact answer, with the counts (default FILE: OUTPUT with -naive-diff.png)
  --naive-image[=FILE]       also write the scene as the plain-double loop renders it
                             (default FILE: OUTPUT with -naive.png)
  --width N, --height N      override the scene's image size
  --samples N                override the samples per pixel (stratified, reproducible)
  --threads N                worker threads (default: every core)
  --progress, --no-progress  force or suppress the progress bar (default: on a terminal)
  --print-demo-scene         print the demo scene's JSON (a starting point for your own) and exit
  --help                     this text

Scene file (JSON; unknown fields are errors; examples in scenes/):
  {"image":  {"width": W, "height": H, "samples_per_pixel": 1, "seed": 1},
   "camera": {"eye": [x,y,z], "target": [x,y,z], "up": [x,y,z],
              "perspective": {"fov_degrees": F, "near": 0.1}
                 or {"window": {"left": l, "right": r, "bottom": b, "top": t}, "near": n}
              or "orthographic": {"height": h} or {"window": {...}, "near": n}},
   "background": [r,g,b] or {"horizon": [r,g,b], "zenith": [r,g,b]},     (optional)
   "fog": {"distance": D},         (optional: half of a colour fades away every D units)
   "planes": [{"name": "floor", "point": [x,y,z], "normal": [x,y,z],
               "color": [r,g,b]  or  "checker": {"colors": [[r,g,b], [r,g,b]], "size": s,
                                                 "u_axis": [x,y,z] (optional)}}, ...],
   "description": "..."}          (optional)
Colours are display (sRGB) values in [0, 1]. Planes are numbered from 0 in file order; on an exact
tie the smaller number wins.

exit status: 0 rendered; 2 usage error, unreadable or invalid scene (reported as
raykernel: FILE: /json/pointer: REASON), or an image that cannot be written
)";

// OUTPUT with its ".png" replaced by `suffix` ("render.png" → "render-stages.png").
std::string sibling(const std::string& output, const std::string& suffix) {
  const std::string stem = output.size() > 4 && output.compare(output.size() - 4, 4, ".png") == 0
                               ? output.substr(0, output.size() - 4)
                               : output;
  return stem + suffix;
}

std::optional<std::uint32_t> parse_count(const std::string& text, std::uint32_t max) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 9) return std::nullopt;
  const unsigned long v = std::strtoul(text.c_str(), nullptr, 10);
  if (v == 0 || v > max) return std::nullopt;
  return static_cast<std::uint32_t>(v);
}

std::string with_thousands(std::uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string percent(std::uint64_t part, std::uint64_t whole) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f%%", whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0);
  return buf;
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
  ~ProgressBar() {
    if (shown_) std::fprintf(stderr, "\r%*s\r", 80, "");  // erase the bar
  }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

 private:
  bool enabled_;
  bool shown_ = false;
  std::string label_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace

int run_render(const std::vector<std::string>& args) {
  std::string scene_path, output = "render.png";
  std::optional<std::string> stages_path, naive_diff_path, naive_image_path;
  SceneOverrides overrides;
  unsigned threads = 0;
  int progress_mode = -1;  // −1: on a terminal
  bool have_scene = false;

  auto value_of = [&](std::size_t& i, const std::string& a, const std::string& name) -> std::optional<std::string> {
    if (a == name) {
      if (i + 1 >= args.size()) return std::nullopt;
      return args[++i];
    }
    return a.substr(name.size() + 1);  // --name=value
  };
  auto is_option = [](const std::string& a, const std::string& name) {
    return a == name || a.rfind(name + "=", 0) == 0;
  };

  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      std::cout << render_help;
      return exit_ok;
    }
    if (a == "--print-demo-scene") {
      std::cout << demo_scene_json();
      return exit_ok;
    }
    if (a == "-o" || is_option(a, "--output")) {
      const std::optional<std::string> v = value_of(i, a, a == "-o" ? "-o" : "--output");
      if (!v || v->empty()) {
        std::cerr << "raykernel render: " << a << " needs a file name\n";
        return exit_usage;
      }
      output = *v;
    } else if (a == "--show-stages" || a.rfind("--show-stages=", 0) == 0) {
      stages_path = a.size() > 14 ? a.substr(14) : "";
    } else if (a == "--compare-naive" || a.rfind("--compare-naive=", 0) == 0) {
      naive_diff_path = a.size() > 16 ? a.substr(16) : "";
    } else if (a == "--naive-image" || a.rfind("--naive-image=", 0) == 0) {
      naive_image_path = a.size() > 14 ? a.substr(14) : "";
    } else if (is_option(a, "--width") || is_option(a, "--height") || is_option(a, "--samples") ||
               is_option(a, "--threads")) {
      const std::string name = a.substr(0, a.find('='));
      const std::optional<std::string> v = value_of(i, a, name);
      const std::uint32_t max = name == "--samples" ? 4096 : (name == "--threads" ? 1024 : 16384);
      const std::optional<std::uint32_t> n = v ? parse_count(*v, max) : std::nullopt;
      if (!n) {
        std::cerr << "raykernel render: " << name << " needs an integer from 1 to " << max << (v ? ", not '" + *v + "'" : "")
                  << "\n";
        return exit_usage;
      }
      if (name == "--width") overrides.width = *n;
      else if (name == "--height") overrides.height = *n;
      else if (name == "--samples") overrides.samples_per_pixel = *n;
      else threads = *n;
    } else if (a == "--progress") {
      progress_mode = 1;
    } else if (a == "--no-progress") {
      progress_mode = 0;
    } else if (a.size() > 1 && a[0] == '-') {
      std::cerr << "raykernel render: unknown option '" << a << "' (see raykernel render --help)\n";
      return exit_usage;
    } else if (have_scene) {
      std::cerr << "raykernel render: more than one scene file ('" << scene_path << "', '" << a << "')\n";
      return exit_usage;
    } else {
      scene_path = a;
      have_scene = true;
    }
  }
  if (stages_path && stages_path->empty()) stages_path = sibling(output, "-stages.png");
  if (naive_diff_path && naive_diff_path->empty()) naive_diff_path = sibling(output, "-naive-diff.png");
  if (naive_image_path && naive_image_path->empty()) naive_image_path = sibling(output, "-naive.png");

  // The scene.
  std::string text;
  std::string scene_name = "demo scene";
  if (have_scene) {
    std::ifstream in(scene_path, std::ios::binary);
    std::ostringstream content;
    if (in) content << in.rdbuf();
    if (!in || in.bad()) {
      std::cerr << "raykernel render: cannot read scene file '" << scene_path << "'\n";
      return exit_usage;
    }
    text = content.str();
    scene_name = scene_path;
  } else {
    text = demo_scene_json();
  }
  const SceneParse parsed = parse_scene(text, overrides);
  if (!parsed.scene) {
    std::cerr << "raykernel: " << (have_scene ? scene_path : "built-in demo scene") << ": " << parsed.error.str() << '\n';
    return exit_usage;
  }
  const Scene& scene = *parsed.scene;

  RenderOptions options;
  options.threads = threads;
  options.stage_image = stages_path.has_value();
  options.compare_naive = naive_diff_path.has_value();
  options.naive_image = naive_image_path.has_value();
  options.legend = true;
  const bool show_progress = progress_mode == 1 || (progress_mode == -1 && isatty(STDERR_FILENO));
  ProgressBar bar(show_progress, "raykernel render");
  options.progress = [&bar](double fraction) { bar(fraction); };

  RenderResult result;
  try {
    result = render_scene(scene, options);
  } catch (const std::exception& e) {
    std::cerr << "raykernel render: " << e.what() << '\n';
    return exit_usage;
  }
  bar(1.0);

  auto write = [](const std::string& path, const Image& image) {
    if (const std::optional<std::string> error = write_png(path, image)) {
      std::cerr << "raykernel render: " << *error << '\n';
      return false;
    }
    return true;
  };
  const RenderStats& s = result.stats;
  if (!write(output, result.image)) return exit_usage;
  std::cout << "raykernel render: " << scene_name << ", " << scene.image.width << "x" << scene.image.height << ", "
            << scene.samples_per_pixel << " sample" << (scene.samples_per_pixel == 1 ? "" : "s") << " per pixel, "
            << scene.planes.size() << " planes, " << s.threads << " thread" << (s.threads == 1 ? "" : "s") << "\n";
  char line[160];
  std::snprintf(line, sizeof line, "wrote %s: %s rays in %.3f s, %.2f million rays/s (%s hit a plane)\n", output.c_str(),
                with_thousands(s.rays).c_str(), s.seconds, s.rays_per_second() / 1e6, percent(s.hit_rays, s.rays).c_str());
  std::cout << line;
  std::cout << "pixels by the slowest stage they needed:";
  for (int k = 0; k < stage_count; ++k)
    std::cout << (k ? ", " : " ") << to_string(static_cast<Stage>(k)) << " " << with_thousands(s.pixels_by_stage[static_cast<std::size_t>(k)]);
  std::cout << "\nrays by the slowest stage they needed: ";
  for (int k = 0; k < stage_count; ++k)
    std::cout << (k ? ", " : "") << to_string(static_cast<Stage>(k)) << " " << with_thousands(s.rays_by_stage[static_cast<std::size_t>(k)]);
  std::cout << "\ncomparisons of two t values by stage: ";
  for (int k = 0; k < stage_count; ++k)
    std::cout << (k ? ", " : "") << to_string(static_cast<Stage>(k)) << " " << with_thousands(s.comparisons_by_stage[static_cast<std::size_t>(k)]);
  std::cout << "\n";
  if (stages_path) {
    if (!write(*stages_path, result.stages)) return exit_usage;
    std::cout << "wrote " << *stages_path << ": " << with_thousands(s.pixels - s.pixels_by_stage[0])
              << " pixels needed a slower stage than the filter (yellow compensated, orange expansion, crimson exact)\n";
  }
  if (s.naive_compared) {
    std::snprintf(line, sizeof line, "naive loop (plain doubles, %.3f s): picks another plane than the exact answer at %s pixels (%s), %s of %s rays\n",
                  s.naive_seconds, with_thousands(s.naive_pixels_differ).c_str(), percent(s.naive_pixels_differ, s.pixels).c_str(),
                  with_thousands(s.naive_rays_differ).c_str(), with_thousands(s.rays).c_str());
    std::cout << line;
  }
  if (naive_diff_path) {
    if (!write(*naive_diff_path, result.naive_difference)) return exit_usage;
    std::cout << "wrote " << *naive_diff_path << ": those pixels in magenta\n";
  }
  if (naive_image_path) {
    if (!write(*naive_image_path, result.naive)) return exit_usage;
    std::cout << "wrote " << *naive_image_path << ": the scene as the naive loop renders it\n";
  }
  return exit_ok;
}

}  // namespace raykernel::cli

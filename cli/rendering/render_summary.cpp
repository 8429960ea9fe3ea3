#include "rendering/render_summary.hpp"

#include "common/text_format.hpp"

namespace raykernel::cli {
namespace {

// "filter 250,104, compensated 116,739, expansion 151,557, exact 0".
std::string by_stage(const std::array<std::uint64_t, stage_count>& counts) {
  std::string out;
  for (std::size_t k = 0; k < stage_count; ++k) {
    if (k) out += ", ";
    out += std::string(to_string(static_cast<Stage>(k))) + " " + with_thousands(counts[k]);
  }
  return out;
}

}  // namespace

std::string output_name(std::string_view path) { return path == "-" ? "standard output" : printable(path); }

std::string render_header(std::string_view scene_name, const Scene& scene, unsigned threads) {
  return "raykernel render: " + printable(scene_name) + ", " + std::to_string(scene.image.width) + "x" +
         std::to_string(scene.image.height) + ", " + count_of(scene.samples_per_pixel, "sample") + " per pixel, " +
         count_of(scene.planes.size(), "plane") + ", " +
         (scene.mesh_files.empty() ? std::string()
                                   : count_of(scene.mesh_files.size(), "mesh", "meshes") + " (" +
                                         count_of(scene.mesh.triangles.size(), "triangle") + "), ") +
         (scene.spheres.empty() ? std::string() : count_of(scene.spheres.size(), "sphere") + ", ") +
         count_of(threads, "thread") + "\n";
}

std::string render_statistics(std::string_view output, const RenderStats& s) {
  return "wrote " + output_name(output) + ": " + count_of(s.rays, "ray") + " in " + duration(s.seconds) + ", " +
         rate(s.rays_per_second(), "rays/s") + " (" + percent(s.hit_rays, s.rays) + " hit the scene)\n" +
         (s.threads_ran < s.threads ? "the system started " + with_thousands(s.threads_ran) + " of the " +
                                          count_of(s.threads, "thread") + " asked for; they rendered every row\n"
                                    : std::string()) +
         "pixels by the slowest stage they needed: " + by_stage(s.pixels_by_stage) + "\n" +
         "rays by the slowest stage they needed: " + by_stage(s.rays_by_stage) + "\n" +
         "comparisons of two t values by stage: " + by_stage(s.comparisons_by_stage) + "\n";
}

std::string stage_image_line(std::string_view path, const RenderStats& s) {
  const std::uint64_t slower = s.pixels - s.pixels_by_stage[static_cast<std::size_t>(Stage::filter)];
  return "wrote " + output_name(path) + ": " + count_of(slower, "pixel") + " needed a slower stage than the " +
         "filter (yellow compensated, orange expansion, crimson exact)\n";
}

std::string naive_comparison_line(const RenderStats& s) {
  return "naive loop (plain doubles, " + duration(s.naive_seconds) + "): picks another surface than the exact " +
         "answer at " + count_of(s.naive_pixels_differ, "pixel") + " (" + percent(s.naive_pixels_differ, s.pixels) +
         "), " + with_thousands(s.naive_rays_differ) + " of " + count_of(s.rays, "ray") + "\n";
}

std::string naive_difference_line(std::string_view path) {
  return "wrote " + output_name(path) + ": those pixels in magenta\n";
}

std::string naive_image_line(std::string_view path) {
  return "wrote " + output_name(path) + ": the scene as the naive loop renders it\n";
}

}  // namespace raykernel::cli

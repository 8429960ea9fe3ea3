// Scenes for `raykernel render`: a camera, an image size, and infinite planes with a colour or a checker
// pattern, read from JSON (nlohmann-json). Parsing never exits and never throws on bad input: it returns
// the error with the JSON Pointer (RFC 6901) of the offending value, so the CLI, tests and the scene fuzzer
// share it.
//
// Format (every field is described in `raykernel render --help`, examples in scenes/; only "camera" with
// its eye and target, and "planes" with point and normal, are required — "planes" may be left out when the
// scene has "spheres"):
//
//   {
//     "image":  {"width": 960, "height": 540, "samples_per_pixel": 4, "seed": 1},
//     "camera": {"eye": [0, 1.6, 6], "target": [0, 0.8, 0], "up": [0, 1, 0],
//                "perspective": {"fov_degrees": 50, "near": 0.1}},
//     "background": [0.75, 0.85, 1.0],
//     "fog": {"distance": 60},
//     "planes": [
//       {"name": "floor", "point": [0, 0, 0], "normal": [0, 1, 0],
//        "checker": {"colors": [[0.9, 0.9, 0.85], [0.35, 0.35, 0.4]], "size": 1}},
//       {"name": "wall", "point": [-4, 0, 0], "normal": [1, 0, 0], "color": [0.8, 0.3, 0.25]}
//     ]
//   }
#pragma once

#include <raykernel/camera.hpp>
#include <raykernel/mesh.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/sphere.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::cli {

// A colour as written in scene files: display (sRGB) values in [0, 1].
struct Rgb {
  double r, g, b;
};

// Two colours alternating in squares of side `size`, aligned with the axes u and v of the plane
// (u = the projection of `u_axis` on the plane, v = n × u), with a corner at the plane's point.
struct Checker {
  Rgb colors[2];
  double size;
  Vec3 u_axis;
};

struct ScenePlane {
  std::string name;  // for messages and --stats; "plane K" when the file gives none
  Plane plane;
  Rgb color;                      // the plane's colour (a checker's first colour)
  std::optional<Checker> checker;
};

// A triangle mesh of the scene, as the file names it: "meshes": [{"file": "PATH", "transform": [16 numbers],
// "rounding": "exact" | "nearest", "color": [r, g, b]}]. PATH is relative to the scene file's directory. The
// transform (row-major 4×4, optional; bottom row 0 0 0 1) is applied to the vertices
//   - "exact" (the default): exactly or not at all — only a diagonal of nonzero powers of two (±2^k) plus a
//     translation, each vertex's image checked exact in doubles (io::exact_affine); a rotation or a general
//     scale would round the vertices and move the geometry the kernel answers for exactly, so it is an error;
//   - "nearest": any affine matrix, each coordinate of each image correctly rounded (raykernel::round_affine:
//     the exact value rounded once). The scene's mesh is then those rounded vertices — stated, not hidden —
//     and equal vertices round alike, so a watertight mesh stays watertight.
struct SceneMeshReference {
  std::string file;
  std::string pointer;  // "/meshes/K", for errors
  std::array<std::array<double, 4>, 3> matrix{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};  // rows, translation last
  bool rounded = false;  // "rounding": "nearest"
  Rgb color;
};

// A sphere of the scene: "spheres": [{"name": "...", "center": [x, y, z], "radius": r, "color": [r, g, b]}]
// (the centre and radius as doubles, taken exactly; the radius finite and positive).
struct SceneSphere {
  std::string name;  // for messages; "sphere K" when the file gives none
  Sphere sphere;
  Rgb color;
};

// The sky: `zenith` straight up (+y), `horizon` at and below the horizon, blended by the ray's elevation.
struct Background {
  Rgb horizon;
  Rgb zenith;
};

struct Scene {
  ImageSize image;
  std::uint32_t samples_per_pixel = 1;
  std::uint64_t seed = 1;
  Camera camera;
  Background background;
  double fog_distance = 0;  // distance at which the fog hides half of a colour; 0: no fog
  std::vector<ScenePlane> planes;
  std::vector<SceneMeshReference> mesh_files;
  std::vector<SceneSphere> spheres;
  // Every mesh of mesh_files, transformed, in order, in one Mesh (filled by load_scene_meshes; empty until
  // then): mesh K's triangles start at mesh_first_triangle[K].
  Mesh mesh;
  std::vector<std::uint32_t> mesh_first_triangle;

  [[nodiscard]] std::vector<Plane> geometry() const;
  [[nodiscard]] std::vector<Sphere> sphere_geometry() const;  // the spheres, in order
  [[nodiscard]] std::size_t mesh_of_triangle(std::uint32_t triangle) const noexcept;  // K  // the planes, in order, for nearest_hit
};

// What a scene file may leave out. A minimal scene is a camera (eye and target) and planes.
namespace scene_defaults {
inline constexpr std::uint32_t width = 960, height = 540;  // samples_per_pixel 1, seed 1 (Scene's members)
inline constexpr Vec3 up{0, 1, 0};
inline constexpr double fov_degrees = 60;  // vertical, of a perspective camera
inline constexpr double near = 0.1;
inline constexpr Background background{{0.86, 0.90, 0.96}, {0.42, 0.60, 0.88}};
// The colours of planes without "color" or "checker", by plane index modulo 6.
inline constexpr std::array<Rgb, 6> plane_colors = {{{0.85, 0.84, 0.80},
                                                     {0.78, 0.30, 0.24},
                                                     {0.30, 0.66, 0.36},
                                                     {0.22, 0.55, 0.75},
                                                     {0.85, 0.72, 0.45},
                                                     {0.55, 0.40, 0.75}}};
}  // namespace scene_defaults

// Where and why a scene is invalid: `pointer` is the JSON Pointer of the offending value ("/planes/2/normal";
// empty for the document itself or for a syntax error), `message` says what is wrong ("zero vector").
struct SceneError {
  std::string pointer;
  std::string message;
  // "/planes/2/normal: zero vector", or the message alone; bytes that are not printable escaped (printable).
  [[nodiscard]] std::string str() const;
};

struct SceneParse {
  std::optional<Scene> scene;  // set when the text is a valid scene
  SceneError error;            // set otherwise
};

// Values that replace the scene file's image settings (the CLI's --width, --height, --samples), applied
// before the camera is built, so that a field-of-view camera keeps the new aspect ratio.
struct SceneOverrides {
  std::optional<std::uint32_t> width, height, samples_per_pixel;
};

// Parses and validates a scene: JSON syntax (errors give line and column), no key twice in one object, every
// required field, types (an integer field accepts any number whose value is an integer: 1e3), finite
// numbers in range, nonzero normals and vectors, a positive image size, a camera that can be built (eye ≠
// target, up not parallel to the view direction) and whose rays are all finite. Unknown fields are errors,
// so typos are caught; fields left out take the defaults above.
[[nodiscard]] SceneParse parse_scene(std::string_view json_text, const SceneOverrides& overrides = {});

// Reads the mesh files of `scene.mesh_files` (raykernel::io's exact readers), PATH relative to
// `scene_directory`, applies each transform exactly and fills scene.mesh. Returns the first error: the
// mesh's JSON Pointer ("/meshes/1/file") and the reader's reason (naming the file and line or byte), or
// "/meshes/1/transform" and the vertex whose image is not exact. parse_scene never reads files (the scene
// fuzzer runs it); this does.
[[nodiscard]] std::optional<SceneError> load_scene_meshes(Scene& scene, const std::filesystem::path& scene_directory);

// The built-in demo scene (what `raykernel render` draws without a scene file), as JSON text: planes meeting
// at shallow angles, a far checkered floor seen at grazing angles, and coincident planes, so that both the
// stage image and the naive-difference image have something to show.
[[nodiscard]] std::string_view demo_scene_json() noexcept;

}  // namespace raykernel::cli

// Scene files for `raykernel render`: validation, with the JSON Pointer of every error (json_locator.hpp
// parses), and the defaults of optional fields.
#include "scenes/scene.hpp"

#include "scenes/json_locator.hpp"
#include "common/limits.hpp"
#include "common/text_format.hpp"

#include <raykernel/io/mesh_file.hpp>
#include <raykernel/io/transform.hpp>
#include <raykernel/transform.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

namespace raykernel::cli {
namespace {

using nlohmann::json;

using limits::max_image_side;
using limits::max_samples_per_pixel;

std::string child(const std::string& pointer, std::string_view key) { return json_pointer_child(pointer, key); }
std::string child(const std::string& pointer, std::size_t index) { return json_pointer_child(pointer, index); }

// ---- Validation --------------------------------------------------------------------------------------

// Unwinds the validation to parse_scene, which turns it into a SceneError (it never leaves this file).
struct Invalid {
  SceneError error;
};
[[noreturn]] void fail(std::string pointer, std::string message) { throw Invalid{{std::move(pointer), std::move(message)}}; }

std::string describe_type(const json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return "an integer";
  if (v.is_number_float()) {
    const double x = v.get<double>();
    return std::trunc(x) == x ? "a number" : "a number with a fraction";
  }
  const std::string t = v.type_name();
  return (t == "array" || t == "object") ? "an " + t : "a " + t;
}

void expect_object(const json& v, const std::string& p) {
  if (!v.is_object()) fail(p, "expected an object, found " + describe_type(v));
}

// Every member of `v` must be one of `allowed`.
void only_fields(const json& v, const std::string& p, std::initializer_list<std::string_view> allowed) {
  for (const auto& [key, member] : v.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string list;
    for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    fail(child(p, key), "unknown field (expected one of: " + list + ")");
  }
}

const json* optional_field(const json& v, std::string_view key) {
  const auto it = v.find(key);
  return it == v.end() ? nullptr : &*it;
}
const json& required_field(const json& v, const std::string& p, std::string_view key) {
  const json* f = optional_field(v, key);
  if (f == nullptr) fail(child(p, key), "missing field");
  return *f;
}

double number(const json& v, const std::string& p) {
  if (!v.is_number()) fail(p, "expected a number, found " + describe_type(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(p, "not a finite number");
  return x;
}
double positive_number(const json& v, const std::string& p) {
  const double x = number(v, p);
  if (!(x > 0)) fail(p, "must be positive");
  return x;
}

// An integer field. The parser turned every number whose text is an integer that fits in 64 bits into an
// integer ("1e3" included, json_locator.hpp); a number that is still a double is either not an integer or
// too large for 64 bits, or -0 (which is 0).
std::uint64_t integer(const json& v, const std::string& p, std::uint64_t min, std::uint64_t max) {
  const std::string too_small = min == 1 ? "must be positive" : "must be at least " + std::to_string(min);
  const std::string too_large = "out of range (at most " + std::to_string(max) + ")";
  if (v.is_number_float()) {
    const double x = v.get<double>();
    if (x == 0) {
      if (min > 0) fail(p, too_small);
      return 0;
    }
    if (x < 0) fail(p, too_small);
    if (x >= 0x1p64) fail(p, too_large);
    fail(p, "expected an integer, found a number with a fraction");
  }
  if (!(v.is_number_integer() || v.is_number_unsigned())) fail(p, "expected an integer, found " + describe_type(v));
  if (!v.is_number_unsigned() && v.get<std::int64_t>() < 0) fail(p, too_small);
  const std::uint64_t x = v.get<std::uint64_t>();
  if (x < min) fail(p, too_small);
  if (x > max) fail(p, too_large);
  return x;
}

Vec3 vec3(const json& v, const std::string& p) {
  if (!v.is_array() || v.size() != 3) {
    fail(p, "expected an array of 3 numbers, found " +
                (v.is_array() ? "an array of " + std::to_string(v.size()) : describe_type(v)));
  }
  return {number(v[0], child(p, 0)), number(v[1], child(p, 1)), number(v[2], child(p, 2))};
}
Vec3 nonzero_vec3(const json& v, const std::string& p) {
  const Vec3 x = vec3(v, p);
  if (x.x == 0 && x.y == 0 && x.z == 0) fail(p, "zero vector");
  return x;
}

Rgb color(const json& v, const std::string& p) {
  if (!v.is_array() || v.size() != 3) {
    fail(p, "expected a colour [r, g, b] with components in [0, 1], found " +
                (v.is_array() ? "an array of " + std::to_string(v.size()) : describe_type(v)));
  }
  double c[3];
  for (std::size_t k = 0; k < 3; ++k) {
    c[k] = number(v[k], child(p, k));
    if (c[k] < 0 || c[k] > 1) fail(child(p, k), "colour component outside [0, 1]");
  }
  return {c[0], c[1], c[2]};
}

// The image settings of a scene: the file's (each optional, with the defaults of scene.hpp), each checked,
// then the overrides.
ImageSize read_image(const json* v, const std::string& p, Scene& scene, const SceneOverrides& overrides) {
  ImageSize size{scene_defaults::width, scene_defaults::height};
  if (v != nullptr) {
    expect_object(*v, p);
    only_fields(*v, p, {"width", "height", "samples_per_pixel", "seed"});
    if (const json* w = optional_field(*v, "width"))
      size.width = static_cast<std::uint32_t>(integer(*w, child(p, "width"), 1, max_image_side));
    if (const json* h = optional_field(*v, "height"))
      size.height = static_cast<std::uint32_t>(integer(*h, child(p, "height"), 1, max_image_side));
    if (const json* s = optional_field(*v, "samples_per_pixel"))
      scene.samples_per_pixel =
          static_cast<std::uint32_t>(integer(*s, child(p, "samples_per_pixel"), 1, max_samples_per_pixel));
    if (const json* s = optional_field(*v, "seed"))
      scene.seed = integer(*s, child(p, "seed"), 0, std::numeric_limits<std::uint64_t>::max());
  }
  if (overrides.width) size.width = *overrides.width;
  if (overrides.height) size.height = *overrides.height;
  if (overrides.samples_per_pixel) scene.samples_per_pixel = *overrides.samples_per_pixel;
  if (size.width == 0 || size.height == 0 || size.width > max_image_side || size.height > max_image_side ||
      scene.samples_per_pixel == 0 || scene.samples_per_pixel > max_samples_per_pixel)
    fail(p, "image size or samples per pixel out of range after overrides");
  return size;
}

NearPlaneWindow read_window(const json& v, const std::string& p, double near) {
  expect_object(v, p);
  only_fields(v, p, {"left", "right", "bottom", "top"});
  NearPlaneWindow w{number(required_field(v, p, "left"), child(p, "left")),
                    number(required_field(v, p, "right"), child(p, "right")),
                    number(required_field(v, p, "bottom"), child(p, "bottom")),
                    number(required_field(v, p, "top"), child(p, "top")), near};
  if (!(w.left < w.right)) fail(child(p, "right"), "must be greater than left");
  if (!(w.bottom < w.top)) fail(child(p, "top"), "must be greater than bottom");
  return w;
}

// Every ray of the image must be valid input (finite). Each coordinate of a ray's origin — the window point
// l + (i + s)/m·(r − l), then its world image — and of the window point a perspective direction normalizes is
// a monotone function of the sample position (sums, and products by constants, each rounded monotonically),
// so it is finite everywhere when it is finite at the image's four corners.
void check_corner_rays(const Camera& camera, const std::string& p) {
  const double last = std::nextafter(1.0, 0.0);
  const std::uint32_t m = camera.image.width - 1, n = camera.image.height - 1;
  const struct { std::uint32_t i, j; double x, y; } corners[] = {{0, 0, 0, 0}, {m, 0, last, 0}, {0, n, 0, last}, {m, n, last, last}};
  for (const auto& c : corners) {
    try {
      (void)camera.ray(c.i, c.j, {c.x, c.y});
    } catch (const invalid_input& e) {
      fail(p, std::string("the image's rays are not finite (") + e.what() + ")");
    }
  }
}

Camera read_camera_unchecked(const json& v, const std::string& p, ImageSize image);

// The camera of a scene, with every ray of its image checked to be valid input (error under `p`).
Camera read_camera(const json& v, const std::string& p, ImageSize image) {
  const Camera camera = read_camera_unchecked(v, p, image);
  check_corner_rays(camera, p);
  return camera;
}

Camera read_camera_unchecked(const json& v, const std::string& p, ImageSize image) {
  expect_object(v, p);
  only_fields(v, p, {"eye", "target", "up", "perspective", "orthographic"});
  const Vec3 eye = vec3(required_field(v, p, "eye"), child(p, "eye"));
  const Vec3 target = vec3(required_field(v, p, "target"), child(p, "target"));
  const json* up_field = optional_field(v, "up");
  const Vec3 up = up_field ? nonzero_vec3(*up_field, child(p, "up")) : scene_defaults::up;
  if (eye.x == target.x && eye.y == target.y && eye.z == target.z) fail(child(p, "target"), "same point as eye");
  // The view direction target − eye must be a finite vector (camera_to_world normalizes it); a target so far
  // from the eye that the difference overflows is the target's fault, not the up vector's.
  const double view[3] = {target.x - eye.x, target.y - eye.y, target.z - eye.z};
  for (double c : view)
    if (!std::isfinite(c)) fail(child(p, "target"), "too far from eye: target − eye overflows");
  Transform to_world;
  try {
    to_world = camera_to_world(eye, target, up);
  } catch (const invalid_input&) {
    if (up_field) fail(child(p, "up"), "parallel to the view direction (eye to target)");
    fail(p, "the default up vector [0, 1, 0] is parallel to the view direction (eye to target): give \"up\"");
  }

  const json* perspective = optional_field(v, "perspective");
  const json* orthographic = optional_field(v, "orthographic");
  if (perspective && orthographic) fail(p, "give either perspective or orthographic, not both");
  const double aspect = static_cast<double>(image.width) / image.height;

  if (!orthographic) {
    if (!perspective) {  // the default camera
      return Camera::perspective(
          to_world, window_from_field_of_view(scene_defaults::fov_degrees, aspect, scene_defaults::near), image);
    }
    const std::string q = child(p, "perspective");
    expect_object(*perspective, q);
    only_fields(*perspective, q, {"fov_degrees", "window", "near", "ray_start"});
    const json* fov = optional_field(*perspective, "fov_degrees");
    const json* window = optional_field(*perspective, "window");
    const json* near_field = optional_field(*perspective, "near");
    if (fov && window) fail(q, "give either fov_degrees or window, not both");
    if (!fov && !window) fail(child(q, "fov_degrees"), "missing field (or window)");
    if (window && !near_field) fail(child(q, "near"), "missing field (a window lies at z = -near)");
    const double near = near_field ? positive_number(*near_field, child(q, "near")) : scene_defaults::near;
    RayStart start = RayStart::near_plane;
    if (const json* s = optional_field(*perspective, "ray_start")) {
      const std::string sq = child(q, "ray_start");
      if (!s->is_string()) fail(sq, "expected \"near_plane\" or \"eye\", found " + describe_type(*s));
      if (*s == "eye") start = RayStart::eye;
      else if (*s != "near_plane") fail(sq, "expected \"near_plane\" or \"eye\", found " + quote(s->get<std::string>()));
    }
    Camera camera = Camera::perspective(
        to_world, window ? read_window(*window, child(q, "window"), near) : NearPlaneWindow{}, image);
    if (!window) {
      const double degrees = number(*fov, child(q, "fov_degrees"));
      if (!(degrees > 0 && degrees < 180)) fail(child(q, "fov_degrees"), "must be in (0, 180)");
      camera.window = window_from_field_of_view(degrees, aspect, near);
    }
    camera.start = start;
    return camera;
  }

  const std::string q = child(p, "orthographic");
  expect_object(*orthographic, q);
  only_fields(*orthographic, q, {"height", "window", "near"});
  const json* height = optional_field(*orthographic, "height");
  const json* window = optional_field(*orthographic, "window");
  if (height && window) fail(q, "give either height or window, not both");
  if (!height && !window) fail(child(q, "height"), "missing field (or window)");
  double near = 0;
  if (const json* n = optional_field(*orthographic, "near")) near = number(*n, child(q, "near"));
  if (window) return Camera::orthographic(to_world, read_window(*window, child(q, "window"), near), image);
  const double h = positive_number(*height, child(q, "height"));
  return Camera::orthographic(to_world, {-h * aspect / 2, h * aspect / 2, -h / 2, h / 2, near}, image);
}

Background read_background(const json& v, const std::string& p) {
  if (v.is_array()) {
    const Rgb c = color(v, p);
    return {c, c};
  }
  if (!v.is_object()) fail(p, "expected a colour [r, g, b] or an object {\"horizon\", \"zenith\"}, found " + describe_type(v));
  only_fields(v, p, {"horizon", "zenith"});
  return {color(required_field(v, p, "horizon"), child(p, "horizon")),
          color(required_field(v, p, "zenith"), child(p, "zenith"))};
}

// Some unit vector in the plane: the world axis least aligned with n, projected (for the checker's u).
Vec3 default_u_axis(const Vec3& n) {
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  if (ay >= ax && ay >= az) return {1, 0, 0};  // a floor or ceiling: x and z
  if (ax >= az) return {0, 0, 1};              // a wall facing x: z and y
  return {1, 0, 0};                            // a wall facing z: x and y
}

// A surface's optional "name" (a string), or `fallback`.
std::string name_field(const json& v, const std::string& p, std::string fallback) {
  const json* name = optional_field(v, "name");
  if (name == nullptr) return fallback;
  if (!name->is_string()) fail(child(p, "name"), "expected a string, found " + describe_type(*name));
  return name->get<std::string>();
}

ScenePlane read_plane(const json& v, const std::string& p, std::size_t index) {
  expect_object(v, p);
  only_fields(v, p, {"name", "point", "normal", "color", "checker"});
  ScenePlane plane;
  plane.name = name_field(v, p, "plane " + std::to_string(index));
  plane.plane.point = vec3(required_field(v, p, "point"), child(p, "point"));
  plane.plane.normal = nonzero_vec3(required_field(v, p, "normal"), child(p, "normal"));
  const json* solid = optional_field(v, "color");
  const json* checker = optional_field(v, "checker");
  if (solid && checker) fail(p, "give either color or checker, not both");
  if (!solid && !checker) {
    plane.color = scene_defaults::plane_colors[index % scene_defaults::plane_colors.size()];
    return plane;
  }
  if (solid) {
    plane.color = color(*solid, child(p, "color"));
    return plane;
  }
  const std::string q = child(p, "checker");
  expect_object(*checker, q);
  only_fields(*checker, q, {"colors", "size", "u_axis"});
  const json& colors = required_field(*checker, q, "colors");
  const std::string cq = child(q, "colors");
  if (!colors.is_array() || colors.size() != 2)
    fail(cq, "expected an array of 2 colours, found " +
                 (colors.is_array() ? "an array of " + std::to_string(colors.size()) : describe_type(colors)));
  Checker c{{color(colors[0], child(cq, 0)), color(colors[1], child(cq, 1))},
            positive_number(required_field(*checker, q, "size"), child(q, "size")),
            default_u_axis(plane.plane.normal)};
  if (const json* u = optional_field(*checker, "u_axis")) {
    c.u_axis = nonzero_vec3(*u, child(q, "u_axis"));
    const Vec3& n = plane.plane.normal;
    const formulas::Vector3<double> side = formulas::cross<double>({c.u_axis.x, c.u_axis.y, c.u_axis.z}, {n.x, n.y, n.z});
    if (side[0] == 0 && side[1] == 0 && side[2] == 0) fail(child(q, "u_axis"), "parallel to the plane's normal");
  }
  plane.color = c.colors[0];
  plane.checker = c;
  return plane;
}

// A power of two (positive or negative): multiplying by it is exact unless the product leaves the double
// range or underflows.
bool is_power_of_two(double s) {
  int exponent = 0;
  return s != 0 && std::isfinite(s) && std::fabs(std::frexp(s, &exponent)) == 0.5;
}

SceneMeshReference read_mesh_reference(const json& v, const std::string& p, std::size_t index) {
  expect_object(v, p);
  only_fields(v, p, {"file", "transform", "rounding", "color"});
  SceneMeshReference m;
  m.pointer = p;
  const json& file = required_field(v, p, "file");
  if (!file.is_string() || file.get<std::string>().empty())
    fail(child(p, "file"), "expected a file name (a non-empty string), found " + describe_type(file));
  m.file = file.get<std::string>();
  // The system's calls end a name at its first NUL: "a.off\u0000x" would open a.off. Refuse it.
  if (m.file.find('\0') != std::string::npos)
    fail(child(p, "file"), "the file name contains a NUL character (\\u0000), which no file name can hold");
  m.color = scene_defaults::plane_colors[(index + 3) % scene_defaults::plane_colors.size()];
  if (const json* c = optional_field(v, "color")) m.color = color(*c, child(p, "color"));
  if (const json* r = optional_field(v, "rounding")) {
    if (!r->is_string() || (r->get<std::string>() != "exact" && r->get<std::string>() != "nearest"))
      fail(child(p, "rounding"), "expected \"exact\" or \"nearest\", found " + describe_type(*r));
    m.rounded = r->get<std::string>() == "nearest";
  }
  if (const json* t = optional_field(v, "transform")) {
    const std::string q = child(p, "transform");
    if (!t->is_array() || t->size() != 16)
      fail(q, "expected 16 numbers (a row-major 4x4 matrix), found " +
                  (t->is_array() ? "an array of " + std::to_string(t->size()) : describe_type(*t)));
    double a[16];
    for (std::size_t k = 0; k < 16; ++k) a[k] = number((*t)[k], child(q, k));
    if (a[12] != 0 || a[13] != 0 || a[14] != 0 || a[15] != 1) fail(q, "the bottom row must be 0 0 0 1 (an affine transform)");
    for (std::size_t r = 0; r < 3; ++r) {
      for (std::size_t c = 0; c < 4; ++c) {
        const double x = a[4 * r + c];
        if (!m.rounded && c < 3 && (r == c ? !is_power_of_two(x) : x != 0))
          fail(child(q, 4 * r + c), "only scalings by powers of two (±2^k on the diagonal) and translations are "
                                    "applied exactly to mesh vertices; this matrix would round them (\"rounding\": "
                                    "\"nearest\" rounds each image correctly instead)");
        m.matrix[r][c] = x;
      }
    }
  }
  return m;
}

SceneSphere read_sphere(const json& v, const std::string& p, std::size_t index) {
  expect_object(v, p);
  only_fields(v, p, {"name", "center", "radius", "color"});
  SceneSphere sphere;
  sphere.name = name_field(v, p, "sphere " + std::to_string(index));
  sphere.sphere.center = vec3(required_field(v, p, "center"), child(p, "center"));
  sphere.sphere.radius = positive_number(required_field(v, p, "radius"), child(p, "radius"));
  sphere.color = scene_defaults::plane_colors[(index + 1) % scene_defaults::plane_colors.size()];
  if (const json* c = optional_field(v, "color")) sphere.color = color(*c, child(p, "color"));
  return sphere;
}

Scene read_scene(const json& doc, const SceneOverrides& overrides) {
  const std::string root;
  expect_object(doc, root);
  only_fields(doc, root, {"description", "image", "camera", "background", "fog", "planes", "meshes", "spheres"});
  Scene scene;
  if (const json* d = optional_field(doc, "description"); d && !d->is_string())
    fail("/description", "expected a string, found " + describe_type(*d));
  scene.image = read_image(optional_field(doc, "image"), "/image", scene, overrides);
  scene.camera = read_camera(required_field(doc, root, "camera"), "/camera", scene.image);
  scene.background = scene_defaults::background;
  if (const json* b = optional_field(doc, "background")) scene.background = read_background(*b, "/background");
  if (const json* f = optional_field(doc, "fog")) {
    expect_object(*f, "/fog");
    only_fields(*f, "/fog", {"distance"});
    scene.fog_distance = positive_number(required_field(*f, "/fog", "distance"), "/fog/distance");
  }
  const json* spheres = optional_field(doc, "spheres");
  if (spheres != nullptr) {
    if (!spheres->is_array()) fail("/spheres", "expected an array of spheres, found " + describe_type(*spheres));
    for (std::size_t k = 0; k < spheres->size(); ++k)
      scene.spheres.push_back(read_sphere((*spheres)[k], child("/spheres", k), k));
  }
  const json* planes = spheres != nullptr ? optional_field(doc, "planes") : &required_field(doc, root, "planes");
  if (planes != nullptr) {
    if (!planes->is_array()) fail("/planes", "expected an array of planes, found " + describe_type(*planes));
    for (std::size_t k = 0; k < planes->size(); ++k)
      scene.planes.push_back(read_plane((*planes)[k], child("/planes", k), k));
  }
  if (const json* meshes = optional_field(doc, "meshes")) {
    if (!meshes->is_array()) fail("/meshes", "expected an array of meshes, found " + describe_type(*meshes));
    for (std::size_t k = 0; k < meshes->size(); ++k)
      scene.mesh_files.push_back(read_mesh_reference((*meshes)[k], child("/meshes", k), k));
  }
  return scene;
}

}  // namespace

std::vector<Sphere> Scene::sphere_geometry() const {
  std::vector<Sphere> g;
  g.reserve(spheres.size());
  for (const SceneSphere& s : spheres) g.push_back(s.sphere);
  return g;
}

std::vector<Plane> Scene::geometry() const {
  std::vector<Plane> g;
  g.reserve(planes.size());
  for (const ScenePlane& p : planes) g.push_back(p.plane);
  return g;
}

std::size_t Scene::mesh_of_triangle(std::uint32_t triangle) const noexcept {
  const auto after = std::upper_bound(mesh_first_triangle.begin(), mesh_first_triangle.end(), triangle);
  return after == mesh_first_triangle.begin() ? 0 : static_cast<std::size_t>(after - mesh_first_triangle.begin() - 1);
}

std::optional<SceneError> load_scene_meshes(Scene& scene, const std::filesystem::path& scene_directory) {
  scene.mesh = Mesh{};
  scene.mesh_first_triangle.clear();
  for (const SceneMeshReference& reference : scene.mesh_files) {
    const std::filesystem::path path = scene_directory / std::filesystem::path(reference.file);
    // A device or a pipe (/dev/zero, /dev/stdin) could be read without end: a scene's mesh is a regular file.
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
        !std::filesystem::is_directory(status))
      return SceneError{child(reference.pointer, "file"), path.string() + ": not a regular file"};
    Mesh mesh;
    try {
      mesh = io::read_mesh(path);
    } catch (const std::exception& e) {
      return SceneError{child(reference.pointer, "file"), e.what()};
    }
    const std::uint64_t vertices = scene.mesh.vertices.size(), triangles = scene.mesh.triangles.size();
    if (vertices + mesh.vertices.size() > std::numeric_limits<std::uint32_t>::max() ||
        triangles + mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max())
      return SceneError{child(reference.pointer, "file"), "the scene's meshes have more than 2^32 - 1 vertices or triangles"};
    scene.mesh_first_triangle.push_back(static_cast<std::uint32_t>(triangles));
    const auto& m = reference.matrix;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const Vec3& x = mesh.vertices[v];
      std::optional<double> image[3];
      for (std::size_t r = 0; r < 3; ++r) {
        if (reference.rounded) {  // the exact image rounded once; ±inf when it rounds beyond the doubles
          const double y = round_affine({m[r][0], m[r][1], m[r][2]}, x, m[r][3]);
          if (std::isfinite(y)) image[r] = y;
        } else {  // a diagonal of powers of two: row r scales coordinate r
          image[r] = io::exact_affine(r == 0 ? x.x : r == 1 ? x.y : x.z, m[r][r], m[r][3]);
        }
      }
      if (!image[0] || !image[1] || !image[2])
        return SceneError{child(reference.pointer, "transform"),
                          "the image of vertex " + std::to_string(v) + " of " + path.string() +
                              (reference.rounded ? " rounds beyond the doubles"
                                                 : " is not exact in doubles (rounded, overflows or underflows)")};
      scene.mesh.vertices.push_back({*image[0], *image[1], *image[2]});
    }
    for (const auto& t : mesh.triangles)
      scene.mesh.triangles.push_back({t[0] + static_cast<std::uint32_t>(vertices), t[1] + static_cast<std::uint32_t>(vertices),
                                      t[2] + static_cast<std::uint32_t>(vertices)});
  }
  return std::nullopt;
}

std::string SceneError::str() const { return printable(pointer.empty() ? message : pointer + ": " + message); }

SceneParse parse_scene(std::string_view text, const SceneOverrides& overrides) {
  const LocatedJson parsed = parse_located_json(text);
  if (!parsed.error.empty()) return {std::nullopt, {parsed.error_pointer, parsed.error}};
  try {
    return {read_scene(parsed.document, overrides), {}};
  } catch (const Invalid& invalid) {
    return {std::nullopt, invalid.error};
  }
}

}  // namespace raykernel::cli

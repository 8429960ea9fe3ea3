// Scene files for `raykernel render`: JSON parsing with the JSON Pointer of every error, and validation.
#include "scene.hpp"

#include <raykernel/transform.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

namespace raykernel::cli {
namespace {

using nlohmann::json;

constexpr std::uint32_t max_image_side = 16384;
constexpr std::uint32_t max_samples_per_pixel = 4096;

// ---- JSON Pointers -----------------------------------------------------------------------------------

std::string escape_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}
std::string child(const std::string& pointer, std::string_view key) { return pointer + "/" + escape_token(key); }
std::string child(const std::string& pointer, std::size_t index) { return pointer + "/" + std::to_string(index); }

// ---- Syntax: a SAX handler that builds the document and knows where it is --------------------------------

// Forwards every event to nlohmann's DOM builder and keeps the pointer of the value being parsed, so that
// a number outside the double range (which the parser reports without a location) gets its pointer.
class LocatingSax {
 public:
  explicit LocatingSax(json& root) : dom_(root, false) {}

  bool null() { return value(), dom_.null(); }
  bool boolean(bool v) { return value(), dom_.boolean(v); }
  bool number_integer(json::number_integer_t v) { return value(), dom_.number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return value(), dom_.number_unsigned(v); }
  bool number_float(json::number_float_t v, const json::string_t& s) { return value(), dom_.number_float(v, s); }
  bool string(json::string_t& v) { return value(), dom_.string(v); }
  bool binary(json::binary_t& v) { return value(), dom_.binary(v); }
  bool start_object(std::size_t n) {
    value();
    frames_.push_back({false, -1, {}});
    return dom_.start_object(n);
  }
  bool key(json::string_t& k) {
    frames_.back().key = k;
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return dom_.end_object();
  }
  bool start_array(std::size_t n) {
    value();
    frames_.push_back({true, -1, {}});
    return dom_.start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return dom_.end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& last_token, const Exception& ex) {
    // `position` is just past the offending token: point at its first character.
    error_position_ = position >= last_token.size() ? position - last_token.size() : 0;
    error_id_ = ex.id;
    error_what_ = ex.what();
    error_pointer_ = pointer_of_next_value();
    return dom_.parse_error(position, last_token, ex);
  }

  [[nodiscard]] bool failed() const noexcept { return error_id_ != 0; }
  [[nodiscard]] int error_id() const noexcept { return error_id_; }
  [[nodiscard]] std::size_t error_position() const noexcept { return error_position_; }
  [[nodiscard]] const std::string& error_what() const noexcept { return error_what_; }
  [[nodiscard]] const std::string& error_pointer() const noexcept { return error_pointer_; }

 private:
  struct Frame {
    bool array;
    long index;       // the element being parsed (arrays)
    std::string key;  // the member being parsed (objects)
  };
  void value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  // The pointer of the value the parser is reading now: in an array, the element after the last one
  // started; in an object, the member of the last key.
  std::string pointer_of_next_value() const {
    std::string p;
    for (std::size_t f = 0; f < frames_.size(); ++f) {
      const Frame& frame = frames_[f];
      const bool innermost = f + 1 == frames_.size();
      if (frame.array) p = child(p, static_cast<std::size_t>(frame.index + (innermost ? 1 : 0)));
      else p = child(p, frame.key);
    }
    return p;
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  std::vector<Frame> frames_;
  int error_id_ = 0;
  std::size_t error_position_ = 0;
  std::string error_what_, error_pointer_;
};

// "line L, column C" of a byte offset (1-based, as nlohmann counts).
std::string line_and_column(std::string_view text, std::size_t position) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < position && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string without_prefix(const std::string& what) {
  const std::size_t end = what.find("] ");
  return end == std::string::npos ? what : what.substr(end + 2);
}

// ---- Validation --------------------------------------------------------------------------------------

// Unwinds the validation to parse_scene, which turns it into a SceneError (it never leaves this file).
struct Invalid {
  SceneError error;
};
[[noreturn]] void fail(std::string pointer, std::string message) { throw Invalid{{std::move(pointer), std::move(message)}}; }

std::string describe_type(const json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return "an integer";
  if (v.is_number_float()) return "a number with a fraction";
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

std::uint64_t integer(const json& v, const std::string& p, std::uint64_t min, std::uint64_t max) {
  if (!(v.is_number_integer() || v.is_number_unsigned())) fail(p, "expected an integer, found " + describe_type(v));
  const std::string too_small = min == 1 ? "must be positive" : "must be at least " + std::to_string(min);
  if (!v.is_number_unsigned() && v.get<std::int64_t>() < 0) fail(p, too_small);
  const std::uint64_t x = v.get<std::uint64_t>();
  if (x < min) fail(p, too_small);
  if (x > max) fail(p, "too large (at most " + std::to_string(max) + ")");
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

ImageSize read_image(const json& v, const std::string& p, Scene& scene, const SceneOverrides& overrides) {
  expect_object(v, p);
  only_fields(v, p, {"width", "height", "samples_per_pixel", "seed"});
  auto width = static_cast<std::uint32_t>(integer(required_field(v, p, "width"), child(p, "width"), 1, max_image_side));
  auto height = static_cast<std::uint32_t>(integer(required_field(v, p, "height"), child(p, "height"), 1, max_image_side));
  if (const json* s = optional_field(v, "samples_per_pixel"))
    scene.samples_per_pixel = static_cast<std::uint32_t>(integer(*s, child(p, "samples_per_pixel"), 1, max_samples_per_pixel));
  if (const json* s = optional_field(v, "seed"))
    scene.seed = integer(*s, child(p, "seed"), 0, std::numeric_limits<std::uint64_t>::max());
  if (overrides.width) width = *overrides.width;
  if (overrides.height) height = *overrides.height;
  if (overrides.samples_per_pixel) scene.samples_per_pixel = *overrides.samples_per_pixel;
  if (width == 0 || height == 0 || width > max_image_side || height > max_image_side || scene.samples_per_pixel == 0 ||
      scene.samples_per_pixel > max_samples_per_pixel)
    fail(p, "image size or samples per pixel out of range after overrides");
  return {width, height};
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
  const Vec3 up = nonzero_vec3(required_field(v, p, "up"), child(p, "up"));
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
    fail(child(p, "up"), "parallel to the view direction (eye to target)");
  }

  const json* perspective = optional_field(v, "perspective");
  const json* orthographic = optional_field(v, "orthographic");
  if (perspective && orthographic) fail(p, "give either perspective or orthographic, not both");
  if (!perspective && !orthographic) fail(child(p, "perspective"), "missing field (or orthographic)");
  const double aspect = static_cast<double>(image.width) / image.height;

  if (perspective) {
    const std::string q = child(p, "perspective");
    expect_object(*perspective, q);
    only_fields(*perspective, q, {"fov_degrees", "window", "near"});
    const json* fov = optional_field(*perspective, "fov_degrees");
    const json* window = optional_field(*perspective, "window");
    const json* near_field = optional_field(*perspective, "near");
    if (fov && window) fail(q, "give either fov_degrees or window, not both");
    if (!fov && !window) fail(child(q, "fov_degrees"), "missing field (or window)");
    if (window && !near_field) fail(child(q, "near"), "missing field (a window lies at z = -near)");
    const double near = near_field ? positive_number(*near_field, child(q, "near")) : 0.1;
    if (window) return Camera::perspective(to_world, read_window(*window, child(q, "window"), near), image);
    const double degrees = number(*fov, child(q, "fov_degrees"));
    if (!(degrees > 0 && degrees < 180)) fail(child(q, "fov_degrees"), "must be in (0, 180)");
    return Camera::perspective(to_world, window_from_field_of_view(degrees, aspect, near), image);
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

ScenePlane read_plane(const json& v, const std::string& p, std::size_t index) {
  expect_object(v, p);
  only_fields(v, p, {"name", "point", "normal", "color", "checker"});
  ScenePlane plane;
  plane.name = "plane " + std::to_string(index);
  if (const json* name = optional_field(v, "name")) {
    if (!name->is_string()) fail(child(p, "name"), "expected a string, found " + describe_type(*name));
    plane.name = name->get<std::string>();
  }
  plane.plane.point = vec3(required_field(v, p, "point"), child(p, "point"));
  plane.plane.normal = nonzero_vec3(required_field(v, p, "normal"), child(p, "normal"));
  const json* solid = optional_field(v, "color");
  const json* checker = optional_field(v, "checker");
  if (solid && checker) fail(p, "give either color or checker, not both");
  if (!solid && !checker) fail(child(p, "color"), "missing field (or checker)");
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

Scene read_scene(const json& doc, const SceneOverrides& overrides) {
  const std::string root;
  expect_object(doc, root);
  only_fields(doc, root, {"description", "image", "camera", "background", "fog", "planes"});
  Scene scene;
  if (const json* d = optional_field(doc, "description"); d && !d->is_string())
    fail("/description", "expected a string, found " + describe_type(*d));
  scene.image = read_image(required_field(doc, root, "image"), "/image", scene, overrides);
  scene.camera = read_camera(required_field(doc, root, "camera"), "/camera", scene.image);
  scene.background = {{0.86, 0.90, 0.96}, {0.42, 0.60, 0.88}};
  if (const json* b = optional_field(doc, "background")) scene.background = read_background(*b, "/background");
  if (const json* f = optional_field(doc, "fog")) {
    expect_object(*f, "/fog");
    only_fields(*f, "/fog", {"distance"});
    scene.fog_distance = positive_number(required_field(*f, "/fog", "distance"), "/fog/distance");
  }
  const json& planes = required_field(doc, root, "planes");
  if (!planes.is_array()) fail("/planes", "expected an array of planes, found " + describe_type(planes));
  for (std::size_t k = 0; k < planes.size(); ++k) scene.planes.push_back(read_plane(planes[k], child("/planes", k), k));
  return scene;
}

}  // namespace

std::vector<Plane> Scene::geometry() const {
  std::vector<Plane> g;
  g.reserve(planes.size());
  for (const ScenePlane& p : planes) g.push_back(p.plane);
  return g;
}

std::string SceneError::str() const { return pointer.empty() ? message : pointer + ": " + message; }

SceneParse parse_scene(std::string_view text, const SceneOverrides& overrides) {
  json doc;
  LocatingSax sax(doc);
  const bool parsed = json::sax_parse(text.begin(), text.end(), &sax, nlohmann::detail::input_format_t::json, true);
  if (!parsed || sax.failed()) {
    SceneParse r;
    if (sax.error_id() == 406) {  // a number outside the double range: its value is known
      r.error = {sax.error_pointer(), "number outside the double range (not finite), at " +
                                          line_and_column(text, sax.error_position())};
    } else {
      r.error = {"", "invalid JSON: " + without_prefix(sax.error_what())};
    }
    return r;
  }
  try {
    return {read_scene(doc, overrides), {}};
  } catch (const Invalid& invalid) {
    return {std::nullopt, invalid.error};
  }
}

}  // namespace raykernel::cli

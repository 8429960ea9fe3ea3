// fuzz_scene: arbitrary bytes as a scene file of `raykernel render` through the scene parser
// (cli::parse_scene) and, when they are a scene, through the renderer (cli::render_scene) at a tiny size.
//
// The input is the whole text of a scene file. It is parsed twice: as written, and with SceneOverrides
// (width and height at most 8, one sample per pixel), as `raykernel render --width --height --samples` does.
// Checked:
//   - parse_scene never throws, and the overrides change nothing but the camera's verdict (they change its
//     aspect ratio): the same scene or the same error, unless one of the two errors is about /camera;
//   - an error has a message, and a pointer that is a JSON Pointer (RFC 6901: empty, or "/"-separated tokens
//     with "~" only in "~0" and "~1"); nesting deeper than limits::max_json_depth is an error at the first
//     value too deep, whatever follows it; otherwise the error is a syntax error ("invalid JSON: ...", or a number outside
//     the double range) exactly when nlohmann's own parse rejects the text; otherwise the pointer leads into
//     the document, resolved here token by token: to an existing value, or, for "missing field", to a missing
//     member of an existing object;
//   - a scene renders at the small size without throwing (its camera gives valid rays for every pixel), with
//     images of the right size, statistics that add up, and every pixel accounted for: each pixel's ray
//     (Camera::ray at the pixel centre) is valid input, and its pixel in the stage image is grey exactly when
//     nearest_hit_traced needed only the fast path and otherwise has that stage's colour; its pixel in the
//     naive-difference image is magenta exactly when nearest_hit_naive picks another plane; a second render on
//     two threads with legends gives the same image.
// A scene's "meshes" are parsed and validated (their errors checked as above) but never loaded: parse_scene reads
// no files and this harness does not call load_scene_meshes, so a fuzzed file name reads nothing.
#include "fuzz_support.hpp"
#include "fuzz_text.hpp"

#include "common/limits.hpp"
#include "rendering/render.hpp"
#include "scenes/scene.hpp"

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace {

using raykernel::fuzz::check;
namespace cli = raykernel::cli;
using nlohmann::json;

constexpr std::uint32_t max_side = 8;

std::string_view current_text;

std::string describe_current() {
  return "scene text (" + std::to_string(current_text.size()) + " bytes, C-escaped):\n" +
         raykernel::fuzz::c_escaped(current_text);
}

cli::SceneParse parse(std::string_view text, const cli::SceneOverrides& overrides, const char* what) {
  try {
    return cli::parse_scene(text, overrides);
  } catch (const std::exception& e) {
    check(false, [&] { return std::string("parse_scene (") + what + ") throws: " + e.what(); });
  } catch (...) {
    check(false, [&] { return std::string("parse_scene (") + what + ") throws a non-standard exception"; });
  }
  return {};
}

// ---- Errors --------------------------------------------------------------------------------------------

// The reference tokens of a JSON Pointer (RFC 6901 §3–4), or nothing when it is not one.
std::optional<std::vector<std::string>> pointer_tokens(std::string_view pointer) {
  std::vector<std::string> tokens;
  if (pointer.empty()) return tokens;
  if (pointer[0] != '/') return std::nullopt;
  std::string token;
  for (std::size_t i = 1; i <= pointer.size(); ++i) {
    if (i == pointer.size() || pointer[i] == '/') {
      tokens.push_back(token);
      token.clear();
    } else if (pointer[i] == '~') {
      if (i + 1 >= pointer.size() || (pointer[i + 1] != '0' && pointer[i + 1] != '1')) return std::nullopt;
      token += pointer[i + 1] == '0' ? '~' : '/';
      ++i;
    } else {
      token += pointer[i];
    }
  }
  return tokens;
}

// The array index a token names (RFC 6901 §4: "0" or digits without a leading zero), if any.
std::optional<std::size_t> array_index(const std::string& token) {
  if (token.empty() || token.size() > 9 || (token.size() > 1 && token[0] == '0')) return std::nullopt;
  std::size_t n = 0;
  for (char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    n = n * 10 + static_cast<std::size_t>(c - '0');
  }
  return n;
}

// The value the tokens lead to, or nothing.
const json* resolve(const json& doc, const std::vector<std::string>& tokens, std::size_t count) {
  const json* v = &doc;
  for (std::size_t k = 0; k < count; ++k) {
    if (v->is_object()) {
      const auto it = v->find(tokens[k]);
      if (it == v->end()) return nullptr;
      v = &*it;
    } else if (v->is_array()) {
      const std::optional<std::size_t> i = array_index(tokens[k]);
      if (!i || *i >= v->size()) return nullptr;
      v = &(*v)[*i];
    } else {
      return nullptr;
    }
  }
  return v;
}

std::uint64_t syntax_errors = 0, nesting_errors = 0, errors_resolved = 0, errors_missing = 0;

void check_error(std::string_view text, const cli::SceneError& error) {
  auto where = [&] { return " (error '" + error.str() + "')"; };
  check(!error.message.empty(), [&] { return "the error has a message" + where(); });
  const std::optional<std::vector<std::string>> tokens = pointer_tokens(error.pointer);
  check(tokens.has_value(), [&] { return "the error's pointer is a JSON Pointer" + where(); });

  const json doc = json::parse(text.begin(), text.end(), nullptr, false);
  if (error.message.starts_with("arrays and objects nested deeper than")) {
    // Reading stops at the first array or object too deep, before any syntax error after it: its pointer has
    // exactly max_json_depth tokens, and leads into the document whenever the text is JSON.
    ++nesting_errors;
    check(tokens->size() == cli::limits::max_json_depth, [&] { return "a nesting error points at the first value too deep" + where(); });
    check(doc.is_discarded() || resolve(doc, *tokens, tokens->size()) != nullptr,
          [&] { return "a nesting error's pointer leads into the document" + where(); });
    return;
  }
  const bool range_error = error.message.starts_with("number outside the double range");
  const bool syntax_error = error.message.starts_with("invalid JSON") || range_error;
  check(syntax_error == doc.is_discarded(),
        [&] { return std::string("a syntax error exactly when nlohmann's parse rejects the text") + where(); });
  if (syntax_error) {
    ++syntax_errors;
    check(range_error || error.pointer.empty(), [&] { return "a syntax error points at the document" + where(); });
    return;
  }
  if (resolve(doc, *tokens, tokens->size()) != nullptr) {
    ++errors_resolved;
    return;
  }
  const json* parent = tokens->empty() ? nullptr : resolve(doc, *tokens, tokens->size() - 1);
  check(error.message.starts_with("missing field") && parent != nullptr && parent->is_object(), [&] {
    return "the error's pointer leads to a value of the document, or (missing field) to a member missing from an "
           "object" + where();
  });
  ++errors_missing;
}

// ---- Scenes --------------------------------------------------------------------------------------------

bool is_grey(const std::uint8_t* px) { return px[0] == px[1] && px[1] == px[2]; }

std::uint64_t scenes = 0, pixels = 0, planes_seen = 0;
std::array<std::uint64_t, raykernel::stage_count> pixels_by_stage{};

void check_render(const cli::Scene& scene) {
  // The pixel oracle below knows planes only: a scene with spheres (never produced by the mutations, whose field
  // names do not include them) is parsed and validated, not rendered (tests/render_test.cpp renders them).
  if (!scene.spheres.empty()) return;
  const std::uint32_t width = scene.image.width, height = scene.image.height;
  check(width >= 1 && width <= max_side && height >= 1 && height <= max_side && scene.samples_per_pixel == 1,
        "the overrides set the image size and one sample per pixel");
  cli::RenderOptions options;
  options.threads = 1;
  options.stage_image = true;
  options.compare_naive = true;
  options.naive_image = true;
  cli::RenderResult result;
  try {
    result = cli::render_scene(scene, options);
  } catch (const std::exception& e) {
    check(false, [&] { return std::string("render_scene of a valid scene throws: ") + e.what(); });
  }
  const std::size_t bytes = std::size_t{width} * height * 3;
  for (const cli::Image* image : {&result.image, &result.stages, &result.naive_difference, &result.naive}) {
    check(image->width == width && image->height == height && image->rgb.size() == bytes,
          "every image has the scene's size (after the overrides)");
  }
  const cli::RenderStats& stats = result.stats;
  std::uint64_t by_stage = 0, rays_by_stage = 0;
  for (std::size_t k = 0; k < raykernel::stage_count; ++k) by_stage += stats.pixels_by_stage[k], rays_by_stage += stats.rays_by_stage[k];
  check(stats.pixels == std::uint64_t{width} * height && stats.rays == stats.pixels && by_stage == stats.pixels &&
            rays_by_stage == stats.rays && stats.hit_rays <= stats.rays && stats.naive_compared,
        "the render's statistics add up");

  const std::vector<raykernel::Plane> geometry = scene.geometry();
  std::uint64_t hits = 0, differ = 0;
  for (std::uint32_t j = 0; j < height; ++j) {
    for (std::uint32_t i = 0; i < width; ++i) {
      const std::uint32_t row = height - 1 - j;
      auto at = [&](const std::string& what) {
        return "pixel (" + std::to_string(i) + ", " + std::to_string(j) + "): " + what;
      };
      const raykernel::Ray ray = scene.camera.ray(i, j, raykernel::PixelSample{});
      check(!raykernel::fuzz::ray_invalid_by_bits(ray), [&] {
        return at("the camera's ray is valid input: " + raykernel::fuzz::hex(ray.origin.x) + " " +
                  raykernel::fuzz::hex(ray.origin.y) + " " + raykernel::fuzz::hex(ray.origin.z) + " " +
                  raykernel::fuzz::hex(ray.direction.x) + " " + raykernel::fuzz::hex(ray.direction.y) + " " +
                  raykernel::fuzz::hex(ray.direction.z));
      });
      const raykernel::TracedNearestHit traced = raykernel::nearest_hit_traced(ray, geometry);
      const raykernel::Stage stage = raykernel::cli::slowest_stage(traced);
      ++pixels_by_stage[static_cast<std::size_t>(stage)];
      hits += traced.hit ? 1 : 0;
      const std::uint8_t* marked = result.stages.pixel(i, row);
      if (stage == raykernel::Stage::filter) {
        check(is_grey(marked), [&] { return at("grey in the stage image (the fast path decided)"); });
      } else {
        const auto& colour = cli::stage_marker_colors[static_cast<std::size_t>(stage)];
        check(std::equal(colour.begin(), colour.end(), marked),
              [&] { return at("the colour of stage " + std::string(raykernel::to_string(stage)) + " in the stage image"); });
      }
      const std::optional<raykernel::NearestHit> naive = raykernel::nearest_hit_naive(ray, geometry);
      const bool differs = naive.has_value() != traced.hit.has_value() || (naive && naive->plane != traced.hit->plane);
      differ += differs ? 1 : 0;
      const std::uint8_t* diff = result.naive_difference.pixel(i, row);
      const auto& magenta = cli::naive_difference_color;
      check(differs ? std::equal(magenta.begin(), magenta.end(), diff) : is_grey(diff),
            [&] { return at(differs ? "magenta (the naive loop picks another surface)" : "grey (the naive loop agrees)"); });
    }
  }
  check(stats.hit_rays == hits && stats.naive_rays_differ == differ && stats.naive_pixels_differ == differ,
        "the render's hit and naive-difference counts are the pixels'");

  options.threads = 2;
  options.legend = true;
  cli::RenderResult again;
  try {
    again = cli::render_scene(scene, options);
  } catch (const std::exception& e) {
    check(false, [&] { return std::string("render_scene on two threads with legends throws: ") + e.what(); });
  }
  check(again.image.rgb == result.image.rgb && again.naive.rgb == result.naive.rgb,
        "the render does not depend on the number of threads");
  ++scenes;
  pixels += stats.pixels;
  planes_seen += geometry.size();
}


// ---- The custom mutator ----------------------------------------------------------------------------------

// Byte mutations break JSON syntax almost every time (in a 90 s run without this mutator, 98 % of the inputs
// were syntax errors and 1 in 120 a scene). When the input parses as JSON, three times in four this mutator
// changes one value of the document instead — a number to an edge of binary64, scaled by 2^k or nudged by
// ulps; a value to another type; a member or element deleted, duplicated or added under one of the format's
// field names; a vector zeroed — and writes the document back (numbers round-trip exactly). Otherwise, and
// when the result does not fit, libFuzzer's byte mutations. RAYKERNEL_FUZZ_PLAIN_MUTATOR=1 turns it off.
bool plain_mutator_requested() {
  static const bool plain = [] {
    const char* v = std::getenv("RAYKERNEL_FUZZ_PLAIN_MUTATOR");
    return v != nullptr && *v != '\0' && std::string_view(v) != "0";
  }();
  return plain;
}

const char* const field_names[] = {"description", "image", "width", "height", "samples_per_pixel", "seed", "camera",
                                   "eye", "target", "up", "perspective", "orthographic", "fov_degrees", "near",
                                   "window", "left", "right", "bottom", "top", "background", "horizon", "zenith", "fog",
                                   "distance", "planes", "name", "point", "normal", "color", "checker", "colors",
                                   "size", "u_axis", "ray_start", "meshes", "file", "transform"};

// Every value of the document, parents before children.
void collect(json& v, std::vector<json*>& out) {
  out.push_back(&v);
  if (v.is_structured())
    for (json& child : v) collect(child, out);
}

json random_value(raykernel::testkit::SplitMix64& rng) {
  static const double special[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e308, -1e308, 1.7976931348623157e308, 5e-324,
                                   -5e-324, 2.2250738585072014e-308, 1e-300, 1e300, 0x1p-1000, 0x1p1000, 179.99999999999997,
                                   1e-16, 3.0, 8.881784197001252e-16};
  switch (rng() % 8) {
    case 0: return special[rng() % (sizeof special / sizeof special[0])];
    case 1: return static_cast<std::int64_t>(rng() % 20) - 4;
    case 2: return json::array({special[rng() % 20], special[rng() % 20], special[rng() % 20]});
    case 3: return json::array({static_cast<int>(rng() % 5) - 2, static_cast<int>(rng() % 5) - 2, static_cast<int>(rng() % 5) - 2});
    case 4: return json::object();
    case 5: return nullptr;
    case 6: return std::string(field_names[rng() % std::size(field_names)]);
    default: return rng() % 2 == 0;
  }
}

void mutate_value(json& doc, raykernel::testkit::SplitMix64& rng) {
  std::vector<json*> values;
  collect(doc, values);
  json& v = *values[rng() % values.size()];
  switch (rng() % 8) {
    case 0:
    case 1:
      if (v.is_number()) {  // an edge value, or this one scaled by 2^k, nudged or negated
        const double x = v.get<double>();
        switch (rng() % 4) {
          case 0: v = random_value(rng); break;
          case 1: v = std::ldexp(x, static_cast<int>(rng() % 2001) - 1000); break;
          case 2: v = std::nextafter(x, rng() % 2 ? HUGE_VAL : -HUGE_VAL); break;
          default: v = -x; break;
        }
        if (v.is_number_float() && !std::isfinite(v.get<double>())) v = x;  // dump would write null
        break;
      }
      [[fallthrough]];
    case 2: v = random_value(rng); break;
    case 3:  // delete a member or an element
      if (v.is_object() && !v.empty()) {
        auto it = v.begin();
        std::advance(it, static_cast<std::ptrdiff_t>(rng() % v.size()));
        v.erase(it);
      } else if (v.is_array() && !v.empty()) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>(rng() % v.size()));
      }
      break;
    case 4:  // duplicate an element or add a member under a field name
      if (v.is_array() && !v.empty()) {
        const json copy = v[rng() % v.size()];
        v.push_back(copy);
      } else if (v.is_object()) {
        v[field_names[rng() % std::size(field_names)]] = random_value(rng);
      }
      break;
    case 5:  // a vector zeroed, or one component zeroed
      if (v.is_array()) {
        for (json& c : v)
          if (c.is_number() && (rng() % 2 == 0)) c = rng() % 2 ? 0.0 : -0.0;
      }
      break;
    case 6:  // swap two elements or the values of two members
      if (v.is_structured() && v.size() >= 2) {
        std::vector<json*> children;
        for (json& c : v) children.push_back(&c);
        std::swap(*children[rng() % children.size()], *children[rng() % children.size()]);
      }
      break;
    default:  // replace this value by a copy of another value of the document
      v = json(*values[rng() % values.size()]);
      break;
  }
}

}  // namespace

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size)
    __attribute__((weak));

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  auto byte_mutation = [&] { return LLVMFuzzerMutate != nullptr ? LLVMFuzzerMutate(data, size, max_size) : size; };
  raykernel::testkit::SplitMix64 rng(seed);
  if (plain_mutator_requested() || rng() % 4 == 0) return byte_mutation();
  json doc = json::parse(data, data + size, nullptr, false);
  if (doc.is_discarded()) return byte_mutation();
  const int rounds = 1 + static_cast<int>(rng() % 3);
  for (int k = 0; k < rounds; ++k) mutate_value(doc, rng);
  const std::string text = doc.dump(rng() % 2 ? 1 : -1, ' ', false, json::error_handler_t::replace);
  if (text.size() > max_size) return byte_mutation();
  std::copy(text.begin(), text.end(), data);
  return text.size();
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("scene");
    raykernel::fuzz::set_input_describer(describe_current);
    raykernel::fuzz::print_at_exit([] {
      auto u = [](std::uint64_t x) { return static_cast<unsigned long long>(x); };
      std::fprintf(stderr,
                   "==== raykernel fuzz stats: scene: %llu scenes rendered (%llu pixels, %llu planes); errors: %llu "
                   "syntax, %llu nesting, %llu pointing at a value, %llu at a missing field; pixels by slowest stage: "
                   "filter %llu, compensated %llu, expansion %llu, exact %llu\n",
                   u(scenes), u(pixels), u(planes_seen), u(syntax_errors), u(nesting_errors), u(errors_resolved), u(errors_missing),
                   u(pixels_by_stage[0]), u(pixels_by_stage[1]), u(pixels_by_stage[2]), u(pixels_by_stage[3]));
    });
    return true;
  }();
  (void)initialized;
  current_text = std::string_view(reinterpret_cast<const char*>(data), size);

  const cli::SceneParse as_written = parse(current_text, {}, "as written");
  cli::SceneOverrides small;
  if (as_written.scene) {
    small.width = std::min(as_written.scene->image.width, max_side);
    small.height = std::min(as_written.scene->image.height, max_side);
  } else {
    small.width = 1 + static_cast<std::uint32_t>(size % max_side);
    small.height = 1 + static_cast<std::uint32_t>(size / max_side % max_side);
  }
  small.samples_per_pixel = 1;
  const cli::SceneParse overridden = parse(current_text, small, "with overrides");
  // The overrides replace the image size before the camera is built (a field-of-view camera takes the new
  // aspect ratio), so they may change the camera's verdict, and nothing else.
  const bool same = as_written.scene.has_value() == overridden.scene.has_value() &&
                    (as_written.scene || (as_written.error.pointer == overridden.error.pointer &&
                                          as_written.error.message == overridden.error.message));
  auto about_camera = [](const cli::SceneParse& p) { return !p.scene && p.error.pointer.starts_with("/camera"); };
  check(same || about_camera(as_written) || about_camera(overridden), [&] {
    return "the overrides change nothing but the camera's verdict (as written: " +
           (as_written.scene ? std::string("a scene") : as_written.error.str()) + "; with overrides: " +
           (overridden.scene ? std::string("a scene") : overridden.error.str()) + ")";
  });
  if (!as_written.scene) check_error(current_text, as_written.error);
  if (!overridden.scene) {
    if (!same) check_error(current_text, overridden.error);
    return 0;
  }
  check_render(*overridden.scene);
  return 0;
}

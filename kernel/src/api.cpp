// The public entry points: validation at the boundary, then the certified cascade, the exact reference or
// the naive baseline.
#include <raykernel/raykernel.hpp>

#include "certified/fp_requirements.hpp"
#include "certified/intersect_certified.hpp"
#include "entry_checks.hpp"
#include "fp_probe.hpp"
#include "exact/exact.hpp"
#include "ray_plane_formula.hpp"

#include <cmath>
#include <limits>
#include <string>


namespace raykernel {
namespace {

void throw_if_invalid(const Ray& ray, const Plane& plane) {
  if (detail::plausibly_valid(ray, plane)) return;
  if (std::optional<std::string> reason = validate(ray, plane)) throw invalid_input(*reason);
}

// The certified answer for any input. The fast path needs no validation (a certified answer implies valid
// input, certified/fast_path.hpp); the full cascade validates before it computes.
inline TracedIntersection certified(const Ray& ray, const Plane& plane) {
  if (!detail::default_floating_point_environment()) [[unlikely]] {
    throw_if_invalid(ray, plane);
    return {detail::exact::intersect(ray, plane), Stage::exact, Stage::exact};
  }
  return detail::intersect_certified(ray, plane);
}

}  // namespace

std::optional<std::string> validate(const Ray& ray, const Plane& plane) {
  struct Field {
    const char* name;
    const Vec3& value;
  };
  const Field fields[] = {{"ray origin", ray.origin},
                          {"ray direction", ray.direction},
                          {"plane point", plane.point},
                          {"plane normal", plane.normal}};
  for (const Field& f : fields) {
    const double component[3] = {f.value.x, f.value.y, f.value.z};
    for (int i = 0; i < 3; ++i) {
      if (std::isnan(component[i])) return std::string(f.name) + " " + "xyz"[i] + " is NaN";
      if (std::isinf(component[i]))
        return std::string(f.name) + " " + "xyz"[i] + " is " + (component[i] > 0 ? "+inf" : "-inf");
    }
  }
  const Vec3& d = ray.direction;
  if (d.x == 0 && d.y == 0 && d.z == 0) return std::string("ray direction is the zero vector");
  const Vec3& n = plane.normal;
  if (n.x == 0 && n.y == 0 && n.z == 0) return std::string("plane normal is the zero vector");
  return std::nullopt;
}

bool floating_point_environment_is_default() noexcept { return detail::default_floating_point_environment(); }

TracedIntersection intersect_traced(const Ray& ray, const Plane& plane) { return certified(ray, plane); }

Intersection intersect(const Ray& ray, const Plane& plane) { return certified(ray, plane).intersection; }

Intersection intersect_exact(const Ray& ray, const Plane& plane) {
  throw_if_invalid(ray, plane);
  return detail::exact::intersect(ray, plane);
}

ExactIntersection intersect_exact_rational(const Ray& ray, const Plane& plane) {
  throw_if_invalid(ray, plane);
  return detail::exact::intersect_rational(ray, plane);
}

Intersection intersect_naive(const Ray& ray, const Plane& plane) noexcept {
  const auto [num, den] = detail::ray_plane_terms<double>(ray, plane, [](double x) { return x; });
  if (den == 0) return {num == 0 ? Relation::in_plane : Relation::parallel, std::numeric_limits<double>::quiet_NaN()};
  const double t = num / den;
  return {t >= 0 ? Relation::hit : Relation::behind, t};
}

std::string_view to_string(Relation relation) noexcept {
  switch (relation) {
    case Relation::hit: return "hit";
    case Relation::behind: return "behind";
    case Relation::parallel: return "parallel";
    case Relation::in_plane: return "in-plane";
  }
  return "?";
}

std::string_view to_string(Stage stage) noexcept {
  switch (stage) {
    case Stage::filter: return "filter";
    case Stage::compensated: return "compensated";
    case Stage::expansion: return "expansion";
    case Stage::exact: return "exact";
  }
  return "?";
}

std::string_view version() noexcept { return RAYKERNEL_VERSION; }

}  // namespace raykernel

namespace raykernel::detail {

// a·a − c as the kernel's compiler flags evaluate it. With -ffp-contract=off it is RN(RN(a·a) − c); a
// build that contracts it into one FMA returns the exact a·a − c instead. tests/fp_environment_test.cpp
// calls it with a = 1 + 2^-30, c = 1 + 2^-29, where the two differ (0 versus 2^-60).
double contraction_probe(double a, double c) noexcept { return a * a - c; }

}  // namespace raykernel::detail

// The triangle reference check (triangle_reference_check.hpp).
#include <raykernel/testkit/triangle_reference_check.hpp>

#include <raykernel/testkit/plane_reference_check.hpp>

#include "default_environment.hpp"

#include <cmath>
#include <ostream>
#include <sstream>

namespace raykernel::testkit {
namespace {

std::string value_text(double x) { return std::isnan(x) ? "nan" : hex_string(x) + " (" + shortest_decimal(x) + ")"; }

std::string answer_text(const TriangleIntersection& x) {
  std::string s = std::string(to_string(x.relation));
  s.resize(11, ' ');
  std::string l = std::string(to_string(x.location));
  l.resize(10, ' ');
  s += l + (x.owned ? "owned  " : "       ");
  s += "t = " + value_text(x.t) + "   u = (" + value_text(x.barycentric[0]) + ", " + value_text(x.barycentric[1]) +
       ", " + value_text(x.barycentric[2]) + ")";
  return s;
}

}  // namespace

std::string to_string(const TriangleQuery& q) {
  auto v = [](const char* name, const Vec3& a) {
    return std::string(name) + " = (" + hex_string(a.x) + ", " + hex_string(a.y) + ", " + hex_string(a.z) + ")";
  };
  return v("o", q.ray.origin) + "  " + v("d", q.ray.direction) + "  " + v("a", q.triangle.a) + "  " +
         v("b", q.triangle.b) + "  " + v("c", q.triangle.c);
}

TriangleReferenceCheck check_against_reference(const TriangleQuery& query, const TriangleIntersection& got,
                                               TriangleRule rule, std::uint64_t max_ulps, bool check_location) {
  const internal::DefaultEnvironmentScope environment;
  TriangleReferenceCheck c;
  c.query = query;
  c.rule = rule;
  c.exact = intersect_exact_rational(query.ray, query.triangle, rule);  // throws invalid_input
  c.expected = c.exact.intersection;
  c.got = got;
  c.max_ulps = max_ulps;
  c.check_location = check_location;
  c.relation_matches = got.relation == c.expected.relation;
  if (check_location) {
    c.location_matches = got.location == c.expected.location;
    c.owned_matches = got.owned == c.expected.owned;
  }
  if (c.expected.location != TriangleLocation::none) {
    const double want[4] = {c.expected.t, c.expected.barycentric[0], c.expected.barycentric[1],
                            c.expected.barycentric[2]};
    const double have[4] = {got.t, got.barycentric[0], got.barycentric[1], got.barycentric[2]};
    for (int k = 0; k < 4; ++k)
      if (!std::isnan(have[k])) c.ulps[static_cast<std::size_t>(k)] = ulp_distance(want[k], have[k]);
  }
  return c;
}

std::string TriangleReferenceCheck::report() const {
  const internal::DefaultEnvironmentScope environment;
  std::ostringstream os;
  os << "raykernel triangle reference check " << (passed() ? "passed" : "FAILED");
  if (!passed()) {
    os << ":";
    if (!relation_matches)
      os << " relation is " << to_string(got.relation) << ", expected " << to_string(expected.relation) << " ("
         << to_string(rule) << " rule);";
    if (!location_matches)
      os << " location is " << to_string(got.location) << ", expected " << to_string(expected.location) << ";";
    if (!owned_matches) os << " owned flag is " << got.owned << ", expected " << expected.owned << ";";
    const char* names[4] = {"t", "ua", "ub", "uc"};
    for (std::size_t k = 0; k < 4; ++k)
      if (ulps[k] && *ulps[k] > max_ulps) os << " " << names[k] << " is " << *ulps[k] << " ulps off;";
  }
  os << '\n';
  os << "  query     " << to_string(query) << '\n';
  os << "  replay    echo '" << triangle_line(query) << "' | raykernel triangle --rule=" << to_string(rule)
     << " --exact --hex\n";
  os << "  expected  " << answer_text(expected) << '\n';
  os << "  got       " << answer_text(got) << '\n';
  os << "  exact     ";
  if (exact.t && exact.barycentric)
    os << "t = " << exact.t->str() << ", u = (" << (*exact.barycentric)[0].str() << ", " << (*exact.barycentric)[1].str()
       << ", " << (*exact.barycentric)[2].str() << "), ";
  os << "den = " << exact.den.str() << ", num = " << exact.num.str() << '\n';
  os << "  errors    ";
  const char* names[4] = {"t", "ua", "ub", "uc"};
  for (std::size_t k = 0; k < 4; ++k)
    os << names[k] << " " << (ulps[k] ? std::to_string(*ulps[k]) : std::string("-")) << (k < 3 ? ", " : "");
  os << " ulps (tolerance " << max_ulps << ")\n";
  return os.str();
}

std::ostream& operator<<(std::ostream& os, const TriangleReferenceCheck& check) { return os << check.report(); }

}  // namespace raykernel::testkit

// Example (c): raykernel as a library — intersect, intersect_exact, the exact t as a rational, the stage
// that decided, and invalid input.
#include <raykernel/raykernel.hpp>

#include <cstdio>
#include <string>

namespace {

void show(const char* what, const raykernel::Intersection& x) {
  std::printf("%-28s %-8s t = %a (%.17g)\n", what, std::string(raykernel::to_string(x.relation)).c_str(), x.t, x.t);
}

}  // namespace

int main() {
  using namespace raykernel;
  std::printf("raykernel %s\n", std::string(version()).c_str());

  // t = 1/10: RN(1/10) = 0x1.999999999999ap-4, bit for bit on every path that is exact.
  const Ray ray{{0, 0, 0}, {10, 0, 0}};
  const Plane plane{{1, 0, 0}, {1, 0, 0}};
  show("intersect", intersect(ray, plane));
  show("intersect_exact", intersect_exact(ray, plane));
  const ExactIntersection x = intersect_exact_rational(ray, plane);
  std::printf("%-28s t = %s, num = %s, den = %s\n", "intersect_exact_rational", x.t->str().c_str(), x.num.str().c_str(),
              x.den.str().c_str());

  // Tiny but exact: d·n = (p − o)·n = 2^-1200, both underflow to 0 in doubles.
  const Ray tiny_ray{{0, 0, 0}, {0x1p-600, 0, 0}};
  const Plane tiny_plane{{0x1p-600, 0, 0}, {0x1p-600, 0, 0}};
  const TracedIntersection traced = intersect_traced(tiny_ray, tiny_plane);
  show("underflow: intersect", traced.intersection);
  std::printf("%-28s relation by %s, t by %s\n", "  decided by", std::string(to_string(traced.relation_stage)).c_str(),
              std::string(to_string(traced.t_stage)).c_str());
  show("underflow: intersect_naive", intersect_naive(tiny_ray, tiny_plane));

  // Invalid input is rejected, never classified.
  try {
    (void)intersect(Ray{{0, 0, 0}, {0, 0, 0}}, plane);
    std::printf("zero direction: not rejected\n");
    return 1;
  } catch (const invalid_input& e) {
    std::printf("%-28s invalid_input: %s\n", "zero direction", e.what());
  }
  return 0;
}

#include "cgal_triangle_baselines.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <limits>

namespace raykernel::bench {
namespace {

template <class K>
typename K::Ray_3 to_ray(const testkit::TriangleQuery& q) {
  const Vec3 &o = q.ray.origin, &d = q.ray.direction;
  return typename K::Ray_3(typename K::Point_3(o.x, o.y, o.z), typename K::Vector_3(d.x, d.y, d.z));
}
template <class K>
typename K::Triangle_3 to_triangle(const testkit::TriangleQuery& q) {
  auto p = [](const Vec3& v) { return typename K::Point_3(v.x, v.y, v.z); };
  return typename K::Triangle_3(p(q.triangle.a), p(q.triangle.b), p(q.triangle.c));
}

}  // namespace

struct EpickTriangles::Impl {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Ray_3> rays;
  std::vector<K::Triangle_3> triangles;
};
EpickTriangles::EpickTriangles(const std::vector<testkit::TriangleQuery>& queries) : impl_(std::make_unique<Impl>()) {
  for (const auto& q : queries) {
    impl_->rays.push_back(to_ray<Impl::K>(q));
    impl_->triangles.push_back(to_triangle<Impl::K>(q));
  }
}
EpickTriangles::~EpickTriangles() = default;
std::size_t EpickTriangles::size() const { return impl_->rays.size(); }
bool EpickTriangles::do_intersect(std::size_t i) const {
  // CGAL's precondition: a non-degenerate triangle (the workloads' degenerate kinds are skipped by the caller).
  return CGAL::do_intersect(impl_->rays[i], impl_->triangles[i]);
}

struct EpeckTriangles::Impl {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  std::vector<K::Ray_3> rays;
  std::vector<K::Triangle_3> triangles;
};
EpeckTriangles::EpeckTriangles(const std::vector<testkit::TriangleQuery>& queries) : impl_(std::make_unique<Impl>()) {
  for (const auto& q : queries) {
    impl_->rays.push_back(to_ray<Impl::K>(q));
    impl_->triangles.push_back(to_triangle<Impl::K>(q));
  }
}
EpeckTriangles::~EpeckTriangles() = default;
std::size_t EpeckTriangles::size() const { return impl_->rays.size(); }
double EpeckTriangles::intersection_t(std::size_t i) const {
  using K = Impl::K;
  const K::Ray_3& ray = impl_->rays[i];
  const auto result = CGAL::intersection(ray, impl_->triangles[i]);
  if (!result) return std::numeric_limits<double>::quiet_NaN();
  if (const K::Point_3* x = boost::get<K::Point_3>(&*result)) {
    const K::Vector_3 d = ray.to_vector();
    return CGAL::to_double(((*x - ray.source()) * d) / (d * d));
  }
  return 0.0;  // a segment: the ray in the triangle's plane
}

}  // namespace raykernel::bench

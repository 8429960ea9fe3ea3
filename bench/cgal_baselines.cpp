#include "cgal_baselines.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <limits>

namespace raykernel::bench {

template <class K>
static typename K::Ray_3 to_ray(const testkit::Query& q) {
  const Vec3 &o = q.ray.origin, &d = q.ray.direction;
  return typename K::Ray_3(typename K::Point_3(o.x, o.y, o.z), typename K::Vector_3(d.x, d.y, d.z));
}
template <class K>
static typename K::Plane_3 to_plane(const testkit::Query& q) {
  const Vec3 &p = q.plane.point, &n = q.plane.normal;
  return typename K::Plane_3(typename K::Point_3(p.x, p.y, p.z), typename K::Vector_3(n.x, n.y, n.z));
}

struct EpickQueries::Impl {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Ray_3> rays;
  std::vector<K::Plane_3> planes;
};
EpickQueries::EpickQueries(const std::vector<testkit::Query>& queries) : impl_(std::make_unique<Impl>()) {
  impl_->rays.reserve(queries.size());
  impl_->planes.reserve(queries.size());
  for (const auto& q : queries) {
    impl_->rays.push_back(to_ray<Impl::K>(q));
    impl_->planes.push_back(to_plane<Impl::K>(q));
  }
}
EpickQueries::~EpickQueries() = default;
std::size_t EpickQueries::size() const { return impl_->rays.size(); }
bool EpickQueries::do_intersect(std::size_t i) const { return CGAL::do_intersect(impl_->rays[i], impl_->planes[i]); }

struct EpeckQueries::Impl {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  std::vector<K::Ray_3> rays;
  std::vector<K::Plane_3> planes;
};
EpeckQueries::EpeckQueries(const std::vector<testkit::Query>& queries) : impl_(std::make_unique<Impl>()) {
  for (const auto& q : queries) {
    impl_->rays.push_back(to_ray<Impl::K>(q));
    impl_->planes.push_back(to_plane<Impl::K>(q));
  }
}
EpeckQueries::~EpeckQueries() = default;
std::size_t EpeckQueries::size() const { return impl_->rays.size(); }
double EpeckQueries::intersection_t(std::size_t i) const {
  using K = Impl::K;
  const K::Ray_3& ray = impl_->rays[i];
  const auto result = CGAL::intersection(ray, impl_->planes[i]);
  if (!result) return std::numeric_limits<double>::quiet_NaN();
  if (const K::Point_3* x = boost::get<K::Point_3>(&*result)) {
    const K::Vector_3 d = ray.to_vector();
    return CGAL::to_double(((*x - ray.source()) * d) / (d * d));
  }
  return 0.0;  // the ray lies in the plane
}

}  // namespace raykernel::bench

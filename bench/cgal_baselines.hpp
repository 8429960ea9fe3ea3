// CGAL's own ray–plane code, as baselines: `Epick` (filtered predicates on doubles) and `Epeck` (lazy exact
// constructions). The CGAL objects are built before timing; building them is not counted against CGAL.
//
// Note on Epick: Plane_3(p, n) stores a, b, c, d with d = −n·p computed in doubles (rounded), and
// Ray_3(o, d) stores o and o + d (rounded): Epick's answer is exact for those rounded objects, not for the
// query's doubles. Epeck computes both exactly.
#pragma once

#include <raykernel/testkit/plane_queries.hpp>

#include <cstddef>
#include <memory>
#include <vector>

namespace raykernel::bench {

class EpickQueries {
 public:
  explicit EpickQueries(const std::vector<testkit::Query>& queries);
  ~EpickQueries();
  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] bool do_intersect(std::size_t i) const;  // CGAL::do_intersect(Ray_3, Plane_3)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class EpeckQueries {
 public:
  explicit EpeckQueries(const std::vector<testkit::Query>& queries);
  ~EpeckQueries();
  [[nodiscard]] std::size_t size() const;
  // CGAL::intersection(Ray_3, Plane_3); t = (x − o)·d / (d·d) from the point x, converted with to_double.
  [[nodiscard]] double intersection_t(std::size_t i) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raykernel::bench

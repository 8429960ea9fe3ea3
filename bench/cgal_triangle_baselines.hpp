// CGAL's ray–triangle code as baselines: Epick's do_intersect(Ray_3, Triangle_3) (filtered predicates on
// doubles: the yes/no answer, the like-for-like baseline of raykernel's relation-only form) and Epeck's
// intersection(Ray_3, Triangle_3) (lazy exact constructions, t recovered from the point). The CGAL objects
// are built before timing.
//
// Like-for-like notes: Epick's Ray_3(o, d) stores o and o + d rounded, so its answer is exact for that rounded
// ray, not for the query's doubles; do_intersect counts the boundary (the closed rule, a shared edge twice).
// Epeck is exact; its to_double of t is an interval midpoint, not correctly rounded.
#pragma once

#include <raykernel/testkit/triangle_queries.hpp>

#include <cstddef>
#include <memory>
#include <vector>

namespace raykernel::bench {

class EpickTriangles {
 public:
  explicit EpickTriangles(const std::vector<testkit::TriangleQuery>& queries);
  ~EpickTriangles();
  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] bool do_intersect(std::size_t i) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class EpeckTriangles {
 public:
  explicit EpeckTriangles(const std::vector<testkit::TriangleQuery>& queries);
  ~EpeckTriangles();
  [[nodiscard]] std::size_t size() const;
  // CGAL::intersection(Ray_3, Triangle_3); t = (x − o)·d/(d·d) from the point x, converted with to_double.
  [[nodiscard]] double intersection_t(std::size_t i) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raykernel::bench

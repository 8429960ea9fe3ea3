# closest: the exact closest point of a mesh to a point (docs/contract.md §11): the formula over any number type,
# the BVH search with an interval filter, the exact stage (GMP rationals, the distance's square root by MPFR), the
# reference and the binary64 baseline.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/closest_point.cpp)

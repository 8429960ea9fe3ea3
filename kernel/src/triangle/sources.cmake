# triangle: ray–triangle (docs/contract.md §6): the formula, the stages, the cascade, the exact stage (GMP
# rationals and MPFR, no CGAL) and the entry points.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/ray_triangle_cascade.cpp ${CMAKE_CURRENT_LIST_DIR}/triangle_api.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/exact_triangle.cpp)

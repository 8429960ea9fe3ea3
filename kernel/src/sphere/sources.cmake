# sphere: ray–sphere (docs/contract.md §10): the formula, the expansion stage, the cascade, the exact stage (GMP
# rationals and MPFR, no CGAL) and the entry points. Not yet registered with the nearest-hit module and the BVH.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/ray_sphere_cascade.cpp ${CMAKE_CURRENT_LIST_DIR}/sphere_api.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/exact_sphere.cpp)

# sphere: ray–sphere (docs/contract.md §10): the formula, the expansion stage, the cascade, the exact stage (GMP
# rationals and MPFR, no CGAL), the entry points (SphereSet and its BVH) and the spawn from a sphere.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/ray_sphere_cascade.cpp ${CMAKE_CURRENT_LIST_DIR}/sphere_api.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/exact_sphere.cpp ${CMAKE_CURRENT_LIST_DIR}/sphere_spawn.cpp)

# core: the shared arithmetic of every certified stage (EFTs, lanes, signs, enclosures, expansions, the
# dot3/det3 stages, quotient rounding, the error bounds), the floating-point environment, validation, threads.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/validation.cpp ${CMAKE_CURRENT_LIST_DIR}/fp_environment.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/parallel.cpp ${CMAKE_CURRENT_LIST_DIR}/large_vector.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/round_affine.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/root_rounding.cpp)

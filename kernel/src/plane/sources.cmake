# plane: ray–plane (docs/contract.md §1): the formula, the stages, the cascade, the exact stage, the entry
# points and the batch API.
#
# The exact stage is the only code that sees CGAL: a separate object library keeps CGAL's compile flags
# (-frounding-math) and its compile time out of the other translation units.
find_package(CGAL REQUIRED)
add_library(raykernel_exact OBJECT ${CMAKE_CURRENT_LIST_DIR}/exact_plane.cpp)
target_include_directories(raykernel_exact PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/include ${CMAKE_CURRENT_SOURCE_DIR}/src)
target_link_libraries(raykernel_exact PRIVATE CGAL::CGAL raykernel_dep::gmpxx raykernel_dep::mpfr
                                              $<BUILD_INTERFACE:raykernel_warnings>)
target_compile_options(raykernel_exact PRIVATE ${RAYKERNEL_FP_FLAGS})
set_target_properties(raykernel_exact PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_sources(raykernel PRIVATE $<TARGET_OBJECTS:raykernel_exact>
                                 ${CMAKE_CURRENT_LIST_DIR}/plane_api.cpp ${CMAKE_CURRENT_LIST_DIR}/ray_plane_cascade.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/exact_plane_compare.cpp ${CMAKE_CURRENT_LIST_DIR}/batch.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/fast_loop_portable.cpp)
# The batch API's fast loop, once per instruction set (fast_loop.hpp): the widest the CPU supports is chosen
# at run time.
if(RAYKERNEL_ISA_VARIANTS)
  target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/fast_loop_avx2.cpp ${CMAKE_CURRENT_LIST_DIR}/fast_loop_avx512.cpp)
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/fast_loop_avx2.cpp PROPERTIES COMPILE_OPTIONS "-march=x86-64-v3")
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/fast_loop_avx512.cpp PROPERTIES COMPILE_OPTIONS "-march=x86-64-v4")
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/batch.cpp PROPERTIES COMPILE_DEFINITIONS
                              "RAYKERNEL_BATCH_AVX2;RAYKERNEL_BATCH_AVX512")
endif()

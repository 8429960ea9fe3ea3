# nearest: the nearest hit over primitives (the exact comparison of two t values, the screen, the module).
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/nearest_hit.cpp ${CMAKE_CURRENT_LIST_DIR}/nearest_screen_portable.cpp)
# nearest_hit's screen (nearest_screen.hpp), once per instruction set: AVX2, or portable.
if(RAYKERNEL_ISA_VARIANTS)
  target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/nearest_screen_avx2.cpp)
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/nearest_screen_avx2.cpp PROPERTIES COMPILE_OPTIONS "-march=x86-64-v3")
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/nearest_hit.cpp PROPERTIES COMPILE_DEFINITIONS RAYKERNEL_NEAREST_AVX2)
endif()

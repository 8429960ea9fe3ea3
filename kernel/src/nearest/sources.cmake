# nearest: the nearest hit over every kind of surface — the module (candidates, search, the certified comparison of
# two t values, the exact stage across kinds), the screen, the entry points for plane sets and scenes.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/nearest_hit.cpp ${CMAKE_CURRENT_LIST_DIR}/exact_nearest.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/nearest_stages.cpp ${CMAKE_CURRENT_LIST_DIR}/interval_bound.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/nearest_screen_portable.cpp)
# nearest_hit's screen (nearest_screen.hpp), once per instruction set: AVX2, or portable.
if(RAYKERNEL_ISA_VARIANTS)
  target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/nearest_screen_avx2.cpp)
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/nearest_screen_avx2.cpp PROPERTIES COMPILE_OPTIONS "-march=x86-64-v3")
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/nearest_hit.cpp PROPERTIES COMPILE_DEFINITIONS RAYKERNEL_NEAREST_AVX2)
endif()

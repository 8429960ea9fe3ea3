# GMP (with its C++ interface gmpxx) and MPFR, as imported targets raykernel_dep::gmp, ::gmpxx, ::mpfr.
# Debian ships no CMake config for them; the headers and libraries are found directly.
include_guard(GLOBAL)

foreach(lib gmp gmpxx mpfr)
  if(NOT TARGET raykernel_dep::${lib})
    string(TOUPPER ${lib} LIB)
    find_library(RAYKERNEL_${LIB}_LIBRARY NAMES ${lib} REQUIRED)
    find_path(RAYKERNEL_${LIB}_INCLUDE_DIR NAMES ${lib}.h REQUIRED)
    add_library(raykernel_dep::${lib} UNKNOWN IMPORTED)
    set_target_properties(raykernel_dep::${lib} PROPERTIES
      IMPORTED_LOCATION "${RAYKERNEL_${LIB}_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${RAYKERNEL_${LIB}_INCLUDE_DIR}")
  endif()
endforeach()
set_property(TARGET raykernel_dep::gmpxx APPEND PROPERTY INTERFACE_LINK_LIBRARIES raykernel_dep::gmp)
set_property(TARGET raykernel_dep::mpfr APPEND PROPERTY INTERFACE_LINK_LIBRARIES raykernel_dep::gmp)

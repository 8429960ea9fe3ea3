# GMP (with its C++ interface gmpxx) and MPFR, as imported targets raykernel_dep::gmp, ::gmpxx, ::mpfr.
# Debian ships no CMake config for them; the headers and libraries are found directly.
# Imported targets are visible in the directory that creates them and below; the installed package's config
# includes this file from every directory that calls find_package(raykernel), hence a per-directory guard.
include_guard(DIRECTORY)

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

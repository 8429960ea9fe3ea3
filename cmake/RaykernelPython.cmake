# The Python module's toolchain: the interpreter (with its headers) and pybind11, found quietly so that the
# top-level option RAYKERNEL_BUILD_PYTHON can default to ON exactly when they are there.
#
# The interpreter: -DPython3_EXECUTABLE=... when given (setup.py passes the one running pip). Otherwise, on
# Debian, /usr/bin/python3: Debian's python3-numpy, python3-pytest, python3-hypothesis and pybind11 belong
# to it, and a python3 found earlier on PATH (pyenv, conda) would not see them.
# Sets RAYKERNEL_PYTHON_AVAILABLE.
include_guard(GLOBAL)

if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python interpreter the raykernel module is built for")
endif()
# Python3 first: pybind11's config then uses FindPython3's results (its "new" mode).
find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
if(Python3_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)
endif()
if(Python3_FOUND AND pybind11_FOUND)
  set(RAYKERNEL_PYTHON_AVAILABLE ON)
else()
  set(RAYKERNEL_PYTHON_AVAILABLE OFF)
endif()

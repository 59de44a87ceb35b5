# A fresh configure of the project, tests and benchmarks included, prints no
# CMake warning: a newcomer's first `make` should not show one (OpenEXR's
# package used to bring Imath's, which warned about a Python library that
# Debian ships elsewhere; see cmake/FindOpenEXRCore.cmake).
# Variables: SOURCE_DIR WORK_DIR GENERATOR C_COMPILER
cmake_minimum_required(VERSION 3.18)
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}" -G "${GENERATOR}"
    "-DCMAKE_C_COMPILER=${C_COMPILER}" -DHITRAY_BUILD_TESTS=ON -DHITRAY_BUILD_BENCH=ON
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(REMOVE_RECURSE "${WORK_DIR}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring failed (${rc}):\n${out}\n${err}")
endif()
# CMake's warnings go to standard error, and so does nothing else of a
# configure that succeeds; status lines that say a file is missing are the
# form the Imath warning took.
if(NOT err STREQUAL "" OR out MATCHES "but this file does not exist")
  message(FATAL_ERROR "configuring printed warnings:\n${err}\n${out}")
endif()
message(STATUS "configured with no warning")

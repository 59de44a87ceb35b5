# CMake toolchain for the manylinux wheels: zig's clang targeting
# x86_64 Linux with glibc 2.17 (manylinux2014), through the wrappers that
# build_deps.sh writes into HITRAY_ZIG_BIN (zig cc, zig c++, zig ar, zig
# ranlib, each with the target). Everything the wheels hold is compiled by
# it: the bundled libraries and hitray itself. No CMAKE_SYSTEM_NAME: the
# machine is the target (x86_64 Linux), only the glibc is older, so CMake
# and FindPython work as for a native build.
if(NOT DEFINED ENV{HITRAY_ZIG_BIN})
  message(FATAL_ERROR "zig-toolchain.cmake: set HITRAY_ZIG_BIN to the wrappers' folder (scripts/wheels/build_deps.sh)")
endif()
set(CMAKE_C_COMPILER "$ENV{HITRAY_ZIG_BIN}/clang")
set(CMAKE_CXX_COMPILER "$ENV{HITRAY_ZIG_BIN}/clang++")
set(CMAKE_AR "$ENV{HITRAY_ZIG_BIN}/ar" CACHE FILEPATH "")
set(CMAKE_RANLIB "$ENV{HITRAY_ZIG_BIN}/ranlib" CACHE FILEPATH "")

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
# zig cc keeps the frame pointer at every optimisation level
# (-mframe-pointer=all), which takes a register from the hot loops that
# GCC's -O2 and -O3 give them; the wheels omit it as the gcc build does.
# A compile option (not CMAKE_C_FLAGS_INIT) so a kept build tree gets it too.
add_compile_options(-fomit-frame-pointer)

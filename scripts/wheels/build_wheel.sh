#!/bin/sh
# One wheel of hitray for one Python, compiled with zig's clang for glibc
# 2.17 against the libraries build_deps.sh built into DEPS/prefix, then
# made a manylinux_2_17 wheel by auditwheel (which copies those libraries
# into hitray.libs/):
#   build_wheel.sh PYTHON SOURCE DEPS WORK OUT AUDITWHEEL
# PYTHON: the interpreter the wheel is for; SOURCE: an sdist or the tree;
# WORK: this Python's CMake build tree (kept, so a rerun compiles only what
# changed); OUT: where the repaired wheel goes; AUDITWHEEL: the program.
set -eu
python=$1 source=$2 deps=$(cd "$3" && pwd) work=$4 out=$5 auditwheel=$6
here=$(cd "$(dirname "$0")" && pwd)
prefix="$deps/prefix"
mkdir -p "$work" "$out"
work=$(cd "$work" && pwd)
export HITRAY_ZIG_BIN="$deps/zig"
export ZIG_GLOBAL_CACHE_DIR="$deps/zig-cache" ZIG_LOCAL_CACHE_DIR="$deps/zig-cache"
# Only the built libraries, never the machine's: pkg-config looks in the
# prefix alone, CMake there first, and each library is named outright.
export PKG_CONFIG_LIBDIR="$prefix/lib/pkgconfig" PKG_CONFIG_PATH=""
export CMAKE_PREFIX_PATH="$prefix"
# pip from a venv of this Python, brought up to date once: an older pip
# (3.10's) takes no -C (--config-settings).
if [ ! -x "$work/venv/bin/python" ]; then
    "$python" -m venv "$work/venv"
    "$work/venv/bin/python" -m pip install -q --disable-pip-version-check --upgrade pip
fi
rm -rf "$work/raw"
# pip unpacks an sdist into a new folder each time, which a CMake tree
# made for another source folder refuses: an sdist's build starts afresh.
[ -d "$source" ] || rm -rf "$work/cmake"
"$work/venv/bin/python" -m pip wheel -q --no-deps --disable-pip-version-check -w "$work/raw" \
    -C build-dir="$work/cmake" \
    -C cmake.define.CMAKE_TOOLCHAIN_FILE="$here/zig-toolchain.cmake" \
    -C cmake.define.ZLIB_ROOT="$prefix" -C cmake.define.ZLIB_LIBRARY="$prefix/lib/libz.a" \
    -C cmake.define.PNG_PNG_INCLUDE_DIR="$prefix/include" \
    -C cmake.define.PNG_LIBRARY="$prefix/lib/libpng16.so" \
    -C cmake.define.OpenEXRCore_INCLUDE_DIR="$prefix/include/OpenEXR" \
    -C cmake.define.OpenEXRCore_LIBRARY="$prefix/lib/libOpenEXRCore-3_1.so" \
    -C cmake.define.HITRAY_FAST_FLOAT_INCLUDE="$prefix/include" \
    "$source"
PATH="$(dirname "$auditwheel"):$PATH" LD_LIBRARY_PATH="$prefix/lib" "$auditwheel" repair --plat manylinux_2_17_x86_64 -w "$out" "$work"/raw/*.whl

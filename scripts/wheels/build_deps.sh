#!/bin/sh
# Build the libraries the manylinux wheels bundle (zlib, libpng, OpenEXRCore,
# stb) and set out fast_float's headers, all from the sources
# fetch_sources.sh unpacked into DIR/src, with zig's clang for glibc 2.17,
# into DIR/prefix (lib/, include/, lib/pkgconfig/). Each library is built
# once: a rerun with DIR/prefix/.built-NAME present skips it.
#   build_deps.sh DIR ZIG     ZIG: the zig program (PyPI's ziglang package)
# Writes DIR/zig/{clang,clang++,ar,ranlib}: zig with the target, for CMake
# (zig-toolchain.cmake) and make alike (named for the compiler zig runs, so
# zlib's configure knows it for one like gcc).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
dir=$(cd "$1" && pwd)
zig=$2
jobs=${JOBS:-2}
target=x86_64-linux-gnu.2.17
prefix="$dir/prefix"
bin="$dir/zig"
mkdir -p "$bin" "$prefix/lib/pkgconfig" "$prefix/include" "$dir/work"

for tool in clang clang++ ar ranlib; do
    case $tool in
        clang) args="cc -target $target" ;;
        clang++) args="c++ -target $target" ;;
        *) args=$tool ;;
    esac
    printf '#!/bin/sh\nexec "%s" %s "$@"\n' "$zig" "$args" >"$bin/$tool.new"
    chmod +x "$bin/$tool.new"
    mv "$bin/$tool.new" "$bin/$tool"
done
export HITRAY_ZIG_BIN="$bin"
# zig caches what it builds for the target (its glibc stubs, libc++) here.
export ZIG_GLOBAL_CACHE_DIR="$dir/zig-cache" ZIG_LOCAL_CACHE_DIR="$dir/zig-cache"

cmake_build() { # NAME SOURCE [CMAKE OPTIONS...]
    name=$1 tree=$2
    shift 2
    rm -rf "$dir/work/$name"
    cmake -S "$tree" -B "$dir/work/$name" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$here/zig-toolchain.cmake" \
        -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" -DCMAKE_INSTALL_LIBDIR=lib \
        -DCMAKE_PREFIX_PATH="$prefix" -DZLIB_ROOT="$prefix" -DZLIB_LIBRARY="$prefix/lib/libz.a" "$@" >"$dir/work/$name.log" 2>&1
    cmake --build "$dir/work/$name" -j "$jobs" >>"$dir/work/$name.log" 2>&1
    cmake --install "$dir/work/$name" >>"$dir/work/$name.log" 2>&1
}

step() { # NAME COMMAND...: run once, logged
    name=$1
    shift
    [ -f "$prefix/.built-$name" ] && return
    echo "build_deps: $name"
    "$@" || { echo "build_deps: $name failed (logs: $dir/work/$name.log)" >&2; exit 1; }
    touch "$prefix/.built-$name"
}

src="$dir/src"
zlib() {
    # zlib's own configure script, as Debian builds it (its CMakeLists.txt
    # wants win32/, which Debian's tarball leaves out), in a copy of the
    # tree; static only, position independent and with its symbols hidden,
    # so each library that links it keeps its own copy inside: libpng
    # calls inflateValidate (ZLIB_1.2.9), newer than the zlib that the
    # manylinux2014 policy lets a wheel take from the system, and auditwheel
    # copies no library that its policy counts as the system's.
    rm -rf "$dir/work/zlib" && cp -r "$src/zlib" "$dir/work/zlib"
    (cd "$dir/work/zlib" && CC="$bin/clang" AR="$bin/ar" RANLIB="$bin/ranlib" CFLAGS="-O2 -fPIC -fvisibility=hidden" \
        ./configure --static --prefix="$prefix" --libdir="$prefix/lib" && make -j "$jobs" && make install) \
        >"$dir/work/zlib.log" 2>&1
}
step zlib zlib
step libpng cmake_build libpng "$src/libpng1.6" -DPNG_STATIC=OFF -DPNG_TESTS=OFF -DPNG_EXECUTABLES=OFF \
    -DSKIP_INSTALL_PROGRAMS=ON
step openexrcore cmake_build openexrcore "$here/openexrcore" -DOPENEXR_SOURCE="$src/openexr" \
    -DIMATH_SOURCE="$src/imath"

stb() {
    # Debian's own Makefile (debian/patches: the shared library libstb.so.0
    # and stb.pc), in a copy of the tree, with the zig compiler, told to
    # compile stb_image and stb_image_write alone, all hitray uses (others
    # of stb's files are errors to clang, which gcc lets by as warnings).
    rm -rf "$dir/work/stb" && cp -r "$src/libstb" "$dir/work/stb"
    make -C "$dir/work/stb" -j "$jobs" CC="$bin/clang" AR="$bin/ar" CFLAGS="-O2 -fPIC -fwrapv" MULTIARCH= \
        HEADERS_TO_BE_PRECOMPILED="stb_image.h stb_image_write.h" SRCS="stb_image.c stb_image_write.c" \
        PREFIX="$prefix" LIBDIR=lib install-shared install-header >"$dir/work/stb.log" 2>&1
}
step stb stb

fast_float() {
    rm -rf "$prefix/include/fast_float"
    cp -r "$src/libfast-float-dev/usr/include/fast_float" "$prefix/include/"
}
step fast_float fast_float

#!/bin/sh
# The zig-built hitray of a wheel against the gcc Release build, on the
# benchmark scenes: median render time and CPU time of the process
# (800x600, 4 spp, 1 thread, rounds interleaved, so a machine whose speed
# drifts shifts both builds alike),
# callgrind's instruction count of a smaller render (the same on a busy
# machine), and whether the two builds write the same PFM, bit for bit, for
# every benchmark scene and every scene of scenes/.
#   scripts/wheels/compare_speed.sh [ROUNDS]          (default 5)
# GCC_BUILD: the gcc tree (default build-gccrel:
#   cmake -B build-gccrel -DCMAKE_BUILD_TYPE=Release && cmake --build build-gccrel);
# ZIG_BUILD: a wheel's CMake tree (default build-wheels/cp311/cmake:
#   make wheels WHEEL_PYTHONS=3.11). SCENES: the timed ones (default
#   spheres torus_csg sphere_grid demo); CALLGRIND=0 skips the counts.
set -eu
cd "$(dirname "$0")/../.."
rounds=${1:-5}
gcc_bin=${GCC_BUILD:-build-gccrel}/bin/hitray
zig_bin=${ZIG_BUILD:-build-wheels/cp311/cmake}/bin/hitray
scenes=${SCENES:-spheres torus_csg sphere_grid demo}
for b in "$gcc_bin" "$zig_bin"; do
    [ -x "$b" ] || { echo "compare_speed: no $b (see the usage above)" >&2; exit 1; }
done
# The zig tree links the libraries that build_deps.sh built, not the machine's.
zig_libs=$(pwd)/$(dirname "$zig_bin")/../../../deps/prefix/lib
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() { # gcc|zig args...
    which=$1
    shift
    if [ "$which" = zig ]; then
        LD_LIBRARY_PATH="$zig_libs" /usr/bin/time -f "cpu %U %S" "$zig_bin" "$@"
    else
        /usr/bin/time -f "cpu %U %S" "$gcc_bin" "$@"
    fi
}
scene_file() {
    if [ -f "bench/scenes/$1.sdl" ]; then echo "bench/scenes/$1.sdl"; else echo "scenes/$1.sdl"; fi
}

round=0
while [ "$round" -lt "$rounds" ]; do
    for s in $scenes; do
        for which in gcc zig; do
            run $which render "$(scene_file "$s")" -o "$tmp/t.png" --size 800x600 --spp 4 \
                --threads 1 -q --stats-json "$tmp/s.json" 2> "$tmp/time"
            tr -d '{}" ' < "$tmp/s.json" | tr ',' '\n' | awk -F: '$1 ~ /seconds/ {print $2}' \
                >> "$tmp/$s.$which"
            # CPU seconds of the whole process (user + system): less moved
            # than the wall time where other jobs share the cores.
            awk '/^cpu / {print $2 + $3}' "$tmp/time" >> "$tmp/$s.$which.cpu"
        done
    done
    round=$((round + 1))
done
median() { sort -n "$1" | awk -v n="$rounds" 'NR == int((n + 1) / 2) {print $1}'; }
# Valgrind 3.19 stops on an instruction of GCC's AVX2 walk (the VEX form of
# movq between two registers): such a count comes out as n/a.
instructions() { # gcc|zig scene
    if LD_LIBRARY_PATH="$zig_libs" valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" -q \
        "$([ "$1" = zig ] && echo "$zig_bin" || echo "$gcc_bin")" render "$(scene_file "$2")" \
        -o "$tmp/c.png" --size 200x150 --spp 4 --threads 1 -q >/dev/null 2>&1; then
        callgrind_annotate "$tmp/cg" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}'
    else
        echo n/a
    fi
}

echo "| scene | gcc (s) | zig (s) | zig/gcc time | zig/gcc CPU time | gcc instructions | zig instructions | zig/gcc instructions |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for s in $scenes; do
    g=$(median "$tmp/$s.gcc") z=$(median "$tmp/$s.zig")
    gc=$(median "$tmp/$s.gcc.cpu") zc=$(median "$tmp/$s.zig.cpu")
    if [ "${CALLGRIND:-1}" = 1 ]; then
        gi=$(instructions gcc "$s") zi=$(instructions zig "$s")
        ir=$([ "$gi" = n/a ] || [ "$zi" = n/a ] && echo - || echo "scale=3; $zi / $gi" | bc)
    else
        gi=- zi=- ir=-
    fi
    printf '| %s | %.3f | %.3f | %.3f | %.3f | %s | %s | %s |\n' "$s" "$g" "$z" "$(echo "scale=4; $z / $g" | bc)" \
        "$(echo "scale=4; $zc / $gc" | bc)" "$gi" "$zi" "$ir"
done
echo
echo "(time: the render's own, median of $rounds interleaved rounds, 800x600, 4 spp, 1 thread;"
echo "CPU time: user + system of the whole process, median; instructions:"
echo "callgrind, 200x150, 4 spp, 1 thread, the whole process; $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"

# The images: each scene's PFM from both builds (320x240, 2 spp); the
# terrain's mesh is written first, beside a copy of its scene.
differ=0
cp bench/scenes/terrain.sdl "$tmp/"
python3 bench/drivers/make_terrain.py "$tmp/terrain.3vn"
all="$(ls bench/scenes/*.sdl scenes/*.sdl scenes/gallery/*.sdl | grep -v /terrain.sdl) $tmp/terrain.sdl"
for f in $all; do
    for which in gcc zig; do
        run $which render "$f" -o "$tmp/$which.pfm" --size 320x240 --spp 2 -q 2>"$tmp/err" ||
            { cat "$tmp/err" >&2; exit 1; }
    done
    if ! cmp -s "$tmp/gcc.pfm" "$tmp/zig.pfm"; then
        echo "DIFFERENT: $f"
        differ=1
    fi
done
[ "$differ" = 0 ] && echo "every scene's PFM the same from both builds: $(echo $all | wc -w) scenes"
exit "$differ"

#!/bin/sh
# Where hitray's time goes, in instructions (callgrind counts are the same
# on a busy machine, unlike wall time): the raw first-hit query of
# bench/raycast and a render of one benchmark scene, each with its top
# functions (self cost).
#   bench/drivers/profile.sh [SCENE...]  (SCENE: a bench/scenes/*.sdl name, default spheres;
#                                 needs `make build-all`, which builds bench/raycast, and valgrind)
set -eu
cd "$(dirname "$0")/../.."
[ $# -gt 0 ] || set -- spheres
build=${BUILD:-build}
command -v valgrind >/dev/null || { echo "profile: valgrind is not installed" >&2; exit 1; }
[ -x "$build/bin/raycast" ] || { echo "profile: build the benchmark programs first (make build-all)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

top() {
    callgrind_annotate --inclusive=no "$1" 2>/dev/null |
        awk '/Auto-annotated/ {exit} /PROGRAM TOTALS/ {print; n = 0; next} /^ *[0-9,]+ \(/ && n < 14 {print; n++}' |
        sed "s|$(pwd)/||g"
}

echo "== raycast: 100,000 spheres, 300 x 300 rays, hitray's hr_scene_first_hit (trace only)"
valgrind --tool=callgrind --toggle-collect=worker --callgrind-out-file="$tmp/ray.out" \
    "$build/bin/raycast" --engine hitray --spheres 100000 --rays-side 300 >/dev/null 2>&1
top "$tmp/ray.out"
if "$build/bin/raycast" --engine embree --spheres 10 --rays-side 2 >/dev/null 2>&1; then
    echo "== raycast: the same rays through Embree (trace only)"
    valgrind --tool=callgrind --toggle-collect=worker --callgrind-out-file="$tmp/emb.out" \
        "$build/bin/raycast" --engine embree --spheres 100000 --rays-side 300 >/dev/null 2>&1
    top "$tmp/emb.out" | head -1
fi

for scene in "$@"; do
    echo "== hitray render bench/scenes/$scene.sdl at 480x270, 1 thread (whole process)"
    cp "bench/scenes/$scene.sdl" "$tmp/"
    if [ "$scene" = terrain ]; then python3 bench/drivers/make_terrain.py "$tmp/terrain.3vn"; fi
    valgrind --tool=callgrind --callgrind-out-file="$tmp/render.out" \
        "$build/bin/hitray" render "$tmp/$scene.sdl" -o "$tmp/out.ppm" --size 480x270 \
        --threads 1 >/dev/null 2>&1
    top "$tmp/render.out"
done

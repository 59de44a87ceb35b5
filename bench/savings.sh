#!/bin/sh
# What each opt-in saving (adaptive supersampling, the contribution cut-off)
# saves in rays and costs in error against the full render, and what the
# effect analysis saves (the effects-all row), on the demo scene and on the
# real Hill scene files: the tables of docs/effects.md.
#   bench/savings.sh [SIZE [SPP]]      (default 320x240 and 16; needs `make build`)
# Extra settings through the environment: ADAPTIVE and MIN_WEIGHT (comma
# lists), THREADS. Ray counts and errors do not depend on the thread count or
# on the machine: the tables are reproducible exactly.
set -eu
cd "$(dirname "$0")/.."
size=${1:-320x240}
spp=${2:-16}
bin=build/bin/hitray
[ -x "$bin" ] || { echo "savings: build first (make build)" >&2; exit 1; }
for scene in scenes/demo.sdl tests/scenes/hill/village.dat tests/scenes/hill/room.dat \
             tests/scenes/hill/chair.dat; do
    "$bin" savings "$scene" --size "$size" --spp "$spp" --threads "${THREADS:-0}" \
        --adaptive "${ADAPTIVE:-0.02,0.05,0.1}" --min-weight "${MIN_WEIGHT:-0.01,0.05,0.1,0.2}"
    echo
done

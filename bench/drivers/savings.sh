#!/bin/sh
# What each opt-in saving (adaptive supersampling, the contribution cut-off)
# saves in rays and costs in error against the full render, and what the
# effect analysis saves (the effects-all row), on the demo scene and on the
# real Hill scene files: the tables of docs/effects.md.
#   bench/drivers/savings.sh [--write PAGE] [SIZE [SPP]]
#                                      (default 320x240 and 16; needs `make build`)
# --write PAGE puts the tables into PAGE between its two markers (the
# comments naming bench/drivers/savings.sh), as docs/effects.md holds them:
#   bench/drivers/savings.sh --write docs/effects.md
# Extra settings through the environment: ADAPTIVE and MIN_WEIGHT (comma
# lists), THREADS, HITRAY (the command; default build/bin/hitray). Ray counts
# and errors do not depend on the thread count or on the machine: the tables
# are reproducible exactly (tests/docs/test_docs.py reruns them).
set -eu
cd "$(dirname "$0")/../.."
page=
if [ "${1:-}" = --write ]; then
    page=${2:?savings: --write needs a page}
    shift 2
fi
size=${1:-320x240}
spp=${2:-16}
bin=${HITRAY:-build/bin/hitray}
[ -x "$bin" ] || { echo "savings: build first (make build)" >&2; exit 1; }
tables() {
    gap=
    for scene in scenes/demo.sdl tests/data/scenes/hill/village.dat tests/data/scenes/hill/room.dat \
                 tests/data/scenes/hill/chair.dat; do
        [ -z "$gap" ] || echo
        gap=1
        "$bin" savings "$scene" --size "$size" --spp "$spp" --threads "${THREADS:-0}" \
            --adaptive "${ADAPTIVE:-0.02,0.05,0.1}" --min-weight "${MIN_WEIGHT:-0.01,0.05,0.1,0.2}"
    done
}
if [ -z "$page" ]; then
    tables
    exit 0
fi
grep -q '^<!-- not run: .*bench/drivers/savings.sh' "$page" && grep -q '^<!-- end of bench/drivers/savings.sh' "$page" ||
    { echo "savings: $page has no bench/drivers/savings.sh markers" >&2; exit 1; }
out=$(mktemp) && trap 'rm -f "$out" "$out.page"' EXIT
tables >"$out"
# The page is replaced whole, and only once every table is made.
awk -v out="$out" '
    /^<!-- end of bench\/drivers\/savings.sh/ { print "```"; skip = 0 }
    !skip { print }
    /^<!-- not run: .*bench\/drivers\/savings.sh/ {
        print "```"
        while ((getline line < out) > 0) print line
        skip = 1
    }' "$page" >"$out.page"
cat "$out.page" >"$page"

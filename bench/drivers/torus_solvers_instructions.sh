#!/bin/sh
# Instructions per torus solve, counted by callgrind, for each root solver
# and ray set of bench/programs/torus_solvers.c: unlike wall time, these do not move
# with the machine's load. Each count is the instructions of the timing loop
# (time_all: every hit; time_first: the first hit after t = 0) divided by
# the rays, so the loop's own few instructions per ray are included.
#
# usage: bench/drivers/torus_solvers_instructions.sh [BUILD_DIR] [RAYS]
# (BUILD_DIR defaults to build, RAYS to 2000; needs valgrind)
set -eu
build=${1:-build}
rays=${2:-2000}
bin=$build/bench/torus_solvers
if [ ! -x "$bin" ]; then
    echo "torus_solvers_instructions.sh: $bin is missing: build the benchmark programs first (make build-all)" >&2
    exit 1
fi
command -v valgrind >/dev/null && command -v callgrind_annotate >/dev/null || {
    echo "torus_solvers_instructions.sh: valgrind (callgrind) is not installed" >&2
    exit 1
}
out=$(mktemp)
trap 'rm -f "$out"' EXIT

printf '%-10s %-15s %10s %10s\n' rays solver "instr all" "instr 1st"
for set in near "far 1e4" "far 1e6" grazing "thin near" "thin graze"; do
    for solver in ferrari ferrari-newton bracketing; do
        valgrind --tool=callgrind --callgrind-out-file="$out" "$bin" --rays="$rays" \
            --repeats=1 --solver="$solver" --set="$set" --no-reference >/dev/null 2>&1
        callgrind_annotate --inclusive=yes "$out" 2>/dev/null | awk -v rays="$rays" \
            -v set="$set" -v solver="$solver" '
            /:time_all / && !all { gsub(",", "", $1); all = $1 }
            /:time_first / && !first { gsub(",", "", $1); first = $1 }
            END { printf "%-10s %-15s %10.0f %10.0f\n", set, solver, all / rays, first / rays }'
    done
done

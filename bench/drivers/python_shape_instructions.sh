#!/bin/sh
# Instructions per hit call of a Python shape against the C sphere, counted
# by callgrind (stable on a busy machine, unlike wall time). Each shape is
# rendered at two sizes and the counts subtracted, which cancels everything
# but the rays: starting Python, importing cffi, reading the headers.
#   bench/drivers/python_shape_instructions.sh [BUILD_DIR]   (default: build)
set -eu
cd "$(dirname "$0")/../.."
build=${1:-build}
python=${PYTHON:-.venv/bin/python}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
count() { # shape size -> instructions of the whole process
    valgrind --tool=callgrind --callgrind-out-file="$tmp/out" -q \
        "$python" bench/drivers/python_shape_cost.py --build-dir "$build" --render-once "$1" \
        --size "$2" >/dev/null 2>&1
    callgrind_annotate "$tmp/out" 2>/dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }'
}
small=100 large=200
rays=$((large * large - small * small))
c=$(( $(count sphere $large) - $(count sphere $small) ))
py=$(( $(count pysphere $large) - $(count pysphere $small) ))
none=$(( $(count pynothing $large) - $(count pynothing $small) ))
echo "rays: $rays (every one a hit call: the sphere's box fills the view)"
echo "C sphere:      $((c / rays)) instructions per ray"
echo "Python sphere: $((py / rays)) instructions per ray"
echo "Python extra:  $(((py - c) / rays)) instructions per hit call, $((py / c))x the C sphere's ray"
echo "a Python hit that returns [] at once: $(((none - c) / rays)) extra instructions per hit call"

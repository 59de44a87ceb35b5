#!/bin/sh
# Median wall time and rays per second of the demo render, as `hitray render`
# reports them, for a few sizes and thread counts. Prints a Markdown table.
#   bench/drivers/demo_timing.sh [RUNS]        (default 5 runs per row; needs `make build`)
# Rows are interleaved (each round runs every row once), so a machine whose
# speed drifts during the run shifts all rows alike.
set -eu
cd "$(dirname "$0")/../.."
runs=${1:-5}
bin=build/bin/hitray
[ -x "$bin" ] || { echo "demo_timing: build first (make build)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rows="640x480:1 640x480:2 1920x1080:2"

round=0
while [ "$round" -lt "$runs" ]; do
    for row in $rows; do
        size=${row%:*} threads=${row#*:}
        "$bin" render scenes/demo.sdl -o "$tmp/d.png" --size "$size" --threads "$threads" \
            --stats-json "$tmp/s.json" > /dev/null
        # seconds and the total of the four ray counts, from the JSON object
        tr -d '{}" ' < "$tmp/s.json" | tr ',' '\n' | awk -F: '
            $1 ~ /seconds/ {s = $2}
            $1 ~ /^(primary|shadow|reflected|refracted)$/ {r += $2}
            END {printf "%.6f %d\n", s, r}' >> "$tmp/$size-$threads"
    done
    round=$((round + 1))
done

echo "| size | threads | median time | rays cast | rays/s |"
echo "|---|---|---|---|---|"
for row in $rows; do
    size=${row%:*} threads=${row#*:}
    sort -n "$tmp/$size-$threads" | awk -v size="$size" -v threads="$threads" -v n="$runs" '
        NR == int((n + 1) / 2) {printf "| %s | %s | %.3f s | %d | %.2f M |\n", size, threads, $1, $2, $2 / $1 / 1e6}'
done
echo
echo "($runs rounds, median per row; $(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"

#!/bin/sh
# Builds the libFuzzer harnesses of tests/fuzz with clang (ASan+UBSan) and
# runs them; see FUZZING.md.
#
#   run_fuzzers.sh [--build DIR] [--seconds N] [--runs N] [--replay] [--seed S] [--jobs N]
#                  [--merge] [--quiet] [HARNESS...]
#
# Each harness (all of them when none is named: shapes csg sdl nff mesh scene) runs
# for N seconds (default 60) starting from its committed seeds in
# tests/fuzz/corpus/<harness>/. New inputs go to DIR/corpus/<harness>/ and
# crashes to DIR/artifacts/<harness>/, so the source tree is never written
# (merge finds into the committed corpus as FUZZING.md says). With --replay
# every committed corpus file is first run once through the fuzz binary.
# --seed S fixes libFuzzer's random seed (default: a new one each run) and
# starts from the committed seeds alone (DIR/corpus/<harness> is emptied
# first), and --runs N stops after N inputs (--seconds still caps the
# time): together they make `make test-fuzz` walk the same inputs on every
# machine, a slower one only stopping earlier on the same path. CI checks
# that nothing regressed; exploring is `make fuzz`'s job. --merge (what
# `make fuzz-long` uses) then merges the inputs a harness found into its
# committed corpus, keeping only those that reach new coverage (libFuzzer's
# -merge=1): the one mode that writes into the source tree.
# Exits non-zero, naming the harness and the input that broke it, on any
# crash, sanitizer report, timeout, leak or contract break. --quiet builds
# without a line per compile (warnings and errors still shown).
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
build=build-fuzz
seconds=60
replay=""
merge=""
seed=""
runs=""
quiet=""
jobs=${FUZZ_JOBS:-2}
harnesses=""
while [ $# -gt 0 ]; do
    case "$1" in
    --build) build=$2; shift 2 ;;
    --seconds) seconds=$2; shift 2 ;;
    --replay) replay=1; shift ;;
    --merge) merge=1; shift ;;
    --seed) seed=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --quiet) quiet=1; shift ;;
    -h | --help) sed -n '2,25p' "$0"; exit 0 ;;
    -*) echo "run_fuzzers.sh: unknown option $1" >&2; exit 2 ;;
    *) harnesses="$harnesses $1"; shift ;;
    esac
done
[ -n "$harnesses" ] || harnesses="shapes csg sdl nff mesh scene"
case "$build" in /*) ;; *) build="$root/$build" ;; esac

# Per input: a hang is a bug (the readers must never hang), and so is a
# run-away allocation.
timeout_s=${FUZZ_TIMEOUT:-10}
rss_mb=${FUZZ_RSS_MB:-2048}

if [ ! -f "$build/build.ninja" ]; then
    echo "run_fuzzers: configuring $build with clang"
    mkdir -p "$build"
    (cd "$root" && cmake --preset fuzz -B "$build") >"$build/configure.log" 2>&1 || {
        cat "$build/configure.log" >&2
        exit 1
    }
fi
targets=""
for h in $harnesses; do
    [ -f "$root/tests/fuzz/fuzz_$h.c" ] || { echo "run_fuzzers: no harness '$h'" >&2; exit 2; }
    targets="$targets fuzz_$h"
done
# shellcheck disable=SC2086 # the target list is meant to split
cmake --build "$build" -j "$jobs" --target $targets ${quiet:+-- --quiet}

# ASan's and UBSan's reports end the run; leaks are reported too.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
mkdir -p "$build/logs"
failed=""
for h in $harnesses; do
    binary="$build/tests/fuzz_$h"
    seeds="$root/tests/fuzz/corpus/$h"
    found="$build/corpus/$h"
    artifacts="$build/artifacts/$h"
    log="$build/logs/$h.log"
    [ -n "$seed" ] && rm -rf "$found"
    mkdir -p "$found" "$artifacts"
    common="-timeout=$timeout_s -rss_limit_mb=$rss_mb -artifact_prefix=$artifacts/"
    dict="$root/tests/fuzz/$h.dict"
    [ "$h" = scene ] && dict="$root/tests/fuzz/sdl.dict" # the same language
    [ -f "$dict" ] && common="$common -dict=$dict"
    [ -n "$seed" ] && common="$common -seed=$seed"
    if [ -n "$replay" ]; then
        echo "run_fuzzers: $h: replaying $(ls "$seeds" | wc -l) corpus files"
        # shellcheck disable=SC2086
        if ! "$binary" $common -runs=0 "$seeds" >"$log.replay" 2>&1; then
            tail -n 40 "$log.replay" >&2
            echo "run_fuzzers: $h: FAILED replaying the committed corpus (log $log.replay)" >&2
            failed="$failed $h"
            continue
        fi
    fi
    echo "run_fuzzers: $h: fuzzing for $seconds s${runs:+ or $runs inputs}${seed:+ from seed $seed} (log $log)"
    # shellcheck disable=SC2086
    limit="-max_total_time=$seconds"
    [ -n "$runs" ] && limit="$limit -runs=$runs"
    if "$binary" $common $limit -print_final_stats=1 "$found" "$seeds" \
        >"$log" 2>&1; then
        grep -E "^#[0-9]+.*DONE|stat::number_of_executed_units|stat::new_units_added" "$log" |
            sed "s/^/run_fuzzers: $h: /"
        if [ -n "$merge" ]; then
            before=$(ls "$seeds" | wc -l)
            # shellcheck disable=SC2086
            "$binary" $common -merge=1 "$seeds" "$found" >"$log.merge" 2>&1 || {
                tail -n 20 "$log.merge" >&2
                echo "run_fuzzers: $h: FAILED merging into $seeds (log $log.merge)" >&2
                failed="$failed $h"
                continue
            }
            echo "run_fuzzers: $h: merged $(($(ls "$seeds" | wc -l) - before)) new inputs into tests/fuzz/corpus/$h"
        fi
    else
        tail -n 60 "$log" >&2
        artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -n 1)
        echo "run_fuzzers: $h: FAILED; the input is ${artifact:-in $artifacts} (log $log)" >&2
        echo "run_fuzzers: reproduce with: $binary ${artifact:-<artifact>}" >&2
        failed="$failed $h"
    fi
done
if [ -n "$failed" ]; then
    echo "run_fuzzers: failed:$failed" >&2
    exit 1
fi
found_total=$(find "$build/corpus" -type f | wc -l)
echo "run_fuzzers: no harness failed. $found_total inputs found so far under $build/corpus;"
echo "run_fuzzers: to keep the interesting ones, merge them into the committed corpus:"
echo "run_fuzzers:   $build/tests/fuzz_<harness> -merge=1 tests/fuzz/corpus/<harness> $build/corpus/<harness>"

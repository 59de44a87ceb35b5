#!/bin/sh
# What the wheels of `make wheels` cost and give, for the release notes:
# each wheel's size, the time pip takes to install it into a fresh venv of
# its Python (its dependencies from pip's cache once warm), the time of
# `import hitray` there (best of 5), and whether the README's picture
# (scenes/demo.sdl, 960x720, 4 spp: `make demo`) that the wheel's hitray
# command renders is byte-identical, PNG and EXR, to the one of the CMake
# build in REFERENCE_BUILD (default build/, `make build`).
#   scripts/wheels/measure.sh [PYTHON_VERSION...]      (default 3.10 to 3.13)
set -eu
cd "$(dirname "$0")/../.."
ref=${REFERENCE_BUILD:-build}/bin/hitray
[ -x "$ref" ] || { echo "measure: no $ref (make build)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
demo="$(pwd)/scenes/demo.sdl --size 960x720 --spp 4"
# shellcheck disable=SC2086
"$ref" render $demo -o "$tmp/ref.png" --exr "$tmp/ref.exr" >/dev/null
echo "| wheel | size (bytes) | pip install (s) | import hitray (s) | demo PNG, EXR vs the CMake build |"
echo "| --- | --- | --- | --- | --- |"
for v in ${*:-3.10 3.11 3.12 3.13}; do
    py=$(scripts/wheels/find_python.sh "$v")
    whl=$(ls dist/wheelhouse/hitray-*-cp"$(echo "$v" | tr -d .)"-*.whl)
    env_dir="$tmp/venv$v"
    "$py" -m venv "$env_dir"
    start=$(date +%s.%N)
    LD_LIBRARY_PATH= "$env_dir/bin/pip" install -q --disable-pip-version-check "$whl"
    install=$(echo "$(date +%s.%N) - $start" | bc)
    best=
    for _ in 1 2 3 4 5; do
        start=$(date +%s.%N)
        (cd "$tmp" && LD_LIBRARY_PATH= "$env_dir/bin/python" -c "import hitray")
        t=$(echo "$(date +%s.%N) - $start" | bc)
        if [ -z "$best" ] || [ "$(echo "$t < $best" | bc)" = 1 ]; then best=$t; fi
    done
    # shellcheck disable=SC2086
    (cd "$tmp" && LD_LIBRARY_PATH= "$env_dir/bin/hitray" render $demo -o "$tmp/w$v.png" --exr "$tmp/w$v.exr" >/dev/null)
    same=$(cmp -s "$tmp/ref.png" "$tmp/w$v.png" && echo same || echo DIFFERENT)
    same="$same, $(cmp -s "$tmp/ref.exr" "$tmp/w$v.exr" && echo same || echo DIFFERENT)"
    printf '| %s | %s | %.1f | %.3f | %s |\n' "$(basename "$whl")" "$(stat -c %s "$whl")" "$install" "$best" "$same"
done

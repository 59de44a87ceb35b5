#!/bin/sh
# Install what a `make` target needs on a Debian machine, only what is
# missing: Debian packages through apt-get (as root, or through sudo), and
# Python tools through pip into the repository's own virtual environment.
#   bootstrap.sh           building the library, the shapes and the command
#                          (make build, make demo, make install)
#   bootstrap.sh --test    and the tests (make test): the sanitizers' and
#                          the fuzzers' clang, valgrind, groff (the man page's
#                          check), Python and every scripts/requirements-*.txt
#   bootstrap.sh --wheel   and the wheels (make wheel, make wheels): Python,
#                          dpkg-dev, the build and repair tools and zig
#                          (requirements-python.txt, -wheel.txt)
#   bootstrap.sh --bench   and what `make bench` compares against
set -eu
cd "$(dirname "$0")/.."

need="cmake ninja-build gcc g++ make pkg-config libpng-dev zlib1g-dev libopenexr-dev libfast-float-dev libstb-dev libsdl2-dev"
python_pkgs="python3 python3-venv python3-dev"
venv_reqs=""
case "${1:-}" in
    "") ;;
    # clang, its runtimes (libFuzzer, the sanitizers) and llvm (the
    # symbolizer) build and run the fuzz harnesses in tests/fuzz; valgrind
    # runs make test-memcheck; xvfb and xdotool give hitray-view's tests
    # a display and key presses.
    --test) need="$need $python_pkgs clang libclang-rt-14-dev llvm valgrind groff-base xvfb xdotool"
            venv_reqs=$(ls scripts/requirements-*.txt) ;;
    # dpkg-dev unpacks the Debian source packages the wheels' libraries
    # are built from (scripts/wheels/fetch_sources.sh: dpkg-source).
    --wheel) need="$need $python_pkgs dpkg-dev"
             venv_reqs="scripts/requirements-python.txt scripts/requirements-wheel.txt" ;;
    --bench) need="$need python3 povray libembree-dev" ;;
    *) echo "bootstrap.sh: unknown option '$1' (--test, --wheel or --bench)" >&2; exit 2 ;;
esac

missing=""
for pkg in $need; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" ||
        missing="$missing $pkg"
done
if [ -n "$missing" ]; then
    echo "bootstrap: installing Debian packages:$missing"
    if [ "$(id -u)" = 0 ]; then sudo=""; else sudo="sudo"; fi
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $missing
fi

[ -n "$venv_reqs" ] || exit 0
# The venv: created once, then each requirements file installed when it is
# newer than its stamp (so a changed file tops the venv up).
venv=.venv
if [ ! -x "$venv/bin/python" ]; then
    echo "bootstrap: creating the Python virtual environment in $venv"
    python3 -m venv "$venv"
    "$venv/bin/python" -m pip install -q --upgrade pip
fi
for req in $venv_reqs; do
    stamp="$venv/.stamp-$(basename "$req" .txt)"
    if [ ! -f "$stamp" ] || [ "$req" -nt "$stamp" ]; then
        "$venv/bin/python" -m pip install -q -r "$req"
        touch "$stamp"
    fi
done

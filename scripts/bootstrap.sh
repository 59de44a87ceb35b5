#!/bin/sh
# Install what `make` needs on a Debian machine, only what is missing:
# Debian packages through apt-get (as root, or through sudo), and the Python
# test tools through pip into the repository's own virtual environment.
set -eu
cd "$(dirname "$0")/.."

# `bootstrap.sh --bench` adds what `make bench` compares against.
bench_pkgs=""
[ "${1:-}" = "--bench" ] && bench_pkgs="povray libembree-dev"
# clang, its runtimes (libFuzzer, the sanitizers) and llvm (the symbolizer)
# build and run the fuzz harnesses in tests/fuzz; valgrind runs make
# test-memcheck. libsdl2-dev builds hitray-view (the window of `hitray
# view`); xvfb and xdotool give its tests a display and key presses.
need_pkgs=""
for pkg in cmake ninja-build gcc g++ make pkg-config libpng-dev zlib1g-dev libopenexr-dev libfast-float-dev \
           python3 python3-venv python3-dev \
           clang libclang-rt-14-dev llvm valgrind libsdl2-dev xvfb xdotool $bench_pkgs; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" ||
        need_pkgs="$need_pkgs $pkg"
done
if [ -n "$need_pkgs" ]; then
    echo "bootstrap: installing Debian packages:$need_pkgs"
    if [ "$(id -u)" = 0 ]; then sudo=""; else sudo="sudo"; fi
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $need_pkgs
fi

# The venv: created once, then only topped up from requirements.
venv=.venv
stamp=$venv/.requirements-stamp
if [ ! -x "$venv/bin/python" ]; then
    echo "bootstrap: creating the Python virtual environment in $venv"
    python3 -m venv "$venv"
fi
# Every scripts/requirements-*.txt is installed; a newer file than the stamp
# triggers the top-up.
stale=""
for req in scripts/requirements-*.txt; do
    if [ ! -f "$stamp" ] || [ "$req" -nt "$stamp" ]; then stale=1; fi
done
if [ -n "$stale" ]; then
    "$venv/bin/python" -m pip install -q --upgrade pip
    for req in scripts/requirements-*.txt; do
        "$venv/bin/python" -m pip install -q -r "$req"
    done
    touch "$stamp"
fi


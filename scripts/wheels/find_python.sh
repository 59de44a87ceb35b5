#!/bin/sh
# The interpreter of CPython X.Y: pythonX.Y on PATH, else the newest pyenv
# build of it (~/.pyenv/versions/X.Y.*). Prints its path, or says how to
# get it and fails.
set -eu
v=$1
for p in "${PYENV_ROOT:-$HOME/.pyenv}"/versions/"$v".*/bin/python"$v"; do
    [ -x "$p" ] && found=$p
done
if [ -z "${found:-}" ] && command -v "python$v" >/dev/null 2>&1; then
    found=$(command -v "python$v")
fi
if [ -z "${found:-}" ]; then
    echo "find_python: no Python $v here (pyenv install $v, or python$v on PATH)" >&2
    exit 1
fi
echo "$found"

"""Helpers shared by the pytest files: the Python package's (tests/python),
the command line's (tests/cli), the viewer's (tests/view) and the benchmark
drivers' (tests/bench); pytest finds this file through pyproject.toml's
[tool.pytest.ini_options] pythonpath.

The package under test is the one installed into the running interpreter
(`make test-python` installs it from the repository's root first); it is never
imported from the source tree. HITRAY_BUILD_DIR (default ./build) names the
CMake build tree, where the test-only shape modules live.
"""

import os
import pathlib
import signal

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("HITRAY_BUILD_DIR", ROOT / "build"))

# The scene of the CLI tests, as SDL: two spheres on a floor, one light.
TWO_SPHERES_SDL = """\
camera 0 2 8   0 0.5 0   0 1 0   40
background 0.1 0.2 0.3
light 5 8 6   1 1 1
push translate -1 1 0  diffuse 0.8 0.2 0.2  sphere pop
push translate 1.2 1 -0.5  diffuse 0.2 0.8 0.2  specular 0.5 0.5 0.5  specularExponent 20  sphere pop
push rotate -90 1 0 0  plane pop
"""


def sigint_as_at_a_terminal():
    """preexec_fn of a child the test sends SIGINT (Ctrl-C) to. A shell starts
    a background job (`make test &`) with SIGINT ignored, the child would
    inherit that and keep it (as a background job must), and the Ctrl-C
    would do nothing: the child gets the default action back, as a command
    started at a terminal has it."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def require_classes(*names):
    """Skip (with the reason shown by `pytest -rs`) unless every shape class
    is installed: the torus, CSG and mesh modules come from their own
    branches of the project."""
    import hitray

    have = hitray.shape_classes()
    missing = [n for n in names if n not in have]
    if missing:
        pytest.skip(f"shape module(s) providing {', '.join(missing)} not installed in this build")


def test_module(name):
    """A module built only for the C tests (tests/modules in the build tree)."""
    path = BUILD / "tests" / "modules" / f"{name}.so"
    if not path.is_file():
        pytest.fail(f"{path} is missing: build the C tests first (make build)")
    return path


test_module.__test__ = False  # a helper, not a test

"""The wheel tests take the wheel to try: `--wheel PATH` (make test-wheel
passes the manylinux wheel that `make wheel` wrote; make test-wheels each of
`make wheels`), and `--python PATH`, the interpreter whose fresh venv gets
it (the one running pytest by default)."""

import pathlib
import sys

import pytest


def pytest_addoption(parser):
    parser.addoption("--wheel", help="the wheel to install and try (make wheel's dist/wheelhouse/*.whl)")
    parser.addoption("--python", help="the Python whose venv gets the wheel (default: the one running pytest)")


@pytest.fixture(scope="session")
def wheel(request):
    given = request.config.getoption("--wheel")
    if not given:
        pytest.fail("no wheel given: run `make test-wheel`, or pytest tests/wheel --wheel PATH")
    path = pathlib.Path(given)
    if not path.is_file():
        pytest.fail(f"--wheel {given}: no such file (make wheel writes dist/wheelhouse/*.whl)")
    return path


@pytest.fixture(scope="session")
def python(request):
    return request.config.getoption("--python") or sys.executable

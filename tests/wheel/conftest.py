"""The wheel tests take the wheel to try: `--wheel PATH` (make test-wheel
passes the manylinux wheel that `make wheel` wrote)."""

import pathlib

import pytest


def pytest_addoption(parser):
    parser.addoption("--wheel", help="the wheel to install and try (make wheel's dist/wheelhouse/*.whl)")


@pytest.fixture(scope="session")
def wheel(request):
    given = request.config.getoption("--wheel")
    if not given:
        pytest.fail("no wheel given: run `make test-wheel`, or pytest tests/wheel --wheel PATH")
    path = pathlib.Path(given)
    if not path.is_file():
        pytest.fail(f"--wheel {given}: no such file (make wheel writes dist/wheelhouse/*.whl)")
    return path

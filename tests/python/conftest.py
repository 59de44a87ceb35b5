"""The Python package's tests: the helpers they share with the command
line's and the viewer's (tests/support/hitray_testing.py, imported here so
that `from conftest import ...` finds them too), and the fixtures."""

import signal

import pytest
from hitray_testing import (  # noqa: F401
    BUILD,
    ROOT,
    TWO_SPHERES_SDL,
    require_classes,
    sigint_as_at_a_terminal,
    test_module,
)


@pytest.fixture
def sigint_raises():
    """SIGINT sent to the test's own process raises KeyboardInterrupt, as at a
    terminal, even when the tests were started with it ignored (a background
    job, where Python leaves it ignored)."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)

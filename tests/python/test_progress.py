"""hitray.render's progress bar: by default only where someone watches
(standard error a terminal, or a notebook), as `hitray render` does;
progress=True forces one, False shows none."""

import fcntl
import os
import pty
import struct
import subprocess
import sys
import termios
import types

import pytest

import hitray
from hitray import _progress

pytest.importorskip("tqdm")

# A render long enough for tqdm to draw its first frame (it draws one when
# the bar is made, whatever the render's length).
RENDER = """
import hitray
scene = hitray.Scene()
scene.add(hitray.Sphere())
hitray.render(scene, size=(32, 32){extra})
"""


def stderr_through_a_pipe(extra=""):
    done = subprocess.run([sys.executable, "-c", RENDER.format(extra=extra)], stdin=subprocess.DEVNULL,
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=60, check=True)
    return done.stderr.decode()


def stderr_at_a_terminal(extra=""):
    """What the render writes to standard error when that is a pseudo-terminal."""
    main, side = pty.openpty()
    # A fresh pseudo-terminal is 0 columns wide, where tqdm draws nothing.
    fcntl.ioctl(side, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 80, 0, 0))
    try:
        child = subprocess.Popen([sys.executable, "-c", RENDER.format(extra=extra)], stdin=subprocess.DEVNULL,
                                 stdout=subprocess.DEVNULL, stderr=side)
        os.close(side)
        out = b""
        while True:
            try:
                chunk = os.read(main, 4096)
            except OSError:  # EIO: the child closed its side
                break
            if not chunk:
                break
            out += chunk
        assert child.wait(timeout=60) == 0, out
    finally:
        os.close(main)
    return out.decode(errors="replace")


def test_no_bar_by_default_when_stderr_is_a_pipe():
    assert stderr_through_a_pipe() == ""


def test_a_bar_by_default_when_stderr_is_a_terminal():
    assert "hitray:" in stderr_at_a_terminal()


def test_progress_true_forces_a_bar_into_a_pipe():
    assert "hitray:" in stderr_through_a_pipe(", progress=True")


def test_progress_false_draws_nothing_at_a_terminal():
    assert "hitray:" not in stderr_at_a_terminal(", progress=False")


def test_a_bar_by_default_in_a_notebook(monkeypatch, capsys):
    shell = types.SimpleNamespace(config={"IPKernelApp": {}})
    monkeypatch.setitem(sys.modules, "IPython", types.SimpleNamespace(get_ipython=lambda: shell))
    monkeypatch.setitem(sys.modules, "ipywidgets", None)  # tqdm's plain bar, drawn into capsys
    scene = hitray.Scene()
    scene.add(hitray.Sphere())
    hitray.render(scene, size=(16, 16))
    assert "hitray:" in capsys.readouterr().err


@pytest.mark.parametrize("stderr", [None, object(), types.SimpleNamespace(isatty=lambda: True)])
def test_wanted_follows_stderr(monkeypatch, stderr):
    monkeypatch.setattr(sys, "stderr", stderr)
    terminal = stderr is not None and hasattr(stderr, "isatty")
    assert _progress.wanted(None) is terminal
    assert _progress.wanted(True) is True and _progress.wanted(False) is False


def test_wanted_on_a_closed_stderr(monkeypatch):
    closed = open(os.devnull, "w")
    closed.close()
    monkeypatch.setattr(sys, "stderr", closed)
    assert _progress.wanted(None) is False

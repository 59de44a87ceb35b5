"""Ctrl-C during a long trace or render (issue 16, defect 6): the calling
thread sees the signal within a poll interval and the work stops at once,
however slow the shapes, with KeyboardInterrupt itself raised (not a
ModuleError wrapping it). No wall time is asserted: a stop is shown by how
few of the rays were traced when the call returned."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import hitray
import hitray.abi as abi


class Slow:
    """A unit box whose hit takes a millisecond (a Python shape doing real
    work), counting its calls."""

    calls = 0
    lock = threading.Lock()

    def bounds(self):
        return ((-1, -1, -1), (1, 1, 1))

    def hit(self, origin, direction, tmin, tmax):
        with Slow.lock:
            Slow.calls += 1
        time.sleep(0.001)
        return []


abi.register_shape("slow_interrupt", Slow)

# The interrupts are SIGINT sent to this process (interrupt_soon).
pytestmark = pytest.mark.usefixtures("sigint_raises")


def slow_scene():
    scene = hitray.Scene()
    scene.add(hitray.Shape("slow_interrupt"))
    return scene


def interrupt_soon():
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_stops_a_long_trace():
    scene = slow_scene()
    n = 100_000  # 100 s of hits on one thread
    origins = np.tile([0.0, 0.0, 5.0], (n, 1))
    directions = np.tile([0.0, 0.0, -1.0], (n, 1))
    Slow.calls = 0
    timer = interrupt_soon()
    try:
        with pytest.raises(KeyboardInterrupt):
            scene.trace(origins, directions, threads=2)
    finally:
        timer.cancel()
    calls = Slow.calls
    time.sleep(0.05)
    assert Slow.calls == calls  # nothing runs on after the call returned
    assert calls < n // 10, f"{calls} of {n} rays traced before the trace stopped"


class SlowEverywhere(Slow):
    """Unbounded, so every camera ray calls its hit."""

    def bounds(self):
        return None


abi.register_shape("slow_everywhere", SlowEverywhere)


def test_ctrl_c_stops_a_render_in_a_slow_shape():
    """Before: the render was cancelled only when a tile (32 x 32 = 1024
    rays of 1 ms each) ended, about a second after Ctrl-C; now within a ray
    (about 300 rays have been traced when the signal comes)."""
    scene = hitray.Scene()
    scene.add(hitray.Shape("slow_everywhere"))
    Slow.calls = 0
    timer = interrupt_soon()
    try:
        with pytest.raises(KeyboardInterrupt):
            hitray.render(scene, hitray.Camera(), size=(64, 64), threads=1, progress=False)
    finally:
        timer.cancel()
    assert Slow.calls < 1024, f"{Slow.calls} rays traced before the render stopped"


def test_ctrl_c_inside_a_hit_on_the_main_thread_is_a_keyboard_interrupt():
    """A short query runs its shapes on the calling thread: the interrupt
    arrives inside hit, and comes out as itself, not as a ModuleError."""

    class Interrupted(Slow):
        def hit(self, origin, direction, tmin, tmax):
            raise KeyboardInterrupt

    abi.register_shape("interrupted_main", Interrupted)
    scene = hitray.Scene()
    scene.add(hitray.Shape("interrupted_main"))
    with pytest.raises(KeyboardInterrupt):
        scene.first_hit((0, 0, 5), (0, 0, -1))
    with pytest.raises(KeyboardInterrupt):
        scene.trace(np.array([[0.0, 0.0, 5.0]]), np.array([[0.0, 0.0, -1.0]]))

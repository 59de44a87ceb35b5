"""The GIL is released while a render runs: two renders from two Python
threads run at the same time, and Ctrl-C cancels a render cleanly."""

import json
import subprocess
import sys
import threading
import time

import numpy as np

import hitray
from conftest import TWO_SPHERES_SDL, sigint_as_at_a_terminal


def test_two_renders_from_two_threads_run_at_the_same_time():
    scene, camera = hitray.parse_sdl(TWO_SPHERES_SDL)
    started = {"a": threading.Event(), "b": threading.Event()}
    spans, images, errors = {}, {}, []

    def job(me, other):
        def progress(fraction):
            # Each render waits, inside its own render, until the other has
            # started too: if a render held the GIL the other could never
            # start, and this would time out.
            started[me].set()
            if not started[other].wait(timeout=120):
                raise RuntimeError(f"render {other} never started while {me} was running")

        try:
            begin = time.monotonic()
            images[me] = hitray.render(scene, camera, size=(160, 120), spp=4, threads=1,
                                       progress=progress)
            spans[me] = (begin, time.monotonic())
        except BaseException as e:  # reported below, not lost in the thread
            errors.append(e)

    threads = [threading.Thread(target=job, args=("a", "b")),
               threading.Thread(target=job, args=("b", "a"))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    # Both finished, with the same image.
    assert np.array_equal(np.asarray(images["a"]), np.asarray(images["b"]))
    # The wall time of the pair is below the sum of the two: they overlapped.
    wall = max(e for _, e in spans.values()) - min(b for b, _ in spans.values())
    total = sum(e - b for b, e in spans.values())
    assert wall < total, (wall, total)


INTERRUPT = r"""
import json, os, signal, sys, threading
import hitray

MODE = sys.argv[1]  # "callable": a progress callable; "bar": the tqdm bar
scene, camera = hitray.parse_sdl(sys.stdin.read())
seen, timer = [], []


def ctrl_c_soon():
    # Ctrl-C 0.2 s from now, from another thread, as a terminal sends it.
    timer.append(threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT)))
    timer[0].start()


def progress(fraction):
    seen.append(fraction)
    if not timer:  # the render is running
        ctrl_c_soon()


threads_before = threading.active_count()
if MODE == "bar":
    ctrl_c_soon()
try:
    hitray.render(scene, camera, size=(2000, 2000), spp=64, threads=1,
                  progress=progress if MODE == "callable" else True)
    outcome = "finished"
except KeyboardInterrupt:
    outcome = "KeyboardInterrupt"
timer[0].join()
# Cleanly: no thread left behind, and the next render works.
after = hitray.render(scene, camera, size=(8, 8), progress=False)
# tqdm keeps a monitor thread of its own for the life of the process.
ours = [t for t in threading.enumerate() if type(t).__name__ != "TMonitor"]
print(json.dumps({"outcome": outcome, "last": seen[-1] if seen else None,
                  "threads_before": threads_before, "threads_after": len(ours),
                  "next_render_rays": after.stats.primary}))
"""


def run_interrupt(mode):
    result = subprocess.run([sys.executable, "-c", INTERRUPT, mode], input=TWO_SPHERES_SDL,
                            capture_output=True, text=True, timeout=300, preexec_fn=sigint_as_at_a_terminal)
    assert result.returncode == 0, result.stderr[-3000:]
    return json.loads(result.stdout.strip().splitlines()[-1])


def test_ctrl_c_cancels_a_render_and_raises_keyboard_interrupt():
    # Uncancelled this render casts 256 million primary rays on one thread
    # (minutes); the interrupt arrives 0.2 s after it started.
    r = run_interrupt("callable")
    assert r["outcome"] == "KeyboardInterrupt"
    assert r["last"] < 1.0  # stopped early, not after finishing
    assert r["threads_after"] == r["threads_before"]
    assert r["next_render_rays"] == 64


def test_ctrl_c_cancels_a_render_showing_a_progress_bar():
    r = run_interrupt("bar")
    assert r["outcome"] == "KeyboardInterrupt"
    assert r["threads_after"] == r["threads_before"]
    assert r["next_render_rays"] == 64

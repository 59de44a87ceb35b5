"""The worker's side of a band: a Dask actor, one per worker and run, that
renders the bands the client sends it straight (no scheduler between them),
in chunks of rows whose progress it keeps, so that the rows of a band not
yet begun can be taken from it (`split`) and rendered elsewhere.

A call to an actor goes from the client to the worker and back, about 1 ms
of both sides' CPU on the development machine, where a Dask task (submit,
schedule, run, report, fetch) is 6 to 8 ms (docs/distributed.md). The
scene stays on the worker for the whole run.
"""

from __future__ import annotations

import collections
import threading
import time
from typing import Any, Dict, Optional, Set, Tuple

import numpy as np

from ..render import render as _render_here
from ._client import dask_distributed, local_cores
from ._pack import ScenePack
from ._shared import open_frame

__all__ = ["BandWorker", "CHUNK_SECONDS", "NEED_SCENE"]

# A chunk of a band is this many seconds of the worker's rendering (each
# chunk is one hitray.render of a window, about 0.04 ms of fixed cost, so
# chunks of a few hundredths of a second cost nothing measurable); rows not
# yet begun can be taken from a band at any chunk's end.
CHUNK_SECONDS = 0.1
# Rows expected to take less than this are not worth a split (the split's
# round trip and the new band's call cost about 2 ms).
MIN_SPLIT_SECONDS = 0.02
# What `render` answers when the worker lacks the scene: the client sends
# it (`ship`) and asks again.
NEED_SCENE = "need-scene"

# Scenes this worker process built lately, by their content (ScenePack.key):
# the next run of the same scene (a render after a render) finds it built.
_RECENT: "collections.OrderedDict[str, ScenePack]" = collections.OrderedDict()
_RECENT_KEPT = 2
_RECENT_LOCK = threading.Lock()


def _recent(pack: ScenePack) -> ScenePack:
    """The pack of the same content built here lately, else `pack` (kept)."""
    with _RECENT_LOCK:
        known = _RECENT.get(pack.key)
        if known is None:
            known = _RECENT[pack.key] = pack
        _RECENT.move_to_end(pack.key)
        while len(_RECENT) > _RECENT_KEPT:
            _RECENT.popitem(last=False)
        return known


# Seconds a worker sleeps before each chunk: a test's way to make one worker
# slow (set through Client.run). Zero in any real run.
_test_delay = 0.0


def set_test_delay(seconds: float) -> float:
    """Make this worker sleep `seconds` before each chunk (tests only);
    returns the delay before."""
    global _test_delay
    before, _test_delay = _test_delay, float(seconds)
    return before


def _worker() -> Tuple[Any, str, int]:
    """This process's Dask worker, its address and its threads (outside a
    worker: None, "local" and this machine's cores)."""
    try:
        w = dask_distributed().get_worker()
    except ValueError:
        return None, "local", local_cores()
    return w, w.address, int(w.state.nthreads)


class _Progress:
    """A band being rendered: the first row not yet begun, and the row it
    stops before (lowered by a split)."""

    __slots__ = ("next", "stop", "row_seconds")

    def __init__(self, start: int, stop: int) -> None:
        self.next, self.stop = start, stop
        self.row_seconds: Optional[float] = None  # measured on this band


class BandWorker:
    """The actor (``Client.submit(BandWorker, actor=True, workers=[w])``).

    `render` runs on the worker's actor thread, one band at a time, each on
    all the worker's threads (or `threads`); `split` and `stop` are
    coroutines, so they run on the worker's event loop while a band renders.
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._packs: Dict[str, ScenePack] = {}
        self._bands: Dict[int, _Progress] = {}
        # Bands split before they began: where they stop; bands finished.
        self._stops: Dict[int, int] = {}
        self._finished: Set[int] = set()
        self._stopped = False

    def ship(self, key: str, pack: ScenePack) -> None:
        """Keep `pack` under `key` (a scene the scatter did not reach: a
        worker that joined later)."""
        self._packs[key] = _recent(pack)

    def drop(self, key: str) -> None:
        self._packs.pop(key, None)

    def _pack(self, key: str) -> Optional[ScenePack]:
        pack = self._packs.get(key)
        if pack is None:
            w = _worker()[0]
            found = None if w is None else w.data.get(key) if key in w.data else None
            if isinstance(found, ScenePack):
                pack = self._packs[key] = _recent(found)
        return pack

    def render(self, band: int, key: str, camera: Any, size: Tuple[int, int], options: Dict[str, Any],
               window: Tuple[int, int, int, int], threads: Optional[int], shared: Optional[str] = None) -> Any:
        """Render the rows of `window` (the band numbered `band`) until its
        end or a split's row; returns (pixels of the rows rendered, or None
        when they were written to the frame's shared memory `shared`; rays
        (primary, shadow, reflected, refracted, effects), worker address,
        threads, the worker's clock when it began and ended, the rows
        rendered), or NEED_SCENE."""
        pack = self._pack(key)
        if pack is None:
            return NEED_SCENE
        scene = pack.scene()
        where, nthreads = _worker()[1:]
        threads = nthreads if threads is None else threads
        x, y0, w, h = window
        with self._lock:
            stop = min(y0 + h, self._stops.pop(band, y0 + h))
            if self._stopped:
                stop = y0
            state = self._bands[band] = _Progress(y0, stop)
        frame = open_frame(shared, size)
        pixels = np.empty((h, w, 3), dtype=np.float32) if frame is None else frame[y0:y0 + h, x:x + w]
        rays = [0, 0, 0, 0]
        effects: Set[str] = set()
        rows = max(1, h // 8)
        began = time.time()
        y = y0
        try:
            while True:
                with self._lock:
                    if y >= state.stop:
                        break
                    n = min(rows, state.stop - y)
                    state.next = y + n  # these rows are this worker's now
                t0 = time.perf_counter()
                if _test_delay:
                    time.sleep(_test_delay)
                image = _render_here(scene, camera, size, threads=threads, progress=False, window=(x, y, w, n),
                                     **options)
                pixels[y - y0:y - y0 + n] = np.asarray(image)
                s = image.stats
                assert s is not None
                for i, v in enumerate((s.primary, s.shadow, s.reflected, s.refracted)):
                    rays[i] += v
                effects.update(s.effects)
                per_row = max(1e-6, time.perf_counter() - t0) / n
                with self._lock:
                    state.row_seconds = per_row
                rows = max(1, min(h, int(CHUNK_SECONDS / per_row)))
                y += n
        finally:
            with self._lock:
                del self._bands[band]
                self._finished.add(band)
        ended = time.time()
        sent = None if frame is not None else pixels[:y - y0]
        return (sent, (rays[0], rays[1], rays[2], rays[3], tuple(sorted(effects))), where, threads, began, ended,
                y - y0)

    async def split(self, band: int, start: int, share: float = 0.5) -> Optional[int]:
        """Give up the last `share` of the rows of band `band` (which begins
        at row `start`) not yet begun: returns the row the worker now stops
        before (the rows from there to the band's end are the caller's), or
        None when none are given up (the band finished, or too little of it
        is left to be worth it). A band not begun yet is given up whole."""
        with self._lock:
            state = self._bands.get(band)
            if state is None:
                if band in self._finished:
                    return None
                self._stops[band] = start  # not begun: when it comes, it renders nothing
                return start
            left = state.stop - state.next
            if left < 2 or (state.row_seconds is not None and left * state.row_seconds < MIN_SPLIT_SECONDS):
                return None
            state.stop -= max(1, min(left - 1, round(left * share)))
            return state.stop

    async def stop(self) -> None:
        """The run is over (or interrupted): end every band at its current
        chunk, begin none."""
        with self._lock:
            self._stopped = True
            for state in self._bands.values():
                state.stop = state.next

"""Which window of which frame each worker renders next: the scheduling
logic of hitray.distributed, with no Dask in it (so it is tested alone,
deterministically, with made-up timings).

A task is a band: full-width rows of one frame (or, with a fixed `tile`,
one tile), rendered by a worker on all its threads. Bands are sized by
measurement, guided self-scheduling: a worker's next band is worth
`share` of the time the whole cluster needs for the work not yet handed
out, at that worker's measured speed, and never under `min_seconds` of
its time (so each task's fixed cost stays a small share of it). Early
bands are long (whole frames of an animation while there are many), the
last ones short, so every worker finishes within about one short band of
the others. A worker's first band, before anything is measured, is a
probe: a slice of the frame small enough that a slow worker cannot hold
the frame up. A band given back (its worker lost) goes back to the front
of the work and is handed on cut to size: split among the workers left.

Rows of an image do not cost the same (sky against a glass sphere), so a
frame about to be cut is first weighed: `row_costs(frame)` gives each
row's relative cost (the client measures it by the rays of a small, cheap
render of the frame), and bands are sized in that work, not in pixels.
A worker that would be idle at the end, with nothing left to hand out,
takes the rest of another worker's work: `victims` lists the bands it could
take (waiting ones first, then the largest being rendered), and `split`
records what the other worker gave up (the client asks the worker's actor
which rows it has not begun). The cost model (_model.py) does not split:
there an idle worker takes the band waiting longest behind another's
(`steal`).
"""

from __future__ import annotations

import bisect
import math
from typing import Callable, Dict, Hashable, List, NamedTuple, Optional, Sequence, Tuple

__all__ = ["Band", "Planner"]

Window = Tuple[int, int, int, int]


class Band(NamedTuple):
    frame: int  # the frame's place in the run (0, 1, ... in the order given)
    window: Window  # x, y, w, h

    @property
    def pixels(self) -> int:
        return self.window[2] * self.window[3]


class _Speed:
    """A worker's measured speed (work over render seconds, all its bands),
    and the bands it holds (the first being rendered, the rest waiting
    behind it, in order)."""

    __slots__ = ("work", "seconds", "held")

    def __init__(self) -> None:
        self.work, self.seconds = 0.0, 0.0
        self.held: List[Band] = []

    def rate(self) -> Optional[float]:
        return self.work / self.seconds if self.work > 0 and self.seconds > 0 else None


class Planner:
    """Hands out bands of `frames` frames of `size` pixels to workers.

    Frames are opened in order, at most `open_frames` at a time (the
    client holds one image per open frame); a frame closes when all its
    pixels are back. With `tile` set, the bands are fixed tiles of that
    side instead, handed out in order (and not sized).
    """

    def __init__(self, size: Tuple[int, int], frames: int, *, open_frames: int = 2,
                 tile: Optional[int] = None, share: float = 1 / 3, min_seconds: float = 0.1,
                 probe_share: float = 1 / 16,
                 row_costs: Optional[Callable[[int], Sequence[float]]] = None) -> None:
        if frames < 0 or open_frames < 1:
            raise ValueError("Planner: frames must be >= 0 and open_frames >= 1")
        self.width, self.height = size
        self.frames, self.open_frames, self.tile = frames, open_frames, tile
        self.share, self.min_seconds, self.probe_share = share, min_seconds, probe_share
        self._next_frame = 0
        # Open frames: their windows not handed out (sorted by y, x) and
        # their pixels not yet back.
        self._free: Dict[int, List[Window]] = {}
        self._missing: Dict[int, int] = {}
        self._speed: Dict[Hashable, _Speed] = {}
        # A frame's weighed rows: the running sum of its rows' costs (mean
        # 1, so a frame's work is its pixels), from row_costs when it is
        # first cut; frames not weighed count every row the same.
        self.row_costs = row_costs
        self._sums: Dict[int, List[float]] = {}

    # --- workers -------------------------------------------------------------
    def add_worker(self, worker: Hashable) -> None:
        self._speed.setdefault(worker, _Speed())

    def remove_worker(self, worker: Hashable) -> List[Band]:
        """A worker lost: its bands not back are given back (and returned)."""
        speed = self._speed.pop(worker, None)
        lost = [] if speed is None else speed.held
        for band in lost:
            self.give_back(band)
        return lost

    def held(self, worker: Hashable) -> int:
        """Bands the worker holds (handed out, not back)."""
        speed = self._speed.get(worker)
        return 0 if speed is None else len(speed.held)

    @property
    def workers(self) -> List[Hashable]:
        return list(self._speed)

    def rate(self, worker: Hashable) -> Optional[float]:
        """The worker's measured pixels per second; for one not measured
        yet, the mean of those that are (None if none is)."""
        speed = self._speed.get(worker)
        mine = speed.rate() if speed is not None else None
        if mine is not None:
            return mine
        known = [r for r in (s.rate() for s in self._speed.values()) if r is not None]
        return sum(known) / len(known) if known else None

    # --- work ------------------------------------------------------------------
    def _open(self) -> bool:
        if self._next_frame >= self.frames or len(self._missing) >= self.open_frames:
            return False
        f = self._next_frame
        self._next_frame += 1
        w, h = self.width, self.height
        if self.tile is None:
            self._free[f] = [(0, 0, w, h)]
        else:
            t = self.tile
            self._free[f] = [(x, y, min(t, w - x), min(t, h - y)) for y in range(0, h, t) for x in range(0, w, t)]
        self._missing[f] = w * h
        return True

    def work(self, frame: int, window: Window) -> float:
        """A window's work: its pixels, weighted by its rows' costs."""
        x, y, w, h = window
        sums = self._sums.get(frame)
        return w * (h if sums is None else sums[y + h] - sums[y])

    def _weigh(self, frame: int) -> None:
        if self.row_costs is None or frame in self._sums:
            return
        costs = [max(0.0, float(c)) for c in self.row_costs(frame)]
        total = sum(costs)
        if len(costs) != self.height or not total > 0:
            raise ValueError(f"Planner: row_costs gave {len(costs)} costs summing to {total} for "
                             f"{self.height} rows")
        sums = [0.0]
        for c in costs:
            sums.append(sums[-1] + c * self.height / total)
        self._sums[frame] = sums

    def remaining(self) -> float:
        """Work not handed out yet: in open frames and in frames to come."""
        free = sum(self.work(f, win) for f, wins in self._free.items() for win in wins)
        return free + (self.frames - self._next_frame) * self.width * self.height

    def _band_work(self, worker: Hashable) -> float:
        """How much work the worker's next band should hold."""
        frame = self.width * self.height
        rate = self.rate(worker)
        if rate is None:  # a probe: nothing is measured yet
            return max(1.0, min(frame, self.remaining() * self.probe_share / max(1, len(self._speed))))
        total_rate = sum(self.rate(w) or rate for w in self._speed) or rate
        seconds = max(self.min_seconds, self.remaining() / total_rate * self.share)
        return rate * seconds

    def next_band(self, worker: Hashable = None) -> Optional[Band]:
        """The next band for `worker` (with fixed tiles, the next tile,
        whoever asks), or None: nothing to hand out until a frame closes."""
        if worker is not None:
            self.add_worker(worker)
        while True:
            frame = next((f for f in sorted(self._free) if self._free[f]), None)
            if frame is not None or not self._open():
                break
        if frame is None:
            return None
        free = self._free[frame]
        if self.tile is not None:
            return self._hold(worker, Band(frame, free.pop(0)))
        want = self._band_work(worker)
        if want < self.work(frame, free[0]):
            self._weigh(frame)
        x, y, w, h = free.pop(0)
        sums = self._sums.get(frame)
        if sums is None:
            rows = max(1, math.ceil(want / w))
        else:  # the fewest rows holding that much work
            rows = max(1, bisect.bisect_left(sums, sums[y] + want / w, y + 1, y + h + 1) - y)
        if h - rows < max(1, rows // 4):  # no sliver left behind: take it all
            rows = h
        if rows < h:
            free.insert(0, (x, y + rows, w, h - rows))
        return self._hold(worker, Band(frame, (x, y, w, rows)))

    def _hold(self, worker: Hashable, band: Band) -> Band:
        if worker is not None:
            self._speed[worker].held.append(band)
        return band

    def steal(self, worker: Hashable) -> Optional[Tuple[Hashable, Band]]:
        """For an idle `worker` when no work is left to hand out: the band
        waiting longest behind another worker's (the last one held by the
        worker with the most seconds of work ahead of it), given back so
        that next_band hands it on; None if no band waits. Returns the
        worker it was taken from and the band (the caller cancels its
        task)."""
        if self.tile is not None or any(self._free.values()) or self._next_frame < self.frames:
            return None
        best: Optional[Tuple[float, Hashable]] = None
        for other, speed in self._speed.items():
            if other == worker or len(speed.held) < 2:
                continue
            rate = self.rate(other) or 1.0
            ahead = sum(self.work(b.frame, b.window) for b in speed.held[:-1]) / rate
            if best is None or ahead > best[0]:
                best = (ahead, other)
        if best is None:
            return None
        band = self._speed[best[1]].held.pop()
        self.give_back(band)
        return best[1], band

    def victims(self, worker: Hashable) -> List[Tuple[Hashable, Band]]:
        """For an idle `worker` when no work is left to hand out: the bands
        of other workers whose rest could be split off and handed to it,
        the most promising first: a band waiting behind another (it is
        given up whole), then the bands being rendered, the largest (in
        work) first. Empty while there is work to hand out."""
        if self.tile is not None or any(self._free.values()) or self._next_frame < self.frames:
            return []
        waiting = [(other, b) for other, speed in self._speed.items() if other != worker for b in speed.held[1:]]
        running = [(other, speed.held[0]) for other, speed in self._speed.items() if other != worker and speed.held]
        running.sort(key=lambda ob: -self.work(ob[1].frame, ob[1].window))
        return waiting + running

    def split(self, worker: Hashable, band: Band, at: int, to: Hashable = None) -> Optional[Band]:
        """`worker`, rendering `band`, gave up its rows from `at` on: it
        holds the rows above, and the rest is a band of its own, held by
        `to` (returned); None if `worker` no longer holds the band."""
        speed = self._speed.get(worker)
        if speed is None or band not in speed.held:
            return None
        x, y, w, h = band.window
        if not y <= at < y + h:
            raise ValueError(f"Planner: split at row {at} outside the band {band}")
        i = speed.held.index(band)
        if at == y:
            del speed.held[i]
        else:
            speed.held[i] = Band(band.frame, (x, y, w, at - y))
        rest = Band(band.frame, (x, at, w, y + h - at))
        if to is not None:
            self.add_worker(to)
        return self._hold(to, rest)

    def give_back(self, band: Band, forget: bool = False) -> None:
        """A band whose worker was lost: back to the front of the work
        (`forget`: and no longer held by the worker it was given to)."""
        if forget:
            self._release(band)
        bisect.insort(self._free.setdefault(band.frame, []), band.window, key=lambda v: (v[1], v[0]))

    def _release(self, band: Band) -> None:
        """The band is no longer held by the worker it was given to (it may
        have run elsewhere)."""
        for speed in self._speed.values():
            if band in speed.held:
                speed.held.remove(band)
                return

    def done(self, band: Band, worker: Hashable, seconds: float) -> bool:
        """A band came back from `worker` after `seconds` of rendering;
        True when that was its frame's last."""
        self._release(band)
        speed = self._speed.get(worker)
        if speed is not None and seconds > 0:
            speed.work += self.work(band.frame, band.window)
            speed.seconds += seconds
        self._missing[band.frame] -= band.pixels
        if self._missing[band.frame] > 0:
            return False
        del self._missing[band.frame]
        if not self._free.get(band.frame):
            self._free.pop(band.frame, None)
        self._sums.pop(band.frame, None)
        return True

    def finished(self) -> bool:
        return not self._missing and self._next_frame >= self.frames

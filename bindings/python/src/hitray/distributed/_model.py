"""A cost model of a distributed run: hitray.distributed's own Planner
played against simulated workers, with costs measured on a real run
(bench/drivers/distributed.py measures them and prints the table of
docs/distributed.md).

What is simulated (in simulated seconds, no clock):
- the scene shipped to the workers first: `ship` seconds per copy, copies
  made along a binary tree (Dask replicates a scattered value between
  workers), so ceil(log2(workers + 1)) copies long;
- a worker renders its bands one after the other, each in its work times
  `pixel` seconds over its `threads` (threads assumed to scale perfectly
  within a band), plus `task` seconds of its own per band (taking the task
  in, sending the pixels back);
- the client and the scheduler are one serial "hub": each band costs it
  `hub` seconds plus `hub_pixel` per pixel coming back (unpickling and
  placing them); a band is handed to a worker when the hub is done with the
  band before it. Each worker holds two bands, as the client does;
- an animation's frames are written by one writer thread, one at a time,
  `save_pixel` seconds per pixel, while the hub goes on; when a frame is
  complete the hub first waits for the last one's write (render_frames
  does so).

Efficiency is the rendering work (pixels x `pixel` seconds, summed over
frames) over the cluster's core time (wall x workers x threads).
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

from ._plan import Band, Planner

__all__ = ["Costs", "Outcome", "simulate"]


@dataclass(frozen=True)
class Costs:
    pixel: float  # one core's seconds per pixel of the frame, at its spp
    task: float = 0.0  # a worker's seconds per band beyond rendering
    hub: float = 0.0  # the client's and scheduler's seconds per band
    hub_pixel: float = 0.0  # the client's seconds per pixel coming back
    save_pixel: float = 0.0  # the client's seconds per pixel of a frame written
    ship: float = 0.0  # seconds to copy the scene to one worker


@dataclass(frozen=True)
class Outcome:
    wall: float
    efficiency: float
    tasks: int
    balance: float  # the slowest worker's busy time over the mean


def simulate(costs: Costs, size: Tuple[int, int], frames: int, workers: int, threads: float,
             row_costs: Optional[Sequence[float]] = None, open_frames: Optional[int] = None,
             min_seconds: float = 0.1, depth: int = 2, save: Optional[bool] = None) -> Outcome:
    """Simulate `frames` frames of `size` on `workers` workers of `threads`
    cores each (a fraction models workers time-sliced on fewer cores).
    `row_costs`: the relative cost of the frame's rows (any length: it is
    stretched to the frame's height), None for rows of equal cost. `save`:
    whether the client writes each frame (default: for an animation, as
    render_frames does; render returns its one frame)."""
    save = frames > 1 if save is None else save
    w, h = size
    if row_costs is not None:
        n = len(row_costs)
        weights = [float(row_costs[min(n - 1, y * n // h)]) for y in range(h)]
        mean = sum(weights) / h
        weights = [c / mean for c in weights]
    planner = Planner(size, frames, open_frames=open_frames or max(2, 2 * workers), min_seconds=min_seconds,
                      row_costs=None if row_costs is None else (lambda f: weights))
    speed = threads / costs.pixel  # pixels (of work) a second, one worker
    names = [f"w{i}" for i in range(workers)]
    for name in names:
        planner.add_worker(name)
    ready = math.ceil(math.log2(workers + 1)) * costs.ship
    queue: Dict[str, List[Tuple[Band, float]]] = {n: [] for n in names}  # band, when it reached the worker
    free = {n: ready for n in names}  # when the worker is done with what it has started
    busy = {n: 0.0 for n in names}
    events: List[Tuple[float, int, str, Band, float]] = []
    hub = ready
    writer = ready  # when the writer thread is done with the last frame
    order = 0
    tasks = 0

    def start(name: str) -> None:
        nonlocal order
        if not queue[name] or any(e[2] == name for e in events):
            return
        band, arrived = queue[name][0]
        began = max(free[name], arrived)
        seconds = planner.work(band.frame, band.window) / speed
        free[name] = began + seconds + costs.task
        busy[name] += seconds
        order += 1
        heapq.heappush(events, (free[name], order, name, band, seconds))

    def fill(name: str) -> None:
        nonlocal hub, tasks
        while len(queue[name]) < depth:
            band = planner.next_band(name)
            if band is None and not queue[name]:
                stolen = planner.steal(name)
                if stolen is not None:
                    victim = str(stolen[0])
                    queue[victim] = [q for q in queue[victim] if q[0] != stolen[1]]
                    band = planner.next_band(name)
            if band is None:
                return
            hub += costs.hub / 2  # submitting: half of the band's cost to the hub
            tasks += 1
            queue[name].append((band, hub))
            start(name)

    for _ in range(depth):
        for name in names:
            fill(name)
    end = ready
    while events:
        t, _, name, band, seconds = heapq.heappop(events)
        queue[name].pop(0)
        hub = max(hub, t) + costs.hub / 2 + band.pixels * costs.hub_pixel
        if planner.done(band, name, seconds) and save:
            hub = max(hub, writer)
            writer = hub + w * h * costs.save_pixel
        end = max(end, hub, writer)
        start(name)
        fill(name)
        for other in names:  # an idle worker may steal now
            if not queue[other]:
                fill(other)
    work = frames * w * h * costs.pixel
    mean = sum(busy.values()) / workers
    return Outcome(end, work / (end * workers * threads), tasks, max(busy.values()) / mean if mean > 0 else 1.0)

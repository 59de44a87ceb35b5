"""What a distributed run did, worker by worker: rays per second, the share
of the cluster's core time not spent rendering, and the balance."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List

__all__ = ["Report", "WorkerReport"]


@dataclass
class WorkerReport:
    """One worker's part: its tasks, and the seconds it spent rendering
    them (on `threads` threads)."""

    address: str
    threads: int = 1
    tasks: int = 0
    pixels: int = 0
    rays: int = 0
    busy: float = 0.0  # seconds rendering, all its tasks
    first: float = math.inf  # the worker's clock when its first task began
    last: float = -math.inf  # ... and when its last one ended
    split: int = 0  # bands it was rendering whose rows not begun went to another worker

    @property
    def rays_per_second(self) -> float:
        return self.rays / self.busy if self.busy > 0 else 0.0

    @property
    def between(self) -> float:
        """Seconds between its first task's start and its last one's end
        not spent rendering: what a task costs on the worker beyond its rays
        (receiving it, returning the pixels), and any wait for the next."""
        return max(0.0, self.last - self.first - self.busy) if self.tasks else 0.0


@dataclass
class Report:
    """A run on the cluster (``hitray.distributed.render(..., report=r)``
    fills `r` in).

    Attributes:
        wall: seconds from the run's start on the cluster (before the scene
            is shipped and the rows weighed) to the last pixels back.
        tasks: tasks run (bands, or tiles with a fixed `tile`).
        frames: frames completed.
        splits: bands whose rows not yet begun were taken from the worker
            rendering them and handed to an idle one.
        workers: by address.
    """

    wall: float = 0.0
    tasks: int = 0
    frames: int = 0
    pixels: int = 0
    splits: int = 0
    workers: Dict[str, WorkerReport] = field(default_factory=dict)

    @property
    def threads(self) -> int:
        """Render threads across the workers (the cluster's cores)."""
        return sum(w.threads for w in self.workers.values())

    @property
    def rendering(self) -> float:
        """Core-seconds spent rendering."""
        return sum(w.busy * w.threads for w in self.workers.values())

    @property
    def overhead_share(self) -> float:
        """The share of the cluster's core time (wall x threads) not spent
        rendering: scheduling, shipping, moving pixels, idle workers."""
        total = self.wall * self.threads
        return max(0.0, 1.0 - self.rendering / total) if total > 0 else 0.0

    @property
    def overhead_per_task(self) -> float:
        """Core-seconds not spent rendering, per task."""
        return max(0.0, self.wall * self.threads - self.rendering) / self.tasks if self.tasks else 0.0

    @property
    def between_per_task(self) -> float:
        """Seconds a worker spent between consecutive tasks, on average: the
        per-task cost on the worker's side alone."""
        gaps = sum(max(0, w.tasks - 1) for w in self.workers.values())
        return sum(w.between for w in self.workers.values()) / gaps if gaps else 0.0

    @property
    def balance(self) -> float:
        """The slowest worker's busy time over the mean (1: balanced)."""
        busy = [w.busy for w in self.workers.values() if w.tasks]
        mean = sum(busy) / len(busy) if busy else 0.0
        return max(busy) / mean if mean > 0 else 1.0

    def lines(self) -> List[str]:
        """The report as text, one line per worker then the totals."""
        out = []
        for w in sorted(self.workers.values(), key=lambda w: w.address):
            out.append(f"  {w.address}: {w.tasks} tasks, {w.threads} thread{'s' if w.threads != 1 else ''}, "
                       f"busy {w.busy:.2f} s, {w.split} split, "
                       f"{w.rays_per_second / 1e6:.2f} Mrays/s")
        out.append(f"  {self.tasks} tasks on {len(self.workers)} workers ({self.threads} render threads) in "
                   f"{self.wall:.2f} s: overhead {100 * self.overhead_share:.1f}% of the core time "
                   f"({1e3 * self.overhead_per_task:.1f} core-ms per task, "
                   f"{1e3 * self.between_per_task:.1f} ms between tasks on a worker), "
                   f"balance {self.balance:.2f}, {self.splits} band{'' if self.splits == 1 else 's'} split")
        return out

"""Frames cut into windows (hr_render_options' window), rendered as Dask
tasks on the cluster's workers and put back together.

Each window is a plain hitray.render of that rectangle, whose pixels are the
full render's bits, so the frame is the same image, bit for bit, however it
is cut and wherever each piece ran. A task is a pure function of its inputs
(the shipped scene, camera, size, options, window): when a worker is lost,
Dask runs its tasks again elsewhere and they give the same bits.
"""

from __future__ import annotations

import collections
import concurrent.futures
import contextlib
import queue
import threading
import os
import stat
import time
import uuid
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Set, Tuple, Union

import numpy as np

from .. import _convert, _progress
from ..camera import Camera
from ..image import Image, RenderStats
from ..render import render as _render_here
from ..scene import Scene
from ._client import connect, dask_distributed, local_cores
from ._band import NEED_SCENE, BandWorker
from ._pack import ScenePack
from ._shared import FrameBuffer
from ._plan import Band, Planner
from ._report import Report, WorkerReport

__all__ = ["render", "render_frames"]

Window = Tuple[int, int, int, int]
Progress = Union[None, bool, Callable[[float], Any]]
FrameSource = Union[Sequence[Tuple[Scene, Optional[Camera]]], Callable[[int], Tuple[Scene, Optional[Camera]]]]


def windows(size: Tuple[int, int], tile: int) -> List[Window]:
    """The windows of `tile` x `tile` pixels that cover an image of `size`,
    row by row (the last of each row and column cut by the edge)."""
    w, h = size
    return [(x, y, min(tile, w - x), min(tile, h - y)) for y in range(0, h, tile) for x in range(0, w, tile)]


# One band at a time in a worker process: a band renders on all the
# worker's threads, so while one renders, a band given to the worker's
# other Dask threads waits here.
_BAND_LOCK = threading.Lock()


def _worker() -> Tuple[str, int]:
    """This worker's address and Dask threads (on a client's local run:
    "local" and this machine's cores)."""
    try:
        w = dask_distributed().get_worker()
    except ValueError:
        return "local", local_cores()
    return w.address, int(w.state.nthreads)


def _cancelled() -> bool:
    """Whether the task running here was cancelled (a band taken by an idle
    worker while it waited for the band lock): then it need not render."""
    try:
        w = dask_distributed().get_worker()
        ts = w.state.tasks.get(w.get_current_task())
    except (ValueError, AttributeError, KeyError):  # not on a worker, or Dask's internals moved
        return False
    return ts is not None and ts.state == "cancelled"


def render_window(pack: ScenePack, camera: Camera, size: Tuple[int, int], options: Dict[str, Any],
                  window: Window, threads: Optional[int] = None) -> Optional[Tuple[Any, ...]]:
    """The task: one window of the frame, on a worker, on `threads` threads
    (None: all the worker's). Returns its pixels, its rays (primary, shadow,
    reflected, refracted, effects), the worker, the threads it rendered on,
    and the worker's clock (time.time) when rendering began and ended; None
    if it was cancelled before it began."""
    where, nthreads = _worker()
    threads = nthreads if threads is None else threads
    scene = pack.scene()
    with _BAND_LOCK if threads == nthreads else contextlib.nullcontext():
        if _cancelled():
            return None
        began = time.time()
        image = _render_here(scene, camera, size, threads=threads, progress=False, window=window, **options)
        ended = time.time()
    s = image.stats
    assert s is not None
    rays = (s.primary, s.shadow, s.reflected, s.refracted, tuple(sorted(s.effects)))
    return np.asarray(image), rays, where, threads, began, ended


def row_costs(scene: Scene, camera: Camera, size: Tuple[int, int], options: Dict[str, Any],
              width: int = 160, bands: int = 16) -> List[float]:
    """Each row's relative cost in a frame of `size`: the rays cast by the
    rows of a small render of it (about `width` pixels wide, 1 sample per
    pixel, one thread), in `bands` windows. Rays, not seconds: the same
    answer on any machine, however busy. Costs a few hundredths of the
    frame at 1 spp."""
    w, h = size
    k = max(1, w // width)
    sw, sh = max(1, w // k), max(1, h // k)
    cheap = dict(options, spp=1, adaptive=None, block_size=None, block=None)
    n = min(bands, sh)
    edges = [round(i * sh / n) for i in range(n + 1)]
    density = []
    for y0, y1 in zip(edges, edges[1:]):
        s = _render_here(scene, camera, (sw, sh), threads=1, progress=False, window=(0, y0, sw, y1 - y0),
                         **cheap).stats
        assert s is not None
        density.append(max(1, s.rays) / (y1 - y0))
    # Row y of the frame lies in row y * sh // h of the small render.
    band_of = [0] * sh
    for i, (y0, y1) in enumerate(zip(edges, edges[1:])):
        band_of[y0:y1] = [i] * (y1 - y0)
    return [density[band_of[min(sh - 1, y * sh // h)]] for y in range(h)]


def _options(spp: int, depth: Optional[int], block: Optional[int], effects: str,
             adaptive: Optional[float], min_weight: Optional[float], exact: bool,
             block_size: Optional[int], all_effects: bool, texture_filter: str) -> Dict[str, Any]:
    """hitray.render's keywords, passed on as given (it checks them)."""
    return {"spp": spp, "depth": depth, "block": block, "effects": effects, "adaptive": adaptive,
            "min_weight": min_weight, "exact": _convert.flag(exact, "render: exact"),
            "block_size": block_size, "all_effects": _convert.flag(all_effects, "render: all_effects"),
            "texture_filter": texture_filter}


def _check_here(scene: Scene, camera: Optional[Camera], size: Tuple[int, int],
                options: Dict[str, Any]) -> Camera:
    """Check the scene, camera and options on this machine, as hitray.render
    does (one pixel rendered), so a mistake raises here with the library's
    message, not on a worker; returns the camera the frame uses."""
    if not isinstance(scene, Scene):
        raise TypeError(f"hitray.distributed: expected a hitray.Scene, got {type(scene).__name__}")
    if camera is None:
        camera = scene.frame_camera(size)
    elif not isinstance(camera, Camera):
        raise TypeError(f"hitray.distributed: camera must be a hitray.Camera or None, "
                        f"not {type(camera).__name__}")
    _render_here(scene, camera, size, threads=1, progress=False, window=(0, 0, 1, 1), **options)
    return camera


class _Frame:
    """One frame on its way: its pixels as they come back."""

    def __init__(self, index: int, path: Optional[str], size: Tuple[int, int], pack_key: str,
                 camera: Camera, shared: bool = False) -> None:
        self.index, self.path, self.pack_key, self.camera = index, path, pack_key, camera
        # Workers on this machine write their rows straight into it.
        self.buffer = FrameBuffer.make(size) if shared else None
        pixels = None if self.buffer is None else self.buffer.pixels
        self.pixels: np.ndarray = np.empty((size[1], size[0], 3), dtype=np.float32) if pixels is None else pixels
        self.rays = [0, 0, 0, 0]
        self.effects: Set[str] = set()
        self.workers: Dict[str, int] = {}
        self.started = time.monotonic()
        self.scene: Optional[Scene] = None
        self.number = -1  # its place in the run (the planner's frame number)

    def place(self, window: Window, result: Tuple[Any, ...]) -> None:
        pixels, rays, where, threads = result[:4]
        x, y, w, h = window
        if pixels is None:  # written into the shared frame
            if self.buffer is None:
                raise RuntimeError("hitray.distributed: a worker sent no pixels for a frame not shared")
        elif pixels.shape != (h, w, 3):
            raise RuntimeError(f"hitray.distributed: a worker returned {pixels.shape} pixels for the "
                               f"{w}x{h} window at ({x}, {y})")
        else:
            self.pixels[y:y + h, x:x + w] = pixels
        for i in range(4):
            self.rays[i] += rays[i]
        self.effects.update(rays[4])
        self.workers[where] = max(self.workers.get(where, 0), threads)

    def image(self) -> Image:
        """The frame's Image (its pixels copied: a shared frame is released)."""
        image = Image(self.pixels)
        self.close()
        image._stats = RenderStats(sum(self.workers.values()), self.rays[0], self.rays[1], self.rays[2],
                                   self.rays[3], time.monotonic() - self.started, frozenset(self.effects))
        return image

    def close(self) -> None:
        if self.buffer is not None:
            self.pixels = np.empty((0, 0, 3), dtype=np.float32)
            self.buffer.close()
            self.buffer = None


class _Bar:
    """Progress over pixels: a tqdm bar, a callable given the fraction done,
    or nothing."""

    def __init__(self, progress: Progress, total: int, what: str) -> None:
        self._callback: Optional[Callable[[float], Any]] = None
        self._bar: Any = None
        self._done, self._total = 0, max(1, total)
        if callable(progress):
            self._callback = progress
        elif progress is None or isinstance(progress, bool):
            # None: a bar where someone watches (standard error a terminal,
            # or a notebook), as hitray.render and the hitray command do.
            if _progress.wanted(progress):
                self._bar = _progress.tqdm_class()(total=total, unit="px", unit_scale=True, desc=what,
                                                   leave=False)
        else:
            raise TypeError("hitray.distributed: progress must be None (auto), True, False or a callable "
                            "taking the fraction done")

    def pixels(self, n: int) -> None:
        self._done += n
        if self._bar is not None:
            self._bar.update(n)
        elif self._callback is not None:
            self._callback(self._done / self._total)

    def frame(self, done: int, total: int) -> None:
        if self._bar is not None:
            self._bar.set_postfix_str(f"frames {done}/{total}")

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()


class _Shipped:
    """A scene scattered to the workers, and the frames in flight using it."""

    __slots__ = ("future", "users", "pack")

    def __init__(self, future: Any, pack: ScenePack) -> None:
        self.future, self.users, self.pack = future, 0, pack


def _same_description(a: Tuple[Any, List[Any], Dict[str, Any]], b: Tuple[Any, List[Any], Dict[str, Any]]) -> bool:
    """Whether two descriptions of a Scene (Scene._description) are the
    same: the same source and recorded operations (each is never changed
    once recorded), equal globals."""
    return (a[0] is b[0] and len(a[1]) == len(b[1]) and all(x is y for x, y in zip(a[1], b[1]))
            and a[2] == b[2])


class _Run:
    """Bands of frames on a client (the Planner says which): each worker
    holds `DEPTH` bands (one rendering, the next waiting, so it never waits
    on the client), scenes shipped once each (scattered to every worker),
    frames handed back as they complete.

    Bands sized by measurement go to one actor per worker (_band.BandWorker),
    called straight from the client, with no scheduler round trip per band.
    A worker left with nothing to do takes the rest of another's band: the
    band waiting behind it whole, or the rows not begun of the one being
    rendered (the actor renders in chunks and gives up the rows it has not
    begun), so a slow worker's band is split and handed on. A worker that
    leaves has its bands not yet back given back to the planner, which
    hands them on cut to size.

    With a fixed tile size, every tile of the open frames is a Dask task,
    submitted at once, and Dask places them."""

    # Scenes no frame in flight uses stay on the workers, this many of the
    # latest, for the next frames (an animation of one scene ships it once);
    # older ones are dropped, so a run of many scenes holds few at a time.
    KEEP_IDLE = 2
    # Bands held by a worker at once.
    DEPTH = 2
    # How often, waiting for bands, the client asks the scheduler which
    # workers there are (seconds; a lost worker's actor also says so as soon
    # as a call to it fails).
    CHECK_WORKERS = 1.0

    def __init__(self, client: Any, size: Tuple[int, int], options: Dict[str, Any], planner: Planner,
                 threads: Optional[int], bar: _Bar, frame_at: Callable[[int], Tuple[int, Optional[str], Scene,
                                                                            Camera]],
                 report: Optional[Report]) -> None:
        self.client, self.size, self.options, self.bar = client, size, options, bar
        self.planner, self.threads, self.frame_at = planner, threads, frame_at
        self.report = report if report is not None else Report()
        self.run_id = uuid.uuid4().hex
        self.sized = planner.tile is None
        self.frames: Dict[int, _Frame] = {}
        # The tasks out: future -> band, and band -> future.
        self.out: Dict[Any, Band] = {}
        self.by_band: Dict[Band, Any] = {}
        self.submitted = 0
        self.done: "queue.Queue[Any]" = queue.Queue()
        self.shipped: "collections.OrderedDict[str, _Shipped]" = collections.OrderedDict()
        # id(scene) -> (the scene, kept so the id stays its own; its
        # description when packed; the pack).
        self.by_scene: Dict[int, Tuple[Scene, Any, ScenePack]] = {}
        self.known: Set[str] = set()
        # Bands sized by measurement: the actors by worker; the calls out,
        # band number -> (worker, the band as it stands after splits);
        # workers whose actor stopped answering; idle workers waiting for a
        # split's answer; bands that would not split.
        self.actors: Dict[str, Any] = {}
        self.actor_futures: Dict[str, Any] = {}
        self.calls: Dict[int, Tuple[str, Band]] = {}
        self.dead: Set[str] = set()
        self.splitting: Set[str] = set()
        # Bands with a split asked for and not answered: one at a time, so
        # the answers come back in the order the worker gave them.
        self.being_split: Set[int] = set()
        self.unsplittable: Set[int] = set()
        if self.sized and planner.row_costs is None:
            planner.row_costs = self._row_costs
        self.checked = 0.0
        self.started = time.monotonic()

    def _pack(self, scene: Scene) -> ScenePack:
        """The scene's pack: made again only if the scene changed since."""
        description = scene._description()
        known = self.by_scene.get(id(scene))
        if known is None or not _same_description(known[1], description):
            known = self.by_scene[id(scene)] = (scene, description, ScenePack(scene))
        return known[2]

    def _frame(self, n: int) -> _Frame:
        frame = self.frames.get(n)
        if frame is None:
            index, path, scene, camera = self.frame_at(n)
            pack = self._pack(scene)
            shipped = self.shipped.get(pack.key)
            if shipped is None:
                shipped = self.shipped[pack.key] = _Shipped(self.client.scatter(pack, broadcast=True, hash=False),
                                                              pack)
            self.shipped.move_to_end(pack.key)
            shipped.users += 1
            frame = self.frames[n] = _Frame(index, path, self.size, pack.key, camera, shared=self.sized)
            frame.scene, frame.number = scene, n
        return frame

    def _row_costs(self, n: int) -> List[float]:
        frame = self._frame(n)
        assert frame.scene is not None
        return row_costs(frame.scene, frame.camera, self.size, self.options)

    def _submit(self, worker: Optional[str]) -> bool:
        """Submit the next tile as a Dask task (fixed tiles)."""
        band = self.planner.next_band(worker)
        if band is None:
            return False
        frame = self._frame(band.frame)
        x, y, w, h = band.window
        where = {} if worker is None else {"workers": [worker], "allow_other_workers": True}
        self.submitted += 1
        future = self.client.submit(render_window, self.shipped[frame.pack_key].future, frame.camera, self.size,
                                    self.options, band.window, self.threads,
                                    key=f"hitray-tile-{self.run_id}-{frame.index}-{x}-{y}-{w}-{h}-{self.submitted}",
                                    pure=False, priority=-band.frame, **where)
        self.out[future] = band
        self.by_band[band] = future
        future.add_done_callback(self.done.put)
        return True

    def _cancel(self, bands: List[Band]) -> None:
        """Forget the tasks of bands given back (a result that comes anyway
        is ignored: the band is rendered again elsewhere, to the same bits)."""
        futures = [self.by_band.pop(b) for b in bands if b in self.by_band]
        for future in futures:
            self.out.pop(future, None)
        if futures:
            self.client.cancel(futures)

    def _workers(self) -> None:
        """Follow the scheduler's workers: new ones get bands, lost ones'
        bands not back are handed on."""
        self.checked = time.monotonic()
        now = set(self.client.scheduler_info()["workers"]) - self.dead
        for gone in self.known - now:
            self._lose(gone)
        new = sorted(now - self.known)
        if self.sized and new:
            futures = {w: self.client.submit(BandWorker, actor=True, workers=[w], allow_other_workers=False,
                                              pure=False, key=f"hitray-bands-{self.run_id}-{w}") for w in new}
            for w, future in futures.items():
                try:
                    self.actors[w] = future.result(timeout=max(10.0, 10 * self.CHECK_WORKERS))
                except Exception:  # noqa: BLE001 - a worker that went as it was joining: skip it
                    future.release()
                    now.discard(w)
                    continue
                self.actor_futures[w] = future
        for w in sorted(now - self.known):
            self.planner.add_worker(w)
        self.known = now

    def _lose(self, worker: str) -> None:
        """A worker gone: its bands not back are handed on."""
        self.known.discard(worker)
        if self.sized:
            for n in [n for n, (w, _) in self.calls.items() if w == worker]:
                del self.calls[n]
            self.actors.pop(worker, None)
            future = self.actor_futures.pop(worker, None)
            if future is not None:
                future.release()
            self.splitting.discard(worker)
            self.planner.remove_worker(worker)
        else:
            self._cancel(self.planner.remove_worker(worker))

    def _fill(self) -> None:
        if not self.sized:
            while self._submit(None):
                pass
            return
        if not self.known or time.monotonic() - self.checked > self.CHECK_WORKERS:
            self._workers()
        for _ in range(self.DEPTH):  # round-robin: every worker's first band before anyone's second
            for worker in sorted(self.known):
                if self.planner.held(worker) < self.DEPTH:
                    self._call(worker)
        for worker in sorted(self.known):
            if not self.planner.held(worker) and worker not in self.splitting:
                self._steal(worker)

    async def _wait(self, what: Tuple[Any, ...], future: Any) -> None:
        """An actor's answer, put on the queue the client's loop reads (this
        runs on Dask's event loop)."""
        try:
            result = await future
        except Exception as e:  # noqa: BLE001 - handed to the client's loop, which raises it or hands the band on
            result = e
        self.done.put((what, result))

    @staticmethod
    async def _release_after(answer: Any, future: Any) -> None:
        try:
            await answer
        except Exception:  # noqa: BLE001 - a worker gone: its actor with it
            pass
        future.release()

    def _call(self, worker: str, band: Optional[Band] = None) -> bool:
        """Send the worker's actor its next band (or `band`)."""
        if band is None:
            band = self.planner.next_band(worker)
            if band is None:
                return False
        self.submitted += 1
        self.calls[self.submitted] = (worker, band)
        self._send(self.submitted)
        return True

    def _send(self, n: int) -> None:
        worker, band = self.calls[n]
        frame = self._frame(band.frame)
        try:
            future = self.actors[worker].render(n, self.shipped[frame.pack_key].future.key, frame.camera,
                                                self.size, self.options, band.window, self.threads,
                                                None if frame.buffer is None else frame.buffer.name)
        except RuntimeError as e:  # Dask's Actor: its worker was lost before the list of workers said so
            self.done.put((("band", n, worker), OSError(str(e))))  # answered as a worker gone (_answer)
            return
        self.client.loop.add_callback(self._wait, ("band", n, worker), future)

    def _steal(self, worker: str) -> None:
        """An idle worker, nothing left to hand out: ask another's actor
        for the rest of a band."""
        by_band: Dict[Tuple[Any, Band], int] = {(w, b): n for n, (w, b) in self.calls.items()}
        for victim, band in self.planner.victims(worker):
            n = by_band.get((victim, band))
            if (n is None or n in self.unsplittable or n in self.being_split or not isinstance(victim, str)
                    or victim not in self.actors):
                continue
            try:
                answer = self.actors[victim].split(n, band.window[1])
            except RuntimeError:  # Dask's Actor: the victim's worker was lost, its bands go on through _lose
                self.unsplittable.add(n)
                continue
            self.splitting.add(worker)
            self.being_split.add(n)
            self.client.loop.add_callback(self._wait, ("split", n, worker, victim), answer)
            return

    def _split(self, n: int, at: int, to: Optional[str]) -> None:
        """Band `n` stops before row `at`: the rest goes to `to`, or back to
        the planner."""
        worker, band = self.calls[n]
        rest = self.planner.split(worker, band, at, to)
        assert rest is not None
        x, y, w, h = band.window
        if at == y:
            del self.calls[n]
        else:
            self.calls[n] = (worker, Band(band.frame, (x, y, w, at - y)))
        if to is None:
            self.planner.give_back(rest)
            return
        self.report.splits += 1
        if at > y:  # begun: the rest of a band being rendered
            self._worker_report(worker).split += 1
        self._call(to, rest)

    def _answer(self, what: Tuple[Any, ...], result: Any) -> Optional[_Frame]:
        """An actor's answer; the frame it completed, if it did."""
        if what[0] == "split":
            n, thief, victim = what[1:]
            self.splitting.discard(thief)
            self.being_split.discard(n)
            if isinstance(result, Exception) or result is None:
                self.unsplittable.add(n)
            elif n in self.calls and thief in self.known:
                self._split(n, result, thief)
            return None
        n, worker = what[1:]
        if n not in self.calls:
            return None  # its worker was lost, or the band was given up whole
        if isinstance(result, Exception):
            if isinstance(result, OSError) and worker in self.actors:  # the worker is not there any more
                self.dead.add(worker)
                self._lose(worker)
                return None
            raise result
        if isinstance(result, str) and result == NEED_SCENE:  # a worker that joined after the scene was shipped
            frame = self.frames[self.calls[n][1].frame]
            shipped = self.shipped[frame.pack_key]
            self.actors[worker].ship(shipped.future.key, shipped.pack).result()
            self._send(n)
            return None
        pixels, rays, where, threads, began, ended, rows = result
        _, band = self.calls[n]
        x, y, w, h = band.window
        if rows < h:  # a split gave up the rest, its answer not in yet
            self._split(n, y + rows, None)
            _, band = self.calls.get(n, (worker, Band(band.frame, (x, y, w, 0))))
        self.calls.pop(n, None)
        if not rows:
            return None
        return self._place(band, result[:6])

    def _place(self, band: Band, result: Tuple[Any, ...]) -> Optional[_Frame]:
        pixels, rays, where, threads, began, ended = result
        frame = self.frames[band.frame]
        frame.place(band.window, result)
        self._count(band, where, threads, rays, began, ended)
        complete = self.planner.done(band, where, ended - began)
        self.bar.pixels(band.pixels)
        return frame if complete else None

    def _next_done(self) -> Any:
        while True:
            try:
                item = self.done.get(timeout=self.CHECK_WORKERS)
            except queue.Empty:
                if self.sized:
                    self._workers()
                    self._fill()
                continue
            if self.sized or item in self.out:
                return item

    def frames_done(self) -> Iterator[_Frame]:
        """Frames as their last band comes back (a worker's failure raised)."""
        self._fill()
        while not self.planner.finished():
            item = self._next_done()
            if self.sized:
                complete = self._answer(*item)
            else:
                complete = self._task_done(item)
            self._fill()
            if complete is not None:
                frame = complete
                del self.frames[frame.number]
                self.shipped[frame.pack_key].users -= 1
                self._drop_idle()
                self.report.frames += 1
                self.report.wall = time.monotonic() - self.started
                yield frame
                self._fill()

    def _task_done(self, future: Any) -> Optional[_Frame]:
        """A tile's task done (fixed tiles)."""
        result = future.result()
        band = self.out.pop(future)
        del self.by_band[band]
        future.release()
        if result is None:  # it saw itself cancelled, yet was still wanted: render it again
            self.planner.give_back(band, forget=True)
            return None
        return self._place(band, result)

    def _worker_report(self, where: str) -> WorkerReport:
        w = self.report.workers.get(where)
        if w is None:
            w = self.report.workers[where] = WorkerReport(where)
        return w

    def _count(self, band: Band, where: str, threads: int, rays: Tuple[Any, ...], began: float,
               ended: float) -> None:
        r = self.report
        w = self._worker_report(where)
        w.threads = max(w.threads, threads)
        w.tasks += 1
        w.pixels += band.pixels
        w.rays += sum(rays[:4])
        w.busy += ended - began
        w.first, w.last = min(w.first, began), max(w.last, ended)
        r.tasks += 1
        r.pixels += band.pixels

    def _drop_idle(self) -> None:
        idle = [key for key, s in self.shipped.items() if s.users == 0]
        for key in idle[:max(0, len(idle) - self.KEEP_IDLE)]:  # the oldest first
            self.shipped.pop(key).future.release()
            for scene_id in [i for i, known in self.by_scene.items() if known[2].key == key]:
                del self.by_scene[scene_id]

    def close(self) -> None:
        """Cancel every band still out (after Ctrl-C or a failure), let
        the workers drop the scenes and the actors, free the frames' shared
        memory."""
        if self.out:
            self.client.cancel(list(self.out))
        self.out.clear()
        self.by_band.clear()
        for worker, actor in self.actors.items():
            # Its band ends at the chunk under way; the actor is dropped once
            # it has heard that (not waited for here).
            try:
                stopped = actor.stop()
            except RuntimeError:  # Dask's Actor: its worker was lost; nothing to stop
                self.actor_futures[worker].release()
                continue
            self.client.loop.add_callback(self._release_after, stopped, self.actor_futures[worker])
        self.actors.clear()
        self.actor_futures.clear()
        self.calls.clear()
        for frame in self.frames.values():
            frame.close()
        for shipped in self.shipped.values():
            shipped.future.release()
        self.shipped.clear()
        self.by_scene.clear()


def _threads(threads: Any) -> Optional[int]:
    if threads is None:
        return None
    n = _convert.integer(threads, "threads")
    if n < 1:
        raise ValueError(f"hitray.distributed: threads must be at least 1 (None: the worker's cores), not {n}")
    return n


# The most tiles a frame is cut into: each is a Dask task, which costs the
# scheduler memory and milliseconds; past this a frame spends far longer
# being scheduled than rendered (docs/distributed.md).
MAX_TILES_PER_FRAME = 100_000


def _tile_size(tile: Any, size: Tuple[int, int]) -> Optional[int]:
    if tile is None:
        return None
    t = _convert.integer(tile, "tile")
    if not 1 <= t <= 65536:
        raise ValueError(f"hitray.distributed: tile must be within 1..65536 pixels (or None: bands sized by "
                         f"measurement), not {t}")
    count = -(-size[0] // t) * -(-size[1] // t)
    if count > MAX_TILES_PER_FRAME:
        raise ValueError(f"hitray.distributed: tiles of {t} pixels cut a {size[0]}x{size[1]} frame into {count} "
                         f"tiles, more than {MAX_TILES_PER_FRAME}: use larger tiles")
    return t


def render(scene: Scene, camera: Optional[Camera] = None, size: Tuple[int, int] = (640, 480), spp: int = 1,
           threads: Optional[int] = None, depth: Optional[int] = None, progress: Progress = None, *,
           block: Optional[int] = None, effects: str = "auto", adaptive: Optional[float] = None,
           min_weight: Optional[float] = None, exact: bool = False, block_size: Optional[int] = None,
           all_effects: bool = False, texture_filter: str = "footprint", client: Any = None,
           tile: Optional[int] = None, workers: Optional[int] = None, timeout: float = 10.0,
           report: Optional[Report] = None) -> Image:
    """Render `scene` through `camera` as :func:`hitray.render` does, on a
    Dask cluster: the frame is cut into bands, each rendered by a worker on
    all its threads, and the Image put back together is bit for bit the one
    ``hitray.render`` gives with the same options (its arguments, in its
    order, plus the cluster's).

    Args:
        client: a ``distributed.Client``; a scheduler address
            (``"tcp://host:8786"``, connected to within `timeout` seconds,
            else SchedulerUnreachable); None: a LocalCluster on this machine
            of `workers` processes (None: one) sharing its cores, closed
            afterwards.
        tile: None: bands of rows sized by the workers' measured speed (the
            first bands are small probes, the rest share out the work so the
            workers finish together); a number: fixed square tiles of that
            side, all handed to Dask at once.
        threads: render threads per task (None: all the worker's, its Dask
            ``nthreads``; a worker then renders one band at a time, so its
            threads never render more than one band together). The image
            is the same whatever the count.
        progress: None (the default) shows a tqdm bar over pixels where
            someone watches (standard error a terminal, or a notebook), as
            hitray.render does; True always; a callable gets the fraction
            of pixels done; False shows nothing.
        report: a :class:`Report` filled in with what each worker did (rays
            per second, the share of core time not spent rendering, the
            balance).

    The scene is shipped to every worker once, with every file it
    references (mesh files) inside it: workers need no shared file system,
    only the same hitray installation (and any shape modules it loads).
    The options are checked here first, so a mistake raises before any task
    runs. Ctrl-C cancels the tasks still out and raises KeyboardInterrupt;
    a worker's failure is raised here; a worker lost has its bands rendered
    by the others. ``image.stats`` adds up the bands' rays (an adaptive
    corner on a band border is cast by both bands).
    """
    size = _convert.size(size)
    tile = _tile_size(tile, size)
    options = _options(spp, depth, block, effects, adaptive, min_weight, exact, block_size, all_effects,
                       texture_filter)
    task_threads = _threads(threads)
    camera = _check_here(scene, camera, size, options)
    with connect(client, workers, timeout) as c:
        bar = _Bar(progress, size[0] * size[1], "hitray.distributed")
        run = _Run(c, size, options, Planner(size, 1, open_frames=1, tile=tile), task_threads, bar,
                   lambda n: (0, None, scene, camera), report)
        try:
            for frame in run.frames_done():
                return frame.image()
        finally:
            run.close()
            bar.close()
    raise RuntimeError("hitray.distributed: the frame never completed")  # unreachable: frames_done() ends with it


def _frame_path(out_pattern: Any, index: int) -> str:
    pattern = os.fsdecode(_convert.path_bytes(out_pattern, "out_pattern"))
    try:
        path = pattern % index
    except (TypeError, ValueError):
        raise ValueError(f"render_frames: out_pattern {pattern!r} needs one integer conversion for the "
                         "frame number, such as 'frame_%04d.png'") from None
    if path == pattern % (index + 1):
        raise ValueError(f"render_frames: out_pattern {pattern!r} gives every frame the same file")
    return path


def _finished(path: str, index: int) -> bool:
    """Whether frame `index` is written already: a regular file with bytes in
    it (frames are written whole, then renamed into place, so an empty file
    is someone else's, not a frame). A directory there is an error: no frame
    can be written at its path."""
    try:
        info = os.stat(path)
    except FileNotFoundError:
        return False
    if stat.S_ISDIR(info.st_mode):
        raise IsADirectoryError(f"render_frames: {path}: a directory is where frame {index} goes")
    return stat.S_ISREG(info.st_mode) and info.st_size > 0


def render_frames(frames: FrameSource, out_pattern: Any, count: Optional[int] = None,
                  size: Tuple[int, int] = (640, 480), spp: int = 1, threads: Optional[int] = None,
                  depth: Optional[int] = None, progress: Progress = None, *, block: Optional[int] = None,
                  effects: str = "auto", adaptive: Optional[float] = None, min_weight: Optional[float] = None,
                  exact: bool = False, block_size: Optional[int] = None, all_effects: bool = False,
                  texture_filter: str = "footprint", client: Any = None, tile: Optional[int] = None,
                  workers: Optional[int] = None, timeout: float = 10.0, frames_in_flight: Optional[int] = None,
                  bits: int = 8, linear: bool = False, half: bool = False,
                  on_frame: Optional[Callable[[int, str], Any]] = None,
                  report: Optional[Report] = None) -> List[str]:
    """Render an animation on a Dask cluster, one file per frame.

    `frames` is a sequence of (scene, camera) pairs, or a function of the
    frame number returning one (then `count` says how many frames). Frame
    `i` is written to ``out_pattern % i`` (``"frame_%04d.png"``; PNG or EXR
    by the extension, with `bits`, `linear` and `half` as Image.save takes
    them), atomically, as soon as its last pixels are in, on a thread of its
    own while the next frame's bands come in (one frame at a time). A frame
    whose file exists already is skipped, so a rerun after an interruption
    renders only what is missing. While there are more frames to do than workers, a task
    is a whole frame; the last frames are cut into bands, so the animation
    ends with every worker busy. At most `frames_in_flight` frames are in
    progress at once (None: two per worker), which bounds the memory held
    for them. `on_frame(i, path)` is called after each frame is written,
    before the next one's write is started.
    Other arguments as :func:`render`; each frame's image is bit for bit
    what ``hitray.render`` gives it. Returns the paths written now.
    """
    if callable(frames):
        if count is None:
            raise TypeError("render_frames: frames is a function of the frame number: give count")
        total = _convert.integer(count, "count")
        if total < 0:
            raise ValueError(f"render_frames: count must be at least 0, not {total}")

        def frame_at(i: int) -> Tuple[Scene, Optional[Camera]]:
            return frames(i)
    else:
        listed = list(frames)
        total = len(listed) if count is None else min(_convert.integer(count, "count"), len(listed))

        def frame_at(i: int) -> Tuple[Scene, Optional[Camera]]:
            return listed[i]
    size = _convert.size(size)
    tile = _tile_size(tile, size)
    in_flight: Optional[int] = None
    if frames_in_flight is not None:
        in_flight = _convert.integer(frames_in_flight, "frames_in_flight")
        if in_flight < 1:
            raise ValueError(f"render_frames: frames_in_flight must be at least 1, not {in_flight}")
    options = _options(spp, depth, block, effects, adaptive, min_weight, exact, block_size, all_effects,
                       texture_filter)
    task_threads = _threads(threads)
    todo = [(i, path) for i, path in ((i, _frame_path(out_pattern, i)) for i in range(total))
            if not _finished(path, i)]
    for index, path in todo:
        folder = os.path.dirname(path) or "."
        if not os.path.isdir(folder):
            raise FileNotFoundError(f"render_frames: {folder}: no such directory for frame {index} ({path})")
    if not todo:
        return []
    written: List[str] = []
    checked = False

    def opened(n: int) -> Tuple[int, Optional[str], Scene, Camera]:
        """The n-th frame to do, asked for when the planner opens it."""
        nonlocal checked
        index, path = todo[n]
        scene, camera = _frame_pair(frame_at(index), index)
        if not checked or camera is None:
            camera = _check_here(scene, camera, size, options)
            checked = True
        return index, path, scene, camera

    with connect(client, workers, timeout) as c:
        if in_flight is None:
            in_flight = max(2, 2 * len(c.scheduler_info()["workers"]))
        bar = _Bar(progress, len(todo) * size[0] * size[1], "hitray.distributed")
        run = _Run(c, size, options, Planner(size, len(todo), open_frames=in_flight, tile=tile), task_threads,
                   bar, opened, report)
        # A frame is written on a thread of its own (Image.save releases the
        # GIL) while the bands of the next come in: one write at a time, the
        # next frame's started only once the last is written and on_frame
        # has been told, so an on_frame that stops the run leaves no other
        # frame half done.
        writer = concurrent.futures.ThreadPoolExecutor(1, thread_name_prefix="hitray-frame-writer")
        writing: Optional[Tuple["concurrent.futures.Future[None]", _Frame]] = None

        def written_out() -> None:
            nonlocal writing
            if writing is None:
                return
            done, frame = writing
            writing = None
            done.result()  # a failed write raised here
            assert frame.path is not None  # for mypy: every frame of render_frames has a path
            written.append(frame.path)
            bar.frame(len(written), len(todo))
            if on_frame is not None:
                on_frame(frame.index, frame.path)

        try:
            for frame in run.frames_done():
                written_out()
                assert frame.path is not None
                writing = (writer.submit(frame.image().save, frame.path, bits=bits, linear=linear, half=half),
                           frame)
            written_out()
        finally:
            writer.shutdown(wait=True)  # a write under way ends (whole: frames are written atomically)
            run.close()
            bar.close()
    return written


def _frame_pair(value: Any, index: int) -> Tuple[Scene, Optional[Camera]]:
    try:
        scene, camera = value
    except (TypeError, ValueError):
        raise TypeError(f"render_frames: frame {index} must be a (scene, camera) pair, "
                        f"got {type(value).__name__}") from None
    if not isinstance(scene, Scene):
        raise TypeError(f"render_frames: frame {index}: expected a hitray.Scene, got {type(scene).__name__}")
    if camera is not None and not isinstance(camera, Camera):
        raise TypeError(f"render_frames: frame {index}: camera must be a hitray.Camera or None, "
                        f"not {type(camera).__name__}")
    return scene, camera

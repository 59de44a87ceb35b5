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
import os
import stat
import time
import uuid
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Set, Tuple, Union

import numpy as np

from .. import _convert
from ..camera import Camera
from ..image import Image, RenderStats
from ..render import render as _render_here
from ..scene import Scene
from ._client import connect, dask_distributed, local_cores
from ._pack import ScenePack

__all__ = ["render", "render_frames"]

Window = Tuple[int, int, int, int]
Progress = Union[bool, Callable[[float], Any]]
FrameSource = Union[Sequence[Tuple[Scene, Optional[Camera]]], Callable[[int], Tuple[Scene, Optional[Camera]]]]


def windows(size: Tuple[int, int], tile: int) -> List[Window]:
    """The windows of `tile` x `tile` pixels that cover an image of `size`,
    row by row (the last of each row and column cut by the edge)."""
    w, h = size
    return [(x, y, min(tile, w - x), min(tile, h - y)) for y in range(0, h, tile) for x in range(0, w, tile)]


def _tile_threads(threads: Optional[int]) -> int:
    """Render threads for one task: `threads` if given, else this machine's
    cores shared among the worker's task threads (a `dask worker --nthreads
    4` on 16 cores renders 4 tiles at once on 4 threads each)."""
    if threads is not None:
        return threads
    distributed = dask_distributed()
    try:
        nthreads = int(distributed.get_worker().state.nthreads)
    except ValueError:  # not on a worker (a client's local run)
        nthreads = 1
    return max(1, local_cores() // max(1, nthreads))


def render_window(pack: ScenePack, camera: Camera, size: Tuple[int, int], options: Dict[str, Any],
                  window: Window, threads: Optional[int] = None
                  ) -> Tuple[np.ndarray, Tuple[int, int, int, int, Tuple[str, ...]], str, int]:
    """The task: one window of the frame, on a worker. Returns its pixels,
    its rays (primary, shadow, reflected, refracted, effects), the worker
    and the threads it rendered on."""
    threads = _tile_threads(threads)
    image = _render_here(pack.scene(), camera, size, threads=threads, progress=False, window=window, **options)
    s = image.stats
    assert s is not None
    rays = (s.primary, s.shadow, s.reflected, s.refracted, tuple(sorted(s.effects)))
    try:
        where = dask_distributed().get_worker().address
    except ValueError:
        where = "local"
    return np.array(image, copy=True), rays, where, threads


def _options(spp: int, depth: Optional[int], block: Optional[int], effects: str,
             adaptive: Optional[float], min_weight: Optional[float], exact: bool,
             block_size: Optional[int], all_effects: bool) -> Dict[str, Any]:
    """hitray.render's keywords, passed on as given (it checks them)."""
    return {"spp": spp, "depth": depth, "block": block, "effects": effects, "adaptive": adaptive,
            "min_weight": min_weight, "exact": _convert.flag(exact, "render: exact"),
            "block_size": block_size, "all_effects": _convert.flag(all_effects, "render: all_effects")}


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
    """One frame on its way: its tiles' futures and the pixels come back."""

    def __init__(self, index: int, path: Optional[str], size: Tuple[int, int], pack_key: str) -> None:
        self.index, self.path, self.pack_key = index, path, pack_key
        self.pixels = np.empty((size[1], size[0], 3), dtype=np.float32)
        self.pending = 0
        self.rays = [0, 0, 0, 0]
        self.effects: Set[str] = set()
        self.workers: Dict[str, int] = {}
        self.started = time.monotonic()

    def place(self, window: Window, result: Tuple[Any, ...]) -> None:
        pixels, rays, where, threads = result
        x, y, w, h = window
        if pixels.shape != (h, w, 3):
            raise RuntimeError(f"hitray.distributed: a worker returned {pixels.shape} pixels for the "
                               f"{w}x{h} window at ({x}, {y})")
        self.pixels[y:y + h, x:x + w] = pixels
        for i in range(4):
            self.rays[i] += rays[i]
        self.effects.update(rays[4])
        self.workers[where] = max(self.workers.get(where, 0), threads)
        self.pending -= 1

    def image(self) -> Image:
        image = Image(self.pixels)
        image._stats = RenderStats(sum(self.workers.values()), self.rays[0], self.rays[1], self.rays[2],
                                   self.rays[3], time.monotonic() - self.started, frozenset(self.effects))
        return image


class _Bar:
    """Progress over tiles: a tqdm bar, a callable given the fraction done,
    or nothing."""

    def __init__(self, progress: Progress, total: int, what: str) -> None:
        self._callback: Optional[Callable[[float], Any]] = None
        self._bar: Any = None
        self._done, self._total = 0, max(1, total)
        if progress is True:
            from tqdm.auto import tqdm  # type: ignore[import-untyped, unused-ignore]

            self._bar = tqdm(total=total, unit="tile", desc=what, leave=False)
        elif callable(progress):
            self._callback = progress
        elif progress not in (False, None):
            raise TypeError("hitray.distributed: progress must be True, False or a callable taking the "
                            "fraction done")

    def tile(self) -> None:
        self._done += 1
        if self._bar is not None:
            self._bar.update(1)
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

    __slots__ = ("future", "users")

    def __init__(self, future: Any) -> None:
        self.future, self.users = future, 0


def _same_description(a: Tuple[Any, List[Any], Dict[str, Any]], b: Tuple[Any, List[Any], Dict[str, Any]]) -> bool:
    """Whether two descriptions of a Scene (Scene._description) are the
    same: the same source and recorded operations (each is never changed
    once recorded), equal globals."""
    return (a[0] is b[0] and len(a[1]) == len(b[1]) and all(x is y for x, y in zip(a[1], b[1]))
            and a[2] == b[2])


class _Run:
    """Tiles of frames on a client: scenes shipped once each (scattered to
    every worker), tiles submitted with earlier frames first, frames handed
    back as they complete."""

    # Scenes no frame in flight uses stay on the workers, this many of the
    # latest, for the next frames (an animation of one scene ships it once);
    # older ones are dropped, so a run of many scenes holds few at a time.
    KEEP_IDLE = 2

    def __init__(self, client: Any, size: Tuple[int, int], options: Dict[str, Any], tile: int,
                 threads: Optional[int], bar: _Bar) -> None:
        distributed = dask_distributed()
        self.client, self.size, self.options, self.bar = client, size, options, bar
        self.threads = threads
        self.windows = windows(size, tile)
        self.run_id = uuid.uuid4().hex
        self.tiles: Dict[Any, Tuple[_Frame, Window]] = {}
        self.shipped: "collections.OrderedDict[str, _Shipped]" = collections.OrderedDict()
        # id(scene) -> (the scene, kept so the id stays its own; its
        # description when packed; the pack).
        self.by_scene: Dict[int, Tuple[Scene, Any, ScenePack]] = {}
        # with_results: each tile's pixels are fetched as soon as it is done,
        # in the client's event loop, not by one round trip per tile here.
        self.completed = distributed.as_completed(with_results=True)

    def _pack(self, scene: Scene) -> ScenePack:
        """The scene's pack: made again only if the scene changed since."""
        description = scene._description()
        known = self.by_scene.get(id(scene))
        if known is None or not _same_description(known[1], description):
            known = self.by_scene[id(scene)] = (scene, description, ScenePack(scene))
        return known[2]

    def submit(self, index: int, path: Optional[str], scene: Scene, camera: Camera) -> None:
        pack = self._pack(scene)
        shipped = self.shipped.get(pack.key)
        if shipped is None:
            shipped = self.shipped[pack.key] = _Shipped(self.client.scatter(pack, broadcast=True, hash=False))
        self.shipped.move_to_end(pack.key)
        shipped.users += 1
        frame = _Frame(index, path, self.size, pack.key)
        n = len(self.windows)
        # One map, one message to the scheduler for the frame's tiles.
        futures = self.client.map(render_window, [shipped.future] * n, [camera] * n, [self.size] * n,
                                  [self.options] * n, self.windows, [self.threads] * n,
                                  key=[f"hitray-tile-{self.run_id}-{index}-{x}-{y}" for x, y, _, _ in self.windows],
                                  pure=False, priority=-index)
        for future, window in zip(futures, self.windows):
            self.tiles[future] = (frame, window)
        frame.pending = n
        self.completed.update(futures)

    def _drop_idle(self) -> None:
        idle = [key for key, s in self.shipped.items() if s.users == 0]
        for key in idle[:max(0, len(idle) - self.KEEP_IDLE)]:  # the oldest first
            self.shipped.pop(key).future.release()
            for scene_id in [i for i, known in self.by_scene.items() if known[2].key == key]:
                del self.by_scene[scene_id]

    def frames(self) -> Iterator[_Frame]:
        """Frames as their last tile comes back (a worker's failure raised)."""
        for future, result in self.completed:
            frame, window = self.tiles.pop(future)
            frame.place(window, result)
            future.release()
            self.bar.tile()
            if frame.pending == 0:
                self.shipped[frame.pack_key].users -= 1
                self._drop_idle()
                yield frame

    def in_flight(self) -> int:
        return len({id(frame) for frame, _ in self.tiles.values()})

    def close(self) -> None:
        """Cancel every tile still out (after Ctrl-C or a failure) and let
        the workers drop the scenes."""
        if self.tiles:
            self.client.cancel(list(self.tiles))
        self.tiles.clear()
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


def _tile_size(tile: Any, size: Tuple[int, int]) -> int:
    t = _convert.integer(tile, "tile")
    if not 1 <= t <= 65536:
        raise ValueError(f"hitray.distributed: tile must be within 1..65536 pixels, not {t}")
    count = -(-size[0] // t) * -(-size[1] // t)
    if count > MAX_TILES_PER_FRAME:
        raise ValueError(f"hitray.distributed: tiles of {t} pixels cut a {size[0]}x{size[1]} frame into {count} "
                         f"tiles, more than {MAX_TILES_PER_FRAME}: use larger tiles")
    return t


def render(scene: Scene, camera: Optional[Camera] = None, size: Tuple[int, int] = (640, 480), spp: int = 1,
           threads: Optional[int] = None, depth: Optional[int] = None, progress: Progress = True, *,
           block: Optional[int] = None, effects: str = "auto", adaptive: Optional[float] = None,
           min_weight: Optional[float] = None, exact: bool = False, block_size: Optional[int] = None,
           all_effects: bool = False, client: Any = None, tile: int = 64, workers: Optional[int] = None,
           timeout: float = 10.0) -> Image:
    """Render `scene` through `camera` as :func:`hitray.render` does, on a
    Dask cluster: the frame is cut into tiles of `tile` x `tile` pixels,
    each rendered by a worker, and the Image put back together is bit for
    bit the one ``hitray.render`` gives with the same options (its
    arguments, in its order, plus the cluster's).

    Args:
        client: a ``distributed.Client``; a scheduler address
            (``"tcp://host:8786"``, connected to within `timeout` seconds,
            else SchedulerUnreachable); None: a LocalCluster on this machine
            of `workers` processes (None: one), closed afterwards.
        tile: tile side in pixels: smaller tiles balance the workers' load,
            larger ones cost less scheduling per pixel (docs/distributed.md).
        threads: render threads per tile (None: the worker machine's cores
            shared among its Dask threads). The image is the same whatever
            the count.
        progress: True shows a tqdm bar over tiles; a callable gets the
            fraction of tiles done; False shows nothing.

    The scene is shipped to every worker once, with every file it
    references (mesh files) inside it: workers need no shared file system,
    only the same hitray installation (and any shape modules it loads).
    The options are checked here first, so a mistake raises before any task
    runs. Ctrl-C cancels the tiles still out and raises KeyboardInterrupt;
    a worker's failure is raised here. ``image.stats`` adds up the tiles'
    rays (an adaptive corner on a tile border is cast by both tiles).
    """
    size = _convert.size(size)
    tile = _tile_size(tile, size)
    options = _options(spp, depth, block, effects, adaptive, min_weight, exact, block_size, all_effects)
    tile_threads = _threads(threads)
    camera = _check_here(scene, camera, size, options)
    with connect(client, workers, timeout) as c:
        bar = _Bar(progress, len(windows(size, tile)), "hitray.distributed")
        run = _Run(c, size, options, tile, tile_threads, bar)
        try:
            run.submit(0, None, scene, camera)
            for frame in run.frames():
                return frame.image()
        finally:
            run.close()
            bar.close()
    raise RuntimeError("hitray.distributed: the frame never completed")  # unreachable: frames() ends with it


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
                  depth: Optional[int] = None, progress: Progress = True, *, block: Optional[int] = None,
                  effects: str = "auto", adaptive: Optional[float] = None, min_weight: Optional[float] = None,
                  exact: bool = False, block_size: Optional[int] = None, all_effects: bool = False,
                  client: Any = None, tile: int = 64, workers: Optional[int] = None, timeout: float = 10.0,
                  frames_in_flight: int = 4, bits: int = 8, linear: bool = False, half: bool = False,
                  on_frame: Optional[Callable[[int, str], Any]] = None) -> List[str]:
    """Render an animation on a Dask cluster, one file per frame.

    `frames` is a sequence of (scene, camera) pairs, or a function of the
    frame number returning one (then `count` says how many frames). Frame
    `i` is written to ``out_pattern % i`` (``"frame_%04d.png"``; PNG or EXR
    by the extension, with `bits`, `linear` and `half` as Image.save takes
    them), atomically, as soon as its last tile is in. A frame whose file
    exists already is skipped, so a rerun after an interruption renders only
    what is missing. Tiles of up to `frames_in_flight` frames are scheduled
    together (earlier frames first), which bounds the memory held for
    frames in progress. `on_frame(i, path)` is called after each frame is
    written. Other arguments as :func:`render`; each frame's image is bit
    for bit what ``hitray.render`` gives it. Returns the paths written now.
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
    in_flight = _convert.integer(frames_in_flight, "frames_in_flight")
    if in_flight < 1:
        raise ValueError(f"render_frames: frames_in_flight must be at least 1, not {in_flight}")
    options = _options(spp, depth, block, effects, adaptive, min_weight, exact, block_size, all_effects)
    tile_threads = _threads(threads)
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
    with connect(client, workers, timeout) as c:
        bar = _Bar(progress, len(todo) * len(windows(size, tile)), "hitray.distributed")
        run = _Run(c, size, options, tile, tile_threads, bar)
        queue = iter(todo)

        def top_up() -> None:
            nonlocal checked
            while run.in_flight() < in_flight:
                item = next(queue, None)
                if item is None:
                    return
                index, path = item
                scene, camera = _frame_pair(frame_at(index), index)
                if not checked or camera is None:
                    camera = _check_here(scene, camera, size, options)
                    checked = True
                run.submit(index, path, scene, camera)

        try:
            top_up()
            for frame in run.frames():
                assert frame.path is not None
                frame.image().save(frame.path, bits=bits, linear=linear, half=half)
                written.append(frame.path)
                bar.frame(len(written), len(todo))
                if on_frame is not None:
                    on_frame(frame.index, frame.path)
                top_up()
        finally:
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

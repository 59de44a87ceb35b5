"""hitray.render: a scene through a camera into an Image."""

from __future__ import annotations

from typing import Any, Callable, Optional, Tuple, Union

from . import _convert, _core, _progress
from .camera import Camera
from .image import RenderedImage
from .scene import Scene

__all__ = ["render"]

Progress = Union[None, bool, Callable[[float], Any]]


class _Bar:
    """A tqdm bar that follows the fraction of tiles done (which the library
    never reports going backwards), with the time left."""

    def __init__(self) -> None:
        self._bar = _progress.tqdm_class()(
            total=100, unit="%", desc="hitray", leave=False,
            bar_format="{desc}: {percentage:3.0f}%|{bar}| {elapsed}<{remaining} left")
        self._shown = 0.0

    def __call__(self, fraction: float) -> None:
        target = 100.0 * fraction
        if target > self._shown:
            self._bar.update(target - self._shown)
            self._shown = target

    def close(self) -> None:
        self._bar.close()


def _window(window: Any, width: int, height: int) -> Tuple[int, int, int, int]:
    """(x, y, width, height) of a render window, checked against the image
    size here so the error names the window as the caller wrote it."""
    try:
        x, y, ww, wh = window
    except (TypeError, ValueError):
        raise TypeError(f"render: window must be (x, y, width, height), got {window!r}") from None
    x, y = _convert.integer(x, "window x"), _convert.integer(y, "window y")
    ww, wh = _convert.integer(ww, "window width"), _convert.integer(wh, "window height")
    if x < 0 or y < 0 or ww < 1 or wh < 1 or x + ww > width or y + wh > height:
        raise ValueError(f"render: window {ww}x{wh} at ({x}, {y}) must be at least 1x1 and lie inside "
                         f"the {width}x{height} image")
    return (x, y, ww, wh)


def render(scene: Scene, camera: Optional[Camera] = None, size: Tuple[int, int] = (640, 480),
           spp: int = 1, threads: Optional[int] = None, depth: Optional[int] = None,
           progress: Progress = None, *, block: Optional[int] = None, effects: str = "auto",
           adaptive: Optional[float] = None, min_weight: Optional[float] = None,
           exact: bool = False, block_size: Optional[int] = None,
           all_effects: bool = False,
           window: Optional[Tuple[int, int, int, int]] = None,
           texture_filter: str = "footprint") -> RenderedImage:
    """Render `scene` through `camera` into a new :class:`Image` of `size`
    (width, height).

    Args:
        camera: None frames every bounded object (``scene.frame_camera(size)``).
        spp: samples per pixel; 1 is the pixel centre, more a fixed
            stratified pattern.
        threads: render threads (None: every core). The image is the same
            bit for bit whatever the count.
        depth: bounces (None: the scene's max_recursion_depth).
        progress: None (the default) shows a tqdm bar where someone watches
            (standard error a terminal, or a Jupyter notebook) and nothing
            elsewhere, as ``hitray render`` does; True always shows one,
            False never; a callable is called with the fraction done (0..1)
            from the calling thread.
        block: Hill's blocksize: one ray per block of block² pixels
            (``hitray render --block``; ``block_size`` is the same, by its
            earlier name).
        effects: "auto" runs only the effects the scene calls for; "all"
            runs every effect's code path (the same image, slower; for
            measuring what the analysis saves). ``all_effects=True`` is
            ``effects="all"``.
        adaptive: adaptive supersampling (``--adaptive``): every pixel corner
            is sampled once and only pixels whose corners differ by more than
            this (0..1, sRGB-encoded) get the `spp` pattern; needs spp >= 2
            and block 1. None: off.
        min_weight: the contribution cut-off (``--min-weight``, 0..1): no
            reflected or refracted ray of weight below it is traced. None:
            the library's default, 2^-24.
        exact: trace every contribution, however small (``--exact``; not
            with min_weight).
        window: (x, y, width, height): render only this rectangle of the
            `size` image, into an Image of width x height whose pixels are
            bit for bit those of the full render (so windows that tile the
            frame give it exactly; hitray.distributed renders that way).
            None: the whole image.
        texture_filter: "footprint" (the default) averages each texture over
            the pixel's footprint on the surface, carried by ray
            differentials through mirrors and glass (pixmaps by their
            mip-maps); "none" point-samples it at the hit
            (``--texture-filter``). A scene without textures renders the
            same either way.

    The GIL is released while the render runs, so other Python threads run
    and several renders can run at once. Ctrl-C (KeyboardInterrupt), or an
    exception from a progress callable, cancels the render cleanly and is
    raised. The render statistics are in ``image.stats``.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"render: expected a hitray.Scene, got {type(scene).__name__}")
    w, h = _convert.size(size)
    spp = _convert.integer(spp, "spp")
    if spp < 1:
        raise ValueError(f"render: spp must be at least 1, not {spp}")
    nthreads = 0 if threads is None else _convert.integer(threads, "threads")
    if threads is not None and nthreads < 1:
        raise ValueError(f"render: threads must be at least 1 (None: every core), not {nthreads}")
    d = -1 if depth is None else _convert.integer(depth, "depth")
    if depth is not None and d < 0:
        raise ValueError(f"render: depth must be at least 0, not {d}")
    blocks = _block(block, block_size)
    all_paths = _effects(effects, all_effects)
    # The library checks these (range, spp and block for adaptive, exact
    # against min_weight) and says what is wrong: ArgumentError.
    threshold = 0.0 if adaptive is None else _convert.number(adaptive, "adaptive")
    weight = 0.0 if min_weight is None else _convert.number(min_weight, "min_weight")
    exact_flag = _convert.flag(exact, "render: exact")
    rect = (0, 0, w, h) if window is None else _window(window, w, h)
    filter_code = _texture_filter(texture_filter)
    if camera is None:
        camera = scene.frame_camera((w, h))
    elif not isinstance(camera, Camera):
        raise TypeError(f"render: camera must be a hitray.Camera or None, not {type(camera).__name__}")

    core_scene = scene._committed()
    bar: Optional[_Bar] = None
    callback: Optional[Callable[[float], Any]]
    if callable(progress):
        callback = progress
    elif progress is None or isinstance(progress, bool):
        bar = _Bar() if _progress.wanted(progress) else None
        callback = bar
    else:
        raise TypeError("render: progress must be None (auto), True, False or a callable taking the "
                        "fraction done")
    try:
        core_image = _core.render(core_scene, camera._as_core(), w, h, spp, nthreads, d, blocks,
                                  all_paths, threshold, weight, exact_flag, rect, filter_code, callback)
    finally:
        if bar is not None:
            bar.close()
    return RenderedImage._wrap(core_image)


def _block(block: Optional[int], block_size: Optional[int]) -> int:
    if block is not None and block_size is not None:
        raise TypeError("render: give block or block_size (the same option), not both")
    given = block if block is not None else block_size
    if given is None:
        return 1
    value = _convert.integer(given, "block")
    if value < 1:
        raise ValueError(f"render: block must be at least 1, not {value}")
    return value


# hr_render_options.texture_filter's values (HR_TEXTURE_FILTER_*).
_TEXTURE_FILTERS = {"footprint": 0, "none": 1}


def _texture_filter(name: str) -> int:
    if not isinstance(name, str) or name not in _TEXTURE_FILTERS:
        raise ValueError(f"render: texture_filter must be 'footprint' or 'none', not {name!r}")
    return _TEXTURE_FILTERS[name]


def _effects(effects: str, all_effects: bool) -> bool:
    if effects not in ("auto", "all"):
        raise ValueError(f"render: effects must be 'auto' or 'all', not {effects!r}")
    return effects == "all" or _convert.flag(all_effects, "render: all_effects")


"""Rendered images: linear float RGB pixels that numpy sees in place, the
library's writers, and a PNG for Jupyter."""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass
from typing import Any, FrozenSet, Optional, Tuple, Type, TypeVar

import numpy as np

from . import _convert, _core

__all__ = ["Image", "RenderedImage", "RenderStats"]

_FORMATS = {None: 0, "png": 1, "exr": 2, "ppm": 3, "pfm": 4}

_ImageT = TypeVar("_ImageT", bound="Image")


@dataclass(frozen=True)
class RenderStats:
    """What a render did: rays cast by kind and the effects that ran.

    Attributes:
        threads: threads that ran.
        primary: rays from the camera.
        shadow: rays toward lights.
        reflected: reflected rays (total internal reflection counts here).
        refracted: transmitted rays.
        seconds: wall time of the render.
        effects: the effects that ran ("diffuse", "shadows", "reflection", ...).
        pixels_refined: adaptive supersampling: pixels given every sample.
        samples_saved: adaptive: camera rays a full render would cast minus
            those cast (negative where the corner samples cost more).
        rays_cut: reflected and refracted rays the contribution cut-off
            (min_weight) did not trace.
    """

    threads: int
    primary: int
    shadow: int
    reflected: int
    refracted: int
    seconds: float
    effects: FrozenSet[str]
    pixels_refined: int = 0
    samples_saved: int = 0
    rays_cut: int = 0

    @property
    def rays(self) -> int:
        """Every ray cast."""
        return self.primary + self.shadow + self.reflected + self.refracted


class Image:
    """An image of linear float RGB pixels, row by row from the top.

    ``numpy.asarray(image)`` is a float32 H×W×3 view of the pixels themselves
    (no copy; writing to it changes the image). ``image.save(path)`` writes
    PNG, EXR, PPM or PFM by the extension, always as a complete file.
    In Jupyter an Image shows itself (``_repr_png_``).
    """

    __slots__ = ("_core", "_stats")

    def __init__(self, array: Any) -> None:
        """An image from an H×W×3 (or ×4) array of linear values (copied)."""
        self._core = _core.Image.from_array(np.asarray(array, dtype=np.float32))
        self._stats: Optional[RenderStats] = None

    @classmethod
    def read(cls: Type[_ImageT], path: _convert.PathLike) -> _ImageT:
        """Read a PNG, BMP or JPEG file (told by its first bytes) as linear
        RGB: PNG through libpng with its gAMA/sRGB chunk honoured, BMP and
        JPEG as 8-bit sRGB. For pixmaps (Scene.pixmap). Raises FileError
        naming the file, UnsupportedError for an image too large to read."""
        return cls._wrap(_core.Image.read(_convert.path_bytes(path)))

    @classmethod
    def _wrap(cls: Type[_ImageT], core: Any) -> _ImageT:
        image = object.__new__(cls)
        image._core = core
        s = core.stats
        image._stats = None if s is None else RenderStats(
            s["threads"], s["primary"], s["shadow"], s["reflected"], s["refracted"], s["seconds"],
            frozenset(s["effects"]), s["pixels_refined"], s["samples_saved"], s["rays_cut"])
        return image

    @property
    def width(self) -> int:
        """Pixels per row."""
        return int(self._core.width)

    @property
    def height(self) -> int:
        """Rows."""
        return int(self._core.height)

    @property
    def channels(self) -> int:
        """3 (RGB) for a render; 3 or 4 for an image made from an array."""
        return int(self._core.channels)

    @property
    def shape(self) -> Tuple[int, int, int]:
        """(height, width, channels), as numpy.asarray(image).shape."""
        return (self.height, self.width, self.channels)

    @property
    def stats(self) -> Optional[RenderStats]:
        """The render's statistics (None for an image made from an array)."""
        return self._stats

    def __reduce__(self) -> Tuple[Any, Tuple[np.ndarray]]:
        """Pickled as its pixels (exactly: float32 both ways), so a scene
        holding an image (a pixmap) travels to other processes
        (hitray.distributed). Render statistics are not carried."""
        return (Image, (np.array(self._core, copy=True),))

    def __array__(self, dtype: Any = None, copy: Optional[bool] = None) -> np.ndarray:
        view = np.asarray(self._core)  # the buffer protocol: no copy
        if dtype is not None and np.dtype(dtype) != view.dtype:
            if copy is False:
                raise ValueError("Image: pixels are float32; a different dtype needs a copy")
            return view.astype(dtype)
        return view.copy() if copy else view

    def save(self, path: _convert.PathLike, *, format: Optional[str] = None, bits: int = 8,
             linear: bool = False, half: bool = False) -> None:
        """Write the image. The format comes from the extension (.png, .exr,
        .ppm, .pfm) unless `format` names one. PNG: `bits` 8 or 16, sRGB-encoded
        unless `linear`; EXR: 32-bit floats, or 16-bit with `half`. The file is
        written beside the target and renamed into place, so a failure never
        leaves half a file. Raises FileError naming the path."""
        raw = _convert.path_bytes(path)
        key = None if format is None else str(format).lower().lstrip(".")
        if key not in _FORMATS:
            raise ValueError(f"save: unknown format {format!r}; use png, exr, ppm or pfm")
        bits = _convert.integer(bits, "bits")
        if bits not in (8, 16):
            raise ValueError(f"save: bits must be 8 or 16, not {bits}")
        self._core.save(raw, _FORMATS[key], bits, bool(linear), bool(half))

    def _repr_png_(self) -> bytes:
        """The image as PNG bytes (8-bit sRGB), for Jupyter and IPython."""
        with tempfile.TemporaryDirectory(prefix="hitray-") as tmp:
            path = os.path.join(tmp, "image.png")
            self.save(path)
            with open(path, "rb") as f:
                return f.read()

    def __repr__(self) -> str:
        return f"<hitray.Image {self.width}x{self.height}x{self.channels}>"


class RenderedImage(Image):
    """What :func:`hitray.render` returns: an :class:`Image` that always has
    its render's statistics, so ``image.stats.rays`` needs no None check
    (and type-checks as such)."""

    __slots__ = ()

    @property
    def stats(self) -> RenderStats:
        """The render's statistics."""
        assert self._stats is not None, "a rendered image carries its statistics"
        return self._stats

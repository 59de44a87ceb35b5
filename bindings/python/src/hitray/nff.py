"""Reading NFF, the format of Eric Haines' Standard Procedural Databases:
hitray.load_nff(path) and hitray.parse_nff(text)."""

from __future__ import annotations

import gzip
import os
import zlib
from typing import Optional, Tuple

from . import _convert
from .camera import Camera
from .errors import NFFError, SDLError
from .scene import Scene, _SDLSource
from .sdl import _read_back, _refuse_nul

__all__ = ["load_nff", "parse_nff"]

_GZIP_MAGIC = b"\x1f\x8b"


def _result(source: _SDLSource) -> Tuple[Scene, Optional[Camera]]:
    try:
        core, cam = source.load()
    except NFFError:
        raise
    except SDLError as e:  # the library's scene file error, in NFF's name
        raise NFFError(e.message, e.status, e.filename, e.line, e.column) from None
    return Scene._from_sdl(source, core), None if cam is None else Camera._from_core(cam)


def load_nff(path: _convert.PathLike) -> Tuple[Scene, Optional[Camera]]:
    """Read an NFF file, plain or gzip-compressed (told by its first bytes):
    returns (scene, camera), camera None if the file has no ``v`` (render
    then frames the scene); the camera's size is the file's ``resolution``.
    docs/nff.md says how each NFF field maps onto Hill's material.

    Raises NFFError (an SDLError) with ``filename``, ``line`` and ``column``
    for an error in the file, FileError if it cannot be read. The scene is
    rebuilt from the text read now, so later changes to the file do not
    reach it.
    """
    raw = _convert.path_bytes(path)
    # The library reads the file first, with its limits (a regular file only,
    # the scene size limit), and says why it cannot; the text is read back
    # after, to rebuild from (where that fails, a rebuild reads the file).
    source = _SDLSource(None, raw, None, raw, nff=True)
    result = _result(source)
    text = _read_back(raw, allow_nul=True)
    if text is not None and text.startswith(_GZIP_MAGIC):
        try:
            text = gzip.decompress(text)
        except (OSError, EOFError, zlib.error):
            text = None
    source.text = None if text is None or b"\0" in text else text
    return result


def parse_nff(text: str, name: str = "<string>") -> Tuple[Scene, Optional[Camera]]:
    """Read a scene from NFF text, as :func:`load_nff` does a file; `name`
    stands for the file in messages."""
    if isinstance(text, bytes):
        data = text
    elif isinstance(text, str):
        data = text.encode("utf-8", "surrogateescape")
    else:
        raise TypeError(f"parse_nff: expected str, got {type(text).__name__}")
    _refuse_nul(data, name, NFFError)
    return _result(_SDLSource(data, os.fsencode(name), None, None, nff=True))

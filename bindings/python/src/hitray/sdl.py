"""Reading Hill's SDL: hitray.load_sdl(path) and hitray.parse_sdl(text)."""

from __future__ import annotations

import os
import stat
from typing import Optional, Tuple, Type

from . import _convert, _core
from .camera import Camera
from .errors import SDLError
from .scene import Scene, _SDLSource

__all__ = ["load_sdl", "parse_sdl"]


def _refuse_nul(data: bytes, name: str, error: Type[SDLError]) -> None:
    """Scene text is handed to the library as a C string: a NUL byte in it is
    refused here, at its place, as the library's readers refuse one."""
    if b"\0" not in data:
        return
    at = data.index(b"\0")
    line = data.count(b"\n", 0, at) + 1
    column = at - (data.rfind(b"\n", 0, at) + 1) + 1
    raise error(f"{name}:{line}:{column}: unexpected NUL byte (is this a text file?)",
                6, name, line, column)


def _result(source: _SDLSource) -> Tuple[Scene, Optional[Camera]]:
    core, cam = source.load()
    return Scene._from_sdl(source, core), None if cam is None else Camera._from_core(cam)


def load_sdl(path: _convert.PathLike) -> Tuple[Scene, Optional[Camera]]:
    """Read a scene file: returns (scene, camera), camera None if the file
    sets none (render then frames the scene). Relative file names in it (a
    mesh's) are read from the file's directory. Shape classes a module adds,
    or hitray.abi registers, are SDL keywords too.

    Raises SDLError with ``filename``, ``line`` and ``column`` for an error
    in the file (its status says what kind), FileError if it cannot be read.
    The scene can be changed and rendered again: it is rebuilt from the text
    read now, so later changes to the file do not reach it.
    """
    raw = _convert.path_bytes(path)
    base_dir = os.path.abspath(os.path.dirname(raw) or b".")
    # The library reads the file first, with its limits (a regular file
    # only, up to its first NUL byte and the scene size limit: reading
    # /dev/zero here would never end) and says why it cannot.
    source = _SDLSource(None, raw, base_dir, raw)
    core, cam = source.load()
    # The text is kept to rebuild from: read back now, as much as the file
    # held (a regular file, so this ends). Where that fails, a rebuild reads
    # the file again.
    source.text = _read_back(raw)
    return Scene._from_sdl(source, core), None if cam is None else Camera._from_core(cam)


def _read_back(path: bytes, allow_nul: bool = False) -> Optional[bytes]:
    """The bytes of a regular file as it is now (None for anything else, or
    if it cannot be read; with a NUL byte too unless `allow_nul`, as a
    gzip stream has): read after the library has read the file with its
    limits, to keep the text a scene is rebuilt from."""
    try:
        with open(path, "rb") as f:
            info = os.fstat(f.fileno())
            if not stat.S_ISREG(info.st_mode):
                return None
            text = f.read(info.st_size)
    except OSError:
        return None
    return None if not allow_nul and b"\0" in text else text


def parse_sdl(text: str, name: str = "<string>",
              base_dir: Optional[_convert.PathLike] = None) -> Tuple[Scene, Optional[Camera]]:
    """Read a scene from SDL text, as :func:`load_sdl` does a file. `name`
    stands for the file in messages; `base_dir` resolves relative file names
    (default: the current directory)."""
    if isinstance(text, bytes):
        data = text
    elif isinstance(text, str):
        data = text.encode("utf-8", "surrogateescape")
    else:
        raise TypeError(f"parse_sdl: expected str, got {type(text).__name__}")
    name_bytes = os.fsencode(name)
    _refuse_nul(data, name, SDLError)
    base = os.path.abspath(_convert.path_bytes(base_dir, "base_dir") if base_dir is not None
                           else os.fsencode(os.getcwd()))
    return _result(_SDLSource(data, name_bytes, base, None))

"""A frame's pixels in shared memory, for workers on the client's machine.

The client puts each frame's pixels in a file of /dev/shm of its own
(``hitray-`` and 32 random hex digits, mode 0600); a worker that can open
it (one on the same machine, same user, same /dev/shm) writes its rows
there and sends none back, so a band's answer is a few hundred bytes
instead of its pixels (12 bytes each) pickled, sent, received and copied.
A worker that cannot (another machine, a container of its own) sends its
pixels back as before. Linux only; elsewhere every band sends its pixels.
"""

from __future__ import annotations

import mmap
import os
import re
import uuid
from typing import Optional, Tuple

import numpy as np

__all__ = ["FrameBuffer", "open_frame"]

_FOLDER = "/dev/shm"
_NAME = re.compile(r"hitray-[0-9a-f]{32}\Z")


def _shape(size: Tuple[int, int]) -> Tuple[int, int, int]:
    return size[1], size[0], 3


class FrameBuffer:
    """A frame's float32 pixels (H x W x 3) in a file of /dev/shm, named
    `name`; `close` unmaps and removes it."""

    def __init__(self, size: Tuple[int, int]) -> None:
        self.name = "hitray-" + uuid.uuid4().hex
        shape = _shape(size)
        nbytes = int(np.prod(shape)) * 4
        path = os.path.join(_FOLDER, self.name)
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL, 0o600)
        try:
            os.ftruncate(fd, max(1, nbytes))
            self._map: Optional[mmap.mmap] = mmap.mmap(fd, max(1, nbytes))
        except BaseException:
            os.unlink(path)
            raise
        finally:
            os.close(fd)
        self.pixels: Optional[np.ndarray] = np.frombuffer(self._map, dtype=np.float32,
                                                          count=nbytes // 4).reshape(shape)

    @classmethod
    def make(cls, size: Tuple[int, int]) -> Optional["FrameBuffer"]:
        """One for a frame of `size`, or None where /dev/shm is not there
        (not Linux) or full."""
        if not os.path.isdir(_FOLDER):
            return None
        try:
            return cls(size)
        except OSError:
            return None

    def close(self) -> None:
        self.pixels = None
        if self._map is not None:
            try:
                self._map.close()
            except BufferError:  # a view of it still held somewhere: the mapping goes with it
                pass
            self._map = None
            try:
                os.unlink(os.path.join(_FOLDER, self.name))
            except FileNotFoundError:
                pass


def open_frame(name: Optional[str], size: Tuple[int, int]) -> Optional[np.ndarray]:
    """On a worker: the frame's pixels in shared memory, to write rows into,
    or None when this process cannot reach them (another machine; no name;
    a file of another size). The mapping lasts as long as the array."""
    if name is None or not _NAME.match(name):
        return None
    shape = _shape(size)
    nbytes = int(np.prod(shape)) * 4
    try:
        fd = os.open(os.path.join(_FOLDER, name), os.O_RDWR)
    except OSError:
        return None
    try:
        if os.fstat(fd).st_size != max(1, nbytes):
            return None
        m = mmap.mmap(fd, max(1, nbytes))
    except OSError:
        return None
    finally:
        os.close(fd)
    return np.frombuffer(m, dtype=np.float32, count=nbytes // 4).reshape(shape)

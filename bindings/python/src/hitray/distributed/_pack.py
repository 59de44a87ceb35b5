"""A Scene made portable: its description and every file it was built
from, in one picklable object that a worker rebuilds the same scene from,
bit for bit, with no shared file system.

What a scene was built from: the files the library read while building it
(``Scene.files``: the readers' pixmaps, a mesh's ``file``), and nothing
else. A word of a scene file's text or a string a shape is given may name
a file without the file being read (in a comment, a macro never used, a
parameter that is no file name): such a file stays where it is. The scene
file itself travels as its text. On the worker the files are written under
a private directory at their own absolute paths (so ``../meshes/x`` from
the scene's directory lands where it did on the client), the scene's
directory becomes that directory's copy, and absolute names of the files
carried are rewritten to point into it.
"""

from __future__ import annotations

import copy
import hashlib
import os
import pickle
import shutil
import stat
import tempfile
import threading
import weakref
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

from ..scene import Scene, _AddLight, _AddObject, _MakePixmap, _SDLSource
from ..shapes import Shape

__all__ = ["ScenePack", "MAX_SHIPPED_BYTES"]

# The most a scene's files may add up to: a shipped scene is held in memory
# by the client, the scheduler's messages and every worker.
MAX_SHIPPED_BYTES = 1 << 30

# Where SDL's lexer ends a word (lib/sdl/sdl_lexer.c): white space, braces and
# the comment mark.
_SDL_BREAKS = frozenset(b" \t\r\n\v\f{}!")


class ShippingError(ValueError):
    """A scene that cannot be shipped (a referenced file too large, a scene
    file that can no longer be read)."""


def _sdl_words(text: bytes) -> List[Tuple[int, int]]:
    """The (start, end) byte spans of the words of SDL text, as the
    library's lexer cuts them (comments skipped)."""
    spans: List[Tuple[int, int]] = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == 0x21:  # '!': a comment to the end of the line
            end = text.find(b"\n", i)
            i = n if end < 0 else end
        elif c in _SDL_BREAKS:
            i += 1
        else:
            start = i
            while i < n and text[i] not in _SDL_BREAKS:
                i += 1
            spans.append((start, i))
    return spans


class _Files:
    """The files a scene read, gathered on the client."""

    def __init__(self, read: List[bytes]) -> None:
        self.read = frozenset(read)  # normalised absolute paths
        self.contents: Dict[bytes, bytes] = {}
        self.total = 0

    def place_of(self, name: bytes, base_dir: Optional[bytes]) -> Optional[bytes]:
        """The place (normalised absolute path) of `name`, relative to
        `base_dir`, where the scene read that file and it is carried; else
        None."""
        if not name or b"\0" in name:
            return None
        if os.path.isabs(name):
            full = name
        elif base_dir:
            full = os.path.join(base_dir, name)
        else:
            return None
        place = os.path.normpath(full)
        return place if place in self.contents else None

    def carry(self, place: bytes) -> None:
        """Carry the regular file at `place` (read by the scene)."""
        if place in self.contents:
            return
        try:
            info = os.stat(place)
        except (OSError, ValueError) as e:
            raise ShippingError(f"hitray.distributed: {os.fsdecode(place)}: the scene read it, but it cannot "
                                f"be read now to ship it: {getattr(e, 'strerror', None) or e}") from None
        if not stat.S_ISREG(info.st_mode):
            raise ShippingError(f"hitray.distributed: {os.fsdecode(place)}: the scene read it, but it is no "
                                "longer a regular file to ship")
        if self.total + info.st_size > MAX_SHIPPED_BYTES:
            raise ShippingError(f"hitray.distributed: {os.fsdecode(place)}: the scene's files would exceed "
                                f"{MAX_SHIPPED_BYTES} bytes, the most a shipped scene carries")
        try:
            with open(place, "rb") as f:
                data = f.read(MAX_SHIPPED_BYTES - self.total + 1)
        except OSError as e:
            raise ShippingError(f"hitray.distributed: {os.fsdecode(place)}: cannot read it to ship it "
                                f"with the scene: {e.strerror}") from None
        if self.total + len(data) > MAX_SHIPPED_BYTES:
            raise ShippingError(f"hitray.distributed: {os.fsdecode(place)}: the scene's files would exceed "
                                f"{MAX_SHIPPED_BYTES} bytes, the most a shipped scene carries")
        self.contents[place] = data
        self.total += len(data)


class _ShippedFile:
    """A shape's string parameter that names a carried file: its place."""

    __slots__ = ("place",)

    def __init__(self, place: bytes) -> None:
        self.place = place

    def __getstate__(self) -> bytes:
        return self.place

    def __setstate__(self, state: bytes) -> None:
        self.place = state


def _map_strings(shape: Shape, fn: Callable[[Any], Any]) -> Shape:
    """A copy of the shape tree with every string parameter (and carried
    file) mapped by `fn`. The tree is walked with a stack of its own, not by
    recursion, as Scene adds it (a chain of booleans may be deep)."""
    order: List[Shape] = []
    stack = [shape]
    while stack:
        node = stack.pop()
        order.append(node)
        stack.extend(v for v in node._params.values() if isinstance(v, Shape))
    copies: Dict[int, Shape] = {}
    for node in reversed(order):  # operands before what consumes them
        out = copy.copy(node)
        out._params = {key: copies[id(v)] if isinstance(v, Shape)
                       else fn(v) if isinstance(v, (str, bytes, os.PathLike, _ShippedFile)) else v
                       for key, v in node._params.items()}
        copies[id(node)] = out
    return copies[id(shape)]


Op = Union[_AddObject, _AddLight, _MakePixmap]


class ScenePack:
    """Everything a worker needs to rebuild a Scene: the scene file's text
    (with the spans of its absolute file names), the objects, lights and
    globals added in Python, and the files the scene read, by absolute path.
    ``key`` is a digest of all of it, so the same scene ships once."""

    __slots__ = ("key", "_sdl", "_spans", "_ops", "_globals", "_files", "_lock", "_scene", "__weakref__")

    def __init__(self, scene: Scene) -> None:
        sdl, ops, globals_ = scene._description()
        # The files the library read to build the scene, and only those.
        read = [os.path.normpath(p) for p in scene._current().files]
        files = _Files(read)
        own = None
        if sdl is not None and sdl.path is not None:
            own = os.path.normpath(os.path.abspath(sdl.path))  # travels as its text
        for place in read:
            if place != own:
                files.carry(place)
        self._spans: List[Tuple[int, int]] = []
        self._sdl: Optional[_SDLSource] = None
        if sdl is not None:
            text = sdl.text
            if text is None:
                # The library read it, but it could not be read back then.
                raise ShippingError(f"hitray.distributed: {os.fsdecode(sdl.path or b'?')}: the scene file "
                                    "could not be read back to ship it")
            if not sdl.nff:
                # NFF names no files; an absolute name of a file carried is
                # rewritten on the worker.
                for start, end in _sdl_words(text):
                    word = text[start:end]
                    if os.path.isabs(word) and files.place_of(word, sdl.base_dir) is not None:
                        self._spans.append((start, end))
            self._sdl = _SDLSource(text, sdl.name, sdl.base_dir, None, sdl.nff)
        self._ops: List[Op] = []
        for op in ops:
            if isinstance(op, _AddObject):
                base = op.base_dir

                def carried(value: Any, base: bytes = base) -> Any:
                    if isinstance(value, _ShippedFile):
                        return value
                    place = files.place_of(os.fsencode(value), base)
                    return value if place is None else _ShippedFile(place)

                self._ops.append(_AddObject(_map_strings(op.shape, carried), dict(op.material), base))
            else:
                self._ops.append(op)
        self._globals = globals_
        self._files = files.contents
        digest = hashlib.sha256(pickle.dumps(self._state(), protocol=pickle.HIGHEST_PROTOCOL))
        self.key = "hitray-scene-" + digest.hexdigest()
        self._lock = threading.Lock()
        self._scene: Optional[Scene] = None

    @property
    def shipped_bytes(self) -> int:
        """The bytes of the files carried."""
        return sum(len(v) for v in self._files.values())

    @property
    def files(self) -> List[str]:
        """The absolute paths of the files carried, sorted."""
        return sorted(os.fsdecode(p) for p in self._files)

    # --- pickling: the description, not what a worker built from it --------
    def _state(self) -> Tuple[Any, ...]:
        sdl = None if self._sdl is None else (self._sdl.text, self._sdl.name, self._sdl.base_dir,
                                               self._sdl.nff)
        # A pixmap's image pickles as its pixels (hitray.Image.__reduce__).
        ops = [("object", op.shape, op.material, op.base_dir) if isinstance(op, _AddObject)
               else ("pixmap", op.index, op.image) if isinstance(op, _MakePixmap)
               else ("light", op.position, op.color) for op in self._ops]
        return (sdl, self._spans, ops, self._globals, self._files)

    def __getstate__(self) -> Tuple[Any, ...]:
        return (self.key,) + self._state()

    def __setstate__(self, state: Tuple[Any, ...]) -> None:
        self.key, sdl, self._spans, ops, self._globals, self._files = state
        self._sdl = None if sdl is None else _SDLSource(sdl[0], sdl[1], sdl[2], None, sdl[3])
        self._ops = [_AddObject(op[1], op[2], op[3]) if op[0] == "object"
                     else _MakePixmap(op[1], op[2]) if op[0] == "pixmap" else _AddLight(op[1], op[2])
                     for op in ops]
        self._lock = threading.Lock()
        self._scene = None

    def __dask_tokenize__(self) -> str:
        return self.key

    # --- on the worker -----------------------------------------------------
    def scene(self) -> Scene:
        """The scene, rebuilt once per process (its files written under a
        private directory removed when this pack is dropped)."""
        with self._lock:
            if self._scene is None:
                self._scene = self._rebuild()
            return self._scene

    def _rebuild(self) -> Scene:
        root = os.path.normpath(os.fsencode(tempfile.mkdtemp(prefix="hitray-scene-")))
        weakref.finalize(self, shutil.rmtree, root, True)

        def place(path: bytes) -> bytes:
            # A pack is data from elsewhere: whatever its paths say, nothing
            # is written or read outside its own folder ('..' climbing out).
            target = os.path.normpath(os.path.join(root, path.lstrip(b"/")))
            if not target.startswith(root + b"/") and target != root:
                raise ShippingError(f"hitray.distributed: the shipped scene names {os.fsdecode(path)!r}, "
                                    "which leaves its folder: refused")
            return target

        targets = [(place(path), data) for path, data in self._files.items()]
        for target, data in targets:
            os.makedirs(os.path.dirname(target), exist_ok=True)
            with open(target, "wb") as f:
                f.write(data)
        sdl = None
        if self._sdl is not None:
            text, base_dir = self._sdl.text, self._sdl.base_dir
            assert text is not None
            if base_dir:
                base_dir = place(base_dir)
                os.makedirs(base_dir, exist_ok=True)
            if self._spans:
                if any(c in _SDL_BREAKS for c in root):
                    raise ShippingError(f"hitray.distributed: the worker's temporary directory "
                                        f"{os.fsdecode(root)!r} has a character SDL ends a file name at; "
                                        "set TMPDIR to a plain path")
                pieces, at = [], 0
                for start, end in self._spans:
                    pieces += [text[at:start], place(text[start:end])]
                    at = end
                text = b"".join(pieces + [text[at:]])
            sdl = _SDLSource(text, self._sdl.name, base_dir, None, self._sdl.nff)

        def shipped(value: Any) -> Any:
            return place(value.place) if isinstance(value, _ShippedFile) else value

        ops: List[Op] = [_AddObject(_map_strings(op.shape, shipped), op.material, place(op.base_dir))
                         if isinstance(op, _AddObject) else op for op in self._ops]
        for op in ops:
            if isinstance(op, _AddObject):
                os.makedirs(op.base_dir, exist_ok=True)
        scene = Scene._from_description(sdl, ops, self._globals)
        scene._committed()  # build and commit now: a bad scene fails here, once
        return scene

"""Scenes built in Python: objects, lights, globals, and Hill's queries.

A Scene is a description (an optional SDL text, then the objects and lights
added in order, then the globals set) and the library scene built from it.
Objects are added to the library scene at once, so a bad shape or material
raises in ``add``. Rendering or querying commits the library scene (it is
then immutable, as the C API wants); changing the Scene afterwards rebuilds
a new library scene from the description, so a Scene can be changed and
rendered again as often as wanted. Indices of objects never change.
"""

from __future__ import annotations

import math
import os
import threading
from typing import Any, Dict, FrozenSet, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _convert, _core, _warnings, material as _material
from ._convert import Vec3
from .camera import Camera
from .image import Image
from .queries import HitInfo, Hits, Light, TraceResult
from .shapes import Shape

__all__ = ["Scene", "SceneObject"]

# Scene globals: Python name -> (SDL name, kind), from the library's table
# of the fields (include/hitray/scene_fields.h).
_GLOBALS = {name: (sdl, kind) for name, sdl, kind in _core.global_fields()}
_GLOBAL_BY_SDL_NAME = {sdl: name for name, (sdl, _) in _GLOBALS.items()}


def _global_value(name: str, value: Any) -> Any:
    kind = _GLOBALS[name][1]
    if kind == "color":
        return _convert.vec3(value, name)
    if kind == "number":
        return _convert.number(value, name)
    return _convert.integer(value, name)


class _SDLSource:
    """The scene file text (SDL, or NFF when `nff`) a scene started from,
    kept to rebuild it."""

    __slots__ = ("text", "name", "base_dir", "path", "nff")

    def __init__(self, text: Optional[bytes], name: Optional[bytes], base_dir: Optional[bytes],
                 path: Optional[bytes], nff: bool = False) -> None:
        self.text, self.name, self.base_dir, self.path = text, name, base_dir, path
        self.nff = nff

    def load(self, warn: bool = True) -> Tuple[Any, Any]:
        """The library scene and camera from the text; its warnings are
        issued (the first read) or dropped (a rebuild, `warn` False)."""
        try:
            result = self._read()
        except BaseException:
            _warnings.discard()  # a failed read's warnings are not the next call's
            raise
        if warn:
            _warnings.issue()
        else:
            _warnings.discard()
        return result

    def _read(self) -> Tuple[Any, Any]:
        if self.nff:
            if self.text is None:
                assert self.path is not None
                return _core.load_nff_file(self.path)
            return _core.load_nff_string(self.text, self.name)
        if self.text is None:
            assert self.path is not None
            return _core.load_sdl_file(self.path)
        return _core.load_sdl_string(self.text, self.name, self.base_dir)


class _AddObject:
    __slots__ = ("shape", "material", "base_dir")

    def __init__(self, shape: Shape, material: Dict[str, Any], base_dir: bytes) -> None:
        self.shape, self.material, self.base_dir = shape, material, base_dir

    def apply(self, core: Any) -> int:
        return _add_tree(core, self.shape, self.material, self.base_dir)


class _AddLight:
    __slots__ = ("position", "color")

    def __init__(self, position: Vec3, color: Vec3) -> None:
        self.position, self.color = position, color

    def apply(self, core: Any) -> int:
        core.add_light(self.position, self.color)
        return int(core.light_count) - 1


class _MakePixmap:
    __slots__ = ("index", "image")

    def __init__(self, index: int, image: Image) -> None:
        self.index, self.image = index, image

    def apply(self, core: Any) -> int:
        core.set_pixmap(self.index, self.image._core)
        return self.index


def _add_tree(core: Any, shape: Shape, inherited: Dict[str, Any], base_dir: bytes) -> int:
    """Add a shape and, first, the shapes among its parameters (a boolean's
    operands), which it consumes. Each leaf's material is its own over the
    one it inherits.

    The tree is walked with a stack of its own, not by recursion: a chain of
    2000 booleans must reach the library, whose limit on composite depth
    (HR_MAX_COMPOSITE_DEPTH) gives the error, not Python's recursion limit."""
    # One frame per shape being added: the shape, its material, its
    # parameters and how many of them are done, the parameters built.
    Frame = List[Any]

    def frame(node: Shape, above: Dict[str, Any]) -> Frame:
        return [node, {**above, **node._material}, list(node._params.items()), 0, []]

    frames: List[Frame] = [frame(shape, inherited)]
    index = -1
    while frames:
        top = frames[-1]
        node, material, items, done, params = top
        if done < len(items):
            key, value = items[done]
            top[3] = done + 1
            if isinstance(value, Shape):
                params.append((key, "object", -1))  # the index, once it is added
                frames.append(frame(value, material))
            elif isinstance(value, (str, bytes, os.PathLike)):
                params.append((key, "string", os.fsencode(value)))
            elif isinstance(value, np.ndarray):
                params.append((key, "numbers", value))  # lent, not copied
            else:  # a number, made a float by Shape
                params.append((key, "number", value))
            continue
        index = int(core.add_object(node.name, params, material, node._transform, base_dir))
        frames.pop()
        if frames:
            parent = frames[-1][4]
            parent[-1] = (parent[-1][0], "object", index)
    return index


class Scene:
    """A scene: objects, lights and globals, queried and rendered as a whole.

    >>> scene = hitray.Scene()
    >>> ball = scene.add(hitray.Sphere().translate(0, 1, 0), diffuse=(1, 0, 0))
    >>> scene.light((5, 8, 6), (1, 1, 1))
    >>> scene.background = (0, 0, 0.6)

    Globals (SDL's names work as aliases): ``background``,
    ``global_ambient`` (``globalAmbient``), ``min_reflectivity``,
    ``min_transparency``, ``max_recursion_depth`` (``maxRecursionDepth``).
    A Scene may be used from several threads; renders of it run at once.
    """

    __slots__ = ("_lock", "_sdl", "_ops", "_globals", "_live")

    def __init__(self) -> None:
        self._lock = threading.RLock()
        self._sdl: Optional[_SDLSource] = None
        self._ops: List[Union[_AddObject, _AddLight, _MakePixmap]] = []
        self._globals: Dict[str, Any] = {}
        self._live: Any = _core.Scene()

    @classmethod
    def _from_sdl(cls, source: _SDLSource, core: Any) -> "Scene":
        scene = cls()
        scene._sdl = source
        scene._live = core
        return scene

    def _description(self) -> Tuple[Optional[_SDLSource], List[Union[_AddObject, _AddLight, _MakePixmap]],
                                    Dict[str, Any]]:
        """What the scene is built from: the scene file source, the objects
        and lights added, the globals set (copies of the lists, taken under
        the lock; hitray.distributed ships them)."""
        with self._lock:
            return self._sdl, list(self._ops), dict(self._globals)

    @classmethod
    def _from_description(cls, sdl: Optional[_SDLSource], ops: List[Union[_AddObject, _AddLight, _MakePixmap]],
                          globals_: Dict[str, Any]) -> "Scene":
        """The scene :meth:`_description` describes, built on first use."""
        scene = cls()
        scene._sdl, scene._ops, scene._globals = sdl, list(ops), dict(globals_)
        scene._live = None
        return scene

    # --- the library scene ----------------------------------------------------
    def _build(self) -> Any:
        core = self._sdl.load(warn=False)[0] if self._sdl is not None else _core.Scene()
        for op in self._ops:
            op.apply(core)
        if self._globals:
            core.set_globals(self._globals)
        return core

    def _editable(self) -> Any:
        """The library scene, not committed yet (rebuilt if it was)."""
        if self._live is None or self._live.committed:
            self._live = self._build()
        return self._live

    def _current(self) -> Any:
        with self._lock:
            if self._live is None:
                self._live = self._build()
            return self._live

    def _committed(self) -> Any:
        """The library scene, committed (what renders and queries use)."""
        with self._lock:
            core = self._current()
            if not core.committed:
                core.commit()
                _warnings.issue()
            return core

    def _record(self, op: Union[_AddObject, _AddLight, _MakePixmap]) -> int:
        with self._lock:
            core = self._editable()
            before = core.object_count
            try:
                result = op.apply(core)
            except BaseException:
                # A boolean may have added its operands before the library
                # refused it: start again from the description next time.
                if core.object_count != before:
                    self._live = None
                raise
            self._ops.append(op)
            return result

    # --- building -------------------------------------------------------------
    def add(self, shape: Shape, **material: Any) -> "SceneObject":
        """Add `shape` as a new object with the material given as SDL's
        keywords (``diffuse=(1, 0, 0)``, ``specularExponent=20``,
        ``reflectivity=0.5``, ...; unnamed fields keep SDL's defaults) and
        return it. A boolean's operands are added first, as objects consumed by
        it; each keeps the material set on it with ``Shape.with_material``,
        else this one. Adding the same Shape again adds another copy.

        Raises ModuleError (no module provides the class), ParameterError (the
        class refused a parameter), ArgumentError (a material value out of
        range), NumericError (a degenerate transform).
        """
        if not isinstance(shape, Shape):
            raise TypeError(f"add: expected a hitray.Shape, got {type(shape).__name__}")
        fields = _material.normalize(material)
        index = self._record(_AddObject(shape, fields, os.fsencode(os.getcwd())))
        return SceneObject(self, index)

    def pixmap(self, index: int, image: Union[Image, _convert.PathLike]) -> None:
        """Hill's makePixmap: make `image` (a hitray.Image, or the path of a
        PNG, BMP or JPEG file, read with Image.read) pixmap number `index`
        (from 1), for objects added later with ``texture=index``. Each number
        is made once. Raises ArgumentError (index below 1, made already, a
        pixel not finite), FileError (a file that cannot be read)."""
        index = _convert.integer(index, "pixmap index")
        if not isinstance(image, Image):
            image = Image.read(image)
        self._record(_MakePixmap(index, image))

    def light(self, position: Sequence[float], color: Sequence[float] = (1.0, 1.0, 1.0)) -> None:
        """Add a point light at `position` (world coordinates) with `color`."""
        self._record(_AddLight(_convert.vec3(position, "light position"),
                               _convert.vec3(color, "light color")))

    def _set_global(self, name: str, value: Any) -> None:
        value = _global_value(name, value)
        with self._lock:
            self._editable().set_globals({name: value})
            self._globals[name] = value

    def _get_global(self, name: str) -> Any:
        return self._current().get_globals()[name]

    def __getattr__(self, name: str) -> Any:
        if name in _GLOBAL_BY_SDL_NAME:
            return self._get_global(_GLOBAL_BY_SDL_NAME[name])
        raise AttributeError(f"'Scene' object has no attribute '{name}'")

    def __setattr__(self, name: str, value: Any) -> None:
        if name in _GLOBAL_BY_SDL_NAME and name not in _GLOBALS:
            self._set_global(_GLOBAL_BY_SDL_NAME[name], value)
        else:
            object.__setattr__(self, name, value)

    @property
    def background(self) -> Vec3:
        """Colour of rays that hit nothing (SDL default 0 0 0.6)."""
        return self._get_global("background")  # type: ignore[no-any-return]

    @background.setter
    def background(self, value: Sequence[float]) -> None:
        self._set_global("background", value)

    @property
    def global_ambient(self) -> Vec3:
        """Ambient light everywhere, times each material's ambient (default 0.1)."""
        return self._get_global("global_ambient")  # type: ignore[no-any-return]

    @global_ambient.setter
    def global_ambient(self, value: Sequence[float]) -> None:
        self._set_global("global_ambient", value)

    @property
    def min_reflectivity(self) -> float:
        """A reflected ray is traced only where reflectivity is at least this (0.5)."""
        return self._get_global("min_reflectivity")  # type: ignore[no-any-return]

    @min_reflectivity.setter
    def min_reflectivity(self, value: float) -> None:
        self._set_global("min_reflectivity", value)

    @property
    def min_transparency(self) -> float:
        """A transmitted ray is traced only where transparency is at least this (0.5)."""
        return self._get_global("min_transparency")  # type: ignore[no-any-return]

    @min_transparency.setter
    def min_transparency(self, value: float) -> None:
        self._set_global("min_transparency", value)

    @property
    def max_recursion_depth(self) -> int:
        """Bounces after the primary ray (default 3; at most 1000)."""
        return self._get_global("max_recursion_depth")  # type: ignore[no-any-return]

    @max_recursion_depth.setter
    def max_recursion_depth(self, value: int) -> None:
        self._set_global("max_recursion_depth", value)

    # --- what is in it --------------------------------------------------------
    @property
    def objects(self) -> List["SceneObject"]:
        """Every object in index order (a boolean's operands too, before it)."""
        return [SceneObject(self, i) for i in range(int(self._current().object_count))]

    @property
    def files(self) -> List[str]:
        """The files the scene was built from: every file the library read
        to make it (the scene file, ``makePixmap`` images, mesh files), once
        each, in the order first read, as absolute paths (``..`` and links
        kept as they were). A file the scene's text names without reading
        it, in a comment or a macro never used, is not among them.
        ``hitray.distributed`` ships exactly these."""
        return [os.fsdecode(p) for p in self._current().files]

    @property
    def lights(self) -> List[Light]:
        """Every light, in the order added (an SDL file's first)."""
        core = self._current()
        return [Light(*core.light(i)) for i in range(int(core.light_count))]

    @property
    def bounds(self) -> Optional[Tuple[Vec3, Vec3]]:
        """(lo, hi) world box of the bounded top-level objects; None if none."""
        return self._current().bounds()  # type: ignore[no-any-return]

    @property
    def effects(self) -> FrozenSet[str]:
        """The effects this scene calls for ("shadows", "reflection", ...):
        the renderer simulates these and nothing else."""
        return frozenset(self._committed().effects())

    def frame_camera(self, size: Tuple[int, int] = (640, 480), angle: float = 45.0) -> Camera:
        """A camera that has every bounded object in view in an image of
        `size` (what rendering with no camera uses)."""
        w, h = _convert.size(size)
        return Camera._from_core(self._current().frame_camera(w, h, _convert.number(angle, "angle")))

    # --- Hill's queries ---------------------------------------------------------
    def first_hit(self, origin: Sequence[float], direction: Sequence[float], tmin: float = 0.0,
                  tmax: float = math.inf) -> Optional[HitInfo]:
        """Hill's getFirstHit: the nearest hit with tmin < t < tmax along
        origin + t·direction (direction need not be unit length), or None.
        At an exact tie in t the object added first wins, then the lower
        surface (hr_scene_first_hit's tie rule)."""
        hit = self._committed().first_hit(_convert.vec3(origin, "origin"),
                                          _convert.vec3(direction, "direction"),
                                          _convert.number(tmin, "tmin"), _convert.number(tmax, "tmax"))
        return None if hit is None else HitInfo._from_core(hit)

    def hits(self, origin: Sequence[float], direction: Sequence[float], tmin: float = 0.0,
             tmax: float = math.inf) -> List[HitInfo]:
        """Hill's Intersection: every hit of every object with tmin < t < tmax,
        sorted by t."""
        found = self._committed().all_hits(_convert.vec3(origin, "origin"),
                                           _convert.vec3(direction, "direction"),
                                           _convert.number(tmin, "tmin"), _convert.number(tmax, "tmax"))
        return [HitInfo._from_core(h) for h in found]

    def _rays(self, what: str, origins: Any, directions: Any, threads: Optional[int]
              ) -> Tuple[np.ndarray, np.ndarray, int]:
        """N x 3 arrays (one 3-vector broadcast to every ray) and the thread
        count for _core (0: every core)."""
        o = np.asarray(origins, dtype=np.float64)
        d = np.asarray(directions, dtype=np.float64)
        for name, a in (("origins", o), ("directions", d)):
            if a.ndim not in (1, 2) or a.shape[-1] != 3:
                raise ValueError(f"{what}: {name} must be N x 3 (or one 3-vector), got shape {a.shape}")
        o2, d2 = np.broadcast_arrays(np.atleast_2d(o), np.atleast_2d(d))
        nthreads = 0 if threads is None else _convert.integer(threads, "threads")
        if nthreads < 0 or (threads is not None and nthreads == 0):
            raise ValueError(f"{what}: threads must be at least 1 (None: every core)")
        return np.ascontiguousarray(o2), np.ascontiguousarray(d2), nthreads

    def trace(self, origins: Any, directions: Any, tmin: float = 0.0, tmax: float = math.inf,
              threads: Optional[int] = None) -> TraceResult:
        """getFirstHit for many rays: `origins` and `directions` are N x 3
        arrays (either may be one 3-vector, shared by every ray). Runs in C
        with the GIL released, over `threads` threads (None: every core),
        each handing its rays to the batch query (``hr_scene_first_hits``).
        Returns arrays t (inf for a miss), normal and object (-1 for a miss);
        :meth:`first_hits` returns every field of the hits.
        A ray with a non-finite value or a zero direction raises ArgumentError
        naming its index."""
        o, d, nthreads = self._rays("trace", origins, directions, threads)
        t, normal, obj = _core.trace(self._committed(), o, d, _convert.number(tmin, "tmin"),
                                     _convert.number(tmax, "tmax"), nthreads)
        return TraceResult(t, normal, obj)

    def first_hits(self, origins: Any, directions: Any, tmin: float = 0.0, tmax: float = math.inf,
                   threads: Optional[int] = None) -> Hits:
        """:meth:`trace` with every field of Hill's HitInfo, as arrays (a
        :class:`Hits`): for each ray the same hit as :meth:`first_hit`, bit
        for bit."""
        o, d, nthreads = self._rays("first_hits", origins, directions, threads)
        return Hits(*_core.trace(self._committed(), o, d, _convert.number(tmin, "tmin"),
                                 _convert.number(tmax, "tmax"), nthreads, True))

    def occluded(self, origins: Any, directions: Any, tmin: float = 0.0, tmax: float = math.inf,
                 threads: Optional[int] = None) -> np.ndarray:
        """Whether each ray meets any object with tmin < t < tmax (the C
        ``hr_scene_occluded``, a shadow ray's question: direction the light
        minus the point and tmax 1): an (N,) bool array. Arrays, threads
        and errors as :meth:`trace`."""
        o, d, nthreads = self._rays("occluded", origins, directions, threads)
        return _core.occluded(self._committed(), o, d, _convert.number(tmin, "tmin"),
                              _convert.number(tmax, "tmax"), nthreads)

    def shade(self, origin: Sequence[float], direction: Sequence[float],
              depth: Optional[int] = None) -> Vec3:
        """Hill's shade: the colour seen along the ray, with reflections and
        refractions down to `depth` bounces (None: the scene's
        max_recursion_depth). A lone ray stands for no pixel, so textures
        are point-sampled at its hits (as ``texture_filter="none"``)."""
        d = -1 if depth is None else _convert.integer(depth, "depth")
        if depth is not None and d < 0:
            raise ValueError("shade: depth must be at least 0")
        return self._committed().shade(_convert.vec3(origin, "origin"),  # type: ignore[no-any-return]
                                       _convert.vec3(direction, "direction"), d)

    def __repr__(self) -> str:
        core = self._current()
        return f"<hitray.Scene: {core.object_count} objects, {core.light_count} lights>"


class SceneObject:
    """One object of a scene, as :meth:`Scene.add` returns it and
    ``scene.objects`` lists it. ``index`` is what hits name as ``object``."""

    __slots__ = ("_scene", "index")

    def __init__(self, scene: Scene, index: int) -> None:
        self._scene = scene
        self.index = index

    def _info(self) -> Dict[str, Any]:
        return self._scene._current().object_info(self.index)  # type: ignore[no-any-return]

    @property
    def scene(self) -> Scene:
        """The scene this object is in."""
        return self._scene

    @property
    def shape(self) -> str:
        """The shape class name."""
        return self._info()["shape"]  # type: ignore[no-any-return]

    @property
    def module(self) -> str:
        """Path of the module that provides the class."""
        return self._info()["module"]  # type: ignore[no-any-return]

    @property
    def material(self) -> Dict[str, Any]:
        """The object's material, every field, by snake_case name."""
        return self._info()["material"]  # type: ignore[no-any-return]

    @property
    def matrix(self) -> np.ndarray:
        """Object-to-world matrix M (4x4)."""
        return np.array(self._info()["transform"], dtype=np.float64).reshape(4, 4)

    @property
    def inverse(self) -> np.ndarray:
        """World-to-object matrix M⁻¹ (4x4)."""
        return np.array(self._info()["inverse"], dtype=np.float64).reshape(4, 4)

    @property
    def bounds(self) -> Tuple[Vec3, Vec3]:
        """(lo, hi) world box; infinities for an unbounded object."""
        return self._info()["bounds"]  # type: ignore[no-any-return]

    @property
    def params(self) -> Dict[str, Any]:
        """The parameters the object was made with, by name, one for each
        parameter its class declares (``hitray shapes`` lists them), the
        defaults filled in: a float, a str, the operand (a SceneObject) of a
        boolean, or for an array parameter (``triangleMesh``'s points) its
        length, as the scene keeps no copy of the array."""
        out: Dict[str, Any] = {}
        for name, kind, value in self._info()["params"]:
            out[name] = SceneObject(self._scene, value) if kind == "object" else value
        return out

    @property
    def top_level(self) -> bool:
        """False for an operand consumed by a boolean."""
        return self._info()["top_level"]  # type: ignore[no-any-return]

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, SceneObject) and other._scene is self._scene
                and other.index == self.index)

    def __hash__(self) -> int:
        return hash((id(self._scene), self.index))

    def __repr__(self) -> str:
        return f"<hitray.SceneObject {self.index}: {self.shape}>"

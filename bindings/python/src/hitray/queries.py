"""The records Hill's queries return: HitInfo (one hit), the arrays of a
vectorised trace, and a scene's lights."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple, Sequence

import numpy as np

from . import _core
from ._convert import Vec3, vec3

__all__ = ["HitInfo", "TraceResult", "Hits", "Light"]


@dataclass(frozen=True)
class HitInfo:
    """Hill's HitInfo: one place where a ray meets a surface, in world space.

    Attributes:
        t: the ray parameter (origin + t·direction is the point; the
            direction is used as given, not normalised).
        point: the hit point.
        normal: the outward unit normal there.
        entering: True where the ray enters the solid, False where it leaves.
        surface: which surface of the shape, 0 .. surface_count - 1; its
            class's ``surface_names`` (``hitray.shape_classes()``) names it.
        object: index of the object in the scene (``scene.objects[i]``); for a
            boolean, the leaf whose surface it is.
        error: a bound on the distance of `point` from the true surface
            point (per coordinate, absolute), what :meth:`spawn_origin`
            moves off by.
    """

    t: float
    point: Vec3
    normal: Vec3
    entering: bool
    surface: int
    object: int
    error: float = 0.0

    @classmethod
    def _from_core(cls, h: Any) -> "HitInfo":
        t, point, normal, surface, entering, obj, error = h
        return cls(t, point, normal, bool(entering), surface, obj, error)

    def spawn_origin(self, side: Sequence[float]) -> Vec3:
        """Where a ray leaving this hit toward `side` starts (the C
        ``hr_hit_spawn_origin``): the point moved off the surface by the
        hit's own error bound, so the ray cannot hit the surface it leaves.
        `side` is a unit normal, or its negation to pass into a solid; the
        renderer's shadow, reflected and refracted rays start this way.
        ``hit.spawn_origin(hit.normal)`` is outside, ``-normal`` inside."""
        x, y, z = _core.spawn_origin(self.point, self.error, vec3(side, "side"))
        return (x, y, z)


class TraceResult(NamedTuple):
    """What :meth:`Scene.trace` returns for N rays (unpacks as a tuple).

    Attributes:
        t: (N,) float64, the nearest hit's t, ``inf`` for a miss.
        normal: (N, 3) float64 unit normals, (0, 0, 0) for a miss.
        object: (N,) int64 object indices, -1 for a miss.
    """

    t: np.ndarray
    normal: np.ndarray
    object: np.ndarray


class Hits(NamedTuple):
    """What :meth:`Scene.first_hits` returns for N rays: each field of
    :class:`HitInfo` as an array, the nearest hit of each ray (unpacks as a
    tuple).

    Attributes:
        t: (N,) float64, ``inf`` for a miss.
        point: (N, 3) float64, (0, 0, 0) for a miss.
        normal: (N, 3) float64 unit normals, (0, 0, 0) for a miss.
        surface: (N,) int32, -1 for a miss.
        entering: (N,) bool, False for a miss.
        object: (N,) int64 object indices, -1 for a miss.
        error: (N,) float64 error bounds of the points, 0 for a miss.
    """

    t: np.ndarray
    point: np.ndarray
    normal: np.ndarray
    surface: np.ndarray
    entering: np.ndarray
    object: np.ndarray
    error: np.ndarray


class Light(NamedTuple):
    """A point light in world coordinates with one colour for diffuse and
    specular (SDL's ``light x y z r g b``)."""

    position: Vec3
    color: Vec3

"""The records Hill's queries return: HitInfo (one hit), the arrays of a
vectorised trace, and a scene's lights."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from ._convert import Vec3

__all__ = ["HitInfo", "TraceResult", "Light"]


@dataclass(frozen=True)
class HitInfo:
    """Hill's HitInfo: one place where a ray meets a surface, in world space.

    Attributes:
        t: the ray parameter (origin + t·direction is the point; the
            direction is used as given, not normalised).
        point: the hit point.
        normal: the outward unit normal there.
        entering: True where the ray enters the solid, False where it leaves.
        surface: which surface of the shape (a cube's 0..5 for ±x, ±y, ±z; a
            tapered cylinder's 0 wall, 1 base, 2 cap; 0 for one-surface shapes).
        object: index of the object in the scene (``scene.objects[i]``); for a
            boolean, the leaf whose surface it is.
    """

    t: float
    point: Vec3
    normal: Vec3
    entering: bool
    surface: int
    object: int

    @classmethod
    def _from_core(cls, h: Any) -> "HitInfo":
        t, point, normal, surface, entering, obj = h
        return cls(t, point, normal, bool(entering), surface, obj)


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


class Light(NamedTuple):
    """A point light in world coordinates with one colour for diffuse and
    specular (SDL's ``light x y z r g b``)."""

    position: Vec3
    color: Vec3

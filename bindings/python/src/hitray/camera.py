"""Hill's camera: an eye, a point it looks at, an up vector and a vertical
view angle in degrees. Its axes follow Hill (n from the look-at point back
to the eye, u = up × n, v = n × u); the image size is the render's."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Tuple

from . import _convert, _core
from ._convert import Vec3

__all__ = ["Camera"]


@dataclass
class Camera:
    """``Camera(eye, look, up, angle)``; the defaults are the library's: eye
    (0, 0, 5) looking at the origin, up +y, 45 degrees.

    The moves are Hill's (slide along u, v, n; roll about n, pitch about u,
    yaw about v); each changes the camera in place and returns it, so they
    chain: ``cam.slide(0, 0, -2).yaw(10)``. A camera that cannot make rays
    (eye at the look-at point, up along the view, angle outside (0, 180))
    raises ArgumentError when rendered or asked for a ray.
    """

    eye: Vec3 = (0.0, 0.0, 5.0)
    look: Vec3 = (0.0, 0.0, 0.0)
    up: Vec3 = (0.0, 1.0, 0.0)
    angle: float = 45.0

    def __post_init__(self) -> None:
        self.eye = _convert.vec3(self.eye, "camera eye")
        self.look = _convert.vec3(self.look, "camera look")
        self.up = _convert.vec3(self.up, "camera up")
        self.angle = _convert.number(self.angle, "camera angle")

    def _as_core(self) -> Tuple[Vec3, Vec3, Vec3, float]:
        # Fields may have been assigned since __init__: check them again.
        return (_convert.vec3(self.eye, "camera eye"), _convert.vec3(self.look, "camera look"),
                _convert.vec3(self.up, "camera up"), _convert.number(self.angle, "camera angle"))

    @classmethod
    def _from_core(cls, value: Any) -> "Camera":
        eye, look, up, angle = value
        return cls(eye, look, up, angle)

    def _move(self, move: str, a: float, b: float = 0.0, c: float = 0.0) -> "Camera":
        eye, look, up, angle = _core.camera_move(self._as_core(), move, _convert.number(a, move),
                                                 _convert.number(b, move), _convert.number(c, move))
        self.eye, self.look, self.up, self.angle = eye, look, up, angle
        return self

    def slide(self, du: float, dv: float, dn: float) -> "Camera":
        """Move eye and look-at point along the camera's own axes u, v, n."""
        return self._move("slide", du, dv, dn)

    def roll(self, degrees: float) -> "Camera":
        """Turn about n (the view axis)."""
        return self._move("roll", degrees)

    def pitch(self, degrees: float) -> "Camera":
        """Turn about u (nod up or down)."""
        return self._move("pitch", degrees)

    def yaw(self, degrees: float) -> "Camera":
        """Turn about v (look left or right)."""
        return self._move("yaw", degrees)

    def ray(self, px: float, py: float, size: Tuple[int, int] = (640, 480)) -> Tuple[Vec3, Vec3]:
        """The ray (origin, unit direction) through image position (px, py),
        in pixels from the top-left corner of an image of `size`; pixel (i, j)
        has its centre at (i + 0.5, j + 0.5)."""
        w, h = _convert.size(size)
        origin, direction = _core.camera_ray(self._as_core(), w, h, _convert.number(px, "px"),
                                             _convert.number(py, "py"))
        return origin, direction

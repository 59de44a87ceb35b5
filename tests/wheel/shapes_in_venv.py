"""Run by the fresh venv's interpreter (tests/wheel/test_wheel.py): a
triangle mesh from numpy arrays (the mesh module of the wheel) and a shape
class written in Python (hitray.abi, through cffi and the wheel's headers),
each hit by one ray; prints the hits as JSON."""

import json
import math

import numpy

import hitray
from hitray import abi


class Ball:
    """a sphere of a given radius at the origin, in Python"""

    closed = True
    hit_relative_error = 1e-12

    def __init__(self, radius=1.0):
        self.radius = radius

    def bounds(self):
        r = self.radius
        return ((-r, -r, -r), (r, r, r))

    def hit(self, origin, direction, tmin, tmax):
        ox, oy, oz = origin
        dx, dy, dz = direction
        a = dx * dx + dy * dy + dz * dz
        b = ox * dx + oy * dy + oz * dz
        c = ox * ox + oy * oy + oz * oz - self.radius * self.radius
        disc = b * b - a * c
        if disc < 0.0:
            return []
        q = -(b + math.copysign(math.sqrt(disc), b))
        t0, t1 = sorted((q / a, c / q))
        return [(t, (ox + t * dx, oy + t * dy, oz + t * dz), entering)
                for t, entering in ((t0, True), (t1, False)) if tmin < t < tmax]


# A tetrahedron whose face z = 0 a ray down the z axis meets at t = 5.
vertices = numpy.array([[-1.0, -1.0, 0.0], [2.0, -1.0, 0.0], [-1.0, 2.0, 0.0], [0.0, 0.0, -1.0]])
faces = numpy.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]], dtype=numpy.int32)
mesh_scene = hitray.Scene()
mesh_scene.add(hitray.Mesh(vertices=vertices, faces=faces))
mesh_hit = mesh_scene.first_hit((0.0, 0.0, 5.0), (0.0, 0.0, -1.0))

abi.register_shape("wheelball", Ball)
ball_scene = hitray.Scene()
ball_scene.add(hitray.Shape("wheelball", radius=2.0))
ball_hit = ball_scene.first_hit((0.0, 0.0, 5.0), (0.0, 0.0, -1.0))

print(json.dumps({
    "mesh_t": mesh_hit.t if mesh_hit else None,
    "ball_t": ball_hit.t if ball_hit else None,
    "ball_normal": list(ball_hit.normal) if ball_hit else None,
    "abi_library": abi.loaded_library_path(),
    "abi_headers": abi.declarations().headers[0],
}))

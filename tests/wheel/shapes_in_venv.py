"""Run by the fresh venv's interpreter (tests/wheel/test_wheel.py): a
triangle mesh from numpy arrays (the mesh module of the wheel) and a shape
class written in Python (hitray.abi, through cffi and the wheel's headers),
each hit by one ray; prints the hits as JSON."""

import json
import pathlib
import sys

import numpy

import hitray
from hitray import abi

# The Python sphere the hitray.abi tests register, from the source tree (it
# needs nothing but math).
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "python"))
from abi_shapes import Ball  # noqa: E402


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

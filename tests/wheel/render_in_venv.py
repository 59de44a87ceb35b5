"""Run by the fresh venv's interpreter (tests/wheel/test_wheel.py): renders
a scene touching every kind of shape module, writes PNG and EXR, and prints
as JSON what the test checks: where hitray was imported from, the image's
numbers, and every shared object this process has mapped."""

import json
import sys

import numpy

import hitray

SCENE = """
camera 0 2 8  0 0.5 0  0 1 0  40
light 4 6 5  1 1 1
push rotate -90 1 0 0 diffuse .6 .6 .6 plane pop
push translate -1.5 1 0 diffuse .9 .2 .2 sphere pop
push translate 1.5 1 0 diffuse .2 .5 .9 scale .6 .6 .6 cube pop
push translate 0 1 -2 diffuse .2 .8 .3 scale .5 .5 .5 tetrahedron pop
push translate 0 2.2 0 diffuse .8 .8 .2 rotate 90 1 0 0 scale .6 .6 .6 torus pop
push translate 0 0.5 1.5 diffuse .7 .3 .7 scale .4 .4 .4 cylinder pop
"""

scene, camera = hitray.parse_sdl(SCENE)
image = hitray.render(scene, camera, size=(64, 48), spp=2, progress=False)
out = sys.argv[1]
image.save(out + ".png")
image.save(out + ".exr")
pixels = numpy.asarray(image)
with open("/proc/self/maps") as maps:
    mapped = sorted({line.split(None, 5)[5].strip() for line in maps
                     if len(line.split(None, 5)) == 6 and ".so" in line})
print(json.dumps({
    "hitray": hitray.__file__,
    "shape": list(pixels.shape),
    "finite": bool(numpy.isfinite(pixels).all()),
    "max": float(pixels.max()),
    "distinct": int(len(numpy.unique(pixels.reshape(-1, 3), axis=0))),
    "mapped": mapped,
}))

"""A scene built in Python: Hill's shapes under transforms, a boolean, a
torus, materials named as in SDL; rendered, saved, and queried.
This is the README's Python example; tests/python/test_examples.py runs it.

    python examples/python/scene_in_code.py [OUTPUT.png]
"""
import sys

import numpy

import hitray

scene = hitray.Scene()
scene.background = (0.1, 0.1, 0.2)
scene.light((5, 8, 6), (1, 1, 1))
scene.add(hitray.Plane().rotate(-90, 1, 0, 0), diffuse=(0.6, 0.6, 0.6))
# A ball with a cube bitten out of it: M = T.S, so the cube is scaled first.
bite = hitray.Cube().translate(-0.6, 1.6, 0.6).scale(0.6)
scene.add(hitray.Sphere().translate(-1.2, 1, 0) - bite,
          diffuse=(0.9, 0.2, 0.2), specular=(0.5, 0.5, 0.5), specularExponent=30)
scene.add(hitray.Torus(tube=0.3).translate(1.3, 1, 0).rotate(60, 1, 0, 0),
          diffuse=(0.2, 0.5, 0.9), reflectivity=0.5)
camera = hitray.Camera(eye=(0, 3, 8), look=(0, 1, 0), up=(0, 1, 0), angle=40)

image = hitray.render(scene, camera, size=(640, 480), spp=4)
image.save(sys.argv[1] if len(sys.argv) > 1 else "scene_in_code.png")
pixels = numpy.asarray(image)          # float32, 480 x 640 x 3, the image's own memory
print(pixels.shape, image.stats.rays, "rays,", sorted(image.stats.effects))
print(scene.first_hit((-1.2, 1, 8), (0, 0, -1)))   # Hill's getFirstHit

# %% [markdown]
# # The demo scene from Python
# Notebook-style: run it as a script, or cell by cell in Jupyter or an editor
# that knows `# %%` cells (there the image shows itself under the cell).
#
#     python examples/python/render_demo.py [--size 480x360] [--spp 2] [-o demo.png]

# %%
import argparse
import pathlib

import numpy as np

import hitray

ROOT = pathlib.Path(__file__).resolve().parents[2]
parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--size", default="640x480", help="WIDTHxHEIGHT")
parser.add_argument("--spp", type=int, default=4, help="samples per pixel")
parser.add_argument("-o", "--output", default="demo_python.png")
args, _ = parser.parse_known_args()  # Jupyter passes arguments of its own
size = tuple(int(v) for v in args.size.split("x"))

# %% Load Hill's SDL scene: the scene and its camera.
scene, camera = hitray.load_sdl(ROOT / "scenes" / "demo.sdl")
print(scene, camera)
print("objects:", [o.shape for o in scene.objects])

# %% Render it; progress shows as a bar at a terminal or in Jupyter, Ctrl-C stops it cleanly.
image = hitray.render(scene, camera, size=size, spp=args.spp)
print(image, image.stats)

# %% The pixels are a numpy array (linear light, no copy).
pixels = np.asarray(image)
print("mean colour:", pixels.reshape(-1, 3).mean(axis=0))

# %% Show it: in Jupyter the Image displays itself; elsewhere, write a PNG.
try:
    from IPython import get_ipython
    from IPython.display import display
except ImportError:
    get_ipython = None
if get_ipython is not None and get_ipython() is not None:
    display(image)
else:
    image.save(args.output)
    print("wrote", args.output)

# %% Hill's queries: every hit along a ray down the middle of the view.
origin, direction = camera.ray(size[0] / 2, size[1] / 2, size)
for hit in scene.hits(origin, direction):
    print(f"t={hit.t:.4f} object={hit.object} ({scene.objects[hit.object].shape}) "
          f"{'enters' if hit.entering else 'leaves'}")

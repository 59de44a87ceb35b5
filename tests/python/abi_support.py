"""What the hitray.abi tests share: which hitray they test, and small
helpers over the raw ABI (scenes from SDL text, queries, renders).

Two modes, chosen once:
- installed: the hitray package is importable with its extension module
  (pip install . at the root, as `make test` does): hitray.abi loads the
  package's own libhitray, as a user's program would;
- build tree: no package, so hitray.abi is imported from
  bindings/python/src and loads lib/libhitray.so.0 of the build tree named by
  HITRAY_BUILD_DIR (default ./build), the way test_cli.py finds the binary.
  HITRAY_ABI_MODE=build chooses this mode even with the package installed
  (to test the source, or a sanitizer build of the library); run only the
  test_abi_* files then, as the stand-in package hides the installed one.
"""

import importlib
import math
import os
import pathlib
import sys
import types

ROOT = pathlib.Path(__file__).resolve().parents[2]
SOURCE = ROOT / "bindings" / "python" / "src"
BUILD = pathlib.Path(os.environ.get("HITRAY_BUILD_DIR", ROOT / "build"))


def _import_abi():
    if os.environ.get("HITRAY_ABI_MODE") != "build":
        try:
            importlib.import_module("hitray._core")
        except ImportError:
            pass
        else:
            return importlib.import_module("hitray.abi"), "installed"
    # The source tree's hitray/__init__.py (if any) needs the extension:
    # stand in for the package with its directory only.
    for name in [n for n in sys.modules if n == "hitray" or n.startswith("hitray.")]:
        del sys.modules[name]
    package = types.ModuleType("hitray")
    package.__path__ = [str(SOURCE / "hitray")]
    sys.modules["hitray"] = package
    abi = importlib.import_module("hitray.abi")
    abi.use_library(BUILD / "lib" / "libhitray.so.0", include_dir=ROOT / "include")
    return abi, "build tree"


abi, MODE = _import_abi()
ffi, lib = abi.ffi, abi.lib
INCLUDE = pathlib.Path(abi.declarations().headers[0]).parent.parent


class SceneContext(abi.Context):
    """An abi.Context that destroys the scenes load_sdl made on it, left
    over by a failed test, before it is destroyed itself (a scene must not
    outlive its context: its objects call back into classes registered
    there)."""

    def __init__(self):
        super().__init__()
        self.scenes = []

    def close(self):
        while self.scenes:
            destroy(self.scenes[-1])
        super().close()


def load_sdl(ctx, text):
    """A committed scene from SDL text, on the SceneContext `ctx`."""
    r = ffi.new("hr_sdl_result *")
    r.struct_size = ffi.sizeof("hr_sdl_result")
    ctx.check(lib.hr_sdl_load_string(ctx.ptr, text.encode(), b"test.sdl", ffi.NULL, r))
    scene = r.scene
    ctx.scenes.append(scene)
    _owners[int(ffi.cast("uintptr_t", scene))] = ctx
    ctx.check(lib.hr_scene_commit(scene))
    camera = ffi.new("hr_camera *")
    camera[0] = r.camera
    return scene, camera


_owners = {}  # scene address -> the SceneContext that holds it


def destroy(scene):
    """Destroy a scene from load_sdl."""
    ctx = _owners.pop(int(ffi.cast("uintptr_t", scene)))
    ctx.scenes.remove(scene)
    lib.hr_scene_destroy(scene)


def ray(origin, direction):
    return ffi.new("hr_ray *", {"origin": tuple(origin), "dir": tuple(direction)})


def first_hit(ctx, scene, origin, direction, tmin=0.0, tmax=math.inf):
    """Hill's getFirstHit: (t, point, normal, object) or None."""
    out = ffi.new("hr_hit *")
    found = ffi.new("int32_t *")
    ctx.check(lib.hr_scene_first_hit(scene, ray(origin, direction), tmin, tmax, out, found))
    if not found[0]:
        return None
    return (out.t, (out.point.x, out.point.y, out.point.z),
            (out.normal.x, out.normal.y, out.normal.z), out.object)


def all_hits(ctx, scene, origin, direction, tmin=0.0, tmax=math.inf):
    """Hill's Intersection: [(t, entering, object), ...]."""
    out = ffi.new("hr_intersection *")
    lib.hr_intersection_init(out)
    try:
        ctx.check(lib.hr_scene_all_hits(scene, ray(origin, direction), tmin, tmax, out))
        return [(out.hits[i].t, out.hits[i].entering, out.hits[i].object)
                for i in range(out.count)]
    finally:
        lib.hr_intersection_release(out)


def render(ctx, scene, camera, width, height, threads):
    """Pixels (a list of floats) of a render at width x height."""
    opts = ffi.new("hr_render_options *")
    lib.hr_render_options_default(opts)
    opts.width, opts.height, opts.threads = width, height, threads
    image = ffi.new("hr_image **")
    ctx.check(lib.hr_render(scene, camera, opts, image, ffi.NULL))
    try:
        n = width * height * 3
        return list(ffi.unpack(lib.hr_image_data(image[0]), n))
    finally:
        lib.hr_image_destroy(image[0])

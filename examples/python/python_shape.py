#!/usr/bin/env python3
"""A shape written in Python, rendered next to hitray's C shapes.

The capped paraboloid below is a solid of revolution about z: inside it
x^2 + y^2 < z < height, so its surfaces are the paraboloid wall and a flat
cap of radius sqrt(height). It is registered with hitray.abi.register_shape
and then named in SDL like any module's class (`paraboloid 1.6`: its one
parameter, positionally), beside a C sphere, cube and plane. With the hitray
package it goes through hitray.parse_sdl and hitray.render; with --build-dir,
through the C API itself (hitray.abi.lib), with no package at all.

  python examples/python/python_shape.py out/paraboloid.png        # installed package
  python examples/python/python_shape.py out/p.png --build-dir build  # a build tree
"""

import argparse
import math
import pathlib
import sys
import types

ROOT = pathlib.Path(__file__).resolve().parents[2]


WALL, CAP = 0, 1


class Paraboloid:
    """capped paraboloid x^2 + y^2 < z < height about the z axis"""

    closed = True        # a solid: entering and leaving alternate (usable in CSG)
    surface_names = ("wall", "cap")  # surface ids 0 and 1 (so surface_count is 2)
    hit_relative_error = 1e-12  # the roots below are stable to a few ulps
    params = {"height": 1.0}

    def __init__(self, height):
        if not height > 0:
            raise ValueError(f"height must be > 0, not {height}")
        self.height = height

    def bounds(self):
        r = math.sqrt(self.height)
        return ((-r, -r, 0.0), (r, r, self.height))

    def hit(self, origin, direction, tmin, tmax):
        ox, oy, oz = origin
        dx, dy, dz = direction
        h = self.height
        # Where the ray is inside the wall: f(t) = a t^2 + b t + c < 0 with
        # f = x^2 + y^2 - z along the ray; a >= 0.
        a = dx * dx + dy * dy
        b = 2.0 * (ox * dx + oy * dy) - dz
        c = ox * ox + oy * oy - oz
        if a > 0.0:
            disc = b * b - 4.0 * a * c
            if disc < 0.0:
                return []
            # The stable pair: no cancellation between -b and the root.
            q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
            if q == 0.0:
                return []  # b = c = 0: the ray touches the apex only
            t_in, t_out = sorted((q / a, c / q))
        elif b != 0.0:  # parallel to the axis: one crossing of the wall
            t = -c / b
            t_in, t_out = (t, math.inf) if b < 0.0 else (-math.inf, t)
        else:
            return []  # never inside (c > 0) or along the surface itself
        s_in = s_out = WALL
        # ... and below the cap: z < h.
        if dz != 0.0:
            t_cap = (h - oz) / dz
            if dz > 0.0 and t_cap < t_out:
                t_out, s_out = t_cap, CAP
            elif dz < 0.0 and t_cap > t_in:
                t_in, s_in = t_cap, CAP
        elif oz >= h:
            return []
        if not t_in <= t_out:
            return []
        hits = []
        for t, surface, entering in ((t_in, s_in, True), (t_out, s_out, False)):
            if tmin < t < tmax:
                if surface == WALL:
                    # Outward: the gradient of x^2 + y^2 - z.
                    normal = (2.0 * (ox + t * dx), 2.0 * (oy + t * dy), -1.0)
                else:
                    normal = (0.0, 0.0, 1.0)
                hits.append((t, normal, entering, surface))
        return hits


SCENE = """! A Python paraboloid beside hitray's C shapes.
camera 0 2.2 7.5   0 0.6 0   0 1 0   38
background 0.55 0.7 0.9
globalAmbient 0.2 0.2 0.2
minReflectivity 0.1                ! let the ball's and the floor's reflectivity count (default 0.5)
light 4 8 6   1 1 1
light -6 5 4  0.4 0.4 0.5

! the paraboloid stands on the floor, opening upwards
push translate 0 0 0 rotate -90 1 0 0
  diffuse 0.9 0.55 0.15 specular 0.6 0.6 0.6 specularExponent 40
  paraboloid 1.6
pop
push translate -2.1 0.8 -0.6 scale 0.8 0.8 0.8
  diffuse 0.2 0.35 0.9 specular 0.8 0.8 0.8 specularExponent 60 reflectivity 0.3
  sphere
pop
push translate 2.0 0.6 -0.3 rotate 30 0 1 0 scale 0.6 0.6 0.6
  diffuse 0.3 0.8 0.3 specular 0.3 0.3 0.3 specularExponent 20
  cube
pop
push rotate -90 1 0 0
  diffuse 0.75 0.75 0.75 reflectivity 0.15
  plane
pop
"""


def render_with_package(width, height, args):
    """The usual way: the hitray package, its default context."""
    import hitray
    import hitray.abi

    hitray.abi.register_shape("paraboloid", Paraboloid)
    scene, camera = hitray.parse_sdl(SCENE, "python_shape.sdl")
    image = hitray.render(scene, camera, size=(width, height), spp=args.spp,
                          threads=args.threads or None, progress=False)
    image.save(args.output)
    return image.stats.seconds, image.stats.threads


def render_with_abi(width, height, args):
    """The C API itself through hitray.abi, on a build tree's libhitray (no
    package needed): the calls a C program makes."""
    package = types.ModuleType("hitray")  # hitray.abi alone, from the source tree
    package.__path__ = [str(ROOT / "bindings" / "python" / "src" / "hitray")]
    sys.modules["hitray"] = package
    import hitray.abi as abi

    abi.use_library(pathlib.Path(args.build_dir) / "lib" / "libhitray.so.0",
                    include_dir=ROOT / "include")
    ffi, lib = abi.ffi, abi.lib
    with abi.Context() as ctx:
        abi.register_shape("paraboloid", Paraboloid, context=ctx)
        result = ffi.new("hr_sdl_result *")
        result.struct_size = ffi.sizeof("hr_sdl_result")
        ctx.check(lib.hr_sdl_load_string(ctx.ptr, SCENE.encode(), b"python_shape.sdl",
                                         ffi.NULL, result))
        image = ffi.new("hr_image **")
        stats = ffi.new("hr_render_stats *")
        stats.struct_size = ffi.sizeof("hr_render_stats")
        try:
            ctx.check(lib.hr_scene_commit(result.scene))
            options = ffi.new("hr_render_options *")
            lib.hr_render_options_default(options)
            options.width, options.height = width, height
            options.samples_per_pixel = args.spp
            options.threads = args.threads
            camera = ffi.new("hr_camera *", result.camera)
            ctx.check(lib.hr_render(result.scene, camera, options, image, stats))
            ctx.check(lib.hr_image_write(ctx.ptr, image[0], str(args.output).encode(),
                                         ffi.NULL))
        finally:
            lib.hr_image_destroy(image[0])
            lib.hr_scene_destroy(result.scene)
        return stats.seconds, stats.threads


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("output", help="image to write (.png, .exr, .ppm or .pfm)")
    ap.add_argument("--size", default="640x480", help="WIDTHxHEIGHT (default 640x480)")
    ap.add_argument("--spp", type=int, default=1, help="samples per pixel")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0: every core)")
    ap.add_argument("--build-dir", help="no package: the C API through hitray.abi, on this "
                                        "build tree's libhitray")
    args = ap.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))
    pathlib.Path(args.output).parent.mkdir(parents=True, exist_ok=True)
    render = render_with_abi if args.build_dir else render_with_package
    seconds, threads = render(width, height, args)
    print(f"{args.output}: {width}x{height} in {seconds:.2f} s on {threads} threads")


if __name__ == "__main__":
    main()

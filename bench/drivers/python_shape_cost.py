#!/usr/bin/env python3
"""What a shape written in Python costs per hit, against the C sphere.

The same unit sphere twice: the C module `sphere` and a Python class with the
same quadratic, registered through hitray.abi. Both are traced through the
same paths:

- render: hr_render casts the primary rays (no lights, so one ray per pixel
  and one hit call per ray whose box test passes); threads 1 and 2, to show
  that Python callbacks serialise on the GIL;
- query: hr_scene_first_hit called from Python once per ray, the path a
  Python program asking Hill's getFirstHit takes (both sides pay cffi's call).

Each timing is the best of --repeat runs (the machine may be busy; the best
run is the one least disturbed). Prints a Markdown table.

  python bench/drivers/python_shape_cost.py                       # the installed package
  python bench/drivers/python_shape_cost.py --build-dir build     # a build tree
"""

import argparse
import math
import os
import pathlib
import sys
import time
import types

ROOT = pathlib.Path(__file__).resolve().parents[2]


def import_abi(build_dir):
    if build_dir is None:
        import hitray.abi as abi
        return abi
    # A build tree: hitray.abi from the source, libhitray from the build.
    package = types.ModuleType("hitray")
    package.__path__ = [str(ROOT / "bindings" / "python" / "src" / "hitray")]
    sys.modules["hitray"] = package
    import hitray.abi as abi
    abi.use_library(pathlib.Path(build_dir) / "lib" / "libhitray.so.0",
                    include_dir=ROOT / "include")
    return abi


class PySphere:
    """unit sphere at the origin, in Python (the C sphere's quadratic)"""

    closed = True
    calls = 0

    def bounds(self):
        return ((-1.0, -1.0, -1.0), (1.0, 1.0, 1.0))

    def hit(self, origin, direction, tmin, tmax):
        PySphere.calls += 1
        ox, oy, oz = origin
        dx, dy, dz = direction
        a = dx * dx + dy * dy + dz * dz
        b = ox * dx + oy * dy + oz * dz
        c = ox * ox + oy * oy + oz * oz - 1.0
        disc = b * b - a * c
        if disc < 0.0:
            return []
        q = -(b + math.copysign(math.sqrt(disc), b))
        t0, t1 = sorted((q / a, c / q))
        hits = []
        if tmin < t0 < tmax:
            hits.append((t0, (ox + t0 * dx, oy + t0 * dy, oz + t0 * dz), True))
        if tmin < t1 < tmax:
            hits.append((t1, (ox + t1 * dx, oy + t1 * dy, oz + t1 * dz), False))
        return hits


class PyNothing(PySphere):
    """the sphere's bounds, but hit returns [] at once: what the layer alone costs"""

    def hit(self, origin, direction, tmin, tmax):
        PySphere.calls += 1
        return []


SCENE = "camera 0 0 4  0 0 0  0 1 0  30\n{shape}\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build-dir", help="use this build tree's libhitray, not the package's")
    ap.add_argument("--size", type=int, default=200, help="image side in pixels (default 200)")
    ap.add_argument("--rays", type=int, default=20000, help="rays for the query path")
    ap.add_argument("--repeat", type=int, default=5, help="runs per timing; the best is kept")
    ap.add_argument("--render-once", choices=("sphere", "pysphere", "pynothing"),
                    help="only render once with this shape on 1 thread (for counting "
                         "instructions, see bench/drivers/python_shape_instructions.sh)")
    args = ap.parse_args()
    abi = import_abi(args.build_dir)
    ffi, lib = abi.ffi, abi.lib

    with abi.Context() as ctx:
        abi.register_shape("pysphere", PySphere, context=ctx)
        abi.register_shape("pynothing", PyNothing, context=ctx)
        scenes = {}
        for name in ("sphere", "pysphere", "pynothing"):
            r = ffi.new("hr_sdl_result *")
            r.struct_size = ffi.sizeof("hr_sdl_result")
            ctx.check(lib.hr_sdl_load_string(ctx.ptr, SCENE.format(shape=name).encode(),
                                             b"bench.sdl", ffi.NULL, r))
            ctx.check(lib.hr_scene_commit(r.scene))
            cam = ffi.new("hr_camera *")
            cam[0] = r.camera
            scenes[name] = (r.scene, cam)

        def render_seconds(name, threads):
            scene, cam = scenes[name]
            opts = ffi.new("hr_render_options *")
            lib.hr_render_options_default(opts)
            opts.width = opts.height = args.size
            opts.threads = threads
            stats = ffi.new("hr_render_stats *")
            stats.struct_size = ffi.sizeof("hr_render_stats")
            best = math.inf
            for _ in range(args.repeat):
                image = ffi.new("hr_image **")
                ctx.check(lib.hr_render(scene, cam, opts, image, stats))
                lib.hr_image_destroy(image[0])
                best = min(best, stats.seconds)
            return best

        # One render to count the hit calls a render makes (deterministic).
        PySphere.calls = 0
        scene, cam = scenes[args.render_once or "pysphere"]
        opts = ffi.new("hr_render_options *")
        lib.hr_render_options_default(opts)
        opts.width = opts.height = args.size
        opts.threads = 1
        image = ffi.new("hr_image **")
        ctx.check(lib.hr_render(scene, cam, opts, image, ffi.NULL))
        lib.hr_image_destroy(image[0])
        calls = PySphere.calls
        rays = args.size * args.size
        if args.render_once:
            for scene, _ in scenes.values():
                lib.hr_scene_destroy(scene)
            print(f"{args.render_once}: {rays} rays, {calls} Python hit calls")
            return

        rows = []
        for threads in (1, 2):
            c = render_seconds("sphere", threads)
            py = render_seconds("pysphere", threads)
            rows.append((f"render, {threads} thread{'s' if threads > 1 else ''}", c, py))

        # The query path: one hr_scene_first_hit per ray, from Python.
        ray = ffi.new("hr_ray *")
        hit = ffi.new("hr_hit *")
        found = ffi.new("int32_t *")
        n = args.rays

        def query_seconds(name):
            scene, _ = scenes[name]
            best = math.inf
            for _ in range(args.repeat):
                start = time.perf_counter()
                for i in range(n):
                    # A fan of rays through the sphere's middle: every one hits.
                    ray.origin = (0.0, 0.0, 4.0)
                    ray.dir = (-0.2 + 0.4 * i / n, 0.1, -1.0)
                    lib.hr_scene_first_hit(scene, ray, 0.0, math.inf, hit, found)
                best = min(best, time.perf_counter() - start)
            return best

        query = (query_seconds("sphere"), query_seconds("pysphere"))
        for scene, _ in scenes.values():
            lib.hr_scene_destroy(scene)

    print(f"libhitray: {abi.loaded_library_path()}")
    print(f"render: {args.size}x{args.size} primary rays, {calls} hit calls on the Python "
          f"sphere; query: {n} rays, all hits; best of {args.repeat}\n")
    print("| path | C sphere ns/ray | Python sphere ns/ray | ratio | Python extra ns/hit call |")
    print("|---|---:|---:|---:|---:|")
    for label, c, py in rows:
        print(f"| {label} | {c / rays * 1e9:.0f} | {py / rays * 1e9:.0f} | {py / c:.0f}x | "
              f"{(py - c) / calls * 1e9:.0f} |")
    c, py = query
    print(f"| hr_scene_first_hit from Python | {c / n * 1e9:.0f} | {py / n * 1e9:.0f} | "
          f"{py / c:.1f}x | {(py - c) / n * 1e9:.0f} |")
    one, two = rows[0][2], rows[1][2]
    print(f"\nPython sphere, 2 threads vs 1: {two / one:.2f}x the time "
          f"(C sphere: {rows[1][1] / rows[0][1]:.2f}x)")
    print(f"cores available: {len(os.sched_getaffinity(0))}")


if __name__ == "__main__":
    main()

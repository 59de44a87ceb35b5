#!/usr/bin/env python3
"""hitray.distributed against hitray.render on this machine: 1 and 2 Dask
workers, tiles of several sizes.

For each worker count a LocalCluster of that many worker processes (one
Dask thread each, the machine's cores shared among them) renders the frame
with each tile size. Reported per run:

- wall: the best of --runs distributed renders (seconds);
- speed-up: hitray.render on every core, divided by wall;
- overhead/tile: what a tile costs beyond its rays, in milliseconds of one
  core: (wall x cores - the single-thread render's time) / tiles. It holds
  shipping the tile's task and its pixels, scheduling, gathering, and the
  rays a tile casts twice (adaptive corners, Hill's blocks cut by a tile);
- ship: scattering the scene (pickled with its files) to every worker once.

The tile size that balances overhead (many small tiles) against idle
workers at the end of the frame (few big ones) is the one with the least
wall time; it is marked. Each figure is the best of --runs (a busy machine
disturbs some runs; the best is the least disturbed). Every distributed
image is checked to be bit-identical to hitray.render's. Prints Markdown.

  .venv/bin/python bench/drivers/distributed.py                     # scenes/demo.sdl, 640x480, spp 4
  .venv/bin/python bench/drivers/distributed.py --size 640x480 --spp 16 --tiles 16,32,64,128
"""

import argparse
import os
import pathlib
import sys
import time

# This file is named distributed.py: its folder, first on sys.path, would
# shadow Dask's `distributed` (here and in the worker processes, which take
# this sys.path).
HERE = pathlib.Path(__file__).resolve().parent
sys.path = [p for p in sys.path if pathlib.Path(p or ".").resolve() != HERE]

try:
    import numpy as np
    import distributed  # noqa: F401 - Dask's, checked here: the cluster is made in main

    import hitray
    import hitray.distributed as hd
    from hitray.distributed._client import local_cores
except ImportError as e:
    # `make demo` builds the command only: the package and Dask are
    # `make python-install`'s (into .venv, with scripts/requirements-test.txt).
    sys.exit(f"bench/distributed.py: {e}: this needs the hitray package and Dask in {sys.executable}; "
             f"`make python-install` puts both into .venv (then run .venv/bin/python bench/distributed.py)")

ROOT = pathlib.Path(__file__).resolve().parents[2]


def best(runs, fn):
    times, out = [], None
    for _ in range(runs):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scene", default=str(ROOT / "scenes" / "demo.sdl"))
    p.add_argument("--size", default="640x480")
    p.add_argument("--spp", type=int, default=4)
    p.add_argument("--tiles", default="8,16,32,64,128")
    p.add_argument("--workers", default="1,2")
    p.add_argument("--runs", type=int, default=3)
    a = p.parse_args()

    size = tuple(int(v) for v in a.size.lower().split("x"))
    tiles = [int(t) for t in a.tiles.split(",")]
    cores = local_cores()
    scene, camera = hitray.load_sdl(a.scene)
    if camera is None:
        camera = scene.frame_camera(size)
    one, _ = best(a.runs, lambda: hitray.render(scene, camera, size, spp=a.spp, threads=1, progress=False))
    full, ref = best(a.runs, lambda: hitray.render(scene, camera, size, spp=a.spp, progress=False))
    reference = np.asarray(ref)
    pack = hd.ScenePack(scene)
    print(f"scene {os.path.relpath(a.scene, ROOT)}, {size[0]}x{size[1]}, spp {a.spp}, {cores} cores; "
          f"hitray.render: {one:.3f} s on 1 thread, {full:.3f} s on {cores}; the shipped scene "
          f"carries {len(pack.files)} file{'' if len(pack.files) == 1 else 's'} ({pack.shipped_bytes} bytes)\n")
    print("| workers | tile | tiles | wall (s) | speed-up | overhead/tile (ms) | ship (ms) |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for workers in (int(w) for w in a.workers.split(",")):
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                      dashboard_address=":0") as cluster, distributed.Client(cluster) as client:
            threads = max(1, cores // workers)

            def ship():
                future = client.scatter(pack, broadcast=True, hash=False)
                future.release()
            ship_time, _ = best(a.runs, ship)
            rows = []
            for tile in tiles:
                wall, image = best(a.runs, lambda: hd.render(scene, camera, size, spp=a.spp, client=client,
                                                             tile=tile, threads=threads, progress=False))
                if not np.array_equal(np.asarray(image), reference):
                    raise SystemExit(f"workers {workers}, tile {tile}: the image differs from hitray.render's")
                count = len(hd.windows(size, tile))
                rows.append((wall, tile, count))
            fastest = min(rows)[1]
            for wall, tile, count in rows:
                overhead = (wall * cores - one) / count * 1e3
                mark = " **best**" if tile == fastest else ""
                print(f"| {workers} | {tile}{mark} | {count} | {wall:.3f} | {full / wall:.2f} | {overhead:.2f} | "
                      f"{ship_time * 1e3:.1f} |")


if __name__ == "__main__":
    main()

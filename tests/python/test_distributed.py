"""hitray.distributed on a LocalCluster of 2 worker processes on loopback,
started once for the module: frames bit-identical to hitray.render (EXR
bytes compared) for every option and tile size, a worker killed mid-frame,
a scene whose mesh file only the client can read, animations written,
skipped and resumed, cancellation, and bad input."""

import json
import os
import pathlib
import re
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import hitray

from conftest import BUILD, ROOT, TWO_SPHERES_SDL, require_classes, sigint_as_at_a_terminal

distributed = pytest.importorskip("distributed", reason="dask[distributed] is not installed")
dask = pytest.importorskip("dask")
hd = pytest.importorskip("hitray.distributed")
from hitray.distributed._client import local_cores  # noqa: E402
from hitray.distributed._render import render_window  # noqa: E402

HITRAY = BUILD / "bin" / "hitray"
MESH_SCENE = ROOT / "tests" / "data" / "scenes" / "mesh_solids.sdl"
CUBE_3VN = ROOT / "tests" / "data" / "meshes" / "cube.3vn"

# ((A | B) - bite) on a mirror floor: booleans nested, shadows and
# reflections through them.
CSG_SDL = """\
camera 0 2 6   0 0.3 0   0 1 0   40
light 4 6 5   1 1 1
diffuse 0.9 0.2 0.1 specular 0.5 0.5 0.5 specularExponent 25
difference
  union
    sphere
    push translate 0.6 0 0.4 diffuse 0.1 0.8 0.2 sphere pop
  push translate 0 0.4 1.1 scale .6 .6 .6 sphere pop
push translate 0 -1 0 rotate -90 1 0 0 diffuse 0.5 0.5 0.5 reflectivity 0.6 plane pop
"""


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       host="127.0.0.1", dashboard_address=":0")
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def exr_bytes(image, path):
    image.save(path)
    return pathlib.Path(path).read_bytes()


def two_spheres():
    scene = hitray.Scene()
    scene.add(hitray.Sphere().translate(-0.8, 1, 0), diffuse=(0.8, 0.2, 0.2), specular=(0.5, 0.5, 0.5),
              specularExponent=20)
    scene.add(hitray.Sphere().translate(1, 1, -0.5), diffuse=(0.1, 0.1, 0.1), transparency=0.8,
              speedOfLight=0.7)
    scene.add(hitray.Plane().rotate(-90, 1, 0, 0), diffuse=(0.6, 0.6, 0.6), reflectivity=0.5)
    scene.light((5, 8, 6), (1, 1, 1))
    return scene, hitray.Camera((0, 2, 8), (0, 1, 0), (0, 1, 0), 40)


def scene_of(kind):
    if kind == "mesh":
        require_classes("mesh")
        return hitray.load_sdl(MESH_SCENE)
    if kind == "csg":
        require_classes("union", "difference")
        return hitray.parse_sdl(CSG_SDL, "csg.sdl")
    return two_spheres()


# (scene, options) of the identity checks: spp 1 and 16, adaptive, blocks
# and depth, a mesh scene and a CSG scene.
CASES = {
    "spp1": ("spheres", {}),
    "spp16": ("spheres", {"spp": 16}),
    "adaptive": ("spheres", {"spp": 8, "adaptive": 0.03}),
    "block3-depth1": ("spheres", {"block_size": 3, "depth": 1}),
    "mesh": ("mesh", {"spp": 2}),
    "csg": ("csg", {"spp": 4, "adaptive": 0.05}),
}


@pytest.mark.parametrize("tile", [None, 17, 64])
@pytest.mark.parametrize("case", sorted(CASES))
def test_distributed_frame_identity(client, tmp_path, case, tile):
    """Bands sized by measurement (None), tiles of 17 (cutting blocks of 3
    and adaptive corners) and 64 (one tile in a row, another cut by the
    edge) give the single render's EXR."""
    kind, options = CASES[case]
    scene, camera = scene_of(kind)
    size = (70, 45)
    here = hitray.render(scene, camera, size, progress=False, **options)
    there = hd.render(scene, camera, size, client=client, tile=tile, progress=False, **options)
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
    # Without adaptive corners or blocks shared by two tiles, the tiles cast
    # exactly the full render's rays.
    if "adaptive" not in options and "block_size" not in options:
        assert there.stats.rays == here.stats.rays
    assert there.stats.effects == here.stats.effects


@pytest.mark.parametrize("case", sorted(CASES))
def test_distributed_frame_identity_one_pixel_tiles(client, tmp_path, case):
    kind, options = CASES[case]
    scene, camera = scene_of(kind)
    size = (19, 13)  # 247 tiles
    here = hitray.render(scene, camera, size, progress=False, **options)
    there = hd.render(scene, camera, size, client=client, tile=1, progress=False, **options)
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")


def test_distributed_windows_cover_the_frame():
    tiles = hd.windows((70, 45), 17)
    covered = np.zeros((45, 70), dtype=int)
    for x, y, w, h in tiles:
        covered[y:y + h, x:x + w] += 1
    assert (covered == 1).all() and len(tiles) == 5 * 3


def killer(client):
    """A progress callback that kills (SIGKILL) one worker the first time
    it is called; the list of fractions it was called at; the pid killed."""
    pids = client.run(os.getpid)
    victim = pids[sorted(pids)[0]]
    killed = []

    def kill_once(fraction):
        if not killed:
            os.kill(victim, signal.SIGKILL)
            killed.append(fraction)
    return kill_once, killed, victim


def test_distributed_worker_killed_mid_frame(client, tmp_path):
    """One worker is killed (SIGKILL) once the first tile is back: its tiles
    run again on the other and on the worker its nanny restarts, and the
    frame is the same bits."""
    scene, camera = two_spheres()
    size, options = (64, 48), {"spp": 24}
    here = hitray.render(scene, camera, size, progress=False, **options)
    kill_once, killed, victim = killer(client)

    # Fetching a finished tile from the dead worker, before the scheduler
    # knows it is dead, is retried for the connect timeout (30 s by default):
    # shorter here, so the test does not wait on it.
    with dask.config.set({"distributed.comm.timeouts.connect": "3s"}):
        there = hd.render(scene, camera, size, client=client, tile=8, threads=1, progress=kill_once, **options)
    assert killed and killed[0] < 1.0
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
    client.wait_for_workers(2, timeout=120)
    assert victim not in client.run(os.getpid).values()


def test_distributed_worker_killed_mid_frame_bands(client, tmp_path):
    """The same with bands sized by measurement: the killed worker's bands
    are given back and handed on, and the frame is the same bits."""
    scene, camera = two_spheres()
    size, options = (96, 64), {"spp": 32}
    here = hitray.render(scene, camera, size, progress=False, **options)
    client.wait_for_workers(2, timeout=120)
    kill_once, killed, _ = killer(client)
    report = hd.Report()
    with dask.config.set({"distributed.comm.timeouts.connect": "3s"}):
        there = hd.render(scene, camera, size, client=client, progress=kill_once, report=report, **options)
    assert killed and killed[0] < 1.0
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
    assert report.pixels >= 96 * 64  # a band may have been rendered twice, never missed
    client.wait_for_workers(2, timeout=120)


def test_distributed_report(client):
    """What each worker did, added up: every band's pixels once, rays as
    the frame's, the balance and overhead share in their ranges."""
    scene, camera = two_spheres()
    size = (80, 60)
    client.wait_for_workers(2, timeout=120)
    report = hd.Report()
    image = hd.render(scene, camera, size, spp=4, client=client, progress=False, report=report)
    assert report.frames == 1 and report.pixels == 80 * 60
    assert report.tasks == sum(w.tasks for w in report.workers.values()) >= 2
    assert sum(w.rays for w in report.workers.values()) == image.stats.rays
    assert set(report.workers) <= set(client.scheduler_info()["workers"])
    assert all(w.threads == 1 and w.busy > 0 and w.rays_per_second > 0 for w in report.workers.values())
    assert report.balance >= 1.0 and 0.0 <= report.overhead_share <= 1.0
    assert report.wall > 0 and report.threads == len(report.workers)
    assert any("balance" in line for line in report.lines())


def test_distributed_slow_workers_band_is_split_and_handed_on(client, tmp_path):
    """One worker made slow (it sleeps 0.3 s before each chunk of rows):
    once the other has nothing left, it takes the rows the slow one has
    not begun, of the band waiting and of the band being rendered, and the
    frame is the single render's bits."""
    from hitray.distributed._band import set_test_delay

    scene, camera = two_spheres()
    size, options = (64, 256), {"spp": 4, "adaptive": 0.05}
    here = hitray.render(scene, camera, size, progress=False, **options)
    client.wait_for_workers(2, timeout=120)
    slow = sorted(client.scheduler_info()["workers"])[0]
    client.run(set_test_delay, 0.3, workers=[slow])
    report = hd.Report()
    try:
        there = hd.render(scene, camera, size, client=client, progress=False, report=report, **options)
    finally:
        client.run(set_test_delay, 0.0, workers=[slow])
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
    assert report.pixels == 64 * 256  # every row rendered once: the rows given up were not rendered
    assert report.workers[slow].split >= 1, report.lines()
    fast = next(w for w in report.workers if w != slow)
    assert report.workers[slow].pixels < report.workers[fast].pixels / 4, report.lines()


def test_distributed_band_on_all_of_a_workers_threads(tmp_path):
    """A worker of 2 Dask threads renders a band on both: one band at a
    time, 2 render threads each (the report says so), same bits."""
    scene, camera = two_spheres()
    here = hitray.render(scene, camera, (60, 40), spp=2, progress=False)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=True, host="127.0.0.1",
                                  dashboard_address=":0") as cluster, distributed.Client(cluster) as c:
        report = hd.Report()
        there = hd.render(scene, camera, (60, 40), spp=2, client=c, progress=False, report=report)
        # Four bands handed to the worker at once: its two Dask threads each
        # take one, yet they render one after the other, each on both
        # threads, never two at once on 2 threads each (4 threads on 2
        # cores). Each task says when it began and ended, on the worker's clock.
        pack = hd.ScenePack(scene)
        futures = [c.submit(render_window, pack, camera, (60, 40), {"spp": 16}, (0, y, 60, 10), pure=False)
                   for y in range(0, 40, 10)]
        results = c.gather(futures)
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
    (worker,) = report.workers.values()
    assert worker.threads == 2 and there.stats.threads == 2
    assert [r[3] for r in results] == [2, 2, 2, 2]
    spans = sorted((r[4], r[5]) for r in results)
    assert all(a[1] <= b[0] for a, b in zip(spans, spans[1:])), spans


def test_distributed_mesh_only_on_the_client(client, tmp_path):
    """A mesh file in a directory only this process can name
    (/proc/self/fd/N is each process's own): the workers cannot read it,
    yet the scene renders there from the copy shipped with it, named
    relative to the scene's directory and by an absolute path."""
    require_classes("mesh")
    shutil.copy(CUBE_3VN, tmp_path / "cube.3vn")
    fd = os.open(tmp_path, os.O_RDONLY | os.O_DIRECTORY)
    try:
        private = f"/proc/self/fd/{fd}"
        assert os.path.isfile(f"{private}/cube.3vn")
        assert not any(client.run(os.path.isfile, f"{private}/cube.3vn").values())
        text = ("camera 3 2.5 4 0 0 0 0 1 0 40\nlight 4 6 5 1 1 1\n"
                "push diffuse 0.8 0.3 0.2 rotate 30 0 1 0 mesh cube.3vn pop\n"
                f"push translate 0 -1.5 0 scale 0.5 0.5 0.5 diffuse 0.2 0.5 0.9 mesh {private}/cube.3vn pop\n")
        scene, camera = hitray.parse_sdl(text, "private.sdl", base_dir=private)
        pack = hd.ScenePack(scene)
        assert pack.files == [f"{private}/cube.3vn"]
        here = hitray.render(scene, camera, (40, 30), progress=False)
        there = hd.render(scene, camera, (40, 30), client=client, tile=16, progress=False)
        assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
        # A scene built in Python: the mesh's file is a string parameter.
        built = hitray.Scene()
        built.add(hitray.Mesh(f"{private}/cube.3vn").rotate(20, 1, 1, 0), diffuse=(0.9, 0.9, 0.2))
        built.light((4, 6, 5))
        here = hitray.render(built, camera, (40, 30), progress=False)
        there = hd.render(built, camera, (40, 30), client=client, tile=16, progress=False)
        assert exr_bytes(there, tmp_path / "there2.exr") == exr_bytes(here, tmp_path / "here2.exr")
    finally:
        os.close(fd)


def test_distributed_textured_scenes(client, tmp_path):
    """Pixmaps travel with the scene: an SDL scene's makePixmap file in a
    directory only this process can name, and a Python scene's pixmap made
    from an array (pickled as its pixels); solid textures need nothing."""
    require_classes("sphere", "square")
    pixels = np.zeros((4, 8, 3), dtype=np.float32)
    pixels[..., 0] = np.linspace(0, 1, 8, dtype=np.float32)
    pixels[::2, :, 2] = 0.75
    hitray.Image(pixels).save(tmp_path / "stripes.png", bits=16)
    fd = os.open(tmp_path, os.O_RDONLY | os.O_DIRECTORY)
    try:
        private = f"/proc/self/fd/{fd}"
        assert not any(client.run(os.path.isfile, f"{private}/stripes.png").values())
        text = (f"camera 0 0 4 0 0 0 0 1 0 40\nlight 3 4 5 1 1 1\nmakePixmap 1 {private}/stripes.png\n"
                "push texture 1 sphere pop\n"
                "push translate 0 -1 0 rotate -90 1 0 0 scale 3 3 3 texture -1 square pop\n")
        scene, camera = hitray.parse_sdl(text, "textured.sdl", base_dir=private)
        here = hitray.render(scene, camera, (40, 30), spp=2, progress=False)
        there = hd.render(scene, camera, (40, 30), spp=2, client=client, tile=16, progress=False)
        assert "texture" in here.stats.effects
        assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
    finally:
        os.close(fd)
    built = hitray.Scene()
    built.pixmap(1, hitray.Image(pixels))
    built.add(hitray.Sphere(), texture=1)
    built.light((3, 4, 5))
    here = hitray.render(built, camera, (40, 30), progress=False)
    there = hd.render(built, camera, (40, 30), client=client, tile=16, progress=False)
    assert exr_bytes(there, tmp_path / "there2.exr") == exr_bytes(here, tmp_path / "here2.exr")


def test_distributed_texture_filter_reaches_the_workers(client, tmp_path):
    """texture_filter travels with the other options: a checkerboard floor
    to the horizon, point-sampled (texture_filter="none") on the cluster,
    is bit for bit hitray.render's point-sampled image, and not its
    filtered one (the option changes this picture, so a worker that dropped
    it would be caught)."""
    require_classes("plane")
    text = ("camera 0 1.5 0  0 -4.353 -12  0 1 0  50\nlight 5 20 10 1 1 1\n"
            "push rotate -90 1 0 0 texture -1 plane pop\n")
    scene, camera = hitray.parse_sdl(text, "floor.sdl")
    size = (48, 36)
    point = hitray.render(scene, camera, size, progress=False, texture_filter="none")
    filtered = hitray.render(scene, camera, size, progress=False)
    there = hd.render(scene, camera, size, client=client, tile=16, progress=False, texture_filter="none")
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(point, tmp_path / "point.exr")
    assert exr_bytes(point, tmp_path / "point.exr") != exr_bytes(filtered, tmp_path / "filtered.exr")
    out = tmp_path / "frame_%d.exr"
    hd.render_frames([(scene, camera)], str(out), size=size, client=client, progress=False,
                     texture_filter="none")
    assert (tmp_path / "frame_0.exr").read_bytes() == (tmp_path / "point.exr").read_bytes()
    (tmp_path / "floor.sdl").write_text(text)
    proc = dist_cli("render", tmp_path / "floor.sdl", "-o", tmp_path / "cli.exr", "--size", "48x36",
                    "--scheduler", client.scheduler.address, "-q", "--texture-filter", "none")
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "cli.exr").read_bytes() == (tmp_path / "point.exr").read_bytes()


def orbit(i, count=12):
    scene, _ = two_spheres()
    angle = 2 * np.pi * i / count
    return scene, hitray.Camera((8 * np.sin(angle), 2, 8 * np.cos(angle)), (0, 1, 0), (0, 1, 0), 40)


def test_distributed_animation_bands_and_whole_frames(client, tmp_path):
    """Bands sized by measurement: whole frames while there are more frames
    than workers, bands at the end; every frame the bits of hitray.render,
    the report counting every pixel of every frame once."""
    pattern = str(tmp_path / "frame_%02d.exr")
    size = (40, 30)
    report = hd.Report()
    written = hd.render_frames(orbit, pattern, count=7, size=size, spp=2, client=client, progress=False,
                               report=report)
    assert sorted(written) == [pattern % i for i in range(7)]
    assert report.frames == 7 and report.pixels == 7 * 40 * 30
    for i in range(7):
        scene, camera = orbit(i)
        here = exr_bytes(hitray.render(scene, camera, size, spp=2, progress=False), tmp_path / "here.exr")
        assert here == pathlib.Path(pattern % i).read_bytes(), i


def test_distributed_slow_worker_split_by_two_idle_workers(tmp_path):
    """Three workers, one slow: the two others both take rows of its band
    (one split asked of a band at a time, so no row is given twice), and
    the frame is the single render's bits, every row rendered once."""
    from hitray.distributed._band import set_test_delay

    scene, camera = two_spheres()
    size, options = (48, 200), {"spp": 2}
    here = hitray.render(scene, camera, size, progress=False, **options)
    with distributed.LocalCluster(n_workers=3, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=":0") as cluster, distributed.Client(cluster) as c:
        slow = sorted(c.scheduler_info()["workers"])[0]
        c.run(set_test_delay, 0.3, workers=[slow])
        report = hd.Report()
        there = hd.render(scene, camera, size, client=c, progress=False, report=report, **options)
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
    assert report.pixels == 48 * 200 and report.splits >= 2, report.lines()
    assert report.workers[slow].split >= 1, report.lines()


def test_distributed_animation_slow_worker_frame_is_split(client, tmp_path):
    """An animation on a slow worker and a fast one: the slow one's whole
    frame is split once the fast one has nothing left, and every frame is
    the bits of hitray.render, every pixel rendered once."""
    from hitray.distributed._band import set_test_delay

    pattern = str(tmp_path / "frame_%02d.exr")
    size = (40, 60)
    client.wait_for_workers(2, timeout=120)
    slow = sorted(client.scheduler_info()["workers"])[0]
    client.run(set_test_delay, 0.2, workers=[slow])
    report = hd.Report()
    try:
        hd.render_frames(orbit, pattern, count=3, size=size, spp=2, client=client, progress=False, report=report)
    finally:
        client.run(set_test_delay, 0.0, workers=[slow])
    assert report.frames == 3 and report.pixels == 3 * 40 * 60
    assert report.splits >= 1, report.lines()
    for i in range(3):
        scene, camera = orbit(i)
        here = exr_bytes(hitray.render(scene, camera, size, spp=2, progress=False), tmp_path / "here.exr")
        assert here == pathlib.Path(pattern % i).read_bytes(), i


def test_distributed_animation_writes_skips_and_resumes(client, tmp_path):
    pattern = str(tmp_path / "frame_%02d.png")
    size = (32, 24)
    written = hd.render_frames(orbit, pattern, count=12, size=size, spp=2, client=client, tile=16,
                               progress=False)
    assert sorted(written) == [pattern % i for i in range(12)]  # in the order they completed
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"frame_{i:02d}.png" for i in range(12)]
    for i in (0, 5, 11):
        scene, camera = orbit(i)
        hitray.render(scene, camera, size, spp=2, progress=False).save(tmp_path / "here.png")
        assert (tmp_path / "here.png").read_bytes() == pathlib.Path(pattern % i).read_bytes()
    os.remove(tmp_path / "here.png")
    stamps = {p: p.stat().st_mtime_ns for p in tmp_path.iterdir()}
    # A rerun has nothing to do.
    assert hd.render_frames(orbit, pattern, count=12, size=size, spp=2, client=client, tile=16,
                            progress=False) == []
    assert {p: p.stat().st_mtime_ns for p in tmp_path.iterdir()} == stamps

    # Interrupted after 4 frames of a fresh run, then resumed: every frame
    # is written once, the first 4 are left alone, and the images are the
    # same bits as the uninterrupted run's.
    first = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    again = tmp_path / "again"
    again.mkdir()
    pattern2 = str(again / "frame_%02d.png")

    class Stop(Exception):
        pass

    def stop_after_four(index, path):
        if len(os.listdir(again)) == 4:
            raise Stop

    with pytest.raises(Stop):
        hd.render_frames(orbit, pattern2, count=12, size=size, spp=2, client=client, tile=16,
                         progress=False, frames_in_flight=2, on_frame=stop_after_four)
    done = sorted(os.listdir(again))
    assert len(done) == 4
    stamps = {name: (again / name).stat().st_mtime_ns for name in done}
    rest = hd.render_frames(orbit, pattern2, count=12, size=size, spp=2, client=client, tile=16,
                            progress=False)
    assert sorted(os.path.basename(p) for p in rest) == sorted(set(first) - set(done))
    assert {name: (again / name).stat().st_mtime_ns for name in done} == stamps
    assert {p.name: p.read_bytes() for p in again.iterdir()} == first


def test_distributed_frames_empty_file_or_folder_is_not_a_frame(client, tmp_path):
    """A 0-byte file where a frame goes is not a finished frame (frames are
    written whole, then renamed): it is rendered. A folder there is an error
    before anything is rendered, not a frame skipped."""
    pattern = str(tmp_path / "f%d.png")
    (tmp_path / "f0.png").write_bytes(b"")
    written = hd.render_frames(orbit, pattern, count=2, size=(16, 12), client=client, progress=False)
    assert sorted(written) == [pattern % 0, pattern % 1]
    scene, camera = orbit(0)
    hitray.render(scene, camera, (16, 12), progress=False).save(tmp_path / "here.png")
    assert (tmp_path / "f0.png").read_bytes() == (tmp_path / "here.png").read_bytes()
    assert settled_tile_tasks(client) == []  # the first call's tiles gone, so the check below sees only the second's
    (tmp_path / "f2.png").mkdir()
    with pytest.raises(IsADirectoryError, match=r"f2\.png: a directory is where frame 2 goes"):
        hd.render_frames(orbit, pattern, count=3, size=(16, 12), client=client, progress=False)
    assert settled_tile_tasks(client) == []


def tile_tasks(client):
    """Keys of hitray tiles the scheduler still knows."""
    def on_scheduler(dask_scheduler):
        return [k for k in dask_scheduler.tasks if str(k).startswith("hitray-tile-")]
    return client.run_on_scheduler(on_scheduler)


def settled_tile_tasks(client):
    """The tiles the scheduler still knows once it has had up to 10 s to
    forget released ones (it does so soon after the client lets go, not at
    once; a band cancelled by Ctrl-C, or taken from a worker by an idle one
    at the end of a run, is forgotten soon after too)."""
    for _ in range(200):
        left = tile_tasks(client)
        if not left:
            break
        time.sleep(0.05)
    return left


def test_distributed_interrupt_cancels_the_tiles(client):
    """Ctrl-C (a KeyboardInterrupt in the waiting loop) cancels every tile
    still out and is raised."""
    scene, camera = two_spheres()

    def interrupt(fraction):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        hd.render(scene, camera, (64, 48), spp=16, client=client, tile=4, progress=interrupt)
    assert settled_tile_tasks(client) == []


def test_distributed_bad_input_raises_on_the_client(client, tmp_path):
    scene, camera = two_spheres()
    with pytest.raises(hitray.ArgumentError, match="adaptive supersampling needs samples per pixel >= 2"):
        hd.render(scene, camera, (20, 10), adaptive=0.1, client=client, progress=False)
    with pytest.raises(ValueError, match=r"tile must be within 1..65536 pixels \(or None: .*\), not 0"):
        hd.render(scene, camera, (20, 10), tile=0, client=client, progress=False)
    with pytest.raises(ValueError, match="cut a 4000x3000 frame into 12000000 tiles, more than 100000"):
        hd.render(scene, camera, (4000, 3000), tile=1, client=client, progress=False)
    with pytest.raises(ValueError, match="needs one integer conversion"):
        hd.render_frames(orbit, str(tmp_path / "frame.png"), count=2, client=client, progress=False)
    with pytest.raises(FileNotFoundError, match=r"nowhere: no such directory for frame 0"):
        hd.render_frames(orbit, str(tmp_path / "nowhere" / "f%d.png"), count=2, client=client, progress=False)
    with pytest.raises(TypeError, match="give count"):
        hd.render_frames(orbit, str(tmp_path / "f%d.png"), client=client, progress=False)
    with pytest.raises(TypeError, match="client must be a distributed.Client"):
        hd.render(scene, camera, (20, 10), client=42, progress=False)
    assert settled_tile_tasks(client) == []


def unused_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_distributed_scheduler_that_does_not_answer():
    """No scheduler at the address: one SchedulerUnreachable naming it and
    the timeout, not a hang (the thread guard fails the test if it hangs)."""
    scene, camera = two_spheres()
    address = f"tcp://127.0.0.1:{unused_port()}"
    caught = []

    def attempt():
        try:
            hd.render(scene, camera, (8, 8), client=address, timeout=2, progress=False)
        except BaseException as e:  # noqa: B902 - handed to the test thread
            caught.append(e)

    t = threading.Thread(target=attempt, daemon=True)
    t.start()
    t.join(120)
    assert not t.is_alive(), "connecting to a silent address hung"
    assert len(caught) == 1 and isinstance(caught[0], hd.SchedulerUnreachable)
    assert address in str(caught[0]) and "within 2 s" in str(caught[0])


def dist_cli(*args, timeout=300):
    return subprocess.run([sys.executable, "-m", "hitray.distributed", *map(str, args)], capture_output=True,
                          text=True, timeout=timeout)


def test_distributed_cli_render_matches_hitray_render(client, tmp_path):
    """`python -m hitray.distributed render` on the module's scheduler gives
    the EXR bytes of `hitray render` (the C command line) with the same
    options."""
    scene_file = tmp_path / "two.sdl"
    scene_file.write_text(TWO_SPHERES_SDL)
    options = ["--size", "40x30", "--spp", "4", "--adaptive", "0.05", "--depth", "2"]
    proc = dist_cli("render", scene_file, "-o", tmp_path / "there.png", "--exr", tmp_path / "there.exr",
                    "--scheduler", client.scheduler.address, "--tile", 17, "-q", *options)
    assert proc.returncode == 0, proc.stderr
    assert "there.png: 40x30" in proc.stdout
    assert "balance" in proc.stdout and "tasks on" in proc.stdout  # the report
    here = hitray.render(*hitray.load_sdl(scene_file), (40, 30), spp=4, adaptive=0.05, depth=2, progress=False)
    assert (tmp_path / "there.exr").read_bytes() == exr_bytes(here, tmp_path / "here.exr")
    if HITRAY.is_file():
        c_cli = subprocess.run([str(HITRAY), "render", str(scene_file), "-o", str(tmp_path / "c.exr"), *options],
                               capture_output=True, text=True, timeout=300)
        assert c_cli.returncode == 0, c_cli.stderr
        assert (tmp_path / "c.exr").read_bytes() == (tmp_path / "there.exr").read_bytes()


def test_distributed_cli_on_a_local_cluster_quiet_off_a_terminal(tmp_path):
    """Without -q and with standard error a pipe (a log file), no progress
    bar: it is drawn only where someone watches. Two local workers share
    the machine's cores, and the summary says how many threads rendered."""
    scene_file = tmp_path / "two.sdl"
    scene_file.write_text(TWO_SPHERES_SDL)
    proc = dist_cli("render", scene_file, "-o", tmp_path / "x.png", "--workers", 2, "--size", "40x30",
                    "--tile", 8)
    assert proc.returncode == 0, proc.stderr
    assert "\r" not in proc.stderr and "px/s" not in proc.stderr, proc.stderr
    threads = int(proc.stdout.split(" rays on ")[1].split()[0])
    assert 2 <= threads <= max(2, local_cores()), proc.stdout


def test_bench_distributed_runs_and_ships_what_the_docs_say(tmp_path):
    """bench/drivers/distributed.py measure (docs/distributed.md's costs) on
    one small frame and a model check of one worker: every image checked
    against hitray.render's by the bench itself, the costs written, and the
    files it ships for the demo scene what the page says."""
    costs = tmp_path / "costs.json"
    done = subprocess.run([sys.executable, str(ROOT / "bench" / "drivers" / "distributed.py"), "measure",
                           "--runs", "1", "--size", "64x48", "--check-size", "32x24", "--check-workers", "1",
                           "--costs", str(costs)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    ships = re.search(r"the shipped scene carries \d+ files? \(\d+ bytes\)", done.stdout)
    assert ships, done.stdout
    page = (ROOT / "docs" / "distributed.md").read_text()
    assert f"The demo scene ships one file, its pixmap: `{ships[0]}`" in page, ships[0]
    assert "| hitray.distributed, 2 workers x 1 thread |" in done.stdout
    assert "| workers x 16 cores |" in done.stdout  # the model's table, from what it measured
    measured = json.loads(costs.read_text())
    assert measured["size"] == [64, 48] and [row[0] for row in measured["check"]] == [1]


def test_bench_distributed_without_the_package_says_what_to_install(tmp_path):
    """After `make demo` alone .venv holds no hitray: the bench says so and
    what installs it, in one line."""
    done = subprocess.run([sys.executable, "-I", "-S", str(ROOT / "bench" / "drivers" / "distributed.py")],
                          capture_output=True, text=True, timeout=60, cwd=tmp_path)
    assert done.returncode == 1 and "make python-install" in done.stderr, done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr


def test_the_bar_is_drawn_by_default_only_where_someone_watches(monkeypatch):
    from hitray import _progress
    from hitray.distributed._render import _Bar

    monkeypatch.setattr(_progress, "in_notebook", lambda: False)
    for terminal, progress, drawn in [(False, None, False), (True, None, True), (False, True, True),
                                      (True, False, False)]:
        monkeypatch.setattr(_progress, "_stderr_is_terminal", lambda: terminal)
        bar = _Bar(progress, 4, "hitray.distributed")
        assert (bar._bar is not None) == drawn, (terminal, progress)
        bar.close()
    with pytest.raises(TypeError, match="None \\(auto\\), True, False or a callable"):
        _Bar("yes", 4, "hitray.distributed")


def test_distributed_cli_frames_from_a_script(client, tmp_path):
    script = tmp_path / "orbit.py"
    script.write_text(
        "import math, hitray\n"
        "count = 3\n"
        "scene = hitray.Scene()\n"
        "scene.add(hitray.Sphere(), diffuse=(0.8, 0.3, 0.2))\n"
        "scene.light((4, 6, 5))\n"
        "def frames(i):\n"
        "    a = 2 * math.pi * i / count\n"
        "    return scene, hitray.Camera((5 * math.sin(a), 1, 5 * math.cos(a)), (0, 0, 0), (0, 1, 0), 40)\n")
    pattern = tmp_path / "f_%03d.exr"
    args = ["frames", script, "-o", pattern, "--scheduler", client.scheduler.address, "--size", "24x16",
            "--tile", "10", "-q"]
    proc = dist_cli(*args)
    assert proc.returncode == 0, proc.stderr
    assert "3 frames written" in proc.stdout
    assert sorted(p.name for p in tmp_path.glob("f_*.exr")) == ["f_000.exr", "f_001.exr", "f_002.exr"]
    again = dist_cli(*args)
    assert again.returncode == 0 and "0 frames written" in again.stdout
    missing = dist_cli("frames", tmp_path / "none.py", "-o", pattern, "--scheduler", client.scheduler.address)
    assert missing.returncode == 1 and "none.py: no such script" in missing.stderr


def test_distributed_cli_scheduler_that_does_not_answer(tmp_path):
    scene_file = tmp_path / "two.sdl"
    scene_file.write_text(TWO_SPHERES_SDL)
    address = f"tcp://127.0.0.1:{unused_port()}"
    proc = dist_cli("render", scene_file, "-o", tmp_path / "x.png", "--scheduler", address, "--timeout", "2",
                    timeout=120)
    assert proc.returncode == 1
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and f"no Dask scheduler answered at '{address}' within 2 s" in lines[0], proc.stderr
    assert not (tmp_path / "x.png").exists()


def test_distributed_frames_of_a_scene_changed_between_frames(client, tmp_path):
    """One Scene changed by the frame function before each frame (its
    background, an object added): every frame ships what the scene was when
    the frame was asked for, though frames are in flight together."""
    scene, camera = two_spheres()
    expected = {}

    def frame(i):
        scene.background = (0.2 * i, 0.1, 0.3)
        if i == 2:
            scene.add(hitray.Sphere().translate(0, 2.5, 0).scale(0.4, 0.4, 0.4), diffuse=(0.9, 0.9, 0.1))
        expected[i] = exr_bytes(hitray.render(scene, camera, (24, 16), progress=False), tmp_path / "here.exr")
        return scene, camera

    pattern = str(tmp_path / "f%d.exr")
    hd.render_frames(frame, pattern, count=4, size=(24, 16), client=client, tile=8, progress=False)
    assert len(set(expected.values())) == 4
    for i in range(4):
        assert pathlib.Path(pattern % i).read_bytes() == expected[i], i


def test_distributed_local_cluster_when_no_client(tmp_path):
    """client=None: a LocalCluster of `workers` processes on this machine,
    started for the render and closed after it."""
    scene, camera = two_spheres()
    here = hitray.render(scene, camera, (30, 20), spp=2, progress=False)
    there = hd.render(scene, camera, (30, 20), spp=2, workers=2, tile=16, progress=False)
    assert exr_bytes(there, tmp_path / "there.exr") == exr_bytes(here, tmp_path / "here.exr")
    # Both workers rendered, on the machine's cores shared among them: each
    # worker process has its share as Dask threads and a tile renders on
    # them, one tile at a time, not on every core (2 workers on 2 cores
    # once rendered on 2 threads each, 4 in all).
    cores = local_cores()
    assert 2 <= there.stats.threads <= max(2, cores), (there.stats.threads, cores)


def test_distributed_cli_ctrl_c_cancels(client, tmp_path):
    """SIGINT to the command line once its tiles are on the scheduler: it
    exits with 130 and one line, writes nothing, and leaves no tile behind."""
    scene_file = tmp_path / "two.sdl"
    scene_file.write_text(TWO_SPHERES_SDL)
    out = tmp_path / "never.png"
    proc = subprocess.Popen([sys.executable, "-m", "hitray.distributed", "render", str(scene_file), "-o", str(out),
                             "--scheduler", client.scheduler.address, "--size", "160x120", "--spp", "64",
                             "--tile", "4", "-q"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=sigint_as_at_a_terminal)
    try:
        for _ in range(1200):  # until its tiles are scheduled (or it ended early)
            if tile_tasks(client) or proc.poll() is not None:
                break
            time.sleep(0.05)
        assert proc.poll() is None, proc.communicate()
        proc.send_signal(signal.SIGINT)
        stdout, stderr = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 130, stderr
    assert stderr.strip().splitlines()[-1] == "python -m hitray.distributed: interrupted"
    assert not out.exists()
    assert settled_tile_tasks(client) == []


def test_distributed_render_takes_hitray_render_arguments():
    """hd.render is a drop-in for hitray.render: the same arguments in the
    same order (all but window: the tiles are windows), then the cluster's."""
    import inspect

    here = [p for p in inspect.signature(hitray.render).parameters if p != "window"]
    there = list(inspect.signature(hd.render).parameters)
    assert there[:len(here)] == here
    assert there[len(here):] == ["client", "tile", "workers", "timeout", "report"]

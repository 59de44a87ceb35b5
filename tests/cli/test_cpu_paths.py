"""Every shipped scene (scenes/) and every benchmark scene (bench/scenes/)
renders to the same bits on every CPU path: HITRAY_CPU=sse2 (the baseline
x86-64 code), fma (the FMA copies of the shapes' hot functions) and avx2 (the
AVX2 walks, mesh filter and texture code as well), each where this CPU runs
it. The whole image is compared, as float (PFM), at a small size; and since
a float image can hide a difference of an ulp in a double t, the first hits
of the same scenes (camera rays, then rays onward from each hit in scattered
directions) are compared too, t, normal and object, bit for bit, through the
Python binding. A value that names no path, or one this CPU lacks, is
refused with a message naming the variable and the values it takes."""

import os
import pathlib
import subprocess
import sys

import pytest

from hitray_testing import BUILD, ROOT

HITRAY = BUILD / "bin" / "hitray"
SIZE = "96x72"

SCENES = sorted((ROOT / "scenes").rglob("*.sdl")) + sorted((ROOT / "bench" / "scenes").glob("*.sdl"))


def cpu_flags():
    try:
        text = pathlib.Path("/proc/cpuinfo").read_text()
    except OSError:
        return set()
    for line in text.splitlines():
        if line.startswith("flags"):
            return set(line.split(":", 1)[1].split())
    return set()


FLAGS = cpu_flags()
# The paths this CPU runs (the library's own check refuses the others, as
# test_refused_paths shows).
PATHS = ["sse2"] + (["fma"] if "fma" in FLAGS else []) + (["avx2"] if {"avx2", "fma"} <= FLAGS else [])


def scene_files(tmp_path):
    """SCENES, terrain.sdl with its mesh written beside a copy of it."""
    out = []
    for scene in SCENES:
        if scene.name == "terrain.sdl":  # its mesh is written when the benchmark runs
            subprocess.run([sys.executable, str(ROOT / "bench" / "drivers" / "make_terrain.py"),
                            str(tmp_path / "terrain.3vn")], check=True, timeout=300)
            (tmp_path / "terrain.sdl").write_text(scene.read_text())
            scene = tmp_path / "terrain.sdl"
        out.append(scene)
    return out


def render(scene, out, cpu, cwd):
    env = {k: v for k, v in os.environ.items() if k not in ("HITRAY_SHAPE_PATH", "HITRAY_CPU")}
    env["HITRAY_CPU"] = cpu
    return subprocess.run([str(HITRAY), "render", str(scene), "-o", str(out), "--size", SIZE, "--threads", "2",
                           "-q"], capture_output=True, text=True, env=env, cwd=cwd, timeout=300)


def test_every_scene_is_listed():
    names = {p.name for p in SCENES}
    assert {"demo.sdl", "csg.sdl", "spheres.sdl", "terrain.sdl"} <= names, names


@pytest.mark.skipif(sys.platform != "linux" or len(PATHS) < 2, reason="one CPU path only on this machine")
@pytest.mark.parametrize("scene", SCENES, ids=lambda p: str(p.relative_to(ROOT)))
def test_same_image_on_every_cpu_path(scene, tmp_path):
    if not HITRAY.is_file():
        pytest.fail(f"{HITRAY} is missing: build first (make build), or set HITRAY_BUILD_DIR")
    if scene.name == "terrain.sdl":
        scene = next(p for p in scene_files(tmp_path) if p.name == "terrain.sdl")
    images = {}
    for cpu in PATHS:
        out = tmp_path / f"{cpu}.pfm"
        r = render(scene, out, cpu, scene.parent)
        assert r.returncode == 0, f"HITRAY_CPU={cpu}: {r.stderr}"
        images[cpu] = out.read_bytes()
    first = PATHS[0]
    for cpu in PATHS[1:]:
        assert images[cpu] == images[first], f"{scene.name}: HITRAY_CPU={cpu} differs from {first}"


def test_refused_paths(tmp_path):
    scene = ROOT / "bench" / "scenes" / "spheres.sdl"
    r = render(scene, tmp_path / "x.pfm", "avx512", tmp_path)
    assert r.returncode == 1 and not (tmp_path / "x.pfm").exists()
    assert r.stderr == ("hitray: HITRAY_CPU='avx512' is not a CPU path: use native, sse2, fma or avx2 "
                        "(or leave it unset)\n")
    if "avx2" not in FLAGS:
        r = render(scene, tmp_path / "x.pfm", "avx2", tmp_path)
        assert r.returncode == 1 and "HITRAY_CPU=avx2: this CPU (or its operating system) has no AVX2" in r.stderr


# Run with HITRAY_CPU set: loads each scene named on the command line and
# writes the first hits of a grid of camera rays, and of rays leaving each hit
# in scattered directions, as raw float64 and int64 bytes.
HITS = r"""
import sys
import numpy as np
import hitray
out = open(sys.argv[1], "wb")
for path in sys.argv[2:]:
    scene, camera = hitray.load_sdl(path)
    if camera is None:
        camera = hitray.Camera(eye=(0, 2, 30))
    w, h = 48, 36
    rays = [camera.ray(i + 0.5, j + 0.5, (w, h)) for j in range(h) for i in range(w)]
    o = np.array([r[0] for r in rays]); d = np.array([r[1] for r in rays])
    t, n, obj = scene.trace(o, d, threads=1)
    hit = obj >= 0
    rng = np.random.default_rng(26)
    p = o[hit] + t[hit, None] * d[hit]
    d2 = rng.normal(size=p.shape)
    t2, n2, obj2 = scene.trace(p, d2, tmin=1e-6, threads=1)
    for a in (t, n, obj, t2, n2, obj2):
        out.write(np.ascontiguousarray(a).tobytes())
"""


@pytest.mark.skipif(sys.platform != "linux" or len(PATHS) < 2, reason="one CPU path only on this machine")
def test_same_hits_on_every_cpu_path(tmp_path):
    pytest.importorskip("numpy")
    pytest.importorskip("hitray")
    scenes = [str(p) for p in scene_files(tmp_path)]
    dumps = {}
    for cpu in PATHS:
        env = {k: v for k, v in os.environ.items() if k not in ("HITRAY_SHAPE_PATH", "HITRAY_CPU")}
        env["HITRAY_CPU"] = cpu
        out = tmp_path / f"{cpu}.hits"
        r = subprocess.run([sys.executable, "-c", HITS, str(out), *scenes], capture_output=True, text=True,
                           env=env, timeout=300)
        assert r.returncode == 0, f"HITRAY_CPU={cpu}: {r.stderr}"
        dumps[cpu] = out.read_bytes()
    assert len(dumps[PATHS[0]]) > 100000
    for cpu in PATHS[1:]:
        assert dumps[cpu] == dumps[PATHS[0]], f"HITRAY_CPU={cpu}: first hits differ from {PATHS[0]}"

"""Tests of the benchmark's own tools (they decide whether the POV-Ray renders
are the same scenes as hitray's): bench/drivers/sdl2pov.py, the SDL to POV-Ray
translator, and bench/drivers/compare_images.py, the object-mask comparison, which need
neither POV-Ray nor a build of hitray; and bench/drivers/run_bench.py --quick, every step
of the benchmark once (skipped without a build)."""

import importlib.util
import math
import os
import pathlib
import re
import struct
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SDL2POV = ROOT / "bench" / "drivers" / "sdl2pov.py"
COMPARE = ROOT / "bench" / "drivers" / "compare_images.py"


def load(path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


sdl2pov = load(SDL2POV)

CAMERA = "camera 0 0 10  0 0 0  0 1 0  40\n"


def translate(tmp_path, text, *extra):
    scene = tmp_path / "s.sdl"
    scene.write_text(text)
    pov = tmp_path / "s.pov"
    result = subprocess.run([sys.executable, str(SDL2POV), str(scene), "-o", str(pov), *extra],
                            capture_output=True, text=True)
    return result, (pov.read_text() if pov.exists() else "")


def matrices(pov_text):
    return [[float(x) for x in m.split(",")] for m in re.findall(r"matrix <([^>]*)>", pov_text)]


def test_transform_order_is_hills(tmp_path):
    # translate then scale: the scale acts first (M = T S), so the sphere's
    # centre is (1, 2, 3) and its axes are 2, 4, 8 long.
    result, pov = translate(tmp_path, CAMERA + "translate 1 2 3 scale 2 4 8 sphere\n")
    assert result.returncode == 0, result.stderr
    assert matrices(pov) == [[2, 0, 0, 0, 4, 0, 0, 0, 8, 1, 2, 3]]


def test_rotation_turns_x_into_y(tmp_path):
    # POV-Ray's matrix rows are the images of x, y, z: rotating 90 degrees
    # about +z (right-handed) takes x to y.
    _, pov = translate(tmp_path, CAMERA + "rotate 90 0 0 1 cube\n")
    m = matrices(pov)[0]
    assert [round(v, 12) for v in m[0:3]] == [0, 1, 0]
    assert [round(v, 12) for v in m[3:6]] == [-1, 0, 0]


def test_macros_push_pop_and_booleans(tmp_path):
    text = CAMERA + ("def two { push translate 1 0 0 sphere pop push translate -1 0 0 cube pop }\n"
                     "use two translate 0 5 0 use two\n"
                     "difference push scale 2 2 2 cube pop sphere\n")
    result, pov = translate(tmp_path, text, "--mask", str(tmp_path / "m.sdl"))
    assert result.returncode == 0, result.stderr
    translations = [m[9:12] for m in matrices(pov)]
    assert translations[:4] == [[1, 0, 0], [-1, 0, 0], [1, 5, 0], [-1, 5, 0]]
    # the boolean's operands keep the transform current when each was read
    assert translations[4:] == [[0, 5, 0], [0, 5, 0]]
    assert "difference {" in pov
    # the flat SDL: one distinct emissive colour before each of the 6 leaves
    mask = (tmp_path / "m.sdl").read_text()
    colours = re.findall(r"^emissive (.*)$", mask, re.M)
    assert len(colours) == 6 and len(set(colours)) == 6
    assert not re.search(r"^(def|use|light) ", mask, re.M)


@pytest.mark.parametrize("transforms", ["translate 1 2 3", "scale 2 -3 4", "rotate 90 1 0 0 scale 2 2 2",
                                        "rotate 30 1 2 3 scale 1 2 3 rotate -70 0 1 1 translate 4 5 6",
                                        "rotate 180 0 1 0", "scale -1 1 1 rotate 45 0 0 1"])
def test_mask_transforms_rebuild_the_matrix(transforms):
    # The flat SDL writes each matrix as translate, rotate, scale, rotate:
    # hitray reads those words back to the same matrix, to rounding.
    hitray = pytest.importorskip("hitray")
    scene, _ = hitray.parse_sdl(transforms + " sphere\n")
    m = scene.objects[0].matrix
    again, _ = hitray.parse_sdl(" ".join(sdl2pov.transform_words(m)) + " sphere\n")
    assert abs(again.objects[0].matrix - m).max() < 1e-13


def test_camera_angle_is_horizontal_for_pov(tmp_path):
    _, pov = translate(tmp_path, CAMERA + "sphere\n", "--size", "1920x1080")
    angle = float(re.search(r"angle ([0-9.e+-]+)", pov).group(1))
    expected = math.degrees(2 * math.atan(math.tan(math.radians(20)) * 1920 / 1080))
    assert abs(angle - expected) < 1e-9
    assert "right -x*1.77777" in pov  # right-handed, as hitray is


def test_material_mapping(tmp_path):
    text = CAMERA + ("globalAmbient .5 .5 .5 minReflectivity .3\n"
                     "ambient .2 .2 .2 diffuse .5 .25 .5 emissive .1 .1 .1 reflectivity .2 sphere\n"
                     "reflectivity .4 maxRecursionDepth 4 sphere\n")
    _, pov = translate(tmp_path, text)
    # POV-Ray multiplies ambient and emission by the pigment (Hill's diffuse)
    assert "ambient rgb <0.2, 0.4, 0.2>" in pov
    assert "emission rgb <0.2, 0.4, 0.2>" in pov
    # reflectivity .2 is below minReflectivity: no reflected ray, as in hitray
    declared = re.findall(r"#declare (T\d+)_tex = (.*)", pov)
    assert "reflection" not in declared[0][1] and "reflection { rgb 0.4 }" in declared[1][1]
    # depth 4 after the primary ray is POV-Ray's trace level 5
    assert "max_trace_level 5" in pov


def test_mesh_polygons_become_triangles(tmp_path):
    # Hill's format: counts, vertices, normals, faces (n, vertex ids, normal ids)
    (tmp_path / "quad.3vn").write_text("4 1 1\n0 0 0  1 0 0  1 1 0  0 1 0\n0 0 1\n"
                                      "4 0 1 2 3 0 0 0 0\n")
    result, pov = translate(tmp_path, CAMERA + "mesh quad.3vn\n")
    assert result.returncode == 0, result.stderr
    inc = (tmp_path / "quad.inc").read_text()
    assert "face_indices { 2" in inc and "<0,1,2>" in inc and "<0,2,3>" in inc
    assert '#include "quad.inc"' in pov


def test_errors_name_the_file(tmp_path):
    result, _ = translate(tmp_path, CAMERA + "sphere frobnicate\n")
    assert result.returncode == 1
    assert "s.sdl" in result.stderr and "frobnicate" in result.stderr
    result, _ = translate(tmp_path, "sphere\n")
    assert result.returncode == 1 and "camera" in result.stderr


def write_ppm(path, width, height, pixel):
    data = bytearray()
    for y in range(height):
        for x in range(width):
            data += bytes(pixel(x, y))
    path.write_bytes(b"P6\n# a comment\n%d %d\n255\n" % (width, height) + bytes(data))


def compare(tmp_path, a, b):
    out = subprocess.run([sys.executable, str(COMPARE), str(a), str(b), str(a), str(b),
                          str(tmp_path / "p.png")], capture_output=True, text=True, check=True)
    return float(out.stdout)


def test_masks_agree_and_disagree(tmp_path):
    red, green = (255, 0, 0), (0, 255, 0)
    write_ppm(tmp_path / "a.ppm", 40, 20, lambda x, y: red)
    write_ppm(tmp_path / "b.ppm", 40, 20, lambda x, y: red if x < 30 else green)
    # 8-bit rounding of the same id colour (sRGB 188 vs 190) is the same id
    write_ppm(tmp_path / "c.ppm", 40, 20, lambda x, y: (188, 0, 0))
    write_ppm(tmp_path / "d.ppm", 40, 20, lambda x, y: (190, 0, 0))
    assert compare(tmp_path, tmp_path / "a.ppm", tmp_path / "a.ppm") == 100.0
    assert compare(tmp_path, tmp_path / "a.ppm", tmp_path / "b.ppm") == 75.0
    assert compare(tmp_path, tmp_path / "c.ppm", tmp_path / "d.ppm") == 100.0
    png = (tmp_path / "p.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = struct.unpack(">II", png[16:24])
    assert (width, height) == (80, 40)  # two renders side by side, masks below


def test_id_colours_survive_srgb(tmp_path):
    compare_mod = load(COMPARE)

    def encode(v):  # linear -> sRGB 8-bit, as both renderers write
        c = v * 12.92 if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
        return round(255 * c)
    seen = set()
    for ident in range(1, 64):
        rgb = sdl2pov.id_colour(ident)
        pixel = bytes(encode(c) for c in rgb)
        seen.add(compare_mod.ids(pixel)[0])
    assert len(seen) == 63 and 0 not in seen  # 63 ids, none read as the black background


def test_run_bench_quick_runs_every_step(tmp_path):
    # The whole benchmark once, tiny (bench/drivers/run_bench.py --quick): the SDL
    # scenes, the SPD scenes where shared/scenes/spd is beside the
    # repository, the raycast; without POV-Ray it runs hitray's side alone.
    build = pathlib.Path(os.environ.get("HITRAY_BUILD_DIR", ROOT / "build"))
    if not (build / "bin" / "hitray").exists():
        pytest.skip(f"no hitray build in {build}")
    out = tmp_path / "RESULTS.md"
    result = subprocess.run([sys.executable, str(ROOT / "bench" / "drivers" / "run_bench.py"), "--quick",
                             "--build", str(build), "--output", str(out)],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    text = out.read_text()
    assert "| spheres | 1 |" in text and "| village | 1 |" in text
    # The thread-scaling table: a speed-up, a CPU ratio and the side-by-side
    # ceiling for every scene, and POV-Ray's own speed-up where it ran.
    assert "## Thread scaling" in text
    # The speed targets, each with met or missed (or not measured).
    assert "## Speed targets" in text
    assert re.search(r"^\| single rays, 1 thread \| >= 1.0x Embree rtcIntersect1 \| .* \| (yes|no|-) \|$",
                     text, re.M)
    # The batch and packet engines beside the single calls, both kinds of rays.
    assert "## Batches and packets" in text
    assert re.search(r"^\| camera \| 1 \| [0-9.]+ M \| [0-9.]+ M \|", text, re.M)
    assert re.search(r"^\| random \| 1 \| [0-9.]+ M \| [0-9.]+ M \|", text, re.M)
    assert re.search(r"^\| spheres \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| (?:[0-9.]+|-) \|$", text, re.M)
    if (ROOT.parent / "shared" / "scenes" / "spd" / "balls.nff.gz").exists():
        assert "## SPD scenes" in text
        for scene in ("balls", "gears", "mount", "rings", "teapot", "tetra", "tree"):
            assert f"| {scene} | 1 |" in text
        # hitray's rays by kind: balls reflects and casts shadows, refracts nothing.
        row = re.search(r"^\| balls \| ([0-9,]+) \| ([0-9,]+) \| ([0-9,]+) \| 0 \|", text, re.M)
        assert row and all(int(x.replace(",", "")) > 0 for x in row.groups())


def test_speed_targets_are_worked_out_from_the_rows():
    # bench/drivers/bench_targets.py: each target from the measured rows, the
    # worst scene and thread count named, met or missed by the goal's side.
    targets = load(ROOT / "bench" / "drivers" / "bench_targets.py")

    def scene(hr_render, pov_render):
        return {t: {"hr_render": [hr_render], "pov_render": [pov_render]} for t in (1, 2)}

    def runs(rate, build, kb, trace=1.0):
        return {t: [{"rays_per_s": rate, "build_s": build, "peak_kb": kb, "trace_s": trace}] for t in (1, 2)}

    ray = {"hitray": runs(8e6, 0.15, 90000), "embree": runs(10e6, 0.03, 30000)}
    scaling = {1000: {"hitray": runs(0, 0, 0, 0.10)}, 1000000: {"hitray": runs(0, 0, 0, 0.15)}}
    batches = {("camera", 1): {"hitray-batch": [15e6], "embree": [10e6], "embree8": [20e6]},
               ("camera", 2): {"hitray-batch": [28e6], "embree": [20e6], "embree8": [30e6]}}
    profile = ("== raycast: 100,000 spheres, 300 x 300 rays, hitray's hr_scene_first_hit\n"
               "135,000,000 (100.0%)  PROGRAM TOTALS\n"
               "== raycast: the same rays through Embree (trace only)\n"
               "90,000,000 (100.0%)  PROGRAM TOTALS\n")
    lines = targets.targets_table([1, 2], [("spheres", scene(0.3, 1.0), 100.0)],
                                  [("teapot", scene(0.5, 1.0), {}), ("balls", scene(0.2, 1.0), {})],
                                  ray, batches, scaling, profile)
    rows = {line.split(" | ")[0][2:]: line for line in lines if line.startswith("| ") and " | " in line}
    assert rows["single rays, 1 thread"].endswith("| 0.80 (100,000 spheres) | no |")
    assert "1,500 against Embree's 1,000: 1.50x" in rows["instructions per query"]
    assert rows["SPD mesh scenes"].endswith("| 0.50 (worst: teapot 1 thr) | no |")
    assert rows["camera rays as a batch, against rtcIntersect1"].endswith("| 1.40 (worst: 2 thr) | no |")
    assert rows["camera rays as a batch, against rtcIntersect8"].endswith("| 0.75 (worst: 1 thr) | no |")
    assert rows["renders, every bench and SPD scene"].endswith("| 0.50 (worst: teapot 1 thr) | no |")
    assert rows["1M spheres per ray over 1k"].endswith("| 1.50 (worst: 1 thr) | yes |")
    assert rows["memory, 100,000 spheres"].endswith("| 3.00 (peak resident) | no |")
    assert rows["build, 100,000 spheres"].endswith("| 5.00 (median) | no |")
    # Nothing measured (no Embree, no profile): said so, never a number.
    bare = targets.targets_table([1], [], [], {"hitray": runs(8e6, 0.1, 1)}, {}, {}, "")
    assert any("single rays, 1 thread" in x and "not measured" in x for x in bare)
    assert not any(x.startswith("| instructions per query") for x in bare)

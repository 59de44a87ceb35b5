"""Tests of the `hitray` command line, run as a user runs it.

The binary comes from the build tree named by HITRAY_BUILD_DIR (the Makefile's
`test-python` sets it; default: ./build). Every user error must end the
process with status 1 and exactly one line "hitray: ..." on stderr: no crash,
no traceback, no partial output file.
"""

import json
import math
import os
import re
import pathlib
import pty
import select
import signal
import stat
import struct
import subprocess
import time

import pytest

from hitray_testing import BUILD, ROOT, sigint_as_at_a_terminal
from hitray_testing import TWO_SPHERES_SDL as SCENE  # two spheres on a floor, one light

HITRAY = BUILD / "bin" / "hitray"


@pytest.fixture(scope="session", autouse=True)
def built():
    if not HITRAY.is_file():
        pytest.fail(f"{HITRAY} is missing: build first (make build), or set HITRAY_BUILD_DIR")


def run(*args, env=None, cwd=None):
    full_env = dict(os.environ)
    full_env.pop("HITRAY_SHAPE_PATH", None)
    if env:
        full_env.update(env)
    return subprocess.run([str(HITRAY), *map(str, args)], capture_output=True, text=True,
                          env=full_env, cwd=cwd, timeout=120, stdin=subprocess.DEVNULL)


def run_bytes(*args, stdin=b"", env=None):
    """hitray with `stdin` as its standard input; stdout kept as bytes."""
    full_env = {k: v for k, v in os.environ.items() if k != "HITRAY_SHAPE_PATH"}
    full_env.update(env or {})
    return subprocess.run([str(HITRAY), *map(str, args)], capture_output=True, input=stdin,
                          env=full_env, timeout=120)


@pytest.fixture
def scene(tmp_path):
    path = tmp_path / "scene.sdl"
    path.write_text(SCENE)
    return path


def write_sdl(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def png_chunks(data):
    """The chunk types and payloads of a PNG, in order."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    chunks, at = [], 8
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind = data[at + 4:at + 8].decode("ascii")
        chunks.append((kind, data[at + 8:at + 8 + length]))
        at += 12 + length
    return chunks


def png_header(path):
    chunks = png_chunks(path.read_bytes())
    kind, ihdr = chunks[0]
    assert kind == "IHDR"
    width, height, bits, colour = struct.unpack(">IIBB", ihdr[:10])
    return width, height, bits, colour, [k for k, _ in chunks]


def read_pfm(path):
    """(width, height, rows top to bottom of (r, g, b) tuples)."""
    data = path.read_bytes()
    parts = data.split(b"\n", 3)
    assert parts[0] == b"PF"
    width, height = map(int, parts[1].split())
    assert float(parts[2]) == -1.0
    floats = struct.unpack(f"<{width * height * 3}f", parts[3])
    rows = [[tuple(floats[(r * width + x) * 3:(r * width + x) * 3 + 3]) for x in range(width)]
            for r in range(height)]
    return width, height, rows[::-1]  # the file stores the bottom row first


# --- render ------------------------------------------------------------------

def test_render_writes_png_and_exr_and_prints_summary(scene, tmp_path):
    out, exr = tmp_path / "out.png", tmp_path / "out.exr"
    r = run("render", scene, "-o", out, "--exr", exr, "--size", "40x30")
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""  # no progress bar: stderr is not a terminal
    width, height, bits, colour, chunks = png_header(out)
    assert (width, height, bits, colour) == (40, 30, 8, 2)
    assert "sRGB" in chunks
    assert exr.read_bytes()[:4] == b"\x76\x2f\x31\x01"
    lines = r.stdout.splitlines()
    assert len(lines) == 1
    assert "40x30" in lines[0] and "rays" in lines[0] and "rays/s" in lines[0]
    assert str(out) in lines[0] and str(exr) in lines[0]
    assert list(tmp_path.iterdir()) != [] and not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_render_default_size_is_640x480(scene, tmp_path):
    out = tmp_path / "big.png"
    r = run("render", scene, "-o", out, "--threads", "2")
    assert r.returncode == 0, r.stderr
    assert png_header(out)[:2] == (640, 480)


NFF_SCENE = """\
v
from 0 -6 2
at 0 0 0.5
up 0 0 1
angle 40
hither 1
resolution 24 16
l 4 -4 6
f 1 0.5 0.25 0.8 0.3 20 0 1
s 0 0 1 1
c 2 0 0 0.5 2 0 2 0.25
p 3
-3 -3 0
3 -3 0
0 3 0
"""


def test_render_reads_nff_and_nff_gz_by_name_at_their_resolution(tmp_path):
    import gzip

    plain = tmp_path / "scene.NFF"
    plain.write_text(NFF_SCENE)
    packed = tmp_path / "scene.nff.gz"
    packed.write_bytes(gzip.compress(NFF_SCENE.encode()))
    for path in (plain, packed):
        out = tmp_path / (path.name + ".png")
        stats = tmp_path / (path.name + ".json")
        r = run("render", path, "-o", out, "--stats-json", stats)
        assert r.returncode == 0, r.stderr
        assert png_header(out)[:2] == (24, 16)  # the file's resolution
        assert json.loads(stats.read_text())["primary"] == 24 * 16
    r = run("render", packed, "-o", tmp_path / "sized.png", "--size", "10x8")
    assert r.returncode == 0, r.stderr
    assert png_header(tmp_path / "sized.png")[:2] == (10, 8)
    r = run("hits", plain, "--origin", "0,-5,1", "--dir", "0,1,0")
    assert r.returncode == 0 and '"shape": "sphere"' in r.stdout


def test_a_bad_nff_file_names_its_place_and_writes_nothing(tmp_path):
    path = tmp_path / "bad.nff"
    path.write_text("f 1 1 1 1 0 1 0 0\ns 0 0 x 1\n")
    out = tmp_path / "out.png"
    r = run("render", path, "-o", out)
    assert r.returncode == 1
    assert r.stderr.strip().splitlines() == [
        f"hitray: {path}:2:7: expected 4 numbers after 's' (x y z radius), found 'x'"]
    assert not out.exists()


@pytest.mark.parametrize("flags, bits, has_srgb", [([], 8, True), (["--png16"], 16, True),
                                                   (["--linear-png"], 8, False),
                                                   (["--png16", "--linear-png"], 16, False)])
def test_png_variants(scene, tmp_path, flags, bits, has_srgb):
    out = tmp_path / "v.png"
    r = run("render", scene, "-o", out, "--size", "8x6", *flags)
    assert r.returncode == 0, r.stderr
    _, _, got_bits, _, chunks = png_header(out)
    assert got_bits == bits
    assert ("sRGB" in chunks) == has_srgb
    assert "gAMA" in chunks


def test_ppm_and_pfm_outputs(scene, tmp_path):
    ppm, pfm = tmp_path / "a.ppm", tmp_path / "a.PFM"
    assert run("render", scene, "-o", ppm, "--size", "9x7").returncode == 0
    assert ppm.read_bytes().startswith(b"P6\n9 7\n255\n")
    assert len(ppm.read_bytes()) == len(b"P6\n9 7\n255\n") + 9 * 7 * 3
    assert run("render", scene, "-o", pfm, "--size", "9x7").returncode == 0
    width, height, rows = read_pfm(pfm)
    assert (width, height) == (9, 7)


def test_window_is_the_full_renders_crop_bit_for_bit(tmp_path):
    """--window X,Y,W,H gives the pixels of the full render exactly, as
    Python's window= does: adaptive corners and samples are placed on the
    full image, so a window cut anywhere (odd corner, odd size) matches."""
    scene, args = ROOT / "scenes" / "demo.sdl", ["--size", "61x43", "--spp", "4", "--adaptive", "0.05"]
    full, window = tmp_path / "full.pfm", tmp_path / "window.pfm"
    assert run("render", scene, "-o", full, *args).returncode == 0
    r = run("render", scene, "-o", window, *args, "--window", "7,11,23,19")
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("rendered 23x19 ")
    _, _, rows = read_pfm(full)
    width, height, crop = read_pfm(window)
    assert (width, height) == (23, 19)
    assert crop == [row[7:7 + 23] for row in rows[11:11 + 19]]


@pytest.mark.parametrize("ext, format_args", [(".png", []), (".ppm", ["--format", "ppm"]),
                                              (".pfm", ["--format", "pfm"]), (".exr", ["--format", "exr"])])
def test_output_to_stdout_is_the_file_it_would_write(scene, tmp_path, ext, format_args):
    """-o - writes to standard output the bytes -o FILE writes (PNG unless
    --format names another), the summary going to stderr; nothing is left
    in TMPDIR."""
    target = tmp_path / f"file{ext}"
    assert run("render", scene, "-o", target, "--size", "13x9").returncode == 0
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    r = run_bytes("render", scene, "-o", "-", "--size", "13x9", *format_args, env={"TMPDIR": str(tmp)})
    assert r.returncode == 0, r.stderr
    assert r.stdout == target.read_bytes()
    assert r.stderr.decode().startswith("rendered 13x9 ") and "standard output" in r.stderr.decode()
    assert list(tmp.iterdir()) == []


def test_output_to_stdout_with_an_unusable_tmpdir_renders_nothing(scene, tmp_path):
    r = run_bytes("render", scene, "-o", "-", "--size", "4x4", env={"TMPDIR": str(tmp_path / "absent")})
    assert r.returncode == 1 and r.stdout == b""
    assert b"absent" in r.stderr and len(r.stderr.splitlines()) == 1


def test_output_to_stdout_on_a_terminal_is_refused(scene):
    master, slave = pty.openpty()
    try:
        r = subprocess.run([str(HITRAY), "render", str(scene), "-o", "-", "--size", "4x4"], stdout=slave,
                           stderr=subprocess.PIPE, timeout=60)
    finally:
        os.close(slave)
        os.close(master)
    assert r.returncode == 2 and b"terminal" in r.stderr


def test_scene_from_stdin_renders_as_the_file(tmp_path):
    """- as the scene reads SDL from standard input, its relative file names
    (textures) from the current directory; its errors name <stdin>."""
    demo = ROOT / "scenes" / "demo.sdl"
    from_file, from_stdin = tmp_path / "file.pfm", tmp_path / "stdin.pfm"
    assert run("render", demo, "-o", from_file, "--size", "24x18").returncode == 0
    r = subprocess.run([str(HITRAY), "render", "-", "-o", str(from_stdin), "--size", "24x18"],
                       input=demo.read_bytes(), capture_output=True, cwd=demo.parent, timeout=120)
    assert r.returncode == 0, r.stderr
    assert from_stdin.read_bytes() == from_file.read_bytes()
    r = run_bytes("render", "-", "-o", tmp_path / "bad.png", stdin=b"sphere\nrotate 1 2\n")
    assert r.returncode == 1 and r.stderr.startswith(b"hitray: <stdin>:3:1: ")
    r = run_bytes("render", "-", "-o", tmp_path / "nul.png", stdin=b"sphere\0\n")
    assert r.returncode == 1 and b"NUL" in r.stderr
    assert not (tmp_path / "bad.png").exists() and not (tmp_path / "nul.png").exists()


def test_stdin_scene_to_stdout_image(scene):
    r = run_bytes("render", "-", "-o", "-", "--size", "5x5", "--format", "ppm", stdin=scene.read_bytes())
    assert r.returncode == 0 and r.stdout.startswith(b"P6\n5 5\n255\n")


def test_quiet_prints_nothing_even_on_a_terminal(scene, tmp_path):
    rc, out, seen = run_on_a_terminal("render", scene, "-o", tmp_path / "q.png", "--size", "64x64", "--quiet")
    assert (rc, out, seen) == (0, b"", "")
    r = run("render", scene, "-o", tmp_path / "q.png", "--size", "8x8", "-q", "--stats")
    assert (r.returncode, r.stdout, r.stderr) == (0, "", "")


@pytest.mark.parametrize("name, pil_format", [("a.bmp", "BMP"), ("a.tga", "TGA"), ("a.jpg", "JPEG"),
                                              ("a.JPEG", "JPEG"), ("a.hdr", None)])
def test_more_output_formats_by_extension(scene, tmp_path, name, pil_format):
    """JPEG, HDR, BMP and TGA beside PNG: BMP and TGA hold exactly the PPM's
    8-bit codes (Pillow reads them back), JPEG codes close to them at
    quality 100, HDR a Radiance file."""
    PIL = pytest.importorskip("PIL.Image", reason="Pillow reads the images (scripts/requirements-test.txt)")
    ppm, out = tmp_path / "ref.ppm", tmp_path / name
    assert run("render", scene, "-o", ppm, "--size", "19x13").returncode == 0
    extra = ["--jpeg-quality", "100"] if pil_format == "JPEG" else []
    r = run("render", scene, "-o", out, "--size", "19x13", *extra)
    assert r.returncode == 0, r.stderr
    if pil_format is None:
        assert out.read_bytes().startswith(b"#?RADIANCE\n")
        return
    reference = PIL.open(ppm).convert("RGB")
    with PIL.open(out) as image:
        assert image.format == pil_format and image.size == (19, 13)
        got = image.convert("RGB").tobytes()
    worst = max(abs(a - b) for a, b in zip(got, reference.tobytes()))
    # JPEG at quality 100 (every DCT coefficient quantised by 1, no chroma
    # subsampling) loses only the DCT's and YCbCr's rounding: 2 codes here.
    assert worst <= (4 if pil_format == "JPEG" else 0)


def test_jpeg_quality_and_format_names(scene, tmp_path):
    sizes = {}
    for q in ("10", "95"):
        r = run_bytes("render", scene, "-o", "-", "--format", "jpeg", "--jpeg-quality", q, "--size", "64x48")
        assert r.returncode == 0 and r.stdout.startswith(b"\xff\xd8"), r.stderr
        sizes[q] = len(r.stdout)
    assert sizes["10"] < sizes["95"]
    r = run("render", scene, "-o", tmp_path / "a.png", "--jpeg-quality", "50")
    assert r.returncode == 2 and "--jpeg-quality" in r.stderr and "png" in r.stderr
    r = run("render", scene, "-o", tmp_path / "a.jpg", "--jpeg-quality", "101")
    assert r.returncode == 2 and "1..100" in r.stderr
    r = run("render", scene, "-o", tmp_path / "a.gif")
    assert r.returncode == 2 and ".jpg" in r.stderr and ".tga" in r.stderr
    help_text = run("render", "--help").stdout
    for name in ("png", "exr", "ppm", "pfm", "jpeg", "hdr", "bmp", "tga"):
        assert name in help_text


TETRAHEDRON_OBJ = "v -1 -1 0\nv 1 -1 0\nv 0 1 0.5\nv 0 0 -1\nf 1 2 3\nf 1 2 4\nf 2 3 4\nf 3 1 4\n"
TETRAHEDRON_3VN = ("4 4 4\n-1 -1 0\n1 -1 0\n0 1 0.5\n0 0 -1\n"
                   "0 -0.24 0.97\n0 -0.71 -0.71\n0.8 0.4 -0.4\n-0.8 0.4 -0.4\n"
                   "3 0 1 2 0 0 0\n3 0 1 3 1 1 1\n3 1 2 3 2 2 2\n3 2 0 3 3 3 3\n")


@pytest.mark.parametrize("name, text", [("tet.obj", TETRAHEDRON_OBJ), ("Tet.3VN", TETRAHEDRON_3VN)])
def test_a_mesh_file_renders_framed_and_lit(tmp_path, name, text):
    """hitray render bunny.obj: the mesh alone, framed by the default
    camera and lit: its pixels are neither all background nor all black."""
    mesh = tmp_path / "in" / name
    mesh.parent.mkdir()
    mesh.write_text(text)
    out = tmp_path / "mesh.pfm"
    r = run("render", mesh, "-o", out, "--size", "32x24")
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""  # no "no lights" or "empty scene" warning
    _, _, rows = read_pfm(out)
    background, pixels = rows[0][0], [p for row in rows for p in row]
    lit = [p for p in pixels if p != background]
    assert len(lit) > len(pixels) // 10  # framed: the mesh fills a good part
    assert max(max(p) for p in lit) > 0.2  # lit, not a silhouette
    assert len(set(lit)) > 2  # shaded: the faces differ


def test_a_mesh_file_with_a_blank_in_its_name_is_refused_clearly(tmp_path):
    mesh = tmp_path / "my tet.obj"
    mesh.write_text(TETRAHEDRON_OBJ)
    r = run("render", mesh, "-o", tmp_path / "o.png")
    assert r.returncode == 1 and "mesh FILE" in r.stderr and len(r.stderr.splitlines()) == 1


def test_stats_json_keys(scene, tmp_path):
    stats = tmp_path / "stats.json"
    r = run("render", scene, "-o", tmp_path / "s.png", "--size", "16x12", "--stats-json", stats, "--threads", "2")
    assert r.returncode == 0, r.stderr
    data = json.loads(stats.read_text())
    assert set(data) == {"primary", "shadow", "reflected", "refracted", "seconds", "effects", "threads",
                         "width", "height", "pixels_refined", "samples_saved", "rays_cut"}
    assert data["primary"] == 16 * 12  # one ray per pixel at 1 spp
    assert data["shadow"] > 0  # one light, lit surfaces
    assert data["reflected"] == 0 and data["refracted"] == 0  # no mirror, no glass
    assert (data["width"], data["height"]) == (16, 12)
    assert 1 <= data["threads"] <= 2
    assert data["seconds"] >= 0
    assert "shadows" in data["effects"] and "diffuse" in data["effects"]
    assert "reflection" not in data["effects"]
    assert all(isinstance(e, str) for e in data["effects"])


def test_stats_flag_prints_ray_kinds_and_effects(scene, tmp_path):
    r = run("render", scene, "-o", tmp_path / "s.png", "--size", "8x8", "--stats", "--spp", "4")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert len(lines) == 3
    assert lines[1].startswith("rays: primary 256, shadow ")
    assert "reflected 0" in lines[1] and "refracted 0" in lines[1]
    assert lines[2].startswith("effects: ") and "supersampling" in lines[2]


# A scene with a mirror floor and a glass ball: every kind of ray.
MIRROR_SCENE = """\
camera 0 2 8   0 0.5 0   0 1 0   40
background 0.1 0.2 0.3
maxRecursionDepth 4
light 5 8 6   1 1 1
push translate -1 1 0  diffuse 0.8 0.2 0.2  sphere pop
push translate 1.2 1 -0.5  diffuse 0.1 0.1 0.1  transparency 0.8  speedOfLight 0.7  sphere pop
push rotate -90 1 0 0  reflectivity 0.7  plane pop
"""


@pytest.mark.parametrize("text, bounces", [(SCENE, False), (MIRROR_SCENE, True)])
def test_effects_all_renders_the_same_image(tmp_path, text, bounces):
    scene = write_sdl(tmp_path, "scene.sdl", text)
    stats = {}
    for mode in ("auto", "all"):
        r = run("render", scene, "-o", tmp_path / f"{mode}.pfm", "--size", "24x18", "--effects", mode,
                "--stats-json", tmp_path / f"{mode}.json")
        assert r.returncode == 0, r.stderr
        stats[mode] = json.loads((tmp_path / f"{mode}.json").read_text())
    assert (tmp_path / "auto.pfm").read_bytes() == (tmp_path / "all.pfm").read_bytes()
    auto, all_ = stats["auto"], stats["all"]
    if not bounces:  # no mirror, no glass: no bounce is cast
        assert auto["reflected"] == 0 and auto["refracted"] == 0
        assert "reflection" not in auto["effects"] and "refraction" not in auto["effects"]
    assert all_["reflected"] > auto["reflected"] and all_["refracted"] > auto["refracted"]
    assert all_["shadow"] > auto["shadow"] and all_["primary"] == auto["primary"]
    assert {"reflection", "refraction", "shadows", "emission"} <= set(all_["effects"])


def test_adaptive_and_cut_off_report_what_they_saved(tmp_path):
    scene = write_sdl(tmp_path, "scene.sdl", MIRROR_SCENE)
    stats = tmp_path / "s.json"
    r = run("render", scene, "-o", tmp_path / "a.pfm", "--size", "32x24", "--spp", "9", "--adaptive", "0.05",
            "--min-weight", "0.6", "--stats", "--stats-json", stats, "--threads", "2")
    assert r.returncode == 0, r.stderr
    data = json.loads(stats.read_text())
    lines = r.stdout.splitlines()
    assert lines[3] == (f"adaptive: {data['pixels_refined']} of 768 pixels refined, "
                        f"{data['samples_saved']} camera rays saved")
    assert lines[4] == f"cut-off: {data['rays_cut']} rays not traced"
    assert 0 < data["pixels_refined"] < 768
    assert data["samples_saved"] == 32 * 24 * 9 - data["primary"] > 0
    assert data["rays_cut"] > 0  # transparency 0.8 and reflectivity 0.7 bounces twice are below 0.6
    # The same image whatever the thread count.
    r = run("render", scene, "-o", tmp_path / "b.pfm", "--size", "32x24", "--spp", "9", "--adaptive", "0.05",
            "--min-weight", "0.6", "--threads", "1")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "a.pfm").read_bytes() == (tmp_path / "b.pfm").read_bytes()


def test_savings_reports_rays_and_error(tmp_path):
    scene = write_sdl(tmp_path, "scene.sdl", MIRROR_SCENE)
    r = run("savings", scene, "--size", "32x24", "--spp", "4", "--adaptive", "0.05", "--min-weight", "0.5",
            "--json", "--threads", "2")
    assert r.returncode == 0, r.stderr
    rows = {row["render"]: row for row in map(json.loads, r.stdout.splitlines())}
    assert list(rows) == ["full", "effects-all", "adaptive", "min-weight", "both"]
    full = rows["full"]
    assert full["rays_saved"] == 0 and full["rmse"] == 0 and full["pixels_differing"] == 0
    assert full["primary"] == 32 * 24 * 4
    for row in rows.values():
        assert row["rays"] == row["primary"] + row["shadow"] + row["reflected"] + row["refracted"]
        assert row["rays_saved"] == full["rays"] - row["rays"]
        assert 0 <= row["rmse"] <= row["max_error"] <= 1
    analysis = rows["effects-all"]  # what the effect analysis saves: rays, at no error
    assert analysis["rays_saved"] < 0 and analysis["max_error"] == 0 and analysis["pixels_differing"] == 0
    assert rows["adaptive"]["parameter"] == 0.05 and rows["adaptive"]["rays_saved"] > 0
    assert rows["adaptive"]["pixels_refined"] > 0
    assert rows["min-weight"]["rays_cut"] > 0 and rows["min-weight"]["rays_saved"] > 0
    assert rows["min-weight"]["primary"] == full["primary"]
    assert rows["both"]["rays"] < min(rows["adaptive"]["rays"], rows["min-weight"]["rays"])
    # The table says the same.
    r = run("savings", scene, "--size", "32x24", "--spp", "4", "--adaptive", "0", "--min-weight", "0.5")
    assert r.returncode == 0, r.stderr
    table = r.stdout.splitlines()
    assert table[1].split()[:2] == ["render", "rays"]
    assert [line.split()[0] for line in table[2:]] == ["full", "effects-all", "min-weight"]
    assert table[4].split()[2] == str(rows["min-weight"]["rays"])
    # Lists of values: a row each, and no "both".
    r = run("savings", scene, "--size", "16x12", "--spp", "4", "--adaptive", "0.02,0.2", "--min-weight", "0",
            "--json")
    assert r.returncode == 0, r.stderr
    rows = [json.loads(line) for line in r.stdout.splitlines()]
    assert [(row["render"], row["parameter"]) for row in rows] == [
        ("full", None), ("effects-all", None), ("adaptive", 0.02), ("adaptive", 0.2)]
    assert rows[2]["pixels_refined"] >= rows[3]["pixels_refined"]


def test_render_is_the_same_whatever_the_thread_count(scene, tmp_path):
    one, many = tmp_path / "one.pfm", tmp_path / "many.pfm"
    assert run("render", scene, "-o", one, "--size", "33x17", "--threads", "1").returncode == 0
    assert run("render", scene, "-o", many, "--size", "33x17", "--threads", "3").returncode == 0
    assert one.read_bytes() == many.read_bytes()


def test_camera_override(scene, tmp_path):
    # From high above the floor looking straight up, away from every object:
    # each pixel is the background colour.
    out = tmp_path / "sky.pfm"
    r = run("render", scene, "-o", out, "--size", "6x4", "--camera", "0,50,0,0,100,0,0,0,1,30")
    assert r.returncode == 0, r.stderr
    _, _, rows = read_pfm(out)
    for row in rows:
        for pixel in row:
            assert pixel == pytest.approx((0.1, 0.2, 0.3), abs=1e-6)
    seen = tmp_path / "seen.pfm"
    assert run("render", scene, "-o", seen, "--size", "6x4").returncode == 0
    assert seen.read_bytes() != out.read_bytes()


def test_scene_without_camera_is_framed(tmp_path):
    path = write_sdl(tmp_path, "nocam.sdl", "light 3 3 3 1 1 1\npush translate 40 0 0 sphere pop\n")
    out = tmp_path / "framed.pfm"
    assert run("render", path, "-o", out, "--size", "8x8").returncode == 0
    _, _, rows = read_pfm(out)
    assert rows[4][4] != pytest.approx(rows[0][0])  # the sphere is in the middle of the picture


def test_block_and_depth_options(scene, tmp_path):
    stats = tmp_path / "b.json"
    r = run("render", scene, "-o", tmp_path / "b.png", "--size", "16x16", "--block", "4", "--depth", "0",
            "--stats-json", stats)
    assert r.returncode == 0, r.stderr
    assert json.loads(stats.read_text())["primary"] == 16  # one ray per 4x4 block


def run_on_a_terminal(*args):
    """Run hitray with stderr on a pseudo-terminal; (exit status, stdout,
    what the terminal got). Stdout is read at the end: keep it small."""
    master, slave = pty.openpty()
    try:
        proc = subprocess.Popen([str(HITRAY), *map(str, args)], stdout=subprocess.PIPE, stderr=slave)
    finally:
        os.close(slave)
    seen = b""
    try:
        while True:
            try:
                chunk = os.read(master, 65536)
            except OSError:  # EIO: the last writer closed the terminal
                break
            if not chunk:
                break
            seen += chunk
        out = proc.stdout.read()
        proc.wait(timeout=120)
    finally:
        os.close(master)
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    return proc.returncode, out, seen.decode("utf-8", "replace")


def test_progress_bar_only_on_a_terminal(scene, tmp_path):
    rc, out, seen = run_on_a_terminal("render", scene, "-o", tmp_path / "p.png", "--size", "64x64")
    assert rc == 0
    assert "rendering [" in seen and "100%" in seen
    assert b"rendering" not in out


def test_ctrl_c_cancels_cleanly(tmp_path):
    """A first Ctrl-C stops the render: status 130, one line, no image."""
    out = tmp_path / "never.png"
    master, slave = pty.openpty()
    proc = subprocess.Popen([str(HITRAY), "render", str(ROOT / "scenes" / "demo.sdl"), "-o", str(out),
                             "--size", "1024x1024", "--spp", "256", "--threads", "2"],
                            stdout=subprocess.PIPE, stderr=slave, preexec_fn=sigint_as_at_a_terminal)
    os.close(slave)
    seen = b""
    try:
        # Wait for the progress bar: the handler is installed by then.
        deadline = time.monotonic() + 60
        while b"rendering [" not in seen and time.monotonic() < deadline:
            ready, _, _ = select.select([master], [], [], 1.0)
            if ready:
                seen += os.read(master, 4096)
        assert b"rendering [" in seen
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=60)
        while True:
            ready, _, _ = select.select([master], [], [], 0.2)
            if not ready:
                break
            try:
                chunk = os.read(master, 4096)
            except OSError:
                break
            if not chunk:
                break
            seen += chunk
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        os.close(master)
    assert proc.returncode == 130
    assert b"hitray: render interrupted" in seen
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == []


# --- hits --------------------------------------------------------------------

def hits(*args):
    r = run("hits", *args)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    return [json.loads(line) for line in r.stdout.splitlines()]


def test_hits_plane_worked_example(tmp_path):
    # Hill's worked example: the generic plane z = 0 and the ray from (4,1,3)
    # along (-3,-5,-3) meet at t = 1, the point (1,-4,0).
    path = write_sdl(tmp_path, "plane.sdl", "plane\n")
    (hit,) = hits(path, "--origin", "4,1,3", "--dir", "-3,-5,-3")
    assert hit["t"] == 1.0
    assert hit["point"] == [1.0, -4.0, 0.0]
    assert hit["normal"] == [0.0, 0.0, 1.0]
    assert hit["entering"] is True
    assert hit["surface"] == 0 and hit["object"] == 0 and hit["shape"] == "plane"
    assert set(hit) == {"t", "point", "normal", "entering", "surface", "object", "shape"}
    # Every number reads back as a float, whole ones too ("1.0", not "1").
    assert all(type(v) is float for v in [hit["t"], *hit["point"], *hit["normal"]])


def test_hits_negative_zero_keeps_its_sign(tmp_path):
    # Origin and direction with x = -0.0 meet the plane at x = -0 + 2 * -0 =
    # -0.0 exactly; it must come back as the float -0.0, not the integer 0.
    path = write_sdl(tmp_path, "plane.sdl", "plane\n")
    (hit,) = hits(path, "--origin", "-0,0,-2", "--dir", "-0,0,1")
    assert type(hit["point"][0]) is float
    assert math.copysign(1.0, hit["point"][0]) == -1.0


def test_hits_all_are_sorted_and_first_matches(tmp_path):
    path = write_sdl(tmp_path, "row.sdl", "sphere\npush translate 0 0 -3 sphere pop\nplane\n")
    every = hits(path, "--origin", "0,0,5", "--dir", "0,0,-1", "--all")
    assert [h["t"] for h in every] == [4.0, 5.0, 6.0, 7.0, 9.0]
    assert [h["shape"] for h in every] == ["sphere", "plane", "sphere", "sphere", "sphere"]
    assert [h["object"] for h in every] == [0, 2, 0, 1, 1]
    spheres = [h["entering"] for h in every if h["shape"] == "sphere"]
    assert spheres == [True, False, True, False]
    (first,) = hits(path, "--origin", "0,0,5", "--dir", "0,0,-1")
    assert first == every[0]


def test_hits_none_prints_nothing(tmp_path):
    path = write_sdl(tmp_path, "s.sdl", "sphere\n")
    assert hits(path, "--origin", "0,0,5", "--dir", "0,0,1") == []
    assert hits(path, "--origin", "0,0,5", "--dir", "0,0,1", "--all") == []


def test_hits_numbers_round_trip(tmp_path):
    path = write_sdl(tmp_path, "s.sdl", "sphere\n")
    r = run("hits", path, "--origin", "0.1,0.2,5", "--dir", "0,0,-1")
    (hit,) = [json.loads(line) for line in r.stdout.splitlines()]
    expected = 5 - math.sqrt(1 - 0.1 ** 2 - 0.2 ** 2)
    assert hit["t"] == pytest.approx(expected, rel=1e-14)
    # 17 significant digits: the text is exactly the double the library had.
    text = r.stdout.split('"t": ')[1].split(",")[0]
    assert len(text.replace("-", "").replace(".", "").lstrip("0")) >= 15
    assert hit["point"][2] == pytest.approx(5 - hit["t"], abs=1e-15)


def test_hits_torus_equatorial_line_and_axis(tmp_path):
    # The generic torus (ring radius 1 about z, tube 0.2): the line along a
    # diameter crosses the tube four times, in and out alternately; the axis,
    # through the hole, misses. Moved and scaled by the SDL transform, t stays
    # the object-space t (Hill): x scaled by 2 doubles the crossings' x.
    path = write_sdl(tmp_path, "torus.sdl", "torus\n")
    every = hits(path, "--origin", "-10,0,0", "--dir", "1,0,0", "--all")
    assert [h["t"] for h in every] == pytest.approx([8.8, 9.2, 10.8, 11.2], rel=1e-15)
    assert [h["entering"] for h in every] == [True, False, True, False]
    assert [h["normal"][0] for h in every] == pytest.approx([-1.0, 1.0, -1.0, 1.0])
    assert all(h["shape"] == "torus" for h in every)
    assert hits(path, "--origin", "0,0,-10", "--dir", "0,0,1", "--all") == []
    scaled = write_sdl(tmp_path, "scaled.sdl", "scale 2 1 1 torus\n")
    (first,) = hits(scaled, "--origin", "-10,0,0", "--dir", "1,0,0")
    assert first["t"] == pytest.approx(10 - 2.4, rel=1e-15)
    assert first["point"] == pytest.approx([-2.4, 0.0, 0.0], abs=1e-14)


# --- shapes ------------------------------------------------------------------

def test_shapes_lists_modules_classes_and_parameters():
    r = run("shapes")
    assert r.returncode == 0, r.stderr
    out = r.stdout
    for name in ("sphere", "plane", "cube", "square"):
        assert f"  {name}" in out, name
    module_paths = [line for line in out.splitlines() if line.endswith(".so")]
    assert module_paths and all(pathlib.Path(p).is_file() for p in module_paths)
    if "taperedCylinder" in out:  # a class with a parameter: name, default, range, help
        line = next(l for l in out.splitlines() if l.strip().startswith("s "))
        assert "default" in line and "range" in line
    if "torus" in out:  # a number and a string parameter, each with its help
        tube = next(l for l in out.splitlines() if l.strip().startswith("tube "))
        assert "default 0.2" in tube and "range [1e-06, 0.999]" in tube
        solver = next(l for l in out.splitlines() if l.strip().startswith("solver "))
        assert all(name in solver for name in ("ferrari", "ferrari-newton", "bracketing"))


def test_shapes_says_which_classes_give_uv():
    """Each class's listing ends with whether an image texture can go on it."""
    out = run("shapes").stdout
    lines = out.splitlines()

    def uv_of(name):
        start = next(i for i, l in enumerate(lines) if l.startswith(f"  {name} "))
        return next(l for l in lines[start + 1:] if l.strip().startswith("(u, v):")).strip()

    for name in ("sphere", "cube", "square", "plane", "cylinder", "cone", "torus", "mesh"):
        assert uv_of(name) == "(u, v): yes, for image textures", name
    assert uv_of("union") == "(u, v): its leaves'"
    assert uv_of("tetrahedron").startswith("(u, v): none (image textures refused")


def test_shapes_reports_modules_that_failed(tmp_path):
    (tmp_path / "broken.so").write_text("not a shared object")
    r = run("shapes", env={"HITRAY_SHAPE_PATH": str(tmp_path)})
    assert r.returncode == 0, r.stderr
    assert str(tmp_path / "broken.so") in r.stdout
    assert "NOT LOADED" in r.stdout
    assert "sphere" in r.stdout  # the built-in modules are still found


# --- help and version --------------------------------------------------------

@pytest.mark.parametrize("verb", ["render", "hits", "shapes", "savings"])
def test_help_of_each_verb(verb):
    for flag in ("--help", "-h"):
        r = run(verb, flag)
        assert r.returncode == 0
        assert r.stdout.startswith(f"usage: hitray {verb}")
        assert r.stderr == ""


def test_top_level_help_and_version():
    for flag in ("--help", "-h", "help"):
        r = run(flag)
        assert r.returncode == 0 and "usage: hitray" in r.stdout
        for verb in ("render", "hits", "shapes"):
            assert verb in r.stdout
    r = run("--version")
    assert r.returncode == 0 and r.stdout.startswith("hitray 0.")


def test_help_lists_the_exit_statuses():
    """The statuses the tests around here check, as --help (and so the man
    page) lists them."""
    statuses = run("--help").stdout.split("exit status:\n")[1]
    listed = [line.split()[0] for line in statuses.splitlines() if line[:3].strip().isdigit()]
    assert listed == ["0", "1", "2", "130"]
    assert "usage error" in statuses and "interrupted" in statuses


# --- user errors: status 1, one line, nothing left behind --------------------

def error_cases(tmp_path, scene):
    bad_sdl = write_sdl(tmp_path, "bad.sdl", "sphere\nrotate 1 2\n")
    directory_png = tmp_path / "dir.png"
    directory_png.mkdir()
    directory_exr = tmp_path / "dir.exr"
    directory_exr.mkdir()
    out = tmp_path / "o.png"
    return {
        "no command": [],
        "unknown command": ["paint"],
        "unknown top-level option": ["--frobnicate"],
        "unknown option": ["render", scene, "-o", out, "--frobnicate"],
        "size not a number": ["render", scene, "-o", out, "--size", "10xq"],
        "size zero": ["render", scene, "-o", out, "--size", "0x5"],
        "size huge": ["render", scene, "-o", out, "--size", "99999999999x5"],
        "spp not a number": ["render", scene, "-o", out, "--spp", "many"],
        "spp zero": ["render", scene, "-o", out, "--spp", "0"],
        "threads negative": ["render", scene, "-o", out, "--threads", "-1"],
        "depth with junk": ["render", scene, "-o", out, "--depth", "3x"],
        "camera too short": ["render", scene, "-o", out, "--camera", "1,2,3"],
        "camera angle": ["render", scene, "-o", out, "--camera", "0,0,5,0,0,0,0,1,0,0"],
        "camera up parallel": ["render", scene, "-o", out, "--camera", "0,0,5,0,0,0,0,0,1,40"],
        "option without value": ["render", scene, "-o", out, "--spp"],
        "flag with value": ["render", scene, "-o", out, "--stats=yes"],
        "missing output": ["render", scene],
        "missing scene": ["render", "-o", out],
        "two scenes": ["render", scene, scene, "-o", out],
        "no such scene": ["render", tmp_path / "absent.sdl", "-o", out],
        "scene syntax error": ["render", bad_sdl, "-o", out],
        "unknown extension": ["render", scene, "-o", tmp_path / "o.tiff"],
        "missing directory": ["render", scene, "-o", tmp_path / "no" / "such" / "o.png"],
        "exr into missing directory": ["render", scene, "-o", out, "--exr", tmp_path / "no" / "o.exr"],
        "stats into missing directory": ["render", scene, "-o", out, "--stats-json", tmp_path / "no" / "s.json"],
        "output is a directory": ["render", scene, "-o", directory_png, "--size", "4x4"],
        "hits without dir": ["hits", scene, "--origin", "0,0,0"],
        "hits without origin": ["hits", scene, "--dir", "0,0,1"],
        "hits bad origin": ["hits", scene, "--origin", "0,0,nan", "--dir", "0,0,1"],
        "hits zero dir": ["hits", scene, "--origin", "0,0,0", "--dir", "0,0,0"],
        "hits four numbers": ["hits", scene, "--origin", "0,0,0,0", "--dir", "0,0,1"],
        "hits no such scene": ["hits", tmp_path / "absent.sdl", "--origin", "0,0,0", "--dir", "0,0,1"],
        "shapes extra argument": ["shapes", "sphere"],
        "size twice": ["render", scene, "-o", out, "--size", "4x4", "--size", "8x8"],
        "output twice": ["render", scene, "-o", out, "-o", tmp_path / "p.png", "--size", "4x4"],
        "hits origin twice": ["hits", scene, "--origin", "0,0,9", "--origin", "0,0,5", "--dir", "0,0,-1"],
        "empty exr name": ["render", scene, "-o", out, "--size", "4x4", "--exr", ""],
        "empty stats name": ["render", scene, "-o", out, "--size", "4x4", "--stats-json", ""],
        "exr is a directory": ["render", scene, "-o", out, "--size", "4x4", "--exr", directory_exr],
        "help with extra words": ["--help", "render"],
        "version with extra words": ["--version", "now"],
        "hexadecimal origin": ["hits", scene, "--origin", "0x1p1,0,5", "--dir", "0,0,-1"],
        "exr not named .exr": ["render", scene, "-o", out, "--size", "4x4", "--exr", tmp_path / "e.png"],
        "stats is a directory": ["render", scene, "-o", out, "--size", "4x4", "--stats-json", directory_png],
        "stats over the image": ["render", scene, "-o", out, "--size", "4x4", "--stats-json", out],
        "exr over the image": ["render", scene, "-o", tmp_path / "o.exr", "--size", "4x4",
                               "--exr", tmp_path / "o.exr"],
        "newline before a number": ["hits", scene, "--origin", "\n0,0,5", "--dir", "0,0,-1"],
        "newline after a comma": ["hits", scene, "--origin", "0,\n0,5", "--dir", "0,0,-1"],
        "effects neither": ["render", scene, "-o", out, "--effects", "some"],
        "adaptive above 1": ["render", scene, "-o", out, "--spp", "4", "--adaptive", "2"],
        "adaptive nan": ["render", scene, "-o", out, "--spp", "4", "--adaptive", "nan"],
        "adaptive at 1 spp": ["render", scene, "-o", out, "--adaptive", "0.1"],
        "adaptive with blocks": ["render", scene, "-o", out, "--spp", "4", "--adaptive", "0.1", "--block", "2"],
        "min-weight negative": ["render", scene, "-o", out, "--min-weight", "-0.1"],
        "exact with a min-weight": ["render", scene, "-o", out, "--exact", "--min-weight", "0.1"],
        "savings without scene": ["savings", "--size", "4x4"],
        "savings at 1 spp": ["savings", scene, "--spp", "1"],
        "savings bad threshold": ["savings", scene, "--adaptive", "x"],
        "window three numbers": ["render", scene, "-o", out, "--window", "0,0,4"],
        "window not whole": ["render", scene, "-o", out, "--window", "0,0,4.5,4"],
        "window empty": ["render", scene, "-o", out, "--window", "0,0,0,4"],
        "window negative": ["render", scene, "-o", out, "--window", "-1,0,4,4"],
        "window outside": ["render", scene, "-o", out, "--size", "8x8", "--window", "4,4,5,4"],
        "unknown format": ["render", scene, "-o", out, "--format", "gif"],
        "format against extension": ["render", scene, "-o", out, "--format", "ppm"],
    }


# The cases above that are scene or input errors (exit status 1): a file that
# cannot be read or written, a camera the library refuses. Every other one is
# a mistake in the command line itself: a usage error, status 2.
INPUT_ERRORS = {
    "camera angle", "camera up parallel", "no such scene", "scene syntax error", "missing directory",
    "exr into missing directory", "stats into missing directory", "output is a directory",
    "hits no such scene", "exr is a directory", "stats is a directory",
}


def test_user_errors_exit_1_or_2_with_one_line(tmp_path, scene):
    cases = error_cases(tmp_path, scene)
    assert INPUT_ERRORS <= set(cases)
    for name, args in cases.items():
        r = run(*args)
        status = 1 if name in INPUT_ERRORS else 2
        assert r.returncode == status, f"{name}: status {r.returncode}, stderr {r.stderr!r}"
        lines = r.stderr.splitlines()
        assert len(lines) == 1, f"{name}: {r.stderr!r}"
        assert lines[0].startswith("hitray: ") and len(lines[0]) > len("hitray: ") + 5, name
        assert "Traceback" not in r.stderr and "Sanitizer" not in r.stderr, name
        assert r.stdout == "", f"{name}: {r.stdout!r}"
    # No output image and no temporary file was left by any of them.
    leftovers = sorted(p.name for p in tmp_path.iterdir())
    assert leftovers == ["bad.sdl", "dir.exr", "dir.png", "scene.sdl"]
    assert list((tmp_path / "dir.png").iterdir()) == []
    assert list((tmp_path / "dir.exr").iterdir()) == []


def test_error_messages_say_what_is_wrong(tmp_path, scene):
    r = run("render", scene, "-o", tmp_path / "o.png", "--size", "10xq")
    assert "--size" in r.stderr and "10xq" in r.stderr
    r = run("render", tmp_path / "absent.sdl", "-o", tmp_path / "o.png")
    assert "absent.sdl" in r.stderr
    bad = write_sdl(tmp_path, "bad.sdl", "sphere\nrotate 1 2\n")
    r = run("render", bad, "-o", tmp_path / "o.png")
    assert "bad.sdl:" in r.stderr  # file:line:col from the SDL reader
    r = run("render", scene, "-o", tmp_path / "no" / "o.png")
    assert str(tmp_path / "no") in r.stderr


def test_stats_json_write_failure_keeps_the_old_file(scene, tmp_path):
    """A --stats-json write that fails part way (the disk fills up) must
    leave the file that was there before, not a truncated JSON object."""
    import resource

    stats = tmp_path / "stats.json"
    stats.write_text('{"old": true}\n')

    def small_files():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # write() fails with EFBIG instead
        resource.setrlimit(resource.RLIMIT_FSIZE, (100, 100))  # the 2x2 PPM fits, the JSON not

    r = subprocess.run([str(HITRAY), "render", str(scene), "-o", str(tmp_path / "o.ppm"), "--size", "2x2",
                        "--stats-json", str(stats)], capture_output=True, text=True, preexec_fn=small_files,
                       timeout=120)
    assert r.returncode == 1, r.stderr
    assert len(r.stderr.splitlines()) == 1 and str(stats) in r.stderr
    assert stats.read_text() == '{"old": true}\n'
    # All outputs of one command or none: the image that did fit is not left.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.sdl", "stats.json"]


def test_an_exr_that_fails_on_a_full_disk_leaves_no_png(scene, tmp_path):
    """Issue 16, defect 8: the PNG was written, then the EXR failed, and
    the command exited 1 leaving the new PNG beside the old EXR."""
    import resource

    probe = run("render", scene, "-o", tmp_path / "probe.png", "--exr", tmp_path / "probe.exr",
                "--size", "32x24")
    assert probe.returncode == 0, probe.stderr
    png_size = (tmp_path / "probe.png").stat().st_size
    exr_size = (tmp_path / "probe.exr").stat().st_size
    assert png_size < exr_size
    for name in ("probe.png", "probe.exr"):
        (tmp_path / name).unlink()
    (tmp_path / "o.png").write_bytes(b"old png")

    def small_files():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # write() fails with EFBIG instead
        resource.setrlimit(resource.RLIMIT_FSIZE, (png_size, png_size))  # the PNG fits, the EXR not

    r = subprocess.run([str(HITRAY), "render", str(scene), "-o", str(tmp_path / "o.png"), "--exr",
                        str(tmp_path / "o.exr"), "--size", "32x24"], capture_output=True, text=True,
                       preexec_fn=small_files, timeout=120)
    assert r.returncode == 1, r.stderr
    assert len(r.stderr.splitlines()) == 1 and "o.exr" in r.stderr
    assert (tmp_path / "o.png").read_bytes() == b"old png"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o.png", "scene.sdl"]


def test_a_link_to_a_special_file_is_not_replaced(scene, tmp_path):
    """Issue 16, defect 4: a link to /dev/full was followed and the device
    replaced by a regular PNG file. The test links to a FIFO of its own
    instead (replacing a real device is what an unfixed build would do)."""
    fifo = tmp_path / "fifo.png"
    link = tmp_path / "out.png"
    os.mkfifo(fifo)
    os.symlink(fifo, link)
    for target in (link, fifo):
        r = run("render", scene, "-o", target, "--size", "4x4")
        assert r.returncode == 1
        assert r.stderr.strip().endswith("not a regular file (a FIFO)"), r.stderr
        assert len(r.stderr.splitlines()) == 1
    assert os.path.islink(link) and stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo.png", "out.png", "scene.sdl"]


def test_a_read_only_target_is_refused(scene, tmp_path):
    out = tmp_path / "out.png"
    out.write_bytes(b"keep me")
    out.chmod(0o444)
    r = run("render", scene, "-o", out, "--size", "4x4")
    assert r.returncode == 1
    assert "read-only (mode 0444)" in r.stderr and len(r.stderr.splitlines()) == 1
    assert out.read_bytes() == b"keep me"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.png", "scene.sdl"]


def signal_while_writing(tmp_path, signo):
    """Render a big 16-bit PNG (one ray per 2048x2048 block: the render is
    instant, the write is not), send `signo` once the progress bar is cleared,
    that is, while the file is being written; return the exit status and the
    image's path."""
    scene = write_sdl(tmp_path, "one.sdl", "light 3 3 3 1 1 1\nsphere\n")
    out = tmp_path / "big.png"
    master, slave = pty.openpty()
    proc = subprocess.Popen([str(HITRAY), "render", str(scene), "-o", str(out), "--size", "4096x4096",
                             "--block", "2048", "--png16"], stdout=subprocess.PIPE, stderr=slave,
                            preexec_fn=sigint_as_at_a_terminal)
    os.close(slave)
    seen = b""
    try:
        deadline = time.monotonic() + 60
        while b"\x1b[K" not in seen and time.monotonic() < deadline:  # the bar is cleared: writing
            ready, _, _ = select.select([master], [], [], 1.0)
            if ready:
                try:
                    seen += os.read(master, 4096)
                except OSError:
                    break
        assert b"\x1b[K" in seen
        proc.send_signal(signo)
        proc.wait(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        os.close(master)
    return proc.returncode, out


def test_ctrl_c_while_writing_leaves_no_temporary_file(tmp_path):
    """Ctrl-C after the render, while the (big, slow) PNG is being written,
    must not kill the process between creating its temporary file and
    renaming it: the write finishes, and nothing else is left behind."""
    returncode, out = signal_while_writing(tmp_path, signal.SIGINT)
    assert returncode == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.png", "one.sdl"]
    assert png_header(out)[:3] == (4096, 4096, 16)


def test_sigkill_while_writing_leaves_no_temporary_file(tmp_path):
    """Issue 16, defect 9: SIGKILL cannot be held, and killed mid-write the
    process left its '.big.png.XXXXXX' beside the target. The file being
    written has no name (O_TMPFILE) until it is complete, so nothing is left
    where the filesystem has O_TMPFILE (tmpfs, ext4, xfs, btrfs do)."""
    returncode, out = signal_while_writing(tmp_path, signal.SIGKILL)
    assert returncode == -signal.SIGKILL
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names in (["one.sdl"], ["big.png", "one.sdl"]), names


def test_sigterm_while_writing_waits_for_the_file(tmp_path):
    """SIGTERM (or SIGHUP, or a second Ctrl-C) during the write is held until
    the image is complete and renamed: the process then dies of it, leaving
    the whole image and no temporary file."""
    returncode, out = signal_while_writing(tmp_path, signal.SIGTERM)
    assert returncode == -signal.SIGTERM
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.png", "one.sdl"]
    assert png_header(out)[:3] == (4096, 4096, 16)


def test_ignored_sigint_stays_ignored(tmp_path):
    """A shell starts background jobs with SIGINT ignored so that Ctrl-C at
    the terminal leaves them running: the render must not be cancelled."""
    out = tmp_path / "bg.png"
    master, slave = pty.openpty()
    proc = subprocess.Popen([str(HITRAY), "render", str(ROOT / "scenes" / "demo.sdl"), "-o", str(out),
                             "--size", "256x256", "--spp", "16", "--threads", "2"],
                            stdout=subprocess.PIPE, stderr=slave,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    os.close(slave)
    seen = b""
    try:
        deadline = time.monotonic() + 60
        while b"rendering [" not in seen and time.monotonic() < deadline:
            ready, _, _ = select.select([master], [], [], 1.0)
            if ready:
                try:
                    seen += os.read(master, 4096)
                except OSError:
                    break
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        os.close(master)
    assert proc.returncode == 0
    assert png_header(out)[:2] == (256, 256)


def test_render_summary_that_cannot_be_written_is_an_error(scene, tmp_path):
    """Like hits and shapes: output lost to a full disk is not success."""
    with open("/dev/full", "w") as full:
        r = subprocess.run([str(HITRAY), "render", str(scene), "-o", str(tmp_path / "f.png"), "--size", "2x2"],
                           stdout=full, stderr=subprocess.PIPE, text=True, timeout=120)
    assert r.returncode == 1
    assert len(r.stderr.splitlines()) == 1 and r.stderr.startswith("hitray: ")


def test_subnormal_numbers_are_numbers_as_in_sdl(tmp_path):
    """Issue 16: strtod's ERANGE on underflow made the CLI call 1e-310 "not
    3 comma-separated numbers"; the SDL reader takes it."""
    scene = write_sdl(tmp_path, "s.sdl", "sphere\n")
    r = run("hits", scene, "--origin", "0,0,7", "--dir", "0,1e-310,-1")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["t"] == 6.0
    r = run("hits", scene, "--origin", "0,0,7", "--dir", "0,1e400,-1")
    assert r.returncode == 2 and "--dir" in r.stderr


def test_framing_a_scene_too_far_names_the_object(tmp_path):
    """Issue 16: `translate 1e308 0 0 sphere` with no camera said only that
    the camera's numbers were not finite; the user wrote no camera."""
    scene = write_sdl(tmp_path, "far.sdl", "sphere\ntranslate 1e308 0 0 cube\n")
    r = run("render", scene, "-o", tmp_path / "o.png", "--size", "4x4")
    assert r.returncode == 1 and len(r.stderr.splitlines()) == 1
    assert "object 1 (a 'cube')" in r.stderr and "give the scene a camera" in r.stderr, r.stderr


def test_exact_renders_the_same_image_as_the_default_cut_off(tmp_path):
    """On a scene whose paths never get fainter than 2^-24, --exact (no
    cut-off) and the default cut-off give the same pixels and rays."""
    scene = write_sdl(tmp_path, "mirror.sdl", "maxRecursionDepth 5 minReflectivity 0\n"
                      "light 4 6 5 1 1 1\nreflectivity 0.3 diffuse .2 .2 .2 sphere\n"
                      "push translate 2 0 0 reflectivity 0.3 cube pop\n")
    a, b = tmp_path / "a.pfm", tmp_path / "b.pfm"
    ra = run("render", scene, "-o", a, "--size", "16x12", "--stats-json", tmp_path / "a.json")
    rb = run("render", scene, "-o", b, "--size", "16x12", "--exact", "--stats-json", tmp_path / "b.json")
    assert ra.returncode == 0 and rb.returncode == 0, ra.stderr + rb.stderr
    assert a.read_bytes() == b.read_bytes()
    sa, sb = (json.loads((tmp_path / n).read_text()) for n in ("a.json", "b.json"))
    assert sa["rays_cut"] == sb["rays_cut"] == 0
    assert [sa[k] for k in ("primary", "shadow", "reflected")] == [sb[k] for k in ("primary", "shadow", "reflected")]


# A number with a unit of time, or a count of instructions or cycles.
_MEASUREMENT = re.compile(r"\d\s*(ns|us|µs|ms)\b|\binstructions?\b|\bcycles?\b")


def test_shape_help_quotes_no_measurement():
    """`hitray shapes` says what a choice does, not what it measured on some
    machine: timings and instruction counts go stale, so they live in
    bench/results/RESULTS.md and the help points there (the torus's solver)."""
    r = run("shapes")
    assert r.returncode == 0, r.stderr
    bad = [line.strip() for line in r.stdout.splitlines() if _MEASUREMENT.search(line)]
    assert not bad, f"help that quotes a measurement: {bad}"
    solver = [line for line in r.stdout.splitlines() if line.strip().startswith("solver ")]
    assert solver and "bench/results/RESULTS.md" in solver[0]


def test_an_output_that_is_the_scene_file_is_refused(tmp_path):
    """`hitray render scene.ppm -o scene.ppm` overwrote its own scene; so
    would the same file under another name (a link) or as --exr or
    --stats-json. Refused before any work, the scene left as it was."""
    scene = tmp_path / "scene.ppm"  # an SDL file, whatever its name
    scene.write_text(SCENE)
    link = tmp_path / "same.png"
    os.link(scene, link)
    before = scene.read_bytes()
    for args in (["-o", scene], ["-o", link], ["-o", tmp_path / "a.png", "--exr", scene],
                 ["-o", tmp_path / "b.png", "--stats-json", scene]):
        r = run("render", scene, *args, "--size", "8x6")
        assert r.returncode == 2, r.stderr
        assert r.stderr.count("\n") == 1 and "is the scene file" in r.stderr, r.stderr
        assert scene.read_bytes() == before
    assert not (tmp_path / "a.png").exists() and not (tmp_path / "b.png").exists()


def test_a_very_long_output_path_keeps_its_reason(scene, tmp_path):
    """A 6,000-byte -o path cut the message before its reason."""
    folder = str(tmp_path / ("d" * 3000))
    path = folder + "/" + "x" * 3000 + ".png"
    r = run("render", scene, "-o", path, "--size", "8x6")
    assert r.returncode == 1
    assert r.stderr.count("\n") == 1, r.stderr[-200:]
    assert r.stderr.endswith(f"': no directory '{folder}'\n"), r.stderr[-200:]


def test_control_bytes_of_a_scene_reach_the_terminal_escaped(tmp_path):
    """A scene's word, or a path, with an escape sequence in it is shown
    with \\xNN, not passed to the terminal."""
    path = tmp_path / "bad.sdl"
    path.write_bytes(b"sph\x1b[31mere\n")
    r = run("render", path, "-o", tmp_path / "out.png", "--size", "8x6")
    assert r.returncode == 1
    assert "\x1b" not in r.stderr and "unknown keyword 'sph\\x1b[31mere'" in r.stderr, r.stderr
    odd = tmp_path / "t\x1b]0;x\x07.nff"
    r = run("render", odd, "-o", tmp_path / "out.png")
    assert r.returncode == 1 and "\x1b" not in r.stderr and "\x07" not in r.stderr, r.stderr

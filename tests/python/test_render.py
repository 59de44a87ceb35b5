"""hitray.render and Image: numpy sees the pixels in place, the writers,
Jupyter's PNG, the statistics, progress, and arguments refused."""

import gc
import struct
import zlib

import numpy as np
import pytest

import hitray
from conftest import TWO_SPHERES_SDL

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
EXR_MAGIC = b"\x76\x2f\x31\x01"


@pytest.fixture(scope="module")
def demo():
    return hitray.parse_sdl(TWO_SPHERES_SDL)


def png_size(data):
    assert data[:8] == PNG_SIGNATURE
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def test_numpy_sees_the_pixels_in_place(demo):
    scene, camera = demo
    image = hitray.render(scene, camera, size=(40, 30), progress=False)
    a = np.asarray(image)
    assert a.shape == (30, 40, 3) and a.dtype == np.float32 and image.shape == (30, 40, 3)
    b = np.asarray(image)
    assert np.shares_memory(a, b)  # both are views of the image's own pixels
    a[0, 0] = (7, 8, 9)
    assert tuple(np.asarray(image)[0, 0]) == (7, 8, 9)
    copied = np.array(image)  # an explicit copy is a copy
    assert not np.shares_memory(copied, a)
    del image, b
    gc.collect()
    assert tuple(a[0, 0]) == (7, 8, 9)  # the view keeps the pixels alive
    assert a.sum() > 0


def test_asarray_with_another_dtype_converts(demo):
    scene, camera = demo
    image = hitray.render(scene, camera, size=(8, 6), progress=False)
    d = np.asarray(image, dtype=np.float64)
    assert d.dtype == np.float64 and np.array_equal(d, np.asarray(image))


def test_the_image_is_the_same_whatever_the_thread_count(demo):
    scene, camera = demo
    one = hitray.render(scene, camera, size=(48, 36), spp=4, threads=1, progress=False)
    two = hitray.render(scene, camera, size=(48, 36), spp=4, threads=2, progress=False)
    assert np.array_equal(np.asarray(one), np.asarray(two))


def test_stats_count_the_rays(demo):
    scene, camera = demo
    image = hitray.render(scene, camera, size=(20, 10), spp=4, threads=1, progress=False)
    s = image.stats
    assert s.primary == 20 * 10 * 4 and s.threads == 1
    assert s.shadow > 0 and s.reflected == 0 and s.refracted == 0
    assert s.rays == s.primary + s.shadow
    assert {"diffuse", "shadows", "supersampling"} <= s.effects
    assert "reflection" not in s.effects


def test_depth_and_block_size_options():
    scene = hitray.Scene()
    scene.add(hitray.Sphere().translate(-1.1, 0, 0), reflectivity=0.9)
    scene.add(hitray.Sphere().translate(1.1, 0, 0), reflectivity=0.9)
    scene.light((0, 5, 5))
    cam = hitray.Camera((0, 0, 6), (0, 0, 0), (0, 1, 0), 40)
    flat = hitray.render(scene, cam, size=(32, 32), depth=0, progress=False)
    deep = hitray.render(scene, cam, size=(32, 32), depth=4, progress=False)
    assert flat.stats.reflected == 0 and deep.stats.reflected > 0
    blocky = np.asarray(hitray.render(scene, cam, size=(32, 32), block_size=4, progress=False))
    assert np.array_equal(blocky[0:4, 0:4], np.broadcast_to(blocky[0, 0], (4, 4, 3)))
    assert hitray.render(scene, cam, size=(8, 8), progress=False, all_effects=True).stats.effects >= {
        "reflection", "refraction", "shadows"}


def test_no_camera_frames_the_scene():
    scene = hitray.Scene()
    scene.add(hitray.Sphere().translate(100, 0, 0), emissive=(1, 1, 1))
    image = np.asarray(hitray.render(scene, None, size=(16, 16), progress=False))
    assert image[8, 8].min() > 0.9  # the sphere is in the middle of the frame


def test_save_png_exr_ppm_pfm(demo, tmp_path):
    scene, camera = demo
    image = hitray.render(scene, camera, size=(24, 16), progress=False)
    image.save(tmp_path / "a.png")
    assert png_size((tmp_path / "a.png").read_bytes()) == (24, 16)
    image.save(str(tmp_path / "b.png"), bits=16, linear=True)
    data = (tmp_path / "b.png").read_bytes()
    assert data[24] == 16  # IHDR bit depth
    image.save(tmp_path / "c.exr")
    assert (tmp_path / "c.exr").read_bytes()[:4] == EXR_MAGIC
    image.save(tmp_path / "d.exr", half=True)
    assert (tmp_path / "d.exr").stat().st_size < (tmp_path / "c.exr").stat().st_size
    image.save(tmp_path / "e.ppm")
    assert (tmp_path / "e.ppm").read_bytes().startswith(b"P6")
    image.save(tmp_path / "f.data", format="pfm")
    assert (tmp_path / "f.data").read_bytes().startswith(b"PF")


def test_save_failures_raise_and_leave_no_file(demo, tmp_path):
    scene, camera = demo
    image = hitray.render(scene, camera, size=(4, 4), progress=False)
    with pytest.raises(hitray.FileError) as err:
        image.save(tmp_path / "missing" / "x.png")
    assert "missing" in str(err.value) and isinstance(err.value, OSError)
    with pytest.raises(hitray.Error):
        image.save(tmp_path / "x.unknown")
    with pytest.raises(ValueError, match="bits"):
        image.save(tmp_path / "x.png", bits=12)
    with pytest.raises(ValueError, match="format"):
        image.save(tmp_path / "x.png", format="gif")
    with pytest.raises(ValueError, match="null"):
        image.save("x\0.png")
    assert list(tmp_path.iterdir()) == []


def test_repr_png_is_a_png_of_the_image(demo):
    scene, camera = demo
    image = hitray.render(scene, camera, size=(12, 9), progress=False)
    data = image._repr_png_()
    assert png_size(data) == (12, 9)


def test_an_image_from_an_array_round_trips_through_png(tmp_path):
    # Linear 0 and 1 map to sRGB 0 and 255 exactly; 0.5 linear is sRGB 188.
    pixels = np.zeros((2, 3, 3), dtype=np.float32)
    pixels[0, 0] = (1, 0, 0)
    pixels[1, 2] = (0.5, 0.5, 0.5)
    image = hitray.Image(pixels)
    assert image.stats is None
    pixels[0, 0] = 0  # copied at construction
    assert tuple(np.asarray(image)[0, 0]) == (1, 0, 0)
    image.save(tmp_path / "x.png")
    rows = png_rows(tmp_path / "x.png")
    assert rows[0][0:3] == bytes((255, 0, 0)) and rows[1][6:9] == bytes((188, 188, 188))
    with pytest.raises(ValueError):
        hitray.Image(np.zeros((2, 3)))


def png_rows(path):
    """Rows of an 8-bit RGB PNG with filter type 0 (what libpng writes for
    tiny images is not guaranteed: undo the Sub/Up/... filters generally)."""
    data = path.read_bytes()
    width, height = png_size(data)
    at, idat = 8, b""
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        if data[at + 4:at + 8] == b"IDAT":
            idat += data[at + 8:at + 8 + length]
        at += 12 + length
    raw = zlib.decompress(idat)
    stride, rows, prev = width * 3, [], bytearray(width * 3)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - 3] if x >= 3 else 0
            b, c = prev[x], prev[x - 3] if x >= 3 else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return rows


def test_progress_callable_sees_fractions_up_to_one(demo):
    scene, camera = demo
    seen = []
    hitray.render(scene, camera, size=(64, 64), progress=seen.append)
    assert seen and seen[-1] == 1.0
    assert seen == sorted(seen) and all(0 <= f <= 1 for f in seen)


def test_progress_bar_is_drawn_on_stderr(demo, capsys):
    scene, camera = demo
    hitray.render(scene, camera, size=(16, 16), progress=True)
    assert "hitray" in capsys.readouterr().err


def test_an_exception_in_the_progress_callable_cancels_and_is_raised(demo):
    scene, camera = demo
    seen = []

    def stop(fraction):
        seen.append(fraction)
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        hitray.render(scene, camera, size=(400, 400), spp=16, threads=1, progress=stop)
    assert seen[0] < 1.0
    # The scene still renders afterwards.
    assert hitray.render(scene, camera, size=(4, 4), progress=False).stats.primary == 16


@pytest.mark.parametrize("kwargs, error", [
    (dict(size=(0, 10)), ValueError),
    (dict(size=(10,)), TypeError),
    (dict(size=(10.5, 10)), TypeError),
    (dict(spp=0), ValueError),
    (dict(threads=0), ValueError),
    (dict(depth=-1), ValueError),
    (dict(depth=5000), hitray.ArgumentError),
    (dict(block_size=0), ValueError),
    (dict(progress="yes"), TypeError),
    (dict(camera="cam"), TypeError),
    (dict(camera=hitray.Camera((0, 0, 0), (0, 0, 0), (0, 1, 0), 45)), hitray.ArgumentError),
    (dict(camera=hitray.Camera((0, 0, 5), (0, 0, 0), (0, 1, 0), 180)), hitray.ArgumentError),
    (dict(window=(0, 0, 0, 4)), ValueError),
    (dict(window=(6, 0, 3, 1)), ValueError),
    (dict(window=(-1, 0, 2, 2)), ValueError),
    (dict(window=(0, 0, 2)), TypeError),
    (dict(window=(0, 0, 2.0, 2)), TypeError),
    (dict(adaptive=0.1), hitray.ArgumentError),  # needs spp >= 2
    (dict(adaptive=1.5, spp=4), hitray.ArgumentError),
    (dict(min_weight=0.1, exact=True), hitray.ArgumentError),
    # A flag is a bool (or 0 or 1), not any object's truth: "no" was True.
    (dict(exact="no"), TypeError),
    (dict(exact=2), TypeError),
    (dict(exact=None), TypeError),
    (dict(all_effects="no"), TypeError),
])
def test_bad_render_arguments_raise(demo, kwargs, error):
    scene, camera = demo
    args = dict(camera=camera, size=(8, 8), progress=False)
    args.update(kwargs)
    with pytest.raises(error):
        hitray.render(scene, **args)


def test_a_window_is_that_part_of_the_full_render(demo):
    """window=(x, y, w, h): a w x h image, bit for bit those pixels of the
    full render, for adaptive supersampling and Hill's blocks too (the C
    tests tile frames in every way; this is the binding's pass-through)."""
    scene, camera = demo
    for options in (dict(spp=4, adaptive=0.05), dict(block_size=3, depth=1), dict(spp=2, exact=True)):
        full = np.asarray(hitray.render(scene, camera, (40, 30), progress=False, **options))
        part = hitray.render(scene, camera, (40, 30), progress=False, window=(7, 4, 17, 11), **options)
        assert part.shape == (11, 17, 3)
        assert np.array_equal(np.asarray(part), full[4:15, 7:24]), options
    with pytest.raises(ValueError, match=r"window 3x1 at \(6, 0\) must be at least 1x1 and lie inside the 8x8"):
        hitray.render(scene, camera, (8, 8), progress=False, window=(6, 0, 3, 1))


def test_camera_moves_and_rays():
    cam = hitray.Camera((0, 0, 5), (0, 0, 0), (0, 1, 0), 90)
    origin, direction = cam.ray(320, 240)
    assert origin == (0, 0, 5) and direction == pytest.approx((0, 0, -1), abs=1e-15)
    # Hill's slide moves along n = eye - look: +1 moves away from the scene.
    cam.slide(0, 0, 1)
    assert cam.eye == pytest.approx((0, 0, 6)) and cam.look == pytest.approx((0, 0, 1))
    # A yaw of 90 degrees turns the view from -z to -x or +x.
    cam.yaw(90)
    _, d = cam.ray(320, 240)
    assert abs(d[0]) == pytest.approx(1.0, abs=1e-12)
    # 90 degrees vertical at 640x480: the top edge's centre is 45 degrees up.
    straight = hitray.Camera((0, 0, 5), (0, 0, 0), (0, 1, 0), 90)
    _, up = straight.ray(320, 0)
    assert up == pytest.approx((0, 2 ** -0.5, -(2 ** -0.5)), abs=1e-12)
    with pytest.raises(TypeError):
        hitray.Camera((0, 0), (0, 0, 0), (0, 1, 0), 45)

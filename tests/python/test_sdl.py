"""hitray.load_sdl and hitray.parse_sdl: scenes and cameras from Hill's SDL,
errors with their place, and SDL scenes changed from Python."""

import os

import numpy as np
import pytest

import hitray
from conftest import ROOT, TWO_SPHERES_SDL


def test_load_sdl_gives_the_scene_and_its_camera(tmp_path):
    path = tmp_path / "scene.sdl"
    path.write_text(TWO_SPHERES_SDL)
    scene, camera = hitray.load_sdl(path)
    assert camera == hitray.Camera((0, 2, 8), (0, 0.5, 0), (0, 1, 0), 40)
    assert [o.shape for o in scene.objects] == ["sphere", "sphere", "plane"]
    assert scene.background == (0.1, 0.2, 0.3)
    assert scene.lights == [hitray.Light((5.0, 8.0, 6.0), (1.0, 1.0, 1.0))]
    same, _ = hitray.parse_sdl(TWO_SPHERES_SDL)
    a = hitray.render(scene, camera, size=(16, 12), progress=False)
    b = hitray.render(same, camera, size=(16, 12), progress=False)
    assert np.array_equal(np.asarray(a), np.asarray(b))


def test_a_file_without_a_camera_gives_none():
    scene, camera = hitray.parse_sdl("sphere")
    assert camera is None
    assert len(scene.objects) == 1


def test_the_demo_scene_loads_and_renders():
    scene, camera = hitray.load_sdl(ROOT / "scenes" / "demo.sdl")
    image = hitray.render(scene, camera, size=(32, 24), progress=False)
    assert np.asarray(image).std() > 0.01


@pytest.mark.parametrize("text, line, column, words", [
    ("sphere\nscale 1 x 1\n", 2, 9, "number"),
    ("sphere\n  nosuchword\n", 2, 3, "nosuchword"),
    ("diamond\n", 1, 1, "diamond.3vn"),
    ("use undefined\n", 1, 5, "undefined"),
    ("scale 0 1 1 sphere\n", 1, 7, "scale"),  # the zero factor
])
def test_errors_in_the_text_name_file_line_and_column(tmp_path, text, line, column, words):
    path = tmp_path / "bad.sdl"
    path.write_text(text)
    with pytest.raises(hitray.SDLError) as err:
        hitray.load_sdl(path)
    e = err.value
    assert (e.filename, e.line, e.column) == (str(path), line, column)
    assert str(e).startswith(f"{path}:{line}:{column}:") and words in str(e)
    assert isinstance(e, hitray.Error)
    with pytest.raises(hitray.SDLError) as err2:
        hitray.parse_sdl(text, name="inline.sdl")
    assert (err2.value.filename, err2.value.line, err2.value.column) == ("inline.sdl", line, column)


def test_unsupported_shapes_are_sdl_errors_with_their_status():
    with pytest.raises(hitray.SDLError) as err:
        hitray.parse_sdl("diamond")
    assert err.value.status == 9  # HR_ERROR_UNSUPPORTED
    assert "never published" in str(err.value)


def test_the_teapot_and_the_buckyball_load():
    scene, _ = hitray.parse_sdl("teapot\npush translate 3 0 0 buckyball pop\n")
    assert [o.shape for o in scene.objects] == ["teapot", "buckyball"]


def test_a_missing_file_is_a_file_error(tmp_path):
    missing = tmp_path / "nope.sdl"
    with pytest.raises(hitray.FileError) as err:
        hitray.load_sdl(missing)
    assert isinstance(err.value, OSError) and str(missing) in str(err.value)
    assert err.value.filename == str(missing)


def test_nul_bytes_are_refused_with_their_place(tmp_path):
    path = tmp_path / "binary.sdl"
    path.write_bytes(b"sphere\ncu\0be\n")
    with pytest.raises(hitray.SDLError) as err:
        hitray.load_sdl(path)
    assert (err.value.line, err.value.column) == (2, 3)
    with pytest.raises(hitray.SDLError) as err:
        hitray.parse_sdl("sphere\ncu\0be\n", name="s")
    assert (err.value.filename, err.value.line, err.value.column) == ("s", 2, 3)


def test_an_sdl_scene_changed_from_python_keeps_its_objects(tmp_path):
    path = tmp_path / "scene.sdl"
    path.write_text(TWO_SPHERES_SDL)
    scene, camera = hitray.load_sdl(path)
    hitray.render(scene, camera, size=(8, 8), progress=False)  # commits
    path.write_text("cube")  # later changes to the file do not reach the scene
    cube = scene.add(hitray.Cube().translate(0, 4, 0))
    scene.max_recursion_depth = 1
    assert cube.index == 3
    assert [o.shape for o in scene.objects] == ["sphere", "sphere", "plane", "cube"]
    assert scene.background == (0.1, 0.2, 0.3) and scene.max_recursion_depth == 1
    assert scene.first_hit((0, 4, 10), (0, 0, -1)).object == 3


def test_a_scene_loaded_by_a_relative_path_rebuilds_after_chdir(tmp_path, monkeypatch):
    # The rebuild reads the text kept at load time, with the file's directory
    # made absolute then: load, chdir away, change it (a rebuild), query.
    path = tmp_path / "scene.sdl"
    path.write_text(TWO_SPHERES_SDL)
    monkeypatch.chdir(tmp_path)
    scene, camera = hitray.load_sdl("scene.sdl")
    hitray.render(scene, camera, size=(4, 4), progress=False)
    monkeypatch.chdir(os.path.dirname(tmp_path))
    scene.add(hitray.Sphere().translate(0, 0, 20))
    assert len(scene.objects) == 4
    assert scene.first_hit((0, 0, 30), (0, 0, -1)).object == 3


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_a_device_is_refused_not_read_forever(device):
    """Issue 16, defect 2: /dev/zero was read until the OOM killer came."""
    if not os.access(device, os.R_OK):
        pytest.skip(f"{device} is not readable here")
    with pytest.raises(hitray.FileError, match="not a regular file"):
        hitray.load_sdl(device)


def test_a_fifo_is_refused_at_once(tmp_path):
    fifo = tmp_path / "scene.sdl"
    os.mkfifo(fifo)
    with pytest.raises(hitray.FileError, match="a FIFO"):
        hitray.load_sdl(fifo)

"""hitray.load_nff and hitray.parse_nff: scenes and cameras from NFF (plain
and gzip), errors as NFFError (an SDLError) with their place."""

import gzip

import numpy as np
import pytest

import hitray
from conftest import ROOT, require_classes

SPD = ROOT.parent / "shared" / "scenes" / "spd"

SCENE = """\
# a sphere on a square floor, two lights without a colour
v
from 0 -6 2
at 0 0 0.5
up 0 0 1
angle 40
hither 1
resolution 32 24
b 0.1 0.2 0.3
l 4 -4 6
l -4 -4 6
f 1 0.5 0.25 0.8 0.3 20 0 1
s 0 0 1 1
f 0.9 0.9 0.9 1 0 1 0 0
p 4
-3 -3 0
3 -3 0
3 3 0
-3 3 0
"""


@pytest.fixture(autouse=True)
def _modules():
    require_classes("sphere", "triangleMesh", "openTaperedCylinder")


def test_parse_nff_gives_the_scene_and_its_camera():
    scene, camera = hitray.parse_nff(SCENE)
    assert camera == hitray.Camera((0, -6, 2), (0, 0, 0.5), (0, 0, 1), 40)
    assert [o.shape for o in scene.objects] == ["sphere", "triangleMesh"]
    assert scene.background == (0.1, 0.2, 0.3)
    share = 1 / np.sqrt(2)
    assert [light.color for light in scene.lights] == [(share, share, share)] * 2
    image = hitray.render(scene, camera, size=(32, 24), progress=False)
    assert np.isfinite(np.asarray(image)).all() and np.asarray(image).std() > 0.01


def test_load_nff_reads_plain_and_gzip_files_alike(tmp_path):
    plain = tmp_path / "scene.nff"
    plain.write_text(SCENE)
    packed = tmp_path / "scene.nff.gz"
    packed.write_bytes(gzip.compress(SCENE.encode()))
    a_scene, a_camera = hitray.load_nff(plain)
    b_scene, b_camera = hitray.load_nff(packed)
    assert a_camera == b_camera
    a = hitray.render(a_scene, a_camera, size=(16, 12), progress=False)
    b = hitray.render(b_scene, b_camera, size=(16, 12), progress=False)
    assert np.array_equal(np.asarray(a), np.asarray(b))


def test_an_nff_scene_can_be_changed_and_rendered_again():
    scene, camera = hitray.parse_nff(SCENE)
    before = np.asarray(hitray.render(scene, camera, size=(16, 12), progress=False)).copy()
    scene.add(hitray.Sphere().translate(1.5, 0, 0.5), diffuse=(0, 0, 1))
    after = np.asarray(hitray.render(scene, camera, size=(16, 12), progress=False))
    assert len(scene.objects) == 3
    assert not np.array_equal(before, after)


@pytest.mark.parametrize("text, line, column, words", [
    ("s 0 0 x 1\n", 1, 7, "expected 4 numbers after 's' (x y z radius), found 'x'"),
    ("sphere 0 0 0 1\n", 1, 1, "expected an NFF entity"),
    ("f 1 1 1 1 0 1 0 0\np 2000000000\n", 2, 1, "vertices need at least"),
    ("f 1 1 1 1 0 1 0 0\nc 0 0 0 0 0 0 1 0\n", 2, 1, "radii of 'c' are both 0"),
])
def test_errors_name_the_place(text, line, column, words):
    with pytest.raises(hitray.NFFError) as info:
        hitray.parse_nff(text, name="bad.nff")
    e = info.value
    assert isinstance(e, hitray.SDLError)
    assert (e.filename, e.line, e.column) == ("bad.nff", line, column)
    assert str(e).startswith(f"bad.nff:{line}:{column}: ") and words in str(e)


def test_a_nul_byte_is_refused_with_its_place(tmp_path):
    with pytest.raises(hitray.NFFError) as info:
        hitray.parse_nff("s 0 0 0 1\n\0", name="bin.nff")
    assert (info.value.line, info.value.column) == (2, 1)
    path = tmp_path / "bin.nff"
    path.write_bytes(b"s 0 0 0 1\n\0")
    with pytest.raises(hitray.NFFError) as info:
        hitray.load_nff(path)
    assert info.value.line == 2 and "NUL" in str(info.value)


def test_a_missing_file_is_a_file_error(tmp_path):
    with pytest.raises(hitray.FileError):
        hitray.load_nff(tmp_path / "missing.nff")


@pytest.mark.skipif(not (SPD / "tetra.nff.gz").exists(),
                    reason="the SPD scenes (shared/scenes/spd beside the repository) are absent")
def test_an_spd_scene_loads_and_renders():
    scene, camera = hitray.load_nff(SPD / "tetra.nff.gz")
    image = hitray.render(scene, camera, size=(24, 24), progress=False)
    assert np.asarray(image).std() > 0.01

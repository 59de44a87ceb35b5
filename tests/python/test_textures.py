"""Textures from Python: solid textures through texture= and parameters=,
pixmaps from a file or an Image (Scene.pixmap), the `texture` effect, and
the errors (a class without (u, v), a pixmap not made, a bad parameter)."""

import numpy as np
import pytest

import hitray

FLAT = dict(ambient=(1, 1, 1), diffuse=(0, 0, 0))


def flat_scene():
    scene = hitray.Scene()
    scene.background = (0, 0, 0)
    scene.global_ambient = (1, 1, 1)
    return scene


def down(scene, x, y):
    return scene.shade((x, y, 10), (0, 0, -1))


def test_checkerboard_floor_known_points():
    scene = flat_scene()
    scene.add(hitray.Plane(), texture=-1, parameters=(0.5, 1, 0, 0, 0, 0, 1), **FLAT)
    # Looked up just inside the floor (z < 0): [0, 0.5)^2 is colour B.
    assert down(scene, 0.25, 0.25) == (0, 0, 1)
    assert down(scene, 0.75, 0.25) == (1, 0, 0)
    assert down(scene, 1.25, 0.25) == (0, 0, 1)
    assert "texture" in scene.effects


def test_untextured_scene_has_no_texture_effect():
    scene = flat_scene()
    scene.add(hitray.Sphere(), **FLAT)
    assert "texture" not in scene.effects


def texels():
    a = np.zeros((2, 2, 3), np.float32)
    a[0, 0] = (1, 0, 0)
    a[0, 1] = (0, 1, 0)
    a[1, 0] = (0, 0, 1)
    a[1, 1] = (1, 1, 1)
    return a


@pytest.mark.parametrize("source", ["image", "file"])
def test_pixmap_on_a_square(tmp_path, source):
    image = hitray.Image(texels())
    if source == "file":
        path = tmp_path / "t.png"
        image.save(path, bits=16, linear=True)
        image = path
    scene = flat_scene()
    scene.pixmap(1, image)
    # nearest; the square's (u, v) are x and y taken to [0, 1].
    scene.add(hitray.Square(), texture=1, parameters=(0, 1, 0, 1, 1), **FLAT)
    assert down(scene, -0.5, 0.5) == (1, 0, 0)  # top left texel
    assert down(scene, 0.5, 0.5) == (0, 1, 0)
    assert down(scene, -0.5, -0.5) == (0, 0, 1)
    assert down(scene, 0.5, -0.5) == (1, 1, 1)


def test_image_read_round_trip(tmp_path):
    path = tmp_path / "t.png"
    hitray.Image(texels()).save(path, bits=16, linear=True)
    back = np.asarray(hitray.Image.read(path))
    assert back.shape == (2, 2, 3) and np.array_equal(back, texels())


def test_errors(tmp_path):
    scene = flat_scene()
    with pytest.raises(hitray.ParameterError, match="needs pixmap 2"):
        scene.add(hitray.Sphere(), texture=2)
    with pytest.raises(hitray.ParameterError, match=r"parameter 1 \(size\) is 0 and must be positive"):
        scene.add(hitray.Sphere(), texture=-1, parameters=(0,))
    scene.pixmap(1, hitray.Image(texels()))
    with pytest.raises(hitray.ArgumentError, match="pixmap 1 is made already"):
        scene.pixmap(1, hitray.Image(texels()))
    with pytest.raises(hitray.ParameterError, match=r"'tetrahedron'.*gives no \(u, v\)"):
        scene.add(hitray.Tetrahedron(), texture=1)
    with pytest.raises(hitray.FileError, match="cannot open image"):
        scene.pixmap(3, tmp_path / "missing.png")
    with pytest.raises(hitray.ArgumentError, match="specularFraction 2 must be within"):
        scene.add(hitray.Sphere(), specularFraction=2)

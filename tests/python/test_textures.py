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


def horizon_floor(textured=True):
    """A checkerboard floor (the plane z = 0) seen toward its horizon, and
    the camera that looks across it."""
    scene = flat_scene()
    extra = dict(texture=-1, parameters=(0.25, 1, 1, 1, 0, 0, 0)) if textured else {}
    scene.add(hitray.Plane(), **FLAT, **extra)
    return scene, hitray.Camera((0, -6, 1), (0, 0, 0.2), (0, 0, 1), 40)


def test_texture_filter_footprint_and_none():
    """texture_filter="footprint" (the default) averages the squares over
    each pixel's footprint: toward the horizon, where many squares fall in
    a pixel, the pixels come near the mean grey instead of black or white
    at random; "none" point-samples them (Hill's), as --texture-filter none
    does. A scene without textures is the same either way."""
    scene, camera = horizon_floor()
    filtered = np.asarray(hitray.render(scene, camera, size=(64, 48), progress=False))
    default = np.asarray(hitray.render(scene, camera, size=(64, 48), progress=False, texture_filter="footprint"))
    point = np.asarray(hitray.render(scene, camera, size=(64, 48), progress=False, texture_filter="none"))
    assert np.array_equal(filtered, default)
    assert not np.array_equal(filtered, point)
    # The rows just under the horizon (a pixel there spans many squares).
    far = slice(20, 23)
    assert np.all(np.abs(filtered[far, :, 0] - 0.5) < 0.2)
    assert np.mean(np.abs(point[far, :, 0] - 0.5)) > 0.4
    plain, camera = horizon_floor(textured=False)
    a = np.asarray(hitray.render(plain, camera, size=(32, 24), progress=False))
    b = np.asarray(hitray.render(plain, camera, size=(32, 24), progress=False, texture_filter="none"))
    assert np.array_equal(a, b)
    with pytest.raises(ValueError, match="'footprint' or 'none'"):
        hitray.render(scene, camera, size=(8, 6), progress=False, texture_filter="mip")

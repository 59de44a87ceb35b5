"""hitray.distributed.ScenePack without a cluster: a scene pickled with the
files it names and rebuilt elsewhere gives the same image bit for bit, after
the original files are gone; what is carried and what is not; the limit on
what a scene may carry."""

import os
import pickle
import shutil

import numpy as np
import pytest

import hitray

from conftest import ROOT, TWO_SPHERES_SDL, require_classes

pytest.importorskip("distributed", reason="dask[distributed] is not installed")
hd = pytest.importorskip("hitray.distributed")
from hitray.distributed import _pack  # noqa: E402

MESHES = ROOT / "tests" / "data" / "meshes"


def rebuilt(pack):
    """The pack as a worker gets it: pickled, then loaded (a fresh object)."""
    return pickle.loads(pickle.dumps(pack))


def pixels(scene, camera, size=(32, 24)):
    return np.asarray(hitray.render(scene, camera, size, spp=2, progress=False))


def test_pack_sdl_mesh_files_travel_and_the_originals_may_go(tmp_path):
    """A mesh named relative to the scene (climbing out of its directory)
    and one named by an absolute path: both carried; once the originals are
    deleted, the rebuilt scene renders the same bits."""
    require_classes("mesh")
    (tmp_path / "scenes").mkdir()
    (tmp_path / "meshes").mkdir()
    shutil.copy(MESHES / "cube.3vn", tmp_path / "meshes" / "cube.3vn")
    shutil.copy(MESHES / "tetra_hill.3vn", tmp_path / "tetra.3vn")
    (tmp_path / "scenes" / "m.sdl").write_text(
        "camera 3 2.5 4 0 0 0 0 1 0 45\nlight 4 6 5 1 1 1\n"
        "! a comment naming ../meshes/cube.3vn is not a word\n"
        "push rotate 30 0 1 0 mesh ../meshes/cube.3vn pop\n"
        f"push translate 0 -1.5 0 diffuse 0.2 0.6 0.9 mesh {tmp_path}/tetra.3vn!glued comment\npop\n"
        "push translate 1 1 0 scale .3 .3 .3 sphere pop\n")
    scene, camera = hitray.load_sdl(tmp_path / "scenes" / "m.sdl")
    pack = hd.ScenePack(scene)
    assert pack.files == sorted([str(tmp_path / "meshes" / "cube.3vn"), str(tmp_path / "tetra.3vn")])
    assert pack.shipped_bytes == (tmp_path / "meshes" / "cube.3vn").stat().st_size + \
        (tmp_path / "tetra.3vn").stat().st_size
    here = pixels(scene, camera)
    shutil.rmtree(tmp_path / "meshes")
    os.remove(tmp_path / "tetra.3vn")
    assert np.array_equal(pixels(rebuilt(pack).scene(), camera), here)


def test_pack_python_scene_with_a_mesh_and_booleans(tmp_path, monkeypatch):
    """A scene built in Python: shapes with their exact transforms, booleans,
    a mesh named relative to the directory current when it was added, globals
    and lights."""
    require_classes("mesh", "difference")
    shutil.copy(MESHES / "cube.obj", tmp_path / "cube.obj")
    monkeypatch.chdir(tmp_path)
    scene = hitray.Scene()
    scene.add(hitray.Mesh("cube.obj").rotate(33, 1, 2, 3).scale(0.8, 1.1, 0.9), diffuse=(0.9, 0.4, 0.1))
    scene.add((hitray.Sphere() - hitray.Sphere().translate(0.5, 0.3, 0.6).scale(0.7, 0.7, 0.7))
              .translate(1.8, 0, 0), diffuse=(0.2, 0.7, 0.3), reflectivity=0.5)
    scene.light((4, 6, 5), (1, 1, 0.9))
    scene.background = (0.1, 0.2, 0.3)
    camera = hitray.Camera((0, 1, 6), (0.8, 0, 0), (0, 1, 0), 45)
    pack = hd.ScenePack(scene)
    assert pack.files == [str(tmp_path / "cube.obj")]
    here = pixels(scene, camera)
    os.remove(tmp_path / "cube.obj")
    again = rebuilt(pack).scene()
    assert again.background == (0.1, 0.2, 0.3)
    assert np.array_equal(pixels(again, camera), here)
    assert [o.matrix.tolist() for o in again.objects] == [o.matrix.tolist() for o in scene.objects]


def test_pack_carries_only_regular_files(tmp_path):
    """Words naming a directory, a missing file or nothing are not carried;
    a scene naming no file carries none; the same scene packs to the same
    key, a changed one to another."""
    (tmp_path / "sphere").mkdir()  # a directory named like a keyword
    scene, _ = hitray.parse_sdl(TWO_SPHERES_SDL + "! missing.3vn\n", base_dir=tmp_path)
    pack = hd.ScenePack(scene)
    assert pack.files == [] and pack.shipped_bytes == 0
    assert hd.ScenePack(scene).key == pack.key
    scene.background = (1, 0, 0)
    assert hd.ScenePack(scene).key != pack.key


def test_pack_ships_only_the_files_the_scene_read(tmp_path):
    """A readable file that the scene's text names in a comment and inside
    a macro never used (relatively and absolutely, as a mesh and as a
    pixmap) is not read, so not shipped: not one byte of it is in the
    pickled pack. The files the scene did read (a pixmap and a mesh, each
    used twice) are shipped, exactly those, and Scene.files lists them with
    the scene file first."""
    require_classes("mesh")
    secret = tmp_path / "id_ed25519"
    secret.write_bytes(b"-----BEGIN OPENSSH PRIVATE KEY----- not for workers\n")
    shutil.copy(MESHES / "cube.obj", tmp_path / "cube.obj")
    hitray.Image(np.full((4, 4, 3), 0.5, dtype=np.float32)).save(tmp_path / "t.png")
    path = tmp_path / "s.sdl"
    path.write_text(
        f"! a comment naming id_ed25519 and {secret}\n"
        f"def unused {{ mesh id_ed25519 makePixmap 7 {secret} mesh {secret} }}\n"
        "makePixmap 1 t.png\nmakePixmap 2 t.png\n"
        "camera 3 2.5 4 0 0 0 0 1 0 45\nlight 4 6 5 1 1 1\n"
        "mesh cube.obj\npush translate 2 0 0 mesh cube.obj texture 1 sphere pop\n")
    scene, camera = hitray.load_sdl(path)
    assert scene.files == [str(path), str(tmp_path / "t.png"), str(tmp_path / "cube.obj")]
    pack = hd.ScenePack(scene)
    assert pack.files == sorted([str(tmp_path / "t.png"), str(tmp_path / "cube.obj")])
    assert pack.shipped_bytes == (tmp_path / "t.png").stat().st_size + (tmp_path / "cube.obj").stat().st_size
    assert b"OPENSSH" not in pickle.dumps(pack)
    here = pixels(scene, camera)
    for name in ("t.png", "cube.obj"):
        os.remove(tmp_path / name)
    assert np.array_equal(pixels(rebuilt(pack).scene(), camera), here)


def test_pack_sdl_string_and_python_mesh(tmp_path, monkeypatch):
    """SDL text given as a string, plus a mesh added in Python: the mesh's
    file is read and shipped; a file the text names in a comment and in a
    macro never used is not."""
    require_classes("mesh")
    shutil.copy(MESHES / "cube.obj", tmp_path / "cube.obj")
    (tmp_path / "secret").write_bytes(b"top secret")
    monkeypatch.chdir(tmp_path)
    scene, _ = hitray.parse_sdl(TWO_SPHERES_SDL + "! secret\ndef unused { mesh secret }\n", base_dir=tmp_path)
    scene.add(hitray.Mesh("cube.obj"))
    assert scene.files == [str(tmp_path / "cube.obj")]
    pack = hd.ScenePack(scene)
    assert pack.files == [str(tmp_path / "cube.obj")]
    assert b"top secret" not in pickle.dumps(pack)


def test_pack_refuses_more_than_the_limit(tmp_path, monkeypatch):
    require_classes("mesh")
    shutil.copy(MESHES / "cube.3vn", tmp_path / "cube.3vn")
    scene, _ = hitray.parse_sdl("mesh cube.3vn\n", base_dir=tmp_path)
    monkeypatch.setattr(_pack, "MAX_SHIPPED_BYTES", (tmp_path / "cube.3vn").stat().st_size - 1)
    with pytest.raises(hd.ShippingError, match=r"cube\.3vn: the scene's files would exceed \d+ bytes"):
        hd.ScenePack(scene)


def test_pack_sdl_words_are_the_lexers():
    text = b"mesh a.3vn{b}c!comment d\n\te\r\nf"
    assert [text[s:e] for s, e in _pack._sdl_words(text)] == [b"mesh", b"a.3vn", b"b", b"c", b"e", b"f"]


def tampered(pack, **changes):
    """The pack as an attacker could pickle it: its state with fields
    replaced (files: the path -> bytes map; sdl_base: the scene's folder)."""
    key, sdl, spans, ops, globals_, files = pack.__getstate__()
    if "files" in changes:
        files = changes["files"]
    if "sdl_base" in changes:
        sdl = (sdl[0], sdl[1], changes["sdl_base"], sdl[3])
    out = hd.ScenePack.__new__(hd.ScenePack)
    out.__setstate__((key, sdl, spans, ops, globals_, files))
    return pickle.loads(pickle.dumps(out))


def test_pack_refuses_paths_that_leave_its_folder(tmp_path):
    """An unpickled pack whose paths climb out of its private folder ('..'
    past the root) writes nothing there and raises; its scene folder may not
    leave either. A path that climbs and comes back inside is fine."""
    scene, camera = hitray.parse_sdl(TWO_SPHERES_SDL, base_dir=tmp_path)
    pack = hd.ScenePack(scene)
    outside = tmp_path / "planted"
    climb = b"/" + b"../" * 40 + os.fsencode(outside)
    with pytest.raises(hd.ShippingError, match=r"leaves its folder: refused"):
        tampered(pack, files={climb: b"owned"}).scene()
    assert not outside.exists()
    with pytest.raises(hd.ShippingError, match=r"leaves its folder: refused"):
        tampered(pack, sdl_base=b"/" + b"../" * 40 + os.fsencode(tmp_path)).scene()
    inside = tampered(pack, files={b"/a/../b/c.txt": b"fine"}).scene()
    assert np.array_equal(pixels(inside, camera), pixels(scene, camera))

"""Python parity with `hitray render` and the newcomer's conveniences:
render's adaptive, min_weight, exact, effects and block (the command's
names and the same numbers), hitray.abi imported lazily, dir(hitray),
HitInfo.spawn_origin (hr_hit_spawn_origin), meshes from numpy arrays (a
million triangles with no Python object per triangle), the library's
warnings as Python warnings, "did you mean" for shape classes, SDL's torus
tube, and tqdm's plain bar in a notebook without ipywidgets."""

import json
import math
import subprocess
import sys
import tracemalloc
import types
import warnings

import numpy as np
import pytest

import hitray
from conftest import BUILD, TWO_SPHERES_SDL, require_classes

HITRAY_CLI = BUILD / "bin" / "hitray"

# A mirror and a glass ball: bounces for the cut-off to cut, edges for
# adaptive supersampling to refine.
BOUNCES_SDL = TWO_SPHERES_SDL + """\
push translate 0 0.6 1.5 scale 0.6 0.6 0.6 reflectivity 0.6 transparency 0.7 speedOfLight 0.7
minReflectivity 0.1 minTransparency 0.1 sphere pop
"""


@pytest.fixture(scope="module")
def bounces():
    return hitray.parse_sdl(BOUNCES_SDL)


# --- render: the command's options ---------------------------------------

@pytest.mark.parametrize("flags, kwargs", [
    (["--adaptive", "0.05", "--spp", "4"], dict(adaptive=0.05, spp=4)),
    (["--min-weight", "0.05"], dict(min_weight=0.05)),
    (["--exact"], dict(exact=True)),
    (["--effects", "all"], dict(effects="all")),
    (["--block", "3"], dict(block=3)),
    (["--texture-filter", "none"], dict(texture_filter="none")),
])
def test_render_options_match_the_command_s(bounces, tmp_path, flags, kwargs):
    """The same option through Python and through `hitray render` casts the
    same rays and saves the same samples (both are hr_render's numbers)."""
    if not HITRAY_CLI.is_file():
        pytest.fail(f"{HITRAY_CLI} is missing: build first (make build)")
    scene_file = tmp_path / "bounces.sdl"
    scene_file.write_text(BOUNCES_SDL)
    stats_file = tmp_path / "stats.json"
    subprocess.run([str(HITRAY_CLI), "render", str(scene_file), "-o", str(tmp_path / "c.pfm"),
                    "--size", "48x36", "--stats-json", str(stats_file), *flags],
                   check=True, capture_output=True, timeout=120)
    cli = json.loads(stats_file.read_text())
    scene, camera = bounces
    image = hitray.render(scene, camera, size=(48, 36), progress=False, **kwargs)
    s = image.stats
    for key in ("primary", "shadow", "reflected", "refracted", "pixels_refined", "samples_saved",
                "rays_cut"):
        assert getattr(s, key) == cli[key], key
    assert s.effects == frozenset(cli["effects"])


def test_adaptive_and_cut_off_save_what_they_say(bounces):
    scene, camera = bounces
    full = hitray.render(scene, camera, size=(48, 36), spp=4, progress=False, exact=True)
    adaptive = hitray.render(scene, camera, size=(48, 36), spp=4, adaptive=0.05, progress=False,
                             exact=True)
    assert 0 < adaptive.stats.pixels_refined < 48 * 36
    assert adaptive.stats.samples_saved == full.stats.primary - adaptive.stats.primary > 0
    cut = hitray.render(scene, camera, size=(48, 36), min_weight=0.5, progress=False)
    assert cut.stats.rays_cut > 0 and full.stats.rays_cut == 0
    assert cut.stats.reflected + cut.stats.refracted < full.stats.reflected + full.stats.refracted


def test_effects_and_block_have_their_earlier_names_too(bounces):
    scene, camera = bounces
    a = hitray.render(scene, camera, size=(16, 12), effects="all", block=2, progress=False)
    b = hitray.render(scene, camera, size=(16, 12), all_effects=True, block_size=2, progress=False)
    assert np.array_equal(np.asarray(a), np.asarray(b)) and a.stats.rays == b.stats.rays


@pytest.mark.parametrize("kwargs, error, words", [
    (dict(effects="some"), ValueError, "'auto' or 'all'"),
    (dict(block=2, block_size=2), TypeError, "not both"),
    (dict(block=0), ValueError, "at least 1"),
    (dict(adaptive=0.1), hitray.ArgumentError, "samples per pixel"),  # spp 1
    (dict(adaptive=0.1, spp=4, block=2), hitray.ArgumentError, "block size"),
    (dict(adaptive=1.5, spp=4), hitray.ArgumentError, "0..1"),
    (dict(min_weight=-0.1), hitray.ArgumentError, "0..1"),
    (dict(min_weight=0.1, exact=True), hitray.ArgumentError, "exclude each other"),
    (dict(adaptive="x"), TypeError, "adaptive"),
])
def test_bad_render_options_say_which(bounces, kwargs, error, words):
    scene, camera = bounces
    with pytest.raises(error, match=words):
        hitray.render(scene, camera, size=(8, 8), progress=False, **kwargs)


# --- the package's namespace ----------------------------------------------

def test_abi_is_a_lazy_attribute_and_dir_shows_no_annotations():
    code = ("import sys, hitray\n"
            "assert 'hitray.abi' not in sys.modules, 'imported eagerly'\n"
            "names = dir(hitray)\n"
            "assert 'abi' in names and 'annotations' not in names, names\n"
            "assert hitray.abi.lib.HR_OK == 0 and 'hitray.abi' in sys.modules\n"
            "import hitray.abi\n"
            "assert hitray.abi is sys.modules['hitray.abi']\n"
            "try:\n"
            "    hitray.no_such_name\n"
            "except AttributeError as e:\n"
            "    assert 'no_such_name' in str(e)\n"
            "else:\n"
            "    raise AssertionError('no AttributeError')\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr


def test_a_rendered_image_always_has_stats():
    scene = hitray.Scene()
    scene.add(hitray.Sphere())
    image = hitray.render(scene, size=(4, 4), progress=False)
    assert isinstance(image, hitray.RenderedImage) and isinstance(image, hitray.Image)
    assert isinstance(image.stats, hitray.RenderStats) and image.stats.primary == 16
    assert hitray.Image(np.zeros((2, 2, 3))).stats is None


# --- HitInfo.spawn_origin -------------------------------------------------

def test_spawn_origin_is_the_library_s_and_leaves_the_surface():
    scene = hitray.Scene()
    scene.add(hitray.Sphere().translate(1e4, 0, 0).scale(3))  # far: a large error bound
    hit = scene.first_hit((1e4, 0, 20), (0, 0, -1))
    assert hit is not None and hit.error > 0
    out = hit.spawn_origin(hit.normal)
    inward = hit.spawn_origin(tuple(-c for c in hit.normal))
    # On either side of the surface, by at least the error bound.
    assert out[2] - hit.point[2] >= hit.error and hit.point[2] - inward[2] >= hit.error
    # The C function itself, through cffi, gives the same bits.
    abi = hitray.abi
    h = abi.ffi.new("hr_hit *")
    h.point = {"x": hit.point[0], "y": hit.point[1], "z": hit.point[2]}
    h.error = hit.error
    o = abi.lib.hr_hit_spawn_origin(h, {"x": hit.normal[0], "y": hit.normal[1], "z": hit.normal[2]})
    assert out == (o.x, o.y, o.z)
    # Leaving outward meets nothing; inward meets the far side, not this one.
    assert scene.first_hit(out, hit.normal) is None
    far = scene.first_hit(inward, (0, 0, -1))
    assert far is not None and math.isclose(far.point[2], -3.0, abs_tol=1e-9)


# --- meshes from arrays ---------------------------------------------------

TETRA_VERTICES = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
TETRA_FACES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)


def test_a_mesh_from_arrays_is_hit_where_its_triangles_are():
    require_classes("triangleMesh")
    scene = hitray.Scene()
    scene.add(hitray.Mesh(vertices=TETRA_VERTICES, faces=TETRA_FACES))
    hits = scene.hits((0.2, 0.2, 5), (0, 0, -1))
    assert [round(h.point[2], 12) for h in hits] == [0.6, 0.0]
    assert [h.entering for h in hits] == [True, False]
    # Any array-like of the right shape, int64 faces, float32 points.
    again = hitray.Mesh(vertices=TETRA_VERTICES.astype(np.float32).tolist(),
                        faces=TETRA_FACES.astype(np.int64))
    scene2 = hitray.Scene()
    scene2.add(again)
    assert [h.t for h in scene2.hits((0.2, 0.2, 5), (0, 0, -1))] == [h.t for h in hits]
    assert "Mesh(vertices=<4 points>, faces=<4 triangles>)" in repr(again)


def test_a_mesh_from_arrays_is_a_value():
    require_classes("triangleMesh")
    vertices = TETRA_VERTICES.copy()
    mesh = hitray.Mesh(vertices=vertices, faces=TETRA_FACES)
    vertices *= 100  # the caller's array changes; the shape does not
    scene = hitray.Scene()
    scene.add(mesh)
    assert scene.first_hit((0.2, 0.2, 5), (0, 0, -1)).point[2] == pytest.approx(0.6)


def test_mesh_normals_shade_smoothly():
    require_classes("triangleMesh")
    normals = TETRA_VERTICES - 0.25
    scene = hitray.Scene()
    scene.add(hitray.Mesh(vertices=TETRA_VERTICES, faces=TETRA_FACES, normals=normals))
    hit = scene.first_hit((0.2, 0.2, 5), (0, 0, -1))
    assert hit is not None and hit.normal != pytest.approx((1 / math.sqrt(3),) * 3)


@pytest.mark.parametrize("kwargs, error, words", [
    (dict(vertices=np.zeros((4, 2)), faces=TETRA_FACES), ValueError, r"vertices must be an \(n, 3\)"),
    (dict(vertices=TETRA_VERTICES, faces=TETRA_FACES.astype(float)), TypeError, "integer vertex"),
    (dict(vertices=TETRA_VERTICES), TypeError, "give a file"),
    (dict(file="a.obj", vertices=TETRA_VERTICES, faces=TETRA_FACES), TypeError, "not both"),
    (dict(vertices=np.array([["a", "b", "c"]]), faces=TETRA_FACES), TypeError, "numbers"),
])
def test_bad_mesh_arrays_are_refused_when_made(kwargs, error, words):
    with pytest.raises(error, match=words):
        hitray.Mesh(**kwargs)


def test_mesh_indices_past_the_vertices_are_refused_by_the_module():
    require_classes("triangleMesh")
    scene = hitray.Scene()
    with pytest.raises(hitray.ParameterError, match="triangles"):
        scene.add(hitray.Mesh(vertices=TETRA_VERTICES, faces=[[0, 1, 9]]))
    with pytest.raises(hitray.ParameterError):
        scene.add(hitray.Mesh(vertices=[[0, 0, 0], [1, 0, 0], [np.nan, 1, 0]], faces=[[0, 1, 2]]))


def grid_mesh(n):
    """An n x n grid of unit squares in z = 0, two triangles each, built
    with numpy alone."""
    xs, ys = np.meshgrid(np.arange(n + 1, dtype=np.float64), np.arange(n + 1, dtype=np.float64))
    vertices = np.stack([xs.ravel(), ys.ravel(), np.zeros(xs.size)], axis=1)
    corner = (np.arange(n)[None, :] + (n + 1) * np.arange(n)[:, None]).ravel()
    a, b, c, d = corner, corner + 1, corner + n + 1, corner + n + 2
    faces = np.concatenate([np.stack([a, b, d], axis=1), np.stack([a, d, c], axis=1)])
    return vertices, faces.astype(np.int32)


def test_a_million_triangle_mesh_from_arrays_has_no_python_object_per_triangle():
    """1,000,000 triangles (a 708 x 708 grid less a few) reach the module as
    arrays: what Python allocates while the shape is made and added stays
    within a small multiple of the arrays' own bytes (one float64 copy each);
    a Python tuple per triangle would be over 100 MB more."""
    require_classes("triangleMesh")
    vertices, faces = grid_mesh(707)
    faces = faces[:1_000_000] if len(faces) >= 1_000_000 else faces
    assert len(faces) == 999_698 or len(faces) == 1_000_000
    array_bytes = vertices.size * 8 + faces.size * 8
    scene = hitray.Scene()
    tracemalloc.start()
    try:
        mesh = hitray.Mesh(vertices=vertices, faces=faces)
        scene.add(mesh)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 1.25 * array_bytes + (1 << 20), (peak, array_bytes)
    hit = scene.first_hit((300.25, 200.75, 5), (0, 0, -1))
    assert hit is not None and hit.point == pytest.approx((300.25, 200.75, 0.0))


# --- warnings ---------------------------------------------------------------

def test_a_coefficient_below_its_threshold_warns_naming_the_line():
    text = "light 1 5 5 1 1 1\ntransparency 0.9 speedOfLight 0.7\nreflectivity 0.08\nsphere\n"
    with pytest.warns(hitray.SceneWarning, match="reflectivity 0.08 is below minReflectivity 0.5") as seen:
        scene, _ = hitray.parse_sdl(text, name="glass.sdl")
    assert len(seen) == 1
    w = seen[0].message
    assert (w.filename, w.line, w.column, w.code) == ("glass.sdl", 3, 1, 2)
    assert seen[0].filename == __file__  # attributed to the caller's line
    # A rebuild (the scene changed) reads the text again without repeating it.
    scene.add(hitray.Cube().translate(3, 0, 0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        hitray.render(scene, size=(4, 4), progress=False)


def test_an_empty_scene_warns_when_rendered():
    scene = hitray.Scene()
    camera = hitray.Camera((0, 0, 5), (0, 0, 0), (0, 1, 0), 45)
    with pytest.warns(hitray.SceneWarning, match="no objects") as seen:
        hitray.render(scene, camera, size=(4, 4), progress=False)
    assert seen[0].message.code == 1 and seen[0].filename == __file__
    # Warnings as errors: the filter's exception comes out of the call.
    scene2 = hitray.Scene()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(hitray.SceneWarning):
            scene2.first_hit((0, 0, 5), (0, 0, -1))


# --- errors that suggest the fix -------------------------------------------

def test_a_misspelt_shape_class_gets_a_suggestion():
    scene = hitray.Scene()
    with pytest.raises(hitray.ModuleError, match=r"'sphre' \(did you mean 'sphere'\?\)"):
        scene.add(hitray.Shape("sphre"))
    with pytest.raises(hitray.SDLError, match=r"did you mean 'specularExponent'"):
        hitray.parse_sdl("exponent 20 sphere")


def test_misspelt_material_keywords_and_shape_parameters_get_suggestions():
    scene = hitray.Scene()
    with pytest.raises(TypeError, match=r"'specularExponet' \(did you mean 'specularExponent'\?\)"):
        scene.add(hitray.Sphere(), specularExponet=30)
    require_classes("torus")
    with pytest.raises(hitray.ParameterError, match=r"no parameter 'tub' \(did you mean 'tube'\?\)"):
        scene.add(hitray.Shape("torus", tub=0.3))


def test_sdl_torus_takes_an_optional_tube_radius():
    require_classes("torus")
    scene, _ = hitray.parse_sdl("torus 0.1")
    assert scene.first_hit((1, 0, 5), (0, 0, -1)).t == pytest.approx(4.9, abs=1e-12)


# --- tqdm in a notebook without ipywidgets ---------------------------------

def test_tqdm_in_a_notebook_without_ipywidgets_is_a_plain_bar(monkeypatch, capsys):
    pytest.importorskip("tqdm")
    shell = types.SimpleNamespace(config={"IPKernelApp": {}})
    monkeypatch.setitem(sys.modules, "IPython", types.SimpleNamespace(get_ipython=lambda: shell))
    monkeypatch.setitem(sys.modules, "ipywidgets", None)  # as if not installed
    from hitray import _progress
    from tqdm.std import tqdm as text_tqdm
    assert _progress.tqdm_class() is text_tqdm
    scene = hitray.Scene()
    scene.add(hitray.Sphere())
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a TqdmWarning would fail here
        hitray.render(scene, size=(16, 16), progress=True)
    err = capsys.readouterr().err
    assert "hitray:" in err and "left" in err

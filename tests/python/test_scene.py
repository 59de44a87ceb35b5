"""Building scenes in Python: shapes, transforms in Hill's order, materials
as SDL keywords, lights, globals, and a Scene changed after it rendered."""

import pathlib

import numpy as np
import pytest

import hitray
from conftest import TWO_SPHERES_SDL, require_classes


def two_spheres_in_python():
    scene = hitray.Scene()
    scene.background = (0.1, 0.2, 0.3)
    scene.light((5, 8, 6), (1, 1, 1))
    scene.add(hitray.Sphere().translate(-1, 1, 0), diffuse=(0.8, 0.2, 0.2))
    scene.add(hitray.Sphere().translate(1.2, 1, -0.5), diffuse=(0.2, 0.8, 0.2),
              specular=(0.5, 0.5, 0.5), specularExponent=20)
    # SDL's material is sticky: the floor has the second sphere's.
    scene.add(hitray.Plane().rotate(-90, 1, 0, 0), diffuse=(0.2, 0.8, 0.2),
              specular=(0.5, 0.5, 0.5), specularExponent=20)
    camera = hitray.Camera((0, 2, 8), (0, 0.5, 0), (0, 1, 0), 40)
    return scene, camera


def test_a_scene_built_in_python_renders_as_its_sdl_does_bit_for_bit():
    py_scene, py_camera = two_spheres_in_python()
    sdl_scene, sdl_camera = hitray.parse_sdl(TWO_SPHERES_SDL)
    assert py_camera == sdl_camera
    for a, b in zip(py_scene.objects, sdl_scene.objects):
        assert a.shape == b.shape
        assert a.material == b.material
        assert np.array_equal(a.matrix, b.matrix) and np.array_equal(a.inverse, b.inverse)
    py_image = hitray.render(py_scene, py_camera, size=(64, 48), progress=False)
    sdl_image = hitray.render(sdl_scene, sdl_camera, size=(64, 48), progress=False)
    assert np.array_equal(np.asarray(py_image), np.asarray(sdl_image))
    assert np.asarray(py_image).std() > 0.05  # not a blank frame


def test_transforms_chain_in_hills_order():
    # translate 2 4 9 scale 1 4 4: M = T.S, the scale acts on the object first.
    shape = hitray.Sphere().translate(2, 4, 9).scale(1, 4, 4)
    T = np.eye(4)
    T[:3, 3] = (2, 4, 9)
    S = np.diag([1.0, 4.0, 4.0, 1.0])
    # Exact: each entry is one product of small integers.
    assert np.array_equal(shape.matrix, T @ S)
    assert np.array_equal(shape.inverse, np.linalg.inv(S) @ np.linalg.inv(T))
    scene = hitray.Scene()
    obj = scene.add(shape)
    assert np.array_equal(obj.matrix, T @ S)
    # The ellipsoid centred at (2, 4, 9) with radii (1, 4, 4): from (2, 4, 20)
    # down -z the first hit is at z = 9 + 4, t = 7.
    hit = scene.first_hit((2, 4, 20), (0, 0, -1))
    assert hit.t == pytest.approx(7.0, rel=1e-15, abs=1e-13)
    # Same shape, same chain in SDL: the same matrices bit for bit.
    sdl_scene, _ = hitray.parse_sdl("translate 2 4 9 scale 1 4 4 sphere")
    assert np.array_equal(sdl_scene.objects[0].matrix, obj.matrix)
    assert np.array_equal(sdl_scene.objects[0].inverse, obj.inverse)


def test_rotate_and_uniform_scale_and_arbitrary_matrix():
    r = hitray.Cube().rotate(90, 0, 0, 1).matrix
    # A quarter turn about z takes x to y: cos 90 in double is 6.1e-17, so
    # compare with a tolerance a few ulps of 1 wide.
    assert np.allclose(r[:3, :3], [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-15)
    assert np.array_equal(hitray.Sphere().scale(2).matrix, np.diag([2.0, 2.0, 2.0, 1.0]))
    m = np.array([[1, 2, 0, 1], [0, 1, 0, 2], [0, 0, 3, 3], [0, 0, 0, 1]], dtype=float)
    s = hitray.Sphere().transform(m)
    assert np.array_equal(s.matrix, m)
    assert np.allclose(s.inverse @ m, np.eye(4), atol=1e-15)
    with pytest.raises(hitray.NumericError):
        hitray.Sphere().transform(np.diag([1.0, 0.0, 1.0, 1.0]))
    with pytest.raises(ValueError):
        hitray.Sphere().transform(np.eye(3))


def test_shapes_are_values_and_a_shape_added_twice_is_two_objects():
    base = hitray.Sphere()
    moved = base.translate(3, 0, 0)
    assert np.array_equal(base.matrix, np.eye(4))  # unchanged
    assert repr(moved) == "Sphere().translate(3, 0, 0)"
    scene = hitray.Scene()
    a = scene.add(moved, diffuse=(1, 0, 0))
    b = scene.add(moved, diffuse=(0, 0, 1))
    assert (a.index, b.index) == (0, 1)
    assert a.material["diffuse"] == (1.0, 0.0, 0.0) and b.material["diffuse"] == (0.0, 0.0, 1.0)
    # Both copies are traced: two hits entering at x = 2, one per object.
    hits = scene.hits((10, 0, 0), (-1, 0, 0))
    assert sorted(h.object for h in hits if h.entering) == [0, 1]


def test_material_keywords_are_sdls_names_or_snake_case():
    scene = hitray.Scene()
    obj = scene.add(hitray.Sphere(), ambient=(0.2, 0.2, 0.2), specularExponent=7,
                    speed_of_light=0.6, reflectivity=0.25, transparency=0.5,
                    emissive=(0.1, 0, 0), texture=-1, parameters=(1, 2.5))
    m = obj.material
    assert m["ambient"] == (0.2, 0.2, 0.2)
    assert m["specular_exponent"] == 7.0 and m["speed_of_light"] == 0.6
    assert m["reflectivity"] == 0.25 and m["transparency"] == 0.5
    assert m["texture"] == -1 and m["parameters"] == (1.0, 2.5)
    assert m["diffuse"] == (0.8, 0.8, 0.8)  # SDL's default
    with pytest.raises(TypeError, match="unknown material keyword 'difuse'"):
        scene.add(hitray.Sphere(), difuse=(1, 0, 0))
    with pytest.raises(TypeError, match="given twice"):
        scene.add(hitray.Sphere(), specularExponent=2, specular_exponent=3)
    with pytest.raises(TypeError, match="diffuse"):
        scene.add(hitray.Sphere(), diffuse=(1, 0))
    with pytest.raises(hitray.ArgumentError, match="reflectivity"):
        scene.add(hitray.Sphere(), reflectivity=2)
    assert len(scene.objects) == 1


def test_shape_material_wins_over_the_material_given_to_add():
    scene = hitray.Scene()
    obj = scene.add(hitray.Sphere().with_material(diffuse=(0, 1, 0)), diffuse=(1, 0, 0),
                    reflectivity=0.5)
    assert obj.material["diffuse"] == (0.0, 1.0, 0.0)
    assert obj.material["reflectivity"] == 0.5


def test_globals_are_attributes_with_sdl_aliases():
    scene = hitray.Scene()
    assert scene.background == (0.0, 0.0, 0.6)  # SDL's defaults
    assert scene.max_recursion_depth == 3
    scene.background = (0, 0, 0)
    scene.globalAmbient = (0.2, 0.2, 0.2)
    scene.max_recursion_depth = 5
    scene.min_reflectivity = 0.1
    assert scene.background == (0.0, 0.0, 0.0)
    assert scene.global_ambient == (0.2, 0.2, 0.2) and scene.globalAmbient == (0.2, 0.2, 0.2)
    assert scene.maxRecursionDepth == 5 and scene.min_reflectivity == 0.1
    with pytest.raises(hitray.ArgumentError, match="maxRecursionDepth"):
        scene.max_recursion_depth = 5000
    assert scene.max_recursion_depth == 5
    with pytest.raises(TypeError):
        scene.background = "blue"
    with pytest.raises(AttributeError):
        scene.backgorund = (0, 0, 0)


def test_lights_are_listed():
    scene = hitray.Scene()
    scene.light((1, 2, 3), (0.5, 0.5, 0.5))
    scene.light([4, 5, 6])
    assert scene.lights == [hitray.Light((1.0, 2.0, 3.0), (0.5, 0.5, 0.5)),
                            hitray.Light((4.0, 5.0, 6.0), (1.0, 1.0, 1.0))]
    with pytest.raises(hitray.ArgumentError):
        scene.light((0, 0, float("nan")))
    assert len(scene.lights) == 2


def test_a_scene_changed_after_a_render_renders_the_change():
    scene, camera = two_spheres_in_python()
    first = np.asarray(hitray.render(scene, camera, size=(32, 24), progress=False)).copy()
    scene.background = (1, 1, 1)
    extra = scene.add(hitray.Cube().translate(0, 3, 0), diffuse=(0, 0, 1))
    assert extra.index == 3
    second = np.asarray(hitray.render(scene, camera, size=(32, 24), progress=False))
    assert not np.array_equal(first, second)
    assert np.allclose(second[0, 0], 1.0)  # the top-left corner sees the new background
    # Indices survive the rebuild.
    assert [o.shape for o in scene.objects] == ["sphere", "sphere", "plane", "cube"]
    assert scene.first_hit((0, 3, 10), (0, 0, -1)).object == 3


def test_effects_and_bounds_and_framing():
    scene = hitray.Scene()
    assert scene.bounds is None
    scene.add(hitray.Sphere().translate(5, 0, 0), reflectivity=0.8)
    scene.light((0, 10, 0))
    lo, hi = scene.bounds
    # The library pads bounds outward by a few ulps (a box must contain its
    # object under rounding): contain the true box, and within 1e-12 of it.
    assert all(a <= b for a, b in zip(lo, (4, -1, -1))) and all(a >= b for a, b in zip(hi, (6, 1, 1)))
    assert lo == pytest.approx((4, -1, -1), abs=1e-12) and hi == pytest.approx((6, 1, 1), abs=1e-12)
    assert {"diffuse", "shadows", "reflection"} <= scene.effects
    cam = scene.frame_camera((100, 100))
    # Framed on the sphere's box: looks at its centre.
    assert cam.look == pytest.approx((5.0, 0.0, 0.0))


def test_generic_shape_by_name_and_its_parameters():
    scene = hitray.Scene()
    obj = scene.add(hitray.Shape("taperedCylinder", s=0.5))
    assert obj.shape == "taperedCylinder"
    # A ray down the axis from above meets the cap disk (radius 0.5) at z = 1.
    hit = scene.first_hit((0, 0, 5), (0, 0, -1))
    assert hit.t == pytest.approx(4.0, abs=1e-12) and hit.surface == 2
    assert repr(hitray.TaperedCylinder(s=0.5)) == "TaperedCylinder(s=0.5)"
    with pytest.raises(TypeError, match="parameter 's'"):
        hitray.Shape("taperedCylinder", s=[1])


def test_booleans_build_the_csg_classes_from_operators():
    a, b = hitray.Sphere(), hitray.Cube().scale(0.5)
    u, i, d = a | b, a & b, a - b
    assert (type(u), u.name) == (hitray.Union, "union")
    assert (type(i), i.name) == (hitray.Intersection, "intersection")
    assert (type(d), d.name) == (hitray.Difference, "difference")
    assert d.params["a"] is a and d.params["b"] is b
    assert repr(d) == "(Sphere() - Cube().scale(0.5, 0.5, 0.5))"
    with pytest.raises(TypeError):
        a | 3


def test_a_refused_boolean_leaves_no_operand_behind():
    # A composite class that refuses: an unknown class name, so the operands
    # are added before the library refuses the boolean itself.
    scene = hitray.Scene()
    scene.add(hitray.Sphere())
    with pytest.raises(hitray.ModuleError, match="nosuchboolean"):
        scene.add(hitray.Shape("nosuchboolean", a=hitray.Sphere(), b=hitray.Cube()))
    assert [o.shape for o in scene.objects] == ["sphere"]
    assert len(scene.hits((0, 0, 5), (0, 0, -1))) == 2


def test_a_deep_boolean_chain_meets_the_library_depth_limit_not_pythons():
    """Issue 16: a 2000-deep `a | b` chain raised RecursionError while being
    added; the library's own limit on composite depth must answer."""
    require_classes("union")
    chain = hitray.Sphere()
    for _ in range(2000):
        chain = chain | hitray.Sphere()
    with pytest.raises(hitray.ParameterError, match="nest composites 1001 deep, beyond the limit of 1000"):
        hitray.Scene().add(chain)
    within = hitray.Sphere()
    for _ in range(999):
        within = within | hitray.Sphere()
    scene = hitray.Scene()
    scene.add(within)
    assert scene.first_hit((0, 0, 5), (0, 0, -1)).t == 4.0


def test_objects_say_the_parameters_they_were_made_with():
    # What a class declares, defaults filled in; a boolean's operands are
    # its objects; a mesh file as the scene wrote it.
    require_classes("taperedCylinder", "torus", "union", "mesh")
    scene, _ = hitray.parse_sdl("taperedCylinder 0.5\nunion sphere torus 0.3\n"
                                "mesh ../data/meshes/cube.3vn\n", base_dir=pathlib.Path(__file__).parent)
    cone, sphere, torus, union, mesh = scene.objects
    assert cone.params["s"] == 0.5
    assert torus.params == {"tube": 0.3, "solver": ""}  # "": the default solver
    assert sphere.params == {}
    assert union.params == {"a": sphere, "b": torus} and not torus.top_level
    assert mesh.params == {"file": "../data/meshes/cube.3vn"}
    made = hitray.Scene().add(hitray.Torus(solver="ferrari")).params
    assert made == {"tube": 0.2, "solver": "ferrari"}  # the tube's default filled in

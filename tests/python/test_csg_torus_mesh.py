"""The booleans, the torus and meshes from Python (the csg, torus and mesh
modules), against positions worked out by hand and an mpmath reference."""

import mpmath
import numpy as np
import pytest

import hitray
from conftest import require_classes

mpmath.mp.dps = 50

# Two unit spheres centred at x = -0.5 (A) and x = +0.5 (B), traced along
# the x axis from x = 5 towards -x: A spans x in [-1.5, 0.5], B [-0.5, 1.5].
A = hitray.Sphere().translate(-0.5, 0, 0)
B = hitray.Sphere().translate(0.5, 0, 0)
ORIGIN, DIRECTION = (5, 0, 0), (-1, 0, 0)
T_ABS = 1e-12  # t is 5 - x for x an exact sum of small binary fractions


def crossings(shape):
    scene = hitray.Scene()
    scene.add(shape)
    return scene, [(h.t, h.entering, h.object, h.normal) for h in scene.hits(ORIGIN, DIRECTION)]


def test_union_keeps_the_outer_boundary():
    require_classes("union")
    scene, hits = crossings(A | B)
    # Operands first (A is 0, B is 1), then the boolean (2), which is the
    # only top-level object; hits name the leaf whose surface they are on.
    assert [o.shape for o in scene.objects] == ["sphere", "sphere", "union"]
    assert [o.top_level for o in scene.objects] == [False, False, True]
    assert [(pytest.approx(t, abs=T_ABS), e, o) for t, e, o, _ in hits] == [
        (3.5, True, 1), (6.5, False, 0)]


def test_intersection_keeps_the_lens():
    require_classes("intersection")
    _, hits = crossings(A & B)
    assert [(pytest.approx(t, abs=T_ABS), e, o) for t, e, o, _ in hits] == [
        (4.5, True, 0), (5.5, False, 1)]


def test_difference_is_a_minus_b_with_b_s_surface_turned_inside_out():
    require_classes("difference")
    _, hits = crossings(A - B)
    assert [(pytest.approx(t, abs=T_ABS), e, o) for t, e, o, _ in hits] == [
        (5.5, True, 1), (6.5, False, 0)]
    # Entering the cut face at x = -0.5: the difference's outward normal
    # there faces +x (B's own normal there faces -x).
    assert hits[0][3] == pytest.approx((1.0, 0.0, 0.0), abs=1e-12)


def test_booleans_nest_and_transform_as_a_whole():
    require_classes("union", "difference")
    shape = ((A | B) - hitray.Cube().scale(0.25)).translate(0, 10, 0)
    scene = hitray.Scene()
    scene.add(shape)
    assert [o.shape for o in scene.objects] == ["sphere", "sphere", "union", "cube", "difference"]
    hits = scene.hits((5, 10, 0), DIRECTION)
    # In at 1.5, out at 0.25 (into the cube), in at -0.25, out at -1.5.
    assert [pytest.approx(h.t, abs=T_ABS) for h in hits] == [3.5, 4.75, 5.25, 6.5]
    assert [h.entering for h in hits] == [True, False, True, False]


def test_a_boolean_renders_as_its_sdl_does_with_each_leaf_s_material():
    require_classes("union")
    py_scene = hitray.Scene()
    py_scene.light((3, 4, 5))
    py_scene.add(A.with_material(diffuse=(1, 0, 0)) | B, diffuse=(0, 0, 1))
    sdl_scene, _ = hitray.parse_sdl("""
        light 3 4 5 1 1 1
        union
          push translate -0.5 0 0 diffuse 1 0 0 sphere pop
          push translate 0.5 0 0 diffuse 0 0 1 sphere pop
    """)
    # The leaves carry the materials (a boolean's own is not used in shading).
    assert [o.shape for o in py_scene.objects] == [o.shape for o in sdl_scene.objects]
    for a, b in zip(py_scene.objects[:2], sdl_scene.objects[:2]):
        assert a.material == b.material
    cam = hitray.Camera((0, 0, 6), (0, 0, 0), (0, 1, 0), 40)
    one = np.asarray(hitray.render(py_scene, cam, size=(48, 32), progress=False))
    two = np.asarray(hitray.render(sdl_scene, cam, size=(48, 32), progress=False))
    assert np.array_equal(one, two)
    row = one[16]
    assert row[20, 0] > 0.5 and row[20, 0] > 10 * row[20, 2]  # the left lobe is red
    assert row[30, 2] > 0.5 and row[30, 2] > 10 * row[30, 0]  # the right one blue


def test_an_open_operand_is_refused_naming_the_parameter():
    require_classes("union")
    scene = hitray.Scene()
    with pytest.raises(hitray.ParameterError):
        scene.add(hitray.Plane() | hitray.Sphere())
    assert scene.objects == []  # neither operand is left behind


def torus_reference(origin, direction, tube):
    """Roots of the torus quartic ((|p|² + 1 - r²)² = 4(x² + y²)) along the
    ray, in mpmath."""
    t = mpmath.mpf
    ox, oy, oz = map(t, origin)
    dx, dy, dz = map(t, direction)
    r = t(tube)
    # |p|² = a t² + b t + c
    a = dx * dx + dy * dy + dz * dz
    b = 2 * (ox * dx + oy * dy + oz * dz)
    c = ox * ox + oy * oy + oz * oz + 1 - r * r
    # (a t² + b t + c)² - 4((dx²+dy²) t² + 2(ox dx + oy dy) t + ox² + oy²) = 0
    e = dx * dx + dy * dy
    f = 2 * (ox * dx + oy * dy)
    g = ox * ox + oy * oy
    coeffs = [c * c - 4 * g, 2 * b * c - 4 * f, b * b + 2 * a * c - 4 * e, 2 * a * b, a * a]
    roots = mpmath.polyroots(coeffs, maxsteps=200, extraprec=200, asc=True)
    return sorted(float(z.real) for z in roots if abs(z.imag) < mpmath.mpf(10) ** -30 and z.real > 0)


@pytest.mark.parametrize("solver", [None, "bracketing", "ferrari-newton"])
def test_torus_hits_match_the_quartic_reference(solver):
    require_classes("torus")
    scene = hitray.Scene()
    scene.add(hitray.Torus(tube=0.3, solver=solver))
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(100):
        origin = rng.normal(size=3) * 3
        target = rng.uniform(-1, 1, size=3) * (1.2, 1.2, 0.25)
        direction = target - origin
        ref = torus_reference(origin, direction, 0.3)
        hits = scene.hits(origin, direction)
        # Skip rays that graze the tube (two roots closer than 1e-6): there
        # a root's condition, not the solver, sets the error.
        if any(abs(x - y) < 1e-6 for x, y in zip(ref, ref[1:])):
            continue
        assert len(hits) == len(ref)
        # 1e-9 relative: well-separated quartic roots found to a few ulps of
        # their condition number (the module's own tests bound it tighter).
        assert [h.t for h in hits] == pytest.approx(ref, rel=1e-9)
        checked += 1
    assert checked > 80


def test_torus_parameters_are_checked():
    require_classes("torus")
    scene = hitray.Scene()
    with pytest.raises(hitray.ParameterError, match="solver"):
        scene.add(hitray.Torus(solver="newton-raphson"))
    with pytest.raises(hitray.ParameterError, match="tube"):
        scene.add(hitray.Torus(tube=2))
    assert repr(hitray.Torus(tube=0.1)) == "Torus(tube=0.1)"
    # Along the x axis: the default tube is 0.2, crossings at |x| = 1.2, 0.8.
    scene.add(hitray.Torus())
    assert [h.t for h in scene.hits(ORIGIN, DIRECTION)] == pytest.approx([3.8, 4.2, 5.8, 6.2],
                                                                         abs=1e-12)


CUBE_OBJ = """\
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 3 4 8 7
f 2 3 7 6
f 1 5 8 4
"""


def test_a_mesh_file_is_read_relative_to_the_directory_at_add_time(tmp_path, monkeypatch):
    require_classes("mesh")
    (tmp_path / "cube.obj").write_text(CUBE_OBJ)
    monkeypatch.chdir(tmp_path)
    scene = hitray.Scene()
    scene.add(hitray.Mesh("cube.obj").translate(0, 0, -3))
    hitray.render(scene, None, size=(4, 4), progress=False)  # commits the scene
    monkeypatch.chdir("/")
    scene.add(hitray.Sphere().translate(0, 0, 10))  # a rebuild, from elsewhere
    hits = scene.hits((0, 0, 5), (0, 0, -1), tmax=100)
    assert [pytest.approx(h.t, abs=1e-12) for h in hits] == [7.0, 9.0]
    assert [h.entering for h in hits] == [True, False]
    with pytest.raises(hitray.FileError, match="missing.obj"):
        scene.add(hitray.Mesh(tmp_path / "missing.obj"))


def test_the_regular_solids():
    require_classes("octahedron", "tetrahedron", "dodecahedron", "icosahedron")
    scene = hitray.Scene()
    scene.add(hitray.Octahedron())
    assert scene.first_hit((0, 0, 5), (0, 0, -1)).t == pytest.approx(4.0, abs=1e-12)
    for cls in (hitray.Tetrahedron, hitray.Dodecahedron, hitray.Icosahedron):
        s = hitray.Scene()
        s.add(cls())
        hit = s.first_hit((0, 0, 5), (0, 0, -1))
        # Vertices on the unit sphere: the surface is within it and, for these
        # solids, beyond their inscribed radius (>= 1/3 for the tetrahedron).
        assert 4.0 <= hit.t <= 5.0 - 1 / 3


def test_the_buckyball_and_the_teapot():
    require_classes("buckyball", "teapot")
    scene = hitray.Scene()
    scene.add(hitray.Buckyball())
    hit = scene.first_hit((0, 0, 5), (0, 0, -1))
    # Vertices on the unit sphere; the nearest faces, the hexagons, are at
    # sqrt(1 - e^2) from the centre, e = 2 / sqrt(9 phi + 10) the edge.
    phi = (1 + 5 ** 0.5) / 2
    edge = 2 / (9 * phi + 10) ** 0.5
    assert 4.0 <= hit.t <= 5.0 - (1 - edge * edge) ** 0.5
    assert repr(hitray.Buckyball()) == "Buckyball()"

    # Straight down onto the knob's top, glutSolidTeapot's 0.825 high.
    teapot = hitray.Scene()
    teapot.add(hitray.Teapot())
    hit = teapot.first_hit((0, 5, 0), (0, -1, 0))
    assert hit.t == pytest.approx(5 - 0.825, abs=1e-12) and hit.entering
    assert hit.normal == pytest.approx((0, 1, 0), abs=1e-12)
    coarse = hitray.Scene()
    coarse.add(hitray.Teapot(tessellation=4))
    assert coarse.first_hit((0, 5, 0), (0, -1, 0)).t == pytest.approx(5 - 0.825, abs=1e-12)
    assert repr(hitray.Teapot(tessellation=4)) == "Teapot(tessellation=4.0)"
    for bad in (2.5, 1, 129):
        with pytest.raises(hitray.ParameterError, match="tessellation"):
            hitray.Scene().add(hitray.Teapot(tessellation=bad))


def test_one_shape_in_two_booleans_is_two_copies():
    require_classes("union", "intersection")
    scene = hitray.Scene()
    ball = A
    scene.add(ball | B)
    scene.add((ball & B).translate(0, 5, 0))
    scene.add(ball | ball)  # even twice in one boolean
    shapes = [o.shape for o in scene.objects]
    assert shapes == ["sphere", "sphere", "union", "sphere", "sphere", "intersection",
                      "sphere", "sphere", "union"]
    # Each boolean consumed operands of its own.
    assert [o.top_level for o in scene.objects].count(True) == 3
    # Along +x from x = -5: A | B spans x in [-1.5, 1.5], the ball united
    # with itself is the ball, [-1.5, 0.5]; the intersection is 5 above.
    hits = scene.hits((-5, 0, 0), (1, 0, 0))
    assert [pytest.approx(h.t, abs=T_ABS) for h in hits] == [3.5, 3.5, 5.5, 6.5]
    leaving = sorted(h.object for h in hits if not h.entering)
    assert leaving[0] == 1 and leaving[1] in (6, 7)  # either copy's surface, they coincide

"""Hits of Python shape classes through the host's queries: against
quad-precision references (mpmath), against the C sphere, unbounded shapes,
more hits than the first allocation, and renders on several threads."""

import math
import random

import mpmath
import pytest

from abi_shapes import Ball, Floor, Slabs
from abi_support import (SceneContext, abi, all_hits, destroy, ffi, first_hit, lib, load_sdl,
                         render)


@pytest.fixture
def ctx():
    with SceneContext() as c:
        abi.register_shape("ball", Ball, context=c)
        abi.register_shape("floor", Floor, context=c)
        abi.register_shape("slabs", Slabs, context=c)
        yield c


def object_matrices(scene, index):
    info = ffi.new("hr_object_info *")
    info.struct_size = ffi.sizeof("hr_object_info")
    assert lib.hr_scene_object_info(scene, index, info) == 0
    return list(info.transform), list(info.inverse), info


def reference_hit(inv, radius, origin, direction):
    """The first hit of the world ray on the transformed sphere, to 50
    digits: the ray taken to object space with the exact matrix entries, the
    quadratic solved there (Hill: t is the same in both spaces), the normal
    taken back with the inverse transpose."""
    mpmath.mp.dps = 50
    I = mpmath.matrix([[mpmath.mpf(inv[4 * r + c]) for c in range(4)] for r in range(4)])
    o = I * mpmath.matrix([mpmath.mpf(v) for v in origin] + [1])
    d = I * mpmath.matrix([mpmath.mpf(v) for v in direction] + [0])
    a = sum(d[i] ** 2 for i in range(3))
    b = sum(o[i] * d[i] for i in range(3))
    c = sum(o[i] ** 2 for i in range(3)) - mpmath.mpf(radius) ** 2
    t = (-b - mpmath.sqrt(b * b - a * c)) / a
    point = [mpmath.mpf(origin[i]) + t * mpmath.mpf(direction[i]) for i in range(3)]
    n_obj = [o[i] + t * d[i] for i in range(3)]
    n = [sum(I[j, i] * n_obj[j] for j in range(3)) for i in range(3)]
    length = mpmath.sqrt(sum(v * v for v in n))
    return t, point, [v / length for v in n]


def test_first_hits_match_a_quad_precision_reference(ctx):
    scene, _ = load_sdl(ctx, "push translate 1 2 3 rotate 30 1 1 0 scale 2 1 0.5 ball 1.5 pop\n")
    _, inv, _ = object_matrices(scene, 0)
    rng = random.Random(7)
    checked = 0
    for _ in range(300):
        origin = [rng.uniform(-20, 20) for _ in range(3)]
        # Aim at a point well inside the ellipsoid so the ray crosses it
        # far from tangency (the roots are well conditioned).
        target = [1 + rng.uniform(-0.5, 0.5), 2 + rng.uniform(-0.3, 0.3),
                  3 + rng.uniform(-0.2, 0.2)]
        direction = [target[i] - origin[i] for i in range(3)]
        got = first_hit(ctx, scene, origin, direction)
        assert got is not None, (origin, direction)
        t, point, normal, obj = got
        rt, rp, rn = reference_hit(inv, 1.5, origin, direction)
        # Sources of error: the host's object-space ray (a few ulps of each
        # coordinate), the Python root (a few ulps), the conditioning of a
        # crossing well inside (< 10): 1e-12 relative is >100x that.
        assert abs(t - float(rt)) <= 1e-12 * abs(float(rt)), (t, rt)
        scale = max(abs(float(v)) for v in rp) + 1
        assert all(abs(point[i] - float(rp[i])) <= 1e-11 * scale for i in range(3))
        # Unit normal, world space; same sources of error.
        assert all(abs(normal[i] - float(rn[i])) <= 1e-10 for i in range(3)), (normal, rn)
        assert obj == 0
        checked += 1
    assert checked == 300
    destroy(scene)


def test_the_python_sphere_agrees_with_the_c_sphere(ctx):
    py_scene, _ = load_sdl(ctx, "push translate 0.5 -1 2 scale 3 3 3 ball 1 pop\n")
    c_scene, _ = load_sdl(ctx, "push translate 0.5 -1 2 scale 3 3 3 sphere pop\n")
    rng = random.Random(11)
    hits = 0
    for _ in range(500):
        origin = [rng.uniform(-10, 10) for _ in range(3)]
        # Aimed near the sphere (radius 3 about (0.5, -1, 2)): hits, misses
        # and near-tangent rays.
        target = [0.5 + rng.uniform(-3.5, 3.5), -1 + rng.uniform(-3.5, 3.5),
                  2 + rng.uniform(-3.5, 3.5)]
        direction = [target[i] - origin[i] for i in range(3)]
        py, c = all_hits(ctx, py_scene, origin, direction), all_hits(ctx, c_scene, origin, direction)
        if len(py) != len(c):
            # Only a ray that grazes the sphere may be seen by one and not
            # the other; then its two roots are within rounding of each other.
            grazing = py or c
            assert len(grazing) == 2 and abs(grazing[0][0] - grazing[1][0]) < 1e-6
            continue
        for (tp, ep, op), (tc, ec, oc) in zip(py, c):
            # Both roots are accurate to a few ulps away from tangency; near
            # it both lose digits as sqrt(disc) does: compare loosely there.
            assert abs(tp - tc) <= 1e-7 * max(1.0, abs(tc)), (tp, tc)
            assert (ep, op) == (ec, oc)
        hits += len(py)
    assert hits > 400
    destroy(py_scene)
    destroy(c_scene)


def test_an_unbounded_python_shape(ctx):
    scene, _ = load_sdl(ctx, "push translate 0 -1 0 floor pop\n")
    _, _, info = object_matrices(scene, 0)
    assert math.isinf(info.world_bounds.lo.x) and math.isinf(info.world_bounds.hi.z)
    t, point, normal, _ = first_hit(ctx, scene, (3, 4, 5), (0, -1, 0))
    assert (t, point, normal) == (5.0, (3.0, -1.0, 5.0), (0.0, 1.0, 0.0))
    assert first_hit(ctx, scene, (3, 4, 5), (0, 1, 0)) is None
    destroy(scene)


def test_more_hits_than_the_first_allocation(ctx):
    assert lib.HR_MIN_HIT_CAPACITY < 20
    scene, _ = load_sdl(ctx, "slabs 20\n")
    hits = all_hits(ctx, scene, (0, 0, -5), (0, 0, 1))
    assert [t for t, _, _ in hits] == [5.0 + k for k in range(20)]
    hits = all_hits(ctx, scene, (0, 0, -5), (0, 0, 1), tmin=10.5, tmax=15.5)
    assert [t for t, _, _ in hits] == [11.0, 12.0, 13.0, 14.0, 15.0]
    destroy(scene)


SCENE = """camera 0 1 6  0 0 0  0 1 0  40
light 4 6 5  1 1 1
push translate -1 0 0 diffuse 0.8 0.3 0.2 {shape} pop
push translate 1.2 0 -0.5 reflectivity 0.6 sphere pop
push translate 0 -1 0 rotate -90 1 0 0 plane pop
"""


def test_renders_are_the_same_on_one_and_two_threads(ctx):
    scene, camera = load_sdl(ctx, SCENE.format(shape="ball 1"))
    one = render(ctx, scene, camera, 48, 36, threads=1)
    two = render(ctx, scene, camera, 48, 36, threads=2)
    assert one == two
    destroy(scene)


def test_a_render_with_the_python_sphere_looks_like_the_c_sphere(ctx):
    py_scene, camera = load_sdl(ctx, SCENE.format(shape="ball 1"))
    c_scene, _ = load_sdl(ctx, SCENE.format(shape="sphere"))
    py = render(ctx, py_scene, camera, 64, 48, threads=2)
    c = render(ctx, c_scene, camera, 64, 48, threads=2)
    # The two spheres round differently, so only a pixel whose ray grazes
    # an edge may change (hit one way, miss the other); 1e-4 is far below
    # what any shading difference of a few-ulp normal could do.
    differing = sum(abs(a - b) > 1e-4 for a, b in zip(py, c))
    assert differing <= 0.01 * len(py), differing
    assert py != [py[0]] * len(py)  # something was drawn
    destroy(py_scene)
    destroy(c_scene)

"""The batch queries from Python: Scene.first_hits (every field of each ray's
first hit, the C hr_scene_first_hits) and Scene.occluded (hr_scene_occluded)
against Scene.first_hit ray by ray, bit for bit, on coherent (a camera's
grid) and random rays with misses, exact ties (coincident spheres and
planes, dyadic rays) and rays from inside objects; and their errors. The
cffi layer declares the C calls from the headers; one call through it
checks they are there and answer as the package does."""

import math

import numpy as np
import pytest

import hitray
from hitray import abi


@pytest.fixture(scope="module")
def scene():
    s = hitray.Scene()
    rng = np.random.default_rng(11)
    for i in range(300):
        x, y, z = (np.floor(rng.uniform(-16, 16, 3)) / 2).tolist()
        shape = hitray.Sphere() if i % 3 else hitray.Cube()
        s.add(shape.translate(x, y, z).scale(0.5))
        if i % 10 == 0:  # a coincident twin: a tie at every hit
            s.add((hitray.Sphere() if i % 3 else hitray.Cube()).translate(x, y, z).scale(0.5))
    s.add(hitray.Plane().translate(0, 0, -9))
    s.add(hitray.Plane().translate(0, 0, -9))
    s.add(hitray.Sphere().translate(0.1, 0.2, 0.3))  # around the inner camera's eye
    return s


def camera_rays(eye, w=64, h=48):
    u = np.floor(((np.arange(w) + 0.5) / w * 2 - 1) * 64) / 64
    v = np.floor(((np.arange(h) + 0.5) / h * 2 - 1) * 64) / 64
    uu, vv = np.meshgrid(u, v)
    d = np.stack([0.9 * uu.ravel(), 0.9 * vv.ravel(), -np.ones(w * h)], axis=1)
    return np.tile(np.array(eye, dtype=float), (w * h, 1)), d


def random_rays(n, seed):
    rng = np.random.default_rng(seed)
    o = rng.uniform(-10, 10, (n, 3))
    d = rng.normal(size=(n, 3))
    o[::2] = np.floor(o[::2] * 4) / 4  # dyadic: ties at faces and planes
    d[::2] = np.floor(d[::2] * 8) / 8
    d[np.all(d == 0, axis=1)] = (0, 0, -1)
    return o, d


def compare(scene, o, d, tmin=0.0, tmax=math.inf):
    got = scene.first_hits(o, d, tmin, tmax)
    blocked = scene.occluded(o, d, tmin, tmax)
    assert got.t.shape == (len(o),) and got.point.shape == (len(o), 3)
    assert got.surface.dtype == np.int32 and got.entering.dtype == np.bool_ and blocked.dtype == np.bool_
    hits = inside = 0
    for i in range(len(o)):
        one = scene.first_hit(o[i], d[i], tmin, tmax)
        assert blocked[i] == (one is not None)
        if one is None:
            assert got.t[i] == math.inf and got.object[i] == -1 and got.surface[i] == -1
            assert not got.entering[i] and tuple(got.point[i]) == (0.0, 0.0, 0.0) and got.error[i] == 0
            continue
        hits += 1
        inside += not one.entering
        # The same library answer: equal bit for bit.
        assert (got.t[i], tuple(got.point[i]), tuple(got.normal[i]), got.surface[i], bool(got.entering[i]),
                got.object[i], got.error[i]) == (one.t, one.point, one.normal, one.surface, one.entering,
                                                 one.object, one.error)
    return hits, len(o) - hits, inside


def test_camera_batches_match_first_hit(scene):
    hits, misses, _ = compare(scene, *camera_rays((0.25, -0.5, 12)), tmax=15.0)  # before the floor
    assert hits > 1000 and misses > 100
    hits, _, _ = compare(scene, *camera_rays((0.25, -0.5, 12)))  # the floor takes the rest
    assert hits == 64 * 48
    _, _, inside = compare(scene, *camera_rays((0.0, 0.0, 0.0), 32, 24), tmin=-1.0)
    assert inside > 300  # (tmin -1: some meet it behind the eye, entering)


def test_random_batches_match_first_hit_on_any_thread_count(scene):
    o, d = random_rays(6000, 12)
    hits, misses, inside = compare(scene, o, d)
    assert hits > 1000 and misses > 500 and inside > 50
    one = scene.first_hits(o, d, threads=1)
    two = scene.first_hits(o, d, threads=2)
    for a, b in zip(one, two):
        assert np.array_equal(a, b)
    assert np.array_equal(scene.occluded(o, d, threads=1), scene.occluded(o, d, threads=2))


def test_trace_is_first_hits_in_part(scene):
    o, d = random_rays(500, 13)
    full, part = scene.first_hits(o, d), scene.trace(o, d)
    assert np.array_equal(full.t, part.t) and np.array_equal(full.normal, part.normal)
    assert np.array_equal(full.object, part.object)


def test_batches_refuse_bad_rays_by_index(scene):
    o, d = random_rays(10, 14)
    d[6] = 0
    with pytest.raises(hitray.ArgumentError, match="ray 6: .*zero"):
        scene.first_hits(o, d)
    with pytest.raises(hitray.ArgumentError, match="ray 6: .*zero"):
        scene.occluded(o, d)
    with pytest.raises(ValueError, match="occluded: origins must be N x 3"):
        scene.occluded(np.zeros((3, 2)), d[:3])
    with pytest.raises(ValueError, match="threads"):
        scene.first_hits(o, d, threads=0)
    with pytest.raises(hitray.ArgumentError, match="tmin <= tmax"):
        scene.first_hits(o[:2], np.ones((2, 3)), tmin=2, tmax=1)
    empty = scene.first_hits(np.zeros((0, 3)), np.zeros((0, 3)))
    assert empty.t.shape == (0,) and empty.point.shape == (0, 3)
    assert scene.occluded(np.zeros((0, 3)), np.zeros((0, 3))).shape == (0,)


def test_the_cffi_layer_has_the_batch_calls(scene):
    """hr_scene_first_hits and hr_scene_occluded through cffi, on a scene
    made there: each answer the single call's."""
    ffi, lib = abi.ffi, abi.lib
    ctx = ffi.new("hr_context **")
    assert lib.hr_context_create(ctx) == 0
    s = ffi.new("hr_scene **")
    assert lib.hr_scene_create(ctx[0], s) == 0
    desc = ffi.new("hr_object_desc *")
    desc.struct_size = ffi.sizeof("hr_object_desc")
    desc.shape = keep = ffi.new("char[]", b"sphere")
    assert lib.hr_scene_add_object(s[0], desc, ffi.NULL) == 0
    assert lib.hr_scene_commit(s[0]) == 0
    rays = ffi.new("hr_ray[3]")
    for i, (z, dz) in enumerate(((5.0, -1.0), (5.0, 1.0), (0.0, 1.0))):
        rays[i].origin.z, rays[i].dir.z = z, dz
    hits, found, blocked = ffi.new("hr_hit[3]"), ffi.new("int32_t[3]"), ffi.new("int32_t[3]")
    assert lib.hr_scene_first_hits(s[0], rays, 3, 0.0, math.inf, hits, found) == 0
    assert lib.hr_scene_occluded(s[0], rays, 3, 0.0, math.inf, blocked) == 0
    assert list(found) == [1, 0, 1] and list(blocked) == [1, 0, 1]
    assert (hits[0].t, hits[0].entering, hits[2].t, hits[2].entering) == (4.0, 1, 1.0, 0)
    assert lib.hr_scene_first_hits(s[0], rays, -1, 0.0, math.inf, hits, found) != 0
    assert b"count -1 is negative" in ffi.string(lib.hr_context_last_error(ctx[0]))
    del keep
    lib.hr_scene_destroy(s[0])
    lib.hr_context_destroy(ctx[0])

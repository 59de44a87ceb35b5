"""Hill's queries from Python: first_hit (getFirstHit), hits (the
Intersection), trace (many rays as numpy arrays) and shade, checked against
references computed with mpmath at 50 digits."""

import math
import random
import threading
import time

import mpmath
import numpy as np
import pytest

import hitray

mpmath.mp.dps = 50

# An ellipsoid: M = T.R.S as Hill's SDL would build it.
MOVE, ANGLE, AXIS, RADII = (1.5, -0.5, 2.0), 30.0, (1.0, 2.0, 3.0), (2.0, 1.0, 0.5)


def ellipsoid_shape():
    return hitray.Sphere().translate(*MOVE).rotate(ANGLE, *AXIS).scale(*RADII)


def reference_matrices():
    """M⁻¹ of the ideal ellipsoid (exact angle) in mpmath."""
    ux, uy, uz = (mpmath.mpf(a) for a in AXIS)
    n = mpmath.sqrt(ux * ux + uy * uy + uz * uz)
    ux, uy, uz = ux / n, uy / n, uz / n
    a = mpmath.radians(ANGLE)
    c, s = mpmath.cos(a), mpmath.sin(a)
    C = 1 - c
    R = mpmath.matrix([[c + ux * ux * C, ux * uy * C - uz * s, ux * uz * C + uy * s],
                       [uy * ux * C + uz * s, c + uy * uy * C, uy * uz * C - ux * s],
                       [uz * ux * C - uy * s, uz * uy * C + ux * s, c + uz * uz * C]])
    S = mpmath.diag([mpmath.mpf(r) for r in RADII])
    A = R * S  # the linear part of M; M p = A p + MOVE
    return A ** -1


def reference_hits(origin, direction):
    """Both roots t of |M⁻¹(o + t d)| = 1 and the outward unit normals."""
    Ainv = reference_matrices()
    o = mpmath.matrix([mpmath.mpf(v) for v in origin]) - mpmath.matrix([mpmath.mpf(v) for v in MOVE])
    d = mpmath.matrix([mpmath.mpf(v) for v in direction])
    oo, dd = Ainv * o, Ainv * d
    a = sum(dd[i] ** 2 for i in range(3))
    b = sum(oo[i] * dd[i] for i in range(3))
    c = sum(oo[i] ** 2 for i in range(3)) - 1
    disc = b * b - a * c
    if disc < 0:
        return []
    out = []
    for t in ((-b - mpmath.sqrt(disc)) / a, (-b + mpmath.sqrt(disc)) / a):
        p_obj = oo + t * dd
        n = Ainv.T * p_obj  # normal = M⁻ᵀ n_obj
        length = mpmath.sqrt(sum(n[i] ** 2 for i in range(3)))
        out.append((t, tuple(float(n[i] / length) for i in range(3))))
    return out


@pytest.fixture(scope="module")
def scene():
    s = hitray.Scene()
    s.add(ellipsoid_shape())
    return s


def random_rays(count, seed):
    """Rays from a shell of radius 10 towards points near the centre, so
    every one hits well away from grazing."""
    rng = random.Random(seed)
    rays = []
    for _ in range(count):
        v = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        origin = [MOVE[i] + 10 * v[i] / n for i in range(3)]
        target = [MOVE[i] + rng.uniform(-0.2, 0.2) for i in range(3)]
        rays.append((origin, [target[i] - origin[i] for i in range(3)]))
    return rays


# Tolerances: the library's t comes from a transform chain (~10 ulps) and a
# quadratic solved away from grazing, so its relative error is ~1e-14; 1e-11
# leaves room while any wrong order of transforms or wrong root is off by O(1).
T_RTOL = 1e-11
N_ATOL = 1e-9


def test_first_hit_and_hits_match_the_mpmath_reference(scene):
    for origin, direction in random_rays(200, seed=1):
        ref = reference_hits(origin, direction)
        assert len(ref) == 2
        hit = scene.first_hit(origin, direction)
        assert hit is not None
        assert hit.t == pytest.approx(float(ref[0][0]), rel=T_RTOL)
        assert hit.normal == pytest.approx(ref[0][1], abs=N_ATOL)
        assert hit.entering and hit.object == 0 and hit.surface == 0
        expected_point = [origin[i] + hit.t * direction[i] for i in range(3)]
        assert hit.point == pytest.approx(expected_point, rel=1e-12, abs=1e-12)
        both = scene.hits(origin, direction)
        assert [h.entering for h in both] == [True, False]
        for h, (t, normal) in zip(both, ref):
            assert h.t == pytest.approx(float(t), rel=T_RTOL)
            assert h.normal == pytest.approx(normal, abs=N_ATOL)


def test_tmin_and_tmax_bound_the_hits(scene):
    origin, direction = random_rays(1, seed=2)[0]
    both = scene.hits(origin, direction)
    mid = 0.5 * (both[0].t + both[1].t)
    assert [h.t for h in scene.hits(origin, direction, tmin=mid)] == [both[1].t]
    assert scene.first_hit(origin, direction, tmin=mid).t == both[1].t
    assert scene.first_hit(origin, direction, tmax=both[0].t) is None  # open interval
    assert scene.first_hit(origin, [-v for v in direction]) is None  # behind the origin


def test_trace_matches_first_hit_ray_by_ray(scene):
    rays = random_rays(300, seed=3)
    origins = np.array([r[0] for r in rays])
    directions = np.array([r[1] for r in rays])
    directions[::3] = -directions[::3]  # every third ray points away: a miss
    result = scene.trace(origins, directions)
    t, normal, obj = result  # unpacks as a tuple
    assert t.shape == (300,) and normal.shape == (300, 3) and obj.shape == (300,)
    assert t.dtype == np.float64 and obj.dtype == np.int64
    for i in range(300):
        hit = scene.first_hit(origins[i], directions[i])
        if hit is None:
            assert t[i] == math.inf and obj[i] == -1 and tuple(normal[i]) == (0.0, 0.0, 0.0)
        else:
            # The same library call per ray: equal bit for bit.
            assert (t[i], tuple(normal[i]), obj[i]) == (hit.t, hit.normal, hit.object)
    assert np.count_nonzero(obj == -1) == 100


def test_trace_broadcasts_one_origin_and_is_the_same_on_any_thread_count(scene):
    rng = np.random.default_rng(4)
    directions = rng.normal(size=(20000, 3))
    origin = np.array(MOVE)  # the ellipsoid's centre: every ray hits
    one = scene.trace(origin, directions, threads=1)
    many = scene.trace(np.tile(origin, (20000, 1)), directions)
    assert np.array_equal(one.t, many.t) and np.array_equal(one.normal, many.normal)
    assert np.all(one.object == 0)


def test_trace_refuses_bad_arrays_and_names_the_bad_ray(scene):
    with pytest.raises(ValueError, match="N x 3"):
        scene.trace(np.zeros((4, 2)), np.ones((4, 3)))
    with pytest.raises(ValueError):
        scene.trace(np.zeros((4, 3)), np.ones((5, 3)))
    d = np.ones((10, 3))
    d[7] = 0
    with pytest.raises(hitray.ArgumentError, match="ray 7: .*zero"):
        scene.trace(np.zeros((10, 3)), d)
    o = np.zeros((10, 3))
    o[2, 1] = np.nan
    with pytest.raises(hitray.ArgumentError, match="ray 2: .*finite"):
        scene.trace(o, np.ones((10, 3)))
    empty = scene.trace(np.zeros((0, 3)), np.zeros((0, 3)))
    assert empty.t.shape == (0,)


def test_single_ray_queries_refuse_bad_rays(scene):
    with pytest.raises(hitray.ArgumentError, match="zero"):
        scene.first_hit((0, 0, 0), (0, 0, 0))
    with pytest.raises(hitray.ArgumentError):
        scene.hits((0, 0, math.inf), (0, 0, 1))
    with pytest.raises(hitray.ArgumentError, match="tmin <= tmax"):
        scene.first_hit((0, 0, 9), (0, 0, -1), tmin=5, tmax=1)
    with pytest.raises(TypeError, match="origin"):
        scene.first_hit("abc", (0, 0, 1))


def test_shade_sees_the_background_on_a_miss_and_a_lit_surface_on_a_hit():
    scene = hitray.Scene()
    scene.background = (0.25, 0.5, 0.75)
    scene.add(hitray.Sphere(), diffuse=(1, 0, 0), ambient=(0, 0, 0))
    scene.light((0, 0, 10), (1, 1, 1))
    assert scene.shade((0, 5, 5), (0, 0, -1)) == (0.25, 0.5, 0.75)
    # Head-on at the light's side: diffuse 1 * (s.m = 1) * light 1 in red.
    r, g, b = scene.shade((0, 0, 5), (0, 0, -1))
    assert (r, g, b) == pytest.approx((1.0, 0.0, 0.0), abs=1e-12)


def test_trace_releases_the_gil():
    # While one thread traces a million rays on one core, a pure-Python
    # thread keeps ticking. If trace held the GIL the ticking thread could
    # run only just before the call entered C and just after it returned,
    # never in the middle half of it.
    scene = hitray.Scene()
    for i in range(50):
        scene.add(hitray.Sphere().translate(3 * (i % 10), 3 * (i // 10), 0))
    rng = np.random.default_rng(5)
    directions = rng.normal(size=(1_000_000, 3))
    origins = np.zeros((1_000_000, 3)) + (13.5, 6, 20)
    ticks = []
    stop = threading.Event()

    def counter():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    thread = threading.Thread(target=counter)
    thread.start()
    try:
        start = time.monotonic()
        scene.trace(origins, directions, threads=1)
        end = time.monotonic()
    finally:
        stop.set()
        thread.join()
    quarter = 0.25 * (end - start)
    middle = [t for t in ticks if start + quarter < t < end - quarter]
    assert middle, f"no Python ran during the trace ({end - start:.2f} s)"


def test_a_tie_goes_to_the_object_added_first():
    """300 coincident pairs of spheres of two colours, the red one added
    first in half the pairs and the green one in the others: every first
    hit, one ray at a time or many at once, is the pair's first-added
    sphere (an even object index), whatever order the BVH meets them in."""
    rng = random.Random(26)
    s = hitray.Scene()
    for i in range(300):
        shape = hitray.Sphere().translate(rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(-6, 6)).scale(
            rng.uniform(0.2, 1.0))
        colours = [(0.9, 0.1, 0.1), (0.1, 0.9, 0.1)]
        for colour in colours if i % 2 else colours[::-1]:
            s.add(shape, diffuse=colour)
    rng_np = np.random.default_rng(26)
    origins = np.tile([0.0, 0.0, 30.0], (4000, 1))
    directions = np.column_stack([rng_np.uniform(-0.3, 0.3, 4000), rng_np.uniform(-0.3, 0.3, 4000),
                                  -np.ones(4000)])
    t, _, obj = s.trace(origins, directions)
    hit = obj >= 0
    assert np.count_nonzero(hit) > 1000
    assert np.all(obj[hit] % 2 == 0), f"{np.count_nonzero(obj[hit] % 2)} rays hit the later-added copy"
    for i in range(0, 4000, 40):
        one = s.first_hit(origins[i], directions[i])
        assert (one is None) == (obj[i] < 0)
        assert one is None or (one.object, one.t) == (obj[i], t[i])

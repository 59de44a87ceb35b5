"""examples/python/python_shape.py: its paraboloid against 50-digit
references, and the script itself rendering an image."""

import importlib.util
import math
import random
import subprocess
import sys

import mpmath
import pytest

from abi_support import BUILD, MODE, ROOT

EXAMPLE = ROOT / "examples" / "python" / "python_shape.py"


def load_example():
    spec = importlib.util.spec_from_file_location("python_shape_example", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def reference_span(height, origin, direction):
    """(t_in, t_out) of the ray in x^2 + y^2 < z < height, to 50 digits,
    or None: the roots of the wall's quadratic cut by the cap's plane."""
    mpmath.mp.dps = 50
    o = [mpmath.mpf(v) for v in origin]
    d = [mpmath.mpf(v) for v in direction]
    a = d[0] ** 2 + d[1] ** 2
    b = 2 * (o[0] * d[0] + o[1] * d[1]) - d[2]
    c = o[0] ** 2 + o[1] ** 2 - o[2]
    disc = b * b - 4 * a * c
    if disc < 0:
        return None
    lo, hi = (-b - mpmath.sqrt(disc)) / (2 * a), (-b + mpmath.sqrt(disc)) / (2 * a)
    t_cap = (mpmath.mpf(height) - o[2]) / d[2]
    if d[2] > 0:
        hi = min(hi, t_cap)
    else:
        lo = max(lo, t_cap)
    return (lo, hi) if lo <= hi else None


def test_the_paraboloid_against_references():
    Paraboloid = load_example().Paraboloid
    shape = Paraboloid(height=1.5)
    rng = random.Random(3)
    compared = 0
    for _ in range(400):
        origin = [rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-2, 4)]
        target = [rng.uniform(-1.3, 1.3), rng.uniform(-1.3, 1.3), rng.uniform(0, 1.6)]
        direction = [target[i] - origin[i] for i in range(3)]
        if direction[2] == 0:
            continue
        hits = shape.hit(origin, direction, -math.inf, math.inf)
        ref = reference_span(1.5, origin, direction)
        if ref is None or ref[1] - ref[0] < 1e-6:
            # A miss, or a ray so near a tangent that one rounding decides.
            assert len(hits) in (0, 2)
            continue
        assert [h[2] for h in hits] == [True, False]
        for (t, normal, _, surface), r in zip(hits, ref):
            # The stable roots are good to a few ulps; the rays here cross
            # away from tangency (span > 1e-6), so 1e-9 relative is loose.
            assert abs(t - float(r)) <= 1e-9 * max(1.0, abs(float(r))), (t, r)
            p = [origin[i] + t * direction[i] for i in range(3)]
            if surface == 1:
                assert normal == (0.0, 0.0, 1.0) and abs(p[2] - 1.5) < 1e-9
            else:
                # The wall's outward normal is the gradient (2x, 2y, -1).
                assert normal == pytest.approx((2 * p[0], 2 * p[1], -1.0), rel=1e-12)
        compared += 1
    assert compared > 150


def test_the_paraboloid_refuses_a_bad_height():
    with pytest.raises(ValueError, match="height must be > 0"):
        load_example().Paraboloid(height=0.0)


def run_example(out, *extra):
    command = [sys.executable, str(EXAMPLE), str(out), "--size", "64x48", "--threads", "2",
               *extra]
    run = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith(f"{out}: 64x48 in ")
    return out.read_bytes()


def check_image(data):
    header = b"P6\n64 48\n255\n"
    assert data.startswith(header) and len(data) == len(header) + 64 * 48 * 3
    # The paraboloid (orange: more red than blue) fills the middle of the frame.
    x, y = 32, 20
    r, g, b = data[len(header) + 3 * (y * 64 + x):][:3]
    assert r > b + 40, (r, g, b)


def test_the_example_renders_through_the_c_api(tmp_path):
    check_image(run_example(tmp_path / "abi.ppm", "--build-dir", str(BUILD)))


@pytest.mark.skipif(MODE != "installed", reason="the hitray package is not installed")
def test_the_example_renders_through_the_package_the_same_image(tmp_path):
    package = run_example(tmp_path / "package.ppm")
    check_image(package)
    assert package == run_example(tmp_path / "abi.ppm", "--build-dir", str(BUILD))

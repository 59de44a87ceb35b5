"""hitray.abi inside the installed package: the same libhitray instance and
default context as the extension, so a class registered with the defaults
works from hitray.Shape, SDL and rendering, and its failures come out as
hitray.Error with the Python message. Skipped without the package (the
build-tree mode of abi_support)."""

import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from abi_shapes import Ball
from abi_support import MODE, abi

pytestmark = pytest.mark.skipif(MODE != "installed", reason="the hitray package is not installed")


@pytest.fixture(scope="module")
def hitray():
    import hitray

    # Names of their own, so the other test files' classes are not shadowed.
    abi.register_shape("pyball", Ball)

    class Grumpy(Ball):
        def hit(self, origin, direction, tmin, tmax):
            raise ArithmeticError("no rays today")

    abi.register_shape("grumpy", Grumpy)
    return hitray


def test_the_same_library_and_context_as_the_extension(hitray):
    from hitray import _core

    assert os.path.realpath(abi.loaded_library_path()) == os.path.realpath(_core._library_path())
    assert int(abi.ffi.cast("uintptr_t", abi.default_context())) == _core._context_address()
    # The headers read are the ones the package ships.
    assert abi.declarations().headers[0].endswith(os.path.join("include", "hitray", "hitray.h"))


def test_a_registered_class_is_listed_and_usable_by_name(hitray):
    assert "pyball" in hitray.shape_classes()
    scene = hitray.Scene()
    scene.add(hitray.Shape("pyball", radius=2.0).translate(0, 0, -1))
    hit = scene.first_hit((0, 0, 5), (0, 0, -1))
    assert hit.t == pytest.approx(4.0, rel=1e-15) and hit.entering
    assert hit.normal == pytest.approx((0, 0, 1))


def test_surface_names_are_listed_with_the_class(hitray):
    class NamedBall(Ball):
        surface_names = ["skin"]

    abi.register_shape("pynamedball", NamedBall)
    listed = hitray.shape_classes()["pynamedball"]
    assert listed.surface_count == 1 and listed.surface_names == ("skin",)
    assert hitray.shape_classes()["pyball"].surface_names == ()


def test_sdl_and_a_two_thread_render(hitray):
    scene, camera = hitray.parse_sdl(
        "camera 0 0 6  0 0 0  0 1 0  40\nlight 3 3 5  1 1 1\n"
        "push translate -1 0 0 pyball 1 pop\npush translate 1.2 0 0 sphere pop\n")
    one = np.asarray(hitray.render(scene, camera, size=(40, 30), threads=1, progress=False))
    two = np.asarray(hitray.render(scene, camera, size=(40, 30), threads=2, progress=False))
    assert np.array_equal(one, two)
    # The Python ball is drawn: the left half has lit pixels.
    assert one[:, :20].max() > 0.3


def test_scene_trace_on_several_threads(hitray):
    scene = hitray.Scene()
    scene.add(hitray.Shape("pyball", radius=1.0))
    scene.add(hitray.Sphere().translate(3, 0, 0))
    n = 2000
    origins = np.zeros((n, 3))
    origins[:, 0] = np.linspace(-0.5, 3.5, n)
    origins[:, 2] = 5.0
    result = scene.trace(origins, (0.0, 0.0, -1.0), threads=4)
    x = origins[:, 0]
    # Rays at |x| < 1 hit the Python ball at t = 5 - sqrt(1 - x^2); those
    # within 1 of x = 3 the C sphere; the rest miss.
    on_ball = np.abs(x) < 0.999
    expected = 5.0 - np.sqrt(1.0 - x[on_ball] ** 2)
    # The stable roots are good to a few ulps of t ~ 5 away from the rim.
    assert np.allclose(result.t[on_ball], expected, rtol=1e-13, atol=0)
    assert (result.object[on_ball] == 0).all()
    assert (result.object[np.abs(x - 3.0) < 0.999] == 1).all()
    assert (result.object[(x > 1.001) & (x < 1.999)] == -1).all()


def test_a_failing_python_shape_raises_hitray_error_with_its_message(hitray):
    scene, camera = hitray.parse_sdl("camera 0 0 6  0 0 0  0 1 0  40\ngrumpy 1\n")
    with pytest.raises(hitray.Error) as e:
        hitray.render(scene, camera, size=(16, 12), threads=2, progress=False)
    assert "a shape failed while tracing" in str(e.value)
    assert "Grumpy.hit raised ArithmeticError: no rays today" in str(e.value)
    assert isinstance(e.value.__cause__, abi.ShapeError)
    with pytest.raises(hitray.Error, match="no rays today"):
        scene.first_hit((0, 0, 5), (0, 0, -1))


def test_a_refused_create_names_the_parameter(hitray):
    with pytest.raises(hitray.Error) as e:
        hitray.parse_sdl("pyball -1\n")
    assert "radius must be positive, not -1.0" in str(e.value)


def test_objects_left_to_interpreter_exit_are_released_cleanly(tmp_path):
    # Their destroy callbacks run while the interpreter shuts down.
    script = tmp_path / "left.py"
    script.write_text(
        "import sys\n"
        f"sys.path.insert(0, {str(pathlib.Path(__file__).parent)!r})\n"
        "import hitray, hitray.abi\n"
        "from abi_shapes import Ball\n"
        "hitray.abi.register_shape('leftball', Ball)\n"
        "scene, camera = hitray.parse_sdl('camera 0 0 6 0 0 0 0 1 0 40 leftball 1 leftball 2')\n"
        "hitray.render(scene, camera, size=(8, 6), progress=False)\n"
        "cycle = [scene]\n"
        "cycle.append(cycle)\n"
        "print('rendered')\n")
    run = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                         timeout=120)
    assert (run.returncode, run.stdout, run.stderr) == (0, "rendered\n", "")


def test_the_example_of_the_docs_runs(hitray, tmp_path, monkeypatch):
    text = (pathlib.Path(__file__).parents[2] / "docs" / "python-shapes.md").read_text()
    code = text.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "docs/python-shapes.md", "exec"), {"__name__": "docs_example"})
    assert (tmp_path / "ball.png").stat().st_size > 1000

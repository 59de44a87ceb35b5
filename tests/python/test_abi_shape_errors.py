"""Python shapes that fail: every exception and every broken hit becomes an
error status with the Python message, in a query and in a render on several
threads, never a crash; and the lifetime of what the context points at."""

import gc
import math
import weakref

import pytest

from abi_shapes import Ball
from abi_support import (MODE, SceneContext, abi, all_hits, destroy, first_hit, lib, load_sdl,
                         render)


@pytest.fixture
def ctx():
    abi.take_shape_error()  # nothing left over from another test
    with SceneContext() as c:
        yield c


def shape_returning(hits_fn):
    class Returns:
        """returns whatever the test says"""

        def bounds(self):
            return ((-1, -1, -1), (1, 1, 1))

        def hit(self, origin, direction, tmin, tmax):
            return hits_fn(origin, direction, tmin, tmax)

    return Returns


def failing_query(ctx, cls, origin=(0, 0, 5), direction=(0, 0, -1)):
    abi.register_shape("rogue", cls, context=ctx)
    scene, _ = load_sdl(ctx, "rogue\n")
    with pytest.raises(abi.HitrayError) as e:
        first_hit(ctx, scene, origin, direction)
    destroy(scene)
    return e.value


def test_an_exception_in_hit_is_an_error_with_its_message(ctx):
    def divide(origin, direction, tmin, tmax):
        return [(1 / 0, (0, 0, 1), True)]

    e = failing_query(ctx, shape_returning(divide))
    assert e.status == lib.HR_ERROR_MODULE
    assert "a shape failed while tracing" in str(e)
    assert "shape 'rogue': Returns.hit raised ZeroDivisionError: division by zero" in str(e)
    assert isinstance(e.__cause__, abi.ShapeError)
    assert isinstance(e.__cause__.__cause__, ZeroDivisionError)
    assert e.__cause__.__cause__.__traceback__ is not None
    assert abi.take_shape_error() is None  # check took it


@pytest.mark.parametrize("hits, complaint", [
    ([(3.0, (0, 0, 1), True), (2.0, (0, 0, 1), False)], "hits are not sorted by t (3.0 then 2.0)"),
    ([(-1.0, (0, 0, 1), True)], "hit 0 at t=-1.0 is outside (0.0, inf)"),
    ([(0.0, (0, 0, 1), True)], "hit 0 at t=0.0 is outside"),
    ([(math.nan, (0, 0, 1), True)], "hit 0 at t=nan is outside"),
    ([(math.inf, (0, 0, 1), True)], "hit 0 at t=inf is outside"),
    ([(2.0, (0, 0, 0), True)], "has normal (0.0, 0.0, 0.0); it must be finite, non-zero"),
    ([(2.0, (0, math.nan, 1), True)], "has normal (0.0, nan, 1.0)"),
    ([(2.0, (0, 1), True)], "hit 0 must be (t, (nx, ny, nz), entering)"),
    ([(2.0,)], "hit 0 must be (t, (nx, ny, nz), entering)"),
    ([("soon", (0, 0, 1), True)], "hit 0 must be (t, (nx, ny, nz), entering)"),
    # Issue 16: float() and truth values would take these.
    ([("4", (0, 0, 1), True)], "hit 0 must be (t, (nx, ny, nz), entering), not ('4'"),
    ([(True, (0, 0, 1), True)], "hit 0 must be (t, (nx, ny, nz), entering)"),
    ([(2.0, (0, "1", 1), True)], "hit 0 must be (t, (nx, ny, nz), entering)"),
    ([(2.0, (0, 0, 1), "yes")], "hit 0 must be (t, (nx, ny, nz), entering), not (2.0"),
    ([(2.0, (0, 0, 1), None)], "hit 0 must be (t, (nx, ny, nz), entering)"),
    ([(2.0, (0, 0, 1), 2)], "hit 0 must be (t, (nx, ny, nz), entering)"),
    ([(2.0, (0, 0, 1), True, 1)], "hit 0 names surface 1; the class has 0..0"),
    ([(2.0, (0, 0, 1), True, 0.0)], "hit 0 names surface 0.0"),
    ([(1e308, (0, 0, 1), True)], "is beyond double's range"),
    (42, "TypeError"),
])
def test_broken_hits_are_refused_by_name(ctx, hits, complaint):
    e = failing_query(ctx, shape_returning(lambda *a: hits), direction=(0, 0, -10))
    assert e.status == lib.HR_ERROR_MODULE
    assert complaint in str(e)


def test_hits_may_be_any_sequence_and_entering_a_bool_or_0_or_1(ctx):
    abi.register_shape("loose", shape_returning(
        lambda o, d, tmin, tmax: ([1.0, [0, 0, 2], 1], (2, (0, 0, -1), False))), context=ctx)
    scene, _ = load_sdl(ctx, "loose\n")
    assert all_hits(ctx, scene, (0, 0, 5), (0, 0, -1)) == [(1.0, 1, 0), (2.0, 0, 0)]
    destroy(scene)


SCENE = """camera 0 0 6  0 0 0  0 1 0  40
light 4 6 5  1 1 1
push translate -1 0 0 {shape} pop
push translate 1.2 0 0 sphere pop
"""


class FailsAfter:
    """a sphere that raises once it has been asked `limit` times"""

    params = {"limit": 0}

    def __init__(self, limit):
        self.limit = limit
        self.calls = 0
        self.ball = Ball()

    def bounds(self):
        return self.ball.bounds()

    def hit(self, origin, direction, tmin, tmax):
        self.calls += 1
        if self.calls > self.limit:
            raise KeyError(f"call {self.calls}")
        return self.ball.hit(origin, direction, tmin, tmax)


@pytest.mark.parametrize("threads", [1, 2])
def test_an_exception_stops_a_render_on_any_thread(ctx, threads):
    abi.register_shape("fails", FailsAfter, context=ctx)
    scene, camera = load_sdl(ctx, SCENE.format(shape="fails 50"))
    with pytest.raises(abi.HitrayError) as e:
        render(ctx, scene, camera, 64, 48, threads=threads)
    assert e.value.status == lib.HR_ERROR_MODULE
    assert "render: a shape failed while tracing" in str(e.value)
    assert "Fails" in str(e.value) and "raised KeyError: 'call 51'" in str(e.value)
    destroy(scene)


def test_keyboard_interrupt_in_hit_stops_the_render_without_a_crash(ctx):
    class Interrupted(FailsAfter):
        def hit(self, origin, direction, tmin, tmax):
            raise KeyboardInterrupt

    abi.register_shape("interrupted", Interrupted, context=ctx)
    scene, camera = load_sdl(ctx, SCENE.format(shape="interrupted 0"))
    # Raised as itself (an `except HitrayError` must not swallow Ctrl-C),
    # and the next call starts clean.
    with pytest.raises(KeyboardInterrupt):
        render(ctx, scene, camera, 32, 24, threads=2)
    assert abi.take_shape_error() is None
    destroy(scene)


def test_registration_keeps_the_class_and_callbacks_alive(ctx):
    def register():
        class Local(Ball):
            pass

        abi.register_shape("local", Local, context=ctx)
        return weakref.ref(Local)

    ref = register()
    gc.collect()
    assert ref() is not None  # the context still points at its callbacks
    scene, _ = load_sdl(ctx, "local 2\n")
    assert first_hit(ctx, scene, (0, 0, 5), (0, 0, -1))[0] == 3.0
    destroy(scene)


def test_instances_live_as_long_as_their_objects():
    with SceneContext() as c:
        made = []

        class Tracked(Ball):
            def __init__(self, radius=1.0):
                super().__init__(radius)
                made.append(weakref.ref(self))

        abi.register_shape("tracked", Tracked, context=c)
        scene, _ = load_sdl(c, "tracked 1 tracked 2 tracked 3\n")
        gc.collect()
        assert len(made) == 3 and all(r() is not None for r in made)
        destroy(scene)
        # Released by hr_scene_destroy itself, not left to a later collection.
        assert all(r() is None for r in made)
        ref = weakref.ref(Tracked)
        del Tracked
    gc.collect()
    # Closing the context released what its registration kept.
    assert ref() is None


def test_a_later_registration_wins_and_earlier_objects_keep_working(ctx):
    class Small(Ball):
        pass

    class Big(Ball):
        def __init__(self, radius=1.0):
            super().__init__(2 * radius)

    abi.register_shape("grows", Small, context=ctx)
    first, _ = load_sdl(ctx, "grows 1\n")
    abi.register_shape("grows", Big, context=ctx)
    second, _ = load_sdl(ctx, "grows 1\n")
    assert first_hit(ctx, first, (0, 0, 5), (0, 0, -1))[0] == 4.0
    assert first_hit(ctx, second, (0, 0, 5), (0, 0, -1))[0] == 3.0
    destroy(first)
    destroy(second)


@pytest.mark.skipif(MODE == "installed", reason="the package has a default context")
def test_without_the_extension_the_default_context_is_explained():
    with pytest.raises(RuntimeError, match="no default context; pass context="):
        abi.register_shape("nowhere", Ball)


def test_a_closed_context_is_refused():
    c = SceneContext()
    c.close()
    with pytest.raises(ValueError, match="closed"):
        abi.register_shape("late", Ball, context=c)

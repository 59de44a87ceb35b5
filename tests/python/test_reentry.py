"""A Python shape whose hit queries the scene it is part of (issue 16,
defect 1): every query nests one level deeper on the same thread, until the
library refuses the query at HR_MAX_QUERY_NESTING; the refusal travels out
through every level as a ModuleError, whether the outermost call was a
query, a render on one thread or on several, or a render called from hit."""

import subprocess
import sys
import textwrap

import pytest

import hitray
import hitray.abi as abi

LIMIT = 16  # HR_MAX_QUERY_NESTING (include/hitray/scene.h)


class Reentrant:
    """A box whose hit asks the scene for the first hit along the same ray."""

    scene = None
    deepest = 0
    depth = 0
    call = "first_hit"

    def bounds(self):
        return ((-1, -1, -1), (1, 1, 1))

    def hit(self, origin, direction, tmin, tmax):
        cls = type(self)
        cls.depth += 1
        cls.deepest = max(cls.deepest, cls.depth)
        try:
            if cls.call == "first_hit":
                cls.scene.first_hit(origin, direction)
            elif cls.call == "hits":
                cls.scene.hits(origin, direction)
            else:
                hitray.render(cls.scene, size=(2, 2), progress=False, threads=1)
        finally:
            cls.depth -= 1
        return []


def reentrant_scene(call):
    class Shape(Reentrant):
        pass

    Shape.call = call
    name = f"reentrant_{call}"
    abi.register_shape(name, Shape)
    scene = hitray.Scene()
    scene.add(hitray.Shape(name))
    Shape.scene = scene
    return scene, Shape


def innermost(error):
    while error.__cause__ is not None:
        error = error.__cause__
    return error


@pytest.mark.parametrize("call", ["first_hit", "hits", "render"])
def test_a_query_from_hit_is_refused_past_the_nesting_limit(call):
    scene, shape = reentrant_scene(call)
    with pytest.raises(hitray.ModuleError) as e:
        scene.first_hit((0, 0, 5), (0, 0, -1))
    assert isinstance(innermost(e.value), hitray.StateError)
    assert f"nested more than {LIMIT} deep" in str(innermost(e.value))
    assert shape.deepest <= LIMIT


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("call", ["first_hit", "render"])
def test_a_render_whose_shape_queries_the_scene_fails_with_a_module_error(call, threads):
    scene, shape = reentrant_scene(call)
    with pytest.raises(hitray.ModuleError) as e:
        hitray.render(scene, size=(8, 6), progress=False, threads=threads)
    assert "render: a shape failed while tracing" in str(e.value)
    assert f"nested more than {LIMIT} deep" in str(e.value)
    assert shape.deepest <= LIMIT


def test_the_depth_is_bounded_whatever_pythons_recursion_limit():
    """The crash of the issue: with a high recursion limit nothing but the
    library's bound stops the recursion in a render thread (before the
    bound, RSS grew without end, or the render thread crashed under a
    memory limit)."""
    script = textwrap.dedent("""
        import resource, sys
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
        sys.setrecursionlimit(1000000)
        import hitray, hitray.abi as abi
        class Shape:
            def bounds(self): return ((-1, -1, -1), (1, 1, 1))
            def hit(self, o, d, tmin, tmax):
                scene.first_hit(o, d)
                return []
        abi.register_shape("reentrant", Shape)
        scene = hitray.Scene()
        scene.add(hitray.Shape("reentrant"))
        try:
            hitray.render(scene, size=(8, 6), progress=False, threads=2)
        except hitray.ModuleError as e:
            print("ModuleError", "nested more than" in str(e))
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "ModuleError True"

"""Errors from Python: each failure of the library raises a hitray.Error
subclass carrying the library's message; bad Python arguments raise
TypeError/ValueError; nothing crashes the interpreter."""

import math
import subprocess
import sys

import numpy as np
import pytest

import hitray
from conftest import test_module


def test_an_unknown_shape_class_is_a_module_error_naming_it():
    scene = hitray.Scene()
    with pytest.raises(hitray.ModuleError) as err:
        scene.add(hitray.Shape("noSuchShape"))
    assert "no shape module provides 'noSuchShape'" in str(err.value)
    assert err.value.status == 4 and err.value.message == str(err.value)


def test_shape_parameters_are_checked_by_name():
    scene = hitray.Scene()
    with pytest.raises(hitray.ParameterError, match="has no parameter 'radius'"):
        scene.add(hitray.Shape("sphere", radius=2))
    with pytest.raises(hitray.ParameterError, match="parameter 's' = -1 is outside"):
        scene.add(hitray.TaperedCylinder(s=-1))
    with pytest.raises(hitray.ParameterError, match="'s' must be a number, not a string"):
        scene.add(hitray.Shape("taperedCylinder", s="wide"))
    with pytest.raises(hitray.ParameterError, match="finite"):
        scene.add(hitray.TaperedCylinder(s=math.nan))
    assert isinstance(hitray.ParameterError("x"), ValueError)
    assert scene.objects == []


def test_degenerate_transforms_are_numeric_errors():
    with pytest.raises(hitray.NumericError, match="scale"):
        hitray.Sphere().scale(1, 0, 1)
    with pytest.raises(hitray.NumericError, match="axis"):
        hitray.Sphere().rotate(30, 0, 0, 0)
    with pytest.raises(hitray.NumericError):
        hitray.Sphere().scale(1e200).scale(1e200)
    with pytest.raises(TypeError):
        hitray.Sphere().translate(1, 2)
    with pytest.raises(TypeError):
        hitray.Sphere().scale(1, 2)


def test_a_module_built_for_another_abi_is_refused_naming_its_path():
    path = test_module("wrong_abi")
    with pytest.raises(hitray.ModuleError) as err:
        hitray.load_module(path)
    assert str(path) in str(err.value) and "ABI version" in str(err.value)
    with pytest.raises(hitray.ModuleError, match="no entry point"):
        hitray.load_module(test_module("no_entry"))
    with pytest.raises(hitray.ModuleError, match="cannot load"):
        hitray.load_module("/nonexistent/module.so")


def test_a_module_loaded_by_path_provides_classes_with_string_parameters():
    hitray.load_module(test_module("probe"))
    probe = hitray.shape_classes()["probeSphere"]
    assert probe.module == str(test_module("probe"))
    assert [p.name for p in probe.params] == ["radius", "refuse", "label"]
    assert [p.type for p in probe.params] == ["number", "number", "string"]
    scene = hitray.Scene()
    scene.add(hitray.Shape("probeSphere", radius=2, label="anything at all"))
    assert scene.first_hit((0, 0, 5), (0, 0, -1)).t == pytest.approx(3.0, abs=1e-12)
    # A refusal from the module's own create names the class and module.
    with pytest.raises(hitray.ParameterError, match="probe refuses") as err:
        scene.add(hitray.Shape("probeSphere", refuse=1))
    assert str(test_module("probe")) in str(err.value)
    with pytest.raises(hitray.ParameterError, match="must be a string"):
        scene.add(hitray.Shape("probeSphere", label=3))
    # The module's class is an SDL keyword too, on the same context.
    sdl_scene, _ = hitray.parse_sdl("probeSphere 1.5 0 some_label")
    assert sdl_scene.objects[0].shape == "probeSphere"


def test_modules_lists_what_the_search_path_holds():
    listing = hitray.modules()
    sphere = [m for m in listing if "sphere" in m.classes]
    assert sphere and sphere[0].loaded and sphere[0].error == ""


def test_every_error_is_a_hitray_error():
    for cls in (hitray.SDLError, hitray.ModuleError, hitray.ParameterError, hitray.ArgumentError,
                hitray.FileError, hitray.NumericError, hitray.StateError, hitray.UnsupportedError):
        assert issubclass(cls, hitray.Error)


CHILD = r"""
import math
from itertools import product

import numpy as np

import hitray

# Values that are wrong in every way a caller can get them wrong.
BAD = [None, "x", b"x", [], [1], [1, 2, 3, 4], math.nan, math.inf, -math.inf, 1e308, -1, 0,
       2**70, object(), np.zeros((2, 2)), (math.nan, 0, 0), True, "a\0b"]
calls = [
    lambda v: hitray.Scene().add(hitray.Sphere(), diffuse=v),
    lambda v: hitray.Scene().add(hitray.Sphere(), reflectivity=v),
    lambda v: hitray.Scene().add(hitray.Sphere(), parameters=v),
    lambda v: hitray.Scene().add(hitray.Shape("taperedCylinder", s=v)),
    lambda v: hitray.Scene().add(v),
    lambda v: hitray.Scene().light(v, v),
    lambda v: setattr(hitray.Scene(), "background", v),
    lambda v: setattr(hitray.Scene(), "max_recursion_depth", v),
    lambda v: hitray.Sphere().translate(v, 0, 0),
    lambda v: hitray.Sphere().scale(v),
    lambda v: hitray.Sphere().rotate(v, 1, 0, 0),
    lambda v: hitray.Sphere().transform(v),
    lambda v: hitray.Shape(v),
    lambda v: hitray.Camera(v, (0, 0, 0), (0, 1, 0), 45),
    lambda v: hitray.Camera((0, 0, 5), (0, 0, 0), (0, 1, 0), v).ray(0, 0),
    lambda v: hitray.render(hitray.Scene(), size=v, progress=False),
    lambda v: hitray.render(hitray.Scene(), size=(4, 4), spp=v, progress=False),
    lambda v: hitray.render(hitray.Scene(), size=(4, 4), threads=v, progress=False),
    lambda v: hitray.render(hitray.Scene(), size=(4, 4), depth=v, progress=False),
    lambda v: hitray.render(hitray.Scene(), v, size=(4, 4), progress=False),
    lambda v: hitray.Scene().first_hit(v, (0, 0, 1)),
    lambda v: hitray.Scene().first_hit((0, 0, 0), (0, 0, 1), tmin=v),
    lambda v: hitray.Scene().hits((0, 0, 0), v),
    lambda v: hitray.Scene().trace(v, v),
    lambda v: hitray.Scene().shade((0, 0, 5), (0, 0, -1), depth=v),
    lambda v: hitray.load_sdl(v),
    lambda v: hitray.parse_sdl(v),
    lambda v: hitray.Image(v),
    lambda v: hitray.Image(np.zeros((2, 2, 3))).save(v),
    lambda v: hitray.load_module(v),
]
accepted = 0
for call, value in product(calls, BAD):
    try:
        call(value)
        accepted += 1
    except (TypeError, ValueError, OSError, hitray.Error):
        pass
print("survived", len(calls) * len(BAD), "calls;", accepted, "accepted")
"""


def test_bad_values_anywhere_raise_instead_of_crashing(tmp_path):
    # In a child process: a crash there is a failing test, not a dead run.
    result = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True,
                            timeout=300, cwd=tmp_path)
    assert result.returncode == 0, result.stderr[-3000:]
    assert "survived" in result.stdout, result.stdout

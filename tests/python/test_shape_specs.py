"""The convenience shape classes of hitray.shapes (Sphere, Torus, ...) are
written out by hand; each must match the parameter spec its shape class
gives (hr_param_spec, read through hitray.shape_classes()), so that a
parameter added, renamed or dropped in C fails here rather than drift. Their
docstrings point to `hitray shapes` for defaults and ranges rather than
repeat numbers that would go stale."""

import inspect
import re

import pytest

import hitray
from hitray import shapes

# A convenience class whose keyword arguments are not the class's own
# parameters: Mesh's arrays reach the triangleMesh class under the library's
# names (vertices -> points, faces -> triangles).
MESH_ARRAYS = {"vertices": "points", "faces": "triangles", "normals": "normals"}

CONVENIENCE = [getattr(shapes, name) for name in shapes.__all__ if name != "Shape"]


def _class_name(cls):
    """The shape class a convenience class makes, by building one."""
    if issubclass(cls, shapes._Boolean):
        return cls(shapes.Sphere(), shapes.Cube())._name
    if cls is shapes.Mesh:
        return cls("unused.obj")._name
    return cls()._name


def _arguments(cls):
    return [p for p in inspect.signature(cls.__init__).parameters.values() if p.name != "self"]


@pytest.mark.parametrize("cls", CONVENIENCE, ids=lambda c: c.__name__)
def test_arguments_are_the_spec(cls):
    specs = hitray.shape_classes()
    name = _class_name(cls)
    assert name in specs, f"{cls.__name__} makes '{name}', which no module provides"
    args = _arguments(cls)
    spec_names = [p.name for p in specs[name].params]
    if cls is shapes.Mesh:
        assert [a.name for a in args][:1] == spec_names
        assert [MESH_ARRAYS[a.name] for a in args[1:]] == [p.name for p in specs["triangleMesh"].params]
        return
    assert [a.name for a in args] == spec_names, (
        f"{cls.__name__}'s arguments are not {name}'s parameters (hitray shapes)")
    if not issubclass(cls, shapes._Boolean):
        # None: the library's default, never a copy of it in Python.
        assert all(a.default is None for a in args), f"{cls.__name__} repeats a default"


@pytest.mark.parametrize("cls", [c for c in CONVENIENCE if not issubclass(c, shapes._Boolean)
                                 and c is not shapes.Mesh and _arguments(c)], ids=lambda c: c.__name__)
def test_docstring_points_to_the_spec(cls):
    doc = " ".join(cls.__doc__.split())
    assert "hitray shapes" in doc, f"{cls.__name__}'s docstring should point to `hitray shapes`"
    specs = hitray.shape_classes()[_class_name(cls)]
    for p in specs.params:
        if isinstance(p.default, float) and p.default:
            shown = re.escape(f"{p.default:g}")
            assert not re.search(rf"(?<![\d.]){shown}(?![\d.]) if omitted", doc), (
                f"{cls.__name__}'s docstring repeats {p.name}'s default")

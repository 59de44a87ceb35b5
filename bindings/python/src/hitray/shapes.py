"""Shapes: a class name, its parameters, a transform and optional material.

A :class:`Shape` is a value: every method returns a new shape and leaves the
one it was called on alone, so one shape may be added many times or used in
several booleans. :meth:`Scene.add` makes new objects in the scene from the
shape each time it is called (a boolean's operands too), so nothing is shared
between two additions: using a shape twice is adding a copy twice.

Transforms chain in Hill's (and OpenGL's) order: each call post-multiplies,
so ``Sphere().translate(2, 4, 9).scale(1, 4, 4)`` has M = T·S, exactly as the
SDL ``translate 2 4 9 scale 1 4 4 sphere`` does (the step written last acts on
the object first), and the matrices come from the same library calls, bit
for bit.
"""

from __future__ import annotations

import os
import typing
from typing import Any, Dict, Mapping, Optional, Tuple

import numpy as np

from . import _convert, _core, material as _material

ParamValue = typing.Union[float, int, str, "os.PathLike[str]", bytes, "Shape", np.ndarray]

__all__ = [
    "Shape", "Sphere", "Cube", "Square", "Plane", "TaperedCylinder", "Cylinder", "Cone",
    "Torus", "Mesh", "Tetrahedron", "Octahedron", "Dodecahedron", "Icosahedron", "Buckyball",
    "Teapot", "Union", "Intersection", "Difference",
]


def _numbers(value: Any, what: str) -> np.ndarray:
    """An array parameter as the library takes it: float64, contiguous and
    flat. One copy in C (never a Python loop over the elements), made
    read-only, so the shape stays a value whatever the caller does to the
    array afterwards."""
    try:
        out = np.array(value, dtype=np.float64, order="C", copy=True).reshape(-1)
    except (TypeError, ValueError) as e:
        raise TypeError(f"{what}: expected an array of numbers ({e})") from None
    out.flags.writeable = False
    return out


def _format_number(x: float) -> str:
    return repr(int(x)) if float(x).is_integer() and abs(x) < 1e15 else repr(float(x))


class Shape:
    """Any shape class a module provides, by name: ``Shape("disk", radius=2)``.

    Parameters are the class's own (see :func:`hitray.shape_classes`): a
    number for a number parameter, a string or path for a string parameter
    (a mesh's ``file``), a Shape for an object parameter (a boolean's ``a``
    and ``b``). The class and parameters are checked when the shape is added
    to a scene, by the module itself, through the package's context (so a
    class registered later with :mod:`hitray.abi` works here too).
    """

    __slots__ = ("_name", "_params", "_transform", "_material", "_steps")

    def __init__(self, name: str, **params: Optional[ParamValue]) -> None:
        if not isinstance(name, str) or not name:
            raise TypeError(f"shape name: expected a non-empty string, got {name!r}")
        checked: Dict[str, ParamValue] = {}
        for key, value in params.items():
            if value is None:
                continue  # None: the class's default
            if isinstance(value, Shape):
                checked[key] = value
            elif _convert.is_number(value):
                checked[key] = _convert.as_float(value, f"shape '{name}': parameter '{key}'")
            elif isinstance(value, (str, bytes, os.PathLike)):
                checked[key] = value
            elif isinstance(value, np.ndarray):
                checked[key] = _numbers(value, f"shape '{name}': parameter '{key}'")
            else:
                raise TypeError(f"shape '{name}': parameter '{key}' must be a number, a string, "
                                f"a numpy array or a Shape, not {type(value).__name__}")
        self._name = name
        self._params = checked
        self._transform = _core.Transform()
        self._material: Dict[str, Any] = {}
        self._steps: Tuple[str, ...] = ()

    # --- what the shape is --------------------------------------------------
    @property
    def name(self) -> str:
        """The shape class name (as in SDL and the C API)."""
        return self._name

    @property
    def params(self) -> Mapping[str, ParamValue]:
        """The parameters given (a copy); omitted ones take the class's defaults."""
        return dict(self._params)

    @property
    def material(self) -> Mapping[str, Any]:
        """Material set on this shape with :meth:`with_material` (snake_case names)."""
        return dict(self._material)

    @property
    def matrix(self) -> np.ndarray:
        """The object-to-world matrix M (4x4, acting on column vectors)."""
        return np.array(self._transform.matrix, dtype=np.float64).reshape(4, 4)

    @property
    def inverse(self) -> np.ndarray:
        """M⁻¹, built from the exact inverse of each step (never by inverting M)."""
        return np.array(self._transform.inverse, dtype=np.float64).reshape(4, 4)

    # --- new shapes from this one -------------------------------------------
    def _derive(self, step: str) -> "Shape":
        out = object.__new__(type(self))
        out._name = self._name
        out._params = self._params
        out._transform = self._transform.copy()
        out._material = self._material
        out._steps = self._steps + (step,)
        return out

    def translate(self, dx: float, dy: float, dz: float) -> "Shape":
        """This shape moved by (dx, dy, dz): M ← M·T."""
        d = _convert.vec3((dx, dy, dz), "translate")
        out = self._derive("translate(%s)" % ", ".join(map(_format_number, d)))
        out._transform.translate(*d)
        return out

    def scale(self, sx: float, sy: Optional[float] = None, sz: Optional[float] = None) -> "Shape":
        """This shape scaled: M ← M·S. One factor scales uniformly. A zero
        factor raises NumericError (the object would have no inverse)."""
        if sy is None and sz is None:
            sy = sz = sx
        if sy is None or sz is None:
            raise TypeError("scale: give one factor or three")
        s = _convert.vec3((sx, sy, sz), "scale")
        out = self._derive("scale(%s)" % ", ".join(map(_format_number, s)))
        out._transform.scale(*s)
        return out

    def rotate(self, angle: float, ux: float, uy: float, uz: float) -> "Shape":
        """This shape rotated by `angle` degrees, right-handed, about the axis
        (ux, uy, uz): M ← M·R. A zero axis raises NumericError."""
        a = _convert.number(angle, "rotate angle")
        u = _convert.vec3((ux, uy, uz), "rotate axis")
        out = self._derive("rotate(%s)" % ", ".join(map(_format_number, (a, *u))))
        out._transform.rotate(a, *u)
        return out

    def transform(self, matrix: Any) -> "Shape":
        """This shape under an arbitrary affine 4x4 matrix: M ← M·A (A's
        inverse is computed; a singular or non-affine A raises NumericError)."""
        a = np.asarray(matrix, dtype=np.float64)
        if a.shape != (4, 4):
            raise ValueError(f"transform: expected a 4x4 matrix, got shape {a.shape}")
        step = _core.Transform.from_matrix([float(v) for v in a.reshape(16)])
        out = self._derive("transform(...)")
        out._transform.compose(step)
        return out

    def with_material(self, **material: Any) -> "Shape":
        """This shape with its own material (SDL's keywords, as for
        :meth:`Scene.add`). It wins over the material given to ``add``; the
        leaves of a boolean keep their own, as in SDL."""
        fields = _material.normalize(material)
        out = self._derive("with_material(%s)" % ", ".join(f"{k}={v!r}" for k, v in material.items()))
        out._material = {**self._material, **fields}
        return out

    # --- booleans (the csg module's classes) ---------------------------------
    def __or__(self, other: "Shape") -> "Shape":
        """``a | b``: the union of a and b."""
        return Union(self, other) if isinstance(other, Shape) else NotImplemented

    def __and__(self, other: "Shape") -> "Shape":
        """``a & b``: the intersection of a and b."""
        return Intersection(self, other) if isinstance(other, Shape) else NotImplemented

    def __sub__(self, other: "Shape") -> "Shape":
        """``a - b``: a with b taken away."""
        return Difference(self, other) if isinstance(other, Shape) else NotImplemented

    def _repr_head(self) -> str:
        args = [repr(self._name)] + [f"{k}={v!r}" for k, v in self._params.items()]
        return f"Shape({', '.join(args)})"

    def __repr__(self) -> str:
        return ".".join((self._repr_head(),) + self._steps)


class Sphere(Shape):
    """Hill's generic sphere: radius 1 at the origin."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("sphere")

    def _repr_head(self) -> str:
        return "Sphere()"


class Cube(Shape):
    """Hill's generic cube: corners at (±1, ±1, ±1)."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("cube")

    def _repr_head(self) -> str:
        return "Cube()"


class Square(Shape):
    """The square z = 0, |x| ≤ 1, |y| ≤ 1."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("square")

    def _repr_head(self) -> str:
        return "Square()"


class Plane(Shape):
    """The whole plane z = 0."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("plane")

    def _repr_head(self) -> str:
        return "Plane()"


class TaperedCylinder(Shape):
    """Axis +z from z = 0 to 1, radius 1 at the base and `s` at the cap
    (base and cap disks belong to the solid). `s`'s default and range:
    ``hitray shapes`` (or ``hitray.shape_classes()["taperedCylinder"]``)."""

    __slots__ = ()

    def __init__(self, s: Optional[float] = None) -> None:
        super().__init__("taperedCylinder", s=s)

    def _repr_head(self) -> str:
        s = self._params.get("s")
        return "TaperedCylinder()" if s is None else f"TaperedCylinder(s={s!r})"


class Cylinder(Shape):
    """taperedCylinder with s = 1."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("cylinder")

    def _repr_head(self) -> str:
        return "Cylinder()"


class Cone(Shape):
    """taperedCylinder with s = 0 (apex at (0, 0, 1))."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("cone")

    def _repr_head(self) -> str:
        return "Cone()"


class Torus(Shape):
    """A ring of radius 1 in the xy-plane about the z axis with tube radius
    `tube`; `solver` picks the quartic root solver. The parameters' defaults,
    ranges and the solvers: ``hitray shapes`` (or
    ``hitray.shape_classes()["torus"]``)."""

    __slots__ = ()

    def __init__(self, tube: Optional[float] = None, solver: Optional[str] = None) -> None:
        super().__init__("torus", tube=tube, solver=solver)

    def _repr_head(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self._params.items())
        return f"Torus({args})"


class Mesh(Shape):
    """A triangle mesh, from a file or from arrays.

    ``Mesh(file)`` reads the file when added: Wavefront OBJ if the name ends
    in .obj, Hill's chapter-6 format otherwise; a relative name is taken from
    the current directory at the time of ``Scene.add``.

    ``Mesh(vertices=V, faces=F, normals=N)`` takes the arrays trimesh and
    Open3D hold a mesh in: V an (n, 3) array of points, F an (m, 3) array of
    vertex indices from 0, N (optional) an (n, 3) array of shading normals,
    one per vertex. They reach the mesh module's ``triangleMesh`` class as
    array parameters, each copied once (in C, as float64) and never touched
    per triangle by Python; the module checks every index against the
    vertex count and builds the same watertight mesh as from a file.
    """

    __slots__ = ()

    def __init__(self, file: typing.Union[str, "os.PathLike[str]", bytes, None] = None, *,
                 vertices: Any = None, faces: Any = None, normals: Any = None) -> None:
        if file is not None:
            if vertices is not None or faces is not None or normals is not None:
                raise TypeError("Mesh: give a file or vertices and faces, not both")
            super().__init__("mesh", file=file)
            return
        if vertices is None or faces is None:
            raise TypeError("Mesh: give a file, or vertices=(n, 3) and faces=(m, 3) arrays")
        arrays: Dict[str, ParamValue] = {
            "points": _rows_of_three(vertices, "vertices"),
            "triangles": _rows_of_three(faces, "faces", integral=True)}
        if normals is not None:
            arrays["normals"] = _rows_of_three(normals, "normals")
        super().__init__("triangleMesh")
        self._params = arrays  # already the library's form: no second copy

    def _repr_head(self) -> str:
        if "file" in self._params:
            return f"Mesh({self._params['file']!r})"
        counts = {k: int(np.asarray(v).size) // 3 for k, v in self._params.items()}
        parts = [f"vertices=<{counts['points']} points>", f"faces=<{counts['triangles']} triangles>"]
        if "normals" in counts:
            parts.append(f"normals=<{counts['normals']} normals>")
        return f"Mesh({', '.join(parts)})"


def _rows_of_three(value: Any, name: str, integral: bool = False) -> np.ndarray:
    """An (n, 3) array (or anything numpy reads as one) for Mesh."""
    a = np.asarray(value)
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"Mesh: {name} must be an (n, 3) array, not of shape {a.shape}")
    if integral and a.size and a.dtype.kind not in "iu":
        raise TypeError(f"Mesh: {name} must hold integer vertex indices, not {a.dtype}")
    if not integral and a.dtype.kind not in "fiu":
        raise TypeError(f"Mesh: {name} must hold numbers, not {a.dtype}")
    return _numbers(a, f"Mesh: {name}")


class Tetrahedron(Shape):
    """The regular tetrahedron, vertices on the unit sphere."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("tetrahedron")

    def _repr_head(self) -> str:
        return "Tetrahedron()"


class Octahedron(Shape):
    """The regular octahedron, vertices at (±1, 0, 0), (0, ±1, 0), (0, 0, ±1)."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("octahedron")

    def _repr_head(self) -> str:
        return "Octahedron()"


class Dodecahedron(Shape):
    """The regular dodecahedron, vertices on the unit sphere."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("dodecahedron")

    def _repr_head(self) -> str:
        return "Dodecahedron()"


class Icosahedron(Shape):
    """The regular icosahedron, vertices on the unit sphere."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("icosahedron")

    def _repr_head(self) -> str:
        return "Icosahedron()"


class Buckyball(Shape):
    """The truncated icosahedron (12 pentagons, 20 hexagons), vertices on the
    unit sphere: Hill's ``buckyball``."""

    __slots__ = ()

    def __init__(self) -> None:
        super().__init__("buckyball")

    def _repr_head(self) -> str:
        return "Buckyball()"


class Teapot(Shape):
    """Newell's teapot, tessellated from its 32 Bezier patches with smooth
    normals: `tessellation` steps along each side of a patch, n, giving
    64 n² - 8 n triangles (its default and range: ``hitray shapes``). The size of
    glutSolidTeapot(1.0), as Hill drew it: y up, the base at y = -0.75, the
    handle towards -x, the spout towards +x. An open surface, as Newell made
    it (the lid sits in the rim with a gap)."""

    __slots__ = ()

    def __init__(self, tessellation: Optional[int] = None) -> None:
        super().__init__("teapot", tessellation=tessellation)

    def _repr_head(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self._params.items())
        return f"Teapot({args})"


class _Boolean(Shape):
    __slots__ = ()
    _class = ""
    _symbol = ""

    def __init__(self, a: Shape, b: Shape) -> None:
        if not isinstance(a, Shape) or not isinstance(b, Shape):
            raise TypeError(f"{type(self).__name__}: both operands must be Shapes")
        super().__init__(self._class, a=a, b=b)

    def _repr_head(self) -> str:
        return f"({self._params['a']!r} {self._symbol} {self._params['b']!r})"


class Union(_Boolean):
    """``a | b``: points in a or in b (the csg module's ``union``)."""

    __slots__ = ()
    _class = "union"
    _symbol = "|"


class Intersection(_Boolean):
    """``a & b``: points in both a and b (the csg module's ``intersection``)."""

    __slots__ = ()
    _class = "intersection"
    _symbol = "&"


class Difference(_Boolean):
    """``a - b``: points in a and not in b (the csg module's ``difference``)."""

    __slots__ = ()
    _class = "difference"
    _symbol = "-"

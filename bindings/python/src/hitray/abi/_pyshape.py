"""Shape classes written in Python, behind the same vtable as a C module.

`register_shape(name, cls)` builds an hr_shape_class whose create, destroy,
bounds and hit are cffi callbacks into `cls`, and registers it on a context
with hr_context_register_shape_class. From then on the name works like any
module's class: hr_scene_add_object, SDL (the name is an object keyword with
positional parameters in declared order), hitray.Shape(name), rendering.

The class:
- `cls(**params)` makes an instance (see _params for what params are);
- `bounds(self)` returns ``((xmin, ymin, zmin), (xmax, ymax, zmax))`` in object
  space, or None for an unbounded shape (infinite bounds, as the plane
  reports); it is asked once, at create time, and must not change;
- `hit(self, origin, direction, tmin, tmax)` returns every hit with
  tmin < t < tmax as a list of ``(t, (nx, ny, nz), entering)`` sorted by t
  (a fourth element, if present, is the surface id); t and the normal are
  numbers (int or float, numpy's too; not strings), the normal points
  outward, any non-zero length; ``entering`` is True where the ray enters
  the solid (a bool, or 0 or 1);
- optional class attributes: ``closed`` (True for a solid whose entering flags
  alternate: HR_SHAPE_CLOSED, CSG-able), ``surface_count`` (default 1, or
  the number of ``surface_names``), ``surface_names`` (a name for each
  surface id, as hitray.shape_classes() and `hitray shapes` show them:
  hr_shape_class.surface_names; default none, surfaces known by number),
  ``help`` (default: the first line of the docstring) and
  ``hit_relative_error`` (how far the computed t may be from the true one,
  relative: the error bound of each hit point is this times
  ``max|origin| + |t| * max|direction|``; default 1e-9, loose enough for a
  closed-form root computed in double precision).

Every callback holds the GIL (cffi takes it on entry, from whichever render
thread calls), catches every exception, and returns a status instead:
create refuses with HR_ERROR_PARAMETER and the exception's text in the
message the host prints; hit returns HR_ERROR_MODULE and the exception is
kept for hitray.abi.check / take_shape_error. Hits are checked before the
host sees them (finite, strictly inside (tmin, tmax), sorted, non-zero
normal); a violation is a ShapeError the same way.
"""

from __future__ import annotations

import inspect
import math
import numbers
import re
import struct
import threading
from typing import Any, Callable, Dict, List, Tuple

from ._context import keep_alive, resolve
from ._errors import ShapeError, record_shape_error
from ._library import load
from ._params import NUMBER, class_params

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*$")
Box = Tuple[float, float, float, float, float, float]  # xmin, ymin, zmin, xmax, ymax, zmax
_UNBOUNDED: Box = (-math.inf, -math.inf, -math.inf, math.inf, math.inf, math.inf)
DEFAULT_HIT_RELATIVE_ERROR = 1e-9

# hr_hit as written from Python: t, point, normal, error, surface, entering,
# object. Checked against the cffi layout (itself checked against the C
# compiler's by the tests) when the first class is registered.
_HIT = struct.Struct("=8d2iq")
_HIT_FIELDS = ("t", "point", "normal", "error", "surface", "entering", "object")
_HIT_OFFSETS = (0, 8, 32, 56, 64, 68, 72)
# hr_hit_args as read: shape, ray (origin, dir), tmin, tmax, out, call; the
# fields appended after call (struct_size) are not read, so the struct may be
# longer than this.
_ARGS = struct.Struct("=Q8dQQ")
_ARGS_FIELDS = ("shape", "ray", "tmin", "tmax", "out", "call")
_ARGS_OFFSETS = (0, 8, 56, 64, 72, 80)


class _Instance:
    """One object's shape: the Python instance, its bound hit and bounds."""

    __slots__ = ("obj", "hit", "bounds", "label", "handle")  # handle: see create

    def __init__(self, obj: Any, hit: Callable[..., Any], bounds: Box, label: str) -> None:
        self.obj = obj
        self.hit = hit
        self.bounds = bounds
        self.label = label
        self.handle: Any = None


class _Registration:
    """Everything one registered class needs alive: the C tables, their
    strings, the callbacks, and the live instances (by handle address)."""

    def __init__(self, name: str, cls: type) -> None:
        self.name = name
        self.cls = cls
        self.label = cls.__name__
        self.origin = f"python:{getattr(cls, '__module__', '?')}.{cls.__qualname__}"
        self.specs = class_params(cls)
        self.closed = bool(getattr(cls, "closed", False))
        self.surface_names = _surface_names(cls)
        self.surface_count = _positive_int(cls, "surface_count", len(self.surface_names) or 1)
        if self.surface_names and len(self.surface_names) != self.surface_count:
            raise ValueError(f"shape class {cls.__qualname__}: {len(self.surface_names)} "
                             f"surface_names for surface_count {self.surface_count}")
        self.relative_error = _relative_error(cls)
        self.host: Any = None     # the context's hr_host, seen at the first create
        # shape pointer -> _Instance (which owns the pointed-at byte)
        self.live: Dict[int, _Instance] = {}
        self.live_lock = threading.Lock()
        self.c_strings: List[Any] = []
        self.c_params: Any = None
        self.c_surface_names: Any = None
        self.c_class: Any = None
        self.callbacks: Tuple[Any, ...] = ()


def _positive_int(cls: type, attr: str, default: int) -> int:
    value = getattr(cls, attr, default)
    if isinstance(value, bool) or not isinstance(value, int) or value < 1 or value > 2**31 - 1:
        raise ValueError(f"shape class {cls.__qualname__}: {attr} must be a positive integer, "
                         f"not {value!r}")
    return int(value)


def _surface_names(cls: type) -> Tuple[str, ...]:
    names = getattr(cls, "surface_names", ())
    if isinstance(names, (str, bytes)) or not isinstance(names, (list, tuple)) or \
            not all(isinstance(n, str) and n and "\0" not in n for n in names):
        raise ValueError(f"shape class {cls.__qualname__}: surface_names must be a list or "
                         f"tuple of non-empty strings, not {names!r}")
    return tuple(names)


def _relative_error(cls: type) -> float:
    value = getattr(cls, "hit_relative_error", DEFAULT_HIT_RELATIVE_ERROR)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or \
            not math.isfinite(value) or value < 0:
        raise ValueError(f"shape class {cls.__qualname__}: hit_relative_error must be a "
                         f"finite number >= 0, not {value!r}")
    return float(value)


def _help_line(cls: type) -> str:
    text = getattr(cls, "help", None)
    if text is None:
        doc = inspect.getdoc(cls) or ""
        text = doc.splitlines()[0] if doc else f"a shape written in Python ({cls.__qualname__})"
    if not isinstance(text, str):
        raise ValueError(f"shape class {cls.__qualname__}: help must be a string")
    return text


def _check_layout(ffi: Any) -> None:
    # hr_hit is written whole (its size must match); hr_hit_args only read.
    for name, fields, offsets, packed, exact in (
            ("hr_hit", _HIT_FIELDS, _HIT_OFFSETS, _HIT, True),
            ("hr_hit_args", _ARGS_FIELDS, _ARGS_OFFSETS, _ARGS, False)):
        got = tuple(ffi.offsetof(name, f) for f in fields)
        size = ffi.sizeof(name)
        if got != offsets or (size != packed.size if exact else size < packed.size) \
                or ffi.sizeof("void *") != 8:
            raise RuntimeError(f"hitray.abi: {name}'s layout {got} (size {ffi.sizeof(name)}) "
                               f"is not the one this module reads and writes {offsets}")


def _check_bounds(value: Any, label: str) -> Box:
    """((lo), (hi)) as 6 floats, or infinities for None."""
    if value is None:
        return _UNBOUNDED
    try:
        (x0, y0, z0), (x1, y1, z1) = value
        box = (float(x0), float(y0), float(z0), float(x1), float(y1), float(z1))
    except (TypeError, ValueError) as e:
        raise ShapeError(f"{label}.bounds() must return ((xmin, ymin, zmin), (xmax, ymax, "
                         f"zmax)) or None, not {value!r}") from e
    if any(math.isnan(v) for v in box) or not all(box[i] <= box[i + 3] for i in range(3)):
        raise ShapeError(f"{label}.bounds() returned {value!r}: each min must be <= its max "
                         "and none may be NaN")
    return box


def _describe(exc: BaseException) -> str:
    text = str(exc)
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def _make_callbacks(reg: _Registration, ffi: Any, lib: Any) -> Tuple[Any, Any, Any, Any]:
    hr_ok = 0
    error_module = int(lib.HR_ERROR_MODULE)
    error_parameter = int(lib.HR_ERROR_PARAMETER)
    NULL = ffi.NULL
    def new_token() -> Any:
        return ffi.new("char[1]")

    buffer, cast, string = ffi.buffer, ffi.cast, ffi.string
    specs = reg.specs
    rel = reg.relative_error
    surfaces = reg.surface_count
    pack_into = _HIT.pack_into
    unpack_args = _ARGS.unpack_from
    memmove = ffi.memmove
    instances = reg.live
    live_lock = reg.live_lock
    uintptr = ffi.typeof("uintptr_t")
    as_int = int
    hit_size = _HIT.size
    isfinite = math.isfinite
    cls = reg.cls
    real = numbers.Real

    def number(value: Any) -> float:
        # float() would take "4" and True: a hit's numbers must be numbers.
        if value.__class__ is float:
            return value
        if isinstance(value, bool) or not isinstance(value, real):
            raise TypeError(f"{value!r} is not a number")
        return float(value)

    def flag(value: Any) -> int:
        # Any truth value would let "no" mean entering: a flag is a bool
        # (Python's or numpy's) or the integer 0 or 1.
        if value is True or value is False:
            return 1 if value else 0
        if (isinstance(value, int) and value in (0, 1)) or type(value).__name__ == "bool_":
            return 1 if value else 0
        raise TypeError(f"entering must be True or False, not {value!r}")

    def fail(where: str, exc: BaseException) -> ShapeError:
        """Keep the error for whoever checks the failed call."""
        if isinstance(exc, ShapeError):
            error = exc
        else:
            error = ShapeError(f"{where} raised {_describe(exc)}")
            error.__cause__ = exc
        record_shape_error(error)
        return error

    def create(args: Any, out_shape: Any) -> int:
        try:
            reg.host = args.host
            kwargs: Dict[str, Any] = {}
            params = args.params
            for i, spec in enumerate(specs):
                p = params[i]
                text = ""
                if spec.kind != NUMBER and p.string != NULL:
                    text = string(p.string).decode("utf-8", "surrogateescape")
                kwargs[spec.name] = spec.to_python(p.number, text)
            # The host's message names the shape and its origin already.
            label = reg.label
            try:
                obj = cls(**kwargs)
            except BaseException as e:
                raise ShapeError(f"{reg.label}(**params) raised {_describe(e)}") from e
            try:
                box = _check_bounds(obj.bounds(), label)
            except ShapeError:
                raise
            except BaseException as e:
                raise ShapeError(f"{label}.bounds() raised {_describe(e)}") from e
            hit = getattr(obj, "hit", None)
            if not callable(hit):
                raise ShapeError(f"{label} has no hit(origin, direction, tmin, tmax) method")
            inst = _Instance(obj, hit, box, f"shape '{reg.name}': {reg.label}")
            # The shape pointer the host keeps is a byte of our own, unique
            # while the instance lives; the callbacks find the instance by it.
            inst.handle = new_token()
            with reg.live_lock:
                reg.live[int(cast("uintptr_t", inst.handle))] = inst
            out_shape[0] = inst.handle
            return hr_ok
        except BaseException as e:
            error = fail(f"{reg.label}(**params)", e)
            message = str(error).encode("utf-8", "replace")[: max(int(args.error_size) - 1, 0)]
            if args.error != NULL and args.error_size > 0:
                buffer(args.error, len(message) + 1)[:] = message + b"\0"
            return error_parameter

    def destroy(shape: Any) -> None:
        # May run while the interpreter exits (a scene freed by the last
        # collection): only names bound here, and nothing may escape.
        try:
            with live_lock:
                instances.pop(as_int(cast(uintptr, shape)), None)
        except BaseException:
            pass

    def bounds(shape: Any, out: Any) -> None:
        try:
            box = instances[int(cast("uintptr_t", shape))].bounds
        except BaseException as e:  # not ours: a host bug; say unbounded, never crash
            fail(f"{reg.name}.bounds", e)
            box = _UNBOUNDED
        out.lo.x, out.lo.y, out.lo.z, out.hi.x, out.hi.y, out.hi.z = box

    def hit(args: Any) -> int:
        try:
            shape, ox, oy, oz, dx, dy, dz, tmin, tmax, _, _ = unpack_args(buffer(args))
            inst = instances[shape]
            try:
                hits = inst.hit((ox, oy, oz), (dx, dy, dz), tmin, tmax)
            except BaseException as e:
                raise ShapeError(f"{inst.label}.hit raised {_describe(e)}") from e
            if not hits:
                return hr_ok
            n = len(hits)
            scale = rel * (max(abs(ox), abs(oy), abs(oz)))
            dmax = max(abs(dx), abs(dy), abs(dz))
            packed = bytearray(n * hit_size)
            previous = tmin
            for i, h in enumerate(hits):
                try:
                    if len(h) == 3:
                        t, (nx, ny, nz), entering = h
                        surface = 0
                    else:
                        t, (nx, ny, nz), entering, surface = h
                    t = number(t)
                    nx, ny, nz = number(nx), number(ny), number(nz)
                    entering = flag(entering)
                except (TypeError, ValueError) as e:
                    raise ShapeError(f"{inst.label}.hit: hit {i} must be (t, (nx, ny, nz), "
                                     f"entering), not {h!r}") from e
                if not (previous <= t < tmax) or t == tmin:
                    if not (tmin < t < tmax):
                        raise ShapeError(f"{inst.label}.hit: hit {i} at t={t!r} is outside "
                                         f"({tmin!r}, {tmax!r})")
                    raise ShapeError(f"{inst.label}.hit: hits are not sorted by t "
                                     f"({previous!r} then {t!r})")
                if not (isfinite(nx) and isfinite(ny) and isfinite(nz)) or \
                        (nx == 0.0 and ny == 0.0 and nz == 0.0):
                    raise ShapeError(f"{inst.label}.hit: hit {i} has normal "
                                     f"({nx!r}, {ny!r}, {nz!r}); it must be finite, non-zero")
                if surface.__class__ is not int or not 0 <= surface < surfaces:
                    raise ShapeError(f"{inst.label}.hit: hit {i} names surface {surface!r}; "
                                     f"the class has 0..{surfaces - 1}")
                px, py, pz = ox + t * dx, oy + t * dy, oz + t * dz
                error = scale + rel * abs(t) * dmax
                if not (isfinite(px) and isfinite(py) and isfinite(pz) and isfinite(error)):
                    raise ShapeError(f"{inst.label}.hit: hit {i} at t={t!r} is beyond "
                                     "double's range")
                pack_into(packed, i * hit_size, t, px, py, pz, nx, ny, nz, error,
                          surface, entering, 0)
                previous = t
            out = args.out
            base = out.count
            if out.capacity - base < n:
                status = int(reg.host.reserve(args.call, out, base + n))
                if status != hr_ok:
                    fail(f"{reg.name}.hit", ShapeError(f"{inst.label}: no room for {n} hits"))
                    return status
            memmove(out.hits + base, packed, n * hit_size)
            out.count = base + n
            return hr_ok
        except BaseException as e:
            fail(f"{reg.name}.hit", e)
            return error_module

    return (ffi.callback("hr_status(const hr_create_args *, void **)", create,
                         error=error_parameter),
            ffi.callback("void(void *)", destroy),
            ffi.callback("void(const void *, hr_bounds *)", bounds),
            ffi.callback("hr_hit_fn", hit, error=error_module))


def _build_class(reg: _Registration, ffi: Any, lib: Any) -> None:
    def c_string(text: str) -> Any:
        s = ffi.new("char[]", text.encode("utf-8"))
        reg.c_strings.append(s)
        return s

    n = len(reg.specs)
    reg.c_params = ffi.new("hr_param_spec[]", max(n, 1))
    for i, spec in enumerate(reg.specs):
        p = reg.c_params[i]
        p.name = c_string(spec.name)
        p.type = lib.HR_PARAM_NUMBER if spec.kind == NUMBER else lib.HR_PARAM_STRING
        p.required = 1 if spec.required else 0
        p.default_number = float(spec.default) if spec.kind == NUMBER and not spec.required \
            else 0.0
        p.min, p.max = spec.min, spec.max
        p.help = c_string(spec.help)
    reg.callbacks = _make_callbacks(reg, ffi, lib)
    create, destroy, bounds, hit = reg.callbacks
    c = ffi.new("hr_shape_class *")
    c.struct_size = ffi.sizeof("hr_shape_class")
    c.flags = lib.HR_SHAPE_CLOSED if reg.closed else 0
    c.name = c_string(reg.name)
    c.help = c_string(_help_line(reg.cls))
    c.params = reg.c_params if n else ffi.NULL
    c.param_count = n
    c.surface_count = reg.surface_count
    if reg.surface_names:
        reg.c_surface_names = ffi.new("const char *[]", [c_string(n) for n in reg.surface_names])
        c.surface_names = reg.c_surface_names
    c.create, c.destroy, c.bounds, c.hit = create, destroy, bounds, hit
    # first_hit and any_hit stay NULL: the host then calls hit and picks.
    reg.c_class = c


def register_shape(name: str, cls: type, context: Any = None) -> Any:
    """Register the Python class `cls` as the shape class `name` on
    `context` (None: the package's default context; a hitray.abi.Context;
    or an hr_context* cdata). A later registration of the same name wins;
    objects made from an earlier one keep working. Returns the
    hr_shape_class* registered."""
    ffi, lib = load()
    _check_layout(ffi)
    if not isinstance(name, str) or not _NAME.match(name):
        raise ValueError(f"shape name {name!r} must be a word of letters, digits and '_' "
                         "not starting with a digit (it is an SDL keyword)")
    if not isinstance(cls, type):
        raise TypeError(f"register_shape({name!r}, ...) takes a class, not "
                        f"{type(cls).__name__}")
    for method in ("bounds", "hit"):
        if not callable(getattr(cls, method, None)):
            raise TypeError(f"shape class {cls.__qualname__} has no method {method}()")
    ctx, keep = resolve(context)
    reg = _Registration(name, cls)
    _build_class(reg, ffi, lib)
    origin = ffi.new("char[]", reg.origin.encode("utf-8"))
    status = lib.hr_context_register_shape_class(ctx, reg.c_class, origin)
    if status != 0:
        from ._errors import check
        check(ctx, status)
    # The context keeps pointers into all of this from now on.
    keep_alive(keep, reg, origin)
    return reg.c_class

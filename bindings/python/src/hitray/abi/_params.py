"""The parameters of a Python shape class, as hr_param_spec entries.

A class says what `cls(**params)` takes in one of two ways:

- a class attribute ``params``: a dict from name to default value (a number
  or a string) or to a `Param` for a range, a help line or no default, in
  the declared order (which is SDL's positional order);
- otherwise, its ``__init__`` signature: each keyword parameter after self,
  in order, with its default (a number or a string); one with no default is
  required, a string if annotated ``str``, else a number.

Numbers reach the class as float, or as int when the default is an int and
the value given is whole. The ABI carries no default for a string
parameter: an omitted string reaches create as "", so an empty string means
the Python default (and a required string must not be empty).
"""

from __future__ import annotations

import inspect
import math
from typing import Any, List, Optional, Union

NUMBER = "number"
STRING = "string"
_REQUIRED = object()


class Param:
    """One parameter: `default` (leave out for a required one), `kind`
    ("number" or "string"; from the default when omitted, else "number"),
    the inclusive range `min`..`max` of a number (checked by the host before
    the class sees it), and a `help` line."""

    def __init__(self, default: Any = _REQUIRED, *, kind: Optional[str] = None,
                 min: float = -math.inf, max: float = math.inf, help: str = "") -> None:
        self.default = default
        self.kind = kind
        self.min = min
        self.max = max
        self.help = help


class ParamSpec:
    """One checked parameter, ready for hr_param_spec."""

    def __init__(self, name: str, kind: str, default: Any, required: bool, lo: float, hi: float,
                 help_text: str, integer: bool) -> None:
        self.name = name
        self.kind = kind
        self.default = default
        self.required = required
        self.min = lo
        self.max = hi
        self.help = help_text
        self.integer = integer  # the default was an int: give whole values as int

    def to_python(self, number: float, string: str) -> Union[int, float, str]:
        """The value `cls(**params)` gets, from an hr_param's fields."""
        if self.kind == NUMBER:
            if self.integer and number.is_integer():
                return int(number)
            return number
        if string == "" and not self.required:
            return str(self.default)
        return string


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _spec(owner: str, name: Any, declared: Any, annotation: Any = None) -> ParamSpec:
    """A ParamSpec from a default value or a Param; `owner` names the class
    in messages."""
    p = declared if isinstance(declared, Param) else Param(declared)
    where = f"shape class {owner}: parameter '{name}'"
    if not isinstance(name, str) or not name.isidentifier():
        raise ValueError(f"shape class {owner}: parameter name {name!r} is not a Python "
                         "identifier (cls(**params) could not take it)")
    required = p.default is _REQUIRED
    kind = p.kind
    if kind is None:
        if required:
            kind = STRING if annotation is str else NUMBER
        elif isinstance(p.default, str):
            kind = STRING
        elif _is_number(p.default):
            kind = NUMBER
        else:
            raise ValueError(f"{where}: default {p.default!r} is neither a number nor a "
                             "string (the only parameter types a Python shape can take)")
    if kind not in (NUMBER, STRING):
        raise ValueError(f"{where}: kind must be 'number' or 'string', not {kind!r}")
    if not (_is_number(p.min) and _is_number(p.max)) or math.isnan(p.min) or math.isnan(p.max) \
            or p.min > p.max:
        raise ValueError(f"{where}: range [{p.min!r}, {p.max!r}] is not a range of numbers")
    default: Any = None if required else p.default
    if kind == NUMBER:
        if not required:
            if not _is_number(default) or not math.isfinite(default):
                raise ValueError(f"{where}: default {default!r} is not a finite number")
            if not p.min <= default <= p.max:
                raise ValueError(f"{where}: default {default!r} is outside "
                                 f"[{p.min!r}, {p.max!r}]")
    else:
        if not required and not isinstance(default, str):
            raise ValueError(f"{where}: default {default!r} is not a string")
        if (p.min, p.max) != (-math.inf, math.inf):
            raise ValueError(f"{where}: a string parameter has no range")
    if not isinstance(p.help, str):
        raise ValueError(f"{where}: help must be a string")
    integer = kind == NUMBER and isinstance(default, int)
    return ParamSpec(name, kind, default, required, float(p.min), float(p.max), p.help, integer)


def class_params(cls: type) -> List[ParamSpec]:
    """The ParamSpecs of `cls`, in declared order."""
    owner = getattr(cls, "__qualname__", repr(cls))
    declared = getattr(cls, "params", None)
    if declared is not None:
        if not isinstance(declared, dict):
            raise ValueError(f"shape class {owner}: 'params' must be a dict from name to "
                             f"default or Param, not {type(declared).__name__}")
        return [_spec(owner, name, value) for name, value in declared.items()]
    try:
        signature = inspect.signature(getattr(cls, "__init__"))
    except (TypeError, ValueError):
        return []
    specs: List[ParamSpec] = []
    var_keyword = ""
    for i, (name, p) in enumerate(signature.parameters.items()):
        if i == 0 and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
            continue  # self
        if p.kind == p.VAR_KEYWORD:
            var_keyword = name
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        if p.kind == p.POSITIONAL_ONLY:
            raise ValueError(f"shape class {owner}: parameter '{name}' of __init__ is "
                             "positional-only; cls(**params) passes keywords")
        declared_default = _REQUIRED if p.default is p.empty else p.default
        specs.append(_spec(owner, name, declared_default, p.annotation))
    if var_keyword and not specs and getattr(cls, "__init__") is not object.__init__:
        # The library checks every parameter a scene gives against the
        # class's list, which **params leaves empty: refused here, with the
        # fix, rather than at the first scene line as "takes no parameters".
        raise ValueError(f"shape class {owner}: __init__ takes only **{var_keyword}, so the "
                         "parameters a scene may give are unknown; declare them, as keyword "
                         "parameters of __init__ (def __init__(self, radius=1.0)) or as a class "
                         "attribute params = {\"radius\": 1.0}")
    return specs

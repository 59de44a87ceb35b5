"""Argument checks shared by the package: three numbers, a path, a size.

They turn what a user may pass (a tuple, a list, a numpy array) into plain
Python values and name the argument in the message when they cannot.
"""

from __future__ import annotations

import numbers
import os
from typing import Any, Tuple, Union

Vec3 = Tuple[float, float, float]
PathLike = Union[str, "os.PathLike[str]", bytes]


def vec3(value: Any, what: str) -> Vec3:
    """Three numbers as a tuple of floats, or TypeError naming `what`."""
    try:
        items = list(value)
    except TypeError:
        raise TypeError(f"{what}: expected three numbers, got {type(value).__name__}") from None
    if len(items) != 3 or not all(is_number(v) for v in items):
        raise TypeError(f"{what}: expected three numbers, got {value!r}")
    return (as_float(items[0], what), as_float(items[1], what), as_float(items[2], what))


def is_number(value: Any) -> bool:
    """A real number that is not a bool (True is not a colour component)."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def as_float(value: Any, what: str) -> float:
    try:
        return float(value)
    except OverflowError:
        raise ValueError(f"{what}: {value!r} is beyond double's range") from None


def number(value: Any, what: str) -> float:
    """A real number as a float (NaN and infinities pass: the library says
    where they are not allowed)."""
    if not is_number(value):
        raise TypeError(f"{what}: expected a number, got {value!r}")
    return as_float(value, what)


def flag(value: Any, what: str) -> bool:
    """A bool (numpy's too, and the integers 0 and 1): not any object's
    truth, so that ``exact="no"`` is an error rather than True."""
    if isinstance(value, bool):
        return value
    if type(value).__name__ == "bool_" or (isinstance(value, numbers.Integral) and int(value) in (0, 1)):
        return bool(value)
    raise TypeError(f"{what}: expected True or False, got {value!r}")


INT32_MAX = 2**31 - 1


def integer(value: Any, what: str) -> int:
    """A whole number that fits the library's int32 fields."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{what}: expected an integer, got {value!r}")
    out = int(value)
    if not -INT32_MAX - 1 <= out <= INT32_MAX:
        raise ValueError(f"{what}: {out} is out of range")
    return out


def path_bytes(path: PathLike, what: str = "path") -> bytes:
    """A path for the C library: bytes as the file system spells them."""
    try:
        raw = os.fsencode(path)
    except TypeError:
        raise TypeError(f"{what}: expected a path (str, bytes or os.PathLike), got {path!r}") from None
    if b"\0" in raw:
        raise ValueError(f"{what}: embedded null byte")
    if not raw:
        raise ValueError(f"{what}: empty path")
    return raw


def size(value: Any, what: str = "size") -> Tuple[int, int]:
    """(width, height), both whole and at least 1."""
    try:
        w, h = value
    except (TypeError, ValueError):
        raise TypeError(f"{what}: expected (width, height), got {value!r}") from None
    w, h = integer(w, f"{what} width"), integer(h, f"{what} height")
    if w < 1 or h < 1:
        raise ValueError(f"{what}: width and height must be at least 1, got {w}x{h}")
    return (w, h)

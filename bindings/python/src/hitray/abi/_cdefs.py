"""cffi declarations made from hitray's public headers, at import time.

The headers are the one description of the ABI, so nothing here copies a
declaration by hand. cffi's parser takes C declarations but no preprocessor,
so this module does the little preprocessing the headers need, and refuses
anything beyond it (with the header, the line and what it could not take), so
a header that stops being plain enough fails loudly instead of losing a
declaration:

- comments are removed and continued lines joined;
- ``#include "x.h"`` is followed (once per file, as the include guards do);
  ``#include <stddef.h>`` and ``<stdint.h>`` are dropped: cffi knows their types;
- ``#if defined(X)``, ``#ifdef``, ``#ifndef``, ``#else`` and ``#endif`` are
  evaluated with nothing predefined: not C++ (``extern "C"`` goes), not
  Windows, and not the library's own build (``HR_API`` is the importing side);
- ``#define NAME <integer literal>`` is kept as a cffi integer constant;
  ``#define NAME "text"`` becomes a Python string constant (cffi has none);
  an object-like macro whose body is another name, an attribute or nothing is
  expanded where declarations use it (``HR_API``, ``HR_EXPORT_ATTR``,
  ``HR_SHAPE_MODULE_ENTRY``); a function-like macro is dropped, and using one
  in a declaration is an error.
"""

from __future__ import annotations

import os
import re
from typing import Dict, Iterator, List, NoReturn, Set, Tuple

# System headers whose types cffi knows without a declaration.
_KNOWN_SYSTEM_HEADERS = {"stddef.h", "stdint.h", "stdbool.h"}

_INT_LITERAL = re.compile(r"-?(0[xX][0-9a-fA-F]+|[0-9]+)[uUlL]*$")
_STRING_LITERAL = re.compile(r'"([^"\\]|\\.)*"$')
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_ATTRIBUTE = re.compile(r"(__attribute__|__declspec)\s*\(")


def _c_integer(literal: str) -> int:
    """The value of a C integer literal (decimal, 0x hexadecimal, 0 octal)."""
    digits = literal.rstrip("uUlL")
    sign = -1 if digits.startswith("-") else 1
    digits = digits.lstrip("-")
    if digits[:2].lower() == "0x":
        return sign * int(digits[2:], 16)
    if len(digits) > 1 and digits[0] == "0":
        return sign * int(digits[1:], 8)
    return sign * int(digits)


class HeaderError(Exception):
    """A public header uses something the cffi layer cannot take."""


class Declarations:
    """What the headers declare, ready for ``ffi.cdef``."""

    def __init__(self) -> None:
        self.cdef = ""                         # declarations and integer #defines
        self.integers: Dict[str, int] = {}     # the #define integer constants
        self.strings: Dict[str, str] = {}      # the #define string constants
        self.dropped: Dict[str, str] = {}      # NAME -> why, macros with no cffi form
        self.headers: List[str] = []           # every header read, in order


def strip_comments(text: str) -> str:
    """Remove /* */ and // comments, keeping string literals and newlines
    (so line numbers stay right)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == '"' or c == "'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            if j < 0:
                raise HeaderError("unterminated comment")
            out.append(" " + "\n" * text.count("\n", i, j))
            i = j + 2
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def _logical_lines(text: str) -> Iterator[Tuple[int, str]]:
    """(line number, line) with backslash-continued lines joined."""
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        start = i
        line = lines[i]
        while line.endswith("\\") and i + 1 < len(lines):
            i += 1
            line = line[:-1] + " " + lines[i]
        yield start + 1, line
        i += 1


class _Reader:
    def __init__(self, include_dir: str) -> None:
        self.include_dir = include_dir
        self.decls = Declarations()
        self.macros: Dict[str, str] = {}       # object-like: NAME -> body
        self.function_macros: Set[str] = set()
        self.seen: Set[str] = set()
        self.code: List[str] = []

    def error(self, where: str, message: str) -> NoReturn:
        raise HeaderError(f"{where}: {message} (hitray.abi reads the public headers "
                          "with cffi, which needs them plain)")

    # --- conditionals -------------------------------------------------------
    def _condition(self, where: str, keyword: str, rest: str) -> bool:
        if keyword == "ifdef":
            return rest.strip() in self.macros or rest.strip() in self.function_macros
        if keyword == "ifndef":
            return not (rest.strip() in self.macros or rest.strip() in self.function_macros)
        m = re.fullmatch(r"\s*(!?)\s*defined\s*(?:\(\s*(\w+)\s*\)|\s+(\w+))\s*", rest)
        if m is None:
            self.error(where, f"cannot evaluate '#{keyword} {rest.strip()}'")
        name = m.group(2) or m.group(3)
        value = name in self.macros or name in self.function_macros
        return not value if m.group(1) else value

    # --- macros -------------------------------------------------------------
    def _define(self, where: str, rest: str, active_code: List[str]) -> None:
        m = re.match(r"\s*([A-Za-z_]\w*)(\()?", rest)
        if m is None:
            self.error(where, f"malformed '#define {rest.strip()}'")
        name = m.group(1)
        if m.group(2):
            self.function_macros.add(name)
            self.decls.dropped[name] = "function-like macro"
            return
        body = rest[m.end():].strip()
        self.macros[name] = body
        if _INT_LITERAL.match(body):
            self.decls.integers[name] = _c_integer(body)
            active_code.append(f"#define {name} {body}")
        elif _STRING_LITERAL.match(body):
            self.decls.strings[name] = bytes(body[1:-1], "utf-8").decode("unicode_escape")
        elif body == "":
            self.decls.dropped[name] = "empty (an include guard or an attribute)"
        elif _IDENT.fullmatch(body) or _ATTRIBUTE.match(body):
            # Expanded where declarations use it; no constant of its own.
            self.decls.dropped[name] = "a name or an attribute, expanded in declarations"
        else:
            self.decls.dropped[name] = f"body '{body}' is not an integer literal"

    def _expand(self, where: str, line: str, depth: int = 0) -> str:
        def replace(m: re.Match[str]) -> str:
            word = m.group(0)
            if word in self.function_macros:
                self.error(where, f"a declaration uses the function-like macro {word}")
            if word not in self.macros:
                return word
            body = self.macros[word]
            if body == "" or _ATTRIBUTE.match(body):
                return ""
            if _INT_LITERAL.match(body):
                return body
            if _IDENT.fullmatch(body):
                if depth > 16:
                    self.error(where, f"macro {word} expands without end")
                return self._expand(where, body, depth + 1)
            self.error(where, f"a declaration uses the macro {word}, whose body '{body}' "
                       "has no cffi form")

        # String literals (extern "C") never reach here: C++ blocks are skipped.
        return _IDENT.sub(replace, line)

    # --- files --------------------------------------------------------------
    def read(self, name: str) -> None:
        path = os.path.join(self.include_dir, name)
        if path in self.seen:
            return
        self.seen.add(path)
        self.decls.headers.append(path)
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            raise HeaderError(f"cannot read the public header {path}: {e.strerror}") from e
        try:
            text = strip_comments(text)
        except HeaderError as e:
            self.error(path, str(e))
        stack: List[Tuple[bool, bool]] = []  # (active, taken) per open conditional
        for number, line in _logical_lines(text):
            where = f"{path}:{number}"
            active = all(a for a, _ in stack)
            m = re.match(r"\s*#\s*(\w*)(.*)$", line)
            if not m:
                if active and line.strip():
                    self.code.append(self._expand(where, line))
                continue
            keyword, rest = m.group(1), m.group(2)
            if keyword in ("if", "ifdef", "ifndef"):
                value = active and self._condition(where, keyword, rest)
                stack.append((value, value))
            elif keyword == "else":
                if not stack:
                    self.error(where, "#else without #if")
                _, taken = stack.pop()
                stack.append((not taken, True))
            elif keyword == "elif":
                if not stack:
                    self.error(where, "#elif without #if")
                _, taken = stack.pop()
                outer = all(a for a, _ in stack)
                value = outer and not taken and self._condition(where, "if", rest)
                stack.append((value, taken or value))
            elif keyword == "endif":
                if not stack:
                    self.error(where, "#endif without #if")
                stack.pop()
            elif not active:
                continue
            elif keyword == "include":
                self._include(where, rest.strip())
            elif keyword == "define":
                self._define(where, rest, self.code)
            elif keyword == "pragma" or keyword == "":
                continue
            else:
                self.error(where, f"cannot take '#{keyword}'")
        if stack:
            self.error(path, "an #if is not closed")

    def _include(self, where: str, target: str) -> None:
        m = re.fullmatch(r'"([^"]+)"|<([^>]+)>', target)
        if m is None:
            self.error(where, f"malformed #include {target}")
        if m.group(1):
            self.read(m.group(1))
        elif m.group(2) not in _KNOWN_SYSTEM_HEADERS:
            self.error(where, f"#include <{m.group(2)}>: only {sorted(_KNOWN_SYSTEM_HEADERS)} "
                       "may be included")


def read_headers(include_dir: str, top: str = "hitray.h") -> Declarations:
    """Declarations of `include_dir`/hitray/`top` and everything it includes.
    `include_dir` is the directory that holds the `hitray` header folder."""
    reader = _Reader(os.path.join(include_dir, "hitray"))
    reader.read(top)
    decls = reader.decls
    decls.cdef = "\n".join(line for line in reader.code if line.strip()) + "\n"
    return decls

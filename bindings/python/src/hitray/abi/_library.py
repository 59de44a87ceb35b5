"""Finding and loading libhitray, and the package's one cffi FFI.

By default the library is the package's own: the file the extension module
reports (``hitray._core._library_path()``), else ``<package>/lib/libhitray.so.0``.
Either way it is the file the extension already loaded, so the dynamic linker
hands back the same instance and a context address from the extension is
valid here. `use_library` points elsewhere (a build tree, an installed prefix)
and must be called before anything is loaded.

The declarations come from the public headers found next to that library
(``<libdir>/../include/hitray``, the layout of an install and of the wheel),
else from the source tree this file sits in, else from `use_library`'s
`include_dir`.
"""

from __future__ import annotations

import importlib
import os
import threading
from typing import Any, Dict, Optional, Tuple, Union

from . import _cdefs

_PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# bindings/python/src/hitray -> the repository's include/ when run from source.
_SOURCE_INCLUDE = os.path.normpath(os.path.join(_PACKAGE_DIR, "..", "..", "..", "..", "include"))

_lock = threading.RLock()
_chosen: Dict[str, Optional[str]] = {"library": None, "include_dir": None}
# (ffi, lib, library path, declarations); cffi objects are typed Any.
_loaded: Optional[Tuple[Any, Any, str, _cdefs.Declarations]] = None

PathLike = Union[str, "os.PathLike[str]"]


class LibraryError(ImportError):
    """libhitray or its headers could not be found or do not match."""


def use_library(path: PathLike, include_dir: Optional[PathLike] = None) -> None:
    """Load `path` instead of the package's libhitray (a build tree's
    ``lib/libhitray.so.0``, say). `include_dir` holds the ``hitray/`` header
    folder; by default the one beside the library or in the source tree. Call
    it before the first use of `ffi`, `lib` or `register_shape`."""
    with _lock:
        path = os.path.abspath(os.fspath(path))
        if _loaded is not None:
            if os.path.realpath(_loaded[2]) == os.path.realpath(path):
                return
            raise LibraryError(f"hitray.abi already loaded {_loaded[2]}; use_library({path!r}) "
                               "must come before the first use")
        _chosen["library"] = path
        _chosen["include_dir"] = os.fspath(include_dir) if include_dir is not None else None


def _default_library_path() -> str:
    try:
        from .. import _core  # the extension module, when the package is built
    except ImportError:
        return os.path.join(_PACKAGE_DIR, "lib", "libhitray.so.0")
    return str(_core._library_path())


def _find_include_dir(library: str) -> str:
    candidates = []
    if _chosen["include_dir"]:
        candidates.append(_chosen["include_dir"])
    candidates.append(os.path.join(os.path.dirname(os.path.realpath(library)), "..", "include"))
    candidates.append(os.path.join(os.path.dirname(library), "..", "include"))
    candidates.append(_SOURCE_INCLUDE)
    for c in candidates:
        if os.path.isfile(os.path.join(c, "hitray", "hitray.h")):
            return os.path.normpath(c)
    raise LibraryError("hitray.abi needs hitray's public headers (hitray/hitray.h); looked in "
                       + ", ".join(os.path.normpath(c) for c in candidates))


def load() -> Tuple[Any, Any]:
    """(ffi, lib): the FFI declared from the headers and the loaded library."""
    return _load()[:2]


def _load() -> Tuple[Any, Any, str, _cdefs.Declarations]:
    global _loaded
    with _lock:
        if _loaded is not None:
            return _loaded
        # Imported by name: cffi ships no type information, so its objects
        # are Any here.
        cffi = importlib.import_module("cffi")

        library = _chosen["library"] or _default_library_path()
        if not os.path.isfile(library):
            raise LibraryError(f"hitray.abi: libhitray not found at {library}")
        decls = _cdefs.read_headers(_find_include_dir(library))
        ffi = cffi.FFI()
        ffi.cdef(decls.cdef)
        try:
            lib = ffi.dlopen(library)
        except OSError as e:
            raise LibraryError(f"hitray.abi: cannot load {library}: {e}") from e
        _check_version(ffi, lib, decls, library)
        _loaded = (ffi, lib, library, decls)
        return _loaded


def _check_version(ffi: Any, lib: Any, decls: _cdefs.Declarations, library: str) -> None:
    """The headers must describe the library that was loaded."""
    v = ffi.new("int32_t[3]")
    lib.hr_version(v + 0, v + 1, v + 2)
    want = (decls.integers["HR_VERSION_MAJOR"], decls.integers["HR_VERSION_MINOR"])
    if (v[0], v[1]) != want:
        raise LibraryError(f"hitray.abi: {library} is version {v[0]}.{v[1]}.{v[2]}, but the "
                           f"headers read are for {want[0]}.{want[1]}")


def loaded_library_path() -> str:
    """The path of the libhitray file loaded (loading it if need be)."""
    return _load()[2]


def declarations() -> _cdefs.Declarations:
    """The `_cdefs.Declarations` the FFI was made from."""
    return _load()[3]

"""The public headers as cffi reads them: they parse, every struct's size and
field offsets agree with the C compiler's, the #define integers agree, and
every function they declare is exported by the library. The preprocessing
refuses what it cannot take, naming the header and line."""

import pathlib
import re
import shutil
import subprocess

import pytest

from abi_support import INCLUDE, abi, ffi, lib

from hitray.abi import _cdefs

# The shape kit (shape_kit*.h) is header-only code compiled into a module,
# no part of the library's ABI: hitray.h does not include it, cffi never
# reads it.
HEADERS = sorted(h for h in (INCLUDE / "hitray").glob("*.h") if not h.name.startswith("shape_kit"))


def public_structs():
    """Every `typedef struct NAME {` of the headers (the ones with a body)."""
    names = []
    for h in HEADERS:
        names += re.findall(r"typedef\s+struct\s+(\w+)\s*\{", h.read_text())
    return sorted(set(names))


def public_functions():
    names = []
    for h in HEADERS:
        text = _cdefs.strip_comments(h.read_text())
        names += re.findall(r"HR_API\s[^;(]*?\b(hr_\w+)\s*\(", text)
    return sorted(set(names))


def test_every_header_is_read():
    read = {pathlib.Path(p).resolve() for p in abi.declarations().headers}
    assert {h.resolve() for h in HEADERS} == read


def test_every_public_struct_is_declared():
    structs = public_structs()
    assert len(structs) >= 20  # the headers hold about 25; a regex gone wrong finds none
    for name in structs:
        assert ffi.sizeof(name) > 0, name


def test_every_public_function_is_exported():
    functions = public_functions()
    assert "hr_context_register_shape_class" in functions and len(functions) > 50
    for name in functions:
        # Attribute access resolves the symbol in the loaded library.
        assert callable(getattr(lib, name)), name


def test_only_macros_without_a_cffi_form_are_dropped():
    decls = abi.declarations()
    for name, why in decls.dropped.items():
        # An integer expression such as (1u << 4) would be lost here: refuse it.
        assert not why.startswith("body"), f"{name}: {why}"
    assert decls.strings == {"HR_SHAPE_MODULE_ENTRY_NAME": "hr_shape_module"}
    assert decls.integers["HR_SHAPE_ABI_VERSION"] == 1
    assert lib.HR_ERROR_MODULE == 4 and lib.HR_EFFECT_SUPERSAMPLING == 128


def _c_layout_program():
    """A C program printing what the compiler says of every struct field and
    integer constant cffi knows, one `name value` per line."""
    lines = ["#include <stddef.h>", "#include <stdio.h>", "#include <hitray/hitray.h>",
             "int main(void) {"]
    expected = {}
    for name in public_structs():
        t = ffi.typeof(name)
        lines.append(f'printf("sizeof {name} %zu\\n", sizeof({name}));')
        lines.append(f'printf("alignof {name} %zu\\n", _Alignof({name}));')
        expected[f"sizeof {name}"] = ffi.sizeof(t)
        expected[f"alignof {name}"] = ffi.alignof(t)
        for field, info in t.fields:
            key = f"offsetof {name}.{field}"
            lines.append(f'printf("{key} %zu\\n", offsetof({name}, {field}));')
            expected[key] = info.offset
            key = f"sizeof {name}.{field}"
            lines.append(f'printf("{key} %zu\\n", sizeof((({name} *)0)->{field}));')
            expected[key] = ffi.sizeof(info.type)
    for name, value in abi.declarations().integers.items():
        lines.append(f'printf("define {name} %lld\\n", (long long)({name}));')
        expected[f"define {name}"] = value
    lines += ["return 0;", "}"]
    return "\n".join(lines) + "\n", expected


def test_struct_layouts_match_the_c_compiler(tmp_path):
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.fail("no C compiler (cc) to compare the layouts with")
    source, expected = _c_layout_program()
    (tmp_path / "layout.c").write_text(source)
    exe = tmp_path / "layout"
    subprocess.run([cc, "-std=c11", "-Wall", "-Werror", "-I", str(INCLUDE),
                    str(tmp_path / "layout.c"), "-o", str(exe)], check=True)
    out = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout
    measured = {}
    for line in out.splitlines():
        key, _, value = line.rpartition(" ")
        measured[key] = int(value)
    assert measured.keys() == expected.keys()
    wrong = {k: (expected[k], measured[k]) for k in expected if expected[k] != measured[k]}
    assert not wrong, f"cffi vs cc: {wrong}"
    # Every field of every struct was compared, not just a few.
    assert sum(k.startswith("offsetof ") for k in measured) > 150


def _write_header(tmp_path, body):
    d = tmp_path / "hitray"
    d.mkdir(exist_ok=True)
    (d / "hitray.h").write_text(body)
    return tmp_path


@pytest.mark.parametrize("body, complaint", [
    ("#if HR_X > 1\n#endif\n", "hitray.h:1: cannot evaluate '#if HR_X > 1'"),
    ("#include <stdio.h>\n", "hitray.h:1: #include <stdio.h>"),
    ("#define F(x) x\nint F(y);\n", "hitray.h:2: a declaration uses the function-like macro F"),
    ("#define N (1 + 2)\nint a[N];\n", "hitray.h:2: a declaration uses the macro N"),
    ("#ifdef X\n", "an #if is not closed"),
    ("#endif\n", "hitray.h:1: #endif without #if"),
    ("#error no\n", "hitray.h:1: cannot take '#error'"),
    ("/* open\n", "unterminated comment"),
    ('#include "missing.h"\n', "cannot read the public header"),
])
def test_preprocessing_refuses_what_it_cannot_take(tmp_path, body, complaint):
    with pytest.raises(_cdefs.HeaderError) as e:
        _cdefs.read_headers(str(_write_header(tmp_path, body)))
    assert complaint in str(e.value)


def test_preprocessing_keeps_what_the_headers_use(tmp_path):
    body = """/* a comment with #define X 1 inside */
#ifndef GUARD_H
#define GUARD_H
#include <stdint.h>
#ifdef __cplusplus
extern "C" {
#endif
#if defined(_WIN32)
#define ATTR __declspec(dllexport)
#else
#define ATTR __attribute__((visibility("default")))
#endif
#define API ATTR
#define ENTRY entry_point
#define NAME "entry_point"
#define FLAG 0x10u
#define OCTAL 017
#define MULTI \\
    3
API int32_t ENTRY(int32_t a); // trailing comment
#ifdef __cplusplus
}
#endif
#endif
"""
    decls = _cdefs.read_headers(str(_write_header(tmp_path, body)))
    assert "extern" not in decls.cdef and "__attribute__" not in decls.cdef
    assert "int32_t entry_point(int32_t a);" in decls.cdef
    assert decls.integers == {"FLAG": 16, "OCTAL": 15, "MULTI": 3}
    assert decls.strings == {"NAME": "entry_point"}

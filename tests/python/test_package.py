"""The installed package: everything inside it (extension, libhitray, shape
modules), found with no environment variable, and the interface hitray.abi
builds on (the context's address, the library's path)."""

import os
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

import hitray
from conftest import ROOT

PACKAGE = pathlib.Path(hitray.__file__).resolve().parent


def test_the_extension_library_and_modules_are_inside_the_package():
    assert pathlib.Path(hitray._core.__file__).parent == PACKAGE
    assert pathlib.Path(hitray._core._library_path()) == PACKAGE / "lib" / "libhitray.so.0"
    shapes = PACKAGE / "lib" / "hitray" / "shapes"
    for name in ("sphere", "plane", "square", "cube", "cylinder"):
        assert (shapes / f"{name}.so").is_file()
    assert hitray.shape_classes()["sphere"].module == str(shapes / "sphere.so")
    assert (PACKAGE / "include" / "hitray" / "hitray.h").is_file()
    assert (PACKAGE / "py.typed").is_file() and (PACKAGE / "_core.pyi").is_file()


def test_the_extension_finds_libhitray_through_its_own_rpath():
    readelf = shutil.which("readelf")
    if readelf is None:
        pytest.skip("readelf (binutils) is not installed")
    out = subprocess.run([readelf, "-d", hitray._core.__file__], capture_output=True, text=True,
                         check=True).stdout
    assert re.search(r"\((RUNPATH|RPATH)\)\s+Library r(un)?path: \[\$ORIGIN/lib\]", out), out
    assert "Shared library: [libhitray.so.0]" in out


def test_a_fresh_interpreter_renders_with_no_environment_variable(tmp_path):
    env = {k: v for k, v in os.environ.items() if not k.startswith(("HITRAY_", "LD_"))}
    code = ("import hitray; s = hitray.Scene(); s.add(hitray.Cube()); "
            "print(hitray.render(s, size=(4, 4), progress=False).stats.primary)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                            cwd=tmp_path, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "16"


def test_the_version_is_the_cmake_project_s():
    cmake = (ROOT / "CMakeLists.txt").read_text()
    version = re.search(r"project\(hitray VERSION ([0-9.]+)", cmake).group(1)
    assert hitray.__version__ == version


def test_the_context_address_is_one_context_for_the_whole_package():
    address = hitray._core._context_address()
    assert isinstance(address, int) and address != 0
    assert hitray._core._context_address() == address


def test_every_public_name_is_documented():
    for name in hitray.__all__:
        obj = getattr(hitray, name)
        assert obj.__doc__ and obj.__doc__.strip(), name
    for cls in (hitray.Scene, hitray.Shape, hitray.Image, hitray.Camera):
        for attr, value in vars(cls).items():
            if attr.startswith("_") or not callable(getattr(value, "fget", value)):
                continue
            doc = getattr(value, "__doc__", None)
            assert doc and doc.strip(), f"{cls.__name__}.{attr}"


def test_the_stubs_match_the_extension_and_the_package_type_checks():
    mypy = pytest.importorskip("mypy", reason="mypy is not installed (scripts/requirements-python.txt)")
    assert mypy
    allowlist = ROOT / "bindings" / "python" / "stubtest-allowlist.txt"
    stubtest = subprocess.run([sys.executable, "-m", "mypy.stubtest", "hitray._core",
                               "--allowlist", str(allowlist)],
                              capture_output=True, text=True, timeout=600)
    assert stubtest.returncode == 0, stubtest.stdout + stubtest.stderr
    # The package's sources type-check strictly against the stubs of _core
    # (from the source tree, where _core is only its .pyi).
    check = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental",
                            "-p", "hitray"], capture_output=True, text=True, timeout=600,
                           cwd=ROOT / "bindings" / "python" / "src")
    assert check.returncode == 0, check.stdout + check.stderr


def test_shape_params_carry_the_exclusive_ends():
    """Every key the library gives for a parameter (hr_param_spec, its
    flags included) is a field of ShapeParam, so shape_classes() works."""
    for cls in hitray.shape_classes().values():
        for p in cls.params:
            assert isinstance(p.min_exclusive, bool) and isinstance(p.max_exclusive, bool)

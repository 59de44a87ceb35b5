"""The sdist as `make wheel` builds it, from a tree that also holds what a
user leaves lying about: a venv/ made by following the README (whose
bin/python3 is a link to an absolute path, which tarfile refuses to unpack),
a build folder and a stray file. The sdist holds tracked files only. And a
machine without the -dev packages hears which ones to install, all at once."""

import pathlib
import shutil
import subprocess
import sys
import tarfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def tracked_files():
    out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
    return [name for name in out.decode().split("\0") if name and (ROOT / name).is_file()]


@pytest.fixture(scope="module")
def sdist(tmp_path_factory):
    tree = tmp_path_factory.mktemp("clone") / "hitray"
    tracked = tracked_files()
    for name in tracked:
        (tree / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / name, tree / name)
    # What following the README leaves behind, and more.
    (tree / "venv" / "bin").mkdir(parents=True)
    (tree / "venv" / "bin" / "python3").symlink_to(sys.executable)
    (tree / "venv" / "pyvenv.cfg").write_text("home = /usr/bin\n")
    (tree / "mybuild" / "lib").mkdir(parents=True)
    (tree / "mybuild" / "lib" / "libhitray.so").write_bytes(b"\x7fELF")
    (tree / "notes.txt").write_text("untracked\n")
    out = tree / "dist"
    result = subprocess.run([sys.executable, "-m", "build", "--sdist", "--no-isolation", "--outdir", str(out),
                             str(tree)], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    (path,) = out.glob("hitray-*.tar.gz")
    return path, set(tracked)


def test_the_sdist_holds_tracked_files_only(sdist):
    path, tracked = sdist
    with tarfile.open(path) as tar:
        members = tar.getmembers()
        # Unpacks under the strictest filter: no link to an absolute path.
        tar.extractall(path.parent / "unpacked", filter="data")
    top = members[0].name.split("/")[0]
    names = {m.name[len(top) + 1:] for m in members if m.isfile()}
    generated = {"PKG-INFO"}
    assert names - generated <= tracked, sorted(names - generated - tracked)
    for wanted in ("CMakeLists.txt", "pyproject.toml", "lib/CMakeLists.txt", "bindings/python/CMakeLists.txt",
                   "cli/main.c", "shapes/sphere/CMakeLists.txt", "bindings/python/src/hitray/__main__.py"):
        assert wanted in names, f"{wanted} missing from the sdist"
    assert not any(n.startswith(("venv/", "mybuild/", "tests/", "bench/")) or n == "notes.txt" for n in names)


def test_a_machine_without_the_dev_packages_hears_which(tmp_path):
    # The packages' absence played by CMake's switches: the configure the
    # sdist's build runs stops with one message naming every missing one.
    result = subprocess.run(["cmake", "-S", str(ROOT), "-B", str(tmp_path), "-DHITRAY_BUILD_TESTS=OFF",
                             "-DHITRAY_BUILD_VIEW=OFF", "-DCMAKE_DISABLE_FIND_PACKAGE_PNG=ON",
                             "-DCMAKE_DISABLE_FIND_PACKAGE_OpenEXRCore=ON"], capture_output=True, text=True)
    assert result.returncode != 0
    message = " ".join(result.stderr.split())
    assert "install the Debian packages: libpng-dev, libopenexr-dev (3.1 or newer)" in message, result.stderr
    assert "zlib1g-dev" not in message and "libstb-dev" not in message

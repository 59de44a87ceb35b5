"""The manylinux wheel of `make wheel`, as a user on another machine gets it:
installed into a fresh venv and imported there from outside the source tree,
it renders with the library search path emptied, loads libpng, OpenEXRCore
and every hitray library from the wheel itself, and each shared object it
ships needs only what the wheel holds or the manylinux policy lets a wheel
take from the system (checked with ldd against auditwheel's own policy
file). `auditwheel show` must find the wheel consistent with its tag, and
the README names the libraries the wheel carries."""

import json
import os
import pathlib
import re
import subprocess
import sys

import pytest

HERE = pathlib.Path(__file__).resolve().parent


def manylinux_policy(wheel):
    """The policy named by the wheel's platform tag, from auditwheel's policy
    file (the one `auditwheel repair` applied)."""
    tag = re.search(r"-(manylinux_\d+_\d+)_[a-z0-9_]+\.whl$", wheel.name)
    assert tag, f"{wheel.name} has no manylinux platform tag (was it repaired by auditwheel?)"
    import auditwheel
    policies = json.loads((pathlib.Path(auditwheel.__file__).parent / "policy" /
                           "manylinux-policy.json").read_text())
    for policy in policies:
        if policy["name"] == tag.group(1) or tag.group(1) in policy.get("aliases", []):
            return policy
    pytest.fail(f"auditwheel knows no policy {tag.group(1)}")


def clean_env():
    """The environment of a user who set nothing: no library search path, no
    shape path, nothing of this repository on Python's path."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("LD_LIBRARY_PATH", "LD_PRELOAD", "HITRAY_SHAPE_PATH", "PYTHONPATH",
                        "HITRAY_BUILD_DIR", "VIRTUAL_ENV")}
    env["LD_LIBRARY_PATH"] = ""
    return env


@pytest.fixture(scope="module")
def venv(tmp_path_factory, wheel):
    """A fresh venv (no system site-packages) with the wheel installed, by
    pip as a user runs it; its dependencies come from the package index."""
    root = tmp_path_factory.mktemp("wheel")
    env_dir = root / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(env_dir)], check=True)
    python = env_dir / "bin" / "python"
    result = subprocess.run([str(python), "-m", "pip", "install", "-q", "--disable-pip-version-check",
                             str(wheel)], capture_output=True, text=True, env=clean_env())
    assert result.returncode == 0, result.stdout + result.stderr
    site = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['platlib'])"],
                          capture_output=True, text=True, check=True).stdout.strip()
    return {"root": root, "python": python, "site": pathlib.Path(site)}


@pytest.fixture(scope="module")
def rendered(venv):
    out = venv["root"] / "render"
    result = subprocess.run([str(venv["python"]), str(HERE / "render_in_venv.py"), str(out)],
                            capture_output=True, text=True, env=clean_env(), cwd=venv["root"],
                            timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    return out, json.loads(result.stdout)


def shipped_elf_files(site):
    files = [p for p in (site / "hitray").rglob("*.so*") if p.is_file()]
    files += [p for p in (site / "hitray" / "bin").iterdir() if p.is_file()]
    files += [p for p in (site / "hitray.libs").glob("*.so*") if p.is_file()]
    return files


def test_imports_from_the_venv_and_renders(venv, rendered):
    out, report = rendered
    assert pathlib.Path(report["hitray"]).is_relative_to(venv["site"]), report["hitray"]
    assert report["shape"] == [48, 64, 3]
    assert report["finite"]
    # Lit shapes of several colours on a grey floor: far more than a few
    # distinct pixels, and some light.
    assert report["max"] > 0.1 and report["distinct"] > 50
    assert out.with_suffix(".png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert out.with_suffix(".exr").read_bytes()[:4] == b"\x76\x2f\x31\x01"


def test_loads_its_libraries_from_the_wheel(venv, rendered):
    # What the process mapped, not what ldd predicts: libpng, OpenEXRCore,
    # libhitray and the shape modules are the wheel's copies, none the
    # system's (this machine has the system's too: the build used them).
    _, report = rendered
    mapped = [pathlib.Path(p) for p in report["mapped"]]
    for wanted in ("libpng16", "libOpenEXRCore", "libhitray.so", "/shapes/sphere.so",
                   "/shapes/mesh.so", "/shapes/torus.so"):
        hits = [p for p in mapped if wanted in str(p)]
        assert hits, f"{wanted} was not loaded; mapped: {report['mapped']}"
        for path in hits:
            assert path.is_relative_to(venv["site"]), f"{wanted} loaded from {path}, not the wheel"


def test_every_shipped_object_needs_only_the_wheel_or_the_policy(venv, wheel):
    allowed = set(manylinux_policy(wheel)["lib_whitelist"])
    files = shipped_elf_files(venv["site"])
    names = {p.name for p in files}
    assert "libhitray.so.0" in names and "sphere.so" in names
    assert any(n.startswith("libpng16-") for n in names), f"libpng not vendored: {sorted(names)}"
    assert any(n.startswith("libOpenEXRCore") for n in names), f"OpenEXRCore not vendored: {sorted(names)}"
    problems = []
    for path in files:
        result = subprocess.run(["ldd", str(path)], capture_output=True, text=True, env=clean_env())
        assert result.returncode == 0, f"ldd {path}: {result.stderr}"
        for line in result.stdout.splitlines():
            line = line.strip()
            found = re.match(r"^(\S+) => (.*?)(?: \(0x[0-9a-f]+\))?$", line)
            if not found:
                continue  # linux-vdso.so.1, the dynamic loader: no file to look up
            name, where = found.groups()
            if where == "not found":
                problems.append(f"{path.name}: {name} not found")
            elif not pathlib.Path(where).resolve().is_relative_to(venv["site"]) and name not in allowed:
                problems.append(f"{path.name}: {name} => {where} (neither in the wheel nor allowed "
                                f"by {manylinux_policy(wheel)['name']})")
    assert not problems, "\n".join(problems)


def test_auditwheel_show_finds_it_consistent(wheel):
    result = subprocess.run([sys.executable, "-m", "auditwheel", "show", str(wheel)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    print(result.stdout)
    tag = re.search(r"-(manylinux_\d+_\d+_[a-z0-9_]+)\.whl$", wheel.name).group(1)
    assert f'consistent with\nthe following platform tag: "{tag}"' in result.stdout.replace(
        "consistent with the", "consistent with\nthe")


DEMO_SCENE = """
camera 0 2 8  0 0.5 0  0 1 0  40
light 4 6 5  1 1 1
push rotate -90 1 0 0 diffuse .6 .6 .6 plane pop
push translate 0 1 0 diffuse .9 .2 .2 sphere pop
"""


@pytest.mark.parametrize("how", ["script", "module"])
def test_the_hitray_command_renders_with_the_wheels_modules(venv, how):
    # The venv's `hitray` script and `python -m hitray` both run the
    # program the wheel carries, which finds the library and the shape
    # modules inside the wheel with no library search path.
    command = [str(venv["python"].parent / "hitray")] if how == "script" else [str(venv["python"]), "-m", "hitray"]
    scene = venv["root"] / f"cli-{how}.sdl"
    scene.write_text(DEMO_SCENE)
    out = venv["root"] / f"cli-{how}.png"
    result = subprocess.run(command + ["render", str(scene), "-o", str(out), "--size", "32x24"],
                            capture_output=True, text=True, env=clean_env(), cwd=venv["root"], timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    shapes = subprocess.run(command + ["shapes"], capture_output=True, text=True, env=clean_env(), timeout=60)
    assert shapes.returncode == 0, shapes.stderr
    assert str(venv["site"] / "hitray" / "lib" / "hitray" / "shapes" / "sphere.so") in shapes.stdout
    version = subprocess.run(command + ["--version"], capture_output=True, text=True, env=clean_env(), timeout=60)
    assert version.returncode == 0 and version.stdout.startswith("hitray "), version.stdout + version.stderr
    # A usage error keeps the program's own exit status.
    assert subprocess.run(command + ["frobnicate"], capture_output=True, env=clean_env(), timeout=60).returncode == 2


def test_hitray_view_says_in_one_line_how_to_get_the_window(venv):
    result = subprocess.run([str(venv["python"].parent / "hitray"), "view", "scene.sdl"], capture_output=True,
                            text=True, env=clean_env(), cwd=venv["root"], timeout=60)
    assert result.returncode == 1 and result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and "libsdl2-dev" in lines[0] and "pip's wheels leave it out" in lines[0], lines


README = HERE.parents[1] / "README.md"


def readme_vendored():
    """The libraries the README says the wheel carries: the names in its
    "(libpng, OpenEXRCore and libstb, ..., copied into `hitray.libs/`"."""
    text = " ".join(README.read_text().split())
    found = re.search(r"`auditwheel repair` \(([^)]*?) copied into `hitray\.libs/`", text)
    assert found, "README.md no longer says which libraries `auditwheel repair` copies into hitray.libs/"
    listed = re.split(r",\s*|\s+and\s+", found.group(1).split(", which")[0])
    return {name.strip() for name in listed if name.strip()}, text


def test_the_readme_names_the_libraries_the_wheel_carries(wheel):
    """The README's sentence on the wheel's bundled libraries is what
    auditwheel put in: each library it names is in hitray.libs/, each
    library there is named, and zlib (the system's, which the manylinux
    policy allows) is not there."""
    import zipfile

    with zipfile.ZipFile(wheel) as z:
        vendored = sorted({pathlib.PurePosixPath(n).name for n in z.namelist()
                           if n.startswith("hitray.libs/") and ".so" in n})
    names, text = readme_vendored()
    # auditwheel names its copies NAME-HASH.so.VERSION (libpng16-a1b2c3d4.so.16.39.0).
    stems = {re.sub(r"-[0-9a-f]{8}\.so.*$", "", v) for v in vendored}

    def carried(name):
        return [s for s in stems if s.lower().startswith(name.lower()) or s.lower() == f"lib{name.lower()}"
                or s.lower().startswith(f"lib{name.lower()}")]

    assert all(carried(n) for n in names), f"README names {sorted(names)}; the wheel carries {vendored}"
    unnamed = [s for s in stems if not any(s in carried(n) for n in names)]
    assert not unnamed, f"the wheel carries {unnamed}, which README.md does not name"
    assert not any(s.startswith("libz") for s in stems), vendored
    assert "zlib is the system's" in text

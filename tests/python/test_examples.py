"""The README's Python example and examples/python/ run as a user runs them."""

import pathlib
import re
import subprocess
import sys

import pytest

from conftest import ROOT, require_classes


def run_python(code_or_args, cwd):
    args = ["-c", code_or_args] if isinstance(code_or_args, str) else code_or_args
    result = subprocess.run([sys.executable, *map(str, args)], capture_output=True, text=True,
                            cwd=cwd, timeout=600)
    assert result.returncode == 0, result.stderr[-3000:]
    return result.stdout


def png_size(path):
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


def readme_python_example():
    readme = (ROOT / "README.md").read_text()
    section = readme[readme.index("### From Python"):]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_readme_python_example_renders_an_image(tmp_path):
    require_classes("difference", "torus")
    out = run_python(readme_python_example(), tmp_path)
    assert png_size(tmp_path / "python.png") == (640, 480)
    assert "HitInfo(t=7.0, point=(-1.2, 1.0, 1.0)" in out


def test_the_readme_python_example_passes_mypy_strict(tmp_path):
    """What a user's editor and CI say about the README's code: it
    type-checks strictly against the installed package's annotations and
    stubs (image.stats is a RenderStats, not an Optional, after render)."""
    mypy = pytest.importorskip("mypy", reason="mypy is not installed (scripts/requirements-python.txt)")
    assert mypy
    example = tmp_path / "readme_example.py"
    example.write_text(readme_python_example())
    check = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental",
                            "--cache-dir", str(tmp_path / "cache"), str(example)],
                           capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert check.returncode == 0, check.stdout + check.stderr


def test_the_scene_in_code_example_is_the_readme_s(tmp_path):
    # The example file and the README show the same scene.
    require_classes("difference", "torus")
    example = (ROOT / "examples" / "python" / "scene_in_code.py").read_text()
    for line in readme_python_example().splitlines():
        if line.startswith(("scene", "bite", "camera", "          ")):
            assert line in example, line
    run_python([ROOT / "examples" / "python" / "scene_in_code.py", tmp_path / "x.png"], tmp_path)
    assert png_size(tmp_path / "x.png") == (640, 480)


def test_the_notebook_style_demo_script_renders_the_demo(tmp_path):
    out = run_python([ROOT / "examples" / "python" / "render_demo.py", "--size", "64x48",
                      "--spp", "1", "-o", tmp_path / "demo.png"], tmp_path)
    assert png_size(tmp_path / "demo.png") == (64, 48)
    assert "objects:" in out and "enters" in out


def test_the_python_shape_example_draws_no_warning(tmp_path):
    """Its scene's reflectivities count (minReflectivity set below them): the
    example does not warn about its own coefficients."""
    result = subprocess.run([sys.executable, "-W", "error", str(ROOT / "examples/python/python_shape.py"),
                             str(tmp_path / "p.png"), "--size", "64x48"], capture_output=True, text=True,
                            cwd=tmp_path, timeout=600)
    assert result.returncode == 0 and "Warning" not in result.stderr, result.stderr[-3000:]
    assert png_size(tmp_path / "p.png") == (64, 48)

"""`make demo` shows a newcomer what the README shows: the Makefile's demo
command and the caption under the README's picture give the same render
options, and rendering with them reproduces docs/demo.png.

The binary is the build tree's (HITRAY_BUILD_DIR, as in test_cli.py)."""

import re
import shlex
import subprocess

import numpy
import pytest

from conftest import BUILD, ROOT

PIL = pytest.importorskip("PIL.Image", reason="Pillow reads the PNGs (scripts/requirements-test.txt)")


def render_options(words):
    """The options of `hitray render scenes/demo.sdl ...`, without the
    output files (which differ by design: out/ against docs/)."""
    options, it = [], iter(words)
    for word in it:
        if word in ("-o", "--output", "--exr", "--stats-json"):
            next(it)
        else:
            options.append(word)
    return options


def makefile_demo_options():
    recipe = re.search(r"^demo:.*?\n((?:\t.*\n)+)", (ROOT / "Makefile").read_text(), re.M)
    assert recipe, "the Makefile has no demo target"
    line = next((l for l in recipe.group(1).splitlines() if "hitray render scenes/demo.sdl" in l), None)
    assert line, f"make demo renders no scenes/demo.sdl:\n{recipe.group(1)}"
    words = shlex.split(line.split("hitray render scenes/demo.sdl", 1)[1])
    return render_options(words)


def readme_picture_options():
    caption = re.search(r"rendered with `build/bin/hitray render scenes/demo\.sdl ([^`]*)`",
                        (ROOT / "README.md").read_text())
    assert caption, "the README's picture has no caption naming its hitray render command"
    return render_options(shlex.split(caption.group(1)))


def test_make_demo_renders_with_the_readme_pictures_options():
    assert makefile_demo_options() == readme_picture_options()
    assert "--spp" in readme_picture_options()


def test_the_readme_picture_is_what_make_demo_renders(tmp_path):
    hitray = BUILD / "bin" / "hitray"
    if not hitray.is_file():
        pytest.fail(f"{hitray} is missing: build first (make build), or set HITRAY_BUILD_DIR")
    out = tmp_path / "demo.png"
    result = subprocess.run([str(hitray), "render", str(ROOT / "scenes" / "demo.sdl"), "-o", str(out),
                             *makefile_demo_options()], capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    ours = numpy.asarray(PIL.open(out).convert("RGB"), dtype=numpy.int16)
    readme = numpy.asarray(PIL.open(ROOT / "docs" / "demo.png").convert("RGB"), dtype=numpy.int16)
    assert ours.shape == readme.shape
    # The render is the same whatever the thread count, so this build gives
    # the picture bit for bit; another compiler may contract a multiply-add
    # differently and move a value across an 8-bit step: at most one step,
    # on at most 0.1% of the pixels. A change to the renderer that changes
    # the picture fails here: render docs/demo.png again with the caption's
    # command.
    diff = numpy.abs(ours - readme).max(axis=2)
    assert diff.max() <= 1 and (diff > 0).mean() <= 1e-3, \
        f"max step {diff.max()}, {(diff > 0).sum()} pixels differ from docs/demo.png"

"""Every picture of README.md and docs/ is what the command its caption names
makes now (scripts/docs_pictures.py reads the commands from the captions;
`make docs` runs them to remake the pictures).

Each picture is rendered again at its own size (a few seconds in all) and
its decoded pixels compared with the committed file's."""

from __future__ import annotations

import importlib.util
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("docs_pictures", ROOT / "scripts" / "docs_pictures.py")
assert spec and spec.loader
docs_pictures = importlib.util.module_from_spec(spec)
sys.modules[spec.name] = docs_pictures  # dataclasses look their module up
spec.loader.exec_module(docs_pictures)
pytest.importorskip("PIL.Image", reason="Pillow decodes the pictures (scripts/requirements-test.txt)")

PICTURES = docs_pictures.every_picture()


def test_every_picture_in_docs_is_shown_with_the_command_that_makes_it():
    problems = [f"{p.where}: {p.path}: {p.problem}" for p in PICTURES if p.problem]
    assert not problems, "\n".join(problems)
    made = {p.path for p in PICTURES if p.command}
    # The pictures rendered from scenes: the demo (README, and its sRGB and
    # linear pair), the gallery's, the Python shape's.
    assert {"docs/demo.png", "docs/demo-srgb.png", "docs/demo-linear.png", "docs/textures.png",
            "docs/cook-torrance.png", "docs/python-shape.png"} <= made


@pytest.mark.parametrize("picture", [p for p in PICTURES if p.command and not p.problem], ids=lambda p: p.path)
def test_the_picture_is_what_its_caption_command_makes(picture, tmp_path):
    hitray = docs_pictures.build_dir() / "bin" / "hitray"
    if not hitray.is_file():
        pytest.fail(f"{hitray} is missing: build first (make build), or set HITRAY_BUILD_DIR")
    out = tmp_path / pathlib.Path(picture.path).name
    docs_pictures.make(picture, out)
    problem = docs_pictures.differences(out, ROOT / picture.path)
    assert problem is None, (f"{picture.where}: {picture.path} is not what `{' '.join(picture.command)}` makes "
                             f"now: {problem}; `make docs` remakes it")


def test_the_checker_finds_captions_and_stale_pictures(tmp_path, monkeypatch):
    """The parts the tests above rely on: a caption's command found across
    its line breaks and in a table, a picture with none or shown by no page
    reported, a picture one step off in a few pixels passed and one redrawn
    failed."""
    numpy = pytest.importorskip("numpy")
    from PIL import Image

    (tmp_path / "docs").mkdir()
    (tmp_path / "README.md").write_text(
        "| a | b |\n|---|---|\n| ![a](docs/a.png) | ![b](docs/b.png) |\n\n"
        "*`build/bin/hitray render s.sdl -o docs/a.png\n--size 4x4` and `python x.py docs/b.png`.*\n\n"
        "![c](docs/c.png)\n\nno caption\n")
    for name in ("a", "b", "c", "d"):
        Image.fromarray(numpy.zeros((4, 4, 3), numpy.uint8)).save(tmp_path / "docs" / f"{name}.png")
    monkeypatch.setattr(docs_pictures, "ROOT", tmp_path)
    found = {p.path: p for p in docs_pictures.every_picture()}
    assert found["docs/a.png"].command == ["build/bin/hitray", "render", "s.sdl", "-o", "docs/a.png",
                                           "--size", "4x4"]
    assert found["docs/b.png"].command == ["python", "x.py", "docs/b.png"]
    assert "no caption" in found["docs/c.png"].problem
    assert "no page" in found["docs/d.png"].problem

    committed = numpy.full((40, 40, 3), 100, numpy.uint8)
    Image.fromarray(committed).save(tmp_path / "committed.png")
    near = committed.copy()
    near[0, 0, 1] += 1  # one step in one pixel of 1600: another compiler's rounding
    Image.fromarray(near).save(tmp_path / "near.png")
    assert docs_pictures.differences(tmp_path / "near.png", tmp_path / "committed.png") is None
    redrawn = committed.copy()
    redrawn[10:20] = 30
    Image.fromarray(redrawn).save(tmp_path / "redrawn.png")
    assert "400 of 1600 pixels differ" in docs_pictures.differences(tmp_path / "redrawn.png",
                                                                      tmp_path / "committed.png")
    Image.fromarray(committed[:20]).save(tmp_path / "smaller.png")
    assert "40x20" in docs_pictures.differences(tmp_path / "smaller.png", tmp_path / "committed.png")

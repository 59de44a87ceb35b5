"""`make demo` shows a newcomer what the README shows: the Makefile's demo
command and the caption under the README's picture give the same render
options. That the caption's command makes docs/demo.png now is
tests/docs/test_pictures.py's check, as for every picture of the docs."""

import re
import shlex

from conftest import ROOT


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


"""The command line's help for a newcomer: "did you mean" for options,
verbs, SDL keywords and shape classes; the library's warnings on stderr; a
progress bar that never goes backwards and says how long is left, for
`hitray render` and for each of `hitray savings`' renders."""

import json
import re

from hitray_testing import ROOT, TWO_SPHERES_SDL, require_classes
from test_cli import run, run_on_a_terminal, write_sdl


def test_a_misspelt_option_or_verb_gets_a_suggestion(tmp_path):
    scene = write_sdl(tmp_path, "s.sdl", TWO_SPHERES_SDL)
    result = run("render", scene, "-o", tmp_path / "x.png", "--sp", "4")
    assert result.returncode == 2
    assert "unknown option '--sp' (did you mean '--spp'?" in result.stderr
    result = run("savings", scene, "--min-wieght", "0.1")
    assert "did you mean '--min-weight'?" in result.stderr
    result = run("rendr", scene)
    assert result.returncode == 2 and "unknown command 'rendr' (did you mean 'render'?" in result.stderr
    # Nothing near: no guess.
    result = run("render", scene, "-o", tmp_path / "x.png", "--frobnicate")
    assert "unknown option '--frobnicate' (see 'hitray render --help')" in result.stderr
    assert not (tmp_path / "x.png").exists()


def test_a_misspelt_sdl_keyword_gets_a_suggestion(tmp_path):
    scene = write_sdl(tmp_path, "s.sdl", "specularExponet 20\nsphere\n")
    result = run("render", scene, "-o", tmp_path / "x.png")
    assert result.returncode == 1
    assert result.stderr.strip() == (f"hitray: {scene}:1:1: unknown keyword 'specularExponet' "
                                     "(did you mean 'specularExponent'?)")
    scene = write_sdl(tmp_path, "c.sdl", "camera 0 0 5 0 0 0 0 1 0\nsphere\n")
    result = run("render", scene, "-o", tmp_path / "x.png")
    assert "'camera' takes 10 numbers" in result.stderr and "found 9 before 'sphere'" in result.stderr


def test_a_keyword_no_module_provides_says_where_modules_were_looked_for(tmp_path):
    modules = tmp_path / "modules"
    modules.mkdir()
    scene = write_sdl(tmp_path, "s.sdl", "light 1 5 5 1 1 1\nzqxjkw 1.5\n")
    result = run("render", scene, "-o", tmp_path / "x.png", env={"HITRAY_SHAPE_PATH": str(modules)})
    assert result.returncode == 1 and len(result.stderr.splitlines()) == 1, result.stderr
    line = result.stderr
    assert line.startswith(f"hitray: {scene}:2:1: unknown keyword 'zqxjkw': no SDL command, and no shape "
                           "module provides 'zqxjkw' (searched: "), line
    assert str(modules) in line and "HITRAY_SHAPE_PATH" in line
    assert not (tmp_path / "x.png").exists()


def test_warnings_go_to_stderr_and_the_render_goes_on(tmp_path):
    glass = write_sdl(tmp_path, "glass.sdl",
                      "light 1 5 5 1 1 1\ntransparency 0.9 speedOfLight 0.7\nreflectivity 0.08\nsphere\n")
    result = run("render", glass, "-o", tmp_path / "g.png")
    assert result.returncode == 0 and (tmp_path / "g.png").is_file()
    assert (f"hitray: warning: {glass}:3:1: reflectivity 0.08 is below minReflectivity 0.5"
            in result.stderr)
    empty = write_sdl(tmp_path, "empty.sdl", "background 0.2 0.3 0.4\n")
    result = run("render", empty, "-o", tmp_path / "e.png")
    assert result.returncode == 0
    assert "hitray: warning: the scene has no objects" in result.stderr
    # hits keeps stdout for its records.
    result = run("hits", empty, "--origin", "0,0,5", "--dir", "0,0,-1")
    assert result.stdout == "" and "no objects" in result.stderr


def bar_percents(terminal, label):
    return [int(p) for p in re.findall(re.escape(label) + r" \[[# ]*\] +(\d+)%", terminal)]


def test_the_render_bar_never_goes_backwards_and_shows_the_time_left(tmp_path):
    # Many small tiles on more threads than cores: the reports race.
    scene = write_sdl(tmp_path, "s.sdl", TWO_SPHERES_SDL)
    rc, _, terminal = run_on_a_terminal("render", scene, "-o", tmp_path / "p.png", "--size",
                                        "320x240", "--spp", "4", "--threads", "8")
    assert rc == 0
    percents = bar_percents(terminal, "rendering")
    assert percents and percents == sorted(percents) and percents[-1] == 100, percents
    assert re.search(r"rendering \[[# ]*\] +\d+%  \d+\.\d s, about \d+ s left", terminal), terminal
    assert f"loading {scene} ..." in terminal


def test_savings_shows_a_bar_for_each_render(tmp_path):
    scene = write_sdl(tmp_path, "s.sdl", TWO_SPHERES_SDL)
    rc, out, terminal = run_on_a_terminal("savings", scene, "--size", "64x48", "--spp", "4")
    assert rc == 0 and b"full" in out
    for label in ("savings: full", "savings: effects-all", "savings: adaptive 0.05",
                  "savings: min-weight 0.05", "savings: both"):
        percents = bar_percents(terminal, label)
        assert percents and percents == sorted(percents), (label, terminal)
    # The table went to stdout only, the bars to the terminal only.
    assert b"savings:" not in out


def test_an_optional_tube_radius_in_sdl(tmp_path):
    require_classes("torus")
    scene = write_sdl(tmp_path, "t.sdl", "torus 0.1\n")
    result = run("hits", scene, "--origin", "1,0,5", "--dir", "0,0,-1")
    assert result.returncode == 0 and '"t": 4.9' in result.stdout


def docs_sdl_start_scene():
    text = (ROOT / "docs" / "sdl.md").read_text()
    return re.search(r"```sdl\n(.*?)```", text, re.S).group(1)


def test_the_scene_docs_sdl_opens_with_renders_without_warnings(tmp_path):
    """docs/sdl.md's first scene is complete: it renders every effect it
    shows, with no warning; without its threshold line, the warning its text
    quotes comes, at the line and column quoted."""
    text = docs_sdl_start_scene()
    scene = write_sdl(tmp_path, "start.sdl", text)
    stats = tmp_path / "stats.json"
    result = run("render", scene, "-o", tmp_path / "start.png", "--size", "64x48", "--stats-json", stats)
    assert result.returncode == 0 and "warning" not in result.stderr, result.stderr
    effects = set(json.loads(stats.read_text())["effects"])
    assert {"diffuse", "specular", "shadows", "reflection", "refraction"} <= effects
    lines = [line for line in text.splitlines() if not line.startswith("minReflectivity")]
    scene = write_sdl(tmp_path, "start.sdl", "\n".join(lines[:4] + [""] + lines[4:]) + "\n")
    result = run("render", scene, "-o", tmp_path / "start.png", "--size", "64x48")
    quoted = re.search(r"`hitray: warning: start\.sdl:(\d+):(\d+): (reflectivity [^:]*):",
                       (ROOT / "docs" / "sdl.md").read_text().replace("\n  ", " "))
    assert quoted, "docs/sdl.md quotes the warning"
    assert (f"hitray: warning: {scene}:{quoted.group(1)}:{quoted.group(2)}: {quoted.group(3)}:"
            in result.stderr), result.stderr

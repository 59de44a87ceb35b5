"""The render flags that `hitray render`, `hitray view` and `hitray savings`
share come from one parser (cli/render_flags.c): each verb takes a flag with
the same limits and the same message, and the limits are the library's own
(include/hitray/render.h), so a value the command line takes is one hr_render
takes. tests/cli/test_render_flags.c checks the parser against hr_render; this
file checks that each verb uses it.
"""

import os
import re
import subprocess

import pytest

from hitray_testing import BUILD, ROOT
from hitray_testing import TWO_SPHERES_SDL as SCENE

HITRAY = BUILD / "bin" / "hitray"
VIEWER = BUILD / "bin" / "hitray-view"
RENDER_H = (ROOT / "include" / "hitray" / "render.h").read_text()
SCENE_H = (ROOT / "include" / "hitray" / "scene.h").read_text()


def limit(name, header=RENDER_H):
    return int(re.search(rf"#define {name} (\d+)", header).group(1))


MAX_THREADS = limit("HR_RENDER_MAX_THREADS")
MAX_SAMPLES = limit("HR_RENDER_MAX_SAMPLES")
MAX_BLOCK = limit("HR_RENDER_MAX_BLOCK")
MAX_SIDE = limit("HR_RENDER_MAX_SIDE")
MAX_DEPTH = limit("HR_MAX_RECURSION_DEPTH", SCENE_H)


def run(*args, env=None):
    full_env = {k: v for k, v in os.environ.items()
                if k not in ("HITRAY_SHAPE_PATH", "DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")}
    full_env.update(env or {})
    return subprocess.run([str(HITRAY), *map(str, args)], capture_output=True, text=True,
                          env=full_env, timeout=120)


@pytest.fixture
def scene(tmp_path):
    path = tmp_path / "scene.sdl"
    path.write_text(SCENE)
    return path


def verbs(tmp_path, scene):
    """Each verb that takes the shared flags, as a command line to which a
    flag is appended. The viewer has no display here: it stops, after every
    option is parsed, at "no display"."""
    found = {
        "render": ["render", scene, "-o", tmp_path / "o.png", "--size", "4x3"],
        "savings": ["savings", scene, "--size", "4x3"],
    }
    if VIEWER.is_file():
        found["view"] = ["view", scene]
    return found


# (flag, the value past the library's limit, the message it gets)
BEYOND = [
    ("--threads", MAX_THREADS + 1, f"--threads: {MAX_THREADS + 1} is out of range 0..{MAX_THREADS}"),
    ("--spp", MAX_SAMPLES + 1, f"--spp: {MAX_SAMPLES + 1} is out of range 1..{MAX_SAMPLES}"),
    ("--depth", MAX_DEPTH + 1, f"--depth: {MAX_DEPTH + 1} is out of range 0..{MAX_DEPTH}"),
]


@pytest.mark.parametrize("flag,value,message", BEYOND)
def test_each_verb_refuses_past_the_librarys_limit_alike(tmp_path, scene, flag, value, message):
    for verb, args in verbs(tmp_path, scene).items():
        r = run(*args, flag, value)
        assert r.returncode == 2, (verb, r.stderr)
        assert r.stderr == f"hitray: {message}\n", verb
    assert not (tmp_path / "o.png").exists()


def test_the_size_limit_is_the_librarys(tmp_path, scene):
    beyond = f"{MAX_SIDE + 1}x1"
    for verb, args in verbs(tmp_path, scene).items():
        r = run(*args[:1], scene, *args[2:4] if verb == "render" else [], "--size", beyond)
        assert r.returncode == 2, (verb, r.stderr)
        assert r.stderr == (f"hitray: --size: {MAX_SIDE + 1}x1 is out of range: "
                            f"each side must be 1..{MAX_SIDE}\n"), verb


def test_the_librarys_largest_thread_count_is_taken_by_each_verb(tmp_path, scene):
    """--threads at the library's limit gets past the parser of every verb:
    render and savings run with it; the viewer goes on to look for a display."""
    for verb, args in verbs(tmp_path, scene).items():
        r = run(*args, "--threads", MAX_THREADS)
        if verb == "view":
            assert r.returncode == 1 and "no display" in r.stderr, r.stderr
        else:
            assert r.returncode == 0, (verb, r.stderr)
    assert (tmp_path / "o.png").is_file()


def test_block_limit_in_render_and_view(tmp_path, scene):
    for verb, args in verbs(tmp_path, scene).items():
        r = run(*args, "--block", MAX_BLOCK + 1)
        if verb == "savings":  # savings renders every pixel: no --block
            assert r.returncode == 2 and "unknown option '--block'" in r.stderr
        else:
            assert r.stderr == f"hitray: --block: {MAX_BLOCK + 1} is out of range 1..{MAX_BLOCK}\n", verb


def test_exact_with_min_weight_is_refused_alike_by_render_and_view(tmp_path, scene):
    for verb, args in verbs(tmp_path, scene).items():
        if verb == "savings":
            continue
        r = run(*args, "--exact", "--min-weight", "0.1")
        assert r.stderr == "hitray: --exact: cannot be combined with --min-weight\n", verb


def test_every_verb_in_the_help_is_run_and_suggested():
    """One table of verbs: each the help lists runs (its own --help), and a
    misspelling of each gets its "did you mean"."""
    r = run("--help")
    listed = re.findall(r"^  ([a-z]+)\b", r.stdout.split("commands:")[1].split("options:")[0], re.M)
    assert "view" in listed and "render" in listed
    for verb in listed:
        typo = verb[:1] + verb[2:]  # one letter dropped: "vew", "rnder"
        r = run(typo)
        assert r.returncode == 2
        assert f"did you mean '{verb}'?" in r.stderr, (typo, r.stderr)

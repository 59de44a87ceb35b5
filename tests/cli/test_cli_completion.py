"""Each verb's --help lists every option its parser takes and nothing else,
and the shell completion (`hitray completion bash|zsh`) offers the same
options: all three read one option table per verb (cli/verbs.c)."""

import re
import shutil
import subprocess

import pytest

from hitray_testing import TWO_SPHERES_SDL
from test_cli import HITRAY, run, write_sdl

OPTION_LINE = re.compile(r"^  (?:(-[a-zA-Z]), )?(--[a-z0-9-]+)(?: (\S+))?", re.M)


def verbs():
    listed = run("--help").stdout.split("commands:\n")[1].split("\n\n")[0]
    return re.findall(r"^  ([a-z]+)\b", listed, re.M)


def help_options(verb):
    """{option: value name or None} of `hitray VERB --help`'s options block,
    aliases included."""
    r = run(verb, "--help")
    assert r.returncode == 0, r.stderr
    block = r.stdout.split("\noptions:\n")[1].split("\n\n")[0]
    found = {}
    for alias, name, value in OPTION_LINE.findall(block):
        found[name] = value or None
        if alias:
            found[alias] = value or None
    assert "--help" in found, verb
    return found


def all_options():
    every = {}
    for verb in verbs():
        every.update(help_options(verb))
    return every


def test_every_verb_has_completion_and_the_help_lists_it():
    assert "completion" in verbs() and "view" in verbs()


@pytest.mark.parametrize("verb", ["render", "hits", "shapes", "savings", "view", "completion"])
def test_the_help_lists_exactly_what_the_parser_takes(verb, tmp_path):
    """Every option any verb's help names is tried on this verb: the parser
    takes it (whatever it then says of its value) exactly when this verb's
    help lists it. The viewer's --min-weight and --exact were once taken
    but not listed."""
    scene = write_sdl(tmp_path, "s.sdl", TWO_SPHERES_SDL)
    listed = help_options(verb)
    for option, value in all_options().items():
        if option in ("--help", "-h"):
            continue
        # Two scenes: whatever the option, the command stops at the second.
        args = [verb, option] + (["not-a-value"] if value else []) + [scene, scene]
        r = run(*args, cwd=tmp_path)
        unknown = f"unknown option '{option}'" in r.stderr
        assert unknown == (option not in listed), (verb, option, r.stderr)


def bash_complete(words):
    """What bash's completion offers for the command line `words` (the last
    being the word under the cursor)."""
    script = run("completion", "bash")
    assert script.returncode == 0, script.stderr
    program = (script.stdout + "\nCOMP_WORDS=(" + " ".join(f"'{w}'" for w in words) + ")\n"
               f"COMP_CWORD={len(words) - 1}\n_hitray\nprintf '%s\\n' \"${{COMPREPLY[@]}}\"\n")
    done = subprocess.run(["bash", "-c", program], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return done.stdout.split()


@pytest.mark.skipif(not shutil.which("bash"), reason="bash is not installed")
def test_bash_completion_offers_every_option_of_the_help():
    assert set(verbs()) <= set(bash_complete(["hitray", ""]))
    assert bash_complete(["hitray", "vi"]) == ["view"]
    for verb in verbs():
        assert set(bash_complete(["hitray", verb, "-"])) == set(help_options(verb)), verb
    assert bash_complete(["hitray", "render", "s.sdl", "--effects", ""]) == ["auto", "all"]
    assert bash_complete(["hitray", "completion", ""]) == ["bash", "zsh"]
    # A value that is not a file gets nothing offered; a file option, files.
    assert bash_complete(["hitray", "render", "s.sdl", "--size", ""]) == []
    assert str(HITRAY.name) in bash_complete(["hitray", "render", "--output", str(HITRAY.parent) + "/"])[0]


def zsh_sections(script):
    """{verb: its _arguments specs} of the zsh script."""
    return dict(re.findall(r"^    ([a-z]+)\)\n(.*?)^        ;;", script, re.M | re.S))


def test_zsh_completion_offers_every_option_of_the_help():
    script = run("completion", "zsh").stdout
    assert script.startswith("#compdef hitray\n")
    sections = zsh_sections(script)
    assert sorted(sections) == sorted(verbs())
    for verb, specs in sections.items():
        offered = set(re.findall(r"'(--[a-z0-9-]+)\[", specs))
        for alias, name in re.findall(r"\{(-[a-zA-Z]),(--[a-z0-9-]+)\}", specs):
            offered |= {alias, name}
        assert offered == set(help_options(verb)), verb
    if shutil.which("zsh"):  # its syntax, where zsh is installed
        done = subprocess.run(["zsh", "-n"], input=script, capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, done.stderr


def test_completion_refuses_another_shell():
    r = run("completion", "fish")
    assert r.returncode == 2 and r.stderr == "hitray: completion: 'fish' is neither 'bash' nor 'zsh'\n"
    r = run("completion")
    assert r.returncode == 2 and "which shell?" in r.stderr

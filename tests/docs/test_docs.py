"""Every fenced block of README.md and docs/*.md is run as a reader would run
it, or says why it is not.

A block is run by its info string:
  sh       its commands, by `sh -e`; they must succeed.
  console  `$ ` lines are commands (a line ending in `\\` goes on), the lines
           after one are what it prints (standard output and error); `...`
           matches anything.
  python   the block as a script, by the interpreter the package is installed in.
  c        the block as prog.c, compiled against include/ and the build's
           libhitray, then run.
  sdl      the block as a scene, read by hitray.parse_sdl with warnings as
           errors.
A block that cannot be run carries the reason in an HTML comment on the
lines just before it: `<!-- not run: opens a window -->`.

Each page's blocks run in order in one scratch folder per page, which holds
the repository's top-level entries as links (so `scenes/demo.sdl` and
`build/bin/hitray` are where the pages say), `build` the build tree under test
(HITRAY_BUILD_DIR) and an empty `out/`, as a clone has after `make demo`. The
scratch folder is the working directory; the clone itself is never written.
"""

from __future__ import annotations

import os
import pathlib
import re
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("HITRAY_BUILD_DIR", ROOT / "build")).resolve()
PAGES = ["README.md"] + sorted(f"docs/{p.name}" for p in (ROOT / "docs").glob("*.md"))
RUNNERS = ("sh", "console", "python", "c", "sdl")
NOT_RUN = re.compile(r"<!--\s*not run:\s*(?P<reason>\S.*?)\s*-->")
FENCE = re.compile(r"^(?P<fence>```+|~~~+)\s*(?P<info>.*)$")
TIMEOUT = 300


class Block:
    def __init__(self, page: str, line: int, info: str, text: str, not_run: str | None) -> None:
        self.page, self.line, self.info, self.text, self.not_run = page, line, info, text, not_run

    @property
    def where(self) -> str:
        return f"{self.page}:{self.line}"


def blocks(page: str) -> list[Block]:
    """The fenced blocks of a page, each with the reason on the lines before
    it for not running it, if any."""
    lines = (ROOT / page).read_text(encoding="utf-8").splitlines()
    found, i = [], 0
    while i < len(lines):
        opening = FENCE.match(lines[i])
        if not opening:
            i += 1
            continue
        fence, info = opening["fence"], opening["info"].strip()
        before = i - 1
        while before >= 0 and not lines[before].strip():
            before -= 1
        mark = NOT_RUN.search(lines[before]) if before >= 0 else None
        end = i + 1
        while end < len(lines) and not lines[end].startswith(fence[:3]):
            end += 1
        assert end < len(lines), f"{page}:{i + 1}: a fenced block that is never closed"
        found.append(Block(page, i + 1, info.split()[0] if info else "", "\n".join(lines[i + 1:end]) + "\n",
                           mark["reason"] if mark else None))
        i = end + 1
    return found


def scratch(tmp_path: pathlib.Path) -> pathlib.Path:
    for entry in ROOT.iterdir():
        if entry.name not in ("build", "out", ".git") and not entry.name.startswith("build-"):
            (tmp_path / entry.name).symlink_to(entry)
    (tmp_path / "build").symlink_to(BUILD)
    (tmp_path / "out").mkdir()
    return tmp_path


def environment() -> dict[str, str]:
    env = dict(os.environ)
    # `python` on a page is the interpreter under test (a venv's, activated).
    env["PATH"] = f"{pathlib.Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env["HITRAY_BUILD_DIR"] = str(BUILD)
    return env


def run(block: Block, argv: list[str], cwd: pathlib.Path, **kw) -> subprocess.CompletedProcess:
    done = subprocess.run(argv, cwd=cwd, env=environment(), stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=TIMEOUT, **kw)
    assert done.returncode == 0, f"{block.where}: {block.info} block failed ({done.returncode}):\n{done.stdout}"
    return done


def console_steps(block: Block) -> list[tuple[str, str]]:
    """(command, output shown) for each `$ ` line of a console block."""
    steps: list[tuple[str, list[str]]] = []
    lines = block.text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("$ "):
            command = line[2:]
            while command.endswith("\\") and i + 1 < len(lines):
                i += 1
                command = command[:-1] + " " + lines[i].strip()
            steps.append((command, []))
        else:
            assert steps, f"{block.where}: a console block must start with a `$ ` command"
            steps[-1][1].append(line)
        i += 1
    return [(c, "\n".join(out)) for c, out in steps]


def matches(shown: str, printed: str) -> bool:
    """Whether `printed` is what the page shows, `...` standing for anything."""
    def lines(text: str) -> str:
        return "\n".join(l.rstrip() for l in text.strip("\n").splitlines())
    pattern = ".*?".join(re.escape(part) for part in lines(shown).split("..."))
    return re.fullmatch(pattern, lines(printed), re.DOTALL) is not None


def run_block(block: Block, cwd: pathlib.Path) -> None:
    if block.info == "sh":
        run(block, ["sh", "-e", "-c", block.text], cwd)
    elif block.info == "console":
        for command, shown in console_steps(block):
            printed = run(block, ["sh", "-e", "-c", command], cwd).stdout
            assert matches(shown, printed), (f"{block.where}: `{command}` printed\n{printed}\n"
                                             f"where the page shows\n{shown}")
    elif block.info == "python":
        (cwd / "block.py").write_text(block.text)
        run(block, [sys.executable, "block.py"], cwd)
    elif block.info == "c":
        (cwd / "prog.c").write_text(block.text)
        lib = BUILD / "lib"
        run(block, [os.environ.get("CC", "cc"), "-std=c11", "-Wall", "-Werror", f"-I{ROOT / 'include'}",
                    "prog.c", "-o", "prog", f"-L{lib}", "-lhitray", f"-Wl,-rpath,{lib}"], cwd)
        run(block, ["./prog"], cwd)
    elif block.info == "sdl":
        (cwd / "block.sdl").write_text(block.text)
        run(block, [sys.executable, "-W", "error", "-c",
                    "import sys, hitray; hitray.parse_sdl(open(sys.argv[1]).read(), sys.argv[1])",
                    "block.sdl"], cwd)
    else:
        raise AssertionError(f"{block.where}: a ```{block.info} block is not run by the tests ("
                             f"{', '.join(RUNNERS)} are) and says no reason: put "
                             f"`<!-- not run: REASON -->` on the line before it")


@pytest.mark.parametrize("page", PAGES)
def test_every_block_runs_or_says_why_not(page, tmp_path):
    cwd = scratch(tmp_path)
    for block in blocks(page):
        if block.not_run is None:
            run_block(block, cwd)


def test_the_checker_reads_marks_and_wildcards(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("x\n<!-- not run: opens a window -->\n\n```sh\nview\n```\n```text\nplain\n```\n")
    global ROOT
    saved, ROOT = ROOT, tmp_path
    try:
        found = blocks("page.md")
    finally:
        ROOT = saved
    assert [(b.line, b.info, b.not_run) for b in found] == [(4, "sh", "opens a window"), (7, "text", None)]
    with pytest.raises(AssertionError, match=r"page.md:7: a ```text block is not run"):
        run_block(found[1], tmp_path)
    assert matches("rendered in ... s: 12 rays\nok", "rendered in 0.25 s: 12 rays  \nok\n")
    assert not matches("rendered in ... s: 12 rays", "rendered in 0.25 s: 13 rays")
    bad = Block("p.md", 3, "console", "$ echo 41\n42\n", None)
    with pytest.raises(AssertionError, match=r"p.md:3: `echo 41` printed"):
        run_block(bad, tmp_path)


def test_the_savings_tables_are_what_bench_savings_sh_prints():
    """docs/effects.md's tables, rerun (ray counts and errors are exact on
    any machine and thread count); `bench/drivers/savings.sh --write docs/effects.md`
    writes them."""
    [table] = [b for b in blocks("docs/effects.md") if b.not_run and "bench/drivers/savings.sh" in b.not_run]
    env = dict(environment(), HITRAY=str(BUILD / "bin" / "hitray"))
    done = subprocess.run([str(ROOT / "bench" / "drivers" / "savings.sh")], env=env, stdout=subprocess.PIPE, text=True,
                          timeout=TIMEOUT, check=True)
    assert done.stdout == table.text, (f"{table.where}: the tables are not what bench/drivers/savings.sh prints "
                                       f"now; run `bench/drivers/savings.sh --write docs/effects.md`")


def savings_rows(table: str) -> dict[str, dict[str, list[float]]]:
    """bench/drivers/savings.sh's tables: scene -> render name -> [rays, saved, saved%,
    rmse, max, differing]."""
    scenes: dict[str, dict[str, list[float]]] = {}
    for part in table.strip().split("\n\n"):
        head, _, *rows = part.splitlines()
        scene = scenes[head.split(":")[0]] = {}
        for row in rows:
            *name, rays, saved, percent, rmse, worst, differing = row.split()
            scene[" ".join(name)] = [float(rays), float(saved), float(percent.rstrip("%")), float(rmse),
                                     float(worst), float(differing)]
    return scenes


def test_the_reading_of_the_savings_tables_is_what_they_show():
    """The sentences under docs/effects.md's tables quote them: each
    number here is worked out from the committed tables (which the test
    above keeps what bench/drivers/savings.sh prints), so a rerun that moves them
    fails until the prose is read again."""
    [table] = [b for b in blocks("docs/effects.md") if b.not_run and "bench/drivers/savings.sh" in b.not_run]
    scenes = savings_rows(table.text)
    demo = scenes.pop("scenes/demo.sdl")
    hill = list(scenes.values())
    assert len(hill) == 3
    page = (ROOT / "docs" / "effects.md").read_text(encoding="utf-8")
    reading = " ".join(page.split("Reading them:", 1)[1].split("## Tests", 1)[0].split())

    def ratio(rows):
        return rows["effects-all"][0] / rows["full"][0]

    def rows_of(rows, kind):
        return [v for k, v in rows.items() if k.startswith(kind)]

    def whole(x):
        return int(x + 0.5)

    adaptive_hill = [r for s in hill for r in rows_of(s, "adaptive")]
    said = [
        f"on the demo, {ratio(demo):.1f} times the rays",
        f"no mirror or glass, {min(map(ratio, hill)):.1f} to {max(map(ratio, hill)):.1f} times",
        f"saves {whole(min(r[2] for r in rows_of(demo, 'adaptive')))} to "
        f"{whole(max(r[2] for r in rows_of(demo, 'adaptive')))} % of the rays on the demo",
        f"{whole(min(r[2] for r in adaptive_hill))} to {whole(max(r[2] for r in adaptive_hill))} % on Hill's",
        f"on the demo it is {min(r[3] for r in rows_of(demo, 'adaptive')):.3f} to "
        f"{max(r[3] for r in rows_of(demo, 'adaptive')):.3f}",
        f"the largest error, {max(r[4] for r in rows_of(demo, 'adaptive')):.2f}",
        f"cut-off** saves {whole(min(r[2] for r in rows_of(demo, 'min-weight')))} to "
        f"{whole(max(r[2] for r in rows_of(demo, 'min-weight')))} % on the demo",
        f"RMSE of {demo['min-weight 0.01'][3]:.1g} for W = 0.01 rising to {demo['min-weight 0.2'][3]:.2g} for W = 0.2",
    ]
    missing = [s for s in said if s not in reading]
    assert not missing, f"docs/effects.md's reading of its tables says otherwise than: {missing}"
    # The claims without a number in them.
    assert "RMSE stays below 0.001" in reading and max(r[3] for r in adaptive_hill) < 0.001
    assert "nothing to cut, no error" in reading
    assert all(r[1] == 0 and r[3] == 0 for s in hill for r in rows_of(s, "min-weight"))
    assert "0.01 and 0.05 cut the same rays on the demo" in reading
    assert demo["min-weight 0.01"][0] == demo["min-weight 0.05"][0]
    by_threshold = sorted((float(k.split()[1]), v) for k, v in demo.items() if k.startswith("adaptive"))
    assert "growing with the threshold" in reading
    assert all(a[1][3] <= b[1][3] and a[1][4] <= b[1][4] for a, b in zip(by_threshold, by_threshold[1:]))
    largest = f"the largest error, {by_threshold[-1][1][4]:.2f}, comes at the threshold {by_threshold[-1][0]:g}"
    assert largest in reading


def test_the_readmes_listing_of_lib_names_every_folder_there():
    """README.md's listing of lib/ (a block not run) names each folder of
    lib/ and no other."""
    [listing] = [b for b in blocks("README.md") if b.not_run and "lib/'s folders" in b.not_run]
    lines = listing.text.splitlines()
    assert lines[0] == "lib/", lines[0]
    named = {word.rstrip("/") for line in lines[1:] if line.startswith("  ") and not line.startswith("   ")
             for word in line.split() if word.endswith("/") and len(word) > 1}
    folders = {p.name for p in (ROOT / "lib").iterdir() if p.is_dir()}
    assert named == folders, f"README.md's listing of lib/ names {sorted(named)}; lib/ holds {sorted(folders)}"

#!/usr/bin/env python3
"""The pictures of README.md and docs/*.md, each made by the command its
caption names: this script reads those commands from the pages, so a
caption cannot name one command while the picture came from another.

  scripts/docs_pictures.py            each picture and the command that makes it
  scripts/docs_pictures.py --write    remake every picture with its command (make docs)
  scripts/docs_pictures.py --check    render each into a scratch folder and compare
                                      its pixels with the committed picture's
  (either takes picture paths, docs/demo.png ..., to do only those)

A picture is `![alt](file)` on a page; its caption is the paragraph after
the line that shows it, an italic one, and its command is the backquoted
`build/bin/hitray ...` or `python ...` in the caption that names the
picture's file as an argument. `build/` is the build tree HITRAY_BUILD_DIR
names (default build), `python` the interpreter running this script, and the
working directory the repository's root, as the pages have it.

Pages written whole by a measuring program show plots of times measured on
one machine, which no rerun reproduces; they are listed in MEASURED with the
program that writes them, and their pictures are not rendered here.
Every other image file under docs/ must be shown by some page with its
command: one no page shows is an error too.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
PICTURE = re.compile(r"!\[[^\]]*\]\((?P<file>[^)\s]+)\)")
CODE = re.compile(r"`([^`]+)`")
IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".svg", ".gif", ".webp")
# Pages a measuring program writes whole, plots included: what writes them.
MEASURED = {"docs/accuracy.md": "bench/drivers/run_accuracy.py (make bench-accuracy); "
                                "tests/bench/test_accuracy_driver.py runs it small"}
TIMEOUT = 600


@dataclasses.dataclass
class Picture:
    path: str         # from the repository's root: docs/demo.png
    page: str         # the page that shows it, and the line
    line: int
    command: list[str] | None   # its caption's command, as written
    problem: str | None = None  # why no command was found

    @property
    def where(self) -> str:
        return f"{self.page}:{self.line}"


def pages() -> list[str]:
    return ["README.md"] + sorted(f"docs/{p.name}" for p in (ROOT / "docs").glob("*.md"))


def caption_after(lines: list[str], i: int) -> str:
    """The paragraph after line i (a blank line between), lines joined by a
    space, if it is italic; else ''."""
    j = i + 1
    while j < len(lines) and not lines[j].strip():
        j += 1
    text = []
    while j < len(lines) and lines[j].strip():
        text.append(lines[j].strip())
        j += 1
    joined = " ".join(text)
    return joined if joined.startswith("*") else ""


def command_for(path: str, caption: str) -> list[str] | None:
    for code in CODE.findall(caption):
        if not code.startswith(("build/bin/hitray ", "python ")):
            continue
        words = shlex.split(code)
        if path in words:
            return words
    return None


def pictures(page: str) -> list[Picture]:
    found = []
    lines = (ROOT / page).read_text(encoding="utf-8").splitlines()
    for i, line in enumerate(lines):
        for m in PICTURE.finditer(line):
            if re.match(r"[a-z]+://", m["file"]):
                continue
            path = os.path.normpath(os.path.join(os.path.dirname(page), m["file"]))
            if page in MEASURED:
                found.append(Picture(path, page, i + 1, None, None))
                continue
            caption = caption_after(lines, i)
            command = command_for(path, caption)
            problem = None
            if not caption:
                problem = "no caption (an italic paragraph after it) names the command that makes it"
            elif command is None:
                problem = (f"its caption names no `build/bin/hitray ...` or `python ...` command "
                           f"writing {path}")
            found.append(Picture(path, page, i + 1, command, problem))
    return found


def every_picture() -> list[Picture]:
    """The pictures the pages show, and an entry with a problem for each
    image file under docs/ that no page shows."""
    found = [p for page in pages() for p in pictures(page)]
    shown = {p.path for p in found}
    for f in sorted((ROOT / "docs").rglob("*")):
        rel = f.relative_to(ROOT).as_posix()
        if f.suffix.lower() in IMAGE_SUFFIXES and rel not in shown:
            found.append(Picture(rel, rel, 0, None, "no page of README.md or docs/ shows it"))
    for p in found:
        if p.problem is None and not (ROOT / p.path).is_file():
            p.problem = f"{p.path} is not in the repository"
    return found


def build_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("HITRAY_BUILD_DIR", ROOT / "build")).resolve()


def make(picture: Picture, out: pathlib.Path) -> None:
    """Run the picture's command with `out` in place of the picture's file."""
    assert picture.command is not None
    argv = [str(out) if w == picture.path else w for w in picture.command]
    if argv[0] == "python":
        argv[0] = sys.executable
    elif argv[0].startswith("build/"):
        argv[0] = str(build_dir() / argv[0][len("build/"):])
    env = dict(os.environ, HITRAY_BUILD_DIR=str(build_dir()))
    done = subprocess.run(argv, cwd=ROOT, env=env, stdin=subprocess.DEVNULL, capture_output=True,
                          text=True, timeout=TIMEOUT)
    if done.returncode != 0 or not out.is_file():
        raise RuntimeError(f"{picture.where}: `{shlex.join(picture.command)}` failed "
                           f"({done.returncode}):\n{done.stdout}{done.stderr}")


def pixels(path: pathlib.Path):
    """The decoded pixels (PNG bytes differ with zlib's version and
    settings; the pixels do not)."""
    import numpy
    from PIL import Image

    with Image.open(path) as image:
        return image.mode, numpy.asarray(image).astype(numpy.int32)


def differences(made: pathlib.Path, committed: pathlib.Path) -> str | None:
    """None where the two pictures agree, else what differs.

    On the build that made it the picture is the same bit for bit (the
    render is the same whatever the thread count). Another compiler may
    contract a multiply-add differently and move a value across an 8-bit
    step: at most one step, on at most 0.1% of the pixels, passes."""
    (mode_a, a), (mode_b, b) = pixels(made), pixels(committed)
    if (mode_a, a.shape) != (mode_b, b.shape):
        return f"made {mode_a} {a.shape[1]}x{a.shape[0]}, committed {mode_b} {b.shape[1]}x{b.shape[0]}"
    step = abs(a - b)
    if step.ndim == 3:
        step = step.max(axis=2)
    if step.max() <= 1 and (step > 0).mean() <= 1e-3:
        return None
    return (f"{(step > 0).sum()} of {step.size} pixels differ ({100 * (step > 0).mean():.1f}%), "
            f"by up to {step.max()} of 255")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument("--write", action="store_true", help="remake the pictures (make docs)")
    mode.add_argument("--check", action="store_true", help="compare them with what their commands make now")
    ap.add_argument("only", nargs="*", help="these pictures (docs/demo.png ...), not all")
    a = ap.parse_args(argv)
    found = every_picture()
    if a.only:
        unknown = set(a.only) - {p.path for p in found}
        if unknown:
            ap.error(f"no page shows {', '.join(sorted(unknown))}")
        found = [p for p in found if p.path in a.only]
    failed = 0
    for p in found:
        if p.problem:
            print(f"{p.where}: {p.path}: {p.problem}", file=sys.stderr)
            failed += 1
        elif p.command is None:
            print(f"{p.path}: measured, written by {MEASURED[p.page]}")
        elif not (a.write or a.check):
            print(f"{p.path}: {shlex.join(p.command)}")
        else:
            # Written beside the picture, then renamed over it: never half a picture.
            beside = ROOT / pathlib.Path(p.path).parent if a.write else None
            with tempfile.TemporaryDirectory(dir=beside) as tmp:
                out = pathlib.Path(tmp) / pathlib.Path(p.path).name
                make(p, out)
                if a.write:
                    out.replace(ROOT / p.path)
                    print(f"{p.path}: made by {shlex.join(p.command)}")
                    continue
                problem = differences(out, ROOT / p.path)
                if problem:
                    print(f"{p.where}: {p.path} is not what `{shlex.join(p.command)}` makes now: {problem} "
                          f"(make docs remakes it)", file=sys.stderr)
                    failed += 1
                else:
                    print(f"{p.path}: as its command makes it")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

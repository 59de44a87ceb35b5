"""python -m hitray.distributed: `hitray render` on a Dask cluster.

    python -m hitray.distributed render SCENE -o OUT [--scheduler ADDRESS | --workers N] [--tile N] ...
    python -m hitray.distributed frames SCRIPT.py -o 'frame_%04d.png' [...]

SCRIPT.py is run as a Python file and must define ``frames``: a sequence of
(scene, camera) pairs, or a function of the frame number returning one,
with ``count`` the number of frames. Errors print one line on stderr and
exit with status 1 (2 for a usage error).
"""

from __future__ import annotations

import argparse
import os
import runpy
import sys
import traceback
from typing import Any, Dict, List, NoReturn, Optional, Sequence, Tuple

from .. import Camera, Error, load_nff, load_sdl
from ._client import SchedulerUnreachable, connect
from ._pack import ShippingError
from ._render import render, render_frames
from ._report import Report

PROG = "python -m hitray.distributed"
# Image.save's formats, by extension.
_EXTENSIONS = (".png", ".exr", ".ppm", ".pfm")


class _Parser(argparse.ArgumentParser):
    """argparse, its usage errors one line (the program, what is wrong and
    where to look) and exit status 2, as the docs promise."""

    def error(self, message: str) -> NoReturn:
        sys.stderr.write(f"{PROG}: {message} (see {self.prog} --help)\n")
        sys.exit(2)


def _message(e: BaseException) -> str:
    """An error's text without the prefix the package's own messages carry
    (the command line puts its own in front)."""
    text = str(e)
    return text[len("hitray.distributed: "):] if text.startswith("hitray.distributed: ") else text


def _size(text: str) -> Tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected WxH, such as 640x480, not {text!r}") from None
    if not (1 <= w <= 65536 and 1 <= h <= 65536):
        raise argparse.ArgumentTypeError(f"width and height must be within 1..65536, not {text!r}")
    return (w, h)


def _camera(text: str) -> Camera:
    try:
        v = [float(p) for p in text.split(",")]
    except ValueError:
        v = []
    if len(v) != 10:
        raise argparse.ArgumentTypeError(f"expected EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE (10 numbers), not {text!r}")
    return Camera((v[0], v[1], v[2]), (v[3], v[4], v[5]), (v[6], v[7], v[8]), v[9])


def _positive(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        n = 0
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number at least 1, not {text!r}")
    return n


def _parser() -> argparse.ArgumentParser:
    p = _Parser(prog=PROG,
                                description="Render scenes and animations on a Dask cluster, bit for bit "
                                            "the images `hitray render` gives.")
    verbs = p.add_subparsers(dest="verb", required=True)
    verbs._parser_class = _Parser  # the verbs' errors one line too
    common = _Parser(add_help=False)
    where = common.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="a running Dask scheduler (tcp://host:8786); default: a local cluster")
    where.add_argument("--workers", type=_positive, metavar="N",
                       help="worker processes of the local cluster (default 1)")
    common.add_argument("--timeout", type=float, default=10.0, metavar="SECONDS",
                        help="how long to wait for the scheduler to answer (default 10)")
    common.add_argument("--tile", type=_positive, metavar="N",
                        help="fixed square tiles of N pixels (default: bands sized by the workers' speed)")
    common.add_argument("--size", type=_size, default=(640, 480), metavar="WxH",
                        help="image size in pixels (default 640x480)")
    common.add_argument("--spp", type=_positive, default=1, metavar="N", help="samples per pixel (default 1)")
    common.add_argument("--depth", type=int, metavar="N", help="recursion depth (default: the scene's)")
    common.add_argument("--block", type=_positive, default=1, metavar="N",
                        help="Hill's blocksize: one ray per NxN pixels (default 1)")
    common.add_argument("--effects", choices=("auto", "all"), default="auto",
                        help="auto: only the effects the scene calls for; all: every effect's code")
    common.add_argument("--adaptive", type=float, default=0.0, metavar="T",
                        help="adaptive supersampling threshold (0..1; needs --spp >= 2)")
    common.add_argument("--min-weight", type=float, default=0.0, metavar="W",
                        help="contribution cut-off (default 2^-24)")
    common.add_argument("--exact", action="store_true", help="trace every contribution (no cut-off)")
    common.add_argument("--texture-filter", choices=("footprint", "none"), default="footprint",
                        help="footprint (default): average each texture over the pixel's footprint; "
                             "none: point-sample it at the hit")
    common.add_argument("--png16", action="store_true", help="16-bit PNG")
    common.add_argument("--linear-png", action="store_true", help="PNG values linear, not sRGB-encoded")
    common.add_argument("--exr-half", action="store_true", help="EXR with 16-bit half floats")
    common.add_argument("-q", "--quiet", action="store_true",
                        help="no progress bar (there is one only when standard error is a terminal)")
    r = verbs.add_parser("render", parents=[common], help="render one scene file")
    r.add_argument("scene", metavar="SCENE", help="Hill's SDL, or NFF if it ends in .nff or .nff.gz")
    r.add_argument("-o", "--output", required=True, metavar="OUT", help=".png, .exr, .ppm or .pfm")
    r.add_argument("--exr", metavar="FILE", help="also write the linear image as OpenEXR")
    r.add_argument("--camera", type=_camera, metavar="EX,EY,EZ,LX,LY,LZ,UX,UY,UZ,ANGLE",
                   help="overrides the scene's camera")
    f = verbs.add_parser("frames", parents=[common], help="render an animation defined by a Python script")
    f.add_argument("script", metavar="SCRIPT.py",
                   help="defines `frames`: (scene, camera) pairs, or a function of the frame number with `count`")
    f.add_argument("-o", "--output", required=True, metavar="PATTERN",
                   help="one file per frame: 'frame_%%04d.png'; frames already written are skipped")
    f.add_argument("--frames-in-flight", type=_positive, metavar="N",
                   help="frames in progress at once (default: two per worker)")
    return p


def _options(a: argparse.Namespace) -> Dict[str, Any]:
    return {"size": a.size, "spp": a.spp, "depth": a.depth, "block_size": a.block,
            "all_effects": a.effects == "all", "adaptive": a.adaptive, "min_weight": a.min_weight,
            "exact": a.exact, "texture_filter": a.texture_filter, "tile": a.tile, "timeout": a.timeout,
            "progress": False if a.quiet else None}


def _load(path: str) -> Tuple[Any, Optional[Camera]]:
    lower = path.lower()
    return load_nff(path) if lower.endswith((".nff", ".nff.gz")) else load_sdl(path)


class ScriptError(Exception):
    """A frames script that failed: one line naming its file and line."""


def _run_script(path: str) -> Dict[str, Any]:
    """The names a frames script defines; its failure as one ScriptError
    naming the script's line (the innermost frame in the script itself)."""
    try:
        return runpy.run_path(path, run_name="__hitray_frames__")
    except SyntaxError as e:
        raise ScriptError(f"{path}:{e.lineno}: {e.msg}") from None
    except (KeyboardInterrupt, SystemExit):
        raise
    except BaseException as e:  # noqa: B902 - whatever the script raised, reported as one line
        where = [f.lineno for f in traceback.extract_tb(e.__traceback__)
                 if os.path.abspath(f.filename) == os.path.abspath(path)]
        line = f":{where[-1]}" if where else ""
        raise ScriptError(f"{path}{line}: {type(e).__name__}: {e}") from None


def _script_frames(path: str) -> Tuple[Any, Optional[int]]:
    if not os.path.isfile(path):
        raise FileNotFoundError(f"{path}: no such script")
    names = _run_script(path)
    if "frames" not in names:
        raise ValueError(f"{path}: the script defines no `frames`")
    frames, count = names["frames"], names.get("count")
    if callable(frames) and count is None:
        raise ValueError(f"{path}: `frames` is a function: the script must define `count` too")
    return frames, count


def _check_output(path: str, what: str) -> None:
    """Before any rendering: the output's format is known by its extension
    and its folder is one this process may write in."""
    if os.path.isdir(path):
        raise IsADirectoryError(f"{path}: {what} is a directory")
    if not path.lower().endswith(_EXTENSIONS):
        raise ValueError(f"{path}: {what} must end in {', '.join(_EXTENSIONS)} (the format comes from it)")
    folder = os.path.dirname(path) or "."
    if not os.path.isdir(folder):
        raise FileNotFoundError(f"{path}: no such directory {folder!r} to write {what} in")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise PermissionError(f"{path}: the directory {folder!r} is not writable")


def _check_outputs(a: argparse.Namespace) -> None:
    if a.verb == "render":
        _check_output(a.output, "the output")
        if a.exr:
            _check_output(a.exr, "--exr")
        return
    try:
        first = a.output % 0
    except (TypeError, ValueError):
        return  # render_frames says what is wrong with the pattern, before rendering
    _check_output(first, "the output pattern")


def main(argv: Optional[Sequence[str]] = None) -> int:
    a = _parser().parse_args(argv)
    opts = _options(a)
    save = {"bits": 16 if a.png16 else 8, "linear": a.linear_png, "half": a.exr_half}
    try:
        # Everything that can be checked here is, before the cluster is
        # asked for anything: the outputs, the scene or the frames script.
        _check_outputs(a)
        if a.verb == "render":
            scene, camera = _load(a.scene)
        else:
            frames, count = _script_frames(a.script)
        with connect(a.scheduler, a.workers, a.timeout) as client:
            report = Report()
            if a.verb == "render":
                image = render(scene, a.camera or camera, client=client, report=report, **opts)
                image.save(a.output, **save)
                if a.exr:
                    image.save(a.exr, half=a.exr_half)
                s = image.stats
                assert s is not None
                print(f"{a.output}: {a.size[0]}x{a.size[1]}, {s.seconds:.2f} s, {s.rays} rays "
                      f"on {s.threads} worker threads")
            else:
                written: List[str] = render_frames(frames, a.output, count, client=client,
                                                   frames_in_flight=a.frames_in_flight, report=report,
                                                   **opts, **save)
                print(f"{len(written)} frames written")
            if report.tasks:
                print("\n".join(report.lines()))
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    except (Error, SchedulerUnreachable, ShippingError, ScriptError, OSError, ValueError, TypeError,
            ImportError) as e:
        print(f"{PROG}: {_message(e)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

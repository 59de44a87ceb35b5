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
from typing import Any, Dict, List, Optional, Sequence, Tuple

from .. import Camera, Error, load_nff, load_sdl
from ._client import SchedulerUnreachable, connect
from ._pack import ShippingError
from ._render import render, render_frames


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
    p = argparse.ArgumentParser(prog="python -m hitray.distributed",
                                description="Render scenes and animations on a Dask cluster, bit for bit "
                                            "the images `hitray render` gives.")
    verbs = p.add_subparsers(dest="verb", required=True)
    common = argparse.ArgumentParser(add_help=False)
    where = common.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="a running Dask scheduler (tcp://host:8786); default: a local cluster")
    where.add_argument("--workers", type=_positive, metavar="N",
                       help="worker processes of the local cluster (default 1)")
    common.add_argument("--timeout", type=float, default=10.0, metavar="SECONDS",
                        help="how long to wait for the scheduler to answer (default 10)")
    common.add_argument("--tile", type=_positive, default=64, metavar="N", help="tile side in pixels (default 64)")
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
    common.add_argument("--png16", action="store_true", help="16-bit PNG")
    common.add_argument("--linear-png", action="store_true", help="PNG values linear, not sRGB-encoded")
    common.add_argument("--exr-half", action="store_true", help="EXR with 16-bit half floats")
    common.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
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
    f.add_argument("--frames-in-flight", type=_positive, default=4, metavar="N",
                   help="frames whose tiles are scheduled together (default 4)")
    return p


def _options(a: argparse.Namespace) -> Dict[str, Any]:
    return {"size": a.size, "spp": a.spp, "depth": a.depth, "block_size": a.block,
            "all_effects": a.effects == "all", "adaptive": a.adaptive, "min_weight": a.min_weight,
            "exact": a.exact, "tile": a.tile, "timeout": a.timeout, "progress": not a.quiet}


def _load(path: str) -> Tuple[Any, Optional[Camera]]:
    lower = path.lower()
    return load_nff(path) if lower.endswith((".nff", ".nff.gz")) else load_sdl(path)


def _script_frames(path: str) -> Tuple[Any, Optional[int]]:
    if not os.path.isfile(path):
        raise FileNotFoundError(f"{path}: no such script")
    names = runpy.run_path(path, run_name="__hitray_frames__")
    if "frames" not in names:
        raise ValueError(f"{path}: the script defines no `frames`")
    frames, count = names["frames"], names.get("count")
    if callable(frames) and count is None:
        raise ValueError(f"{path}: `frames` is a function: the script must define `count` too")
    return frames, count


def main(argv: Optional[Sequence[str]] = None) -> int:
    a = _parser().parse_args(argv)
    opts = _options(a)
    save = {"bits": 16 if a.png16 else 8, "linear": a.linear_png, "half": a.exr_half}
    try:
        with connect(a.scheduler, a.workers, a.timeout) as client:
            if a.verb == "render":
                scene, camera = _load(a.scene)
                image = render(scene, a.camera or camera, client=client, **opts)
                image.save(a.output, **save)
                if a.exr:
                    image.save(a.exr, half=a.exr_half)
                s = image.stats
                assert s is not None
                print(f"{a.output}: {a.size[0]}x{a.size[1]}, {s.seconds:.2f} s, {s.rays} rays "
                      f"on {s.threads} worker threads")
            else:
                frames, count = _script_frames(a.script)
                written: List[str] = render_frames(frames, a.output, count, client=client,
                                                   frames_in_flight=a.frames_in_flight, **opts, **save)
                print(f"{len(written)} frames written")
    except KeyboardInterrupt:
        print("python -m hitray.distributed: interrupted", file=sys.stderr)
        return 130
    except (Error, SchedulerUnreachable, ShippingError, OSError, ValueError, TypeError, ImportError) as e:
        print(f"python -m hitray.distributed: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

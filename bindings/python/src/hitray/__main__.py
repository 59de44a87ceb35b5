"""``python -m hitray`` and the ``hitray`` script of the wheel: the command
line program the package carries (``hitray/bin/hitray``, beside the library
and shape modules it finds through its RPATH), run with these arguments in
place of this process, so its exit status, output and signals are the
program's own."""

from __future__ import annotations

import os
import pathlib
import sys
from typing import List, Optional

PROGRAM = pathlib.Path(__file__).resolve().parent / "bin" / "hitray"


def main(argv: Optional[List[str]] = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if not os.access(PROGRAM, os.X_OK):
        print(f"hitray: the command line program {PROGRAM} is missing or not executable "
              "(reinstall the package: pip install --force-reinstall hitray)", file=sys.stderr)
        return 1
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(PROGRAM, ["hitray", *args])
    return 1  # not reached: execv replaces this process or raises


if __name__ == "__main__":
    sys.exit(main())

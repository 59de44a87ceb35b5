"""Whether, and how, to draw a progress bar.

A bar is for someone watching: standard error a terminal, or a Jupyter
notebook. Anywhere else (a log file, a pipe, a batch job) it would only fill
the output with carriage returns, so the default draws none there, as the
`hitray` command does. ``progress=True`` forces one, ``False`` shows none.
"""

from __future__ import annotations

import importlib.util
import sys
from typing import Any, Optional

__all__ = ["wanted", "tqdm_class"]


def in_notebook() -> bool:
    """Whether this runs in a Jupyter kernel (IPython's kernel app)."""
    ipython = sys.modules.get("IPython")
    get = getattr(ipython, "get_ipython", None)
    shell = get() if callable(get) else None
    return shell is not None and "IPKernelApp" in getattr(shell, "config", {})


def _stderr_is_terminal() -> bool:
    # sys.stderr may be None (pythonw, a daemon), replaced by an object
    # without isatty, or closed (ValueError).
    isatty = getattr(sys.stderr, "isatty", None)
    try:
        return bool(isatty()) if callable(isatty) else False
    except (OSError, ValueError):
        return False


def wanted(progress: Optional[bool]) -> bool:
    """Whether to draw a bar for a `progress` argument of True (always),
    False (never) or None (auto: standard error a terminal, or a notebook)."""
    if progress is None:
        return _stderr_is_terminal() or in_notebook()
    return progress is True


def tqdm_class() -> Any:
    """tqdm's notebook widget where it can be drawn, its plain text bar
    everywhere else. tqdm.auto would pick the widget in any notebook and,
    without ipywidgets, warn (TqdmWarning: IProgress not found) before
    falling back; this falls back without the warning."""
    if in_notebook() and importlib.util.find_spec("ipywidgets") is not None:
        from tqdm.notebook import tqdm as notebook_tqdm  # type: ignore[import-untyped, unused-ignore]
        return notebook_tqdm
    from tqdm.std import tqdm as text_tqdm  # type: ignore[import-untyped, unused-ignore]
    return text_tqdm

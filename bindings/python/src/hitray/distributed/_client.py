"""The Dask client a distributed render runs on: the caller's, one connected
to a scheduler's address, or a LocalCluster started for the render."""

from __future__ import annotations

import contextlib
import os
from typing import Any, Iterator, Optional

__all__ = ["SchedulerUnreachable", "dask_distributed", "connect", "local_cores"]


class SchedulerUnreachable(ConnectionError):
    """No Dask scheduler answered at the address within the timeout."""


def dask_distributed() -> Any:
    """The module ``distributed``, or an ImportError that says how to get it."""
    try:
        import distributed
    except ImportError as e:
        raise ImportError("hitray.distributed needs Dask's distributed scheduler: "
                          "pip install 'hitray[distributed]' (or 'dask[distributed]')") from e
    return distributed


def local_cores() -> int:
    """The cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


@contextlib.contextmanager
def connect(client: Any = None, workers: Optional[int] = None, timeout: float = 10.0) -> Iterator[Any]:
    """The client to render on, closed afterwards if made here.

    `client`: a ``distributed.Client`` (used as it is), a scheduler address
    such as ``"tcp://10.0.0.5:8786"`` (connected to, giving up after
    `timeout` seconds with SchedulerUnreachable), or None: a LocalCluster on
    this machine of `workers` processes (None: one) sharing its cores.
    """
    distributed = dask_distributed()
    if isinstance(client, distributed.Client):
        yield client
        return
    if client is not None and not isinstance(client, str):
        raise TypeError(f"hitray.distributed: client must be a distributed.Client, a scheduler address "
                        f"or None, not {type(client).__name__}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"hitray.distributed: workers must be a whole number at least 1, not {workers!r}")
    if not timeout > 0:
        raise ValueError(f"hitray.distributed: timeout must be positive, not {timeout!r}")
    if isinstance(client, str):
        if workers is not None:
            raise ValueError("hitray.distributed: workers starts a local cluster; a scheduler's workers "
                             "are started on their machines (dask worker ADDRESS)")
        try:
            made = distributed.Client(client, timeout=timeout)
        except (OSError, TimeoutError, ValueError) as e:
            raise SchedulerUnreachable(f"hitray.distributed: no Dask scheduler answered at {client!r} "
                                       f"within {timeout:g} s ({e})") from None
        try:
            yield made
        finally:
            made.close()
        return
    n = 1 if workers is None else workers
    # ":0": the scheduler's HTTP server (health checks, and the dashboard
    # where bokeh is installed) on a free port, so clusters never collide.
    cluster = distributed.LocalCluster(n_workers=n, threads_per_worker=max(1, local_cores() // n),
                                       processes=True, dashboard_address=":0")
    try:
        made = distributed.Client(cluster)
        try:
            yield made
        finally:
            made.close()
    finally:
        cluster.close()

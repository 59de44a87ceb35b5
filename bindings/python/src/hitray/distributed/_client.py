"""The Dask client a distributed render runs on: the caller's, one connected
to a scheduler's address, or a LocalCluster started for the render."""

from __future__ import annotations

import contextlib
import os
import socket
import struct
import time
from typing import Any, Iterator, Optional, Tuple

__all__ = ["SchedulerUnreachable", "dask_distributed", "connect", "probe", "local_cores", "QUIET"]

# Dask's own monitoring, relaxed for a cluster that renders. By default
# every worker and scheduler wakes 50 times a second (the event loop's
# tick), measures its memory 10 times a second and samples its threads'
# stacks 100 times a second: 20-30 ms of CPU a second per process on the
# development machine, a few percent of its cores taken from rendering.
# These settings bring that under 7 ms (docs/distributed.md); the
# LocalClusters made here use them, and a cluster's workers can be given
# them as DASK_DISTRIBUTED__... environment variables.
QUIET = {"distributed.admin.tick.interval": "500ms", "distributed.admin.system-monitor.interval": "2s",
         "distributed.worker.memory.monitor-interval": "1s", "distributed.worker.profile.enabled": False}


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


# A Dask scheduler's first message on a new connection is its handshake: an
# 8-byte little-endian length, then that many bytes of msgpack, a few hundred
# (distributed/comm/tcp.py). A length past this is not Dask talking.
_HANDSHAKE_MOST = 1 << 20


def _host_port(address: str) -> Optional[Tuple[str, int]]:
    """(host, port) of a tcp:// (or schemeless) address; None for the other
    schemes (tls://, ws://, inproc://), which only Dask itself can speak."""
    scheme, sep, rest = address.partition("://")
    if not sep:
        scheme, rest = "tcp", address
    if scheme != "tcp":
        return None
    host, colon, port = rest.rpartition(":")
    if not colon or not port.isdigit():
        raise ValueError("expected tcp://HOST:PORT")
    return host.strip("[]") or "127.0.0.1", int(port)


def probe(address: str, timeout: float) -> None:
    """Check that a Dask scheduler answers at `address` within `timeout`
    seconds in all: the TCP connect and its handshake's first bytes. A port
    nobody listens on fails at once; a silent listener, or one speaking
    another protocol (the dashboard's HTTP on 8787), fails by the deadline.
    Dask's own connect bounds only the connect, not the handshake read
    that follows, so it is not left to meet these. Raises
    SchedulerUnreachable naming the address."""
    def unreachable(why: str) -> SchedulerUnreachable:
        return SchedulerUnreachable(f"hitray.distributed: no Dask scheduler answered at {address!r} "
                                    f"within {timeout:g} s ({why})")

    try:
        where = _host_port(address)
    except ValueError as e:
        raise unreachable(str(e)) from None
    if where is None:
        return
    deadline = time.monotonic() + timeout
    header = b""
    try:
        with socket.create_connection(where, timeout=timeout) as s:
            while len(header) < 8:
                left = deadline - time.monotonic()
                if left <= 0:
                    break
                s.settimeout(left)
                got = s.recv(8 - len(header))
                if not got:
                    raise unreachable("the connection was closed before a handshake")
                header += got
    except socket.timeout:
        pass
    except SchedulerUnreachable:
        raise
    except OSError as e:
        raise unreachable(e.strerror or str(e)) from None
    if len(header) < 8:
        raise unreachable("nothing there sent a Dask handshake")
    (length,) = struct.unpack("<Q", header)
    if not 0 < length <= _HANDSHAKE_MOST:
        raise unreachable("the server there does not speak Dask's protocol")


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
        started = time.monotonic()
        probe(client, timeout)
        try:
            made = distributed.Client(client, timeout=max(0.1, timeout - (time.monotonic() - started)))
        except Exception as e:  # noqa: BLE001 - any failure to connect is the one error the docs promise
            raise SchedulerUnreachable(f"hitray.distributed: no Dask scheduler answered at {client!r} "
                                       f"within {timeout:g} s ({e})") from None
        try:
            yield made
        finally:
            made.close()
        return
    n = 1 if workers is None else workers
    import dask

    with dask.config.set(QUIET):
        # ":0": the scheduler's HTTP server (health checks, and the dashboard
        # where bokeh is installed) on a free port, so clusters never collide.
        cluster = distributed.LocalCluster(n_workers=n, threads_per_worker=max(1, local_cores() // n),
                                           processes=True, dashboard_address=":0")
        try:
            # Straight to the workers (all on this machine): a band's call to a
            # worker's actor then skips the scheduler.
            made = distributed.Client(cluster, direct_to_workers=True)
            try:
                yield made
            finally:
                made.close()
        finally:
            cluster.close()

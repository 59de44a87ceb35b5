"""hitray.distributed's errors without a cluster: a scheduler address where
something else answers (a silent listener, an HTTP server, a refused port,
garbage), and `python -m hitray.distributed`'s one-line errors (usage, the
output checked before anything is rendered, a broken frames script)."""

import http.server
import socket
import subprocess
import sys
import threading

import pytest

import hitray

from conftest import TWO_SPHERES_SDL

pytest.importorskip("distributed", reason="dask[distributed] is not installed")
hd = pytest.importorskip("hitray.distributed")
from hitray.distributed import _client  # noqa: E402

PROG = "python -m hitray.distributed"


def unused_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def guarded(fn, limit=60):
    """fn() in a thread: what it raised, or a failure if it still runs after
    `limit` seconds (a hang, which the timeout should have ended)."""
    caught = []

    def attempt():
        try:
            fn()
        except BaseException as e:  # noqa: B902 - handed to the test thread
            caught.append(e)

    t = threading.Thread(target=attempt, daemon=True)
    t.start()
    t.join(limit)
    assert not t.is_alive(), "connecting hung past the timeout"
    assert len(caught) == 1, caught
    return caught[0]


@pytest.fixture
def silent_listener():
    """A port that accepts connections (the kernel's backlog) and never
    says a word."""
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    s.listen(4)
    yield f"tcp://127.0.0.1:{s.getsockname()[1]}"
    s.close()


@pytest.fixture
def http_server():
    """An HTTP server, as the dashboard on 8787 is (typed for 8786)."""
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), http.server.SimpleHTTPRequestHandler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"tcp://127.0.0.1:{server.server_address[1]}"
    server.shutdown()
    server.server_close()


@pytest.fixture
def chatty_server():
    """A server that greets with text (an SMTP or SSH banner would do)."""
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    s.listen(4)

    def serve():
        while True:
            try:
                conn, _ = s.accept()
            except OSError:
                return
            with conn:
                conn.sendall(b"HTTP/1.1 400 Bad Request\r\n\r\n")

    threading.Thread(target=serve, daemon=True).start()
    yield f"tcp://127.0.0.1:{s.getsockname()[1]}"
    s.close()


def unreachable_render(address, timeout=2):
    scene, camera = hitray.parse_sdl(TWO_SPHERES_SDL)
    return guarded(lambda: hd.render(scene, camera, (8, 8), client=address, timeout=timeout, progress=False))


@pytest.mark.parametrize("where", ["silent_listener", "http_server"])
def test_scheduler_address_that_accepts_but_is_not_dask(request, where):
    """Something accepts TCP but never sends Dask's handshake: the whole
    connect is bounded by the timeout, and it is SchedulerUnreachable naming
    the address (before the fix: a hang of over 100 s, or MemoryError)."""
    address = request.getfixturevalue(where)
    e = unreachable_render(address)
    assert isinstance(e, hd.SchedulerUnreachable), repr(e)
    assert f"no Dask scheduler answered at {address!r} within 2 s" in str(e)
    assert "sent a Dask handshake" in str(e)


def test_scheduler_address_that_speaks_another_protocol(chatty_server):
    e = unreachable_render(chatty_server)
    assert isinstance(e, hd.SchedulerUnreachable), repr(e)
    assert chatty_server in str(e) and "does not speak Dask's protocol" in str(e)


def test_scheduler_address_refused_says_so():
    """Nobody listens: the refusal is the answer (given at once, not after
    the timeout: the message is the kernel's, not the deadline's)."""
    address = f"tcp://127.0.0.1:{unused_port()}"
    e = unreachable_render(address, timeout=600)
    assert isinstance(e, hd.SchedulerUnreachable), repr(e)
    assert address in str(e) and "refused" in str(e).lower()


def test_probe_passes_other_schemes_to_dask():
    """tls:// and the rest are Dask's to speak: the probe leaves them."""
    assert _client.probe("tls://127.0.0.1:1", 1) is None
    with pytest.raises(hd.SchedulerUnreachable, match="expected tcp://HOST:PORT"):
        _client.probe("tcp://nohost", 1)


def dist_cli(*args, timeout=120):
    return subprocess.run([sys.executable, "-m", "hitray.distributed", *map(str, args)], capture_output=True,
                          text=True, timeout=timeout)


def one_line(proc):
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith(f"{PROG}: ") and "hitray.distributed: hitray.distributed" not in lines[0]
    return lines[0]


@pytest.fixture
def scene_file(tmp_path):
    path = tmp_path / "two.sdl"
    path.write_text(TWO_SPHERES_SDL)
    return path


@pytest.mark.parametrize("args, says", [
    (["--tile", "0"], "argument --tile: expected a whole number at least 1, not '0'"),
    (["--size", "10"], "argument --size: expected WxH"),
    (["--bogus"], "unrecognized arguments: --bogus"),
])
def test_cli_usage_errors_are_one_line_and_status_2(scene_file, tmp_path, args, says):
    proc = dist_cli("render", scene_file, "-o", tmp_path / "x.png", *args)
    assert proc.returncode == 2, proc.stderr
    assert says in one_line(proc)


def test_cli_usage_error_without_a_verb():
    proc = dist_cli()
    assert proc.returncode == 2 and "required: verb" in one_line(proc)


@pytest.mark.parametrize("output, says", [
    ("x.jpg", "x.jpg: the output must end in .png, .exr, .ppm, .pfm"),
    ("nowhere/x.png", "no such directory"),
    (".", "the output is a directory"),
])
def test_cli_output_checked_before_connecting(scene_file, tmp_path, output, says):
    """A bad output is reported before the cluster is asked for anything:
    here no scheduler listens, and the error is the output's."""
    address = f"tcp://127.0.0.1:{unused_port()}"
    proc = dist_cli("render", scene_file, "-o", tmp_path / output if output != "." else tmp_path,
                    "--scheduler", address)
    assert proc.returncode == 1
    assert says in one_line(proc)


def test_cli_frames_pattern_checked_before_connecting(tmp_path):
    script = tmp_path / "f.py"
    script.write_text("frames = []\n")
    proc = dist_cli("frames", script, "-o", tmp_path / "f_%03d.tif", "--scheduler",
                    f"tcp://127.0.0.1:{unused_port()}")
    assert proc.returncode == 1 and "f_000.tif: the output pattern must end in .png" in one_line(proc)


@pytest.mark.parametrize("body, says", [
    ("import math\ncount = 2\nx = 1 / 0\n", ":3: ZeroDivisionError: division by zero"),
    ("count = 2\ndef frames(i):\n    return (\n", ":3: '(' was never closed"),
    ("def helper():\n    raise RuntimeError('no camera')\n\nhelper()\n", ":2: RuntimeError: no camera"),
    ("count = 1\n", "the script defines no `frames`"),
])
def test_cli_broken_frames_script_is_one_line(tmp_path, body, says):
    """A frames script that fails: one line naming its file and the line
    (the innermost of the script's own), status 1, no traceback."""
    script = tmp_path / "orbit.py"
    script.write_text(body)
    proc = dist_cli("frames", script, "-o", tmp_path / "f_%03d.png", "--scheduler",
                    f"tcp://127.0.0.1:{unused_port()}")
    assert proc.returncode == 1
    line = one_line(proc)
    assert f"{script}" in line and says in line, line


def test_cli_unreachable_scheduler_has_one_prefix(scene_file, tmp_path, http_server):
    proc = dist_cli("render", scene_file, "-o", tmp_path / "x.png", "--scheduler", http_server, "--timeout", "2")
    assert proc.returncode == 1
    assert one_line(proc).startswith(f"{PROG}: no Dask scheduler answered at '{http_server}' within 2 s")
    assert not (tmp_path / "x.png").exists()

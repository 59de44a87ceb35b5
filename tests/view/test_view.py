"""Tests of `hitray view` (the hitray-view program), run as a user runs it.

The window opens on a private Xvfb server (Debian's xvfb), started once for
this file on a display number of its own choosing (-displayfd), so tests run
side by side never share one; key presses come from xdotool. Where Xvfb
cannot start, the tests that need a window are skipped with the reason.

What is checked: the final pass is `hitray render`'s image bit for bit (PFM
files hold the floats as they are, so equal files mean equal pixels), an
early pass is `hitray render --block N`'s, camera keys move the camera as
Hill's slide and yaw define and the next final pass is `hitray render
--camera` of the printed line; and every refusal is one located line and
exit status 1, with no window left open.
"""

import ctypes
import ctypes.util
import math
import os
import select
import shutil
import subprocess
import threading
import time

import pytest

from hitray_testing import BUILD, ROOT

HITRAY = BUILD / "bin" / "hitray"
VIEWER = BUILD / "bin" / "hitray-view"
DEMO = ROOT / "scenes" / "demo.sdl"
SIZE = "160x120"  # small: every pass of the demo takes milliseconds
WAIT = 60  # seconds before a wait counts as a hang (never a measure of speed)


def view_turned_off():
    """1 if the build was configured with -DHITRAY_BUILD_VIEW=OFF."""
    cache = BUILD / "CMakeCache.txt"
    return cache.is_file() and "HITRAY_BUILD_VIEW:BOOL=OFF" in cache.read_text(errors="replace")


@pytest.fixture(scope="module", autouse=True)
def built():
    if not HITRAY.is_file():
        pytest.fail(f"{HITRAY} is missing: build first (make build), or set HITRAY_BUILD_DIR")
    if not VIEWER.is_file():
        if view_turned_off():
            pytest.skip(f"{BUILD} was configured with -DHITRAY_BUILD_VIEW=OFF: no hitray-view to test")
        pytest.fail(f"{VIEWER} is missing: build first (make build, with SDL2), or set HITRAY_BUILD_DIR")


def clean_env(**extra):
    """The environment without any display, plus `extra`."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER", "HITRAY_SHAPE_PATH")}
    env.update(extra)
    return env


@pytest.fixture(scope="module")
def display():
    xvfb = shutil.which("Xvfb")
    if not xvfb:
        pytest.skip("Xvfb is not installed (Debian's xvfb; scripts/bootstrap.sh installs it)")
    if not shutil.which("xdotool"):
        pytest.fail("xdotool is not installed (Debian's xdotool; scripts/bootstrap.sh installs it)")
    read_end, write_end = os.pipe()
    proc = subprocess.Popen([xvfb, "-displayfd", str(write_end), "-screen", "0", "640x480x24", "-nolisten", "tcp"],
                            pass_fds=(write_end,), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    os.close(write_end)
    number = b""
    while select.select([read_end], [], [], WAIT)[0]:
        chunk = os.read(read_end, 64)
        if not chunk:
            break
        number += chunk
        if number.endswith(b"\n"):
            break
    os.close(read_end)
    if not number.strip().isdigit():
        proc.kill()
        _, err = proc.communicate()
        pytest.skip(f"Xvfb could not start: {err.decode(errors='replace').strip() or 'no display number'}")
    yield f":{number.strip().decode()}"
    proc.terminate()
    proc.wait(timeout=WAIT)


def run(*args, env, cwd=None):
    return subprocess.run([str(HITRAY), *map(str, args)], capture_output=True, text=True, env=env, cwd=cwd,
                          timeout=WAIT * 2)


def render(tmp_path, name, *args):
    out = tmp_path / name
    r = run("render", DEMO, "--size", SIZE, "-o", out, *args, env=clean_env())
    assert r.returncode == 0, r.stderr
    return out.read_bytes()


def camera_values(line):
    """The ten numbers of a printed 'camera ...' line (the text after the
    last 'camera ')."""
    words = line[line.rindex("camera ") + len("camera "):].split()
    assert len(words) == 10, line
    return [float(w) for w in words]


def view_windows(display):
    r = subprocess.run(["xdotool", "search", "--name", "^hitray view"], capture_output=True, text=True,
                       env=clean_env(DISPLAY=display), timeout=WAIT)
    return r.stdout.split()


# --- the passes --------------------------------------------------------------

@pytest.mark.parametrize("args", [(), ("--spp", "4"), ("--block", "8"), ("--block", "4", "--spp", "2"),
                                  ("--min-weight", "0.05", "--depth", "3"), ("--exact",)],
                         ids=["final", "final-spp4", "block8", "block4-spp2", "min-weight-depth", "exact"])
def test_view_last_pass_equals_render(display, tmp_path, args):
    """The pass the refinement ends with is `hitray render`'s image with the
    same options: the full-quality pass, or with --block N the block pass
    that `hitray render --block N` makes (an early pass of the plain run)."""
    shot = tmp_path / "shot.pfm"
    r = run("view", DEMO, "--size", SIZE, "--screenshot", shot, "--exit-when-done", *args,
            env=clean_env(DISPLAY=display))
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    assert r.stdout.splitlines() == [f"wrote {shot}: camera 7 4.2000000000000002 10  0 1.1000000000000001 0  "
                                     "0 1 0  38"]
    assert shot.read_bytes() == render(tmp_path, "ref.pfm", *args)
    assert view_windows(display) == []  # gone with the process


def test_view_block_passes_differ_from_the_final(display, tmp_path):
    """The block passes are coarser pictures, not the final one again: the
    --block 8 pass is the 8x8-block render and differs from the final."""
    block8 = render(tmp_path, "b8.pfm", "--block", "8")
    assert block8 != render(tmp_path, "full.pfm")


# --- the camera keys ---------------------------------------------------------

class Viewer:
    """hitray view running in the background, its stdout lines collected as
    they come (a line may come before the one a test waits for first: the
    final pass of a small image can be written before the next key is)."""

    def __init__(self, display, *args, cwd):
        self.display = display
        self.proc = subprocess.Popen([str(HITRAY), "view", *map(str, args)], stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True, env=clean_env(DISPLAY=display), cwd=cwd)
        self.lines, self.ended = [], False
        self.changed = threading.Condition()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.proc.stdout:
            with self.changed:
                self.lines.append(line.rstrip("\n"))
                self.changed.notify_all()
        with self.changed:
            self.ended = True
            self.changed.notify_all()

    def line(self, starts, nth=1, ends=""):
        """The nth stdout line so far beginning with `starts` and ending with
        `ends`, waiting for it."""
        def found():
            matches = [x for x in self.lines if x.startswith(starts) and x.endswith(ends)]
            return matches[nth - 1] if len(matches) >= nth else None
        with self.changed:
            if not self.changed.wait_for(lambda: found() is not None or self.ended, timeout=WAIT):
                title = self.title(wait=False)
                self.proc.kill()
                pytest.fail(f"no line {nth} starting {starts!r} from hitray view within {WAIT} s "
                            f"(title: {title!r}; lines: {self.lines!r}; stderr: {self.proc.stderr.read()!r})")
            line = found()
        assert line is not None, f"hitray view ended before printing {starts!r}: {self.proc.stderr.read()}"
        return line

    def exits_ok(self):
        """Whether the viewer exits with status 0; what it wrote to stderr
        otherwise, in the failure."""
        status = self.proc.wait(timeout=WAIT)
        assert status == 0, f"hitray view exited {status}: stderr {self.proc.stderr.read()!r}"
        return True

    def xdotool(self, *args):
        r = subprocess.run(["xdotool", *args], capture_output=True, text=True,
                           env=clean_env(DISPLAY=self.display), timeout=WAIT)
        assert r.returncode == 0, r.stderr
        return r.stdout.strip()

    def keys(self, *names):
        window = self.xdotool("search", "--sync", "--name", "^hitray view")
        self.xdotool("windowfocus", "--sync", window.split()[0])
        self.xdotool("key", "--delay", "20", *names)

    def title(self, wait=True):
        """The window's title (waiting for the window), or "" with wait=False
        and no window."""
        if not wait and not view_windows(self.display):
            return ""
        return self.xdotool("getwindowname", self.xdotool("search", "--sync", "--name", "^hitray view").split()[0])

    def close(self):
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait(timeout=WAIT)


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def scaled(a, s):
    return [x * s for x in a]


def unit(a):
    length = math.sqrt(sum(x * x for x in a))
    return [x / length for x in a]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def hill_forward_then_yaw_left(cam):
    """Hill's camera (chapter 7): n = (eye - look)/|..|, u = up x n, v = n x u.
    W slides by d = |eye - look| / 20 along -n (eye and look together); Left
    yaws by 5 degrees, n' = cos n + sin u, keeping v and the distance."""
    eye, look, up, angle = cam[0:3], cam[3:6], cam[6:9], cam[9]
    dist = math.sqrt(sum(x * x for x in sub(eye, look)))
    n = unit(sub(eye, look))
    u = unit(cross(up, n))
    v = cross(n, u)
    d = dist / 20.0
    eye = sub(eye, scaled(n, d))
    c, s = math.cos(math.radians(5.0)), math.sin(math.radians(5.0))
    n2 = [c * a + s * b for a, b in zip(n, u)]
    look = sub(eye, scaled(n2, dist))
    return eye + look + v + [angle]


def test_view_keys_move_the_camera_as_hill_defines(display, tmp_path):
    shot, saved = tmp_path / "shot.pfm", tmp_path / "saved.exr"
    viewer = Viewer(display, DEMO, "--size", SIZE, "--screenshot", shot, "-o", saved, cwd=tmp_path)
    try:
        first = viewer.line("wrote ")
        assert first == f"wrote {shot}: camera 7 4.2000000000000002 10  0 1.1000000000000001 0  0 1 0  38"
        title = viewer.title()
        assert "final pass" in title and "rays/s" in title and "effects: " in title and "shadows" in title
        # C prints the camera, W slides forward, Left yaws left, C again.
        viewer.keys("c", "w", "Left", "c")
        before = camera_values(viewer.line("camera "))
        after_line = viewer.line("camera ", nth=2)
        after = camera_values(after_line)
        assert before == [7, 4.2, 10, 0, 1.1, 0, 0, 1, 0, 38]
        expected = hill_forward_then_yaw_left(before)
        for got, want in zip(after, expected):
            assert got == pytest.approx(want, rel=1e-12, abs=1e-12)  # double rounding of a few operations
        # The final pass of that camera is written (a move's refinement
        # cancelled by the next key writes nothing).
        viewer.line(f"wrote {shot}: ", ends=after_line)
        camera_arg = ",".join(after_line.split()[1:])
        # Each camera line comes with its --camera option, the same numbers.
        assert viewer.line("--camera ", nth=2) == f"--camera {camera_arg}"
        assert shot.read_bytes() == render(tmp_path, "ref.pfm", "--camera", camera_arg)
        # The line is one for the SDL file: the scene with it renders the same.
        moved = tmp_path / "moved.sdl"
        # The copy names its pixmap by a relative path, as the demo does.
        shutil.copytree(DEMO.parent / "textures", tmp_path / "textures")
        moved.write_text("".join(after_line + "\n" if line.startswith("camera ") else line
                                 for line in DEMO.read_text().splitlines(keepends=True)))
        r = run("render", moved, "--size", SIZE, "-o", tmp_path / "moved.pfm", env=clean_env())
        assert r.returncode == 0, r.stderr
        assert (tmp_path / "moved.pfm").read_bytes() == shot.read_bytes()
        # P saves the picture shown (EXR from the extension) with its camera.
        viewer.keys("p")
        assert viewer.line("saved ") == f"saved {saved}: {after_line}"
        assert saved.read_bytes() == render(tmp_path, "ref.exr", "--camera", camera_arg)
        # P again saves beside it, numbered: the first picture stays.
        viewer.keys("p")
        second = tmp_path / "saved-2.exr"
        assert viewer.line("saved ", nth=2) == f"saved {second}: {after_line}"
        assert second.read_bytes() == saved.read_bytes()
        viewer.keys("Escape")
        assert viewer.exits_ok()
        assert viewer.proc.stderr.read() == ""
    finally:
        viewer.close()


def read_ppm(data):
    """(width, height, RGB bytes) of a binary PPM as hitray writes it."""
    magic, size, maxval, pixels = data.split(b"\n", 3)
    assert magic == b"P6" and maxval == b"255"
    width, height = map(int, size.split())
    return width, height, pixels


def window_pixels(display, window, width, height, zoom=1):
    """The window's pixels as the X server has them (libX11 through ctypes:
    Xvfb has no compositor, so this is what is on the screen), as 0xRRGGBB:
    of an image shown at `zoom` screen pixels a pixel, the centre of each
    image pixel's square (width x height being the window's)."""
    x11 = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XGetImage.restype = ctypes.c_void_p
    x11.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int, ctypes.c_uint,
                              ctypes.c_uint, ctypes.c_ulong, ctypes.c_int]
    x11.XGetPixel.restype = ctypes.c_ulong
    x11.XGetPixel.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int]
    x11.XDestroyImage.argtypes = [ctypes.c_void_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    connection = x11.XOpenDisplay(display.encode())
    assert connection, f"cannot open {display}"
    try:
        image = x11.XGetImage(connection, window, 0, 0, width, height, 0xFFFFFFFF, 2)  # ZPixmap
        assert image, "XGetImage failed"
        half = zoom // 2
        try:
            return [[x11.XGetPixel(image, zoom * x + half, zoom * y + half) & 0xFFFFFF
                     for x in range(width // zoom)] for y in range(height // zoom)]
        finally:
            x11.XDestroyImage(image)
    finally:
        x11.XCloseDisplay(connection)


def ppm_codes(data):
    """(width, height, rows of 0xRRGGBB) of a binary PPM as hitray writes it."""
    width, height, pixels = read_ppm(data)
    return width, height, [[(pixels[3 * (y * width + x)] << 16) | (pixels[3 * (y * width + x) + 1] << 8)
                            | pixels[3 * (y * width + x) + 2] for x in range(width)] for y in range(height)]


def window_zoom(viewer, image_width, image_height):
    """The viewer's window id and how many screen pixels an image pixel
    takes (a small image is shown at a whole multiple of its size)."""
    # A window found by name can be gone by the next request while SDL is
    # still setting the viewer up (BadWindow): then it is looked for again.
    for attempt in range(10):
        window = viewer.xdotool("search", "--sync", "--name", "^hitray view").split()[0]
        try:
            shell = viewer.xdotool("getwindowgeometry", "--shell", window)
            break
        except AssertionError:
            if attempt == 9:
                raise
            time.sleep(0.2)
    geometry = dict(line.split("=") for line in shell.split())
    width, height = int(geometry["WIDTH"]), int(geometry["HEIGHT"])
    zoom = width // image_width
    assert zoom >= 1 and (width, height) == (zoom * image_width, zoom * image_height)
    return int(window), zoom


def test_view_window_shows_the_final_pass(display, tmp_path):
    """What is on the screen is the final pass in 8-bit sRGB, the same codes
    `hitray render` writes to a PPM (a small image is shown at a whole
    multiple of its size: each image pixel is a square of screen pixels)."""
    shot = tmp_path / "shot.pfm"
    viewer = Viewer(display, DEMO, "--size", SIZE, "--screenshot", shot, cwd=tmp_path)
    try:
        viewer.line("wrote ")  # printed after the pass is drawn
        iw, ih, want = ppm_codes(render(tmp_path, "ref.ppm"))
        window, zoom = window_zoom(viewer, iw, ih)
        def wrong_pixels():
            screen = window_pixels(display, window, zoom * iw, zoom * ih, zoom)
            return sum(screen[y][x] != want[y][x] for y in range(ih) for x in range(iw))
        # The X server draws the viewer's requests in its own time: give it
        # a few seconds to show the pass the viewer has drawn.
        for _ in range(30):
            wrong = wrong_pixels()
            if wrong == 0:
                break
            time.sleep(0.1)
        assert wrong == 0, f"{wrong} of {iw * ih} pixels on the screen differ from hitray render's PPM"
        viewer.keys("Escape")
        assert viewer.exits_ok()
    finally:
        viewer.close()


TILE = 32  # hr_render's tiles (its default, which the viewer keeps)


def tile_sources(screen, sources):
    """For each 32x32 tile of the screen's image (row-major): the set of the
    named images in `sources` it equals in every pixel."""
    height, width = len(screen), len(screen[0])
    found = []
    for ty in range(0, height, TILE):
        for tx in range(0, width, TILE):
            cells = [(y, x) for y in range(ty, min(ty + TILE, height)) for x in range(tx, min(tx + TILE, width))]
            found.append({name for name, image in sources.items()
                          if all(screen[y][x] == image[y][x] for y, x in cells)})
    return found


def test_view_passes_replace_the_last_tile_by_tile(display, tmp_path):
    """While the full-quality pass runs (128 samples a pixel on one thread:
    seconds, its 20 tiles one after the other), the window shows its
    finished tiles and, everywhere else, the pass before it (one ray a
    pixel): every 32x32 tile on the screen is wholly one of the two, and a
    screenshot mid-pass holds tiles of each."""
    spp = "128"
    iw, ih, previous = ppm_codes(render(tmp_path, "previous.ppm"))
    _, _, final = ppm_codes(render(tmp_path, "final.ppm", "--spp", spp))
    sources = {"previous": previous, "final": final}
    viewer = Viewer(display, DEMO, "--size", SIZE, "--spp", spp, "--threads", "1", cwd=tmp_path)
    try:
        window, zoom = window_zoom(viewer, iw, ih)
        deadline, mixed = time.monotonic() + WAIT, False
        while time.monotonic() < deadline:
            tiles = tile_sources(window_pixels(display, window, zoom * iw, zoom * ih, zoom), sources)
            # Before the final pass the earlier passes show (tiles of
            # neither); once it runs, every tile is one of the two.
            if not all(tiles):
                continue
            mixed = any(t == {"final"} for t in tiles) and any(t == {"previous"} for t in tiles)
            if mixed or all("final" in t for t in tiles):  # seen, or the pass is over
                break
        assert mixed, f"no screenshot showed tiles of the final pass beside the pass before it (last: {tiles})"
        viewer.keys("Escape")
        assert viewer.exits_ok()
    finally:
        viewer.close()


def test_view_quits_during_a_pass_of_minutes(display, tmp_path):
    """Esc while the full-quality pass runs (65536 samples a pixel on one
    thread: far longer than WAIT) cancels it rather than waiting for it."""
    viewer = Viewer(display, DEMO, "--size", "64x48", "--spp", "65536", "--threads", "1", cwd=tmp_path)
    try:
        for _ in range(WAIT * 10):
            if "pass 6 of 6" in viewer.title():
                break
            time.sleep(0.1)
        else:
            pytest.fail(f"the final pass did not start: {viewer.title()!r}")
        viewer.keys("Escape")
        assert viewer.exits_ok()
    finally:
        viewer.close()


def test_view_help_key_lists_the_keys(display, tmp_path):
    viewer = Viewer(display, DEMO, "--size", "32x24", cwd=tmp_path)
    try:
        viewer.keys("h")
        assert "slide forward" in viewer.line("  W / S")
        viewer.keys("Escape")
        assert viewer.exits_ok()
    finally:
        viewer.close()


# --- refusals ----------------------------------------------------------------

def one_error_line(r, status=1):
    assert r.returncode == status, (r.stdout, r.stderr)
    assert r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("hitray: "), r.stderr
    return lines[0]


def test_view_without_a_display_says_so(tmp_path):
    line = one_error_line(run("view", DEMO, env=clean_env()))
    assert line == ("hitray: view: no display to open a window on (neither DISPLAY nor WAYLAND_DISPLAY is set); "
                    "'hitray render' writes the image to a file instead")


def test_view_unreachable_display_is_one_line(tmp_path):
    line = one_error_line(run("view", DEMO, env=clean_env(DISPLAY=":4095")))
    assert line.startswith("hitray: view: cannot open a window on DISPLAY ':4095': ")


def test_view_scene_error_is_located_and_no_window_opens(display, tmp_path):
    bad = tmp_path / "bad.sdl"
    bad.write_text("light 1 1 1  1 1 1\nsphere\npush translate 1 2 frog\n")
    line = one_error_line(run("view", bad, "--size", SIZE, env=clean_env(DISPLAY=display)))
    assert line.startswith(f"hitray: {bad}:3:20: ")
    assert view_windows(display) == []


def test_view_bad_camera_is_refused_before_a_window(display, tmp_path):
    line = one_error_line(run("view", DEMO, "--camera", "0,0,0,0,0,0,0,1,0,40", env=clean_env(DISPLAY=display)))
    assert "camera" in line
    assert view_windows(display) == []


@pytest.mark.parametrize("args, message, status", [
    (("--exit-when-done",), "--exit-when-done: needs --screenshot FILE", 2),
    (("--screenshot", "shot.gif"), "--screenshot: cannot tell the format of 'shot.gif'", 2),
    (("-o", "nodir/x.png"), "cannot write 'nodir/x.png': no directory 'nodir'", 1),
    (("--block", "0"), "--block", 2),
    (("--spp", "x"), "--spp", 2),
    (("--exact", "--min-weight", "0.1"), "--exact: cannot be combined with --min-weight", 2),
    (("--bogus",), "view: unknown option '--bogus'", 2),
])
def test_view_bad_options(tmp_path, args, message, status):
    line = one_error_line(run("view", DEMO, *args, env=clean_env(), cwd=tmp_path), status)
    assert message in line


def test_view_help_needs_no_display():
    r = run("view", "--help", env=clean_env())
    assert r.returncode == 0 and r.stderr == ""
    assert "usage: hitray view SCENE" in r.stdout and "W / S" in r.stdout and "--screenshot" in r.stdout


def test_view_without_the_viewer_beside_hitray(tmp_path):
    """hitray runs hitray-view from its own directory, never from PATH: a
    hitray without one beside it says where it looked."""
    (tmp_path / "bin").mkdir()
    (tmp_path / "lib").symlink_to(BUILD / "lib")
    lonely = tmp_path / "bin" / "hitray"
    shutil.copy2(HITRAY, lonely)
    r = subprocess.run([str(lonely), "view", DEMO], capture_output=True, text=True, env=clean_env(), timeout=WAIT)
    line = one_error_line(r)
    assert line == (f"hitray: view: the viewer '{tmp_path}/bin/hitray-view' is not there (it is built only where "
                    "SDL2 is installed, so pip's wheels leave it out: install Debian's libsdl2-dev and build "
                    "from source, make build)")

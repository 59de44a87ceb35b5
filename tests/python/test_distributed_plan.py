"""The scheduling logic of hitray.distributed (its Planner), alone and with
made-up timings: no cluster, no clock, so every assertion is exact.

A small event simulation plays workers of given speeds against the planner:
each worker holds two bands, renders them one after the other, and the
planner hears back each band's render time."""

import asyncio
import heapq
import os
import threading

import numpy as np
import pytest

plan = pytest.importorskip("hitray.distributed._plan")
Planner, Band = plan.Planner, plan.Band


def simulate(planner, speeds, cost=None, lose=None, depth=2):
    """Play workers (name -> pixels per second) against `planner` until it
    is finished, as the client does: each worker holds `depth` bands and
    renders them in order; an idle worker with nothing left to hand out
    steals the band waiting behind another's. `cost(frame, y)`: the
    relative cost of a row (1 if None). `lose`: (worker, time): that worker
    vanishes then, its bands given back. Returns every band done with its
    worker and start/end times."""
    cost = cost or (lambda f, y: 1.0)
    held = {w: [] for w in speeds}  # bands, in order; the first is rendering
    began = {}  # worker -> when its first band began
    done = []
    for w in speeds:
        planner.add_worker(w)

    def duration(w, band):
        x, y, bw, bh = band.window
        return sum(cost(band.frame, r) for r in range(y, y + bh)) * bw / speeds[w]

    def fill(now):
        for _ in range(depth):
            for w in sorted(held):
                if len(held[w]) < depth:
                    band = planner.next_band(w)
                    if band is None and not held[w]:
                        stolen = planner.steal(w)
                        if stolen is not None:
                            held[stolen[0]].remove(stolen[1])
                            band = planner.next_band(w)
                    if band is None:
                        continue
                    if not held[w]:
                        began[w] = now
                    held[w].append(band)

    now = 0.0
    fill(now)
    while any(held.values()):
        w = min((w for w in held if held[w]), key=lambda w: (began[w] + duration(w, held[w][0]), w))
        end = began[w] + duration(w, held[w][0])
        if lose and w != lose[0] and lose[0] in held and end > lose[1]:
            now = lose[1]
            planner.remove_worker(lose[0])
            del held[lose[0]]
            fill(now)
            continue
        now = end
        band = held[w].pop(0)
        done.append((band, w, began[w], now))
        began[w] = now
        planner.done(band, w, now - done[-1][2])
        fill(now)
    assert planner.finished()
    return done


def coverage(done, frames, size):
    covered = np.zeros((frames, size[1], size[0]), dtype=int)
    for band, *_ in done:
        x, y, w, h = band.window
        covered[band.frame, y:y + h, x:x + w] += 1
    return covered


def test_bands_cover_the_frame_once_in_full_rows():
    size = (300, 200)
    done = simulate(Planner(size, 1), {"a": 1e5, "b": 1e5})
    assert (coverage(done, 1, size) == 1).all()
    assert all(b.window[0] == 0 and b.window[2] == 300 for b, *_ in done)


def test_first_bands_are_probes():
    """Before anything is measured, a band is a sixteenth of the work per
    worker: a slow worker cannot hold the frame up."""
    p = Planner((100, 160), 1)
    p.add_worker("a")
    p.add_worker("b")
    assert p.next_band("a") == Band(0, (0, 0, 100, 5))
    assert p.next_band("b") == Band(0, (0, 5, 100, 5))


@pytest.mark.parametrize("speeds", [{"a": 1e5, "b": 1e5}, {"a": 3e5, "b": 1e5, "c": 5e4},
                                    {f"w{i}": 1e5 * (1 + i % 3) for i in range(8)}])
def test_workers_finish_within_one_band_of_each_other(speeds):
    """Workers of different speeds, rows of different cost (a band of the
    image costs 10 times the rest, as the planner is told by row_costs):
    the last worker ends no later than one of its last bands after the
    first ends, and the bands are few."""
    size = (640, 480)

    def cost(frame, y):
        return 10.0 if 200 <= y < 300 else 1.0

    planner = Planner(size, 1, min_seconds=0.01, row_costs=lambda f: [cost(f, y) for y in range(480)])
    done = simulate(planner, {w: v * 3.63 for w, v in speeds.items()}, cost)
    assert (coverage(done, 1, size) == 1).all()
    ends = {w: max(t for _, v, _, t in done if v == w) for w in speeds}
    last = {w: max((t - s for _, v, s, t in done if v == w and t == ends[w])) for w in speeds}
    assert max(ends.values()) - min(ends.values()) <= max(last.values()) + 1e-9
    # Guided self-scheduling: bands shrink geometrically (a third of the
    # work left each), so their number grows with the log of the frame's
    # time over the shortest band's.
    assert len(done) <= 20 * len(speeds)


def test_animation_whole_frames_then_bands():
    """More frames to do than workers: a task is a whole frame; the last
    frames are cut into bands so the animation ends with every worker busy."""
    size, frames = (64, 48), 20
    done = simulate(Planner(size, frames, open_frames=4, min_seconds=0.001), {"a": 1e4, "b": 1e4})
    assert (coverage(done, frames, size) == 1).all()
    whole = [b.frame for b, *_ in done if b.window == (0, 0, 64, 48)]
    cut = {b.frame for b, *_ in done if b.window != (0, 0, 64, 48)}
    # The first band of each worker is a probe (nothing is measured yet),
    # cutting frames 0 and 1.
    assert set(range(2, frames - 4)) <= set(whole)
    assert cut - {0, 1} and min(cut - {0, 1}) >= frames - 4


def test_open_frames_bound_what_is_in_progress():
    """Two frames open at most: a third is opened only when one is back."""
    p = Planner((10, 10), 5, open_frames=2, probe_share=1.0)
    p.add_worker("a")
    bands = [p.next_band("a") for _ in range(3)]
    assert [b.frame for b in bands[:2]] == [0, 1] and bands[2] is None
    assert p.done(bands[1], "a", 0.1)
    assert p.next_band("a").frame == 2


def test_a_lost_workers_bands_are_split_and_handed_on():
    """Worker "c" vanishes mid-frame: its bands go back and are rendered,
    cut into pieces, by the others; every pixel once."""
    size = (200, 400)
    speeds = {"a": 1e5, "b": 1e5, "c": 1e5}
    done = simulate(Planner(size, 1, min_seconds=0.001), speeds, lose=("c", 0.2))
    assert (coverage(done, 1, size) == 1).all()
    assert any(w == "c" for _, w, *_ in done) and all(t <= 0.2 for _, w, _, t in done if w == "c")


def test_given_back_band_is_cut_to_size():
    """All the work handed out, then worker "c" is lost: its band goes back
    and the next band given is the start of it, cut to a share of it."""
    p = Planner((100, 1000), 1, min_seconds=0.001)
    for w in "abc":
        p.add_worker(w)
    for w in "abc":
        band = p.next_band(w)
        p.done(band, w, band.pixels / 1e4)  # each renders 1e4 pixels a second
    while [p.next_band(w) for w in "abc"] != [None] * 3:
        pass
    lost = p.remove_worker("c")
    assert lost
    again = p.next_band("a")
    assert again.window[1] == lost[0].window[1] and again.window[3] < lost[0].window[3]
    assert p.workers == ["a", "b"]


def test_fixed_tiles_in_order():
    p = Planner((70, 45), 1, tile=17)
    tiles = []
    while (band := p.next_band()) is not None:
        tiles.append(band.window)
    assert len(tiles) == 15 and tiles[0] == (0, 0, 17, 17) and tiles[-1] == (68, 34, 2, 11)


def test_row_costs_weigh_the_rows_by_their_rays():
    """The weighing of a frame's rows (by the rays of a small render): one
    cost a row, sky rows (a primary ray each) cheaper than rows through a
    glass sphere and a mirror floor; the same answer every time."""
    hitray = pytest.importorskip("hitray")
    from hitray.distributed._render import row_costs

    scene = hitray.Scene()
    scene.add(hitray.Sphere().translate(0, -0.5, 0), diffuse=(0.1, 0.1, 0.1), transparency=0.8, speedOfLight=0.7)
    scene.add(hitray.Plane().rotate(-90, 1, 0, 0).translate(0, -1.5, 0), diffuse=(0.5, 0.5, 0.5), reflectivity=0.5)
    scene.light((5, 8, 6), (1, 1, 1))
    camera = hitray.Camera((0, 0, 6), (0, 0, 0), (0, 1, 0), 40)
    costs = row_costs(scene, camera, (480, 300), {"spp": 4, "depth": None})
    assert len(costs) == 300 and min(costs) > 0
    assert costs[0] < costs[200]  # the top row is sky; row 200 crosses the sphere and the floor
    assert row_costs(scene, camera, (480, 300), {"spp": 4, "depth": None}) == costs


class FakeFuture:
    """A Dask future, done at once."""

    def __init__(self, value, worker=None):
        self.value, self.worker = value, worker

    def result(self, timeout=None):
        return self.value

    def release(self):
        pass


class FakeLoop:
    """Dask's event loop as _Run uses it (add_callback of a coroutine
    function): an asyncio loop on a thread of its own."""

    def __init__(self):
        self.loop = asyncio.new_event_loop()
        threading.Thread(target=self.loop.run_forever, daemon=True).start()

    def add_callback(self, fn, *args):
        asyncio.run_coroutine_threadsafe(fn(*args), self.loop)


class FakeCall:
    """An actor call's future: its answer, or none ever (`hang`)."""

    def __init__(self, fn, hang):
        self.fn, self.hang, self.called = fn, hang, False

    def result(self, timeout=None):
        return self.fn()

    def __await__(self):
        async def answer():
            self.called = True
            while self.hang:
                await asyncio.sleep(3600)
            value = self.fn()
            return await value if asyncio.iscoroutine(value) else value
        return answer().__await__()


class FakeActor:
    """A worker's BandWorker, run in this process; a worker not in the
    client's `running` takes bands and never answers."""

    def __init__(self, client, worker):
        from hitray.distributed._band import BandWorker
        self.client, self.worker, self.real = client, worker, BandWorker()

    def __getattr__(self, name):
        method = getattr(self.real, name)

        def call(*args):
            future = FakeCall(lambda: method(*args), self.worker not in self.client.running)
            if name == "render":
                self.client.calls.append(future)
            return future
        return call


class FakeClient:
    """The Dask client as _Run uses it (an actor per worker), its workers a
    set the test changes."""

    def __init__(self, workers):
        self.workers, self.running = set(workers), set(workers)
        self.calls = []
        self.loop = FakeLoop()

    def scheduler_info(self):
        return {"workers": {w: {} for w in self.workers}}

    def scatter(self, value, broadcast, hash):
        future = FakeFuture(value)
        future.key = "the-scene"
        return future

    def submit(self, cls, *, actor, workers, allow_other_workers, pure, key):
        assert actor
        return FakeFuture(FakeActor(self, workers[0]), workers[0])


def one_sphere(hitray):
    """The fake-Dask tests' scene: a lit, reflective sphere, and a camera on it."""
    scene = hitray.Scene()
    scene.add(hitray.Sphere(), diffuse=(0.8, 0.3, 0.2), reflectivity=0.3)
    scene.light((4, 6, 5))
    return scene, hitray.Camera((0, 1, 5), (0, 0, 0), (0, 1, 0), 40)


def test_client_hands_a_lost_workers_bands_on(tmp_path):
    """The client's loop (_Run) with a fake Dask: worker "b" takes bands
    and never answers, then leaves the scheduler. Its bands are given back
    and rendered by "a", and the frame is the bits of hitray.render."""
    hitray = pytest.importorskip("hitray")
    from hitray.distributed._render import _Bar, _Run

    scene, camera = one_sphere(hitray)
    size, options = (40, 64), {"spp": 2}
    client = FakeClient({"a", "b"})
    client.running = {"a"}  # "b" takes bands and never returns them
    seen = []

    def progress(fraction):
        if not seen:  # the first band back: "b" leaves the scheduler
            client.workers = {"a"}
            run.checked = 0.0
        seen.append(fraction)

    run = _Run(client, size, dict(options, depth=None), Planner(size, 1), None, _Bar(progress, 40 * 64, "t"),
               lambda n: (0, None, scene, camera), None)
    frames = []
    # In a thread: without the bands handed on, the frame would wait for
    # "b" for ever; the test fails instead of hanging.
    worker = threading.Thread(target=lambda: frames.extend(run.frames_done()), daemon=True)
    worker.start()
    worker.join(60)
    assert not worker.is_alive(), "the lost worker's bands were never handed on"
    assert any(c.hang and c.called for c in client.calls)
    assert len(frames) == 1 and seen[-1] == 1.0
    here = hitray.render(scene, camera, size, progress=False, **options)
    assert np.array_equal(np.asarray(frames[0].image()), np.asarray(here))


class LostActor(FakeActor):
    """A BandWorker whose worker is gone while the scheduler still lists it:
    as Dask's Actor does then, every call raises RuntimeError at once."""

    def __getattr__(self, name):
        if self.worker in self.client.lost:
            raise RuntimeError("Worker holding Actor was lost.  Status: error")
        return super().__getattr__(name)


def test_client_goes_on_when_a_lost_workers_actor_raises(tmp_path):
    """Worker "b"'s actor raises on every call (a band, a split, the stop
    at the end) before the scheduler drops "b": the band sent to it is
    handed on as a lost worker's, the run closes without raising, and the
    frame is the bits of hitray.render."""
    hitray = pytest.importorskip("hitray")
    from hitray.distributed._render import _Bar, _Run

    scene, camera = one_sphere(hitray)
    size, options = (40, 64), {"spp": 2}
    client = FakeClient({"a", "b"})
    client.lost = {"b"}
    client.submit = lambda cls, *, actor, workers, allow_other_workers, pure, key: FakeFuture(
        LostActor(client, workers[0]), workers[0])
    run = _Run(client, size, dict(options, depth=None), Planner(size, 1), None, _Bar(False, 40 * 64, "t"),
               lambda n: (0, None, scene, camera), None)
    frames = []
    errors = []

    def go():
        try:
            frames.extend(run.frames_done())
            run.close()
        except Exception as e:  # noqa: BLE001 - the test reports it
            errors.append(e)
    worker = threading.Thread(target=go, daemon=True)
    worker.start()
    worker.join(60)
    assert not worker.is_alive(), "the lost worker's band was never handed on"
    assert not errors, errors
    assert len(frames) == 1
    here = hitray.render(scene, camera, size, progress=False, **options)
    assert np.array_equal(np.asarray(frames[0].image()), np.asarray(here))


def test_band_worker_writes_into_shared_memory_or_sends_the_pixels(tmp_path):
    """A band's rows go into the frame's shared memory where the worker can
    open it (and none are sent back), and are sent back where it cannot (no
    name, a name not of hitray's form, a file of another size): the same
    bits either way, and the frame's file is gone once closed."""
    hitray = pytest.importorskip("hitray")
    from hitray.distributed._band import BandWorker
    from hitray.distributed._pack import ScenePack
    from hitray.distributed._shared import FrameBuffer, open_frame

    scene, camera = one_sphere(hitray)
    size, window = (40, 30), (0, 5, 40, 20)
    here = np.asarray(hitray.render(scene, camera, size, spp=2, progress=False))
    actor = BandWorker()
    actor.ship("s", ScenePack(scene))
    sent = actor.render(0, "s", camera, size, {"spp": 2}, window, 1, None)
    assert sent[6] == 20 and np.array_equal(sent[0], here[5:25])
    buffer = FrameBuffer.make(size)
    if buffer is None:
        pytest.skip("no /dev/shm here")
    try:
        written = actor.render(1, "s", camera, size, {"spp": 2}, window, 1, buffer.name)
        assert written[0] is None and written[6] == 20
        assert np.array_equal(buffer.pixels[5:25], here[5:25])
        assert open_frame(buffer.name, (40, 31)) is None  # another size
        assert open_frame("psm_" + buffer.name[7:], size) is None  # not a name of hitray's
        assert open_frame("hitray-" + "0" * 32, size) is None  # no such file
    finally:
        path = "/dev/shm/" + buffer.name
        buffer.close()
    assert not os.path.exists(path)


def test_band_worker_split_gives_up_rows_not_begun():
    """The actor's split, alone: a band not begun is given up whole; one
    finished gives nothing; a band being rendered gives half of its rows
    not yet begun, and stops before them."""
    from hitray.distributed._band import BandWorker, _Progress

    actor = BandWorker()
    assert asyncio.run(actor.split(7, 100)) == 100  # not begun: whole
    actor._finished.add(8)
    assert asyncio.run(actor.split(8, 0)) is None
    actor._bands[9] = _Progress(0, 40)
    actor._bands[9].next = 10  # rows 0..9 begun
    assert asyncio.run(actor.split(9, 0)) == 25 and actor._bands[9].stop == 25
    actor._bands[9].next = 24
    assert asyncio.run(actor.split(9, 0)) is None  # one row left


def test_split_band_hands_the_rest_on_and_the_frame_completes():
    """Nothing left to hand out: an idle worker's victims are the band
    waiting behind another's, then the bands being rendered, largest first.
    A band split at a row is held as its rows above by its worker and its
    rest by the idle one; the frame completes when both are back."""
    p = Planner((10, 100), 1, min_seconds=0.001)
    p.add_worker("a")
    p.add_worker("b")
    first = p.next_band("a")
    p.done(first, "a", first.pixels / 1e3)
    bands = []
    while (band := p.next_band("a")) is not None:
        bands.append(band)
    assert p.victims("b") == [("a", b) for b in bands[1:]] + [("a", bands[0])]
    assert p.victims("a") == []  # nothing held by another
    running = bands[0]
    x, y, w, h = running.window
    rest = p.split("a", running, y + h // 2, "b")
    assert rest.window == (x, y + h // 2, w, h - h // 2)
    kept = Band(running.frame, (x, y, w, h // 2))
    assert p.held("b") == 1 and kept in p._speed["a"].held
    assert p.split("b", kept, y) is None  # "b" does not hold it
    for band in bands[1:]:
        assert not p.done(band, "a", 0.01)
    assert not p.done(rest, "b", 0.01)
    assert p.done(kept, "a", 0.01) and p.finished()

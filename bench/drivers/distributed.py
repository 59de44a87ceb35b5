#!/usr/bin/env python3
"""hitray.distributed against hitray.render on this machine, side by side in
one run, and the cost model of bigger clusters fed with what it measured.

  .venv/bin/python bench/drivers/distributed.py measure [--size 1920x1080 --spp 4 --runs 3] [--costs FILE]
  .venv/bin/python bench/drivers/distributed.py model bench/results/distributed_costs.json

`measure`: warm LocalClusters of 2 workers x 1 thread and 1 worker x 2
threads (on a machine of 2 cores; Dask's monitoring relaxed as
hitray.distributed's own LocalClusters have it, _client.QUIET) render the
frame, interleaved run by run with hitray.render on every core, so a busy
moment disturbs all three alike. Each setup's best wall and best CPU time
of --runs are given, and "paired": the median over runs of a run's wall
over the hitray.render run just before it (less disturbed by a load that
drifts than the ratio of the best walls). Every image is checked to be
bit-identical to hitray.render's. Then it measures the model's costs and
checks the model against 1, 2, 4 and 8 workers of 1 thread (--check-workers) on this
machine (time-sliced on its cores: that checks the overheads, not the
speed-up), writes the costs to --costs (JSON) and prints everything as
Markdown.

`model`: the table of docs/distributed.md, from a costs file: the
predicted efficiency at 16, 64 and 256 workers of 16 cores, for a 4K frame
at 16 spp and a 240-frame animation of such frames. Deterministic: the
same file gives the same table (tests/python/test_distributed_model.py
checks the page's table is this command's output).
"""

import argparse
import json
import os
import pathlib
import pickle
import sys
import tempfile
import time

# This file is named distributed.py: its folder, first on sys.path, would
# shadow Dask's `distributed` (here and in the worker processes, which take
# this sys.path).
HERE = pathlib.Path(__file__).resolve().parent
sys.path = [p for p in sys.path if pathlib.Path(p or ".").resolve() != HERE]

try:
    import numpy as np
    import distributed  # Dask's

    import hitray
    import hitray.distributed as hd
    from hitray.distributed._client import QUIET, local_cores
    from hitray.distributed._model import Costs, simulate
    from hitray.distributed._band import BandWorker
    from hitray.distributed._render import render_window, row_costs
except ImportError as e:
    # `make demo` builds the command only: the package and Dask are
    # `make python-install`'s (into .venv, with scripts/requirements-test.txt).
    sys.exit(f"bench/drivers/distributed.py: {e}: this needs the hitray package and Dask in {sys.executable}; "
             f"`make python-install` puts both into .venv (then run .venv/bin/python bench/drivers/distributed.py)")

ROOT = pathlib.Path(__file__).resolve().parents[2]
BIG = (3840, 2160)
BIG_SPP = 16
ANIMATION = 240
CLUSTERS = (16, 64, 256)
CORES_EACH = 16


def size_of(text):
    w, h = (int(v) for v in text.lower().split("x"))
    return w, h


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def cluster(distributed, workers, threads):
    c = distributed.LocalCluster(n_workers=workers, threads_per_worker=threads, processes=True,
                                 dashboard_address=":0")
    # As hitray.distributed's own LocalClusters: the client talks to the
    # workers straight (a band's call to a worker's actor skips the scheduler).
    return c, distributed.Client(c, direct_to_workers=True)


def cpu_of(fn):
    """CPU seconds of this process (all its threads) running fn: unlike the
    wall time, barely changed by other processes on a busy machine."""
    t0 = time.process_time()
    fn()
    return time.process_time() - t0


def worker_cpu(client):
    """CPU seconds the workers' processes have used so far, summed."""
    return sum(client.run(time.process_time).values())


def live_threads():
    """CPU seconds of each thread of this process still running, by thread
    id. hitray's render threads live for one render each, so between two
    readings the threads that are still there are the ones that do not
    render: the main thread, Dask's event loop (and a LocalCluster's
    scheduler on it), a worker's actor thread."""
    tick = os.sysconf("SC_CLK_TCK")
    out = {}
    for tid in os.listdir("/proc/self/task"):
        try:
            with open(f"/proc/self/task/{tid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:  # ended since the listing
            continue
        out[tid] = (int(fields[11]) + int(fields[12])) / tick
    return out


def grown(before, after):
    """CPU seconds the threads of `after` used since `before` (a thread
    started since: all of its time)."""
    return sum(v - before.get(tid, 0.0) for tid, v in after.items())


def dask_threads(client):
    """live_threads() of this process and of every worker's."""
    return live_threads(), client.run(live_threads)


def dask_cpu(client, before):
    """CPU seconds the non-rendering threads (here and on the workers) used
    since `before` (a dask_threads() reading)."""
    here, there = dask_threads(client)
    return grown(before[0], here) + sum(grown(before[1].get(w, {}), t) for w, t in there.items())


def per_band(client, scene, camera, size, spp, count):
    """What a band costs beyond its rendering, on warm workers: the CPU
    seconds of every process (the client with its scheduler, the workers),
    less their idle rate, per band of one pixel, sent `count` times one
    after the other to each worker in turn, (1) as a Dask task (submit,
    schedule, run, report, fetch: how every band went before the actors,
    and how fixed tiles go), (2) as a call to the worker's actor (how bands
    go now). Returns {way: (CPU seconds per band, of which the workers',
    wall seconds per band)}."""
    workers = sorted(client.scheduler_info()["workers"])
    pack = client.scatter(hd.ScenePack(scene), broadcast=True, hash=False)
    # The same cluster through a client of Dask's default, which sends an
    # actor's calls through the scheduler (it relays them).
    relayed = distributed.Client(client.scheduler.address, direct_to_workers=False)
    futures = {(w, c): c.submit(BandWorker, actor=True, workers=[w], pure=False)
               for w in workers for c in (client, relayed)}
    actors = {key: future.result() for key, future in futures.items()}
    options = {"spp": spp}

    def as_task(i):
        w = workers[i % len(workers)]
        client.submit(render_window, pack, camera, size, options, (0, 0, 1, 1), None, pure=False,
                      workers=[w]).result()

    def as_call(i):
        w = workers[i % len(workers)]
        actors[w, client].render(i, pack.key, camera, size, options, (0, 0, 1, 1), None, None).result()

    def as_relayed_call(i):
        w = workers[i % len(workers)]
        actors[w, relayed].render(i, pack.key, camera, size, options, (0, 0, 1, 1), None, None).result()

    out = {}
    for way, fn in (("a Dask task", as_task), ("an actor call relayed by the scheduler", as_relayed_call),
                    ("an actor call straight to the worker", as_call)):
        for i in range(10):  # warm
            fn(i)
        idle0, cpu0, t0 = worker_cpu(client), time.process_time(), time.perf_counter()
        time.sleep(1.0)
        t = time.perf_counter() - t0
        idle_workers, idle_here = (worker_cpu(client) - idle0) / t, (time.process_time() - cpu0) / t
        before, cpu0, t0 = worker_cpu(client), time.process_time(), time.perf_counter()
        for i in range(count):
            fn(i)
        wall = time.perf_counter() - t0
        workers_cpu = worker_cpu(client) - before - idle_workers * wall
        cpu = workers_cpu + time.process_time() - cpu0 - idle_here * wall
        out[way] = (cpu / count, workers_cpu / count, wall / count)
    for future in futures.values():
        future.release()
    relayed.close()
    pack.release()
    return out


def median(values):
    v = sorted(values)
    return (v[(len(v) - 1) // 2] + v[len(v) // 2]) / 2


def keep(best, name, wall, cpu, report):
    """The least wall time and the least CPU time of a setup's runs, each
    with its run's report."""
    mine = best.setdefault(name, {"wall": (float("inf"), None), "cpu": (float("inf"), None)})
    if wall < mine["wall"][0]:
        mine["wall"] = (wall, report)
    if cpu < mine["cpu"][0]:
        mine["cpu"] = (cpu, report)


def measure(a):
    size = size_of(a.size)
    cores = local_cores()
    scene, camera = hitray.load_sdl(a.scene)
    if camera is None:
        camera = scene.frame_camera(size)
    pixels = size[0] * size[1]
    setups = {"2 workers x 1 thread": (2, 1), "1 worker x 2 threads": (1, 2)}
    clusters = {name: cluster(distributed, *shape) for name, shape in setups.items()}
    best = {}
    paired = {}  # each run's wall over the hitray.render run just before it
    load = os.getloadavg()[0]
    try:
        for c, client in clusters.values():  # warm: the workers have imported hitray and run a task
            hd.render(scene, camera, (64, 32), spp=1, client=client, progress=False)
        # The client process's CPU time while idle (the schedulers of the
        # LocalClusters run in it, with their heartbeats), taken out of the
        # CPU time of the runs below.
        cpu0 = time.process_time()
        time.sleep(2.0)
        idle = (time.process_time() - cpu0) / 2.0
        reference = None
        walls = {}  # every run's wall, by setup
        direct = {}  # every run's CPU of the threads that do not render, beyond hitray.render's, by setup
        splits = {}
        # The rows' weighing (the client's, on threads of their own that end
        # with it): part of every frame's cost.
        weigh = min(cpu_of(lambda: row_costs(scene, camera, size, {"spp": a.spp})) for _ in range(3))
        for run in range(a.runs):
            cpu0 = time.process_time()
            caller0 = time.thread_time()
            t, image = timed(lambda: hitray.render(scene, camera, size, spp=a.spp, threads=cores, progress=False))
            cpu = time.process_time() - cpu0
            # What hitray.render's own calling thread spent (setting up, the
            # pixels' conversion): a distributed run spends it on its actor
            # threads too, and it is not overhead.
            caller = time.thread_time() - caller0
            walls.setdefault("hitray.render", []).append(t)
            reference = np.asarray(image) if reference is None else reference
            keep(best, "hitray.render", t, cpu, None)
            t_local, cpu_local_run = t, cpu
            for name, (c, client) in clusters.items():
                report = hd.Report()
                before = worker_cpu(client)
                threads0 = dask_threads(client)
                cpu0 = time.process_time()
                t, image = timed(lambda: hd.render(scene, camera, size, spp=a.spp, client=client, progress=False,
                                                   report=report))
                cpu = time.process_time() - cpu0 - idle * t + worker_cpu(client) - before
                direct.setdefault(name, []).append((dask_cpu(client, threads0) - caller + weigh, report.tasks,
                                                    cpu_local_run))
                walls.setdefault(name, []).append(t)
                splits.setdefault(name, []).append(report.splits)
                if not np.array_equal(np.asarray(image), reference):
                    raise SystemExit(f"{name}: the image differs from hitray.render's")
                keep(best, name, t, cpu, report)
                paired.setdefault(name, []).append(t / t_local)
            print(f"run {run + 1}: " + ", ".join(f"{k} {v['wall'][0]:.3f} s ({v['cpu'][0]:.3f} s CPU)"
                                                 for k, v in best.items()), file=sys.stderr)

        local, local_cpu = best["hitray.render"]["wall"][0], best["hitray.render"]["cpu"][0]
        print(f"scene {os.path.relpath(a.scene, ROOT)}, {size[0]}x{size[1]}, spp {a.spp}, {cores} cores, "
              f"best of {a.runs} runs each, interleaved (load average before: {load:.1f}, after: "
              f"{os.getloadavg()[0]:.1f})\n")
        print("| run | wall (s) | over hitray.render | paired | CPU (s) | over hitray.render | tasks | extra core-ms "
              "per task | overhead share | ms between tasks | balance |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        print(f"| hitray.render, {cores} threads | {local:.3f} | 1.00 | 1.00 | {local_cpu:.3f} | 1.00 | | | | | |")
        for name in setups:
            t, r = best[name]["wall"][0], best[name]["wall"][1]
            cpu, rc = best[name]["cpu"][0], best[name]["cpu"][1]
            print(f"| hitray.distributed, {name} | {t:.3f} | {t / local:.2f} | {median(paired[name]):.2f} | "
                  f"{cpu:.3f} | "
                  f"{cpu / local_cpu:.2f} | "
                  f"{rc.tasks} | {1e3 * (cpu - local_cpu) / rc.tasks:.1f} | {100 * r.overhead_share:.1f}% | "
                  f"{1e3 * r.between_per_task:.1f} | {r.balance:.2f} |")
        print()
        print(f"Overhead measured directly, run by run: the CPU time of every thread that does not render (the "
              f"client's and its scheduler's, the workers' event loops and actor threads; hitray's render threads "
              f"end with each render), plus the rows' weighing ({1e3 * weigh:.1f} ms), less what hitray.render's "
              f"own calling thread spends on the frame; its share of the core time is over that plus the CPU time "
              f"of hitray.render on {cores} threads in the same run. Walls: min and median of the {a.runs} "
              f"runs.\n")
        print("| run | wall min (s) | wall median (s) | min over hitray.render's min | paired median | tasks | "
              "overhead per task, min / median (core-ms) | overhead share, min / median | bands split |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
        lw = walls["hitray.render"]
        print(f"| hitray.render, {cores} threads | {min(lw):.3f} | {median(lw):.3f} | 1.00 | 1.00 | | | | |")
        for name in setups:
            w = walls[name]
            per_task = [o / n for o, n, _ in direct[name]]
            share = [o / (o + c) for o, _, c in direct[name]]
            print(f"| hitray.distributed, {name} | {min(w):.3f} | {median(w):.3f} | {min(w) / min(lw):.2f} | "
                  f"{median(paired[name]):.2f} | {median([n for _, n, _ in direct[name]]):.0f} | "
                  f"{1e3 * min(per_task):.2f} / {1e3 * median(per_task):.2f} | "
                  f"{100 * min(share):.1f}% / {100 * median(share):.1f}% | {median(splits[name]):.0f} |")
        print()
        c, client = clusters["2 workers x 1 thread"]
        bands = per_band(client, scene, camera, size, a.spp, 200)
        print(f"Per band, beyond its rendering (2 workers x 1 thread, 200 bands of one pixel one after the other, "
              f"all processes' CPU less their idle rate): " + ", ".join(
                  f"as {way} {1e3 * cpu:.2f} core-ms ({1e3 * on_workers:.2f} of them the worker's; "
                  f"{1e3 * wall:.2f} ms wall)" for way, (cpu, on_workers, wall) in bands.items())
              + "\n")
        if a.skip_model:
            return

        # The model's costs.
        one = min(cpu_of(lambda: hitray.render(scene, camera, size, spp=a.spp, threads=1, progress=False))
                  for _ in range(2))
        prepass, _ = timed(lambda: row_costs(scene, camera, size, {"spp": a.spp}))
        blob = np.zeros((size[1], size[0], 3), dtype=np.float32)
        back, _ = timed(lambda: np.copyto(blob, pickle.loads(pickle.dumps(blob, protocol=5))))
        with tempfile.TemporaryDirectory() as tmp:
            save, _ = timed(lambda: hitray.Image(blob).save(os.path.join(tmp, "f.png")))
        c, client = clusters["2 workers x 1 thread"]
        pack = hd.ScenePack(scene)
        print(f"the shipped scene carries {len(pack.files)} file{'' if len(pack.files) == 1 else 's'} "
              f"({pack.shipped_bytes} bytes)\n")
        ship = min(timed(lambda: client.scatter(pack, broadcast=True, hash=False).release())[0] for _ in range(3))
        # A worker rebuilds the scene from the pack before its first band.
        build = min(cpu_of(lambda: pickle.loads(pickle.dumps(pack)).scene()) for _ in range(3))
        # A worker's CPU while idle (heartbeats): counted in the check.
        before = worker_cpu(client)
        time.sleep(2.0)
        worker_idle = (worker_cpu(client) - before) / 2.0 / 2
        hub_pixel = back / pixels
        call = bands["an actor call straight to the worker"]
        costs = {
            "scene": os.path.relpath(a.scene, ROOT), "size": list(size), "spp": a.spp,
            "pixel": one / pixels,
            # A band's cost beyond its rendering, as bands go (a call to the
            # worker's actor, straight to it): the worker's part, and the
            # client's and scheduler's.
            "task": max(0.0, call[1]),
            "hub": max(0.0, call[0] - call[1]),
            "hub_pixel": hub_pixel,
            "save_pixel": save / pixels,
            "ship": ship / 2 + build,
            "worker_idle": worker_idle,
            "row_costs": row_costs(scene, camera, BIG, {"spp": 1}, bands=64)[::BIG[1] // 64],
        }
        print(f"costs (CPU time): {one:.3f} s for the frame on 1 thread ({1e9 * costs['pixel']:.0f} ns a pixel), "
              f"{1e3 * costs['task']:.2f} ms per task on a worker, {1e3 * costs['hub']:.2f} ms per task on the "
              f"client and scheduler, {1e9 * hub_pixel:.1f} ns a pixel back, {1e9 * costs['save_pixel']:.0f} ns "
              f"a pixel written (PNG), {1e3 * ship:.1f} ms to ship the scene to 2 workers and {1e3 * build:.1f} ms "
              f"to build it on one, {1e3 * prepass:.1f} ms to weigh the rows, {1e3 * worker_idle:.1f} ms a second "
              f"for an idle worker\n")
    finally:
        for c, client in clusters.values():
            client.close()
            c.close()

    # The check: 1, 2, 4, 8 workers of 1 thread time-sliced on this machine.
    check = size_of(a.check_size)
    model = Costs(**{k: costs[k] for k in ("pixel", "task", "hub", "hub_pixel", "save_pixel", "ship")})
    ratio = (check[0] * check[1]) / pixels
    check_workers = [int(n) for n in a.check_workers.split(",")]
    n_text = ", ".join(map(str, check_workers))
    print(f"model check at {check[0]}x{check[1]}, spp {a.spp}: {n_text} workers of 1 thread time-sliced on "
          f"{cores} cores. CPU: the client's and the workers' CPU seconds for the render, against the "
          f"model's core time (rendering plus every cost it counts); wall: the model's wall on {cores} "
          f"cores the runs had to themselves (this machine's were shared, so its wall is longer):\n")
    print("| workers | tasks (measured, model) | CPU (s) | model (s) | model / measured | wall (s) | model (s) |")
    print("|---:|---|---:|---:|---:|---:|---:|")
    rows = []
    for n in check_workers:
        c, client = cluster(distributed, n, 1)
        try:
            hd.render(scene, camera, (64, 32), spp=1, client=client, progress=False)
            runs = []
            for _ in range(a.runs):
                report = hd.Report()
                before = worker_cpu(client)
                cpu0 = time.process_time()
                wall = timed(lambda: hd.render(scene, camera, check, spp=a.spp, client=client, progress=False,
                                               report=report))[0]
                cpu = time.process_time() - cpu0 - idle * wall + worker_cpu(client) - before
                runs.append((cpu, wall, report.tasks))
        finally:
            client.close()
            c.close()
        cpu, wall, tasks = min(runs)
        wall = min(r[1] for r in runs)
        predicted = simulate(model, check, 1, n, min(1.0, cores / n), row_costs=costs["row_costs"])
        # The model's core time: rendering, the workers' and the hub's
        # costs per task, pixels back, shipping and building the scene, the
        # rows' weighing, and the idle workers' heartbeats.
        core = (check[0] * check[1] * (model.pixel + model.hub_pixel) + predicted.tasks * (model.task + model.hub)
                + n * model.ship + prepass * ratio + n * worker_idle * wall)
        rows.append((n, cpu, core, wall, predicted.wall))
        print(f"| {n} | {tasks}, {predicted.tasks} | {cpu:.3f} | {core:.3f} | {core / cpu:.2f} | "
              f"{wall:.3f} | {predicted.wall:.3f} |")
    costs["check"] = [list(r) for r in rows]
    print()
    if a.costs:
        pathlib.Path(a.costs).write_text(json.dumps(costs, indent=1) + "\n")
        print(f"costs written to {a.costs}\n")
    print(model_table(costs))


def model_table(costs):
    """The predictions, as the Markdown table of docs/distributed.md."""
    model = Costs(**{k: costs[k] for k in ("pixel", "task", "hub", "hub_pixel", "save_pixel", "ship")})
    per_pixel = model.pixel * BIG_SPP / costs["spp"]  # a sample costs the same at any spp
    big = Costs(per_pixel, model.task, model.hub, model.hub_pixel, model.save_pixel, model.ship)
    lines = [f"| workers x {CORES_EACH} cores | 4K frame, {BIG_SPP} spp: wall (s) | efficiency | tasks "
             f"| {ANIMATION} frames: wall (s) | efficiency | tasks |",
             "|---:|---:|---:|---:|---:|---:|---:|"]
    for n in CLUSTERS:
        one = simulate(big, BIG, 1, n, CORES_EACH, row_costs=costs["row_costs"])
        anim = simulate(big, BIG, ANIMATION, n, CORES_EACH, row_costs=costs["row_costs"])
        lines.append(f"| {n} | {one.wall:.2f} | {100 * one.efficiency:.0f}% | {one.tasks} | {anim.wall:.1f} | "
                     f"{100 * anim.efficiency:.0f}% | {anim.tasks} |")
    frame = BIG[0] * BIG[1] * per_pixel
    lines.append("")
    lines.append(f"(One 4K frame at {BIG_SPP} spp is {frame:.0f} core-seconds of rendering, from "
                 f"{costs['scene']} measured at {costs['size'][0]}x{costs['size'][1]}, spp {costs['spp']}.)")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    verbs = p.add_subparsers(dest="verb", required=True)
    m = verbs.add_parser("measure")
    m.add_argument("--scene", default=str(ROOT / "scenes" / "demo.sdl"))
    m.add_argument("--size", default="1920x1080")
    m.add_argument("--spp", type=int, default=4)
    m.add_argument("--runs", type=int, default=3)
    m.add_argument("--check-size", default="960x540")
    m.add_argument("--check-workers", default="1,2,4,8", help="the model check's clusters: workers of 1 thread")
    m.add_argument("--costs", help="write the measured costs here (JSON)")
    m.add_argument("--skip-model", action="store_true", help="measure the two clusters only: no model costs, "
                   "no check of the model")
    t = verbs.add_parser("model")
    t.add_argument("costs")
    a = p.parse_args()
    if a.verb == "measure":
        import dask

        # The clusters as hitray.distributed makes them (client=None): with
        # Dask's monitoring relaxed.
        with dask.config.set(QUIET):
            measure(a)
    else:
        print(model_table(json.loads(pathlib.Path(a.costs).read_text())))


if __name__ == "__main__":
    main()

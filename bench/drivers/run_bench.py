#!/usr/bin/env python3
"""hitray against POV-Ray 3.7 (whole renders) and Embree 3 (raw first hits).

    bench/drivers/run_bench.py [--runs 5] [--scaling-runs 3] [--build build]
                       [--scenes spheres,torus_csg,sphere_grid,terrain,village,balls,...]
                       [--size 1920x1080] [--spd-size 1024x1024] [--output bench/results/RESULTS.md]
    bench/drivers/run_bench.py --quick --output FILE   (every step once, tiny: a test runs it)

Run by `make bench` (which builds hitray and bench/raycast and installs
povray and libembree-dev first). Writes bench/results/RESULTS.md and
bench/results/previews/<scene>.png (the two renders side by side, and the object masks
with the disagreeing pixels in white).

Scenes: each is an SDL file in bench/scenes/ (village: Hill's village.dat from
tests/data/scenes/hill/, with a camera given on the command line, since Hill's
file has none); its POV-Ray twin is made by bench/drivers/sdl2pov.py, which documents
how materials, camera and depth map. Both renderers get the same image size,
one sample per pixel, the same recursion depth and 1 or 2 threads, and write
a binary PPM; the time is the whole process (parse + render + write), taken
around the child, with the render-only time each reports beside it (hitray:
--stats-json seconds; POV-Ray: its Trace Time). Peak memory is the child's
maximum resident set (wait4). Each figure is the median of --runs runs; the
runs alternate hitray / POV-Ray, and which one goes first alternates every
round, so drift in the machine's speed hits both alike.

Matching content: every scene is also rendered by both at 480x270 as a flat
id-colour mask (sdl2pov.py --mask); the table gives the share of pixels whose
object agrees (bench/drivers/compare_images.py).

SPD scenes: the seven Standard Procedural Databases of ../shared/scenes/spd
(balls, gears, mount, rings, teapot, tetra, tree; skipped where that folder
is absent), read by hitray as NFF (docs/nff.md) and by POV-Ray as the
*.pov.gz twins the SPD's generators wrote beside them, at --spd-size (square,
as their cameras are). Their table gives both ratios, whole process and
render only, and the rays of each kind both renderers count (hitray: its
render statistics; POV-Ray: its statistics block). They have no id-colour
mask: the twins come from the SPD, not from sdl2pov.py.

--quick runs every step once at a tiny size (one run, one thread, no
profile, the raycast with 1,000 spheres), writes to --output and to a
previews folder in the work directory, and leaves README.md alone; without
POV-Ray (or bench/raycast) it runs hitray's side and says what it left
out. tests/bench/test_bench_tools.py runs it, so the script cannot rot.

Raw intersection: bench/raycast (see its header) with 100,000 random spheres
and 1M primary rays, hitray's hr_scene_first_hit against Embree's native
spheres, 1 and 2 threads, alternating; then the batch query and Embree's
packet and stream calls beside the single calls on the same rays, camera
(coherent) and random; then the scaling runs (1k, 10k, 100k, 1M spheres)
with --scaling-runs runs each."""
import argparse
import datetime
import gzip
import os
import platform
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import time

import bench_targets

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BENCH = os.path.join(ROOT, "bench")

# scene name -> (SDL file relative to the repository, camera for both or None,
#                shape classes hitray needs beyond the core ones)
SCENES = {
    "spheres": ("bench/scenes/spheres.sdl", None, []),
    "torus_csg": ("bench/scenes/torus_csg.sdl", None, ["torus", "union", "intersection", "difference"]),
    "sphere_grid": ("bench/scenes/sphere_grid.sdl", None, []),
    "terrain": ("bench/scenes/terrain.sdl", None, ["mesh"]),
    "village": ("tests/data/scenes/hill/village.dat", "9,7,24,0,0,2,0,1,0,40", []),
}
# The SPD scenes: NFF (gzip) and their POV-Ray twins, beside the repository.
SPD_DIR = os.path.join(os.path.dirname(ROOT), "shared", "scenes", "spd")
SPD_SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]
MASK_SIZE = "480x270"
WORK = None  # build/bench-work: scenes, renders, logs
HAVE_POV = True
PREVIEWS = os.path.join(BENCH, "results", "previews")
README_BEGIN = "<!-- bench-results: written by bench/drivers/run_bench.py -->"
README_END = "<!-- /bench-results -->"


def run_measured(cmd, cwd):
    """Run cmd; return (wall seconds, peak RSS KiB, stdout, stderr, CPU seconds)
    using wait4 (the child's own peak resident set and its user + system time,
    its children's included). Its output
    goes through files in the work directory, so no pipe can stall it."""
    out_path = os.path.join(WORK, ".stdout")
    err_path = os.path.join(WORK, ".stderr")
    with open(out_path, "wb") as fo, open(err_path, "wb") as fe:
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=fo, stderr=fe)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
    with open(out_path, errors="replace") as f:
        out = f.read()
    with open(err_path, errors="replace") as f:
        err = f.read()
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({proc.returncode}):\n{err[-2000:]}")
    return wall, usage.ru_maxrss, out, err, usage.ru_utime + usage.ru_stime


def run_pair(cmds, cwd):
    """Run the commands at once, each a process of its own; returns each
    one's stdout. Two one-thread renders side by side show what this
    machine gives two independent workers (shared caches, memory bandwidth,
    a hypervisor's cores): the most a two-thread render could gain here."""
    procs = []
    for i, cmd in enumerate(cmds):
        fo = open(os.path.join(WORK, f".pair{i}.stdout"), "wb")
        fe = open(os.path.join(WORK, f".pair{i}.stderr"), "wb")
        procs.append((subprocess.Popen(cmd, cwd=cwd, stdout=fo, stderr=fe), fo, fe, cmd))
    failed = None
    for proc, fo, fe, cmd in procs:
        proc.wait()
        fo.close()
        fe.close()
        if proc.returncode != 0 and failed is None:
            with open(fe.name, errors="replace") as f:
                failed = f"{' '.join(cmd)} failed ({proc.returncode}):\n{f.read()[-2000:]}"
    if failed:
        raise RuntimeError(failed)
    return [open(fo.name, errors="replace").read() for _, fo, _, _ in procs]


def pov_seconds(text, label):
    m = re.search(label + r" Time:.*?\(([0-9.]+) seconds\)", text)
    return float(m.group(1)) if m else 0.0


def hitray_classes(hitray):
    out = subprocess.run([hitray, "shapes"], capture_output=True, text=True).stdout
    return set(re.findall(r"^\s+(\w+) - ", out, re.M))


def prepare_spd(name, work):
    """The NFF file as it is; the POV-Ray twin unpacked into the work
    directory (POV-Ray reads no gzip)."""
    d = os.path.join(work, name)
    os.makedirs(d, exist_ok=True)
    with gzip.open(os.path.join(SPD_DIR, name + ".pov.gz"), "rb") as f, \
            open(os.path.join(d, name + ".pov"), "wb") as out:
        shutil.copyfileobj(f, out)
    return d


def prepare_scene(name, work, hitray_known):
    sdl_rel, camera, needs = SCENES[name]
    d = os.path.join(work, name)
    os.makedirs(d, exist_ok=True)
    sdl = os.path.join(d, name + ".sdl")
    shutil.copyfile(os.path.join(ROOT, sdl_rel), sdl)
    if name == "terrain":
        subprocess.run([sys.executable, os.path.join(BENCH, "drivers", "make_terrain.py"),
                        os.path.join(d, "terrain.3vn")], check=True)
    conv = [sys.executable, os.path.join(BENCH, "drivers", "sdl2pov.py"), sdl]
    cam = ["--camera", camera] if camera else []
    subprocess.run(conv + ["-o", os.path.join(d, name + ".pov"), "--size", ARGS.size] + cam, check=True)
    subprocess.run(conv + ["-o", os.path.join(d, name + ".mask.pov"), "--size", MASK_SIZE,
                           "--mask", os.path.join(d, name + ".mask.sdl")] + cam, check=True)
    missing = [c for c in needs if c not in hitray_known]
    return d, camera, missing


def hitray_cmd(hitray, scene, out, size, threads, camera, stats=None):
    cmd = [hitray, "render", scene, "-o", out, "--size", size, "--threads", str(threads)]
    if camera:
        cmd += ["--camera", camera]
    if stats:
        cmd += ["--stats-json", stats]
    return cmd


def pov_cmd(pov, out, size, threads):
    w, h = size.split("x")
    return ["povray", "+I" + pov, "+O" + out, f"+W{w}", f"+H{h}", "-A", f"+WT{threads}", "-D",
            "+FP", "-V", "-P"]


def median(xs):
    return statistics.median(xs) if xs else float("nan")


def fmt_count(x):
    return "-" if x != x else f"{x:,.0f}"  # NaN: not printed by that renderer


def json_number(text, key):
    m = re.search(r'"' + key + r'":\s*([0-9.eE+-]+)', text)
    return float(m.group(1)) if m else float("nan")


def pov_rays(text):
    """The rays of each kind in POV-Ray's statistics block (absent: NaN)."""
    def count(label):
        m = re.search(label + r":\s+([0-9,]+)", text)
        return float(m.group(1).replace(",", "")) if m else float("nan")
    return {"rays": count(r"\bRays"), "shadow": count("Shadow Ray Tests"),
            "reflected": count("Reflected Rays"), "refracted": count("Refracted Rays"),
            "transmitted": count("Transmitted Rays")}


def bench_scene(name, d, camera, hitray, scene_file=None, size=None):
    """Alternating timed runs; returns rows per thread count, and the rays
    of each kind of the last run of each renderer."""
    scene_file = scene_file or name + ".sdl"
    size = size or ARGS.size
    res = {t: {"hr": [], "hr_render": [], "hr_mem": [], "hr_cpu": [], "pov": [], "pov_render": [],
               "pov_mem": []}
           for t in ARGS.threads}
    rays = {"hitray": {}, "pov": {}}
    res["pair"] = []  # render-only seconds of two 1-thread hitray renders run at once
    for rnd in range(ARGS.runs):
        for t in ARGS.threads:
            order = ("hr", "pov") if rnd % 2 == 0 else ("pov", "hr")
            for who in order:
                if who == "hr":
                    stats = os.path.join(d, "stats.json")
                    wall, mem, _, _, cpu = run_measured(
                        hitray_cmd(hitray, scene_file, "hitray.ppm", size, t, camera, stats), d)
                    with open(stats) as f:
                        text = f.read()
                    res[t]["hr"].append(wall)
                    res[t]["hr_render"].append(json_number(text, "seconds"))
                    res[t]["hr_mem"].append(mem)
                    res[t]["hr_cpu"].append(cpu)
                    rays["hitray"] = {k: json_number(text, k)
                                      for k in ("primary", "shadow", "reflected", "refracted")}
                elif HAVE_POV:
                    wall, mem, out, err, _ = run_measured(pov_cmd(name + ".pov", "pov.ppm", size, t), d)
                    res[t]["pov"].append(wall)
                    res[t]["pov_render"].append(pov_seconds(out + err, "Trace"))
                    res[t]["pov_mem"].append(mem)
                    rays["pov"] = pov_rays(out + err)
            pov_time = f"{res[t]['pov'][-1]:.2f} s" if res[t]["pov"] else "not run"
            print(f"  {name} round {rnd + 1}/{ARGS.runs} threads {t}: hitray {res[t]['hr'][-1]:.2f} s, "
                  f"POV-Ray {pov_time}", flush=True)
        if len(ARGS.threads) > 1:
            stats = [os.path.join(d, f"pair{i}.json") for i in range(2)]
            run_pair([hitray_cmd(hitray, scene_file, f"pair{i}.ppm", size, 1, camera, stats[i])
                      for i in range(2)], d)
            for path in stats:
                with open(path) as f:
                    res["pair"].append(json_number(f.read(), "seconds"))
    return res, rays


def mask_agreement(name, d, camera, hitray):
    run_measured(hitray_cmd(hitray, name + ".mask.sdl", "hitray.mask.ppm", MASK_SIZE, 2, None), d)
    run_measured(pov_cmd(name + ".mask.pov", "pov.mask.ppm", MASK_SIZE, 2), d)
    os.makedirs(PREVIEWS, exist_ok=True)
    out = subprocess.run([sys.executable, os.path.join(BENCH, "drivers", "compare_images.py"),
                          "hitray.mask.ppm", "pov.mask.ppm", "hitray.ppm", "pov.ppm",
                          os.path.join(PREVIEWS, name + ".png")],
                         cwd=d, capture_output=True, text=True, check=True).stdout
    return float(out.strip())


def raycast_runs(raycast, spheres, threads, runs, engines):
    """Alternating raycast runs; returns {engine: {threads: [parsed dicts]}}."""
    res = {e: {t: [] for t in threads} for e in engines}
    for rnd in range(runs):
        for t in threads:
            order = engines if rnd % 2 == 0 else list(reversed(engines))
            for e in order:
                wall, mem, out, _, _ = run_measured(
                    [raycast, "--engine", e, "--spheres", str(spheres), "--threads", str(t)], ROOT)
                kv = dict(x.split("=", 1) for x in out.split())
                kv["peak_kb"] = mem
                res[e][t].append(kv)
    return res


BATCH_ENGINES = ["hitray", "hitray-batch", "embree", "embree8", "embree1M"]


def batch_runs(raycast, spheres, threads, runs, embree):
    """The batch and packet engines on the same rays, all in one raycast run
    each (so each sees the machine alike): {(kind, threads): {engine: [rays/s]}}."""
    engines = BATCH_ENGINES if embree else BATCH_ENGINES[:2]
    res = {}
    for _ in range(runs):
        for kind in ("camera", "random"):
            for t in threads:
                out = subprocess.run([raycast, "--engine", ",".join(engines), "--rays", kind, "--spheres",
                                      str(spheres), "--threads", str(t)],
                                     capture_output=True, text=True, check=True).stdout
                for line in out.splitlines():
                    if line.startswith("engine="):
                        kv = dict(x.split("=", 1) for x in line.split())
                        res.setdefault((kind, t), {}).setdefault(kv["engine"], []).append(
                            float(kv["rays_per_s"]))
    return res


def batch_table(res, runs):
    """Rays/s of each engine and the batch's ratios to Embree's calls."""
    L = ["", f"## Batches and packets: 1M rays, the same rays for every engine (median of {runs})", "",
         "bench/raycast `--engine hitray,hitray-batch,embree,embree8,embree1M --rays camera|random`: "
         "`hr_scene_first_hit` per ray, `hr_scene_first_hits` on each chunk of 256 rays (packets of 8 "
         "where the rays share an octant), Embree's `rtcIntersect1`, `rtcIntersect8` and `rtcIntersect1M` "
         "(coherent flag for camera rays). Targets: batch at least 1.5x rtcIntersect1 and 1.0x "
         "rtcIntersect8.", "",
         "| rays | threads | hitray | hitray batch | rtcIntersect1 | rtcIntersect8 | rtcIntersect1M | "
         "batch / rtcIntersect1 | batch / rtcIntersect8 |",
         "|---|---|---|---|---|---|---|---|---|"]
    for (kind, t), by in res.items():
        rate = {e: median(v) for e, v in by.items()}
        cells = [f"{rate[e] / 1e6:.2f} M" if e in rate else "-" for e in BATCH_ENGINES]
        ratios = [ratio(rate["hitray-batch"], rate[e]) if e in rate else "-" for e in ("embree", "embree8")]
        L.append(f"| {kind} | {t} | " + " | ".join(cells + ratios) + " |")
    return L


def ratio(a, b):
    """a / b to two places; '-' where b is not a positive time (a tiny
    --quick render can report a trace time of 0.00 s)."""
    return f"{a / b:.2f}" if b == b and b > 0 else "-"


def fmt_mem(kb):
    return f"{kb / 1024:.0f} MiB"


def machine_line():
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            m = re.search(r"model name\s*:\s*(.*)", f.read())
            cpu = m.group(1).strip() if m else cpu
    except OSError:
        pass
    mem = ""
    try:
        with open("/proc/meminfo") as f:
            kb = int(re.search(r"MemTotal:\s*(\d+)", f.read()).group(1))
            mem = f", {kb / 1024 / 1024:.0f} GiB memory"
    except (OSError, AttributeError):
        pass
    return f"{cpu}, {os.cpu_count()} logical cores{mem}, {platform.system()} {platform.release()}"


def versions():
    m = None
    if HAVE_POV:  # --quick runs without it
        pov = subprocess.run(["povray", "--version"], capture_output=True, text=True)
        m = re.search(r"POV-Ray (\S+)", pov.stdout + pov.stderr)
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    emb = "not found"
    for line in open(os.path.join(ARGS.build, "CMakeCache.txt"), errors="replace"):
        if line.startswith("embree_DIR:"):
            m2 = re.search(r"embree-([0-9.]+)", line)
            emb = m2.group(1) if m2 else "found"
    return (m.group(1) if m else "unknown" if HAVE_POV else "not installed"), emb, commit


def main():
    global ARGS
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--scaling-runs", type=int, default=3)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--scenes", default=",".join(list(SCENES) + SPD_SCENES))
    ap.add_argument("--spd-size", default="1024x1024", help="image size of the SPD scenes")
    ap.add_argument("--quick", action="store_true",
                    help="every step once, tiny, into --output (a test of the script)")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--scaling", default="1000,10000,100000,1000000")
    ap.add_argument("--output", default=os.path.join(BENCH, "results", "RESULTS.md"))
    ap.add_argument("--note", default="", help="a line to add under the machine (e.g. other load)")
    ap.add_argument("--no-profile", action="store_true", help="skip bench/drivers/profile.sh (callgrind)")
    ap.add_argument("--readme", default=os.path.join(ROOT, "README.md"),
                    help="README whose results block is replaced ('' leaves it alone)")
    ARGS = ap.parse_args()
    if ARGS.quick:
        if ARGS.output == os.path.join(BENCH, "results", "RESULTS.md"):
            sys.exit("run_bench: --quick needs --output (it must not replace bench/results/RESULTS.md)")
        ARGS.runs, ARGS.scaling_runs, ARGS.threads = 1, 1, "1,2"
        ARGS.size, ARGS.spd_size, ARGS.scaling = "64x36", "32x32", "1000"
        ARGS.no_profile, ARGS.readme = True, ""
    ARGS.build = os.path.abspath(ARGS.build)
    ARGS.threads = [int(x) for x in ARGS.threads.split(",")]
    hitray = os.path.join(ARGS.build, "bin", "hitray")
    raycast = os.path.join(ARGS.build, "bin", "raycast")
    global WORK, HAVE_POV, PREVIEWS
    HAVE_POV = shutil.which("povray") is not None
    have_raycast = os.access(raycast, os.X_OK)
    if not os.access(hitray, os.X_OK) or (not have_raycast and not ARGS.quick):
        sys.exit(f"run_bench: {hitray if not os.access(hitray, os.X_OK) else raycast} is missing: "
                 "build first (make build)")
    if not HAVE_POV and not ARGS.quick:
        sys.exit("run_bench: povray is not installed (make bench installs it)")
    work = WORK = os.path.join(ARGS.build, "bench-quick" if ARGS.quick else "bench-work")
    os.makedirs(work, exist_ok=True)
    PREVIEWS = os.path.join(work, "previews") if ARGS.quick else os.path.join(BENCH, "results", "previews")
    known = hitray_classes(hitray)
    load_before = os.getloadavg()
    started = datetime.datetime.now(datetime.timezone.utc)

    scene_rows, spd_rows, skipped = [], [], []
    for name in ARGS.scenes.split(","):
        if name in SPD_SCENES:
            if not os.path.exists(os.path.join(SPD_DIR, name + ".nff.gz")):
                print(f"{name}: skipped, the SPD scenes are not in {SPD_DIR}", flush=True)
                skipped.append((name, ["the SPD scenes beside the repository (shared/scenes/spd)"]))
                continue
            d = prepare_spd(name, work)
            print(f"{name}: timing", flush=True)
            try:
                res, rays = bench_scene(name, d, None, hitray,
                                        os.path.join(SPD_DIR, name + ".nff.gz"), ARGS.spd_size)
            except RuntimeError as e:
                print(f"{name}: failed: {e}", flush=True)
                skipped.append((name, ["a working render (" + str(e).split(chr(10))[0][:80] + ")"]))
                continue
            spd_rows.append((name, res, rays))
            continue
        if name not in SCENES:
            sys.exit(f"run_bench: no scene '{name}' (there are {', '.join(list(SCENES) + SPD_SCENES)})")
        d, camera, missing = prepare_scene(name, work, known)
        if missing:
            skipped.append((name, missing))
            missing = ["shape class " + c for c in missing]
            print(f"{name}: skipped, hitray has no {', '.join(missing)}", flush=True)
            continue
        print(f"{name}: timing", flush=True)
        try:
            res, _ = bench_scene(name, d, camera, hitray)
            agree = mask_agreement(name, d, camera, hitray) if HAVE_POV else float("nan")
        except RuntimeError as e:  # one scene failing does not lose the others
            print(f"{name}: failed: {e}", flush=True)
            skipped.append((name, ["a working render (" + str(e).split(chr(10))[0][:80] + ")"]))
            continue
        scene_rows.append((name, res, agree))

    embree = have_raycast and "embree" in subprocess.run(
        [raycast, "--engine", "embree", "--spheres", "10", "--rays-side", "4"],
        capture_output=True, text=True).stdout
    engines = ["hitray", "embree"] if embree else ["hitray"]
    raw_spheres = 1000 if ARGS.quick else 100000
    ray, check, scaling, batches = None, None, {}, {}
    if have_raycast:
        print(f"raycast: {raw_spheres:,} spheres", flush=True)
        ray = raycast_runs(raycast, raw_spheres, ARGS.threads, ARGS.runs, engines)
        if embree:
            out = subprocess.run([raycast, "--engine", "both", "--spheres", str(raw_spheres)],
                                 capture_output=True, text=True, check=True).stdout
            # hitray's line, then Embree's with the agreement: take both.
            check = dict(x.split("=", 1) for line in out.splitlines() if line.startswith("engine=")
                         for x in line.split() if not x.startswith(("engine=", "hits=")))
            check["hits"] = out.split("hits=", 1)[1].split()[0]
        print(f"raycast batches: {raw_spheres:,} spheres", flush=True)
        batches = batch_runs(raycast, raw_spheres, ARGS.threads, ARGS.runs, embree)
        for n in [int(x) for x in ARGS.scaling.split(",")]:
            print(f"raycast scaling: {n} spheres", flush=True)
            scaling[n] = raycast_runs(raycast, n, ARGS.threads, ARGS.scaling_runs, engines)
    load_after = os.getloadavg()
    profile = ""
    if shutil.which("valgrind") and not ARGS.no_profile:
        print("profile: callgrind", flush=True)
        profile = subprocess.run([os.path.join(BENCH, "drivers", "profile.sh"), "spheres", "terrain"],
                                 capture_output=True, text=True,
                                 env=dict(os.environ, BUILD=ARGS.build)).stdout

    pov_version, emb_version, commit = versions()
    cmdline = "bench/drivers/run_bench.py " + shlex.join(sys.argv[1:]) if sys.argv[1:] else "make bench"
    L = []
    L.append("# hitray benchmark results")
    L.append("")
    L.append(f"Made by `{cmdline}` on {started:%Y-%m-%d %H:%M} UTC, hitray commit {commit}, "
             f"POV-Ray {pov_version}, Embree {emb_version}.")
    L.append("")
    L.append(f"Machine: {machine_line()}. Load average before / after: "
             f"{load_before[0]:.1f} / {load_after[0]:.1f}.")
    if ARGS.note:
        L.append("")
        L.append(ARGS.note)
    L += bench_targets.targets_table(ARGS.threads, scene_rows, spd_rows, ray, batches, scaling, profile,
                                     raw_spheres)
    sdl_skipped = [(n, m) for n, m in skipped if n not in SPD_SCENES]
    spd_skipped = [(n, m) for n, m in skipped if n in SPD_SCENES]
    if scene_rows or sdl_skipped:
        L += scenes_table(scene_rows, sdl_skipped)
    if spd_rows or spd_skipped:
        L += spd_tables(spd_rows, spd_skipped)
    L += scaling_table(scene_rows + spd_rows)
    if not HAVE_POV:
        L.append("")
        L.append("POV-Ray is not installed: its columns are empty (`make bench` installs it).")
    if ray is None:
        L.append("")
        L.append("bench/raycast is not built: no raw intersection runs.")
        with open(ARGS.output, "w") as f:
            f.write("\n".join(L) + "\n")
        print("\n".join(L))
        return
    L.append("")
    L.append(f"## Raw intersection: 1M primary rays, {raw_spheres:,} random spheres (median of {ARGS.runs})")
    L.append("")
    L.append("bench/raycast: hitray's `hr_scene_first_hit` (double precision) against Embree's "
             "native spheres (`rtcIntersect1`, float); trace time only, the build apart. "
             "Ratio = hitray rays/s / Embree rays/s (target: at least 1.0).")
    L.append("")
    L.append("| threads | hitray rays/s | Embree rays/s | ratio | hitray build | Embree build | hitray memory | Embree memory |")
    L.append("|---|---|---|---|---|---|---|---|")
    for t in ARGS.threads:
        h = ray["hitray"][t]
        hr_rate = median([float(x["rays_per_s"]) for x in h])
        hb = median([float(x["build_s"]) for x in h])
        if embree:
            e = ray["embree"][t]
            em_rate = median([float(x["rays_per_s"]) for x in e])
            eb = median([float(x["build_s"]) for x in e])
            L.append(f"| {t} | {hr_rate / 1e6:.2f} M | {em_rate / 1e6:.2f} M | {hr_rate / em_rate:.2f} | "
                     f"{hb:.2f} s | {eb:.2f} s | {fmt_mem(max(x['peak_kb'] for x in h))} | "
                     f"{fmt_mem(max(x['peak_kb'] for x in e))} |")
        else:
            L.append(f"| {t} | {hr_rate / 1e6:.2f} M | (no Embree) | | {hb:.2f} s | | "
                     f"{fmt_mem(max(x['peak_kb'] for x in h))} | |")
    if check:
        L.append("")
        L.append(f"Same answers: {int(check['same_first_object']):,} of {int(check['rays']):,} rays "
                 f"name the same first sphere in both (the rest graze a silhouette, where float "
                 f"and double differ); hitray hits {int(check['hits']):,}.")
    L += batch_table(batches, ARGS.runs)
    L.append("")
    L.append(f"## Scaling (median of {ARGS.scaling_runs}; trace time of 1M rays, build apart)")
    L.append("")
    L.append("| spheres | " + " | ".join(f"hitray {t} thr" for t in ARGS.threads) +
             (" | " + " | ".join(f"Embree {t} thr" for t in ARGS.threads) if embree else "") +
             " | hitray build | hitray memory |")
    L.append("|---" * (1 + len(ARGS.threads) * (2 if embree else 1) + 2) + "|")
    for n, res in scaling.items():
        cells = [f"{median([float(x['trace_s']) for x in res['hitray'][t]]):.3f} s" for t in ARGS.threads]
        if embree:
            cells += [f"{median([float(x['trace_s']) for x in res['embree'][t]]):.3f} s" for t in ARGS.threads]
        h = [x for t in ARGS.threads for x in res["hitray"][t]]
        cells.append(f"{median([float(x['build_s']) for x in h]):.2f} s")
        cells.append(fmt_mem(max(x["peak_kb"] for x in h)))
        L.append(f"| {n:,} | " + " | ".join(cells) + " |")
    L.append("")
    notes = os.path.join(BENCH, "results", "profile_notes.md")
    if profile and os.path.exists(notes):
        with open(notes) as f:
            L += f.read().rstrip("\n").split("\n")
        L += ["", "```", "$ bench/drivers/profile.sh spheres terrain"] + profile.rstrip("\n").split("\n") + ["```", ""]
    with open(ARGS.output, "w") as f:
        f.write("\n".join(L))
    print("\n".join(L))
    update_readme(L, cmdline)


SCENES_HEADER = ("| scene | threads | hitray time | POV-Ray time | whole | render | hitray memory | "
                 "POV-Ray memory | mask |")
SPD_HEADER = "| scene | threads | hitray time | POV-Ray time | whole | render | hitray memory | POV-Ray memory |"


def scenes_table(rows, skipped):
    """The bench scenes' table: times, memory, mask agreement."""
    L = ["", f"## Scenes ({ARGS.size}, 1 sample per pixel, median of {ARGS.runs} alternating runs)",
         "",
         "Time is the whole process (parse + render + write a PPM); render-only in brackets "
         "(hitray: its render statistics; POV-Ray: its Trace Time). whole = whole-process ratio, "
         "render = render-only ratio, hitray / POV-Ray (target: at most 0.5 for both). Memory is "
         "peak resident. Mask = pixels whose object agrees in the flat id-colour renders (see "
         "bench/results/previews/).", "",
         SCENES_HEADER,
         "|---|---|---|---|---|---|---|---|---|"]
    for name, res, agree in rows:
        for t in ARGS.threads:
            r = res[t]
            hr, pv = median(r["hr"]), median(r["pov"])
            hrr, pvr = median(r["hr_render"]), median(r["pov_render"])
            L.append(f"| {name} | {t} | {hr:.2f} s ({hrr:.2f}) | {pv:.2f} s ({pvr:.2f}) | {ratio(hr, pv)} | "
                     f"{ratio(hrr, pvr)} | {fmt_mem(max(r['hr_mem']))} | "
                     f"{fmt_mem(max(r['pov_mem'] or [float('nan')]))} | {agree:.2f}% |")
    for name, missing in skipped:
        L.append(f"| {name} | - | not run: needs {', '.join(missing)} | | | | | | |")
    return L


def scaling_table(rows):
    """hitray's speed-up from the first thread count to each other one, beside
    the CPU time it spent: on a machine that other work keeps busy the wall
    speed-up falls, while the CPU time shows whether the threads themselves
    added work (contention, shared cache lines, waiting at the end)."""
    base = ARGS.threads[0]
    more = [t for t in ARGS.threads if t != base]
    if not rows or not more:
        return []
    L = ["", f"## Thread scaling (hitray, median of {ARGS.runs})", "",
         f"Speed-up = render-only time at {base} thread(s) / at N threads (the target: at least "
         f"1.85 at 2). CPU = the whole process's user + system time at N threads / at {base}: "
         "1.00 means the threads did no more work between them than one did alone, so a "
         "speed-up below N with CPU near 1.00 is the machine's other load, not the renderer. "
         "Side by side = 2 x the render-only time of one 1-thread render / the mean of two "
         "1-thread renders run at once as separate processes (sharing nothing but the "
         "machine): what two independent workers gain on this machine, the ceiling of a "
         "2-thread speed-up here. POV-Ray = its own Trace Time at 1 / at N threads.",
         "", "| scene | " + " | ".join(f"speed-up {t} thr | CPU {t} thr" for t in more) +
         " | side by side | POV-Ray " + " | POV-Ray ".join(f"{t} thr" for t in more) + " |",
         "|---|" + "---|---|" * len(more) + "---|" + "---|" * len(more)]
    for name, res, _ in rows:
        one = res[base]
        cells = []
        for t in more:
            r = res[t]
            cells.append(f"{median(one['hr_render']) / median(r['hr_render']):.2f}")
            cells.append(f"{median(r['hr_cpu']) / median(one['hr_cpu']):.2f}")
        pair = res.get("pair") or []
        cells.append(f"{2 * median(one['hr_render']) / statistics.mean(pair):.2f}" if pair else "-")
        for t in more:
            pv1, pvt = median(one["pov_render"]), median(res[t]["pov_render"])
            cells.append(f"{pv1 / pvt:.2f}" if pv1 == pv1 and pvt == pvt and pvt > 0 else "-")
        L.append(f"| {name} | " + " | ".join(cells) + " |")
    return L


def spd_tables(rows, skipped):
    """The SPD scenes' times (both ratios) and their rays by kind."""
    L = ["", f"## SPD scenes ({ARGS.spd_size}, NFF for hitray, the SPD's POV-Ray twins, median of "
         f"{ARGS.runs} alternating runs)", "",
         "The Standard Procedural Databases as their generators wrote them (docs/nff.md). Time "
         "is the whole process, render-only in brackets; whole = whole-process ratio, render = "
         "render-only ratio (hitray / POV-Ray).", "",
         SPD_HEADER,
         "|---|---|---|---|---|---|---|---|"]
    for name, res, _ in rows:
        for t in ARGS.threads:
            r = res[t]
            hr, pv = median(r["hr"]), median(r["pov"])
            hrr, pvr = median(r["hr_render"]), median(r["pov_render"])
            pov_mem = fmt_mem(max(r["pov_mem"] or [float("nan")]))
            L.append(f"| {name} | {t} | {hr:.2f} s ({hrr:.2f}) | {pv:.2f} s ({pvr:.2f}) | "
                     f"{ratio(hr, pv)} | {ratio(hrr, pvr)} | {fmt_mem(max(r['hr_mem']))} | {pov_mem} |")
    L += ["", "Rays by kind, as each renderer counts them (the last run; POV-Ray's `Rays` is "
          "every ray it traced, its eye rays among them; '-' where it prints none):", "",
          "| scene | hitray eye | hitray shadow | hitray reflected | hitray refracted | "
          "POV-Ray rays | POV-Ray shadow tests | POV-Ray reflected | POV-Ray refracted | "
          "POV-Ray transmitted |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for name, _, rays in rows:
        h, p = rays["hitray"], rays["pov"]
        cells = [fmt_count(h.get(k, float("nan"))) for k in ("primary", "shadow", "reflected", "refracted")]
        cells += [fmt_count(p.get(k, float("nan")))
                  for k in ("rays", "shadow", "reflected", "refracted", "transmitted")]
        L.append(f"| {name} | " + " | ".join(cells) + " |")
    for name, missing in skipped:
        L.append(f"| {name} | not run: needs {', '.join(missing)} | | | | | | | | |")
    return L


def update_readme(lines, cmdline):
    """Put the machine line and the main tables (the scenes, the raw intersection, the SPD
    scenes' times) between the README's markers."""
    if not ARGS.readme or not os.path.exists(ARGS.readme):
        return
    with open(ARGS.readme) as f:
        text = f.read()
    if README_BEGIN not in text or README_END not in text:
        return
    tables, current = [], []
    for line in lines:  # consecutive table lines form one table
        if line.startswith("|"):
            current.append(line)
        elif current:
            tables.append(current)
            current = []
    if current:
        tables.append(current)
    machine = [x for x in lines if x.startswith("Machine:")]
    notes = [x for x in lines if x == ARGS.note and x]
    body = [README_BEGIN, "", f"Made by `{cmdline}`; everything it measured, with the scaling "
            "runs, is in [bench/results/RESULTS.md](bench/results/RESULTS.md).", ""] + machine + [""] + notes
    # The targets, the bench scenes, the raw intersection and the SPD scenes' times.
    wanted = (bench_targets.HEADER, SCENES_HEADER, "| threads | hitray rays/s", SPD_HEADER)
    for head in wanted:
        for table in tables:
            if table[0] == head or (head.startswith("| threads") and table[0].startswith(head)):
                body += [""] + table
    body += ["", README_END]
    start = text.index(README_BEGIN)
    end = text.index(README_END) + len(README_END)
    with open(ARGS.readme, "w") as f:
        f.write(text[:start] + "\n".join(body) + text[end:])


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""What each accuracy knob of hitray costs in time, measured on this machine.

    bench/drivers/run_accuracy.py [--build build] [--quick] [--docs docs]
                                   [--cache DIR]

Run by `make bench-accuracy` (which builds first and installs matplotlib
into .venv); builds nothing itself. Runs the study's programs and renders,
keeps what each printed under DOCS/accuracy/raw/, and writes DOCS/accuracy.md
(the tables, each row quoting the command that printed it) and the PNG plots
in DOCS/accuracy/:

- torus solvers: build/bench/torus_solvers --json (ns per solve, t error
  against a __float128 Sturm reference, missed and spurious roots) and
  build/bench/accuracy/torus_far (speckled pixels of a far torus per solver);
- sphere and cylinder: build/bench/accuracy/quadric_forms (the textbook
  quadratic against the modules' stable forms, by distance);
- spawned rays: build/bench/accuracy/spawn_offset (fixed epsilons against
  hr_hit_spawn_origin: self-hits over scene scale, thinnest shell);
- samples per pixel, adaptive supersampling and the contribution cut-off:
  `hitray render` of scenes/demo.sdl and bench/scenes/sphere_grid.sdl, RMSE of the shown
  (sRGB-encoded, clamped) values against a high-sample reference rendered
  once and cached under BUILD/accuracy-cache (keyed by the scene, the size,
  the sample count and the bytes of the hitray binary and libraries).

Timings are the best of several repeats (the C programs take the fastest
pass themselves; renders: the fastest --stats-json `seconds`): a busy
machine only slows runs down. --quick shrinks every set for a smoke run
(seconds, not minutes); its numbers are not for the docs."""
import argparse
import datetime
import hashlib
import importlib.util
import json
import os
import pathlib
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]

# name -> (scene file relative to ROOT, what it shows, whether the
# contribution cut-off can cut anything: only mirrors and glass spawn rays
# with a weight below 1)
RENDER_SCENES = {
    "demo": ("scenes/demo.sdl", "the demo: textures on a checkerboard floor, a mirror, a glass ball, shadows, depth 6", True),
    "sphere_grid": ("bench/scenes/sphere_grid.sdl",
                    "10,000 small spheres receding to the horizon: detail far below a pixel; no "
                    "mirror or glass, so no --min-weight rows", False),
}

# Each setting of the study in full and in --quick form.
FULL = dict(torus_rays=20000, torus_repeats=5, quad_rays=50000, quad_repeats=5,
            spawn_rays=20000, shell_rays=500, far_size="320x240", far_repeats=3,
            render_size="200x150", spp=[1, 2, 4, 8, 16, 32, 64, 128, 256], ref_spp=2048,
            adaptive=[0.02, 0.05, 0.1], adaptive_spp=[4, 16, 64, 256],
            min_weight=[0.01, 0.05, 0.1, 0.2], min_weight_spp=16, render_repeats=3)
QUICK = dict(torus_rays=1000, torus_repeats=1, quad_rays=1000, quad_repeats=1,
             spawn_rays=500, shell_rays=20, far_size="64x48", far_repeats=1,
             render_size="48x36", spp=[1, 4, 16], ref_spp=64,
             adaptive=[0.05], adaptive_spp=[16], min_weight=[0.1], min_weight_spp=4,
             render_repeats=1)


ERROR_HEADER = ["worst rel", "p99 rel", "worst u·c", "p99 u·c", "clear −/+", "tangent −/+"]


def error_cells(t):
    """The error and root-count columns of bench_util.c's rows, as printed."""
    return [t["worst_rel"], t["p99_rel"], t["worst_uc"], t["p99_uc"],
            f"{t['missed_clear']}/{t['spurious_clear']}",
            f"{t['missed_tangent']}/{t['spurious_tangent']}"]


def table(header, rows):
    """A Markdown table, then a blank line."""
    return (["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
            + ["| " + " | ".join(str(c) for c in row) + " |" for row in rows] + [""])


def style_axes(ax, xlabel, ylabel, title, logy=True, legend=8):
    """Log-log (or log-linear) axes with a grid, labels and a legend."""
    ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    if legend:
        ax.legend(fontsize=legend)


def load_run_bench():
    """bench/drivers/run_bench.py's machine description, shared by both studies."""
    spec = importlib.util.spec_from_file_location("run_bench", ROOT / "bench" / "drivers" / "run_bench.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def rel(path):
    """A path as the docs quote it: relative to the repository when inside."""
    try:
        return str(pathlib.Path(path).resolve().relative_to(ROOT))
    except ValueError:
        return str(path)


def quote(cmd):
    return " ".join(shlex.quote(rel(c) if os.path.isabs(str(c)) else str(c)) for c in cmd)


class Study:
    def __init__(self, args):
        self.args = args
        self.s = QUICK if args.quick else FULL
        self.build = pathlib.Path(args.build).resolve()
        self.docs = pathlib.Path(args.docs).resolve()
        self.assets = self.docs / "accuracy"
        self.raw = self.assets / "raw"
        self.cache = (pathlib.Path(args.cache).resolve() if args.cache
                      else self.build / "accuracy-cache")
        self.work = pathlib.Path(tempfile.mkdtemp(prefix="hitray-accuracy-"))
        self.md = []
        self.loads = []
        self.summary = []  # (section title, anchor, the reading's advice for a user)

    # --- running things ----------------------------------------------------

    def exe(self, *parts):
        path = self.build.joinpath(*parts)
        if not path.is_file():
            sys.exit(f"run_accuracy: {path} is missing: build first (make build)")
        return path

    def run_json(self, name, cmd):
        """Runs a program that prints one JSON object per line; keeps its
        output in raw/NAME.jsonl. Each row is returned twice over: numbers
        as floats (for sums and plots) and as the text printed (for tables)."""
        print(f"run_accuracy: {quote(cmd)}", file=sys.stderr, flush=True)
        start = time.monotonic()
        out = subprocess.run([str(c) for c in cmd], cwd=ROOT, capture_output=True, text=True)
        if out.returncode != 0:
            sys.exit(f"run_accuracy: {quote(cmd)} failed ({out.returncode}):\n{out.stderr}")
        (self.raw / f"{name}.jsonl").write_text(out.stdout)
        rows = []
        for line in out.stdout.splitlines():
            if line.startswith("{"):
                rows.append((json.loads(line), json.loads(line, parse_float=str, parse_int=str)))
        self.note_load(name, time.monotonic() - start)
        return rows

    def program(self, path, *flags, **options):
        """Runs BUILD/PATH with the flags and --NAME=VALUE options (a
        keyword's underscores become dashes); returns the command and its rows."""
        cmd = [self.exe(*path.split("/")), *flags]
        cmd += [f"--{k.replace('_', '-')}={v}" for k, v in options.items()]
        return cmd, self.run_json(pathlib.Path(path).name, cmd)

    def advise(self, title, anchor, reading):
        """Keeps a reading's last line, its advice for a user, for the summary
        at the top; returns the reading."""
        advice = [line for line in reading if line.startswith("- For a user: ")]
        if advice:
            self.summary.append((title, anchor, advice[-1][len("- For a user: "):]))
        return reading

    def note_load(self, what, seconds):
        self.loads.append((what, seconds, os.getloadavg()))

    # --- the sections -------------------------------------------------------

    def torus(self):
        s = self.s
        cmd, rows = self.program("bench/torus_solvers", "--json", rays=s["torus_rays"],
                                 repeats=s["torus_repeats"])
        md = self.md
        md += ["## Torus root solvers", "",
               "The torus module's `solver` parameter: `ferrari` (closed form), `ferrari-newton` "
               "(the same roots polished by Newton steps on the accurate f) and `bracketing` "
               "(the default; it always polishes: its last steps are Newton on the accurate f, "
               "and it has no unpolished form a user can choose). Ray sets and columns are "
               "those of `bench/programs/torus_solvers.c`'s header: ns per solve for every root (ns all) "
               "and for the first hit after t = 0 (ns 1st), best of "
               f"{s['torus_repeats']} passes; |t error| against the __float128 Sturm "
               "reference, worst and 99th percentile, relative and in units of u·condition "
               "(u = 2^-53); missed (−) and spurious (+) roots on rays clear of any tangency "
               "(reference margin > 1e-12) and on rays within it.", "",
               f"Rows printed by `{quote(cmd)}`:", ""]
        md += table(["rays", "tube", "solver", "ns all", "ns 1st"] + ERROR_HEADER,
                    [[t["set"], t["tube"], t["solver"], t["ns_all"], t["ns_first"]]
                     + error_cells(t) for _, t in rows])
        self.plot_torus([r for r, _ in rows])
        md += ["![torus solvers: time against error](accuracy/torus_solvers.png)", ""]

        far_cmd, far = self.program("bench/accuracy/torus_far", size=s["far_size"],
                                    repeats=s["far_repeats"], images=self.work)
        far_cmd_shown = far_cmd[:-1] + ["--images=DIR"]
        md += ["### The far torus, rendered", "",
               "`bench/programs/accuracy/torus_far.c`: a torus 1e4 and 1e6 away from the eye, framed "
               "tightly, one light, rendered at 1 sample per pixel with each solver. hit/miss: "
               "pixels whose primary ray hits where the __float128 Sturm reference (the world "
               "ray carried into object space in quad precision) misses, or the reverse; "
               "clear: those of them more than 1e-9 from a tangency. t rel: the worst relative "
               "error of t where both hit. shade: pixels of the 8-bit sRGB image that differ "
               "from the bracketing render (bracketing is the reference image because its own "
               "hit/miss count against the quad reference is in the table). seconds: the render, "
               f"best of {s['far_repeats']}.", "",
               f"Rows printed by `{quote(far_cmd_shown)}`:", ""]
        md += table(["distance", "tube", "solver", "hits", "hit/miss", "clear", "t rel", "shade",
                     "seconds"],
                    [[t[k] for k in ("distance", "tube", "solver", "hits", "hitmiss",
                                     "hitmiss_clear", "t_rel", "shade", "seconds")]
                     for _, t in far])
        speckle = self.plot_speckles([r for r, _ in far])
        if speckle:
            md += [f"![{speckle[1]}](accuracy/torus_far_speckles.png)", "",
                   f"*{speckle[1]}*", ""]
        md += self.advise("Torus solvers", "torus-root-solvers",
                          self.torus_reading([r for r, _ in rows], [r for r, _ in far]))

    def torus_reading(self, rows, far):
        out = ["**Reading it.**", ""]
        by = {(r["set"], r["solver"]): r for r in rows}
        sets = list(dict.fromkeys(r["set"] for r in rows))
        solvers = list(dict.fromkeys(r["solver"] for r in rows))

        def wrong(solver, kind):
            return sum(by[st, solver][f"missed_{kind}"] + by[st, solver][f"spurious_{kind}"]
                       for st in sets)

        for solver in solvers:
            bad = [f"{st} ({by[st, solver]['missed_clear']}/{by[st, solver]['spurious_clear']} "
                   f"clear, {by[st, solver]['missed_tangent']}/"
                   f"{by[st, solver]['spurious_tangent']} tangent)"
                   for st in sets
                   if any(by[st, solver][k] for k in ("missed_clear", "spurious_clear",
                                                       "missed_tangent", "spurious_tangent"))]
            worst = max(by[st, solver]["worst_uc"] for st in sets)
            worst_set = max(sets, key=lambda st: by[st, solver]["worst_uc"])
            line = f"- `{solver}`: worst t error {worst:.3g} u·c (on {worst_set})"
            if solver != "bracketing":
                speed = [by[st, "bracketing"]["ns_first"] / by[st, solver]["ns_first"]
                         for st in sets]
                line += (f"; first hits {min(speed):.2f}–{max(speed):.2f}× the speed of "
                         "`bracketing` over the sets")
            out.append(line + "; missed/spurious roots (−/+) on "
                       + (", ".join(bad) if bad else "no set") + ".")
        views = {}
        for r in far:
            views.setdefault(r["solver"], []).append(r)
        pixels = far[0]["width"] * far[0]["height"] if far else 0
        parts = [f"`{sv}` {sum(r['shade'] for r in rs)} shade, "
                 f"{sum(r['hitmiss'] for r in rs)} hit/miss"
                 for sv, rs in views.items()]
        line = (f"- Far renders ({len(far) // max(len(views), 1)} views of {pixels} pixels), "
                f"speckled pixels summed over the views: {'; '.join(parts)}.")
        if any(r["shade"] for r in far) and not any(r["hitmiss"] for r in far):
            line += (" Every primary ray agreed with the reference on hit or miss, so the "
                     "shade differences come from secondary rays; the scene has no mirror or "
                     "glass, so from shadow rays, which start on the surface (the situation of "
                     "the 'near' set above, not of the far ones).")
        out.append(line)
        clean = [sv for sv in solvers if wrong(sv, "clear") == 0
                 and not any(r["shade"] for r in views.get(sv, []) if sv != "bracketing")]
        fastest = {sv: sum(1 for st in sets
                           if min(solvers, key=lambda x: by[st, x]["ns_first"]) == sv)
                   for sv in solvers}
        far_sets = [st for st in sets if st.startswith("far")]
        other = [st for st in sets if st not in far_sets]
        def worst_of(solver, group):
            return max((by[st, solver]["worst_uc"] for st in group), default=0)

        closed_far = worst_of("ferrari", far_sets)
        polished_far = worst_of("ferrari-newton", far_sets)
        closed, polished = worst_of("ferrari", other), worst_of("ferrari-newton", other)
        out.append(
            "- For a user: the solvers with no wrong root count on clear rays and no speckle "
            f"in these renders: {', '.join(f'`{sv}`' for sv in clean) if clean else 'none'}. "
            "Fastest first hit on how many of the sets: "
            + ", ".join(f"`{sv}` {n}" for sv, n in fastest.items())
            + f". For rays from far away (the far sets) the closed form's worst error is "
            f"{closed_far:.3g} u·c and the polished solvers' at most "
            f"{max(polished_far, worst_of('bracketing', far_sets)):.3g} u·c; on the other sets "
            "(near the torus, grazing, thin tubes: also where shadow rays start) the closed "
            f"form's worst error reaches {closed:.3g} u·c and Newton polishing brings it to "
            f"{polished:.3g} u·c, but polishing cannot restore a root the closed form lost, nor "
            "remove one it invented (the −/+ counts of the table).")
        out.append("")
        return out

    def quadrics(self):
        s = self.s
        cmd, rows = self.program("bench/accuracy/quadric_forms", rays=s["quad_rays"],
                                 repeats=s["quad_repeats"])
        self.md += ["## Sphere and cylinder: the textbook quadratic against the stable forms", "",
               "`bench/programs/accuracy/quadric_forms.c`: the textbook quadratic (b² − ac, then "
               "(−b ± √disc)/a; written in the benchmark as the baseline) against the sphere's "
               "and the cylinder wall's code in their modules (Lagrange's identity for the "
               "discriminant, compensated sums, the stable root pair), called through the "
               f"module ABI. {s['quad_rays']} rays per distance from that far, aimed at random "
               "points of the shape's bounds. ns: per call, best of "
               f"{s['quad_repeats']} passes; the module's figure includes the ABI call and the hit "
               "records (point, normal, error bound), the textbook's only the roots. Errors "
               "against the __float128 reference where both agree on the count; "
               "missed/spurious as for the torus.", "",
               f"Rows printed by `{quote(cmd)}`:", ""]
        self.md += table(["shape", "distance", "form", "ns"] + ERROR_HEADER,
                    [[t["shape"], t["distance"], t["form"], t["ns"]] + error_cells(t)
                     for _, t in rows])
        self.plot_quadrics([r for r, _ in rows])
        self.md += ["![sphere and cylinder: error by distance](accuracy/quadric_forms.png)", ""]
        rs = [r for r, _ in rows]
        out = ["**Reading it.**", ""]
        for shape in dict.fromkeys(r["shape"] for r in rs):
            tb = [r for r in rs if r["shape"] == shape and r["form"] == "textbook"]
            st = [r for r in rs if r["shape"] == shape and r["form"] != "textbook"]
            cost = [b["ns"] / a["ns"] for a, b in zip(tb, st)]
            far_tb, far_st = tb[-1], st[-1]
            wrong_tb = sum(r["missed_clear"] + r["spurious_clear"] for r in tb)
            wrong_st = sum(r["missed_clear"] + r["spurious_clear"] for r in st)
            slope = np.polyfit(np.log10([r["distance"] for r in tb]),
                               np.log10([max(r["worst_rel"], 1e-300) for r in tb]), 1)[0]
            out.append(
                f"- {shape}: the textbook form's worst relative t error grows from "
                f"{tb[0]['worst_rel']:.2g} at distance {tb[0]['distance']:g} to "
                f"{far_tb['worst_rel']:.2g} at {far_tb['distance']:g} (slope {slope:.2f} on "
                "log-log axes: the discriminant b² − ac cancels more the farther the ray "
                f"starts), that is up to {far_tb['worst_uc']:.3g} u·c, an absolute error in t "
                f"of up to {far_tb['worst_rel'] * far_tb['distance']:.2g} on a unit object; the "
                "stable "
                f"form stays at {max(r['worst_uc'] for r in st):.3g} u·c or less at every "
                f"distance. Clear rays with a wrong hit count: textbook {wrong_tb}, stable "
                f"{wrong_st}. The module call costs {min(cost):.1f}–{max(cost):.1f}× the bare "
                "textbook roots (that includes filling the hit records).")
        worst_tb = max(rs, key=lambda r: r["worst_uc"] if r["form"] == "textbook" else 0)
        worst_st = max(r["worst_uc"] for r in rs if r["form"] != "textbook")
        out.append("- For a user: nothing to choose: the modules always use the stable forms, "
                   f"whose t stayed within {worst_st:.3g} u·c at every distance, where the "
                   f"textbook quadratic's error grows with the distance ({worst_tb['worst_uc']:.3g} "
                   f"u·c, relative {worst_tb['worst_rel']:.2g}, for a {worst_tb['shape']} "
                   f"{worst_tb['distance']:g} away). A shape written with the textbook formula "
                   "(a Python or plug-in shape, say) would have that error for far rays.")
        out.append("")
        self.md += self.advise("Sphere and cylinder",
                               "sphere-and-cylinder-the-textbook-quadratic-against-the-stable-forms",
                               out)

    def spawn(self):
        s = self.s
        cmd, rows = self.program("bench/accuracy/spawn_offset", rays=s["spawn_rays"],
                                 shell_rays=s["shell_rays"])
        md = self.md
        selfhit = [(r, t) for r, t in rows if r["test"] == "self-hit"]
        shell = [(r, t) for r, t in rows if r["test"] == "shell"]
        methods = list(dict.fromkeys(r["method"] for r, _ in selfhit))
        md += ["## Spawned-ray offset", "",
               "`bench/programs/accuracy/spawn_offset.c`, through the library: a fixed epsilon along the "
               "normal (1e-3, 1e-6 world units) against `hr_hit_spawn_origin` (the renderer's "
               "rule: the hit's own error bound). The scene is scaled by S and placed "
               "S·(3, −2, 5) from the origin, so only the offsets do not scale. At each hit of a "
               "camera ray two rays are spawned: out (into the outer hemisphere: any hit of the "
               "convex solid is a self-hit) and in (into the solid: it must leave it; entering "
               "first is a self-hit, no hit at all is a ray lost through the object). Each cell: "
               "out self-hits / in self-hits / in lost, of the `hits` camera-ray hits; offset: "
               "mean distance of the spawned origin from the hit point, relative to S (0: the "
               "epsilon vanished in the rounding of the coordinates).", "",
               f"Rows printed by `{quote(cmd)}` (its self-hit lines, one per shape, scale and "
               "method, three to a row here):", ""]
        cells = {}
        for r, t in selfhit:
            cells.setdefault((r["shape"], r["scale"]), {})[r["method"]] = t
        body = []
        for (shape, _), by in cells.items():
            first = by[methods[0]]
            row = [shape, first["scale"], first["hits"]]
            for m in methods:
                row += [f"{by[m]['out_self']}/{by[m]['in_self']}/{by[m]['in_lost']}",
                        by[m]["offset"]]
            body.append(row)
        md += table(["shape", "scale S", "hits"]
                    + [h for m in methods for h in (f"{m}: out/in/lost", "offset / S")], body)
        md += ["The thinnest shell: two concentric spheres of radius S and S(1 − g); a ray "
               "spawned inward at the outer one (within 30° of the inward normal) must enter the "
               "inner one. g sweeps 10^-1, 10^-1.5, …, 10^-16; thinnest g: the smallest down to "
               f"which every g was found by all {s['shell_rays']} rays (1: even 10^-1 was missed).",
               "", "Rows printed by the same command (its shell lines, three to a row here):", ""]
        gaps = {}
        for r, t in shell:
            gaps.setdefault(t["scale"], {})[r["method"]] = t["thinnest_gap"]
        md += table(["scale S"] + [f"{m}: thinnest g" for m in methods],
                    [[scale] + [by[m] for m in methods] for scale, by in gaps.items()])
        self.plot_spawn([r for r, _ in selfhit], [r for r, _ in shell])
        md += ["![spawned rays: self-hits and thinnest shell over scale]"
               "(accuracy/spawn_offset.png)", ""]
        out = ["**Reading it.**", ""]
        for method in methods:
            rs = [r for r, _ in selfhit if r["method"] == method]
            bad = [r["scale"] for r in rs if r["out_self"] + r["in_self"]]
            lost = [r["scale"] for r in rs if r["in_lost"]]
            gaps = {r["scale"]: r["thinnest_gap"] for r, _ in shell if r["method"] == method}
            picks = sorted(set([min(gaps), 1.0, 1e6, max(gaps)]) & set(gaps))
            def scales(xs, what):
                listed = ", ".join(f"{x:g}" for x in sorted(set(xs)))
                return f"{what} at S = {listed}" if xs else f"no {what} at any scale"

            out.append(
                f"- {method}: {scales(bad, 'self-hits')}; "
                f"{scales(lost, 'rays lost through the object')}; thinnest shell found "
                + ", ".join(f"{gaps[x]:.3g} at S = {x:g}" for x in picks) + ".")
        bound_ok = not any(r["out_self"] + r["in_self"] + r["in_lost"]
                           for r, _ in selfhit if r["method"] == "error bound")
        out.append("- For a user: a fixed epsilon is right only for a band of scene sizes (too "
                   "large for small scenes: thin walls vanish and rays pass through small "
                   "objects; too small for large or far-off ones: self-hits). The error-bound "
                   "offset needs no setting"
                   + (" and had no self-hit and no lost ray at any scale measured"
                      if bound_ok else "; it too failed where the table says")
                   + "; hitray spawns every shadow, reflected and refracted ray with it, so "
                   "there is no knob: this section is why.")
        out.append("")
        md += self.advise("Spawned-ray offset", "spawned-ray-offset", out)

    # --- renders: samples per pixel, adaptive supersampling, the cut-off --------

    def tool_hash(self):
        """The bytes that decide a render: the binary, the library, the modules."""
        h = hashlib.sha256()
        files = [self.exe("bin", "hitray")] + sorted(
            p for p in (self.build / "lib").rglob("*") if p.is_file() and ".so" in p.name)
        for p in files:
            h.update(p.name.encode())
            h.update(p.read_bytes())
        return h.hexdigest()

    def render(self, scene, spp, out, adaptive=None, min_weight=None):
        cmd = [self.exe("bin", "hitray"), "render", scene, "-o", out, "--size",
               self.s["render_size"], "--spp", str(spp)]
        if adaptive:
            cmd += ["--adaptive", str(adaptive)]
        if min_weight:
            cmd += ["--min-weight", str(min_weight)]
        stats = out.with_suffix(".json")
        result = subprocess.run([str(c) for c in cmd + ["--stats-json", stats]], cwd=ROOT,
                                capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"run_accuracy: {quote(cmd)} failed:\n{result.stderr}")
        return cmd, json.loads(stats.read_text())

    def reference(self, name, scene):
        key = hashlib.sha256()
        key.update((ROOT / scene).read_bytes())
        key.update(f"{self.s['render_size']} {self.s['ref_spp']} {self.tool_hash()}".encode())
        self.cache.mkdir(parents=True, exist_ok=True)
        size, spp = self.s["render_size"], self.s["ref_spp"]
        path = self.cache / f"{name}-{size}-{spp}-{key.hexdigest()[:16]}.pfm"
        cmd = [self.exe("bin", "hitray"), "render", scene, "-o", "REF.pfm", "--size",
               self.s["render_size"], "--spp", str(self.s["ref_spp"])]
        if not path.exists():
            print(f"run_accuracy: reference {rel(path)} (once)", file=sys.stderr, flush=True)
            tmp = self.work / f"{name}-ref.pfm"
            self.render(scene, self.s["ref_spp"], tmp)
            shutil.copyfile(tmp, path)
        return read_pfm(path), cmd

    def samples(self):
        s = self.s
        md = self.md
        md += ["## Samples per pixel, adaptive supersampling and the cut-off", "",
               f"`hitray render` at {s['render_size']}, every core, `--spp N` for N = "
               f"{', '.join(map(str, s['spp']))}, and `--adaptive T --spp N` for T = "
               f"{', '.join(map(str, s['adaptive']))} and N = "
               f"{', '.join(map(str, s['adaptive_spp']))} (adaptive supersampling, "
               "docs/effects.md: pixels whose corners differ by more than T get the N-sample "
               "pattern, the others the mean of their corners), and the other opt-in saving, "
               f"`--min-weight W --spp {s['min_weight_spp']}` for W = "
               f"{', '.join(map(str, s['min_weight']))} (the contribution cut-off: no reflected "
               "or refracted ray whose path weight is below W). Error (computed by "
               "run_accuracy.py from the PFM images the commands wrote): RMSE of every channel "
               "of every pixel as shown (sRGB-encoded, clamped to [0, 1], the PNG's value "
               "before rounding) against a reference rendered with "
               f"`--spp {s['ref_spp']}` (the same command with that count; cached in the "
               "build tree, keyed by the scene and the binaries). The reference has an error "
               "of its own, so the smallest RMSEs are an upper bound on the distance to the "
               "true image. Time: the render's wall time (--stats-json `seconds`: not the "
               f"loading of the scene or the writing of the image), best of "
               f"{s['render_repeats']} runs, shown to 0.1 ms. rays: every ray cast (camera, "
               "shadow, reflected, refracted); pixels refined and rays cut: the statistics "
               "`pixels_refined` and `rays_cut`.", ""]
        plots = {}
        raw = []  # each render's fastest --stats-json and its RMSE, for raw/renders.jsonl
        for name, (scene, what, cuts) in RENDER_SCENES.items():
            ref, ref_cmd = self.reference(name, scene)
            start = time.monotonic()
            settings = [dict(spp=n) for n in s["spp"]]
            settings += [dict(spp=n, adaptive=t) for t in s["adaptive"] for n in s["adaptive_spp"]]
            if cuts:
                settings += [dict(spp=s["min_weight_spp"], min_weight=w) for w in s["min_weight"]]
            rows = []
            for i, setting in enumerate(settings):
                out = self.work / f"{name}-{i}.pfm"
                best = None
                for _ in range(s["render_repeats"]):
                    cmd, stats = self.render(scene, out=out, **setting)
                    if best is None or stats["seconds"] < best["seconds"]:
                        best = stats
                rays = sum(best[k] for k in ("primary", "shadow", "reflected", "refracted"))
                rmse = display_rmse(read_pfm(out), ref)
                shown = [c if c != out else "OUT.pfm" for c in cmd] + ["--stats-json", "S.json"]
                raw.append(json.dumps({"scene": scene, "command": quote(shown),
                                       "best_stats": best, "rmse": rmse}))
                rows.append(dict({"adaptive": None, "min_weight": None}, **setting,
                                 seconds=best["seconds"], rays=rays, rmse=rmse,
                                 refined=best.get("pixels_refined", 0),
                                 cut=best.get("rays_cut", 0), cmd=shown))
            self.note_load(f"renders of {name}", time.monotonic() - start)
            plots[name] = rows
            md += [f"### {name}: `{scene}`", "", f"{what.capitalize()}. Reference: "
                   f"`{quote(ref_cmd)}`.", ""]
            md += table(["setting", "seconds", "rays", "pixels refined", "rays cut", "RMSE",
                         "command"],
                        [[setting_label(r), f"{r['seconds']:.4f}", r["rays"],
                          r["refined"] if r["adaptive"] else "—",
                          r["cut"] if r["min_weight"] else "—",
                          f"{r['rmse']:.3e}", f"`{quote(r['cmd'])}`"]
                         for r in rows])
        (self.raw / "renders.jsonl").write_text("\n".join(raw) + "\n")
        self.plot_samples(plots)
        md += ["![RMSE against render time, log-log](accuracy/samples.png)", ""]
        md += self.advise("Samples, adaptive supersampling, cut-off",
                          "samples-per-pixel-adaptive-supersampling-and-the-cut-off",
                          self.samples_reading(plots))

    def samples_reading(self, plots):
        out = ["**Reading it.**", ""]
        for name, rows in plots.items():
            full = [r for r in rows if r["adaptive"] is None and r["min_weight"] is None]
            adaptive = [r for r in rows if r["adaptive"] is not None]
            # An adaptive setting beats full sampling when some full setting
            # is both slower and less accurate (dominated).
            wins = []
            for a in adaptive:
                cheaper = [f for f in full if f["rmse"] <= a["rmse"]]
                if cheaper:
                    f = min(cheaper, key=lambda r: r["seconds"])
                    wins.append((a, f))
            if len(full) >= 2:
                slope = np.polyfit(np.log([r["seconds"] for r in full]),
                                   np.log([max(r["rmse"], 1e-12) for r in full]), 1)[0]
                lead = (f"- {name}: full sampling from {full[0]['spp']} to {full[-1]['spp']} spp "
                        f"takes the RMSE from {full[0]['rmse']:.3g} to {full[-1]['rmse']:.3g}; a "
                        f"straight-line fit on the log-log plot has slope {slope:.2f} (RMSE ∝ "
                        f"time^{slope:.2f}).")
            else:
                lead = f"- {name}: one full-sampling setting only."
            better = [f"T = {a['adaptive']} at {a['spp']} spp {f['seconds'] / a['seconds']:.1f}× "
                      f"faster than {f['spp']} spp"
                      for a, f in wins if a["seconds"] < f["seconds"]]
            out.append(lead + (" Adaptive settings faster than the fastest full render at least "
                               "as accurate: " + "; ".join(better) + "." if better else
                               " No adaptive setting was faster than every full render at least "
                               "as accurate."))
            top = max((r["spp"] for r in adaptive), default=None)
            flat = sorted((a for a in adaptive if a["spp"] == top), key=lambda a: a["adaptive"])
            same = [f["rmse"] for f in full if f["spp"] == top]
            if flat and same:
                rising = len(flat) > 1 and all(x["rmse"] < y["rmse"]
                                               for x, y in zip(flat, flat[1:]))
                out.append(f"  At {top} spp the adaptive RMSE is "
                           + ", ".join(f"{a['rmse']:.3g} (T = {a['adaptive']})" for a in flat)
                           + f" where the full render reaches {same[0]:.3g}: what is left is the "
                           "error of the pixels not refined, which more samples do not reduce"
                           + ("; the smaller T, the lower it was here." if rising else "."))
            cut = [r for r in rows if r["min_weight"] is not None]
            base = [f for f in full if cut and f["spp"] == cut[0]["spp"]]
            if cut and base:
                b = base[0]
                out.append(f"  The cut-off at {b['spp']} spp (full: {b['seconds']:.3g} s, RMSE "
                           f"{b['rmse']:.3g}): "
                           + "; ".join(f"W = {r['min_weight']} {r['cut']} rays cut, "
                                       f"{b['seconds'] / r['seconds']:.2f}× the speed, RMSE "
                                       f"{r['rmse']:.3g}" for r in cut) + ".")
        out.append("- For a user: read the plot at the error you can accept; adaptive "
                   "supersampling pays where most pixels are flat (its corners agree) and "
                   "cannot see detail that falls between the corners (docs/effects.md), which "
                   "the sphere grid has plenty of.")
        out.append("")
        return out

    # --- plots -------------------------------------------------------------

    def save(self, fig, name):
        fig.tight_layout()
        fig.savefig(self.assets / name, dpi=110)
        plt.close(fig)

    def plot_torus(self, rows):
        sets = list(dict.fromkeys(r["set"] for r in rows))
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        markers = {"ferrari": "o", "ferrari-newton": "s", "bracketing": "^"}
        colours = plt.cm.tab10(np.linspace(0, 1, 10))
        for ax, key, title in ((axes[0], "worst_uc", "worst |t error|"),
                               (axes[1], "p99_uc", "99th percentile |t error|")):
            for i, st in enumerate(sets):
                for r in rows:
                    if r["set"] == st:
                        ax.scatter(r["ns_first"], max(r[key], 1e-3), marker=markers[r["solver"]],
                                   color=colours[i], label=f"{st}: {r['solver']}")
            style_axes(ax, "ns per first-hit solve (best of passes)", "u · condition", title,
                       legend=0)
        handles = [plt.Line2D([], [], marker=m, ls="", color="k", label=s)
                   for s, m in markers.items()]
        handles += [plt.Line2D([], [], marker="o", ls="", color=colours[i], label=st)
                    for i, st in enumerate(sets)]
        axes[1].legend(handles=handles, fontsize=7, loc="best")
        self.save(fig, "torus_solvers.png")

    def plot_speckles(self, far):
        """The far render with the most shade speckles, beside bracketing's,
        the differing pixels ringed; None when no solver speckled."""
        worst = max(far, key=lambda r: r["shade"], default=None)
        if not worst or worst["shade"] == 0:
            return None
        stem = f"torus_far_{worst['distance']:g}_{worst['tube']:g}"
        a = plt.imread(self.work / f"{stem}_bracketing.png")[..., :3]
        b = plt.imread(self.work / f"{stem}_{worst['solver']}.png")[..., :3]
        ys, xs = np.nonzero(np.abs(a - b).max(axis=2) > 0.5 / 255)
        # A window around the speckles, enlarged: at full size they are a
        # few pixels of a large frame.
        half = 16
        cy = int(np.clip(np.median(ys), half, a.shape[0] - half))
        cx = int(np.clip(np.median(xs), half, a.shape[1] - half))
        window = (slice(cy - half, cy + half), slice(cx - half, cx + half))
        fig, axes = plt.subplots(1, 3, figsize=(12, 4))
        axes[0].imshow(a, interpolation="nearest")
        axes[0].add_patch(plt.Rectangle((cx - half, cy - half), 2 * half, 2 * half, fill=False,
                                        edgecolor="red"))
        axes[0].set_title("bracketing, whole frame")
        for ax, img, title in ((axes[1], a, "bracketing"), (axes[2], b, worst["solver"])):
            ax.imshow(img[window], interpolation="nearest")
            ax.scatter(xs - (cx - half), ys - (cy - half), s=160, facecolors="none",
                       edgecolors="red", linewidths=1)
            ax.set_xlim(-0.5, 2 * half - 0.5)
            ax.set_ylim(2 * half - 0.5, -0.5)
            ax.set_title(f"{title}, the red box enlarged")
        for ax in axes:
            ax.axis("off")
        caption = (f"Distance {worst['distance']:g}, tube {worst['tube']:g}: the "
                   f"{worst['shade']} pixels where `{worst['solver']}` differs from "
                   "`bracketing` (8-bit sRGB), ringed in red.")
        self.save(fig, "torus_far_speckles.png")
        return stem, caption

    def plot_quadrics(self, rows):
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        for ax, shape in zip(axes, dict.fromkeys(r["shape"] for r in rows)):
            for form, style in (("textbook", "o-"), ("stable (module)", "s-")):
                rs = [r for r in rows if r["shape"] == shape and r["form"] == form]
                d = [r["distance"] for r in rs]
                ax.plot(d, [max(r["worst_rel"], 1e-18) for r in rs], style, label=f"{form}: worst")
                ax.plot(d, [max(r["p99_rel"], 1e-18) for r in rs], style, alpha=0.5,
                        label=f"{form}: p99")
            style_axes(ax, "distance of the ray origin", "relative |t error|", shape)
        self.save(fig, "quadric_forms.png")

    def plot_spawn(self, selfhit, shell):
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        methods = list(dict.fromkeys(r["method"] for r in shell))
        for m in methods:
            rs = [r for r in selfhit if r["method"] == m]
            scales = sorted(set(r["scale"] for r in rs))
            rate = []
            for sc in scales:
                hits = sum(r["hits"] for r in rs if r["scale"] == sc)
                bad = sum(r["out_self"] + r["in_self"] + r["in_lost"]
                          for r in rs if r["scale"] == sc)
                rate.append(bad / (2 * hits) if hits else 0)
            axes[0].plot(scales, rate, "o-", label=m)
            rs = [r for r in shell if r["method"] == m]
            axes[1].plot([r["scale"] for r in rs], [r["thinnest_gap"] for r in rs], "o-", label=m)
        axes[0].set_ylim(-0.05, 1.05)
        style_axes(axes[0], "scene scale S", "share of spawned rays wrong (self-hit or lost)",
                   "sphere and cylinder, both directions", logy=False)
        style_axes(axes[1], "scene scale S", "thinnest shell found, g (relative)",
                   "concentric spheres")
        self.save(fig, "spawn_offset.png")

    def plot_samples(self, plots):
        fig, axes = plt.subplots(1, len(plots), figsize=(5.5 * len(plots), 4.4))
        axes = np.atleast_1d(axes)
        for ax, (name, rows) in zip(axes, plots.items()):
            full = [r for r in rows if r["adaptive"] is None and r["min_weight"] is None]
            ax.plot([r["seconds"] for r in full], [r["rmse"] for r in full], "o-", color="k",
                    label="--spp N")
            cut = [r for r in rows if r["min_weight"] is not None]
            if cut:
                ax.plot([r["seconds"] for r in cut], [r["rmse"] for r in cut], "^", color="m",
                        label=f"--min-weight W --spp {cut[0]['spp']}")
                for r in cut:
                    ax.annotate(f"W={r['min_weight']}", (r["seconds"], r["rmse"]), fontsize=6,
                                xytext=(-30, 4), textcoords="offset points")
            for r in full:
                ax.annotate(str(r["spp"]), (r["seconds"], r["rmse"]), fontsize=7,
                            xytext=(3, 3), textcoords="offset points")
            for t in dict.fromkeys(r["adaptive"] for r in rows if r["adaptive"] is not None):
                rs = [r for r in rows if r["adaptive"] == t]
                ax.plot([r["seconds"] for r in rs], [r["rmse"] for r in rs], "s--",
                        label=f"--adaptive {t} --spp N")
                for r in rs:
                    ax.annotate(str(r["spp"]), (r["seconds"], r["rmse"]), fontsize=6,
                                xytext=(3, -8), textcoords="offset points")
            style_axes(ax, "render seconds (best of runs)",
                       "RMSE against the reference (shown values)", name, legend=7)
        self.save(fig, "samples.png")

    # --- the document ------------------------------------------------------

    def run(self):
        self.assets.mkdir(parents=True, exist_ok=True)
        self.raw.mkdir(parents=True, exist_ok=True)
        started = datetime.datetime.now(datetime.timezone.utc)
        load_before = os.getloadavg()
        wall = time.monotonic()
        try:
            self.torus()
            self.quadrics()
            self.spawn()
            self.samples()
        finally:
            shutil.rmtree(self.work, ignore_errors=True)
        load_after = os.getloadavg()
        elapsed = time.monotonic() - wall
        head = ["# Accuracy: what each knob costs in time", "",
                "Written by `bench/drivers/run_accuracy.py` (`make bench-accuracy`); every number "
                "below is what the quoted command printed in that run (the raw output of each "
                "program, and the statistics of each render, are in `docs/accuracy/raw/`). "
                "Rerun it to measure another machine.", "",
                f"- Machine: {load_run_bench().machine_line()}",
                f"- Run: {started:%Y-%m-%d %H:%M} UTC, commit {git_commit()}, "
                + ("--quick (smoke run: small sets, not for reading)" if self.args.quick
                   else "full")
                + f", {elapsed:.0f} s in all",
                f"- Load average (1, 5, 15 min): {fmt_load(load_before)} before, "
                f"{fmt_load(load_after)} after; after each part: "
                + "; ".join(f"{w} ({sec:.0f} s) {fmt_load(l)}" for w, sec, l in self.loads),
                "- Timing: the best of several repeats (the count is given with each table): a "
                "busy machine only slows a run down, so the fastest is the closest to the "
                "machine's speed. Other work on the machine still shifts every time; the errors "
                "and counts do not depend on it.", "", "## In short", ""]
        head += [f"- **[{title}](#{anchor})**: {advice}" for title, anchor, advice in self.summary]
        head.append("")
        # The texture-filtering section is texture_filter.py's: kept as it was.
        target = self.docs / "accuracy.md"
        kept = texture_section(target.read_text()) if target.exists() else ""
        target.write_text("\n".join(head + self.md).rstrip() + "\n" + ("\n" + kept + "\n" if kept else ""))
        print(f"run_accuracy: wrote {rel(self.docs / 'accuracy.md')} in {elapsed:.0f} s",
              file=sys.stderr)


def texture_section(text):
    """The section bench/drivers/texture_filter.py wrote into `text`, with
    its markers ("" if none)."""
    spec = importlib.util.spec_from_file_location("texture_filter", pathlib.Path(__file__).with_name(
        "texture_filter.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.kept_section(text)


def setting_label(r):
    if r["adaptive"] is not None:
        return f"adaptive {r['adaptive']}, {r['spp']} spp"
    if r["min_weight"] is not None:
        return f"min-weight {r['min_weight']}, {r['spp']} spp"
    return f"{r['spp']} spp"


def fmt_load(load):
    return " ".join(f"{x:.2f}" for x in load)


def git_commit():
    out = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                         capture_output=True, text=True).stdout.strip() or "unknown"
    # What this study writes does not count: a rerun over an earlier one's
    # docs is still a run of the committed code.
    dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no",
                            "--", ".", ":!docs/accuracy.md", ":!docs/accuracy"],
                           capture_output=True, text=True).stdout.strip()
    return out + (" (with uncommitted changes)" if dirty else "")


def read_pfm(path):
    """A colour PFM as a height x width x 3 array, top row first."""
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            raise ValueError(f"{path}: not a colour PFM")
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1].astype(np.float64)


def shown(linear):
    """Linear values as the PNG shows them: clamped, sRGB-encoded, in [0, 1]."""
    v = np.clip(linear, 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


def display_rmse(image, reference):
    return float(np.sqrt(np.mean((shown(image) - shown(reference)) ** 2)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build", help="the CMake build tree (default build)")
    parser.add_argument("--quick", action="store_true", help="small sets: a smoke run")
    parser.add_argument("--docs", default=str(ROOT / "docs"),
                        help="where accuracy.md and accuracy/ go (default docs/)")
    parser.add_argument("--cache", default=None,
                        help="where reference renders are kept (default BUILD/accuracy-cache)")
    Study(parser.parse_args()).run()


if __name__ == "__main__":
    main()

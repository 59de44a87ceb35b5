"""The speed targets, each worked out from the rows run_bench.py measured in
the same run, with met or missed beside it: the one table a reader needs to
see where hitray stands against its peers, and how far each target is.

Every figure is a ratio of two measurements taken side by side in one run
(alternating, medians), so a busy machine moves both sides; the instruction
counts come from callgrind (bench/drivers/profile.sh), which a busy machine
does not move at all."""
import re
import statistics

# The SPD scenes made of triangle meshes: their own render target.
MESH_SCENES = ("teapot", "gears", "mount", "tetra")
HEADER = "| target | goal | measured | met |"
RAYS_PROFILED = 300 * 300  # profile.sh's --rays-side 300


def _median(xs):
    xs = [x for x in xs if x == x]
    return statistics.median(xs) if xs else float("nan")


def _row(target, goal, value, limit, at_least, detail):
    """One table row; value is nan where the run measured nothing."""
    if value != value:
        return f"| {target} | {goal} | not measured ({detail}) | - |"
    met = value >= limit if at_least else value <= limit
    return f"| {target} | {goal} | {value:.2f} ({detail}) | {'yes' if met else 'no'} |"


def _worst(pairs, at_least):
    """(value, label) of the worst pair: the lowest where the goal is a
    floor, the highest where it is a ceiling; (nan, 'none') for none."""
    pairs = [p for p in pairs if p[0] == p[0]]
    if not pairs:
        return float("nan"), "none"
    return (min if at_least else max)(pairs, key=lambda p: p[0])


def render_ratio(res):
    """hitray's render-only time over POV-Ray's trace time, medians."""
    pov = _median(res["pov_render"])
    return _median(res["hr_render"]) / pov if pov > 0 else float("nan")


def instructions_per_query(profile):
    """(hitray, Embree) instructions per first-hit query in profile.sh's
    output: the program totals of its two raycast runs over the same rays."""
    counts = []
    for section in ("== raycast: 100,000 spheres", "== raycast: the same rays through Embree"):
        m = re.search(re.escape(section) + r"[^\n]*\n([0-9,]+)[^\n]*PROGRAM TOTALS", profile)
        counts.append(int(m.group(1).replace(",", "")) / RAYS_PROFILED if m else float("nan"))
    return tuple(counts)


def targets_table(threads, scene_rows, spd_rows, ray, batches, scaling, profile, spheres=100000):
    """The table's lines. scene_rows and spd_rows are run_bench.py's rows
    ((name, {threads: results}, extra)); ray is raycast_runs()'s answer for
    `spheres` spheres ({engine: {threads: [dict]}}), batches batch_runs()'s,
    scaling {spheres: raycast_runs() answer}, profile profile.sh's output."""
    L = ["", "## Speed targets", "",
         "Each target worked out from the tables below (same run). Render ratios are hitray's "
         "render-only time over POV-Ray's own trace time, the worst scene and thread count named; "
         "ray ratios are hitray's rays/s over Embree's.", "", HEADER, "|---|---|---|---|"]
    embree = ray is not None and "embree" in ray
    for t in threads:
        value = float("nan")
        if embree:
            value = (_median([float(x["rays_per_s"]) for x in ray["hitray"][t]]) /
                     _median([float(x["rays_per_s"]) for x in ray["embree"][t]]))
        L.append(_row(f"single rays, {t} thread{'s' if t > 1 else ''}",
                      ">= 1.0x Embree rtcIntersect1", value, 1.0, True, f"{spheres:,} spheres"))
    hr_i, em_i = instructions_per_query(profile or "")
    if hr_i == hr_i and em_i == em_i:
        L.append(f"| instructions per query | (as few as Embree's) | {hr_i:,.0f} against Embree's "
                 f"{em_i:,.0f}: {hr_i / em_i:.2f}x (callgrind, 90,000 rays) | - |")
    mesh = [(render_ratio(res[t]), f"{name} {t} thr") for name, res, _ in spd_rows
            if name in MESH_SCENES for t in threads]
    value, label = _worst(mesh, False)
    L.append(_row("SPD mesh scenes", "<= 0.4x POV-Ray", value, 0.4, False, "worst: " + label))
    for peer, goal in (("embree", 1.5), ("embree8", 1.0)):
        pairs = []
        for (kind, t), by in (batches or {}).items():
            if kind == "camera" and peer in by and "hitray-batch" in by:
                pairs.append((_median(by["hitray-batch"]) / _median(by[peer]), f"{t} thr"))
        value, label = _worst(pairs, True)
        call = "rtcIntersect1" if peer == "embree" else "rtcIntersect8"
        L.append(_row(f"camera rays as a batch, against {call}", f">= {goal}x", value, goal, True,
                      "worst: " + label))
    renders = [(render_ratio(res[t]), f"{name} {t} thr") for name, res, _ in scene_rows + spd_rows
               for t in threads]
    value, label = _worst(renders, False)
    L.append(_row("renders, every bench and SPD scene", "<= 0.33x POV-Ray", value, 0.33, False,
                  "worst: " + label))
    small, large = (scaling or {}).get(1000), (scaling or {}).get(1000000)
    if small and large:
        pairs = [(_median([float(x["trace_s"]) for x in large["hitray"][t]]) /
                  _median([float(x["trace_s"]) for x in small["hitray"][t]]), f"{t} thr")
                 for t in threads]
        value, label = _worst(pairs, False)
    else:
        value, label = float("nan"), "no 1k and 1M rows"
    L.append(_row("1M spheres per ray over 1k", "<= 1.6x", value, 1.6, False,
                  ("worst: " if value == value else "") + label))
    for key, what, goal in (("peak_kb", f"memory, {spheres:,} spheres", 2.0),
                            ("build_s", f"build, {spheres:,} spheres", 3.0)):
        value = float("nan")
        if embree:
            h = [float(x[key]) for t in threads for x in ray["hitray"][t]]
            e = [float(x[key]) for t in threads for x in ray["embree"][t]]
            value = (max(h) / max(e)) if key == "peak_kb" else _median(h) / _median(e)
        L.append(_row(what, f"<= {goal:g}x Embree", value, goal, False,
                      "peak resident" if key == "peak_kb" else "median"))
    return L

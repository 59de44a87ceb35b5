"""bench/drivers/run_accuracy.py --quick (the smoke run of `make
bench-accuracy`) into a temporary folder: it runs every program of the study
and writes the document, the plots and the raw output, and the tables quote
what the programs printed. A few seconds; needs the build's bench programs
and matplotlib (scripts/requirements-test.txt)."""

import json
import subprocess
import sys

import pytest

from hitray_testing import BUILD, ROOT

DRIVER = ROOT / "bench" / "drivers" / "run_accuracy.py"
PROGRAMS = ["bench/torus_solvers", "bench/accuracy/quadric_forms",
            "bench/accuracy/spawn_offset", "bench/accuracy/torus_far", "bin/hitray"]


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    missing = [p for p in PROGRAMS if not (BUILD / p).is_file()]
    if missing:
        pytest.skip(f"not built: {', '.join(missing)} (HITRAY_BUILD_BENCH)")
    out = tmp_path_factory.mktemp("accuracy")
    result = subprocess.run([sys.executable, str(DRIVER), "--quick", "--build", str(BUILD),
                             "--docs", str(out), "--cache", str(out / "cache")],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    return out


def test_writes_every_section_and_plot(quick_run):
    text = (quick_run / "accuracy.md").read_text()
    for heading in ("## Torus root solvers", "### The far torus, rendered",
                    "## Sphere and cylinder", "## Spawned-ray offset",
                    "## Samples per pixel, adaptive supersampling and the cut-off"):
        assert heading in text
    for png in ("torus_solvers", "quadric_forms", "spawn_offset", "samples"):
        path = quick_run / "accuracy" / f"{png}.png"
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", path
        assert f"(accuracy/{png}.png)" in text
    assert "--quick" in text  # a smoke run says so


def test_tables_quote_what_the_programs_printed(quick_run):
    text = (quick_run / "accuracy.md").read_text()
    raw = quick_run / "accuracy" / "raw"
    for line in (raw / "torus_solvers.jsonl").read_text().splitlines():
        row = json.loads(line, parse_float=str, parse_int=str)
        assert (f"| {row['set']} | {row['tube']} | {row['solver']} | {row['ns_all']} | "
                f"{row['ns_first']} | {row['worst_rel']} |") in text
    for line in (raw / "quadric_forms.jsonl").read_text().splitlines():
        row = json.loads(line, parse_float=str, parse_int=str)
        assert (f"| {row['shape']} | {row['distance']} | {row['form']} | {row['ns']} | "
                f"{row['worst_rel']} | {row['p99_rel']} |") in text
    assert "build/bench/accuracy/spawn_offset --rays=" in text
    # Every render row names its own command.
    renders = [r for r in text.splitlines() if r.startswith("| ") and "hitray render" in r]
    # Two scenes: spp 1, 4, 16 and one adaptive setting; the demo also one
    # cut-off (the sphere grid has nothing to cut).
    assert len(renders) == 2 * 4 + 1
    kept = [json.loads(line) for line in (raw / "renders.jsonl").read_text().splitlines()]
    assert [f"`{k['command']}`" in text for k in kept] == [True] * len(renders)


TEXTURE_DRIVER = ROOT / "bench" / "drivers" / "texture_filter.py"


def test_texture_filter_writes_its_section_and_keeps_the_rest(tmp_path):
    """bench/drivers/texture_filter.py --quick writes the section "Texture
    filtering" between its markers, leaves the rest of accuracy.md as it
    was, replaces the section on a rerun, and run_accuracy.py carries the
    section over when it rewrites the file."""
    if not (BUILD / "bin" / "hitray").is_file():
        pytest.skip("not built: bin/hitray")
    docs = tmp_path / "docs"
    docs.mkdir()
    before = "# Accuracy\n\nSome earlier section.\n"
    (docs / "accuracy.md").write_text(before)

    def run():
        result = subprocess.run([sys.executable, str(TEXTURE_DRIVER), "--quick", "--build", str(BUILD),
                                 "--docs", str(docs), "--cache", str(tmp_path / "cache")],
                                capture_output=True, text=True, timeout=300)
        assert result.returncode == 0, result.stderr
        return (docs / "accuracy.md").read_text()

    text = run()
    assert text.startswith(before)
    assert text.count("## Texture filtering") == 1
    for name, scene in (("demo", "scenes/demo.sdl"), ("horizon", "bench/scenes/checker_horizon.sdl")):
        assert f"### {name}: `{scene}`" in text
    rows = [r for r in text.splitlines() if r.startswith("| ") and "hitray render" in r]
    assert len(rows) == 2 * 2 * 2  # two scenes, spp 1 and 4, footprint and none
    raw = (docs / "accuracy" / "raw" / "texture_filter.jsonl").read_text().splitlines()
    assert [f"`{json.loads(line)['command']}`" in text for line in raw] == [True] * len(rows)
    again = run()
    assert again.count("## Texture filtering") == 1 and again.startswith(before)
    sys.path.insert(0, str(TEXTURE_DRIVER.parent))
    try:
        import texture_filter
    finally:
        sys.path.pop(0)
    kept = texture_filter.kept_section(again)
    assert kept.startswith(texture_filter.BEGIN) and kept.endswith(texture_filter.END)
    assert "## Texture filtering" in kept

"""The cost model of docs/distributed.md (hitray.distributed._model): exact
on cases worked out by hand, and the page's table is what its command
prints from the costs measured and committed (bench/results/distributed_costs.json)."""

import math
import pathlib
import subprocess
import sys

import pytest

model = pytest.importorskip("hitray.distributed._model")
Costs, simulate = model.Costs, model.simulate

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_one_worker_no_overheads_is_all_rendering():
    """No costs but the pixels': one worker is busy from start to end."""
    out = simulate(Costs(pixel=1e-6), (200, 100), 1, 1, 4)
    assert out.wall == pytest.approx(200 * 100 * 1e-6 / 4, rel=1e-12)
    assert out.efficiency == pytest.approx(1.0, rel=1e-12) and out.balance == 1.0


def test_worker_costs_add_per_task():
    """A worker's cost per task adds once per task it runs (its bands
    follow one another, the next one already there)."""
    base = simulate(Costs(pixel=1e-6), (200, 100), 1, 1, 1)
    costly = simulate(Costs(pixel=1e-6, task=0.01), (200, 100), 1, 1, 1)
    assert costly.tasks == base.tasks
    assert costly.wall == pytest.approx(base.wall + costly.tasks * 0.01, rel=1e-9)


def test_shipping_is_a_tree():
    """The scene reaches 2^k - 1 workers in k copies."""
    for workers, copies in ((1, 1), (3, 2), (4, 3), (7, 3)):
        out = simulate(Costs(pixel=1e-9, ship=1.0), (10, 10), 1, workers, 1)
        assert math.floor(out.wall) == copies, workers


def test_time_sliced_workers_share_the_cores():
    """Two workers on one core (half a core each) take as long as one."""
    one = simulate(Costs(pixel=1e-6), (2000, 1000), 1, 1, 1.0)
    two = simulate(Costs(pixel=1e-6), (2000, 1000), 1, 2, 0.5)
    assert two.wall == pytest.approx(one.wall, rel=0.05)


def test_saving_frames_is_serial_on_the_client():
    """An animation's frames are written one after another by the client:
    with writing far slower than rendering, the wall is the writing."""
    out = simulate(Costs(pixel=1e-9, save_pixel=1e-3), (10, 10), 20, 8, 1)
    assert out.wall == pytest.approx(20 * 100 * 1e-3, rel=0.01)


def test_the_docs_table_is_the_models_output():
    costs = ROOT / "bench" / "results" / "distributed_costs.json"
    proc = subprocess.run([sys.executable, str(ROOT / "bench" / "drivers" / "distributed.py"), "model", str(costs)],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    page = (ROOT / "docs" / "distributed.md").read_text()
    assert proc.stdout.strip() in page


def test_frames_are_written_while_the_next_comes_in():
    """The writer thread overlaps a frame's write with the next frame's
    pixels coming in: as long as the longer of the two, not their sum."""
    out = simulate(Costs(pixel=1e-9, hub_pixel=1e-3, save_pixel=1e-3), (10, 10), 20, 8, 1)
    assert out.wall == pytest.approx(20 * 0.1 + 0.1, rel=0.1)

"""The study command (examples/paper_study.py, which scripts/main.sh runs) on a tiny
setting: it runs on the default local Dask cluster, writes its tables and figures, and a
second invocation reuses every run."""

import os
import re
import subprocess

import pandas as pd
import pytest

from study_support import EXAMPLES, PYTHON
from tribo_study.figures import FIGURES


@pytest.fixture(scope="module")
def tiny_study(fmu_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("study")
    cmd = [PYTHON, os.path.join(EXAMPLES, "paper_study.py"), "--epsilons", "0.3,1.0", "--t-end", "200",
           "--transition-width", "0.25", "--out", str(out), "--fmu", fmu_file(2), "--workers", "2",
           "--no-progress"]
    first = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert first.returncode == 0, first.stderr
    return out, cmd, first.stdout


def test_writes_tables_and_figures(tiny_study):
    out, _, stdout = tiny_study
    assert "local cluster (2 worker processes)" in stdout
    for name in FIGURES:
        with open(out / name, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", name
    runs = pd.read_csv(out / "study_runs.csv")
    assert list(zip(runs["friction"], runs["epsilon"])) == [("low", 0.3), ("low", 1.0),
                                                            ("high", 0.3), ("high", 1.0)]
    assert {"Q_static_t200", "Q_sliding_t40", "fraction_rolling_after_warmup", "assumption_warnings",
            "cpu_s", "wall_s"} <= set(runs.columns)
    assert (runs["Q_static_t200"] > 0).all() and (runs["cpu_s"] > 0).all()
    points = pd.read_csv(out / "transition_points.csv")
    assert set(points["friction"]) == {"low", "high"} and (~points["on_grid"]).any()


def test_study_md_reports_what_the_tables_hold(tiny_study):
    out, _, _ = tiny_study
    md = (out / "study.md").read_text()
    points = pd.read_csv(out / "transition_points.csv")
    for friction in ("low", "high"):
        p = points[points.friction == friction].sort_values("epsilon")
        hi = p[p.turned_over == 1]["epsilon"].min()
        lo = p[(p.turned_over == 0) & (p.epsilon < hi)]["epsilon"].max()
        assert hi - lo <= 0.25 + 1e-9
        assert f"({lo:.4f}, {hi:.4f}]" in md, friction
    for name in FIGURES:
        assert f"]({name})" in md


def test_second_invocation_reuses_every_run(tiny_study):
    _, cmd, first = tiny_study
    total = int(re.search(r"(\d+) of (\d+) runs executed", first).group(2))
    again = subprocess.run(cmd + ["--serial"], capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert f"0 of {total} runs executed" in again.stdout


def test_the_dashpots_side_by_side(fmu_file, tmp_path):
    """--dashpots 0,1: the grid with both normal dashpots, compared in one table and in the
    bounce and charge figures (a row per dashpot); the centre's runs are really the centre
    law's: at high friction it holds the centre's height and indents ten times deeper."""
    cmd = [PYTHON, os.path.join(EXAMPLES, "paper_study.py"), "--epsilons", "0.3", "--t-end", "100",
           "--transition-width", "0.5", "--out", str(tmp_path), "--fmu", fmu_file(2), "--serial",
           "--no-progress", "--dashpots", "0,1"]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    runs = pd.read_csv(tmp_path / "study_runs.csv")
    assert sorted(zip(runs["damping_point"], runs["friction"])) == [(0, "high"), (0, "low"),
                                                                  (1, "high"), (1, "low")]
    high = runs[runs.friction == "high"].set_index("damping_point")
    assert high.loc[1, "delta_y_max"] > 3 * high.loc[0, "delta_y_max"]
    md = (tmp_path / "study.md").read_text()
    section = md.split("## The dashpots side by side", 1)[1].split("## Run time", 1)[0]
    assert section.count("| contact point |") == 2 and section.count("| centre |") == 2
    from matplotlib.image import imread
    one = imread(tmp_path / "bounce_amplitude.png").shape[0]
    assert one > 1.8 * 380  # two rows of 3.8 inches at 100 dpi

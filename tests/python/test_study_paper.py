"""The study command (tribo-study, which scripts/main.sh runs) on a tiny setting: it runs on
the default local Dask cluster, writes its tables and figures (each panel with its legend,
the axes saying what is normalised by what), and a second invocation reuses every run."""

import re
import subprocess

import numpy as np
import pandas as pd
import pytest

from figure_checks import assert_legends_cover_no_data
from study_support import command
from tribo.study.figures import FIGURES


@pytest.fixture(scope="module")
def tiny_study(fmu_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("study")
    cmd = [command("tribo-study"), "--epsilons", "0.3,1.0", "--t-end", "200",
           "--transition-width", "0.25", "--out", str(out), "--fmu", fmu_file(3), "--workers", "2",
           "--no-progress"]
    first = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert first.returncode == 0, first.stderr
    return out, cmd, first.stdout


def test_writes_tables_and_figures(tiny_study):
    out, _, stdout = tiny_study
    assert "local cluster (2 threads)" in stdout
    for name in FIGURES:
        with open(out / name, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", name
    runs = pd.read_csv(out / "study_runs.csv")
    assert list(zip(runs["friction"], runs["epsilon"])) == [("low", 0.3), ("low", 1.0),
                                                            ("high", 0.3), ("high", 1.0)]
    assert {"Q_static_end", "Q_sliding_20pct", "fraction_rolling_after_warmup", "assumption_warnings",
            "cpu_s", "wall_s"} <= set(runs.columns)
    assert (runs["Q_static_end"] > 0).all() and (runs["cpu_s"] > 0).all()
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
    cmd = [command("tribo-study"), "--epsilons", "0.3", "--t-end", "100",
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


@pytest.fixture(scope="module")
def tiny_result(tiny_study, fmu_file):
    """The tiny study's result in this process (every run reused from its runs/)."""
    from dataclasses import replace

    from tribo.batch.executors import SerialExecutor
    from tribo.fmu import FmuImage
    from tribo.study.runner import REDUCED, run_study
    out, _, _ = tiny_study
    settings = replace(REDUCED, epsilons=(0.3, 1.0), t_end=200.0, transition_width=0.25)
    result = run_study(settings, FmuImage.load(fmu_file(3)), str(out), SerialExecutor(), progress=False)
    assert result.executed == 0
    return result


def test_the_study_uses_the_fmus_default_tolerances(tiny_study, tiny_result, fmu_file):
    """The runs carry the FMU's default rtol and atol (its modelDescription's start values),
    and a grid run is, bit for bit, the run that leaves them unset; the old pinned rtol 1e-8
    gives other numbers."""
    from tribo.fmu import model_description
    from tribo.batch.particle import simulate
    out, _, _ = tiny_study
    start = {v.name: float(v.start) for v in model_description(fmu_file(3)).modelVariables
             if v.name in ("rtol", "atol")}
    runs = pd.read_csv(out / "study_runs.csv")
    assert (runs["rtol"] == start["rtol"]).all() and (runs["atol"] == start["atol"]).all()
    assert tiny_result.tolerances == start
    assert "(the FMU's defaults)" in (out / "study.md").read_text()
    row = runs.iloc[0]
    params = {n: row[n] for n in ("epsilon", "mu", "nu", "n_segments", "integrator",
                                  "damping_point", "Gamma", "beta_deg", "tau0", "Sigma0", "eta", "tau_r",
                                  "drop_speed")}
    from tribo.fmu import FmuImage
    fmu = FmuImage.load(fmu_file(3))
    unset = simulate(fmu, params, 200.0).series
    pinned = simulate(fmu, dict(params, rtol=1e-8, atol=1e-10), 200.0).series
    recorded = tiny_result.series_of(0, row["friction"], row["epsilon"])
    assert unset["Y"].to_numpy() == pytest.approx(recorded["Y"].to_numpy(), rel=1e-9)  # CSV: 10 digits
    assert unset["Q_static"].iloc[-1] == row["Q_static_end"]
    assert pinned["Q_static"].iloc[-1] != row["Q_static_end"]


def _panels(fig):
    """The panels of a figure, without the twin axes that share a panel."""
    twins = {a for ax in fig.axes for a in ax.get_shared_x_axes().get_siblings(ax) if a is not ax}
    return [ax for ax in fig.axes if ax not in twins or ax.get_legend() is not None]


@pytest.mark.parametrize("name", [n for n in FIGURES])
def test_every_panel_has_a_legend_and_distinct_lines(tiny_result, name):
    from matplotlib.colors import to_hex

    from tribo.study import figures
    writer = getattr(figures, name[:-len(".png")])
    fig = writer(tiny_result)
    panels = _panels(fig)
    assert panels
    for ax in panels:
        legend = ax.get_legend()
        assert legend is not None, (name, ax.get_title())
        texts = [t.get_text() for t in legend.get_texts()]
        assert len(texts) >= 2 and all(texts), (name, texts)
        assert min(t.get_fontsize() for t in legend.get_texts()) >= 7  # readable
        # the lines of a legend are told apart by colour, or by marker where they share one
        styles = [(to_hex(line.get_color()), line.get_marker(), line.get_linestyle())
                  for line in ax.get_lines() if not line.get_label().startswith("_")]
        assert len(set(styles)) == len(styles), (name, ax.get_title(), styles)
    assert_legends_cover_no_data(fig)


def test_the_legend_check_sees_a_legend_over_a_line():
    from tribo.plotting import legend, plt
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0.5, 0.5], label="a line across the middle")
    ax.plot([0, 1], [0.0, 1.0], label="another")
    legend(ax, loc="center")
    with pytest.raises(AssertionError, match="covers"):
        assert_legends_cover_no_data(fig)
    legend(ax, outside=True)
    assert_legends_cover_no_data(fig)
    plt.close(fig)


def test_axes_say_what_is_normalised_by_what(tiny_result):
    from tribo.study import figures
    fig = figures.charge_vs_time(tiny_result)
    for ax in fig.axes:
        assert ax.get_xlabel() == "τ = t / sqrt(m/k)"
        assert "Q / Q_saturation" in ax.get_ylabel() and ("σ0" in ax.get_ylabel() or "Σ0" in ax.get_ylabel())
    trajectory = figures.trajectory(tiny_result)
    labels = [ax.get_ylabel() for ax in trajectory.axes]
    assert "height of the centre Y / a" in labels and any("revolutions" in y for y in labels)
    # the height plotted is the run's Y
    line = trajectory.axes[0].get_lines()[0]
    series = tiny_result.series_of(0, "low", 0.3)
    assert list(line.get_ydata()) == list(series["Y"])


def test_the_segment_map_is_a_polar_plot_of_the_segment_charges(tiny_result):
    from tribo.study import figures
    fig = figures.segment_charge(tiny_result)
    assert all(ax.name == "polar" for ax in fig.axes) and len(fig.axes) == 4
    ax = fig.axes[0]  # static, low friction
    line = ax.get_lines()[0]
    q = tiny_result.segments_of(0, "low", 0.3)["static"].to_numpy()
    assert list(line.get_ydata()[:-1]) == list(q) and len(q) == 2000
    assert line.get_xdata()[0] == pytest.approx(np.pi / 2000)  # the middle of segment 0
    # at epsilon 0.3, low friction, the particle charges the side it rests on, not all round
    assert q.max() > 0.5 and q.min() == 0.0


def test_an_fmi2_fmu_gives_no_segment_map(tiny_result):
    from dataclasses import replace

    from tribo.study import figures
    without = replace(tiny_result, all_segments={k: None for k in tiny_result.all_segments})
    assert figures.segment_charge(without) is None

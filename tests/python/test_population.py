"""Populations (tribo.population, tribo population): the seeded draw, resuming, the summary
against a direct computation, bad input in one line, the figure's legends."""

import multiprocessing
import os
import pickle
import subprocess
import sys

import fmpy
import numpy as np
import pandas as pd
import pytest

import tribo
from tribo.batch.executors import DaskExecutor, SerialExecutor, run_each, runs_per_task
from tribo.batch.results import csv_line, read_results
from tribo.fmu.charge_models import charge_models
from tribo.fmu.names import fmu_outputs, from_fmu_column, to_fmu
from tribo.cli.main import main as tribo_command
from tribo.fmu import FmuImage
from tribo.populations import plot as population_plot
from tribo.populations.feed import Feed, FeedError, draw, outputs, particle_parameters
from tribo.populations.particle import run_particle
from tribo.populations.runner import prepare_population, run_population
from tribo.populations.summary import statistics, stream_statistics, summarize_population
from figure_checks import assert_legends_cover_no_data, assert_tick_labels_apart

# a short chute: each particle a few impacts, ~0.05 s of CPU
SHORT = {"chute_length": 0.02}


@pytest.fixture(scope="module")
def si_image():
    return FmuImage.load(tribo.find_fmu(variant="si"))


def test_the_draw_is_reproducible_by_seed_and_measured_rows_stay_together():
    feed = Feed()
    a, b, c = draw(feed, 50, 7), draw(feed, 50, 7), draw(feed, 50, 8)
    pd.testing.assert_frame_equal(a, b)
    assert not np.array_equal(a["epsilon"], c["epsilon"])
    assert a["epsilon"].between(0.3, 1.0).all() and a["size"].between(2e-4, 2e-3).all()
    assert (a["drop_height"] == 0.01).all()
    # measured values: drawn by row, so that epsilon and size measured together stay together
    measured = pd.DataFrame({"epsilon": [0.4, 0.6, 0.9], "size": [1e-3, 5e-4, 2e-4]})
    d = draw(Feed(measured=measured), 40, 3)
    pairs = set(zip(measured["epsilon"], measured["size"]))
    assert set(zip(d["epsilon"], d["size"])) <= pairs and len(set(d["epsilon"])) > 1
    # the package's names: the size (the long diameter), angles in degrees; the chute's
    # tilt set explicitly (the reference case's 30 degrees)
    params = particle_parameters(feed, a.head(2))
    assert params[0]["size"] == a["size"][0] and params[0]["sigma0"] == -1e-3  # the table's
    assert params[0]["tilt_deg"] == 30.0 and 0 <= params[0]["phi0_deg"] <= 180
    assert not {"semi_major_axis", "tilt", "phi0"} & set(params[0])


def test_the_first_n_grains_of_a_seed_are_the_same_whatever_n():
    # changing n redrew every grain (issue 42): across the draw's blocks too
    feed = Feed(measured=pd.DataFrame({"epsilon": [0.4, 0.6, 0.9], "size": [1e-3, 5e-4, 2e-4]}))
    for f in (Feed(), feed):
        whole = draw(f, 2500, 4)
        for n in (1, 3, 1024, 1025, 2000):
            pd.testing.assert_frame_equal(draw(f, n, 4), whole.head(n))


def test_a_population_extends_running_only_the_new_grains(tmp_path, capsys):
    out = str(tmp_path / "p")
    argv = ["population", "--chute-length", "0.02", "--t-end", "1", "--serial", "--no-plot",
            "--no-progress", "--out", out]
    assert tribo_command(argv + ["-n", "3"]) == 0
    first = pd.read_csv(os.path.join(out, "particles.csv"))
    # the table is in µC/kg, the files in C/kg: the line says both (it said the first)
    assert "q/m (µC/kg here; summary.csv and particles.csv hold C/kg;" in capsys.readouterr().out
    assert tribo_command(argv + ["-n", "5"]) == 0  # refused "another set-up" before
    assert "2 run, 3 already in the file" in capsys.readouterr().out
    rows = pd.read_csv(os.path.join(out, "particles.csv"))
    pd.testing.assert_frame_equal(rows.head(3), first)
    assert tribo_command(argv + ["-n", "2"]) == 0  # the first of its own
    assert "0 run, 2 already in the file" in capsys.readouterr().out


def test_a_population_resumes_after_an_interruption_with_the_same_numbers(tmp_path, si_image):
    feed = Feed(chute=SHORT)
    whole = run_population(feed, 5, 11, 1.0, si_image, str(tmp_path / "whole"), SerialExecutor(),
                           progress=False, figure=False)
    assert whole.complete and whole.executed == 5 and not whole.failed
    part = run_population(feed, 5, 11, 1.0, si_image, str(tmp_path / "part"), SerialExecutor(),
                          progress=False, figure=False, max_runs=2)
    assert not part.complete and part.summary is None and len(part.results) == 2
    rest = run_population(feed, 5, 11, 1.0, si_image, str(tmp_path / "part"), SerialExecutor(),
                          progress=False, figure=False)
    assert (rest.executed, rest.skipped) == (3, 2) and rest.complete
    columns = ["key", "epsilon", "charge_to_mass_static", "charge_to_mass_sliding", "exit_time",
               "impacts", "fraction_flight"]
    pd.testing.assert_frame_equal(rest.results[columns], whole.results[columns])
    assert (whole.results["exited"] == 1).all() and (whole.results["impacts"] >= 1).all()
    fractions = whole.results[[f"fraction_{c}" for c in ("flight", "rocking", "rolling", "tumbling",
                                                         "bouncing")]].sum(axis=1)
    assert np.allclose(fractions, 1.0, atol=1e-12)


def assert_the_serial_rows(tasks, feed, n, seed, image, tmp_path):
    """`tasks`, a population run on Dask, ran every grain, and its rows are the serial
    run's, every column but the timings to the bit."""
    serial = run_population(feed, n, seed, 1.0, image, str(tmp_path / "serial"),
                            SerialExecutor(), progress=False, figure=False)
    assert tasks.complete and tasks.executed == n and not tasks.failed
    timing = ["cpu_s", "wall_s"]
    pd.testing.assert_frame_equal(tasks.results.drop(columns=timing),
                                  serial.results.drop(columns=timing))


def test_a_population_in_tasks_of_several_grains_is_fmpys_grain_by_grain_to_the_bit(
        tmp_path, si_image):
    """The population's path (Dask tasks of several grains each, the FMU loaded once per
    process, rows written without pandas) against each grain run alone by fmpy's
    simulate_fmu from the .fmu file: every grain's outputs the same to the bit; the
    particles.csv of the tasks the serial run's, row for row, every column but the timings,
    and each row as pandas writes it."""
    feed, n = Feed(chute=SHORT), 8
    assert runs_per_task(n, 1) == 2  # the tasks below hold two grains each
    with DaskExecutor(workers=1) as executor:
        tasks = run_population(feed, n, 11, 1.0, si_image, str(tmp_path / "tasks"), executor,
                               progress=False, figure=False)
    assert_the_serial_rows(tasks, feed, n, 11, si_image, tmp_path)
    with open(tmp_path / "tasks" / "particles.csv") as f:
        lines = f.read().splitlines(keepends=True)
    table = read_results(str(tmp_path / "tasks" / "particles.csv"))
    for i, row in table.iterrows():
        assert csv_line(list(row)) == lines[i + 1]
    md = si_image.model_description()
    names = outputs(charge_models(md), md)
    fmu_names = fmu_outputs(md, names)
    path = tribo.find_fmu(3, variant="si")
    specs = prepare_population(feed, n, 11, 1.0, si_image)
    for spec, (_, row) in zip(specs, tasks.results.iterrows()):
        alone = fmpy.simulate_fmu(path, start_values=to_fmu(md, spec.params), stop_time=spec.t_end,
                                  output_interval=spec.t_end, output=fmu_names,
                                  fmi_type="CoSimulation", validate=False)[-1]
        for name, fmu_name in zip(names, fmu_names):
            value = float(from_fmu_column(md, fmu_name, float(alone[fmu_name]))[1])
            assert row[name] == value or (np.isnan(value) and np.isnan(row[name])), (name, row["key"])


def test_a_rows_plain_floats_and_ints_are_written_as_their_numpy_kin_and_as_pandas_writes():
    """csv_line's first test (Python's float and int) writes what its general branches write
    for the same numbers as numpy's, and what pandas writes of the one-row DataFrame."""
    plain = [0.1, -0.0, float("nan"), float("inf"), -1e-300, 1.0, 2.0 ** 60, 5, -3, 0, 10 ** 18,
             True, "a, b", None]
    kin = [np.float64(v) if type(v) is float else np.int64(v) if type(v) is int else v
           for v in plain]
    assert [type(v) for v in kin].count(np.float64) == 7
    assert csv_line(plain) == csv_line(kin) == \
        pd.DataFrame([kin]).to_csv(header=False, index=False)


def test_a_worker_process_runs_a_grain_without_pandas_and_gives_the_same_row(si_image):
    """What a Dask worker process imports to run a task of grains (the task's functions
    and the FMU's image, unpickled in a fresh interpreter) holds no pandas, matplotlib,
    scipy nor the feed (docs/populations.md, "Benchmark": importing them cost each worker a
    third of a second of CPU before its first grain), and its row is this process's, to
    the bit but the timings."""
    spec = prepare_population(Feed(chute=SHORT), 1, 3, 1.0, si_image)[0]
    task = pickle.dumps((run_each, run_particle, si_image, [spec]))
    script = ("import pickle, sys\n"
              "run_each, run, image, specs = pickle.loads(sys.stdin.buffer.read())\n"
              "rows = [r.row for r in run_each(run, image, specs)]\n"
              "heavy = sorted(m for m in sys.modules if m.split('.')[0] in "
              "('pandas', 'matplotlib', 'scipy') or m == 'tribo.populations.feed')\n"
              "sys.stdout.buffer.write(pickle.dumps((rows, heavy)))\n")
    package = os.path.dirname(os.path.dirname(tribo.__file__))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([package, os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run([sys.executable, "-c", script], input=task, capture_output=True,
                          env=env, check=True)
    (row,), heavy = pickle.loads(done.stdout)
    assert heavy == []
    here = run_particle(si_image, spec).row
    # repr: a float's shortest round-trip form, so that equal is the same bits (NaN too)
    assert ({k: repr(v) for k, v in row.items() if k not in ("cpu_s", "wall_s")}
            == {k: repr(v) for k, v in here.items() if k not in ("cpu_s", "wall_s")})


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="worker processes are forked on Linux only")
def test_worker_processes_are_forked_with_this_ones_modules_and_give_the_serial_rows(
        tmp_path, si_image):
    """The local cluster's worker processes are forked from this one (executors.
    worker_start_method): they hold the modules this process imported (the feed, pandas),
    so that none imports Dask or the package again before its first grain, and the rows
    they give are the serial run's, to the bit but the timings."""
    feed, n = Feed(chute=SHORT), 4
    with DaskExecutor(workers=1, processes=True) as executor:
        held = executor.client.run(lambda: "tribo.populations.feed" in sys.modules
                                   and multiprocessing.parent_process() is not None)
        assert list(held.values()) == [True]
        tasks = run_population(feed, n, 5, 1.0, si_image, str(tmp_path / "tasks"), executor,
                               progress=False, figure=False)
    assert_the_serial_rows(tasks, feed, n, 5, si_image, tmp_path)


def test_the_summary_is_the_direct_computation():
    rng = np.random.default_rng(5)
    results = pd.DataFrame({"epsilon": rng.uniform(0.3, 1.0, 200), "size": rng.uniform(2e-4, 2e-3, 200),
                            "charge_to_mass_static": rng.normal(-1e-9, 3e-10, 200),
                            "charge_to_mass_sliding": rng.lognormal(-10, 1, 200)})
    edges = [0.3, 0.5, 0.8, 1.0]
    s = summarize_population(results, ("static", "sliding"), shape_edges=edges)
    for model in ("static", "sliding"):
        qm = results[f"charge_to_mass_{model}"].to_numpy()
        row = s[(s.grouping == "all") & (s.model == model)].iloc[0]
        assert row["n"] == 200 and row["mean"] == pytest.approx(qm.mean(), rel=1e-12)
        assert row["std"] == pytest.approx(qm.std(ddof=1), rel=1e-12)
        assert row["p95"] == pytest.approx(np.percentile(qm, 95), rel=1e-12)
        eps = results["epsilon"].to_numpy()
        for i in range(3):
            inside = (eps > edges[i]) & (eps <= edges[i + 1]) | ((i == 0) & (eps == edges[0]))
            row = s[(s.grouping == "shape") & (s.model == model) & (s.low == edges[i])].iloc[0]
            assert row["n"] == inside.sum()
            assert row["p25"] == pytest.approx(np.percentile(qm[inside], 25), rel=1e-12)
            assert row["mean"] == pytest.approx(qm[inside].mean(), rel=1e-12)
        sizes = s[(s.grouping == "size") & (s.model == model)]
        assert len(sizes) == 4 and sizes["n"].sum() == 200  # 4 classes cover the range


@pytest.mark.parametrize("argv, says", [
    (["-n", "0"], "whole number >= 1"),
    (["-n", "3", "--epsilon", "uniform:1:0.3"], "LOW < HIGH"),
    (["-n", "3", "--size", "gauss:1:2"], "unknown distribution 'gauss'"),
    (["-n", "3", "--particle", "cheese"], "unknown particle material 'cheese'"),
    (["-n", "3", "--set", "mu=-1"], "mu"),
    (["-n", "3", "--epsilon", "2"], "epsilon"),
    (["-n", "3", "--t-end", "0"], "horizon"),
    (["-n", "3", "--tilt-deg", "95"], "tilt_deg = 95 is invalid: the valid range is 0 <= tilt_deg < 90"),
    (["-n", "3", "--set", "tilt=0.6"], "the package takes this parameter as tilt_deg"),
    (["-n", "3", "--set", "epsilon=0.5"], "epsilon is a feed variable"),
    (["-n", "3", "--set", "chute_length=-0.3"], "chute_length = -0.3 is invalid"),
    # refused once every particle had run, or every run failed (issue 42)
    (["-n", "3", "--shape-classes", "5,1"], "--shape-classes: 5,1: at least two finite numbers"),
    (["-n", "3", "--size-classes", "1e-3"], "--size-classes: 0.001: at least two"),
    (["-n", "3", "--t-end", "1e308"], "t_end = 1e+308 s: at most"),
    # ran without a word (issue 42)
    (["-n", "3", "--size", "1"], "size = 1 m: the grain is as long as the chute"),
    (["-n", "3", "--size", "uniform:1e-3:0.1", "--chute-length", "0.05"], "chute_length = 0.05 m"),
])
def test_bad_input_is_one_line_before_anything_runs(tmp_path, capsys, argv, says):
    try:
        status = tribo_command(["population", *argv, "--out", str(tmp_path / "p"), "--serial"])
    except SystemExit as e:  # argparse's own errors
        status = e.code
    assert status == 2
    err = capsys.readouterr().err
    assert says in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "p" / "particles.csv").exists()


def test_bad_class_edges_are_refused_by_the_api_before_any_run(tmp_path):
    with pytest.raises(ValueError, match="size class edges 0.002,0.001: at least two"):
        tribo.population(3, shape_edges=[0.3, 1], size_edges=[2e-3, 1e-3], serial=True,
                         out=str(tmp_path / "p"))
    assert not (tmp_path / "p").exists()


def test_measured_values_with_an_unknown_column_are_one_line(tmp_path, capsys):
    path = tmp_path / "m.csv"
    path.write_text("epsilon,diameter\n0.5,1e-3\n")
    assert tribo_command(["population", "-n", "3", "--measured", str(path), "--out",
                          str(tmp_path / "p")]) == 2
    err = capsys.readouterr().err
    assert "diameter" in err and len(err.strip().splitlines()) == 1


def synthetic_population(n, seed=1):
    """Rows as a population of a negatively charging pair gives them: a bimodal static q/m
    (most grains barely charged, a few much more), sizes in m."""
    rng = np.random.default_rng(seed)
    few = rng.random(n) < 0.15
    return pd.DataFrame({"epsilon": rng.uniform(0.3, 1, n), "size": rng.uniform(2e-4, 2e-3, n),
                         "charge_to_mass_static": -np.where(few, rng.lognormal(-14, 1, n),
                                                            rng.lognormal(-19, 0.3, n)),
                         "charge_to_mass_sliding": -rng.lognormal(-10, 1, n),
                         "charge_static": -rng.lognormal(-27, 1, n),
                         "charge_sliding": -rng.lognormal(-23, 1, n),
                         "exit_speed": rng.uniform(0.5, 1, n)})


def figure_of(results):
    """The figure as the runner draws it: from the population's summary."""
    summary = summarize_population(results, ("static", "sliding"))
    return population_plot.population_figure(results, summary)


def test_the_figure_has_a_legend_beside_every_panel_and_says_its_units():
    results = synthetic_population(60)
    fig = figure_of(results)
    axes = fig.axes
    assert len(axes) == 8
    for ax in axes:
        assert ax.get_legend() is not None and ax.get_xlabel() and ax.get_ylabel(), ax.get_title()
    assert_legends_cover_no_data(fig)
    # the pair charges negatively: the log axes show -q/m; sizes in m, as in the tables
    assert axes[0].get_xlabel().startswith("−q/m, static model (µC/kg)")
    assert axes[2].get_xlabel() == "size, the long diameter 2a (m)"
    assert any("(m)" in t.get_text() or " m (" in t.get_text()
               for t in axes[1].get_legend().get_texts())


def test_the_figures_mean_and_percentiles_are_the_summarys():
    results = synthetic_population(200, seed=3)
    summary = summarize_population(results, ("static", "sliding"))
    fig = population_plot.population_figure(results, summary)
    for ax, model in ((fig.axes[0], "static"), (fig.axes[4], "sliding")):
        row = summary[(summary.grouping == "all") & (summary.model == model)].iloc[0]
        lines = {line.get_label().split(" ")[0] if "percentile" not in line.get_label()
                 else " ".join(line.get_label().split(" ")[:2]): line
                 for line in ax.get_lines()}
        for label, column in (("mean", "mean"), ("median", "p50"), ("5th percentile", "p5"),
                              ("95th percentile", "p95")):
            line = lines[label]
            # drawn at the magnitude, labelled with the signed value of summary.csv
            assert line.get_xdata()[0] == pytest.approx(abs(row[column]) * 1e6, rel=1e-12)
            assert f"{row[column] * 1e6:.3g} µC/kg" in line.get_label()
    # the CSV's 5th percentile of a negative q/m is the largest magnitude: its line is
    # right of the 95th's on the magnitude axis
    assert lines["5th percentile"].get_xdata()[0] > lines["95th percentile"].get_xdata()[0]


@pytest.mark.parametrize("narrow", [False, True])
def test_no_tick_labels_overlap_on_any_range(narrow):
    # a 3 mm grain's q/m spans less than a decade: its axes labelled minor ticks one over
    # the next (issue 42)
    results = synthetic_population(60, seed=2)
    if narrow:
        for c in ("charge_to_mass_static", "charge_to_mass_sliding", "charge_static",
                  "charge_sliding"):
            results[c] = results[c].iloc[0] * np.linspace(1.0, 1.8, len(results))
        results["size"] = np.linspace(3e-3, 3.4e-3, len(results))
    assert_tick_labels_apart(figure_of(results))


def test_panels_of_no_information_are_left_out_saying_why():
    # spheres of one size leaving at one speed: the roundness, size and exit speed panels
    # were empty, or plotted 1e-10 m/s of noise on an offset axis
    results = synthetic_population(30, seed=5).assign(epsilon=1.0, size=1e-3)
    results["exit_speed"] = 1.37 + 1e-10 * np.arange(len(results))
    fig = figure_of(results)
    assert len(fig.axes) == 2  # the histogram of each model
    title = fig._suptitle.get_text()
    for why in ("q/m against roundness (every grain roundness ε 1)",
                "q/m against size (every grain size 0.001 m)",
                "exit speed against charge (every grain left at 1.37 m/s)"):
        assert f"left out, no information: {why}" in title, title
    only_size = synthetic_population(30, seed=5).assign(epsilon=1.0)
    titles = [ax.get_title() for ax in figure_of(only_size).axes]
    assert "q/m against size" in titles and "q/m against roundness" not in titles
    # speeds that differ in the fifth digit: drawn, written out without an offset
    close = synthetic_population(30, seed=5)
    close["exit_speed"] = 1.42 + 1e-5 * np.arange(len(close))
    fig = figure_of(close)
    fig.canvas.draw()
    speed = next(ax for ax in fig.axes if ax.get_title() == "exit speed against charge")
    assert speed.yaxis.get_offset_text().get_text() == ""


def test_the_figure_draws_the_streams_mass_weighted_mean():
    # the number to design on was the one the figure did not draw (issue 42)
    results = synthetic_population(80, seed=6)
    results["exited"], results["density"] = 1, 950.0
    summary = summarize_population(results, ("static", "sliding"))
    fig = population_plot.population_figure(results, summary)
    row = summary[(summary.grouping == "all") & (summary.model == "static")].iloc[0]
    assert np.isfinite(row["stream_mean"]) and row["stream_mean"] != row["mean"]
    line = next(line for line in fig.axes[0].get_lines() if line.get_label().startswith("stream mean"))
    assert line.get_xdata()[0] == pytest.approx(abs(row["stream_mean"]) * 1e6, rel=1e-12)
    assert f"{row['stream_mean'] * 1e6:.3g} µC/kg" in line.get_label()


def test_the_title_says_the_materials_file_and_the_vibrating_chute():
    described = {"particle": "PE", "wall": "steel", "materials": "out/cal/materials.toml",
                 "vibration": (5e-4, 50.0)}
    title = population_plot.population_title(described, 10, 1, "at the exit")
    assert title.endswith("; materials from materials.toml, the chute vibrating 0.5 mm at 50 Hz")


def test_the_figure_draws_the_summary_it_is_given():
    """The figure's classes and statistics are the summary's (computed once), not computed
    again from the particles: a summary of other edges and one model gives that figure."""
    results = synthetic_population(100, seed=4)
    summary = summarize_population(results, ("sliding",), shape_edges=[0.3, 0.65, 1.0],
                                   size_edges=[2e-4, 1e-3, 2e-3])
    summary.loc[summary["grouping"] == "all", "mean"] = -1e-6  # a mean the rows do not give
    fig = population_plot.population_figure(results, summary)
    assert len(fig.axes) == 4 and "sliding" in fig.axes[0].get_xlabel()
    mean = next(line for line in fig.axes[0].get_lines() if line.get_label().startswith("mean"))
    assert mean.get_xdata()[0] == pytest.approx(1.0)  # µC/kg, the summary's
    shapes = [t.get_text() for t in fig.axes[2].get_legend().get_texts()]
    assert [t.split(" (")[0] for t in shapes] == ["ε 0.30–0.65", "ε 0.65–1.00"]
    sizes = [t.get_text() for t in fig.axes[1].get_legend().get_texts()]
    assert len(sizes) == 2 and sizes[0].startswith("size 0.0002–0.001 m")


@pytest.mark.parametrize("n", [30, 100, 1000])
def test_the_histograms_bins_follow_the_number_of_particles(n):
    results = synthetic_population(n, seed=n)
    fig = figure_of(results)
    bars = [p for p in fig.axes[0].patches]
    assert len(bars) == population_plot.histogram_bins(n)
    assert population_plot.histogram_bins(30) >= 5  # not 3
    assert population_plot.histogram_bins(30) < population_plot.histogram_bins(100) \
        < population_plot.histogram_bins(1000)
    assert sum(b.get_height() for b in bars) == n


def test_the_api_runs_a_population_and_the_command_says_how_it_went(tmp_path, capsys):
    report = tribo.population(4, seed=2, chute=SHORT, t_end=1.0, out=str(tmp_path / "api"),
                              serial=True)
    assert report.complete and report.summary is not None
    assert (tmp_path / "api" / "population.png").exists()
    overall = report.summary[(report.summary.grouping == "all")]
    assert list(overall["n"]) == [4, 4]
    # each row says what it is: the materials, the seed, the chute, the cylinder depth
    rows = tribo.load_results(str(tmp_path / "api"))
    assert list(rows.columns[:4]) == ["key", "particle", "wall", "seed"]
    assert (rows["particle"] == "PE").all() and (rows["wall"] == "steel").all()
    assert (rows["seed"] == 2).all() and (rows["chute_length"] == 0.02).all()
    assert (rows["tilt_deg"] == 30.0).all() and (rows["cylinder_length"] == 1e-3).all()
    assert {"size", "phi0_deg", "drop_angle_deg"} <= set(rows.columns)
    # the air-breakdown limit's share of each grain's boundary (model.md section 8b)
    for model in ("static", "sliding"):
        assert rows[f"capped_fraction_{model}"].between(0.0, 1.0).all()
    # the stream a Faraday cup at the chute's end reads: the grains' charge over their mass
    # (the spheroid's, docs/model.md section 8c), of those that left
    mass = np.pi / 6 * rows["density"] * rows["size"] ** 3 * rows["epsilon"] ** 2
    left = rows["exited"] == 1
    for model in ("static", "sliding"):
        row = overall[overall.model == model].iloc[0]
        assert row["stream_mean"] == pytest.approx(
            rows.loc[left, f"charge_{model}"].sum() / mass[left].sum(), rel=1e-9)
        assert row["stayed"] == pytest.approx(mass[~left].sum() / mass.sum(), abs=1e-15)
    # the command over the same folder: everything already there
    assert tribo_command(["population", "-n", "4", "--seed", "2", "--chute-length", "0.02",
                          "--t-end", "1", "--out", str(tmp_path / "api"), "--serial",
                          "--no-progress"]) == 0
    assert "0 run, 4 already in the file" in capsys.readouterr().out


def test_the_streams_statistics_are_mass_weighted_over_the_grains_that_left():
    q = pd.Series([-1.0, -3.0, -10.0, -7.0])
    m = pd.Series([1.0, 3.0, 2.0, 4.0])
    left = pd.Series([1, 1, 0, 1])
    stats = stream_statistics(q, m, left)
    mean = (-1 * 1 - 3 * 3 - 7 * 4) / 8
    assert stats["stream_mean"] == pytest.approx(mean, rel=1e-15)
    assert stats["stream_std"] == pytest.approx(
        np.sqrt((1 * (-1 - mean) ** 2 + 3 * (-3 - mean) ** 2 + 4 * (-7 - mean) ** 2) / 8), rel=1e-15)
    assert stats["stayed"] == pytest.approx(2 / 10, rel=1e-15)
    # rows that do not say the masses or the exits, or a stream of nothing: NaN, said so
    assert all(np.isnan(v) for v in stream_statistics(q, None, left).values())
    nothing = stream_statistics(q, m, pd.Series([0, 0, 0, 0]))
    assert np.isnan(nothing["stream_mean"]) and nothing["stayed"] == 1.0


def test_grains_that_came_to_rest_are_counted_apart_and_said_so(tmp_path, capsys):
    """On a chute tilted 0.5 degrees (mu_roll at its SI default) every grain settles and its
    run ends at rest: none leaves, the stream is empty, the whole mass stays, at rest."""
    out = tmp_path / "flat"
    assert tribo_command(["population", "-n", "3", "--seed", "0", "--tilt-deg", "0.5",
                          "--t-end", "5", "--out", str(out), "--serial", "--no-progress"]) == 0
    said = capsys.readouterr().out
    assert ("population: 3 grains: 0 left the chute, 3 at rest on it (100 % of the mass), "
            "0 still on it at the horizon of 5 s (0 % of the mass)") in said
    rows = tribo.load_results(str(out))
    assert (rows["exited"] == 0).all() and (rows["end_reason"] == 3).all()
    assert (rows["at_rest"] == 1).all()
    # the run ends where the grain comes to rest, well before the horizon
    assert (rows["rest_time"] > 0).all() and (rows["rest_time"] < 5).all()
    assert (rows["rest_time"] == rows["time_end"]).all()
    summary = pd.read_csv(out / "summary.csv")
    overall = summary[summary.grouping == "all"]
    assert (overall["n_exited"] == 0).all() and (overall["n_at_rest"] == 3).all()
    assert (overall["n_at_horizon"] == 0).all()
    assert (overall["at_rest_fraction"] == 1).all() and (overall["stayed"] == 1).all()
    assert overall["stream_mean"].isna().all() and overall["stream_std"].isna().all()


def test_a_population_of_all_three_ends_keeps_the_stream_to_the_grains_that_left(tmp_path):
    """Tilted 5 degrees with a 1.5 s horizon, the seed's six grains end all three ways (two
    each, seen in the run): the counts and mass fractions are those of the rows, and the
    stream's statistics are over the grains that left only."""
    report = tribo.population(6, seed=2, chute={"chute_length": 0.3, "tilt_deg": 5}, t_end=1.5,
                              out=str(tmp_path / "mixed"), serial=True)
    rows = report.results
    ends = {1: "left", 3: "at rest", 0: "at the horizon"}
    assert sorted(rows["end_reason"].map(ends)) == sorted(["left", "at rest", "at the horizon"] * 2)
    assert ((rows["exited"] == 1) == (rows["end_reason"] == 1)).all()
    assert ((rows["at_rest"] == 1) == (rows["end_reason"] == 3)).all()
    horizon = rows["end_reason"] == 0
    assert (rows.loc[horizon, "time_end"] == 1.5).all() and (rows.loc[horizon, "rest_time"] == 0).all()
    mass = np.pi / 6 * rows["density"] * rows["size"] ** 3 * rows["epsilon"] ** 2
    left, rest = rows["end_reason"] == 1, rows["end_reason"] == 3
    overall = report.summary[report.summary.grouping == "all"]
    for model in ("static", "sliding"):
        row = overall[overall.model == model].iloc[0]
        assert (row["n"], row["n_exited"], row["n_at_rest"], row["n_at_horizon"]) == (6, 2, 2, 2)
        assert row["at_rest_fraction"] == pytest.approx(mass[rest].sum() / mass.sum(), rel=1e-12)
        assert row["at_horizon_fraction"] == pytest.approx(mass[horizon].sum() / mass.sum(),
                                                           rel=1e-12)
        assert row["stayed"] == pytest.approx(row["at_rest_fraction"] + row["at_horizon_fraction"],
                                              rel=1e-12)
        qm = rows[f"charge_to_mass_{model}"]
        assert row["stream_mean"] == pytest.approx((mass[left] * qm[left]).sum() / mass[left].sum(),
                                                   rel=1e-12)
        # the plain mean is of every grain, wherever its run ended
        assert row["mean"] == pytest.approx(qm.mean(), rel=1e-12)
    # per class the counts add up to the whole
    for grouping in ("shape", "size"):
        classes = report.summary[(report.summary.grouping == grouping)
                                 & (report.summary.model == "static")]
        assert classes[["n_exited", "n_at_rest", "n_at_horizon"]].sum().tolist() == [2, 2, 2]


def test_the_figure_stacks_the_grains_by_how_their_runs_ended():
    results = synthetic_population(60, seed=5)
    rng = np.random.default_rng(5)
    reason = rng.choice([1, 3, 0], size=60, p=[0.6, 0.3, 0.1])
    results = results.assign(exited=(reason == 1).astype(int), end_reason=reason,
                             density=950.0)
    summary = summarize_population(results, ("static",))
    fig = population_plot.population_figure(results, summary)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    mass = np.pi / 6 * 950.0 * results["size"] ** 3 * results["epsilon"] ** 2
    for code, text in ((1, "left the chute"), (3, "at rest on the chute"),
                       (0, "on the chute at the horizon")):
        share = 100 * mass[reason == code].sum() / mass.sum()
        assert f"{(reason == code).sum()} {text}, {share:.3g} % of the mass" in labels
    # every grain is in one stack; the exit speeds are of the grains that left
    bars = fig.axes[0].patches
    assert sum(b.get_height() for b in bars) == 60
    assert sum(len(c.get_offsets()) for c in fig.axes[3].collections) == (reason == 1).sum()
    assert "the grains that left" in fig.axes[3].get_title()
    assert_legends_cover_no_data(fig)


def test_rows_that_do_not_say_why_a_grain_stayed_are_counted_as_far_as_they_go():
    """Rows of an FMU without end_reason and at_rest: the grains that left are counted, the
    others only as having stayed; the words say no more than the rows."""
    from tribo.populations.summary import ends_text
    rows = pd.DataFrame({"epsilon": [0.5, 0.6, 0.7], "size": [1e-3] * 3, "density": [950.0] * 3,
                         "exited": [1, 0, 1], "charge_to_mass_static": [-1e-7, -2e-7, -3e-7]})
    row = summarize_population(rows, ("static",)).iloc[0]
    assert (row["n_exited"], row["stayed"]) == (2, pytest.approx(0.6 ** 2 / (0.25 + 0.36 + 0.49)))
    assert np.isnan(row["n_at_rest"]) and np.isnan(row["at_rest_fraction"])
    assert ends_text(row) == "3 grains: 2 left the chute, 1 did not (32.7 % of the mass)"
    # an at_rest column alone tells the two apart
    told = summarize_population(rows.assign(at_rest=[0, 1, 0]), ("static",)).iloc[0]
    assert (told["n_at_rest"], told["n_at_horizon"]) == (1, 0)


def test_failed_runs_are_said_on_stderr_and_a_work_limit_set_is_taken(tmp_path, capsys,
                                                                      monkeypatch):
    argv = ["population", "-n", "2", "--chute-length", "0.02", "--t-end", "1", "--serial",
            "--no-progress", "--no-plot"]
    # --set work_limit was a TypeError traceback ("multiple values for keyword argument")
    assert tribo_command(argv + ["--set", "work_limit=1000", "--out", str(tmp_path / "w")]) == 0
    assert (pd.read_csv(tmp_path / "w" / "particles.csv")["work_limit"] == 1000).all()
    capsys.readouterr()
    # every run failing: rc 1 with the reason on stdout alone before (issue 42)
    import tribo.populations.runner as runner

    def failing(image, spec):
        raise RuntimeError("the FMU failed in the step from time 0: a reason")

    monkeypatch.setattr(runner, "run_particle", failing)
    assert tribo_command(argv + ["--out", str(tmp_path / "f")]) == 1
    err = capsys.readouterr().err.strip()
    assert err == ("tribo population: error: 2 particle(s) failed, e.g.: the FMU failed in the "
                   "step from time 0: a reason"), err

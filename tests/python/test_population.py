"""Populations (tribo.population, tribo-population): the seeded draw, resuming, the summary
against a direct computation, bad input in one line, the figure's legends."""

import numpy as np
import pandas as pd
import pytest

import tribo
from tribo.batch.executors import SerialExecutor
from tribo.cli import population as cli
from tribo.fmu import FmuImage
from tribo.populations import plot as population_plot
from tribo.populations.feed import Feed, draw, particle_parameters
from tribo.populations.runner import run_population
from tribo.populations.summary import summarize_population

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
    # size is the long diameter: the FMU's semi-major axis is half of it
    params = particle_parameters(feed, a.head(2))
    assert params[0]["semi_major_axis"] == a["size"][0] / 2 and params[0]["sigma0"] == -1e-5


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


def test_the_summary_is_the_direct_computation():
    rng = np.random.default_rng(5)
    results = pd.DataFrame({"epsilon": rng.uniform(0.3, 1.0, 200), "size": rng.uniform(2e-4, 2e-3, 200),
                            "charge_to_mass_static": rng.normal(-1e-9, 3e-10, 200),
                            "charge_to_mass_sliding": rng.lognormal(-10, 1, 200)})
    edges = [0.3, 0.5, 0.8, 1.0]
    s = summarize_population(results, shape_edges=edges)
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
])
def test_bad_input_is_one_line_before_anything_runs(tmp_path, capsys, argv, says):
    assert cli.main(argv + ["--out", str(tmp_path / "p"), "--serial"]) == 2
    err = capsys.readouterr().err
    assert says in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "p" / "particles.csv").exists()


def test_measured_values_with_an_unknown_column_are_one_line(tmp_path, capsys):
    path = tmp_path / "m.csv"
    path.write_text("epsilon,diameter\n0.5,1e-3\n")
    assert cli.main(["-n", "3", "--measured", str(path), "--out", str(tmp_path / "p")]) == 2
    err = capsys.readouterr().err
    assert "diameter" in err and len(err.strip().splitlines()) == 1


def test_the_figure_has_a_legend_on_every_panel(tmp_path, monkeypatch):
    rng = np.random.default_rng(1)
    n = 60
    results = pd.DataFrame({"epsilon": rng.uniform(0.3, 1, n), "size": rng.uniform(2e-4, 2e-3, n),
                            "charge_to_mass_static": -rng.lognormal(-20, 1, n),
                            "charge_to_mass_sliding": -rng.lognormal(-10, 1, n),
                            "charge_static": -rng.lognormal(-27, 1, n),
                            "charge_sliding": -rng.lognormal(-23, 1, n),
                            "exit_speed": rng.uniform(0.5, 1, n)})
    figures = []
    monkeypatch.setattr(population_plot, "save", lambda fig, path: figures.append(fig) or path)
    population_plot.write_population_figure(results, str(tmp_path / "p.png"))
    axes = figures[0].axes
    assert len(axes) == 8
    for ax in axes:
        assert ax.get_legend() is not None and ax.get_xlabel() and ax.get_ylabel(), ax.get_title()


def test_the_api_runs_a_population_and_the_command_says_how_it_went(tmp_path, capsys):
    report = tribo.population(4, seed=2, chute=SHORT, t_end=1.0, out=str(tmp_path / "api"),
                              serial=True)
    assert report.complete and report.summary is not None
    assert (tmp_path / "api" / "population.png").exists()
    overall = report.summary[(report.summary.grouping == "all")]
    assert list(overall["n"]) == [4, 4]
    # the command over the same folder: everything already there
    assert cli.main(["-n", "4", "--seed", "2", "--chute-length", "0.02", "--t-end", "1",
                     "--out", str(tmp_path / "api"), "--serial", "--no-progress"]) == 0
    assert "0 run, 4 already in the file" in capsys.readouterr().out

"""A population run into a folder: the particles (batch.sweep.run_sweep's resumable
results file, one row per particle), the summary, the figure and what was run.

    <out>/particles.csv   one row per particle, with its materials and every parameter of
                          its run (tribo.load_results reads it)
    <out>/summary.csv     q/m statistics overall, per shape class, per size class
    <out>/population.png  the figure
    <out>/population.json the feed, N, the seed, the horizon and the FMU
"""

import json
import os
from dataclasses import dataclass

import pandas as pd

from ..batch.grid import values_of
from ..batch.job import Job, Report
from ..batch.sweep import keys_of, run_sweep
from ..fmu import FmuImage
from ..fmu.charge_models import charge_models
from ..fmu.locate import find_fmu
from ..fmu.names import format_number, start_value
from ..fmu.parameters import check_values
from .feed import Feed, check_horizon, result_columns, run_particle, specs_of
from .summary import check_class_edges, ends_text, summarize_population

PARTICLES, SUMMARY, FIGURE, METADATA = "particles.csv", "summary.csv", "population.png", "population.json"


@dataclass(kw_only=True)
class PopulationReport(Report):
    """The particles' rows (`results`, in the draw's order) and, once every particle has
    run, their summary."""

    summary: pd.DataFrame | None = None


def population_setup(feed: Feed, n: int, seed: int, t_end: float) -> dict:
    """What makes a population this one (an output folder's record, batch/folder.py): not
    n, since the first n grains of a draw are the same whatever n (feed.draw), so that a
    folder takes more grains, or the first of its own."""
    return {"seed": seed, "t_end_s": t_end, "feed": feed.describe()}


def prepare_population(feed: Feed, n: int, seed: int, t_end: float, image: FmuImage):
    """The runs, every value checked by the FMU before anything runs. The cylinder depth is
    set explicitly (the FMU's default unless the feed sets it), so that particles.csv says
    what the charges in C are for."""
    depth = start_value(image.model_description(), "cylinder_length")
    specs = specs_of(feed, n, seed, t_end, {"cylinder_length": depth})
    check_values(image, values_of(specs))
    check_horizon(image, specs)
    return specs


def run_population(feed: Feed, n: int, seed: int, t_end: float, image: FmuImage, out: str,
                   executor, *, resume: bool = True, max_runs: int | None = None,
                   progress: bool = True, figure: bool = True, shape_edges=None,
                   size_edges=None, specs=None) -> PopulationReport:
    """The population's runs on the executor (entered by the caller, or a SerialExecutor),
    then, once all have run, its summary and figure: feed -> runs -> particles.csv ->
    summary.csv -> population.png."""
    specs = specs if specs is not None else prepare_population(feed, n, seed, t_end, image)
    os.makedirs(out, exist_ok=True)
    described = feed.describe()
    metadata = {"n": n, "seed": seed, "t_end_s": t_end, "fmu": image.name,
                "fmu_sha256": image.sha256, "feed": described}
    with open(os.path.join(out, METADATA), "w") as f:
        json.dump(metadata, f, indent=2)
    models = charge_models(image.model_description())
    runs = run_sweep(specs, image, os.path.join(out, PARTICLES), executor, resume=resume,
                     max_runs=max_runs, progress=progress, desc="particles", run=run_particle,
                     result_columns=result_columns(models),
                     constants={"particle": described["particle"], "wall": described["wall"],
                                "seed": seed})
    report = PopulationReport(**vars(runs))
    report.files += [os.path.join(out, PARTICLES), os.path.join(out, METADATA)]
    if report.complete:
        report.summary = summarize_population(report.results, models, shape_edges, size_edges)
        report.summary.to_csv(os.path.join(out, SUMMARY), index=False)
        report.files.append(os.path.join(out, SUMMARY))
        if figure:
            # matplotlib only when a figure is drawn: `import tribo` stays without it
            from .plot import population_title, write_population_figure
            chute = described["chute"]
            overall = report.summary.iloc[0]
            where = (f"at the exit of a {format_number(chute['chute_length'])} m chute tilted "
                     f"{format_number(chute['tilt_deg'])}°")
            if overall["n_exited"] != overall["n"]:  # some stayed, or the rows do not say
                where = (f"on a {format_number(chute['chute_length'])} m chute tilted "
                         f"{format_number(chute['tilt_deg'])}°, q/m where each run ended: "
                         f"{ends_text(overall, t_end)}")
            title = population_title(described, n, seed, where)
            report.files.append(write_population_figure(report.results, report.summary,
                                                        os.path.join(out, FIGURE), title))
    return report


class PopulationJob(Job):
    """A population into an output folder (batch/job.py's flow): n particles drawn from
    `feed` with `seed`, each to `t_end` s through the SI FMU `fmu` (a path, 2 / 3, or the
    build's)."""

    kind, noun, results_file = "population", "particle", PARTICLES

    def __init__(self, feed: Feed, n: int, seed: int = 0, t_end: float = 5.0, fmu=None, *,
                 figure: bool = True, shape_edges=None, size_edges=None):
        self.feed, self.n, self.seed, self.t_end, self.fmu = feed, n, seed, t_end, fmu
        self.figure, self.shape_edges, self.size_edges = figure, shape_edges, size_edges
        self.keys = []

    def prepare(self) -> None:
        check_class_edges(self.shape_edges, self.size_edges)
        self.image = FmuImage.load(find_fmu(self.fmu, "si"))
        self.specs = prepare_population(self.feed, self.n, self.seed, self.t_end, self.image)
        self.sha256 = self.image.sha256
        self.keys = keys_of(self.specs, self.image)

    def setup(self) -> dict:
        return population_setup(self.feed, self.n, self.seed, self.t_end)

    def describe(self, out: str, executor) -> str:
        return (f"population: {self.n} particles of {self.feed.particle} on {self.feed.wall} "
                f"(seed {self.seed}) into {out}")

    def run(self, out: str, executor, *, progress: bool, max_runs: int | None) -> PopulationReport:
        return run_population(self.feed, self.n, self.seed, self.t_end, self.image, out, executor,
                              max_runs=max_runs, progress=progress, figure=self.figure,
                              shape_edges=self.shape_edges, size_edges=self.size_edges,
                              specs=self.specs)

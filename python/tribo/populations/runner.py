"""A population run into a folder: the particles (batch.sweep.run_sweep's resumable
results file, one row per particle), the summary, the figure and what was run.

    <out>/particles.csv   one row per particle (tribo.load_results reads it)
    <out>/summary.csv     q/m statistics overall, per shape class, per size class
    <out>/population.png  the figure
    <out>/population.json the feed, N, the seed, the horizon and the FMU
"""

import json
import os
from dataclasses import dataclass

import pandas as pd

from ..batch.grid import values_of
from ..batch.sweep import run_sweep
from ..fmu import FmuImage
from ..fmu.parameters import check_values
from .feed import RESULT_COLUMNS, Feed, run_particle, specs_of
from .summary import summarize_population

PARTICLES, SUMMARY, FIGURE, METADATA = "particles.csv", "summary.csv", "population.png", "population.json"


@dataclass
class PopulationReport:
    results: pd.DataFrame  # the finished particles, in the draw's order
    summary: pd.DataFrame | None  # None until every particle has run
    total: int
    executed: int
    skipped: int
    failed: list  # (spec, exception)
    files: list
    backup: str | None = None

    @property
    def complete(self) -> bool:
        return len(self.results) == self.total


def prepare_population(feed: Feed, n: int, seed: int, t_end: float, image: FmuImage):
    """The runs, every value checked by the FMU before anything runs."""
    specs = specs_of(feed, n, seed, t_end)
    check_values(image, values_of(specs))
    return specs


def run_population(feed: Feed, n: int, seed: int, t_end: float, image: FmuImage, out: str,
                   executor, *, resume: bool = True, max_runs: int | None = None,
                   progress: bool = True, figure: bool = True, shape_edges=None,
                   size_edges=None, specs=None) -> PopulationReport:
    specs = specs if specs is not None else prepare_population(feed, n, seed, t_end, image)
    os.makedirs(out, exist_ok=True)
    metadata = {"n": n, "seed": seed, "t_end_s": t_end, "fmu": image.name,
                "fmu_sha256": image.sha256, "feed": feed.describe()}
    with open(os.path.join(out, METADATA), "w") as f:
        json.dump(metadata, f, indent=2)
    with executor:
        report = run_sweep(specs, image, os.path.join(out, PARTICLES), executor, resume=resume,
                           max_runs=max_runs, progress=progress, desc="particles",
                           run=run_particle, result_columns=RESULT_COLUMNS)
    files = [os.path.join(out, PARTICLES), os.path.join(out, METADATA)]
    summary = None
    if report.complete:
        summary = summarize_population(report.results, shape_edges, size_edges)
        summary.to_csv(os.path.join(out, SUMMARY), index=False)
        files.append(os.path.join(out, SUMMARY))
        if figure:
            # matplotlib only when a figure is drawn: `import tribo` stays without it
            from .plot import write_population_figure
            title = (f"{n} particles of {feed.particle} on {feed.wall} (seed {seed}), "
                     f"at the chute's exit")
            files.append(write_population_figure(report.results, os.path.join(out, FIGURE),
                                                 shape_edges, size_edges, title))
    return PopulationReport(report.results, summary, len(report.keys), report.executed,
                            report.skipped, report.failed, files, report.backup)

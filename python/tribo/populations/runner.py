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
from ..batch.sweep import run_sweep
from ..fmu import FmuImage
from ..fmu.names import format_number, start_value
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


def population_setup(feed: Feed, n: int, seed: int, t_end: float) -> dict:
    """What makes a population this one (an output folder's record, batch/folder.py)."""
    return {"n": n, "seed": seed, "t_end_s": t_end, "feed": feed.describe()}


def prepare_population(feed: Feed, n: int, seed: int, t_end: float, image: FmuImage):
    """The runs, every value checked by the FMU before anything runs. The cylinder depth is
    set explicitly (the FMU's default unless the feed sets it), so that particles.csv says
    what the charges in C are for."""
    depth = start_value(image.model_description(), "cylinder_length")
    specs = specs_of(feed, n, seed, t_end, {"cylinder_length": depth})
    check_values(image, values_of(specs))
    return specs


def run_population(feed: Feed, n: int, seed: int, t_end: float, image: FmuImage, out: str,
                   executor, *, resume: bool = True, max_runs: int | None = None,
                   progress: bool = True, figure: bool = True, shape_edges=None,
                   size_edges=None, specs=None) -> PopulationReport:
    specs = specs if specs is not None else prepare_population(feed, n, seed, t_end, image)
    os.makedirs(out, exist_ok=True)
    described = feed.describe()
    metadata = {"n": n, "seed": seed, "t_end_s": t_end, "fmu": image.name,
                "fmu_sha256": image.sha256, "feed": described}
    with open(os.path.join(out, METADATA), "w") as f:
        json.dump(metadata, f, indent=2)
    with executor:
        report = run_sweep(specs, image, os.path.join(out, PARTICLES), executor, resume=resume,
                           max_runs=max_runs, progress=progress, desc="particles",
                           run=run_particle, result_columns=RESULT_COLUMNS,
                           constants={"particle": described["particle"],
                                      "wall": described["wall"], "seed": seed})
    files = [os.path.join(out, PARTICLES), os.path.join(out, METADATA)]
    summary = None
    if report.complete:
        summary = summarize_population(report.results, shape_edges, size_edges)
        summary.to_csv(os.path.join(out, SUMMARY), index=False)
        files.append(os.path.join(out, SUMMARY))
        if figure:
            # matplotlib only when a figure is drawn: `import tribo` stays without it
            from .plot import write_population_figure
            chute = described["chute"]
            title = (f"{n} particles of {described['particle']} on {described['wall']} (seed "
                     f"{seed}), at the exit of a {format_number(chute['chute_length'])} m chute "
                     f"tilted {format_number(chute['tilt_deg'])}°")
            files.append(write_population_figure(report.results, os.path.join(out, FIGURE),
                                                 shape_edges, size_edges, title))
    return PopulationReport(report.results, summary, len(report.keys), report.executed,
                            report.skipped, report.failed, files, report.backup)

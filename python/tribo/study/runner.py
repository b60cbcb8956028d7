"""The paper's study (docs/model.md section 7) through the FMU: both friction cases, a range
of roundness values, both charge models, to the horizon; the transition roundness of
each friction case; figures and tables. Optionally the same grid with other normal
dashpots (damping_point, docs/model.md section 3), side by side with the study's own.

The runs use the FMU's default tolerances (rtol, atol: the start values of its
modelDescription, set explicitly so that the results file shows them) unless the settings
give others.

Everything a run produces goes to <out>/runs/ (results.csv: one row per run, keyed;
series/<key>.csv: its time series; series/<key>.segments.csv: each segment's charge at
the end, from an FMI 3.0 FMU), so a study that is interrupted resumes where it
stopped, and a second study with the same runs (e.g. the transition search's coarse
grid, which is the study's roundness grid) reuses them.
"""

import os
import time
from dataclasses import dataclass, field

import pandas as pd

from ..batch.sweep import read_segments, read_series, run_sweep
from ..fmu.parameters import integer_names
from . import figures, tables
from .paper import FRICTION_CASES, paper_spec
from .transition import Transition, find_transition

PAPER_EPSILONS = tuple(round(0.1 * k, 10) for k in range(1, 11))
# the tighter tolerance at which the ends of each final bracket are re-run: the verdict
# (turns or not) must not be an artefact of the integration error
CHECK_TOLERANCES = {"rtol": 1e-10, "atol": 1e-12}


@dataclass(frozen=True)
class StudySettings:
    epsilons: tuple
    t_end: float
    transition_width: float
    record_interval: float = 1.0
    frictions: tuple = tuple(FRICTION_CASES)
    # points per round of the eps_t multi-section: a setting of the study, not of the
    # executor, so that the search (and the runs it makes) is the same wherever it runs
    points_per_round: int = 2
    # the normal dashpots (damping_point values): the first is the study's own (eps_t,
    # the detailed tables); the grid is run with the others too, for comparison
    dashpots: tuple = (0,)
    # (name, value) pairs that override the FMU's default tolerances, e.g. (("rtol", 1e-8),)
    tolerances: tuple = ()

    @property
    def dashpot(self) -> int:
        return self.dashpots[0]


FULL = StudySettings(epsilons=PAPER_EPSILONS, t_end=5000.0, transition_width=0.002)
# the main job's default: under two minutes on 2 cores, set-up included
REDUCED = StudySettings(epsilons=(0.1, 0.3, 0.5, 0.7, 0.9, 1.0), t_end=1000.0,
                        transition_width=0.02)


@dataclass
class StudyResult:
    settings: StudySettings
    # one row per (dashpot, friction, epsilon) of the grid, with "friction" and
    # "damping_point" columns, the study's own dashpot first
    all_runs: pd.DataFrame
    all_series: dict  # (damping_point, friction, epsilon) -> time series
    all_segments: dict  # (damping_point, friction, epsilon) -> segment charges at the end, or None
    transitions: dict  # friction -> Transition
    transition_points: pd.DataFrame  # every evaluated point of the searches
    tolerance_checks: pd.DataFrame  # the bracket ends at CHECK_TOLERANCES
    executed: int = 0  # runs executed by this invocation (the rest came from runs/)
    total_runs: int = 0
    wall_s: float = 0.0  # of this invocation, until the figures and tables were written
    executor: str = ""
    fmu_name: str = ""
    fmu_sha256: str = ""
    tolerances: dict = field(default_factory=dict)  # rtol and atol the runs used
    backup: str | None = None  # where --fresh moved the earlier results
    files: list = field(default_factory=list)

    @property
    def runs(self) -> pd.DataFrame:
        """The grid with the study's own dashpot: one row per (friction, epsilon)."""
        return self.runs_of(self.settings.dashpot)

    def runs_of(self, dashpot: int) -> pd.DataFrame:
        return self.all_runs[self.all_runs["damping_point"] == dashpot].reset_index(drop=True)

    def series_of(self, dashpot: int, friction: str, epsilon: float) -> pd.DataFrame:
        return self.all_series[(dashpot, friction, epsilon)]

    def segments_of(self, dashpot: int, friction: str, epsilon: float) -> pd.DataFrame | None:
        return self.all_segments[(dashpot, friction, epsilon)]



def run_study(settings: StudySettings, image, out_dir: str, executor, *, resume: bool = True,
              progress: bool = True, command: str = "", started: float | None = None) -> StudyResult:
    """Run the study into out_dir. `started`: time.perf_counter() at which the invocation
    began (for the reported wall time; default now)."""
    start = time.perf_counter() if started is None else started
    runs_dir = os.path.join(out_dir, "runs")
    results_path = os.path.join(runs_dir, "results.csv")
    series_dir = os.path.join(runs_dir, "series")
    counts = {"executed": 0, "total": set(), "backup": None}
    # set in every run, so that the results file says which; the grid's equal the runs
    # that leave them at the FMU's defaults, bit for bit
    tolerances = tolerances_of(image, settings)
    integers = integer_names(image.model_description())

    def sweep(specs, desc, fresh=False):
        report = run_sweep(specs, image, results_path, executor, resume=not fresh,
                           series_dir=series_dir, progress=progress, desc=desc)
        counts["backup"] = counts["backup"] or report.backup
        if report.failed:
            spec, error = report.failed[0]
            raise RuntimeError(f"{len(report.failed)} run(s) failed, e.g. {spec.params}: {error}")
        counts["executed"] += report.executed
        counts["total"].update(report.keys)
        return report.results

    def spec(e, friction, dashpot=settings.dashpot, **overrides):
        return paper_spec(e, friction, settings.t_end, settings.record_interval,
                          integer_names=integers, damping_point=dashpot,
                          **dict(tolerances, **overrides))

    grid = [(d, f, e) for d in settings.dashpots for f in settings.frictions
            for e in settings.epsilons]
    runs = sweep([spec(e, f, d) for d, f, e in grid], "study runs", fresh=not resume)
    runs.insert(1, "friction", [f for _, f, _ in grid])
    series = {(d, f, e): read_series(series_dir, k) for (d, f, e), k in zip(grid, runs["key"])}
    segments = {(d, f, e): read_segments(series_dir, k) for (d, f, e), k in zip(grid, runs["key"])}

    transitions, points, checks = {}, [], []
    for friction in settings.frictions:
        def turns(epsilons, friction=friction):
            rows = sweep([spec(e, friction) for e in epsilons], f"eps_t search, {friction} friction")
            return [bool(v) for v in rows["turned_over"]]

        found = find_transition(turns, settings.epsilons, settings.transition_width,
                                points_per_round=settings.points_per_round)
        transitions[friction] = found
        evaluated = sweep([spec(e, friction) for e in sorted(found.evaluated)], "eps_t points")
        points.append(evaluated.assign(friction=friction,
                                       on_grid=evaluated["epsilon"].isin(found.grid)))
        checks += _tolerance_check(found, friction, spec, sweep)

    result = StudyResult(settings, runs, series, segments, transitions,
                         pd.concat(points, ignore_index=True), pd.DataFrame(checks),
                         executed=counts["executed"], total_runs=len(counts["total"]),
                         executor=executor.describe(), fmu_name=image.name,
                         fmu_sha256=image.sha256, tolerances=tolerances,
                         backup=counts["backup"])
    os.makedirs(out_dir, exist_ok=True)
    result.files += figures.write_all(result, out_dir)
    result.wall_s = time.perf_counter() - start
    result.files += tables.write_all(result, out_dir, command)
    return result


def _tolerance_check(found: Transition, friction: str, spec, sweep) -> list:
    ends = [e for e in (found.lo, found.hi) if e is not None]
    if not ends:
        return []
    specs = [spec(e, friction, **CHECK_TOLERANCES) for e in ends]
    tight = sweep(specs, f"tolerance check, {friction} friction")
    return [{"friction": friction, "epsilon": e, "turns_at_study_tolerance": found.evaluated[e],
             "turns_at_rtol_1e-10": bool(t), "turns_max_at_rtol_1e-10": m}
            for e, t, m in zip(ends, tight["turned_over"], tight["turns_max"])]


def tolerances_of(image, settings: StudySettings) -> dict:
    """rtol and atol of the study's runs: the settings' overrides, else the FMU's defaults
    (the start values in its modelDescription)."""
    variables = {v.name: v for v in image.model_description().modelVariables}
    out = {name: float(variables[name].start) for name in ("rtol", "atol") if name in variables}
    out.update(dict(settings.tolerances))
    return out

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
from dataclasses import asdict, dataclass, field

import pandas as pd

from ..batch.job import Job, Report, raise_on_failure
from ..batch.particle import communication_points
from ..batch.sweep import RESULTS, read_segments, read_series, run_sweep
from ..fmu import FmuImage
from ..fmu.locate import find_fmu
from ..fmu.parameters import check_values, integer_names
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


@dataclass(kw_only=True)
class StudyResult(Report):
    """The study's report: `keys` every run it is made of (the grid, the eps_t searches, the
    tolerance checks), `executed` those this invocation ran (the rest came from runs/)."""

    settings: StudySettings
    # one row per (dashpot, friction, epsilon) of the grid, with "friction" and
    # "damping_point" columns, the study's own dashpot first
    all_runs: pd.DataFrame
    all_series: dict  # (damping_point, friction, epsilon) -> time series
    all_segments: dict  # (damping_point, friction, epsilon) -> segment charges at the end, or None
    transitions: dict  # friction -> Transition
    transition_points: pd.DataFrame  # every evaluated point of the searches
    tolerance_checks: pd.DataFrame  # the bracket ends at CHECK_TOLERANCES
    wall_s: float = 0.0  # of this invocation, until the figures and tables were written
    executor: str = ""
    fmu_name: str = ""
    fmu_sha256: str = ""
    tolerances: dict = field(default_factory=dict)  # rtol and atol the runs used

    @property
    def total_runs(self) -> int:
        return len(self.keys)

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
    counts = {"executed": 0, "keys": {}, "backup": None}
    # set in every run, so that the results file says which; the grid's equal the runs
    # that leave them at the FMU's defaults, bit for bit
    tolerances = tolerances_of(image, settings)
    integers = integer_names(image.model_description())

    def sweep(specs, desc, fresh=False):
        report = run_sweep(specs, image, results_path, executor, resume=not fresh,
                           series_dir=series_dir, progress=progress, desc=desc)
        counts["backup"] = counts["backup"] or report.backup
        raise_on_failure(report, "run")
        counts["executed"] += report.executed
        counts["keys"].update(dict.fromkeys(report.keys))
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

    result = StudyResult(settings=settings, all_runs=runs, all_series=series,
                         all_segments=segments, transitions=transitions,
                         transition_points=pd.concat(points, ignore_index=True),
                         tolerance_checks=pd.DataFrame(checks), keys=list(counts["keys"]),
                         results=runs, executed=counts["executed"],
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


class StudyJob(Job):
    """The study into an output folder (batch/job.py's flow), with `settings` (FULL,
    REDUCED or one of them replaced), the FMU `fmu` (a path, 2 / 3, or the build's);
    `command` (the command line, for study.md) and `started` (time.perf_counter() at its
    start, for the reported wall time)."""

    kind, noun, results_file = "study", "run", os.path.join("runs", RESULTS)

    def __init__(self, settings: StudySettings, fmu=None, *, command: str = "",
                 started: float | None = None):
        self.settings, self.fmu, self.command, self.started = settings, fmu, command, started
        self.keys = []  # made as the eps_t search goes: not known beforehand

    def prepare(self) -> None:
        """The FMU, every parameter value of the grid (by the FMU), the horizon and the
        search's settings, checked."""
        s = self.settings
        communication_points(s.t_end, s.record_interval)
        if not s.transition_width > 0:
            raise ValueError(f"--transition-width {s.transition_width:g}: must be > 0")
        if s.points_per_round < 1:
            raise ValueError(f"--points-per-round {s.points_per_round}: at least 1")
        self.image = FmuImage.load(find_fmu(self.fmu))
        integers = integer_names(self.image.model_description())
        specs = [paper_spec(e, f, s.t_end, integer_names=integers, damping_point=d,
                            **dict(s.tolerances))
                 for d in s.dashpots for f in s.frictions for e in s.epsilons]
        values = {}
        for spec in specs:
            for name, value in spec.params.items():
                values.setdefault(name, []).append(value)
        check_values(self.image, values)
        self.sha256 = self.image.sha256

    def setup(self) -> dict:
        return asdict(self.settings)

    def describe(self, out: str, executor) -> str:
        s = self.settings
        return (f"study: {len(s.epsilons)} roundness values x {len(s.frictions)} friction cases "
                f"to tau = {s.t_end:g}, damping_point {', '.join(map(str, s.dashpots))}, FMU "
                f"{self.image.name}, into {out}, on {executor.describe()}")

    def run(self, out: str, executor, *, progress: bool, max_runs: int | None) -> StudyResult:
        return run_study(self.settings, self.image, out, executor, progress=progress,
                         command=self.command, started=self.started)

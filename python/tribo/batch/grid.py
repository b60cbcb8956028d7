"""The runs of a parameter sweep: every combination of the values given for each swept
parameter, over a base set-up; and the sweep as a job (`SweepJob`, batch/job.py's flow:
tribo.sweep and `tribo sweep`).

The paper's base (docs/model.md section 7, CVODE, epsilon 0.5, mu = nu = 0.1, the FMU's
default tolerances, every charge model the FMU has at its switch's default) or the FMU's
start values; as in the paper, nu follows mu and tau_r follows tau0 unless they are swept
too (tie=False: they don't).
"""

import itertools
import math
import os

import numpy as np

from ..fmu import FmuImage
from ..fmu.locate import find_fmu
from ..fmu.names import ParameterError, format_number
from ..fmu.parameters import check_names, check_values, integer_names
from .job import Job
from .particle import communication_points
from .specs import RunSpec, check_count, normalise_values
from .sweep import FIGURE, RESULTS, SERIES, keys_of, run_sweep, sweep_setup

# docs/model.md section 7 (the paper's set-up), with CVODE instead of the paper's fixed step
# (faster at equal error, see docs/work_precision.md) at the FMU's default tolerances (rtol,
# atol: not set here), with every charge model (the FMU's default switches), and the normal
# dashpot on the contact point (docs/model.md section 3).
# The study sets epsilon, mu and nu per run; a sweep's paper base takes PAPER_BASE's.
PAPER_SETUP = {
    "Gamma": 0.001,
    "beta_deg": 45.0,  # the FMU's beta is pi/4 rad (fmu/names.py)
    "tau0": 1.0,
    "Sigma0": 0.01,
    "eta": 0.1,
    "tau_r": 1.0,  # tau_r = tau0
    "n_segments": 2000,
    "drop_speed": 0.025,
    "integrator": 1,  # CVODE (Adams)
    "damping_point": 0,
}
PAPER_BASE = dict(PAPER_SETUP, epsilon=0.5, mu=0.1, nu=0.1)
TIES = {"nu": "mu", "tau_r": "tau0"}  # follower: leader (the paper's mu = nu, tau_r = tau0)


def parse_values(text: str) -> list[float]:
    """'a:b:n' (n values from a to b), 'v1,v2,...' or 'v'; ValueError saying why not."""
    try:
        if ":" in text:
            a, b, n = text.split(":")
            a, b, n = float(a), float(b), int(n)
            if n < 1:
                raise ValueError("need at least one value")
        else:
            values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError as e:
        raise ValueError(f"{e} (expected a:b:n, v1,v2,... or v)") from None
    if ":" in text:
        check_count(n, f"{text}: the number of values")
        return list(np.linspace(a, b, n))
    if not values:
        raise ValueError("no values (expected a:b:n, v1,v2,... or v)")
    return values


def parse_param(text: str) -> tuple[str, list[float]]:
    """'NAME=VALUES' -> (name, values)."""
    name, sep, values = text.partition("=")
    if not sep or not name.strip():
        raise ValueError(f"--param {text!r}: expected NAME=VALUES")
    try:
        return name.strip(), parse_values(values)
    except ValueError as e:
        raise ValueError(f"--param {text}: {e}") from None


def build_specs(swept: list[tuple[str, list[float]]], base: dict, integer_names, t_end: float,
                record_interval: float, tie: bool = True) -> list[RunSpec]:
    """Every combination of the swept values (the first parameter varies slowest)."""
    names = [n for n, _ in swept]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ValueError(f"given more than once: {', '.join(twice)}")
    check_count(math.prod(len(values) for _, values in swept),
                f"runs of the grid {' x '.join(str(len(v)) for _, v in swept)}")
    specs = []
    for combo in itertools.product(*(values for _, values in swept)):
        params = dict(base, **dict(zip(names, combo)))
        if tie:
            for follower, leader in TIES.items():
                if leader in names and follower not in names:
                    params[follower] = params[leader]
        specs.append(RunSpec(normalise_values(params, integer_names), float(t_end),
                             float(record_interval)))
    return specs


def vibration_parameters(vibration, image) -> dict:
    """A sweep's --vibration (AMPLITUDE, FREQUENCY[, ANGLE_DEG]) as the dimensionless FMU's
    parameters, by the package's names: the amplitude A in units of the grain's semi-major axis
    a, the frequency f in cycles per t*, the stroke's angle in degrees give vib_omega = 2 pi f,
    vib_accel = A (2 pi f)^2 (docs/model.md section 9b, as src/si/si.c derives them from m and
    Hz, with a and t* the units) and vib_angle_deg. ValueError / ParameterError, one line
    naming --vibration, its value and the range, for a value the FMU refuses."""
    values = tuple(float(v) for v in vibration)
    text = ",".join(format_number(v) for v in values)
    if len(values) not in (2, 3):
        raise ValueError(f"--vibration {text}: expected AMPLITUDE,FREQUENCY[,ANGLE_DEG], two or "
                         f"three numbers")
    amplitude, frequency = values[:2]
    if not (math.isfinite(amplitude) and amplitude >= 0):
        raise ValueError(f"--vibration {text}: the amplitude {format_number(amplitude)} (in units "
                         f"of the semi-major axis a) must be 0 or more")
    if not (math.isfinite(frequency) and frequency > 0):
        raise ValueError(f"--vibration {text}: the frequency {format_number(frequency)} (cycles "
                         f"per t*) must be above 0, at most 1/(2 pi) = {1 / (2 * math.pi):.6g}")
    omega = 2.0 * math.pi * frequency
    params = {"vib_accel": amplitude * omega * omega, "vib_omega": omega}
    if len(values) == 3:
        params["vib_angle_deg"] = values[2]
    try:
        check_values(image, {name: [value] for name, value in params.items()})
    except ParameterError as e:
        raise ParameterError(f"--vibration {text} (A = {format_number(amplitude)} a, f = "
                             f"{format_number(frequency)} per t*): {e}") from None
    return params


def values_of(specs: list[RunSpec]) -> dict:
    """Parameter name -> the distinct values the runs give it."""
    out = {}
    for s in specs:
        for name, value in s.params.items():
            out.setdefault(name, {})[value] = None
    return {name: list(values) for name, values in out.items()}


class SweepJob(Job):
    """A parameter sweep of the dimensionless FMU into an output folder (batch/job.py):
    `swept` the (name, values) of each swept parameter, the rest as in build_specs; the
    figure results.png unless figure=False, each run's series with series=True; `vibration`
    (AMPLITUDE, FREQUENCY[, ANGLE_DEG] in the model's units, vibration_parameters) swept at
    one value each, after the others."""

    kind, noun, results_file = "sweep", "run", RESULTS

    def __init__(self, swept: list[tuple[str, list]], *, t_end: float, record_interval: float = 1.0,
                 base: str = "paper", tie: bool = True, fmu=None, series: bool = False,
                 figure: bool = True, vibration=None):
        self.given = [(name, list(values)) for name, values in swept]
        self.vibration = vibration
        self.swept = list(self.given)  # with the vibration's, once prepared
        self.names = [name for name, _ in self.swept]
        self.t_end, self.record_interval = t_end, record_interval
        self.base, self.tie, self.fmu = base, tie, fmu
        self.series, self.figure = series, figure
        self.keys = []

    def prepare(self) -> None:
        """The FMU, the swept values (types by the modelDescription, ranges by the FMU)
        and the horizon, checked."""
        if self.base not in ("paper", "fmu"):
            raise ValueError(f"base = {self.base!r}: paper or fmu")
        communication_points(self.t_end, self.record_interval)
        self.image = FmuImage.load(find_fmu(self.fmu))
        md = self.image.model_description()
        check_names(md, self.names)
        if self.vibration is not None:
            vibrating = vibration_parameters(self.vibration, self.image)
            both = [name for name in vibrating if name in self.names]
            if both:
                raise ValueError(f"{both[0]} is given twice: swept (--param) and by --vibration")
            self.swept = self.given + [(name, [value]) for name, value in vibrating.items()]
            self.names = [name for name, _ in self.swept]
        self.specs = build_specs(self.swept, PAPER_BASE if self.base == "paper" else {},
                                 integer_names(md), self.t_end, self.record_interval, self.tie)
        check_values(self.image, values_of(self.specs))  # by the FMU itself
        self.sha256 = self.image.sha256
        self.keys = keys_of(self.specs, self.image)

    def setup(self) -> dict:
        return sweep_setup(self.names, self.base, self.tie)

    def describe(self, out: str, executor) -> str:
        return (f"sweep: {len(self.specs)} runs to t = {self.t_end:g} on {executor.describe()}, "
                f"into {out}")

    def run(self, out: str, executor, *, progress: bool, max_runs: int | None):
        report = run_sweep(self.specs, self.image, self.results_path(out), executor,
                           series_dir=os.path.join(out, SERIES) if self.series else None,
                           max_runs=max_runs, progress=progress, desc="sweep")
        report.files.append(self.results_path(out))
        if self.figure and len(report.results):
            # matplotlib only when a figure is drawn: `import tribo` stays without it
            from .plot import write_sweep_figure
            report.files.append(write_sweep_figure(report.results, self.names,
                                                   os.path.join(out, FIGURE)))
        return report

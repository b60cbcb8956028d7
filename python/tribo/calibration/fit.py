"""The fit of a pair's charging parameters to measured points (data.py), through the SI
FMU's observables (observables.py): sigma0 (signed, |sigma0| within its bound) and
whichever of charging_time (t0) and eta the data determine; sigma0 a lower bound where the
data stand at the gas's limit.

**What is fitted.** The residual of a point is log10(model / measured) of its charge
(impacts: Delta q; chutes: the stream's q/m), weighted by the measured standard deviation
in decades, std / (|value| ln 10), where every point gives one (else all alike, said in
a warning where only some do). The
parameters are fitted in decades too, log10 |sigma0|, log10 t0, log10 eta, by scipy's
least_squares within bounds: |sigma0| up to the materials table's bound, 1e-2 C/m2 (the
contact's own density, docs/model.md section 8e; with breakdown_model = fixed, up to
breakdown_density where lower, section 8b), t0 over the range where it acts on these
data (a hundredth of the shortest contact period to ten times the longest run), eta from
1e-14 to 1e3 (the sliding model's work raises the saturation by sqrt(eta
omega) in units of sqrt(kappa k' a), some 1e2 C/m2 for a mm grain: an eta of 1e-10 already
takes an oblique impact's saturation above sigma0). sigma0's sign is the data's.

**The static model's structure.** With the static model, no band at the gas's limit and a uniform initial density sigma_init, every band's density is a mix of sigma0 and
sigma_init, so the charge an impact gives is exactly (sigma0 - sigma_init) F, F depending on
t0 (and the mechanics) but not on sigma0 (docs/model.md sections 5a, 8c; with t0 = 0, F is
the charged area); n impacts on fresh spots follow the recurrence q_(k+1) = q_k + (sigma0 -
q_k/A_s) F; a chute's stream q/m is sigma0 G. So one run per point at each t0 gives every
sigma0: the fit runs the points at t0 = 0 and on a grid of t0 over the range (impacts
two per decade, chute runs one) in one batch, interpolates log F in log t0 (monotone
cubic), fits sigma0 and t0 on that, and runs the points at the fitted t0, adding those
runs to the interpolation and fitting again where it was off there. Other
charge models (sliding) are fitted on runs at every step (forward differences of 0.05
decades for the Jacobian, all in one batch per step).

**What the data determine** is read off the fit's sensitivities: the Jacobian J of the
residuals in the parameters' decades at the optimum, J = U S V^T. A direction v of
parameter space moves the fit by S_k per decade; with the data's scatter s (from the
residuals, or 1 with measured standard deviations; at least FLOOR_DECADES), its standard
deviation is s / S_k decades. A direction with more than UNDETERMINED_DECADES is one the
data do not determine: a single parameter (t0 with complete transfer; eta where the data
have little sliding) or a combination (t0 far above the contact time: sigma0 and t0 move
together, only sigma0/t0 is determined). Where t0 = 0 fits as well as the best t0 (its
sum of squares within COMPLETE_TRANSFER_CHI2 s^2 of the best: a test of t0 > 0 at three
standard deviations), t0 = 0 is taken (complete transfer, the SI default) and sigma0
fitted alone; the largest t0 of the grid that fits as well is said. A parameter the data
do not determine otherwise keeps its fitted value, with the uncertainty that says so and a
warning naming the combination that is determined.

**At the gas's limit** (docs/model.md section 8e). A patch keeps at most sigma_P(L_e) of
its episode's region, the grain at most sigma_P(R_s) A_s; where |sigma0| is above that, the
charge is the limit's, whatever sigma0. The structure is checked at the fit's own runs:
where a band stands at the limit there, the fit is made again on runs at every step. Then,
where a decade more of |sigma0| fits the data as well as the fit (its sum of squares within
COMPLETE_TRANSFER_CHI2 times their variance), the data stand at the limit and determine no
value of sigma0, only a bound: the smallest |sigma0| that fits as well, found by bisection,
is written with the status "lower bound" and the warning that says why (Matsuyama &
Yamamoto's charge relaxation: single impacts in air measure the limit). Data below the
limit are fitted as before.

Uncertainties: the covariance s^2 (J^T J)^-1 (a pseudo-inverse), in decades, given as the
standard deviation of each value (value x ln 10 x its decades) and the range value / 10^d
to value x 10^d; none (NaN) where the points are as many as the parameters and carry no
standard deviations.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from .observables import Runs, chunks, run_all, stream_of

# the charging parameters a fit may take, their units, and their bounds in decades
PARAMETERS = {"sigma0": "C/m2", "charging_time": "s", "eta": "1"}
DEFAULT_FIT = {"static": ("sigma0", "charging_time"),
               "sliding": ("sigma0", "charging_time", "eta")}
ETA_DECADES = (-14.0, 3.0)
SIGMA0_DECADES_BELOW = 8.0  # |sigma0| from the limit down by this many decades
# a direction of parameter space the data pin down to less than a decade: determined
UNDETERMINED_DECADES = 1.0
# the data's scatter taken as at least this (decades: 2 %), so that data the model fits
# exactly do not make an insensitive direction look determined
FLOOR_DECADES = 0.01
# t0 = 0 fits as well as the best t0 where its sum of squares is within this many times
# the data's variance of the best one's: a test of t0 > 0 at three standard deviations
# (chi-squared of one degree of freedom; 0.3 % of the data sets made with t0 = 0 claim a
# t0). Measured on 10 synthetic sets of 12 impacts made with t0 = 0 and 0.05 decades of
# noise: at 1 (one standard deviation) 2 of them found a t0 in their noise, at 4 one did
COMPLETE_TRANSFER_CHI2 = 9.0
GRID_PER_DECADE = 2  # the profile's t0, and an impact's runs
# the t0 each kind of point is run at, per decade: a chute's stream is many grains' charge
# and varies smoothly with t0 (and its runs cost ten times an impact's)
GRIDS = {"impact": GRID_PER_DECADE, "chute": 1}
# the interpolation in t0 is made exact at the optimum: at most REFINEMENTS more runs of the
# points, until the interpolant is within REFINED decades of them there (measured on a
# chute's stream at one run a decade: up to 0.035 decades off between the runs)
REFINEMENTS, REFINED = 3, 1e-3
JACOBIAN_STEP = 0.05  # decades, the forward differences of a fit on runs
# sigma0's lower bound (data at the gas's limit) is found to this many decades (0.5 %)
LOWER_BOUND_DECADES = 0.002
LOWER_BOUND_SPAN = 3.0  # decades below the fit where the bound is sought
# and not below 1e-5 C/m2 (log10): the gas's limit of a region up to a centimetre is 4.9e-5
# and more, so data at the limit are bounded above it; smaller sigma0 may leave the model's
# range of Sigma0 for large, stiff grains
LOWER_BOUND_FLOOR = -5.0
IMPACT_CHUNK, GRAIN_CHUNK = 25, 8  # runs per task (about 0.1 s each)


class FitError(ValueError):
    """A fit that cannot be made (one line: what is wrong with the points or the fit asked)."""


@dataclass
class Point:
    """A measured point as the model runs it: `runs` its parameters (one impact, or the
    chute's grains), `repeat` impacts on fresh spots, the grain's initial charge and surface
    (impacts), the horizon."""

    kind: str  # "impact" or "chute"
    label: str  # the file and row
    measured: float
    std: float
    runs: list = field(repr=False)
    horizon: float
    in_t_star: bool
    steps: int = 1
    repeat: int = 1
    initial_charge: float = 0.0
    surface: float = 0.0


@dataclass
class Problem:
    """What is fitted: the points, the base parameters (the pair's, the settings, the
    charge model's switch), the parameters to fit and the values of the others."""

    points: list
    base: dict
    charge_model: str
    fit: tuple
    fixed: dict  # name -> value of the charging parameters not fitted (None: the FMU's)
    sign: float
    sigma0_limit: float
    # the gas's limit in force, in words (for the warnings): section 8e's or 8b's
    gas_limit: str = "the air-breakdown limit (breakdown_density, docs/model.md section 8b)"

    @property
    def measured(self) -> np.ndarray:
        return np.array([p.measured for p in self.points])

    @property
    def weights(self) -> np.ndarray | None:
        """1 / the standard deviation in decades of each point; None where a point has none."""
        std = np.array([p.std for p in self.points])
        if not np.all(np.isfinite(std)):
            return None
        return np.abs(self.measured) * math.log(10) / std

    @property
    def structured(self) -> bool:
        """The static model's structure holds (the module's text)."""
        return self.charge_model == "static"


@dataclass
class Fit:
    """The fit's result: the parameters (name -> value, standard deviation, its decades d:
    the range value/10^d..value*10^d, status: "fitted", "not determined" or "fixed"), the
    model's value at each point, the
    residuals in decades, their RMS, the warnings, and the t0 profile (static model: t0,
    sigma0, the RMS at each t0 of the grid) where one was made."""

    values: dict
    stds: dict
    decades: dict
    status: dict
    model: np.ndarray
    residuals: np.ndarray
    rms_log10: float
    scatter: float
    warnings: list
    profile: list | None = None
    evaluations: int = 0
    runs: int = 0


class Evaluator:
    """The model's values at the points for sets of the charging parameters, on an executor
    (entered by the caller): one batch of runs for all the sets."""

    def __init__(self, problem: Problem, image, executor):
        self.problem, self.image, self.executor = problem, image, executor
        self.evaluations = 0
        self.runs = 0

    def rows(self, sets: list[dict], subsets: list | None = None) -> list[list]:
        """For each parameter set, for each point, the rows of its runs (None for a point
        not among the set's `subsets`: point indices, default all). The runs of every set
        and point that run alike (the same horizon and repeats) go into common batches, so
        that an instance of the FMU serves many of them."""
        groups = {}  # (horizon, in_t_star, steps, repeat) -> [(set, point, params)]
        for s, values in enumerate(sets):
            for i, point in enumerate(self.problem.points):
                if subsets is not None and i not in subsets[s]:
                    continue
                kind = (point.horizon, point.in_t_star, point.steps, point.repeat)
                groups.setdefault(kind, []).extend((s, i, dict(p, **values)) for p in point.runs)
        batches, where = [], []
        for (horizon, in_t_star, steps, repeat), runs in groups.items():
            size = IMPACT_CHUNK if in_t_star else GRAIN_CHUNK
            for chunk in chunks(runs, math.ceil(len(runs) / size)):
                batches.append(Runs(tuple(p for _, _, p in chunk), horizon,
                                    self.problem.charge_model, in_t_star=in_t_star, steps=steps,
                                    repeat=repeat))
                where.append([(s, i) for s, i, _ in chunk])
                self.runs += len(chunk) * repeat
        results = run_all(self.executor, self.image, batches)
        out = [[[] if subsets is None or i in subsets[s] else None
                for i in range(len(self.problem.points))] for s in range(len(sets))]
        for places, rows in zip(where, results):
            for (s, i), row in zip(places, rows):
                out[s][i].append(row)
        self.evaluations += len(sets)
        return out

    def values(self, sets: list[dict]) -> np.ndarray:
        """The model's value at each point (impacts: the charge gained, C; chutes: the
        stream's q/m, C/kg) for each set: an array (sets x points)."""
        return np.array([[value_of(point, rows) for point, rows in zip(self.problem.points, per)]
                         for per in self.rows(sets)])


def value_of(point: Point, rows: list) -> float:
    if point.kind == "impact":
        row = rows[0]
        return row["charge"] - row["charge_initial"]
    stream = stream_of(rows)
    if stream["n_exited"] == 0:
        raise FitError(f"{point.label}: no grain of the feed leaves the chute in the model "
                       f"(raise t_end, or check the chute)")
    return stream["q_per_m"]


def weighing(problem: Problem) -> list:
    """The warning where only some points give a standard deviation."""
    given = sum(math.isfinite(p.std) for p in problem.points)
    if 0 < given < len(problem.points):
        return [f"only {given} of {len(problem.points)} points give a standard deviation: "
                f"the fit weighs every point alike"]
    return []


def residuals(model: np.ndarray, problem: Problem) -> np.ndarray:
    """log10(model / measured) per point, weighted; a model of the wrong sign (or 0) is
    taken as 1e-30 of the measured value's sign (30 decades off)."""
    measured = problem.measured
    ratio = model / measured
    r = np.log10(np.where(ratio > 0, ratio, 1e-30))
    w = problem.weights
    return r if w is None else r * w


# ---- the static model's structure -----------------------------------------------------------

def structured_values(problem: Problem, sigma0: float, factors: np.ndarray) -> np.ndarray:
    """The static model's value at each point from the factors (impacts: F, the charge per
    unit sigma0 of one impact on an uncharged grain; chutes: G, the stream's q/m per unit
    sigma0), at this sigma0 (the module's text)."""
    out = np.empty(len(problem.points))
    for i, (point, f) in enumerate(zip(problem.points, factors)):
        if point.kind == "chute":
            out[i] = sigma0 * f
            continue
        q0, area = point.initial_charge, point.surface
        if point.repeat == 1:
            out[i] = (sigma0 - q0 / area) * f
        else:  # q_n = sigma0 A + (q0 - sigma0 A)(1 - F/A)^n
            qn = sigma0 * area + (q0 - sigma0 * area) * (1.0 - f / area) ** point.repeat
            out[i] = qn - q0
    return out


def sigma0_bounds(problem: Problem) -> tuple[float, float]:
    """The bounds of log10 |sigma0|: the limit, and where every impact's initial density is
    below it (a band charges towards sigma0 from the initial density)."""
    high = math.log10(problem.sigma0_limit)
    low = high - SIGMA0_DECADES_BELOW
    inits = [problem.sign * p.initial_charge / p.surface for p in problem.points
             if p.kind == "impact" and p.initial_charge]
    above = max([d for d in inits if d > 0], default=0.0)
    if above > 0:
        low = max(low, math.log10(above) + 1e-9)
        if low >= high:
            raise FitError(f"the initial charges reach a density of {above:.3g} C/m2 of the pair's "
                           f"sign, at or above the limit of |sigma0|, {problem.sigma0_limit:g} "
                           f"C/m2: the model would charge them no further")
    return low, high


def fit_sigma0(problem: Problem, factors: np.ndarray, start: float | None = None):
    """sigma0 alone at given factors: (x = log10 |sigma0|, the least-squares result)."""
    from scipy.optimize import least_squares  # scipy only when a fit is made

    low, high = sigma0_bounds(problem)

    def fun(x):
        return residuals(structured_values(problem, problem.sign * 10 ** x[0], factors), problem)

    if start is None:  # the closed form without initial charges, within the bounds
        guess = np.log10(np.abs(problem.measured) / np.abs(factors))
        start = float(np.median(guess))
    x0 = min(max(start, low + 1e-9), high - 1e-9)
    result = least_squares(fun, [x0], bounds=([low], [high]), x_scale=[1.0], method="trf")
    return float(result.x[0]), result


def t0_grid(low: float, high: float, per_decade: int) -> np.ndarray:
    """t0 from low to high (s), the ends included, about `per_decade` a decade: the range in
    whole steps of at most a decade, each cut in `per_decade`, so that a coarser grid's t0
    are all on a finer one."""
    steps = max(1, int(math.ceil(math.log10(high / low) - 1e-9)))
    return np.logspace(math.log10(low), math.log10(high), per_decade * steps + 1)


def t0_range(rows0: list) -> tuple[float, float]:
    """The t0 that act on these points (s): a hundredth of the shortest contact period (pi
    t*) to ten times the longest run (an impact's contact time, a grain's time to its
    exit)."""
    t_star = min(r["t_star"] for rows in rows0 for r in rows)
    longest = max(max(r["contact_time"], r["time_end"]) for rows in rows0 for r in rows)
    return 0.01 * math.pi * t_star, 10.0 * longest


def factors_of(problem: Problem, rows_per_set: list, sigma_ref: float) -> np.ndarray:
    """The factors (structured_values) of each set's rows, run at sigma0 = sigma_ref on
    uncharged grains with one impact."""
    return np.array([[value_of(point, rows) / sigma_ref for point, rows in
                      zip(problem.points, per)] for per in rows_per_set])


def structured_problem_runs(problem: Problem) -> Problem:
    """The problem whose runs give the factors: uncharged grains, one impact each."""
    points = []
    for p in problem.points:
        runs = [dict(r, initial_charge_density=0.0) for r in p.runs]
        points.append(Point(p.kind, p.label, p.measured, p.std, runs, p.horizon, p.in_t_star,
                            p.steps, 1, 0.0, p.surface))
    return Problem(points, problem.base, problem.charge_model, problem.fit, problem.fixed,
                   problem.sign, problem.sigma0_limit, problem.gas_limit)


def fit_structured(problem: Problem, evaluator: Evaluator) -> Fit:
    """The static model's fit (the module's text)."""
    # the factors come from runs on uncharged grains with one impact each
    run_on = Evaluator(structured_problem_runs(problem), evaluator.image, evaluator.executor)
    sigma_ref = problem.sign * min(1e-5, problem.sigma0_limit)
    fixed = {k: v for k, v in problem.fixed.items() if v is not None}
    warnings = weighing(problem)
    if "charging_time" not in problem.fit:
        fit = fit_at_fixed_t0(problem, run_on, fixed, sigma_ref, warnings)
    else:
        fit = fit_with_t0(problem, run_on, fixed, sigma_ref, warnings)
    fit.evaluations, fit.runs = run_on.evaluations, run_on.runs
    return fit


def factors_run(problem: Problem, run_on: Evaluator, fixed: dict, sigma_ref: float,
                t0: float) -> np.ndarray:
    """The factors of every point from its runs at this t0."""
    rows = run_on.rows([dict(fixed, sigma0=sigma_ref, charging_time=t0)])
    return factors_of(problem, rows, sigma_ref)[0]


def fit_at_fixed_t0(problem: Problem, run_on: Evaluator, fixed: dict, sigma_ref: float,
                    warnings: list) -> Fit:
    """sigma0 alone, at the t0 given (0, complete transfer, where none is)."""
    t0_fixed = fixed.get("charging_time")
    t0 = 0.0 if t0_fixed is None else t0_fixed
    factors = factors_run(problem, run_on, fixed, sigma_ref, t0)
    x, result = fit_sigma0(problem, factors)
    return finish(problem, {"sigma0": x}, result.jac, result.fun,
                  structured_values(problem, problem.sign * 10 ** x, factors), warnings,
                  {"charging_time": t0})


def fit_with_t0(problem: Problem, run_on: Evaluator, fixed: dict, sigma_ref: float,
                warnings: list) -> Fit:
    """sigma0 and t0 on the factors interpolated in t0, or sigma0 alone where complete
    transfer fits as well; with the t0 profile."""
    # t0 = 0 first: the contact periods and run times set the grid of t0
    rows0 = run_on.rows([dict(fixed, sigma0=sigma_ref, charging_time=0.0)])
    factors0 = factors_of(problem, rows0, sigma_ref)[0]
    grid, nodes = t0_grid_runs(problem, run_on, fixed, sigma_ref, *t0_range(rows0[0]))
    curves = FactorCurves(nodes)
    profile = t0_profile(problem, factors0, grid, curves)
    # sigma0 and t0 together on the interpolated factors, from the grid's best point
    log_grid = np.log10(grid)
    s_low, s_high = sigma0_bounds(problem)
    bounds = ([s_low, log_grid[0]], [s_high, log_grid[-1]])
    best = int(np.argmin(profile.sums))
    start = [min(max(math.log10(abs(profile.rows[best + 1][1])), s_low + 1e-9), s_high - 1e-9),
             log_grid[best]]
    joint = fit_sigma0_t0(problem, curves, bounds, start)
    ss = float(np.sum(joint.fun ** 2))
    scatter = data_scatter(joint.fun, problem, 2)
    floor = max(scatter, FLOOR_DECADES)
    if profile.ss0 <= ss + COMPLETE_TRANSFER_CHI2 * floor ** 2:
        fit = complete_transfer_fit(problem, profile, factors0, grid, floor, warnings)
    else:
        joint, exact_factors = refine_at_optimum(problem, run_on, fixed, sigma_ref, curves,
                                                 bounds, joint)
        exact = structured_values(problem, problem.sign * 10 ** joint.x[0], exact_factors)
        fit = finish(problem, {"sigma0": joint.x[0], "charging_time": joint.x[1]}, joint.jac,
                     residuals(exact, problem), exact, warnings, {},
                     at_bounds=_at_bounds(joint.x, *bounds, ("sigma0", "charging_time")))
    fit.profile = profile.rows
    return fit


def t0_grid_runs(problem: Problem, run_on: Evaluator, fixed: dict, sigma_ref: float,
                 t_low: float, t_high: float) -> tuple[np.ndarray, list]:
    """The profile's grid of t0, and per point the runs on its kind's grid ({log10 t0: log10
    F}), all in one batch."""
    grid = t0_grid(t_low, t_high, GRID_PER_DECADE)
    # each point on its kind's grid (a chute's grains are many and smooth the curve)
    kinds = [p.kind for p in problem.points]
    own = {kind: t0_grid(t_low, t_high, per) for kind, per in GRIDS.items()}
    sets, subsets = [], []
    for t in grid:
        chosen = [i for i, kind in enumerate(kinds) if np.isclose(own[kind], t, rtol=1e-9).any()]
        if chosen:
            sets.append(dict(fixed, sigma0=sigma_ref, charging_time=float(t)))
            subsets.append(chosen)
    ran = run_on.rows(sets, subsets)
    nodes = []
    for i, kind in enumerate(kinds):
        ts = [st["charging_time"] for st, rows in zip(sets, ran) if rows[i] is not None]
        fs = [value_of(problem.points[i], rows[i]) / sigma_ref
              for rows in ran if rows[i] is not None]
        if min(fs) <= 0:
            raise FitError(f"{problem.points[i].label}: its charge per unit sigma0 is not positive "
                           f"at some t0: the static model's structure does not hold here")
        nodes.append(dict(zip(np.log10(ts), np.log10(fs))))
    return grid, nodes


class FactorCurves:
    """Each point's factor against t0: a monotone cubic of log10 F in log10 t0 through its
    runs (`nodes`, per point {log10 t0: log10 F}), remade as runs are added."""

    def __init__(self, nodes: list):
        self.nodes = nodes
        self.interpolate()

    def interpolate(self) -> None:
        from scipy.interpolate import PchipInterpolator  # scipy only when a fit is made
        self.curves = [PchipInterpolator(sorted(n), [n[k] for k in sorted(n)]) for n in self.nodes]

    def add(self, log_t0: float, factors: np.ndarray) -> None:
        """The runs at log_t0 as nodes of the curves."""
        for n, f in zip(self.nodes, factors):
            n[float(log_t0)] = math.log10(f)
        self.interpolate()

    def __call__(self, log_t0: float) -> np.ndarray:
        return np.array([10 ** float(c(log_t0)) for c in self.curves])


@dataclass
class Profile:
    """sigma0 fitted at t0 = 0 (x0 = log10 |sigma0|, the least-squares result, its sum of
    squares) and at each t0 of the grid (their sums of squares); `rows`: (t0, sigma0, RMS),
    t0 = 0 first."""

    x0: float
    result0: object
    ss0: float
    sums: list
    rows: list


def t0_profile(problem: Problem, factors0: np.ndarray, grid: np.ndarray,
               curves: FactorCurves) -> Profile:
    """sigma0 fitted alone at t0 = 0 and at each t0 of the grid."""
    factors = np.array([curves(math.log10(t)) for t in grid])
    x0, result0 = fit_sigma0(problem, factors0)
    ss0 = float(np.sum(result0.fun ** 2))
    rows = [(0.0, problem.sign * 10 ** x0, rms(result0.fun, problem))]
    sums = []
    for t, f in zip(grid, factors):
        x, r = fit_sigma0(problem, f, start=x0)
        sums.append(float(np.sum(r.fun ** 2)))
        rows.append((float(t), problem.sign * 10 ** x, rms(r.fun, problem)))
    return Profile(x0, result0, ss0, sums, rows)


def fit_sigma0_t0(problem: Problem, curves: FactorCurves, bounds: tuple, start):
    """sigma0 and t0 together on the interpolated factors: the least-squares result (x =
    log10 |sigma0|, log10 t0)."""
    from scipy.optimize import least_squares  # scipy only when a fit is made

    def fun(x):
        return residuals(structured_values(problem, problem.sign * 10 ** x[0], curves(x[1])),
                         problem)

    return least_squares(fun, start, bounds=bounds, x_scale=[1.0, 1.0], method="trf")


def complete_transfer_fit(problem: Problem, profile: Profile, factors0: np.ndarray,
                          grid: np.ndarray, floor: float, warnings: list) -> Fit:
    """t0 = 0 and sigma0 alone, with the warning that names the largest t0 of the grid up
    to which every t0 fits as well as t0 = 0."""
    largest = None
    for t, total in zip(grid, profile.sums):
        if total > profile.ss0 + COMPLETE_TRANSFER_CHI2 * floor ** 2:
            break
        largest = float(t)
    bound = f"; t0 up to {largest:.2g} s fits them as well" if largest else ""
    warnings.append(f"charging_time is not determined: the data are those of complete "
                    f"transfer (t0 = 0 fits them as well as any t0{bound}); written as 0, "
                    f"instantaneous transfer")
    x0 = profile.x0
    return finish(problem, {"sigma0": x0}, profile.result0.jac, profile.result0.fun,
                  structured_values(problem, problem.sign * 10 ** x0, factors0), warnings,
                  {"charging_time": 0.0}, undetermined={"charging_time": True})


def refine_at_optimum(problem: Problem, run_on: Evaluator, fixed: dict, sigma_ref: float,
                      curves: FactorCurves, bounds: tuple, joint) -> tuple:
    """The joint fit made exact at its optimum: (the fit, the factors run at its t0)."""
    # the points run at the fitted t0; where the interpolation was off there (more than
    # REFINED decades), the runs become nodes of the curves and the fit is made again,
    # until it holds at its optimum
    for _ in range(REFINEMENTS):
        exact_factors = factors_run(problem, run_on, fixed, sigma_ref, 10 ** joint.x[1])
        off = np.max(np.abs(np.log10(exact_factors) - np.log10(curves(joint.x[1]))))
        if off <= REFINED:
            break
        curves.add(joint.x[1], exact_factors)
        moved = fit_sigma0_t0(problem, curves, bounds, joint.x)
        if np.allclose(moved.x, joint.x, atol=REFINED):
            joint = moved
            break
        joint = moved
    else:  # the last fit's own runs
        exact_factors = factors_run(problem, run_on, fixed, sigma_ref, 10 ** joint.x[1])
    return joint, exact_factors


def _at_bounds(x, low, high, names) -> dict:
    return {n: ("low" if v <= lo + 1e-6 else "high" if v >= hi - 1e-6 else None)
            for n, v, lo, hi in zip(names, x, low, high)}


# ---- any charge model: runs at every step ----------------------------------------------------

def fit_runs(problem: Problem, evaluator: Evaluator) -> Fit:
    """The fit on runs at every step (a charge model without the static one's structure)."""
    fixed = {k: v for k, v in problem.fixed.items() if v is not None}
    names = list(problem.fit)
    warnings = weighing(problem)
    bounds, start = bounds_and_start(problem, evaluator, fixed, names)
    on_runs = RunsFit(problem, evaluator, fixed, bounds, start)
    result, jacobian = on_runs.solve(names, {})
    scatter = max(data_scatter(result.fun, problem, len(names)), FLOOR_DECADES)
    fitted = dict(zip(names, result.x))
    model = on_runs.values([result.x], names, {})[0]
    undetermined = {}
    complete = ("charging_time" in names
                and complete_transfer_on_runs(problem, on_runs, names, result, scatter))
    if complete:
        warnings.append("charging_time is not determined: the data are those of complete "
                        "transfer (t0 = 0 fits them as well as any t0); written as 0, "
                        "instantaneous transfer")
        names, result, jacobian = complete
        fitted = dict(zip(names, result.x))
        model = on_runs.values([result.x], names, {"charging_time": 0.0})[0]
        undetermined["charging_time"] = True
        fixed = dict(fixed, charging_time=0.0)
    warnings += capped_warnings(problem, evaluator, fixed, fitted)
    fit = finish(problem, fitted, jacobian, result.fun, model, warnings,
                 {k: v for k, v in fixed.items() if k in PARAMETERS and k not in fitted},
                 undetermined=undetermined,
                 at_bounds=_at_bounds(result.x, [bounds[n][0] for n in names],
                                      [bounds[n][1] for n in names], names))
    fit.evaluations, fit.runs = evaluator.evaluations, evaluator.runs
    return fit


def bounds_and_start(problem: Problem, evaluator: Evaluator, fixed: dict,
                     names: list) -> tuple[dict, dict]:
    """Each parameter's bounds and starting point in decades; t0's range from first runs at
    the fixed values (and t0 = 0 where t0 is fitted)."""
    s_low, s_high = sigma0_bounds(problem)
    first = dict(fixed, sigma0=problem.sign * min(1e-5, problem.sigma0_limit))
    if "charging_time" in names:
        first["charging_time"] = 0.0
    rows0 = evaluator.rows([first])
    t_low, t_high = t0_range(rows0[0])
    bounds = {"sigma0": (s_low, s_high), "charging_time": (math.log10(t_low), math.log10(t_high)),
              "eta": ETA_DECADES}
    start = {"sigma0": math.log10(abs(first["sigma0"])), "charging_time": math.log10(t_low),
             "eta": math.log10(fixed.get("eta", 0.1))}
    for name, value in fixed.items():
        if name in bounds and name != "sigma0" and value and name in names:
            start[name] = math.log10(value)
    return bounds, start


class RunsFit:
    """Least squares on runs: the model's values at sets of the free parameters (in decades,
    the others fixed), each set run once, and the Jacobian's forward differences in one
    batch per step."""

    def __init__(self, problem: Problem, evaluator: Evaluator, fixed: dict, bounds: dict,
                 start: dict):
        self.problem, self.evaluator, self.fixed = problem, evaluator, fixed
        self.bounds, self.start = bounds, start
        self.cache = {}

    def sets_of(self, xs, free) -> list[dict]:
        return [dict(self.fixed, **{n: (self.problem.sign if n == "sigma0" else 1.0) * 10 ** v
                                    for n, v in zip(free, x)}) for x in xs]

    def values(self, xs, free, extra: dict) -> list:
        """The model's values at each x (the `free` parameters' decades, `extra` set)."""
        keys = [tuple(np.round(x, 12)) + tuple(sorted(extra.items())) for x in xs]
        todo = [(k, x) for k, x in zip(keys, xs) if k not in self.cache]
        if todo:
            sets = [dict(s, **extra) for s in self.sets_of([x for _, x in todo], free)]
            for (k, _), v in zip(todo, self.evaluator.values(sets)):
                self.cache[k] = v
        return [self.cache[k] for k in keys]

    def solve(self, free: list, extra: dict) -> tuple:
        """The fit of the `free` parameters (`extra` set): (the least-squares result, the
        Jacobian at its optimum)."""
        from scipy.optimize import least_squares  # scipy only when a fit is made

        problem = self.problem
        lo = [self.bounds[n][0] for n in free]
        hi = [self.bounds[n][1] for n in free]
        x0 = [min(max(self.start[n], l + 1e-9), h - 1e-9) for n, l, h in zip(free, lo, hi)]

        def fun(x):
            return residuals(self.values([np.asarray(x)], free, extra)[0], problem)

        def jac(x):
            x = np.asarray(x)
            steps = []
            for j in range(len(x)):
                h = JACOBIAN_STEP if x[j] + JACOBIAN_STEP <= hi[j] else -JACOBIAN_STEP
                steps.append((j, h, x + np.eye(len(x))[j] * h))
            base, *moved = self.values([x] + [m for _, _, m in steps], free, extra)
            r0 = residuals(base, problem)
            return np.column_stack([(residuals(v, problem) - r0) / h
                                    for (j, h, _), v in zip(steps, moved)])

        result = least_squares(fun, x0, jac=jac, bounds=(lo, hi), x_scale=1.0, method="trf",
                               max_nfev=50)
        return result, jac(result.x)


def complete_transfer_on_runs(problem: Problem, on_runs: RunsFit, names: list, result,
                              scatter: float):
    """The fit with t0 = 0 where it fits as well as the best t0: (the names fitted, the
    result, its Jacobian); else None."""
    rest = [n for n in names if n != "charging_time"]
    result0, jac0 = on_runs.solve(rest, {"charging_time": 0.0})
    if np.sum(result0.fun ** 2) <= np.sum(result.fun ** 2) + COMPLETE_TRANSFER_CHI2 * scatter ** 2:
        return rest, result0, jac0
    return None


def capped_warnings(problem: Problem, evaluator: Evaluator, fixed: dict, fitted: dict) -> list:
    """The warning where the model's charge stands at the breakdown limit at some points:
    there no parameter acts on it."""
    final = dict(fixed, **{n: (problem.sign if n == "sigma0" else 1.0) * 10 ** v
                           for n, v in fitted.items()})
    capped = [p.label for p, rows in zip(problem.points, evaluator.rows([final])[0])
              if any(r["capped"] > 0 for r in rows)]
    if not capped:
        return []
    return [f"at {len(capped)} of {len(problem.points)} points (e.g. {capped[0]}) "
            f"the model's charge stands at {problem.gas_limit}: there no charging "
            f"parameter acts on it"]


# ---- what the data determine ----------------------------------------------------------------

def rms(weighted: np.ndarray, problem: Problem) -> float:
    """The RMS of the residuals in decades (unweighted)."""
    w = problem.weights
    r = weighted if w is None else weighted / w
    return float(np.sqrt(np.mean(r ** 2)))


def data_scatter(weighted: np.ndarray, problem: Problem, n_parameters: int) -> float:
    """The scatter of the data about the model in the residuals' units: 1 with measured
    standard deviations (more where the fit is worse than they say), else the residuals'
    RMS over the degrees of freedom (NaN without any)."""
    dof = len(weighted) - n_parameters
    if problem.weights is not None:
        return max(1.0, math.sqrt(np.sum(weighted ** 2) / dof)) if dof > 0 else 1.0
    return math.sqrt(np.sum(weighted ** 2) / dof) if dof > 0 else math.nan


def combination(names, v) -> str:
    """The combination of parameters a null direction v (in decades) leaves determined,
    in words."""
    big = [(n, c) for n, c in zip(names, v) if abs(c) > 0.1]
    if len(big) == 1:
        return big[0][0]
    (a, ca), (b, cb) = big[0], big[1]
    power = -ca / cb  # a * b^power is constant along v
    if abs(power + 1) < 0.15:
        text = f"{a}/{b}"
    elif abs(power - 1) < 0.15:
        text = f"{a}·{b}"
    else:
        text = f"{a}·{b}^{power:.2g}"
    return text + (" (and " + ", ".join(n for n, _ in big[2:]) + ")" if len(big) > 2 else "")


def finish(problem: Problem, fitted: dict, jacobian, weighted, model, warnings: list,
           fixed_values: dict, *, undetermined: dict | None = None,
           at_bounds: dict | None = None) -> Fit:
    """The Fit of a solution: values, uncertainties, what the data do not determine."""
    names = list(fitted)
    x = np.array([fitted[n] for n in names])
    J = np.atleast_2d(np.asarray(jacobian, dtype=float))
    scatter = data_scatter(weighted, problem, len(names))
    floor = max(scatter, FLOOR_DECADES) if math.isfinite(scatter) else FLOOR_DECADES
    _, S, Vt = np.linalg.svd(J, full_matrices=False)
    S_full = np.zeros(len(names))
    S_full[:len(S)] = S
    if len(S) < len(names):  # fewer residuals than parameters cannot happen (checked before)
        Vt = np.vstack([Vt, np.zeros((len(names) - len(S), len(names)))])
    cov = scatter ** 2 * np.linalg.pinv(J.T @ J) if math.isfinite(scatter) else \
        np.full((len(names), len(names)), np.nan)
    decades = {n: float(math.sqrt(max(cov[i, i], 0.0))) if math.isfinite(cov[i, i]) else math.nan
               for i, n in enumerate(names)}
    status = {n: "fitted" for n in names}
    for k in range(len(names)):
        spread = floor / S_full[k] if S_full[k] > 0 else math.inf
        if spread > UNDETERMINED_DECADES:
            v = Vt[k]
            what = combination(names, v)
            alone = [n for n, c in zip(names, v) if abs(c) > 0.1]
            for n in alone:
                status[n] = "not determined"
            if len(alone) == 1:
                warnings.append(f"{alone[0]} is not determined by these data (a decade of it "
                                f"moves the fit by {S_full[k]:.2g} of their scatter); its "
                                f"value is the fit's end point, not a measurement")
            else:
                warnings.append(f"{', '.join(alone)} are not determined apart: only {what} is "
                                f"(with t0 far above the contact time, the charge follows "
                                f"sigma0/t0); the values written reproduce the data but are one "
                                f"pair of many")
            decades.update({n: max(decades[n], spread) if math.isfinite(decades[n]) else
                            decades[n] for n in alone})
    for n, side in (at_bounds or {}).items():
        if side and n in names:
            what = {"sigma0": "the bound on |sigma0|" if side == "high" else
                    f"{SIGMA0_DECADES_BELOW:g} decades below it",
                    "charging_time": "the range where it acts on these data",
                    "eta": f"1e{ETA_DECADES[1 if side == 'high' else 0]:g}"}[n]
            warnings.append(f"{n} stands at the {side} end of its range ({what})")
    values, stds, ranges = {}, {}, {}
    for n in names:
        value = (problem.sign if n == "sigma0" else 1.0) * 10 ** fitted[n]
        values[n] = value
        d = decades[n]
        stds[n] = abs(value) * math.log(10) * d if math.isfinite(d) else math.nan
        ranges[n] = d
    for n, v in fixed_values.items():
        values[n], stds[n], ranges[n] = v, math.nan, math.nan
        status[n] = "not determined" if (undetermined or {}).get(n) else "fixed"
    r = np.asarray(weighted)
    return Fit(values, stds, ranges, status, np.asarray(model), r, rms(r, problem), scatter,
               warnings)


# ---- data at the gas's limit: sigma0 a lower bound (docs/model.md section 8e) ----------------

def fit_pair(problem: Problem, evaluator: Evaluator) -> Fit:
    """The fit (the module's text): the static model's on its structure, else on runs; then
    the structure checked at the optimum's own runs (no band at the gas's limit), the fit
    made on runs where it does not hold, and sigma0 turned into a lower bound where the data
    stand at the limit."""
    fit = (fit_structured if problem.structured else fit_runs)(problem, evaluator)
    if problem.structured and capped_at(problem, evaluator, fit.values):
        # the structure (charge linear in sigma0) does not hold where the gas caps a band:
        # the fit on runs (its counts are the evaluator's, this check's included)
        first = (fit.evaluations, fit.runs)
        fit = fit_runs(problem, evaluator)
        fit.warnings.insert(0, f"the model's charge stands at {problem.gas_limit} at some "
                               f"points: fitted on runs at every step, not on the static "
                               f"model's structure")
        fit.evaluations += first[0]
        fit.runs += first[1]
    elif problem.structured:
        fit.evaluations += 1
        fit.runs += sum(len(p.runs) * p.repeat for p in problem.points)
    return at_gas_limit(problem, evaluator, fit)


def parameter_set(problem: Problem, values: dict) -> dict:
    """The charging parameters of a run: the fixed ones, then the fit's values."""
    return dict({k: v for k, v in problem.fixed.items() if v is not None}, **values)


def capped_at(problem: Problem, evaluator: Evaluator, values: dict) -> bool:
    """Some run of some point has a band at the gas's limit at these values."""
    rows = evaluator.rows([parameter_set(problem, values)])[0]
    return any(r["capped"] > 0 for point_rows in rows for r in point_rows)


def sum_of_squares(problem: Problem, evaluator: Evaluator, values: dict, log_sigma0: float):
    """The weighted sum of squares and the model's values with |sigma0| = 10^log_sigma0."""
    model = evaluator.values([parameter_set(problem, dict(
        values, sigma0=problem.sign * 10 ** log_sigma0))])[0]
    r = residuals(model, problem)
    return float(np.sum(r ** 2)), model, r


def at_gas_limit(problem: Problem, evaluator: Evaluator, fit: Fit) -> Fit:
    """The fit with sigma0 a lower bound where a decade more of |sigma0| (up to its bound)
    fits the data as well as the fit: the charge stands at the gas's limit and only the
    limit is measured. The bound is the smallest |sigma0| that fits as well (sum of squares
    within COMPLETE_TRANSFER_CHI2 times the data's variance of the best, as t0's test),
    found by bisection in decades to LOWER_BOUND_DECADES; the fit unchanged elsewhere."""
    counts = (evaluator.evaluations, evaluator.runs)
    bounded = lower_bound(problem, evaluator, fit)
    fit.evaluations += evaluator.evaluations - counts[0]
    fit.runs += evaluator.runs - counts[1]
    return bounded


def lower_bound(problem: Problem, evaluator: Evaluator, fit: Fit) -> Fit:
    """at_gas_limit's work (the runs it makes counted by the caller)."""
    x = math.log10(abs(fit.values["sigma0"]))
    low, high = sigma0_bounds(problem)
    up = min(x + 1.0, high)
    if up <= x + 1e-9:
        return fit  # at its bound already: finish's warning says so
    values = {k: v for k, v in fit.values.items()}
    ss_fit, model_fit, r_fit = sum_of_squares(problem, evaluator, values, x)
    floor = max(fit.scatter, FLOOR_DECADES) if math.isfinite(fit.scatter) else FLOOR_DECADES
    threshold = ss_fit + COMPLETE_TRANSFER_CHI2 * floor ** 2
    if sum_of_squares(problem, evaluator, values, up)[0] > threshold or not capped_at(
            problem, evaluator, dict(values, sigma0=problem.sign * 10 ** up)):
        return fit  # sigma0 acts on the data, or they do not depend on it for another reason
    # the smallest |sigma0| within the threshold: between a point outside it and the fit;
    # data that fit as well LOWER_BOUND_SPAN decades below bound nothing (the sliding
    # model's charge at the limit, raised by the work whatever sigma0: not determined)
    below = max(low, x - LOWER_BOUND_SPAN, LOWER_BOUND_FLOOR)
    if below >= x or sum_of_squares(problem, evaluator, values, below)[0] <= threshold:
        return fit
    inside, model, r = x, model_fit, r_fit
    while inside - below > LOWER_BOUND_DECADES:
        middle = 0.5 * (inside + below)
        ss, m, rm = sum_of_squares(problem, evaluator, values, middle)
        if ss <= threshold:
            inside, model, r = middle, m, rm
        else:
            below = middle
    bound = problem.sign * 10 ** inside
    fit.values["sigma0"] = bound
    fit.stds["sigma0"], fit.decades["sigma0"] = math.nan, math.nan
    fit.status["sigma0"] = "lower bound"
    fit.model, fit.residuals, fit.rms_log10 = np.asarray(model), r, rms(r, problem)
    fit.warnings = [w for w in fit.warnings if not w.startswith("sigma0 ")]
    fit.warnings.insert(0, f"sigma0 is a lower bound, not a value: the data stand at "
                           f"{problem.gas_limit}, where the charge no longer follows sigma0; "
                           f"every |sigma0| >= {abs(bound):.3g} C/m2 fits them as well (a "
                           f"decade more changes the fit by less than their scatter). They "
                           f"measure what the gas lets the contact keep, not the contact's own "
                           f"density; written as the bound")
    return fit

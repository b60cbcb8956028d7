"""A calibration into an output folder (batch/job.py's flow): a pair's charging parameters
fitted to measured impacts and chute runs (data.py, fit.py), and what it writes:

    <out>/fit.csv           a row per charging parameter: value, standard deviation, its
                            decades d and the range value/10^d to value*10^d, status
                            (fitted, not determined, fixed, or lower bound: |sigma0| at
                            least |value|, where the data stand at the gas's limit), unit
    <out>/points.csv        a row per measured point: its file and row, what was measured
                            (the file's columns), the model's value, log10(model/measured)
    <out>/profile.csv       (static model, t0 fitted) sigma0 fitted at each t0 of the grid
                            and the RMS error there: how far t0 is told apart
    <out>/materials.toml    the materials file of the pair (tribo.materials: [sigma0], the
                            other fitted or fixed charging parameters in [charging], where
                            the numbers came from in [calibration]); `--materials FILE` /
                            `materials=` of every command and function take it
    <out>/calibration.png   the data against the model (and the t0 profile)
    <out>/calibration.json  the set-up, the fit, the warnings, the runs made and the time

Every value is checked before a run is made (the data's files, the settings, the FMU's
ranges): a mistake is one line and nothing is written.
"""

import datetime
import json
import math
import os
import time
from dataclasses import dataclass, field
from importlib import metadata as package_metadata

import numpy as np
import pandas as pd

from ..batch.job import Job, Report
from ..fmu import FmuImage
from ..fmu.charge_models import charge_models, switches
from ..fmu.locate import find_fmu
from ..fmu.names import format_number, start_value
from ..fmu.parameters import check_values
from ..impact.defaults import DEFAULT_LIMIT
from ..materials import CHARGING_KEYS, table_of
from ..populations.distributions import parse
from ..populations.feed import Feed, draw, particle_parameters
from ..populations.feed_variables import DEFAULT_CHUTE, FEED_VARIABLES
from .bounds import check_charges
from .data import DataError, combined_sign, read
from .fit import DEFAULT_FIT, PARAMETERS, Evaluator, FitError, Point, Problem, fit_pair
from .observables import impact_parameters, model_switches, spheroid_surface

FIT, POINTS, PROFILE, MATERIALS, FIGURE, METADATA = (
    "fit.csv", "points.csv", "profile.csv", "materials.toml", "calibration.png",
    "calibration.json")
# what the data and the observables set: not settings of a calibration
WHAT = {"impacts": ("impact", "impacts"), "chutes": ("chute run", "chute runs")}
SET_BY_DATA = ("size", "epsilon", "phi0_deg", "omega0", "drop_height", "drop_speed",
               "drop_angle_deg", "tilt_deg", "chute_length", "run_end", "x0",
               "initial_charge_density", "grain_geometry", "sigma0")


@dataclass(kw_only=True)
class CalibrationReport(Report):
    """The points' rows (`results`, points.csv) and the fit: `fit` (fit.csv), `rms_log10`
    (the RMS of log10(model/measured) over the points), `warnings` (what the data do not
    determine, parameters at a bound), `profile` (static model, t0 fitted: the RMS against
    t0), `materials_file` (the written materials file) and the time it took (`wall_s`)."""

    fit: pd.DataFrame | None = None
    rms_log10: float = math.nan
    warnings: list = field(default_factory=list)
    profile: pd.DataFrame | None = None
    materials_file: str | None = None
    wall_s: float = math.nan
    cpu_s: float = math.nan  # this process's (the local cluster's threads included)
    runs: int = 0


class CalibrationJob(Job):
    """A calibration of `particle` on `wall` against impacts and/or chute runs (CSV paths or
    DataFrames, data.py) with `charge_model`, fitting `fit` (default: the model's charging
    parameters, fit.DEFAULT_FIT); `settings`: other SI parameters; `materials`: the table
    the pair's constants come from (and that the written file adds to)."""

    kind, noun, results_file = "calibration", "point", POINTS

    def __init__(self, particle: str, wall: str, impacts=None, chutes=None, *,
                 charge_model: str = "static", fit=None, settings: dict | None = None,
                 materials=None, limit: float = DEFAULT_LIMIT, fmu=None, figure: bool = True):
        self.particle, self.wall = particle, wall
        self.impacts, self.chutes = impacts, chutes
        self.charge_model, self.fit_names = charge_model, fit
        self.settings = dict(settings or {})
        self.materials, self.limit, self.fmu, self.figure = materials, limit, fmu, figure
        self.keys = []

    def prepare(self) -> None:
        self.table = table_of(self.materials)
        self.particle = self.table.material(self.particle, "particle").key
        self.wall = self.table.material(self.wall, "wall").key
        if self.impacts is None and self.chutes is None:
            raise DataError("no data: give impacts (a CSV of single impacts) and/or chutes "
                            "(a CSV of chute runs)")
        self.data = [read(kind, d) for kind, d in (("impacts", self.impacts),
                                                   ("chutes", self.chutes)) if d is not None]
        sign = combined_sign(self.data)
        self.image = FmuImage.load(find_fmu(self.fmu, "si"))
        md = self.image.model_description()
        models = charge_models(md)
        model_switches(self.charge_model, models)
        names = tuple(self.fit_names) if self.fit_names is not None else \
            DEFAULT_FIT.get(self.charge_model, ("sigma0", "charging_time"))
        self.fit_names = check_fit(names, self.charge_model)
        both = [n for n in self.fit_names if n in self.settings and n != "sigma0"]
        if both:
            raise FitError(f"{both[0]} is fitted and set: fit it, or hold it at the value set "
                           f"(fit without it: --fit {','.join(n for n in self.fit_names if n != both[0])})")
        bad = [k for k in self.settings if k in SET_BY_DATA or k in switches(models)]
        if bad:
            raise FitError(f"{bad[0]} is set by the data or by the calibration, not a setting "
                           f"(the settings are the other SI parameters: mu, nu, ...)")
        if not (isinstance(self.limit, (int, float)) and math.isfinite(self.limit) and self.limit > 0):
            raise FitError(f"limit = {self.limit!r}: an impact's time limit in t*, a positive number")
        charging = self.table.pair_charging(self.particle, self.wall)
        fixed = {n: self.settings.pop(n, charging.get(n)) for n in CHARGING_KEYS
                 if n not in self.fit_names}
        fixed = {n: v for n, v in fixed.items() if n in PARAMETERS or v is not None}
        base = dict(self.table.pair_values(self.particle, self.wall, sigma0=False),
                    **model_switches(self.charge_model, models), **self.settings)
        for n in self.fit_names:
            base.pop(n, None)
        limit, gas_limit = sigma0_limit(self.table, self.settings, md)
        placeholder = dict(sigma0=sign * min(1e-5, limit), **{n: v for n, v in fixed.items()
                                                              if v is not None})
        points = []
        for d in self.data:
            points += (impact_points if d.kind == "impacts" else chute_points)(
                d, base, self.particle, self.wall, self.limit)
        if len(points) < len(self.fit_names):
            raise FitError(f"{len(points)} point(s) for {len(self.fit_names)} parameters "
                           f"({', '.join(self.fit_names)}): give more points, or fit fewer "
                           f"(fit=('sigma0',), --fit sigma0)")
        check_charges(points)
        values = {}
        for p in points:
            for run in p.runs:
                for k, v in dict(run, **placeholder).items():
                    values.setdefault(k, {})[v] = None
        check_values(self.image, {k: list(v) for k, v in values.items()})
        self.problem = Problem(points, base, self.charge_model, self.fit_names, fixed, sign, limit,
                               gas_limit)
        self.sha256 = self.image.sha256
        self.keys = [p.label for p in points]

    def setup(self) -> dict:
        return {"particle": self.particle, "wall": self.wall, "charge_model": self.charge_model,
                "fit": list(self.fit_names), "settings": self.settings,
                "fixed": {k: v for k, v in self.problem.fixed.items()},
                "materials": None if self.table.sha256 is None else
                {"file": self.table.source, "sha256": self.table.sha256},
                "data": [{"kind": d.kind, "source": d.source, "sha256": d.sha256,
                          "rows": len(d.frame)} for d in self.data],
                "time_limit_t_star": self.limit}

    def describe(self, out: str, executor) -> str:
        counts = ", ".join(f"{len(d.frame)} {WHAT[d.kind][len(d.frame) != 1]}" for d in self.data)
        return (f"calibration: {self.particle} on {self.wall}, {counts}; fitting "
                f"{', '.join(self.fit_names)} ({self.charge_model} model) into {out}")

    def run(self, out: str, executor, *, progress: bool, max_runs: int | None) -> CalibrationReport:
        started, cpu = time.perf_counter(), time.process_time()
        evaluator = Evaluator(self.problem, self.image, executor)
        fit = fit_pair(self.problem, evaluator)
        # this process's CPU time: the local cluster's threads included, not worker processes
        # or another machine's
        wall_s, cpu_s = time.perf_counter() - started, time.process_time() - cpu
        os.makedirs(out, exist_ok=True)
        points = points_table(self.problem, self.data, fit)
        points.to_csv(os.path.join(out, POINTS), index=False, float_format="%.10g")
        table = fit_table(fit)
        table.to_csv(os.path.join(out, FIT), index=False, float_format="%.10g")
        profile = None if fit.profile is None else pd.DataFrame(
            fit.profile, columns=["charging_time", "sigma0", "rms_log10"])
        if profile is not None:
            profile.to_csv(os.path.join(out, PROFILE), index=False, float_format="%.10g")
        materials_path = os.path.join(out, MATERIALS)
        with open(materials_path, "w", encoding="utf-8") as f:
            f.write(materials_text(self, fit))
        files = [os.path.join(out, n) for n in (POINTS, FIT, MATERIALS)] + \
            ([os.path.join(out, PROFILE)] if profile is not None else [])
        if self.figure:
            # matplotlib only when a figure is drawn: `import tribo` stays without it
            from .plot import write_calibration_figure
            files.append(write_calibration_figure(points, profile, fit, self.particle,
                                                  self.wall, self.charge_model,
                                                  os.path.join(out, FIGURE)))
        with open(os.path.join(out, METADATA), "w") as f:
            json.dump({**self.setup(), "fit": table.to_dict(orient="records"),
                       "rms_log10": fit.rms_log10, "warnings": fit.warnings,
                       "evaluations": fit.evaluations, "runs": fit.runs, "wall_s": wall_s,
                       "cpu_s_this_process": cpu_s,
                       "fmu": self.image.name, "fmu_sha256": self.image.sha256,
                       "package_version": _version()}, f, indent=2, default=_plain)
        files.append(os.path.join(out, METADATA))
        return CalibrationReport(keys=self.keys, results=points, executed=len(points),
                                 files=files, fit=table, rms_log10=fit.rms_log10,
                                 warnings=list(fit.warnings), profile=profile,
                                 materials_file=materials_path, wall_s=wall_s, cpu_s=cpu_s,
                                 runs=fit.runs)


def sigma0_limit(table, settings: dict, md) -> tuple[float, str]:
    """The bound on |sigma0| and the gas's limit in force, in words. With breakdown_model
    paschen (docs/model.md section 8e) |sigma0| reaches the table's bound (the contact's own
    density; the gas caps what a patch keeps, and data at that cap give a lower bound);
    with fixed, the cap breakdown_density too (section 8b: no sigma0 above it charges more)."""
    model = settings.get("breakdown_model", start_value(md, "breakdown_model"))
    if model is not None and int(model) == 1:
        return table.sigma0_limit(), ("the gas's relaxation limit (breakdown_model = paschen, "
                                      "docs/model.md section 8e)")
    breakdown = float(settings.get("breakdown_density", start_value(md, "breakdown_density")))
    limit = min(table.sigma0_limit(), breakdown) if breakdown > 0 else table.sigma0_limit()
    return limit, "the air-breakdown limit (breakdown_density, docs/model.md section 8b)"


def check_fit(names, charge_model: str) -> tuple:
    """The parameters to fit, checked: sigma0 always, the others the charge model's."""
    names = tuple(dict.fromkeys(str(n).strip() for n in names))
    allowed = DEFAULT_FIT.get(charge_model, ("sigma0", "charging_time"))
    unknown = [n for n in names if n not in allowed]
    if unknown:
        raise FitError(f"fit {unknown[0]!r}: the {charge_model} model's charging parameters "
                       f"are {', '.join(allowed)}" + (" (eta acts on the sliding model only)"
                                                      if unknown[0] == "eta" else ""))
    if "sigma0" not in names:
        raise FitError(f"fit {', '.join(names) or 'nothing'}: a calibration fits sigma0 "
                       f"(and whichever of {', '.join(allowed[1:])} the data determine)")
    return names


def impact_points(d, base: dict, particle: str, wall: str, limit: float) -> list[Point]:
    points = []
    for i, row in d.frame.iterrows():
        params = impact_parameters(base, speed=row["speed"], angle_deg=row["angle_deg"],
                                   size=row["size"], epsilon=row["epsilon"],
                                   phi0_deg=row["phi0_deg"], initial_charge=row["initial_charge"])
        params.setdefault("initial_charge_density", 0.0)
        points.append(Point("impact", f"{d.source} row {i + 2}", float(row["charge"]),
                            float(row["charge_std"]), [params], float(limit), True, 1,
                            int(row["impacts"]), float(row["initial_charge"]),
                            spheroid_surface(row["size"], row["epsilon"])))
    return points


def chute_points(d, base: dict, particle: str, wall: str, limit: float) -> list[Point]:
    points = []
    settings = {k: v for k, v in base.items()}
    for i, row in d.frame.iterrows():
        distributions = {n: parse(n, row[n]) for n in FEED_VARIABLES
                         if n in d.frame.columns and str(row[n]).strip()}
        feed = Feed(particle, wall, distributions, dict(DEFAULT_CHUTE, chute_length=row["chute_length"],
                                                        tilt_deg=row["tilt_deg"]),
                    dict(settings, sigma0=1e-5))  # sigma0: each fit's, set per run
        drawn = draw(feed, int(row["grains"]), int(row["seed"]))
        runs = [{k: v for k, v in p.items() if k != "sigma0"}
                for p in particle_parameters(feed, drawn, {"cylinder_length": 1e-3})]
        # in one communication step: the FMU's results do not depend on the communication
        # points (docs/model.md section 9; tests/python/test_calibration.py), and the 100
        # steps of a population's grid cost a quarter more
        points.append(Point("chute", f"{d.source} row {i + 2}", float(row["q_per_m"]),
                            float(row["q_per_m_std"]), runs, float(row["t_end"]), False, 1))
    return points


def points_table(problem: Problem, data, fit) -> pd.DataFrame:
    frames, start = [], 0
    for d in data:
        n = len(d.frame)
        frame = d.frame.copy()
        measured = "charge" if d.kind == "impacts" else "q_per_m"
        model = fit.model[start:start + n]
        ratio = model / frame[measured].to_numpy()
        head = pd.DataFrame({"kind": "impact" if d.kind == "impacts" else "chute",
                             "source": d.source, "row": np.arange(2, n + 2),
                             "measured": frame[measured].to_numpy(), "model": model,
                             "residual_log10": np.log10(np.where(ratio > 0, ratio, np.nan))})
        frames.append(pd.concat([head, frame], axis=1))
        start += n
    return pd.concat(frames, ignore_index=True)


def fit_table(fit) -> pd.DataFrame:
    rows = []
    for name, value in fit.values.items():
        d = fit.decades.get(name, math.nan)
        if math.isfinite(d):  # beyond 300 decades: the range is everything of its sign
            factor = 10.0 ** min(d, 300.0)
            low, high = value / factor, value * factor
        else:
            low, high = math.nan, math.nan
        rows.append({"parameter": name, "value": value, "std": fit.stds.get(name, math.nan),
                     "decades": d, "low": min(low, high), "high": max(low, high),
                     "status": fit.status[name], "unit": PARAMETERS[name]})
    return pd.DataFrame(rows)


def _version():
    try:
        return package_metadata.version("tribo")
    except package_metadata.PackageNotFoundError:
        return None


def _plain(value):
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    raise TypeError(f"{type(value).__name__} is not JSON")


# ---- the materials file ------------------------------------------------------------------------

def toml_value(value) -> str:
    """A TOML value of a plain Python one (numbers as they read back, nan and inf as TOML
    writes them)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"{value!r}: not a TOML value here")


def toml_tables(tables: dict, prefix: str = "") -> list[str]:
    """Lines of nested tables (dicts of plain values and dicts)."""
    lines, plain = [], {k: v for k, v in tables.items() if not isinstance(v, dict)}
    if plain and prefix:
        lines.append(f"[{prefix}]")
        lines += [f"{_key(k)} = {toml_value(v)}" for k, v in plain.items()]
        lines.append("")
    for k, v in tables.items():
        if isinstance(v, dict):
            lines += toml_tables(v, f"{prefix}.{_key(k)}" if prefix else _key(k))
    return lines


def _key(k: str) -> str:
    return k if all(c.isalnum() or c in "_-" for c in k) else json.dumps(k)


def materials_text(job: CalibrationJob, fit) -> str:
    """The materials file: the table given (its own entries, where a file was given) with
    the pair's calibrated sigma0, its other charging parameters, and where they came from."""
    overlay = {}
    if job.table.sha256 is not None:  # the file given: its entries stay in the one written
        import tomllib  # the file given, read again as written
        with open(job.table.source, "rb") as f:
            overlay = tomllib.load(f)
    p, w = job.particle, job.wall
    overlay.setdefault("sigma0", {}).setdefault(w, {})[p] = fit.values["sigma0"]
    charging = {n: v for n, v in fit.values.items() if n != "sigma0"}
    charging.update({n: v for n, v in job.problem.fixed.items() if v is not None and n not in charging})
    if charging:
        overlay.setdefault("charging", {}).setdefault(w, {})[p] = charging
    provenance = {"charge_model": job.charge_model, "date": datetime.date.today().isoformat(),
                  "package_version": _version() or "", "fmu_sha256": job.image.sha256,
                  "points": len(job.problem.points), "rms_log10": fit.rms_log10,
                  "data": [f"{d.kind}: {d.source} ({len(d.frame)} rows, sha256 {d.sha256})"
                           for d in job.data],
                  "settings": [f"{k} = {format_number(v)}" for k, v in job.settings.items()],
                  "warnings": list(fit.warnings)}
    for n, v in fit.values.items():
        provenance[n] = v
        provenance[f"{n}_std"] = fit.stds.get(n, math.nan)
        provenance[f"{n}_status"] = fit.status[n]
    overlay.setdefault("calibration", {}).setdefault(w, {})[p] = provenance
    head = [f"# A materials file written by `tribo calibrate` (tribo.calibrate): {p} on {w}, "
            f"the {job.charge_model} model,",
            f"# fitted to {', '.join(os.path.basename(d.source) for d in job.data)}. It is read "
            f"over the package's table:",
            "# `--materials FILE` of every command, `materials=` of the package's functions "
            "(docs/calibration.md).",
            "# [calibration] says where the numbers came from; it is not read as values.", ""]
    return "\n".join(head + toml_tables(overlay)) + "\n"

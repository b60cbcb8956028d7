"""A particle population: a feed description, N particles drawn from it with a seed, each
run through the SI FMU down the chute, one row per particle.

A feed is the particle and wall materials (tribo.materials), the chute (chute_length in
m, tilt_deg in degrees), any other SI parameter (by the package's names, fmu/names.py),
and a distribution (distributions.py) or measured values (a CSV, its rows drawn with
replacement, so that values measured together stay together) for each of

    epsilon         roundness b/a
    size            the particle's size, its long diameter 2a (m)
    phi0_deg        orientation of the long axis at the drop (degrees)
    omega0          spin at the drop (rad/s)
    drop_height     height of the lowest point above the chute (m)
    drop_speed      speed at the drop (m/s), in the direction drop_angle_deg
    drop_angle_deg  from the vertical, positive towards down-slope (degrees)

The draw uses numpy's generator seeded with `seed`, the variables in that order: the same
feed and seed give the same particles. Each particle is a run of the SI FMU (no unit
conversion here: the FMU maps the SI set-up onto the model) from the drop to the chute's
exit or the horizon, keyed like a sweep's run (batch.specs.run_key), so that a population is
resumable like a sweep (batch.sweep.run_sweep).

Per particle (`result_columns`), after the materials and every parameter of its run (the
feed variables, the chute, the materials' constants): whether and when it left the chute;
how its run ended (END_COLUMNS, where the FMU outputs them: `end_reason` 1 chute_exit,
3 at_rest, 0 still running at the horizon; `at_rest`, and `rest_time` in s, the time it came
to rest on the chute, model.md section 3c); its velocity there (u along, v normal to the chute, the speed, the spin); each charge model's charge and
charge-to-mass ratio, and the fraction of the grain's bands held at the gas's limit
(capped_fraction_<model>, model.md sections 8e, 8b; the cylinder's segments with
grain_geometry 0; the models are the FMU's,
fmu/charge_models.py); the area its contact patch charged (charged_area, m2, model.md
section 8c, where the FMU outputs it); the contact fraction; impacts, the contacts made
while approaching the plate (the core's count, model.md section 3b: each bounce is one, the
drop's first landing included); the fraction of the time in each motion class.
"""

import hashlib
import math
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..batch.particle import RunResult, run_to_end
from ..batch.specs import RunSpec, check_count
from ..batch.summary import MOTION_CLASSES
from ..fmu import FmuImage
from ..fmu.charge_models import charge_models, per_model
from ..materials import material, pair_values
from .distributions import Distribution, parse
from .feed_variables import DEFAULT_CHUTE, DEFAULT_DISTRIBUTIONS, FEED_VARIABLES


# the SI FMU's outputs of each charge model a particle's row holds (charge_<model>, ...)
MODEL_PREFIXES = ("charge_", "charge_to_mass_", "capped_fraction_")
# how a run ended (docs/model.md sections 3c, 9): the SI FMU's tribo.EndReason and the rest;
# a row of an FMU without them holds NaN there
END_COLUMNS = ("end_reason", "at_rest", "rest_time")
END_RUNNING, END_CHUTE_EXIT, END_FIRST_LIFTOFF, END_AT_REST = 0, 1, 2, 3  # tribo.EndReason
# the area the grain's contact patch has charged, m2 (docs/model.md section 8c); NaN in the
# row of an FMU without it, as END_COLUMNS
AREA_COLUMN = "charged_area"


def optional_outputs(md) -> list[str]:
    """END_COLUMNS and AREA_COLUMN that the FMU (its description `md`) outputs."""
    names = {v.name for v in md.modelVariables if v.causality == "output"}
    return [c for c in (*END_COLUMNS, AREA_COLUMN) if c in names]


def outputs(models, md=None) -> list[str]:
    """The SI FMU's outputs a particle's run records, for the charge models `models` (and
    how the run ended, where the FMU's description `md` has those outputs)."""
    return (["exited", "exit_time", "u", "v", "omega", "contact_fraction", "impacts",
             "assumption_warnings"] + per_model(MODEL_PREFIXES, models)
            + [f"fraction_{c}" for c in MOTION_CLASSES] + (optional_outputs(md) if md else []))


def result_columns(models) -> list[str]:
    """The columns of a particle's results row, for the charge models `models`."""
    return (["exited", "exit_time", *END_COLUMNS, "time_end", "u", "v", "exit_speed", "omega"]
            + per_model(MODEL_PREFIXES, models) + [AREA_COLUMN, "contact_fraction", "impacts"]
            + [f"fraction_{c}" for c in MOTION_CLASSES] + ["assumption_warnings"])

# a particle's RunSpec carries record_interval = t_end / STEPS_PER_RUN: it is part of the
# run's key and of its row in particles.csv (batch/specs.py), which stay as they were so
# that a folder resumes; the run itself reads only the end (run_particle)
STEPS_PER_RUN = 100
# the FMU's work limit per step, raised to its maximum: a particle that rocks down the chute
# takes many more steps than one that bounces, and the horizon bounds the work anyway
WORK_LIMIT = 2**31 - 1


class FeedError(ValueError):
    """A feed that cannot be drawn from (the message names the variable or column)."""


@dataclass
class Feed:
    """What the particles are drawn from (see the module's text)."""

    particle: str = "PE"
    wall: str = "steel"
    distributions: dict = field(default_factory=dict)  # feed variable -> text or Distribution
    chute: dict = field(default_factory=lambda: dict(DEFAULT_CHUTE))  # the defaults for those not given
    settings: dict = field(default_factory=dict)  # any other SI parameter by name
    measured: pd.DataFrame | None = None  # columns among FEED_VARIABLES

    def resolved(self) -> dict:
        """feed variable -> Distribution (the defaults for those not given)."""
        unknown = [n for n in self.distributions if n not in FEED_VARIABLES]
        if unknown:
            raise FeedError(f"not feed variables: {', '.join(unknown)} (they are: "
                            f"{', '.join(FEED_VARIABLES)})")
        drawn_too = [n for n in list(self.chute) + list(self.settings) if n in FEED_VARIABLES]
        if drawn_too:
            raise FeedError(f"{drawn_too[0]} is a feed variable, drawn for each particle: give it "
                            f"as a distribution or a number (--{drawn_too[0].replace('_', '-')}), "
                            f"not as a setting")
        out = {}
        for name in FEED_VARIABLES:
            d = self.distributions.get(name, DEFAULT_DISTRIBUTIONS[name])
            out[name] = d if isinstance(d, Distribution) else parse(name, d)
        return out

    def describe(self) -> dict:
        """The feed as plain values (for a results folder's metadata and record)."""
        measured = list(self.measured.columns) if self.measured is not None else []
        out = {"particle": material(self.particle, "particle").key,
               "wall": material(self.wall, "wall").key,
               "chute": dict(DEFAULT_CHUTE, **self.chute), "settings": dict(self.settings),
               "measured_columns": measured,
               "distributions": {n: d.text() for n, d in self.resolved().items()
                                 if n not in measured}}
        if self.measured is not None:  # the values themselves, by their digest
            text = self.measured.to_csv(index=False, float_format="%.17g").encode()
            out["measured_sha256"] = hashlib.sha256(text).hexdigest()
        return out


def read_measured(path: str) -> pd.DataFrame:
    """A CSV of measured values: a column per feed variable it gives (others refused)."""
    try:
        df = pd.read_csv(path)
    except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
        raise FeedError(f"cannot read the measured values {path}: {str(e).splitlines()[0]}") from None
    return check_measured(df, path)


def check_measured(df: pd.DataFrame, where: str = "measured values") -> pd.DataFrame:
    unknown = [c for c in df.columns if c not in FEED_VARIABLES]
    if unknown:
        raise FeedError(f"{where}: columns {', '.join(map(str, unknown))} are not feed variables "
                        f"({', '.join(FEED_VARIABLES)})")
    if len(df) == 0:
        raise FeedError(f"{where}: no rows")
    for c in df.columns:
        values = pd.to_numeric(df[c], errors="coerce")
        if not np.isfinite(values).all():
            row = int(np.flatnonzero(~np.isfinite(values))[0])
            raise FeedError(f"{where}: column {c}, row {row + 1}: {df[c].iloc[row]!r} is not a finite number")
    return df.astype(float)


def draw(feed: Feed, n: int, seed: int) -> pd.DataFrame:
    """n particles' feed variables (a column each), drawn with the seed."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise FeedError(f"the number of particles must be a whole number >= 1, got {n!r}")
    check_count(int(n), "the number of particles")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise FeedError(f"the seed must be a whole number >= 0, got {seed!r}")
    distributions = feed.resolved()
    rng = np.random.default_rng(seed)
    measured = feed.measured
    rows = rng.integers(0, len(measured), n) if measured is not None else None
    columns = {}
    for name in FEED_VARIABLES:
        if measured is not None and name in measured.columns:
            columns[name] = measured[name].to_numpy(dtype=float)[rows]
        else:
            columns[name] = distributions[name].draw(rng, n)
    return pd.DataFrame(columns)


def particle_parameters(feed: Feed, drawn: pd.DataFrame, defaults: dict | None = None) -> list[dict]:
    """The SI FMU's parameters of each drawn particle, by the package's names; `defaults`
    (e.g. the FMU's cylinder depth) unless the feed sets them."""
    settings = {**(defaults or {}), **dict(DEFAULT_CHUTE, **feed.chute), **feed.settings}
    base = dict(pair_values(feed.particle, feed.wall, sigma0="sigma0" not in settings),
                work_limit=WORK_LIMIT, **settings)
    return [dict(base, **{name: float(value) for name, value in zip(drawn.columns, row)})
            for row in drawn.itertuples(index=False)]


def specs_of(feed: Feed, n: int, seed: int, t_end: float, defaults: dict | None = None) -> list[RunSpec]:
    if not (math.isfinite(t_end) and t_end > 0):
        raise FeedError(f"the horizon t_end must be a positive number of seconds, got {t_end!r}")
    return [RunSpec(p, float(t_end), float(t_end) / STEPS_PER_RUN)
            for p in particle_parameters(feed, draw(feed, n, seed), defaults)]


def run_particle(image: FmuImage, spec: RunSpec) -> RunResult:
    """One particle down the chute: its results row (`result_columns` of the FMU's charge
    models), no series. The row needs only the end: one step to the horizon or the exit
    (batch/particle.py, run_to_end)."""
    wall0, cpu0 = time.perf_counter(), time.thread_time()
    md = image.model_description()
    recorded = outputs(charge_models(md), md)
    end = run_to_end(image, spec.params, spec.t_end, recorded)
    values = end.values
    row = {"time_end": end.time, "exit_speed": math.hypot(values["u"], values["v"])}
    row.update(dict.fromkeys((*END_COLUMNS, AREA_COLUMN), math.nan))
    row.update(values)
    row["exited"] = int(row["exited"])
    for name in ("end_reason", "at_rest"):
        if name in values:
            row[name] = int(row[name])
    row["impacts"] = int(row["impacts"])
    row["assumption_warnings"] = int(row["assumption_warnings"])
    row.update(cpu_s=time.thread_time() - cpu0, wall_s=time.perf_counter() - wall0)
    return RunResult(row, None)

"""A particle population: a feed description, N particles drawn from it with a seed, each
run through the SI FMU down the chute, one row per particle.

A feed is the particle and wall materials (tribo.materials), the chute (SI parameters:
chute_length, tilt), any other SI parameter, and a distribution (distributions.py) or
measured values (a CSV, its rows drawn with replacement, so that values measured together
stay together) for each of

    epsilon       roundness b/a
    size          the particle's size, its long diameter 2a (m)
    phi0          orientation of the long axis at the drop (rad)
    omega0        spin at the drop (rad/s)
    drop_height   height of the lowest point above the chute (m)
    drop_speed    speed at the drop (m/s), in the direction drop_angle
    drop_angle    from the vertical, positive towards down-slope (rad)

The draw uses numpy's generator seeded with `seed`, the variables in that order: the same
feed and seed give the same particles. Each particle is a run of the SI FMU (no unit
conversion here: the FMU maps the SI set-up onto the model) from the drop to the chute's
exit or the horizon, keyed like a sweep's run (batch.specs.run_key), so that a population is
resumable like a sweep (batch.sweep.run_sweep).

Per particle (RESULT_COLUMNS): size; whether and when it left the chute; its velocity
there (u along, v normal to the chute, the speed, the spin); both models' charge and
charge-to-mass ratio; the contact fraction; impacts, the contacts made after a flight
(the core's count, model.md section 9: each bounce is one, the drop's first contact
included); the fraction of the time in each motion class.
"""

import math
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..batch.particle import RunResult, simulate
from ..batch.specs import RunSpec
from ..batch.summary import MOTION_CLASSES
from ..fmu import FmuImage
from ..materials import start_values
from .distributions import Distribution, parse

# feed variable -> the SI FMU's parameter it sets (size: the long diameter, 2a)
FEED_VARIABLES = {"epsilon": "epsilon", "size": "semi_major_axis", "phi0": "phi0",
                  "omega0": "omega0", "drop_height": "drop_height", "drop_speed": "drop_speed",
                  "drop_angle": "drop_angle"}
# the SI reference case's feed (README, docs/reference_case.md): shapes 0.3-1, sizes
# 0.2-2 mm, random orientation, dropped from 10 mm at rest onto 0.3 m of steel at 30 degrees
DEFAULT_DISTRIBUTIONS = {"epsilon": "uniform:0.3:1", "size": "uniform:2e-4:2e-3",
                         "phi0": f"uniform:0:{math.pi!r}", "omega0": 0.0, "drop_height": 0.01,
                         "drop_speed": 0.0, "drop_angle": 0.0}
DEFAULT_CHUTE = {"chute_length": 0.3}

MODELS = ("static", "sliding")
OUTPUTS = (["exited", "exit_time", "u", "v", "omega", "contact_fraction", "impacts",
            "assumption_warnings"]
           + [f"charge_{m}" for m in MODELS] + [f"charge_to_mass_{m}" for m in MODELS]
           + [f"fraction_{c}" for c in MOTION_CLASSES])
RESULT_COLUMNS = ["size", "exited", "exit_time", "time_end", "u", "v", "exit_speed", "omega",
                  "charge_static", "charge_sliding", "charge_to_mass_static",
                  "charge_to_mass_sliding", "contact_fraction", "impacts"] \
    + [f"fraction_{c}" for c in MOTION_CLASSES] + ["assumption_warnings"]
# communication steps per run
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
    chute: dict = field(default_factory=lambda: dict(DEFAULT_CHUTE))
    settings: dict = field(default_factory=dict)  # any other SI parameter by name
    measured: pd.DataFrame | None = None  # columns among FEED_VARIABLES

    def resolved(self) -> dict:
        """feed variable -> Distribution (the defaults for those not given)."""
        unknown = [n for n in self.distributions if n not in FEED_VARIABLES]
        if unknown:
            raise FeedError(f"not feed variables: {', '.join(unknown)} (they are: "
                            f"{', '.join(FEED_VARIABLES)})")
        out = {}
        for name in FEED_VARIABLES:
            d = self.distributions.get(name, DEFAULT_DISTRIBUTIONS[name])
            out[name] = d if isinstance(d, Distribution) else parse(name, d)
        return out

    def describe(self) -> dict:
        """The feed as plain values (for a results folder's metadata)."""
        measured = list(self.measured.columns) if self.measured is not None else []
        return {"particle": self.particle, "wall": self.wall, "chute": dict(self.chute),
                "settings": dict(self.settings), "measured_columns": measured,
                "distributions": {n: d.text() for n, d in self.resolved().items()
                                  if n not in measured}}


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


def particle_parameters(feed: Feed, drawn: pd.DataFrame) -> list[dict]:
    """The SI FMU's parameters of each drawn particle."""
    base = start_values(feed.particle, feed.wall, **{"work_limit": WORK_LIMIT, **feed.chute,
                                                     **feed.settings})
    out = []
    for row in drawn.itertuples(index=False):
        params = dict(base)
        for name, value in zip(drawn.columns, row):
            params[FEED_VARIABLES[name]] = float(value) / 2.0 if name == "size" else float(value)
        out.append(params)
    return out


def specs_of(feed: Feed, n: int, seed: int, t_end: float) -> list[RunSpec]:
    if not (math.isfinite(t_end) and t_end > 0):
        raise FeedError(f"the horizon t_end must be a positive number of seconds, got {t_end!r}")
    return [RunSpec(p, float(t_end), float(t_end) / STEPS_PER_RUN)
            for p in particle_parameters(feed, draw(feed, n, seed))]


def run_particle(image: FmuImage, spec: RunSpec) -> RunResult:
    """One particle down the chute: its results row (RESULT_COLUMNS)."""
    wall0, cpu0 = time.perf_counter(), time.thread_time()
    recording = simulate(image, spec.params, spec.t_end, spec.record_interval, OUTPUTS)
    end = recording.series.iloc[-1]
    row = {"size": 2.0 * spec.params["semi_major_axis"], "time_end": float(end["time"]),
           "exit_speed": math.hypot(end["u"], end["v"])}
    row.update({name: float(end[name]) for name in OUTPUTS})
    row["exited"] = int(row["exited"])
    row["impacts"] = int(row["impacts"])
    row["assumption_warnings"] = int(row["assumption_warnings"])
    row.update(cpu_s=time.thread_time() - cpu0, wall_s=time.perf_counter() - wall0)
    return RunResult(row, recording.series)

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

The draw takes the grains in blocks of DRAW_BLOCK, each block from numpy's generator
seeded with the seed's child of that block (numpy.random.SeedSequence(seed, spawn_key=
(block,))), the variables in that order: the same feed and seed give the same particles,
and the first n of them are the same whatever n, so that a population of more grains is
the one of fewer and more (`-n 2000` on a folder of 1000 runs the 1000 new ones). Each
particle is a run of the SI FMU (no unit conversion here: the FMU maps the SI set-up onto
the model) from the drop to the chute's exit or the horizon, keyed like a sweep's run
(batch.specs.run_key), so that a population is resumable like a sweep
(batch.sweep.run_sweep).

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
import io
import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from fmpy.fmi1 import FMICallException

from ..batch.specs import RunSpec, check_count
from ..batch.summary import MOTION_CLASSES
from ..fmu import FmuImage, Instance
from ..fmu.charge_models import per_model
from ..fmu.names import to_fmu
from ..input_files import read_input
from ..materials import material, pair_values
from ..model_time import check_horizon as check_horizon_of
from .distributions import Distribution, parse
from .feed_variables import DEFAULT_CHUTE, DEFAULT_DISTRIBUTIONS, FEED_VARIABLES
# a particle's run and its outputs (no pandas there: what a Dask worker process imports),
# and the names the package has always taken from here
from .particle import (AREA_COLUMN, END_AT_REST, END_CHUTE_EXIT, END_COLUMNS,  # noqa: F401
                       END_FIRST_LIFTOFF, END_RUNNING, MODEL_PREFIXES, optional_outputs,
                       outputs, run_particle)


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


# the draw's grains come in blocks of this many, each block from its own generator (draw)
DRAW_BLOCK = 1024


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
    # the materials file the pair's values in `settings` came from, where one did: said in
    # the record and the figure's title
    materials: str | None = None

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
        if self.materials is not None:
            out["materials"] = str(self.materials)
        if self.measured is not None:  # the values themselves, by their digest
            text = self.measured.to_csv(index=False, float_format="%.17g").encode()
            out["measured_sha256"] = hashlib.sha256(text).hexdigest()
        return out


def read_measured(path: str) -> pd.DataFrame:
    """A CSV of measured values: a column per feed variable it gives (others refused)."""
    text = read_input(path, FeedError, "the measured values")
    try:
        df = pd.read_csv(io.BytesIO(text))
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
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
    measured = feed.measured
    blocks = []
    for block in range(-(-int(n) // DRAW_BLOCK)):
        # each block of grains from a generator of its own (the seed's child `block`), drawn
        # whole: the first n grains are the same whatever n, so a population extends
        rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(block,)))
        rows = rng.integers(0, len(measured), DRAW_BLOCK) if measured is not None else None
        columns = {}
        for name in FEED_VARIABLES:
            if measured is not None and name in measured.columns:
                columns[name] = measured[name].to_numpy(dtype=float)[rows]
            else:
                columns[name] = distributions[name].draw(rng, DRAW_BLOCK)
        blocks.append(pd.DataFrame(columns))
    return pd.concat(blocks, ignore_index=True).iloc[:n].reset_index(drop=True)


def particle_parameters(feed: Feed, drawn: pd.DataFrame, defaults: dict | None = None) -> list[dict]:
    """The SI FMU's parameters of each drawn particle, by the package's names; `defaults`
    (e.g. the FMU's cylinder depth) unless the feed sets them."""
    settings = {**(defaults or {}), **dict(DEFAULT_CHUTE, **feed.chute), **feed.settings}
    # a setting wins over the work limit too
    base = {**pair_values(feed.particle, feed.wall, sigma0="sigma0" not in settings),
            "work_limit": WORK_LIMIT, **settings}
    if "size" in drawn.columns and "chute_length" in base and len(drawn):
        check_fits(float(drawn["size"].max()), float(base["chute_length"]))
    return [dict(base, **{name: float(value) for name, value in zip(drawn.columns, row)})
            for row in drawn.itertuples(index=False)]


def check_fits(size: float, chute_length: float) -> None:
    """FeedError for a grain as long as its chute or longer: it would land across the chute's
    end (the FMU checks each value alone, not the one against the other)."""
    if 0 < chute_length <= size:  # a length that is no length: the FMU's refusal says it
        raise FeedError(f"size = {size:g} m: the grain is as long as the chute it runs down "
                        f"(chute_length = {chute_length:g} m) or longer; a grain's long "
                        f"diameter is in m (1 mm: 1e-3)")


def specs_of(feed: Feed, n: int, seed: int, t_end: float, defaults: dict | None = None) -> list[RunSpec]:
    if not (math.isfinite(t_end) and t_end > 0):
        raise FeedError(f"the horizon t_end must be a positive number of seconds, got {t_end!r}")
    return [RunSpec(p, float(t_end), float(t_end) / STEPS_PER_RUN)
            for p in particle_parameters(feed, draw(feed, n, seed), defaults)]


def check_horizon(image: FmuImage, specs: list[RunSpec]) -> None:
    """FeedError, before any run, for a horizon the model cannot resolve (model_time.py):
    one of more than model_time.TIME_MAX of the quickest grain's t*. t* = sqrt(m'/k') with
    m' = rho pi a^2 epsilon (model.md section 8, src/si/si.c): the grains of a feed share
    their materials and settings, so the quickest is the one of the least size^2 epsilon,
    and its t* is read from the FMU."""
    if not specs:
        return
    quickest = min(specs, key=lambda s: s.params["size"] ** 2 * s.params["epsilon"])
    instance = Instance(image, name="tribo_horizon")
    try:
        instance.set_parameters(to_fmu(image.model_description(), quickest.params))
        if instance.version == 2:
            instance.fmu.setupExperiment(startTime=0.0)
            instance.fmu.enterInitializationMode()
        else:
            instance.fmu.enterInitializationMode(startTime=0.0)
        t_star = float(instance.get("t_star"))
    except FMICallException:  # a set-up the FMU refuses: its runs say why
        return
    finally:
        instance.free()
    check_horizon_of(quickest.t_end, t_star, "the horizon t_end", FeedError)

"""The measurable quantities that calibrate and check the model's charging (docs/model.md
section 8d), each through the SI FMU with the spheroid's charge (section 8c):

    single_impact     one impact of an uncharged (or uniformly charged) grain without spin
                      on a fresh, level wall: the charge it picks up, Delta q (C), and the
                      charged area after it, A_max (m2: for an impact the staircase of bands
                      under its largest patch, docs/model.md section 8c)
    repeated_impacts  n such impacts, each on a fresh wall spot: the charge after each
    chute_stream      a feed down a chute: the exit stream's mass-weighted mean q/m and its
                      spread (a Faraday cup at the chute's end), and the mass fraction that
                      stays on the chute

An impact is impact.episode's episode (tilt 0, drop_height 0, drop_speed the speed,
drop_angle_deg = 90 - angle_deg, run_end = first lift-off), with the grain's size, roundness
and orientation, and its initial charge spread uniformly over the spheroid's surface
(initial_charge_density = charge / the surface, section 8c); it ends at the first lift-off,
or at the time limit (`limit` contact periods' worth of t*), where the grain has not lifted
off: `lifted_off` says which, `time_end` when.

**Repeated impacts (an approximation, stated):** the model knows one wall and one contact
at a time, so the impacts are run one after another, each a single impact of the same
speed, angle and orientation on a fresh wall spot, and between two impacts the charge the
grain carries is taken spread evenly over its surface: it enters the next impact as its
initial density. So each impact charges its patch from the grain's mean density towards
saturation, the condenser model's approach to a saturation over **the whole spheroid's
surface** A_s: with complete transfer, q_n = s A_s (1 - (1 - A/A_s)^n), A the patch's area,
s the density a patch keeps (|sigma0|, or the gas's sigma_P(L_e) of the patch where that
is lower, docs/model.md section 8e: tested), up to the grain's own limit. The series'
ceiling (the column `ceiling`) is `ceiling_of`'s: min(|sigma0|, sigma_P(R_s)) A_s with
breakdown_model = paschen (sigma_P(R_s) A_s, the grain's limit, for the table's pairs),
min(|sigma0|, breakdown_density) A_s with fixed. A real grain carries its charge where it
touched, and meets the wall on other spots: the even spread is the simplest such mixing.

**Not the chute's grain.** A chute run (chute_stream, tribo.population) moves the grain in
one plane: its contacts charge only the belt its section sweeps (the bands of docs/model.md
section 8c, its `charged_area`), never the rest of the spheroid, so its ceiling is that
belt at the density its patches keep (min(|sigma0|, sigma_P(L_e)) times the belt's area,
at most the grain's limit): under a thousandth of the surface (2.1e-3 mm2 on average down
the reference chute, docs/validation.md). The two
describe different grains: repeated impacts one tumbling between impacts, the chute one
that keeps its orientation plane; the column `surface` of repeated_impacts says so.

The runs of a calibration are many and short (an impact is about a millisecond of the
core's time): `Runs` is a batch of them in one FMU instance, reset between runs, so that
each costs the core's time and not an instance's (`run_runs`, a task for the package's
executors). A chute's grains are stepped through the population's communication grid
(populations.feed), so that their charges are the population's.
"""

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from fmpy.fmi1 import FMICallException

from ..batch.executors import executor_for
from ..batch.particle import communication_points
from ..fmu import FmuImage, Instance
from ..fmu.charge_models import charge_models, switches
from ..fmu.locate import find_fmu
from ..fmu.names import failure, to_fmu
from ..fmu.parameters import check_values
from ..impact.defaults import DEFAULT_LIMIT
from ..impact.episode import check_axis, episode_parameters
from ..fmu.names import start_value
from ..materials import table_of, with_pair
from ..paschen import Gas, grain_limit
from ..paschen import spheroid_area as spheroid_surface
from ..populations.feed import STEPS_PER_RUN, Feed, draw, particle_parameters
from ..populations.feed_variables import DEFAULT_CHUTE
from ..populations.summary import stream_statistics

# what an impact's or a grain's run reads at its end (the charge model's charge is added)
RUN_OUTPUTS = ("charged_area", "lifted_off", "contact_time", "exited", "mass")
MAX_IMPACTS = 10_000  # repeated impacts: more is a typing mistake, not a measurement


class ObservableError(ValueError):
    """An observable that cannot be run as asked (the message, one line, names the value)."""


def spheroid_mass(size: float, epsilon: float, density: float) -> float:
    """(4/3) pi rho a b^2, kg (docs/model.md section 8c)."""
    a = size / 2.0
    return 4.0 / 3.0 * math.pi * density * a * (epsilon * a) ** 2


def model_switches(charge_model: str, models) -> dict:
    """The switches that leave one charge model of `models` (the FMU's) on: the others'
    work would be spent for nothing (they are alternative laws of the same charge)."""
    if charge_model not in models:
        raise ObservableError(f"charge_model = {charge_model!r}: one of {', '.join(models)}")
    return {switch: int(m == charge_model) for m, switch in zip(models, switches(models))}


@dataclass(frozen=True)
class Runs:
    """A batch of runs of one kind, for one task: the parameters of each (the package's
    names and units), the horizon (in units of each run's t* where `in_t_star`, an impact's
    time limit; else in s) reached in `steps` communication steps, the charge model whose
    charge is read, and `repeat`: impacts one after another on fresh wall spots (the
    module's text), each entering with the charge before it spread over the surface."""

    params: tuple = field(hash=False)
    horizon: float
    charge_model: str = "static"
    in_t_star: bool = True
    steps: int = 1
    repeat: int = 1


def run_runs(image: FmuImage, runs: Runs) -> list[dict]:
    """Each run of the batch in one instance of the FMU, reset between runs: a row per run
    (charge, C, the grain's, before the first and after the last impact: `charge_initial`,
    `charge`; `capped`, the fraction of its bands at the gas's limit; charged_area,
    m2; lifted_off, contact_time, exited, mass; t_star, time_end in s). With `repeat` > 1 a row also holds `charges`: the charge after each impact."""
    md = image.model_description()
    outputs = (f"charge_{runs.charge_model}", f"capped_fraction_{runs.charge_model}") + RUN_OUTPUTS
    rows = []
    instance = Instance(image, name="tribo_calibration")
    try:
        for params in runs.params:
            rows.append(_chain(instance, md, params, runs, outputs))
    except FMICallException as e:
        raise RuntimeError(f"a run failed: {failure(md, instance.messages, e)}") from None
    finally:
        instance.free()
    return rows


def _chain(instance: Instance, md, params: dict, runs: Runs, outputs) -> dict:
    """One run, or `repeat` impacts one after another (the module's text)."""
    surface = spheroid_surface(params["size"], params["epsilon"]) if "size" in params else None
    density = params.get("initial_charge_density", 0.0)
    charge_initial = density * surface if surface else 0.0
    charges = []
    for _ in range(runs.repeat):
        instance.set_parameters(to_fmu(md, dict(params, initial_charge_density=density)))
        if runs.in_t_star:
            instance.init(0.0)
            t_star = instance.get("t_star")
            times = [runs.horizon * t_star]
        else:
            instance.init(0.0, runs.horizon)
            t_star = instance.get("t_star")
            times = communication_points(runs.horizon, runs.horizon / runs.steps)[1:]
        for t in times:
            if not instance.step_to(t):
                break
        end = instance.get_many(outputs)
        row = {"charge": float(end[outputs[0]]), "capped": float(end[outputs[1]]),
               "charged_area": float(end["charged_area"]),
               "lifted_off": int(end["lifted_off"]), "contact_time": float(end["contact_time"]),
               "exited": int(end["exited"]), "mass": float(end["mass"]),
               "t_star": float(t_star), "time_end": float(instance.t)}
        instance.terminate()
        instance.reset()
        charges.append(row["charge"])
        if surface:  # the next impact's: the charge carried, spread over the surface
            density = row["charge"] / surface
    row["charge_initial"] = charge_initial
    if runs.repeat > 1:
        row["charges"] = charges
    return row


def impact_parameters(base: dict, *, speed: float, angle_deg: float = 90.0, size: float = 1e-3,
                      epsilon: float = 1.0, phi0_deg: float = 0.0,
                      initial_charge: float = 0.0) -> dict:
    """An impact's SI parameters by the package's names: `base` (the pair's and any other
    settings) with the episode's (impact.episode), the size and the initial charge as the
    spheroid's uniform density."""
    for name, value in (("speed", speed), ("angle_deg", angle_deg), ("phi0_deg", phi0_deg),
                        ("epsilon", epsilon)):
        try:
            check_axis(name, [value])
        except ValueError as e:
            raise ObservableError(str(e)) from None
    if not (isinstance(size, (int, float)) and math.isfinite(size) and size > 0):
        raise ObservableError(f"size = {size!r}: the long diameter 2a in m, a positive number")
    if not (isinstance(initial_charge, (int, float)) and math.isfinite(initial_charge)):
        raise ObservableError(f"initial_charge = {initial_charge!r}: a charge in C, finite")
    params = episode_parameters(dict(base, size=float(size)), speed, angle_deg, phi0_deg, epsilon)
    if initial_charge:
        params["initial_charge_density"] = float(initial_charge) / spheroid_surface(size, epsilon)
    return params


def _image_and_base(particle, wall, settings, materials, fmu, charge_model):
    image = FmuImage.load(find_fmu(fmu, "si"))
    models = charge_models(image.model_description())
    settings = dict(settings or {})
    base = dict(table_of(materials).pair_values(particle, wall, sigma0="sigma0" not in settings),
                **model_switches(charge_model, models), **settings)
    return image, base


def _checked_limit(limit: float) -> float:
    if not (isinstance(limit, (int, float)) and math.isfinite(limit) and limit > 0):
        raise ObservableError(f"limit = {limit!r}: the time limit in units of t*, a positive number")
    return float(limit)


def single_impact(particle: str = "PE", wall: str = "steel", *, speed: float,
                  angle_deg: float = 90.0, size: float = 1e-3, epsilon: float = 1.0,
                  phi0_deg: float = 0.0, initial_charge: float = 0.0,
                  charge_model: str = "static", settings: dict | None = None, materials=None,
                  limit: float = DEFAULT_LIMIT, fmu: str | int | None = None) -> dict:
    """One impact (the module's text): the grain of `size` (the long diameter 2a, m),
    `epsilon` and orientation phi0_deg meets a fresh level wall at `speed` (m/s) and
    angle_deg to it (90 head-on), carrying `initial_charge` (C) spread evenly over it.
    Returns `charge` (Delta q, C, by `charge_model`), `charged_area` (A_max, m2),
    `charge_after` (C), `initial_charge`, `lifted_off` (False: no lift-off within `limit`
    t*, the values then at `time_end`), `contact_time` and `time_end` (s), `t_star` (s),
    `mass` (kg), `surface_area` (m2). settings: other SI parameters (mu, nu, charging_time,
    ...); materials: a materials file (tribo.materials)."""
    image, base = _image_and_base(particle, wall, settings, materials, fmu, charge_model)
    params = impact_parameters(base, speed=speed, angle_deg=angle_deg, size=size,
                               epsilon=epsilon, phi0_deg=phi0_deg, initial_charge=initial_charge)
    check_values(image, {k: [v] for k, v in params.items()})
    row = run_runs(image, Runs((params,), _checked_limit(limit), charge_model))[0]
    return {"charge": row["charge"] - row["charge_initial"], "charged_area": row["charged_area"],
            "charge_after": row["charge"], "initial_charge": row["charge_initial"],
            "lifted_off": bool(row["lifted_off"]), "contact_time": row["contact_time"],
            "time_end": row["time_end"], "t_star": row["t_star"], "mass": row["mass"],
            "surface_area": spheroid_surface(size, epsilon), "charge_model": charge_model}


def repeated_impacts(particle: str = "PE", wall: str = "steel", n: int = 10, *, speed: float,
                     angle_deg: float = 90.0, size: float = 1e-3, epsilon: float = 1.0,
                     phi0_deg: float = 0.0, initial_charge: float = 0.0,
                     charge_model: str = "static", settings: dict | None = None,
                     materials=None, limit: float = DEFAULT_LIMIT,
                     fmu: str | int | None = None) -> pd.DataFrame:
    """n impacts as single_impact's, each on a fresh wall spot, the charge carried spread
    evenly over the grain between them (the module's text). A row per impact: `impact`
    (1..n), `charge` (the grain's after it, C), `charge_gained` (since the first impact
    began, C), `delta` (this impact's Delta q, C), `ceiling` (C: the charge the series
    approaches, ceiling_of) and `surface` (what the impacts charge: the whole spheroid's
    surface, not a chute run's belt)."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 1 <= n <= MAX_IMPACTS:
        raise ObservableError(f"n = {n!r}: the number of impacts, a whole number from 1 to "
                              f"{MAX_IMPACTS}")
    image, base = _image_and_base(particle, wall, settings, materials, fmu, charge_model)
    md = image.model_description()
    params = impact_parameters(base, speed=speed, angle_deg=angle_deg, size=size,
                               epsilon=epsilon, phi0_deg=phi0_deg, initial_charge=initial_charge)
    check_values(image, {k: [v] for k, v in params.items()})
    row = run_runs(image, Runs((params,), _checked_limit(limit), charge_model, repeat=int(n)))[0]
    charges = np.array(row.get("charges", [row["charge"]]))
    before = np.concatenate([[row["charge_initial"]], charges[:-1]])
    return pd.DataFrame({"impact": np.arange(1, len(charges) + 1), "charge": charges,
                         "charge_gained": charges - row["charge_initial"],
                         "delta": charges - before,
                         "ceiling": ceiling_of(md, params, charge_model),
                         "surface": REPEATED_SURFACE})


# what repeated_impacts charges, beside a chute run (the module's text)
REPEATED_SURFACE = ("fresh spots over the whole spheroid (the charge spread evenly between "
                    "impacts); a chute run charges only the belt its section sweeps")


def _paschen(md, params: dict) -> bool:
    """The gas's limit of section 8e is in force (breakdown_model = 1, paschen)."""
    model = params.get("breakdown_model", start_value(md, "breakdown_model"))
    return model is not None and int(model) == 1


def ceiling_of(md, params: dict, charge_model: str = "static") -> float:
    """The charge (C, of sigma0's sign) that repeated impacts approach (the module's
    text): the whole surface A_s at the density the grain keeps. The static model's
    |sigma0|, capped by the gas: with breakdown_model = paschen the grain's limit
    sigma_P(R_s) A_s (docs/model.md section 8e), with fixed breakdown_density (section 8b;
    0: none). The sliding model's saturation grows with the work: the gas's cap alone (inf
    without one)."""
    def value(name):
        v = params.get(name, start_value(md, name))
        return None if v is None else float(v)
    sigma0 = value("sigma0") or 0.0
    size, epsilon = value("size"), value("epsilon")
    area = spheroid_surface(size, epsilon)
    own = abs(sigma0) * area if charge_model == "static" else math.inf
    if _paschen(md, params):
        gas = Gas.of(params, md)
        cap = grain_limit(size, epsilon, gas, bool(value("wall_conducting") or 0))
    else:
        density = value("breakdown_density") or 0.0
        cap = density * area if density > 0 else math.inf
    return math.copysign(min(own, cap), sigma0)


@dataclass
class Stream:
    """A feed's exit stream (chute_stream): `statistics` (q_per_m: the mass-weighted mean
    q/m of the grains that left, C/kg; q_per_m_std: the mass-weighted standard deviation of
    their q/m; stayed: the mass fraction that did not leave; n, n_exited) and `grains` (a
    row per grain: its feed variables, exited, charge (C), mass (kg), charged_area (m2: the
    belt its contacts charged, the most it can charge: the module's text), surface_area (m2,
    the spheroid's), charge_to_mass)."""

    statistics: dict
    grains: pd.DataFrame


def chunks(items: list, n: int) -> list[list]:
    """`items` in about n consecutive pieces (at least one item each)."""
    n = max(1, min(n, len(items)))
    size = math.ceil(len(items) / n)
    return [items[i:i + size] for i in range(0, len(items), size)]


def run_all(executor, image: FmuImage, batches: list[Runs]) -> list[list[dict]]:
    """The batches on the executor (entered by the caller), their rows in their order;
    RuntimeError naming the first failure."""
    out = [None] * len(batches)
    for i, result in executor.run(run_runs, image, batches):
        if isinstance(result, BaseException):
            raise RuntimeError(str(result).splitlines()[0] if str(result) else type(result).__name__)
        out[i] = result
    return out


def stream_of(rows: list[dict]) -> dict:
    """The stream statistics (populations.summary.stream_statistics) of a chute's grains'
    rows (run_runs's)."""
    mass = pd.Series([r["mass"] for r in rows], dtype=float)
    charge = pd.Series([r["charge"] for r in rows], dtype=float)
    exited = pd.Series([r["exited"] for r in rows], dtype=float)
    stats = stream_statistics(charge / mass, mass, exited)
    return {"q_per_m": stats["stream_mean"], "q_per_m_std": stats["stream_std"],
            "stayed": stats["stayed"], "n": len(rows), "n_exited": int((exited != 0).sum())}


def chute_parameters(feed: Feed, n: int, seed: int, charge_model: str, models) -> tuple:
    """The feed's drawn grains (a DataFrame of the feed variables) and each one's SI
    parameters (populations.feed), with one charge model on."""
    drawn = draw(feed, n, seed)
    params = [dict(p, **model_switches(charge_model, models))
              for p in particle_parameters(feed, drawn, {"cylinder_length": 1e-3})]
    return drawn, params


def chute_stream(particle: str = "PE", wall: str = "steel", n: int = 100, *, seed: int = 0,
                 distributions: dict | None = None, chute: dict | None = None,
                 settings: dict | None = None, charge_model: str = "static", materials=None,
                 t_end: float = 5.0, fmu: str | int | None = None,
                 scheduler: str | None = None, workers: int | None = None,
                 serial: bool = False, processes: bool = False) -> Stream:
    """n grains drawn with the seed from a feed (as tribo.population's: distributions of
    the feed variables, chute_length and tilt_deg in `chute`, other SI parameters in
    `settings`) down the chute, each to its exit or t_end (s): the exit stream (`Stream`).
    Runs on a local Dask cluster (or `scheduler`, or serial=True: this process)."""
    if not (isinstance(t_end, (int, float)) and math.isfinite(t_end) and t_end > 0):
        raise ObservableError(f"t_end = {t_end!r}: the horizon in s, a positive number")
    image = FmuImage.load(find_fmu(fmu, "si"))
    models = charge_models(image.model_description())
    feed = Feed(particle, wall, dict(distributions or {}), dict(DEFAULT_CHUTE, **(chute or {})),
                with_pair(particle, wall, dict(settings or {}), materials))
    drawn, params = chute_parameters(feed, n, seed, charge_model, models)
    check_values(image, {k: [p[k] for p in params] for k in params[0]})
    executor = executor_for(serial, scheduler, workers, processes)
    with executor:
        batches = [Runs(tuple(c), float(t_end), charge_model, in_t_star=False, steps=STEPS_PER_RUN)
                   for c in chunks(params, 4 * executor.workers)]
        rows = [r for batch in run_all(executor, image, batches) for r in batch]
    grains = drawn.assign(exited=[r["exited"] for r in rows], charge=[r["charge"] for r in rows],
                          mass=[r["mass"] for r in rows],
                          charged_area=[r["charged_area"] for r in rows],
                          surface_area=[spheroid_surface(p["size"], p["epsilon"]) for p in params])
    grains["charge_to_mass"] = grains["charge"] / grains["mass"]
    return Stream(stream_of(rows), grains)

"""Charge per impact: one impact episode of the SI FMU, and the episodes of a map's grid.

An episode is a particle arriving at a level plate (tilt 0) with its lowest point touching
it (drop_height 0) at `speed`, at `angle_deg` from the plate's surface (90 degrees:
head-on; towards +x), with orientation phi0_deg and spin omega0, run with run_end =
first_liftoff: the
FMU ends the run where the contact made is lost (located exactly, docs/model.md section 9),
or at the time limit (`limit` contact periods' worth of t*, read from the FMU): a sustained
contact, `lifted_off` = 0. Gravity stays on (its effect over an impact of microseconds is
the model's, not removed). An episode that does not lift off may also end at rest on the
plate (a grazing or very slow arrival settles: the FMU ends the run there, docs/model.md
section 3c): `end_reason` says which (2 lifted off, 3 at rest, 0 in contact at the time
limit); its "rebound" is then the state it rests or slides in, no rebound at all.

Its results (`episode_columns`): the charge each charge model of the FMU transferred (C,
the grain's: the spheroid's by default, the cylinder of the depth set with grain_geometry
= cylinder; and per unit mass; fmu/charge_models.py), the area the
contact patch charged (`charged_area`, m2: for a first impact on an uncharged grain with
instantaneous transfer the static charge is sigma0 times it where |sigma0| is below the
gas's limit of the patch, and that limit times it above, docs/model.md sections 5c, 8c, 8e), the rebound (velocity along and normal to the plate, speed,
angle from the surface in degrees, spin), the contact time, whether it lifted off and how
the episode ended (`end_reason`; NaN where the FMU lacks it, as `charged_area`).

A map's grid point is (speed m/s, angle_deg, phi0_deg, epsilon): angles in degrees, as
everywhere in the package (tribo/fmu/names.py converts them for the FMU).
"""

import itertools
import math
import time
from dataclasses import dataclass

from fmpy.fmi1 import FMICallException

from ..batch.particle import RunResult
from ..batch.specs import RunSpec, check_count
from ..fmu import FmuImage
from ..fmu.image import per_description
from ..fmu.charge_models import charge_models, per_model
from ..fmu.names import failure, to_fmu
from ..fmu.reuse import Instances, instance_for, shares_instances
from ..materials import pair_values
from ..model_time import check_limit

AXES = ("speed", "angle_deg", "phi0_deg", "epsilon")
AXIS_UNITS = {"speed": "m/s", "angle_deg": "deg from the plate's surface (90: head-on)",
              "phi0_deg": "deg, long axis from the plate", "epsilon": "b/a"}
AXIS_RANGES = {"speed": (0.0, 1e3, False), "angle_deg": (0.0, 90.0, False),
               "phi0_deg": (-180.0, 180.0, True), "epsilon": (1e-3, 1.0, True)}  # low, high, low end included
# the SI FMU's outputs of each charge model an episode's row holds (charge_<model>, ...)
MODEL_PREFIXES = ("charge_", "charge_to_mass_")
AREA_COLUMN = "charged_area"
MOTION_COLUMNS = ["rebound_u", "rebound_v", "rebound_speed", "rebound_angle_deg",
                  "rebound_omega", "contact_time", "lifted_off", "end_reason", "time_end", "t_star"]
# tribo.EndReason of an episode (run_end = first_liftoff); 0: still in contact at the limit
LIFTED_OFF, AT_REST, AT_LIMIT = 2, 3, 0


class ImpactError(ValueError):
    """A grid or an episode the FMU cannot run (the message names the value)."""


def episode_columns(models) -> list[str]:
    """The columns of an episode's results row, for the charge models `models`."""
    return per_model(MODEL_PREFIXES, models) + [AREA_COLUMN] + MOTION_COLUMNS


def episode_parameters(base: dict, speed: float, angle_deg: float, phi0_deg: float,
                       epsilon: float, omega0: float = 0.0) -> dict:
    """The SI FMU's parameters of an episode, by the package's names."""
    return dict(base, tilt_deg=0.0, drop_height=0.0, drop_speed=float(speed),
                drop_angle_deg=90.0 - float(angle_deg), phi0_deg=float(phi0_deg),
                epsilon=float(epsilon), omega0=float(omega0), run_end=1)


def check_axis(name: str, values) -> list[float]:
    values = [float(v) for v in values]
    lo, hi, closed = AXIS_RANGES[name]
    if not values:
        raise ImpactError(f"{name}: no values")
    for v in values:
        if not (math.isfinite(v) and (lo <= v if closed else lo < v) and v <= hi):
            raise ImpactError(f"{name} = {v:g} ({AXIS_UNITS[name]}): outside "
                              f"{'[' if closed else '('}{lo:g}, {hi:g}]")
    if len(set(values)) != len(values) or values != sorted(values):
        raise ImpactError(f"{name} {values}: the values must increase")
    return values


@dataclass(frozen=True)
class Grid:
    speed: tuple
    angle_deg: tuple
    phi0_deg: tuple
    epsilon: tuple

    @classmethod
    def of(cls, **axes) -> "Grid":
        missing = [a for a in AXES if a not in axes]
        unknown = [a for a in axes if a not in AXES]
        if missing or unknown:
            raise ImpactError(f"the grid's axes are {', '.join(AXES)}"
                              + (f"; missing {', '.join(missing)}" if missing else "")
                              + (f"; unknown {', '.join(unknown)}" if unknown else ""))
        grid = cls(**{a: tuple(check_axis(a, axes[a])) for a in AXES})
        check_count(math.prod(len(getattr(grid, a)) for a in AXES),
                    f"episodes of the grid {' x '.join(str(len(getattr(grid, a))) for a in AXES)}")
        return grid

    def points(self) -> list[tuple]:
        return list(itertools.product(self.speed, self.angle_deg, self.phi0_deg, self.epsilon))

    def axes(self) -> dict:
        return {a: list(getattr(self, a)) for a in AXES}


def episode_specs(grid: Grid, particle: str, wall: str, settings: dict, limit: float,
                  omega0: float = 0.0) -> list[RunSpec]:
    """One run per grid point, in the grid's order (speed slowest, epsilon fastest). Its
    t_end is the time limit in units of t* (the FMU's, which depends on the point)."""
    check_limit(limit, "the time limit", ImpactError)
    base = dict(pair_values(particle, wall, sigma0="sigma0" not in settings), **settings)
    return [RunSpec(episode_parameters(base, *point, omega0=omega0), float(limit), float(limit))
            for point in grid.points()]


@per_description
def episode_outputs(md) -> tuple[tuple, tuple, tuple]:
    """(each charge model's outputs, those of AREA_COLUMN and end_reason the FMU has, all
    that an episode reads at its end): once per description, not a walk over its variables
    per episode (docs/populations.md, "Benchmark")."""
    outputs = {v.name for v in md.modelVariables if v.causality == "output"}
    charges = tuple(per_model(MODEL_PREFIXES, charge_models(md)))
    optional = tuple(n for n in (AREA_COLUMN, "end_reason") if n in outputs)
    return charges, optional, charges + ("u", "v", "omega", "contact_time", "lifted_off") + optional


@shares_instances
def run_episode(image: FmuImage, spec: RunSpec, instances: Instances | None = None) -> RunResult:
    """One impact episode: its row (`episode_columns` of the FMU's charge models), on an
    instance of `instances` (fmu/reuse.py: a task's, reset between its runs) or of its own."""
    wall0, cpu0 = time.perf_counter(), time.thread_time()
    md = image.model_description()
    charges, optional, read = episode_outputs(md)
    with instance_for(image, "tribo_impact", instances) as instance:
        try:
            instance.set_parameters(to_fmu(md, spec.params))
            instance.initialize(0.0)
            t_star = instance.get("t_star")
            instance.step_to(spec.t_end * t_star)
            end = instance.get_many(read)
            reached = instance.t
            instance.terminate()
        except FMICallException as e:
            raise RuntimeError(f"the impact episode failed: "
                               f"{failure(md, instance.messages, e)}") from None
    row = {name: end[name] for name in charges}
    u, v = end["u"], end["v"]
    row[AREA_COLUMN] = float(end.get(AREA_COLUMN, math.nan))
    row.update(rebound_u=u, rebound_v=v, rebound_speed=math.hypot(u, v),
               rebound_angle_deg=math.degrees(math.atan2(v, u)), rebound_omega=end["omega"],
               contact_time=end["contact_time"], lifted_off=int(end["lifted_off"]),
               end_reason=int(end["end_reason"]) if "end_reason" in end else math.nan,
               time_end=reached, t_star=t_star,
               cpu_s=time.thread_time() - cpu0, wall_s=time.perf_counter() - wall0)
    return RunResult(row, None)

"""A charge-per-impact map: the episodes of a grid over (impact speed, impact angle,
orientation, roundness) for a materials pair, run resumably (batch.sweep.run_sweep),
written as a table with its metadata, and the lookup a DEM or CFD wall model calls.

    <out>/episodes.csv     the runs, one row each as they finish (resumable)
    <out>/impact_map.csv   the map: the grid's axes (speed, angle_deg, phi0_deg, epsilon),
                           the episode's results (episode.episode_columns), in the grid's
                           order, then the set-up the charges depend on (SET_UP_COLUMNS:
                           materials, size, cylinder depth), the same on every row
    <out>/impact_map.json  metadata: the set-up (materials, size, cylinder depth, every SI
                           parameter set), the time limit, the grid, the FMU (name,
                           SHA-256, instantiation token, generation tool), the package
    <out>/impact_map.png   the figure, its title the set-up

    m = tribo.ImpactMap.load("out/impact_map")
    m("charge_static", speed=3.0, angle_deg=45.0, phi0_deg=10.0, epsilon=0.6)   # C per impact

The lookup interpolates linearly (scipy's RegularGridInterpolator) over the axes with more
than one value; an axis with one value takes only that value. A point outside the grid is
an error naming the axis and its range, never an extrapolation.
"""

import json
import os
from dataclasses import dataclass
from importlib import metadata as package_metadata

import numpy as np
import pandas as pd

from ..batch.grid import values_of
from ..batch.job import Job, Report
from ..batch.sweep import keys_of, run_sweep
from ..fmu import FmuImage
from ..fmu.charge_models import charge_models
from ..fmu.locate import find_fmu
from ..fmu.names import format_number, start_value
from ..fmu.parameters import check_values
from ..materials import material
from .episode import (AT_LIMIT, AT_REST, AXES, AXIS_UNITS, MODEL_PREFIXES, Grid,
                      episode_columns, episode_specs, run_episode)

EPISODES, TABLE, METADATA, FIGURE = "episodes.csv", "impact_map.csv", "impact_map.json", "impact_map.png"
# what a charge per impact depends on beyond the grid: the pair, the size, and the depth of
# the cylinder the 2D particle stands for (with grain_geometry = cylinder the charges in C
# scale with it; the spheroid's do not, nor does q/m)
SET_UP_COLUMNS = ["particle", "wall", "size", "cylinder_length"]
# the most episodes a Dask task holds: an episode costs the core about a third of a
# population's grain, and a task some milliseconds of CPU whatever it holds (docs/populations.md,
# "Benchmark")
EPISODES_PER_TASK = 64


@dataclass(kw_only=True)
class MapReport(Report):
    """The episodes' rows (`results`) and, once every episode has run, the map's table."""

    table: pd.DataFrame | None = None


def prepare_map(grid: Grid, particle: str, wall: str, settings: dict, limit: float,
                image: FmuImage, omega0: float = 0.0):
    """The episodes' runs, every value checked by the FMU before anything runs."""
    specs = episode_specs(grid, particle, wall, settings, limit, omega0)
    check_values(image, values_of(specs))
    return specs


def map_setup(grid: Grid, particle: str, wall: str, settings: dict, limit: float,
              omega0: float) -> dict:
    """What makes a map this one (an output folder's record, batch/folder.py)."""
    return {"particle": material(particle, "particle").key, "wall": material(wall, "wall").key,
            "settings": dict(settings), "time_limit_t_star": limit, "omega0_rad_s": omega0,
            "grid": grid.axes()}


def map_set_up(particle: str, wall: str, settings: dict, image: FmuImage) -> dict:
    """The set-up of a map's episodes: the materials, the size (m), the cylinder depth (m)
    and the grain's geometry as set or the FMU's defaults, then every other SI parameter
    set."""
    md = image.model_description()
    set_up = {"particle": material(particle, "particle").key, "wall": material(wall, "wall").key}
    for name in ("size", "cylinder_length", "grain_geometry"):
        set_up[name] = float(settings[name]) if name in settings else start_value(md, name)
    set_up.update({k: v for k, v in settings.items() if k not in set_up})
    return set_up


def set_up_title(set_up: dict) -> str:
    """The set-up in a line, for a figure's title."""
    # the charges in C are the spheroid's, or the cylinder's of its depth (docs/model.md §8c)
    grain = ("the spheroid's charge" if set_up.get("grain_geometry") != 0 else
             f"cylinder depth ℓ = {format_number(set_up['cylinder_length'])} m")
    return (f"{set_up['particle']} on {set_up['wall']}, size 2a = {format_number(set_up['size'])} m, "
            f"{grain}")


def ends_text(table: pd.DataFrame, limit: float) -> str:
    """How a map's episodes ended, in words: how many lifted off, came to rest on the plate
    (no rebound: their rebound columns are the state they rest in) and were still in contact
    at the time limit (t*); from `lifted_off` alone where the rows lack `end_reason`."""
    n = len(table)
    lifted = int((table["lifted_off"] != 0).sum())
    text = f"{lifted} of {n} episodes lifted off"
    reason = table["end_reason"] if "end_reason" in table.columns else None
    if reason is None or reason.isna().any():
        return text + f", {n - lifted} in sustained contact (at rest or at the time limit)"
    rest, held = int((reason == AT_REST).sum()), int((reason == AT_LIMIT).sum())
    return (text + f", {rest} came to rest on the plate (no rebound), {held} still in "
            f"contact at the time limit of {limit:g} t*")


def map_metadata(grid: Grid, particle: str, wall: str, settings: dict, limit: float,
                 omega0: float, image: FmuImage) -> dict:
    md = image.model_description()
    columns = episode_columns(charge_models(md))
    try:
        version = package_metadata.version("tribo")
    except package_metadata.PackageNotFoundError:
        version = None
    return {"particle": particle, "wall": wall, "set_up": map_set_up(particle, wall, settings, image),
            "settings": settings, "omega0_rad_s": omega0,
            "time_limit_t_star": limit,
            "grid": {a: {"values": list(getattr(grid, a)), "unit": AXIS_UNITS[a]} for a in AXES},
            "columns": {c: _unit(c) for c in columns + SET_UP_COLUMNS},
            "model": {"fmu": image.name, "fmu_sha256": image.sha256,
                      "instantiation_token": md.guid, "generation_tool": md.generationTool,
                      "package_version": version}}


def _unit(column: str) -> str:
    # the grain's charge: the spheroid's by default (docs/model.md section 8c)
    units = dict(zip(MODEL_PREFIXES, ("C per impact, the grain's: the spheroid's (grain_geometry "
                                      "1, the default); the cylinder's of depth cylinder_length "
                                      "with grain_geometry 0", "C/kg")))
    for prefix in sorted(units, key=len, reverse=True):  # charge_to_mass_ before charge_
        if column.startswith(prefix):
            return units[prefix]
    return {"rebound_u": "m/s", "rebound_v": "m/s",
            "rebound_speed": "m/s", "rebound_angle_deg": "deg from the surface",
            "rebound_omega": "rad/s", "contact_time": "s", "lifted_off": "1 (0: sustained contact)",
            "charged_area": "m2, the area the contact patch charged",
            "end_reason": "tribo.EndReason (2 lifted off, 3 at rest on the plate, 0 in contact "
                          "at the time limit)",
            "time_end": "s", "t_star": "s", "particle": "material", "wall": "material",
            "size": "m, the long diameter 2a",
            "cylinder_length": "m, the cylinder's depth (its charges with grain_geometry 0 "
                               "only)"}[column]


def run_impact_map(grid: Grid, particle: str, wall: str, settings: dict, limit: float,
                   image: FmuImage, out: str, executor, *, omega0: float = 0.0,
                   resume: bool = True, max_runs: int | None = None, progress: bool = True,
                   figure: bool = True, specs=None) -> MapReport:
    """The map's episodes on the executor (entered by the caller, or a SerialExecutor),
    then, once all have run, its table, metadata and figure."""
    specs = specs if specs is not None else prepare_map(grid, particle, wall, settings, limit,
                                                        image, omega0)
    os.makedirs(out, exist_ok=True)
    models = charge_models(image.model_description())
    columns = episode_columns(models)
    runs = run_sweep(specs, image, os.path.join(out, EPISODES), executor, resume=resume,
                     max_runs=max_runs, progress=progress, desc="episodes", run=run_episode,
                     result_columns=columns, task_runs=EPISODES_PER_TASK)
    report = MapReport(**vars(runs))
    report.files.append(os.path.join(out, EPISODES))
    if report.complete:
        by_key = report.results.set_index("key")
        points = pd.DataFrame(grid.points(), columns=list(AXES))
        table = pd.concat([points, by_key.loc[report.keys, columns].reset_index(drop=True)], axis=1)
        set_up = map_set_up(particle, wall, settings, image)
        report.table = table.assign(**{c: set_up[c] for c in SET_UP_COLUMNS})
        report.table.to_csv(os.path.join(out, TABLE), index=False)
        with open(os.path.join(out, METADATA), "w") as f:
            json.dump(map_metadata(grid, particle, wall, settings, limit, omega0, image), f, indent=2)
        report.files += [os.path.join(out, TABLE), os.path.join(out, METADATA)]
        if figure:
            # matplotlib only when a figure is drawn: `import tribo` stays without it
            from .plot import write_impact_figure
            title = f"charge per impact: {set_up_title(set_up)}"
            if (report.table["lifted_off"] == 0).any():
                title += f"\n{ends_text(report.table, limit)}"
            report.files.append(write_impact_figure(report.table, models, os.path.join(out, FIGURE),
                                                    title))
    return report


class MapJob(Job):
    """A charge-per-impact map into an output folder (batch/job.py's flow): the episodes of
    `grid` for the pair, `settings` (other SI parameters), the time limit (t*) and spin
    omega0, through the SI FMU `fmu`."""

    kind, noun, results_file = "impact map", "episode", EPISODES

    def __init__(self, grid: Grid, particle: str, wall: str, settings: dict, limit: float,
                 omega0: float = 0.0, fmu=None, *, figure: bool = True):
        self.grid, self.particle, self.wall = grid, particle, wall
        self.settings, self.limit, self.omega0, self.fmu = dict(settings), limit, omega0, fmu
        self.figure = figure
        self.keys = []

    def prepare(self) -> None:
        self.image = FmuImage.load(find_fmu(self.fmu, "si"))
        self.specs = prepare_map(self.grid, self.particle, self.wall, self.settings, self.limit,
                                 self.image, self.omega0)
        self.sha256 = self.image.sha256
        self.keys = keys_of(self.specs, self.image)

    def setup(self) -> dict:
        return map_setup(self.grid, self.particle, self.wall, self.settings, self.limit,
                         self.omega0)

    def describe(self, out: str, executor) -> str:
        return (f"impact map: {len(self.specs)} episodes of {self.particle} on {self.wall} into "
                f"{out}")

    def run(self, out: str, executor, *, progress: bool, max_runs: int | None) -> MapReport:
        return run_impact_map(self.grid, self.particle, self.wall, self.settings, self.limit,
                              self.image, out, executor, omega0=self.omega0, max_runs=max_runs,
                              progress=progress, figure=self.figure, specs=self.specs)


class ImpactMap:
    """A map's table and metadata, and the lookup (see the module's text)."""

    def __init__(self, table: pd.DataFrame, metadata: dict):
        missing = [a for a in AXES if a not in metadata.get("grid", {})]
        if missing:
            raise ValueError(f"the map's metadata has no axis {', '.join(missing)} (its axes: "
                             f"{', '.join(metadata.get('grid', {}))}, the package's are "
                             f"{', '.join(AXES)}): make the map again")
        # the looked-up quantities: the metadata's columns less the set-up
        self.columns = [c for c in metadata.get("columns", {}) if c not in SET_UP_COLUMNS]
        self.table = table
        self.metadata = metadata
        self.axes = {a: np.asarray(metadata["grid"][a]["values"], dtype=float) for a in AXES}
        self.varying = [a for a in AXES if len(self.axes[a]) > 1]
        shape = tuple(len(self.axes[a]) for a in AXES)
        if len(table) != int(np.prod(shape)):
            raise ValueError(f"the table has {len(table)} rows, the grid {int(np.prod(shape))} points")
        self._values = {c: table[c].to_numpy(dtype=float).reshape(shape) for c in self.columns}
        self._interpolators = {}

    @classmethod
    def load(cls, folder: str) -> "ImpactMap":
        """The map written into `folder` by run_impact_map (tribo impact-map --out)."""
        with open(os.path.join(folder, METADATA)) as f:
            meta = json.load(f)
        return cls(pd.read_csv(os.path.join(folder, TABLE)), meta)

    def _interpolator(self, quantity: str):
        # scipy only at the first lookup: `import tribo` stays without it
        from scipy.interpolate import RegularGridInterpolator

        if quantity not in self._values:
            raise KeyError(f"{quantity!r} is not a column of the map ({', '.join(self.columns)})")
        if quantity not in self._interpolators:
            values = self._values[quantity]
            index = tuple(slice(None) if a in self.varying else 0 for a in AXES)
            self._interpolators[quantity] = RegularGridInterpolator(
                [self.axes[a] for a in self.varying], values[index], method="linear",
                bounds_error=True) if self.varying else None
        return self._interpolators[quantity]

    @property
    def set_up(self) -> dict:
        """The materials, size (m), cylinder depth (m) and other SI parameters of the map."""
        return dict(self.metadata["set_up"])

    def __call__(self, quantity: str, speed, angle_deg, phi0_deg, epsilon):
        """The quantity (a column of the map, e.g. "charge_static" in C per impact) at the
        point(s): scalars or arrays that broadcast together."""
        point = dict(zip(AXES, np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                                     for v in (speed, angle_deg, phi0_deg, epsilon)))))
        for a in AXES:
            lo, hi = self.axes[a][0], self.axes[a][-1]
            outside = (point[a] < lo) | (point[a] > hi) | ~np.isfinite(point[a])
            if np.any(outside):
                bad = point[a][outside].flat[0]
                raise ValueError(f"{a} = {bad:g} is outside the map's grid [{lo:g}, {hi:g}] "
                                 f"({AXIS_UNITS[a]})")
        interpolator = self._interpolator(quantity)
        if interpolator is None:
            value = self._values[quantity].flat[0]
            return np.full(point["speed"].shape, value) if point["speed"].shape else float(value)
        shape = point["speed"].shape
        coords = np.stack([point[a].ravel() for a in self.varying], axis=-1)
        out = interpolator(coords).reshape(shape)
        return out if shape else float(out)

"""Each impact a DEM run reports, charged by the project's single-impact law: the impact
map of the pair (tribo.impact_map, docs/model.md sections 8c, 8d) for spheres (epsilon =
1: LIGGGHTS' grains are spheres), tabulated once per pair, settings and grain size and
kept on disk (`maps`, a folder of maps: a second run with the same pair finds them).

**The map.** Axes: speed SPEEDS (m/s), angle ANGLES (degrees from the surface), phi0 = 0,
epsilon = 1, for `sizes` grain diameters spread over the feed's (geometric, at most
SIZES). A lookup interpolates linearly in speed and angle (ImpactMap), and between two
sizes linearly in log size of the charge over the size squared (the patch's area grows as
the size squared at a given speed, section 8c). Below the slowest speed of the grid the
charge is the slowest's scaled by the speed (the largest patch grows linearly with the
normal speed, section 8c); below the shallowest angle, the shallowest angle at the same
normal speed; above the fastest speed, the fastest's scaled by the speed (counted in the
report's notes: grain-grain collisions can throw a grain faster than the device does).

**A grain's charge carried from impact to impact.** Between impacts the grain's charge is
taken spread evenly over its surface (the package's choice for repeated impacts, section
8d, tribo.repeated_impacts): the next impact charges its patch from that density towards
the pair's sigma0, so an impact of a grain carrying q gains `dq (1 - q / (sigma0 A_s))`,
dq the map's (uncharged grain), A_s = pi size^2 (the condenser law with complete transfer,
section 8c: dq = (sigma0 - sigma_init) A; tested there). A second impact on the spot an
earlier one charged is thus not recognised as such: the grain's charge is mixed over its
surface, the simplest such mixing (as for repeated_impacts). So after impacts dq_k,
q = Q (1 - prod_k (1 - dq_k / Q)), Q = sigma0 A_s. The gas's limits (sections 8b, 8e) are
the maps' only (each impact's dq is held at its patch's limit): a chute's grains stay far
below the grain's own limit, and a spot's later contacts are not told apart (docs/dem.md:
at the table's sigma0 the chute model's rolling band raises the impacts' spots to sigma0,
which this composition does not).

**Sustained contact.** A grain that comes to rest on the plate or rolls on it (a contact
that lasts: contacts.py's `sustained`) keeps touching it under its own weight, and in the
model every point of its great circle comes into contact as it rolls: the band of the
model's patch under its weight (section 8c: half-width S = sqrt(a delta_w) across, with
the model's own indentation under the weight, delta_w = m' g cos(tilt) / k', m' = rho pi
a^2 the lamina's mass per length, k' = (pi/4) E*, section 8) all round it charges once:
`sigma0 2 pi a 2 S`, carried like an impact's gain (the module's next paragraph). An
impact's map charge does not hold it: an episode ends at its first lift-off. The grain
rolls many times its circumference on a chute; a shorter roll is not told apart.

**Restitution.** The DEM's normal restitution is the model's: the map's rebound over
impact normal speed, head-on, at the feed's first landing speed, for the median size.
"""

import hashlib
import json
import math
import os

import numpy as np
import pandas as pd

from ..batch.executors import SerialExecutor
from ..batch.folder import claim
from ..batch.job import check_writable_dir, execute
from ..impact.episode import Grid
from ..impact.map import ImpactMap, MapJob

SPEEDS = (0.05, 0.1, 0.2, 0.4, 0.7, 1.0, 1.5, 2.5)  # m/s
ANGLES = (5.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0)  # degrees from the surface
SIZES = 4  # the most grain sizes a feed's maps are made for


def map_sizes(sizes: np.ndarray) -> np.ndarray:
    """The grain diameters the maps are made for: the feed's range, geometric, SIZES at
    most (one where all grains are one size)."""
    lo, hi = float(np.min(sizes)), float(np.max(sizes))
    if hi <= lo * (1 + 1e-9):
        return np.array([lo])
    return np.geomspace(lo, hi, SIZES)


def map_folder(maps: str, particle: str, wall: str, settings: dict, size: float, fmu) -> str:
    """The folder of one map in the cache `maps`: named by what makes it."""
    what = json.dumps({"particle": particle, "wall": wall, "settings": settings,
                       "size": float(size), "speeds": SPEEDS, "angles": ANGLES,
                       "fmu": str(fmu)}, sort_keys=True)
    digest = hashlib.sha256(what.encode()).hexdigest()[:12]
    return os.path.join(maps, f"{particle}-{wall}-{size:.4g}m-{digest}")


def _current(folder: str, fmu_sha256: str | None) -> bool:
    """Whether `folder` holds a finished map of the FMU of that SHA-256 (any, if None)."""
    try:
        with open(os.path.join(folder, "impact_map.json")) as f:
            made_by = json.load(f)["model"]["fmu_sha256"]
    except (OSError, ValueError, KeyError):
        return False
    return os.path.exists(os.path.join(folder, "impact_map.csv")) and (
        fmu_sha256 is None or made_by == fmu_sha256)


def make_map(job: MapJob, folder: str, executor=None):
    """The map's job into its folder (batch/job.py's flow) on `executor`, entered by the
    caller (the DEM job's), or in this process."""
    if executor is None:
        return execute(job, folder, SerialExecutor(), progress=False)
    job.prepare()
    check_writable_dir(folder)
    with claim(folder, job.kind, job.setup(), job.sha256, False):
        return job.run(folder, executor, progress=False, max_runs=None)


class Charger:
    """The maps of a pair for a feed's sizes, and the charging of impacts (module's text)."""

    def __init__(self, particle: str, wall: str, settings: dict, sizes, maps: str, fmu=None,
                 say=None, executor=None, fmu_sha256: str | None = None):
        self.sizes = map_sizes(np.asarray(sizes, dtype=float))
        grid = Grid.of(speed=SPEEDS, angle_deg=ANGLES, phi0_deg=(0.0,), epsilon=(1.0,))
        self.maps, self.built = [], 0
        for size in self.sizes:
            folder = map_folder(maps, particle, wall, settings, size, fmu)
            if not _current(folder, fmu_sha256):  # missing, or another FMU's: made (again)
                if say:
                    say(f"dem: tabulating the impact map of {particle} on {wall}, size "
                        f"{size:.4g} m, into {folder} (once)")
                report = make_map(MapJob(grid, particle, wall, dict(settings, size=float(size)),
                                         200.0, 0.0, fmu, figure=False), folder, executor)
                if report.failed:
                    raise RuntimeError(f"the impact map of size {size:.4g} m failed: "
                                       f"{report.failed[0][1]}")
                self.built += 1
            self.maps.append(ImpactMap.load(folder))
        self.models = [c.removeprefix("charge_") for c in self.maps[0].columns
                       if c.startswith("charge_") and not c.startswith("charge_to_mass_")]

    def restitution(self, speed: float) -> float:
        """The model's normal restitution head-on at `speed` (m/s), the median size's map."""
        m = self.maps[len(self.maps) // 2]
        v = min(max(speed, SPEEDS[0]), SPEEDS[-1])
        return float(m("rebound_v", v, 90.0, 0.0, 1.0)) / v

    def _lookup(self, quantity: str, k: int, normal, tangential) -> np.ndarray:
        """Map k's quantity at the impacts (the module's text: the grid's edges)."""
        speed = np.hypot(normal, tangential)
        angle = np.degrees(np.arctan2(normal, tangential))
        shallow = angle < ANGLES[0]
        speed = np.where(shallow, normal / math.sin(math.radians(ANGLES[0])), speed)
        angle = np.clip(angle, ANGLES[0], ANGLES[-1])
        scale = np.where(speed < SPEEDS[0], speed / SPEEDS[0],
                         np.where(speed > SPEEDS[-1], speed / SPEEDS[-1], 1.0))
        inside = np.clip(speed, SPEEDS[0], SPEEDS[-1])
        return np.asarray(self.maps[k](quantity, inside, angle, 0.0, 1.0)) * scale

    def charge(self, quantity: str, size, normal, tangential) -> np.ndarray:
        """The map's `quantity` (charge_<model>, C) of impacts of grains of diameter `size`
        at normal and tangential speeds (m/s): an uncharged grain's gain."""
        size, normal, tangential = (np.asarray(a, dtype=float) for a in (size, normal, tangential))
        if len(self.sizes) == 1:
            return self._lookup(quantity, 0, normal, tangential) * (size / self.sizes[0]) ** 2
        x = np.log(self.sizes)
        j = np.clip(np.searchsorted(x, np.log(size)) - 1, 0, len(x) - 2)
        w = np.clip((np.log(size) - x[j]) / (x[j + 1] - x[j]), 0.0, 1.0)
        out = np.zeros_like(size)
        for k in np.unique(j):
            at = j == k
            lo = self._lookup(quantity, k, normal[at], tangential[at]) / self.sizes[k] ** 2
            hi = self._lookup(quantity, k + 1, normal[at], tangential[at]) / self.sizes[k + 1] ** 2
            out[at] = ((1 - w[at]) * lo + w[at] * hi) * size[at] ** 2
        return out


def carried(grain: np.ndarray, gains: np.ndarray, saturation: np.ndarray, n: int) -> np.ndarray:
    """Each grain's charge after its impacts' gains (an uncharged grain's each), the charge
    carried spread over the surface (the module's text): Q (1 - prod (1 - dq/Q)),
    `saturation` Q = sigma0 A_s per grain."""
    out = np.zeros(n)
    if len(grain) == 0:
        return out
    q_sat = saturation[grain]
    keep = np.log1p(-np.clip(gains / q_sat, None, 1.0 - 1e-15))
    total = np.bincount(grain, weights=keep, minlength=n)
    return saturation * -np.expm1(total)


def band_charge(size: np.ndarray, density: float, effective_modulus: float, tilt_deg: float,
                sigma0: float) -> np.ndarray:
    """The charge (C) of the band a grain rolling on the plate brings into contact under
    its weight (the module's text), per grain of diameter `size` (m); E* in Pa (the
    materials', docs/model.md section 8)."""
    a = np.asarray(size, dtype=float) / 2.0
    delta = density * math.pi * a ** 2 * 9.81 * math.cos(math.radians(tilt_deg)) / (
        math.pi / 4.0 * effective_modulus)
    return sigma0 * 2.0 * math.pi * a * 2.0 * np.sqrt(a * delta)


def charges(charger: Charger, found: pd.DataFrame, size: np.ndarray, sigma0: float,
            band: np.ndarray | None = None) -> dict:
    """Per charge model, each grain's charge (C) after its impacts `found` (contacts.py),
    its diameter `size` (m), the pair's sigma0 (C/m2); `band`: each grain's sustained
    contact's charge (band_charge), gained by those with a sustained contact."""
    n = len(size)
    grain = found["grain"].to_numpy(dtype=np.int64)
    saturation = sigma0 * math.pi * size ** 2
    rolled = np.zeros(0, dtype=np.int64)
    if band is not None and len(found):
        rolled = np.unique(grain[found["sustained"].to_numpy() != 0])
    out = {}
    for model in charger.models:
        gains = charger.charge(f"charge_{model}", size[grain], found["normal_speed"].to_numpy(),
                               found["tangential_speed"].to_numpy()) if len(grain) else np.zeros(0)
        out[model] = carried(np.r_[grain, rolled],
                             np.r_[gains, band[rolled] if len(rolled) else np.zeros(0)],
                             saturation, n)
    return out

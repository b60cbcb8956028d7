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

**A grain's charge account** (docs/model.md section 8e, the grain's charge of section 8c;
`account`). Each impact k of a grain brings its patch, of area A_k (the map's
`charged_area`), to the density s_k = dq_k / A_k the map's impact leaves on an uncharged
grain (dq_k its charge): the contact's sigma0, or the gas's limit sigma_P(L_e) of the
patch's region where that is lower (section 8e; the map holds it). Between impacts the
grain's charge q is taken spread evenly over its surface A_s (the package's choice for
repeated impacts, section 8d, tribo.repeated_impacts): the patch held q A_k / A_s before, so
the impact gains `(s_k - q / A_s) A_k = dq_k (1 - q / (s_k A_s))`: its fresh share of the
surface, the area already charged counted as the charge carried over the density the patch
keeps. The grain's charge never passes its own limit |q| <= sigma_P(R_s) A_s (section 8e;
R_s the radius of the sphere of area A_s, here the grain's own): a gain that would raise it
further is lost to the gas. With the FMU's breakdown_model = fixed (section 8b) the
limit is breakdown_density A_s (none at 0), as the map's patches are held at
breakdown_density. **The charge lost to the gas**, per grain (`lost`, of sigma0's sign):
each patch's relaxation, what the contact left above what the patch keeps, (sigma0 - s_k)
A_k (the static model with complete transfer, the SI default charging_time 0, section 5c;
for the sliding model, whose saturation rises above sigma0 with the work, a lower bound),
and what the grain's limit took back.

**Sustained contact.** A grain that comes to rest on the plate or rolls on it (a contact
that lasts: contacts.py's `sustained`) keeps touching it under its own weight, and in the
model every point of its great circle comes into contact as it rolls: the band of the
model's patch under its weight (section 8c: half-width S = sqrt(a delta_w) across, with
the model's own indentation under the weight, delta_w = m' g cos(tilt) / k', m' = rho pi
a^2 the lamina's mass per length, k' = (pi/4) E*, section 8) all round it, of area
2 pi a 2 S, charges once, at its first sustained contact, by the same account as an
impact: its density the contact's sigma0 or the gas's limit of its region, the equal-area
radius of the patch under the weight, S (section 8e's choice for a rolling episode), where
that is lower. An impact's map charge does not hold it: an episode ends at its first
lift-off. The grain rolls many times its circumference on a chute; a shorter roll is not
told apart.

**Restitution.** The DEM's normal restitution is the model's: the map's rebound over
impact normal speed, head-on, at the feed's first landing speed, for the median size.
"""

import hashlib
import json
import math
import os
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..batch.executors import SerialExecutor
from ..batch.folder import claim
from ..batch.job import check_writable_dir, execute
from ..fmu.names import start_value
from ..impact.episode import AREA_COLUMN as AREA, Grid
from ..impact.map import ImpactMap, MapJob
from ..paschen import AIR, Gas
from ..paschen import limit as paschen_limit

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


ROUNDING = 1e-9  # relative: a patch's density within this of sigma0 is at sigma0
LIMIT_NODES = 32  # per decade of radius: the gas's limit tabulated, interpolated in log-log


@dataclass(frozen=True)
class GasLimits:
    """The gas's limits the FMU's map was made under (the module's text): section 8e's
    sigma_P of a region (`paschen`, of `gas`, at a conducting or insulating wall) or section
    8b's fixed breakdown_density (0: none)."""

    paschen: bool
    gas: Gas = AIR
    conducting: bool = True
    breakdown_density: float = 0.0

    @classmethod
    def of(cls, md, params: dict) -> "GasLimits":
        """The limits of a run's SI parameters `params`, the rest the FMU's start values."""
        def value(name):
            v = params.get(name, start_value(md, name))
            return None if v is None else float(v)
        model = value("breakdown_model")
        return cls(model is not None and int(model) == 1, Gas.of(params, md),
                   bool(value("wall_conducting") if value("wall_conducting") is not None else 1),
                   value("breakdown_density") or 0.0)

    def density(self, radius) -> np.ndarray:
        """The highest density (C/m2) a charged region of radius `radius` (m) keeps."""
        radius = np.asarray(radius, dtype=float)
        if not self.paschen:
            return np.full(radius.shape, self.breakdown_density if self.breakdown_density > 0
                           else math.inf)
        # sigma_P is smooth in log-log (section 8e's table): nodes over the radii asked for
        lo, hi = float(np.min(radius)), float(np.max(radius))
        count = max(2, int(math.ceil(LIMIT_NODES * math.log10(hi / lo))) + 1) if hi > lo else 1
        nodes = np.geomspace(lo, hi, count)
        values = np.log([paschen_limit(float(r), self.gas, self.conducting) for r in nodes])
        if count == 1:
            return np.full(radius.shape, math.exp(values[0]))
        return np.exp(np.interp(np.log(radius), np.log(nodes), values))

    def grain(self, size) -> np.ndarray:
        """Each sphere's own limit (C, positive; inf where none): the density of a region
        of the grain's own radius over its surface, sigma_P(R_s) A_s (section 8e), or the
        fixed cap's over it (section 8b)."""
        size = np.asarray(size, dtype=float)
        return self.density(size / 2.0) * math.pi * size ** 2


def account(grain: np.ndarray, gain: np.ndarray, area: np.ndarray, surface: np.ndarray,
            ceiling: np.ndarray, sigma0: float) -> tuple[np.ndarray, np.ndarray]:
    """Each grain's charge and the charge it lost to the gas (C, per grain: the module's
    text) after its events in order: event k of grain `grain[k]` (grains 0..len(surface)-1,
    each grain's events in the order they happened) leaves its patch of `area[k]` (m2) at
    the density gain[k] / area[k], gain[k] the charge it gives an uncharged grain (C);
    `surface` A_s (m2) and `ceiling` (C, positive) per grain; sigma0 the contact's own
    density (C/m2)."""
    n = len(surface)
    q, lost = np.zeros(n), np.zeros(n)
    grain = np.asarray(grain, dtype=np.int64)
    if len(grain) == 0:
        return q, lost
    if np.any(np.diff(grain) < 0):
        order = np.argsort(grain, kind="stable")
        grain, gain, area = grain[order], np.asarray(gain)[order], np.asarray(area)[order]
    gain, area = np.asarray(gain, dtype=float), np.asarray(area, dtype=float)
    # each event's place in its grain's sequence: the grains' k-th events at once
    first = np.r_[0, np.flatnonzero(np.diff(grain)) + 1]
    rank = np.arange(len(grain)) - np.repeat(first, np.diff(np.r_[first, len(grain)]))
    # the patch's relaxation: what the contact (sigma0) left above what the patch keeps (a
    # patch at sigma0 itself, interpolated in the map as sigma0 times its area, to rounding)
    relaxed = np.where(np.abs(sigma0 * area) > np.abs(gain) * (1 + ROUNDING),
                       sigma0 * area - gain, 0.0)
    lost += np.bincount(grain, weights=relaxed, minlength=n)
    for r in range(int(rank.max()) + 1):
        at = rank == r
        g, dq, a = grain[at], gain[at], area[at]
        # section 8e: the patch from the grain's mean density to the density it keeps
        new = q[g] + dq - q[g] / surface[g] * a
        # section 8e: the grain's own limit, the excess lost to the gas
        held = np.clip(new, -ceiling[g], ceiling[g])
        lost[g] += new - held
        q[g] = held
    return q, lost


def band(size: np.ndarray, density: float, effective_modulus: float, tilt_deg: float,
         sigma0: float, limits: GasLimits) -> tuple[np.ndarray, np.ndarray]:
    """The area (m2) of the band a grain rolling on the plate brings into contact under its
    weight and the charge it takes on an uncharged grain (C; the module's text), per grain
    of diameter `size` (m); E* in Pa (the materials', docs/model.md section 8)."""
    a = np.asarray(size, dtype=float) / 2.0
    delta = density * math.pi * a ** 2 * 9.81 * math.cos(math.radians(tilt_deg)) / (
        math.pi / 4.0 * effective_modulus)
    half_width = np.sqrt(a * delta)
    area = 2.0 * math.pi * a * 2.0 * half_width
    # section 8e: the rolling episode's region, the patch under the weight (Sc = S_perp)
    kept = np.minimum(abs(sigma0), limits.density(half_width))
    return area, math.copysign(1.0, sigma0) * kept * area


def charges(charger: Charger, found: pd.DataFrame, size: np.ndarray, sigma0: float,
            limits: GasLimits, rolled_band: tuple | None = None) -> dict:
    """Per charge model, (each grain's charge, the charge it lost to the gas), C, after its
    impacts `found` (contacts.py, in time order per grain), its diameter `size` (m), the
    pair's sigma0 (C/m2), the gas's `limits`; `rolled_band`: band()'s area and charge per
    grain, taken once at a grain's first sustained contact."""
    n = len(size)
    grain = found["grain"].to_numpy(dtype=np.int64)
    order = np.lexsort((found["time"].to_numpy(), grain)) if len(grain) else np.zeros(0, int)
    grain = grain[order]
    normal = found["normal_speed"].to_numpy()[order]
    tangential = found["tangential_speed"].to_numpy()[order]
    area = charger.charge(AREA, size[grain], normal, tangential) if len(grain) else np.zeros(0)
    # the band after the grain's first sustained contact: an event of its own
    at = np.zeros(0, dtype=np.int64)
    if rolled_band is not None and len(grain):
        sustained = found["sustained"].to_numpy()[order] != 0
        if "wall" in found:  # the plate's (a feeder's side walls are not rolled on)
            sustained &= found["wall"].to_numpy()[order] == 0
        first = np.flatnonzero(sustained)
        first = first[np.r_[True, grain[first][1:] != grain[first][:-1]]] if len(first) else first
        at = first + 1  # inserted after it
    events = np.insert(grain, at, grain[at - 1]) if len(at) else grain
    surface = math.pi * size ** 2
    ceiling = limits.grain(size)
    out = {}
    for model in charger.models:
        gains = charger.charge(f"charge_{model}", size[grain], normal, tangential) \
            if len(grain) else np.zeros(0)
        g, a = gains, area
        if len(at):
            owner = grain[at - 1]
            g = np.insert(gains, at, rolled_band[1][owner])
            a = np.insert(area, at, rolled_band[0][owner])
        out[model] = account(events, g, a, surface, ceiling, sigma0)
    return out

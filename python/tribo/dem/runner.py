"""A DEM-coupled population into a folder: n grains drawn from a population's feed
(populations/feed.py) as spheres, moved through the device by LIGGGHTS (a separate
process, engine.py), each grain-wall impact read from its output (contacts.py) and charged
by the project's impact map (charging.py); the exit stream written as a population's.

    <out>/particles.csv   a row per grain, a population's columns (populations/feed.py:
                          the materials, every parameter of its run, exited, exit_time,
                          u, v, exit_speed, omega, charge_<model>, charge_to_mass_<model>,
                          capped_fraction_<model> (empty: the DEM's grain has no
                          segments), charge_lost_<model> (C, to the gas: charging.py),
                          contact_fraction, impacts, fraction_<motion> (empty: LIGGGHTS does
                          not classify the motion), cpu_s and wall_s (the coupled run's
                          per grain), and its key, as the population's grain of the same
                          draw has it
    <out>/impacts.csv     a row per impact (contacts.py's columns, the wall it met: 0 the
                          plate, 1 a feeder's side wall, and its charge gain by each model
                          for an uncharged grain, C); particles.csv's `impacts` count the
                          plate's, a feeder's `side_impacts` the side walls'.
    <out>/summary.csv, population.png, population.json   as a population's
    <out>/liggghts/       the LIGGGHTS run: its input, the plate's STL, its outputs and log

Grain-grain collisions are LIGGGHTS' (the grains bounce off each other); they transfer no
charge: only grain-wall impacts charge.
"""

import json
import math
import os
import re
import shutil
import time
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..batch.job import Job, Report
from ..batch.specs import RunSpec, run_key
from ..fmu import FmuImage
from ..fmu.charge_models import charge_models
from ..fmu.locate import find_fmu
from ..fmu.names import format_number, start_value
from ..fmu.parameters import check_values
from ..populations.feed import (STEPS_PER_RUN, Feed, draw, particle_parameters, result_columns)
from ..populations.runner import FIGURE, METADATA, PARTICLES, SUMMARY
from ..populations.summary import check_class_edges, summarize_population
from . import contacts, engine, script
from .charging import Charger, GasLimits, band, charges
from .device import Chute, DeviceError, entries

IMPACTS = "impacts.csv"
REFERENCE_IMPACTS = "reference_impacts.csv"  # the dense reference's (reference_every)
STOPPED = "stopped.json"  # a run stopped by a signal: its settings, CPU so far, parts run
RUN_FOLDER = "liggghts"
SLOWEST = 1e-3  # m/s: contacts slower along the normal are not written (contacts.py)
PLATE_WALL, SIDE_WALL = 0, 1  # impacts.csv's `wall`: the plate's impact or a side wall's


class DemError(ValueError):
    """A DEM job that cannot run as asked (the message, one line, names the value)."""


@dataclass(kw_only=True)
class DemReport(Report):
    summary: pd.DataFrame | None = None
    impacts: pd.DataFrame | None = None
    dem_cpu_s: float = math.nan
    charging_cpu_s: float = math.nan
    maps_built: int = 0


def _spheres(feed: Feed) -> None:
    d = feed.resolved()["epsilon"]
    text = d.text()
    if feed.measured is not None and "epsilon" in feed.measured.columns:
        raise DemError("epsilon: measured roundness is not taken: LIGGGHTS' grains here are "
                       "spheres (give --epsilon 1)")
    try:
        value = float(text)
    except ValueError:
        value = None
    if value != 1.0:
        raise DemError(f"epsilon = {text}: LIGGGHTS' grains here are spheres, epsilon 1 "
                       f"(give --epsilon 1)")


class DemJob(Job):
    """n grains of `feed` (spheres) through the chute in LIGGGHTS, charged by the impact
    map (the module's text). feed_rate None: the dilute limit (a lane each, all dropped at
    once); else grains/s into `lanes` lanes. vibration (amplitude m, frequency Hz[, the
    stroke's angle from the plate in degrees, 90 by default: along its normal]): a feeder,
    the plate and its side walls moved along the stroke (device.py). ranks: LIGGGHTS' MPI
    ranks. stiffness_scale: the Young's moduli LIGGGHTS takes, as a fraction of the
    materials' (a larger time step; the charges are the map's, at the impact speeds). maps:
    the folder the impact maps are kept in. law, law_properties: LIGGGHTS' contact law and
    the properties it reads (script.py; by default its Hertz-Mindlin law), for comparing
    laws. reference_every: LIGGGHTS also writes the contacts every that many steps
    (script.REFERENCE), whose impacts go to reference_impacts.csv, to check the sampling
    against (contacts.compare_impacts, scripts/check_dem_sampling.sh)."""

    kind, noun, results_file = "dem", "grain", PARTICLES

    def __init__(self, feed: Feed, n: int, seed: int = 0, t_end: float = 5.0, fmu=None, *,
                 feed_rate: float | None = None, lanes: int | None = None,
                 lane_spacing: float | None = None, vibration: tuple | None = None,
                 ranks: int = 1, stiffness_scale: float = 1.0,
                 maps: str = os.path.join("out", "impact-maps"), figure: bool = True,
                 shape_edges=None, size_edges=None, law: str = script.LAW,
                 law_properties: tuple = (), reference_every: int | None = None):
        self.feed, self.n, self.seed, self.t_end, self.fmu = feed, n, seed, t_end, fmu
        self.feed_rate, self.lanes, self.lane_spacing = feed_rate, lanes, lane_spacing
        self.vibration = tuple(vibration) if vibration else None
        if self.vibration is not None and len(self.vibration) == 2:
            self.vibration += (90.0,)
        self.ranks, self.stiffness_scale, self.maps = ranks, stiffness_scale, maps
        self.figure, self.shape_edges, self.size_edges = figure, shape_edges, size_edges
        self.law, self.law_properties = law, tuple(law_properties)
        self.reference_every = reference_every
        self.keys = []

    def prepare(self) -> None:
        if isinstance(self.ranks, bool) or not isinstance(self.ranks, int) or self.ranks < 1:
            raise DemError(f"ranks = {self.ranks!r}: LIGGGHTS' MPI ranks, a whole number >= 1")
        s = self.stiffness_scale
        if not (isinstance(s, (int, float)) and math.isfinite(s) and 0 < s <= 1):
            raise DemError(f"stiffness_scale = {s!r}: the fraction of the Young's moduli "
                           f"LIGGGHTS takes, in (0, 1]")
        if not (isinstance(self.t_end, (int, float)) and math.isfinite(self.t_end) and self.t_end > 0):
            raise DemError(f"t_end = {self.t_end!r}: the horizon in s, a positive number")
        r = self.reference_every
        if r is not None and (isinstance(r, bool) or not isinstance(r, int) or r < 1):
            raise DemError(f"reference_every = {r!r}: the reference's sample interval in "
                           f"steps, a whole number >= 1")
        if self.lanes is not None and self.feed_rate is None:
            raise DemError(f"lanes = {self.lanes!r}: the lanes of a fed stream, taken with a "
                           f"feed rate only (the dilute limit gives each grain its own)")
        for name, text in (("law", self.law), *(("law_properties", p) for p in self.law_properties)):
            if not isinstance(text, str) or not text.strip() or "\n" in text:
                raise DemError(f"{name} = {text!r}: words of one line of LIGGGHTS' input "
                               f"(the contact law's, or a property it reads)")
        _spheres(self.feed)
        check_class_edges(self.shape_edges, self.size_edges)
        if self.vibration is not None and len(self.vibration) != 3:
            raise DemError(f"vibration = {self.vibration!r}: the amplitude (m), the frequency "
                           f"(Hz) and the stroke's angle from the plate (degrees)")
        amplitude, frequency, angle = self.vibration or (0.0, 0.0, 90.0)
        chute = self.feed.describe()["chute"]
        self.chute = Chute(chute["chute_length"], chute["tilt_deg"], amplitude=amplitude,
                           frequency=frequency, angle_deg=angle)
        self.image = FmuImage.load(find_fmu(self.fmu, "si"))
        md = self.image.model_description()
        depth = start_value(md, "cylinder_length")
        self.drawn = draw(self.feed, self.n, self.seed)
        self.params = particle_parameters(self.feed, self.drawn, {"cylinder_length": depth})
        check_values(self.image, {k: [p[k] for p in self.params] for k in self.params[0]})
        self._check_horizon()
        self.entry = entries(self.chute, self.drawn["size"].to_numpy(), self.drawn["drop_height"],
                             self.drawn["drop_speed"], self.drawn["drop_angle_deg"],
                             self.feed_rate, self.lanes, self.lane_spacing)
        if not (self.drawn["omega0"] == 0).all():
            raise DemError("omega0: the grains enter without spin here (give --omega0 0)")
        engine.command(self.ranks)
        self.sha256 = self.image.sha256
        specs = [RunSpec(p, float(self.t_end), float(self.t_end) / STEPS_PER_RUN) for p in self.params]
        self.keys = [run_key(s, self.sha256) for s in specs]
        self.models = charge_models(md)

    def _contact(self, restitution: float) -> script.Contact:
        """LIGGGHTS' contact law of the feed's pair (script.py) with `restitution`."""
        p0, md = self.params[0], self.image.model_description()
        return script.Contact(
            p0["youngs_modulus_particle"] * self.stiffness_scale, p0["poisson_ratio_particle"],
            p0["youngs_modulus_wall"] * self.stiffness_scale, p0["poisson_ratio_wall"],
            p0["density"], restitution, p0.get("mu", start_value(md, "mu")),
            p0.get("mu_roll", start_value(md, "mu_roll")))

    def _check_horizon(self) -> None:
        """DemError, before anything runs, for a horizon of more steps than LIGGGHTS runs:
        the time step is at most a fraction of the smallest grain's Rayleigh time
        (script.time_step), which the restitution does not change."""
        smallest = float(np.min(self.drawn["size"]))
        longest_step = script.RAYLEIGH_FRACTION * script.rayleigh_time(smallest, self._contact(0.5))
        if self.t_end / longest_step > script.MAX_STEPS:
            raise DemError(f"t_end = {self.t_end:g}: the horizon in s, at most "
                           f"{script.MAX_STEPS * longest_step:.3g} s here: at a time step of "
                           f"{longest_step:.3g} s or less it is above the {script.MAX_STEPS} "
                           f"steps LIGGGHTS runs")

    def setup(self) -> dict:
        return {"n": self.n, "seed": self.seed, "t_end_s": self.t_end, "feed": self.feed.describe(),
                "feed_rate": self.feed_rate, "lanes": self.lanes, "lane_spacing": self.lane_spacing,
                "vibration": list(self.vibration) if self.vibration else None,
                "ranks": self.ranks, "stiffness_scale": self.stiffness_scale, **self._law()}

    def _law(self) -> dict:
        """The contact law where it is not the default (a folder of a default run stays
        valid)."""
        if (self.law, self.law_properties) == (script.LAW, ()):
            return {}
        return {"law": [self.law, *self.law_properties]}

    def describe(self, out: str, executor) -> str:
        how = ("dilute: a lane each, dropped at once" if self.feed_rate is None
               else f"{format_number(self.feed_rate)} grains/s")
        return (f"dem: {self.n} grains of {self.feed.particle} on {self.feed.wall} (seed "
                f"{self.seed}, {how}) through LIGGGHTS on {self.ranks} rank(s) into {out}")

    def kept(self, out: str) -> str:
        return ("LIGGGHTS' run up to its restart file (the same command resumes from it) "
                f"and the impact maps made, in {self.maps}")

    def run(self, out: str, executor, *, progress: bool, max_runs: int | None) -> DemReport:
        wall0 = time.perf_counter()
        say = (lambda line: print(line, flush=True)) if progress else None
        settings = {k: v for k, v in self.feed.settings.items()}
        charger = Charger(self.feed.particle, self.feed.wall, settings, self.drawn["size"],
                          self.maps, self.fmu, say=say, executor=executor,
                          fmu_sha256=self.sha256)
        size = self.drawn["size"].to_numpy(dtype=float)
        p0 = self.params[0]
        md = self.image.model_description()
        # the model's own restitution, friction and rolling resistance (script.py)
        first = float(np.median(np.sqrt(2 * 9.81 * math.cos(math.radians(self.chute.tilt_deg))
                                        * self.drawn["drop_height"])))
        contact = self._contact(min(max(charger.restitution(first), 0.05), 0.95))
        g = 9.81
        # the fastest impact: a free fall from the drop to the chute's end, onto a plate
        # coming up at its vibration's fastest
        fastest = float(self.chute.amplitude * 2 * math.pi * self.chute.frequency
                        + np.max(self.drawn["drop_speed"]) + math.sqrt(
            2 * g * (float(np.max(self.drawn["drop_height"])) + self.chute.chute_length
                     * math.sin(math.radians(self.chute.tilt_deg)))))
        dt, every = script.time_step(size, fastest, contact, script.SAMPLES_PER_CONTACT
                                     if self.chute.amplitude else
                                     script.STILL_SAMPLES_PER_CONTACT)
        near = 2.0 * fastest * every * dt
        folder = os.path.join(out, RUN_FOLDER)
        done_path = os.path.join(folder, engine.DONE)
        run = {"dt": dt, "sample_every": every, "exit_every": max(1, int(1e-4 / dt)),
               "near": near, "slowest": SLOWEST, "restitution": contact.restitution,
               "friction": contact.friction, "rolling_friction": contact.rolling_friction,
               "youngs_modulus_particle": contact.youngs_particle,
               "youngs_modulus_wall": contact.youngs_wall, "ranks": self.ranks}
        if self.chute.amplitude:  # a feeder: its stroke, and its side walls
            run["vibration"] = list(self.vibration)
        run.update(self._law())
        if self.reference_every:
            run["reference_every"] = self.reference_every
        previous = _read(done_path)
        if previous is None or previous.get("run") != run:
            previous = self._simulate(folder, run, size, contact, progress, wall0)
        cpu0 = time.process_time()
        gravity = tuple(9.81 * c for c in self.chute.gravity_vector)
        walls = [contacts.Wall(gravity, self.chute, others=bool(self.chute.amplitude))]
        if self.chute.amplitude:  # the feeder's side walls: charged alike, counted apart
            walls.append(contacts.Wall(gravity, self.chute, side=True,
                                       half_width=self.entry.width / 2, others=True))
        found = self._impacts(os.path.join(folder, script.CONTACTS), dt, every, walls)
        left = contacts.exits(os.path.join(folder, script.EXITS), dt, self.chute.chute_length, self.n)
        sigma0 = float(p0["sigma0"])
        # the materials' own moduli (not LIGGGHTS' scaled ones): the model's indentation
        modulus = script.effective_modulus(p0["youngs_modulus_particle"],
                                           p0["poisson_ratio_particle"],
                                           p0["youngs_modulus_wall"], p0["poisson_ratio_wall"])
        limits = GasLimits.of(md, p0)
        rolled = band(size, p0["density"], modulus, self.chute.tilt_deg, sigma0, limits)
        charged = charges(charger, found, size, sigma0, limits, rolled)
        for model in charger.models:
            grains = found["grain"].to_numpy(dtype=np.int64)
            found[f"gain_{model}"] = charger.charge(
                f"charge_{model}", size[grains], found["normal_speed"].to_numpy(),
                found["tangential_speed"].to_numpy()) if len(found) else []
        charging_cpu = time.process_time() - cpu0
        report = self._rows(out, found, left, charged, size, previous, charging_cpu,
                            time.perf_counter() - wall0)
        report.maps_built = charger.built
        if self.reference_every:
            path = os.path.join(out, REFERENCE_IMPACTS)
            # its contacts joined across a turn as the sampling's are (contacts.py)
            self._impacts(os.path.join(folder, script.REFERENCE), dt, self.reference_every,
                          walls, joined=2 * every).to_csv(path, index=False)
            report.files.append(path)
        return report

    def _impacts(self, path: str, dt: float, every: int, walls: list,
                 joined: int | None = None) -> pd.DataFrame:
        """The impacts of a contacts' dump sampled every `every` steps against `walls` (the
        plate's, a feeder's side walls'), with the wall each met, by grain and time (joined:
        contacts.walls_impacts)."""
        return pd.concat([f.assign(wall=kind) for kind, f in zip(
            (PLATE_WALL, SIDE_WALL), contacts.walls_impacts(path, dt, every, walls, self.n,
                                                            joined))],
            ignore_index=True).sort_values(["grain", "time"], kind="stable").reset_index(drop=True)

    def _simulate(self, folder, run, size, contact, progress, wall0) -> dict:
        """LIGGGHTS' run into `folder`, resumed from the restart file of a run stopped by a
        signal with the same settings (engine.py), else from the start; its record."""
        stopped_path = os.path.join(folder, STOPPED)
        stopped = _read(stopped_path)
        # a feeder's run too: its restart file holds the meshes where they were and the time
        # of their motion, which goes on from there
        restart = (_restart(folder) if stopped is not None and stopped.get("run") == run
                   else None)
        if restart is None:  # from the start: what an earlier run left goes
            if os.path.isdir(folder):
                shutil.rmtree(folder)
            os.makedirs(folder)
            stopped = {"run": run, "cpu_s": 0.0, "parts": 0}
        part = stopped["parts"]
        input_name = script.INPUT if part == 0 else f"resume-{part}.{script.INPUT}"
        log_name = script.LOG if part == 0 else f"resume-{part}.{script.LOG}"
        text, steps = script.write_input(
            self.chute, self.entry, size, contact, dt=run["dt"], sample_every=run["sample_every"],
            t_end=self.t_end, exit_every=run["exit_every"],
            progress_every=max(1, int(self.t_end / run["dt"] / 200)), near=run["near"],
            slowest=SLOWEST, reference_every=run.get("reference_every"), restart=restart,
            law=self.law, law_properties=self.law_properties)
        with open(os.path.join(folder, input_name), "w") as f:
            f.write(text)
        with open(os.path.join(folder, script.PLATE), "w") as f:
            f.write(self.chute.stl(self.entry.width, self.chute.start(float(np.max(size)))))
        if self.chute.amplitude:
            with open(os.path.join(folder, script.SIDES), "w") as f:
                f.write(self.chute.sides_stl(self.entry.width, script.box_top(self.entry, size),
                                             self.chute.start(float(np.max(size)))))

        def on_stop(cpu):
            with open(stopped_path, "w") as f:
                json.dump(dict(stopped, cpu_s=stopped["cpu_s"] + cpu, parts=part + 1), f)

        cpu = engine.run(folder, input_name, log_name, steps, self.ranks, progress=progress,
                         first_step=restart[1] if restart else 0, on_stop=on_stop)
        record = {"run": run, "cpu_s": stopped["cpu_s"] + cpu, "parts": part + 1,
                  "wall_s": time.perf_counter() - wall0}
        with open(os.path.join(folder, engine.DONE), "w") as f:
            json.dump(record, f, indent=2)
        if os.path.exists(stopped_path):
            os.remove(stopped_path)
        return record

    def _rows(self, out, found, left, charged, size, dem, charging_cpu, wall) -> DemReport:
        n = self.n
        plate = found[found["wall"] == PLATE_WALL]
        mass = math.pi / 6.0 * self.drawn["size"].to_numpy() ** 3 * float(self.params[0]["density"])
        end = np.where(left["exited"] == 1, left["exit_time"], self.t_end)
        rows = pd.DataFrame(self.params)
        rows.insert(0, "seed", self.seed)
        rows.insert(0, "wall", self.feed.describe()["wall"])
        rows.insert(0, "particle", self.feed.describe()["particle"])
        rows.insert(0, "key", self.keys)
        rows["t_end"] = float(self.t_end)
        rows["record_interval"] = float(self.t_end) / STEPS_PER_RUN
        rows["fmu_sha256"] = self.sha256
        columns = result_columns(self.models)
        result = {c: np.nan for c in columns}
        result.update({"exited": left["exited"].to_numpy(), "exit_time": left["exit_time"].to_numpy(),
                       "time_end": end, "u": left["u"].to_numpy(), "v": left["v"].to_numpy(),
                       "exit_speed": left["exit_speed"].to_numpy(), "omega": left["omega"].to_numpy(),
                       "contact_fraction": contacts.contact_time(plate, n) / end,
                       "impacts": contacts.count(plate, n), "assumption_warnings": 0})
        # how a grain's run ended, where the population's rows say it (populations/feed.py):
        # one that left by the chute's end ended there (1); of one that did not, LIGGGHTS
        # does not say whether it rests, rolls or fell off the plate's side: left empty
        left_by_end = left["exited"].to_numpy() == 1
        result.update({"end_reason": np.where(left_by_end, 1.0, np.nan),
                       "at_rest": np.where(left_by_end, 0.0, np.nan)})
        lost = {}
        for model in self.models:
            q, lost[model] = charged.get(model, (np.full(n, np.nan), np.full(n, np.nan)))
            result[f"charge_{model}"] = q
            result[f"charge_to_mass_{model}"] = q / mass
            # the share of a grain's boundary at its limit has no meaning without segments
            result[f"capped_fraction_{model}"] = np.nan
        for c in columns:  # the population's columns, those it has
            rows[c] = result[c]
        for model in self.models:  # and the DEM's own: the charge lost to the gas (charging.py)
            rows[f"charge_lost_{model}"] = lost[model]
        if self.chute.amplitude:  # a feeder's side walls' impacts, counted apart
            rows["side_impacts"] = contacts.count(found[found["wall"] == SIDE_WALL], n)
        total_cpu = dem["cpu_s"] + charging_cpu
        rows["cpu_s"] = total_cpu / n
        rows["wall_s"] = wall / n
        os.makedirs(out, exist_ok=True)
        paths = [os.path.join(out, x) for x in (PARTICLES, IMPACTS, SUMMARY, METADATA)]
        rows.to_csv(paths[0], index=False, float_format="%.17g")
        found.to_csv(paths[1], index=False)
        summary = summarize_population(rows, self.models, self.shape_edges, self.size_edges)
        summary.to_csv(paths[2], index=False)
        described = self.feed.describe()
        with open(paths[3], "w") as f:
            json.dump({"n": n, "seed": self.seed, "t_end_s": self.t_end, "fmu": self.image.name,
                       "fmu_sha256": self.sha256, "feed": described, "dem": dem["run"],
                       "dem_cpu_s": dem["cpu_s"], "charging_cpu_s": charging_cpu,
                       "feed_rate": self.feed_rate, "lanes": self.lanes,
                       "stiffness_scale": self.stiffness_scale}, f, indent=2)
        report = DemReport(keys=self.keys, results=rows, executed=n, files=paths, summary=summary,
                           impacts=found, dem_cpu_s=dem["cpu_s"], charging_cpu_s=charging_cpu)
        if self.figure:
            # matplotlib only when a figure is drawn: `import tribo.dem` stays without it
            from ..populations.plot import population_title, write_population_figure
            chute = described["chute"]
            how = ("dilute" if self.feed_rate is None else f"{format_number(self.feed_rate)} grains/s")
            # the title names the amplitude and frequency; the stroke's angle is said here
            stroke = (f", its stroke at {format_number(self.vibration[2])}° to it"
                      if self.vibration and self.vibration[2] != 90 else "")
            title = population_title(
                dict(described, vibration=self.vibration[:2] if self.vibration else None), n,
                self.seed, f"at the exit of a {format_number(chute['chute_length'])} m chute "
                f"tilted {format_number(chute['tilt_deg'])}°{stroke}",
                head=f"DEM (LIGGGHTS, spheres, {how}): ")
            report.files.append(write_population_figure(rows, summary, os.path.join(out, FIGURE),
                                                        title))
        return report


def _restart(folder: str):
    """(file, step, grains created) of the latest restart file LIGGGHTS wrote when it was
    stopped in `folder`, or None. The grains created are counted from its logs (each
    create_atoms says "Created 1 atoms")."""
    found = [(int(m.group(1)), name) for name in os.listdir(folder)
             if (m := re.fullmatch(r"restart_forced_liggghts_(\d+)\.data", name))]
    if not found:
        return None
    step, name = max(found)
    created = 0
    for log in os.listdir(folder):
        if log.endswith(script.LOG):
            with open(os.path.join(folder, log), errors="replace") as f:
                created += sum(line.startswith("Created 1 atoms") for line in f)
    return name, step, created


def _read(path: str):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


__all__ = ["DemJob", "DemError", "DemReport", "DeviceError"]

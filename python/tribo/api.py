"""The package's functions for users: one particle as a DataFrame, a sweep, its results, a
population, an impact map, the separation line, a calibration.

Names and units are the package's (tribo/fmu/names.py): angles in degrees as <name>_deg
(beta_deg, tilt_deg, phi0_deg, ...), the SI FMUs' size as `size` (the long diameter 2a,
m), everything else the FMU's. Each function that writes results takes a folder `out`,
which holds one function's (or command's) results of one set-up (tribo/batch/folder.py):
another's is refused in one line, a second process on it is locked out. They run the same
flow as the `tribo` command's subcommands (tribo/batch/job.py: prepare, claim the folder,
run, report), and raise on a failed run. Those of a real particle take `materials`: a
materials file (tribo.materials, e.g. a calibration's) read over the package's table.
"""

import os

import pandas as pd

from .batch.executors import executor_for
from .batch.grid import SweepJob
from .batch.job import execute, raise_on_failure
from .batch.particle import simulate
from .batch.results import read_results
from .batch.sweep import RESULTS
from .fmu import FmuImage
from .fmu.locate import find_fmu
from .fmu.names import ParameterError, output_names
from .fmu.parameters import check_values
from .impact.defaults import DEFAULT_LIMIT
from .impact.episode import Grid
from .impact.map import EPISODES, ImpactMap, MapJob
from .line.grain import check_separator, load_images, run_line_grain
from .calibration.runner import CalibrationJob
from .line.defaults import DEFAULT_PAIR
from .line.mixture import Line, LineJob, check_line, line_specs
from .materials import pair_values, with_pair
from .populations.feed import Feed, check_measured, read_measured
from .populations.feed_variables import DEFAULT_CHUTE
from .populations.runner import PARTICLES, PopulationJob


def scene_of(scene: str | dict | None = None, **parameters) -> dict:
    """Parameters from a mapping or a text "name=value name=value ...", updated by the
    keyword arguments. ParameterError, one line naming the parameter, for a text item that
    is not name=number."""
    if isinstance(scene, str):
        pairs = [item.partition("=") for item in scene.split()]
        bad = [name for name, sep, value in pairs if not sep or not value or not name]
        if bad:
            raise ParameterError(f"scene {scene!r}: expected name=value items, not {' '.join(bad)}")
        parsed = {}
        for name, _, value in pairs:
            if name in parsed:
                raise ParameterError(f"scene {scene!r}: {name} is given twice")
            try:
                parsed[name] = float(value)
            except ValueError:
                raise ParameterError(f"{name} = {value!r} is not a number (in the scene "
                                     f"{scene!r})") from None
        scene = parsed
    return dict(scene or {}, **parameters)


def run(scene: str | dict | None = None, *, t_end: float = 100.0,
        record_interval: float | None = 1.0, outputs: list[str] | None = None,
        fmu: str | int | None = None, variant: str = "dimensionless",
        **parameters) -> pd.DataFrame:
    """Run one particle and return its outputs as a DataFrame: a column "time" (tau for
    the dimensionless FMU), then one column per output, a row every `record_interval`
    from 0 to t_end (fewer if the FMU ends the run early); record_interval=None: one row,
    the end (t_end or where the FMU ended the run), which costs the model's run alone
    (the same numbers as the last row of any record interval).

    scene: FMU parameters as a mapping or a text "epsilon=0.3 mu=1"; keyword arguments
    add to it. Parameters not given keep the FMU's start values (docs/model.md section 7
    at epsilon 0.5, mu = nu = 0.1), the tolerances included. outputs: the names to record
    (default: every scalar output). fmu: a path, or 2 / 3 for the build's FMI 2.0 / 3.0
    FMU (default 3); variant: "dimensionless" (tribo_fmi<v>) or "si" (tribo_si_fmi<v>, in
    SI units: time and t_end in seconds). Angles in degrees, named <name>_deg (beta_deg,
    phi0_deg; the output phi_deg), as everywhere in the package."""
    image = FmuImage.load(find_fmu(fmu, variant))
    params = scene_of(scene, **parameters)
    check_values(image, {name: [value] for name, value in params.items()})
    if outputs is None:
        outputs = output_names(image.model_description())
    return simulate(image, params, t_end, record_interval, outputs).series


def run_si(particle: str | None = None, wall: str | None = None, *, t_end: float = 10.0,
           record_interval: float | None = 1e-4, outputs: list[str] | None = None,
           fmu: str | int | None = None, materials=None, **parameters) -> pd.DataFrame:
    """Run one real particle through the SI FMU (docs/model.md section 8) and return its
    outputs in SI units as a DataFrame: "time" in s, then one column per output, a row
    every `record_interval` seconds until the run ends: at the chute's exit (`exited`), where
    the grain comes to rest on the chute (`at_rest`, at `rest_time`; docs/model.md section
    3c), or at t_end; the FMU ends the run at the first two, and the last row is that end
    (`end_reason` says which: 1 chute_exit, 3 at_rest, 0 t_end reached on the chute).
    record_interval=None: one row, the end, at the
    cost of the model's run alone (a calibration's or a sweep's way: the numbers of the
    last row of any record interval); each recorded row costs the FMU a communication
    point (docs/reference_case.md, "The package's cost").

    particle, wall: names of the materials table (tribo.materials), whose elastic
    constants, density and sigma0 become start values; keyword arguments are SI parameters
    by the package's names (size=1e-3: the long diameter 2a in m; tilt_deg=30;
    chute_length=0.3, ...) and win. Without materials, parameters not given keep the SI
    FMU's start values (the reference case: chute_length 0.3 m, mu_roll 0.01). fmu: a path, or 2 / 3
    for the build's SI FMU (default 3); materials: a materials file the pair's values come
    from (tribo.materials)."""
    if (particle is None) != (wall is None):
        raise ValueError("give both a particle and a wall material, or neither")
    params = dict(pair_values(particle, wall, sigma0="sigma0" not in parameters,
                              materials=materials), **parameters) \
        if particle else dict(parameters)
    image = FmuImage.load(find_fmu(fmu, variant="si"))
    check_values(image, {name: [value] for name, value in params.items()})
    if outputs is None:
        outputs = output_names(image.model_description())
    return simulate(image, params, t_end, record_interval, outputs).series


def sweep(grid: dict, *, t_end: float, out: str = "out/sweep", record_interval: float = 1.0,
          base: str = "paper", tie: bool = True, fmu: str | int | None = None,
          scheduler: str | None = None, workers: int | None = None, serial: bool = False,
          processes: bool = False, fresh: bool = False, series: bool = False,
          figure: bool = True, progress: bool = False, vibration=None) -> pd.DataFrame:
    """Run every combination of the values in `grid` (parameter name -> values), one row
    per run appended to <out>/results.csv as it finishes; runs already there are not run
    again; the figure <out>/results.png. Returns the sweep's rows (the columns of
    tribo sweep --help).

    base: "paper" (docs/model.md section 7, CVODE) or "fmu" (the FMU's start values) for
    the parameters not swept; the tolerances are the FMU's unless swept. tie: nu follows
    mu and tau_r follows tau0 unless they are swept too. Runs on a local Dask cluster
    (threads; processes=True: worker processes), on the one at `scheduler`, or in this
    process (serial=True). fresh: start the folder over, keeping what it held in
    <out>/backup-<n>/. series: also each run's time series, in <out>/series/. vibration:
    (AMPLITUDE, FREQUENCY[, ANGLE_DEG]) a vibrating plate in the model's units (amplitude in
    units of the semi-major axis a, frequency in cycles per t*, angle in degrees), as tribo
    sweep --vibration."""
    job = SweepJob(list(grid.items()), t_end=t_end, record_interval=record_interval, base=base,
                   tie=tie, fmu=fmu, series=series, figure=figure, vibration=vibration)
    report = execute(job, out, executor_for(serial, scheduler, workers, processes), fresh=fresh,
                     progress=progress)
    return raise_on_failure(report, "run").results


def load_results(path: str) -> pd.DataFrame:
    """The rows of a results file, floats exactly as written: the file, or the output
    folder of a sweep (results.csv), a study (runs/results.csv), a population
    (particles.csv) or an impact map (episodes.csv)."""
    if os.path.isdir(path):
        for name in (RESULTS, os.path.join("runs", RESULTS), PARTICLES, EPISODES):
            if os.path.isfile(os.path.join(path, name)):
                return read_results(os.path.join(path, name))
        raise FileNotFoundError(f"{path} holds no results file ({RESULTS}, runs/{RESULTS}, "
                                f"{PARTICLES} or {EPISODES})")
    return read_results(path)


def population(n: int, *, seed: int = 0, particle: str = "PE", wall: str = "steel",
               distributions: dict | None = None, measured: str | pd.DataFrame | None = None,
               chute: dict | None = None, settings: dict | None = None, t_end: float = 5.0,
               out: str = "out/population", fmu: str | int | None = None,
               scheduler: str | None = None, workers: int | None = None, serial: bool = False,
               processes: bool = False, fresh: bool = False, progress: bool = False,
               shape_edges=None, size_edges=None, materials=None):
    """Draw n particles from a feed with the seed and run each down the chute through the
    SI FMU (tribo.populations.feed: the feed variables epsilon, size (the long diameter 2a,
    m), phi0_deg, omega0, drop_height, drop_speed, drop_angle_deg, each a distribution
    text like "uniform:0.3:1" or a number; measured: a CSV path or DataFrame of measured
    values whose rows are drawn instead). chute: chute_length (m, default 0.3) and
    tilt_deg (default 30); settings: any other SI parameter. Results go into the folder
    `out` (particles.csv, summary.csv, population.png, population.json); an interrupted
    population resumes. Returns the report: .results (a row per particle), .summary (q/m
    statistics overall, per shape and size class, the exit stream's mass-weighted q/m over
    the grains that left, and the grains that came to rest on the chute or were still on
    it at the horizon t_end, counted apart: n_at_rest, n_at_horizon and their mass
    fractions).
    materials: a materials file the pair's values come from (they go into the settings)."""
    settings = with_pair(particle, wall, dict(settings or {}), materials)
    if isinstance(measured, str):
        measured = read_measured(measured)
    elif measured is not None:
        measured = check_measured(measured)
    feed = Feed(particle, wall, dict(distributions or {}), dict(DEFAULT_CHUTE, **(chute or {})),
                settings, measured,
                materials=os.fspath(materials) if isinstance(materials, (str, os.PathLike))
                else None)
    job = PopulationJob(feed, n, seed, t_end, fmu, shape_edges=shape_edges, size_edges=size_edges)
    report = execute(job, out, executor_for(serial, scheduler, workers, processes), fresh=fresh,
                     progress=progress)
    return raise_on_failure(report, "particle")


def impact_map(*, speed, angle_deg, phi0_deg, epsilon, particle: str = "PE",
               wall: str = "steel", settings: dict | None = None, limit: float | None = None,
               omega0: float = 0.0, out: str = "out/impact_map", fmu: str | int | None = None,
               scheduler: str | None = None, workers: int | None = None, serial: bool = False,
               processes: bool = False, fresh: bool = False, progress: bool = False,
               materials=None):
    """The charge-per-impact map of a materials pair over the grid of impact speeds (m/s),
    angles (angle_deg: degrees from the plate's surface, 90 head-on), orientations
    (phi0_deg, degrees) and roundness values (tribo.impact.episode): one SI FMU episode per
    point, from first contact to the lift-off, the grain at rest on the plate or the time
    limit (`limit` in t*; default DEFAULT_LIMIT; `end_reason` says which), with the charge
    and the charged area (`charged_area`, m2) per impact. settings: other SI parameters (size, cylinder_length, ...). Written
    into `out` (impact_map.csv, impact_map.json, impact_map.png, episodes.csv), resumable;
    returns tribo.ImpactMap for lookups. materials: a materials file the pair's values come
    from (they go into the settings)."""
    grid = Grid.of(speed=speed, angle_deg=angle_deg, phi0_deg=phi0_deg, epsilon=epsilon)
    job = MapJob(grid, particle, wall, with_pair(particle, wall, dict(settings or {}), materials),
                 DEFAULT_LIMIT if limit is None else limit, omega0, fmu)
    raise_on_failure(execute(job, out, executor_for(serial, scheduler, workers, processes),
                             fresh=fresh, progress=progress), "episode")
    return ImpactMap.load(out)


# ---- the separation line: the chute, then the free-fall separator (docs/line.md) ----------

DEFAULT_VOLTAGES = tuple(float(v) for v in range(5000, 40001, 5000))  # 5 to 40 kV, 8 values


def line_grain(particle: str = "PE", wall: str = "steel", *, voltage: float = 30e3,
               size: float = 1e-3, epsilon: float = 0.6, phi0_deg: float = 0.0,
               x_entry: float = 0.0, chute: dict | None = None, settings: dict | None = None,
               separator: dict | None = None, charge_model: str = "static", t_end: float = 5.0,
               fmu: str | int | None = None, separator_fmu: str | int | None = None,
               materials=None) -> dict:
    """One grain through the line (tribo.line.grain): down the SI chute (the pair's
    materials, `size` the long diameter 2a in m, dropped at rest from 10 mm; chute:
    chute_length, tilt_deg; settings: any other SI chute parameter) to its exit, then through
    the separator (separator: its settings, gap, height, n_bins, ...; the voltage U in V;
    x_entry the entry across the gap, m) from the chute's exit state. The chute with one
    charge model ("static" or "sliding"). Returns the chute's results (exited, exit_time,
    end_reason, at_rest, rest_time: a grain that came to rest on the chute or was still on
    it at t_end never enters the separator and lands nowhere; u, v, charged_area, ...),
    charge_to_mass (C/kg), mass (kg), the landing (landed, electrode, bin,
    x_end, z_end, flight_time, time_land) and the CPU times (chute_cpu_s, cpu_s).
    materials: a materials file the pair's values come from (tribo.materials)."""
    line = Line((particle,), wall, distributions={"epsilon": epsilon, "size": size,
                                                  "phi0_deg": phi0_deg},
                chute=dict(DEFAULT_CHUTE, **(chute or {})), settings=dict(settings or {}),
                separator=dict(separator or {}), feed_width=0.0, charge_model=charge_model,
                materials=materials)
    images = load_images(fmu, separator_fmu, line.separator, [voltage])
    specs = line_specs(line, 1, 0, t_end, images.models)
    specs[0].params["x_entry"] = float(x_entry)
    check_line(line, specs, images)
    check_separator(images.separator, dict(images.settings, x_entry=x_entry), [voltage], [size])
    result = run_line_grain(images, specs[0])
    return {"particle": line.particles[0], "wall": wall, "voltage": float(voltage),
            **result.row}


def _run_line(kind, line, n, seed, t_end, voltages, out, fmu, separator_fmu, scheduler,
              workers, serial, processes, fresh, progress, figure=True):
    voltages = [voltages] if isinstance(voltages, (int, float)) else voltages
    job = LineJob(kind, line, n, seed, t_end, voltages, fmu, separator_fmu, figure=figure)
    report = execute(job, out, executor_for(serial, scheduler, workers, processes), fresh=fresh,
                     progress=progress)
    return raise_on_failure(report, "grain")


def line_population(n: int, *, seed: int = 0, particle: str = "PE", wall: str = "steel",
                    voltage: float = 30e3, distributions: dict | None = None,
                    chute: dict | None = None, settings: dict | None = None,
                    separator: dict | None = None, feed_width: float = 0.01,
                    charge_model: str = "static", t_end: float = 5.0,
                    out: str = "out/line-population", fmu: str | int | None = None,
                    separator_fmu: str | int | None = None, scheduler: str | None = None,
                    workers: int | None = None, serial: bool = False, processes: bool = False,
                    fresh: bool = False, progress: bool = False, materials=None):
    """n grains of one material drawn from a feed (as tribo.population's) through the line
    at one voltage (V), each entering the separator at a point drawn across `feed_width`
    (m). Into `out` (particles.csv with the landing columns, landings.csv, line.csv: the
    mass per region; resumable). Returns tribo.line.mixture.LineReport. materials: a
    materials file the pair's values come from (tribo.materials)."""
    line = Line((particle,), wall, distributions=dict(distributions or {}),
                chute=dict(DEFAULT_CHUTE, **(chute or {})), settings=dict(settings or {}),
                separator=dict(separator or {}), feed_width=feed_width, charge_model=charge_model,
                materials=materials)
    return _run_line("population", line, n, seed, t_end, voltage, out, fmu, separator_fmu,
                     scheduler, workers, serial, processes, fresh, progress)


def line_mixture(n: int, *, seed: int = 0, particles=DEFAULT_PAIR, fraction: float = 0.5,
                 wall: str = "steel", voltage=30e3, distributions: dict | None = None,
                 chute: dict | None = None, settings: dict | None = None,
                 separator: dict | None = None, feed_width: float = 0.01,
                 splitter: float = 0.0, charge_model: str = "static", t_end: float = 5.0,
                 out: str = "out/line-mixture", fmu: str | int | None = None,
                 separator_fmu: str | int | None = None, scheduler: str | None = None,
                 workers: int | None = None, serial: bool = False, processes: bool = False,
                 fresh: bool = False, progress: bool = False, figure: bool = True,
                 materials=None):
    """A binary mixture of two particle materials of opposite polarity on one wall (default
    PE and nylon on steel, 50:50 by mass: `fraction` of the first) through the line at one
    voltage or several (`voltage`: a number or a list, V; the chute once per grain, the
    separator per voltage). The products split at x = `splitter` (m; 0 the centre line).
    Into `out`: particles.csv, landings.csv, line.csv (per voltage: masses per material and
    region, grade and recovery of each product), bins.csv, line.png (several voltages).
    Returns tribo.line.mixture.LineReport (.table is line.csv). materials: a materials
    file the particles' values come from (tribo.materials)."""
    line = Line(tuple(particles), wall, fraction, dict(distributions or {}),
                dict(DEFAULT_CHUTE, **(chute or {})), dict(settings or {}), dict(separator or {}),
                feed_width, charge_model, splitter, materials)
    return _run_line("mixture", line, n, seed, t_end, voltage, out, fmu, separator_fmu,
                     scheduler, workers, serial, processes, fresh, progress, figure)


def line_sweep(n: int, *, voltages=DEFAULT_VOLTAGES, out: str = "out/line-sweep", **options):
    """tribo.line_mixture over `voltages` (default 5 to 40 kV, 8 values), with its figure."""
    return line_mixture(n, voltage=list(voltages), out=out, **options)


# ---- calibration against measurements (docs/calibration.md) ----------------------------------

def calibrate(particle: str = "PE", wall: str = "steel", *, impacts=None, chutes=None,
              charge_model: str = "static", fit=None, settings: dict | None = None,
              materials=None, limit: float = DEFAULT_LIMIT, out: str = "out/calibration",
              fmu: str | int | None = None, scheduler: str | None = None,
              workers: int | None = None, serial: bool = False, processes: bool = False,
              fresh: bool = False, progress: bool = False, figure: bool = True):
    """Fit the pair's charging parameters to measured data (tribo.calibration): `impacts`
    and/or `chutes`, CSV paths or DataFrames of the columns of docs/calibration.md (single
    impacts: speed, angle_deg, size, epsilon, charge, ...; chute runs: chute_length,
    tilt_deg, q_per_m and the feed). Fits sigma0 and whichever of charging_time (and, with
    the sliding model, eta) the data determine (`fit`: the names to fit, default all of
    them); settings: other SI parameters (mu, nu, ...); materials: the table the pair's
    constants come from. Into `out`: fit.csv, points.csv, materials.toml (the file that
    `materials=` and `--materials` take), calibration.png, calibration.json. Returns
    tribo.calibration.runner.CalibrationReport (.fit, .rms_log10, .warnings,
    .materials_file)."""
    job = CalibrationJob(particle, wall, impacts, chutes, charge_model=charge_model, fit=fit,
                         settings=settings, materials=materials, limit=limit, fmu=fmu,
                         figure=figure)
    return execute(job, out, executor_for(serial, scheduler, workers, processes), fresh=fresh,
                   progress=progress)

"""The package's functions for users: one particle as a DataFrame, a sweep, its results."""

import pandas as pd

from .batch.executors import DaskExecutor, SerialExecutor
from .batch.grid import PAPER_BASE, build_specs, values_of
from .batch.particle import simulate
from .batch.results import read_results
from .batch.sweep import run_sweep
from .fmu import FmuImage
from .fmu.locate import find_fmu
from .fmu.parameters import check_names, check_values, integer_names
from .impact.episode import DEFAULT_LIMIT, Grid
from .impact.map import ImpactMap, run_impact_map
from .materials import start_values
from .populations.feed import DEFAULT_CHUTE, Feed, check_measured, read_measured
from .populations.runner import run_population


def scene_of(scene: str | dict | None = None, **parameters) -> dict:
    """Parameters from a mapping or a text "name=value name=value ...", updated by the
    keyword arguments."""
    if isinstance(scene, str):
        pairs = [item.partition("=") for item in scene.split()]
        bad = [name for name, sep, value in pairs if not sep or not value]
        if bad:
            raise ValueError(f"scene {scene!r}: expected name=value items, not {' '.join(bad)}")
        scene = {name: float(value) for name, _, value in pairs}
    return dict(scene or {}, **parameters)


def run(scene: str | dict | None = None, *, t_end: float = 100.0, record_interval: float = 1.0,
        outputs: list[str] | None = None, fmu: str | int | None = None,
        variant: str = "dimensionless", **parameters) -> pd.DataFrame:
    """Run one particle and return its outputs as a DataFrame: a column "time" (tau for
    the dimensionless FMU), then one column per output, a row every `record_interval`
    from 0 to t_end (fewer if the FMU ends the run early).

    scene: FMU parameters as a mapping or a text "epsilon=0.3 mu=1"; keyword arguments
    add to it. Parameters not given keep the FMU's start values (docs/model.md section 7
    at epsilon 0.5, mu = nu = 0.1), the tolerances included. outputs: the names to record
    (default: every scalar output). fmu: a path, or 2 / 3 for the build's FMI 2.0 / 3.0
    FMU (default 3); variant: "dimensionless" (tribo_fmi<v>) or "si" (tribo_si_fmi<v>, in
    SI units: time and t_end in seconds)."""
    image = FmuImage.load(find_fmu(fmu, variant))
    md = image.model_description()
    params = scene_of(scene, **parameters)
    check_values(image, {name: [value] for name, value in params.items()})
    if outputs is None:
        outputs = [v.name for v in md.modelVariables if v.causality == "output" and not v.dimensions]
    return simulate(image, params, t_end, record_interval, outputs).series


def run_si(particle: str | None = None, wall: str | None = None, *, t_end: float = 10.0,
           record_interval: float = 1e-4, outputs: list[str] | None = None,
           fmu: str | int | None = None, **parameters) -> pd.DataFrame:
    """Run one real particle through the SI FMU (docs/model.md section 8) and return its
    outputs in SI units as a DataFrame: "time" in s, then one column per output, a row
    every `record_interval` seconds until t_end or the chute's exit (the last row is the
    exit: the FMU ends the run there).

    particle, wall: names of the materials table (tribo.materials), whose elastic
    constants, density and sigma0 become start values; keyword arguments are SI parameters
    by name (semi_major_axis=0.5e-3, chute_length=0.3, ...) and win. Without materials,
    parameters not given keep the SI FMU's start values (the reference case, on an endless
    chute). fmu: a path, or 2 / 3 for the build's SI FMU (default 3)."""
    if (particle is None) != (wall is None):
        raise ValueError("give both a particle and a wall material, or neither")
    params = start_values(particle, wall, **parameters) if particle else dict(parameters)
    image = FmuImage.load(find_fmu(fmu, variant="si"))
    md = image.model_description()
    check_values(image, {name: [value] for name, value in params.items()})
    if outputs is None:
        outputs = [v.name for v in md.modelVariables if v.causality == "output" and not v.dimensions]
    return simulate(image, params, t_end, record_interval, outputs).series


def sweep(grid: dict, *, t_end: float, out: str, record_interval: float = 1.0,
          base: str = "paper", tie: bool = True, fmu: str | int | None = None,
          scheduler: str | None = None, workers: int | None = None, serial: bool = False,
          fresh: bool = False, series_dir: str | None = None, progress: bool = False) -> pd.DataFrame:
    """Run every combination of the values in `grid` (parameter name -> values), one row
    per run appended to the CSV `out` as it finishes; runs already in the file are not
    run again. Returns the sweep's rows (the columns of tribo-sweep --help).

    base: "paper" (docs/model.md section 7, CVODE) or "fmu" (the FMU's start values) for
    the parameters not swept; the tolerances are the FMU's unless swept. tie: nu follows
    mu and tau_r follows tau0 unless they are swept too. Runs on a local Dask cluster, on
    the one at `scheduler`, or in this process (serial=True). fresh: start the file over,
    keeping the old one as <name>.backup-<n>.csv."""
    image = FmuImage.load(find_fmu(fmu))
    md = image.model_description()
    check_names(md, grid)
    specs = build_specs([(n, list(v)) for n, v in grid.items()], PAPER_BASE if base == "paper" else {},
                        integer_names(md), t_end, record_interval, tie)
    check_values(image, values_of(specs))
    executor = SerialExecutor() if serial else DaskExecutor(scheduler, workers)
    with executor:
        report = run_sweep(specs, image, out, executor, resume=not fresh, series_dir=series_dir,
                           progress=progress)
    if report.failed:
        spec, error = report.failed[0]
        raise RuntimeError(f"{len(report.failed)} run(s) failed, e.g. {spec.params}: {error}")
    return report.results


def load_results(path: str) -> pd.DataFrame:
    """A results file of a sweep or a study (runs/results.csv), floats exactly as written."""
    return read_results(path)


def population(n: int, *, seed: int = 0, particle: str = "PE", wall: str = "steel",
               distributions: dict | None = None, measured: str | pd.DataFrame | None = None,
               chute: dict | None = None, settings: dict | None = None, t_end: float = 5.0,
               out: str = "out/population", fmu: str | int | None = None,
               scheduler: str | None = None, workers: int | None = None, serial: bool = False,
               fresh: bool = False, progress: bool = False, shape_edges=None, size_edges=None):
    """Draw n particles from a feed with the seed and run each down the chute through the
    SI FMU (tribo.populations.feed: the feed variables epsilon, size, phi0, omega0, drop_height,
    drop_speed, drop_angle, each a distribution text like "uniform:0.3:1" or a number;
    measured: a CSV path or DataFrame of measured values whose rows are drawn instead).
    chute: SI chute parameters (default chute_length 0.3 m); settings: any other SI
    parameter. Results go into the folder `out` (particles.csv, summary.csv,
    population.png); an interrupted population resumes. Returns the report: .results (a
    row per particle), .summary (q/m statistics overall, per shape and size class)."""
    if isinstance(measured, str):
        measured = read_measured(measured)
    elif measured is not None:
        measured = check_measured(measured)
    feed = Feed(particle, wall, dict(distributions or {}), dict(chute or DEFAULT_CHUTE),
                dict(settings or {}), measured)
    image = FmuImage.load(find_fmu(fmu, "si"))
    executor = SerialExecutor() if serial else DaskExecutor(scheduler, workers)
    report = run_population(feed, n, seed, t_end, image, out, executor, resume=not fresh,
                            progress=progress, shape_edges=shape_edges, size_edges=size_edges)
    if report.failed:
        spec, error = report.failed[0]
        raise RuntimeError(f"{len(report.failed)} particle(s) failed, e.g.: {error}")
    return report


def impact_map(*, speed, angle, phi0, epsilon, particle: str = "PE", wall: str = "steel",
               settings: dict | None = None, limit: float | None = None, omega0: float = 0.0,
               out: str = "out/impact_map", fmu: str | int | None = None,
               scheduler: str | None = None, workers: int | None = None, serial: bool = False,
               fresh: bool = False, progress: bool = False):
    """The charge-per-impact map of a materials pair over the grid of impact speeds (m/s),
    angles (deg from the plate's surface, 90 head-on), orientations phi0 (deg) and
    roundness values (tribo.impact.episode): one SI FMU episode per point, from first
    contact to the lift-off or the time limit (`limit` in t*; default DEFAULT_LIMIT).
    settings: other SI parameters (semi_major_axis, ...). Written into `out`
    (impact_map.csv, impact_map.json, impact_map.png), resumable; returns tribo.ImpactMap
    for lookups."""
    grid = Grid.of(speed=speed, angle=angle, phi0=phi0, epsilon=epsilon)
    image = FmuImage.load(find_fmu(fmu, "si"))
    executor = SerialExecutor() if serial else DaskExecutor(scheduler, workers)
    report = run_impact_map(grid, particle, wall, dict(settings or {}),
                            DEFAULT_LIMIT if limit is None else limit, image, out, executor,
                            omega0=omega0, resume=not fresh, progress=progress)
    if report.failed:
        spec, error = report.failed[0]
        raise RuntimeError(f"{len(report.failed)} episode(s) failed, e.g.: {error}")
    return ImpactMap.load(out)

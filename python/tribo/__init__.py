"""tribo: the tribocharging particle model's FMUs from Python: one particle, parameter
sweeps, the paper's study.

The API (each function documented where it is defined, in tribo/api.py):

    import tribo
    df = tribo.run(epsilon=0.3, mu=1.0, nu=1.0, t_end=200)       # one particle -> DataFrame
    df = tribo.run("epsilon=0.3 mu=1 nu=1", t_end=200)           # the same, as a scene text
    df = tribo.run_si("PE", "steel", semi_major_axis=0.5e-3, chute_length=0.3)
                                                                  # a real particle, SI units
    res = tribo.sweep({"epsilon": [0.3, 0.6, 1.0], "mu": [0.1, 1.0]}, t_end=500,
                      out="out/sweep/results.csv")                # a parameter sweep
    res = tribo.load_results("out/sweep/results.csv")             # its results file
    path = tribo.find_fmu()                                       # the FMU used by default
    start = tribo.materials.start_values("PE", "steel", semi_major_axis=0.5e-3)
                                                                  # SI start values of a pair
    pop = tribo.population(1000, seed=1, out="out/population")   # a feed down the chute
    pop.summary                                                   # q/m by shape, size class
    m = tribo.impact_map(speed=[1, 5], angle=[30, 90], phi0=[0, 45], epsilon=[0.5, 1])
    m("charge_static", speed=3, angle=60, phi0=20, epsilon=0.7)  # C per impact

The commands: tribo-study (the paper's study), tribo-sweep (parameter sweeps),
tribo-population (particle populations) and tribo-impact-map (charge-per-impact maps), each
with --help. The FMUs are those of the build directory (build/, or $TRIBO_BUILD_DIR) or
the one given by path (fmu=...).

Modules, one responsibility each:

    api         the functions above
    fmu         the fmpy driver (one instance, its logger, steps that end early), shared
                with the tests
    locate      where the FMUs are
    particle    one particle's run: series, segment charges, summary row
    parameters  parameter values checked by the FMU before any run
    specs       what one run is (parameters, horizon, recording interval) and its key
    grid        the runs of a sweep: combinations of values over a base set-up
    summary     what a time series is summarised into (bounce envelope, charges, modes)
    results     the results CSV: append a row per finished run, resume, backups
    executors   where runs execute: serially here, or on Dask (local cluster or address)
    sweep       a sweep: skip finished runs, run the rest, record them as they finish
    transition  the transition roundness eps_t: coarse grid, then multi-section
    study       the paper's study (docs/model.md section 7): runs, eps_t, figures, tables
    figures     the study's figures; sweep_plot: a sweep's; plotting: what they share
    tables      the study's tables (CSV and markdown)
    materials   the materials table (data/materials.toml): a particle/wall pair as the SI
                FMU's start values
    distributions  a feed variable's distribution, as text, drawn with a seed
    population_feed  a feed, its seeded draw, one particle's run down the chute (SI FMU)
    population_runner, population_summary, population_plot: a population into a folder,
                its q/m statistics by class, its figure
    impact      one impact episode (run_end = first_liftoff) and a map's grid
    impact_table  a map's runs, table, metadata and the lookup ImpactMap; impact_plot: its figure
    cli         the commands
"""

from . import materials
from .api import impact_map, load_results, population, run, run_si, sweep
from .impact_table import ImpactMap
from .locate import find_fmu

__all__ = ["run", "run_si", "sweep", "load_results", "find_fmu", "materials", "population",
           "impact_map", "ImpactMap"]

"""tribo: the tribocharging particle model's FMUs from Python: one particle, parameter
sweeps, the paper's study.

The API (each function documented where it is defined, in tribo/api.py):

    import tribo
    df = tribo.run(epsilon=0.3, mu=1.0, nu=1.0, t_end=200)       # one particle -> DataFrame
    df = tribo.run("epsilon=0.3 mu=1 nu=1", t_end=200)           # the same, as a scene text
    df = tribo.run_si("PE", "steel", size=1e-3, chute_length=0.3, tilt_deg=30)
                                                                  # a real particle, SI units
    res = tribo.sweep({"epsilon": [0.3, 0.6, 1.0], "mu": [0.1, 1.0]}, t_end=500,
                      out="out/sweep")                            # a parameter sweep
    res = tribo.load_results("out/sweep")                         # its results
    path = tribo.find_fmu()                                       # the FMU used by default
    start = tribo.materials.start_values("PE", "steel", semi_major_axis=0.5e-3)
                                                                  # the FMU's start values of a pair
    pop = tribo.population(1000, seed=1, out="out/population")   # a feed down the chute
    pop.summary                                                   # q/m by shape, size class
    m = tribo.impact_map(speed=[1, 5], angle_deg=[30, 90], phi0_deg=[0, 45], epsilon=[0.5, 1])
    m("charge_static", speed=3, angle_deg=60, phi0_deg=20, epsilon=0.7)  # C per impact
    g = tribo.line_grain("nylon", "steel", voltage=30e3)         # chute, then separator
    mix = tribo.line_sweep(200, seed=1, out="out/line-sweep")     # PE + nylon against U
    mix.table                                                     # grade, recovery per U
    tribo.single_impact("PE", "steel", speed=1.0, size=2e-3)      # Delta q (C), A_max (m2)
    tribo.repeated_impacts("PE", "steel", 10, speed=1.0)          # the charge after each
    tribo.chute_stream("PE", "steel", 50, seed=1)                 # the exit stream's q/m
    cal = tribo.calibrate("PE", "steel", impacts="impacts.csv", out="out/calibration")
    cal.fit                                                       # sigma0, t0 ± std
    tribo.population(100, materials="out/calibration/materials.toml", out="out/calibrated")

Names and units (tribo/fmu/names.py): angles in degrees, named <name>_deg; the SI size as
size, the long diameter 2a in m; the rest the FMU's names and SI units. Results go into an
output folder (out=) that holds one function's results of one set-up (tribo/batch/folder.py).

The command: `tribo`, a subcommand per job, each with --help: tribo population (particle
populations), tribo line (grains through the chute and the separator), tribo impact-map
(charge-per-impact maps), tribo calibrate (a pair's charging parameters from measured
data), tribo sweep (parameter sweeps), tribo study (the paper's study);
they and the functions above run one flow (batch/job.py). The FMUs are those of the build
directory (build/, or $TRIBO_BUILD_DIR) or the one given by path (fmu=...).

Its subpackages, by concern (each module's docstring says what it does):

    api          the functions above
    materials    the materials table (data/materials.toml): a particle/wall pair as the SI
                 FMU's start values; a materials file read over it (a calibration's)
    paschen      the gas's limit sigma_P(L) of a charged region (docs/model.md section 8e):
                 the ceilings of a grain and of repeated impacts
    plotting     what every figure shares (axis labels, colours, legends; matplotlib)
    ssp          the separation line as an SSP 1.0 package (the SI chute's FMU feeding the
                 separator's) for SSP importers: libcosim, ecos (standard library only)
    fmu/         the fmpy driver, shared with the tests: instance, image (an FMU as bytes),
                 locate (where the FMUs are), names (the package's names and units),
                 parameters (values checked by the FMU)
    batch/       many runs of the FMU: specs (a run and its key), grid (a sweep's runs, the
                 sweep as a job), run (one run of the FMU, numpy and fmpy only), particle
                 (one run: series, segment charges, summary row), summary (what a series
                 is summarised into), results (the results CSV),
                 executors (serial or Dask), folder (an output folder: its record and
                 lock), sweep (skip finished runs, run the rest, record them), job (the one
                 flow of every job: prepare, claim the folder, run, report), plot
    study/       the paper's study (docs/model.md section 7): paper (its runs), runner,
                 transition (eps_t), figures, tables
    populations/ particle populations down the chute (SI FMU): distributions, feed (a feed,
                 its seeded draw, one particle's run), runner, summary (q/m by class), plot
    impact/      charge-per-impact maps (SI FMU): episode (one impact, a map's grid), map
                 (the runs, the table, the lookup ImpactMap), plot
    line/        the separation line (SI chute, then the separator FMU): grain (one grain,
                 the chute once and the separator per voltage), mixture (a population or a
                 binary mixture, grade and recovery), plot
    calibration/ measurements and the model (docs/model.md section 8d): observables (a
                 single impact, repeated impacts, a chute's exit stream), data (the CSV
                 files), fit (sigma0, t0, eta and what the data determine), plot, runner
                 (a calibration into a folder, the materials file it writes)
    dem/         a population's grains through a device in LIGGGHTS (docs/dem.md): device
                 (the chute, the grains' entries), script (the LIGGGHTS input), engine
                 (LIGGGHTS as a process), contacts (the impacts from its output), charging
                 (the maps, the charge carried), runner (the job), plot
    cli/         the command `tribo` (main) and its subcommands, a module each

Each imports only its own modules and the layers below it: plotting and fmu at the
bottom, then materials, paschen and batch, then study, populations and impact (not each other), then
line, calibration and dem (on populations and impact; not each other), then api and cli (CONTRIBUTING.md; tests/python/test_package_layout.py checks it).
"""

import importlib

# where each name of the API is defined: imported at its first use, so that `import tribo`
# (and the command, tribo/cli) does not import the libraries of every job
_DEFINED_IN = {
    "fmu": None, "materials": None, "paschen": None,
    **{name: ".api" for name in ("calibrate", "impact_map", "line_grain", "line_mixture",
                                 "line_population", "line_sweep", "load_results", "population",
                                 "run", "run_si", "sweep")},
    **{name: ".calibration.observables" for name in ("chute_stream", "repeated_impacts",
                                                     "single_impact")},
    "find_fmu": ".fmu.locate",
    "ImpactMap": ".impact.map",
}

__all__ = ["run", "run_si", "sweep", "load_results", "find_fmu", "materials", "paschen", "population",
           "impact_map", "ImpactMap", "line_grain", "line_population", "line_mixture",
           "line_sweep", "single_impact", "repeated_impacts", "chute_stream", "calibrate"]


def __getattr__(name: str):
    if name not in _DEFINED_IN:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    module = _DEFINED_IN[name]
    if module is None:  # a subpackage or module of the API itself
        value = importlib.import_module(f".{name}", __name__)
    else:
        value = getattr(importlib.import_module(module, __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))

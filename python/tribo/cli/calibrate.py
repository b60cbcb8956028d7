"""tribo calibrate: a pair's charging parameters fitted to measured data (docs/calibration.md):
sigma0 and whichever of the charging time t0 (and eta, with the sliding model) the data
determine, each with its uncertainty, and a materials file the other commands take.

    tribo calibrate --impacts examples/data/impacts.csv --particle PE --wall steel --out out/calibration
    tribo calibrate --impacts examples/data/impacts.csv --chutes examples/data/chutes.csv --workers 2 --out out/cal-pe
    tribo population -n 200 --materials out/calibration/materials.toml --out out/calibrated

--impacts CSV: a row per single impact, columns speed (m/s), angle_deg (degrees to the
wall, 90 head-on), size (m, the grain's long diameter 2a), epsilon (b/a), charge (C, the
charge the impact gave the grain); optional phi0_deg (the long axis to the wall, degrees,
default 0), initial_charge (C, the grain's before, spread over it; default 0), charge_std
(C), impacts (the charge gathered over that many impacts on fresh spots; default 1).
--chutes CSV: a row per chute run, columns chute_length (m), tilt_deg, q_per_m (C/kg, the
mass-weighted mean q/m of the grains that left the chute); optional q_per_m_std (C/kg),
grains (how many the model draws, default 50), seed (default 0), t_end (s, default 5) and
the feed: epsilon, size, phi0_deg, omega0, drop_height, drop_speed, drop_angle_deg, each a
number or a distribution (uniform:0.3:1, lognormal:1e-3:0.3, ...; default the population's
feed). Every point is of --particle on --wall; the charges have the pair's one sign.

--fit names the parameters to fit (default sigma0,charging_time; with --charge-model
sliding also eta); --set gives other SI parameters (mu, nu, ...). The fit says what the
data do not determine (with complete transfer, t0; with t0 far above the contact time,
only sigma0/t0) and writes t0 = 0 where complete transfer fits as well. Bad input is one
line and nothing is written.

Writes into the folder --out: fit.csv (value, std, range, status of each parameter),
points.csv (each point, the model's value, log10(model/measured)), profile.csv (t0
fitted: the fit at each t0 of the grid), materials.toml (the
pair's sigma0 and charging parameters with where they came from: --materials FILE of
tribo population, line, impact-map and calibrate, materials= in the API),
calibration.png (data against model, the fit against t0), calibration.json. Dask: as
tribo population (a local cluster in this process, or --scheduler, or --serial).
"""

import os

from ..calibration.columns import columns_text
from ..impact.defaults import DEFAULT_LIMIT
from .common import add_si_job_options, name_value, run_job


def add_arguments(p) -> None:
    p.add_argument("--impacts", metavar="CSV", help=f"single impacts: {columns_text('impacts')}")
    p.add_argument("--chutes", metavar="CSV", help=f"chute runs: {columns_text('chutes')}")
    p.add_argument("--particle", default="PE", help="particle material (default PE)")
    p.add_argument("--wall", default="steel", help="wall material (default steel)")
    p.add_argument("--charge-model", default="static",
                   help="the charge model fitted: static (default) or another of the SI FMU's "
                        "(sliding)")
    p.add_argument("--fit", metavar="NAMES",
                   help="the parameters to fit, comma-separated (default sigma0,charging_time; "
                        "sliding: and eta)")
    p.add_argument("--set", type=name_value, action="append", default=[], metavar="NAME=VALUE",
                   help="any other SI parameter by the package's names (mu=0.5, nu=0.3, "
                        "charging_time=0 where it is not fitted, ...)")
    p.add_argument("--limit", type=float, default=DEFAULT_LIMIT,
                   help=f"an impact's time limit in t* (default {DEFAULT_LIMIT:g})")
    add_si_job_options(p, os.path.join("out", "calibration"))


def job_of(args):
    # the job's modules (and numpy, pandas, scipy, fmpy) once it runs: --help and a mistake in
    # the options need none of them (common.py)
    from ..calibration.runner import CalibrationJob
    fit = None if args.fit is None else [n for n in args.fit.split(",") if n.strip()]
    return CalibrationJob(args.particle, args.wall, args.impacts, args.chutes,
                          charge_model=args.charge_model, fit=fit, settings=dict(args.set),
                          materials=args.materials, limit=args.limit, fmu=args.fmu,
                          figure=not args.no_plot)


def told(job, report) -> list[str]:
    lines = [f"calibration: {len(report.results)} points, {report.runs} model runs in "
             f"{report.wall_s:.1f} s ({report.cpu_s:.1f} s of CPU in this process); RMS error "
             f"{report.rms_log10:.3f} decades of the charge"]
    for row in report.fit.itertuples():
        spread = f" ± {row.std:.2g}" if row.std == row.std else ""
        if row.status == "lower bound":  # the data at the gas's limit (docs/calibration.md)
            lines.append(f"  |{row.parameter}| >= {abs(row.value):.4g} {row.unit} (lower bound; "
                         f"written as {row.value:.4g})")
            continue
        lines.append(f"  {row.parameter} = {row.value:.4g}{spread} {row.unit} ({row.status})")
    lines += [f"calibration: warning: {w}" for w in report.warnings]
    lines += [f"calibration: wrote {', '.join(report.files)}",
              f"calibration: use it with --materials {report.materials_file}"]
    return lines


def run(args) -> int:
    return run_job(args, job_of, told)

"""tribo population: a particle population down the chute through the SI FMU, on Dask: N
particles drawn from a feed with a seed, one row per particle, the q/m summary and figure.

    tribo population -n 1000 --seed 1 --out out/population
    tribo population -n 200 --particle PP --wall glass --epsilon uniform:0.5:1 \\
        --size lognormal:1e-3:0.3 --chute-length 0.5 --tilt-deg 35 --out out/pp-glass
    tribo population -n 500 --measured examples/data/sieve.csv --out out/sieve  # measured rows
    tribo population -n 200 --chute-length 0.5 --tilt-deg 0 --vibration 5e-4,50,30 \\
        --t-end 30 --out out/feeder   # a level vibratory feeder: 0.5 mm, 50 Hz, 30 degrees

The feed variables (tribo/populations/feed.py) take a number or a distribution: uniform:LOW:HIGH,
normal:MEAN:SD, lognormal:MEDIAN:SIGMA, choice:V1,V2,...; --measured CSV gives columns of
measured values (any of epsilon, size, phi0_deg, omega0, drop_height, drop_speed,
drop_angle_deg), whose rows are drawn with replacement instead. Units: size is the long
diameter 2a in m, angles in degrees (phi0_deg, drop_angle_deg, --tilt-deg), omega0 in
rad/s, drop_height in m, drop_speed in m/s. Defaults: the SI reference case's feed
(epsilon uniform 0.3-1, size uniform 0.2-2 mm, phi0_deg uniform 0-180, dropped at rest
from 10 mm onto 0.3 m of steel tilted 30 degrees).

Writes into the folder --out: particles.csv (one row per particle: the materials, the seed,
every parameter of its run (the feed variables, the chute, the materials' constants), then
exited, exit_time, end_reason (1 left the chute, 3 came to rest on it, 0 still on it at the
horizon), at_rest, rest_time (s), time_end, u, v, exit_speed, omega, then for each charge model of the FMU
(static, sliding) charge_<model> (C, the grain's: the spheroid's; with --set
grain_geometry=0 the cylinder's of depth cylinder_length), charge_to_mass_<model> (C/kg),
capped_fraction_<model> (of the grain's bands at the gas's limit, docs/model.md §8e; of the
cylinder's segments with grain_geometry 0), charged_area (m2, the area the grain's contact patch charged), contact_fraction, impacts (contacts made while approaching the plate: bounces, the drop's
first landing included), fraction_flight ... fraction_bouncing, cpu_s, wall_s), summary.csv (q/m in C/kg:
n, mean, std, percentiles 5 25 50 75 95, stream_mean and stream_std (q/m of the grains that
left the chute, mass-weighted: what a Faraday cup at its end reads) and stayed (the mass
fraction that did not leave), n_exited, n_at_rest and n_at_horizon (how many grains left,
came to rest on the chute, were still on it at the horizon) and at_rest_fraction and
at_horizon_fraction (the mass fraction of the last two), overall and per shape and size
class),
population.png and population.json. Read stream_mean for what a stream carries (README.md,
docs/populations.md). An interrupted population (Ctrl-C) resumes when the same command
is run again; another set-up needs another --out, or --fresh (the folder's earlier
contents are kept in <out>/backup-<n>/). Dask: as tribo sweep (a local cluster in this
process, or --scheduler).
"""

import os

from .common import (QM_UNITS_SAID, add_chute_options, add_class_options, add_feed_options,
                     add_si_job_options, add_vibration_option, feed_of, name_value, qm_table,
                     run_job)


def add_arguments(p) -> None:
    add_feed_options(p, "particles")
    p.add_argument("--measured", metavar="CSV", help="measured values, a column per feed variable")
    add_chute_options(p)
    add_vibration_option(p)
    p.add_argument("--set", type=name_value, action="append", default=[], metavar="NAME=VALUE",
                   help="any other SI parameter by the package's names (mu=0.5, "
                        "cylinder_length=2e-3, n_segments=500, ...)")
    p.add_argument("--t-end", type=float, default=5.0, help="horizon of each particle, s (default 5)")
    add_class_options(p)
    add_si_job_options(p, os.path.join("out", "population"), max_runs="particles")


def job_of(args):
    # the job's modules (and numpy, pandas, fmpy) once it runs: --help and a mistake in the
    # options need none of them (common.py)
    from ..populations.feed import read_measured
    from ..populations.runner import PopulationJob  # the same
    measured = read_measured(args.measured) if args.measured else None
    return PopulationJob(feed_of(args, measured), args.particles, args.seed, args.t_end, args.fmu,
                         figure=not args.no_plot, shape_edges=args.shape_classes,
                         size_edges=args.size_classes)


def told(job, report) -> list[str]:
    from ..populations.summary import ends_text  # loaded by the job that made the report
    lines = [f"population: {report.executed} run, {report.skipped} already in the file, "
             f"{len(report.failed)} failed; {len(report.results)} of {report.total} done"]
    if report.summary is not None:
        lines += [f"q/m ({QM_UNITS_SAID}; size classes in m; stream_mean and stream_std: mass-weighted, "
                  "of the grains that left the chute, what a Faraday cup there reads; stayed: "
                  "the mass fraction that did not leave; the median is the typical grain: "
                  "docs/populations.md):",
                  qm_table(report.summary),
                  f"population: {ends_text(report.summary.iloc[0], job.t_end)}; stream_mean and "
                  f"stream_std are of those that left",
                  f"population: wrote {', '.join(report.files)}"]
    return lines


def run(args) -> int:
    return run_job(args, job_of, told)

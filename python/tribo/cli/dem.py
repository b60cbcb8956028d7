"""tribo dem: a population's grains, as spheres, through the reference chute in LIGGGHTS (a
separate process), each grain-wall impact charged by the project's impact map; the exit
stream written as a population's (docs/dem.md).

    tribo dem -n 1000 --out out/dem
    tribo dem -n 2000 --feed-rate 40 --lanes 5 --ranks 2 --out out/dem-stream
    tribo dem -n 50 --size uniform:6e-4:1e-3 --stiffness-scale 0.01 --out out/dem-soft
    tribo dem -n 100 --vibration 5e-4,50 --out out/dem-vibrating
    tribo dem -n 20 --vibration 5e-4,50,30 --tilt-deg 0 --chute-length 0.05 --out out/dem-feeder

The feed is a population's (tribo population --help: --size, --drop-height, ... and the
materials), its grains spheres: --epsilon 1, the default here (LIGGGHTS holds spheres here;
ellipses are not represented) and no spin at the drop. Without --feed-rate the grains are
in the dilute limit: each in its own lane across a plate wide enough for all, dropped at
once, so that none meets another; with it, grains/s dropped one after another into --lanes lanes (5 by
default) closer than a grain, three drop points along each, so that they collide
(LIGGGHTS moves them through it; grain-grain contacts transfer no charge).

LIGGGHTS runs as `liggghts` or `mpirun -np RANKS liggghts` in <out>/liggghts/ (its input,
plate.stl, outputs and log); its progress is shown; a failed run is said in one line with
LIGGGHTS' own error. Ctrl-C stops LIGGGHTS at a restart file it writes, and the same
command resumes from it; a finished run is kept, and running the command again only
charges again. The impact maps of the pair (one per grain size class) are made once into
--maps and found there by later runs; their episodes run on Dask as a population's (a
local cluster in this process, --scheduler, or --serial).

Writes into --out: particles.csv, summary.csv, population.png and population.json as a
population (tribo population --help), impacts.csv (a row per grain-wall impact: grain,
time, normal_speed, tangential_speed, angle_deg, duration, sustained, from_flight, wall (0
the plate, 1 a feeder's side wall), and its charge gain gain_<model> for an uncharged grain,
C) and liggghts/. --vibration makes the chute a vibratory feeder: the plate and its side
walls move along the stroke; a stroke inclined forward conveys the grains on a level
plate (--tilt-deg 0).
"""

import os

SPHERES = "1"  # --epsilon: LIGGGHTS holds spheres here

from .common import (QM_UNITS_SAID, add_chute_options, add_class_options, add_feed_options,
                     add_si_job_options, feed_of, name_value, numbers, positive_number, qm_table,
                     run_job)


def add_arguments(p) -> None:
    add_feed_options(p, "grains")
    # the grains are spheres here: the feed that runs is the command's default
    p.set_defaults(epsilon=SPHERES)
    add_chute_options(p)
    p.add_argument("--set", type=name_value, action="append", default=[], metavar="NAME=VALUE",
                   help="any other SI parameter by the package's names (mu=0.5, ...)")
    p.add_argument("--t-end", type=float, default=5.0,
                   help="horizon of the DEM run, s (default 5; it ends once every grain has left)")
    p.add_argument("--feed-rate", type=positive_number, metavar="PER_S",
                   help="grains/s dropped one after another (default: the dilute limit)")
    p.add_argument("--lanes", type=int, help="lanes of a fed stream (default 5)")
    p.add_argument("--vibration", type=numbers, metavar="AMPLITUDE,FREQUENCY[,ANGLE_DEG]",
                   help="a vibratory feeder: the plate and its side walls move along a stroke "
                        "of that amplitude (m) and frequency (Hz) at ANGLE_DEG to the plate "
                        "(default 90: along its normal; 20-45 convey); --tilt-deg 0 for a "
                        "level one")
    p.add_argument("--ranks", type=int, default=1, help="LIGGGHTS' MPI ranks (default 1)")
    p.add_argument("--stiffness-scale", type=float, default=1.0, metavar="F",
                   help="the Young's moduli LIGGGHTS takes, as a fraction of the materials' "
                        "(default 1; less: a larger time step, docs/dem.md)")
    p.add_argument("--maps", default=os.path.join("out", "impact-maps"), metavar="FOLDER",
                   help="where the impact maps are kept (default out/impact-maps)")
    p.add_argument("--contact-law", default=None, metavar="WORDS",
                   help="LIGGGHTS' contact law, the words after `model` of its pair style "
                        "(default: hertz tangential history rolling_friction cdt), for "
                        "comparing laws (docs/dem.md)")
    p.add_argument("--contact-property", action="append", default=[], metavar="LINE",
                   help="a property the contact law reads, NAME STYLE VALUES of LIGGGHTS' "
                        "fix property/global (e.g. 'characteristicVelocity scalar 0.2' for "
                        "hooke); repeatable")
    add_class_options(p)
    add_si_job_options(p, os.path.join("out", "dem"))


def job_of(args):
    # the job's modules (and numpy, pandas, fmpy, scipy) once it runs: --help and a mistake in
    # the options need none of them (common.py)
    from ..dem import DemJob, script
    return DemJob(feed_of(args), args.particles, args.seed, args.t_end, args.fmu,
                  feed_rate=args.feed_rate, lanes=args.lanes, ranks=args.ranks,
                  vibration=_vibration(args.vibration),
                  stiffness_scale=args.stiffness_scale, maps=args.maps,
                  figure=not args.no_plot, shape_edges=args.shape_classes,
                  size_edges=args.size_classes, law=args.contact_law or script.LAW,
                  law_properties=tuple(args.contact_property))


def _vibration(values):
    if values is None:
        return None
    if len(values) not in (2, 3):
        raise ValueError(f"--vibration {','.join(f'{v:g}' for v in values)}: two or three "
                         f"numbers, the amplitude in m, the frequency in Hz and the stroke's "
                         f"angle from the plate in degrees (default 90)")
    return values


def told(job, report) -> list[str]:
    lines = []
    if report.failed:
        lines.append(f"dem: {report.failed[0][1]}")
        return lines
    share = report.charging_cpu_s / report.dem_cpu_s if report.dem_cpu_s > 0 else float("nan")
    found = report.impacts
    lines.append(f"dem: {len(report.results)} grains, {len(found)} grain-wall impacts "
                 f"({int(found['sustained'].sum()) if len(found) else 0} ending in sustained "
                 f"contact); CPU: LIGGGHTS {report.dem_cpu_s:.3g} s, charging "
                 f"{report.charging_cpu_s:.3g} s ({100 * share:.2g} % of LIGGGHTS')")
    lines += [f"q/m ({QM_UNITS_SAID}; stream_mean and stream_std: mass-weighted, of the grains that "
              "left the chute; stayed: the mass fraction that did not leave; docs/dem.md):",
              qm_table(report.summary),
              f"dem: {int(report.summary.iloc[0]['n_exited'])} of {len(report.results)} grains "
              f"left by the chute's end",
              f"dem: wrote {', '.join(report.files)}"]
    return lines


def run(args) -> int:
    return run_job(args, job_of, told)

"""tribo impact-map: the charge one wall impact transfers, as a map over impact speed,
impact angle, orientation and roundness for a materials pair, through the SI FMU on Dask.

    tribo impact-map --speed 0.5:10:5 --angle-deg 15:90:6 --phi0-deg 0:90:4 \\
        --epsilon 0.4,0.7,1 --particle PE --wall steel --out out/impact_map
    tribo impact-map --speed 1,4 --angle-deg 45,90 --set size=4e-4 --out out/impact_small

Each grid point is one impact episode (tribo/impact/episode.py): the particle arrives with
its lowest point touching a level plate, at the speed (m/s) and angle (--angle-deg:
degrees from the plate's surface; 90 is head-on), orientation (--phi0-deg: degrees) and
spin --omega0 (rad/s); the SI FMU runs it with run_end = first_liftoff and ends it
exactly where it leaves the plate, where it comes to rest on it (a grazing or very slow
arrival settles), or at the time limit (--limit, in t*, default 200); the last two are
sustained contacts (lifted_off = 0), end_reason says which (2 lifted off, 3 at rest, 0 at
the limit), and the closing line counts each. VALUES: a:b:n (n values from a to b),
v1,v2,... or one value. The particle's size (--set size=..., the long diameter 2a in m,
default 1e-3) is the SI FMU's; the charges in C are the grain's, the spheroid's (with
--set grain_geometry=0 the cylinder's of the depth --set cylinder_length=..., m, default
1e-3; q/m does not depend on it).

Writes into the folder --out: impact_map.csv (speed, angle_deg, phi0_deg, epsilon, then
charge_<model> for each charge model of the FMU (static, sliding: C per impact, the
grain's), then charge_to_mass_<model> (C/kg), charged_area (m2, the
area the contact patch charged), rebound_u, rebound_v, rebound_speed (m/s),
rebound_angle_deg, rebound_omega (rad/s), contact_time (s), lifted_off, end_reason,
time_end, t_star, then the set-up on every row: particle, wall, size,
cylinder_length),
impact_map.json (the set-up, the grid, time limit, the FMU and package versions),
impact_map.png (its title the set-up) and episodes.csv (the runs as they finish: an
interrupted map resumes when the same command is run again; another set-up or grid needs
another --out, or --fresh). A wall model looks charges up with tribo.ImpactMap.load(out).
Dask: as tribo sweep (a local cluster in this process, or --scheduler).
"""

import os

from ..impact.defaults import DEFAULT_LIMIT
from .common import add_si_job_options, name_value, run_job, value_list


def add_arguments(p) -> None:
    p.add_argument("--speed", type=value_list, required=True, metavar="VALUES", help="impact speeds, m/s")
    p.add_argument("--angle-deg", type=value_list, required=True, metavar="VALUES",
                   help="impact angles, degrees from the plate's surface (90: head-on)")
    p.add_argument("--phi0-deg", type=value_list, default=[0.0], metavar="VALUES",
                   help="orientations of the long axis, degrees (default 0)")
    p.add_argument("--epsilon", type=value_list, default=[0.6], metavar="VALUES",
                   help="roundness values b/a (default 0.6)")
    p.add_argument("--omega0", type=float, default=0.0, help="spin at the impact, rad/s (default 0)")
    p.add_argument("--particle", default="PE", help="particle material (default PE)")
    p.add_argument("--wall", default="steel", help="wall material (default steel)")
    p.add_argument("--set", type=name_value, action="append", default=[], metavar="NAME=VALUE",
                   help="any other SI parameter by the package's names (size=4e-4, "
                        "cylinder_length=2e-3, mu=0.5, ...)")
    p.add_argument("--limit", type=float, default=DEFAULT_LIMIT,
                   help=f"time limit of an episode in t* (default {DEFAULT_LIMIT:g})")
    add_si_job_options(p, os.path.join("out", "impact_map"), max_runs="episodes")


def job_of(args):
    # the job's modules (and numpy, pandas, fmpy) once it runs: --help and a mistake in the
    # options need none of them (common.py)
    from ..impact.episode import Grid
    from ..impact.map import MapJob  # the same
    from ..materials import with_pair  # the same
    grid = Grid.of(speed=args.speed, angle_deg=args.angle_deg, phi0_deg=args.phi0_deg,
                   epsilon=args.epsilon)
    return MapJob(grid, args.particle, args.wall,
                  with_pair(args.particle, args.wall, dict(args.set), args.materials), args.limit,
                  args.omega0,
                  args.fmu, figure=not args.no_plot)


def told(job, report) -> list[str]:
    from ..impact.map import ends_text  # loaded by the job that made the report
    lines = [f"impact map: {report.executed} run, {report.skipped} already in the file, "
             f"{len(report.failed)} failed; {report.total} episodes"]
    if report.table is not None:
        lines.append(f"impact map: {ends_text(report.table, job.limit)}; wrote "
                     f"{', '.join(report.files)}")
    return lines


def run(args) -> int:
    return run_job(args, job_of, told)

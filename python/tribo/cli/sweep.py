"""tribo sweep: a parameter sweep of the tribo FMU (the dimensionless model) on Dask: every
combination of the values given, one row per run in a CSV that pandas loads
(tribo.load_results), resumable, and a figure of the results.

    tribo sweep --param epsilon=0.1:1.0:10 --param mu=0.1,1.0 --t-end 1000 --out out/sweep
    tribo sweep --param beta_deg=30,45,60 --t-end 200 --out out/sweep-tilt --serial
    tribo sweep --param epsilon=0.5 --t-end 100 --scheduler tcp://scheduler-host:8786
    tribo sweep --param mu=0.1,0.5 --vibration 0.02,0.005,30 --t-end 500 --out out/sweep-vibrating

--param NAME=VALUES, VALUES one of: a:b:n (n values from a to b, ends included),
v1,v2,... or a single value. NAME is any parameter of the FMU by the package's names
(epsilon, mu, nu, Gamma, beta_deg (the plate's tilt, degrees), tau0, Sigma0, eta, tau_r,
n_segments, drop_speed, phi0_deg, Omega0, rtol, ...: angles in degrees, named _deg).
The other parameters are the paper's set-up (docs/model.md section 7, CVODE; epsilon 0.5,
mu = nu = 0.1, beta_deg 45) unless --base fmu (the FMU's start values); the tolerances
are the FMU's defaults unless given (--param rtol=1e-8). As in the paper, nu follows mu
and tau_r follows tau0 unless they are given too (--no-tie: they don't). Every value and
the horizon are checked (by the FMU itself) before anything runs.

--vibration AMPLITUDE,FREQUENCY[,ANGLE_DEG] makes the plate vibrate (docs/model.md section 9b)
in the dimensionless model's own units, since a sweep has no size nor time in SI units: the
amplitude A in units of the grain's semi-major axis a, the frequency f in cycles per t*, the
stroke's angle from the plate in degrees (90 by default: along its normal). They are the FMU's
vib_omega = 2 pi f, vib_accel = A (2 pi f)^2 and vib_angle_deg, as the SI FMU derives them
from its own (m, Hz) with a and t* as the units, and set as a --param of one value each
would be: the same runs, keys and rows. 2 pi f must be at most 1 (a period of at least 2 pi
t*, the contact's own) and A (2 pi f)^2 at most 10: a value outside is one line naming
--vibration, before anything runs. For the SI chute's vibration in m and Hz: tribo population
--vibration (docs/feeder.md).

Writes into the folder --out: results.csv (a row per run as it finishes, keyed by a hash
of the run's parameters, horizon and FMU), results.png (the charges, the contact fraction
and the turns against the first swept parameter, a line per value of the others; not
with --no-plot), series/<key>.csv with --series (each run's time series). After an
interruption (Ctrl-C) the same command runs only the missing runs; runs of other values
or horizons of the same swept parameters go into the same folder; another set-up (other
swept parameters, --base, --no-tie) needs another --out, or --fresh (the folder's earlier
contents are kept in <out>/backup-<n>/). Columns: key, the parameters, t_end,
record_interval, fmu_sha256, the summary (tribo/batch/summary.py: Q_static_20pct ...
Q_static_end and the same for Q_sliding, and any other charge model's mean charge the FMU
outputs, at 1/5 ... 5/5 of t_end; contact fraction,
turns, turned_over, mode fractions, assumption warnings, bounce amplitude, and how the run
ended: exited, end_reason (0 ran to the horizon, 1 left the chute, 3 came to rest on it),
at_rest, rest_time), cpu_s, wall_s. A run that came to rest ends there: its charges at the
later fractions of t_end are those it rested with; the closing line and the figure (a ring)
say which runs ended so.

The local cluster runs in threads of this process (--processes: worker processes). On an
existing cluster the workers need fmpy, numpy and pandas (this package and the FMU are
sent to them). To keep one on this machine's loopback interface (Dask's HTTP servers
listen on all interfaces unless --dashboard-address says otherwise, even with
--no-dashboard):
    dask scheduler --host 127.0.0.1 --dashboard-address 127.0.0.1:8787 --no-dashboard
    dask worker tcp://127.0.0.1:8786 --host 127.0.0.1 --dashboard-address 127.0.0.1:0 --no-dashboard
"""

import os

from .common import add_job_options, add_out_option, run_job, vibration_values


def add_arguments(p) -> None:
    p.add_argument("--param", action="append", required=True, metavar="NAME=VALUES",
                   help="a swept parameter and its values (repeat for more)")
    p.add_argument("--vibration", type=vibration_values, metavar="AMPLITUDE,FREQUENCY[,ANGLE_DEG]",
                   help="a vibrating plate in the model's units: the stroke's amplitude in units "
                        "of the grain's semi-major axis a, its frequency in cycles per t*, its "
                        "angle from the plate (degrees, default 90: along its normal); the same "
                        "as --param vib_accel=A(2 pi f)^2 --param vib_omega=2 pi f --param "
                        "vib_angle_deg=ANGLE (docs/sweeps.md)")
    p.add_argument("--t-end", type=float, default=1000.0, help="horizon of every run (default 1000)")
    p.add_argument("--record-interval", type=float, default=1.0, help="output interval (default 1)")
    p.add_argument("--base", choices=("paper", "fmu"), default="paper",
                   help="values of the parameters not swept (default: the paper's set-up)")
    p.add_argument("--no-tie", dest="tie", action="store_false",
                   help="nu and tau_r do not follow mu and tau0")
    add_out_option(p, os.path.join("out", "sweep"))
    p.add_argument("--series", action="store_true", help="also write each run's time series to <out>/series/")
    p.add_argument("--fmu", help="the FMU (default: tribo_fmi3.fmu of $TRIBO_BUILD_DIR or the "
                                 "checkout's build/)")
    add_job_options(p, max_runs="runs")
    p.add_argument("--no-plot", action="store_true", help="no figure")


def job_of(args):
    # the job's modules (and numpy, pandas, fmpy) once it runs: --help and a mistake in the
    # options need none of them (common.py)
    from ..batch.grid import SweepJob, parse_param
    return SweepJob([parse_param(text) for text in args.param], t_end=args.t_end,
                    record_interval=args.record_interval, base=args.base, tie=args.tie,
                    fmu=args.fmu, series=args.series, figure=not args.no_plot,
                    vibration=args.vibration)


def told(job, report) -> list[str]:
    from ..batch.summary import ends_text  # loaded by the job that made the report
    lines = [f"sweep: {report.executed} executed, {report.skipped} already in the file, "
             f"{len(report.failed)} failed; {len(report.results)} of {report.total} runs done"]
    if len(report.results):
        charges = [c for c in report.results.columns if c.startswith("Q_") and c.endswith("_end")]
        lines.append(report.results[job.names + ["turned_over", "contact_fraction"] + charges]
                     .to_string(index=False))
        ends = ends_text(report.results)
        if ends:
            lines.append(f"sweep: {ends}")
        lines += [f"sweep: figure {path}" for path in report.files if path.endswith(".png")]
    return lines


def run(args) -> int:
    return run_job(args, job_of, told)

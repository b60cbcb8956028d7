"""tribo-sweep: a parameter sweep of the tribo FMU (the dimensionless model) on Dask: every
combination of the values given, one row per run in a CSV that pandas loads
(tribo.load_results), resumable, and a figure of the results.

    tribo-sweep --param epsilon=0.1:1.0:10 --param mu=0.1,1.0 --t-end 1000 --out out/sweep
    tribo-sweep --param beta_deg=30,45,60 --t-end 200 --out out/sweep-tilt --serial
    tribo-sweep --param epsilon=0.5 --t-end 100 --scheduler tcp://scheduler-host:8786

--param NAME=VALUES, VALUES one of: a:b:n (n values from a to b, ends included),
v1,v2,... or a single value. NAME is any parameter of the FMU by the package's names
(epsilon, mu, nu, Gamma, beta_deg (the plate's tilt, degrees), tau0, Sigma0, eta, tau_r,
n_segments, drop_speed, phi0_deg, Omega0, rtol, ...: angles in degrees, named _deg).
The other parameters are the paper's set-up (docs/model.md section 7, CVODE; epsilon 0.5,
mu = nu = 0.1, beta_deg 45) unless --base fmu (the FMU's start values); the tolerances
are the FMU's defaults unless given (--param rtol=1e-8). As in the paper, nu follows mu
and tau_r follows tau0 unless they are given too (--no-tie: they don't). Every value and
the horizon are checked (by the FMU itself) before anything runs.

Writes into the folder --out: results.csv (a row per run as it finishes, keyed by a hash
of the run's parameters, horizon and FMU), results.png (the charges, the contact fraction
and the turns against the first swept parameter, a line per value of the others; not
with --no-plot), series/<key>.csv with --series (each run's time series). After an
interruption (Ctrl-C) the same command runs only the missing runs; runs of other values
or horizons of the same swept parameters go into the same folder; another set-up (other
swept parameters, --base, --no-tie) needs another --out, or --fresh (the folder's earlier
contents are kept in <out>/backup-<n>/). Columns: key, the parameters, t_end,
record_interval, fmu_sha256, the summary (tribo/batch/summary.py: Q_static_20pct ...
Q_static_end and the same for Q_sliding, at 1/5 ... 5/5 of t_end; contact fraction,
turns, turned_over, mode fractions, assumption warnings, bounce amplitude), cpu_s, wall_s.

The local cluster runs in threads of this process (--processes: worker processes). On an
existing cluster the workers need fmpy, numpy and pandas (this package and the FMU are
sent to them). To keep one on this machine's loopback interface (Dask's HTTP servers
listen on all interfaces unless --dashboard-address says otherwise, even with
--no-dashboard):
    dask scheduler --host 127.0.0.1 --dashboard-address 127.0.0.1:8787 --no-dashboard
    dask worker tcp://127.0.0.1:8786 --host 127.0.0.1 --dashboard-address 127.0.0.1:0 --no-dashboard
"""

import os
import sys

from ..batch.executors import ClusterUnreachable
from ..batch.folder import FolderError, claim
from ..batch.grid import PAPER_BASE, build_specs, parse_param, values_of
from ..batch.particle import communication_points
from ..batch.sweep import (FIGURE, RESULTS, SERIES, check_out_folder, keys_of, kept, run_sweep,
                           sweep_setup)
from ..fmu import FmuImage
from ..fmu.locate import find_fmu
from ..fmu.parameters import check_names, check_values, integer_names
from .common import (add_execution_options, add_out_option, check_writable_dir, command_parser,
                     executor_of, fail)

PROG = "tribo-sweep"


def parse_args(argv=None):
    p = command_parser(PROG, __doc__)
    p.add_argument("--param", action="append", required=True, metavar="NAME=VALUES",
                   help="a swept parameter and its values (repeat for more)")
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
    add_execution_options(p)
    p.add_argument("--fresh", action="store_true",
                   help="start the folder over (what it held is kept in <out>/backup-<n>/)")
    p.add_argument("--max-runs", type=int, help="execute at most this many runs now (the rest later)")
    p.add_argument("--no-plot", action="store_true", help="no figure")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    return p.parse_args(argv)


def prepare(args):
    """Everything checked before any cluster starts or any run is made: the FMU, the
    swept values (types by the modelDescription, ranges by the FMU), the horizon and the
    output folder. Returns (image, specs, executor)."""
    check_out_folder(args.out)
    swept = [parse_param(text) for text in args.param]
    communication_points(args.t_end, args.record_interval)
    image = FmuImage.load(find_fmu(args.fmu))
    md = image.model_description()
    check_names(md, [n for n, _ in swept])
    base = PAPER_BASE if args.base == "paper" else {}
    specs = build_specs(swept, base, integer_names(md), args.t_end,
                        args.record_interval, args.tie)
    check_values(image, values_of(specs))  # by the FMU itself
    check_writable_dir(args.out)
    if args.max_runs is not None and args.max_runs < 0:
        raise ValueError(f"--max-runs {args.max_runs}: at least 0")
    return image, specs, executor_of(args)


def main(argv=None) -> int:
    args = parse_args(argv)
    keys = []
    path = os.path.join(args.out, RESULTS)
    try:
        try:
            image, specs, executor = prepare(args)
        except (ValueError, OSError) as e:
            return fail(PROG, str(e))
        keys = keys_of(specs, image)
        swept = [parse_param(text)[0] for text in args.param]
        with claim(args.out, "sweep", sweep_setup(swept, args.base, args.tie), image.sha256,
                   args.fresh) as folder:
            if folder.note:
                print(f"sweep: {folder.note}", flush=True)
            with executor:
                print(f"sweep: {len(specs)} runs to t = {args.t_end:g} on {executor.describe()}, "
                      f"into {args.out}", flush=True)
                report = run_sweep(specs, image, path, executor,
                                   series_dir=os.path.join(args.out, SERIES) if args.series else None,
                                   max_runs=args.max_runs, progress=not args.no_progress,
                                   desc="sweep")
            print(f"sweep: {report.executed} executed, {report.skipped} already in the file, "
                  f"{len(report.failed)} failed; {len(report.results)} of {len(report.keys)} runs done")
            if len(report.results):
                print(report.results[swept + ["turned_over", "contact_fraction", "Q_static_end"]]
                      .to_string(index=False))
                if not args.no_plot:
                    # matplotlib only when a figure is drawn: --no-plot runs without it
                    from ..batch.plot import write_sweep_figure
                    figure = write_sweep_figure(report.results, swept, os.path.join(args.out, FIGURE))
                    print(f"sweep: figure {figure}")
    except (ClusterUnreachable, FolderError) as e:
        return fail(PROG, str(e))
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted: {kept(path, keys)} of {len(keys)} runs kept in "
              f"{path}; run the same command to resume", file=sys.stderr, flush=True)
        return 130
    return 1 if report.failed else 0


if __name__ == "__main__":
    sys.exit(main())

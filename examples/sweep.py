"""A parameter sweep of the tribo FMU on Dask: every combination of the values given,
one row per run in a CSV that pandas loads, resumable.

    .venv/bin/python examples/sweep.py --param epsilon=0.1:1.0:10 --param mu=0.1,1.0 \\
        --t-end 1000 --out out/sweep/results.csv
    # on an existing Dask cluster (its workers need fmpy, numpy and pandas; this package
    # and the FMU are sent to them):
    .venv/bin/python examples/sweep.py ... --scheduler tcp://scheduler-host:8786

--param NAME=VALUES, VALUES one of: a:b:n (n values from a to b, ends included),
v1,v2,... or a single value. NAME is any parameter of the FMU (epsilon, mu, nu, Gamma,
beta (rad), tau0, Sigma0, eta, tau_r, n_segments, drop_speed, phi0, Omega0, ...).
The other parameters are the paper's set-up (docs/model.md section 7, CVODE; epsilon 0.5,
mu = nu = 0.1) unless --base fmu (the FMU's start values). As in the paper, nu follows mu
and tau_r follows tau0 unless they are given too (--no-tie: they don't).

Rows are appended as runs finish, keyed by a hash of the run's parameters, horizon and
FMU; run the same command again after an interruption and only the missing runs run
(--fresh: start the file over). Columns: key, the parameters, t_end, record_interval,
fmu_sha256, the summary of tribo_study/summary.py (charges at 1/5 ... 5/5 of t_end,
contact fraction, turns, turned_over, mode fractions, assumption warnings, bounce
amplitude), cpu_s, wall_s.
"""

import argparse
import itertools
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

from tribo_study.executors import DaskExecutor, SerialExecutor  # noqa: E402
from tribo_study.fmu_run import FmuImage, parameter_kinds  # noqa: E402
from tribo_study.specs import PAPER_SETUP, RunSpec, normalise_values  # noqa: E402
from tribo_study.sweep import run_sweep  # noqa: E402

PAPER_BASE = dict(PAPER_SETUP, epsilon=0.5, mu=0.1, nu=0.1)
TIES = {"nu": "mu", "tau_r": "tau0"}  # follower: leader (the paper's mu = nu, tau_r = tau0)


def parse_values(text: str) -> list[float]:
    """'a:b:n' (n values from a to b), 'v1,v2,...' or 'v'."""
    if ":" in text:
        a, b, n = text.split(":")
        if int(n) < 1:
            raise ValueError(f"{text}: need at least one value")
        return list(np.linspace(float(a), float(b), int(n)))
    return [float(v) for v in text.split(",") if v.strip()]


def parse_param(text: str) -> tuple[str, list[float]]:
    name, sep, values = text.partition("=")
    if not sep or not name.strip():
        raise argparse.ArgumentTypeError(f"--param {text!r}: expected NAME=VALUES")
    try:
        return name.strip(), parse_values(values)
    except ValueError as e:
        raise argparse.ArgumentTypeError(f"--param {text!r}: {e}")


def build_specs(swept: list[tuple[str, list[float]]], base: dict, kinds: dict[str, bool],
                t_end: float, record_interval: float, tie: bool = True) -> list[RunSpec]:
    """Every combination of the swept values (the first parameter varies slowest)."""
    unknown = [n for n, _ in swept if n not in kinds]
    if unknown:
        raise SystemExit(f"not parameters of the FMU: {', '.join(unknown)} "
                         f"(its parameters: {', '.join(kinds)})")
    names = [n for n, _ in swept]
    if len(set(names)) != len(names):
        raise SystemExit("a parameter is given twice")
    integers = [n for n, is_int in kinds.items() if is_int]
    specs = []
    for combo in itertools.product(*(values for _, values in swept)):
        params = dict(base, **dict(zip(names, combo)))
        if tie:
            for follower, leader in TIES.items():
                if leader in names and follower not in names:
                    params[follower] = params[leader]
        specs.append(RunSpec(normalise_values(params, integers), float(t_end), float(record_interval)))
    return specs


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n\n", 1)[1])
    p.add_argument("--param", type=parse_param, action="append", required=True, metavar="NAME=VALUES")
    p.add_argument("--t-end", type=float, default=1000.0, help="horizon of every run (default 1000)")
    p.add_argument("--record-interval", type=float, default=1.0, help="output interval (default 1)")
    p.add_argument("--base", choices=("paper", "fmu"), default="paper",
                   help="values of the parameters not swept (default: the paper's set-up)")
    p.add_argument("--no-tie", dest="tie", action="store_false",
                   help="nu and tau_r do not follow mu and tau0")
    p.add_argument("--out", default=os.path.join(ROOT, "out", "sweep", "results.csv"),
                   help="the results CSV (default out/sweep/results.csv)")
    p.add_argument("--series-dir", help="also write each run's time series to DIR/<key>.csv")
    p.add_argument("--fmu", default=os.path.join(os.environ.get("TRIBO_BUILD_DIR", os.path.join(ROOT, "build")),
                                                 "fmu", "tribo_fmi2.fmu"),
                   help="the FMU (default $TRIBO_BUILD_DIR or build/, fmu/tribo_fmi2.fmu)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="the existing Dask cluster to run on")
    where.add_argument("--serial", action="store_true", help="run in this process, without Dask")
    p.add_argument("--workers", type=int, help="worker processes of the local cluster (default: one per core)")
    p.add_argument("--fresh", action="store_true", help="start the results file over")
    p.add_argument("--max-runs", type=int, help="execute at most this many runs now (the rest later)")
    p.add_argument("--no-progress", action="store_true")
    return p.parse_args(argv)


def main(argv=None) -> int:
    args = parse_args(argv)
    if not os.path.exists(args.fmu):
        sys.exit(f"{args.fmu} not found: build first (scripts/setup.sh) or give --fmu")
    kinds = parameter_kinds(args.fmu)
    base = PAPER_BASE if args.base == "paper" else {}
    specs = build_specs(args.param, base, kinds, args.t_end, args.record_interval, args.tie)
    image = FmuImage.load(args.fmu)
    executor = SerialExecutor() if args.serial else DaskExecutor(args.scheduler, args.workers)
    with executor:
        print(f"sweep: {len(specs)} runs to tau = {args.t_end:g} on {executor.describe()}, "
              f"into {args.out}", flush=True)
        report = run_sweep(specs, image, args.out, executor, resume=not args.fresh,
                           series_dir=args.series_dir, max_runs=args.max_runs,
                           progress=not args.no_progress, desc="sweep")
    swept = [n for n, _ in args.param]
    print(f"sweep: {report.executed} executed, {report.skipped} already in the file, "
          f"{len(report.failed)} failed; {len(report.results)} of {len(report.keys)} runs done")
    if len(report.results):
        last = [c for c in report.results.columns if c.startswith("Q_static_t")][-1]
        print(report.results[swept + ["turned_over", "contact_fraction", last]].to_string(index=False))
    return 1 if report.failed else 0


if __name__ == "__main__":
    sys.exit(main())

"""The paper's parameter study through the tribo FMU (docs/model.md section 7): both friction
cases, a range of roundness values, both charge models; the transition roundness eps_t
of each friction case; figures and tables.

    .venv/bin/python examples/paper_study.py                 # reduced: 6 eps, tau to 1000
    .venv/bin/python examples/paper_study.py --full          # the paper's: 10 eps, tau to 5000
    .venv/bin/python examples/paper_study.py --scheduler tcp://host:8786   # an existing Dask cluster
    .venv/bin/python examples/paper_study.py --full --dashpots 0,1   # with the centre dashpot too

Writes into --out (default out/study, or out/study-full with --full): study.md (set-up,
definitions, eps_t, tables, run time, figures), study_runs.csv, transition_points.csv,
the PNG figures, and runs/ (every run's summary row in runs/results.csv and its time
series in runs/series/). An interrupted study resumes from runs/ (--fresh: start over).
"""

import argparse
import os
import shlex
import sys
import time

STARTED = time.perf_counter()
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

from tribo_study.executors import DaskExecutor, SerialExecutor  # noqa: E402
from tribo_study.fmu_run import FmuImage  # noqa: E402
from tribo_study.paper import FULL, REDUCED, run_study  # noqa: E402


def default_fmu() -> str:
    build = os.environ.get("TRIBO_BUILD_DIR", os.path.join(ROOT, "build"))
    return os.path.join(build, "fmu", "tribo_fmi2.fmu")


def floats(text: str) -> tuple:
    return tuple(float(x) for x in text.split(","))


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n\n", 1)[1])
    p.add_argument("--full", action="store_true",
                   help="the paper's study: epsilon 0.1..1.0, tau to 5000 (default: reduced)")
    p.add_argument("--out", help="output directory (default out/study or out/study-full)")
    p.add_argument("--fmu", default=default_fmu(),
                   help="the FMU (FMI 2.0 or 3.0; default $TRIBO_BUILD_DIR or build/, fmu/tribo_fmi2.fmu)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="run on the existing Dask cluster at ADDRESS (default: a local cluster)")
    where.add_argument("--serial", action="store_true", help="run in this process, without Dask")
    p.add_argument("--workers", type=int, help="worker processes of the local cluster (default: one per core)")
    resume = p.add_mutually_exclusive_group()
    resume.add_argument("--resume", dest="resume", action="store_true", default=True,
                        help="reuse the finished runs in <out>/runs (default)")
    resume.add_argument("--fresh", dest="resume", action="store_false", help="run everything again")
    p.add_argument("--dashpots", type=lambda text: tuple(int(x) for x in text.split(",")),
                   help="normal dashpots (damping_point values, docs/model.md section 3), the "
                        "study's own first: 0 the contact point (default), 1 the centre; e.g. "
                        "0,1 runs the grid with both and compares them")
    p.add_argument("--epsilons", type=floats, help="override the roundness grid, e.g. 0.2,0.6,1.0")
    p.add_argument("--t-end", type=float, help="override the horizon")
    p.add_argument("--transition-width", type=float, help="override the final width of the eps_t bracket")
    p.add_argument("--points-per-round", type=int,
                   help="runs per round of the eps_t multi-section (default 2; 1 = bisection)")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    return p.parse_args(argv)


def main(argv=None) -> int:
    args = parse_args(argv)
    settings = FULL if args.full else REDUCED
    overrides = {k: v for k, v in (("epsilons", args.epsilons), ("t_end", args.t_end),
                                   ("dashpots", args.dashpots),
                                   ("transition_width", args.transition_width),
                                   ("points_per_round", args.points_per_round)) if v is not None}
    if overrides:
        from dataclasses import replace
        settings = replace(settings, **overrides)
    out = args.out or os.path.join(ROOT, "out", "study-full" if args.full else "study")
    if not os.path.exists(args.fmu):
        sys.exit(f"{args.fmu} not found: build first (scripts/setup.sh) or give --fmu")
    image = FmuImage.load(args.fmu)
    executor = SerialExecutor() if args.serial else DaskExecutor(args.scheduler, args.workers)
    arguments = [os.path.relpath(a, ROOT) if a.startswith(ROOT + os.sep) else a
                 for a in (sys.argv[1:] if argv is None else argv)]
    command = "examples/paper_study.py " + " ".join(shlex.quote(a) for a in arguments)
    print(f"study: {len(settings.epsilons)} roundness values x {len(settings.frictions)} friction "
          f"cases to tau = {settings.t_end:g}, damping_point {', '.join(map(str, settings.dashpots))}, "
          f"FMU {args.fmu}, into {out}", flush=True)
    with executor:
        print(f"study: running on {executor.describe()}", flush=True)
        result = run_study(settings, image, out, executor, resume=args.resume,
                           progress=not args.no_progress, command=command.strip(), started=STARTED)
    for friction, t in result.transitions.items():
        print(f"study: {friction} friction: {t.describe()}")
    print(f"study: {result.executed} of {result.total_runs} runs executed, "
          f"{result.wall_s:.1f} s wall; wrote {os.path.join(out, 'study.md')} and "
          f"{len(result.files) - 1} more files")
    return 0


if __name__ == "__main__":
    sys.exit(main())

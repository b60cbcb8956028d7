"""tribo study: the paper's parameter study through the tribo FMU (docs/model.md section 7):
both friction cases, a range of roundness values, both charge models; the transition
roundness eps_t of each friction case; figures and tables.

    tribo study                          # reduced: 6 eps, tau to 1000, into out/study
    tribo study --full                   # the paper's: 10 eps, tau to 5000, into out/study-full
    tribo study --scheduler tcp://host:8786      # an existing Dask cluster
    tribo study --full --dashpots 0,1    # with the centre dashpot too

Writes into the folder --out: study.md (set-up, definitions, eps_t, tables, run time,
figures), study_runs.csv, transition_points.csv, the PNG figures, and runs/ (every run's
summary row in runs/results.csv, its time series and segment charges in runs/series/). An
interrupted study (Ctrl-C) resumes from runs/ when the same command is run again; a study
of other settings needs another --out, or --fresh (the folder's earlier contents are kept
in <out>/backup-<n>/). The runs use the FMU's default tolerances unless --rtol / --atol
are given. The segment charge map needs the FMI 3.0 FMU (the default), whose arrays hold
each segment's charge.
"""

import argparse
import os
import shlex
from dataclasses import replace

from .common import add_execution_options, add_out_option, numbers, run_job


def integers(text: str) -> tuple:
    try:
        return tuple(int(x) for x in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected whole numbers separated by commas") from None


def add_arguments(p) -> None:
    p.add_argument("--full", action="store_true",
                   help="the paper's study: epsilon 0.1..1.0, tau to 5000 (default: reduced)")
    add_out_option(p, None)
    p.set_defaults(out=None)
    p.add_argument("--fmu", help="the FMU (FMI 3.0 or 2.0; default: tribo_fmi3.fmu of "
                                 "$TRIBO_BUILD_DIR or the checkout's build/)")
    add_execution_options(p)
    resume = p.add_mutually_exclusive_group()
    resume.add_argument("--resume", dest="resume", action="store_true", default=True,
                        help="reuse the finished runs in <out>/runs (default)")
    resume.add_argument("--fresh", dest="resume", action="store_false",
                        help="run everything again (what the folder held is kept in "
                             "<out>/backup-<n>/)")
    p.add_argument("--dashpots", type=integers,
                   help="normal dashpots (damping_point values, docs/model.md section 3), the "
                        "study's own first: 0 the contact point (default), 1 the centre; e.g. "
                        "0,1 runs the grid with both and compares them")
    p.add_argument("--epsilons", type=numbers, help="override the roundness grid, e.g. 0.2,0.6,1.0")
    p.add_argument("--t-end", type=float, help="override the horizon")
    p.add_argument("--rtol", type=float, help="CVODE's relative tolerance (default: the FMU's)")
    p.add_argument("--atol", type=float, help="CVODE's absolute tolerance (default: the FMU's)")
    p.add_argument("--transition-width", type=float, help="override the final width of the eps_t bracket")
    p.add_argument("--points-per-round", type=int,
                   help="runs per round of the eps_t multi-section (default 2; 1 = bisection)")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")


def settings_of(args):
    # the job's modules (and numpy, pandas, fmpy, matplotlib) once it runs: --help and a
    # mistake in the options need none of them (common.py)
    from ..study.runner import FULL, REDUCED
    settings = FULL if args.full else REDUCED
    tolerances = tuple((n, v) for n, v in (("rtol", args.rtol), ("atol", args.atol)) if v is not None)
    overrides = {k: v for k, v in (("epsilons", args.epsilons), ("t_end", args.t_end),
                                   ("dashpots", args.dashpots), ("tolerances", tolerances or None),
                                   ("transition_width", args.transition_width),
                                   ("points_per_round", args.points_per_round)) if v is not None}
    return replace(settings, **overrides)


def command_line(prog: str, argv: list[str]) -> str:
    """The command as run, paths inside the checkout relative to it (for study.md)."""
    from ..fmu.locate import CHECKOUT  # the FMU driver's package: once a job runs (settings_of)
    arguments = [os.path.relpath(a, CHECKOUT) if a.startswith(CHECKOUT + os.sep) else a
                 for a in argv]
    return " ".join([prog] + [shlex.quote(a) for a in arguments])


def job_of(args):
    from ..study.runner import StudyJob  # the job's modules once it runs (settings_of)
    # the folder's default and --fresh follow --full and --resume (run_job reads them here)
    args.out = args.out or os.path.join("out", "study-full" if args.full else "study")
    args.fresh = not args.resume
    return StudyJob(settings_of(args), args.fmu, command=command_line("tribo study", args.typed),
                    started=args.started)


def told(job, report) -> list[str]:
    lines = [f"study: {friction} friction: {t.describe()}"
             for friction, t in report.transitions.items()]
    return lines + [f"study: {report.executed} of {report.total_runs} runs executed, "
                    f"{report.wall_s:.1f} s wall; wrote {report.files[-1]} and "
                    f"{len(report.files) - 1} more files"]


def run(args) -> int:
    return run_job(args, job_of, told)

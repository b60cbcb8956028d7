"""tribo-study: the paper's parameter study through the tribo FMU (docs/model.md section 7):
both friction cases, a range of roundness values, both charge models; the transition
roundness eps_t of each friction case; figures and tables.

    tribo-study                          # reduced: 6 eps, tau to 1000, into out/study
    tribo-study --full                   # the paper's: 10 eps, tau to 5000, into out/study-full
    tribo-study --scheduler tcp://host:8786      # an existing Dask cluster
    tribo-study --full --dashpots 0,1    # with the centre dashpot too

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
import sys
import time
from dataclasses import asdict, replace

from ..batch.executors import ClusterUnreachable
from ..batch.folder import FolderError, claim
from ..batch.particle import communication_points
from ..batch.results import read_results
from ..fmu import FmuImage
from ..fmu.locate import CHECKOUT, find_fmu
from ..fmu.parameters import check_values, integer_names
from ..study.paper import paper_spec
from ..study.runner import FULL, REDUCED, run_study
from .common import (add_execution_options, check_writable_dir, command_parser, executor_of, fail,
                     numbers)

PROG = "tribo-study"



def integers(text: str) -> tuple:
    try:
        return tuple(int(x) for x in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected whole numbers separated by commas") from None


def parse_args(argv=None):
    p = command_parser(PROG, __doc__)
    p.add_argument("--full", action="store_true",
                   help="the paper's study: epsilon 0.1..1.0, tau to 5000 (default: reduced)")
    p.add_argument("--out", metavar="FOLDER",
                   help="the output folder (default out/study, with --full out/study-full): it "
                        "holds one command's results of one set-up; another's is refused, "
                        "--fresh starts it over (what it held is kept in FOLDER/backup-<n>/)")
    p.add_argument("--fmu", help="the FMU (FMI 3.0 or 2.0; default: tribo_fmi3.fmu of "
                                 "$TRIBO_BUILD_DIR or the checkout's build/)")
    add_execution_options(p)
    resume = p.add_mutually_exclusive_group()
    resume.add_argument("--resume", dest="resume", action="store_true", default=True,
                        help="reuse the finished runs in <out>/runs (default)")
    resume.add_argument("--fresh", dest="resume", action="store_false",
                        help="run everything again (the old runs/results.csv is kept as a backup)")
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
    return p.parse_args(argv)


def settings_of(args):
    settings = FULL if args.full else REDUCED
    tolerances = tuple((n, v) for n, v in (("rtol", args.rtol), ("atol", args.atol)) if v is not None)
    overrides = {k: v for k, v in (("epsilons", args.epsilons), ("t_end", args.t_end),
                                   ("dashpots", args.dashpots), ("tolerances", tolerances or None),
                                   ("transition_width", args.transition_width),
                                   ("points_per_round", args.points_per_round)) if v is not None}
    return replace(settings, **overrides)


def prepare(args):
    """Everything checked before any cluster starts: the FMU, every parameter value of
    the grid (by the FMU), the horizon, the search's settings, the output folder."""
    settings = settings_of(args)
    communication_points(settings.t_end, settings.record_interval)
    if not settings.transition_width > 0:
        raise ValueError(f"--transition-width {settings.transition_width:g}: must be > 0")
    if settings.points_per_round < 1:
        raise ValueError(f"--points-per-round {settings.points_per_round}: at least 1")
    image = FmuImage.load(find_fmu(args.fmu))
    integers = integer_names(image.model_description())
    specs = [paper_spec(e, f, settings.t_end, integer_names=integers, damping_point=d,
                        **dict(settings.tolerances))
             for d in settings.dashpots for f in settings.frictions for e in settings.epsilons]
    values = {}
    for s in specs:
        for name, value in s.params.items():
            values.setdefault(name, []).append(value)
    check_values(image, values)
    out = args.out or os.path.join("out", "study-full" if args.full else "study")
    check_writable_dir(out)  # runs/ is made when the folder is claimed and the runs start
    return settings, image, out, executor_of(args)


def command_line(argv) -> str:
    """The command as run, paths inside the checkout relative to it (for study.md)."""
    arguments = [os.path.relpath(a, CHECKOUT) if a.startswith(CHECKOUT + os.sep) else a
                 for a in (sys.argv[1:] if argv is None else argv)]
    return " ".join([PROG] + [shlex.quote(a) for a in arguments])


def main(argv=None) -> int:
    started = time.perf_counter()
    args = parse_args(argv)
    out = None
    try:
        try:
            settings, image, out, executor = prepare(args)
        except (ValueError, OSError) as e:
            return fail(PROG, str(e))
        with claim(out, "study", asdict(settings), image.sha256, not args.resume) as folder:
            if folder.note:
                print(f"study: {folder.note}", flush=True)
            print(f"study: {len(settings.epsilons)} roundness values x {len(settings.frictions)} "
                  f"friction cases to tau = {settings.t_end:g}, damping_point "
                  f"{', '.join(map(str, settings.dashpots))}, FMU {image.name}, into {out}",
                  flush=True)
            with executor:
                print(f"study: running on {executor.describe()}", flush=True)
                result = run_study(settings, image, out, executor, progress=not args.no_progress,
                                   command=command_line(argv), started=started)
    except (ClusterUnreachable, FolderError) as e:
        return fail(PROG, str(e))
    except KeyboardInterrupt:
        path = os.path.join(out, "runs", "results.csv") if out else None
        n = len(read_results(path)) if path and os.path.exists(path) else 0
        print(f"{PROG}: interrupted: {n} runs kept in {path or 'nothing'}; run the same command "
              f"to resume", file=sys.stderr, flush=True)
        return 130
    for friction, t in result.transitions.items():
        print(f"study: {friction} friction: {t.describe()}")
    print(f"study: {result.executed} of {result.total_runs} runs executed, "
          f"{result.wall_s:.1f} s wall; wrote {os.path.join(out, 'study.md')} and "
          f"{len(result.files) - 1} more files")
    return 0


if __name__ == "__main__":
    sys.exit(main())

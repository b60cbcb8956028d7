"""What the subcommands share (their parser is parsing.py's): argument types, the options
every job takes (--out, --fresh, where runs execute, --no-progress) and `run_job`, which
runs a job through the package's one flow (tribo/batch/job.py) and meets every mistake with
one line."""

import argparse
import sys

from ..populations.feed_variables import DEFAULT_CHUTE, FEED_UNITS, FEED_VARIABLES

# The jobs' modules, and the libraries they load (numpy, pandas, fmpy, Dask), are imported in
# the functions that run a job, not here: the options are made of constants alone, so that
# --help and a mistake in the options are answered at once.

# what a mistake in the input raises (every error class of the package is one of these, with
# a message of one line): the command says it in one line and exits 2
INPUT_ERRORS = (ValueError, OSError)


def numbers(text: str) -> tuple:
    """argparse type: numbers separated by commas."""
    try:
        return tuple(float(x) for x in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected numbers separated by commas") from None


def name_value(text: str) -> tuple:
    """argparse type: NAME=VALUE, the value a number (a --set option)."""
    name, sep, value = text.partition("=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"{text!r}: expected NAME=VALUE")
    try:
        return name, float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: {value!r} is not a number") from None


def value_list(text: str) -> list:
    """argparse type: values as a sweep's --param takes them (grid.parse_values)."""
    from ..batch.grid import parse_values  # the job's libraries, only for an option given
    try:
        return parse_values(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(f"{text!r}: {e}") from None


def positive_number(text: str) -> float:
    """argparse type: a positive number."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (value > 0 and value < float("inf")):
        raise argparse.ArgumentTypeError(f"{text}: must be a positive number")
    return value


def fail(prog: str, message: str, status: int = 2) -> int:
    print(f"{prog}: error: {message}", file=sys.stderr, flush=True)
    return status


def vibration_values(text: str) -> tuple:
    """argparse type: AMPLITUDE,FREQUENCY[,ANGLE_DEG], a vibration's two or three numbers (their
    units the command's: the SI chute's m, Hz, degrees; tribo sweep's its model's)."""
    values = numbers(text)
    if len(values) not in (2, 3):
        raise argparse.ArgumentTypeError(f"{text!r}: expected AMPLITUDE,FREQUENCY[,ANGLE_DEG], "
                                         f"two or three numbers")
    return values


def vibration(text: str) -> dict:
    """argparse type: AMPLITUDE,FREQUENCY[,ANGLE_DEG], the chute's vibration (docs/feeder.md)
    as the SI FMU's parameters by the package's names (m, Hz, degrees); the FMU checks their
    ranges."""
    names = ("vibration_amplitude", "vibration_frequency", "vibration_angle_deg")
    return dict(zip(names, vibration_values(text)))


def add_vibration_option(p: argparse.ArgumentParser) -> None:
    """--vibration, the SI chute's (vibration_of reads it)."""
    p.add_argument("--vibration", type=vibration, default={}, dest="chute_vibration",
                   metavar="AMPLITUDE,FREQUENCY[,ANGLE_DEG]",
                   help="a vibrating chute, a vibratory feeder: the stroke's amplitude (m), "
                        "frequency (Hz) and angle from the chute (degrees, default 90: along its "
                        "normal; docs/feeder.md)")


def vibration_of(args) -> dict:
    """The chute's vibration given by --vibration (add_vibration_option), or none."""
    return getattr(args, "chute_vibration", {})


def add_out_option(p: argparse.ArgumentParser, default: str | None) -> None:
    shown = f" (default {default})" if default else ""
    p.add_argument("--out", default=default, metavar="FOLDER",
                   help=f"the output folder{shown}: it holds one command's results of one "
                        f"set-up; another's is refused, --fresh starts it over (what it held is "
                        f"kept in FOLDER/backup-<n>/)")


def add_materials_option(p: argparse.ArgumentParser) -> None:
    p.add_argument("--materials", metavar="FILE",
                   help="a materials file read over the package's table (tribo.materials: "
                        "a pair's sigma0 and charging parameters, e.g. the materials.toml of "
                        "tribo calibrate)")


def add_feed_options(p: argparse.ArgumentParser, what: str) -> None:
    """What a population's draw takes: -n (how many `what`), --seed, --particle, --wall and a
    distribution per feed variable (populations/feed.py)."""
    p.add_argument("-n", "--particles", type=int, required=True, help=f"how many {what}")
    p.add_argument("--seed", type=int, default=0, help="the draw's seed (default 0)")
    p.add_argument("--particle", default="PE", help="particle material (default PE)")
    p.add_argument("--wall", default="steel", help="wall material (default steel)")
    for name in FEED_VARIABLES:
        p.add_argument(f"--{name.replace('_', '-')}", dest=name, metavar="DIST",
                       help=f"distribution of {name} ({FEED_UNITS[name]})")


def add_chute_options(p: argparse.ArgumentParser) -> None:
    """--chute-length (m) and --tilt-deg, the reference chute's by default."""
    p.add_argument("--chute-length", type=float, default=DEFAULT_CHUTE["chute_length"],
                   help=f"length of the chute, m (default {DEFAULT_CHUTE['chute_length']:g})")
    p.add_argument("--tilt-deg", type=float, default=DEFAULT_CHUTE["tilt_deg"],
                   help=f"tilt of the chute from the horizontal, degrees (default "
                        f"{DEFAULT_CHUTE['tilt_deg']:g})")


def class_edges(text: str) -> tuple:
    """argparse type: class edges, numbers separated by commas, increasing."""
    from ..populations.summary import checked_edges  # the job's libraries, for an option given
    try:
        return tuple(checked_edges(numbers(text), ""))
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def add_class_options(p: argparse.ArgumentParser) -> None:
    """--shape-classes and --size-classes: the edges of a summary's classes."""
    p.add_argument("--shape-classes", type=class_edges, metavar="E0,E1,...",
                   help="edges of the shape classes (default: 4 equal classes over the range)")
    p.add_argument("--size-classes", type=class_edges, metavar="S0,S1,...",
                   help="edges of the size classes, m (default: 4 equal classes over the range)")


def feed_of(args, measured=None):
    """The feed the options of add_feed_options, add_chute_options, --set and --materials
    describe (measured: rows read from --measured, where the command takes it)."""
    from ..materials import with_pair  # the job's libraries, once it runs (see the imports)
    from ..populations.feed import Feed  # the same
    distributions = {n: getattr(args, n) for n in FEED_VARIABLES if getattr(args, n) is not None}
    return Feed(args.particle, args.wall, distributions,
                {"chute_length": args.chute_length, "tilt_deg": args.tilt_deg, **vibration_of(args)},
                with_pair(args.particle, args.wall, dict(args.set), args.materials), measured,
                materials=args.materials)


def add_si_job_options(p: argparse.ArgumentParser, out: str, *, max_runs: str | None = None) -> None:
    """What a job of the SI FMU takes after its own options: --materials, --out (default
    `out`), --fmu, the job options (add_job_options) and --no-plot."""
    add_materials_option(p)
    add_out_option(p, out)
    p.add_argument("--fmu", help="the SI FMU (default: tribo_si_fmi3.fmu of the build)")
    add_job_options(p, max_runs=max_runs)
    p.add_argument("--no-plot", action="store_true", help="no figure")


def add_job_options(p: argparse.ArgumentParser, *, max_runs: str | None = None,
                    fresh: bool = True) -> None:
    """--fresh, --max-runs (where the job takes it: `max_runs` says what it counts),
    --no-progress and where runs execute."""
    add_execution_options(p)
    if fresh:
        p.add_argument("--fresh", action="store_true",
                       help="start the folder over (what it held is kept in <out>/backup-<n>/)")
    if max_runs:
        p.add_argument("--max-runs", type=int, help=f"run at most this many {max_runs} now "
                                                    f"(the rest later)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def add_execution_options(p: argparse.ArgumentParser) -> None:
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="run on the existing Dask cluster at ADDRESS: [tcp://]host[:port], "
                            "port 8786 if none (default: a local cluster in this process, on "
                            "127.0.0.1 only, no dashboard)")
    where.add_argument("--serial", action="store_true", help="run in this process, without Dask")
    where.add_argument("--processes", action="store_true",
                       help="the local cluster's workers as processes on 127.0.0.1 instead of "
                            "threads (many cores and short runs: docs/sweeps.md)")
    p.add_argument("--workers", type=int,
                   help="threads (with --processes: processes) of the local cluster (default: one per core)")
    p.add_argument("--connect-timeout", type=positive_number, default=5.0, metavar="S",
                   help="seconds within which --scheduler must answer as a Dask scheduler with "
                        "workers (default 5)")


def executor_of(args):
    """The executor the options ask for (ValueError for an address Dask does not take).
    Nothing starts until it is entered."""
    from ..batch.executors import executor_for  # the job's libraries, once it runs
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers {args.workers}: at least 1")
    return executor_for(args.serial, args.scheduler, args.workers, args.processes,
                        args.connect_timeout)


def run_job(args, make_job, tell) -> int:
    """A subcommand's run: the job `make_job(args)` through the package's flow into
    args.out (batch/job.py), saying what happens; then `tell(job, report)` gives the lines
    that report it. A mistake is one line on stderr (exit 2), Ctrl-C one line saying what is
    kept (exit 130), failed runs exit 1."""
    from ..batch.job import execute, kept  # the job's libraries, once it runs
    job = None
    try:
        job = make_job(args)
        executor = executor_of(args)
        report = execute(job, args.out, executor, fresh=getattr(args, "fresh", False),
                         progress=not args.no_progress, max_runs=getattr(args, "max_runs", None),
                         say=lambda line: print(line, flush=True))
    except INPUT_ERRORS as e:
        return fail(args.prog, one_line(e))
    except RuntimeError as e:  # a run that failed (a DEM engine's): one line, exit 1
        return fail(args.prog, one_line(e), 1)
    except MemoryError:  # what the bounds (batch/specs.py's MAX_RUNS) let through
        return fail(args.prog, "not enough memory for this job: make it smaller")
    except KeyboardInterrupt:
        what = "nothing kept"
        if job is not None and hasattr(job, "sha256"):  # a job may say what it keeps itself
            what = job.kept(args.out) if hasattr(job, "kept") else kept(job, args.out)
        print(f"{args.prog}: interrupted: {what}; run the same command to resume",
              file=sys.stderr, flush=True)
        return 130
    for line in report.notes + tell(job, report):
        print(line)
    if report.failed:  # said on stderr too, where a script looks for what went wrong
        _, error = report.failed[0]
        return fail(args.prog, f"{len(report.failed)} {getattr(job, 'noun', 'run')}(s) failed, "
                               f"e.g.: {one_line(error)}", 1)
    return 0


# what the console's q/m table says of its unit: the files hold C/kg
QM_UNITS_SAID = "µC/kg here; summary.csv and particles.csv hold C/kg"


def qm_table(summary) -> str:
    """A population's summary (populations/summary.py) as a text table, q/m in µC/kg; the
    counts of how the grains ended are said apart (ends_text)."""
    from ..populations.summary import END_COLUMNS  # loaded by the job that made the summary
    table = summary.drop(columns=END_COLUMNS)
    for c in table.columns[5:]:
        if c not in ("n", "stayed"):
            table[c] = table[c] * 1e6
    return table.drop(columns=["low", "high"]).to_string(index=False,
                                                         float_format=lambda v: f"{v:.4g}")


def one_line(e: BaseException) -> str:
    """An error's message on one line (the first, for a message of several)."""
    text = str(e).strip() or type(e).__name__
    return text.splitlines()[0]

"""tribo: the tribocharging particle model's FMUs from the command line, one subcommand per
job (`tribo <command> --help` for each).

Every job writes into an output folder (--out) that holds one command's results of one
set-up, runs on Dask (a local cluster in this process, --scheduler for an existing one,
--serial for none), resumes when run again after an interruption, and meets a mistake
with one line (docs/sweeps.md). The package's functions (tribo.population, tribo.sweep,
...) run the same jobs from Python.
"""

import importlib
import sys
import time

from .parsing import OneLineParser, described

# the subcommands, each a module of this folder (tribo/cli/<module>.py) with add_arguments
# (parser) and run(args), by name with the module and the line `tribo --help` gives it: a new
# subcommand is its module and its line here
SUBCOMMANDS = {
    "population": ("population",
                   "particles drawn from a feed, down the chute (SI FMU): q/m statistics and figure"),
    "grain": ("grain", "one grain down the chute (SI FMU): how its run ended and its q/m"),
    "line": ("line", "grains down the SI chute and through the separator: one grain, a mixture, "
                     "a voltage sweep"),
    "impact-map": ("impact_map", "the charge one wall impact transfers, over speed, angle, "
                                 "orientation and roundness"),
    "calibrate": ("calibrate", "a pair's charging parameters fitted to measured impacts and chute "
                               "runs; a materials file"),
    "sweep": ("sweep", "a parameter sweep of the dimensionless FMU: every combination of the "
                       "values given"),
    "study": ("study", "the paper's study (docs/model.md section 7): eps_t of each friction "
                       "case, figures, tables"),
    "dem": ("dem", "a population's grains through the chute in LIGGGHTS, each impact charged: q/m"),
}
# other names of the subcommands, as console scripts (pyproject.toml): each runs its
# subcommand, with its options, and its --help says whose alias it is
ALIASES = {"tribo-population": "population", "tribo-line": "line",
           "tribo-impact-map": "impact-map", "tribo-sweep": "sweep", "tribo-study": "study"}


def subcommand(name: str):
    return importlib.import_module(f"{__package__}.{SUBCOMMANDS[name][0]}")


def add_subcommand(p, module, prog: str) -> None:
    """A subcommand's options on the parser p (its prog set for the messages)."""
    module.add_arguments(p)
    p.set_defaults(run=module.run, prog=prog)


def parser(argv=None) -> OneLineParser:
    """`tribo`'s parser. Given the command line argv, only the subcommand it names is
    imported and takes its options (the others are listed with their line), so that a
    command does not import every job's libraries, and --help or a mistake answers at once;
    without, every subcommand's."""
    p = OneLineParser(prog="tribo", **described(__doc__))
    commands = p.add_subparsers(title="commands", dest="command", metavar="COMMAND",
                                required=True, parser_class=OneLineParser)
    named = None if argv is None else next((a for a in argv if not a.startswith("-")), "")
    p.subcommands = {}  # name -> its parser, which says what it does not take (_run)
    for name, (_, line) in SUBCOMMANDS.items():
        if named is None or name == named:
            module = subcommand(name)
            sub = commands.add_parser(name, help=line, **described(module.__doc__))
            add_subcommand(sub, module, sub.prog)
        else:
            sub = commands.add_parser(name, help=line)
        p.subcommands[name] = sub
    return p


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    return _run(parser(argv), argv, 1)


def _run(p, argv, skip: int) -> int:
    """Parse argv (default: the command line) and run its subcommand, telling it the
    arguments as typed after the `skip` that name it and when the command started (what
    a job may report: the study's study.md says both)."""
    started = time.perf_counter()
    argv = sys.argv[1:] if argv is None else list(argv)
    args, unknown = p.parse_known_args(argv)
    if unknown:  # said by the subcommand, whose options they are not
        parser = getattr(p, "subcommands", {}).get(getattr(args, "command", None), p)
        parser.error(f"unrecognized arguments: {' '.join(unknown)}")
    args.typed, args.started = argv[skip:], started
    return args.run(args)


def alias(name: str, argv=None) -> int:
    """The console script `name` (ALIASES): its subcommand's options and run, its --help
    saying it is an alias."""
    module = subcommand(ALIASES[name])
    new = f"tribo {ALIASES[name]}"
    options = described(module.__doc__)
    what = options["description"].removeprefix(f"{new}: ")
    options["description"] = f"{name}: alias of `{new}`: {what}"
    p = OneLineParser(prog=name, **options)
    add_subcommand(p, module, name)
    return _run(p, argv, 0)


def population(argv=None) -> int:
    return alias("tribo-population", argv)


def line(argv=None) -> int:
    return alias("tribo-line", argv)


def impact_map(argv=None) -> int:
    return alias("tribo-impact-map", argv)


def sweep(argv=None) -> int:
    return alias("tribo-sweep", argv)


def study(argv=None) -> int:
    return alias("tribo-study", argv)


if __name__ == "__main__":
    sys.exit(main())

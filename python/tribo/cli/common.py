"""What the commands share: errors in one line, the checks made before any run (the
output is writable, the scheduler's address is one Dask takes), the output folder (--out,
the same for every command) and where runs execute."""

import argparse
import os
import sys
import tempfile

from ..batch.executors import DaskExecutor, SerialExecutor
from ..batch.grid import parse_values


class OneLineParser(argparse.ArgumentParser):
    """argparse, with a usage error in one line (no usage block)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


def command_parser(prog: str, doc: str) -> OneLineParser:
    """A command's parser: its description the first paragraph of the module's docstring
    `doc`, the rest of it the epilogue of --help."""
    return OneLineParser(prog=prog, description=doc.split("\n\n")[0],
                         formatter_class=argparse.RawDescriptionHelpFormatter,
                         epilog=doc.split("\n\n", 1)[1])


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
    try:
        return parse_values(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(f"{text!r}: {e}") from None


def fail(prog: str, message: str, status: int = 2) -> int:
    print(f"{prog}: error: {message}", file=sys.stderr, flush=True)
    return status


def check_writable_dir(path: str) -> None:
    """OSError, naming the path, unless files can be made in the folder (made if missing)."""
    if os.path.exists(path) and not os.path.isdir(path):
        raise OSError(f"cannot write into {path}: a file, not a folder")
    try:
        os.makedirs(path, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path, prefix=".tribo_write_check_"):
            pass
    except OSError as e:
        raise OSError(f"cannot write into {path}: {e.strerror or e}") from None


def positive_number(text: str) -> float:
    """argparse type: a positive number."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not (value > 0 and value < float("inf")):
        raise argparse.ArgumentTypeError(f"{text}: must be a positive number")
    return value


def add_out_option(p: argparse.ArgumentParser, default: str) -> None:
    p.add_argument("--out", default=default, metavar="FOLDER",
                   help=f"the output folder (default {default}): it holds one command's "
                        f"results of one set-up; another's is refused, --fresh starts it over "
                        f"(what it held is kept in FOLDER/backup-<n>/)")


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
    if args.serial:
        return SerialExecutor()
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers {args.workers}: at least 1")
    return DaskExecutor(args.scheduler, args.workers, connect_timeout=args.connect_timeout,
                        processes=args.processes)

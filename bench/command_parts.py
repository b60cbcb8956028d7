"""command_parts: a package command's CPU split into its runs' own and the rest, serially,
on the local cluster's 2 threads and on 2 worker processes (a command, not a test;
docs/populations.md "Benchmark: the map against its core", docs/line.md "Benchmark").

    TRIBO_BUILD_DIR=build .venv/bin/python bench/command_parts.py COMMAND [ARGS...]

e.g. `bench/command_parts.py impact-map --speed 0.25:8:10 --angle-deg 15:90:6 --phi0-deg
0:150:6 --epsilon 0.4:1:6`. Each mode runs `tribo COMMAND ARGS` in a fresh interpreter, into
a temporary folder, without a figure or a progress bar, which then reports its own CPU (the
local cluster's threads included), its worker processes' (waited for as the cluster
closes) and the sum of the runs' own CPU (the `cpu_s` column of the rows the command
wrote: each run's thread's CPU). The rest is the command's: its imports, its folder, its
rows, and on Dask the cluster, its tasks and their results.
"""

import contextlib
import io
import os
import resource
import subprocess
import sys
import tempfile

import pandas as pd

MODES = {"serial": ["--serial"], "threads": ["--workers", "2"],
         "processes": ["--workers", "2", "--processes"]}


def one(out: str, command: list[str]) -> None:
    """The command in this process, then its CPU: this process's, its children's, the runs'."""
    from tribo.cli.main import main as tribo_command

    with contextlib.redirect_stdout(io.StringIO()):
        tribo_command([*command, "--no-plot", "--no-progress", "--out", out])
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    runs = sum(pd.read_csv(os.path.join(out, name))["cpu_s"].sum()
               for name in os.listdir(out)
               if name.endswith(".csv") and "cpu_s" in pd.read_csv(os.path.join(out, name), nrows=0))
    print(own.ru_utime + own.ru_stime, children.ru_utime + children.ru_stime, runs)


def main():
    if sys.argv[1] == "--one":
        one(sys.argv[2], sys.argv[3:])
        return
    command = sys.argv[1:]
    print(f"tribo {' '.join(command)}")
    print("| mode | CPU in all | the command's process | its worker processes | the runs' own | the rest |")
    print("|---|---|---|---|---|---|")
    for mode, options in MODES.items():
        with tempfile.TemporaryDirectory(prefix="tribo_parts_") as tmp:
            said = subprocess.run([sys.executable, __file__, "--one", os.path.join(tmp, "out"),
                                   *command, *options], check=True, capture_output=True,
                                  text=True).stdout
        own, children, runs = (float(x) for x in said.split())
        total = own + children
        print(f"| {mode} | {total:.2f} s | {own:.2f} s | {children:.2f} s | {runs:.2f} s | "
              f"{total - runs:.2f} s |")


if __name__ == "__main__":
    main()

"""Shared by the tests of the package's study and sweep tools: short runs, the FMU as the
package takes it, the commands as a user runs them."""

import os
import sys
from functools import cache

from tribo.batch.particle import run_fmu
from tribo.batch.sweep import TIMING_COLUMNS
from tribo.fmu import FmuImage, model_description
from tribo.fmu.locate import find_fmu
from tribo.fmu.parameters import integer_names
from tribo.study.paper import paper_spec

PYTHON = sys.executable
BIN = os.path.dirname(PYTHON)  # the venv's bin/, where pip put the entry points


def command(name: str) -> str:
    """The path of a console command of the package (tribo, or an alias such as tribo-sweep)."""
    return os.path.join(BIN, name)


def subcommand(name: str) -> list[str]:
    """The command line of a subcommand of `tribo` (population, sweep, ...), as typed."""
    return [command("tribo"), name]


@cache
def fmu_integer_names() -> tuple:
    """The parameters that take whole numbers, from the build's FMU (both FMI versions have
    the same)."""
    return integer_names(model_description(find_fmu()))


def short_spec(epsilon, friction, t_end=200.0, **overrides):
    """A short run of the paper's set-up with few segments (turning and the motion classes do
    not depend on the segment count: charging does not act back on the motion)."""
    return paper_spec(epsilon, friction, t_end, integer_names=fmu_integer_names(),
                      **dict({"n_segments": 64}, **overrides))


def without_timing(df):
    """A results table without the columns that differ between executions of a run."""
    return df.drop(columns=[c for c in TIMING_COLUMNS if c in df.columns])


class CountingRun:
    """run_fmu, counting (and optionally stopping) the runs it executes."""

    def __init__(self, interrupt_after=None):
        self.specs = []
        self.interrupt_after = interrupt_after

    def __call__(self, image, spec):
        if self.interrupt_after is not None and len(self.specs) >= self.interrupt_after:
            raise KeyboardInterrupt  # as Ctrl-C in the middle of a sweep
        self.specs.append(spec)
        return run_fmu(image, spec)


def image_of(fmu_file, version=2):
    return FmuImage.load(fmu_file(version))

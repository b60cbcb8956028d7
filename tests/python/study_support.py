"""Shared by the tests of the study package (examples/tribo_study): puts examples/ on
sys.path and gives the FMU as the package takes it."""

import os
import sys

EXAMPLES = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "examples"))
if EXAMPLES not in sys.path:
    sys.path.insert(0, EXAMPLES)

from tribo_study.fmu_run import FmuImage, run_fmu  # noqa: E402
from tribo_study.specs import paper_spec  # noqa: E402
from tribo_study.sweep import TIMING_COLUMNS  # noqa: E402

PYTHON = sys.executable


def short_spec(epsilon, friction, t_end=200.0, **overrides):
    """A short run of the paper's set-up with few segments (turning and the contact modes do
    not depend on the segment count: charging does not act back on the motion)."""
    return paper_spec(epsilon, friction, t_end, **dict({"n_segments": 64}, **overrides))


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

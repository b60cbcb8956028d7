"""examples/feeder.py, which makes docs/feeder.md's tables and figures, runs as its docstring
says, at one grain a length, into a folder that does not exist yet; a bad size is refused in
one line before any work."""

import os
import subprocess

import pandas as pd

from study_support import PYTHON
from tribo_fmu import ROOT

SCRIPT = os.path.join(ROOT, "examples", "feeder.py")


def test_the_feeder_example_writes_its_tables_and_figures_into_a_new_folder(tmp_path):
    out = tmp_path / "not" / "yet"
    subprocess.run([PYTHON, SCRIPT, "--grains", "1", "--workers", "1", "--out", str(out)],
                   check=True, capture_output=True, text=True, timeout=600)
    for name in ("feeder_speed.csv", "feeder_length.csv", "feeder_speed.png", "feeder_length.png"):
        assert (out / name).stat().st_size > 0, name
    speeds = pd.read_csv(out / "feeder_speed.csv")
    # Every set-up of the table conveys along the stroke: a throw number above 1 hops the grain.
    assert (speeds["speed"] > 0).all() and (speeds["K"] > 1).all()
    lengths = pd.read_csv(out / "feeder_length.csv").pivot(index="length_m", columns="device",
                                                           values="impacts_median")
    # A feeder's grain meets the plate at every hop: more impacts than the still chute's at the
    # same length, from 0.3 m on (at 0.1 m one grain's count is too few to order them).
    assert (lengths.loc[lengths.index >= 0.3, "feeder"] >
            lengths.loc[lengths.index >= 0.3, "still chute"]).all()


def test_the_feeder_example_refuses_a_size_below_one(tmp_path):
    run = subprocess.run([PYTHON, SCRIPT, "--grains", "0", "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 2
    assert "--grains 0" in run.stderr and "at least 1" in run.stderr
    assert list(tmp_path.iterdir()) == []

"""The vibrating chute, a vibratory feeder (docs/model.md section 9b), through the SI FMUs and
the package: the SI names, the throw number, the vibration's work, the commands' --vibration
and bad input in one line."""

import math
import os
import subprocess
import sys

import pandas as pd
import pytest

import tribo

FEEDER = dict(size=1e-3, epsilon=0.6, chute_length=0.05, tilt_deg=0.0, drop_height=1e-3,
              vibration_amplitude=5e-4, vibration_frequency=50.0, vibration_angle_deg=30.0)


@pytest.mark.parametrize("version", [2, 3])
def test_a_level_feeder_conveys_the_grain_forward_by_hops(version):
    df = tribo.run_si("PE", "steel", t_end=3.0, record_interval=0.01, fmu=version, **FEEDER)
    last = df.iloc[-1]
    # K = A (2 pi f)^2 sin(psi) / (g cos(tilt)) = 5e-4 (100 pi)^2 0.5 / 9.81
    K = 5e-4 * (2 * math.pi * 50) ** 2 * 0.5 / 9.81
    assert last["throw_number"] == pytest.approx(K, rel=1e-12)
    assert last["exited"] == 1  # a level chute: the stroke alone conveys the grain
    assert last["x"] >= 0.05
    assert last["impacts"] >= 10  # hops: measured 40
    assert last["work_vibration"] > 0.0


def test_a_still_chute_does_no_vibration_work():
    last = tribo.run_si("PE", "steel", size=1e-3, chute_length=0.05, drop_height=1e-3,
                        record_interval=None).iloc[-1]
    assert last["work_vibration"] == 0.0
    assert last["throw_number"] == 0.0


@pytest.mark.parametrize("settings, expect", [
    (dict(vibration_amplitude=-1e-4), ["vibration_amplitude", "-0.0001", "0 <= vibration_amplitude"]),
    (dict(vibration_amplitude=5e-4, vibration_frequency=0.0),
     ["vibration_frequency = 0 Hz", "vibration_amplitude = 0.0005 m", "(0, 1e6]"]),
    (dict(vibration_angle_deg=100.0), ["vibration_angle_deg", "100"]),
    (dict(vibration_amplitude=0.1, vibration_frequency=1e5), ["vib_accel", "<= 10", "size = 0.001 m"]),
])
def test_bad_vibrations_are_refused_in_one_line(settings, expect):
    # a value out of its own range before the run (ValueError); a combination the front end
    # refuses when the FMU makes its model (RuntimeError), in the package's terms
    with pytest.raises((ValueError, RuntimeError)) as e:
        tribo.run_si("PE", "steel", size=1e-3, chute_length=0.05, record_interval=None, **settings)
    message = str(e.value)
    assert "\n" not in message and "semi_major_axis" not in message
    for part in expect:
        assert part in message, message


def test_the_population_and_the_line_take_the_vibration(tmp_path):
    population = tmp_path / "population"
    done = subprocess.run(
        [sys.executable, "-m", "tribo", "population", "-n", "2", "--seed", "1",
         "--chute-length", "0.03", "--tilt-deg", "0", "--vibration", "5e-4,50,30", "--serial",
         "--no-plot", "--no-progress", "--t-end", "3", "--out", str(population)],
        capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    rows = pd.read_csv(population / "particles.csv")
    assert (rows["vibration_amplitude"] == 5e-4).all()
    assert (rows["vibration_frequency"] == 50.0).all()
    assert (rows["vibration_angle_deg"] == 30.0).all()
    assert (rows["exited"] == 1).all()
    # the line's chute= takes the SI names
    grain = tribo.line_grain("PE", "steel", chute=dict(chute_length=0.03, tilt_deg=0.0,
                                                       vibration_amplitude=5e-4,
                                                       vibration_frequency=50.0,
                                                       vibration_angle_deg=30.0), t_end=3.0)
    assert grain["exited"] == 1


def test_a_malformed_vibration_option_is_refused_in_one_line(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "tribo", "population", "-n", "2", "--vibration", "5e-4",
         "--serial", "--out", str(tmp_path / "p")], capture_output=True, text=True)
    assert done.returncode == 2
    assert "AMPLITUDE,FREQUENCY[,ANGLE_DEG]" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr

"""The motion classes at physical scale (docs/model.md, "Derived outputs"): a 1 mm grain
through the SI FMU (Gamma ~ 1e-8) is classed as the paper's classes say, one set-up per
class. The classifier's window is the paper's 20 time units at its set-up, scaled to a
scene's gravity time and to the flights of its drop's bounces; at Gamma = 1e-8 the paper's
window (20 t*, ~13 us) once read a grain rolling without slip as 77 % rocking, 0 % rolling,
and every bouncing grain as ~99.9 % flight. The fractions' bounds below leave the first
window's filling (it reads bouncing, a few per cent) and the drop's flight to the other
classes."""

import pytest

from tribo_fmu import Slave

SI = "tribo_si"
CLASSES = ["flight", "rocking", "rolling", "tumbling", "bouncing"]
# set down on the chute (no drop), or dropped from 1 cm (the SI default); 64 segments: the
# charges play no part
SET_DOWN = {"drop_height": 0.0, "n_segments": 64}
DROPPED = {"n_segments": 64}


def classes(fmu_dir, t_end, **params):
    """(the class every 10 ms, the fractions at the end) of a run of the SI FMU."""
    s = Slave(fmu_dir(3, SI), 3).init(**params)
    seen = []
    for k in range(1, round(t_end / 0.01) + 1):
        if not s.step_to(k * 0.01):
            break
        seen.append(CLASSES[int(s.get("motion_class"))])
    assert s.errors() == []
    return seen, {c: s.get(f"fraction_{c}") for c in CLASSES}


def test_a_sphere_rolling_without_slip_reads_rolling(fmu_dir):
    # a circle's section (epsilon = 1) at mu = 1: it rolls down the 30 degree chute, a w = u
    # (measured: 93 % rolling, 4 % rocking while its spin is still slow, 3 % filling)
    seen, fraction = classes(fmu_dir, 0.3, epsilon=1.0, mu=1.0, **SET_DOWN)
    assert fraction["rolling"] > 0.85 and seen[-1] == "rolling"
    assert fraction["flight"] == fraction["tumbling"] == 0.0


def test_a_flat_grain_sliding_reads_rocking(fmu_dir):
    # epsilon = 0.3 set down flat at mu = 0.1: it slides with its orientation kept (measured
    # 96.5 % rocking)
    seen, fraction = classes(fmu_dir, 0.3, epsilon=0.3, mu=0.1, **SET_DOWN)
    assert fraction["rocking"] > 0.9 and seen[-1] == "rocking"
    assert fraction["flight"] == fraction["rolling"] == 0.0


def test_a_grain_falling_reads_flight_then_bouncing_on_a_level_plate(fmu_dir):
    # dropped from 2 cm onto a level frictionless plate: no spin, so its bounces do not turn
    # it; it falls for 64 ms (measured: 13 % flight, 87 % bouncing over 0.5 s)
    seen, fraction = classes(fmu_dir, 0.5, tilt=0.0, mu=0.0, nu=0.1, drop_height=0.02,
                             n_segments=64)
    assert seen[:5] == ["flight"] * 5
    assert fraction["bouncing"] > 0.8 and 0.05 < fraction["flight"] < 0.2
    assert fraction["rolling"] == fraction["tumbling"] == 0.0


def test_a_grain_bouncing_down_the_chute_reads_tumbling(fmu_dir):
    # the SI default: dropped from 1 cm onto the 30 degree chute, each impact spins it up and
    # it turns over between bounces of 60-90 ms (measured: 10.5 % flight, the drop; 89 %
    # tumbling)
    seen, fraction = classes(fmu_dir, 0.4, **DROPPED)
    assert fraction["tumbling"] > 0.75 and fraction["flight"] < 0.2
    assert seen.count("flight") <= 5  # the drop's 45 ms, not the flights between bounces

"""examples/image_force.py: the master that feeds the image charge's pull back into the SI
FMU every communication step (F_N_ext = -lambda^2 / (4 pi eps0 max(y, b)))."""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

import tribo

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "image_force.py"
EPS0 = 8.8541878128e-12  # F/m, CODATA 2018, written here again, not taken from the example

# a 1 mm PE grain dropped 1 mm onto steel: first impact after about 14 ms
SMALL = dict(chute_length=0.3, drop_height=1e-3)
T_END, STEP = 0.03, 1e-4


def example():
    spec = importlib.util.spec_from_file_location("image_force", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def image_force():
    return example()


def params(**kw):
    return tribo.materials.start_values("PE", "steel", **SMALL, **kw)


def test_the_loop_feeds_the_image_pull_of_the_output_charge(image_force):
    times, rows, _, _ = image_force.run_coupled(params(), T_END, STEP, "sliding",
                                                outputs=("y", "charge_per_length_sliding",
                                                         "in_contact"))
    assert len(times) == round(T_END / STEP) + 1 and np.all(np.diff(times) > 0)
    b = 0.6 * 0.5e-3  # the SI FMU's default epsilon and semi-major axis
    fed = [r for r in rows[:-1] if r["lambda"] != 0.0]
    assert len(fed) > 10, "the grain charged on its first impacts"
    for r in fed:
        # the line charge is the cylinder's charge per length (whatever grain the charge
        # outputs report)
        assert r["lambda"] == pytest.approx(r["charge_per_length_sliding"], rel=1e-12)
        expected = -r["lambda"] ** 2 / (4 * math.pi * EPS0 * max(r["y"], b))
        assert r["F_N_ext"] < 0.0  # towards the chute
        assert r["F_N_ext"] == pytest.approx(expected, rel=1e-9)  # eps0's digits


def test_the_height_is_bounded_at_the_semi_minor_axis(image_force):
    # an indented grain (y < b) is pulled as at y = b; above b the force falls as 1 / y
    b = 3e-4
    at_b = image_force.image_force_per_length(1e-9, b, b)
    assert at_b == pytest.approx(-1e-18 / (4 * math.pi * EPS0 * b), rel=1e-9)
    assert image_force.image_force_per_length(1e-9, 0.999 * b, b) == at_b
    assert image_force.image_force_per_length(1e-9, 2 * b, b) == pytest.approx(at_b / 2, rel=1e-15)


def test_with_no_charge_the_coupled_run_is_the_uncoupled_one(image_force):
    outs = ("x", "y", "phi", "u", "v", "omega", "energy")
    off = dict(charge_model_static=0, charge_model_sliding=0)
    closed = image_force.run_coupled(params(**off), T_END, STEP, "sliding", outputs=outs)
    open_ = image_force.run_coupled(params(**off), T_END, STEP, "sliding", couple=False,
                                    outputs=outs)
    assert all(r["F_N_ext"] == 0.0 for r in closed[1][:-1])
    np.testing.assert_array_equal(closed[0], open_[0])
    for a, b in zip(closed[1], open_[1]):
        assert [a[n] for n in outs] == [b[n] for n in outs]


def test_a_charge_changes_the_motion(image_force):
    # the sliding model's charge (-100 uC/kg in the reference case) pulls harder than the
    # weight at contact: the coupled grain's path leaves the uncoupled one's
    closed = image_force.run_coupled(params(), T_END, STEP, "sliding")
    open_ = image_force.run_coupled(params(), T_END, STEP, "sliding", couple=False)
    assert closed[1][-1]["y"] != open_[1][-1]["y"]


def test_threshold_scales_as_the_formula(image_force):
    # image force at y = b over m' g cos(tilt): at fixed q/m it is (q/m)^2 rho a / (4 eps0 g
    # cos tilt), independent of epsilon; at fixed sigma it falls as 1/a
    rows = image_force.threshold_table([0.1, 1.0], 0.6, 950.0, math.radians(30), 1e-4)
    for r in rows:
        a = 0.5e-3 * r["size_mm"]
        expected = 1e-8 * 950.0 * a / (4 * EPS0 * 9.81 * math.cos(math.radians(30)))
        assert r["ratio_reference_qm"] == pytest.approx(expected, rel=1e-9)
    assert rows[0]["ratio_breakdown"] == pytest.approx(10 * rows[1]["ratio_breakdown"], rel=1e-12)

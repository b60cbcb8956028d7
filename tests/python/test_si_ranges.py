"""The SI FMUs' declared ranges are true (src/si/si_quantities.def, docs/model.md §8): each SI
parameter alone at its declared min and at its declared max, the others at their start
values, is accepted at exitInitializationMode and runs one short doStep with finite
outputs. A range the model cannot take whole is narrowed in the table, with the conditions
that involve other parameters stated in the variable's description."""

import math

import pytest
from fmpy import read_model_description

from tribo_fmu import OK, VERSIONS, Slave

SI = "tribo_si"
# a short communication step, in s: a few t_star of the reference case (t_star ~ 1e-6 s)
STEP = 1e-6
# DISCARD: a step that spent its work limit (FMI 2.0) or ended the run (the chute's end,
# a lift-off) still leaves finite outputs at the time reached
DISCARD = 2
# conditions on several parameters, stated in the variable's description: the value at the
# end of the range is set with these (the rigid stick needs CVODE and the contact point's
# dashpot; the drop lies before the chute's end, 0.3 m by default)
WITH = {("integrator", 0): {"stick_model": 0}, ("damping_point", 1): {"stick_model": 0},
        ("x0", 100.0): {"chute_length": math.inf}}


def conditions(described, name, value):
    """What the end `value` of `name` is set with: WITH's, and for charge_to_mass_model = n
    the n-th charge model switched on (its description: the model named must be included;
    its switch charge_model_<name> has the value reference 60 + n - 1), which a model that
    is off by default needs."""
    given = dict(WITH.get((name, value), {}))
    if name == "charge_to_mass_model" and value > 0:
        switch = next(v.name for v in described.modelVariables
                      if v.valueReference == 60 + int(value) - 1)
        given[switch] = 1
    return given


def stated(description, other):
    """Whether a description states the condition on `other` (a switch by its pattern)."""
    return other in description or (other.startswith("charge_model_") and
                                    "charge_model_<name>" in description)


def ends(described):
    """(name, value) for each end of each SI parameter's declared range, and the Boolean
    ones' two values."""
    out = []
    for v in described.modelVariables:
        if v.causality not in ("parameter", "structuralParameter"):
            continue
        for bound in (v.min, v.max):
            if bound is not None and math.isfinite(float(bound)):
                out.append((v.name, float(bound)))
    # sigma0 = 0, inside its range: a neutral pair
    return out + [("sigma0", 0.0)]


@pytest.mark.parametrize("version", VERSIONS)
def test_every_si_parameter_runs_at_both_ends_of_its_range(version, fmu_file, fmu_dir):
    described = read_model_description(fmu_file(version, SI))
    outputs = [v.name for v in described.modelVariables
               if v.causality == "output" and v.type in ("Real", "Float64")
               and not v.dimensions]
    refused = []
    for name, value in ends(described):
        with Slave(fmu_dir(version, SI), version, name=SI) as s:
            given = conditions(described, name, value)
            refused += [f"{name} = {value!r} needs {other}, which its description does not state"
                        for other in given
                        if not stated(described_of(described, name).description, other)]
            s.set_parameters({name: value, **given})
            try:
                s.init()
            except Exception as e:  # noqa: BLE001: every refusal is collected, then reported
                refused.append(f"{name} = {value!r}: refused at initialization ({e})")
                continue
            status, _, _ = s.do_step(0.0, STEP)
            bad = [o for o, x in s.get_many(outputs).items() if not math.isfinite(x)]
            if status not in (OK, DISCARD) or bad:
                refused.append(f"{name} = {value!r}: doStep status {status}, non-finite {bad}")
    assert not refused, "\n".join(refused)



def described_of(described, name):
    return next(v for v in described.modelVariables if v.name == name)

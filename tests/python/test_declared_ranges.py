"""Every FMU's declared ranges are the ranges it accepts: each parameter and input alone, the
others at their start values, at both ends of its declared range and just inside them (the
next double; the next integer), is taken by the set call, initializes, and runs one short
doStep with every output a number (docs/fmu.md, docs/si.md, docs/separator.md). A range the
model cannot take whole at the start values is narrowed in the table, the conditions that
involve other parameters stated in the variable's description; a default that depends on
another parameter follows it (`stick_model` in the SI FMUs, rigid only where the integrator
and the dashpot allow it)."""

import math

import pytest
from fmpy import read_model_description

from test_model_description import raw_variables
from tribo_fmu import OK, VERSIONS, Slave

DISCARD = 2
# one short communication step in each FMU's unit of time (the SI chute's: a few t_star)
STEPS = {"tribo": 0.1, "tribo_si": 1e-6, "tribo_separator": 1e-3}
# every value of a Boolean
BOOLEAN_VALUES = (0, 1)
# A parameter that only some set-ups use is tried in one that uses it: these settings go
# with every value tried.
USED_WHERE = {("tribo_si", "contact_stiffness"): {"stiffness_source": 0}}


def values_to_try(v, attributes):
    """The ends of v's declared range and the values just inside them."""
    if v.type == "Boolean":
        return list(BOOLEAN_VALUES)
    lo, hi = float(attributes["min"]), float(attributes.get("max", math.inf))
    if v.type in ("Real", "Float64"):
        ends = [lo, math.nextafter(lo, hi)]
        if math.isfinite(hi):
            ends += [math.nextafter(hi, lo), hi]
        return ends
    return sorted({int(lo), min(int(lo) + 1, int(hi)), max(int(hi) - 1, int(lo)), int(hi)})


def settable(md):
    return [v for v in md.modelVariables
            if v.causality in ("parameter", "structuralParameter", "input")
            and not v.dimensions and v.name != "hold_at_end"]


def outputs(md):
    return [v for v in md.modelVariables if v.causality in ("output", "calculatedParameter")
            and not v.dimensions]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("prefix", sorted(STEPS))
def test_every_variable_alone_runs_at_and_inside_both_ends_of_its_range(fmu_dir, prefix,
                                                                         version):
    md = read_model_description(fmu_dir(version, prefix), validate=False)
    # (the XML's own min and max: fmpy leaves out those of some types)
    attributes = {a["name"]: a for a in raw_variables(fmu_dir, version, prefix)}
    computed = outputs(md)
    refused = []
    for v in settable(md):
        for value in values_to_try(v, attributes[v.name]):
            with Slave(fmu_dir(version, prefix), version, name=prefix) as s:
                what = f"{v.name} = {value!r}"
                try:
                    s.set(**USED_WHERE.get((prefix, v.name), {}), **{v.name: value})
                except Exception as e:  # noqa: BLE001: every refusal is collected, then reported
                    refused.append(f"{what}: refused by the set call ({s.errors()[-1:]}: {e})")
                    continue
                try:
                    s.init()
                except Exception as e:  # noqa: BLE001
                    refused.append(f"{what}: refused at initialization ({e})")
                    continue
                status, _, _ = s.do_step(0.0, STEPS[prefix])
                got = s.get_many([o.name for o in computed])
                # (a calculated parameter of a parameter that may be INF may be INF: the
                # chute's length with no end, no breakdown limit)
                bad = [o.name for o in computed if not math.isfinite(got[o.name]) and
                       not (got[o.name] == math.inf and o.causality == "calculatedParameter")]
                if status not in (OK, DISCARD) or bad:
                    refused.append(f"{what}: doStep status {status} ({s.errors()[-1:]}), "
                                   f"not numbers: {bad}")
    assert not refused, "\n".join(refused)

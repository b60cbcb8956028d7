"""What the descriptions declare about types, metadata and structure, and that the FMUs
behave so: flags are Booleans, choices and the motion class Enumerations whose items are
the values the FMU takes and gives, counts Integers; the metadata is complete; and the
declared (empty) dependencies of the outputs on the inputs hold: setting an input
changes no output until the next step."""

import math
import os
import re

import pytest
from fmpy import read_model_description

from tribo_fmu import ERROR, ROOT, VERSIONS, Slave, core_run, status_of

SMALL = {"n_segments": 64}


def description(fmu_dir, version):
    return read_model_description(fmu_dir(version), validate=True)


def variables(fmu_dir, version):
    return {v.name: v for v in description(fmu_dir, version).modelVariables}


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(tribo VERSION ([\d.]+)", f.read()).group(1)


@pytest.mark.parametrize("version", VERSIONS)
def test_flags_are_booleans_and_counts_integers(fmu_dir, version):
    v = variables(fmu_dir, version)
    for flag in ("in_contact", "slipping", "exited", "lifted_off", "at_rest"):
        assert (v[flag].type, v[flag].variability) == ("Boolean", "discrete"), flag
    for count in ("assumption_warnings", "impacts"):
        assert v[count].type == ("Integer" if version == 2 else "Int32"), count
        assert v[count].variability == "discrete", count
    assert v["n_segments"].type == ("Integer" if version == 2 else "UInt64")
    # everything else an output is, is a real
    others = {n for n, x in v.items() if x.causality == "output"} - \
        {"in_contact", "slipping", "exited", "lifted_off", "at_rest", "assumption_warnings", "impacts",
         "motion_class", "end_reason"}
    assert {v[n].type for n in others} == {"Real" if version == 2 else "Float64"}


ENUMERATIONS = {  # variable: (type, items by value)
    "charge_model_static": ("tribo.Switch", ["off", "on"]),
    "integrator": ("tribo.Integrator", ["fixed_step", "cvode_adams", "cvode_bdf"]),
    "motion_class": ("tribo.MotionClass", ["flight", "rocking", "rolling", "tumbling", "bouncing"]),
    "run_end": ("tribo.RunEnd", ["chute_exit", "first_liftoff"]),
    "end_reason": ("tribo.EndReason", ["running", "chute_exit", "first_liftoff", "at_rest"]),
}


@pytest.mark.parametrize("version", VERSIONS)
def test_choices_and_motion_class_are_enumerations(fmu_dir, version):
    v = variables(fmu_dir, version)
    for name, (type_name, items) in ENUMERATIONS.items():
        assert v[name].type == "Enumeration", name
        declared = v[name].declaredType
        assert declared.name == type_name
        assert [(i.name, int(i.value)) for i in declared.items] == \
            [(item, value) for value, item in enumerate(items)]
        assert all(i.description for i in declared.items)
        if v[name].causality == "parameter":
            # the declared range is exactly the items, and every item is accepted
            assert (int(v[name].min), int(v[name].max)) == (0, len(items) - 1)
            for value in range(len(items)):
                s = Slave(fmu_dir(version), version)
                s.set(**{name: value})
                assert s.get(name) == value
                s.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_enumerated_and_boolean_outputs_read_as_the_core_gives_them(fmu_dir, reference_exe, version):
    """Through the typed getters, at a time the particle is in contact and slipping."""
    s = Slave(fmu_dir(version), version).init(**SMALL)
    core = core_run(reference_exe, SMALL, [(t, []) for t in (0.5, 1.0, 60.0)])
    for t, c in zip((0.5, 1.0, 60.0), core):
        s.step_to(t)
        got = s.get_many(["in_contact", "slipping", "motion_class", "assumption_warnings"])
        assert got == {"in_contact": bool(c["in_contact"]), "slipping": bool(c["slipping"]),
                       "motion_class": int(c["motion_class"]),
                       "assumption_warnings": int(c["assumption_warnings"])}, t
    assert any(c["in_contact"] for c in core) and any(not c["in_contact"] for c in core)
    assert s.get("motion_class") != 0  # not flight: the enumeration is read, not a default


@pytest.mark.parametrize("version", VERSIONS)
def test_a_boolean_output_cannot_be_set(fmu_dir, version):
    s = Slave(fmu_dir(version), version).init(**SMALL)
    vr = s.variables["in_contact"].valueReference
    assert status_of(s.fmu.setBoolean, [vr], [True]) == ERROR
    assert "in_contact" in s.errors()[-1] and "output" in s.errors()[-1]


@pytest.mark.parametrize("version", VERSIONS)
def test_metadata(fmu_dir, version):
    md = description(fmu_dir, version)
    assert md.generationTool == f"tribo model_description {project_version()}"
    assert md.version == project_version()
    assert md.author and "Copyright" in md.copyright and "BSD-3-Clause" in md.license
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", md.generationDateAndTime)


@pytest.mark.parametrize("version", VERSIONS)
def test_declared_dependencies(fmu_dir, version):
    md = description(fmu_dir, version)
    outputs = [v for v in md.modelVariables if v.causality == "output"]
    # every parameter but the FMU layer's hold_at_end, which acts after the run's end only
    parameters = [v for v in md.modelVariables
                  if v.causality in ("parameter", "structuralParameter") and v.name != "hold_at_end"]
    assert [u.variable for u in md.outputs] == outputs
    assert all(u.dependencies == [] for u in md.outputs)
    assert [u.variable for u in md.initialUnknowns] == outputs
    assert all(u.dependencies == parameters for u in md.initialUnknowns)


def scalar_outputs(s):
    return [n for n, v in s.variables.items() if v.causality == "output" and not v.dimensions]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", [0, 1])
def test_setting_an_input_changes_no_output_until_the_next_step(fmu_dir, version, integrator):
    """The declared empty dependencies: in Initialization Mode and between steps, setting
    either input (to a force that matters) changes no output; the next step does."""
    s = Slave(fmu_dir(version), version)
    s.set(integrator=integrator, **SMALL)
    if version == 2:
        s.fmu.setupExperiment(startTime=0.0)
        s.fmu.enterInitializationMode()
    else:
        s.fmu.enterInitializationMode(startTime=0.0)
    names = scalar_outputs(s)
    for name in ("F_T_ext", "F_N_ext"):
        before = s.get_many(names)
        s.set(**{name: 0.01})
        assert s.get_many(names) == before, name
        s.set(**{name: 0.0})
    s.fmu.exitInitializationMode()
    s.step_to(1.0)
    undisturbed = Slave(fmu_dir(version), version).init(integrator=integrator, **SMALL)
    undisturbed.step_to(1.0)
    for name in ("F_T_ext", "F_N_ext"):
        before = s.get_many(names)
        s.set(**{name: 0.01})
        assert s.get_many(names) == before, name
    s.step_to(2.0)
    undisturbed.step_to(2.0)
    changed = [n for n in ("X", "Y", "U", "V", "work_external")
               if s.get(n) != undisturbed.get(n)]
    assert changed, "the inputs acted on nothing: the test above could not fail"
    assert math.isfinite(s.get("X"))

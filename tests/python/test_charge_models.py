"""The package's charge models and enumeration values against the FMUs' modelDescriptions:
the registered models come from the FMU (tribo.fmu.charge_models), so that a registry row
(src/chute/charge/charge_registry.def) needs no Python edit, and each name or integer the package still
writes down for a model-specific output or a choice is checked here to be the FMU's."""

import re

import pytest
from fmpy import read_model_description

from tribo.batch import grid, summary
from tribo.batch.particle import simulate
from tribo.fmu import FmuImage
from tribo.fmu.charge_models import charge_models, enumeration, segment_arrays
from tribo.impact.episode import episode_parameters
from tribo.plotting import CHARGE_LABELS, SHORT_CHARGE_LABELS
from tribo.populations import feed
from tribo_fmu import ROOT, VERSIONS

PREFIXES = ("tribo", "tribo_si")


def registry_rows():
    """The names of src/chute/charge/charge_registry.def's rows, in order."""
    with open(f"{ROOT}/src/chute/charge/charge_registry.def", encoding="utf-8") as f:
        return tuple(re.findall(r"^TRIBO_CHARGE_MODEL\(\w+, (\w+),", f.read(), re.MULTILINE))


@pytest.mark.parametrize("prefix", PREFIXES)
@pytest.mark.parametrize("version", VERSIONS)
def test_the_charge_models_are_the_registrys(version, prefix, fmu_file):
    md = read_model_description(fmu_file(version, prefix))
    assert charge_models(md) == registry_rows()
    array = {"tribo": "segment_charge_", "tribo_si": "segment_sigma_"}[prefix]
    expected = {m: array + m for m in registry_rows()} if version == 3 else {}
    assert segment_arrays(md) == expected


def test_a_run_records_the_segments_of_every_registered_model(fmu_file):
    recording = simulate(FmuImage.load(fmu_file(3)), {"n_segments": 32}, 1.0, 1.0, ["X"],
                         segments=True)
    assert tuple(recording.segments.columns) == registry_rows()
    assert len(recording.segments) == 32


def test_the_models_with_their_own_outputs_are_registered_and_have_them(fmu_file):
    """Q_<model> (dimensionless) and charge_<model> (SI) are rows of the tables written for
    a model, not made by the registry: the package names them where it plots or tabulates."""
    md = read_model_description(fmu_file(3))
    si = read_model_description(fmu_file(3, "tribo_si"))
    outputs = {v.name for v in md.modelVariables if v.causality == "output"}
    si_outputs = {v.name for v in si.modelVariables if v.causality == "output"}
    for model in set(CHARGE_LABELS) | set(SHORT_CHARGE_LABELS):
        assert model in charge_models(md) and f"Q_{model}" in outputs, model
    for model in feed.MODELS:
        assert model in charge_models(si) and f"charge_{model}" in si_outputs, model


def test_the_enumeration_values_the_package_writes_are_the_fmus(fmu_file):
    md = read_model_description(fmu_file(3))
    assert tuple(enumeration(md, "tribo.MotionClass")) == summary.MOTION_CLASSES
    assert list(enumeration(md, "tribo.MotionClass").values()) == list(range(len(summary.MOTION_CLASSES)))
    # every charge model runs in the paper's set-up: the FMU's default switches, none set
    assert not any(k.startswith("charge_model") for k in grid.PAPER_SETUP)
    assert grid.PAPER_SETUP["integrator"] == enumeration(md, "tribo.Integrator")["cvode_adams"]
    assert grid.PAPER_SETUP["damping_point"] == enumeration(md, "tribo.DampingPoint")["contact_point"]
    run_end = episode_parameters({}, 1.0, 0.0, 0.0, 1.0)["run_end"]
    assert run_end == enumeration(md, "tribo.RunEnd")["first_liftoff"]


def test_an_undeclared_enumeration_names_the_declared_ones(fmu_file):
    md = read_model_description(fmu_file(3))
    with pytest.raises(KeyError, match="tribo.MotionClass"):
        enumeration(md, "tribo.NoSuch")

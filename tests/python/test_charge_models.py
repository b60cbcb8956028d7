"""The package's charge models and enumeration values against the FMUs' modelDescriptions:
the registered models come from the FMU (tribo.fmu.charge_models), so that a registry row
(src/chute/charge/charge_registry.def) needs no Python edit: every table's columns are made
from the model list (a third model gets its columns), no module but the paper's study names
the models, and the models are selected by their switches only (`charge_model` is refused
in one line). Each name or integer the package still writes down for a model-specific output
or a choice is checked here to be the FMU's."""

import ast
import os
import re
import subprocess
from types import SimpleNamespace

import pytest
from fmpy import read_model_description

import tribo
from study_support import subcommand
from tribo.batch import grid, summary
from tribo.batch.particle import recorded, simulate
from tribo.fmu import FmuImage
from tribo.fmu.charge_models import (charge_models, enumeration, mean_charges, per_model,
                                     segment_arrays)
from tribo.fmu.names import ParameterError
from tribo.impact.episode import MODEL_PREFIXES as EPISODE_PREFIXES
from tribo.impact.episode import episode_columns, episode_parameters
from tribo.line import grain
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
    # every SI output per model the package reads, for every registered model
    prefixes = set(feed.MODEL_PREFIXES) | set(EPISODE_PREFIXES) | {"charge_per_length_",
                                                                   "sigma_mean_"}
    for name in per_model(sorted(prefixes), charge_models(si)):
        assert name in si_outputs, name


def test_the_enumeration_values_the_package_writes_are_the_fmus(fmu_file):
    md = read_model_description(fmu_file(3))
    assert tuple(enumeration(md, "tribo.MotionClass")) == summary.MOTION_CLASSES
    assert list(enumeration(md, "tribo.MotionClass").values()) == list(range(len(summary.MOTION_CLASSES)))
    # the models are the FMU's switches at their defaults: no bitmask
    assert not [n for n in grid.PAPER_SETUP if n.startswith("charge_model")]
    assert grid.PAPER_SETUP["integrator"] == enumeration(md, "tribo.Integrator")["cvode_adams"]
    assert grid.PAPER_SETUP["damping_point"] == enumeration(md, "tribo.DampingPoint")["contact_point"]
    run_end = episode_parameters({}, 1.0, 0.0, 0.0, 1.0)["run_end"]
    assert run_end == enumeration(md, "tribo.RunEnd")["first_liftoff"]


def test_an_undeclared_enumeration_names_the_declared_ones(fmu_file):
    md = read_model_description(fmu_file(3))
    with pytest.raises(KeyError, match="tribo.MotionClass"):
        enumeration(md, "tribo.NoSuch")


def switch(name):
    return SimpleNamespace(name=f"charge_model_{name}", causality="structuralParameter",
                           declaredType=SimpleNamespace(name="tribo.Switch"))


def test_a_third_registered_model_gets_its_columns_everywhere():
    """A modelDescription with a third switch (as a registry row makes it): the models and
    every table's columns follow without a Python edit."""
    md = SimpleNamespace(modelVariables=[switch("static"), switch("sliding"), switch("decaying")]
                         + [SimpleNamespace(name=f"Q_{m}", causality="output", declaredType=None)
                            for m in ("static", "sliding", "decaying")])
    models = charge_models(md)
    assert models == ("static", "sliding", "decaying") and mean_charges(md) == models
    assert {"charge_decaying", "charge_to_mass_decaying", "capped_fraction_decaying"} <= \
        set(feed.result_columns(models)) <= set(grain.result_columns(models))
    assert {"charge_decaying", "charge_to_mass_decaying"} <= set(episode_columns(models))
    assert "Q_decaying_end" in summary.summary_columns(models)
    assert "Q_decaying" in recorded(models)
    switches = grain.charge_model_settings("decaying", models)
    assert switches == {"charge_model_static": 0, "charge_model_sliding": 0,
                        "charge_model_decaying": 1, "charge_to_mass_model": 3}


def test_no_module_but_the_papers_study_names_the_models():
    """The models are not spelled in the package's code (docstrings aside; the paper's study
    and the labels of the two models' dimensionless charges excepted): no literal holds both
    names, no string names a model's column (charge_to_mass_static, Q_sliding, ...)."""
    package = os.path.dirname(tribo.__file__)
    spelled = []
    for folder, _, files in os.walk(package):
        if os.path.basename(folder) == "study":
            continue
        for name in sorted(f for f in files if f.endswith(".py") and f != "plotting.py"):
            path = os.path.join(folder, name)
            tree = ast.parse(open(path, encoding="utf-8").read())
            docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                          if isinstance(node, (ast.Module, ast.FunctionDef, ast.ClassDef))
                          and node.body and isinstance(node.body[0], ast.Expr)}
            for node in ast.walk(tree):
                if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
                    names = {e.value for e in node.elts if isinstance(e, ast.Constant)}
                    if {"static", "sliding"} <= names:
                        spelled.append(f"{name}:{node.lineno}: a literal of both models")
                elif (isinstance(node, ast.Constant) and isinstance(node.value, str)
                      and id(node) not in docstrings
                      and re.search(r"\w_(static|sliding)\b", node.value)):
                    spelled.append(f"{name}:{node.lineno}: {node.value[:60]!r}")
    assert not spelled, spelled


def test_the_bitmask_is_refused_in_one_line_naming_the_switches(fmu_file, tmp_path):
    with pytest.raises(ParameterError, match=r"^charge_model was removed: each charge model has "
                                             r"its own switch, charge_model_static, "
                                             r"charge_model_sliding \(1 on, 0 off\)$"):
        tribo.run(charge_model=1, t_end=1.0, fmu=fmu_file(3))
    done = subprocess.run([*subcommand("population"), "-n", "2", "--set", "charge_model=1",
                           "--out", str(tmp_path / "p"), "--serial"], capture_output=True,
                          text=True, timeout=120)
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(lines) == 1, done.stderr
    assert "charge_model was removed" in lines[0] and "charge_model_sliding" in lines[0]

"""The two modelDescription.xml files say what the variable table (fmu/variables.c) says,
the table covers the core, and fmpy finds nothing wrong with either FMU."""

import math
import os

import xml.etree.ElementTree as ET

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from tribo_fmu import ROOT, VERSIONS

XML = {v: os.path.join(ROOT, "modelDescription", f"fmi{v}.xml") for v in VERSIONS}


def parsed(version):
    return read_model_description(XML[version], validate=True)


def raw_attributes(version):
    """Each variable's XML attributes (FMI 2.0: with those of its type element), read
    without fmpy, which skips some (min / max of UInt64)."""
    root = ET.parse(XML[version]).getroot()
    attributes = {}
    for element in root.find("ModelVariables"):
        a = dict(element.attrib)
        if version == 2:
            a.update(element[0].attrib)
        attributes[a["name"]] = a
    return attributes


def table_rows(table, version):
    return [v for v in table["variables"] if v[f"type_fmi{version}"] is not None]


def as_number(text, type_name):
    return int(text) if type_name in ("Integer", "Int32", "UInt64") else float(text)


@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_validation_finds_no_problem(fmu_file, version):
    assert validate_fmu(fmu_file(version)) == []


@pytest.mark.parametrize("version", VERSIONS)
def test_packed_description_is_the_source_file(fmu_dir, version):
    with open(os.path.join(fmu_dir(version), "modelDescription.xml"), "rb") as packed, \
            open(XML[version], "rb") as source:
        assert packed.read() == source.read()


@pytest.mark.parametrize("version", VERSIONS)
def test_variables_agree_with_the_table(table, version):
    md = parsed(version)
    declared = {v.name: v for v in md.modelVariables}
    raw = raw_attributes(version)
    rows = table_rows(table, version)
    assert [v.name for v in md.modelVariables] == [r["name"] for r in rows]
    for r in rows:
        v = declared[r["name"]]
        assert v.valueReference == r["vr"], r["name"]
        assert v.type == r[f"type_fmi{version}"], r["name"]
        assert v.causality == r[f"causality_fmi{version}"], r["name"]
        assert v.variability == r["variability"], r["name"]
        assert v.description == r["description"], r["name"]
        if r["start"] is None:
            assert v.start is None, r["name"]
        else:
            assert as_number(v.start, v.type) == r["start"], r["name"]
        if v.type in ("Real", "Float64"):
            assert v.unit == r["unit"], r["name"]
        else:
            # FMI has no unit attribute for integers; the core's unit for them is "1"
            assert r["unit"] == "1", r["name"]
        for bound in ("min", "max"):
            expected = r.get(bound)
            declared_bound = raw[r["name"]].get(bound)
            if expected is None:
                assert declared_bound is None, (r["name"], bound)
            else:
                assert as_number(declared_bound, v.type) == expected, (r["name"], bound)


def test_fmi3_arrays_are_sized_by_the_structural_parameter(table):
    md = parsed(3)
    by_vr = {v.valueReference: v for v in md.modelVariables}
    arrays = [r for r in table["variables"] if r["maps_to"] == "segments"]
    assert arrays, "the table has segment arrays"
    for r in arrays:
        v = by_vr[r["vr"]]
        assert len(v.dimensions) == 1
        size = by_vr[v.dimensions[0].valueReference]
        assert size.name == r["dimension"] == "n_segments"
        # FMI 3.0: a dimension refers to a UInt64 structural parameter (or a constant)
        assert (size.type, size.causality) == ("UInt64", "structuralParameter")
        assert v.shape == (int(size.start),)
    assert all(r["type_fmi2"] is None for r in arrays), "FMI 2.0 has no arrays"


@pytest.mark.parametrize("version", VERSIONS)
def test_model_structure_lists_every_output(table, version):
    md = parsed(version)
    outputs = [r["name"] for r in table_rows(table, version)
               if r[f"causality_fmi{version}"] == "output"]
    assert [u.variable.name for u in md.outputs] == outputs
    assert [u.variable.name for u in md.initialUnknowns] == outputs


@pytest.mark.parametrize("version", VERSIONS)
def test_token_log_categories_units_and_experiment(table, version):
    md = parsed(version)
    assert md.guid == table["token"]
    assert [(c.name, c.description) for c in md.logCategories] == \
        [(c["name"], c["description"]) for c in table["log_categories"]]
    defined = {u.name for u in md.unitDefinitions}
    assert {v.unit for v in md.modelVariables if v.unit} <= defined
    deg = next(u for u in md.unitDefinitions if u.name == "deg")
    assert (deg.baseUnit.rad, deg.baseUnit.factor) == (1, math.pi / 180)
    cs = md.coSimulation
    assert cs.modelIdentifier == f"tribo_fmi{version}"
    assert cs.canHandleVariableCommunicationStepSize
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate
    e = md.defaultExperiment
    assert (e.startTime, e.stopTime) == ("0", "1000")
    # the default tolerance is the default of rtol, the parameter that sets it
    assert float(e.tolerance) == next(r["start"] for r in table["variables"] if r["name"] == "rtol")
    assert float(e.stepSize) > 0


def test_table_covers_every_core_parameter_and_quantity(table):
    rows = table["variables"]
    params = [r for r in rows if r["maps_to"] == "parameter"]
    assert [r["name"] for r in params] == table["core_parameters"]
    quantities = [r for r in rows if r["maps_to"] == "quantity"]
    assert [r["name"] for r in quantities] == table["core_quantities"][1:]  # "time" aside
    assert all(r["name"] == r["core_name"] for r in quantities)
    assert [r["name"] for r in rows if r["maps_to"] == "time"] == ["time"]
    assert [r["name"] for r in rows if r["maps_to"] == "input"] == ["F_T_ext", "F_N_ext"]


def test_parameter_rows_follow_the_core(table):
    for r in (r for r in table["variables"] if r["maps_to"] == "parameter"):
        expected = "tunable" if r["core_variability"] == "tunable" else "fixed"
        assert r["variability"] == expected, r["name"]
        structural_in_fmi3 = r["name"] == "n_segments"  # the one that sizes arrays
        assert r["causality_fmi3"] == ("structuralParameter" if structural_in_fmi3 else "parameter")
        assert r["causality_fmi2"] == "parameter"
        assert (r["type_fmi2"] == "Integer") == r["core_is_integer"], r["name"]


def test_every_variable_is_described_with_a_unit(table):
    for r in table["variables"]:
        assert r["description"], r["name"]
        assert r["unit"], r["name"]


def test_value_references_are_unique(table):
    vrs = [r["vr"] for r in table["variables"]]
    assert len(vrs) == len(set(vrs))

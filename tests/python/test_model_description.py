"""The modelDescription files are generated from the core's table (src/chute/quantities.def; the
SI FMUs' from src/si/si_quantities.def, the separator's from src/separator/separator_quantities.def) at
build time. Here: the generated ones are the
reviewed ones committed in modelDescription/,
their instantiation token is a hash of the description itself, fmpy finds nothing wrong
with either FMU, and what they declare is what the binaries do (every declared range is
the range the FMU accepts; the outputs are the core's quantities)."""

import hashlib
import math
import os
import re
import subprocess
import xml.etree.ElementTree as ET

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from tribo.fmu.charge_models import charge_models
from tribo_fmu import BUILD_DIR, ERROR, OK, ROOT, VERSIONS, Slave, core_run, status_of

# the dimensionless FMUs (tribo_fmi<v>), the SI ones (tribo_si_fmi<v>) and the separator's
# (tribo_separator_fmi<v>)
PREFIXES = ("tribo", "tribo_si", "tribo_separator")
GOLDEN_NAMES = {("tribo", v): f"fmi{v}.xml" for v in VERSIONS} | \
    {(prefix, v): f"{prefix}_fmi{v}.xml" for prefix in PREFIXES[1:] for v in VERSIONS}
GOLDEN = {key: os.path.join(ROOT, "modelDescription", name) for key, name in GOLDEN_NAMES.items()}
GOLDEN.update({v: GOLDEN[("tribo", v)] for v in VERSIONS})
PLACEHOLDER = "@INSTANTIATION_TOKEN@"
TOKEN_ATTRIBUTE = {2: "guid", 3: "instantiationToken"}


def packed_text(fmu_dir, version, prefix="tribo"):
    with open(os.path.join(fmu_dir(version, prefix), "modelDescription.xml"), encoding="utf-8") as f:
        return f.read()


def raw_variables(fmu_dir, version, prefix="tribo"):
    """Each variable's XML attributes (FMI 2.0: with those of its type element) and type,
    read without fmpy, which skips some (min / max of UInt64)."""
    root = ET.fromstring(packed_text(fmu_dir, version, prefix).encode())
    out = []
    for element in root.find("ModelVariables"):
        a = dict(element.attrib)
        a["type"] = element[0].tag if version == 2 else element.tag
        if version == 2:
            a.update(element[0].attrib)
        out.append(a)
    return out


@pytest.mark.parametrize("prefix", PREFIXES)
@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_validation_finds_no_problem(fmu_file, version, prefix):
    assert validate_fmu(fmu_file(version, prefix)) == []


def without_date_and_token(text):
    """The description less what changes with every commit: generationDateAndTime (the
    source date) and so the token, which hashes it."""
    text = re.sub(r'generationDateAndTime="[^"]*"', 'generationDateAndTime=""', text)
    return re.sub(r'(guid|instantiationToken)="[^"]*"', r'\1=""', text)


@pytest.mark.parametrize("prefix", PREFIXES)
@pytest.mark.parametrize("version", VERSIONS)
def test_generated_description_is_the_reviewed_one(fmu_dir, version, prefix):
    with open(GOLDEN[(prefix, version)], encoding="utf-8") as f:
        golden = f.read()
    assert without_date_and_token(packed_text(fmu_dir, version, prefix)) == \
        without_date_and_token(golden), (
        "the table (src/chute/quantities.def, src/si/si_quantities.def) or the generator changed the "
        "modelDescription: run `cmake --build build --target update_model_descriptions` and "
        "review the diff")


@pytest.mark.parametrize("prefix", PREFIXES)
@pytest.mark.parametrize("version", VERSIONS)
def test_description_is_reproducible_from_the_source_date(version, prefix):
    """The same sources and SOURCE_DATE_EPOCH give the same bytes; the date is the epoch's."""
    generator = os.path.join(BUILD_DIR, "fmu", f"{prefix}_model_description")
    runs = [subprocess.run([generator, str(version), "0.1.0", str(epoch)], capture_output=True,
                           text=True, check=True).stdout for epoch in (1700000000, 1700000000, 1)]
    assert runs[0] == runs[1]
    assert 'generationDateAndTime="2023-11-14T22:13:20Z"' in runs[0]
    assert 'generationDateAndTime="1970-01-01T00:00:01Z"' in runs[2]
    assert without_date_and_token(runs[0]) == without_date_and_token(runs[2])


@pytest.mark.parametrize("prefix", PREFIXES)
@pytest.mark.parametrize("version", VERSIONS)
def test_token_is_a_hash_of_the_description(fmu_dir, version, prefix):
    text = packed_text(fmu_dir, version, prefix)
    token = re.search(rf'{TOKEN_ATTRIBUTE[version]}="([^"]+)"', text).group(1)
    h = hashlib.sha256(text.replace(token, PLACEHOLDER).encode()).hexdigest()
    assert token == "{%s-%s-%s-%s-%s}" % (h[:8], h[8:12], h[12:16], h[16:20], h[20:32])
    # and the other descriptions, which differ, have other tokens
    for other_prefix in PREFIXES:
        for other_version in VERSIONS:
            if (other_prefix, other_version) != (prefix, version):
                assert token not in packed_text(fmu_dir, other_version, other_prefix)


@pytest.mark.parametrize("prefix", PREFIXES)
@pytest.mark.parametrize("version", VERSIONS)
def test_declared_ranges_are_what_the_fmu_accepts(fmu_dir, version, prefix):
    """Every declared min and max is accepted, the nearest value beyond it is refused (an
    open end is declared as the nearest value inside it), and a parameter without a bound
    accepts any finite value there."""
    for a in raw_variables(fmu_dir, version, prefix):
        if a["causality"] not in ("parameter", "structuralParameter"):
            continue
        name, is_real = a["name"], a["type"] in ("Real", "Float64")
        for bound, outward in (("min", -math.inf), ("max", math.inf)):
            s = Slave(fmu_dir(version, prefix), version)
            if bound in a:
                inside = float(a[bound]) if is_real else int(a[bound])
                outside = math.nextafter(inside, outward) if is_real else inside + int(math.copysign(1, outward))
                assert status_of(s.set, **{name: inside}) == OK, (name, bound, inside, s.errors())
                if not is_real and outside < 0 and a["type"] == "UInt64":
                    continue  # not representable
                assert status_of(s.set, **{name: outside}) == ERROR, (name, bound, outside)
                assert name in s.errors()[-1]
            elif is_real:
                assert status_of(s.set, **{name: math.copysign(1e300, outward)}) == OK, (name, bound)
            s.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_outputs_are_the_cores_quantities(fmu_dir, reference_exe, version):
    md = read_model_description(fmu_dir(version), validate=False)
    scalar_outputs = [v.name for v in md.modelVariables if v.causality == "output" and not v.dimensions]
    quantities = list(core_run(reference_exe, {}, [(0.0, [])])[0])
    assert ["time"] + scalar_outputs == quantities
    assert [u.variable.name for u in md.outputs] == \
        [v.name for v in md.modelVariables if v.causality == "output"]
    assert [u.variable.name for u in md.initialUnknowns] == [u.variable.name for u in md.outputs]


def test_fmi3_arrays_are_sized_by_the_structural_parameter(fmu_dir):
    md = read_model_description(fmu_dir(3), validate=True)
    by_vr = {v.valueReference: v for v in md.modelVariables}
    arrays = [v for v in md.modelVariables if v.dimensions]
    # one per registered charge model (src/chute/charge/charge_registry.def), none other
    assert [v.name for v in arrays] == [f"segment_charge_{m}" for m in charge_models(md)]
    assert charge_models(md)
    for v in arrays:
        size = by_vr[v.dimensions[0].valueReference]
        # FMI 3.0: a dimension refers to a UInt64 structural parameter (or a constant)
        assert (size.name, size.type, size.causality) == ("n_segments", "UInt64", "structuralParameter")
        assert v.shape == (int(size.start),)
    fmi2 = read_model_description(GOLDEN[2], validate=False)
    assert not any(v.name.startswith("segment_charge") for v in fmi2.modelVariables)


@pytest.mark.parametrize("version", VERSIONS)
def test_units_log_categories_and_experiment(fmu_dir, version):
    md = read_model_description(fmu_dir(version), validate=True)
    defined = {u.name for u in md.unitDefinitions}
    assert {v.unit for v in md.modelVariables if v.unit} == defined == {"1", "rad", "rad/tau"}
    units = {u.name: u for u in md.unitDefinitions}
    exponents = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")
    # every unit says what it is in SI base units: "1" is dimensionless, angles are radians
    # (shown in degrees), and so is an angular velocity, the time being dimensionless
    for name, rad in (("1", 0), ("rad", 1), ("rad/tau", 1)):
        base = units[name].baseUnit
        assert base is not None, name
        assert [getattr(base, e) for e in exponents] == [0] * 7 + [rad], name
        assert (base.factor, base.offset) == (1, 0), name
    assert [(d.name, d.factor) for d in units["rad"].displayUnits] == [("deg", 180 / math.pi)]
    assert not units["1"].displayUnits and not units["rad/tau"].displayUnits
    by_name = {v.name: v for v in md.modelVariables}
    for angle in ("beta", "phi0", "phi"):
        assert (by_name[angle].unit, by_name[angle].displayUnit) == ("rad", "deg"), angle
    for spin in ("Omega0", "Omega"):
        assert by_name[spin].unit == "rad/tau", spin
    assert float(by_name["beta"].start) == 45 * (math.pi / 180)
    assert [c.name for c in md.logCategories] == \
        ["logStatusError", "logStatusWarning", "logFmiCalls", "logCore"]
    cs = md.coSimulation
    assert cs.modelIdentifier == f"tribo_fmi{version}"
    assert cs.canHandleVariableCommunicationStepSize
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate
    e = md.defaultExperiment
    assert (e.startTime, e.stopTime) == ("0", "1000")
    # the default tolerance is the default of rtol, the parameter that sets it
    rtol = next(v for v in md.modelVariables if v.name == "rtol")
    assert float(e.tolerance) == float(rtol.start)


@pytest.mark.parametrize("prefix", PREFIXES)
@pytest.mark.parametrize("version", VERSIONS)
def test_every_variable_is_described_and_value_references_are_unique(fmu_dir, version, prefix):
    md = read_model_description(fmu_dir(version, prefix), validate=False)
    assert all(v.description for v in md.modelVariables)
    vrs = [v.valueReference for v in md.modelVariables]
    assert len(vrs) == len(set(vrs))

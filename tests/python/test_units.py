"""One unit per kind, and the docs, the commands' --help and the messages say the same
(tribo/fmu/names.py): every angle the package takes or gives is in degrees and named
<name>_deg, the SI size is `size` (the long diameter 2a, m); the FMUs' own names for those
are refused in one line that names the package's."""

import math
import os
import re
import subprocess

import numpy as np
import pytest

import tribo
from study_support import subcommand
from tribo.fmu import model_description
from tribo.fmu.names import (ParameterError, fmu_outputs, from_fmu_column, parameter_names,
                             renamed, to_fmu)
from tribo_fmu import ROOT

VARIANTS = [("dimensionless", 3), ("dimensionless", 2), ("si", 3), ("si", 2)]
SUBCOMMANDS = ["study", "sweep", "population", "impact-map", "line"]


def md_of(variant, version):
    return model_description(tribo.find_fmu(version, variant))


@pytest.mark.parametrize("variant, version", VARIANTS)
def test_every_angle_of_the_fmu_has_a_degrees_name_and_converts_exactly(variant, version):
    md = md_of(variant, version)
    in_rad = [v.name for v in md.modelVariables if v.unit == "rad"]
    assert in_rad  # beta or tilt, phi0, drop_angle, phi
    table = renamed(md)
    for name in in_rad:
        r = table[name + "_deg"]
        assert r.fmu_name == name and r.unit == "deg"
    names = parameter_names(md)
    assert not set(in_rad) & set(names)
    for value in (0.0, 30.0, 45.0, 89.9, -120.5):
        for name in in_rad:
            if name + "_deg" in names:
                assert to_fmu(md, {name + "_deg": value})[name] == math.radians(value)
    column, values = from_fmu_column(md, "phi", np.array([0.0, math.pi / 4, -math.pi]))
    assert column == "phi_deg" and list(values) == [0.0, 45.0, -180.0]
    if variant == "si":
        assert table["size"].fmu_name == "semi_major_axis"
        assert to_fmu(md, {"size": 1e-3}) == {"semi_major_axis": 5e-4}
        assert "size" in names and "semi_major_axis" not in names


@pytest.mark.parametrize("variant, version", VARIANTS)
def test_the_fmus_names_of_renamed_quantities_are_refused_naming_the_packages(variant, version):
    md = md_of(variant, version)
    for r in renamed(md).values():
        kind = "output" if r.fmu_name == "phi" else "parameter"
        with pytest.raises(ParameterError) as e:
            if kind == "output":
                fmu_outputs(md, [r.fmu_name])
            else:
                to_fmu(md, {r.fmu_name: 1.0})
        message = str(e.value)
        assert message.startswith(f"{r.fmu_name}: the package takes this {kind} as {r.name} (")
        assert "\n" not in message


def test_the_api_refuses_radians_and_says_the_range_in_degrees():
    with pytest.raises(ParameterError, match=r"^tilt: the package takes this parameter as tilt_deg"):
        tribo.run_si("PE", "steel", tilt=0.5)
    with pytest.raises(ParameterError, match=r"^tilt_deg = 90 is invalid: the valid range is "
                                             r"0 <= tilt_deg < 90$"):
        tribo.run_si("PE", "steel", tilt_deg=90)
    with pytest.raises(ParameterError, match=r"^size = 3 is invalid: the valid range is "
                                             r"2e-07 <= size <= 2$"):
        tribo.run_si("PE", "steel", size=3)
    with pytest.raises(ParameterError, match=r"^beta_deg = -1 is invalid: the valid range is "
                                             r"0 <= beta_deg < 90$"):
        tribo.run(beta_deg=-1)
    with pytest.raises(ParameterError, match=r"^phi: the package takes this output as phi_deg"):
        tribo.run(t_end=2, outputs=["phi"])


def test_values_are_echoed_as_given_and_a_text_value_names_its_parameter():
    with pytest.raises(ParameterError, match=r"^chute_length = -0.3 is invalid"):
        tribo.run_si("PE", "steel", chute_length=-0.3)
    with pytest.raises(ParameterError, match=r"^mu = 'abc' is not a number \(in the scene "
                                             r"'epsilon=0.3 mu=abc'\)$"):
        tribo.run("epsilon=0.3 mu=abc")
    with pytest.raises(ParameterError, match=r"^epsilon = 1.5 is invalid"):
        tribo.run("epsilon=1.50")


def helps() -> dict:
    return {name: subprocess.run([*subcommand(name), "--help"], capture_output=True, text=True,
                                 check=True, timeout=60).stdout for name in SUBCOMMANDS}


def test_the_commands_name_every_angle_in_degrees_and_the_size_as_size():
    for name, text in helps().items():
        options = re.findall(r"^\s+(--[\w-]+)", text, re.M)
        for option in options:
            if re.search(r"angle|phi|tilt|beta", option):
                assert option.endswith("-deg"), (name, option)
        # no FMU name of a renamed quantity as something to type
        for fmu_name in ("semi_major_axis", "tilt", "phi0", "drop_angle", "beta"):
            assert not re.search(rf"(?<![\w-]){fmu_name}(=|\s*\(rad)", text), (name, fmu_name)
        assert " rad)" not in text.replace("rad/s", "")
    population = " ".join(helps()["population"].split())
    assert "size is the long diameter 2a in m" in population and "angles in degrees" in population


def documents() -> dict:
    """README.md, CONTRIBUTING.md and the user guide's pages (docs/README.md's table; the
    reports are what their commands printed)."""
    from test_examples import guide_pages
    paths = [os.path.join(ROOT, p) for p in guide_pages() + ["CONTRIBUTING.md", "docs/README.md"]]
    return {os.path.relpath(p, ROOT): open(p, encoding="utf-8").read() for p in paths}


def test_the_docs_give_no_degree_values_to_a_radian_name():
    """`0 <= beta < 90`, `beta = 45` (the FMU's beta is in radians): a value beyond 2 pi given
    to an FMU angle's own name, or a degree sign next to it."""
    angle = r"(?<![\w-])`?(beta|tilt|phi0|drop_angle|phi)`?"
    pattern = re.compile(angle + r"\s*(=|<|<=|≤|>=|≥)\s*(\d+(\.\d+)?)(°)?")
    wrong = []
    for where, text in documents().items():
        for m in pattern.finditer(text):
            if float(m.group(3)) > 2 * math.pi or m.group(5):
                wrong.append(f"{where}: {m.group(0)}")
    assert not wrong, wrong


def test_the_docs_and_examples_use_the_packages_names_in_package_calls():
    """A call of the package (tribo.run, run_si, sweep, population, impact_map) in the docs
    or the --help never passes an FMU name the package renames."""
    call = re.compile(r"tribo\.(run|run_si|sweep|population|impact_map)\((.*?)\)\s*$", re.S | re.M)
    bad = []
    for where, text in documents().items():
        for m in call.finditer(text):
            for fmu_name in ("semi_major_axis", "tilt", "phi0", "drop_angle", "beta", "angle"):
                if re.search(rf"(?<![\w\"']){fmu_name}\s*=", m.group(2)):
                    bad.append(f"{where}: {fmu_name} in {m.group(0)[:80]}")
    assert not bad, bad

"""tribo.materials: the table against the SI front end's parameters (src/si/si_quantities.def),
the physical bounds on its numbers, and its one-line errors."""

import math
import os
import re

import pytest
from fmpy import read_model_description

import tribo
from tribo import materials

EPS0 = 8.8541878128e-12
# the parameter each registered charge model adds (charge_model_<name>, src/si/si_quantities.def):
# the registry's, not a set-up's, so not among materials' names
SWITCH = re.compile(r"charge_model_\w+")


@pytest.fixture(scope="module")
def si_rows(fmu_file):
    """name -> (min, max, default) of every parameter the SI FMU declares
    (src/si/si_quantities.def, ranges a parameter that is the model's takes from quantities.def)."""
    described = read_model_description(fmu_file(3, "tribo_si"), validate=False)

    def bound(text, otherwise):
        return otherwise if text is None else float(text)

    return {v.name: (bound(v.min, -math.inf), bound(v.max, math.inf), float(v.start))
            for v in described.modelVariables
            # hold_at_end is the FMU layer's (every FMU's), not a set-up's
            if v.causality in ("parameter", "structuralParameter") and v.name != "hold_at_end"}


def test_the_si_parameter_names_are_the_fmus(si_rows):
    """start_values checks names against the SI FMU itself: a parameter added to the SI
    table is known to the package with no edit here."""
    assert list(materials.si_parameters()) == list(si_rows) + ["hold_at_end"]
    assert set(SWITCH.findall(" ".join(si_rows))) >= {"charge_model_static", "charge_model_sliding"}


def test_exported_from_the_package():
    assert tribo.materials is materials
    assert "materials" in tribo.__all__


def test_the_lists_hold_the_common_materials():
    assert set(materials.particles()) >= {"PE", "PP", "PS", "PMMA", "PVC", "nylon", "PTFE",
                                          "glass"}
    assert set(materials.walls()) >= {"steel", "aluminium", "PTFE", "glass"}


def test_every_material_is_physical():
    for key in set(materials.particles()) | set(materials.walls()):
        m = materials.material(key)
        assert 1e6 < m.youngs_modulus < 1e12, key
        assert 0.0 < m.poisson_ratio <= 0.5, key
        assert 500.0 < m.density < 2e4, key


def test_every_start_value_is_in_the_si_range(si_rows):
    rows = si_rows
    for p in materials.particles():
        for w in materials.walls():
            values = materials.start_values(p, w, sigma0=-1e-5)
            for name, value in values.items():
                lo, hi, _ = rows[name]
                assert lo <= value <= hi, (p, w, name, value)


def test_sigma0_is_the_contacts_own_density_within_the_si_range(si_rows):
    """docs/model.md section 8e: |sigma0| = 1e-3 C/m2 (the condenser model's order,
    eps0 x 0.05-0.5 V / 0.4 nm) for every polymer-metal and glass-metal pair, the sign the
    series'; the pairs on an insulating wall keep their saturation densities, below air's
    3 MV/m density; every |sigma0| within the bound, which is the SI FMU's range."""
    limit = materials.sigma0_limit()
    assert limit == 1e-2 and si_rows["sigma0"][:2] == (-limit, limit)
    n = 0
    for p in materials.particles():
        for w in materials.walls():
            try:
                s = materials.pair_sigma0(p, w)
            except materials.MaterialError:
                continue
            n += 1
            assert 0.0 < abs(s) <= limit, (p, w, s)
            if materials.material(w).conducting:
                assert abs(s) == 1e-3, (p, w, s)
            else:
                assert abs(s) <= EPS0 * 3e6, (p, w, s)
    assert n >= 8
    assert materials.pair_sigma0("glass", "aluminium") == 1e-3  # Ema et al.'s pair (validation.md)


def test_the_wall_sets_wall_conducting():
    """The gas's limit takes the image form on a grounded metal, the pair form on an
    insulator (docs/model.md section 8e): the table's walls say which."""
    for wall, conducting in (("steel", 1), ("aluminium", 1), ("PTFE", 0), ("glass", 0)):
        assert materials.pair_values("PE", wall)["wall_conducting"] == conducting, wall
        assert materials.start_values("PE", wall)["wall_conducting"] == conducting, wall


def test_sigma0_signs_follow_the_triboelectric_series():
    # PTFE is at the negative end of the series, so a particle is charged more positively
    # on a PTFE wall than on a metal; on glass (near the positive end) less positively. The
    # signs only: the metal pairs' magnitudes are the contact's own density, the insulating
    # walls' a saturation's (docs/materials.md), not comparable.
    def get(p, w):
        s = _get(p, w)
        return None if s is None else math.copysign(1.0, s)

    def _get(p, w):
        try:
            return materials.pair_sigma0(p, w)
        except materials.MaterialError:
            return None

    checked = 0
    for p in materials.particles():
        for metal in ("steel", "aluminium"):
            s_metal = get(p, metal)
            if s_metal is None:
                continue
            if (s := get(p, "PTFE")) is not None:
                assert s >= s_metal, (p, metal)
                checked += 1
            if (s := get(p, "glass")) is not None:
                assert s <= s_metal, (p, metal)
                checked += 1
    assert checked >= 4
    assert materials.pair_sigma0("PTFE", "steel") < 0 < materials.pair_sigma0("nylon", "steel")


def test_kappa_is_epsilon0_over_the_gap_and_the_si_default(si_rows):
    kappa = materials.interface_capacitance()
    assert kappa == pytest.approx(EPS0 / 0.4e-9, rel=1e-12)
    assert kappa == pytest.approx(si_rows["interface_capacitance"][2], rel=1e-12)


def test_polyethylene_on_steel_is_the_reference_case(si_rows):
    rows = si_rows
    values = materials.start_values("PE", "steel")
    for name in ("youngs_modulus_particle", "poisson_ratio_particle", "density",
                 "youngs_modulus_wall", "poisson_ratio_wall", "interface_capacitance",
                 "wall_conducting"):
        assert values[name] == pytest.approx(rows[name][2], rel=1e-12), name
    # sigma0: the SI FMU's default is revision 4's -1e-5 (a weakly charging pair, below the
    # gas's limit), the table's the contact's own -1e-3 (docs/model.md section 8e): the sign
    # is the pair's in both
    assert values["sigma0"] * rows["sigma0"][2] > 0


def test_overrides_win_and_names_are_case_insensitive():
    values = materials.start_values("pe", "STEEL", semi_major_axis=1e-3, epsilon=0.3,
                                    chute_length=0.3, drop_height=0.02, density=900.0)
    assert values["semi_major_axis"] == 1e-3
    assert values["epsilon"] == 0.3
    assert values["chute_length"] == 0.3
    assert values["drop_height"] == 0.02
    assert values["density"] == 900.0
    assert values["youngs_modulus_wall"] == materials.material("steel").youngs_modulus


def one_line_error(call):
    with pytest.raises(materials.MaterialError) as info:
        call()
    msg = str(info.value)
    assert "\n" not in msg
    return msg


def test_an_unknown_material_names_it_and_lists_the_known():
    msg = one_line_error(lambda: materials.start_values("unobtainium", "steel"))
    assert "unobtainium" in msg and "PE" in msg and "glass" in msg
    msg = one_line_error(lambda: materials.start_values("PE", "wood"))
    assert "wood" in msg and "steel" in msg and "aluminium" in msg


def test_a_wall_is_not_a_particle():
    msg = one_line_error(lambda: materials.start_values("steel", "steel"))
    assert "particle" in msg and "'steel'" in msg and "PE" in msg


def test_a_pair_without_sigma0_names_it_and_the_pairs_with_one():
    msg = one_line_error(lambda: materials.start_values("PMMA", "steel"))
    assert "PMMA" in msg and "steel" in msg and "PE/steel" in msg and "sigma0=" in msg
    values = materials.start_values("PMMA", "steel", sigma0=-5e-6)
    assert values["sigma0"] == -5e-6
    assert values["density"] == materials.material("PMMA").density


def test_an_unknown_parameter_names_it():
    msg = one_line_error(lambda: materials.start_values("PE", "steel", radius=1e-3))
    assert "'radius'" in msg and "semi_major_axis" in msg


def pairs_used() -> set:
    """Every particle/wall pair README.md, the user guide and the commands' --help use:
    run_si("P", "W", ...), particle="P", wall="W", --particle P --wall W (the defaults,
    PE and steel, where one of the two is left out)."""
    import subprocess

    from study_support import subcommand
    from test_examples import guide_pages
    from tribo_fmu import ROOT

    texts = [open(os.path.join(ROOT, p), encoding="utf-8").read() for p in guide_pages()]
    texts += [subprocess.run([*subcommand(c), "--help"], capture_output=True, text=True,
                             check=True, timeout=60).stdout for c in ("population", "impact-map")]
    pairs = set()
    for text in texts:
        text = " ".join(text.split())
        pairs |= set(re.findall(r"run_si\(\"(\w+)\", \"(\w+)\"", text))
        for call in re.findall(r"tribo\.(?:population|impact_map)\((.*?)\)", text):
            p = re.search(r"particle=\"(\w+)\"", call)
            w = re.search(r"wall=\"(\w+)\"", call)
            pairs.add((p.group(1) if p else "PE", w.group(1) if w else "steel"))
        for line in re.findall(r"tribo (?:population|impact-map) [^\n]*?(?=tribo |$)", text):
            p = re.search(r"--particle (\w+)", line)
            w = re.search(r"--wall (\w+)", line)
            pairs.add((p.group(1) if p else "PE", w.group(1) if w else "steel"))
    # the usage line's metavars
    return {(p, w) for p, w in pairs if (p, w) != ("PARTICLE", "WALL")}


def test_every_pair_the_docs_and_help_use_has_sigma0():
    pairs = pairs_used()
    assert {("PE", "steel"), ("PP", "glass"), ("PP", "aluminium")} <= pairs
    for particle, wall in sorted(pairs):
        assert abs(materials.pair_sigma0(particle, wall)) <= materials.sigma0_limit(), (particle, wall)


# ---- a materials file read over the table ----------------------------------------------------

def write(tmp_path, text, name="materials.toml"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_a_materials_file_replaces_and_adds_entries_and_the_table_stays(tmp_path):
    path = write(tmp_path, "[sigma0.steel]\nPE = -2.2e-5\nPMMA = -4e-6\n\n"
                           "[charging.steel.PE]\ncharging_time = 1e-6\n\n"
                           "[material.PE]\ndensity = 960.0\n\n"
                           "[calibration.steel.PE]\ndata = [\"impacts.csv\"]\n")
    table = materials.load(path)
    assert table.source == os.path.abspath(path) and len(table.sha256) == 64
    values = materials.pair_values("PE", "steel", materials=path)
    assert values["sigma0"] == -2.2e-5 and values["charging_time"] == 1e-6
    assert values["density"] == 960.0 and values["youngs_modulus_particle"] == 1e9
    assert materials.pair_sigma0("PMMA", "steel", materials=table) == -4e-6  # a pair added
    assert materials.pair_sigma0("nylon", "steel", materials=table) == 1e-3  # the table's
    # the package's table is untouched, and a pair without a [charging] table has none
    assert materials.pair_values("PE", "steel")["sigma0"] == -1e-3
    assert "charging_time" not in materials.pair_values("PE", "steel")
    assert "charging_time" not in materials.pair_values("nylon", "steel", materials=table)
    # start_values and with_pair carry the file's values; the settings win
    assert materials.start_values("PE", "steel", materials=path)["sigma0"] == -2.2e-5
    assert materials.with_pair("PE", "steel", {"sigma0": -1e-6}, path)["sigma0"] == -1e-6
    assert materials.with_pair("PE", "steel", {"mu": 0.5}, None) == {"mu": 0.5}


@pytest.mark.parametrize("text, words", [
    ("[colour]\nPE = 1\n", ["[colour]", "sections"]),
    ("[material.EC]\ndensity = 1000.0\n", ["[material.EC]", "not a material of the package"]),
    ("[material.PE]\nhardness = 1.0\n", ["hardness", "density"]),
    ("[material.PE]\npoisson_ratio = 0.7\n", ["poisson_ratio = 0.7", "[0, 0.5]"]),
    ("[sigma0.steel]\nPE = -3e-2\n", ["PE = -0.03", "[-0.01, 0.01]"]),
    ("[sigma0]\nbreakdown_limit = 2.7e-5\n", ["breakdown_limit", "breakdown_model"]),
    ("[sigma0]\nlimit = 1.0\n", ["limit", "does not set it"]),
    ("[material.steel]\nconducting = 1\n", ["conducting = 1", "true"]),
    ("[sigma0.steel]\nPE = nan\n", ["PE = nan", "finite"]),
    ("[sigma0.wood]\nPE = -1e-5\n", ["wood", "steel"]),
    ("[sigma0.steel]\nsteel = -1e-5\n", ["steel", "particle"]),
    ("[charging.steel.PE]\ncharging_time = -1.0\n", ["charging_time = -1.0", "[0, inf]"]),
    ("[charging.steel.PE]\nbackflow = 1.0\n", ["backflow", "charging_time"]),
    ("[sigma0.steel\nPE = 1\n", ["not TOML"]),
])
def test_a_bad_materials_file_is_one_line_naming_the_file_and_the_entry(tmp_path, text, words):
    path = write(tmp_path, text)
    msg = one_line_error(lambda: materials.load(path))
    assert path in msg, msg
    for w in words:
        assert w in msg, msg


def test_a_missing_materials_file_is_one_line(tmp_path):
    msg = one_line_error(lambda: materials.load(str(tmp_path / "none.toml")))
    assert "none.toml" in msg

"""tribo.paschen: the gas's limit sigma_P(L) of a charged region (docs/model.md section 8e)
as the package states it, against the table of model.md section 8e and its limits; and the SI FMU's
impacts against it, an independent check of the core's table (here a grid refined by
golden sections, there the core's own minimisation)."""

import math

import pytest

import tribo
from tribo import paschen

# docs/model.md section 8e: sigma_P of air at 101325 Pa (A 11.25, B 273.8, gamma 0.01),
# metal wall, at these radii (um); the table's digits (2-3) set the tolerance: 2 %
TABLE = {1: 5.5e-3, 3: 1.9e-3, 10: 6.7e-4, 30: 3.1e-4, 100: 1.65e-4, 300: 1.10e-4,
         1000: 7.8e-5, 10000: 4.9e-5}


def test_sigma_p_is_model_mds_table():
    for radius_um, value in TABLE.items():
        assert paschen.limit(radius_um * 1e-6) == pytest.approx(value, rel=0.02), radius_um


def test_the_paschen_minimum_of_air():
    """About 305 V at 11 um (section 8e)."""
    assert paschen.AIR.minimum_voltage == pytest.approx(305.3, abs=0.1)
    assert paschen.AIR.minimum_gap == pytest.approx(11.0e-6, rel=0.01)
    # held at the minimum below its gap, and the curve rises on both sides of it
    assert paschen.AIR.breakdown_voltage(1e-7) == paschen.AIR.minimum_voltage
    d = paschen.AIR.minimum_gap
    assert paschen.AIR.breakdown_voltage(2 * d) > paschen.AIR.minimum_voltage


def test_sigma_p_is_the_minimum_over_every_gap():
    """No gap breaks down below sigma_P; at sigma_P some gap just does (to 1e-6): the
    golden sections found the minimum of the grid's bracket."""
    for radius in (2e-6, 5e-5, 3e-3):
        s = paschen.limit(radius) / paschen.EPSILON0
        h = radius / 2
        ratios = [paschen._ratio(paschen.AIR, h, 10 ** (k / 400.0)) for k in range(-3200, 0)]
        assert min(ratios) >= s * (1 - 1e-6)
        assert min(ratios) <= s * (1 + 1e-3)


def test_the_limits_of_small_and_large_regions():
    """Large regions: the plane's eps0 Vb(d)/d at gaps about the region's size (sigma_P
    falls slowly, within a factor 2 of it at d = L/2 for L of a millimetre and more); small
    ones: the minimum's voltage across the region's radius (g saturates at L/2: sigma_P ->
    eps0 Vmin / (L/2) as L falls below the minimum's gap)."""
    for radius in (1e-3, 1e-2):
        plane = paschen.EPSILON0 * paschen.AIR.breakdown_voltage(radius / 2) / (radius / 2)
        assert plane <= paschen.limit(radius) <= 2 * plane
    small = 1e-7
    assert paschen.limit(small) == pytest.approx(
        paschen.EPSILON0 * paschen.AIR.minimum_voltage / (small / 2), rel=0.02)
    values = [paschen.limit(10 ** (k / 4.0)) for k in range(-26, -7)]
    assert all(b < a for a, b in zip(values, values[1:]))  # falls with the size


def test_an_insulating_wall_keeps_less():
    """The pair form (L/2 -> L): sigma_P of an insulating wall is the image form's at 2 L."""
    for radius in (3e-6, 1e-4, 1e-3):
        assert paschen.limit(radius, conducting=False) == pytest.approx(
            paschen.limit(2 * radius), rel=1e-6)
        assert paschen.limit(radius, conducting=False) < paschen.limit(radius)


def test_the_grain_limit_of_a_2_mm_sphere():
    """sigma_P(1 mm) A_s, about 980 pC (section 8e)."""
    assert paschen.grain_limit(2e-3, 1.0) == pytest.approx(980e-12, rel=0.01, abs=0)
    assert paschen.spheroid_area(2e-3, 1.0) == pytest.approx(4 * math.pi * 1e-6, rel=1e-12, abs=0)


@pytest.mark.parametrize("settings, words", [
    ({"gas_pressure": 0.0}, ["gas_pressure = 0.0", "(0, inf)"]),
    ({"secondary_emission": 1.0}, ["secondary_emission = 1.0", "(0, 1)"]),
    ({"paschen_A": math.nan}, ["paschen_A = nan"]),
])
def test_a_bad_gas_is_one_line(settings, words):
    with pytest.raises(ValueError) as e:
        paschen.Gas.of(settings)
    assert len(str(e.value).splitlines()) == 1
    for w in words:
        assert w in str(e.value)


def test_a_lower_pressure_keeps_less():
    """Paschen's law in p d: at a tenth of the pressure a large region keeps less."""
    thin = paschen.Gas(pressure=10132.5)
    assert paschen.limit(1e-3, thin) < paschen.limit(1e-3)


# ---- the SI FMU against the package's sigma_P, and the new parameters through the commands --

def test_an_impact_leaves_sigma_p_of_its_region_or_sigma0_below_it():
    """docs/model.md section 8e: Delta q / A_max = sigma_P(L_e) where |sigma0| is above it
    (L_e the equal-area radius of the largest patch, sqrt(A_max / pi)), = |sigma0| where it
    is below; on an insulating wall the pair form. The core's sigma_P table against this
    module's own minimisation: measured within 0.16 % (0.2-10 mm, 0.1-10 m/s, 30 and 90
    degrees, eps 0.7; the core's table to 1e-4), held to 0.5 %."""
    for size, speed in ((2e-4, 1.0), (2e-4, 8.0), (2e-3, 0.5), (2e-3, 8.0), (1e-2, 2.0)):
        hit = tribo.single_impact("PE", "steel", speed=speed, size=size)  # sigma0 -1e-3
        radius = math.sqrt(hit["charged_area"] / math.pi)
        assert abs(hit["charge"]) / hit["charged_area"] == pytest.approx(
            min(1e-3, paschen.limit(radius)), rel=5e-3, abs=0), (size, speed)
        weak = tribo.single_impact("PE", "steel", speed=speed, size=size,
                                   settings={"sigma0": -1e-5})
        assert weak["charge"] / weak["charged_area"] == pytest.approx(-1e-5, rel=1e-9, abs=0)
    hit = tribo.single_impact("PE", "steel", speed=2.0, size=2e-3,
                              settings={"sigma0": -1e-3, "wall_conducting": 0})
    radius = math.sqrt(hit["charged_area"] / math.pi)
    assert abs(hit["charge"]) / hit["charged_area"] == pytest.approx(
        paschen.limit(radius, conducting=False), rel=5e-3, abs=0)


def test_the_gas_parameters_reach_the_core_through_the_api_and_the_commands(tmp_path, capsys):
    """breakdown_model 0 is revision 4's cap (breakdown_density); a thinner gas keeps less
    (settings= and --set take the new parameters by name, as every SI parameter); a value
    out of range is one line naming it, its value and its range, and nothing is written."""
    from tribo.cli.main import main as tribo_command
    fixed = tribo.single_impact("PE", "steel", speed=2.0, size=2e-3,
                                settings={"breakdown_model": 0})
    assert fixed["charge"] / fixed["charged_area"] == pytest.approx(-2.7e-5, rel=1e-9, abs=0)
    air = tribo.single_impact("PE", "steel", speed=2.0, size=2e-3)
    thin = tribo.single_impact("PE", "steel", speed=2.0, size=2e-3,
                               settings={"gas_pressure": 1e4})
    assert abs(thin["charge"]) < abs(air["charge"])
    gas = paschen.Gas.of({"gas_pressure": 1e4})
    assert abs(thin["charge"]) / thin["charged_area"] == pytest.approx(
        paschen.limit(math.sqrt(thin["charged_area"] / math.pi), gas), rel=5e-3, abs=0)
    out = tmp_path / "map"
    assert tribo_command(["impact-map", "--speed", "2", "--angle-deg", "90", "--set",
                          "gas_pressure=1e4", "--set", "secondary_emission=0.05", "--serial",
                          "--no-progress", "--no-plot", "--out", str(out)]) == 0
    capsys.readouterr()
    for bad, words in (("gas_pressure=0", ["gas_pressure", "0"]),
                       ("secondary_emission=1", ["secondary_emission", "1"]),
                       ("paschen_A=inf", ["paschen_A"]),
                       ("breakdown_model=2", ["breakdown_model", "2"]),
                       ("sigma0=-0.02", ["sigma0", "-0.02"])):
        bad_out = tmp_path / bad.split("=")[0]
        assert tribo_command(["impact-map", "--speed", "2", "--angle-deg", "90", "--set", bad,
                              "--serial", "--no-progress", "--out", str(bad_out)]) == 2, bad
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "valid range" in err, err
        for w in words:
            assert w in err, err
        assert not bad_out.exists()

"""The air-breakdown limit through the SI FMUs, both FMI versions. The fixed limit (docs/model.md
§8b, breakdown_model = 0): the reference case's sliding densities stand at most at
breakdown_density (2.7e-5 C/m2 by default), some at it, the rest booked as lost; with
breakdown_density = 0 there is no limit and the densities pass it. The Paschen limit (§8e,
the default): what it means for a set-up (the calculated parameters), what it leaves on an
impact, and bad gas constants refused with one line before anything runs."""

import math

import pytest
from fmpy import extract, simulate_fmu
from tribo_fmu import Slave

SI = "tribo_si"
LIMIT = 2.7e-5
OUTPUTS = ["capped_fraction_sliding", "charge_lost_sliding", "charge_to_mass_sliding",
           "capped_fraction_static", "Sigma_bd"]


def last_row(fmu_file, version, **start):
    kwargs = {"early_return_allowed": True} if version == 3 else {}
    r = simulate_fmu(fmu_file(version, SI), stop_time=0.5, output_interval=0.05,
                     start_values={"chute_length": 0.3, "n_segments": 400, "breakdown_model": 0,
                                   **start},
                     output=OUTPUTS, **kwargs)
    return r[-1]


@pytest.mark.parametrize("version", [2, 3])
def test_default_limit_caps_the_sliding_model(fmu_file, version):
    capped = last_row(fmu_file, version)
    free = last_row(fmu_file, version, breakdown_density=0.0)
    assert 0.0 < capped["capped_fraction_sliding"] < 1.0
    assert capped["charge_lost_sliding"] != 0.0
    assert capped["capped_fraction_static"] == 0.0  # |sigma0| = 1e-5 C/m2 is below it
    assert free["Sigma_bd"] == float("inf")
    assert free["capped_fraction_sliding"] == 0.0 and free["charge_lost_sliding"] == 0.0
    # the limit only takes charge away
    assert abs(capped["charge_to_mass_sliding"]) < abs(free["charge_to_mass_sliding"])


# (name, value, the range the message gives): a pressure of 0, gamma at 1 and 0 (the curve's
# minimum, at A p d = e ln(1 + 1/gamma), needs gamma in (0, 1)), sigma0 beyond 1e-2 C/m2,
# gas constants that are not numbers, and constants whose curve has no minimum: A or B not
# positive (ln(A p d) undefined, or a breakdown voltage below 0)
BAD = [("gas_pressure", 0.0, "1000 <= gas_pressure <= 1e+07"),
       ("secondary_emission", 1.0, "0 < secondary_emission < 1"),
       ("secondary_emission", 0.0, "0 < secondary_emission < 1"),
       ("sigma0", 2e-2, "-0.01 <= sigma0 <= 0.01"),
       ("sigma0", -2e-2, "-0.01 <= sigma0 <= 0.01"),
       ("paschen_A", math.nan, "0.1 <= paschen_A <= 1000"),
       ("paschen_B", math.inf, "1 <= paschen_B <= 10000"),
       ("gas_pressure", -math.inf, "1000 <= gas_pressure <= 1e+07"),
       ("paschen_A", -11.25, "0.1 <= paschen_A <= 1000"),
       ("paschen_B", 0.0, "1 <= paschen_B <= 10000")]


@pytest.mark.parametrize("version", [2, 3])
def test_bad_gas_constants_are_refused_in_one_line(fmu_file, version):
    unpacked = extract(fmu_file(version, SI))
    for name, value, valid in BAD:
        with Slave(unpacked, version, name=SI) as s:
            with pytest.raises(Exception):
                s.set(**{name: value})
            errors = s.errors()
            assert len(errors) == 1, errors
            assert f"{name} = {value:g}" in errors[0] and valid in errors[0], errors[0]


@pytest.mark.parametrize("version", [2, 3])
def test_the_paschen_limit_of_the_reference_gas(fmu_file, version):
    """Air at 101325 Pa: its least breakdown voltage about 305 V at 11 um (§8e), and a 2 mm
    sphere's own limit sigma_P(1 mm) A_s about 980 pC."""
    r = simulate_fmu(fmu_file(version, SI), stop_time=1e-6,
                     start_values={"semi_major_axis": 1e-3, "epsilon": 1.0},
                     output=["paschen_minimum_voltage", "paschen_minimum_gap",
                             "grain_charge_limit", "paschen_gap_scale"])[-1]
    assert r["paschen_minimum_voltage"] == pytest.approx(305.3, abs=0.5)
    assert r["paschen_minimum_gap"] == pytest.approx(11.0e-6, abs=0.1e-6)
    assert r["grain_charge_limit"] == pytest.approx(980e-12, rel=0.01)
    assert r["paschen_gap_scale"] == pytest.approx(11.25 * 101325 * 1e-3, rel=1e-12)


@pytest.mark.parametrize("version", [2, 3])
def test_an_impact_is_held_at_its_regions_limit_by_default(fmu_file, version):
    """A 2 mm PE sphere at 1 m/s head-on on steel with |sigma0| = 1e-3 C/m2 keeps sigma_P of
    its region: about 1.26 pC (§8e: 1.3); on an insulating wall (wall_conducting = 0, the
    pair form: the image form's at twice the size) less; with breakdown_model = 0, §8b's
    2.7e-5 C/m2 on every band."""
    def charge(**more):
        start = {"semi_major_axis": 1e-3, "epsilon": 1.0, "tilt": 0.0, "drop_height": 0.0,
                 "drop_speed": 1.0, "run_end": 1, "sigma0": -1e-3, **more}
        kwargs = {"early_return_allowed": True} if version == 3 else {}
        r = simulate_fmu(fmu_file(version, SI), stop_time=1e-3, output_interval=1e-4,
                         start_values=start, output=["charge_static", "charged_area"], **kwargs)
        return r[-1]["charge_static"], r[-1]["charged_area"]
    q, area = charge()
    assert q == pytest.approx(-1.26e-12, rel=0.02)
    q_pair, _ = charge(wall_conducting=0)
    assert q < q_pair < 0.0
    q_fixed, area_fixed = charge(breakdown_model=0)
    assert q_fixed == pytest.approx(-2.7e-5 * area_fixed, rel=1e-9)

"""The air-breakdown limit (docs/model.md §8b) through the SI FMUs, both FMI versions: the
reference case's sliding densities stand at most at breakdown_density (2.7e-5 C/m2 by
default), some at it, the rest booked as lost; with breakdown_density = 0 there is no limit
and the densities pass it."""

import pytest
from fmpy import simulate_fmu

SI = "tribo_si"
LIMIT = 2.7e-5
OUTPUTS = ["capped_fraction_sliding", "charge_lost_sliding", "charge_to_mass_sliding",
           "capped_fraction_static", "Sigma_bd"]


def last_row(fmu_file, version, **start):
    kwargs = {"early_return_allowed": True} if version == 3 else {}
    r = simulate_fmu(fmu_file(version, SI), stop_time=0.5, output_interval=0.05,
                     start_values={"chute_length": 0.3, "n_segments": 400, **start},
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

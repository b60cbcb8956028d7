"""Never a silent failure (issue 4): when the integrator cannot go on, doStep returns an
error and the logger says why, with the time and the state."""

import pytest

from tribo_fmu import ERROR, VERSIONS, Slave, status_of


@pytest.mark.parametrize("version", VERSIONS)
def test_cvode_failure_is_an_fmi_error_with_time_and_state(fmu_dir, version):
    # a spin of 1e12 rad per time unit would need steps of 2e-13 to follow the lowest point
    s = Slave(fmu_dir(version), version).init(integrator=1, Omega0=1e12, gap0=0.5, charge_model=0)
    assert status_of(s.fmu.doStep, 0.0, 1.0) == ERROR
    errors = " ".join(s.errors())
    assert "too much work" in errors and "t = " in errors and "Omega = " in errors

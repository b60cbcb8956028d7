"""Where the model's assumptions break: a contact indented beyond 0.1 min(epsilon, rho_c)
is reported through the FMI logger as a warning, and counted in the assumption_warnings
output, never returned quietly."""

import pytest

from tribo_fmu import VERSIONS, WARNING, Slave

# With the centre dashpot (damping_point = 1) at nu = 1 a particle turning over in normal
# lock indents far beyond the contact model's assumptions (delta_y ~ 0.4 for eps = 0.6);
# the paper's low-friction drop does not.
NO_CHARGE = dict(charge_model_static=0, charge_model_sliding=0)
DEEP = dict(epsilon=0.6, mu=1.0, nu=1.0, integrator=1, damping_point=1, **NO_CHARGE)
SHALLOW = dict(integrator=1, **NO_CHARGE)


@pytest.mark.parametrize("version", VERSIONS)
def test_deep_indentation_is_a_logged_and_counted_warning(fmu_dir, version):
    s = Slave(fmu_dir(version), version).init(**DEEP)
    s.step_to(100.0)
    counted = s.get("assumption_warnings")
    warnings = [(c, m) for status, c, m in s.messages if status == WARNING]
    assert counted >= 1
    # logged without debug logging on: the first ten one by one, in the warnings' category
    assert len(warnings) == min(counted, 10)
    assert all(c == "logStatusWarning" and "delta_y" in m and "rho_c" in m for c, m in warnings)


@pytest.mark.parametrize("version", VERSIONS)
def test_warnings_can_be_silenced_but_are_still_counted(fmu_dir, version):
    s = Slave(fmu_dir(version), version)
    s.fmu.setDebugLogging(False, [])  # every category off
    s.init(**DEEP)
    s.step_to(100.0)
    assert s.get("assumption_warnings") >= 1
    assert not [m for status, _, m in s.messages if status == WARNING]


@pytest.mark.parametrize("version", VERSIONS)
def test_the_papers_drop_stays_within_the_assumptions(fmu_dir, version):
    s = Slave(fmu_dir(version), version).init(**SHALLOW)
    s.step_to(100.0)
    assert s.get("assumption_warnings") == 0
    assert not [m for status, _, m in s.messages if status == WARNING]

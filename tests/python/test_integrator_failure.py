"""Never a silent failure: when the integrator cannot go on, doStep returns an
error and the logger says why, with the time and the state; the instance then only
resets or restores a state.

No valid scene starts such a run (the ranges keep the spin to what CVODE follows),
so a consistent but hostile FMU state brings the spin in: 1e12 rad per time unit in the
committed point and in CVODE's restart point alike."""

import struct

import pytest

from tribo_fmu import ERROR, OK, VERSIONS, Slave, status_of


def with_spin(data, old, new):
    """The serialized state with the spin `old` of the motion (its third and fourth
    8-byte occurrence: after the FMU's and the core's parameter Omega0) made `new`."""
    data = bytearray(data)
    marker = struct.pack("=d", old)
    at = [i for i in range(0, len(data) - 7, 8) if data[i:i + 8] == marker]
    assert len(at) == 4, at  # Omega0 (FMU, core), the committed spin, CVODE's restart spin
    for i in at[2:]:
        data[i:i + 8] = struct.pack("=d", new)
    return bytes(data)


@pytest.mark.parametrize("version", VERSIONS)
def test_cvode_failure_is_an_fmi_error_with_time_and_state(fmu_dir, version):
    # the work limit raised, so that CVODE's guard against runaway integration speaks first
    s = Slave(fmu_dir(version), version).init(integrator=1, Omega0=77.0, gap0=0.5,
                                               charge_model_static=0, charge_model_sliding=0,
                                               work_limit=2**31 - 1)
    hostile = with_spin(s.serialize(s.get_state()), 77.0, 1e12)
    s.set_state(s.deserialize(hostile))
    # a spin of 1e12 would need steps of 2e-13 to follow the lowest point
    assert status_of(s.fmu.doStep, 0.0, 1e-3) == ERROR
    errors = " ".join(s.errors())
    assert "too much work" in errors and "t = " in errors and "Omega = " in errors
    assert status_of(s.fmu.doStep, 0.0, 1e-3) == ERROR  # failed: no more steps...
    assert "Error" in s.errors()[-1]
    s.reset()  # ...until a reset
    s.init(integrator=1)
    assert status_of(s.fmu.doStep, 0.0, 0.5) == OK

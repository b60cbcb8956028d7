"""FMU states: saved, restored, serialized and deserialized, they continue a run
bit-identically, in the same instance or in a fresh one."""

import pytest

from tribo_fmu import ERROR, INTEGRATORS, VERSIONS, Slave, integrator_id, status_of

SMALL = {"n_segments": 64}
LATER = [1.25, 1.5, 1.75, 2.0]


def outputs(s, output_names):
    return output_names + (["segment_charge_static", "segment_charge_sliding"] if s.version == 3 else [])


def started(fmu_dir, version, integrator, **params):
    s = Slave(fmu_dir(version), version).init(integrator=integrator, **dict(SMALL, **params))
    s.run([0.5, 1.0], ["X"])
    return s


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", INTEGRATORS, ids=integrator_id)
def test_state_round_trips_continue_bit_identically(fmu_dir, output_names, version, integrator):
    s = started(fmu_dir, version, integrator)
    names = outputs(s, output_names)
    state = s.get_state()
    data = s.serialize(state)
    first = s.run(LATER, names)

    s.set_state(state)
    assert s.get("time") == 1.0
    s.t = 1.0
    assert s.run(LATER, names) == first

    restored = s.deserialize(data)  # from bytes, into the same instance
    s.set_state(restored)
    s.t = 1.0
    assert s.run(LATER, names) == first
    s.free_state(state)
    s.free_state(restored)

    fresh = Slave(fmu_dir(version), version)  # never initialized
    fresh.set_state(fresh.deserialize(data))
    fresh.t = 1.0
    assert fresh.get("time") == 1.0 and fresh.get("n_segments") == 64
    assert fresh.run(LATER, names) == first
    assert s.errors() == fresh.errors() == []


@pytest.mark.parametrize("version", VERSIONS)
def test_state_holds_no_pointers(fmu_dir, version):
    """Two instances in the same state serialize to the same bytes: nothing in them
    depends on where an instance lives in memory."""
    a, b = (started(fmu_dir, version, 0) for _ in range(2))
    assert a.serialize(a.get_state()) == b.serialize(b.get_state())


@pytest.mark.parametrize("version", VERSIONS)
def test_state_remembers_the_fmi_state_and_parameters(fmu_dir, version):
    s = Slave(fmu_dir(version), version)
    s.set(epsilon=0.3, n_segments=48)
    data = s.serialize(s.get_state())  # before initialization: no core instance yet
    other = Slave(fmu_dir(version), version)
    other.set_state(other.deserialize(data))
    assert other.get("epsilon") == 0.3 and other.get("n_segments") == 48
    assert status_of(other.fmu.doStep, 0.0, 0.1) == ERROR  # still Instantiated
    other.init()
    other.step_to(0.5)
    assert other.get("epsilon") == 0.3


@pytest.mark.parametrize("version", VERSIONS)
def test_state_restores_tunables_changed_after_it(fmu_dir, output_names, version):
    s = started(fmu_dir, version, 0)
    state = s.get_state()
    first = s.run(LATER, output_names)
    s.set_state(state)
    s.t = 1.0
    s.set(mu=0.9)
    s.run(LATER, output_names)
    s.set_state(state)  # mu back to what it was when saved
    s.t = 1.0
    assert s.get("mu") == 0.1
    assert s.run(LATER, output_names) == first


@pytest.mark.parametrize("version", VERSIONS)
def test_corrupt_or_foreign_states_are_refused(fmu_dir, version):
    s = started(fmu_dir, version, 0)
    data = s.serialize(s.get_state())
    time = s.get("time")
    assert status_of(s.deserialize, data[:-8]) == ERROR
    assert "size" in s.errors()[-1]
    assert status_of(s.deserialize, b"garbage!" + data[8:]) == ERROR
    assert "not a state of this FMU" in s.errors()[-1]
    other_version = 5 - version
    foreign = started(fmu_dir, other_version, 0)
    assert status_of(s.deserialize, foreign.serialize(foreign.get_state())) == ERROR
    assert "other FMI version" in s.errors()[-1]
    # a state of a scene with other structural parameters is rebuilt, not refused
    big = started(fmu_dir, version, 0, n_segments=128)
    s.set_state(s.deserialize(big.serialize(big.get_state())))
    assert s.get("n_segments") == 128
    # and the instance survived the refusals
    assert time == 1.0 and s.get("time") == 1.0


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("geometry", [0, 1], ids=["cylinder", "spheroid"])
def test_states_under_a_tiny_breakdown_limit_restore(fmu_dir, version, geometry):
    """A breakdown limit Sigma_bd far below the saturation (1e-300 .. 1e-14: held values a
    tiny fraction of what the rate laws reach) keeps each model's running sum that of its
    held values: a state the FMU gave back is taken back and continues bit for bit, and the
    static charge Q_static (the running sum's mean) is the segments' mean. (The sum once
    rounded at the unheld scale, up to 1e16 times the held values: every state refused.)"""
    for limit in (1e-300, 1e-100, 1e-30, 1e-14):
        s = started(fmu_dir, version, 1, Sigma_bd=limit, grain_geometry=geometry,
                    charge_model_static=1, charge_model_sliding=1)
        state = s.get_state()
        first = s.run(LATER, ["X", "Q_static", "Q_sliding"])
        s.set_state(s.deserialize(s.serialize(state)))
        s.t = 1.0
        assert s.run(LATER, ["X", "Q_static", "Q_sliding"]) == first, limit
        assert s.errors() == [], (limit, s.errors())
        if version == 3:
            # the sum of 64 values of one sign rounds within 64 ulps of their mean
            values = s.get("segment_charge_static")
            assert s.get("Q_static") == pytest.approx(sum(values) / len(values), rel=1e-14)
            assert max(values) > 0.0

"""hold_at_end (every FMU, the FMU layer: fmu/step.c): at the run's end (the chute's exit,
the separator's landing) a step completes and later steps hold every output there, so that a
master that takes fmi2Discard / terminateSimulation for a failure runs on; false (the
default) ends the simulation there as before."""

import numpy as np
import pytest
from fmpy import simulate_fmu

from conftest import built
from tribo_fmu import Slave

# each kind's run to its end well before the stop time
CASES = {
    "tribo_si": ({"chute_length": 0.05}, 1.0, 0.01, "exited"),
    "tribo_separator": ({"released": True, "u_entry": 0.5}, 1.0, 0.01, "ended"),
    "tribo": ({"chute_length": 20.0}, 1000.0, 10.0, "exited"),
}


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("prefix", sorted(CASES))
def test_held_at_the_end_the_run_completes_with_every_output_constant(prefix, version):
    values, stop, interval, flag = CASES[prefix]
    fmu = built("fmu", f"{prefix}_fmi{version}.fmu")
    held = simulate_fmu(fmu, stop_time=stop, output_interval=interval,
                        start_values=values | {"hold_at_end": True})
    ended = simulate_fmu(fmu, stop_time=stop, output_interval=interval, start_values=values)
    # without: the simulation ends at the run's end, as it always did
    t_end = ended["time"][-1]
    assert t_end < stop / 2 and ended[flag][-1]
    # with: to the stop time; the same run up to its end, then every output held
    assert held["time"][-1] == pytest.approx(stop)
    n = len(ended) - 1  # the last communication point before the end
    for name in ended.dtype.names:
        if name != "time":
            assert np.array_equal(held[name][:n], ended[name][:n]), name
    after = held[held["time"] > t_end]
    assert len(after) > 10 and after[flag].all()
    for name in held.dtype.names:
        if name != "time":
            # (FMI 3.0: the segment arrays too)
            assert all(np.array_equal(v, ended[name][-1]) for v in after[name]), name


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("prefix", sorted(CASES))
def test_a_state_saved_while_held_restores_and_holds_on(prefix, version, fmu_dir):
    """Saved past the run's end, restored in the same instance and deserialized into a
    fresh one: the same time, the same outputs, and later steps held as before."""
    values, stop, interval, flag = CASES[prefix]
    s = Slave(fmu_dir(version, prefix), version).init(**(values | {"hold_at_end": True}))
    times = [interval * k for k in range(1, round(stop / interval) + 1)]
    names = [v.name for v in s.md.modelVariables
             if v.causality == "output" and not v.dimensions]
    t_save = times[len(times) * 3 // 4]
    assert all(s.step_to(t) for t in times if t <= t_save) and s.get(flag)
    state = s.get_state()
    data = s.serialize(state)
    saved = s.get_many(names)
    assert all(s.step_to(t) for t in times if t > t_save) and s.get_many(names) == saved
    s.set_state(state)
    assert s.get("time") == pytest.approx(t_save) and s.get_many(names) == saved
    fresh = Slave(fmu_dir(version, prefix), version)
    fresh.set_state(fresh.deserialize(data))
    fresh.t = s.t = t_save
    for instance in (s, fresh):
        assert all(instance.step_to(t) for t in times if t > t_save)
        assert instance.get_many(names) == saved and instance.get(flag)
    assert s.errors() == fresh.errors() == []

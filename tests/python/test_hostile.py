"""Hostile and careless importers: each defect that fuzzing the FMUs found, as an importer
meets it through fmpy. The fuzz suite itself: test_fuzz.py (tests/fuzz)."""

import math
import struct
import time

import pytest

from tribo_fmu import DISCARD, ERROR, INTEGRATORS, OK, VERSIONS, Slave, integrator_id, status_of

# A guard against a call that never returns, not a bound on its cost (the work limit bounds
# that, and the C tests assert it in units of work): sixty times the second of CPU a doStep
# may take, so that a busy machine does not fail it.
HANG_GUARD_S = 60.0

SMALL = {"n_segments": 64}
MOTION = ["X", "Y", "phi", "U", "V", "Omega", "Q_static", "Q_sliding", "energy"]


def finite_outputs(s, output_names):
    return all(math.isfinite(v) for v in s.get_many(output_names).values())


# ---- the fixed step restores its own state at accumulated times -------------------------------

@pytest.mark.parametrize("version", VERSIONS)
def test_fixed_step_restores_its_state_when_the_importer_adds_up_time(fmu_dir, version):
    s = Slave(fmu_dir(version), version).init(integrator=0, **SMALL)
    t = 0.0
    for _ in range(40):  # 0.30000000000000004, 0.9999999999999999, ...
        s.fmu.doStep(t, 0.1)
        t += 0.1
        state = s.get_state()
        s.set_state(state)  # was: "state is corrupt (times or inputs)" from the 10th step on
        s.free_state(state)
    assert s.errors() == []
    s.t = t
    s.step_to(t + 0.1)


# ---- a restored state runs on with its own tolerances -----------------------------------------

@pytest.mark.parametrize("version", VERSIONS)
def test_state_restored_into_other_tolerances_continues_the_saved_run(fmu_dir, version):
    saver = Slave(fmu_dir(version), version).init(integrator=1, rtol=1e-6, atol=1e-8, **SMALL)
    saver.step_to(10.0)
    data = saver.serialize(saver.get_state())
    other = Slave(fmu_dir(version), version).init(integrator=1, **SMALL)  # rtol 1e-9
    other.set_state(other.deserialize(data))
    other.t = 10.0
    assert other.get("rtol") == 1e-6
    # was: X 0.424780 against 0.424808 at 25
    assert other.run([25.0], MOTION) == saver.run([25.0], MOTION)


# ---- a state of Initialization Mode after a change restores -----------------------------------

def enter_initialization(s):
    if s.version == 2:
        s.fmu.setupExperiment(startTime=0.0)
        s.fmu.enterInitializationMode()
    else:
        s.fmu.enterInitializationMode(startTime=0.0)


@pytest.mark.parametrize("version", VERSIONS)
def test_state_of_initialization_mode_after_a_change_restores(fmu_dir, version):
    s = Slave(fmu_dir(version), version)
    s.set(**SMALL)
    enter_initialization(s)
    s.get("X")  # the core instance is made, for epsilon = 0.5
    s.set(epsilon=0.3)  # and outdated
    state = s.get_state()
    s.set(epsilon=0.7)
    s.set_state(state)  # was: "state was saved with epsilon = 0.5, this instance has 0.3"
    assert s.get("epsilon") == 0.3 and s.errors() == []
    s.fmu.exitInitializationMode()
    reference = Slave(fmu_dir(version), version).init(epsilon=0.3, **SMALL)
    assert s.run([1.0], MOTION) == reference.run([1.0], MOTION)


# ---- corrupt states are refused, and the instance stays as it was -----------------------------

def offsets(s):
    """Where fields lie in a serialized state (fmu/fmu_state.c, src/chute/state_io.c, the CVODE
    integrator's bytes at the end)."""
    n = len([v for v in s.md.modelVariables if v.causality in ("parameter", "structuralParameter")])
    core = 32 + 8 * 8 + 2 * 8 + 8 * n
    params_end = core + 24 + 8 * n
    return {"core t_out": params_end + 16, "steps": params_end + 24,
            "X": params_end + 24 + 48 + 8, "fmu time": 64}


def mutated(data, offset, value, fmt="=d"):
    data = bytearray(data)
    data[offset:offset + 8] = struct.pack(fmt, value)
    return bytes(data)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", (0, 1), ids=integrator_id)
def test_corrupt_states_are_refused_and_change_nothing(fmu_dir, output_names, version, integrator):
    s = Slave(fmu_dir(version), version).init(integrator=integrator, **SMALL)
    twin = Slave(fmu_dir(version), version).init(integrator=integrator, **SMALL)
    s.step_to(1.0)
    twin.step_to(1.0)
    data = s.serialize(s.get_state())
    at = offsets(s)
    bad = {
        "NaN in the motion": mutated(data, at["X"], math.nan),
        "infinity in the motion": mutated(data, at["X"], math.inf),
        "an output time of 1e9": mutated(data, at["core t_out"], 1e9),  # was: endless
        "the FMU's time off the core's": mutated(data, at["fmu time"], 7.0),
        "a step counter at 2^63 - 1": mutated(data, at["steps"], 2**63 - 1, "=q"),  # was: UB
        "a replay of 2^62 steps": mutated(data, len(data) - 176 + 96, 2**62, "=q"),
    }
    before = s.get_many(output_names)
    for what, corrupt in bad.items():
        state = s.deserialize(corrupt)  # only the header is checked here
        start = time.monotonic()
        assert status_of(s.set_state, state) == ERROR, what
        assert time.monotonic() - start < HANG_GUARD_S, what  # was: endless
        assert "corrupt" in s.errors()[-1] or "refused" in s.errors()[-1], (what, s.errors()[-1])
        assert s.get_many(output_names) == before, what
        s.free_state(state)
    # a refused header or size does not change the instance either
    assert status_of(s.deserialize, data[:-8]) == ERROR
    assert status_of(s.deserialize, b"garbage!" + data[8:]) == ERROR
    assert s.run([2.0], output_names) == twin.run([2.0], output_names)


# ---- huge steps are refused or bounded --------------------------------------------------------

@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", INTEGRATORS, ids=integrator_id)
def test_huge_steps_are_refused_or_end_early(fmu_dir, output_names, version, integrator):
    s = Slave(fmu_dir(version), version).init(integrator=integrator, **SMALL)
    for huge in (1e300, 1e18, 2e12):
        status, _, _ = s.do_step(0.0, huge)
        assert status == ERROR, huge  # refused before the core moves
        assert "cannot advance" in s.errors()[-1], s.errors()[-1]
    assert status_of(s.fmu.doStep, 0.0, 0.5) == OK  # the instance is still at 0, usable
    start = time.monotonic()
    status, reached, early = s.do_step(0.5, 1e6)  # was: +-inf and NaN, or never returned
    assert time.monotonic() - start < HANG_GUARD_S  # ended by the work limit (under a second)
    assert status == DISCARD and not early and 0.5 < reached < 1e6
    assert s.get("time") == reached and finite_outputs(s, output_names)
    if version == 2:  # stepFailed: no step, but terminate, reset or a saved state
        assert s.do_step(reached, 1.0)[0] == ERROR
        s.fmu.terminate()
    else:  # Step Mode goes on from the time reached
        assert s.do_step(reached, 1.0)[0] == OK


# ---- the work of one step is bounded; stopping early changes nothing --------------------------

@pytest.mark.parametrize("integrator", (0, 1), ids=integrator_id)
def test_early_returns_continue_the_same_run(fmu_dir, output_names, integrator):
    """FMI 3.0 with early returns allowed: a step that spends work_limit returns early at
    the time reached, and going on from there gives the run of unlimited steps."""
    limit = 12000 if integrator == 0 else 80  # some 20000 fixed steps, 10 CVODE steps
    parts = Slave(fmu_dir(3), 3, early_return=True).init(integrator=integrator, work_limit=limit,
                                                          **SMALL)
    whole = Slave(fmu_dir(3), 3).init(integrator=integrator, work_limit=2**31 - 1, **SMALL)
    t, returns = 0.0, 0
    while t < 10.0:
        status, reached, early = parts.do_step(t, 10.0 - t)
        assert status == OK and reached > t and early == (reached < 10.0)
        returns += early
        t = reached
    assert returns > 2
    whole.step_to(10.0)
    assert parts.get_many(output_names) == whole.get_many(output_names)


@pytest.mark.parametrize("version", VERSIONS)
def test_a_stiff_input_ends_the_step_early_instead_of_running_for_minutes(fmu_dir, output_names,
                                                                             version):
    s = Slave(fmu_dir(version), version).init(integrator=0, **SMALL)
    s.set(F_N_ext=-10.0, nu=100.0)  # pushed into the plate: thousands of sub-steps per step
    start = time.monotonic()
    status, reached, _ = s.do_step(0.0, 1.0)
    assert time.monotonic() - start < HANG_GUARD_S  # ended by the work limit (under a second)
    assert status in (OK, DISCARD) and 0.0 < reached <= 1.0
    assert finite_outputs(s, output_names)


# ---- valid extreme values give finite outputs -------------------------------------------------

EXTREMES = [{"tau0": 1e-9, "tau_r": 1e-9}, {"Sigma0": 1e-9, "eta": 1e9}, {"Sigma0": 1e9},
            {"Gamma": 10.0}, {"drop_speed": 10.0}, {"epsilon": 1e-3}, {"mu": 100.0, "nu": 100.0},
            {"F_T_ext": 10.0, "F_N_ext": -10.0}, {"Omega0": 100.0, "epsilon": 0.2}]


@pytest.mark.parametrize("integrator", (0, 1), ids=integrator_id)
@pytest.mark.parametrize("extreme", EXTREMES, ids=lambda e: ",".join(f"{k}={v:g}" for k, v in e.items()))
def test_values_at_the_ends_of_their_ranges_give_finite_outputs(fmu_dir, output_names, integrator,
                                                                extreme):
    s = Slave(fmu_dir(2), 2).init(integrator=integrator, **dict(SMALL, **extreme))
    status, reached, _ = s.do_step(0.0, 0.5)
    assert status in (OK, DISCARD), s.errors()
    assert finite_outputs(s, output_names)


# ---- a set call is checked whole before any of it is applied ----------------------------------

@pytest.mark.parametrize("version", VERSIONS)
def test_a_set_with_one_refused_value_applies_none(fmu_dir, output_names, version):
    s = Slave(fmu_dir(version), version)
    set_real = s.fmu.setReal if version == 2 else s.fmu.setFloat64
    mu, y, eps = (s.variables[n].valueReference for n in ("mu", "Y", "epsilon"))
    assert status_of(set_real, [mu, y], [0.7, 1.0]) == ERROR  # Y is an output
    assert s.get("mu") == 0.1  # was: 0.7
    s.init(**SMALL)
    s.step_to(0.5)
    force = s.variables["F_T_ext"].valueReference
    assert status_of(set_real, [mu, force, eps], [0.7, 0.5, 0.3]) == ERROR  # epsilon is fixed
    assert status_of(set_real, [mu, force], [0.7, math.nan]) == ERROR
    assert s.get("mu") == 0.1 and s.get("F_T_ext") == 0.0
    undisturbed = Slave(fmu_dir(version), version).init(**SMALL).run([0.5, 1.0], output_names)[-1]
    assert s.run([1.0], output_names)[-1] == undisturbed


# ---- a refused call changes nothing -----------------------------------------------------------

def serialized(s):
    """The instance's own state, as bytes."""
    state = s.get_state()
    data = s.serialize(state)
    s.free_state(state)
    return data


def restores(s):
    """Whether the instance takes back its own state (logging why not)."""
    state = s.get_state()
    try:
        return status_of(s.set_state, state) == OK
    finally:
        s.free_state(state)


def set_up_experiment(s, tolerance, start, stop):
    """fmi2SetupExperiment, or fmi3EnterInitializationMode: the status."""
    f = s.fmu._functions
    if s.version == 2:
        return f["fmi2SetupExperiment"](s.fmu.component, 1, tolerance, start, 1, stop)
    return f["fmi3EnterInitializationMode"](s.fmu.component, True, tolerance, start, True, stop)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("tolerance", (2.0, math.nan, 0.0, -1e-6))
@pytest.mark.parametrize("explicit", ({}, {"rtol": 1e-6, "atol": 1e-8}),
                         ids=("tolerance used", "rtol and atol set"))
def test_a_refused_experiment_changes_nothing(fmu_dir, version, tolerance, explicit):
    s = Slave(fmu_dir(version), version)
    s.set(**explicit)
    before = serialized(s)
    assert set_up_experiment(s, tolerance, 5.0, 10.0) == ERROR
    assert "tolerance" in s.errors()[-1] and "rtol" in s.errors()[-1], s.errors()[-1]
    assert serialized(s) == before  # was: start and stop times kept
    if version == 2:
        s.fmu.enterInitializationMode()
    else:
        s.fmu.enterInitializationMode(startTime=0.0)
    s.fmu.exitInitializationMode()
    assert s.get("time") == 0.0  # was: 5, and a step from 0 refused
    assert s.do_step(0.0, 0.5)[0] == OK


@pytest.mark.parametrize("version", VERSIONS)
def test_an_initialization_refused_for_its_inputs_changes_nothing(fmu_dir, version):
    # the SI FMU's input is in its declared range, its model value (F / (k' a)) is not: a
    # grain of a = 0.1 mm takes at most 10 k' a = 9.9e5 N/m
    s = Slave(fmu_dir(version, "tribo_si"), version)
    s.set(semi_major_axis=1e-4, F_T_ext=4e6)
    enter_initialization(s)
    before = serialized(s)
    assert status_of(s.fmu.exitInitializationMode) == ERROR
    assert "F_T_ext" in s.errors()[-1] and "-10 <= F_T_ext <= 10" in s.errors()[-1], s.errors()[-1]
    assert serialized(s) == before  # was: the core instance made for the inputs kept
    s.set(F_T_ext=1.0)
    s.fmu.exitInitializationMode()
    assert s.do_step(0.0, 1e-4)[0] == OK


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("params, huge", [({"integrator": 1}, 1e300),
                                          ({"integrator": 0, "dt": 1e-9}, 4e4)],
                         ids=("beyond the core's time", "beyond the fixed step's grid"))
def test_a_step_refused_for_its_size_leaves_the_inputs_pending(fmu_dir, output_names, version,
                                                               params, huge):
    s = Slave(fmu_dir(version), version).init(**SMALL, **params)
    undisturbed = Slave(fmu_dir(version), version).init(**SMALL, **params)
    for x in (s, undisturbed):
        x.set(F_T_ext=0.5)
    before = serialized(s)
    assert s.do_step(0.0, huge)[0] == ERROR
    assert "cannot advance" in s.errors()[-1], s.errors()[-1]
    assert serialized(s) == before  # was: the inputs handed to the model, its integrator restarted
    assert s.run([1e-5], output_names) == undisturbed.run([1e-5], output_names)

# ---- the FMU's time is the model's, and never goes back ---------------------------------------

@pytest.mark.parametrize("version", VERSIONS)
def test_a_step_that_would_end_before_the_fmus_time_is_refused(fmu_dir, version):
    # at 1e9 a communication point may be off by up to 1 (rounding): 0.9 behind is the FMU's
    # time, but a step of 0.1 from there ends 0.8 before it
    s = Slave(fmu_dir(version), version).init(start=1e9, **SMALL)
    before = serialized(s)
    for _ in range(3):  # was: OK each time, the time walking back below the start time
        assert s.do_step(1e9 - 0.9, 0.1)[0] == ERROR
        message = s.errors()[-1]
        assert "999999999.2" in message and "1000000000" in message and "cannot go back" in message
        assert s.get("time") == 1e9 and serialized(s) == before
    assert restores(s), s.errors()[-1]  # was: "the state is corrupt: its time ..."
    assert s.do_step(1e9, 0.5)[0] == OK and s.get("time") == 1e9 + 0.5


@pytest.mark.parametrize("version", VERSIONS)
def test_a_point_a_rounding_behind_steps_the_model_to_the_steps_end(fmu_dir, output_names, version):
    s = Slave(fmu_dir(version), version).init(start=1e9, **SMALL)
    end = (1e9 - 0.05) + 0.1
    assert s.do_step(1e9 - 0.05, 0.1)[0] == OK
    assert s.get("time") == end and restores(s)
    # the model's time is the FMU's less the start time: where a run from 0 is after a step there
    from_zero = Slave(fmu_dir(version), version).init(**SMALL)
    from_zero.step_to(end - 1e9)
    assert s.get_many(output_names) == from_zero.get_many(output_names)


# ---- a step the work limit ends early ends before the step's end ------------------------------

@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", (0, 1), ids=integrator_id)
def test_a_step_ended_early_reports_a_time_before_its_end(fmu_dir, output_names, version, integrator):
    # from 1e15 the FMU's time moves in steps of 0.125: the time the work limit stops at
    # (0.077 and 0.081 from a start at 0, both between 0.0625 and 0.1) rounds to the
    # step's end, 1e15 + 0.125
    limit = 650 if integrator == 0 else 150
    s = Slave(fmu_dir(version), version).init(start=1e15, integrator=integrator, work_limit=limit)
    end = 1e15 + 0.1
    status, reached, early = s.do_step(1e15, 0.1)
    assert status == DISCARD and not early
    assert 1e15 <= reached < end, reached  # was: reached == end with Discard
    assert s.get("time") == reached and restores(s), s.errors()[-1:]
    if version == 2:
        return
    # FMI 3.0 goes on from the time reached, to the run of a step without a limit
    for _ in range(10):
        status, reached, _ = s.do_step(reached, end - reached)
        if status == OK:
            break
    assert status == OK and reached == end
    whole = Slave(fmu_dir(version), version).init(integrator=integrator)
    whole.step_to(end - 1e15)
    assert s.get_many(output_names) == whole.get_many(output_names)

# ---- the own state restores after a step past the end of a very short chute ----------------------

@pytest.mark.parametrize("prefix, step", (("tribo", 0.1), ("tribo_si", 1e-4)), ids=("model", "SI"))
@pytest.mark.parametrize("version", VERSIONS)
def test_own_state_restores_after_a_step_past_a_very_short_chutes_end(fmu_dir, version, prefix,
                                                                     step):
    s = Slave(fmu_dir(version, prefix), version).init(chute_length=1e-300, n_segments=16,
                                                      work_limit=50)
    status, _, _ = s.do_step(0.0, step)
    assert status in (OK, DISCARD), s.errors()
    # the particle is on the chute, or the run is over (model.md §9)
    position = s.get("X" if prefix == "tribo" else "x")
    assert position < 1e-300 or s.get("exited"), position
    assert restores(s), s.errors()[-1]


@pytest.mark.parametrize("version", VERSIONS)
def test_a_run_past_a_chute_of_dbl_min_keeps_its_contact_time_and_its_state(fmu_dir, version):
    s = Slave(fmu_dir(version), version).init(chute_length=2.2250738585072014e-308,
                                              phi0=784.5657543407981, rtol=1e-6, atol=1e-8,
                                              n_segments=16)
    status, reached, _ = s.do_step(0.0, 0.01)
    assert status in (OK, DISCARD), s.errors()
    assert 0.0 <= s.get("contact_time") <= reached, s.get("contact_time")
    assert restores(s), s.errors()[-1]

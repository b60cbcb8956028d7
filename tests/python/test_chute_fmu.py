"""The chute through the FMUs (docs/model.md §9): a run ends where the particle leaves it.
FMI 2.0 answers the step with fmi2Discard, fmi2Terminated and the exit as
fmi2LastSuccessfulTime; FMI 3.0 with terminateSimulation (and an early return where
allowed); a further step is refused, saying why. fmpy's simulate_fmu stops there cleanly.
The default length, no end, is written INF in the modelDescription: fmpy, libcosim and ecos
read it."""

import math

import pytest
from fmpy import read_model_description, simulate_fmu

from tribo_fmu import DISCARD, ERROR, OK, VERSIONS, Slave, core_run, libcosim_run, status_of

CHUTE = {"chute_length": 3.0, "n_segments": 64}  # the paper's drop slides off at tau ~ 75
OUTPUTS = ["X", "U", "Q_static", "Q_sliding", "exit_time", "impacts"]


def core_exit(reference_exe, **params):
    """The core's run to the exit (its outputs there)."""
    return core_run(reference_exe, dict(CHUTE, **params), [(1000.0, [])])[0]


@pytest.mark.parametrize("version", VERSIONS)
def test_simulate_fmu_stops_at_the_exit(fmu_file, reference_exe, version):
    core = core_exit(reference_exe)
    assert core["exited"] == 1.0 and 70 < core["exit_time"] < 80
    kwargs = {"early_return_allowed": True} if version == 3 else {}
    r = simulate_fmu(fmu_file(version), stop_time=1000, output_interval=1.0, start_values=CHUTE,
                     output=OUTPUTS + ["exited"], **kwargs)
    # the last row is the exit, at the exit time, with the core's outputs bit for bit
    assert float(r["time"][-1]) == core["exit_time"]
    assert bool(r["exited"][-1]) and not any(r["exited"][:-1])
    assert {n: float(r[n][-1]) for n in OUTPUTS} == {n: core[n] for n in OUTPUTS}
    assert float(r["time"][-2]) == math.floor(core["exit_time"])
    if version == 3:
        # without early returns fmpy records the frozen outputs at the step's end
        r = simulate_fmu(fmu_file(3), stop_time=1000, output_interval=1.0, start_values=CHUTE,
                         output=OUTPUTS)
        assert float(r["time"][-1]) == math.ceil(core["exit_time"])
        assert {n: float(r[n][-1]) for n in OUTPUTS} == {n: core[n] for n in OUTPUTS}


def step_past_the_exit(s):
    for t in range(1, 76):
        s.step_to(float(t))
    return s.do_step(75.0, 1.0)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("early_return", [False, True])
def test_the_exit_ends_the_run_and_says_so(fmu_dir, reference_exe, version, early_return):
    if version == 2 and early_return:
        pytest.skip("FMI 2.0 has no early return")
    core = core_exit(reference_exe)
    s = Slave(fmu_dir(version), version, early_return=early_return).init(**CHUTE)
    status, reached, early = step_past_the_exit(s)
    assert reached == core["exit_time"]
    f = s.fmu._functions
    if version == 2:
        assert (status, early) == (DISCARD, False)
        from ctypes import byref, c_int
        terminated = c_int(0)
        assert f["fmi2GetBooleanStatus"](s.fmu.component, 3, byref(terminated)) == OK
        assert terminated.value == 1  # fmi2Terminated
    else:
        assert (status, early) == (OK, early_return)
    assert s.get("time") == core["exit_time"] and s.get("exited")
    assert s.get_many(OUTPUTS) == {n: core[n] for n in OUTPUTS}
    # a further step is refused with the reason; sets too; terminate ends it
    assert s.do_step(reached, 1.0)[0] == ERROR
    assert "left the chute" in s.errors()[-1] and "run is over" in s.errors()[-1]
    assert status_of(s.set, mu=0.5) == ERROR
    assert status_of(s.set, F_T_ext=0.01) == ERROR
    assert status_of(s.fmu.terminate) == OK
    s.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_an_exited_state_restores(fmu_dir, version):
    s = Slave(fmu_dir(version), version).init(**CHUTE)
    step_past_the_exit(s)
    outputs = s.get_many(OUTPUTS)
    data = s.serialize(s.get_state())
    other = Slave(fmu_dir(version), version)
    other.set_state(other.deserialize(data))
    assert other.get_many(OUTPUTS) == outputs and other.get("exited")
    assert other.do_step(outputs["exit_time"], 1.0)[0] == ERROR
    assert status_of(other.fmu.terminate) == OK
    other.free()
    s.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_a_drop_beyond_the_end_is_refused_at_initialization(fmu_dir, version):
    s = Slave(fmu_dir(version), version)
    s.set(chute_length=2.0, X0=2.5)
    if version == 2:
        s.fmu.setupExperiment(startTime=0.0)
        s.fmu.enterInitializationMode()
    else:
        s.fmu.enterInitializationMode(startTime=0.0)
    assert status_of(s.fmu.exitInitializationMode) == ERROR
    assert "X0 = 2.5" in s.errors()[-1] and "chute_length = 2" in s.errors()[-1]
    s.set(X0=1.5)  # still in Initialization Mode: fixed
    assert status_of(s.fmu.exitInitializationMode) == OK
    s.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_reads_inf_as_no_end(fmu_file, fmu_dir, version):
    md = read_model_description(fmu_file(version), validate=True)
    L = next(v for v in md.modelVariables if v.name == "chute_length")
    assert float(L.start) == math.inf and L.max is None
    s = Slave(fmu_dir(version), version)
    assert s.get("chute_length") == math.inf
    s.free()


def test_libcosim_reads_inf_and_stops_at_the_exit(fmu_file):
    """libcosim (FMI 2.0) takes the INF start value, and a run that leaves the chute ends
    at the exit step: simulate_until returns false there, with the last whole step's
    values observed (libcosim treats fmi2Discard as the end)."""
    fmu = fmu_file(2)
    results = {length: libcosim_run(fmu, 1.0, 100.0, {} if length is None else {"chute_length": length},
                                    {"n_segments": 64}, ["chute_length", "X"])
               for length in (None, 3.0)}
    done, now, (L, X) = results[None]
    assert done and now == 100.0 and L == math.inf and X > 3.0
    done, now, (L, X) = results[3.0]
    assert not done and now == 75.0 and L == 3.0 and X < 3.0


@pytest.mark.parametrize("version", VERSIONS)
def test_ecos_reads_inf(fmu_file, version):
    from ecospy import EcosSimulation, EcosSimulationStructure

    with EcosSimulationStructure() as structure:
        structure.add_model("tribo", fmu_file(version))
        structure.add_parameter_set("set-up", {"tribo::epsilon": 0.5})
        with EcosSimulation(structure=structure, step_size=1.0) as sim:
            assert sim.init(parameter_set="set-up")
            assert sim.get_real("tribo::chute_length") == math.inf
            sim.step(10)
            assert sim.get_real("tribo::exit_time") == 0.0 and sim.get_real("tribo::X") > 0.0

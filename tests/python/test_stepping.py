"""doStep: where it goes, what it accepts, and what changes between steps do."""

import pytest

from tribo_fmu import (ERROR, INTEGRATORS, OK, VERSIONS, Slave, core_run, integrator_id,
                       status_of)

SMALL = {"n_segments": 64}  # the charge models at a size that keeps the tests quick
TUNABLES = {"mu": 0.5, "nu": 0.4, "eta": 0.3, "tau0": 0.5, "tau_r": 3.0, "Sigma0": 0.02}


def slave(fmu_dir, version, **params):
    return Slave(fmu_dir(version), version).init(**dict(SMALL, **params))


def with_arrays(s, names):
    return names + (["segment_charge_static", "segment_charge_sliding"] if s.version == 3 else [])


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", INTEGRATORS, ids=integrator_id)
def test_n_steps_equal_one_step(fmu_dir, reference_exe, output_names, version, integrator):
    names = None
    finals = []
    for times in ([k / 16 for k in range(1, 17)],           # 16 equal steps
                  [0.125, 0.25, 0.375, 0.5, 0.625, 0.6875, 0.75, 1.0],  # variable steps
                  [1.0]):                                     # one step
        s = slave(fmu_dir, version, integrator=integrator)
        names = with_arrays(s, output_names)
        rows = s.run(times, names)
        assert s.get("time") == 1.0
        finals.append(rows[-1])
        s.free()
    assert finals[0] == finals[1] == finals[2]
    core = core_run(reference_exe, dict(SMALL, integrator=integrator), [(1.0, [])])[0]
    assert {n: finals[0][n] for n in output_names} == {n: core[n] for n in output_names}


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", INTEGRATORS, ids=integrator_id)
@pytest.mark.parametrize("tunable", TUNABLES)
def test_tunable_change_takes_effect_from_the_next_step(fmu_dir, reference_exe, output_names,
                                                        version, integrator, tunable):
    times = [k / 8 for k in range(1, 17)]  # to 2, changing at 1 (in contact, slipping)
    change_at = 8
    value = TUNABLES[tunable]

    s = slave(fmu_dir, version, integrator=integrator)
    rows = s.run(times[:change_at], output_names)
    assert s.get("in_contact") == 1.0
    s.set(**{tunable: value})
    assert s.get(tunable) == value
    rows += s.run(times[change_at:], output_names)

    params = dict(SMALL, integrator=integrator)
    script = [(t, [f"param {tunable} {value!r}"] if k == change_at - 1 else [])
              for k, t in enumerate(times)]
    assert rows == [{n: c[n] for n in output_names} for c in core_run(reference_exe, params, script)]

    unchanged = [{n: c[n] for n in output_names}
                 for c in core_run(reference_exe, params, [(t, []) for t in times])]
    assert rows[:change_at] == unchanged[:change_at]
    assert all(a != b for a, b in zip(rows[change_at:], unchanged[change_at:]))


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("name, value", [("epsilon", 0.3), ("n_segments", 32), ("charge_model_static", 0),
                                         ("integrator", 1), ("Gamma", 0.002), ("dt", 1e-4),
                                         ("damping_point", 1)])
def test_structural_and_fixed_parameters_are_refused_after_initialization(
        fmu_dir, output_names, version, name, value):
    s = slave(fmu_dir, version)
    before = s.get(name)
    s.step_to(0.5)
    assert status_of(s.set, **{name: value}) == ERROR
    message = s.errors()[-1]
    assert name in message and "Step Mode" in message and "valid range" in message
    assert s.get(name) == before
    # refused without harm: the run goes on as if nothing had been asked
    after = s.run([1.0], output_names)
    undisturbed = slave(fmu_dir, version).run([0.5, 1.0], output_names)
    assert after[-1] == undisturbed[-1]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", INTEGRATORS, ids=integrator_id)
def test_external_forces_apply_from_the_next_step(fmu_dir, reference_exe, output_names, version,
                                                  integrator):
    times = [0.25, 0.5, 0.75, 1.0]
    s = slave(fmu_dir, version, integrator=integrator)
    rows = s.run(times[:2], output_names)
    s.set(F_T_ext=0.002, F_N_ext=-0.001)
    rows += s.run(times[2:], output_names)
    script = [(t, ["force 0.002 -0.001"] if t == 0.5 else []) for t in times]
    core = core_run(reference_exe, dict(SMALL, integrator=integrator), script)
    assert rows == [{n: c[n] for n in output_names} for c in core]
    assert rows[1]["work_external"] == 0 and rows[-1]["work_external"] != 0


@pytest.mark.parametrize("version", VERSIONS)
def test_without_a_stop_time_any_step_is_allowed(fmu_dir, version):
    s = slave(fmu_dir, version, dt=0.01)  # no stop time; a coarse step to get far quickly
    s.step_to(0.5)
    s.step_to(1200.0)  # past the default experiment's stop time
    assert s.get("time") == 1200.0


@pytest.mark.parametrize("version", VERSIONS)
def test_a_step_past_the_stop_time_is_refused(fmu_dir, version):
    s = Slave(fmu_dir(version), version).init(stop=1.0, **SMALL)
    s.step_to(0.5)
    s.step_to(1.0)  # ends on the stop time
    assert status_of(s.fmu.doStep, 1.0, 0.25) == ERROR
    assert "stop time" in s.errors()[-1] and "1.25" in s.errors()[-1]
    assert s.get("time") == 1.0


@pytest.mark.parametrize("version", VERSIONS)
def test_communication_points_off_by_rounding_are_accepted(fmu_dir, version):
    s = slave(fmu_dir, version)
    # the importer counts k * h while the FMU adds h up: the two drift apart by rounding
    h = 0.1
    drifted = 0
    for k in range(20):
        drifted += (k * h != s.get("time"))
        assert status_of(s.fmu.doStep, k * h, h) == OK
    assert drifted > 0, "no rounding difference came up: the test tests nothing"
    assert s.errors() == []


@pytest.mark.parametrize("version", VERSIONS)
def test_a_real_communication_point_mismatch_is_refused(fmu_dir, version):
    s = slave(fmu_dir, version)
    s.step_to(1.0)
    assert status_of(s.fmu.doStep, 1.001, 0.1) == ERROR
    assert "currentCommunicationPoint = 1.0009" in s.errors()[-1]
    for bad_step in (0.0, -0.1, float("nan"), float("inf")):
        assert status_of(s.fmu.doStep, 1.0, bad_step) == ERROR
        assert "communicationStepSize" in s.errors()[-1]
    s.step_to(1.5)  # still usable
    assert s.get("time") == 1.5


def test_fmi3_configuration_mode_sets_the_structural_parameter(fmu_dir, reference_exe):
    s = Slave(fmu_dir(3), 3)
    s.fmu.enterConfigurationMode()
    s.set(n_segments=32)
    assert status_of(s.set, epsilon=0.3) == ERROR  # only structural parameters here
    assert "Configuration Mode" in s.errors()[-1]
    s.fmu.exitConfigurationMode()
    s.init()
    assert status_of(s.set, n_segments=40) == ERROR  # not in Step Mode
    s.step_to(1.0)
    static = s.get("segment_charge_static")
    core = core_run(reference_exe, {"n_segments": 32}, [(1.0, [])], segments=True)[0]
    assert static == core["segments"]["static"] and len(static) == 32


def test_fmi3_structural_parameter_is_refused_in_initialization_mode(fmu_dir):
    s = Slave(fmu_dir(3), 3)
    s.fmu.enterInitializationMode()
    assert status_of(s.set, n_segments=32) == ERROR
    assert "n_segments" in s.errors()[-1] and "Configuration Mode" in s.errors()[-1]
    s.set(epsilon=0.4)  # a fixed parameter is fine here
    s.fmu.exitInitializationMode()
    assert s.get("epsilon") == 0.4 and s.get("n_segments") == 2000


@pytest.mark.parametrize("version", VERSIONS)
def test_a_new_Sigma0_moves_the_target_not_the_charge(fmu_dir, version):
    """docs/model.md §5b: Q_sliding is normalised by Sigma0 at the start; Sigma_mean is the
    absolute mean density. Doubling Sigma0 between steps changes neither at once."""
    s = slave(fmu_dir, version, epsilon=0.3)
    s.step_to(20.0)
    q, mean = s.get("Q_sliding"), s.get("Sigma_mean")
    assert q > 0.1 and mean == pytest.approx(0.01 * q, rel=1e-14)
    s.set(Sigma0=0.02)
    assert (s.get("Q_sliding"), s.get("Sigma_mean")) == (q, mean)
    s.step_to(60.0)
    assert s.get("Sigma_mean") == pytest.approx(0.01 * s.get("Q_sliding"), rel=1e-14)
    assert s.get("Q_sliding") > 1.2 * q  # towards the new, higher target

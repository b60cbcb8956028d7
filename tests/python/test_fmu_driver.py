"""The package's fmpy driver (tribo.fmu), which the tests use too: a run the FMU ends
early (a doStep that returns Discard and asks to terminate, as a particle leaving a chute
does) is recorded up to where it ended, rows kept; a Discard without that is an error with
FMI 2.0, and with FMI 3.0 (the work limit: the FMU stays in Step Mode) the step goes on.
The FMUs here never end early, so the end is played by wrapping the FMU's doStep: the
real step to the end time, then the FMI status and flags an ending FMU gives."""

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.fmi1 import FMICallException

from tribo.batch.particle import simulate
from tribo.fmu import DISCARD, OK, FmuImage, Instance, record

NAMES = ["X", "Y", "phi", "Q_static", "Q_sliding", "contact_fraction", "motion_class"]
TIMES = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
END = 2.5  # the time the FMU "ends" the run


def ending_at(instance, end, terminate=True):
    """Make the instance's FMU end the run at `end`: the step that would pass it steps to
    `end` for real, then answers as an FMU that ends the run there."""
    if instance.version == 2:
        real = instance.fmu.doStep

        def do_step(t, h, *args):
            if t + h <= end:
                return real(t, h)
            real(t, end - t)
            raise FMICallException("fmi2DoStep", DISCARD)

        instance.fmu.doStep = do_step
        instance.fmu.getBooleanStatus = lambda kind: terminate
        instance.fmu.getRealStatus = lambda kind: end
    else:
        real = instance._do_step3

        def do_step3(t, h):
            if t + h <= end:
                return real(t, h)
            status, _, early, reached = real(t, end - t)
            assert status == OK and not early and reached == end
            return DISCARD, terminate, False, reached

        instance._do_step3 = do_step3


def reference(fmu_dir, times):
    with Instance(fmu_dir) as s:
        s.init(n_segments=64)
        return record(s, times, NAMES)


@pytest.mark.parametrize("version", [2, 3])
def test_a_run_the_fmu_ends_early_keeps_its_rows(fmu_dir, version):
    with Instance(fmu_dir(version)) as s:
        s.init(n_segments=64)
        ending_at(s, END)
        reached, rows = record(s, TIMES, NAMES)
        assert s.ended and s.t == END
    assert list(reached) == [0.0, 1.0, 2.0, END]
    full_times, full = reference(fmu_dir(version), TIMES)
    assert np.array_equal(rows[:3], full[:3])  # the rows before the end, as in a full run
    _, to_end = reference(fmu_dir(version), [0.0, 1.0, 2.0, END])
    assert np.array_equal(rows[3], to_end[3])  # the last row: the outputs where it ended
    assert not np.array_equal(rows[3], full[3])


def test_an_fmi2_discard_without_terminate_is_an_error(fmu_dir):
    """FMI 2.0 leaves the instance in stepFailed after a Discard: it cannot go on."""
    with Instance(fmu_dir(2)) as s:
        s.init(n_segments=64)
        ending_at(s, END, terminate=False)
        s.step_to(1.0)
        with pytest.raises(FMICallException) as e:
            s.step_to(3.0)
        assert e.value.status == DISCARD and not s.ended


@pytest.mark.parametrize("early_return", [False, True])
def test_fmi3_steps_cut_by_the_work_limit_go_on_to_the_same_run(fmu_dir, early_return):
    """A work limit of 150 units per doStep (a CVODE step is 8) cuts the paper's case's steps
    (Discard, or an early return where allowed); step_to goes on from the time reached,
    and the run is the one without the limit, bit for bit (fmu/README.md, "Work limit")."""
    times = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0]
    _, full = reference(fmu_dir(3), times)
    with Instance(fmu_dir(3), early_return=early_return) as s:
        s.init(n_segments=64, work_limit=150)
        reached, rows = record(s, times, NAMES)
        assert s.work_limit_returns >= 5 and not s.ended
    assert list(reached) == times
    assert np.array_equal(rows, full)


def test_fmi3_terminate_with_ok_ends_the_run_too(fmu_dir):
    """FMI 3.0 lets an FMU complete the step and ask to terminate (status OK)."""
    with Instance(fmu_dir(3)) as s:
        s.init(n_segments=64)
        real = s._do_step3
        s._do_step3 = lambda t, h: (lambda r: (r[0], t + h >= 2.0, r[2], r[3]))(real(t, h))
        reached, rows = record(s, TIMES, NAMES)
    assert list(reached) == [0.0, 1.0, 2.0]


def test_simulate_and_the_api_record_an_early_end(fmu_file, monkeypatch):
    """The path tribo.run and the sweeps take (tribo.batch.particle.simulate) stops there too."""
    real = Instance._do_step3

    def do_step3(self, t, h):
        if t + h <= END:
            return real(self, t, h)
        status, _, _, reached = real(self, t, END - t)
        return DISCARD, True, False, reached

    monkeypatch.setattr(Instance, "_do_step3", do_step3)
    # the package's names: phi in degrees
    names = [n if n != "phi" else "phi_deg" for n in NAMES]
    recording = simulate(FmuImage.load(fmu_file(3)), {"n_segments": 64}, 5.0, 1.0, names, segments=True)
    assert list(recording.series["time"]) == [0.0, 1.0, 2.0, END]
    assert len(recording.segments) == 64  # read where the run ended
    assert recording.segments["static"].mean() == pytest.approx(recording.series["Q_static"].iloc[-1],
                                                                rel=1e-12)


@pytest.mark.parametrize("version", [2, 3])
def test_the_papers_fixed_step_in_steps_of_100_stays_within_the_default_work_limit(fmu_file,
                                                                                  version):
    """fmpy's simulate_fmu with the paper's fixed step (dt = 8e-5) and an output interval of
    100: each doStep is 1.25e6 RK4 steps, within the default work limit (fmu/README.md,
    "Work limit"), so none is cut and fmpy does not raise."""
    result = simulate_fmu(fmu_file(version), stop_time=200.0, output_interval=100.0,
                          start_values={"integrator": 0}, output=["X", "Q_static"])
    assert list(result["time"]) == [0.0, 100.0, 200.0]
    assert np.all(np.isfinite(result["X"]))

"""The importer's tolerance (setupExperiment / enterInitializationMode) is CVODE's rtol,
with atol in the defaults' ratio (atol = 1e-11 * tolerance / 1e-9); rtol or atol set
explicitly wins; the FMU logs which; a tolerance outside rtol's range is refused, saying what
it would have set; CVODE works to at most rtol 1e-3 and atol 1e-5, where every declared
tolerance runs."""

import pytest

from tribo_fmu import ERROR, OK, VERSIONS, Slave, core_run, status_of

SMALL = {"n_segments": 64}
TIMES = [1.0, 5.0, 20.0]
COMPARED = ["X", "Y", "phi", "U", "V", "Omega", "Q_static", "energy"]


def run_with_tolerance(fmu_dir, version, tolerance, **params):
    s = Slave(fmu_dir(version), version)
    s.fmu.setDebugLogging(True, ["logFmiCalls"])  # the choice of tolerances is logged there
    s.set(**SMALL, **params)
    if version == 2:
        s.fmu.setupExperiment(tolerance=tolerance, startTime=0.0)
        s.fmu.enterInitializationMode()
    else:
        s.fmu.enterInitializationMode(tolerance=tolerance, startTime=0.0)
    s.fmu.exitInitializationMode()
    return s


def core(reference_exe, **params):
    runs = core_run(reference_exe, dict(SMALL, **params), [(t, []) for t in TIMES])
    return [{n: r[n] for n in COMPARED} for r in runs]


def fmu_run(s):
    return [{n: v for n, v in r.items()} for r in s.run(TIMES, COMPARED)]


@pytest.mark.parametrize("version", VERSIONS)
def test_the_tolerance_sets_rtol_and_atol(fmu_dir, reference_exe, version):
    s = run_with_tolerance(fmu_dir, version, 1e-6)
    assert (s.get("rtol"), s.get("atol")) == (1e-6, 1e-11 * (1e-6 / 1e-9))
    assert any("tolerance = 1e-06: rtol = 1e-06 (the tolerance)" in m for _, _, m in s.messages)
    assert fmu_run(s) == core(reference_exe, rtol=1e-6, atol=1e-11 * (1e-6 / 1e-9))
    # (and the tolerance mattered)
    assert core(reference_exe, rtol=1e-6, atol=1e-11 * (1e-6 / 1e-9)) != core(reference_exe)


@pytest.mark.parametrize("version", VERSIONS)
def test_the_default_experiments_tolerance_gives_the_defaults(fmu_dir, reference_exe, version):
    s = run_with_tolerance(fmu_dir, version, 1e-9)
    assert (s.get("rtol"), s.get("atol")) == (1e-9, 1e-11)
    assert fmu_run(s) == core(reference_exe)


@pytest.mark.parametrize("version", VERSIONS)
def test_an_explicit_rtol_wins(fmu_dir, reference_exe, version):
    s = run_with_tolerance(fmu_dir, version, 1e-6, rtol=1e-7)
    assert (s.get("rtol"), s.get("atol")) == (1e-7, 1e-11 * (1e-6 / 1e-9))
    assert any("rtol = 1e-07 (set explicitly)" in m for _, _, m in s.messages)
    assert fmu_run(s) == core(reference_exe, rtol=1e-7, atol=1e-11 * (1e-6 / 1e-9))


@pytest.mark.parametrize("version", VERSIONS)
def test_explicit_rtol_and_atol_win_and_the_tolerance_is_not_used(fmu_dir, version):
    s = run_with_tolerance(fmu_dir, version, 1e-6, rtol=1e-8, atol=1e-12)
    assert (s.get("rtol"), s.get("atol")) == (1e-8, 1e-12)
    assert any("tolerance = 1e-06 not used" in m for _, _, m in s.messages)


@pytest.mark.parametrize("version", VERSIONS)
def test_the_fixed_step_says_it_uses_dt(fmu_dir, version):
    s = run_with_tolerance(fmu_dir, version, 1e-6, integrator=0)
    assert any("dt sets its accuracy" in m for _, _, m in s.messages)


@pytest.mark.parametrize("version", VERSIONS)
def test_a_tolerance_outside_rtols_range_is_refused(fmu_dir, version):
    s = Slave(fmu_dir(version), version)
    if version == 2:
        status = status_of(s.fmu.setupExperiment, tolerance=1e-20, startTime=0.0)
    else:
        status = status_of(s.fmu.enterInitializationMode, tolerance=1e-20, startTime=0.0)
    assert status == ERROR
    assert "tolerance = 9.9999999999999995e-21" in s.errors()[-1] and "1e-14 <= rtol < 1" in s.errors()[-1]
    assert s.get("rtol") == 1e-9


@pytest.mark.parametrize("version", VERSIONS)
def test_an_explicit_rtol_survives_an_fmu_state(fmu_dir, version):
    """rtol set explicitly, the state saved before initialization and restored into a fresh
    instance: the importer's tolerance still does not override it (the state keeps which
    tolerances were set)."""
    a = Slave(fmu_dir(version), version)
    a.set(**SMALL, rtol=1e-7)
    data = a.serialize(a.get_state())
    b = Slave(fmu_dir(version), version)
    b.fmu.setDebugLogging(True, ["logFmiCalls"])
    b.set_state(b.deserialize(data))
    if version == 2:
        b.fmu.setupExperiment(tolerance=1e-6, startTime=0.0)
        b.fmu.enterInitializationMode()
    else:
        b.fmu.enterInitializationMode(tolerance=1e-6, startTime=0.0)
    b.fmu.exitInitializationMode()
    assert (b.get("rtol"), b.get("atol")) == (1e-7, 1e-11 * (1e-6 / 1e-9))
    assert any("rtol = 1e-07 (set explicitly)" in m for _, _, m in b.messages)


# CVODE works to at most these (src/chute/model.h, docs/model.md §3 "the loosest tolerances")
LOOSEST = {"rtol": 1e-3, "atol": 1e-5}


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("tolerance, params", [
    (0.05, {}), (0.5, {}), (0.99, {}),
    (None, {"rtol": 0.1}), (None, {"rtol": 0.5, "atol": 1e-11}),
    (None, {"atol": 5e-3}), (None, {"rtol": 1e-9, "atol": 1.0})],
    ids=["tolerance_0.05", "tolerance_0.5", "tolerance_0.99", "rtol_0.1", "rtol_0.5",
         "atol_5e-3", "atol_1"])
def test_a_loose_tolerance_runs_at_the_loosest_the_event_logic_takes(
        fmu_dir, reference_exe, version, tolerance, params):
    """Every declared tolerance runs to the end, each of rtol and atol at most at the loosest
    CVODE is given: the run is the core's at those, bit for bit (rtol 0.1 or 0.5, an
    importer's tolerance of 0.05 or 0.5, or atol 5e-3 once ended in an "event cascade" or
    crept on by 1e-6 per FMI 3.0 doStep)."""
    s = run_with_tolerance(fmu_dir, version, tolerance, **params)
    s.t = 0.0
    times = TIMES + [40.0, 80.0]
    got = []
    for t in times:  # each step whole (not continued past a spent work limit: no livelock)
        status, _, early = s.do_step(s.t, t - s.t)
        assert status == OK and not early, (t, status, s.errors()[-1:])
        s.t = t
        got.append({n: s.get(n) for n in COMPARED})
    assert s.errors() == []
    rtol, atol = s.get("rtol"), s.get("atol")
    used = {"rtol": min(rtol, LOOSEST["rtol"]), "atol": min(atol, LOOSEST["atol"])}
    assert rtol > LOOSEST["rtol"] or atol > LOOSEST["atol"]  # (the limit acts)
    runs = core_run(reference_exe, dict(SMALL, **used), [(t, []) for t in times])
    assert got == [{n: r[n] for n in COMPARED} for r in runs]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("explicit, sets", [
    ({}, "it would set CVODE's rtol, and atol;"),
    ({"rtol": 1e-8}, "it would set CVODE's atol (rtol was set explicitly);"),
    ({"atol": 1e-12}, "it would set CVODE's rtol (atol was set explicitly);"),
    ({"rtol": 1e-8, "atol": 1e-12}, "it would set neither of CVODE's rtol and atol (both were "
                                    "set explicitly);")])
def test_a_refused_tolerance_says_what_it_would_have_set(fmu_dir, version, explicit, sets):
    """(It once said "it sets CVODE's rtol" where rtol and atol were set, and it set none.)"""
    s = Slave(fmu_dir(version), version)
    s.set(**explicit)
    if version == 2:
        status = status_of(s.fmu.setupExperiment, tolerance=2.0, startTime=0.0)
    else:
        status = status_of(s.fmu.enterInitializationMode, tolerance=2.0, startTime=0.0)
    assert status == ERROR
    assert sets in s.errors()[-1] and "1e-14 <= rtol < 1" in s.errors()[-1], s.errors()[-1]

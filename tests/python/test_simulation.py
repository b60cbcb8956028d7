"""fmpy.simulate_fmu on both FMUs gives the numbers the core gives when run directly."""

import numpy as np
import pytest
from fmpy import simulate_fmu

from tribo_fmu import INTEGRATORS, VERSIONS, core_run, integrator_id

SCENES = {
    "defaults": {},
    # five tunables away from their start values, and a structural one (fewer segments)
    "changed": {"epsilon": 0.3, "mu": 1.0, "nu": 1.0, "eta": 0.2, "tau0": 2.0, "n_segments": 64},
    # dropped from a height it lands at t ~ 1.2: its in_contact changes during the run
    "dropped": {"gap0": 0.02},
}
ARRAYS = {"segment_charge_static": "static", "segment_charge_sliding": "sliding"}


def compare(result, core, names):
    for name in names:
        fmu_values = [float(x) for x in result[name]]
        assert fmu_values == [c[name] for c in core], name


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", INTEGRATORS, ids=integrator_id)
@pytest.mark.parametrize("scene", SCENES)
def test_simulate_fmu_matches_the_core(fmu_dir, reference_exe, output_names, version, integrator,
                                       scene):
    start_values = dict(SCENES[scene], integrator=integrator)
    # the arrays are recorded at the size the modelDescription declares (n_segments' start)
    arrays = list(ARRAYS) if version == 3 and "n_segments" not in start_values else []
    result = simulate_fmu(fmu_dir(version), stop_time=2.0, start_values=start_values,
                          output=output_names + arrays)
    times = [float(t) for t in result["time"]]
    assert times[0] == 0.0 and times[-1] == 2.0 and len(times) == 21  # stepSize 0.1
    core = core_run(reference_exe, start_values, [(t, []) for t in times], segments=bool(arrays))
    compare(result, core, output_names)
    # the particle is on the plate at t = 2 and has charged; dropped from a height, it was in
    # flight before, so the comparison of in_contact above saw both values and the landing
    assert core[-1]["in_contact"] == 1 and core[-1]["Q_static"] > 0
    if scene == "dropped":
        assert core[0]["in_contact"] == 0 and core[0]["Q_static"] == 0
    for name, which in ((n, w) for n, w in ARRAYS.items() if n in arrays):
        assert np.array_equal(result[name], np.array([c["segments"][which] for c in core])), name
        assert result[name][-1].max() > 0


def test_the_scenes_differ(reference_exe):
    """(So that the comparison above would see a parameter the FMU ignored.)"""
    runs = [core_run(reference_exe, SCENES[s], [(2.0, [])])[0] for s in SCENES]
    assert all(runs[0][q] != runs[1][q] for q in ("X", "Y", "phi", "Q_static", "Q_sliding"))


@pytest.mark.parametrize("version", VERSIONS)
def test_start_time_offsets_the_core_time(fmu_dir, reference_exe, output_names, version):
    result = simulate_fmu(fmu_dir(version), start_time=10.0, stop_time=11.0,
                          start_values={"n_segments": 64}, output=output_names)
    times = [float(t) for t in result["time"]]
    assert times[0] == 10.0 and times[-1] == 11.0
    core = core_run(reference_exe, {"n_segments": 64}, [(t - 10.0, []) for t in times])
    compare(result, core, output_names)

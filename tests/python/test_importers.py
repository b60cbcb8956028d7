"""The FMU in other importers: libcosim (libcosimpy, FMI 2.0) and ecos (ecospy, FMI 2.0 and
3.0) give fmpy's numbers, bit for bit, at the end of the same run (the paper's
low-friction case at epsilon = 0.3, steps of 0.1 to tau = 2; ecos also runs the SI FMUs:
a 1 mm grain dropped 5 mm, through its first impact)."""

import subprocess
import sys

import pytest
from fmpy import read_model_description, simulate_fmu

from tribo_fmu import Slave

REALS = ["X", "Y", "phi", "U", "V", "Omega", "Q_static", "Q_sliding", "energy"]
PARAMS = {"epsilon": 0.3, "n_segments": 64}
STOP, STEP = 2.0, 0.1


def fmpy_end(fmu):
    r = simulate_fmu(fmu, stop_time=STOP, output_interval=STEP, start_values=PARAMS,
                     output=REALS + ["in_contact"])
    assert float(r["time"][-1]) == STOP
    return {n: float(r[n][-1]) for n in REALS}, bool(r["in_contact"][-1])


def test_libcosim_fmi2_gives_fmpys_numbers(fmu_file):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    fmu = fmu_file(2)
    vr = {v.name: v.valueReference for v in read_model_description(fmu).modelVariables}
    execution = CosimExecution.from_step_size(step_size=int(STEP * 1e9))  # nanoseconds
    slave = CosimLocalSlave(fmu_path=fmu, instance_name="tribo")
    index = execution.add_local_slave(local_slave=slave)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    execution.real_initial_value(index, vr["epsilon"], PARAMS["epsilon"])
    execution.integer_initial_value(index, vr["n_segments"], PARAMS["n_segments"])
    assert execution.simulate_until(target_time=int(STOP * 1e9))
    values = observer.last_real_values(index, [vr[n] for n in REALS])
    reals, _ = fmpy_end(fmu)
    assert dict(zip(REALS, values)) == reals
    assert reals["X"] != 0.0


# Loads each FMU in libcosim in a process of its own, at libcosim's default log level
# (trace: everything libcosim and the FMI Library say goes to the process's output)
LIBCOSIM_LOAD = """
import sys
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimSlave import CosimLocalSlave
execution = CosimExecution.from_step_size(step_size=10**8)
for i, path in enumerate(sys.argv[1:]):
    execution.add_local_slave(local_slave=CosimLocalSlave(fmu_path=path, instance_name=f"fmu{i}"))
"""


def test_libcosim_finds_nothing_wrong_in_the_fmi2_descriptions(fmu_file):
    """The FMI Library (libcosim's) parses each FMI 2.0 description without an error: it
    took the FMU's time, declared independent without a start value (which the standard
    requires of an independent variable), for a variable missing one ("Start attribute is
    required for this causality, variability and initial combination"), twice per FMU."""
    fmus = [fmu_file(2, prefix) for prefix in ("tribo", "tribo_si", "tribo_separator")]
    done = subprocess.run([sys.executable, "-c", LIBCOSIM_LOAD, *fmus], capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    said = done.stdout + done.stderr
    assert "[error]" not in said and "Start attribute" not in said, said[-2000:]


def ecos_end(fmu, params, stop, step=STEP, reals=REALS):
    """Run the FMU in ecos (ecospy) with the parameters applied at initialisation, in steps
    of `step` to `stop`; returns the time ecos reached and the outputs there."""
    from ecospy import EcosSimulation, EcosSimulationStructure

    with EcosSimulationStructure() as structure:
        structure.add_model("tribo", fmu)
        # ecos names variables <instance>::<variable>
        structure.add_parameter_set("set-up", {f"tribo::{name}": value for name, value in params.items()})
        with EcosSimulation(structure=structure, step_size=step) as sim:
            assert sim.init(parameter_set="set-up")
            assert all(sim.get_real(f"tribo::{name}") == value for name, value in params.items()
                       if isinstance(value, float))
            sim.step(round(stop / step))
            return sim.get_time(), {n: sim.get_real(f"tribo::{n}") for n in reals}


@pytest.mark.parametrize("version", [2, 3])
def test_ecos_gives_fmpys_numbers(fmu_file, fmu_dir, version):
    """ecos accumulates its communication times (20 steps of 0.1 end a rounding away from
    2); the FMU's results depend on the end time only, so fmpy steps to the same end.
    ecos 0.7.2 skips FMI 3.0 UInt64 and Enumeration variables ("unsupported type"), so
    there n_segments keeps its start value (README)."""
    params = PARAMS if version == 2 else {"epsilon": PARAMS["epsilon"]}
    t_end, values = ecos_end(fmu_file(version), params, STOP)
    assert abs(t_end - STOP) < 1e-12
    s = Slave(fmu_dir(version), version).init(**params)
    s.step_to(t_end)
    assert values == s.get_many(REALS)
    assert values["X"] != 0.0
    s.free()


SI_REALS = ["x", "y", "phi", "u", "v", "omega", "charge_static", "charge_sliding", "energy",
            "contact_time"]


@pytest.mark.parametrize("version", [2, 3])
def test_ecos_runs_the_si_fmus_with_fmpys_numbers(fmu_file, fmu_dir, version):
    """Seconds and metres: a 1 mm grain dropped 5 mm (it lands after 32 ms), to 50 ms in
    steps of 1 ms."""
    params = {"epsilon": 0.4, "drop_height": 5e-3}
    stop, step = 0.05, 1e-3
    t_end, values = ecos_end(fmu_file(version, "tribo_si"), params, stop, step, SI_REALS)
    assert abs(t_end - stop) < 1e-12
    s = Slave(fmu_dir(version, "tribo_si"), version).init(**params)
    s.step_to(t_end)
    assert values == s.get_many(SI_REALS)
    # the grain landed: in contact for a while, charged
    assert values["contact_time"] > 0.0 and values["charge_static"] != 0.0
    s.free()

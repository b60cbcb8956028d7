"""The FMU in another importer: libcosim (libcosimpy, FMI 2.0) gives fmpy's numbers, bit
for bit, at the end of the same run (the paper's low-friction case at epsilon = 0.3,
steps of 0.1 to tau = 2)."""

from fmpy import read_model_description, simulate_fmu

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

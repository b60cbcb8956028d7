"""Drive the tribo FMUs and the core the same way for FMI 2.0 and 3.0.

`Slave` is one FMU instance through the package's fmpy driver (tribo.fmu.Instance: the
importer's logger captured per instance), checked to be of the FMI version the test
asks for; `core_run` runs the core directly (build/fmu/tribo_reference_run) for the
FMU's results to be compared against, number for number.
"""

import json
import os
import subprocess

from tribo.fmu import DISCARD, ERROR, FATAL, OK, WARNING, Instance, model_description, status_of  # noqa: F401
from tribo.fmu.locate import CHECKOUT, build_dir

ROOT = CHECKOUT
# build/ unless TRIBO_BUILD_DIR names another build directory
BUILD_DIR = build_dir()
VERSIONS = (2, 3)
# 0: fixed step, 1: CVODE (Adams), 2: CVODE (BDF); the FMU must give what the core gives
# with each
INTEGRATORS = (0, 1, 2)


def integrator_id(integrator):
    return {0: "fixed_step", 1: "cvode", 2: "cvode_bdf"}[integrator]


def Slave(fmu_dir, version, name="tribo", logging_on=False, early_return=False):
    """An instance of the FMU unpacked in fmu_dir, which must be of FMI `version`
    (early_return: FMI 3.0's earlyReturnAllowed)."""
    s = Instance(fmu_dir, name=name, logging_on=logging_on, early_return=early_return)
    assert s.version == version, (fmu_dir, s.version, version)
    return s


def core_run(exe, params, script, segments=False):
    """Run the core directly: params set before creation, then `script`, a list of
    (time, [commands]) in time order: advance to each time, print every quantity there,
    then apply the commands (e.g. "param mu 0.5", "force 0.1 0"). Returns one dict of
    quantities per time (with "segments" if asked)."""
    lines = [f"set {name} {float(value)!r}" for name, value in params.items()] + ["create"]
    for t, commands in script:
        lines += [f"advance {float(t)!r}", "print"] + (["segments"] if segments else [])
        lines += commands
    out = subprocess.run([exe], input="\n".join(lines) + "\n", capture_output=True, text=True)
    records = [json.loads(line) for line in out.stdout.splitlines()]
    if out.returncode != 0:
        raise RuntimeError(f"reference run failed: {records[-1] if records else out.stderr}")
    if not segments:
        return records
    return [dict(q, segments=s) for q, s in zip(records[0::2], records[1::2])]


def libcosim_run(fmu, step_size, stop_time, reals=None, integers=None, observed=()):
    """One run of an FMI 2.0 FMU in libcosim from 0 (times in seconds, as libcosim's
    nanoseconds): (whether simulate_until reached stop_time, the time reached, the last
    values of the observed reals)."""
    from fmpy import read_model_description
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    vr = {v.name: v.valueReference for v in read_model_description(fmu).modelVariables}
    execution = CosimExecution.from_step_size(step_size=round(step_size * 1e9))
    index = execution.add_local_slave(local_slave=CosimLocalSlave(fmu_path=fmu, instance_name="tribo"))
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    for name, value in (integers or {}).items():
        execution.integer_initial_value(index, vr[name], value)
    for name, value in (reals or {}).items():
        execution.real_initial_value(index, vr[name], value)
    done = execution.simulate_until(target_time=round(stop_time * 1e9))
    return (done, execution.status().current_time / 1e9,
            observer.last_real_values(index, [vr[name] for name in observed]))

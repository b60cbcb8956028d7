"""One run of the tribo FMU with fmpy: parameters in, recorded time series and its
summary row out.

The FMU travels as bytes (`FmuImage`), so that a task on any Dask worker, local or on
another machine, can load it without a shared file system: each run writes the bytes
to a private temporary directory, unpacks them, runs, and removes the directory. That
costs a few milliseconds against runs of a tenth of a second and more, and keeps no
state between runs. Works with the FMI 2.0 and the FMI 3.0 FMU.
"""

import hashlib
import os
import tempfile
import time
from dataclasses import dataclass

import numpy as np
import pandas as pd
from ctypes import byref, c_void_p

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave
from fmpy.logging import addLoggerProxy

from .specs import RunSpec
from .summary import MODES, summarize

# The outputs recorded at every communication point (the summary and figures use them).
RECORDED = ["X", "Y", "phi", "U", "V", "Omega", "delta_y", "in_contact", "Q_static", "Q_sliding",
            "contact_fraction", "turns", "motion_class"] + [f"fraction_{m}" for m in MODES] \
           + ["assumption_warnings"]

_REAL_TYPES = ("Real", "Float64", "Float32")
_SETTERS = {"Real": "setReal", "Integer": "setInteger",  # FMI 2.0
            "Float64": "setFloat64", "Int32": "setInt32", "UInt64": "setUInt64"}  # FMI 3.0
# the getter of each type (FMI 2.0 reads enumerations as Integers, FMI 3.0 as Int64)
_GETTERS = {2: {"Real": "getReal", "Integer": "getInteger", "Enumeration": "getInteger",
                "Boolean": "getBoolean"},
            3: {"Float64": "getFloat64", "Int32": "getInt32", "Enumeration": "getInt64",
                "Boolean": "getBoolean"}}
_SETTERS_OF_VERSION = {2: dict(_SETTERS, Enumeration="setInteger"),
                       3: dict(_SETTERS, Enumeration="setInt64")}


# The FMU's log messages (warnings reach the importer even without debug logging) are
# kept per run instead of printed: the study counts the warnings (assumption_warnings) and
# quotes the errors when a run fails. fmpy's FMI 2.0 logger proxy (which formats the
# printf-style messages) calls one process-wide Python callback, the last one registered,
# so there is one, alive for the process, and it finds the run's list of messages by the
# instance's componentEnvironment. A Dask worker runs one run at a time per thread.
_fmi2_sinks: dict[int, list] = {}


def _fmi2_dispatch(environment, instance_name, status, category, message):
    sink = _fmi2_sinks.get(environment)
    if sink is not None:
        sink.append((status, message.decode(errors="replace")))


_FMI2_LOGGER = fmi2CallbackLoggerTYPE(_fmi2_dispatch)
_ERROR = 3  # fmi2Error / fmi3Error; 4 is fatal


@dataclass(frozen=True)
class FmuImage:
    """The bytes of an .fmu file, its name and their SHA-256."""

    name: str
    data: bytes
    sha256: str

    @classmethod
    def load(cls, path: str) -> "FmuImage":
        with open(path, "rb") as f:
            data = f.read()
        return cls(os.path.basename(path), data, hashlib.sha256(data).hexdigest())


@dataclass
class RunResult:
    row: dict  # the summary (summary.summarize) plus cpu_s and wall_s
    series: pd.DataFrame  # tau and the RECORDED outputs at every communication point


def parameter_kinds(path: str) -> dict[str, bool]:
    """The FMU's parameters: name -> whether it is an integer (from its modelDescription)."""
    md = read_model_description(path, validate=False)
    return {v.name: v.type not in _REAL_TYPES for v in md.modelVariables
            if v.causality in ("parameter", "structuralParameter")}


def run_fmu(image: FmuImage, spec: RunSpec) -> RunResult:
    """Run the FMU from 0 to spec.t_end, recording every spec.record_interval."""
    wall0, cpu0 = time.perf_counter(), time.thread_time()
    with tempfile.TemporaryDirectory(prefix="tribo_run_") as tmp:
        path = os.path.join(tmp, image.name)
        with open(path, "wb") as f:
            f.write(image.data)
        unzipdir = extract(path, os.path.join(tmp, "fmu"))
        series = _simulate(unzipdir, spec)
    row = summarize(series, spec.t_end)
    # thread time: the run executes in this thread; a Dask worker's other threads
    # (communication, heartbeats) are not the run's cost
    row.update(cpu_s=time.thread_time() - cpu0, wall_s=time.perf_counter() - wall0)
    return RunResult(row, series)


def _communication_points(t_end: float, interval: float) -> np.ndarray:
    n = int(round(t_end / interval))
    if n < 1 or abs(n * interval - t_end) > 1e-9 * max(1.0, t_end):
        raise ValueError(f"t_end = {t_end} is not a whole number of record intervals ({interval})")
    times = np.arange(n + 1) * interval
    times[-1] = t_end
    return times


def _simulate(unzipdir: str, spec: RunSpec) -> pd.DataFrame:
    md = read_model_description(unzipdir, validate=False)
    variables = {v.name: v for v in md.modelVariables}
    fmi2 = md.fmiVersion.startswith("2")
    slave = (FMU2Slave if fmi2 else FMU3Slave)(
        guid=md.guid, unzipDirectory=unzipdir,
        modelIdentifier=md.coSimulation.modelIdentifier, instanceName="tribo_study")
    times = _communication_points(spec.t_end, spec.record_interval)
    version = 2 if fmi2 else 3
    # the recorded outputs by type: (their columns, their value references, the getter)
    groups = {}
    for column, name in enumerate(RECORDED):
        v = variables[name]
        columns, refs, _ = groups.setdefault(v.type, ([], [], getattr(slave, _GETTERS[version][v.type])))
        columns.append(column)
        refs.append(v.valueReference)

    def get():
        row = np.empty(len(RECORDED))
        for columns, refs, getter in groups.values():
            row[columns] = getter(refs)
        return row

    data = np.empty((len(times), len(RECORDED)))
    messages = []  # (status, message) as the FMU logged them
    callbacks = _instantiate(slave, fmi2, messages)  # noqa: F841 (alive while the instance is)
    stage = "setting the parameters"
    try:
        for name, value in spec.params.items():
            _set_parameter(slave, variables, name, value, version)
        stage = "initialization"
        if fmi2:
            slave.setupExperiment(startTime=0.0, stopTime=spec.t_end)
            slave.enterInitializationMode()
        else:
            slave.enterInitializationMode(startTime=0.0, stopTime=spec.t_end)
        slave.exitInitializationMode()
        data[0] = get()
        for k in range(1, len(times)):
            stage = f"the step to tau = {times[k]:g}"
            slave.doStep(times[k - 1], times[k] - times[k - 1])
            data[k] = get()
        slave.terminate()
    except FMICallException as e:
        errors = [m for status, m in messages if status >= _ERROR]
        raise RuntimeError(f"the FMU failed in {stage} with {spec.params}: {e}; "
                           f"it logged: {errors}") from e
    finally:
        slave.freeInstance()
        _fmi2_sinks.pop(id(messages), None)
    series = pd.DataFrame(data, columns=RECORDED)
    series.insert(0, "tau", times)
    return series


def _instantiate(slave, fmi2: bool, messages: list):
    """Instantiate with a logger that appends (status, message) to `messages`; returns what
    must stay alive as long as the instance."""
    if not fmi2:
        slave.instantiate(logMessage=lambda env, status, category, message:
                          messages.append((status, message.decode(errors="replace"))))
        return None
    callbacks = fmi2CallbackFunctions()
    callbacks.logger = _FMI2_LOGGER
    callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    callbacks.componentEnvironment = c_void_p(id(messages))
    _fmi2_sinks[id(messages)] = messages
    addLoggerProxy(byref(callbacks))
    slave.instantiate(callbacks=callbacks)
    return callbacks


def _set_parameter(slave, variables, name, value, version):
    v = variables.get(name)
    if v is None or v.causality not in ("parameter", "structuralParameter"):
        raise KeyError(f"{name!r} is not a parameter of the FMU")
    setter = getattr(slave, _SETTERS_OF_VERSION[version].get(v.type, ""), None)
    if setter is None:
        raise TypeError(f"parameter {name!r} has type {v.type}, which this driver does not set")
    setter([v.valueReference], [value if v.type in _REAL_TYPES else int(value)])

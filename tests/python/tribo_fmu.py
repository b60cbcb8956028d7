"""Drive the tribo FMUs and the core the same way for FMI 2.0 and 3.0.

`Slave` is one FMU instance through fmpy's low-level API, with the importer's logger
captured; `core_run` runs the core directly (build/fmu/tribo_reference_run) for the
FMU's results to be compared against, number for number.
"""

import json
import os
import subprocess
from ctypes import byref, c_bool, c_double, c_void_p

from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
from fmpy.fmi3 import FMU3Slave
from fmpy.logging import addLoggerProxy
from fmpy import calloc, free

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# build/ unless TRIBO_BUILD_DIR names another build directory
BUILD_DIR = os.path.abspath(os.environ.get("TRIBO_BUILD_DIR", os.path.join(ROOT, "build")))
VERSIONS = (2, 3)
# 0: fixed step, 1: CVODE (Adams), 2: CVODE (BDF); the FMU must give what the core gives
# with each
INTEGRATORS = (0, 1, 2)


def integrator_id(integrator):
    return {0: "fixed_step", 1: "cvode", 2: "cvode_bdf"}[integrator]


OK, WARNING, DISCARD, ERROR, FATAL = range(5)

# fmpy's FMI 2.0 logger proxy (which formats the printf-style message, as importers do)
# forwards to one process-wide Python callback, the last one registered. So there is
# one, alive for the whole session, and it finds the Slave by componentEnvironment.
_fmi2_listeners = {}


def _fmi2_dispatch(environment, instance_name, status, category, message):
    listener = _fmi2_listeners.get(environment)
    if listener is None:  # an instance fmpy made with its default callbacks
        print(f"[{status}] {message.decode()}")
    else:
        listener(instance_name, status, category, message)


_FMI2_LOGGER = fmi2CallbackLoggerTYPE(_fmi2_dispatch)

_descriptions = {}


def model_description(fmu_dir):
    if fmu_dir not in _descriptions:
        _descriptions[fmu_dir] = read_model_description(fmu_dir, validate=False)
    return _descriptions[fmu_dir]


def status_of(call, *args, **kwargs):
    """The FMI status of a call through fmpy (which raises on errors)."""
    try:
        call(*args, **kwargs)
    except FMICallException as e:
        return e.status
    return OK


class Slave:
    """One co-simulation instance of a tribo FMU (fmu_dir: the unpacked .fmu)."""

    def __init__(self, fmu_dir, version, name="tribo", logging_on=False, early_return=False):
        self.version = version
        self.early_return = early_return  # FMI 3.0: earlyReturnAllowed
        self.md = model_description(fmu_dir)
        self.variables = {v.name: v for v in self.md.modelVariables}
        self.messages = []  # (status, category, message) as the logger received them
        self.logged_instance_names = []  # FMI 2.0 passes the instance name to the logger
        cls = FMU2Slave if version == 2 else FMU3Slave
        self.fmu = cls(guid=self.md.guid, unzipDirectory=fmu_dir,
                       modelIdentifier=self.md.coSimulation.modelIdentifier, instanceName=name)
        self.instantiate(logging_on)
        self.t = 0.0

    # ---- life cycle ----------------------------------------------------------------

    def instantiate(self, logging_on=False):
        if self.version == 2:
            key = id(self)
            _fmi2_listeners[key] = self._log2
            callbacks = fmi2CallbackFunctions()
            callbacks.logger = _FMI2_LOGGER
            callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
            callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
            callbacks.componentEnvironment = c_void_p(key)
            addLoggerProxy(byref(callbacks))
            self._callbacks = callbacks
            self.fmu.instantiate(callbacks=callbacks, loggingOn=logging_on)
        else:
            self.fmu.instantiate(loggingOn=logging_on, logMessage=self._log3,
                                 earlyReturnAllowed=self.early_return)

    def _log2(self, instance_name, status, category, message):
        self.logged_instance_names.append(instance_name.decode())
        self.messages.append((status, category.decode(), message.decode()))

    def _log3(self, environment, status, category, message):
        self.messages.append((status, category.decode(), message.decode()))

    def _explained(self, call, *args):
        """Make the call; if the FMU refuses, fail with what it logged."""
        try:
            return call(*args)
        except FMICallException as e:
            raise FMICallException(f"{e.function} (the FMU logged: {self.errors()})", e.status)

    def init(self, start=0.0, stop=None, **params):
        """Set parameters (before initialization), then initialize."""
        self.set(**params)
        if self.version == 2:
            self.fmu.setupExperiment(startTime=start, stopTime=stop)
            self.fmu.enterInitializationMode()
        else:
            self.fmu.enterInitializationMode(startTime=start, stopTime=stop)
        self._explained(self.fmu.exitInitializationMode)
        self.t = start
        return self

    def step_to(self, t):
        self._explained(self.fmu.doStep, self.t, t - self.t)
        self.t = t

    def do_step(self, t, h):
        """doStep without fmpy's raising: (status, the last successful time, early return)."""
        f = self.fmu._functions
        if self.version == 2:
            status = f["fmi2DoStep"](self.fmu.component, t, h, 1)
            reached = c_double(float("nan"))
            if f["fmi2GetRealStatus"](self.fmu.component, 2, byref(reached)) != OK:  # fmi2LastSuccessfulTime
                reached.value = float("nan")
            return status, reached.value, False
        event, terminate, early, reached = c_bool(), c_bool(), c_bool(), c_double(float("nan"))
        status = f["fmi3DoStep"](self.fmu.component, t, h, True, byref(event), byref(terminate),
                                 byref(early), byref(reached))
        return status, reached.value, early.value

    def run(self, times, outputs):
        """Step to each time and read the outputs there: a list of dicts."""
        rows = []
        for t in times:
            self.step_to(t)
            rows.append(self.get_many(outputs))
        return rows

    def reset(self):
        self.fmu.reset()
        self.t = 0.0

    def free(self):
        self.fmu.freeInstance()

    # ---- values --------------------------------------------------------------------

    def _accessor(self, verb, name):
        v = self.variables[name]
        # FMI 2.0 reads enumerations as Integers, FMI 3.0 as Int64
        kind = {"Enumeration": "Integer" if self.version == 2 else "Int64"}.get(v.type, v.type)
        return v, getattr(self.fmu, verb + kind)

    def set(self, **values):
        for name, value in values.items():
            v, setter = self._accessor("set", name)
            setter([v.valueReference], [value])

    def get(self, name):
        v, getter = self._accessor("get", name)
        if v.dimensions:
            return getter([v.valueReference], nValues=self.get("n_segments"))
        return getter([v.valueReference])[0] if self.version == 2 else \
            getter([v.valueReference], nValues=1)[0]

    def get_many(self, names):
        return {name: self.get(name) for name in names}

    def errors(self):
        return [m for s, c, m in self.messages if s == ERROR]

    # ---- FMU states -----------------------------------------------------------------

    def get_state(self):
        return self.fmu.getFMUState()

    def set_state(self, state):
        self.fmu.setFMUState(state)

    def free_state(self, state):
        self.fmu.freeFMUState(state)

    def serialize(self, state):
        return self.fmu.serializeFMUState(state)

    def deserialize(self, data):
        return self.fmu.deserializeFMUState(data)


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

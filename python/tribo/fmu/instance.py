"""One co-simulation instance of a tribo FMU (FMI 2.0 and 3.0) through fmpy's low-level
API: the driver the package and the tests share.

`Instance` captures the FMU's log messages per instance (`messages`), sets and reads
values by name whatever their FMI type, and notices an FMU ending the run early (a doStep
that returns Discard and asks to terminate, as a particle leaving the chute does):
`step_to` then returns False and the instance's time is the last time the FMU reached.
"""

import threading
from ctypes import byref, c_double, c_void_p
from functools import lru_cache

import numpy as np
from fmpy import calloc, free, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, fmi2LastSuccessfulTime,
                       fmi2Terminated)
from fmpy.fmi3 import FMU3Slave, fmi3Boolean, fmi3Float64
from fmpy.logging import addLoggerProxy

OK, WARNING, DISCARD, ERROR, FATAL = range(5)  # fmi2Status / fmi3Status
PARAMETER_CAUSALITIES = ("parameter", "structuralParameter")
REAL_TYPES = ("Real", "Float64", "Float32")

# fmpy's FMI 2.0 logger proxy (which formats the printf-style message, as importers do)
# forwards to one process-wide Python callback, the last one registered. So there is one,
# alive for the process, and it finds the instance by componentEnvironment.
_fmi2_listeners = {}


def _fmi2_dispatch(environment, instance_name, status, category, message):
    listener = _fmi2_listeners.get(environment)
    if listener is None:  # an instance fmpy made with its default callbacks
        print(f"[{status}] {message.decode(errors='replace')}")
    else:
        listener(instance_name, status, category, message)


_FMI2_LOGGER = fmi2CallbackLoggerTYPE(_fmi2_dispatch)

# fmpy loads an FMU's library with the working directory changed to the library's folder
# and back: the working directory is the process's, so two threads loading at once (the
# local Dask cluster's runs) would each restore the other's. One load at a time; and the
# package's own file paths are absolute while runs go on (other threads' relative paths
# would resolve in the library's folder for that moment).
_LIBRARY_LOAD = threading.Lock()


@lru_cache(maxsize=32)
def model_description(path: str):
    """fmpy's model description of an .fmu file, an unpacked FMU or a modelDescription.xml."""
    return read_model_description(path, validate=False)


class Instance:
    """One co-simulation instance of a tribo FMU (fmu_dir: the unpacked .fmu)."""

    def __init__(self, fmu_dir: str, name: str = "tribo", logging_on: bool = False,
                 early_return: bool = False):
        self.md = model_description(fmu_dir)
        self.early_return = early_return  # FMI 3.0: earlyReturnAllowed
        self.version = 2 if self.md.fmiVersion.startswith("2") else 3
        self.variables = {v.name: v for v in self.md.modelVariables}
        self.messages = []  # (status, category, message) as the logger received them
        self.logged_instance_names = []  # FMI 2.0 passes the instance name to the logger
        cls = FMU2Slave if self.version == 2 else FMU3Slave
        with _LIBRARY_LOAD:
            self.fmu = cls(guid=self.md.guid, unzipDirectory=fmu_dir,
                           modelIdentifier=self.md.coSimulation.modelIdentifier, instanceName=name)
        self.instantiate(logging_on)
        self.t = 0.0
        self.ended = False  # the FMU ended the run before the time asked for (see step_to)
        self.work_limit_returns = 0  # FMI 3.0 steps cut by the work limit and continued

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.free()
        return False

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
            self._callbacks = callbacks  # alive as long as the instance
            self.fmu.instantiate(callbacks=callbacks, loggingOn=logging_on)
        else:
            self.fmu.instantiate(loggingOn=logging_on, logMessage=self._log3,
                                 earlyReturnAllowed=self.early_return)

    def _log2(self, instance_name, status, category, message):
        self.logged_instance_names.append(instance_name.decode(errors="replace"))
        self.messages.append((status, category.decode(errors="replace"),
                              message.decode(errors="replace")))

    def _log3(self, environment, status, category, message):
        self.messages.append((status, category.decode(errors="replace"),
                              message.decode(errors="replace")))

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
        self.ended = False
        return self

    def step_to(self, t) -> bool:
        """One communication step to t. False if the FMU ended the run before t: then
        `self.t` is the last time it reached, `self.ended` is set, and the outputs are
        those of that time. With FMI 3.0, a step cut short by the FMU's work limit
        (`work_limit`) is continued from where it stopped until it reaches t (counted in
        `work_limit_returns`); with FMI 2.0 that leaves the instance in stepFailed, and the
        call raises."""
        if self.version == 2:
            try:
                self._explained(self.fmu.doStep, self.t, t - self.t)
            except FMICallException as e:
                if e.status != DISCARD or not self.fmu.getBooleanStatus(fmi2Terminated):
                    raise
                return self._end(self.fmu.getRealStatus(fmi2LastSuccessfulTime))
            self.t = t
            return True
        while True:
            status, terminate, early, reached = self._do_step3(self.t, t - self.t)
            if status > WARNING and status != DISCARD:
                raise FMICallException(f"fmi3DoStep (the FMU logged: {self.errors()})", status)
            if terminate:
                return self._end(reached)
            if status == OK and not early:
                self.t = t
                return True
            # the step's work limit was spent (Discard, or an early return): the FMU stays
            # in Step Mode at the time reached, and the run goes on from there unchanged
            # (fmu/README.md, "Work limit"); a return without progress would loop for ever
            if not reached > self.t:
                raise FMICallException(f"fmi3DoStep made no progress from time {self.t!r} "
                                       f"(the FMU logged: {self.errors()})", status)
            self.t = reached
            self.work_limit_returns += 1

    def _do_step3(self, t, h):
        """fmi3DoStep called directly: fmpy raises on Discard and so loses the step's
        outputs (terminateSimulation, earlyReturn, lastSuccessfulTime), which tell why."""
        event, terminate, early, reached = fmi3Boolean(), fmi3Boolean(), fmi3Boolean(), fmi3Float64()
        status = self.fmu.dll.fmi3DoStep(self.fmu.component, t, h, fmi3Boolean(True), byref(event),
                                         byref(terminate), byref(early), byref(reached))
        return status, bool(terminate.value), bool(early.value), reached.value

    def do_step(self, t, h):
        """doStep without raising, for callers that handle every status: (status, the last
        successful time, whether FMI 3.0 returned early)."""
        if self.version == 3:
            status, _, early, reached = self._do_step3(t, h)
            return status, reached, early
        f = self.fmu._functions  # fmpy's wrapper raises on Discard / Error
        status = f["fmi2DoStep"](self.fmu.component, t, h, 1)
        reached = c_double(float("nan"))
        if f["fmi2GetRealStatus"](self.fmu.component, 2, byref(reached)) != OK:  # fmi2LastSuccessfulTime
            reached.value = float("nan")
        return status, reached.value, False

    def _end(self, reached) -> bool:
        self.t = reached
        self.ended = True
        return False

    def run(self, times, outputs):
        """Step to each time and read the outputs there: a list of dicts (up to the time
        the FMU ended the run, if it did)."""
        rows = []
        for t in times:
            going = self.step_to(t)
            rows.append(self.get_many(outputs))
            if not going:
                break
        return rows

    def terminate(self):
        self.fmu.terminate()

    def reset(self):
        self.fmu.reset()
        self.t = 0.0
        self.ended = False

    def free(self):
        self.fmu.freeInstance()
        _fmi2_listeners.pop(id(self), None)

    # ---- values --------------------------------------------------------------------

    def _accessor(self, verb, name):
        v = self.variables.get(name)
        if v is None:
            raise KeyError(f"{name!r} is not a variable of the FMU")
        # FMI 2.0 reads and sets enumerations as Integers, FMI 3.0 as Int64
        kind = {"Enumeration": "Integer" if self.version == 2 else "Int64"}.get(v.type, v.type)
        return v, getattr(self.fmu, verb + kind)

    def set(self, **values):
        for name, value in values.items():
            v, setter = self._accessor("set", name)
            setter([v.valueReference], [value])

    def set_parameters(self, params: dict):
        """Set parameters by name, each converted to its variable's type (an integer
        parameter given as 64.0 is set as 64)."""
        for name, value in params.items():
            v = self.variables.get(name)
            if v is None or v.causality not in PARAMETER_CAUSALITIES:
                raise KeyError(f"{name!r} is not a parameter of the FMU")
            self.set(**{name: float(value) if v.type in REAL_TYPES else int(value)})

    def get(self, name):
        v, getter = self._accessor("get", name)
        if v.dimensions:
            return getter([v.valueReference], nValues=self.get("n_segments"))
        return getter([v.valueReference])[0] if self.version == 2 else \
            getter([v.valueReference], nValues=1)[0]

    def get_many(self, names):
        return {name: self.get(name) for name in names}

    def reader(self, names):
        """A function that reads the scalar variables `names` at once (one call per FMI
        type), as a numpy array in that order."""
        groups = {}
        for column, name in enumerate(names):
            v, getter = self._accessor("get", name)
            columns, refs, _ = groups.setdefault(v.type, ([], [], getter))
            columns.append(column)
            refs.append(v.valueReference)

        def read():
            row = np.empty(len(names))
            for columns, refs, getter in groups.values():
                row[columns] = getter(refs)
            return row

        return read

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


def status_of(call, *args, **kwargs):
    """The FMI status of a call through fmpy (which raises on errors)."""
    try:
        call(*args, **kwargs)
    except FMICallException as e:
        return e.status
    return OK


def record(instance: Instance, times, names) -> tuple[np.ndarray, np.ndarray]:
    """Read `names` now (at times[0]) and after a step to each later time; stops where the
    FMU ends the run early, keeping the rows up to there. Returns (the times reached,
    one row of values per time)."""
    read = instance.reader(names)
    reached, rows = [instance.t], [read()]
    for t in times[1:]:
        going = instance.step_to(t)
        reached.append(instance.t)
        rows.append(read())
        if not going:
            break
    return np.array(reached), np.array(rows).reshape(len(rows), len(names))

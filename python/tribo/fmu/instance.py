"""One co-simulation instance of a tribo FMU (FMI 2.0 and 3.0) through fmpy's low-level
API: the driver the package and the tests share.

`Instance` captures the FMU's log messages per instance (`messages`), sets and reads
values by name whatever their FMI type, and notices an FMU ending the run early (a doStep
that returns Discard and asks to terminate, as a particle leaving the chute does):
`step_to` then returns False and the instance's time is the last time the FMU reached.
An instance is made from an FmuImage (the process's loaded copy of the FMU,
fmu/library.py: the package's runs) or from an unpacked FMU's directory (its library
loaded for the instance and released with it).

`record` and `Instance.reader` read many outputs at many times: one FMI call per type of
variable and time, straight into numpy arrays (`Rows`), no Python object per value; `Values`
sets many variables at once, one FMI call per type.
"""

import ctypes
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

from .image import FmuImage
from .library import LIBRARY_LOAD, loaded, raw_getters, raw_setters

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


@lru_cache(maxsize=32)
def model_description(path: str):
    """fmpy's model description of an .fmu file, an unpacked FMU or a modelDescription.xml."""
    return read_model_description(path, validate=False)


class Instance:
    """One co-simulation instance of a tribo FMU. fmu: an FmuImage (the process's loaded
    copy of it, fmu/library.py, which outlives the instance) or the directory of an
    unpacked .fmu (its library loaded for this instance, released by `free`)."""

    def __init__(self, fmu: "FmuImage | str", name: str = "tribo", logging_on: bool = False,
                 early_return: bool = False):
        self.early_return = early_return  # FMI 3.0: earlyReturnAllowed
        self.messages = []  # (status, category, message) as the logger received them
        self.logged_instance_names = []  # FMI 2.0 passes the instance name to the logger
        if isinstance(fmu, FmuImage):
            library = loaded(fmu)
            self.md, self.version, self.variables = library.md, library.version, library.variables
            self.fmu = library.slave(name)
            self.getters, self.setters = library.getters, library.setters
            self._library = library
            self._owns_library = False
        else:
            self.md = model_description(fmu)
            self.version = 2 if self.md.fmiVersion.startswith("2") else 3
            self.variables = {v.name: v for v in self.md.modelVariables}
            cls = FMU2Slave if self.version == 2 else FMU3Slave
            with LIBRARY_LOAD:
                self.fmu = cls(guid=self.md.guid, unzipDirectory=fmu,
                               modelIdentifier=self.md.coSimulation.modelIdentifier,
                               instanceName=name)
            self.getters = raw_getters(self.fmu.dll, self.version)
            self.setters = raw_setters(self.fmu.dll, self.version)
            self._library = None
            self._owns_library = True
        # fmi3DoStep's output arguments, made once (_do_step3)
        self._step_flags = (fmi3Boolean(), fmi3Boolean(), fmi3Boolean(), fmi3Float64())
        self._step_refs = tuple(byref(x) for x in self._step_flags)
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
        return self.initialize(start, stop)

    def initialize(self, start=0.0, stop=None):
        """Enter and exit initialization mode with the values set so far."""
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
        _, terminate, early, reached = self._step_flags
        event, terminate_ref, early_ref, reached_ref = self._step_refs
        status = self.fmu.dll.fmi3DoStep(self.fmu.component, t, h, True, event, terminate_ref,
                                         early_ref, reached_ref)
        return status, terminate.value, early.value, reached.value

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
        """fmi3Reset / fmi2Reset: the state a new instance has (the tribo FMUs free their core
        and restore every start value), and so this object's record of a run: its time, its
        log (a new list: the earlier run's stays that run's), the work limit's returns."""
        self.fmu.reset()
        self.t = 0.0
        self.ended = False
        self.messages = []
        self.logged_instance_names = []
        self.work_limit_returns = 0

    def free(self):
        if self._owns_library:
            self.fmu.freeInstance()  # fmpy's: the instance, then the library
        elif self.version == 2:
            self.fmu.fmi2FreeInstance(self.fmu.component)  # the library stays for the process
        else:
            self.fmu.fmi3FreeInstance(self.fmu.component)
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
        names = tuple(params)
        real = self.layout("parameters", names, lambda: parameter_types(self, names))
        values = [float(value) if is_real else int(value)
                  for is_real, value in zip(real, params.values())]
        # in the order given, the values of one type next to each other in one call (a
        # population's particle sets tens: by name, each cost an fmpy setter's checks)
        Values(self, names).set(values)

    def get(self, name):
        v, getter = self._accessor("get", name)
        if v.dimensions:
            return getter([v.valueReference], nValues=self.get("n_segments"))
        return getter([v.valueReference])[0] if self.version == 2 else \
            getter([v.valueReference], nValues=1)[0]

    def layout(self, what: str, names, make):
        """`make()` for `names`, once per loaded FMU (fmu/library.py's LoadedFmu.layout);
        each time for an FMU this instance loaded itself."""
        if self._library is None:
            return make()
        return self._library.layout(what, tuple(names), make)

    def get_many(self, names):
        """The variables `names` as `get` reads them (Python floats, ints, bools as fmpy's
        getters give), the scalars in one FMI call per type."""
        names = list(names)
        try:
            groups = self.layout("read", names, lambda: read_layout(self, names))
        except (KeyError, ValueError):  # arrays, types not read at once: one by one
            return {name: self.get(name) for name in names}
        read = {}
        component, fmi3 = self.fmu.component, self.version == 3
        for function, c_function, vrs, columns, dtype in groups:
            n = len(columns)
            values = np.empty(n, dtype)
            address = values.__array_interface__["data"][0]
            status = (c_function(component, vrs, n, address, n) if fmi3
                      else c_function(component, vrs, n, address))
            if status > WARNING:  # as fmpy's own getters
                raise FMICallException(function, status)
            # numpy's scalars as Python's, as fmpy's getters give them
            read.update(zip((names[c] for c in columns), values.tolist()))
        return {name: read[name] for name in names}

    def reader(self, names):
        """A function that reads the scalar variables `names` at once (one call per FMI
        type), as a numpy array in that order."""
        rows = Rows(self, names, capacity=1)

        def read():
            rows.clear()
            rows.read()
            return rows.table()[0]

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
    # Python floats: the FMI calls take them as they are
    times = times.tolist() if isinstance(times, np.ndarray) else [float(t) for t in times]
    rows = Rows(instance, names, capacity=min(len(times), 4096))  # grown as the run goes on
    rows.read()
    reached = [instance.t]
    step_to, read = instance.step_to, rows.read
    for t in times[1:]:
        going = step_to(t)
        reached.append(instance.t)
        read()
        if not going:
            break
    return np.array(reached), rows.table()


def _scalar(instance: Instance, name: str, functions: dict, instead: str, how: str):
    """The scalar variable `name`, of a type `functions` has: KeyError for a name that is
    not a variable, ValueError for an array (`instead`: what to do) or another type."""
    v = instance.variables.get(name)
    if v is None:
        raise KeyError(f"{name!r} is not a variable of the FMU")
    if v.dimensions:
        raise ValueError(f"{name!r} is an array: {instead}")
    if v.type not in functions:
        raise ValueError(f"{name!r}: the FMU's type {v.type} is not one {how}")
    return v


def read_layout(instance: Instance, names) -> tuple:
    """How the scalar variables `names` are read at once: (function name, C function, value
    references, their positions in `names`, numpy type) per FMI type. KeyError for a name
    that is not a variable, ValueError for an array or a type not read so."""
    by_type = {}
    for column, name in enumerate(names):
        v = _scalar(instance, name, instance.getters, "read it with get", "read in rows")
        columns, refs = by_type.setdefault(v.type, ([], []))
        columns.append(column)
        refs.append(v.valueReference)
    return tuple((*instance.getters[kind][:2], (ctypes.c_uint32 * len(refs))(*refs),
                  tuple(columns), instance.getters[kind][2])
                 for kind, (columns, refs) in by_type.items())


class Rows:
    """The scalar variables `names` of an instance read into a table, a row per `read`:
    one FMI call per type of variable, writing straight into a numpy array (grown as
    needed), so that a row costs a few calls whatever the number of names. `table()`:
    the rows so far as floats, a column per name in that order (booleans 0 / 1)."""

    def __init__(self, instance: Instance, names, capacity: int = 64):
        self.instance, self.width = instance, len(names)
        self.groups = [_Group(function, c_function, vrs, columns,
                              np.empty((max(capacity, 1), len(columns)), dtype))
                       for function, c_function, vrs, columns, dtype
                       in instance.layout("read", names, lambda: read_layout(instance, names))]
        self.capacity = max(capacity, 1)
        self.n = 0

    def clear(self):
        self.n = 0

    def read(self):
        """Append the values now as a row."""
        i = self.n
        if i == self.capacity:
            self.capacity *= 2
            for g in self.groups:
                g.hold(np.concatenate([g.block, np.empty_like(g.block)]))
        component = self.instance.fmu.component
        fmi3 = self.instance.version == 3
        for g in self.groups:
            address = g.address + i * g.row_bytes
            status = (g.c_function(component, g.vrs, g.n, address, g.n) if fmi3
                      else g.c_function(component, g.vrs, g.n, address))
            if status > WARNING:  # as fmpy's own getters
                raise FMICallException(g.function, status)
        self.n = i + 1

    def table(self) -> np.ndarray:
        out = np.empty((self.n, self.width))
        for g in self.groups:
            out[:, g.columns] = g.block[:self.n]
        return out


def parameter_types(instance: Instance, names) -> tuple:
    """Whether each of `names` is a real parameter (else an integer one, Boolean and
    enumeration included): KeyError for a name that is not a parameter."""
    real = []
    for name in names:
        v = instance.variables.get(name)
        if v is None or v.causality not in PARAMETER_CAUSALITIES:
            raise KeyError(f"{name!r} is not a parameter of the FMU")
        real.append(v.type in REAL_TYPES)
    return tuple(real)


def write_layout(instance: Instance, names) -> tuple:
    """How the scalar variables `names` are set at once, in their order: (function name, C
    function, value references, their positions in `names`, ctypes array type) per run of
    names of one type. KeyError for a name that is not a variable, ValueError for an array
    or a type not set so."""
    runs = []  # (type, positions, value references): names of one type next to each other
    for position, name in enumerate(names):
        v = _scalar(instance, name, instance.setters, "set it with set", "set at once")
        if not runs or runs[-1][0] != v.type:
            runs.append((v.type, [], []))
        runs[-1][1].append(position)
        runs[-1][2].append(v.valueReference)
    out = []
    for kind, positions, refs in runs:
        function, c_function, c_type = instance.setters[kind]
        out.append((function, c_function, (ctypes.c_uint32 * len(refs))(*refs),
                    tuple(positions), c_type * len(refs)))
    return tuple(out)


class Values:
    """The scalar variables `names` of an instance set at once, in their order: one FMI call
    per run of names of one type, the values converted to the FMI type as fmpy's setters
    convert them (`Instance.set`: the same values reach the FMU, in the same order). A call
    by name costs a look-up, an fmpy wrapper and its checks per value; the FMU checks one
    call's values together (FMI's semantics), which a set of values accepted one by one
    passes too."""

    def __init__(self, instance: Instance, names):
        self.instance = instance
        self.names = tuple(names)
        self.groups = instance.layout("write", self.names,
                                      lambda: write_layout(instance, self.names))

    def set(self, values) -> None:
        """Set the variables to `values`, in the order of `names`."""
        component = self.instance.fmu.component
        fmi3 = self.instance.version == 3
        for function, c_function, vrs, positions, array in self.groups:
            n = len(positions)
            data = array(*[values[i] for i in positions])
            status = (c_function(component, vrs, n, data, n) if fmi3
                      else c_function(component, vrs, n, data))
            if status > WARNING:  # as fmpy's own setters (the FMU logged why)
                raise FMICallException(function, status)


class _Group:
    """The variables of one FMI type that Rows reads in one call, and their block of rows
    (with the address of its first row, taken once per block)."""

    def __init__(self, function, c_function, vrs, columns, block):
        self.function, self.c_function, self.vrs, self.columns = function, c_function, vrs, columns
        self.n = len(columns)
        self.hold(block)

    def hold(self, block):
        self.block, self.row_bytes = block, block.strides[0]
        self.address = block.__array_interface__["data"][0]  # cheaper than block.ctypes

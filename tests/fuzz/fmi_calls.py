"""Raw FMI calls on one instance of a tribo FMU, for the fuzz suite: every call returns the
FMI status (fmpy would raise), and each value is passed in the C type of the function
that takes it. The variables and their types come from the modelDescription, the C types
from fmpy's prototypes, so that the suite follows a change of types there."""

from ctypes import byref, c_bool, c_double, c_int, c_size_t, c_void_p

# instantiation and the importer's logger: the package's driver
from tribo.fmu import DISCARD, ERROR, FATAL, OK, WARNING  # noqa: F401
from tribo.fmu import Instance as Driver

# the functions that take a variable type's values: FMI 2.0 passes enumerations as
# Integer, FMI 3.0 as Int64
FUNCTION_TYPE = {
    2: {"Real": "Real", "Integer": "Integer", "Enumeration": "Integer", "Boolean": "Boolean"},
    3: {"Enumeration": "Int64"},
}


def function_type(version, variable_type):
    return FUNCTION_TYPE[version].get(variable_type, variable_type)


class Instance:
    """One instance, driven by raw calls. `calls` counts every FMI call made."""

    def __init__(self, fmu_dir, version, early_return=False):
        self.version = version
        self.slave = Driver(fmu_dir, early_return=early_return)
        assert self.slave.version == version, (fmu_dir, version)
        self.fmu = self.slave.fmu
        self.md = self.slave.md
        self.f = self.fmu._functions
        self.c = self.fmu.component
        self.calls = 1
        self.S = "FMUstate" if version == 2 else "FMUState"

    def _call(self, name, *args):
        self.calls += 1
        return self.f[f"fmi{self.version}{name}"](self.c, *args)

    def errors(self):
        return self.slave.errors()

    # ---- life cycle --------------------------------------------------------------------

    def free(self):
        state = getattr(self, "_snapshot_state", None)
        if state is not None:
            self.free_state(state)
        self.calls += 1
        self.fmu.freeInstance()

    def setup_experiment(self, start, stop, tolerance=None):
        """FMI 2.0's fmi2SetupExperiment (None: undefined); FMI 3.0 takes the same with
        initialization."""
        return self._call("SetupExperiment", int(tolerance is not None),
                          0.0 if tolerance is None else tolerance, start, int(stop is not None),
                          0.0 if stop is None else stop)

    def enter_initialization(self, start=0.0, stop=None, tolerance=None):
        if self.version == 2:
            return self._call("EnterInitializationMode")
        return self._call("EnterInitializationMode", tolerance is not None,
                          0.0 if tolerance is None else tolerance, start, stop is not None,
                          0.0 if stop is None else stop)

    def exit_initialization(self):
        return self._call("ExitInitializationMode")

    def enter_configuration(self):
        return self._call("EnterConfigurationMode")

    def exit_configuration(self):
        return self._call("ExitConfigurationMode")

    def terminate(self):
        return self._call("Terminate")

    def reset(self):
        return self._call("Reset")

    def do_step(self, t, h):
        """(status, the last successful time, early return, the FMU asks to terminate)"""
        if self.version == 2:
            status = self._call("DoStep", t, h, 1)
            reached, terminated = c_double(float("nan")), c_int(0)
            self._call("GetRealStatus", 2, byref(reached))  # fmi2LastSuccessfulTime
            self._call("GetBooleanStatus", 3, byref(terminated))  # fmi2Terminated
            return status, reached.value, False, bool(terminated.value)
        event, terminate, early, reached = c_bool(), c_bool(), c_bool(), c_double(float("nan"))
        status = self._call("DoStep", t, h, True, byref(event), byref(terminate), byref(early),
                            byref(reached))
        return status, reached.value, early.value, terminate.value

    # ---- values ------------------------------------------------------------------------

    def _values_type(self, verb, ftype):
        return self.f[f"fmi{self.version}{verb}{ftype}"].argtypes[3]._type_

    def get(self, ftype, vrs, n_values):
        """(status, values) of the getter of function type ftype."""
        ctype = self._values_type("Get", ftype)
        values = (ctype * max(1, n_values))()
        refs = (self.f[f"fmi{self.version}Get{ftype}"].argtypes[1]._type_ * max(1, len(vrs)))(*vrs)
        args = (refs, len(vrs), values) + (() if self.version == 2 else (n_values,))
        status = self._call(f"Get{ftype}", *args)
        return status, list(values)[:n_values]

    def set(self, ftype, vrs, values):
        ctype = self._values_type("Set", ftype)
        array = (ctype * max(1, len(values)))(*values)
        refs = (self.f[f"fmi{self.version}Set{ftype}"].argtypes[1]._type_ * max(1, len(vrs)))(*vrs)
        args = (refs, len(vrs), array) + (() if self.version == 2 else (len(values),))
        return self._call(f"Set{ftype}", *args)

    def c_value(self, ftype, value):
        """What the C type of the setter makes of a Python value."""
        return self._values_type("Set", ftype)(value).value

    # ---- FMU states --------------------------------------------------------------------

    def get_state(self, state=None):
        """(status, state); pass a state to overwrite it."""
        handle = c_void_p(state)
        status = self._call(f"Get{self.S}", byref(handle))
        return status, handle.value

    def set_state(self, state):
        return self._call(f"Set{self.S}", state)

    def free_state(self, state):
        handle = c_void_p(state)
        return self._call(f"Free{self.S}", byref(handle))

    def serialize(self, state):
        """(status, bytes)"""
        size = c_size_t()
        status = self._call(f"Serialized{self.S}Size", state, byref(size))
        if status != OK:
            return status, b""
        byte = self.f[f"fmi{self.version}Serialize{self.S}"].argtypes[2]._type_
        buffer = (byte * size.value)()
        status = self._call(f"Serialize{self.S}", state, buffer, size.value)
        return status, bytes(buffer)

    def deserialize(self, data):
        """(status, state)"""
        name = "DeSerializeFMUstate" if self.version == 2 else "DeserializeFMUState"
        byte = self.f[f"fmi{self.version}{name}"].argtypes[1]._type_
        buffer = (byte * max(1, len(data))).from_buffer_copy(data or b"\0")
        handle = c_void_p()
        status = self._call(name, buffer, len(data), byref(handle))
        return status, handle.value

    def snapshot(self):
        """The instance's current state as bytes (or None if it has none to give). The state
        is saved into one kept for this (an FMU state is overwritten when passed again), which
        saves a free and an allocation per snapshot: the fuzz suite takes two around every
        call it expects may be refused."""
        status, state = self.get_state(getattr(self, "_snapshot_state", None))
        if status != OK:
            return None
        self._snapshot_state = state
        status, data = self.serialize(state)
        return data if status == OK else None


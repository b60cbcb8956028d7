"""An FMU loaded once per process (`loaded(image)`), for any number of instances.

A run used to unpack the FMU into a fresh temporary directory, parse its model
description, load its library and let fmpy wrap each FMI function (with
inspect.signature), then remove the directory again: tens of milliseconds per run, more
than many runs' own work. FMI lets one loaded FMU make several independent instances (the
tribo FMUs keep no state outside an instance: no static variables, one SUNDIALS context
per instance; they do not declare canBeInstantiatedOnlyOncePerProcess), so a process (a
Dask worker, the command's own process) unpacks each FMU once, into a private temporary
directory removed when the process exits, and keeps its model description and one fmpy
object with the library loaded and the functions wrapped. Each instance (fmu/instance.py)
gets its own copy of that object, whose instantiate makes its own FMI instance and whose
component, callbacks and log are its own; the library stays loaded for the process (the
instance frees only itself). What is shared is read only after loading: the directory,
the description, the library's function pointers.

The cache is keyed by the FMU's SHA-256, so a rebuilt FMU (other bytes) is loaded anew
beside the old one. A forked child uses its parent's copy and leaves its removal to the
parent.
"""

import copy
import io
import multiprocessing.util
import os
import shutil
import tempfile
import threading
import zipfile
from ctypes import c_bool, c_double, c_float, c_int, c_int8, c_int16, c_int32, c_int64, \
    c_size_t, c_uint8, c_uint16, c_uint32, c_uint64, c_void_p
from dataclasses import dataclass, field

import numpy as np
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

from .image import FmuImage

# fmpy loads an FMU's library with the working directory changed to the library's folder
# and back: the working directory is the process's, so two threads loading at once (the
# local Dask cluster's runs) would each restore the other's. One load at a time; and the
# package's own file paths are absolute while runs go on (other threads' relative paths
# would resolve in the library's folder for that moment).
LIBRARY_LOAD = threading.Lock()


# the FMI getters instance.Rows calls directly, by the variable's type: (function, numpy
# type of its values); FMI 2.0 reads enumerations as Integers, FMI 3.0 as Int64, and FMI
# 2.0's Boolean is an int
_GETTERS = {
    2: {"Real": ("fmi2GetReal", np.float64), "Integer": ("fmi2GetInteger", np.int32),
        "Enumeration": ("fmi2GetInteger", np.int32), "Boolean": ("fmi2GetBoolean", np.int32)},
    3: {"Float64": ("fmi3GetFloat64", np.float64), "Float32": ("fmi3GetFloat32", np.float32),
        "Int64": ("fmi3GetInt64", np.int64), "Enumeration": ("fmi3GetInt64", np.int64),
        "UInt64": ("fmi3GetUInt64", np.uint64), "Int32": ("fmi3GetInt32", np.int32),
        "UInt32": ("fmi3GetUInt32", np.uint32),
        "Int16": ("fmi3GetInt16", np.int16), "UInt16": ("fmi3GetUInt16", np.uint16),
        "Int8": ("fmi3GetInt8", np.int8), "UInt8": ("fmi3GetUInt8", np.uint8),
        "Boolean": ("fmi3GetBoolean", np.bool_)},
}


# the FMI setters instance.Values calls directly, by the variable's type: (function, the C
# type of its values, as fmpy's own setters convert them)
_SETTERS = {
    2: {"Real": ("fmi2SetReal", c_double), "Integer": ("fmi2SetInteger", c_int32),
        "Enumeration": ("fmi2SetInteger", c_int32), "Boolean": ("fmi2SetBoolean", c_int32)},
    3: {"Float64": ("fmi3SetFloat64", c_double), "Float32": ("fmi3SetFloat32", c_float),
        "Int64": ("fmi3SetInt64", c_int64), "Enumeration": ("fmi3SetInt64", c_int64),
        "UInt64": ("fmi3SetUInt64", c_uint64), "Int32": ("fmi3SetInt32", c_int32),
        "UInt32": ("fmi3SetUInt32", c_uint32),
        "Int16": ("fmi3SetInt16", c_int16), "UInt16": ("fmi3SetUInt16", c_uint16),
        "Int8": ("fmi3SetInt8", c_int8), "UInt8": ("fmi3SetUInt8", c_uint8),
        "Boolean": ("fmi3SetBoolean", c_bool)},
}


def raw_setters(dll, version: int) -> dict:
    """The library's setters for raw calls, by the variable's type: (function name, the C
    function, the C type of its values), as raw_getters (instance.Values calls them)."""
    return _raw_functions(dll, version, _SETTERS[version])


def raw_getters(dll, version: int) -> dict:
    """The library's getters for raw calls, by the variable's type: (function name, the C
    function, the numpy type of its values). Each C function is an object of its own (not
    the one fmpy typed), its arguments plain addresses: instance.Rows passes numpy's."""
    return _raw_functions(dll, version, _GETTERS[version])


def _raw_functions(dll, version: int, table: dict) -> dict:
    """`table`'s functions (type -> (name, values' type)) of the library, for raw calls."""
    out = {}
    for kind, (function, values_type) in table.items():
        try:
            c_function = dll[function]  # a new object: fmpy's keeps its own argtypes
        except AttributeError:  # a library without it: its type is not read or set at once
            continue
        c_function.restype = c_int
        c_function.argtypes = ((c_void_p, c_void_p, c_size_t, c_void_p, c_size_t) if version == 3
                               else (c_void_p, c_void_p, c_size_t, c_void_p))
        out[kind] = (function, c_function, values_type)
    return out


@dataclass(eq=False)
class LoadedFmu:
    """An FMU unpacked in `directory` with its library loaded (one per process and FMU)."""

    image_name: str
    sha256: str
    directory: str
    md: object  # fmpy's ModelDescription
    version: int  # 2 or 3
    variables: dict = field(repr=False)  # name -> fmpy ModelVariable
    template: object = field(repr=False)  # an fmpy slave never instantiated: the library
    getters: dict = field(repr=False)  # raw_getters of the library
    setters: dict = field(repr=False)  # raw_setters of the library
    # what instance.Rows and instance.Values make of a list of names (which FMI function,
    # which value references), by (what, names): made once per process, read only after
    layouts: dict = field(default_factory=dict, repr=False)

    def layout(self, what: str, names: tuple, make):
        """`make()`'s layout of `names` for `what` ("read", "write"), made on first use (a
        population's particle asked for the same ones' anew, tens of look-ups a run).
        Threads that make the same one at once each make it; one is kept."""
        key = (what, names)
        found = self.layouts.get(key)
        if found is None:
            found = self.layouts.setdefault(key, make())
        return found

    def slave(self, name: str):
        """A new fmpy slave on the loaded library, not yet instantiated: its instantiate
        makes an FMI instance of its own (a shallow copy: the library and its wrapped
        functions are shared, read only)."""
        s = copy.copy(self.template)
        s.instanceName = name
        s.component = None
        s.callbacks = None
        return s


def loaded(image: FmuImage) -> LoadedFmu:
    """The process's LoadedFmu of `image`, made on first use."""
    found = _loaded.get(image.sha256)
    if found is None:
        with LIBRARY_LOAD:
            found = _loaded.get(image.sha256)
            if found is None:
                found = _loaded[image.sha256] = _load(image)
    return found


def _load(image: FmuImage) -> LoadedFmu:
    md = image.model_description()
    directory = tempfile.mkdtemp(prefix="tribo_fmu_")
    _remove_at_exit(directory)
    with zipfile.ZipFile(io.BytesIO(image.data)) as z:
        z.extractall(directory)
    version = 2 if md.fmiVersion.startswith("2") else 3
    cls = FMU2Slave if version == 2 else FMU3Slave
    template = cls(guid=md.guid, unzipDirectory=directory,
                   modelIdentifier=md.coSimulation.modelIdentifier, instanceName="tribo")
    return LoadedFmu(image.name, image.sha256, directory, md, version,
                     {v.name: v for v in md.modelVariables}, template,
                     raw_getters(template.dll, version), raw_setters(template.dll, version))


# the process's loaded FMUs by SHA-256; written under LIBRARY_LOAD only, never emptied
# while the process runs (instances may be running on them)
_loaded: dict[str, LoadedFmu] = {}


def _remove_at_exit(directory: str) -> None:
    """Remove `directory` when this process exits. multiprocessing's exit finalizers run
    at a main process's exit (through atexit) and at the end of its children (Dask's
    worker processes), which leave with os._exit and so run no atexit handler of their
    own. Not in a forked child: the parent's runs may still use the directory."""
    pid = os.getpid()

    def remove():
        if os.getpid() == pid:
            shutil.rmtree(directory, ignore_errors=True)

    multiprocessing.util.Finalize(None, remove, exitpriority=0)

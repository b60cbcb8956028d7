"""The fmpy driver of the tribo FMUs (FMI 2.0 and 3.0), shared by the package and the tests.

    instance    one co-simulation instance (`Instance`): its log, values by name, steps
                that notice an FMU ending the run early; `record` and `Rows` (outputs
                read into numpy arrays, one FMI call per type), `status_of`
    image       an .fmu file as bytes (`FmuImage`) for any Dask worker; `unpacked`
    library     an FmuImage unpacked and loaded once per process, for its instances
    locate      where the build's FMUs are (`find_fmu`)
    names       the package's names and units of the FMUs' variables: angles in degrees
                (<name>_deg), the SI FMUs' size as the long diameter `size`
    parameters  parameter names and values checked by the FMU before any run
    charge_models  the registered charge models and the enumerations an FMU declares

The driver's names are importable from here (`from tribo.fmu import Instance, FmuImage`).
"""

from .image import FmuImage, unpacked
from .instance import (DISCARD, ERROR, FATAL, OK, PARAMETER_CAUSALITIES, REAL_TYPES, WARNING,
                       Instance, Rows, model_description, record, status_of)

__all__ = ["OK", "WARNING", "DISCARD", "ERROR", "FATAL", "PARAMETER_CAUSALITIES", "REAL_TYPES",
           "Instance", "Rows", "model_description", "record", "status_of", "FmuImage", "unpacked"]

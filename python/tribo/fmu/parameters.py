"""Parameter values checked before any run: the names (the package's, names.py), the type
from the FMU's modelDescription (an integer or enumeration parameter takes whole numbers
only), the range by the FMU itself.

`check_values` instantiates the FMU here, in this process, and sets every value once:
the FMU refuses a value out of its range, and the refusal is told in one line with the
package's name, the value as given and the valid range in the package's unit (the same
check as in a run, with open and closed ends as the FMU has them). So a sweep or a study
with a bad value stops with that message before a cluster starts or any run is made.
"""

import math
import numbers

from fmpy.fmi1 import FMICallException

from .image import FmuImage
from .instance import PARAMETER_CAUSALITIES, REAL_TYPES, Instance
from .names import ParameterError, check_parameter_names, format_number, refusal_message, to_fmu


def parameter_variables(md) -> dict:
    """The FMU's parameters (structural ones included): name -> fmpy ModelVariable."""
    return {v.name: v for v in md.modelVariables if v.causality in PARAMETER_CAUSALITIES}


def integer_names(md) -> tuple:
    """The parameters that take whole numbers (Integer, UInt64, Enumeration, ...)."""
    return tuple(n for n, v in parameter_variables(md).items() if v.type not in REAL_TYPES)


def check_names(md, names) -> None:
    """ParameterError, one line, unless every name is a parameter by the package's names
    (fmu/names.py: angles as <name>_deg, the SI FMUs' size as size)."""
    check_parameter_names(md, names)


def check_values(image: FmuImage, values: dict) -> None:
    """values: parameter name (the package's) -> the values it will take. Raises
    ParameterError with the first refused value's reason."""
    md = image.model_description()
    check_names(md, values)
    integers = set(integer_names(md))
    for name, options in values.items():
        for value in options:
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                raise ParameterError(f"{name} = {value!r} is not a number")
            if name in integers and not (math.isfinite(value) and float(value).is_integer()):
                kind = parameter_variables(md)[name].type.lower()
                raise ParameterError(f"{name} = {format_number(value)} is not a whole number "
                                     f"({name} is {kind}: it takes whole numbers only)")
    instance = Instance(image, name="tribo_check")
    try:
        for name, options in values.items():
            for value in dict.fromkeys(options):
                try:
                    instance.set_parameters(to_fmu(md, {name: value}))
                except FMICallException:
                    errors = instance.errors()
                    raise ParameterError(refusal_message(md, name, value, _reason(errors[-1]))
                                         if errors else f"{name} = {format_number(value)}: "
                                                        f"refused by the FMU") from None
    finally:
        instance.free()


def _reason(message: str) -> str:
    """The FMU's message without the FMI function's name it starts with."""
    head, sep, rest = message.partition(": ")
    return rest if sep and head.startswith("fmi") else message


"""The package's names for the FMUs' parameters and outputs: one unit per kind of quantity.

The FMUs are SI: their angles are in radians (`beta`, `tilt`, `phi0`, `drop_angle`, the
output `phi`), and the SI FMUs give a particle's size as its semi-major axis
`semi_major_axis` (a). What a user of the package types and reads is

    <name>_deg   every angle, in degrees (beta_deg, tilt_deg, phi0_deg, drop_angle_deg,
                 phi_deg): each FMU variable whose unit is rad
    size         the particle's size, its long diameter 2a in m (the SI FMUs)

and everything else under the FMU's own name and unit. The FMU's names of those
quantities are refused, in one line naming the package's, so that `tilt=30` (meant in
degrees) is never read as 30 rad. The conversion happens here only, at the FMU's door:
results files, tables and figures show the package's names.

Values are echoed as they were given (`format_number`): -0.3, not -0.29999999999999999.
"""

import math
import re
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable

from .charge_models import removed_message
from .image import per_description
from .instance import ERROR, PARAMETER_CAUSALITIES

DEGREES = "_deg"
SIZE, SEMI_MAJOR_AXIS = "size", "semi_major_axis"


class ParameterError(ValueError):
    """A parameter name or value the FMU does not take (the message, one line, says why)."""


@dataclass(frozen=True)
class Renamed:
    """A quantity the package names and measures otherwise than the FMU."""

    name: str  # the package's
    fmu_name: str
    unit: str  # the package's
    to_fmu: Callable[[float], float]
    from_fmu: Callable[[float], float]
    how: str  # how the two relate, for messages


# as math.radians and math.degrees compute them, bit for bit, for numpy arrays too
_RAD_PER_DEG, _DEG_PER_RAD = math.pi / 180.0, 180.0 / math.pi


def _radians(x):
    return x * _RAD_PER_DEG


def _degrees(x):
    return x * _DEG_PER_RAD


def _half(x):
    return 0.5 * x


def _twice(x):
    return 2.0 * x


# the tables below are made once per model description (image.per_description)
@per_description
def renamed(md) -> MappingProxyType:
    """The package name -> Renamed of each FMU variable the package names otherwise."""
    out = {}
    for v in md.modelVariables:
        unit = v.unit or (v.declaredType.unit if v.declaredType is not None else None)
        if unit == "rad":
            out[v.name + DEGREES] = Renamed(v.name + DEGREES, v.name, "deg", _radians, _degrees,
                                            f"in degrees; the FMU's {v.name} is in radians")
        elif v.name == SEMI_MAJOR_AXIS:
            out[SIZE] = Renamed(SIZE, SEMI_MAJOR_AXIS, "m", _half, _twice,
                                "the long diameter 2a in m; the FMU's semi_major_axis is a = size / 2")
    return MappingProxyType(out)


@per_description
def _by_fmu_name(md) -> MappingProxyType:
    return MappingProxyType({r.fmu_name: r for r in renamed(md).values()})


def package_name(md, fmu_name: str) -> str:
    """The package's name of an FMU variable."""
    r = _by_fmu_name(md).get(fmu_name)
    return r.name if r else fmu_name


def parameter_names(md) -> list[str]:
    """The parameters a user gives the package, by the package's names, in the FMU's order."""
    return list(_parameter_names(md))


@per_description
def _parameter_names(md) -> tuple[str, ...]:
    return tuple(package_name(md, v.name) for v in md.modelVariables
                 if v.causality in PARAMETER_CAUSALITIES)


@per_description
def _parameter_set(md) -> frozenset:
    return frozenset(_parameter_names(md))


@per_description
def _variable_names(md) -> frozenset:
    return frozenset(v.name for v in md.modelVariables)


def output_names(md, scalar_only: bool = True) -> list[str]:
    """The FMU's outputs by the package's names (scalar ones unless told otherwise)."""
    return [package_name(md, v.name) for v in md.modelVariables
            if v.causality == "output" and not (scalar_only and v.dimensions)]


def format_number(value) -> str:
    """A number as a person types it: the shortest text that reads back as the same float
    (45, -0.3, 1e-05), or an int as it is."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, int):
        return str(value)
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _refusal(md, name: str, kind: str) -> ParameterError:
    """A name of the FMU's that the package gives another name: say which."""
    r = _by_fmu_name(md)[name]
    example = f"{r.name}=30" if r.unit == "deg" else f"{r.name}=1e-3"
    return ParameterError(f"{name}: the package takes this {kind} as {r.name} ({r.how}), "
                          f"e.g. {example}")


def check_parameter_names(md, names) -> None:
    """ParameterError, one line, unless every name is a parameter by the package's names
    (a removed one, such as charge_model, told with what replaces it)."""
    for name in names:
        message = removed_message(md, name)
        if message:
            raise ParameterError(message)
    known, by_fmu = _parameter_set(md), _by_fmu_name(md)  # once, not per name
    fmu_only = [n for n in names if n in by_fmu]
    if fmu_only:
        raise _refusal(md, fmu_only[0], "parameter")
    unknown = [n for n in names if n not in known]
    if unknown:
        raise ParameterError(f"not parameters of the FMU: {', '.join(unknown)} "
                             f"(its parameters: {', '.join(_parameter_names(md))})")


def to_fmu(md, params: dict) -> dict:
    """The parameters by the FMU's names and in its units."""
    names = tuple(params)
    plans = _to_fmu_plans(md)
    plan = plans.get(names)
    if plan is None:
        check_parameter_names(md, names)
        table = renamed(md)
        plan = plans[names] = tuple((table[n].fmu_name, table[n].to_fmu) if n in table
                                    else (n, None) for n in names)
    return {fmu_name: value if convert is None else convert(float(value))
            for (fmu_name, convert), value in zip(plan, params.values())}


@per_description
def _to_fmu_plans(md) -> dict:
    """to_fmu's names (a tuple, checked) -> each one's (FMU name, conversion or None): a
    sweep's runs set the same names, each run's checked and looked up once, not per run
    (docs/populations.md, "Benchmark")."""
    return {}


def fmu_outputs(md, names) -> list[str]:
    """Output names (the package's) as the FMU's; ParameterError for an FMU name the
    package renames or an unknown output."""
    by_fmu, table, variables = _by_fmu_name(md), renamed(md), _variable_names(md)
    out = []
    for name in names:
        if name in by_fmu:
            raise _refusal(md, name, "output")
        fmu_name = table[name].fmu_name if name in table else name
        if fmu_name not in variables:
            raise ParameterError(f"{name!r} is not a variable of the FMU (its outputs: "
                                 f"{', '.join(output_names(md))})")
        out.append(fmu_name)
    return out


def from_fmu_column(md, fmu_name: str, values):
    """(the package's name, the values in the package's unit) of an FMU variable's values
    (a number or a numpy array)."""
    r = _by_fmu_name(md).get(fmu_name)
    return (fmu_name, values) if r is None else (r.name, r.from_fmu(values))


def start_value(md, name: str) -> float | None:
    """A parameter's start value in the FMU's description, in the package's unit."""
    r = renamed(md).get(name)
    fmu_name = r.fmu_name if r else name
    for v in md.modelVariables:
        if v.name == fmu_name and v.start is not None:
            value = float(v.start)
            return r.from_fmu(value) if r else value
    return None


_INVALID = re.compile(r"^(?P<name>\w+) = (?P<value>\S+) is invalid: the valid range is "
                      r"(?P<kind>an? \w+ with )?(?P<lo>\S+) (?P<op1><=?) (?P=name) "
                      r"(?P<op2><=?) (?P<hi>\S+)(?P<rest>.*)$")


def refusal_message(md, name: str, value, message: str) -> str:
    """The FMU's refusal of a value, told in the package's name and unit with the value as
    given: "tilt_deg = 95 is invalid: the valid range is 0 <= tilt_deg < 90"."""
    m = _INVALID.match(message)
    if not m:
        return f"{name} = {format_number(value)}: {message}"
    r = renamed(md).get(name)
    lo, hi = m["lo"], m["hi"]
    if r is not None:
        v = {x.name: x for x in md.modelVariables}[r.fmu_name]

        def bound(text, limit):
            try:
                float(text)
            except ValueError:
                return text
            return f"{r.from_fmu(float(limit)):.6g}" if limit is not None else text

        lo, hi = bound(lo, v.min), bound(hi, v.max)
    return (f"{name} = {format_number(value)} is invalid: the valid range is {m['kind'] or ''}"
            f"{lo} {m['op1']} {name} {m['op2']} {hi}{m['rest']}")


_FMU_CALL = re.compile(r"^fmi[23]\w+: ")
_ASSIGNMENT = re.compile(r"\b(?P<name>\w+) = (?P<value>[-+0-9.eE]+|INF|-INF)(?P<unit> (?:rad|m)\b)?")


def in_package_terms(md, message: str) -> str:
    """An FMU's message with the FMI function's name dropped and its values of renamed
    variables told in the package's names and units ("semi_major_axis = 5e-06 m" becomes
    "size = 1e-05 m")."""
    by_fmu = _by_fmu_name(md)

    def swap(m):
        r = by_fmu.get(m["name"])
        if r is None:
            return m.group(0)
        try:
            value = r.from_fmu(float(m["value"]))
        except ValueError:
            return m.group(0)
        return f"{r.name} = {value:.6g}" + (f" {r.unit}" if m["unit"] else "")

    return _ASSIGNMENT.sub(swap, _FMU_CALL.sub("", message.strip()))


def failure(md, messages, error) -> str:
    """Why a run failed, in the package's terms: the last error the FMU logged (`messages`,
    an Instance's), else the exception's own text."""
    errors = [m for status, _, m in messages if status >= ERROR]
    return in_package_terms(md, errors[-1]) if errors else str(error)

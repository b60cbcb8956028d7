"""What a measured charge can be: no grain in air holds more than its own limit, the
Paschen limit of the sphere of its area spread over its surface (docs/model.md section 8e),
sigma_P(R_s) A_s for an impact's grain (its charge and the charge it carried before) and
sigma_P(R_s) A_s / m for the grains of a chute run (the stream's q/m is a mean of theirs);
the larger of a metal wall's and an insulating one's, a bound whatever the wall. A charge above that is a mistake in the file, most often its
unit: the files are in C and C/kg, and charges measured in pC typed as they are read
(-1.2 for -1.2 pC) would be fitted as -1.2 C, decades off. The message says which unit
would make the value one a grain can hold."""

import math

from ..paschen import grain_limit
from .data import DataError
from .observables import spheroid_mass

# the units a charge, and a charge-to-mass ratio, are measured in, the largest first
CHARGE_UNITS = (("mC", 1e-3), ("µC", 1e-6), ("nC", 1e-9), ("pC", 1e-12), ("fC", 1e-15))
RATIO_UNITS = (("mC/kg", 1e-3), ("µC/kg", 1e-6), ("nC/kg", 1e-9))


def most_held(size: float, epsilon: float) -> float:
    """The most charge (C) a grain holds in air, on either kind of wall (section 8e)."""
    return max(grain_limit(size, epsilon, conducting=c) for c in (True, False))


def check_charges(points) -> None:
    """DataError, naming the file, row and column, for a point whose charge (impacts:
    `charge` and `initial_charge`; chute runs: `q_per_m`) is above what its grains can
    hold in air."""
    for p in points:
        if p.kind == "impact":
            most = most_held(p.runs[0]["size"], p.runs[0]["epsilon"])
            checks = (("charge", p.measured), ("initial_charge", p.initial_charge))
            unit, units = "C", CHARGE_UNITS
            grain = (f"a grain of {p.runs[0]['size']:g} m, epsilon {p.runs[0]['epsilon']:g}, "
                     f"holds at most")
        else:
            most = max(most_held(r["size"], r["epsilon"])
                       / spheroid_mass(r["size"], r["epsilon"], r["density"]) for r in p.runs)
            checks = (("q_per_m", p.measured),)
            unit, units = "C/kg", RATIO_UNITS
            grain = "the run's grains hold at most"
        for name, value in checks:
            if abs(value) > most:
                raise DataError(f"{p.label}, {name} = {value:g} {unit}: {grain} {most:.3g} "
                                f"{unit} in air (its Paschen limit){_unit_hint(value, most, unit, units)}")


def _unit_hint(value: float, most: float, unit: str, units) -> str:
    """Which unit the value may have been typed in: the largest that makes it at most a
    hundredth of the most. A grain charged to its limit all over is not met: its charged
    area is about a hundredth of its surface even after hundreds of impacts (0.6 % and 1.1 %
    on a feeder, docs/dem.md), and its patches keep their own limits, not the grain's; a
    hundredth tells -0.5 typed in µC/kg from the mC/kg that the most alone would take for
    the smallest grains of a run."""
    for name, factor in units:
        if math.isfinite(value) and abs(value) * factor <= most / 100:
            return (f"; the file's values are in {unit}: typed in {name}? {value:g} {name} is "
                    f"{value * factor:.3g} {unit}")
    return ""

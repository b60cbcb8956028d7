"""What one run is, and the key that identifies it.

A run is the FMU's parameters (those the study or the sweep sets; the rest keep the
FMU's start values, which the FMU's hash in the key pins down), the horizon t_end and the
interval at which the outputs are recorded. Its key is a hash of those and of the FMU's bytes:
the same key means the same numbers, so a finished run can be skipped on resume, and
a rebuilt FMU with other behaviour is not mistaken for the old one.
"""

import hashlib
import json
from dataclasses import dataclass, field

# Parameters given as decimals (e.g. from a linspace) are rounded to this many decimal
# places, so that 0.30000000000000004 and 0.3 are the same run.
DECIMALS = 12
# The most runs one job may have (a sweep's grid, a population, a map's episodes, a line's
# grains), and the most values one list a:b:n may give: a million runs of a tenth of a
# second are a day of one core, and their specs take about 1 GB of memory. A larger number is
# a typing mistake more often than a plan: refused in one line before any memory is taken.
MAX_RUNS = 1_000_000


def check_count(n: int, what: str) -> None:
    """ValueError, one line naming the number and the bound, for more than MAX_RUNS."""
    if n > MAX_RUNS:
        raise ValueError(f"{what}: {n} is more than the {MAX_RUNS} one job may have "
                         f"(split it into several)")


@dataclass(frozen=True)
class RunSpec:
    """One run: FMU parameters (name -> value), the horizon, the recording interval."""

    params: dict = field(hash=False)
    t_end: float
    record_interval: float = 1.0

    def as_json(self) -> str:
        return json.dumps({"params": self.params, "t_end": self.t_end,
                           "record_interval": self.record_interval}, sort_keys=True)


def normalise_values(params: dict, integer_names, exact_names=("Omega0",)) -> dict:
    """Integers (integer_names: the FMU's, parameters.integer_names) as int, the exact
    names (in rad/tau, no decimal numbers: multiples of pi) as they are, everything else
    (angles in degrees too) as a float rounded to DECIMALS places."""
    out = {}
    for name, value in params.items():
        if name in integer_names:
            if not float(value).is_integer():
                raise ValueError(f"{name} = {value:g} is not a whole number ({name} takes whole numbers only)")
            out[name] = int(value)
        elif name in exact_names:
            out[name] = float(value)
        else:
            out[name] = round(float(value), DECIMALS)
    return out


def run_key(spec: RunSpec, fmu_sha256: str) -> str:
    """A stable key of the run: 16 hex digits of the SHA-256 of the spec and the FMU. The
    text hashed is that of {"fmu": ..., "run": json.loads(spec.as_json())} with sorted keys,
    made in one json.dumps: JSON's text of a spec reads back as the same values (Python's
    floats in their shortest round-trip form, text keys), so that reading it back and
    writing it again gave the same text (tests/python/test_study_sweep.py)."""
    text = json.dumps({"fmu": fmu_sha256, "run": {"params": spec.params, "t_end": spec.t_end,
                                                  "record_interval": spec.record_interval}},
                      sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]

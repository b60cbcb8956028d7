"""What one run is, and the key that identifies it.

A run is the FMU's parameters (those the study or the sweep sets; the rest keep the
FMU's start values, which the FMU's hash in the key pins down), the horizon t_end and the
interval at which the outputs are recorded. Its key is a hash of those and of the FMU's bytes:
the same key means the same numbers, so a finished run can be skipped on resume, and
a rebuilt FMU with other behaviour is not mistaken for the old one.
"""

import hashlib
import json
import math
from dataclasses import dataclass, field

# docs/model.md section 7 (the paper's set-up), with CVODE instead of the paper's fixed step
# (faster at equal error, see docs/work_precision.md) at the FMU's default tolerances (rtol,
# atol: not set here), and the normal dashpot on the contact point (docs/model.md section 3).
# epsilon, mu and nu are set per run.
PAPER_SETUP = {
    "Gamma": 0.001,
    "beta": 45 * (math.pi / 180.0),  # rad
    "tau0": 1.0,
    "Sigma0": 0.01,
    "eta": 0.1,
    "tau_r": 1.0,  # tau_r = tau0
    "n_segments": 2000,
    "drop_speed": 0.025,
    "charge_model": 3,  # both charge models
    "integrator": 1,  # CVODE (Adams)
    "damping_point": 0,
}

FRICTION_CASES = {"low": 0.1, "high": 1.0}  # mu = nu
# damping_point: the velocity the normal dashpot opposes (docs/model.md section 3)
DASHPOTS = {0: "contact point", 1: "centre"}


def dashpot_name(damping_point: int) -> str:
    return DASHPOTS.get(damping_point, f"damping_point = {damping_point}")

# Parameters given as decimals (e.g. from a linspace) are rounded to this many decimal
# places, so that 0.30000000000000004 and 0.3 are the same run.
DECIMALS = 12


@dataclass(frozen=True)
class RunSpec:
    """One run: FMU parameters (name -> value), the horizon, the recording interval."""

    params: dict = field(hash=False)
    t_end: float
    record_interval: float = 1.0

    def as_json(self) -> str:
        return json.dumps({"params": self.params, "t_end": self.t_end,
                           "record_interval": self.record_interval}, sort_keys=True)


def paper_spec(epsilon: float, friction: str, t_end: float, record_interval: float = 1.0,
               **overrides) -> RunSpec:
    """The paper's run at a roundness and friction case ("low" or "high")."""
    mu = FRICTION_CASES[friction]
    params = dict(PAPER_SETUP, epsilon=epsilon, mu=mu, nu=mu)
    params.update(overrides)
    return RunSpec(normalise_values(params), float(t_end), float(record_interval))


def normalise_values(params: dict, integer_names=("n_segments", "charge_model", "integrator",
                                                  "damping_point"),
                     exact_names=("beta", "phi0", "Omega0")) -> dict:
    """Integers as int, angles (in rad: no decimal numbers) as they are, everything else as
    a float rounded to DECIMALS places."""
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
    """A stable key of the run: 16 hex digits of the SHA-256 of the spec and the FMU."""
    text = json.dumps({"fmu": fmu_sha256, "run": json.loads(spec.as_json())}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]

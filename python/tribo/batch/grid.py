"""The runs of a parameter sweep: every combination of the values given for each swept
parameter, over a base set-up.

The paper's base (docs/model.md section 7, CVODE, epsilon 0.5, mu = nu = 0.1, the FMU's
default tolerances) or the FMU's start values; as in the paper, nu follows mu and tau_r
follows tau0 unless they are swept too (tie=False: they don't).
"""

import itertools

import numpy as np

from .specs import RunSpec, normalise_values

# docs/model.md section 7 (the paper's set-up), with CVODE instead of the paper's fixed step
# (faster at equal error, see docs/work_precision.md) at the FMU's default tolerances (rtol,
# atol: not set here), with every charge model (the FMU's default switches), and the normal
# dashpot on the contact point (docs/model.md section 3).
# The study sets epsilon, mu and nu per run; a sweep's paper base takes PAPER_BASE's.
PAPER_SETUP = {
    "Gamma": 0.001,
    "beta_deg": 45.0,  # the FMU's beta is pi/4 rad (fmu/names.py)
    "tau0": 1.0,
    "Sigma0": 0.01,
    "eta": 0.1,
    "tau_r": 1.0,  # tau_r = tau0
    "n_segments": 2000,
    "drop_speed": 0.025,
    "integrator": 1,  # CVODE (Adams)
    "damping_point": 0,
}
PAPER_BASE = dict(PAPER_SETUP, epsilon=0.5, mu=0.1, nu=0.1)
TIES = {"nu": "mu", "tau_r": "tau0"}  # follower: leader (the paper's mu = nu, tau_r = tau0)


def parse_values(text: str) -> list[float]:
    """'a:b:n' (n values from a to b), 'v1,v2,...' or 'v'; ValueError saying why not."""
    try:
        if ":" in text:
            a, b, n = text.split(":")
            if int(n) < 1:
                raise ValueError("need at least one value")
            return list(np.linspace(float(a), float(b), int(n)))
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError as e:
        raise ValueError(f"{e} (expected a:b:n, v1,v2,... or v)") from None
    if not values:
        raise ValueError("no values (expected a:b:n, v1,v2,... or v)")
    return values


def parse_param(text: str) -> tuple[str, list[float]]:
    """'NAME=VALUES' -> (name, values)."""
    name, sep, values = text.partition("=")
    if not sep or not name.strip():
        raise ValueError(f"--param {text!r}: expected NAME=VALUES")
    try:
        return name.strip(), parse_values(values)
    except ValueError as e:
        raise ValueError(f"--param {text}: {e}") from None


def build_specs(swept: list[tuple[str, list[float]]], base: dict, integer_names, t_end: float,
                record_interval: float, tie: bool = True) -> list[RunSpec]:
    """Every combination of the swept values (the first parameter varies slowest)."""
    names = [n for n, _ in swept]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ValueError(f"given more than once: {', '.join(twice)}")
    specs = []
    for combo in itertools.product(*(values for _, values in swept)):
        params = dict(base, **dict(zip(names, combo)))
        if tie:
            for follower, leader in TIES.items():
                if leader in names and follower not in names:
                    params[follower] = params[leader]
        specs.append(RunSpec(normalise_values(params, integer_names), float(t_end),
                             float(record_interval)))
    return specs


def values_of(specs: list[RunSpec]) -> dict:
    """Parameter name -> the distinct values the runs give it."""
    out = {}
    for s in specs:
        for name, value in s.params.items():
            out.setdefault(name, {})[value] = None
    return {name: list(values) for name, values in out.items()}

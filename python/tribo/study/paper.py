"""The paper's runs (docs/model.md section 7): its two friction cases, the normal dashpots
the study compares, and the run at a roundness and a friction case on the paper's set-up
(batch.grid.PAPER_SETUP)."""

from ..batch.grid import PAPER_SETUP
from ..batch.specs import RunSpec, normalise_values

FRICTION_CASES = {"low": 0.1, "high": 1.0}  # mu = nu
FRICTION_TITLES = {"low": "low (mu = nu = 0.1)", "high": "high (mu = nu = 1.0)"}
# damping_point: the velocity the normal dashpot opposes (docs/model.md section 3)
DASHPOTS = {0: "contact point", 1: "centre"}


def dashpot_name(damping_point: int) -> str:
    return DASHPOTS.get(damping_point, f"damping_point = {damping_point}")


def paper_spec(epsilon: float, friction: str, t_end: float, record_interval: float = 1.0, *,
               integer_names, **overrides) -> RunSpec:
    """The paper's run at a roundness and friction case ("low" or "high"). integer_names:
    the FMU's parameters that take whole numbers (fmu.parameters.integer_names)."""
    mu = FRICTION_CASES[friction]
    params = dict(PAPER_SETUP, epsilon=epsilon, mu=mu, nu=mu)
    params.update(overrides)
    return RunSpec(normalise_values(params, integer_names), float(t_end), float(record_interval))

"""The columns of a calibration's measured files (data.py reads and checks them): each
one's unit and meaning, whether it is required, its range and default. Constants and the
text that lists them alone, so that the command's --help is made without loading the job's
libraries."""

import math

from ..populations.feed_variables import FEED_UNITS, FEED_VARIABLES

# name -> (unit and meaning, required, low, high, low end open, default)
IMPACT_COLUMNS = {
    "speed": ("m/s, the impact speed", True, 0.0, 1e3, True, None),
    "angle_deg": ("degrees to the wall, 90 head-on", True, 0.0, 90.0, True, None),
    "size": ("m, the grain's long diameter 2a", True, 0.0, 1.0, True, None),
    "epsilon": ("b/a, the grain's roundness", True, 1e-3, 1.0, False, None),
    "charge": ("C, the charge the impact gave the grain (Delta q)", True, -math.inf, math.inf, False, None),
    "phi0_deg": ("degrees, the long axis to the wall", False, -180.0, 180.0, False, 0.0),
    "initial_charge": ("C, the grain's charge before the impact", False, -math.inf, math.inf, False, 0.0),
    "charge_std": ("C, the standard deviation of charge", False, 0.0, math.inf, True, None),
    "impacts": ("impacts on fresh spots the charge was gathered over", False, 1.0, 1e4, False, 1.0),
}
DEFAULT_GRAINS = 50
CHUTE_COLUMNS = {
    "chute_length": ("m, the chute's length", True, 0.0, 100.0, True, None),
    "tilt_deg": ("degrees from the horizontal", True, 0.0, 90.0, False, None),
    "q_per_m": ("C/kg, the mass-weighted mean q/m of the grains that left the chute", True,
                -math.inf, math.inf, False, None),
    "q_per_m_std": ("C/kg, the standard deviation of q_per_m", False, 0.0, math.inf, True, None),
    "grains": ("grains the model draws from the feed", False, 1.0, 1e5, False, float(DEFAULT_GRAINS)),
    "seed": ("the draw's seed", False, 0.0, 2.0 ** 63, False, 0.0),
    "t_end": ("s, the horizon of each grain", False, 0.0, 1e3, True, 5.0),
}
# the feed's columns: a number or a distribution text each (populations/distributions.py)
FEED_COLUMNS = {name: FEED_UNITS[name] for name in FEED_VARIABLES}
WHOLE = ("impacts", "grains", "seed")


def columns_text(kind: str) -> str:
    """The columns of a kind of file, for messages and --help."""
    columns = IMPACT_COLUMNS if kind == "impacts" else dict(CHUTE_COLUMNS, **{
        n: (u, False) for n, u in FEED_COLUMNS.items()})
    required = [n for n, c in columns.items() if c[1]]
    optional = [n for n, c in columns.items() if not c[1]]
    return f"{', '.join(required)}; optional {', '.join(optional)}"

"""The longest time the model integrates, in its unit t* (src/chute/tribo.h, TRIBO_TIME_MAX:
beyond it a step's end is not resolved finely enough and the FMU refuses the step), and the
checks of a job's horizon against it, made before any run: a horizon the FMU would refuse
at the first step of every run is one line, not as many failed runs."""

import math

TIME_MAX = 1e12  # t*: TRIBO_TIME_MAX of src/chute/tribo.h


def check_limit(limit: float, what: str, error=ValueError) -> None:
    """A horizon in t* (`what` names it): positive and at most TIME_MAX."""
    if not (isinstance(limit, (int, float)) and math.isfinite(limit) and 0 < limit <= TIME_MAX):
        raise error(f"{what} = {limit!r}: a positive number of t*, at most {TIME_MAX:g} (the "
                    f"model's time is not resolved beyond)")


def check_horizon(t_end: float, t_star: float, what: str, error=ValueError) -> None:
    """A horizon in s (`what` names it) of a run whose unit of time is t_star s."""
    if t_end > TIME_MAX * t_star:
        raise error(f"{what} = {t_end:g} s: at most {TIME_MAX * t_star:.3g} s here, "
                    f"{TIME_MAX:g} times the model's unit of time t* = {t_star:.3g} s of its "
                    f"quickest grain (the model's time is not resolved beyond)")

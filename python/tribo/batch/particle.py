"""One particle's run of the FMU: parameters in; the recorded time series, each segment's
charge at the end (from an FMI 3.0 FMU, whose arrays hold them) and the summary row out.

Each run is an instance of its own on the process's loaded copy of the FMU (unpacked and
loaded once per process and FMU, fmu/library.py): no state is kept between runs but the
loaded library, and two runs in threads of one Dask worker never share an instance. The
FMU's log messages are kept per run, not printed: the summary counts the warnings
(assumption_warnings) and a failed run quotes the errors.

A run that needs only the end (record_interval None: a population's particle, a line's
grain) is one doStep to the horizon (continued where the FMU's work limit cuts it, and
ending where the FMU ends the run): the committed integration does not depend on the
communication points (fmu/README.md, "Work limit"; the CVODE integrator's steps are its
own, the state at an asked time comes from its dense output), so its end is the end of
the same run recorded at any interval, bit for bit, without the cost of the points.
"""

import time
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..fmu import FmuImage
from ..fmu.charge_models import MEAN_CHARGE_PREFIX, mean_charges
from ..fmu.names import fmu_outputs, from_fmu_column
# the run itself (numpy and fmpy only), and what the package has always imported from here
from .run import End, RunResult, check_horizon, run_to_end, run_values  # noqa: F401
from .specs import RunSpec
from .summary import END_OUTPUTS, MOTION_CLASSES, summarize


def recorded(models, md=None) -> list[str]:
    """The outputs the study records at every communication point (its summary and figures
    use them), with the mean charge Q_<model> of each of `models`, and how the run ended
    (END_OUTPUTS: those the FMU's description `md` has, all without one)."""
    names = None if md is None else {v.name for v in md.modelVariables}
    return (["X", "Y", "phi_deg", "U", "V", "Omega", "delta_y", "in_contact"]
            + [MEAN_CHARGE_PREFIX + m for m in models]
            + ["contact_fraction", "turns", "motion_class"]
            + [f"fraction_{m}" for m in MOTION_CLASSES] + ["assumption_warnings"]
            + [n for n in END_OUTPUTS if names is None or n in names])

# more recorded points than this is a mistake in the horizon or the interval, not a run
MAX_POINTS = 10_000_000


@dataclass
class Recording:
    series: pd.DataFrame  # "time", then the outputs at every communication point reached
    segments: pd.DataFrame | None  # one row per segment at the end, a column per charge model
    messages: list  # (status, category, message) as the FMU logged them


def communication_points(t_end: float, interval: float) -> np.ndarray:
    """0, interval, 2 interval, ..., t_end. ValueError (saying why) for a horizon or an
    interval that is not positive and finite, or not a whole number of intervals."""
    check_horizon(t_end)
    if not (np.isfinite(interval) and interval > 0):
        raise ValueError(f"the record interval must be a positive number, got {interval:g}")
    n = int(round(t_end / interval))
    if n < 1 or abs(n * interval - t_end) > 1e-9 * max(1.0, t_end):
        raise ValueError(f"t_end = {t_end:g} is not a whole number of record intervals ({interval:g})")
    if n + 1 > MAX_POINTS:
        raise ValueError(f"t_end / record interval = {n:.3g} points to record, more than "
                         f"{MAX_POINTS}: take a longer record interval")
    times = np.arange(n + 1) * interval
    times[-1] = t_end
    return times


def simulate(image: FmuImage, params: dict, t_end: float, record_interval: float | None = 1.0,
             outputs=None, segments: bool = False) -> Recording:
    """Run the FMU from 0 to t_end with `params`, recording `outputs` (default: the study's,
    `recorded`) every record_interval, or (record_interval None) only at the end: one
    row (and, if `segments` and the FMU has the arrays, each segment's charge at the end).
    Parameters and outputs by the package's names and in its units (fmu/names.py: angles
    in degrees). A run the FMU ends early is recorded up to where it ended."""
    times = None if record_interval is None else communication_points(t_end, record_interval)
    md = image.model_description()
    outputs = recorded(mean_charges(md), md) if outputs is None else list(outputs)
    fmu_names = fmu_outputs(md, outputs)
    reached, data, arrays, messages = run_values(image, params, t_end, times, fmu_names, segments)
    series = pd.DataFrame({name: from_fmu_column(md, fmu_name, data[:, i])[1]
                           for i, (name, fmu_name) in enumerate(zip(outputs, fmu_names))},
                          columns=outputs)
    series.insert(0, "time", reached)
    return Recording(series, pd.DataFrame(arrays) if arrays else None, messages)


def run_fmu(image: FmuImage, spec: RunSpec) -> RunResult:
    """The study's run: the `recorded` series, the segments' charges at the end (FMI 3.0)
    and the summary row."""
    wall0, cpu0 = time.perf_counter(), time.thread_time()
    recording = simulate(image, spec.params, spec.t_end, spec.record_interval, segments=True)
    row = summarize(recording.series, spec.t_end, mean_charges(image.model_description()))
    # thread time: the run executes in this thread; a Dask worker's other threads
    # (communication, heartbeats) are not the run's cost
    row.update(cpu_s=time.thread_time() - cpu0, wall_s=time.perf_counter() - wall0)
    return RunResult(row, recording.series, recording.segments)

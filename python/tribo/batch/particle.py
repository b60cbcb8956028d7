"""One particle's run of the FMU: parameters in; the recorded time series, each segment's
charge at the end (from an FMI 3.0 FMU, whose arrays hold them) and the summary row out.

Each run unpacks the FMU's bytes into a private temporary directory and removes it
afterwards: a few milliseconds against runs of a tenth of a second and more, no state
kept between runs, and the same on any Dask worker. The FMU's log messages are kept per
run, not printed: the summary counts the warnings (assumption_warnings) and a failed run
quotes the errors.
"""

import time
from dataclasses import dataclass

import numpy as np
import pandas as pd
from fmpy.fmi1 import FMICallException

from ..fmu import ERROR, FmuImage, Instance, record, unpacked
from ..fmu.charge_models import MEAN_CHARGE_PREFIX, mean_charges, segment_arrays
from ..fmu.names import fmu_outputs, from_fmu_column, in_package_terms, to_fmu
from .specs import RunSpec
from .summary import MOTION_CLASSES, summarize


def recorded(models) -> list[str]:
    """The outputs the study records at every communication point (its summary and figures
    use them), with the mean charge Q_<model> of each of `models`."""
    return (["X", "Y", "phi_deg", "U", "V", "Omega", "delta_y", "in_contact"]
            + [MEAN_CHARGE_PREFIX + m for m in models]
            + ["contact_fraction", "turns", "motion_class"]
            + [f"fraction_{m}" for m in MOTION_CLASSES] + ["assumption_warnings"])

# more recorded points than this is a mistake in the horizon or the interval, not a run
MAX_POINTS = 10_000_000


@dataclass
class Recording:
    series: pd.DataFrame  # "time", then the outputs at every communication point reached
    segments: pd.DataFrame | None  # one row per segment at the end, a column per charge model
    messages: list  # (status, category, message) as the FMU logged them


@dataclass
class RunResult:
    row: dict  # the summary (summary.summarize) plus cpu_s and wall_s
    series: pd.DataFrame
    segments: pd.DataFrame | None = None


def communication_points(t_end: float, interval: float) -> np.ndarray:
    """0, interval, 2 interval, ..., t_end. ValueError (saying why) for a horizon or an
    interval that is not positive and finite, or not a whole number of intervals."""
    for name, value in (("the horizon t_end", t_end), ("the record interval", interval)):
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive number, got {value:g}")
    n = int(round(t_end / interval))
    if n < 1 or abs(n * interval - t_end) > 1e-9 * max(1.0, t_end):
        raise ValueError(f"t_end = {t_end:g} is not a whole number of record intervals ({interval:g})")
    if n + 1 > MAX_POINTS:
        raise ValueError(f"t_end / record interval = {n} points to record, more than {MAX_POINTS}: "
                         f"take a longer record interval")
    times = np.arange(n + 1) * interval
    times[-1] = t_end
    return times


def simulate(image: FmuImage, params: dict, t_end: float, record_interval: float = 1.0,
             outputs=None, segments: bool = False) -> Recording:
    """Run the FMU from 0 to t_end with `params`, recording `outputs` (default: the study's,
    `recorded`) every record_interval (and, if `segments` and the FMU has the arrays, each
    segment's charge at the end). Parameters and outputs by the package's names and in its
    units (fmu/names.py: angles in degrees). A run the FMU ends early is recorded up to
    where it ended."""
    times = communication_points(t_end, record_interval)
    md = image.model_description()
    outputs = recorded(mean_charges(md)) if outputs is None else list(outputs)
    fmu_params, fmu_names = to_fmu(md, params), fmu_outputs(md, outputs)
    with unpacked(image) as fmu_dir:
        instance = Instance(fmu_dir, name="tribo")
        stage = "setting the parameters"
        try:
            instance.set_parameters(fmu_params)
            stage = "initialization"
            instance.init(0.0, t_end)
            stage = "the run"
            reached, data = record(instance, times, fmu_names)
            arrays = {model: instance.get(name) for model, name in segment_arrays(md).items()
                      if segments}
            instance.terminate()
        except FMICallException as e:
            errors = [m for status, _, m in instance.messages if status >= ERROR]
            where = stage if stage != "the run" else f"the step from time {instance.t:g}"
            raise RuntimeError(f"the FMU failed in {where}: "
                               f"{in_package_terms(md, errors[-1]) if errors else e}") from None
        finally:
            instance.free()
    series = pd.DataFrame({name: from_fmu_column(md, fmu_name, data[:, i])[1]
                           for i, (name, fmu_name) in enumerate(zip(outputs, fmu_names))},
                          columns=outputs)
    series.insert(0, "time", reached)
    return Recording(series, pd.DataFrame(arrays) if arrays else None, instance.messages)


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

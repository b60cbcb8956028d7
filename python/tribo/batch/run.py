"""One run of the FMU on an instance of its own: its outputs' values at the times asked
(batch/particle.py makes them a series and a summary) or, for a run that reads only its end
(a population's particle, a line's grain), at the end (`run_to_end`). numpy and fmpy only,
no pandas: a Dask worker process that runs a population's grains imports this and not
pandas, which would cost it a third of a second of CPU before its first grain
(docs/populations.md, "Benchmark").
"""

from __future__ import annotations  # the DataFrames of RunResult are its caller's (pandas)

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from fmpy.fmi1 import FMICallException

from ..fmu import ERROR, FmuImage, Rows, record
from ..fmu.charge_models import segment_arrays
from ..fmu.names import fmu_outputs, from_fmu_column, in_package_terms, to_fmu
from ..fmu.reuse import Instances, instance_for

if TYPE_CHECKING:
    import pandas as pd

WORK_LIMIT = "work_limit"  # the FMUs' parameter bounding one doStep's work


@dataclass
class RunResult:
    row: dict  # the summary (summary.summarize) plus cpu_s and wall_s
    # a DataFrame, or a dict of equally long columns (a line's grain's landings: no DataFrame
    # made per grain); None for a run that reads only its end
    series: pd.DataFrame | dict | None
    segments: pd.DataFrame | None = None


def check_horizon(t_end: float) -> None:
    """ValueError, saying why, for a horizon that is not positive and finite."""
    if not (np.isfinite(t_end) and t_end > 0):
        raise ValueError(f"the horizon t_end must be a positive number, got {t_end:g}")


@dataclass
class End:
    time: float  # where the run ended: t_end, or where the FMU ended it
    values: dict  # output (the package's name) -> its value there (a float, the package's unit)
    messages: list  # (status, category, message) as the FMU logged them


def run_to_end(image: FmuImage, params: dict, t_end: float, outputs,
               instances: Instances | None = None) -> End:
    """simulate(image, params, t_end, None, outputs)'s one row without a DataFrame: for runs
    that read only the end (a population's particle, a line's grain). `instances`: a task's
    (fmu/reuse.py), whose instance the run takes, reset, and leaves to the task's next run."""
    md = image.model_description()
    outputs = list(outputs)
    fmu_names = fmu_outputs(md, outputs)
    reached, data, _, messages = run_values(image, params, t_end, None, fmu_names, False,
                                            instances)
    values = {name: float(from_fmu_column(md, fmu_name, data[0, i])[1])
              for i, (name, fmu_name) in enumerate(zip(outputs, fmu_names))}
    return End(float(reached[0]), values, messages)


def run_values(image: FmuImage, params: dict, t_end: float, times, fmu_names, segments: bool,
               instances: Instances | None = None):
    """One run on an instance of its own (or of `instances`, run_to_end's): (the times
    reached, a row of `fmu_names`' values per time, the segment arrays if `segments`, the
    FMU's messages). `times` None: only the end, one step to t_end."""
    if times is None:
        check_horizon(t_end)
        t_end = float(t_end)  # the time reached is a float, as the recorded times are
    md = image.model_description()
    fmu_params = to_fmu(md, params)
    with instance_for(image, "tribo", instances) as instance:
        if times is None and instance.version == 2 and WORK_LIMIT in instance.variables:
            # an FMI 2.0 step cut by the work limit cannot go on (stepFailed), where FMI 3.0's
            # does: the one step to the end gets the most work the FMU allows unless the
            # caller set the limit (no result depends on it: fmu/README.md, "Work limit")
            fmu_params.setdefault(WORK_LIMIT, int(instance.variables[WORK_LIMIT].max))
        stage = "setting the parameters"
        try:
            instance.set_parameters(fmu_params)
            stage = "initialization"
            instance.initialize(0.0, t_end)
            stage = "the run"
            if times is None:
                rows = Rows(instance, fmu_names, capacity=1)
                instance.step_to(t_end)
                rows.read()
                reached, data = np.array([instance.t]), rows.table()
            else:
                reached, data = record(instance, times, fmu_names)
            arrays = ({model: instance.get(name) for model, name in segment_arrays(md).items()}
                      if segments else {})
            instance.terminate()
        except FMICallException as e:
            errors = [m for status, _, m in instance.messages if status >= ERROR]
            where = stage if stage != "the run" else f"the step from time {instance.t:g}"
            raise RuntimeError(f"the FMU failed in {where}: "
                               f"{in_package_terms(md, errors[-1]) if errors else e}") from None
    return reached, data, arrays, instance.messages

"""One particle of a population down the chute: the SI FMU's outputs its run records and
its results row (`run_particle`; the columns, feed.result_columns). numpy and fmpy only, no
pandas: a Dask worker process that runs a population's grains imports this module (the
task's function is its run_particle) and not pandas, which would cost each worker a third
of a second of CPU before its first grain (docs/populations.md, "Benchmark").
"""

import math
import time

from ..batch.run import RunResult, run_to_end
from ..batch.specs import RunSpec
from ..batch.summary import MOTION_CLASSES
from ..fmu import FmuImage
from ..fmu.image import per_description
from ..fmu.charge_models import charge_models, per_model
from ..fmu.reuse import Instances, shares_instances

# the SI FMU's outputs of each charge model a particle's row holds (charge_<model>, ...)
MODEL_PREFIXES = ("charge_", "charge_to_mass_", "capped_fraction_")
# how a run ended (docs/model.md sections 3c, 9): the SI FMU's tribo.EndReason and the rest;
# a row of an FMU without them holds NaN there
END_COLUMNS = ("end_reason", "at_rest", "rest_time")
END_RUNNING, END_CHUTE_EXIT, END_FIRST_LIFTOFF, END_AT_REST = 0, 1, 2, 3  # tribo.EndReason
# the area the grain's contact patch has charged, m2 (docs/model.md section 8c); NaN in the
# row of an FMU without it, as END_COLUMNS
AREA_COLUMN = "charged_area"


def optional_outputs(md) -> list[str]:
    """END_COLUMNS and AREA_COLUMN that the FMU (its description `md`) outputs."""
    return list(_optional_outputs(md))


@per_description
def _optional_outputs(md) -> tuple:
    # once per description, not a walk over its variables per grain
    names = {v.name for v in md.modelVariables if v.causality == "output"}
    return tuple(c for c in (*END_COLUMNS, AREA_COLUMN) if c in names)


@per_description
def _outputs(md) -> tuple:
    # once per description, not per grain
    return tuple(outputs(charge_models(md), md))


def outputs(models, md=None) -> list[str]:
    """The SI FMU's outputs a particle's run records, for the charge models `models` (and
    how the run ended, where the FMU's description `md` has those outputs)."""
    return (["exited", "exit_time", "u", "v", "omega", "contact_fraction", "impacts",
             "assumption_warnings"] + per_model(MODEL_PREFIXES, models)
            + [f"fraction_{c}" for c in MOTION_CLASSES] + (optional_outputs(md) if md else []))


@shares_instances
def run_particle(image: FmuImage, spec: RunSpec, instances: Instances | None = None) -> RunResult:
    """One particle down the chute: its results row (`result_columns` of the FMU's charge
    models), no series. The row needs only the end: one step to the horizon or the exit
    (batch/particle.py, run_to_end), on an instance of `instances` (fmu/reuse.py: a
    task's, reset between its runs) or of its own."""
    wall0, cpu0 = time.perf_counter(), time.thread_time()
    md = image.model_description()
    end = run_to_end(image, spec.params, spec.t_end, _outputs(md), instances)
    values = end.values
    row = {"time_end": end.time, "exit_speed": math.hypot(values["u"], values["v"])}
    row.update(dict.fromkeys((*END_COLUMNS, AREA_COLUMN), math.nan))
    row.update(values)
    row["exited"] = int(row["exited"])
    for name in ("end_reason", "at_rest"):
        if name in values:
            row[name] = int(row[name])
    row["impacts"] = int(row["impacts"])
    row["assumption_warnings"] = int(row["assumption_warnings"])
    row.update(cpu_s=time.thread_time() - cpu0, wall_s=time.perf_counter() - wall0)
    return RunResult(row, None)

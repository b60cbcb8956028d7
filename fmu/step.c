/* step.c: the co-simulation step. */
#include "instance_private.h"

#include <math.h>

/* Communication points that differ from the instance's time by less than this are the
   same point computed another way (t + h + h ... against t + n h): accepted. */
static double rounding_tolerance(double time) { return 1e-9 * fmax(1.0, fabs(time)); }

fmu_status fmu_do_step(fmu_instance *inst, const char *fn, double current_time, double step,
                       double *reached)
{
    if (!inst)
        return FMU_ERROR;
    *reached = inst->time;
    if (!fmu_lifecycle_allows(inst, fn, FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_STEP)))
        return FMU_ERROR;
    const double tolerance = rounding_tolerance(inst->time);
    if (!isfinite(current_time) || fabs(current_time - inst->time) > tolerance)
        return fmu_error(inst,
                         "%s: currentCommunicationPoint = %.17g is not the FMU's time %.17g "
                         "(they may differ by rounding only, up to %.3g)",
                         fn, current_time, inst->time, tolerance);
    if (!(isfinite(step) && step > 0.0))
        return fmu_error(inst, "%s: communicationStepSize = %.17g is invalid: it must be > 0 and finite",
                         fn, step);
    const double end = current_time + step;
    if (inst->stop_time_defined && end > inst->stop_time + rounding_tolerance(inst->stop_time))
        return fmu_error(inst,
                         "%s: a step from %.17g by %.17g ends at %.17g, after the stop time %.17g "
                         "set at initialization",
                         fn, current_time, step, end, inst->stop_time);

    /* inputs set since the last step hold from this communication point on */
    tribo_model *m = inst->model;
    tribo_status st = tribo_set_inputs(m, inst->inputs);
    if (st == TRIBO_OK) {
        /* the communication point may lie a rounding error before the core's time */
        const double core_end = fmax(end - inst->start_time, tribo_get(m, TRIBO_Q_TIME));
        st = tribo_advance(m, core_end);
    }
    if (st != TRIBO_OK) {
        inst->lifecycle = FMU_LIFECYCLE_FAILED;
        return fmu_error(inst, "%s: the step from %.17g to %.17g failed: %s", fn, current_time, end,
                         tribo_last_error(m));
    }
    inst->time = end;
    *reached = end;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s(currentCommunicationPoint = %.17g, "
            "communicationStepSize = %.17g)", fn, current_time, step);
    return FMU_OK;
}

/* step.c: the co-simulation step. */
#include "instance_private.h"

#include <math.h>

double fmu_rounding_tolerance(double time) { return 1e-9 * fmax(1.0, fabs(time)); }

/* A step the core ended early (tribo_stop_early, for the reason it gives): the instance
   stays at the time reached. */
static fmu_status ended_early(fmu_instance *inst, const char *fn, double end, int *early_return)
{
    const char *why = tribo_last_error(inst->model);
    if (inst->early_return_allowed) {
        *early_return = 1;
        fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s: early return at %.17g before %.17g: %s", fn,
                inst->time, end, why);
        return FMU_OK;
    }
    /* FMI 2.0: stepFailed until terminate, reset or a restored state; FMI 3.0: Step Mode
       goes on from the time reached */
    if (inst->fmi_version == 2)
        inst->lifecycle = FMU_LIFECYCLE_STEP_DISCARDED;
    fmu_log(inst, FMU_DISCARD, FMU_LOG_WARNING,
            "%s: the step to %.17g ended early at %.17g, the last successful time: %s", fn, end,
            inst->time, why);
    return FMU_DISCARD;
}

/* The run ended during the step (model.md §9): the particle left the chute, or lifted off
   where run_end = first_liftoff. */
static fmu_status exited(fmu_instance *inst, const char *fn, double end, int *early_return,
                         int *terminate)
{
    inst->lifecycle = FMU_LIFECYCLE_EXITED;
    *terminate = 1;
    /* FMI 3.0: an early return where the importer allows it; either way the simulation is to
       terminate, at lastSuccessfulTime */
    *early_return = inst->early_return_allowed;
    fmu_log(inst, inst->fmi_version == 2 ? FMU_DISCARD : FMU_OK, FMU_LOG_CALLS,
            "%s: the step to %.17g ends at %.17g, the last successful time: %s", fn, end,
            inst->time, tribo_last_error(inst->model));
    return inst->fmi_version == 2 ? FMU_DISCARD : FMU_OK;
}

fmu_status fmu_do_step(fmu_instance *inst, const char *fn, double current_time, double step,
                       double *reached, int *early_return, int *terminate)
{
    *early_return = 0;
    *terminate = 0;
    if (!inst)
        return FMU_ERROR;
    *reached = inst->time;
    if (inst->lifecycle == FMU_LIFECYCLE_EXITED)
        return fmu_error(inst, "%s: the run is over at t = %.17g (the particle %s): terminate, "
                         "reset or restore a state", fn, inst->time,
                         tribo_get(inst->model, TRIBO_Q_LIFTED_OFF) != 0.0
                             ? "lifted off the plate, run_end = first_liftoff"
                             : "left the chute");
    if (!fmu_lifecycle_allows(inst, fn, FMU_LIFECYCLE_BIT(FMU_LIFECYCLE_STEP)))
        return FMU_ERROR;
    const double tolerance = fmu_rounding_tolerance(inst->time);
    if (!isfinite(current_time) || fabs(current_time - inst->time) > tolerance)
        return fmu_error(inst,
                         "%s: currentCommunicationPoint = %.17g is not the FMU's time %.17g "
                         "(they may differ by rounding only, up to %.3g)",
                         fn, current_time, inst->time, tolerance);
    if (!(isfinite(step) && step > 0.0))
        return fmu_error(inst, "%s: communicationStepSize = %.17g is invalid: it must be > 0 and finite",
                         fn, step);
    const double end = current_time + step;
    if (!(end > current_time) || !isfinite(end))
        return fmu_error(inst,
                         "%s: communicationStepSize = %.17g is lost in the rounding of the time "
                         "%.17g (the step would end where it starts)",
                         fn, step, current_time);
    if (inst->stop_time_defined && end > inst->stop_time + fmu_rounding_tolerance(inst->stop_time))
        return fmu_error(inst,
                         "%s: a step from %.17g by %.17g ends at %.17g, after the stop time %.17g "
                         "set at initialization",
                         fn, current_time, step, end, inst->stop_time);

    /* inputs set since the last step hold from this communication point on (checked when
       set: a refusal here changes nothing) */
    if (fmu_pass_inputs(inst, fn) != FMU_OK)
        return FMU_ERROR;
    tribo_model *m = inst->model;
    /* the FMU's time is the start time plus the core's, in the front end's unit */
    const double unit = fmu_front_time_unit(&inst->derived);
    /* the communication point may lie a rounding error before the core's time */
    const double core_end = fmax((end - inst->start_time) / unit, tribo_get(m, TRIBO_Q_TIME));
    tribo_status st = tribo_advance(m, core_end);
    if (st == TRIBO_INCOMPLETE || st == TRIBO_ENDED) {
        inst->time = inst->start_time + unit * tribo_get(m, TRIBO_Q_TIME);
        *reached = inst->time;
        return st == TRIBO_ENDED ? exited(inst, fn, end, early_return, terminate)
                                 : ended_early(inst, fn, end, early_return);
    }
    if (st != TRIBO_OK) {
        /* a time the core refuses changes nothing; any other failure leaves it broken */
        if (st != TRIBO_ERR_TIME)
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

/* step.c: the co-simulation step. */
#include "instance_private.h"

#include <math.h>

double fmu_rounding_tolerance(double time) { return 1e-9 * fmax(1.0, fabs(time)); }

/* The time a step that stopped early (the work limit, or the run's end) reached: the core's
   as the FMU's time (the start time plus the core's time in the front end's unit, rounded to
   the nearest), kept inside the step: never before the FMU's time, and before `end` where
   the step ended early (at most `end` where the run ended), which the rounding of a large
   time may otherwise reach (from 1e15 the FMU's time moves by 0.125). */
static double reached_time(const fmu_instance *inst, double end, int before_end)
{
    const double unit = fmu_front_time_unit(&inst->derived);
    double t = inst->start_time + unit * fmu_front_core_time(inst->core);
    t = fmin(t, before_end ? nextafter(end, -INFINITY) : end);
    return fmax(t, inst->time);
}

/* A step the core ended early (tribo_stop_early, for the reason it gives): the instance
   stays at the time reached. */
static fmu_status ended_early(fmu_instance *inst, const char *fn, double end, int *early_return)
{
    const char *why = fmu_front_last_error(inst->core);
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

/* The core's run ended during the step: the chute's particle left it, or lifted off where
   run_end = first_liftoff (model.md §9); the separator's grain reached the bins or a plate
   (§10). */
static fmu_status exited(fmu_instance *inst, const char *fn, double end, int *early_return,
                         int *terminate)
{
    if (inst->hold_at_end) {
        /* a master that takes any discarded or terminating step for a failure (libcosim)
           still runs the other FMUs on: the step completes, the outputs stay at the end */
        fmu_log(inst, FMU_OK, FMU_LOG_CALLS,
                "%s: the run ended at %.17g; held there to %.17g (hold_at_end): %s", fn,
                inst->time, end, fmu_front_last_error(inst->core));
        inst->time = end;
        return FMU_OK;
    }
    inst->lifecycle = FMU_LIFECYCLE_EXITED;
    *terminate = 1;
    /* FMI 3.0: an early return where the importer allows it; either way the simulation is to
       terminate, at lastSuccessfulTime */
    *early_return = inst->early_return_allowed;
    fmu_log(inst, inst->fmi_version == 2 ? FMU_DISCARD : FMU_OK, FMU_LOG_CALLS,
            "%s: the step to %.17g ends at %.17g, the last successful time: %s", fn, end,
            inst->time, fmu_front_last_error(inst->core));
    return inst->fmi_version == 2 ? FMU_DISCARD : FMU_OK;
}

/* Whether the core can advance to t, checked before the step changes anything (the core
   refuses these times too, but only after the inputs handed to it have restarted its
   integrator): beyond TRIBO_TIME_MAX, and what the front end knows its core cannot resolve
   (the chute's fixed step: a grid where t / dt reaches 2^45). */
static fmu_status check_core_time(fmu_instance *inst, const char *fn, double current_time,
                                  double step, double t)
{
    if (t > TRIBO_TIME_MAX)
        return fmu_error(inst,
                         "%s: the step from %.17g by %.17g cannot advance the model to t = %.17g: "
                         "beyond t = %g its time is not resolved finely enough to integrate",
                         fn, current_time, step, t, TRIBO_TIME_MAX);
    char why[256];
    if (!fmu_front_time_resolved(inst->core, t, why, sizeof why))
        return fmu_error(inst, "%s: the step from %.17g by %.17g cannot advance %s", fn,
                         current_time, step, why);
    return FMU_OK;
}

/* The communication point and step an importer gives, checked against the instance: its
   state, its time (up to rounding), a step that moves it, and the stop time; the step's end
   in *end. */
static fmu_status check_step(fmu_instance *inst, const char *fn, double current_time, double step,
                             double *end)
{
    if (inst->lifecycle == FMU_LIFECYCLE_EXITED) {
        char reason[400];
        fmu_front_over_reason(inst->core, reason, sizeof reason);
        return fmu_error(inst, "%s: the run is over at t = %.17g (%s): terminate, reset or "
                         "restore a state", fn, inst->time, reason);
    }
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
    *end = current_time + step;
    if (!(*end > current_time) || !isfinite(*end))
        return fmu_error(inst,
                         "%s: communicationStepSize = %.17g is lost in the rounding of the time "
                         "%.17g (the step would end where it starts)",
                         fn, step, current_time);
    /* a communication point a rounding before the FMU's time is that time, but the step must
       still end after it: the time never goes back */
    if (!(*end > inst->time))
        return fmu_error(inst,
                         "%s: a step from %.17g by %.17g ends at %.17g, not after the FMU's time "
                         "%.17g: the time cannot go back",
                         fn, current_time, step, *end, inst->time);
    if (inst->stop_time_defined && *end > inst->stop_time + fmu_rounding_tolerance(inst->stop_time))
        return fmu_error(inst,
                         "%s: a step from %.17g by %.17g ends at %.17g, after the stop time %.17g "
                         "set at initialization",
                         fn, current_time, step, *end, inst->stop_time);
    return FMU_OK;
}

/* The core's time of the step's end: the FMU's time is the start time plus the core's, in
   the front end's unit, so the step ends where the core's time is end's, which must lie
   after the core's time now (else the FMU's time would move and the model's not) and be
   one the core can advance to. */
static fmu_status core_time_of(fmu_instance *inst, const char *fn, double current_time,
                               double step, double end, double *core_end)
{
    const double unit = fmu_front_time_unit(&inst->derived);
    const double core_now = fmu_front_core_time(inst->core);
    *core_end = (end - inst->start_time) / unit;
    if (!(*core_end > core_now))
        return fmu_error(inst,
                         "%s: communicationStepSize = %.17g is lost in the rounding of the time: "
                         "the step from %.17g to %.17g does not move the model's time t = %.17g",
                         fn, step, current_time, end, core_now);
    return check_core_time(inst, fn, current_time, step, *core_end);
}

/* The core advanced to core_end with status st: the instance follows it (the step's end,
   the time reached where it stopped early, or a failure). */
static fmu_status after_advance(fmu_instance *inst, const char *fn, double current_time,
                                double step, double end, tribo_status st, double *reached,
                                int *early_return, int *terminate)
{
    if (st == TRIBO_INCOMPLETE || st == TRIBO_ENDED) {
        inst->time = reached_time(inst, end, st == TRIBO_INCOMPLETE);
        const fmu_status status = st == TRIBO_ENDED ? exited(inst, fn, end, early_return, terminate)
                                                    : ended_early(inst, fn, end, early_return);
        *reached = inst->time;
        return status;
    }
    if (st != TRIBO_OK) {
        /* a time the core refuses changes nothing (check_core_time refused those it knows
           before the inputs were handed over); any other failure leaves it broken */
        if (st != TRIBO_ERR_TIME)
            inst->lifecycle = FMU_LIFECYCLE_FAILED;
        return fmu_error(inst, "%s: the step from %.17g to %.17g failed: %s", fn, current_time, end,
                         fmu_front_last_error(inst->core));
    }
    /* the core is at core_end, the model's time of end */
    inst->time = end;
    *reached = end;
    fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s(currentCommunicationPoint = %.17g, "
            "communicationStepSize = %.17g)", fn, current_time, step);
    return FMU_OK;
}

fmu_status fmu_do_step(fmu_instance *inst, const char *fn, double current_time, double step,
                       double *reached, int *early_return, int *terminate)
{
    *early_return = 0;
    *terminate = 0;
    if (!inst)
        return FMU_ERROR;
    *reached = inst->time;
    double end, core_end;
    if (check_step(inst, fn, current_time, step, &end) != FMU_OK)
        return FMU_ERROR;
    if (inst->hold_at_end && fmu_front_run_over(inst->core)) {
        /* held at the run's end: the core stays there (it cannot advance), its inputs with
           it; only the FMU's time follows the master */
        inst->time = end;
        *reached = end;
        fmu_log(inst, FMU_OK, FMU_LOG_CALLS, "%s(currentCommunicationPoint = %.17g, "
                "communicationStepSize = %.17g): held at the run's end", fn, current_time, step);
        return FMU_OK;
    }
    if (core_time_of(inst, fn, current_time, step, end, &core_end) != FMU_OK)
        return FMU_ERROR;
    /* inputs set since the last step hold from this communication point on (checked when
       set: a refusal here changes nothing) */
    if (fmu_pass_inputs(inst, fn) != FMU_OK)
        return FMU_ERROR;
    const tribo_status st = fmu_front_advance(inst->core, core_end);
    return after_advance(inst, fn, current_time, step, end, st, reached, early_return, terminate);
}

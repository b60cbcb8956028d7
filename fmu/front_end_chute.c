/* front_end_chute.c: the core functions of front_end.h for the chute's FMUs, dimensionless
   and SI alike: their core is the chute model (src/chute/tribo.h) of the scene the front end
   derived (fmu_front_model_scene). */
#include "front_end_chute.h"

#include <stdio.h>

/* The chute model is the core: fmu_core is only its name here. */
static tribo_model *model_of(fmu_core *core) { return (tribo_model *)core; }
static const tribo_model *const_model_of(const fmu_core *core) { return (const tribo_model *)core; }

const char fmu_front_exited_state_name[] =
    "Exited (the run is over: the particle left the chute, or lifted off where run_end = "
    "first_liftoff, or came to rest on the chute; terminate, reset or restore a state)";

int fmu_front_input_count(void) { return TRIBO_INPUT_COUNT; }

fmu_core *fmu_front_create(const fmu_derived *d, const fmu_core *like, tribo_log_fn log,
                           void *user, char *why, size_t why_size)
{
    /* the scene is only read: the derived numbers stay the caller's */
    tribo_model *m = tribo_create_like(fmu_front_model_scene((fmu_derived *)d),
                                       const_model_of(like), why, why_size);
    if (m)
        tribo_set_logger(m, log, user);
    return (fmu_core *)m;
}

void fmu_front_free(fmu_core *core) { tribo_free(model_of(core)); }

const char *fmu_front_last_error(const fmu_core *core)
{
    return tribo_last_error(const_model_of(core));
}

double fmu_front_core_time(fmu_core *core)
{
    return tribo_get(model_of(core), TRIBO_QUANTITY_TIME);
}

tribo_status fmu_front_set_inputs(fmu_core *core, const double model_values[])
{
    return tribo_set_inputs(model_of(core), model_values);
}

tribo_status fmu_front_advance(fmu_core *core, double t)
{
    return tribo_advance(model_of(core), t);
}

/* The fixed step's grid where t / dt reaches 2^45 (src/chute/integrators/integrator_fixed_step.c,
   GRID_MAX_STEPS). */
int fmu_front_time_resolved(const fmu_core *core, double t, char *why, size_t why_size)
{
    const tribo_scene *scene = tribo_get_scene(const_model_of(core));
    if (scene->integrator == TRIBO_INTEGRATOR_FIXED_STEP && !(t / scene->dt < 0x1p45)) {
        snprintf(why, why_size,
                 "the fixed step to t = %.17g: steps of dt = %g are not resolved there (t / dt "
                 "must stay below 2^45)",
                 t, scene->dt);
        return 0;
    }
    return 1;
}

tribo_status fmu_front_set_param(fmu_core *core, fmu_derived *d, const char *model_name,
                                 double model_value)
{
    const tribo_status st = tribo_set_param(model_of(core), model_name, model_value);
    if (st == TRIBO_OK)
        tribo_param_write(fmu_front_model_scene(d), tribo_param_find(model_name), model_value);
    return st;
}

int fmu_front_run_over(fmu_core *core)
{
    return tribo_get(model_of(core), TRIBO_QUANTITY_END_REASON) != 0.0;
}

void fmu_front_over_reason(fmu_core *core, char *reason, size_t reason_size)
{
    const double why = tribo_get(model_of(core), TRIBO_QUANTITY_END_REASON);
    snprintf(reason, reason_size, "the particle %s",
             why == TRIBO_END_LIFTOFF ? "lifted off the plate, run_end = first_liftoff"
             : why == TRIBO_END_REST  ? "came to rest on the chute"
                                      : "left the chute");
}

tribo_status fmu_front_segments(const fmu_derived *d, fmu_core *core, int which, double *out,
                                size_t n)
{
    const tribo_segment_charge w = (tribo_segment_charge)which;
    /* a charge model the scene leaves out has no charge: zeros, as its mean */
    if (!tribo_includes_charge_model(model_of(core), w)) {
        for (size_t i = 0; i < n; i++)
            out[i] = 0.0;
        return TRIBO_OK;
    }
    const tribo_status st = tribo_get_segment_charges(model_of(core), w, out, n);
    if (st != TRIBO_OK)
        return st;
    const double factor = fmu_front_segment_factor(d, w);
    for (size_t i = 0; i < n; i++)
        out[i] *= factor;
    return TRIBO_OK;
}

size_t fmu_front_state_size(const fmu_core *core) { return tribo_state_size(const_model_of(core)); }

tribo_status fmu_front_state_save(const fmu_core *core, void *bytes, size_t size)
{
    return tribo_state_save(const_model_of(core), bytes, size);
}

tribo_status fmu_front_state_load(fmu_core *core, const fmu_derived *d, const void *bytes,
                                  size_t size, char *why, size_t why_size)
{
    tribo_model *m = model_of(core);
    double t;
    if (tribo_state_time(bytes, size, &t) != TRIBO_OK) {
        snprintf(why, why_size, "the state is corrupt: its core state is not one");
        return TRIBO_ERR_STATE;
    }
    if (tribo_state_load(m, bytes, size) != TRIBO_OK) {
        snprintf(why, why_size, "the core refused the state: %s", tribo_last_error(m));
        return TRIBO_ERR_STATE;
    }
    /* the parameters the FMU reports are the core's */
    const tribo_scene *scene = fmu_front_model_scene((fmu_derived *)d);
    size_t n_params;
    const tribo_param_info *params = tribo_param_table(&n_params);
    for (size_t i = 0; i < n_params; i++) {
        const double mine = tribo_param_read(scene, &params[i]),
                     core = tribo_param_read(tribo_get_scene(m), &params[i]);
        if (mine != core) {
            snprintf(why, why_size,
                     "the state is corrupt: its parameters make %s = %.17g, its core state has "
                     "%.17g",
                     params[i].name, mine, core);
            return TRIBO_ERR_STATE;
        }
    }
    return TRIBO_OK;
}

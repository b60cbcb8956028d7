/* front_end_separator.c: the separator FMUs' front end (front_end.h): the free-fall
   separator's core (src/separator/separator.h, docs/model.md §10) and its table
   (src/separator/separator_quantities.def), in SI units like the core, every value passed on as it
   is (front_end_identity.c; every parameter is fixed, so a tunable would be the core's own). */
#include "front_end.h"

#include <stdio.h>
#include <stdlib.h>

/* The separator, and what its run's end means to the importer: the core's own message is
   about failures, and the end is none. */
struct fmu_core {
    tribo_separator *separator;
    char ended[512];
    char refused[256]; /* a call the separator does not have (no tunables, no segments) */
};

const char fmu_front_prefix[] = "tribo_separator";
const char fmu_front_table_file[] = "src/separator/separator_quantities.def";
const char fmu_front_description[] =
    "A charged grain leaving a chute falls between two vertical plate electrodes, through "
    "still air, into one of n bins or onto a plate: the free-fall separator, in SI units (the "
    "equations: documentation/index.html, section 10)";
const char fmu_front_exited_state_name[] =
    "Exited (the run is over: the grain reached the bins or a plate; terminate, reset or "
    "restore a state)";

/* the default set-up's grain falls 0.5 m in about a third of a second */
const struct fmu_default_experiment fmu_front_default_experiment = {1, 1e-3};

const tribo_param_info *fmu_front_params(size_t *count)
{
    return tribo_separator_param_table(count);
}

const tribo_param_info *fmu_front_param_find(const char *name)
{
    return tribo_separator_param_find(name);
}

const tribo_param_info *fmu_front_inputs(void) { return tribo_separator_input_table(NULL); }

int fmu_front_input_count(void) { return TRIBO_SEPARATOR_INPUT_COUNT; }

void fmu_front_defaults(fmu_scene *scene) { tribo_separator_scene_defaults(&scene->separator); }

tribo_status fmu_front_derive(const fmu_scene *scene, fmu_derived *d, char *msg, size_t msg_size)
{
    d->separator.scene = scene->separator;
    return tribo_separator_derive(&d->separator.scene, &d->separator.d, msg, msg_size);
}

const char *fmu_front_notice(const fmu_derived *d)
{
    (void)d;
    return NULL;
}

double fmu_front_get(const fmu_derived *d, fmu_core *core, int quantity)
{
    (void)d;
    return tribo_separator_get(core->separator, (tribo_separator_quantity)quantity);
}

tribo_status fmu_front_segments(const fmu_derived *d, fmu_core *core, int which, double *out,
                                size_t n)
{
    (void)d;
    (void)which;
    (void)out;
    (void)n;
    snprintf(core->refused, sizeof core->refused, "the separator has no segment charges");
    return TRIBO_ERR_INVALID_ARGUMENT;
}

/* ---- the core instance ------------------------------------------------------------------ */

fmu_core *fmu_front_create(const fmu_derived *d, const fmu_core *like, tribo_log_fn log,
                           void *user, char *why, size_t why_size)
{
    (void)like; /* nothing of the separator's core is costly to make */
    (void)log;  /* the separator's core logs nothing: its refusals come back as messages */
    (void)user;
    fmu_core *core = calloc(1, sizeof *core);
    if (!core) {
        snprintf(why, why_size, "out of memory");
        return NULL;
    }
    if (!(core->separator = tribo_separator_create(&d->separator.scene, why, why_size))) {
        free(core);
        return NULL;
    }
    return core;
}

void fmu_front_free(fmu_core *core)
{
    if (!core)
        return;
    tribo_separator_free(core->separator);
    free(core);
}

int fmu_front_run_over(fmu_core *core)
{
    return tribo_separator_end_of(core->separator) != TRIBO_SEPARATOR_RUNNING;
}

const char *fmu_front_last_error(const fmu_core *core)
{
    return tribo_separator_end_of(core->separator) != TRIBO_SEPARATOR_RUNNING ? core->ended
           : *core->refused         ? core->refused
                                    : tribo_separator_last_error(core->separator);
}

double fmu_front_core_time(fmu_core *core)
{
    return tribo_separator_get(core->separator, TRIBO_SEPARATOR_Q_TIME);
}

tribo_status fmu_front_set_inputs(fmu_core *core, const double model_values[])
{
    *core->refused = '\0';
    return tribo_separator_set_inputs(core->separator, model_values);
}

void fmu_front_over_reason(fmu_core *core, char *reason, size_t reason_size)
{
    const tribo_separator *s = core->separator;
    if (tribo_separator_end_of(s) == TRIBO_SEPARATOR_LANDED)
        snprintf(reason, reason_size, "the grain landed in bin %d of %d at x = %.17g m",
                 tribo_separator_bin(s), tribo_separator_get_scene(s)->n_bins,
                 tribo_separator_get(s, TRIBO_SEPARATOR_Q_X_END));
    else
        snprintf(reason, reason_size,
                 "the grain was caught on the plate at x = %s gap/2, z = %.17g m",
                 tribo_separator_get(s, TRIBO_SEPARATOR_Q_ELECTRODE) > 0 ? "+" : "-",
                 tribo_separator_get(s, TRIBO_SEPARATOR_Q_Z_END));
}

/* How the run ended, as the message of the step that ended it and of any later one. */
static void note_end(fmu_core *core)
{
    char reason[400];
    fmu_front_over_reason(core, reason, sizeof reason);
    snprintf(core->ended, sizeof core->ended, "%s at t = %.17g s: the run is over there; reset "
             "to run again", reason, fmu_front_core_time(core));
}

tribo_status fmu_front_advance(fmu_core *core, double t)
{
    *core->refused = '\0';
    const tribo_status st = tribo_separator_advance(core->separator, t);
    if (st == TRIBO_ENDED)
        note_end(core);
    return st;
}

int fmu_front_time_resolved(const fmu_core *core, double t, char *why, size_t why_size)
{
    /* CVODE's own step sizes resolve any time below TRIBO_TIME_MAX */
    (void)core;
    (void)t;
    (void)why;
    (void)why_size;
    return 1;
}

tribo_status fmu_front_set_param(fmu_core *core, fmu_derived *d, const char *model_name,
                                 double model_value)
{
    (void)d;
    (void)model_value;
    snprintf(core->refused, sizeof core->refused, "%s is fixed: it cannot change during a run",
             model_name);
    return TRIBO_ERR_INVALID_ARGUMENT;
}

size_t fmu_front_state_size(const fmu_core *core)
{
    return tribo_separator_state_size(core->separator);
}

tribo_status fmu_front_state_save(const fmu_core *core, void *bytes, size_t size)
{
    return tribo_separator_state_save(core->separator, bytes, size);
}

tribo_status fmu_front_state_load(fmu_core *core, const fmu_derived *d, const void *bytes,
                                  size_t size, char *why, size_t why_size)
{
    (void)d; /* the core's load refuses another scene's state */
    if (tribo_separator_state_load(core->separator, bytes, size) != TRIBO_OK) {
        snprintf(why, why_size, "the core refused the state: %s",
                 tribo_separator_last_error(core->separator));
        return TRIBO_ERR_STATE;
    }
    if (fmu_front_run_over(core))
        note_end(core);
    return TRIBO_OK;
}

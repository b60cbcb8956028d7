/*
 * front_end.h: what lies between the importer's variables and a core, the one thing the
 * FMUs do differently. The instance layer (lifecycle.c, access.c, step.c, fmu_state.c) is
 * the same for all of them; each FMU links one front end and the variable table made from
 * its table (variables_impl.h, compiled once per table: variables_model.c, variables_si.c,
 * variables_separator.c):
 *
 *   front_end_model.c      the dimensionless FMUs: the chute's core and its table
 *                          (src/chute/quantities.def); the identity
 *   front_end_si.c         the SI FMUs: src/si/si_quantities.def; the physical set-up becomes
 *                          the chute model's scene by docs/model.md §8 (src/si/si.h), the
 *                          outputs are the model's in SI units
 *   front_end_chute.c      what those two share: the chute's core (src/chute/tribo.h) behind the
 *                          core functions below
 *   front_end_separator.c  the separator FMUs: the free-fall separator's core
 *                          (src/separator/separator.h, docs/model.md §10) and its table
 *                          (src/separator/separator_quantities.def)
 *   front_end_identity.c   what the dimensionless and the separator's front ends share: the
 *                          importer's values passed on as they are
 *
 * The front end holds no physics: it calls a core and, for the SI FMUs, the core's mapping
 * (si.h). The instance layer sees a core only through these functions (fmu_core is the
 * front end's own type), so that it hosts any of them.
 */
#ifndef TRIBO_FMU_FRONT_END_H
#define TRIBO_FMU_FRONT_END_H

#include <stddef.h>

#include "separator.h"
#include "si.h"
#include "tribo.h"

/* The parameters as the importer sees them (the front end's table), and what the front
   end derived from them for its core. Storage for any front end; only the front end reads
   their members. */
typedef union fmu_scene {
    tribo_scene model;
    tribo_si_scene si;
    tribo_separator_scene separator;
} fmu_scene;

typedef union fmu_derived {
    tribo_scene model;
    tribo_si_derived si;
    struct fmu_separator_derived {
        tribo_separator_scene scene;
        tribo_separator_derived d;
    } separator;
} fmu_derived;

/* The core instance of a front end: a chute model or a separator. */
typedef struct fmu_core fmu_core;

/* Room for the inputs of any front end; each has fmu_front_input_count of them. */
#define FMU_MAX_INPUTS                                                                         \
    ((int)TRIBO_INPUT_COUNT > (int)TRIBO_SEPARATOR_INPUT_COUNT ? (int)TRIBO_INPUT_COUNT        \
                                                               : (int)TRIBO_SEPARATOR_INPUT_COUNT)

/* "tribo", "tribo_si" or "tribo_separator": the FMUs' modelIdentifiers are
   <prefix>_fmi2 and <prefix>_fmi3. */
extern const char fmu_front_prefix[];
/* The table the variables come from (for the description's comment), and the FMU's
   one-line description. */
extern const char fmu_front_table_file[];
extern const char fmu_front_description[];
/* The description's default experiment, in the FMU's unit of time. */
extern const struct fmu_default_experiment {
    double stop_time, step_size;
} fmu_front_default_experiment;
/* The name of the instance's state once the core's run is over (FMI 2.0's fmi2Terminated,
   FMI 3.0's terminateSimulation): what ended it. */
extern const char fmu_front_exited_state_name[];

/* The front end's parameters and inputs (inputs: fmu_front_input_count rows, in the
   core's order). */
const tribo_param_info *fmu_front_params(size_t *count);
const tribo_param_info *fmu_front_param_find(const char *name);
const tribo_param_info *fmu_front_inputs(void);
int fmu_front_input_count(void);

void fmu_front_defaults(fmu_scene *scene);

/* The core's scene of the importer's parameters, checked whole (every value in its range,
   and every derived one in the core's); the failure's message names the importer's
   variables. */
tribo_status fmu_front_derive(const fmu_scene *scene, fmu_derived *d, char *msg, size_t msg_size);

/* What the derived scene's set-up asks that it does not do (a parameter set that nothing
   uses), for a warning; NULL when nothing. */
const char *fmu_front_notice(const fmu_derived *d);

/* A tunable parameter's new value as the core's parameter (name, value), checked against
   the core's range. */
tribo_status fmu_front_tunable(const fmu_derived *d, const tribo_param_info *p, double value,
                               const char **model_name, double *model_value, char *msg,
                               size_t msg_size);
/* The importer's inputs as the core's, checked against the core's ranges. */
tribo_status fmu_front_model_inputs(const fmu_derived *d, const double values[],
                                    double model_values[], char *msg, size_t msg_size);

/* The importer's unit of time per unit of the core's (1, or t_star in seconds). */
double fmu_front_time_unit(const fmu_derived *d);
/* An output or calculated parameter (the variable's index) of the core instance. */
double fmu_front_get(const fmu_derived *d, fmu_core *core, int quantity);
/* The values of a segment-charge array (which: tribo_segment_charge), n of them, in the
   importer's units (zeros for a charge model the scene leaves out); a failure's reason is
   fmu_front_last_error's. */
tribo_status fmu_front_segments(const fmu_derived *d, fmu_core *core, int which, double *out,
                                size_t n);

/* ---- the core instance ------------------------------------------------------------------ */

/* A core instance of what the front end derived, its messages routed to log(user, ...);
   NULL and the reason in why on failure. `like` (NULL: none) is a core instance whose work
   the new one may reuse where their set-ups share it (the instance's own, which a state load
   or a new model replaces): the result is the same as without. */
fmu_core *fmu_front_create(const fmu_derived *d, const fmu_core *like, tribo_log_fn log,
                           void *user, char *why, size_t why_size);
void fmu_front_free(fmu_core *core);
const char *fmu_front_last_error(const fmu_core *core);
/* The core's time, in its own unit. */
double fmu_front_core_time(fmu_core *core);
/* The core's inputs (model values, fmu_front_model_inputs's) from its time on. */
tribo_status fmu_front_set_inputs(fmu_core *core, const double model_values[]);
/* Advance the core to its time t: the core's status (TRIBO_OK, TRIBO_ENDED,
   TRIBO_INCOMPLETE, or a failure). */
tribo_status fmu_front_advance(fmu_core *core, double t);
/* 1 if the core can advance to its time t, else 0 and in why what stops it ("the fixed
   step to t = ...: ..."), beyond TRIBO_TIME_MAX, which the instance layer checks. */
int fmu_front_time_resolved(const fmu_core *core, double t, char *why, size_t why_size);
/* A tunable parameter's new value (the core's name and value, fmu_front_tunable's) from
   the core's time on; d follows it. */
tribo_status fmu_front_set_param(fmu_core *core, fmu_derived *d, const char *model_name,
                                 double model_value);
/* Whether the core's run is over (TRIBO_ENDED), and a clause that says how ("the particle
   left the chute"). */
int fmu_front_run_over(fmu_core *core);
void fmu_front_over_reason(fmu_core *core, char *reason, size_t reason_size);

/* The core's state: plain bytes, no pointers. A load into a fresh core checks the bytes
   against the core's scene (d's: the parameters the FMU reports must be the core's) and its
   ranges; after a refusal, the reason in why, the core is only to be freed. */
size_t fmu_front_state_size(const fmu_core *core);
tribo_status fmu_front_state_save(const fmu_core *core, void *bytes, size_t size);
tribo_status fmu_front_state_load(fmu_core *core, const fmu_derived *d, const void *bytes,
                                  size_t size, char *why, size_t why_size);

#endif

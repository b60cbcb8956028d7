/*
 * front_end.h: what lies between the importer's variables and the core, the one thing the
 * dimensionless and the SI FMUs do differently. The instance layer (lifecycle.c, access.c,
 * step.c, fmu_state.c) is the same for both; each FMU links one front end and the variable
 * table made from its table (variables_impl.h, compiled once per table: variables_model.c,
 * variables_si.c):
 *
 *   front_end_model.c   the dimensionless FMUs: the core's table (src/quantities.def); the
 *                       identity
 *   front_end_si.c      the SI FMUs: src/si_quantities.def; the physical set-up becomes the
 *                       model's scene by docs/model.md §8 (src/si.h), the outputs are the
 *                       model's in SI units
 *
 * The front end holds no physics: it calls the core's mapping (si.h) or none.
 */
#ifndef TRIBO_FMU_FRONT_END_H
#define TRIBO_FMU_FRONT_END_H

#include <stddef.h>

#include "si.h"
#include "tribo.h"

/* The parameters as the importer sees them (the front end's table), and what the front
   end derived from them for the core. Storage for either front end; only the front end
   reads their members. */
typedef union fmu_scene {
    tribo_scene model;
    tribo_si_scene si;
} fmu_scene;

typedef union fmu_derived {
    tribo_scene model;
    tribo_si_derived si;
} fmu_derived;

/* "tribo" or "tribo_si": the FMUs' modelIdentifiers are <prefix>_fmi2 and <prefix>_fmi3. */
extern const char fmu_front_prefix[];
/* The table the variables come from (for the description's comment), and the FMU's
   one-line description. */
extern const char fmu_front_table_file[];
extern const char fmu_front_description[];
/* The description's default experiment, in the FMU's unit of time. */
extern const struct fmu_default_experiment {
    double stop_time, step_size;
} fmu_front_default_experiment;

/* The front end's parameters and inputs (inputs: TRIBO_INPUT_COUNT rows, in the core's
   order). */
const tribo_param_info *fmu_front_params(size_t *count);
const tribo_param_info *fmu_front_param_find(const char *name);
const tribo_param_info *fmu_front_inputs(void);

void fmu_front_defaults(fmu_scene *scene);

/* The model's scene of the importer's parameters, checked whole (every value in its range,
   and every derived one in the model's); the failure's message names the importer's
   variables. */
tribo_status fmu_front_derive(const fmu_scene *scene, fmu_derived *d, char *msg, size_t msg_size);
tribo_scene *fmu_front_model_scene(fmu_derived *d);

/* A tunable parameter's new value as the model's parameter (name, value), checked against
   the model's range. */
tribo_status fmu_front_tunable(const fmu_derived *d, const tribo_param_info *p, double value,
                               const char **model_name, double *model_value, char *msg,
                               size_t msg_size);
/* The importer's inputs as the model's, checked against the model's ranges. */
tribo_status fmu_front_model_inputs(const fmu_derived *d, const double values[TRIBO_INPUT_COUNT],
                                    double model_values[TRIBO_INPUT_COUNT], char *msg,
                                    size_t msg_size);

/* The importer's unit of time per unit of the model's (1, or t_star in seconds). */
double fmu_front_time_unit(const fmu_derived *d);
/* An output or calculated parameter (the variable's index) of the instance m. */
double fmu_front_get(const fmu_derived *d, tribo_model *m, int quantity);
/* The factor from the model's per-segment values to the importer's. */
double fmu_front_segment_factor(const fmu_derived *d, tribo_segment_charge which);

#endif

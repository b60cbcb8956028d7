/* front_end_model.c: the dimensionless FMUs' front end (front_end.h): the core's own table,
   every value passed on as it is (front_end_identity.c). */
#include "front_end_chute.h"

const char fmu_front_prefix[] = "tribo";
const char fmu_front_table_file[] = "src/chute/quantities.def";
const char fmu_front_description[] =
    "A 2D elliptical particle tribocharging on a tilted plate (after Ireland 2012; the "
    "equations: documentation/index.html)";

const struct fmu_default_experiment fmu_front_default_experiment = {1000, 0.1};

const tribo_param_info *fmu_front_params(size_t *count) { return tribo_param_table(count); }

const tribo_param_info *fmu_front_param_find(const char *name) { return tribo_param_find(name); }

const tribo_param_info *fmu_front_inputs(void) { return tribo_input_table(NULL); }

void fmu_front_defaults(fmu_scene *scene) { tribo_scene_defaults(&scene->model); }

tribo_status fmu_front_derive(const fmu_scene *scene, fmu_derived *d, char *msg, size_t msg_size)
{
    d->model = scene->model;
    return tribo_scene_validate(&d->model, msg, msg_size);
}

const char *fmu_front_notice(const fmu_derived *d)
{
    (void)d;
    return NULL;
}

tribo_scene *fmu_front_model_scene(fmu_derived *d) { return &d->model; }

double fmu_front_get(const fmu_derived *d, fmu_core *core, int quantity)
{
    (void)d;
    return tribo_get((tribo_model *)core, (tribo_quantity)quantity);
}

double fmu_front_segment_factor(const fmu_derived *d, tribo_segment_charge which)
{
    (void)d;
    (void)which;
    return 1.0;
}

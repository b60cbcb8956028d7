/* front_end_si.c: the SI FMUs' front end (front_end.h): a physical set-up in SI units
   (src/si/si_quantities.def) mapped onto the model by the core's SI front end (src/si/si.h,
   docs/model.md §8). */
#include "front_end_chute.h"

const char fmu_front_prefix[] = "tribo_si";
const char fmu_front_table_file[] = "src/si/si_quantities.def";
const char fmu_front_description[] =
    "A 2D elliptical particle tribocharging on a tilted chute, in SI units: a physical "
    "particle and wall mapped onto the dimensionless model (after Ireland 2012; the "
    "equations and the mapping: documentation/index.html)";

const struct fmu_default_experiment fmu_front_default_experiment = {1, 1e-3};

const tribo_param_info *fmu_front_params(size_t *count) { return tribo_si_param_table(count); }

const tribo_param_info *fmu_front_param_find(const char *name) { return tribo_si_param_find(name); }

const tribo_param_info *fmu_front_inputs(void) { return tribo_si_input_table(NULL); }

void fmu_front_defaults(fmu_scene *scene) { tribo_si_scene_defaults(&scene->si); }

tribo_status fmu_front_derive(const fmu_scene *scene, fmu_derived *d, char *msg, size_t msg_size)
{
    return tribo_si_derive(&scene->si, &d->si, msg, msg_size);
}

const char *fmu_front_notice(const fmu_derived *d) { return d->si.notice[0] ? d->si.notice : NULL; }

tribo_scene *fmu_front_model_scene(fmu_derived *d) { return &d->si.scene; }

tribo_status fmu_front_tunable(const fmu_derived *d, const tribo_param_info *p, double value,
                               const char **model_name, double *model_value, char *msg,
                               size_t msg_size)
{
    if (tribo_param_check(p, value, msg, msg_size) != TRIBO_OK)
        return TRIBO_ERR_INVALID_ARGUMENT;
    return tribo_si_model_param(&d->si, p, value, model_name, model_value, msg, msg_size);
}

tribo_status fmu_front_model_inputs(const fmu_derived *d, const double values[],
                                    double model_values[], char *msg, size_t msg_size)
{
    return tribo_si_model_inputs(&d->si, values, model_values, msg, msg_size);
}

double fmu_front_time_unit(const fmu_derived *d) { return d->si.t_star; }

double fmu_front_get(const fmu_derived *d, fmu_core *core, int quantity)
{
    return tribo_si_get(&d->si, (tribo_model *)core, (tribo_si_quantity)quantity);
}

double fmu_front_segment_factor(const fmu_derived *d, tribo_segment_charge which)
{
    return tribo_si_segment_factor(&d->si, which);
}

_Static_assert((int)TRIBO_SI_INPUT_COUNT == (int)TRIBO_INPUT_COUNT,
               "the SI inputs are the model's, one for one");

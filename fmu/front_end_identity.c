/* front_end_identity.c: what the front ends that pass the importer's values on as they are
   share (front_end.h): the dimensionless chute's (front_end_model.c) and the separator's
   (front_end_separator.c), whose tables are their cores' own, in the cores' units. */
#include "front_end.h"

#include <string.h>

tribo_status fmu_front_tunable(const fmu_derived *d, const tribo_param_info *p, double value,
                               const char **model_name, double *model_value, char *msg,
                               size_t msg_size)
{
    (void)d;
    *model_name = p->name;
    *model_value = value;
    return tribo_param_check(p, value, msg, msg_size);
}

tribo_status fmu_front_model_inputs(const fmu_derived *d, const double values[],
                                    double model_values[], char *msg, size_t msg_size)
{
    (void)d;
    const int n = fmu_front_input_count();
    if (tribo_params_check(fmu_front_inputs(), n, values, msg, msg_size) != TRIBO_OK)
        return TRIBO_ERR_INVALID_ARGUMENT;
    memcpy(model_values, values, (size_t)n * sizeof values[0]);
    return TRIBO_OK;
}

double fmu_front_time_unit(const fmu_derived *d)
{
    (void)d;
    return 1.0;
}

/* variables.c: the table of the FMU's variables (see variables.h). */
#include "variables.h"


/* The FMI causality and variability of each kind of row of the core's table. The
   parameter that sizes the segment arrays (type COUNT) is an FMI 3.0 structural parameter;
   structural and fixed parameters are fixed. */
#define CAUSALITY_OF_REAL FMU_CAUSALITY_PARAMETER
#define CAUSALITY_OF_INTEGER FMU_CAUSALITY_PARAMETER
#define CAUSALITY_OF_COUNT FMU_CAUSALITY_STRUCTURAL_PARAMETER
#define VARIABILITY_OF_STRUCTURAL FMU_VARIABILITY_FIXED
#define VARIABILITY_OF_FIXED FMU_VARIABILITY_FIXED
#define VARIABILITY_OF_TUNABLE FMU_VARIABILITY_TUNABLE

/* The index of each parameter in the core's table (tribo_param_table). */
enum {
#define TRIBO_PARAMETER(name, ...) PARAM_##name,
#include "quantities.def"
};

/* Every row of the core's table (src/quantities.def), in its order. */
static const fmu_variable VARIABLES[] = {
#define TRIBO_PARAMETER(name, type, vr, unit, min, min_end, max, max_end, start, variability,     \
                        description)                                                             \
    {vr, #name, FMU_TYPE_##type, CAUSALITY_OF_##type, VARIABILITY_OF_##variability,               \
     FMU_MAPS_TO_PARAMETER, PARAM_##name, FMU_IN_BOTH, description, unit},
#define TRIBO_TIME(id, name, vr, unit, description, value)                                       \
    {vr, name, FMU_TYPE_REAL, FMU_CAUSALITY_INDEPENDENT, FMU_VARIABILITY_CONTINUOUS,            \
     FMU_MAPS_TO_TIME, 0, FMU_IN_BOTH, description, unit},
#define TRIBO_INPUT(id, name, vr, unit, min, max, description)                                   \
    {vr, name, FMU_TYPE_REAL, FMU_CAUSALITY_INPUT, FMU_VARIABILITY_CONTINUOUS, FMU_MAPS_TO_INPUT, \
     TRIBO_INPUT_##id, FMU_IN_BOTH, description, unit},
#define TRIBO_OUTPUT(id, name, vr, unit, description, value)                                     \
    {vr, name, FMU_TYPE_REAL, FMU_CAUSALITY_OUTPUT, FMU_VARIABILITY_CONTINUOUS,                 \
     FMU_MAPS_TO_QUANTITY, TRIBO_Q_##id, FMU_IN_BOTH, description, unit},
/* arrays exist in FMI 3.0 only */
#define TRIBO_SEGMENTS(id, name, vr, unit, description)                                          \
    {vr, name, FMU_TYPE_REAL, FMU_CAUSALITY_OUTPUT, FMU_VARIABILITY_CONTINUOUS,                 \
     FMU_MAPS_TO_SEGMENTS, TRIBO_SEGMENTS_##id, FMU_IN_FMI3, description, unit},
#include "quantities.def"
};

#define N_VARIABLES (sizeof VARIABLES / sizeof VARIABLES[0])

const fmu_variable *fmu_variables(size_t *count)
{
    if (count)
        *count = N_VARIABLES;
    return VARIABLES;
}

int fmu_variable_in_version(const fmu_variable *v, int fmi_version)
{
    return (v->versions & (fmi_version == 2 ? FMU_IN_FMI2 : FMU_IN_FMI3)) != 0;
}

const fmu_variable *fmu_variable_find(fmu_vr vr, int fmi_version)
{
    for (size_t i = 0; i < N_VARIABLES; i++)
        if (VARIABLES[i].vr == vr)
            return fmu_variable_in_version(&VARIABLES[i], fmi_version) ? &VARIABLES[i] : NULL;
    return NULL;
}

const tribo_param_info *fmu_variable_param(const fmu_variable *v)
{
    switch (v->maps_to) {
    case FMU_MAPS_TO_PARAMETER: return &tribo_param_table(NULL)[v->index];
    case FMU_MAPS_TO_INPUT: return &tribo_input_table(NULL)[v->index];
    default: return NULL;
    }
}

const fmu_variable *fmu_variable_dimension(const fmu_variable *v)
{
    if (v->maps_to != FMU_MAPS_TO_SEGMENTS)
        return NULL;
    for (size_t i = 0; i < N_VARIABLES; i++)
        if (VARIABLES[i].type == FMU_TYPE_COUNT)
            return &VARIABLES[i];
    return NULL;
}

const char *fmu_type_name(fmu_type type, int fmi_version)
{
    switch (type) {
    case FMU_TYPE_REAL: return fmi_version == 2 ? "Real" : "Float64";
    case FMU_TYPE_INTEGER: return fmi_version == 2 ? "Integer" : "Int32";
    case FMU_TYPE_COUNT: return fmi_version == 2 ? "Integer" : "UInt64";
    }
    return "?";
}

const char *fmu_causality_name(fmu_causality causality, int fmi_version)
{
    switch (causality) {
    case FMU_CAUSALITY_INDEPENDENT: return "independent";
    case FMU_CAUSALITY_PARAMETER: return "parameter";
    case FMU_CAUSALITY_STRUCTURAL_PARAMETER:
        return fmi_version == 2 ? "parameter" : "structuralParameter";
    case FMU_CAUSALITY_INPUT: return "input";
    case FMU_CAUSALITY_OUTPUT: return "output";
    }
    return "?";
}

const char *fmu_variability_name(fmu_variability variability)
{
    switch (variability) {
    case FMU_VARIABILITY_FIXED: return "fixed";
    case FMU_VARIABILITY_TUNABLE: return "tunable";
    case FMU_VARIABILITY_CONTINUOUS: return "continuous";
    }
    return "?";
}

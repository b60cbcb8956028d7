/* variables_impl.h: the table of the FMU's variables (see variables.h), made from the table
   of its front end (front_end.h). Not a header to include: the body of the one compile
   unit of each FMU pair, variables_model.c (src/chute/quantities.def), variables_si.c (with
   TRIBO_FMU_SI: src/si/si_quantities.def) and variables_separator.c (with TRIBO_FMU_SEPARATOR:
   src/separator/separator_quantities.def), so that every C file of an FMU's sources/ is one to
   compile and none needs a preprocessor definition. The units and enumerations are
   quantities.def's (the units "1" and "rad") and the front end's table's own; the
   description declares those its variables use. */
#include "variables.h"

#include <math.h>
#include <string.h>

#include "front_end.h"

#ifdef TRIBO_FMU_SI
#define FMU_TABLE "si_quantities.def"
#define FMU_OWN_TABLE "si_quantities.def"
#define QUANTITY(id) TRIBO_SI_QUANTITY_##id
#define INPUT(id) TRIBO_SI_INPUT_##id
#elif defined TRIBO_FMU_SEPARATOR
#define FMU_TABLE "separator_quantities.def"
#define FMU_OWN_TABLE "separator_quantities.def"
#define QUANTITY(id) TRIBO_SEPARATOR_Q_##id
#define INPUT(id) TRIBO_SEPARATOR_INPUT_##id
#else
#define FMU_TABLE "quantities.def"
#define QUANTITY(id) TRIBO_QUANTITY_##id
#define INPUT(id) TRIBO_INPUT_##id
#endif


/* What each type of the core's table is in the FMUs (an ENUM(<id>) type names its
   enumeration). The parameter that sizes the segment arrays (type COUNT) is an FMI 3.0
   structural parameter; structural and fixed parameters are fixed. Outputs of a type
   other than REAL change only at events: FMI calls them discrete. */
#define TYPE_REAL FMU_TYPE_REAL
#define TYPE_INTEGER FMU_TYPE_INTEGER
#define TYPE_COUNT FMU_TYPE_COUNT
#define TYPE_BOOLEAN FMU_TYPE_BOOLEAN
#define TYPE_ENUM(enumeration) FMU_TYPE_ENUMERATION
#define ENUMERATION_OF_REAL -1
#define ENUMERATION_OF_INTEGER -1
#define ENUMERATION_OF_COUNT -1
#define ENUMERATION_OF_BOOLEAN -1
#define ENUMERATION_OF_ENUM(enumeration) ENUMERATION_##enumeration
#define CAUSALITY_OF_REAL FMU_CAUSALITY_PARAMETER
#define CAUSALITY_OF_INTEGER FMU_CAUSALITY_PARAMETER
#define CAUSALITY_OF_COUNT FMU_CAUSALITY_STRUCTURAL_PARAMETER
#define CAUSALITY_OF_ENUM(enumeration) FMU_CAUSALITY_PARAMETER
#define OUTPUT_VARIABILITY_OF_REAL FMU_VARIABILITY_CONTINUOUS
#define OUTPUT_VARIABILITY_OF_BOOLEAN FMU_VARIABILITY_DISCRETE
#define OUTPUT_VARIABILITY_OF_INTEGER FMU_VARIABILITY_DISCRETE
#define OUTPUT_VARIABILITY_OF_ENUM(enumeration) FMU_VARIABILITY_DISCRETE
#define VARIABILITY_OF_STRUCTURAL FMU_VARIABILITY_FIXED
#define VARIABILITY_OF_FIXED FMU_VARIABILITY_FIXED
#define VARIABILITY_OF_TUNABLE FMU_VARIABILITY_TUNABLE

/* The index of each parameter in the front end's table (fmu_front_params), and of each
   enumeration in ENUMERATIONS. */
enum {
#define TRIBO_PARAMETER(name, ...) PARAM_##name,
#include FMU_TABLE
};
enum {
#define TRIBO_ENUMERATION(id, ...) ENUMERATION_##id,
#include "quantities.def"
#ifdef FMU_OWN_TABLE
#define TRIBO_ENUMERATION(id, ...) ENUMERATION_##id,
#include FMU_OWN_TABLE
#endif
    N_ENUMERATIONS
};

/* Every row of the front end's table, in its order. */
static const fmu_variable VARIABLES[] = {
#define TRIBO_PARAMETER(name, type, vr, unit, min, min_end, max, max_end, start, variability,     \
                        description)                                                             \
    {vr, #name, TYPE_##type, CAUSALITY_OF_##type, VARIABILITY_OF_##variability,                  \
     FMU_MAPS_TO_PARAMETER, PARAM_##name, FMU_IN_BOTH, description, unit, ENUMERATION_OF_##type},
#define TRIBO_TIME(id, name, vr, unit, description, value)                                       \
    {vr, name, FMU_TYPE_REAL, FMU_CAUSALITY_INDEPENDENT, FMU_VARIABILITY_CONTINUOUS,            \
     FMU_MAPS_TO_TIME, 0, FMU_IN_BOTH, description, unit, -1},
#define TRIBO_INPUT(id, name, vr, unit, min, max, description)                                   \
    {vr, name, FMU_TYPE_REAL, FMU_CAUSALITY_INPUT, FMU_VARIABILITY_CONTINUOUS, FMU_MAPS_TO_INPUT, \
     INPUT(id), FMU_IN_BOTH, description, unit, -1},
/* a switch: FMI's Boolean, which changes only at events */
#define TRIBO_BOOLEAN_INPUT(id, name, vr, description)                                           \
    {vr, name, FMU_TYPE_BOOLEAN, FMU_CAUSALITY_INPUT, FMU_VARIABILITY_DISCRETE, FMU_MAPS_TO_INPUT, \
     INPUT(id), FMU_IN_BOTH, description, "1", -1},
#define TRIBO_OUTPUT(id, name, type, vr, unit, description, value)                               \
    {vr, name, TYPE_##type, FMU_CAUSALITY_OUTPUT, OUTPUT_VARIABILITY_OF_##type,                 \
     FMU_MAPS_TO_QUANTITY, QUANTITY(id), FMU_IN_BOTH, description, unit, ENUMERATION_OF_##type},
#define TRIBO_CALCULATED(id, name, vr, unit, variability, description, value)                    \
    {vr, name, FMU_TYPE_REAL, FMU_CAUSALITY_CALCULATED_PARAMETER, VARIABILITY_OF_##variability,  \
     FMU_MAPS_TO_QUANTITY, QUANTITY(id), FMU_IN_BOTH, description, unit, -1},
/* arrays exist in FMI 3.0 only */
#define TRIBO_SEGMENTS(id, name, vr, unit, description)                                          \
    {vr, name, FMU_TYPE_REAL, FMU_CAUSALITY_OUTPUT, FMU_VARIABILITY_CONTINUOUS,                 \
     FMU_MAPS_TO_SEGMENTS, TRIBO_SEGMENTS_##id, FMU_IN_FMI3, description, unit, -1},
#include FMU_TABLE
    /* What the FMU does at the run's end is the FMU layer's (step.c), not a core's: so the
       row is here, once for every FMU, rather than in each core's table, whose scene and
       C API it would otherwise join. */
    {FMU_HOLD_AT_END_VR, "hold_at_end", FMU_TYPE_BOOLEAN, FMU_CAUSALITY_PARAMETER,
     FMU_VARIABILITY_FIXED, FMU_MAPS_TO_INSTANCE, 0, FMU_IN_BOTH,
     "what a step does at the run's end (the chute's exit or first lift-off, the separator's "
     "landing): false, it ends the simulation there (FMI 2.0: fmi2Discard and fmi2Terminated; "
     "FMI 3.0: terminateSimulation); true, it and every later step complete to their "
     "communication point, every output held at its value at the end, for masters that take "
     "the end of one FMU's run for a failed step",
     "1", -1},
};

/* The value references retired (TRIBO_RETIRED rows), and an end that is none of them (a
   table may have none). */
static const fmu_retired RETIRED[] = {
#define TRIBO_RETIRED(kind, vr, name, instead) {vr, name, instead},
#include FMU_TABLE
    {0, NULL, NULL}};
const fmu_retired *fmu_retired_find(fmu_vr vr)
{
    for (const fmu_retired *r = RETIRED; r->name; r++)
        if (r->vr == vr)
            return r;
    return NULL;
}

/* hold_at_end as a parameter row: a switch (0, 1), fixed, false by default */
static const tribo_param_info HOLD_AT_END = {
    .name = "hold_at_end", .description = "", .unit = "1", .vr = FMU_HOLD_AT_END_VR,
    .type = TRIBO_TYPE_INTEGER, .min = 0.0, .max = 1.0, .min_inclusive = 1, .max_inclusive = 1,
    .start = 0.0, .variability = TRIBO_PARAM_FIXED};

#define UNIT_ROW(name, quantity, base_unit, display_unit, display_factor, description)           \
    {name, quantity, base_unit, display_unit, display_factor, description},
static const fmu_unit UNITS[] = {
#define TRIBO_UNIT UNIT_ROW
#include "quantities.def"
#ifdef FMU_OWN_TABLE
#define TRIBO_UNIT UNIT_ROW
#include FMU_OWN_TABLE
#endif
};

/* Every display unit: the units' own (TRIBO_UNIT) and the others (TRIBO_DISPLAY_UNIT). */
#define DISPLAY_OF_UNIT(name, quantity, base_unit, display_unit, display_factor, description)    \
    {name, display_unit, display_factor},
#define DISPLAY_ROW(unit, name, factor) {unit, name, factor},
static const fmu_display_unit DISPLAY_UNITS[] = {
#define TRIBO_UNIT DISPLAY_OF_UNIT
#define TRIBO_DISPLAY_UNIT DISPLAY_ROW
#include "quantities.def"
#ifdef FMU_OWN_TABLE
#define TRIBO_UNIT DISPLAY_OF_UNIT
#define TRIBO_DISPLAY_UNIT DISPLAY_ROW
#include FMU_OWN_TABLE
#endif
};

static const fmu_enumeration ENUMERATIONS[] = {
#define TRIBO_ENUMERATION(id, type_name, description) [ENUMERATION_##id] = {type_name, description},
#include "quantities.def"
#ifdef FMU_OWN_TABLE
#define TRIBO_ENUMERATION(id, type_name, description) [ENUMERATION_##id] = {type_name, description},
#include FMU_OWN_TABLE
#endif
};

/* The items of every enumeration, each enumeration's together and in the table's order. */
static const int ITEM_ENUMERATION[] = {
#define TRIBO_ENUM_ITEM(id, name, value, description) ENUMERATION_##id,
#include "quantities.def"
#ifdef FMU_OWN_TABLE
#define TRIBO_ENUM_ITEM(id, name, value, description) ENUMERATION_##id,
#include FMU_OWN_TABLE
#endif
};
static const fmu_enum_item ITEMS[] = {
#define TRIBO_ENUM_ITEM(id, name, value, description) {name, value, description},
#include "quantities.def"
#ifdef FMU_OWN_TABLE
#define TRIBO_ENUM_ITEM(id, name, value, description) {name, value, description},
#include FMU_OWN_TABLE
#endif
};

#define N_ITEMS (sizeof ITEMS / sizeof ITEMS[0])

const fmu_enumeration *fmu_enumerations(size_t *count)
{
    if (count)
        *count = N_ENUMERATIONS;
    return ENUMERATIONS;
}

const fmu_enum_item *fmu_enum_items(int enumeration, size_t *count)
{
    size_t first = 0, n = 0;
    while (first < N_ITEMS && ITEM_ENUMERATION[first] != enumeration)
        first++;
    while (first + n < N_ITEMS && ITEM_ENUMERATION[first + n] == enumeration)
        n++;
    *count = n;
    return n ? &ITEMS[first] : NULL;
}

#define N_VARIABLES (sizeof VARIABLES / sizeof VARIABLES[0])

const fmu_variable *fmu_variables(size_t *count)
{
    if (count)
        *count = N_VARIABLES;
    return VARIABLES;
}

const fmu_unit *fmu_units(size_t *count)
{
    if (count)
        *count = sizeof UNITS / sizeof UNITS[0];
    return UNITS;
}

const fmu_display_unit *fmu_display_units(const char *unit, size_t *index)
{
    for (size_t i = *index; i < sizeof DISPLAY_UNITS / sizeof DISPLAY_UNITS[0]; i++)
        if (DISPLAY_UNITS[i].name && strcmp(DISPLAY_UNITS[i].unit, unit) == 0) {
            *index = i + 1;
            return &DISPLAY_UNITS[i];
        }
    return NULL;
}

const fmu_unit *fmu_unit_find(const char *name)
{
    for (size_t u = 0; u < sizeof UNITS / sizeof UNITS[0]; u++)
        if (strcmp(UNITS[u].name, name) == 0)
            return &UNITS[u];
    return NULL;
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
    case FMU_MAPS_TO_PARAMETER: return &fmu_front_params(NULL)[v->index];
    case FMU_MAPS_TO_INPUT: return &fmu_front_inputs()[v->index];
    case FMU_MAPS_TO_INSTANCE: return &HOLD_AT_END;
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
    case FMU_TYPE_BOOLEAN: return "Boolean";
    case FMU_TYPE_ENUMERATION: return "Enumeration";
    }
    return "?";
}

const char *fmu_causality_name(fmu_causality causality, int fmi_version)
{
    switch (causality) {
    /* FMI 2.0: the FMU's time is a local variable, readable; the independent one is
       implicit there. Declared independent, it leaves an FMI 2.0 importer no right answer:
       the standard forbids it a start value, which the FMI Library (libcosim's) requires */
    case FMU_CAUSALITY_INDEPENDENT: return fmi_version == 2 ? "local" : "independent";
    case FMU_CAUSALITY_PARAMETER: return "parameter";
    case FMU_CAUSALITY_STRUCTURAL_PARAMETER:
        return fmi_version == 2 ? "parameter" : "structuralParameter";
    case FMU_CAUSALITY_INPUT: return "input";
    case FMU_CAUSALITY_OUTPUT: return "output";
    case FMU_CAUSALITY_CALCULATED_PARAMETER: return "calculatedParameter";
    }
    return "?";
}

const char *fmu_variability_name(fmu_variability variability)
{
    switch (variability) {
    case FMU_VARIABILITY_FIXED: return "fixed";
    case FMU_VARIABILITY_TUNABLE: return "tunable";
    case FMU_VARIABILITY_DISCRETE: return "discrete";
    case FMU_VARIABILITY_CONTINUOUS: return "continuous";
    }
    return "?";
}

/*
 * variables.h: the FMU's variables, one table for FMI 2.0 and FMI 3.0, made from the
 * front end's table (src/chute/quantities.def or src/si/si_quantities.def: front_end.h), row for row.
 *
 * Each row says what the importer sees (value reference, name, type, causality,
 * variability, description, unit) and what it maps to (a parameter of the front end's
 * scene, a quantity of the front end (fmu_front_get), an input, a segment-charge array).
 * Parameters' ranges and start values are the front end's table's (fmu_front_params). The modelDescription files are
 * generated from this table at build time (tools/model_description.c).
 */
#ifndef TRIBO_FMU_VARIABLES_H
#define TRIBO_FMU_VARIABLES_H

#include <stddef.h>

#include "tribo.h"

typedef unsigned int fmu_vr;

/* Version-neutral types; each FMI version names them its own way (fmu_type_name). */
typedef enum fmu_type {
    FMU_TYPE_REAL,       /* FMI 2.0 Real,    FMI 3.0 Float64 */
    FMU_TYPE_INTEGER,    /* FMI 2.0 Integer, FMI 3.0 Int32   */
    FMU_TYPE_COUNT,      /* FMI 2.0 Integer, FMI 3.0 UInt64: sizes arrays in FMI 3.0 */
    FMU_TYPE_BOOLEAN,    /* FMI 2.0 Boolean, FMI 3.0 Boolean */
    FMU_TYPE_ENUMERATION /* FMI 2.0 and 3.0 Enumeration (FMI 3.0: accessed as Int64) */
} fmu_type;

typedef enum fmu_causality {
    FMU_CAUSALITY_INDEPENDENT,
    FMU_CAUSALITY_PARAMETER,
    /* FMI 3.0 structuralParameter (it sizes arrays); a plain parameter in FMI 2.0 */
    FMU_CAUSALITY_STRUCTURAL_PARAMETER,
    FMU_CAUSALITY_INPUT,
    FMU_CAUSALITY_OUTPUT,
    /* a number derived from the parameters alone (TRIBO_CALCULATED rows) */
    FMU_CAUSALITY_CALCULATED_PARAMETER
} fmu_causality;

typedef enum fmu_variability {
    FMU_VARIABILITY_FIXED,
    FMU_VARIABILITY_TUNABLE,
    FMU_VARIABILITY_DISCRETE, /* outputs that are not reals: they change only at events */
    FMU_VARIABILITY_CONTINUOUS
} fmu_variability;

typedef enum fmu_mapping {
    FMU_MAPS_TO_TIME,       /* the FMU's time: start time + the core's time */
    FMU_MAPS_TO_PARAMETER,  /* the scene parameter of the same name         */
    FMU_MAPS_TO_INPUT,      /* index: the front end's input (tribo_input order) */
    FMU_MAPS_TO_QUANTITY,   /* index: the front end's quantity (fmu_front_get) */
    FMU_MAPS_TO_SEGMENTS,   /* index: tribo_segment_charge, n_segments values */
    FMU_MAPS_TO_INSTANCE    /* the FMU layer's own parameter, hold_at_end (instance.h) */
} fmu_mapping;

/* hold_at_end's value reference: free in every front end's table (the tables' parameters
   are below 100, their registered switches from 60 on) */
#define FMU_HOLD_AT_END_VR 50u


/* Which FMI versions declare a variable (arrays exist in FMI 3.0 only). */
enum { FMU_IN_FMI2 = 1, FMU_IN_FMI3 = 2, FMU_IN_BOTH = 3 };

typedef struct fmu_variable {
    fmu_vr vr;
    const char *name;
    fmu_type type;
    fmu_causality causality;
    fmu_variability variability;
    fmu_mapping maps_to;
    int index;          /* see fmu_mapping; for parameters, the row in fmu_front_params */
    unsigned versions;  /* FMU_IN_* */
    const char *description;
    const char *unit;
    int enumeration;    /* FMU_TYPE_ENUMERATION: its index in fmu_enumerations; else -1 */
} fmu_variable;

/* The units the variables name (the TRIBO_UNIT rows). */
typedef struct fmu_unit {
    const char *name;
    const char *quantity;     /* the FMI quantity of its variables; "" for none */
    const char *base_unit;    /* FMI BaseUnit attributes; "" for a dimensionless unit */
    const char *display_unit; /* NULL: displayed as itself */
    double display_factor;    /* display value = display_factor * value */
    const char *description;
} fmu_unit;

/* A unit importers may display a unit's values in (display value = factor * value). */
typedef struct fmu_display_unit {
    const char *unit, *name;
    double factor;
} fmu_display_unit;

/* The enumeration types (TRIBO_ENUMERATION rows) and their items (TRIBO_ENUM_ITEM). */
typedef struct fmu_enum_item {
    const char *name;
    int value;
    const char *description;
} fmu_enum_item;

typedef struct fmu_enumeration {
    const char *type_name;
    const char *description;
} fmu_enumeration;

const fmu_variable *fmu_variables(size_t *count);
const fmu_unit *fmu_units(size_t *count);
/* The unit named `name`, or NULL. */
const fmu_unit *fmu_unit_find(const char *name);
/* The display units of `unit`, one per call from *index on (start at 0), or NULL after
   the last. */
const fmu_display_unit *fmu_display_units(const char *unit, size_t *index);
const fmu_enumeration *fmu_enumerations(size_t *count);
/* The items of the enumeration with index `enumeration`, in increasing value. */
const fmu_enum_item *fmu_enum_items(int enumeration, size_t *count);
/* A value reference that a published variable had and no row takes again (TRIBO_RETIRED
   rows of the front end's table): what to use instead. */
typedef struct fmu_retired {
    fmu_vr vr;
    const char *name;    /* the variable that had it */
    const char *instead; /* what to use */
} fmu_retired;
/* The retired value reference vr, or NULL. */
const fmu_retired *fmu_retired_find(fmu_vr vr);

/* The row with value reference vr declared in FMI version fmi_version, or NULL. */
const fmu_variable *fmu_variable_find(fmu_vr vr, int fmi_version);
int fmu_variable_in_version(const fmu_variable *v, int fmi_version);

/* The front end's entry of a parameter or an input row: its range, start value, ... (NULL for
   other rows). */
const tribo_param_info *fmu_variable_param(const fmu_variable *v);
/* The parameter that sizes an array row (NULL for scalars). */
const fmu_variable *fmu_variable_dimension(const fmu_variable *v);

/* "Real", "Integer", "Boolean", "Enumeration", "Float64", "Int32", "UInt64" */
const char *fmu_type_name(fmu_type type, int fmi_version);
/* "parameter", "structuralParameter" (FMI 3.0 only), "input", ... */
const char *fmu_causality_name(fmu_causality causality, int fmi_version);
const char *fmu_variability_name(fmu_variability variability);

#endif

/*
 * variables.h: the FMU's variables, one table for FMI 2.0 and FMI 3.0.
 *
 * Each row says what the importer sees (value reference, name, type, causality,
 * variability) and what the row maps to in the core (a parameter of the scene, a
 * quantity of tribo_get, an external force, a segment-charge array). Parameters take
 * their description, unit, range and start value from the core's parameter table,
 * so the physics is described once, in src/params.c.
 *
 * The two modelDescription.xml files restate this table; tests/python checks that
 * they agree with it (through the tribo_fmu_variables tool, which prints it as JSON).
 */
#ifndef TRIBO_FMU_VARIABLES_H
#define TRIBO_FMU_VARIABLES_H

#include <stddef.h>

#include "tribo.h"

typedef unsigned int fmu_vr;

/* Version-neutral types; each FMI version names them its own way (fmu_type_name). */
typedef enum fmu_type {
    FMU_TYPE_REAL,    /* FMI 2.0 Real,    FMI 3.0 Float64 */
    FMU_TYPE_INTEGER, /* FMI 2.0 Integer, FMI 3.0 Int32   */
    FMU_TYPE_COUNT    /* FMI 2.0 Integer, FMI 3.0 UInt64: sizes arrays in FMI 3.0 */
} fmu_type;

typedef enum fmu_causality {
    FMU_CAUSALITY_INDEPENDENT,
    FMU_CAUSALITY_PARAMETER,
    /* FMI 3.0 structuralParameter (it sizes arrays); a plain parameter in FMI 2.0 */
    FMU_CAUSALITY_STRUCTURAL_PARAMETER,
    FMU_CAUSALITY_INPUT,
    FMU_CAUSALITY_OUTPUT
} fmu_causality;

typedef enum fmu_variability {
    FMU_VARIABILITY_FIXED,
    FMU_VARIABILITY_TUNABLE,
    FMU_VARIABILITY_CONTINUOUS
} fmu_variability;

typedef enum fmu_mapping {
    FMU_MAPS_TO_TIME,       /* the FMU's time: start time + the core's time */
    FMU_MAPS_TO_PARAMETER,  /* the scene parameter of the same name         */
    FMU_MAPS_TO_INPUT,      /* index: FMU_INPUT_*                           */
    FMU_MAPS_TO_QUANTITY,   /* index: tribo_quantity                        */
    FMU_MAPS_TO_SEGMENTS    /* index: tribo_segment_charge, n_segments values */
} fmu_mapping;

enum { FMU_INPUT_F_T, FMU_INPUT_F_N, FMU_INPUT_COUNT };

/* Which FMI versions declare a variable (arrays exist in FMI 3.0 only). */
enum { FMU_IN_FMI2 = 1, FMU_IN_FMI3 = 2, FMU_IN_BOTH = 3 };

typedef struct fmu_variable {
    fmu_vr vr;
    const char *name;
    fmu_type type;
    fmu_causality causality;
    fmu_variability variability;
    fmu_mapping maps_to;
    int index;          /* see fmu_mapping; unused for the time and parameters */
    unsigned versions;  /* FMU_IN_* */
    const char *description; /* NULL for parameters: the core's table has it */
    const char *unit;        /* NULL for parameters */
} fmu_variable;

/* Changing the table (or anything importers see in modelDescription.xml) means a new
   token in both modelDescription files. */
#define FMU_INSTANTIATION_TOKEN "{8c1d7f0e-5b3a-4e52-9a61-3f0e1c2b7a01}"

const fmu_variable *fmu_variables(size_t *count);
/* The row with value reference vr declared in FMI version fmi_version, or NULL. */
const fmu_variable *fmu_variable_find(fmu_vr vr, int fmi_version);
/* The row named name, or NULL. */
const fmu_variable *fmu_variable_named(const char *name);
int fmu_variable_in_version(const fmu_variable *v, int fmi_version);

/* The core's entry of a parameter row (NULL for other rows). */
const tribo_param_info *fmu_variable_param(const fmu_variable *v);
const char *fmu_variable_description(const fmu_variable *v);
const char *fmu_variable_unit(const fmu_variable *v);

/* "Real", "Integer", "Float64", "Int32", "UInt64" */
const char *fmu_type_name(fmu_type type, int fmi_version);
/* "parameter", "structuralParameter" (FMI 3.0 only), "input", ... */
const char *fmu_causality_name(fmu_causality causality, int fmi_version);
const char *fmu_variability_name(fmu_variability variability);

#endif

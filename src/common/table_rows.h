/*
 * table_rows.h: every kind of row of the tables (quantities.def, si_quantities.def) that the
 * including file leaves undefined expands to nothing. A table includes this first and
 * table_end.h last; quantities.def describes the rows.
 */
#ifndef TRIBO_PARAMETER
#define TRIBO_PARAMETER(name, type, vr, unit, min, min_end, max, max_end, start, variability, description)
#endif
/* A reader of TRIBO_PARAMETER rows that does not read ranges (a struct's fields, the FMUs'
   variables) reads a TRIBO_SAME_PARAMETER row as one; the reader that does (si.c) defines it
   itself. TRIBO_MODEL_RANGE is defined nowhere, so that any other reader of the range fails
   to compile rather than read a made-up one. */
#ifndef TRIBO_SAME_PARAMETER
#define TRIBO_SAME_PARAMETER(name, type, vr, unit, start, variability, description)               \
    TRIBO_PARAMETER(name, type, vr, unit, TRIBO_MODEL_RANGE, MODEL_RANGE_END, TRIBO_MODEL_RANGE,   \
                    MODEL_RANGE_END, start, variability, description)
#endif
#ifndef TRIBO_MAPS
#define TRIBO_MAPS(name, model, how)
#endif
#ifndef TRIBO_DERIVES
#define TRIBO_DERIVES(model, description)
#endif
#ifndef TRIBO_TIME
#define TRIBO_TIME(id, name, vr, unit, description, value)
#endif
#ifndef TRIBO_INPUT
#define TRIBO_INPUT(id, name, vr, unit, min, max, description)
#endif
#ifndef TRIBO_OUTPUT
#define TRIBO_OUTPUT(id, name, type, vr, unit, description, value)
#endif
#ifndef TRIBO_CALCULATED
#define TRIBO_CALCULATED(id, name, vr, unit, variability, description, value)
#endif
#ifndef TRIBO_SEGMENTS
#define TRIBO_SEGMENTS(id, name, vr, unit, description)
#endif
#ifndef TRIBO_UNIT
#define TRIBO_UNIT(name, quantity, base_unit, display_unit, display_factor, description)
#endif
#ifndef TRIBO_DISPLAY_UNIT
#define TRIBO_DISPLAY_UNIT(unit, name, factor)
#endif
#ifndef TRIBO_ENUMERATION
#define TRIBO_ENUMERATION(id, type_name, description)
#endif
#ifndef TRIBO_ENUM_ITEM
#define TRIBO_ENUM_ITEM(id, name, value, description)
#endif
#ifndef TRIBO_RETIRED
#define TRIBO_RETIRED(kind, vr, name, instead)
#endif

/*
 * param_table.h: a table of parameters (tribo_param_info rows over one struct) and what is
 * done with one by name, value or string (param_table.c), whichever table it is: the model's
 * scene (quantities.def, scene.c), the SI front end's (si_quantities.def, si.c) or the
 * separator's (separator_quantities.def). Internal to the core.
 */
#ifndef TRIBO_PARAM_TABLE_H
#define TRIBO_PARAM_TABLE_H

#include <stddef.h>

#include "tribo.h"

/* A table's rows as tribo_param_info initialisers: a TRIBO_PARAMETER row of the struct
   `scene_type`, and a TRIBO_INPUT row (a real, tunable, both ends closed, start 0). A row
   whose range comes from another table (si.c) is initialised in two parts: all but the
   range, then the range. */
#define TRIBO_CLOSED 1
#define TRIBO_OPEN 0
#define TRIBO_TYPE_ENUM(enumeration) TRIBO_TYPE_ENUM
#define TRIBO_PARAM_FIELDS_BUT_RANGE(scene_type, name_, type_, vr_, unit_, start_, variability_,  \
                                     description_)                                             \
    .name = #name_, .description = description_, .unit = unit_, .vr = vr_,                     \
    .offset = offsetof(scene_type, name_), .type = TRIBO_TYPE_##type_, .start = start_,         \
    .variability = TRIBO_PARAM_##variability_
#define TRIBO_PARAM_RANGE(min_, min_end, max_, max_end)                                          \
    .min = min_, .max = max_, .min_inclusive = TRIBO_##min_end, .max_inclusive = TRIBO_##max_end
#define TRIBO_PARAM_INFO(scene_type, name_, type_, vr_, unit_, min_, min_end, max_, max_end,     \
                         start_, variability_, description_)                                    \
    {TRIBO_PARAM_FIELDS_BUT_RANGE(scene_type, name_, type_, vr_, unit_, start_, variability_,    \
                                  description_),                                                \
     TRIBO_PARAM_RANGE(min_, min_end, max_, max_end)}
#define TRIBO_INPUT_INFO(name_, vr_, unit_, min_, max_, description_)                           \
    {.name = name_, .description = description_, .unit = unit_, .vr = vr_,                     \
     .type = TRIBO_TYPE_REAL, .min = min_, .max = max_, .min_inclusive = TRIBO_CLOSED,         \
     .max_inclusive = TRIBO_CLOSED, .start = 0.0, .variability = TRIBO_PARAM_TUNABLE}

/* A parameter taken out of the table (its TRIBO_RETIRED row of kind PARAMETER): setting it
   by name is refused with `instead`. */
typedef struct tribo_param_retired {
    const char *name;
    const char *instead;
} tribo_param_retired;
/* The retired parameters of a table, each row of kind PARAMETER, ending in a NULL name. */
#define TRIBO_RETIRED_PARAMETER(name, instead) {name, instead},
#define TRIBO_RETIRED_OUTPUT(name, instead)
#define TRIBO_PARAM_RETIRED_ROW(kind, vr, name, instead) TRIBO_RETIRED_##kind(name, instead)

typedef struct tribo_param_table_of {
    const tribo_param_info *rows;
    size_t n;
    const tribo_param_retired *retired; /* NULL: none */
} tribo_param_table_of;

/* The name of the scene's parameter `field` as its row in quantities.def gives it, and the
   name of the item `value` of its enumeration ("?" for none): a message that names a
   parameter or a choice takes the name from the table, and one naming a field the table no
   longer has does not compile. */
#define TRIBO_PARAM_NAME(field) (tribo_param_of_field(offsetof(tribo_scene, field))->name)
#define TRIBO_PARAM_ITEM_NAME(field, value) tribo_param_item_name(offsetof(tribo_scene, field), value)
const tribo_param_info *tribo_param_of_field(size_t offset);
const char *tribo_param_item_name(size_t offset, int value);
/* Why the scene has no parameter `name` where quantities.def retired it (what to use
   instead), or NULL. */
const char *tribo_param_retired_why(const char *name);

/* Every row at its start value (the rest of the struct zero). */
void tribo_table_defaults(tribo_param_table_of t, void *scene, size_t scene_size);
/* The row named `name`, or NULL. */
const tribo_param_info *tribo_table_find(tribo_param_table_of t, const char *name);
/* What to use instead of the retired parameter `name`, or NULL where it is none. */
const char *tribo_table_retired(tribo_param_table_of t, const char *name);
/* Set `name` to `value` after checking it (tribo_param_check); an unknown name is refused,
   a retired one saying what to use instead. */
tribo_status tribo_table_set(tribo_param_table_of t, void *scene, const char *name, double value,
                             char *msg, size_t msg_size);
/* "name=value name=value ...", each with tribo_table_set; stops at the first refused. */
tribo_status tribo_table_apply(tribo_param_table_of t, void *scene, const char *settings, char *msg,
                               size_t msg_size);
/* Every row's value checked; the first failure is reported. */
tribo_status tribo_table_validate(tribo_param_table_of t, const void *scene, char *msg, size_t msg_size);

#endif

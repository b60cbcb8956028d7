/* scene.c: the scene's parameters (quantities.def): defaults, valid ranges, validation
   (through the table machinery every core shares, param_table.h). */
#include "param_table.h"

#include <math.h> /* M_PI, INFINITY in quantities.def */
#include <stdio.h>
#include <string.h>

/* The rows of quantities.def. Every bound is finite: the ranges are what the model can
   compute (beyond them the arithmetic overflows, or the work of a step has no bound); a cap
   with another reason says so in its description. The one infinite bound, chute_length's,
   is the plate without end. */
static const tribo_param_info PARAMS[] = {
#define TRIBO_PARAMETER(...) TRIBO_PARAM_INFO(tribo_scene, __VA_ARGS__),
#include "quantities.def"
};

#define N_PARAMS (sizeof PARAMS / sizeof PARAMS[0])
static const tribo_param_retired RETIRED[] = {
#define TRIBO_RETIRED TRIBO_PARAM_RETIRED_ROW
#include "quantities.def"
    {NULL, NULL}};
static const tribo_param_table_of TABLE = {PARAMS, N_PARAMS, RETIRED};

static const tribo_param_info INPUTS[TRIBO_INPUT_COUNT] = {
#define TRIBO_INPUT(id_, ...) [TRIBO_INPUT_##id_] = TRIBO_INPUT_INFO(__VA_ARGS__),
#include "quantities.def"
};

const tribo_param_info *tribo_input_table(size_t *count)
{
    if (count)
        *count = TRIBO_INPUT_COUNT;
    return INPUTS;
}

void tribo_scene_defaults(tribo_scene *s) { tribo_table_defaults(TABLE, s, sizeof *s); }

const tribo_param_info *tribo_param_table(size_t *count)
{
    if (count)
        *count = N_PARAMS;
    return PARAMS;
}

const tribo_param_info *tribo_param_find(const char *name) { return tribo_table_find(TABLE, name); }

const char *tribo_param_retired_why(const char *name) { return tribo_table_retired(TABLE, name); }

const tribo_param_info *tribo_param_of_field(size_t offset)
{
    for (size_t i = 0; i < N_PARAMS; i++)
        if (PARAMS[i].offset == offset)
            return &PARAMS[i];
    return NULL;
}

/* The enumeration of each parameter (parallel to PARAMS), NULL for a number, and every item. */
#define ENUMERATION_OF_REAL NULL
#define ENUMERATION_OF_INTEGER NULL
#define ENUMERATION_OF_COUNT NULL
#define ENUMERATION_OF_ENUM(id) #id
static const char *const ENUMERATION_OF[N_PARAMS] = {
#define TRIBO_PARAMETER(name, type, ...) ENUMERATION_OF_##type,
#include "quantities.def"
};
static const struct {
    const char *enumeration, *name;
    int value;
} ITEMS[] = {
#define TRIBO_ENUM_ITEM(id, name, value, description) {#id, name, value},
#include "quantities.def"
};

const char *tribo_param_item_name(size_t offset, int value)
{
    const tribo_param_info *p = tribo_param_of_field(offset);
    const char *enumeration = p ? ENUMERATION_OF[p - PARAMS] : NULL;
    for (size_t i = 0; enumeration && i < sizeof ITEMS / sizeof ITEMS[0]; i++)
        if (strcmp(ITEMS[i].enumeration, enumeration) == 0 && ITEMS[i].value == value)
            return ITEMS[i].name;
    return "?";
}

tribo_status tribo_scene_set(tribo_scene *scene, const char *name, double value, char *msg,
                             size_t msg_size)
{
    return tribo_table_set(TABLE, scene, name, value, msg, msg_size);
}

tribo_status tribo_scene_apply(tribo_scene *scene, const char *settings, char *msg,
                               size_t msg_size)
{
    return tribo_table_apply(TABLE, scene, settings, msg, msg_size);
}

tribo_status tribo_scene_validate(const tribo_scene *scene, char *msg, size_t msg_size)
{
    const tribo_status st = tribo_table_validate(TABLE, scene, msg, msg_size);
    return st != TRIBO_OK ? st : tribo_scene_check_combinations(scene, msg, msg_size);
}

int tribo_rigid_stick_allowed(int integrator, int damping_point)
{
    return integrator != TRIBO_INTEGRATOR_FIXED_STEP && damping_point != TRIBO_DAMPING_CENTRE;
}

tribo_status tribo_scene_check_combinations(const tribo_scene *scene, char *msg, size_t msg_size)
{
    /* the drop lies on the chute (model.md §9) */
    if (!(scene->X0 < scene->chute_length)) {
        if (msg && msg_size)
            snprintf(msg, msg_size,
                     "X0 = %.17g is invalid with chute_length = %.17g: the particle must start "
                     "before the end of the chute, X0 < chute_length",
                     scene->X0, scene->chute_length);
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    /* the rigid stick is a phase of the event-driven integrator, held by the contact point's
       normal lock (model.md §3b): the fixed step has no phases, and the centre dashpot's
       lock does not hold the contact point */
    if (scene->stick_model == TRIBO_STICK_RIGID && scene->integrator == TRIBO_INTEGRATOR_FIXED_STEP) {
        if (msg && msg_size)
            snprintf(msg, msg_size,
                     "stick_model = 1 (rigid) is invalid with integrator = 0 (fixed_step): the rigid "
                     "stick needs CVODE (integrator = 1 or 2), or set stick_model = 0 (compliant)");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    if (scene->stick_model == TRIBO_STICK_RIGID && scene->damping_point == TRIBO_DAMPING_CENTRE) {
        if (msg && msg_size)
            snprintf(msg, msg_size,
                     "stick_model = 1 (rigid) is invalid with damping_point = 1 (centre): the rigid "
                     "stick needs the contact point's normal lock (damping_point = 0), or set "
                     "stick_model = 0 (compliant)");
        return TRIBO_ERR_INVALID_ARGUMENT;
    }
    return TRIBO_OK;
}

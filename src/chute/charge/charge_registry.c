/* charge_registry.c: the registry of charge models, made from charge_registry.def's rows. */
#include "charge_registry.h"

const tribo_charge_model *const TRIBO_CHARGE_MODELS[TRIBO_SEGMENTS_COUNT] = {
#define TRIBO_CHARGE_MODEL(id, name, slot, model, on, values) [TRIBO_SEGMENTS_##id] = &model,
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL
};

/* a row's slot is its place: the value references follow it */
#define TRIBO_CHARGE_MODEL(id, name, slot, model, on, values)                                   \
    _Static_assert(TRIBO_SEGMENTS_##id == (slot), "charge_registry.def: " #name "'s slot is not its place");
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL

unsigned tribo_charge_selection(const tribo_scene *s)
{
    unsigned on = 0;
#define TRIBO_CHARGE_MODEL(id, name, slot, model, on_, values)                                  \
    if (s->charge_model_##name)                                                                       \
        on |= 1u << TRIBO_SEGMENTS_##id;
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL
    return on;
}

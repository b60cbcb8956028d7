/* charge_registry.c: the registry of charge models, made from charge_registry.def's rows. */
#include "charge_registry.h"

#include <math.h>

#include "model.h"

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
    const unsigned legacy = (1u << TRIBO_CHARGE_MODEL_LEGACY) - 1u;
    return on & (~legacy | ((unsigned)s->charge_model & legacy));
}

/* ---- every model's outputs of the breakdown limit (docs/model.md §8b) -------------------- */

double tribo_capped_fraction(tribo_model *m, int index)
{
    const tribo_charge_view v = tribo_charge_view_of(m, index);
    const tribo_charge_model *model = m->charging.slot[index].model;
    /* without a limit nothing stands at it: no copy of the segments is made to say so */
    if (!v.selected || !model->cap || !isfinite(model->cap(&m->scene)))
        return 0.0;
    const double *values = tribo_charge_values_of(m, index);
    if (!values)
        return NAN;
    return (double)tribo_charging_capped(&m->charging.slot[index], &m->scene, values, v.n) /
           v.n;
}

double tribo_charge_lost(tribo_model *m, int index)
{
    const tribo_charge_view v = tribo_charge_view_of(m, index);
    if (!v.selected)
        return 0.0;
    /* the mean over the segments, in the units of the model's array (segment_values is
       linear) */
    const double mean = v.lost / v.n;
    double reported;
    m->charging.slot[index].model->segment_values(&m->scene, v.globals, &mean, &reported, 1);
    return reported;
}

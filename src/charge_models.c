/* charge_models.c: the registry of charge models: one line per model. */
#include "charge_models.h"

const tribo_charge_model *const TRIBO_CHARGE_MODELS[TRIBO_SEGMENTS_COUNT] = {
    [TRIBO_SEGMENTS_STATIC] = &tribo_charge_static,
    [TRIBO_SEGMENTS_SLIDING] = &tribo_charge_sliding,
};

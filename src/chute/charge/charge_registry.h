/* charge_registry.h: the registered charge models (charge_registry.def) and what they
   contribute to the outputs. */
#ifndef TRIBO_CHARGE_MODELS_H
#define TRIBO_CHARGE_MODELS_H

#include "charge_interface.h"

/* The models an instance made by tribo_create knows, in the order of the segment arrays
   (TRIBO_SEGMENTS_<id>, the registry's slots). */
extern const tribo_charge_model *const TRIBO_CHARGE_MODELS[TRIBO_SEGMENTS_COUNT];

#define TRIBO_CHARGE_MODEL(id, name, slot, model, on, values) extern const tribo_charge_model model;
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL

/* The registered models a scene includes: bit i for TRIBO_CHARGE_MODELS[i], where its switch
   charge_model_<name> is on. */
unsigned tribo_charge_selection(const tribo_scene *s);

/* The outputs of the models' own (quantities.def's rows), each defined in its model's file
   from the model's view at the output point (the table's accessor passes
   tribo_charge_view_of(m, TRIBO_SEGMENTS_<id>)). */
double tribo_static_charge(tribo_charge_view v);
double tribo_sliding_charge(tribo_charge_view v);
double tribo_sliding_mean_density(tribo_charge_view v);
double tribo_sliding_saturation(tribo_charge_view v);
double tribo_sliding_work(tribo_charge_view v);

#endif

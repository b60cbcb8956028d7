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
   charge_model_<name> is on and, for the first TRIBO_CHARGE_MODEL_LEGACY slots (static, sliding),
   bit i of the older charge_model is set too. */
#define TRIBO_CHARGE_MODEL_LEGACY 2
unsigned tribo_charge_selection(const tribo_scene *s);

/* A model's state at the output point of an instance. */
typedef struct tribo_charge_view {
    const tribo_scene *scene;
    int selected;
    int n;
    double sum;                /* of its n values, pending updates included (NaN: out of memory) */
    double lost;               /* the sum of what the breakdown limit took, pending included */
    const double *globals;     /* its global states */
    const double *quadratures; /* its quadratures   */
} tribo_charge_view;

/* The view of the model at `index` of the instance's model set (model.c). */
tribo_charge_view tribo_charge_view_of(tribo_model *m, int index);

/* Every model's outputs of the breakdown limit (docs/model.md §8b): the fraction of its
   segments at the limit, and the charge lost to the gas as a mean over the segments in the
   units of its array (0 for a model the scene leaves out). */
double tribo_capped_fraction(tribo_model *m, int index);
double tribo_charge_lost(tribo_model *m, int index);

/* The outputs the models contribute (quantities.def). */
double tribo_static_charge(tribo_model *m);
double tribo_sliding_charge(tribo_model *m);
double tribo_sliding_mean_density(tribo_model *m);
double tribo_sliding_saturation(tribo_model *m);
double tribo_sliding_work(tribo_model *m);

#endif

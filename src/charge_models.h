/* charge_models.h: the registered charge models and what they contribute to the outputs. */
#ifndef TRIBO_CHARGE_MODELS_H
#define TRIBO_CHARGE_MODELS_H

#include "charge_model.h"

/* The models an instance made by tribo_create knows, in the order of the segment arrays
   (TRIBO_SEGMENTS_<id>); scene.charge_model selects model i with bit (1 << i). */
extern const tribo_charge_model *const TRIBO_CHARGE_MODELS[TRIBO_SEGMENTS_COUNT];

extern const tribo_charge_model tribo_charge_static;  /* §5a */
extern const tribo_charge_model tribo_charge_sliding; /* §5b */

/* A model's state at the output point of an instance. */
typedef struct tribo_charge_view {
    const tribo_scene *scene;
    int selected;
    int n;
    double sum;                /* of its n values, pending updates included (NaN: out of memory) */
    const double *globals;     /* its global states */
    const double *quadratures; /* its quadratures   */
} tribo_charge_view;

/* The view of the model at `index` of the instance's model set (model.c). */
tribo_charge_view tribo_charge_view_of(tribo_model *m, int index);

/* The outputs the models contribute (quantities.def). */
double tribo_static_charge(tribo_model *m);
double tribo_sliding_charge(tribo_model *m);
double tribo_sliding_mean_density(tribo_model *m);
double tribo_sliding_saturation(tribo_model *m);
double tribo_sliding_work(tribo_model *m);

#endif

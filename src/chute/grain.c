/* grain.c: the three-dimensional grain's charge (docs/model.md §8c): the prolate spheroid of
   semi-axes a, b, b, charged in bands under its contact patch. */
#include <math.h>

#include "geometry.h"
#include "model.h"

/* A charge of a model's own values times an area as the model reports its values
   (segment_values is linear). */
static double reported(tribo_model *m, int index, const tribo_charge_view *v, double own)
{
    double out;
    m->charging.slot[index].model->segment_values(&m->scene, v->globals, &own, &out, 1);
    return out;
}

double tribo_grain_charge(tribo_model *m, int index)
{
    const tribo_charge_view v = tribo_charge_view_of(m, index);
    if (!v.selected || !m->charging.keep_bands)
        return 0.0;
    const tribo_charge_model *model = m->charging.slot[index].model;
    /* Q = sigma_init (A_s - sum W L) + sum sigma_b W L; an indentation far outside the model's
       assumptions can make patches whose bands add up to more than the surface: then none of
       it is uncharged */
    const double uncharged = fmax(0.0, tribo_spheroid_area(m->scene.epsilon) - tribo_charged_area(m));
    return reported(m, index, &v, tribo_charging_initial_value(&m->charging, model, &m->scene) * uncharged +
                                      v.band_charge);
}

double tribo_grain_charge_lost(tribo_model *m, int index)
{
    const tribo_charge_view v = tribo_charge_view_of(m, index);
    if (!v.selected || !m->charging.keep_bands)
        return 0.0;
    return reported(m, index, &v, v.band_lost);
}

double tribo_grain_capped_area(tribo_model *m, int index)
{
    const tribo_charge_view v = tribo_charge_view_of(m, index);
    if (!v.selected || !m->charging.keep_bands)
        return 0.0;
    const tribo_band_geometry *g;
    const double *bands = tribo_charge_bands_of(m, index, &g);
    if (!bands)
        return NAN;
    return tribo_charging_capped_area(&m->charging, &m->charging.slot[index], &m->scene, bands, g);
}

double tribo_get_grain_charge(tribo_model *m, tribo_segment_charge which)
{
    return (unsigned)which < (unsigned)m->charging.n_models ? tribo_grain_charge(m, which) : 0.0;
}

double tribo_get_grain_charge_lost(tribo_model *m, tribo_segment_charge which)
{
    return (unsigned)which < (unsigned)m->charging.n_models ? tribo_grain_charge_lost(m, which) : 0.0;
}

double tribo_get_grain_capped_area(tribo_model *m, tribo_segment_charge which)
{
    return (unsigned)which < (unsigned)m->charging.n_models ? tribo_grain_capped_area(m, which) : 0.0;
}

/* charge_outputs.c: an instance's charges at its output point (the committed charges with
   the pending updates applied), each model's view of them, and what every model has: the
   mean of its values, the outputs of the breakdown limit (docs/model.md §8b). This file reads the instance (model.h) so that
   the charge models and their registry need not: a model's own outputs are computed in its
   file from the view made here (charge_interface.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"

int tribo_charges_out(tribo_model *m)
{
    tribo_charging *c = &m->charging;
    if (m->n_pending == 0 || m->charges_out_valid)
        return 1;
    if (tribo_charging_copy_out(c) != 0)
        return 0;
    for (size_t i = 0; i < m->n_pending; i++)
        tribo_charging_apply(c, &m->scene, &m->pending[i], TRIBO_CHARGE_PENDING);
    m->charges_out_valid = 1;
    return 1;
}

int tribo_pending_sums(tribo_model *m)
{
    if (m->pending_sums_valid)
        return 1;
    if (tribo_charging_pending_totals(&m->charging, &m->scene, m->pending, m->n_pending,
                                      &m->pending_totals) != 0)
        return 0;
    m->pending_sums_valid = 1;
    return 1;
}

tribo_charge_view tribo_charge_view_of(tribo_model *m, int index)
{
    const tribo_charge_slot *slot = &m->charging.slot[index];
    tribo_charge_view v = {&m->scene, slot->segments != NULL, m->charging.n, 0.0, 0.0, 0.0, 0.0,
                           m->out.charge_globals + slot->globals_at,
                           m->out.y + TRIBO_NMOTION + slot->quadratures_at};
    if (v.selected && tribo_pending_sums(m)) {
        const tribo_charging *c = &m->charging;
        const tribo_charge_totals *p = &m->pending_totals;
        v.sum = tribo_charging_sum(c, index) + p->sum[index];
        v.lost = tribo_charging_lost(c, index) + p->lost[index];
        v.band_charge = tribo_compensated_value(&c->band_charge[index]) + p->band_charge[index];
        v.band_lost = tribo_compensated_value(&c->band_lost[index]) + p->band_lost[index];
    } else if (v.selected) {
        v.sum = v.lost = v.band_charge = v.band_lost = NAN;
    }
    return v;
}

const double *tribo_charge_values_of(tribo_model *m, int index)
{
    const tribo_charge_slot *slot = &m->charging.slot[index];
    if (!tribo_charges_out(m))
        return NULL;
    return m->n_pending ? slot->segments_out : slot->segments;
}

const double *tribo_charge_bands_of(tribo_model *m, int index, const tribo_band_geometry **geometry)
{
    const tribo_charge_slot *slot = &m->charging.slot[index];
    if (!tribo_charges_out(m))
        return NULL;
    *geometry = m->n_pending ? &m->charging.bands_out : &m->charging.bands;
    return m->n_pending ? slot->bands_out : slot->bands;
}

double tribo_charged_area(tribo_model *m)
{
    if (!m->charging.keep_bands)
        return 0.0;
    if (!tribo_pending_sums(m))
        return NAN;
    return tribo_compensated_value(&m->charging.area) + m->pending_totals.area;
}

/* ---- every model's outputs of the breakdown limit (docs/model.md §8b) -------------------- */

double tribo_capped_fraction(tribo_model *m, int index)
{
    const tribo_charge_view v = tribo_charge_view_of(m, index);
    const tribo_charge_model *model = m->charging.slot[index].model;
    /* without a limit nothing stands at it: no copy of the segments is made to say so */
    if (!v.selected || !model->density_unit ||
        !isfinite(m->scene.Sigma_bd / model->density_unit(&m->scene)))
        return 0.0;
    const double *values = tribo_charge_values_of(m, index);
    if (!values)
        return NAN;
    return (double)tribo_charging_capped(&m->charging.slot[index], &m->scene, values, v.n) /
           v.n;
}

/* The mean over the segments of a sum of the model's own values, in the units of its
   reported values: segment_values is linear, so the mean of the reported values is the
   value reported for the mean of its own. */
static double reported_mean(tribo_model *m, int index, const tribo_charge_view *v, double sum)
{
    const double mean = sum / v->n;
    double reported;
    m->charging.slot[index].model->segment_values(&m->scene, v->globals, &mean, &reported, 1);
    return reported;
}

double tribo_charge_lost(tribo_model *m, int index)
{
    const tribo_charge_view v = tribo_charge_view_of(m, index);
    return v.selected ? reported_mean(m, index, &v, v.lost) : 0.0;
}

double tribo_get_mean_charge(tribo_model *m, tribo_segment_charge which)
{
    if (!m || (unsigned)which >= (unsigned)m->charging.n_models)
        return NAN;
    const tribo_charge_view v = tribo_charge_view_of(m, which);
    return v.selected ? reported_mean(m, which, &v, v.sum) : 0.0;
}

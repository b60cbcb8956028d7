/* charging.c: an instance's charge models over the boundary segments (docs/model.md §5). */
#include "charging.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int tribo_charging_init(tribo_charging *c, const tribo_charge_model *const *models, int n_models,
                        unsigned selection, double eps, int n)
{
    memset(c, 0, sizeof *c);
    if (n_models > TRIBO_CHARGE_MAX_MODELS)
        return -2;
    c->n_models = n_models;
    c->n = n;
    for (int i = 0; i < n_models; i++) {
        tribo_charge_slot *slot = &c->slot[i];
        slot->model = models[i];
        slot->selected = (selection >> i) & 1u;
        slot->globals_at = c->n_globals;
        slot->quadratures_at = c->n_quadratures;
        c->n_globals += models[i]->n_globals;
        c->n_quadratures += models[i]->n_quadratures;
        c->any_selected |= slot->selected;
    }
    if (c->n_globals > TRIBO_CHARGE_MAX_GLOBALS || c->n_quadratures > TRIBO_CHARGE_MAX_QUADRATURES)
        return -2;
    /* Without a selected model no segment table is built, and no segment is touched. */
    if (!c->any_selected)
        return 0;
    if (tribo_arclength_init(&c->arc, eps) != 0)
        goto fail;
    c->segments_per_length = (double)n / c->arc.perimeter;
    for (int i = 0; i < n_models; i++) {
        tribo_charge_slot *slot = &c->slot[i];
        if (!slot->selected)
            continue;
        if (!(slot->segments = malloc((size_t)n * sizeof *slot->segments)))
            goto fail;
        if (slot->model->cache_size && !(slot->cache = malloc(slot->model->cache_size)))
            goto fail;
    }
    tribo_charging_reset(c);
    return 0;
fail:
    tribo_charging_free(c);
    return -1;
}

void tribo_charging_free(tribo_charging *c)
{
    tribo_arclength_free(&c->arc);
    for (int i = 0; i < c->n_models; i++) {
        free(c->slot[i].segments);
        free(c->slot[i].segments_out);
        free(c->slot[i].cache);
        free(c->slot[i].window);
        c->slot[i].segments = c->slot[i].segments_out = c->slot[i].window = NULL;
        c->slot[i].window_cap = 0;
        c->slot[i].cache = NULL;
    }
}

void tribo_charging_reset(tribo_charging *c)
{
    for (int i = 0; i < c->n_models; i++) {
        tribo_charge_slot *slot = &c->slot[i];
        if (slot->segments)
            memset(slot->segments, 0, (size_t)c->n * sizeof *slot->segments);
        slot->sum = slot->sum_c = 0.0;
        slot->lost = slot->lost_c = 0.0;
        if (slot->cache)
            memset(slot->cache, 0, slot->model->cache_size);
    }
    memset(&c->decay, 0, sizeof c->decay);
}

void tribo_charging_start(const tribo_charging *c, const tribo_scene *s, double *globals)
{
    for (int i = 0; i < c->n_models; i++)
        if (c->slot[i].model->start)
            c->slot[i].model->start(s, globals + c->slot[i].globals_at);
}

void tribo_charging_quadrature_rates(const tribo_charging *c, const tribo_contact_kinematics *k,
                                     double *rates)
{
    for (int i = 0; i < c->n_models; i++) {
        const tribo_charge_slot *slot = &c->slot[i];
        for (int q = 0; q < slot->model->n_quadratures; q++)
            rates[slot->quadratures_at + q] =
                slot->selected ? slot->model->quadrature_rate(q, k) : 0.0;
    }
}

void tribo_charging_step(tribo_charging *c, const tribo_scene *s, const tribo_pose *pose,
                         double delta_y, double h, const double *q0, const double *q1,
                         const double *g0, double *g1, tribo_contact_sample *sample)
{
    sample->duration = h;
    const int in_contact = delta_y > 0.0;
    if (in_contact) {
        const double eps = c->arc.eps;
        const double rho_c = tribo_contact_curvature_radius(eps * eps, pose->h);
        tribo_charging_locate(c, tribo_arclength_at(&c->arc, tribo_contact_parameter(eps, pose)),
                              sqrt(rho_c * delta_y) /* Sc, §5 (paper eq. 4) */, sample);
    } else {
        sample->first = sample->count = 0;
    }
    memcpy(g1, g0, (size_t)c->n_globals * sizeof *g1);
    for (int i = 0; i < c->n_models; i++) {
        const tribo_charge_slot *slot = &c->slot[i];
        if (slot->selected && slot->model->n_globals)
            slot->model->step_globals(slot->cache, s, h, in_contact,
                                      q0 + slot->quadratures_at, q1 + slot->quadratures_at,
                                      g0 + slot->globals_at, g1 + slot->globals_at);
    }
    /* the globals taken linear over the step */
    for (int k = 0; k < c->n_globals; k++) {
        sample->globals_begin[k] = g0[k];
        sample->globals_mid[k] = 0.5 * (g0[k] + g1[k]);
        sample->globals_end[k] = g1[k];
    }
}

void tribo_compensated_add(double *sum, double *c, double x)
{
    const double t = *sum + x;
    *c += fabs(*sum) >= fabs(x) ? (*sum - t) + x : (x - t) + *sum;
    *sum = t;
}

void tribo_charging_run(const tribo_charging *c, double lo_segment, double hi_segment,
                        tribo_contact_sample *sample)
{
    /* in doubles until the values are known to fit a long */
    const double n = (double)c->n;
    if (!(hi_segment - lo_segment + 1.0 < n)) {
        sample->first = 0;
        sample->count = c->n;
        return;
    }
    double wrapped = lo_segment - n * floor(lo_segment / n);
    if (!(wrapped >= 0.0 && wrapped < n))
        wrapped = 0.0;
    sample->first = (long)wrapped;
    sample->count = (long)(hi_segment - lo_segment + 1.0);
}

void tribo_charging_locate(const tribo_charging *c, double s_centre, double half_width,
                           tribo_contact_sample *sample)
{
    const double lo = (s_centre - half_width) * c->segments_per_length;
    const double hi = (s_centre + half_width) * c->segments_per_length;
    if (!(hi - lo < (double)c->n)) { /* wider than the boundary, or not a number */
        sample->first = 0;
        sample->count = c->n;
        return;
    }
    tribo_charging_run(c, floor(lo), floor(hi), sample);
}

/* The run of segments a sample charges: none for an empty interval. */
static long segment_run(const tribo_contact_sample *sample, long *first)
{
    if (!(sample->duration > 0.0) || sample->count <= 0)
        return 0;
    *first = sample->first;
    return sample->count;
}

/* Hold values[0..count) within +-cap (§8b: charging that would raise a segment above the
   limit leaves it there); returns the charge so taken. The rate laws approach their
   saturation monotonically over a sample, so a value above the cap at its end reached it
   within the sample and stays: the excess at the end is what went to the gas. */
static double hold_at_cap(double *values, long count, double cap)
{
    double taken = 0.0;
    for (long i = 0; i < count; i++) {
        if (values[i] > cap) {
            taken += values[i] - cap;
            values[i] = cap;
        } else if (values[i] < -cap) {
            taken += values[i] + cap;
            values[i] = -cap;
        }
    }
    return taken;
}

/* The bound on a slot's values (INF: none). */
static double cap_of(const tribo_charge_slot *slot, const tribo_scene *s)
{
    return slot->model->cap ? slot->model->cap(s) : INFINITY;
}

/* The same, kept in the slot: a sample takes it without a call (or the division a model's
   units may cost) while Sigma_bd and Sigma0 stay. */
static double slot_cap(tribo_charge_slot *slot, const tribo_scene *s)
{
    if (!slot->cap_taken || slot->cap_Sigma_bd != s->Sigma_bd || slot->cap_Sigma0 != s->Sigma0) {
        slot->cap = cap_of(slot, s);
        slot->cap_Sigma_bd = s->Sigma_bd;
        slot->cap_Sigma0 = s->Sigma0;
        slot->cap_taken = 1;
    }
    return slot->cap;
}

/* Charge values[first .. first + count) of one model under a sample, in at most two
   contiguous slices of a ring of n values, held within its breakdown limit; returns the
   change of their sum, and adds the charge the limit took to *lost. */
static double charge_run(tribo_charging *c, tribo_charge_slot *slot, const tribo_scene *s,
                         const tribo_contact_sample *sample, double *values, long n, long first,
                         long count, double *lost)
{
    const tribo_charge_forcing f = {sample->duration, sample->globals_begin + slot->globals_at,
                                    sample->globals_mid + slot->globals_at,
                                    sample->globals_end + slot->globals_at, &c->decay};
    const long head = count < n - first ? count : n - first;
    double delta = slot->model->charge(slot->cache, s, &f, values + first, head);
    if (count > head)
        delta += slot->model->charge(slot->cache, s, &f, values, count - head);
    const double cap = slot_cap(slot, s);
    if (isfinite(cap)) { /* (without a limit, nothing more: the paper's model, bit for bit) */
        double taken = hold_at_cap(values + first, head, cap);
        if (count > head)
            taken += hold_at_cap(values, count - head, cap);
        delta -= taken;
        *lost += taken;
    }
    return delta;
}

long tribo_charging_capped(const tribo_charge_slot *slot, const tribo_scene *s, const double *values,
                           long n)
{
    const double cap = cap_of(slot, s);
    long capped = 0;
    if (isfinite(cap))
        for (long i = 0; i < n; i++)
            capped += fabs(values[i]) >= cap; /* held values are the cap exactly */
    return capped;
}

long tribo_charging_apply(tribo_charging *c, const tribo_scene *s, const tribo_contact_sample *sample,
                          tribo_charge_destination where)
{
    long first;
    const long count = segment_run(sample, &first);
    long updates = 0;
    for (int k = 0; count > 0 && k < c->n_models; k++) {
        tribo_charge_slot *slot = &c->slot[k];
        double *values = where == TRIBO_CHARGE_COMMIT ? slot->segments : slot->segments_out;
        if (!slot->selected || !values)
            continue;
        double lost = 0.0;
        const double delta = charge_run(c, slot, s, sample, values, c->n, first, count, &lost);
        if (where == TRIBO_CHARGE_COMMIT) {
            tribo_compensated_add(&slot->sum, &slot->sum_c, delta);
            if (lost != 0.0)
                tribo_compensated_add(&slot->lost, &slot->lost_c, lost);
        }
        updates += count;
    }
    return updates;
}

/* The pending samples' runs lie in one window of the ring (the contact moves
   continuously): the window is copied once and charged in place of the ring. */
int tribo_charging_pending_sums(tribo_charging *c, const tribo_scene *s,
                                const tribo_contact_sample *samples, size_t n_samples,
                                double *deltas, double *lost)
{
    const long n = c->n;
    long anchor = -1, lo = 0, hi = 0; /* the window [anchor + lo, anchor + hi), unwrapped */
    for (size_t i = 0; i < n_samples; i++) {
        long first;
        const long count = segment_run(&samples[i], &first);
        if (!count)
            continue;
        if (anchor < 0) {
            anchor = first;
            hi = count;
            continue;
        }
        long offset = (first - anchor) % n;
        if (offset < 0)
            offset += n;
        if (offset > n / 2)
            offset -= n; /* just before the anchor */
        lo = offset < lo ? offset : lo;
        hi = offset + count > hi ? offset + count : hi;
    }
    for (int k = 0; k < c->n_models; k++)
        deltas[k] = lost[k] = 0.0;
    if (anchor < 0)
        return 0;
    const long len = hi - lo < n ? hi - lo : n;
    long start = len < n ? (anchor + lo) % n : 0;
    if (start < 0)
        start += n;
    for (int k = 0; k < c->n_models; k++) {
        tribo_charge_slot *slot = &c->slot[k];
        if (!slot->selected || !slot->segments)
            continue;
        if (slot->window_cap < (size_t)len) {
            double *w = realloc(slot->window, (size_t)len * sizeof *w);
            if (!w)
                return -1;
            slot->window = w;
            slot->window_cap = (size_t)len;
        }
        const long head = len < n - start ? len : n - start;
        memcpy(slot->window, slot->segments + start, (size_t)head * sizeof(double));
        memcpy(slot->window + head, slot->segments, (size_t)(len - head) * sizeof(double));
        for (size_t i = 0; i < n_samples; i++) {
            long first;
            const long count = segment_run(&samples[i], &first);
            if (!count)
                continue;
            long offset = (first - start) % n;
            if (offset < 0)
                offset += n;
            /* in a window shorter than the ring a run never wraps: it lies inside */
            deltas[k] += charge_run(c, slot, s, &samples[i], slot->window, len, offset, count,
                                    &lost[k]);
        }
    }
    return 0;
}

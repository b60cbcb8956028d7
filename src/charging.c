/* charging.c: static (capacitive) and sliding (frictional-work) charge models (MODEL §5). */
#include "charging.h"

#include <stdlib.h>
#include <string.h>

int tribo_charging_init(tribo_charging *c, double eps, int n, int with_static, int with_sliding)
{
    memset(c, 0, sizeof *c);
    c->with_static = with_static;
    c->with_sliding = with_sliding;
    c->n = n;
    if (tribo_arclength_init(&c->arc, eps) != 0)
        return -1;
    c->segments_per_length = (double)n / c->arc.perimeter;
    if (with_static && !(c->q = malloc((size_t)n * sizeof *c->q)))
        goto fail;
    if (with_sliding && !(c->sigma = malloc((size_t)n * sizeof *c->sigma)))
        goto fail;
    tribo_charging_reset(c);
    return 0;
fail:
    tribo_charging_free(c);
    return -1;
}

void tribo_charging_free(tribo_charging *c)
{
    tribo_arclength_free(&c->arc);
    free(c->q);
    free(c->sigma);
    c->q = c->sigma = NULL;
}

void tribo_charging_reset(tribo_charging *c)
{
    if (c->q)
        memset(c->q, 0, (size_t)c->n * sizeof *c->q);
    if (c->sigma)
        memset(c->sigma, 0, (size_t)c->n * sizeof *c->sigma);
    c->charge_cache.duration = c->relax_cache.duration = -1.0;
}

void tribo_charging_sample(const tribo_charging *c, const tribo_pose *pose, double delta_y,
                           double duration, double work_begin, double work_end,
                           tribo_contact_sample *sample)
{
    sample->duration = duration;
    sample->work_begin = work_begin;
    sample->work_end = work_end;
    sample->in_contact = delta_y > 0.0;
    if (!sample->in_contact) {
        sample->s_centre = sample->half_width = 0.0;
        return;
    }
    const double eps = c->arc.eps;
    const double rho_c = tribo_contact_curvature_radius(eps * eps, pose->h);
    sample->half_width = sqrt(rho_c * delta_y); /* MODEL §5 (paper eq. 4) */
    sample->s_centre = tribo_arclength_at(&c->arc, tribo_contact_parameter(eps, pose));
}

/* exp(-duration / tau) and phi1(z) = (1 - e^-z) / z, z = duration / tau, recomputed
   only when the duration or tau changed. */
static const tribo_decay_cache *decay(tribo_decay_cache *k, double duration, double tau)
{
    if (k->duration != duration || k->tau != tau) {
        const double z = duration / tau;
        k->duration = duration;
        k->tau = tau;
        k->one_minus_decay = -expm1(-z);
        k->decay = 1.0 - k->one_minus_decay;
        k->phi1 = z > 1e-8 ? k->one_minus_decay / z : 1.0 - 0.5 * z;
    }
    return k;
}

void tribo_charging_saturation(tribo_charging *c, const tribo_charge_params *p, double *Sigma_s,
                               tribo_contact_sample *sample)
{
    const double s0 = *Sigma_s;
    double s1 = s0;
    if (sample->in_contact && sample->duration > 0.0) {
        /* MODEL §5b: dSigma_s = eta domega / sqrt(Sigma0^2 + 2 eta omega) + (Sigma0 - Sigma_s) / tau_r.
           The work term is the exact increment of sqrt(Sigma0^2 + 2 eta omega); with the
           relaxation solved exactly for a constant work rate over the sample, the update
           is stable for any tau_r (a stiff tau_r just pins Sigma_s to Sigma0). */
        const double g0 = sqrt(p->Sigma0 * p->Sigma0 + 2.0 * p->eta * sample->work_begin);
        const double g1 = sqrt(p->Sigma0 * p->Sigma0 + 2.0 * p->eta * sample->work_end);
        const tribo_decay_cache *k = decay(&c->relax_cache, sample->duration, p->tau_r);
        s1 = p->Sigma0 + (s0 - p->Sigma0) * k->decay + (g1 - g0) * k->phi1;
    }
    /* in flight the back-flow stops (c = 0 in MODEL §5b) and no work is done */
    sample->Sigma_s_begin = s0;
    sample->Sigma_s_end = s1;
    *Sigma_s = s1;
}

void tribo_charging_segments(tribo_charging *c, const tribo_charge_params *p,
                             const tribo_contact_sample *sample, double *q, double *sigma)
{
    if (!sample->in_contact || sample->duration <= 0.0 || (!q && !sigma))
        return;
    /* Segments whose arc [i L, (i+1) L) overlaps [s_c - Sc, s_c + Sc], periodic (MODEL §5). */
    const double lo = (sample->s_centre - sample->half_width) * c->segments_per_length;
    const double hi = (sample->s_centre + sample->half_width) * c->segments_per_length;
    const long first = (long)floor(lo);
    long count = (long)floor(hi) - first + 1;
    if (count > c->n)
        count = c->n;
    long i = first % c->n;
    if (i < 0)
        i += c->n;

    /* Exact over the sample: the static model has constant coefficients (MODEL §5a);
       the sliding one has Sigma_s(t) linear, whose solution of
       dSigma_i = (Sigma_s - Sigma_i) / tau0 is
       Sigma_i <- Sigma_s1 - dSigma_s phi1 + (Sigma_i - Sigma_s0) e^{-dt/tau0}. */
    const tribo_decay_cache *k = decay(&c->charge_cache, sample->duration, p->tau0);
    const double d = k->decay, one_minus_d = k->one_minus_decay;
    const double s1 = sample->Sigma_s_end, s0 = sample->Sigma_s_begin;
    const double lag = (s1 - s0) * k->phi1;
    for (long j = 0; j < count; j++) {
        if (q)
            q[i] += (1.0 - q[i]) * one_minus_d; /* MODEL §5a */
        if (sigma)
            sigma[i] = s1 - lag + (sigma[i] - s0) * d; /* MODEL §5b */
        if (++i == c->n)
            i = 0;
    }
}

double tribo_charging_mean(const double *v, int n)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++)
        sum += v[i];
    return sum / (double)n;
}

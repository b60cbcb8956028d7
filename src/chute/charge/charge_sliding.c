/* charge_sliding.c: the sliding (frictional-work) charge model, docs/model.md §5b (paper
   eqs. 11-13). Per segment Sigma_i, relaxing towards the dynamic saturation density
   Sigma_s in contact; Sigma_s (a global state) is raised by the frictional work per unit
   contact area omega (a quadrature) and relaxes back to Sigma0 through contact. Q_sliding
   is normalised by Sigma0 at the start of the run (Sigma0,ref, a global state that never
   changes), so that a tunable Sigma0 moves the saturation target, not the charge. */
#include "charge_registry.h"

#include <math.h>

typedef struct cache {
    tribo_decay_cache relax; /* over tau_r (the charge's over tau0 is the set's) */
} cache;

enum { SIGMA_S, SIGMA0_REF }; /* globals     */
enum { WORK };                /* quadratures */

static void start(const tribo_scene *s, double *g)
{
    g[SIGMA_S] = s->Sigma0;
    g[SIGMA0_REF] = s->Sigma0; /* §5b: Sigma0,ref */
}

/* d omega / dtau = mu delta_y |vs| / (2 Sc) with Sc = sqrt(rho_c delta_y), i.e.
   mu |vs| sqrt(delta_y / rho_c) / 2 (paper eq. 11) */
static double quadrature_rate(int k, const tribo_contact_kinematics *c)
{
    (void)k;
    return 0.5 * c->mu * fabs(c->vs) * sqrt(c->delta_y / c->rho_c);
}

/* Sigma_s after an interval of contact of length h over which omega goes w0 -> w1:
   dSigma_s = eta domega / sqrt(Sigma0^2 + 2 eta omega) + (Sigma0 - Sigma_s) / tau_r. The
   work term is the exact increment of sqrt(Sigma0^2 + 2 eta omega); with the relaxation
   solved exactly for a constant work rate, the update is stable for any tau_r (a stiff
   tau_r just pins Sigma_s to Sigma0). */
static double saturation_after(cache *k, const tribo_scene *s, double S, double h, double w0,
                               double w1)
{
    const double g0 = sqrt(s->Sigma0 * s->Sigma0 + 2.0 * s->eta * w0);
    const double g1 = sqrt(s->Sigma0 * s->Sigma0 + 2.0 * s->eta * w1);
    const tribo_decay_cache *d = tribo_decay_phi1(&k->relax, h, s->tau_r);
    return s->Sigma0 + (S - s->Sigma0) * d->decay + (g1 - g0) * d->phi1;
}

static void step_globals(void *c, const tribo_scene *s, double h, int in_contact,
                         const double *q0, const double *q1, const double *g0, double *g1)
{
    if (in_contact && h > 0.0) {
        g1[SIGMA_S] = saturation_after(c, s, g0[SIGMA_S], h, q0[WORK], q1[WORK]);
    } else if (q1[WORK] != q0[WORK]) {
        /* a step that ends in flight after contact: it is charged as flight (no back-flow,
           c = 0 in §5b), but the work done before lift-off still raises Sigma_s */
        g1[SIGMA_S] = g0[SIGMA_S] + sqrt(s->Sigma0 * s->Sigma0 + 2.0 * s->eta * q1[WORK]) -
                      sqrt(s->Sigma0 * s->Sigma0 + 2.0 * s->eta * q0[WORK]);
    } else {
        g1[SIGMA_S] = g0[SIGMA_S];
    }
}

/* Sigma_s at the middle and the end of a piece. The relaxation is linear, so
   Sigma_s - Sigma0 is the start value decayed plus the integral of e^{-(h - s)/tau_r} g(s),
   g = eta (d omega/dtau) / sqrt(Sigma0^2 + 2 eta omega); where tau_r is not stiff over the
   piece, that integral is taken by Simpson on the five points omega already used, as
   accurate as omega. Where it is stiff, the exact update for a constant work rate is
   taken over the halves and the whole, and they must agree. */
static int piece_globals(void *c, const tribo_scene *s, double h, const double (*rates)[5],
                         const double *q_begin, const double *q_mid, const double *q_end,
                         const double *g0, double *g_mid, double *g_end, double rtol, double atol)
{
    const double *r = rates[WORK];
    const double work0 = q_begin[WORK], work_mid = q_mid[WORK], work1 = q_end[WORK];
    const double S0 = g0[SIGMA_S];
    const double z = h / s->tau_r;
    if (z <= 1.0) {
        /* omega at the quarter points only feeds sqrt(Sigma0^2 + 2 eta omega): trapezoids */
        const double quarter = 0.25 * h;
        const double works[5] = {work0, work0 + 0.5 * quarter * (r[0] + r[1]), work_mid,
                                 work_mid + 0.5 * quarter * (r[2] + r[3]), work1};
        double g[5];
        for (int j = 0; j < 5; j++)
            g[j] = s->eta * r[j] / sqrt(s->Sigma0 * s->Sigma0 + 2.0 * s->eta * works[j]);
        const double d = exp(-0.25 * z); /* e^{-(quarter of the piece) / tau_r} */
        const double d2 = d * d, d3 = d2 * d, d4 = d2 * d2;
        g_mid[SIGMA_S] = s->Sigma0 + (S0 - s->Sigma0) * d2 + h / 12.0 * (d2 * g[0] + 4.0 * d * g[1] + g[2]);
        g_end[SIGMA_S] = s->Sigma0 + (S0 - s->Sigma0) * d4 +
                         h / 12.0 * (d4 * g[0] + 4.0 * d3 * g[1] + 2.0 * d2 * g[2] + 4.0 * d * g[3] + g[4]);
        return 1;
    }
    g_mid[SIGMA_S] = saturation_after(c, s, S0, 0.5 * h, work0, work_mid);
    g_end[SIGMA_S] = saturation_after(c, s, g_mid[SIGMA_S], 0.5 * h, work_mid, work1);
    const double whole = saturation_after(c, s, S0, h, work0, work1);
    return fabs(g_end[SIGMA_S] - whole) <= rtol * fabs(g_end[SIGMA_S]) + atol;
}

/* dSigma_i = (Sigma_s - Sigma_i) / tau0 with Sigma_s = A + B u + C u^2 over u in [0, 1] is
   Sigma_i <- e^{-z} Sigma_i + K, K = (A + B + C)(1 - e^{-z}) - (B + 2C) z F_1(z) + C z F_2(z),
   z = duration / tau0: exact over the interval. */
static double charge(void *c, const tribo_scene *s, const tribo_charge_forcing *f, double *sigma,
                     long count)
{
    (void)c;
    const double A = f->begin[SIGMA_S];
    const double C = 2.0 * (A - 2.0 * f->mid[SIGMA_S] + f->end[SIGMA_S]);
    const double B = f->end[SIGMA_S] - A - C;
    /* a Sigma_s that holds still (no work done) needs no moments: the terms they weight
       are 0 */
    const int still = B == 0.0 && C == 0.0;
    const tribo_decay_cache *k = still ? tribo_decay(f->decay, f->duration, s->tau0)
                                       : tribo_decay_moments(f->decay, f->duration, s->tau0);
    const double d = k->decay, one_minus_d = k->one_minus_decay;
    const double K = still ? A * one_minus_d
                           : (A + B + C) * one_minus_d - (B + 2.0 * C) * k->zf1 + C * k->zf2;
    double change = 0.0;
    for (long i = 0; i < count; i++) {
        const double old = sigma[i];
        sigma[i] = d * old + K;
        change += sigma[i] - old;
    }
    return change;
}

static void segment_values(const tribo_scene *s, const double *globals, const double *sigma,
                           double *out, int n)
{
    (void)s;
    for (int i = 0; i < n; i++)
        out[i] = sigma[i] / globals[SIGMA0_REF];
}

/* Sigma_s relaxes towards Sigma0 > 0 and work only raises it: it stays positive; the
   normalisation Sigma0,ref is a Sigma0 */
static int valid(const tribo_scene *s, const double *globals, const double *sigma, int n)
{
    (void)s, (void)sigma, (void)n;
    return globals[SIGMA_S] > 0.0 && globals[SIGMA0_REF] > 0.0;
}

/* §5c: a segment in contact is at Sigma_i = Sigma_s at once */
static double saturation(const tribo_scene *s, const double *g)
{
    (void)s;
    return g[SIGMA_S];
}

/* Sigma_i is the density itself: |Sigma_i| <= Sigma_bd (§8b). */
static double density_unit(const tribo_scene *s)
{
    (void)s;
    return 1.0;
}

/* At rest no work is done and the contact holds: Sigma_s relaxes to Sigma0 (§5b, §3c); the
   normalisation stays. */
static void rest_limits(const tribo_scene *s, double *g)
{
    g[SIGMA_S] = s->Sigma0;
}

const tribo_charge_model tribo_charge_sliding = {
    .name = "sliding",
    .n_globals = 2,
    .n_quadratures = 1,
    .cache_size = sizeof(cache),
    .start = start,
    .quadrature_rate = quadrature_rate,
    .step_globals = step_globals,
    .piece_globals = piece_globals,
    .charge = charge,
    .segment_values = segment_values,
    .valid = valid,
    .saturation = saturation,
    .density_unit = density_unit,
    /* Sigma_i / Sigma0,ref with Sigma0,ref = |sigma0| / sqrt(kappa k' a) (sigma0 is fixed in
       the SI front end): sigma_i = sigma0 times the value (§8) */
    .si_unit = TRIBO_CHARGE_PER_SIGMA0,
    .rest_limits = rest_limits,
};

double tribo_sliding_charge(tribo_charge_view v)
{
    /* Q_sliding, §5b */
    return v.selected ? v.sum / v.n / v.globals[SIGMA0_REF] : 0.0;
}

double tribo_sliding_mean_density(tribo_charge_view v)
{
    return v.selected ? v.sum / v.n : 0.0; /* mean Sigma_i, §5b */
}

double tribo_sliding_saturation(tribo_charge_view v) { return v.globals[SIGMA_S]; }

double tribo_sliding_work(tribo_charge_view v) { return v.quadratures[WORK]; }

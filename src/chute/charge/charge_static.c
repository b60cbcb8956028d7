/* charge_static.c: the static (capacitive) charge model, docs/model.md §5a (paper eq. 2).
   Per segment q_i = sigma_i / sigma_0, dq_i/dtau = (1 - q_i) / tau0 in contact; no
   global states. */
#include "charge_registry.h"

#include <string.h>

static double charge(void *cache, const tribo_scene *s, const tribo_charge_forcing *f, double *q,
                     long count)
{
    (void)cache;
    /* linear with constant coefficients: exact over the interval */
    const double one_minus_d = tribo_decay(f->decay, f->duration, s->tau0)->one_minus_decay;
    double change = 0.0;
    for (long i = 0; i < count; i++) {
        const double old = q[i];
        q[i] += (1.0 - old) * one_minus_d;
        change += q[i] - old;
    }
    return change;
}

static void segment_values(const tribo_scene *s, const double *globals, const double *q,
                           double *out, int n)
{
    (void)s, (void)globals;
    memcpy(out, q, (size_t)n * sizeof *out);
}

/* q_i = sigma_i / sigma_0 starts at 0 and only relaxes towards 1 */
static int valid(const tribo_scene *s, const double *globals, const double *q, int n)
{
    (void)s, (void)globals;
    for (int i = 0; i < n; i++)
        if (!(q[i] >= 0.0 && q[i] <= 1.0))
            return 0;
    return 1;
}

/* §5c: a segment in contact is at q_i = 1 at once */
static double saturation(const tribo_scene *s, const double *globals)
{
    (void)s, (void)globals;
    return 1.0;
}

/* The density of a segment is Sigma0 q_i (model.md §8: sigma_i = sigma0 q_i): the breakdown
   limit |Sigma_i| <= Sigma_bd is q_i <= Sigma_bd / Sigma0 (§8b). */
static double density_unit(const tribo_scene *s)
{
    return s->Sigma0;
}

const tribo_charge_model tribo_charge_static = {
    .name = "static",
    .charge = charge,
    .segment_values = segment_values,
    .valid = valid,
    .saturation = saturation,
    .density_unit = density_unit,
    .si_unit = TRIBO_CHARGE_PER_SIGMA0,
};

double tribo_static_charge(tribo_charge_view v)
{
    return v.selected ? v.sum / v.n : 0.0; /* Q_static, §5a */
}

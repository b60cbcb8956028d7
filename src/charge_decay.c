/* charge_decay.c: the exponentials the charge models' exact updates take (docs/model.md §5). */
#include "charge_model.h"

#include <math.h>

/* F_k(z) = int_0^1 v^k e^{-z v} dv, k = 1, 2: by its series where the closed form
   cancels (small z), else closed. */
static double moment(int k, double z)
{
    if (z < 0.5) {
        double term = 1.0, sum = 0.0;
        for (int n = 0; n < 30; n++) {
            sum += term / (double)(n + k + 1);
            term *= -z / (double)(n + 1);
        }
        return sum;
    }
    const double e = exp(-z);
    return k == 1 ? (1.0 - e * (1.0 + z)) / (z * z) : (2.0 - e * (z * z + 2.0 * z + 2.0)) / (z * z * z);
}

const tribo_decay_cache *tribo_decay(tribo_decay_cache *k, double duration, double tau)
{
    if (k->duration != duration || k->tau != tau) {
        const double z = duration / tau;
        k->duration = duration;
        k->tau = tau;
        k->one_minus_decay = -expm1(-z);
        k->decay = 1.0 - k->one_minus_decay;
        k->phi1 = z > 1e-8 ? k->one_minus_decay / z : 1.0 - 0.5 * z;
        k->has_moments = 0;
    }
    return k;
}

const tribo_decay_cache *tribo_decay_moments(tribo_decay_cache *k, double duration, double tau)
{
    tribo_decay(k, duration, tau);
    if (!k->has_moments) {
        const double z = duration / tau;
        k->zf1 = z * moment(1, z);
        k->zf2 = z * moment(2, z);
        k->has_moments = 1;
    }
    return k;
}

double tribo_sum(const double *v, long n)
{
    double sum = 0.0;
    for (long i = 0; i < n; i++)
        sum += v[i];
    return sum;
}

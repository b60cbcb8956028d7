/* charge_decay.c: the exponentials the charge models' exact updates take (docs/model.md §5). */
#include "charge_interface.h"

#include <math.h>

/* The coefficients 1 / (n! (n + k + 1)) of the series of F_k below, k = 1, 2, to the term
   that is below 1e-18 of F_k at z = 0.5 (0.5^17 / 17! < 3e-20). */
#define SERIES_TERMS 18
static const double SERIES[2][SERIES_TERMS] = {{
    1.0 / 2.0, 1.0 / 3.0, 1.0 / 8.0, 1.0 / 30.0, 1.0 / 144.0, 1.0 / 840.0, 1.0 / 5760.0, 1.0 / 45360.0,
    1.0 / 403200.0, 1.0 / 3991680.0, 1.0 / 43545600.0, 1.0 / 518918400.0, 1.0 / 6706022400.0,
    1.0 / 93405312000.0, 1.0 / 1394852659200.0, 1.0 / 22230464256000.0, 1.0 / 376610217984000.0,
    1.0 / 6758061133824000.0}, {
    1.0 / 3.0, 1.0 / 4.0, 1.0 / 10.0, 1.0 / 36.0, 1.0 / 168.0, 1.0 / 960.0, 1.0 / 6480.0, 1.0 / 50400.0,
    1.0 / 443520.0, 1.0 / 4354560.0, 1.0 / 47174400.0, 1.0 / 558835200.0, 1.0 / 7185024000.0,
    1.0 / 99632332800.0, 1.0 / 1482030950400.0, 1.0 / 23538138624000.0, 1.0 / 397533007872000.0,
    1.0 / 7113748561920000.0}};

/* F_k(z) = int_0^1 v^k e^{-z v} dv = sum_n (-z)^n / (n! (n + k + 1)), k = 1, 2: by its series
   where the closed form cancels (small z), else closed. The series' terms fall in size from
   the first; it is summed from the last one that is above 2^-57 (F_k >= 1/4 for z < 0.5:
   a quarter of the rounding of the smallest F_k), so that the charging sweep's short samples
   (z ~ 1e-4) take a handful of terms. */
static double moment(int k, double z)
{
    if (z < 0.5) {
        const double *c = SERIES[k - 1];
        int n = 1;
        for (double power = z; n < SERIES_TERMS && power * c[n] >= 0x1p-57; n++)
            power *= z;
        double sum = 0.0;
        while (n-- > 0)
            sum = c[n] - z * sum;
        return sum;
    }
    const double e = exp(-z);
    /* where e^-z is 0 its products with powers of z are too (at z = inf they would be NaN) */
    if (e == 0.0)
        return k == 1 ? 1.0 / (z * z) : 2.0 / (z * z * z);
    return k == 1 ? (1.0 - e * (1.0 + z)) / (z * z) : (2.0 - e * (z * z + 2.0 * z + 2.0)) / (z * z * z);
}

const tribo_decay_cache *tribo_decay(tribo_decay_cache *k, double duration, double tau)
{
    if (k->duration != duration || k->tau != tau) {
        k->z = duration / tau;
        k->duration = duration;
        k->tau = tau;
        k->one_minus_decay = -expm1(-k->z);
        k->decay = 1.0 - k->one_minus_decay;
        k->has_phi1 = k->has_moments = 0;
    }
    return k;
}

const tribo_decay_cache *tribo_decay_phi1(tribo_decay_cache *k, double duration, double tau)
{
    tribo_decay(k, duration, tau);
    if (!k->has_phi1) {
        k->phi1 = k->z > 1e-8 ? k->one_minus_decay / k->z : 1.0 - 0.5 * k->z;
        k->has_phi1 = 1;
    }
    return k;
}

const tribo_decay_cache *tribo_decay_moments(tribo_decay_cache *k, double duration, double tau)
{
    tribo_decay(k, duration, tau);
    if (!k->has_moments) {
        /* z F_k(z) -> 0 as z -> inf (a tau0 so small that duration / tau0 overflows) */
        k->zf1 = isinf(k->z) ? 0.0 : k->z * moment(1, k->z);
        k->zf2 = isinf(k->z) ? 0.0 : k->z * moment(2, k->z);
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

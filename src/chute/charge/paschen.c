/* paschen.c: the Paschen limit of a charged region (docs/model.md §8e), by minimisation over
   the gap and from a table of it. */
#include "paschen.h"

#include <math.h>

/* F(x; c) = c + x - sqrt(x^2 + c^2), in the form without cancellation on either side of
   x = c. */
static double gap_voltage(double x, double c)
{
    const double h = hypot(x, c);
    return x <= c ? x - x * x / (c + h) : c - c * c / (x + h);
}

/* Paschen's G(x), held at its minimum e K below the minimum's gap (§8e's choice). */
static double breakdown(double x, double log_K, double x_min)
{
    return x > x_min ? x / (log(x) - log_K) : x_min;
}

/* K = ln(1 + 1/gamma), finite for every gamma > 0 (1/gamma overflows below 5.6e-309). */
static double log_K_of(double gamma) { return log(log1p(gamma) - log(gamma)); }

double tribo_paschen_minimum(double gamma) { return M_E * exp(log_K_of(gamma)); }

/* The minimum of G / F over ln x in [lo, hi] by golden section, and its x. */
static double minimise(double c, double log_K, double x_min, double *x_at)
{
    const double r = 0.5 * (sqrt(5.0) - 1.0);
    double lo = log(x_min), hi = log(x_min + c);
    double u1 = hi - r * (hi - lo), u2 = lo + r * (hi - lo);
    double f1 = breakdown(exp(u1), log_K, x_min) / gap_voltage(exp(u1), c);
    double f2 = breakdown(exp(u2), log_K, x_min) / gap_voltage(exp(u2), c);
    /* 60 steps shrink the bracket (at most ln(1 + c / e K), 40 for c = 1e18) below 1e-11:
       S, stationary there, to rounding */
    for (int i = 0; i < 60; i++) {
        if (f1 <= f2) {
            hi = u2;
            u2 = u1;
            f2 = f1;
            u1 = hi - r * (hi - lo);
            f1 = breakdown(exp(u1), log_K, x_min) / gap_voltage(exp(u1), c);
        } else {
            lo = u1;
            u1 = u2;
            f1 = f2;
            u2 = lo + r * (hi - lo);
            f2 = breakdown(exp(u2), log_K, x_min) / gap_voltage(exp(u2), c);
        }
    }
    *x_at = f1 <= f2 ? exp(u1) : exp(u2);
    return f1 <= f2 ? f1 : f2;
}

double tribo_paschen_reduced(double gamma, double c)
{
    const double x_min = tribo_paschen_minimum(gamma);
    double x;
    return minimise(c, log_K_of(gamma), x_min, &x);
}

void tribo_paschen_build(tribo_paschen *t, double gamma, double c_max)
{
    const double x_min = tribo_paschen_minimum(gamma);
    const double c_lo = 1e-4 * x_min;
    if (t->gamma == gamma && t->n > 0 && t->c_hi >= c_max)
        return;
    t->gamma = gamma;
    t->log_K = log_K_of(gamma);
    t->x_min = x_min;
    t->c_lo = c_lo;
    t->dv = log(10.0) / TRIBO_PASCHEN_PER_DECADE;
    t->v0 = log(c_lo);
    int n = (int)ceil((log(fmax(c_max, c_lo)) - t->v0) / t->dv) + 2;
    if (n > TRIBO_PASCHEN_MAX_NODES)
        n = TRIBO_PASCHEN_MAX_NODES;
    t->n = n;
    t->c_hi = exp(t->v0 + (n - 1) * t->dv);
    /* each node is minimised where a size first needs it: an instance's contacts meet a few */
    for (int i = 0; i < n; i++)
        t->y[i] = NAN;
}

/* Node i: ln S and its slope, by the envelope theorem (dS/dc = -(G / F^2) dF/dc at the
   minimum, dF/dc = 1 - c / sqrt(x^2 + c^2)). */
static void make_node(tribo_paschen *t, int i)
{
    const double c = exp(t->v0 + i * t->dv);
    double x;
    const double S = minimise(c, t->log_K, t->x_min, &x);
    t->y[i] = log(S);
    t->slope[i] = -c * (1.0 - c / hypot(x, c)) / gap_voltage(x, c);
}

double tribo_paschen_limit(tribo_paschen *t, double c)
{
    if (c < t->c_lo) /* the gap's voltage saturates at c long before the minimum's gap */
        return t->x_min / gap_voltage(t->x_min, c);
    if (!(c <= t->c_hi))
        return tribo_paschen_reduced(t->gamma, c);
    const double v = (log(c) - t->v0) / t->dv;
    int i = (int)v;
    if (i > t->n - 2)
        i = t->n - 2;
    if (isnan(t->y[i]))
        make_node(t, i);
    if (isnan(t->y[i + 1]))
        make_node(t, i + 1);
    const double u = v - i, u2 = u * u, u3 = u2 * u;
    /* cubic Hermite in ln S */
    const double y = (2 * u3 - 3 * u2 + 1) * t->y[i] + (u3 - 2 * u2 + u) * t->dv * t->slope[i] +
                     (-2 * u3 + 3 * u2) * t->y[i + 1] + (u3 - u2) * t->dv * t->slope[i + 1];
    return exp(y);
}

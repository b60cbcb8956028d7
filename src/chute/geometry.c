/* geometry.c: arc length of the ellipse boundary, for cutting it into N segments of
   equal arc length (model.md §5). */
#include "geometry.h"

#include <stdlib.h>
#include <string.h>

/* 8-point Gauss-Legendre nodes and weights on [-1, 1]. */
static const double GL_X[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
static const double GL_W[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};

static double gauss8(double eps2, double a, double b)
{
    const double m = 0.5 * (a + b), r = 0.5 * (b - a);
    double sum = 0.0;
    for (int i = 0; i < 4; i++)
        sum += GL_W[i] * (tribo_boundary_speed(eps2, m - r * GL_X[i]) +
                          tribo_boundary_speed(eps2, m + r * GL_X[i]));
    return r * sum;
}

/* The speed is analytic but, for a needle, varies on a scale eps near t = 0 and pi:
   bisect until the two halves agree with the whole. */
static double adaptive(double eps2, double a, double b, double whole, int depth)
{
    const double m = 0.5 * (a + b);
    const double left = gauss8(eps2, a, m), right = gauss8(eps2, m, b);
    if (depth >= 40 || fabs(left + right - whole) <= 1e-15 * (fabs(whole) + 1e-300) + 1e-17)
        return left + right;
    return adaptive(eps2, a, m, left, depth + 1) + adaptive(eps2, m, b, right, depth + 1);
}

double tribo_arc_between(double eps, double t0, double t1)
{
    const double eps2 = eps * eps;
    return adaptive(eps2, t0, t1, gauss8(eps2, t0, t1), 0);
}

double tribo_ellipse_perimeter(double eps)
{
    /* four quarters, each with its own smooth interior, sum to the whole */
    return 4.0 * tribo_arc_between(eps, 0.0, 0.5 * M_PI);
}

/* Whether adaptive()'s first test passes on every interval of half-length r within [0, tmax]
   whatever its place, so that its result, the halves' sum, can be taken without the whole
   rule it is tested against (a third of the table's work). By an a-priori bound on
   |left + right - whole| below the test's floor of 1e-17:
   - rounding: each speed is computed within 4u (u = 2^-53) of its value, at a node within
     2u tmax of its own, where |ds/dt| <= 1 (speed >= |sin t|), so within u (2 tmax + 4); a
     rule of half-length h sums its eight terms with weights summing to 2 within 12u of the
     sum: within u h (4 tmax + 32) of the rule with exact speeds; the halves and the whole
     and their sum, within u r (8 tmax + 66);
   - quadrature: the speed sqrt(sin^2 t + eps^2 cos^2 t) is analytic in the strip
     |Im t| < atanh(eps) (its branch points are k pi +- i atanh(eps)) and at most
     sqrt(2) cosh(y) at height y; the Bernstein ellipse of the interval reaching half way to
     them, rho - 1/rho = atanh(eps) / r, bounds the 8-point Gauss rule's error by
     (64/15) M rho^-16 / (rho^2 - 1) r (Trefethen, Approximation Theory and Approximation
     Practice, Thm 19.3), and the halves' by less. */
static int halves_suffice(double eps, double r, double tmax)
{
    if (eps >= 1.0)
        return 1; /* a circle: the speed is 1 */
    const double u = 0x1p-53, beta = atanh(eps);
    const double rounding = u * r * (8.0 * tmax + 66.0);
    const double x = beta / r, rho = 0.5 * (x + sqrt(x * x + 4.0));
    const double M = sqrt(2.0) * cosh(0.5 * beta);
    const double quadrature = 3.0 * (64.0 / 15.0) * M * pow(rho, -16.0) / (rho * rho - 1.0) * r;
    return rounding + quadrature <= 1e-17;
}

/* Grid fine enough that Hermite interpolation error (h^4 |s''''| / 384, with
   |s''''| ~ 1/eps^2 near the tips) stays far below a segment at every allowed N. */
#define ARC_INTERVALS 8192

int tribo_arclength_init(tribo_arclength *a, double eps, const tribo_arclength *like)
{
    const size_t n = ARC_INTERVALS;
    const double eps2 = eps * eps;
    a->eps = eps;
    a->n_intervals = n;
    a->dt_grid = 2.0 * M_PI / (double)n;
    a->s = malloc((n + 1) * sizeof *a->s);
    a->speed = malloc((n + 1) * sizeof *a->speed);
    if (!a->s || !a->speed) {
        tribo_arclength_free(a);
        return -1;
    }
    if (like && like->s && like->speed && like->eps == eps && like->n_intervals == n) {
        memcpy(a->s, like->s, (n + 1) * sizeof *a->s);
        memcpy(a->speed, like->speed, (n + 1) * sizeof *a->speed);
        a->perimeter = like->perimeter;
        return 0;
    }
    a->s[0] = 0.0;
    const int halves = halves_suffice(eps, 0.5 * a->dt_grid, 2.0 * M_PI);
    for (size_t k = 0; k <= n; k++) {
        const double t = a->dt_grid * (double)k;
        a->speed[k] = tribo_boundary_speed(eps2, t);
        if (k == 0)
            continue;
        const double t0 = a->dt_grid * (double)(k - 1);
        double arc;
        if (eps == 1.0) {
            arc = t - t0; /* a circle's boundary runs at speed 1: its arc is its angle */
        } else if (halves) { /* what tribo_arc_between returns, its test passing */
            const double m = 0.5 * (t0 + t);
            arc = gauss8(eps2, t0, m) + gauss8(eps2, m, t);
        } else {
            arc = tribo_arc_between(eps, t0, t);
        }
        a->s[k] = a->s[k - 1] + arc;
    }
    a->perimeter = a->s[n];
    return 0;
}

void tribo_arclength_free(tribo_arclength *a)
{
    free(a->s);
    free(a->speed);
    a->s = a->speed = NULL;
}

double tribo_arclength_parameter(const tribo_arclength *a, double s)
{
    if (s <= 0.0)
        return 0.0;
    if (s >= a->perimeter)
        return 2.0 * M_PI;
    /* bracket in the table, then Newton on the exact speed from the linear guess */
    size_t lo = 0, hi = a->n_intervals;
    while (hi - lo > 1) {
        const size_t mid = (lo + hi) / 2;
        if (a->s[mid] <= s)
            lo = mid;
        else
            hi = mid;
    }
    const double t_lo = a->dt_grid * (double)lo, t_hi = t_lo + a->dt_grid;
    double t = t_lo + a->dt_grid * (s - a->s[lo]) / (a->s[hi] - a->s[lo]);
    const double eps2 = a->eps * a->eps;
    for (int it = 0; it < 50; it++) {
        const double f = a->s[lo] + tribo_arc_between(a->eps, t_lo, t) - s;
        double t_new = t - f / tribo_boundary_speed(eps2, t);
        if (t_new < t_lo)
            t_new = t_lo;
        if (t_new > t_hi)
            t_new = t_hi;
        if (fabs(t_new - t) <= 1e-15 * (1.0 + t))
            return t_new;
        t = t_new;
    }
    return t;
}

double tribo_spheroid_area(double eps)
{
    const double e = sqrt(fmax(0.0, 1.0 - eps * eps));
    /* asin(e) / e -> 1 + e^2 / 6 as e -> 0 (a sphere), where the quotient loses its digits */
    const double ratio = e < 1e-4 ? 1.0 + e * e / 6.0 : asin(e) / e;
    return 2.0 * M_PI * eps * (eps + ratio);
}

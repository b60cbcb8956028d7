/* flight.c: the motion between contacts in closed form, and where it ends (flight.h). */
#include "flight.h"

#include <float.h>
#include <math.h>
#include <string.h>

void tribo_flight_start(tribo_flight *f, const tribo_dyn_params *p, double t0, const double *y0, int n)
{
    f->t0 = t0;
    memcpy(f->y0, y0, sizeof f->y0);
    f->n = n;
    /* model.md §4 with Psi_N = Psi_T = 0 */
    f->a_t = p->g_t + p->F_T;
    f->a_n = -p->g_n + p->F_N;
}

void tribo_flight_state(const tribo_flight *f, const tribo_dyn_params *p, double t, double *y)
{
    const double s = t - f->t0;
    const double *y0 = f->y0;
    memcpy(y, y0, sizeof f->y0);
    const double U0 = y0[TRIBO_IU], V0 = y0[TRIBO_IV];
    y[TRIBO_IX] = y0[TRIBO_IX] + s * (U0 + 0.5 * f->a_t * s);
    y[TRIBO_IY] = y0[TRIBO_IY] + s * (V0 + 0.5 * f->a_n * s);
    y[TRIBO_IPHI] = y0[TRIBO_IPHI] + y0[TRIBO_IOMEGA] * s;
    y[TRIBO_IU] = U0 + f->a_t * s;
    y[TRIBO_IV] = V0 + f->a_n * s;
    /* dW_ext/dtau = F_T U + F_N V */
    y[TRIBO_IWEXT] = y0[TRIBO_IWEXT] + p->F_T * s * (U0 + 0.5 * f->a_t * s) +
                     p->F_N * s * (V0 + 0.5 * f->a_n * s);
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    y[TRIBO_IGAP] = y[TRIBO_IY] - g.h;
}

/* The lowest point's indentation delta(s) = h(phi) - Y = -G at s from the flight's start, its
   rate -vn and the quantities the decision at the plate needs. */
typedef struct clearance {
    double delta, rate, curvature, V, spin, Y, h;
} clearance;

static clearance clearance_at(const tribo_flight *f, const tribo_dyn_params *p, double s)
{
    const double *y0 = f->y0;
    const double Om = y0[TRIBO_IOMEGA];
    tribo_pose g;
    tribo_pose_at(p->eps2, y0[TRIBO_IPHI] + Om * s, &g);
    clearance c;
    c.Y = y0[TRIBO_IY] + s * (y0[TRIBO_IV] + 0.5 * f->a_n * s);
    c.V = y0[TRIBO_IV] + f->a_n * s;
    c.spin = g.cx * Om;
    c.h = g.h;
    c.delta = g.h - c.Y;
    c.rate = -(c.V + c.spin); /* d(delta)/dtau = (dh/dphi) Omega - V, dh/dphi = -cx */
    c.curvature = -tribo_pose_kappa(p->eps2, &g) * Om * Om - f->a_n; /* h'' = -kappa */
    return c;
}

/* The first positive root of q(d) = delta + rate d + M d^2 / 2 (INFINITY where q stays
   negative; 0 where it does not start negative), which bounds delta from above while
   delta'' <= M. delta <= 0. */
static double quadratic_root(double delta, double rate, double M)
{
    const double depth = -delta; /* >= 0 */
    if (rate < 0.0) {
        if (!(M > 0.0))
            return INFINITY; /* moving away, and nothing brings it back */
        return (-rate + sqrt(rate * rate + 2.0 * M * depth)) / M;
    }
    const double disc = rate * rate + 2.0 * M * depth;
    if (disc < 0.0)
        return INFINITY; /* M < 0: q peaks below 0 */
    const double den = rate + sqrt(disc);
    if (den > 0.0)
        return 2.0 * depth / den;
    /* rate = 0 and (depth = 0 or M = 0): q = delta + M d^2 / 2 */
    return M > 0.0 || depth == 0.0 ? 0.0 : INFINITY;
}

/* Whether the lowest point certainly stays off the plate over the step d: q(d) with
   M_d = min(M, curvature + B d), which bounds delta'' over the step (the third derivative
   is bounded by B), has no root before d. */
static int step_is_safe(double delta, double rate, double curvature, double M, double B, double d)
{
    return quadratic_root(delta, rate, fmin(M, curvature + B * d)) >= d;
}

/* How far from the point (delta <= 0, its rate, its second derivative now curvature) the
   lowest point certainly stays off the plate, up to `most`: the largest safe step
   (step_is_safe), found by doubling from the one the global bound M allows, then halving the
   gap four times. Near a tangency the global bound alone would allow no step; the local one
   allows the curvature's own. At least `least`. */
static double safe_step(double delta, double rate, double curvature, double M, double B,
                        double most, double least)
{
    double d = fmax(quadratic_root(delta, rate, M), least);
    if (d >= most)
        return most;
    double bad = most;
    for (int k = 0; k < 64 && 2.0 * d < most; k++) {
        if (!step_is_safe(delta, rate, curvature, M, B, 2.0 * d)) {
            bad = 2.0 * d;
            break;
        }
        d *= 2.0;
    }
    for (int k = 0; k < 4; k++) {
        const double mid = 0.5 * (d + bad);
        if (step_is_safe(delta, rate, curvature, M, B, mid))
            d = mid;
        else
            bad = mid;
    }
    return d;
}

/* The first s >= s_from where X reaches the chute's end L (INFINITY if none): the smaller
   positive root of X0 + U0 s + a s^2 / 2 = L, in the form that keeps its digits. */
static double exit_time(const tribo_flight *f, const tribo_dyn_params *p, double s_from)
{
    const double L = p->chute_length;
    if (!isfinite(L))
        return INFINITY;
    const double d = L - f->y0[TRIBO_IX], U0 = f->y0[TRIBO_IU], a = f->a_t;
    double s = INFINITY;
    if (d <= 0.0)
        return s_from;
    if (a == 0.0) {
        if (U0 > 0.0)
            s = d / U0;
    } else {
        const double disc = U0 * U0 + 2.0 * a * d;
        if (disc >= 0.0) {
            const double q = -0.5 * (U0 + copysign(sqrt(disc), U0 == 0.0 ? 1.0 : U0));
            /* the roots of (a/2) s^2 + U0 s - d = 0: q / (a/2) and -d / q */
            const double r1 = q / (0.5 * a), r2 = q != 0.0 ? -d / q : INFINITY;
            if (r1 > 0.0)
                s = r1;
            if (r2 > 0.0 && r2 < s)
                s = r2;
        }
    }
    /* on or past L, not a rounding short of it */
    for (int k = 0; k < 8 && isfinite(s); k++) {
        const double X = f->y0[TRIBO_IX] + s * (U0 + 0.5 * a * s);
        if (X >= L)
            break;
        s = nextafter(s, INFINITY);
    }
    return fmax(s, s_from);
}

double tribo_flight_end_of(const tribo_flight *f, const tribo_dyn_params *p, double t_from,
                           double t_max, long budget, tribo_flight_end *why, long *used)
{
    const double Om = f->y0[TRIBO_IOMEGA];
    /* the largest second derivative of delta, -kappa Omega^2 - a_n, can be: -kappa <=
       (1 - eps^2) / eps; its third, dkappa/dphi Omega^3, is bounded through |dkappa/dphi| <
       2 (1 - eps^2) / eps^2 (the supremum, approached as eps -> 1; 10 % more here) */
    const double M = (1.0 - p->eps2) / p->eps * Om * Om - f->a_n;
    const double B = 2.2 * (1.0 - p->eps2) / p->eps2 * fabs(Om * Om * Om);
    const double s_max = t_max - f->t0;
    double s_end = s_max;
    *why = TRIBO_FLIGHT_GOES_ON;
    const double s_exit = exit_time(f, p, t_from - f->t0);
    if (s_exit <= s_end) {
        s_end = s_exit;
        *why = TRIBO_FLIGHT_EXIT;
    }
    double s = t_from - f->t0;
    long k = 0;
    while (s < s_end) {
        if (k >= budget) {
            s_end = s;
            *why = TRIBO_FLIGHT_GOES_ON;
            break;
        }
        const clearance c = clearance_at(f, p, s);
        k++;
        /* within the rounding of G = Y - h of the plate: a contact where the lowest point
           approaches it (vn below minus its rounding), or rests on it pressed in (delta''
           > 0); a touch that moves away is not one (model.md §3b) */
        const double rounding = 8.0 * DBL_EPSILON * (fabs(c.Y) + c.h);
        double delta = c.delta;
        if (delta >= -rounding) {
            const double vn = -c.rate, vn_rounding = tribo_velocity_rounding(p, c.V, c.spin);
            if (vn < -vn_rounding || (vn <= vn_rounding && c.curvature > 0.0)) {
                s_end = s;
                *why = TRIBO_FLIGHT_CONTACT;
                break;
            }
            delta = fmin(delta, 0.0);
        }
        /* at least a rounding of the time, so that a touch that moves away is passed */
        const double least = 4.0 * DBL_EPSILON * (fabs(f->t0 + s) + 1.0);
        s += safe_step(delta, c.rate, c.curvature, M, B, s_end - s, least);
    }
    *used = k;
    return f->t0 + s_end;
}

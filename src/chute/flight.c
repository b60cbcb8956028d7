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
    const double phase = p->vib_omega * t0 + p->vib_phase;
    f->vib_sin0 = tribo_vibrating(p) ? sin(phase) : 0.0;
    f->vib_cos0 = tribo_vibrating(p) ? cos(phase) : 0.0;
}

/* 1 - cos d and d - sin d, to their full relative precision where d is small (a flight of a
   small part of the plate's period). */
static double one_minus_cos(double d)
{
    const double half = sin(0.5 * d);
    return 2.0 * half * half;
}

static double d_minus_sin(double d)
{
    if (fabs(d) > 0.5)
        return d - sin(d);
    /* d^3/3! - d^5/5! + ..., to d^15 (the next term is below 1e-18 of the sum) */
    const double d2 = d * d;
    return d * d2 / 6.0 *
           (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0 * (1.0 - d2 / 72.0 * (1.0 - d2 / 110.0 *
                                                                         (1.0 - d2 / 156.0)))));
}

/* The plate's inertial force over a flight (model.md §9b), along the stroke: what it has added
   to the centre's displacement and velocity after s, its value and its rate at s. */
typedef struct stroke {
    double x, v, force, rate;
} stroke;

static stroke stroke_at(const tribo_flight *f, const tribo_dyn_params *p, double s)
{
    const double w = p->vib_omega, L = p->vib_accel, d = w * s;
    const double sd = sin(d), cd = cos(d), s0 = f->vib_sin0, c0 = f->vib_cos0;
    stroke k;
    /* the integrals of L sin(theta0 + w u) over [0, s], once and twice */
    k.v = L / w * (c0 * one_minus_cos(d) + s0 * sd);
    k.x = L / (w * w) * (c0 * d_minus_sin(d) + s0 * one_minus_cos(d));
    k.force = L * (s0 * cd + c0 * sd);
    k.rate = L * w * (c0 * cd - s0 * sd);
    return k;
}

/* The work of the inertial force along one axis over s (model.md §9b), where the steady
   acceleration a, the initial velocity u0 and the stroke's displacement x and velocity v
   along the axis: the kinetic energy gained less the steady load's work,
   v (u0 + a s + v/2) - a x, which is the integral of the force times the velocity. */
static double stroke_work(double u0, double a, double s, double x, double v)
{
    return v * (u0 + a * s + 0.5 * v) - a * x;
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
    if (tribo_vibrating(p)) {
        const stroke k = stroke_at(f, p, s);
        const double ct = p->vib_cos, sn = p->vib_sin;
        y[TRIBO_IX] += k.x * ct;
        y[TRIBO_IY] += k.x * sn;
        y[TRIBO_IU] += k.v * ct;
        y[TRIBO_IV] += k.v * sn;
        y[TRIBO_IWEXT] += p->F_T * k.x * ct + p->F_N * k.x * sn;
        y[p->vib_slot] = y0[p->vib_slot] + stroke_work(U0, f->a_t, s, k.x * ct, k.v * ct) +
                         stroke_work(V0, f->a_n, s, k.x * sn, k.v * sn);
    }
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    y[TRIBO_IGAP] = y[TRIBO_IY] - g.h;
}

/* The lowest point's indentation delta(s) = h(phi) - Y = -G at s from the flight's start, its
   rate -vn and the quantities the decision at the plate needs. */
typedef struct clearance {
    double delta, rate, curvature, V, spin, Y, h;
    double curvature_rate; /* on a vibrating plate (model.md §9b); 0 on a still one */
    double X, U;           /* the centre along the plate, on a vibrating plate */
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
    c.curvature_rate = 0.0;
    if (tribo_vibrating(p)) {
        /* model.md §9b: the stroke's share of Y, V and of the normal acceleration, and
           delta''' = h''' Omega^3 - da_n/dtau (h''' = -dkappa/dphi) */
        const stroke k = stroke_at(f, p, s);
        const double kappa = tribo_pose_kappa(p->eps2, &g);
        c.Y += k.x * p->vib_sin;
        c.V += k.v * p->vib_sin;
        c.delta = g.h - c.Y;
        c.rate = -(c.V + c.spin);
        c.curvature -= k.force * p->vib_sin;
        c.curvature_rate = -tribo_pose_kappa_slope(&g, kappa) * Om * Om * Om - k.rate * p->vib_sin;
        c.X = y0[TRIBO_IX] + s * (y0[TRIBO_IU] + 0.5 * f->a_t * s) + k.x * p->vib_cos;
        c.U = y0[TRIBO_IU] + f->a_t * s + k.v * p->vib_cos;
    }
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

/* The bounds on the clearance's derivatives over a flight: M on the second, B on the third's
   size; on a vibrating plate (cubic) also B4 on the fourth's and the third's value now, slope
   (model.md §9b: a grain lifted off by the plate leaves it with delta' = delta'' = 0, where
   only the third derivative shows that it moves away). */
typedef struct bounds {
    double M, B;
    int cubic;
    double slope, B4;
} bounds;

/* Whether the lowest point certainly stays off the plate over the step d: q(d) with
   M_d = min(M, curvature + B d), which bounds delta'' over the step (the third derivative
   is bounded by B), has no root before d; with the fourth derivative bounded by B4, delta''
   <= curvature + slope u + B4 u^2 / 2 over the step too, a convex bound whose largest value
   is at an end. */
static int step_is_safe(double delta, double rate, double curvature, const bounds *b, double d)
{
    double M_d = fmin(b->M, curvature + b->B * d);
    if (b->cubic)
        M_d = fmin(M_d, fmax(curvature, curvature + d * (b->slope + 0.5 * b->B4 * d)));
    return quadratic_root(delta, rate, M_d) >= d;
}

/* How far from the point (delta <= 0, its rate, its second derivative now curvature) the
   lowest point certainly stays off the plate, up to `most`: the largest safe step
   (step_is_safe), found by doubling from the one the global bound M allows, then halving the
   gap four times. Near a tangency the global bound alone would allow no step; the local one
   allows the curvature's own. At least `least`. */
static double safe_step(double delta, double rate, double curvature, const bounds *b,
                        double most, double least)
{
    double d = fmax(quadratic_root(delta, rate, b->M), least);
    if (d >= most)
        return most;
    double bad = most;
    for (int k = 0; k < 64 && 2.0 * d < most; k++) {
        if (!step_is_safe(delta, rate, curvature, b, 2.0 * d)) {
            bad = 2.0 * d;
            break;
        }
        d *= 2.0;
    }
    for (int k = 0; k < 4; k++) {
        const double mid = 0.5 * (d + bad);
        if (step_is_safe(delta, rate, curvature, b, mid))
            d = mid;
        else
            bad = mid;
    }
    return d;
}

/* On a vibrating plate, the step a lowest point at the plate (within the rounding of its
   clearance) that moves away only by its third derivative can take (model.md §9b): a grain the
   plate lifted off, whose indentation, rate and second derivative are 0 but for rounding. Its
   indentation stays below delta + r+ u + c+ u^2 / 2 + c' u^3 / 6 + B4 u^4 / 24 (r+, c+ the rate
   and second derivative where positive), and the last two terms stay negative for u < 4 |c'| /
   B4: the step is the largest within which the first three stay within the clearance's
   rounding, and within nine tenths of that. (Without it the search crawls away by roundings of
   the time, while the cubic separation stays below the rounding.) 0 where the third derivative
   does not move the point away. */
static double escape_step(const clearance *c, const bounds *b, double rounding)
{
    if (!(c->curvature_rate < 0.0))
        return 0.0;
    const double away = b->B4 > 0.0 ? 3.6 * -c->curvature_rate / b->B4 : INFINITY;
    const double rate = fmax(c->rate, 0.0), curvature = fmax(c->curvature, 0.0);
    const double room = fmax(rounding - fmax(c->delta, 0.0), 0.0);
    double within = INFINITY;
    if (curvature > 0.0)
        within = (sqrt(rate * rate + 2.0 * curvature * room) - rate) / curvature;
    else if (rate > 0.0)
        within = room / rate;
    return fmin(away, within);
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
    const int vibrating = tribo_vibrating(p);
    /* the largest second derivative of delta, -kappa Omega^2 - a_n, can be: -kappa <=
       (1 - eps^2) / eps; its third, dkappa/dphi Omega^3, is bounded through |dkappa/dphi| <
       2 (1 - eps^2) / eps^2 (the supremum, approached as eps -> 1; 10 % more here); on a
       vibrating plate the stroke adds Lambda_v |sin psi_v| w_v^k to the (k+2)-th (model.md
       §9b), and the fourth, d2kappa/dphi2 Omega^4, is bounded through |d2kappa/dphi2| <
       4 (1 - eps^2) / eps^3 (the supremum, approached as eps -> 1; 10 % more here) */
    const double stroke_n = vibrating ? p->vib_accel * fabs(p->vib_sin) : 0.0;
    bounds b = {(1.0 - p->eps2) / p->eps * Om * Om - f->a_n,
                2.2 * (1.0 - p->eps2) / p->eps2 * fabs(Om * Om * Om), 0, 0.0, 0.0};
    if (vibrating) {
        b.M += stroke_n;
        b.B += stroke_n * p->vib_omega;
        b.cubic = 1;
        b.B4 = 4.4 * (1.0 - p->eps2) / (p->eps2 * p->eps) * Om * Om * Om * Om +
               stroke_n * p->vib_omega * p->vib_omega;
    }
    /* on a vibrating plate the exit is searched for like the contact: the centre's
       acceleration along the plate is at most a_t + Lambda_v |cos psi_v| */
    const double M_exit = f->a_t + (vibrating ? p->vib_accel * fabs(p->vib_cos) : 0.0);
    const int find_exit = vibrating && isfinite(p->chute_length);
    const double s_max = t_max - f->t0;
    double s_end = s_max;
    *why = TRIBO_FLIGHT_GOES_ON;
    const double s_exit = vibrating ? INFINITY : exit_time(f, p, t_from - f->t0);
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
        double delta = c.delta, escape = 0.0;
        if (delta >= -rounding) {
            if (tribo_touch_makes_contact(-c.rate, tribo_velocity_rounding(p, c.V, c.spin),
                                          tribo_pressed_in(p, c.curvature, c.curvature_rate))) {
                s_end = s;
                *why = TRIBO_FLIGHT_CONTACT;
                break;
            }
            delta = fmin(delta, 0.0);
            if (vibrating)
                escape = escape_step(&c, &b, rounding);
        }
        if (find_exit && c.X >= p->chute_length) {
            s_end = s;
            *why = TRIBO_FLIGHT_EXIT;
            break;
        }
        /* at least a rounding of the time, so that a touch that moves away is passed */
        const double least = 4.0 * DBL_EPSILON * (fabs(f->t0 + s) + 1.0);
        b.slope = c.curvature_rate;
        double step = fmax(safe_step(delta, c.rate, c.curvature, &b, s_end - s, least),
                           fmin(escape, s_end - s));
        if (find_exit)
            step = fmin(step, fmax(quadratic_root(c.X - p->chute_length, c.U, M_exit), least));
        s += step;
    }
    *used = k;
    return f->t0 + s_end;
}

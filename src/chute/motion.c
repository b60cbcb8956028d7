/* motion.c: classifying the motion into the paper's motion classes. */
#include "motion.h"

#include <math.h>

/* "Continuous" contact: in contact at least this fraction of the window. */
#define CONTINUOUS_CONTACT 0.95
/* "No contact" within the window, at the paper's scale (tribo_motion_scales_of). */
#define NO_CONTACT 0.01
/* "Turning": the orientation progresses by at least an eighth of a turn per window, on
   the signed average (rocking about a fixed orientation averages out), slip or not:
   what matters for charging is that new surface comes round to the plate. */
#define TURNING_ANGLE (M_PI / 4.0)

/* The paper's drop speed, whose bounces TRIBO_MOTION_WINDOW spans (model.md §7). */
#define PAPER_DROP_SPEED 0.025
#define PAPER_GAMMA 1e-3

tribo_motion_scales tribo_motion_scales_of(double Gamma, double impact_speed)
{
    /* the paper's window in units of the gravity time sqrt(a/g) = 1/sqrt(Gamma), or, where
       longer, in units of the flight of a bounce at the impact speed, 2 V / Gamma (0.4 of
       it, as at the paper's drop). At the paper's Gamma and drop both ratios are 1 exactly:
       its classes, bit for bit. */
    const double gravity = TRIBO_MOTION_WINDOW / sqrt(Gamma / PAPER_GAMMA);
    const double bounce = TRIBO_MOTION_WINDOW * (impact_speed / PAPER_DROP_SPEED) * (PAPER_GAMMA / Gamma);
    const double window = fmax(gravity, bounce);
    /* a contact's share of the window (its duration, ~pi, over the window) scales with it */
    return (tribo_motion_scales){.window = window,
                                 .no_contact = NO_CONTACT * (TRIBO_MOTION_WINDOW / window)};
}

static int classify(const tribo_motion_scales *sc, double contact, double spin, int in_contact)
{
    const int turning = fabs(spin) * sc->window > TURNING_ANGLE;
    if (!in_contact && contact < sc->no_contact)
        return TRIBO_MOTION_FLIGHT;
    if (contact >= CONTINUOUS_CONTACT)
        return turning ? TRIBO_MOTION_ROLLING : TRIBO_MOTION_ROCKING;
    return turning ? TRIBO_MOTION_TUMBLING : TRIBO_MOTION_BOUNCING;
}

/* Where, within (0, h), an average relaxing from x0 towards target crosses a threshold;
   appended to cuts. */
static int add_crossing(double *cuts, int n, double x0, double target, double threshold,
                        double h, double window)
{
    const double q = (threshold - target) / (x0 - target);
    if (q > 0.0 && q < 1.0) {
        const double s = -window * log(q);
        if (s > 0.0 && s < h)
            cuts[n++] = s;
    }
    return n;
}

/* Over an interval the contact indicator and the spin rate are taken as constant, so the
   averages relax exponentially; the class time is booked between the exact times at which
   an average crosses a class threshold. A long interval (an analytic flight) is then
   booked as a chain of short ones would be: the classes do not depend on the step sizes. */
void tribo_motion_update(tribo_motion *m, const tribo_motion_scales *sc, double h, double decay,
                         int in_contact, double dphi)
{
    if (!(h > 0.0))
        return;
    const double w = sc->window;
    const double contact_target = in_contact ? 1.0 : 0.0, rate = dphi / h;
    const double c0 = m->contact, s0 = m->spin, turning_rate = TURNING_ANGLE / w;
    double cuts[5];
    int n = 0;
    n = add_crossing(cuts, n, c0, contact_target, sc->no_contact, h, w);
    n = add_crossing(cuts, n, c0, contact_target, CONTINUOUS_CONTACT, h, w);
    n = add_crossing(cuts, n, s0, rate, turning_rate, h, w);
    n = add_crossing(cuts, n, s0, rate, -turning_rate, h, w);
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; j--) {
            const double t = cuts[j];
            cuts[j] = cuts[j - 1];
            cuts[j - 1] = t;
        }
    cuts[n] = h;
    double start = 0.0;
    for (int i = 0; i < n; i++) {  /* the pieces before the last cut */
        const double e = exp(-0.5 * (start + cuts[i]) / w);
        const int c = classify(sc, contact_target + (c0 - contact_target) * e,
                               rate + (s0 - rate) * e, in_contact);
        m->class_time[c] += cuts[i] - start;
        start = cuts[i];
    }
    m->contact = contact_target + (c0 - contact_target) * decay;
    m->spin = rate + (s0 - rate) * decay;
    m->current = classify(sc, m->contact, m->spin, in_contact);
    m->class_time[m->current] += h - start;
}

int tribo_indentation_too_deep(double delta_y, double epsilon, double rho_c)
{
    return delta_y > TRIBO_INDENTATION_LIMIT * fmin(epsilon, rho_c);
}

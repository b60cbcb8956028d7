/* motion.c: classifying the motion into the paper's motion classes. */
#include "motion.h"

#include <math.h>

/* "Continuous" contact: in contact at least this fraction of the window. */
#define CONTINUOUS_CONTACT 0.95
/* "No contact" within the window. */
#define NO_CONTACT 0.01
/* "Turning": the orientation progresses by at least an eighth of a turn per window, on
   the signed average (rocking about a fixed orientation averages out), slip or not:
   what matters for charging is that new surface comes round to the plate. */
#define TURNING_ANGLE (M_PI / 4.0)

static int classify(double contact, double spin, int in_contact)
{
    const int turning = fabs(spin) * TRIBO_MOTION_WINDOW > TURNING_ANGLE;
    if (!in_contact && contact < NO_CONTACT)
        return TRIBO_MOTION_FLIGHT;
    if (contact >= CONTINUOUS_CONTACT)
        return turning ? TRIBO_MOTION_ROLLING : TRIBO_MOTION_ROCKING;
    return turning ? TRIBO_MOTION_TUMBLING : TRIBO_MOTION_BOUNCING;
}

/* Where, within (0, h), an average relaxing from x0 towards target crosses a threshold;
   appended to cuts. */
static int add_crossing(double *cuts, int n, double x0, double target, double threshold,
                        double h)
{
    const double q = (threshold - target) / (x0 - target);
    if (q > 0.0 && q < 1.0) {
        const double s = -TRIBO_MOTION_WINDOW * log(q);
        if (s > 0.0 && s < h)
            cuts[n++] = s;
    }
    return n;
}

/* Over an interval the contact indicator and the spin rate are taken as constant, so the
   averages relax exponentially; the class time is booked between the exact times at which
   an average crosses a class threshold. A long interval (an analytic flight) is then
   booked as a chain of short ones would be: the classes do not depend on the step sizes. */
void tribo_motion_update(tribo_motion *m, double h, double decay, int in_contact, double dphi)
{
    if (!(h > 0.0))
        return;
    const double contact_target = in_contact ? 1.0 : 0.0, rate = dphi / h;
    const double c0 = m->contact, s0 = m->spin, turning_rate = TURNING_ANGLE / TRIBO_MOTION_WINDOW;
    double cuts[5];
    int n = 0;
    n = add_crossing(cuts, n, c0, contact_target, NO_CONTACT, h);
    n = add_crossing(cuts, n, c0, contact_target, CONTINUOUS_CONTACT, h);
    n = add_crossing(cuts, n, s0, rate, turning_rate, h);
    n = add_crossing(cuts, n, s0, rate, -turning_rate, h);
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; j--) {
            const double t = cuts[j];
            cuts[j] = cuts[j - 1];
            cuts[j - 1] = t;
        }
    cuts[n] = h;
    double start = 0.0;
    for (int i = 0; i < n; i++) {  /* the pieces before the last cut */
        const double e = exp(-0.5 * (start + cuts[i]) / TRIBO_MOTION_WINDOW);
        const int c = classify(contact_target + (c0 - contact_target) * e,
                               rate + (s0 - rate) * e, in_contact);
        m->class_time[c] += cuts[i] - start;
        start = cuts[i];
    }
    m->contact = contact_target + (c0 - contact_target) * decay;
    m->spin = rate + (s0 - rate) * decay;
    m->current = classify(m->contact, m->spin, in_contact);
    m->class_time[m->current] += h - start;
}

int tribo_indentation_too_deep(double delta_y, double epsilon, double rho_c)
{
    return delta_y > TRIBO_INDENTATION_LIMIT * fmin(epsilon, rho_c);
}

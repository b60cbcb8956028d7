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

void tribo_motion_update(tribo_motion *m, double h, double decay, int in_contact, double dphi)
{
    if (!(h > 0.0))
        return;
    const double w = 1.0 - decay;
    m->contact = decay * m->contact + w * (in_contact ? 1.0 : 0.0);
    m->spin = decay * m->spin + w * dphi / h;

    const int turning = fabs(m->spin) * TRIBO_MOTION_WINDOW > TURNING_ANGLE;
    if (!in_contact && m->contact < NO_CONTACT)
        m->current = TRIBO_MOTION_FLIGHT;
    else if (m->contact >= CONTINUOUS_CONTACT)
        m->current = turning ? TRIBO_MOTION_ROLLING : TRIBO_MOTION_ROCKING;
    else
        m->current = turning ? TRIBO_MOTION_TUMBLING : TRIBO_MOTION_BOUNCING;
    m->class_time[m->current] += h;
}

int tribo_indentation_too_deep(double delta_y, double epsilon, double rho_c)
{
    return delta_y > TRIBO_INDENTATION_LIMIT * fmin(epsilon, rho_c);
}

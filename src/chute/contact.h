/* contact.h: the contact force law (model.md §3): spring-dashpot normal force and the
   stick / slip / roll Coulomb friction of the tangential spring. */
#ifndef TRIBO_CONTACT_H
#define TRIBO_CONTACT_H

#include <math.h>

/* Indentation delta_y = h(phi) - Y = -G if positive, else 0 (model.md §2), from the clearance
   G of the lowest point. */
static inline double tribo_indentation(double gap)
{
    return gap < 0.0 ? -gap : 0.0;
}

/* Normal force Psi_N = delta_y (1 - nu s), clamped at >= 0 (no adhesion), where s is the
   sign of the damped normal velocity (the contact point's vn, or the centre's V), or its
   regularisation / set-valued choice (model.md §3). */
static inline double tribo_normal_force(double delta_y, double nu, double s)
{
    const double f = delta_y * (1.0 - nu * s);
    return f > 0.0 ? f : 0.0;
}

/* The regularised sign s = tanh(vn / v_reg) of the fixed-step integrator (model.md §3).
   A plain sgn(vn) makes the normal force chatter between delta_y (1 -+ nu) at rest,
   and with it the Coulomb limit, so that high-friction runs depend on the step. */
static inline double tribo_regularised_sign(double vn, double v_reg)
{
    return tanh(vn / v_reg);
}

/* The tangential spring stretch held within the Coulomb limit |dx| <= mu Psi_N
   (model.md §3): in stick Psi_T = -dx, in slip Psi_T = -mu Psi_N sgn(dx) = -clamp(dx): the
   slip force opposes the stretch (the spring-slider rule of §3's revised Choice), under
   which friction never does positive work.
   Slip is entered when the stretch would exceed the limit and left by itself when
   v_s reverses and |dx| falls below it. */
static inline double tribo_clamp(double dx, double limit)
{
    return dx > limit ? limit : (dx < -limit ? -limit : dx);
}

#endif

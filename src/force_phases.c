/* force_phases.c: the phases of the force law and the switches between them (model.md §3). */
#include "force_phases.h"

#include <math.h>
#include <string.h>

const tribo_force_law TRIBO_PHASE_FLIGHT = {TRIBO_CONTACT_OFF, TRIBO_NORMAL_SIGN, -1.0, TRIBO_TANGENT_STICK,
                                     0.0};

/* The normal lock holds while Psi_N* (tribo_lock_force) lies in the band of normal forces
   the set-valued sign allows (model.md §3), max(0, dy(1 - nu)) <= Psi_N* <= dy(1 + nu), and,
   slipping, while A > 0. */
static double lock_lower(const tribo_dyn_params *p, double dy)
{
    return fmax(0.0, dy * (1.0 - p->nu));
}

static int contact_point_lock(const tribo_dyn_params *p, const tribo_force_law *law)
{
    return law->normal == TRIBO_NORMAL_LOCK && p->damping_point == TRIBO_DAMPING_CONTACT_POINT;
}

void tribo_switch_functions(const tribo_dyn_params *p, const tribo_force_law *law, const double *y,
                            double *g)
{
    tribo_contact_eval ev;
    for (int i = 0; i < TRIBO_N_SWITCHES; i++)
        g[i] = 1.0;
    if (isfinite(p->chute_length))
        g[TRIBO_SWITCH_EXIT] = p->chute_length - y[TRIBO_IX];
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &ev.pose);
    g[TRIBO_SWITCH_CONTACT] = ev.pose.h - y[TRIBO_IY];
    if (!tribo_touching(law))
        return;
    /* the contact as the phase sees it, even where delta_y has just gone negative */
    tribo_contact_at(p, law, y, &ev);
    const double dy = ev.pose.h - y[TRIBO_IY];
    if (law->normal == TRIBO_NORMAL_LOCK) {
        const double psi_star = ev.psi_n;
        g[TRIBO_SWITCH_NORMAL_A] = psi_star - lock_lower(p, dy);
        g[TRIBO_SWITCH_NORMAL_B] = dy * (1.0 + p->nu) - psi_star;
        if (contact_point_lock(p, law) && law->tangent == TRIBO_TANGENT_SLIP)
            tribo_lock_force(p, law, &ev.pose, y, &g[TRIBO_SWITCH_LOCK_FACTOR]);
    } else if (p->nu > 0.0) {
        g[TRIBO_SWITCH_NORMAL_A] = tribo_damped_velocity(p, &ev.pose, y);
    }
    if (law->tangent == TRIBO_TANGENT_STICK) {
        g[TRIBO_SWITCH_TANGENT_A] = ev.limit - y[TRIBO_IDX];
        g[TRIBO_SWITCH_TANGENT_B] = ev.limit + y[TRIBO_IDX];
    } else {
        g[TRIBO_SWITCH_TANGENT_A] = law->slip_sign * ev.vs - ev.limit_rate;
    }
}

/* Crossing directions that mean a switch in each phase (others are not switches). */
void tribo_switch_directions(const tribo_dyn_params *p, const tribo_force_law *ph, int *dir)
{
    for (int i = 0; i < TRIBO_N_SWITCHES; i++)
        dir[i] = 0;
    if (isfinite(p->chute_length))
        dir[TRIBO_SWITCH_EXIT] = -1; /* the centre passes X = L going down-slope */
    if (!tribo_touching(ph)) {
        dir[TRIBO_SWITCH_CONTACT] = +1;
        return;
    }
    dir[TRIBO_SWITCH_CONTACT] = -1;
    if (ph->normal == TRIBO_NORMAL_LOCK) {
        dir[TRIBO_SWITCH_NORMAL_A] = dir[TRIBO_SWITCH_NORMAL_B] = -1;
        if (contact_point_lock(p, ph) && ph->tangent == TRIBO_TANGENT_SLIP)
            dir[TRIBO_SWITCH_LOCK_FACTOR] = -1;
    } else if (p->nu > 0.0) {
        dir[TRIBO_SWITCH_NORMAL_A] = ph->normal_sign < 0 ? +1 : -1; /* vn reaches 0 */
    }
    dir[TRIBO_SWITCH_TANGENT_A] = -1;
    if (ph->tangent == TRIBO_TANGENT_STICK)
        dir[TRIBO_SWITCH_TANGENT_B] = -1;
}

static void tangent_from_state(const tribo_dyn_params *p, double *y, tribo_force_law *law);

/* dvn/dtau at y in the normal phase of sign s (s = 0: the spring force alone, Psi_N =
   delta_y), with the tangential rule that phase gives the stretch. */
static double normal_acceleration(const tribo_dyn_params *p, const double *y,
                                  const tribo_force_law *law, double s)
{
    double z[TRIBO_NSTATE_MAX], f[TRIBO_NMOTION];
    memcpy(z, y, sizeof z);
    tribo_force_law trial = *law;
    trial.normal = TRIBO_NORMAL_SIGN;
    trial.normal_sign = s;
    tangent_from_state(p, z, &trial);
    tribo_contact_eval ev;
    tribo_dynamics_rhs(p, &trial, z, f, &ev);
    const double Om = z[TRIBO_IOMEGA];
    return f[TRIBO_IV] + tribo_pose_kappa(p->eps2, &ev.pose) * Om * Om + ev.pose.cx * f[TRIBO_IOMEGA];
}

/* Where no lock can hold the contact point (A <= 0, a Painleve-type configuration, model.md
   §3): the sign under which vn leaves 0 consistently, s dvn/dtau > 0 in the phase that sign
   leads into (its Coulomb limit decides stick or slip; the stretch is never raised to a new
   limit). Where both signs are consistent (A < 0 allows it), or neither, vn leaves in the
   direction dvn/dtau has under the spring force alone. */
static double leaving_sign(const tribo_dyn_params *p, const double *y, const tribo_force_law *law)
{
    const int lifts = normal_acceleration(p, y, law, +1.0) > 0.0;
    const int presses = normal_acceleration(p, y, law, -1.0) < 0.0;
    if (lifts != presses)
        return lifts ? +1.0 : -1.0;
    return normal_acceleration(p, y, law, 0.0) > 0.0 ? +1.0 : -1.0;
}

/* The normal rule of a contact whose damped velocity is exactly 0 (model.md §3): normal lock
   if the force that holds it (in the law's tangential rule) is within the band, otherwise
   the sign the net normal force gives the velocity: below the band the contact lifts
   (s = +1), above it presses in (s = -1); where A <= 0 there is no lock (leaving_sign). */
static void normal_at_rest(const tribo_dyn_params *p, const double *y, double dy, tribo_force_law *law)
{
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    /* A contact-point lock's force depends on the tangential rule the lock itself would have
       (the rule before may be a slip at a zero limit, the contact having been unloaded):
       that rule decides, on a copy of the state. */
    tribo_force_law as_locked = *law;
    double z[TRIBO_NSTATE_MAX];
    memcpy(z, y, sizeof z);
    if (p->damping_point == TRIBO_DAMPING_CONTACT_POINT) {
        as_locked.normal = TRIBO_NORMAL_LOCK;
        tangent_from_state(p, z, &as_locked);
    }
    double A;
    const double psi_star = tribo_lock_force(p, &as_locked, &g, z, &A);
    if (!(A > 0.0)) {
        law->normal = TRIBO_NORMAL_SIGN;
        law->normal_sign = leaving_sign(p, y, law);
    } else if (p->nu > 0.0 && psi_star >= lock_lower(p, dy) && psi_star <= dy * (1.0 + p->nu)) {
        law->normal = TRIBO_NORMAL_LOCK;
        law->normal_sign = 0.0;
    } else {
        law->normal = TRIBO_NORMAL_SIGN;
        law->normal_sign = psi_star < lock_lower(p, dy) ? +1.0 : -1.0;
    }
}

/* d2h/dphi2 at the pose of y, by central difference (h'' = -dcx/dphi). */
static double h_curvature(const tribo_dyn_params *p, double phi)
{
    const double d = 1e-4;
    tribo_pose a, b, g;
    tribo_pose_at(p->eps2, phi + d, &a);
    tribo_pose_at(p->eps2, phi - d, &b);
    tribo_pose_at(p->eps2, phi, &g);
    return (a.h - 2.0 * g.h + b.h) / (d * d);
}

/* With the stretch on the limit and the first derivatives tied (sigma vs = d(limit)/dtau),
   the second derivatives under the stick law decide: the stretch leaves the limit where
   sigma dvs/dtau > d2(limit)/dtau2. Fills both. */
static void second_derivatives(const tribo_dyn_params *p, const double *y,
                               const tribo_force_law *law, double *dvs, double *dlimit2)
{
    tribo_force_law stick = *law;
    stick.tangent = TRIBO_TANGENT_STICK;
    double f[TRIBO_NMOTION];
    tribo_contact_eval ev;
    tribo_dynamics_rhs(p, &stick, y, f, &ev);
    const double Om = y[TRIBO_IOMEGA], h2 = h_curvature(p, y[TRIBO_IPHI]);
    /* vs = U + h Omega; dh/dphi = -cx */
    *dvs = f[TRIBO_IU] + ev.pose.h * f[TRIBO_IOMEGA] - ev.pose.cx * Om * Om;
    /* limit = mu (1 - nu s) delta_y in a sign phase (taken as constant in a lock);
       delta_y' = -cx Om - V */
    const double ddy2 = h2 * Om * Om - ev.pose.cx * f[TRIBO_IOMEGA] - f[TRIBO_IV];
    const double factor = law->normal == TRIBO_NORMAL_LOCK ? 0.0 : 1.0 - p->nu * law->normal_sign;
    *dlimit2 = factor > 0.0 ? p->mu * factor * ddy2 : 0.0;
}

/* A stretch of 0 at a limit of 0 (a particle set down at rest: everything 0): whether
   sticking would leave the limit, and which way. Returns the slip direction, or 0 to stick. */
static double slip_at_second_order(const tribo_dyn_params *p, const double *y,
                                   const tribo_force_law *law)
{
    double dvs, dlimit2;
    second_derivatives(p, y, law, &dvs, &dlimit2);
    const double sigma = dvs > 0.0 ? 1.0 : -1.0;
    return sigma * dvs > dlimit2 ? sigma : 0.0;
}

/* At a switch between stick and slip with the stretch on the limit: whether it leaves the
   limit, sigma vs > d(limit)/dtau (the slip phase's rate). Where the two differ by no more
   than the rounding of a located switch (1e-9 of their size, as for grazing switches), the
   first order does not decide: the contact sticks. A stick that should slip sees the limit
   crossed a moment later, by then decisively; deciding by the second derivatives instead
   would need the limit's second derivative, which in a contact-point lock depends on the
   whole motion. */
static int stretch_leaves_limit(double sigma, double vs, double rate)
{
    const double lead = sigma * vs - rate, noise = 1e-9 * (fabs(vs) + fabs(rate));
    return lead > noise;
}

/* Stick or slip for a stretch checked against the limit of the (new) normal phase:
   a stretch beyond the limit is clamped to it (the spring energy released is dissipated);
   at the limit the contact slips if the stretch would leave it, sigma vs > d(limit)/dtau,
   to second order where the first ties. */
static void tangent_from_state(const tribo_dyn_params *p, double *y, tribo_force_law *law)
{
    tribo_contact_eval ev;
    law->tangent = TRIBO_TANGENT_STICK;
    law->slip_sign = 0.0;
    tribo_contact_at(p, law, y, &ev);
    const double dx = y[TRIBO_IDX];
    double sigma = dx > 0.0 ? 1.0 : dx < 0.0 ? -1.0 : (ev.vs >= 0.0 ? 1.0 : -1.0);
    double L = ev.limit, limit_rate = ev.limit_rate;
    if (contact_point_lock(p, law)) {
        /* Psi_N* depends on the tangential rule. With A > 0 for slip in the stretch's
           direction, |dx| <= mu Psi_N*(stick) exactly when |dx| <= mu Psi_N*(slip), the two
           agree at the limit, and the stretch leaves the limit when sigma vs exceeds the
           slipping limit's rate. With A <= 0 the stretch cannot reach the limit that way:
           it sticks (model.md §3). */
        tribo_force_law slip = *law;
        slip.tangent = TRIBO_TANGENT_SLIP;
        slip.slip_sign = sigma;
        tribo_contact_eval es;
        tribo_contact_at(p, &slip, y, &es);
        double A;
        tribo_lock_force(p, &slip, &es.pose, y, &A);
        if (!(A > 0.0))
            return;
        L = es.limit;
        limit_rate = es.limit_rate;
    }
    if (fabs(dx) < L * (1.0 - 1e-12))
        return;
    y[TRIBO_IDX] = sigma * L;
    if (sigma * ev.vs == limit_rate && dx == 0.0 && L == 0.0) {
        sigma = slip_at_second_order(p, y, law);
        if (sigma == 0.0)
            return;
    } else if (!(sigma * ev.vs > limit_rate)) {
        return;
    }
    law->tangent = TRIBO_TANGENT_SLIP;
    law->slip_sign = sigma;
}

/* A contact-point lock decided before its tangential rule was: Psi_N* and A change with the
   rule, so the lock is checked again under the final one; if it no longer holds, the
   contact leaves it and the tangential rule follows the new normal phase. */
static void confirm_lock(const tribo_dyn_params *p, double *y, tribo_force_law *law)
{
    if (!contact_point_lock(p, law))
        return;
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    normal_at_rest(p, y, g.h - y[TRIBO_IY], law);
    if (law->normal != TRIBO_NORMAL_LOCK)
        tangent_from_state(p, y, law);
}

/* Whether a particle touching the plate at rest (delta_y = 0 and d(delta_y)/dtau = 0) is
   pressed into it: d2(delta_y)/dtau2 > 0 in flight, i.e. the net normal force pulls it
   down against the rate at which rotation lifts the lowest point, h''(phi) Omega^2.
   Without this, a particle set down on the plate would start in flight, and the contact
   root, zero at the start and a small step later, would never see it sink in. */
static int pressed_in(const tribo_dyn_params *p, const double *y)
{
    const double Om = y[TRIBO_IOMEGA];
    return h_curvature(p, y[TRIBO_IPHI]) * Om * Om + (p->g_n - p->F_N) > 0.0;
}

/* A contact point that leaves vn = 0 in a sign phase (after a vn switch, out of a lock, or
   set down at rest) may do so slowly: at the edge of the lock's band dvn/dtau starts at 0.
   Its switch function vn would then sit within integration error of 0 and be seen
   crossing back at once, again and again. It starts that error's size on its side,
   vn = s m (the energy this changes is booked with the switch). The centre dashpot's V
   is left exactly at 0, as it always was. */
static void leave_rest(const tribo_dyn_params *p, double *y, const tribo_force_law *law)
{
    if (p->damping_point != TRIBO_DAMPING_CONTACT_POINT || !tribo_touching(law) ||
        law->normal != TRIBO_NORMAL_SIGN || p->nu == 0.0)
        return;
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    const double spin = g.cx * y[TRIBO_IOMEGA];
    if (y[TRIBO_IV] + spin != 0.0)
        return;
    const double m = 10.0 * (p->rtol * (fabs(y[TRIBO_IV]) + fabs(spin)) + p->atol);
    y[TRIBO_IV] = -spin + law->normal_sign * m;
}

/* The phase after an event (fired: the roots found) or, with fired = NULL, the phase a
   state is in when the integration (re)starts there. Adjusts y to put the switched
   boundary exactly on it (Y = h, damped velocity 0, delta_x = +-limit), so that CVODE's root
   functions start at 0 and look at the direction the motion takes. */
static tribo_force_law next_phase(const tribo_dyn_params *p, const tribo_force_law *old, double *y,
                                 const int *fired)
{
    tribo_force_law ph = *old;
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    const double dy = g.h - y[TRIBO_IY];
    const double ddy = -g.cx * y[TRIBO_IOMEGA] - y[TRIBO_IV];

    if (fired && fired[TRIBO_SWITCH_CONTACT])
        ph.contact = tribo_touching(old) ? TRIBO_CONTACT_OFF : TRIBO_CONTACT_ON;
    else if (fired && tribo_touching(old) && dy < 0.0)
        /* another switch where the lowest point is already above the plate: the contact
           was lost within the root finding's resolution of this switch, and its root,
           negative from the restart on, would never be seen (the phase would stay in
           contact with no force, its tangent switch firing at every stretch rounding) */
        ph.contact = TRIBO_CONTACT_OFF;
    else if (!fired)
        ph.contact = dy > 0.0 || (dy == 0.0 && (ddy > 0.0 || (ddy == 0.0 && pressed_in(p, y))))
                         ? TRIBO_CONTACT_ON
                         : TRIBO_CONTACT_OFF;
    const int onset = tribo_touching(&ph) && (!tribo_touching(old) || !fired);
    if (fired && fired[TRIBO_SWITCH_CONTACT])
        y[TRIBO_IY] = g.h;

    if (!tribo_touching(&ph)) {
        ph = TRIBO_PHASE_FLIGHT;
        /* model.md §3: the stretch is 0 when contact is regained; at lift-off it is already
           within a vanishing limit */
        y[TRIBO_IDX] = 0.0;
        return ph;
    }
    if (onset && fired)
        y[TRIBO_IDX] = 0.0;

    /* normal */
    const double dy_now = g.h - y[TRIBO_IY];
    if (p->nu == 0.0) {
        ph.normal = TRIBO_NORMAL_SIGN; /* the sign does not matter */
        ph.normal_sign = -1.0;
    } else if (onset) {
        const double vn = tribo_damped_velocity(p, &g, y);
        if (vn != 0.0) {
            ph.normal = TRIBO_NORMAL_SIGN;
            ph.normal_sign = vn < 0.0 ? -1.0 : 1.0;
        } else {
            normal_at_rest(p, y, dy_now, &ph);
        }
    } else if (fired && (fired[TRIBO_SWITCH_NORMAL_A] || fired[TRIBO_SWITCH_NORMAL_B] ||
                         fired[TRIBO_SWITCH_LOCK_FACTOR])) {
        if (old->normal == TRIBO_NORMAL_LOCK) {
            ph.normal = TRIBO_NORMAL_SIGN;
            ph.normal_sign = fired[TRIBO_SWITCH_LOCK_FACTOR] ? leaving_sign(p, y, &ph)
                             : fired[TRIBO_SWITCH_NORMAL_A] ? +1.0
                                                            : -1.0;
        } else {
            /* the damped velocity exactly 0 */
            y[TRIBO_IV] = p->damping_point == TRIBO_DAMPING_CENTRE ? 0.0 : -g.cx * y[TRIBO_IOMEGA];
            normal_at_rest(p, y, dy_now, &ph);
        }
    }

    /* tangential */
    const int tangent_event = fired && !onset && (fired[TRIBO_SWITCH_TANGENT_A] || fired[TRIBO_SWITCH_TANGENT_B]) &&
                              !fired[TRIBO_SWITCH_NORMAL_A] && !fired[TRIBO_SWITCH_NORMAL_B] &&
                              !fired[TRIBO_SWITCH_LOCK_FACTOR];
    if (tangent_event && old->tangent == TRIBO_TANGENT_STICK) {
        tribo_contact_eval ev;
        ph.tangent = TRIBO_TANGENT_SLIP;
        ph.slip_sign = fired[TRIBO_SWITCH_TANGENT_A] ? +1.0 : -1.0;
        double A;
        if (contact_point_lock(p, &ph) && (tribo_lock_force(p, &ph, &g, y, &A), !(A > 0.0))) {
            /* a lock that cannot slip this way is no lock (model.md §3): the contact
               leaves it, and the stretch is checked against the new normal phase's limit */
            ph.normal = TRIBO_NORMAL_SIGN;
            ph.normal_sign = leaving_sign(p, y, &ph);
            tangent_from_state(p, y, &ph);
        } else {
            tribo_contact_at(p, &ph, y, &ev);
            y[TRIBO_IDX] = ph.slip_sign * ev.limit;
            /* slip only where the stretch leaves the limit: at a grazing crossing the first
               order can show the opposite by rounding, and a slip that starts with
               sigma vs < d(limit)/dtau never sees its slip -> stick switch, and does
               positive work */
            if (!stretch_leaves_limit(ph.slip_sign, ev.vs, ev.limit_rate)) {
                /* The switch was crossed by integration error alone: on the limit, the stick
                   would see it crossed again at once. It starts that error's size inside
                   (the spring energy this takes out is booked as dissipated). */
                y[TRIBO_IDX] = ph.slip_sign * (ev.limit - 10.0 * (p->rtol * ev.limit + p->atol));
                ph.tangent = TRIBO_TANGENT_STICK;
                ph.slip_sign = 0.0;
            }
        }
    } else if (tangent_event) {
        tribo_contact_eval ev;
        tribo_contact_at(p, &ph, y, &ev);
        y[TRIBO_IDX] = ph.slip_sign * ev.limit;
        /* likewise, it sticks only where the stretch comes off the limit */
        if (!stretch_leaves_limit(ph.slip_sign, ev.vs, ev.limit_rate)) {
            ph.tangent = TRIBO_TANGENT_STICK;
            ph.slip_sign = 0.0;
        }
    } else {
        tangent_from_state(p, y, &ph);
    }
    confirm_lock(p, y, &ph);
    leave_rest(p, y, &ph);
    return ph;
}

tribo_force_law tribo_phase_after(const tribo_dyn_params *p, const tribo_force_law *old, double *y,
                                 const int *fired)
{
    /* the energy the adjustments of the state take out (a stretch clamped or reset, V set
       to 0 at a normal lock, Y put on the plate) is booked as dissipated work, so that the
       energy balance of model.md §6 holds across switches */
    const double before = tribo_energy(p, y);
    const tribo_force_law ph = next_phase(p, old, y, fired);
    y[TRIBO_IWDISS] += before - tribo_energy(p, y);
    return ph;
}

/* force_phases.c: the phases of the force law and the switches between them (model.md §3;
   the rigid stick and what an impact is, §3b). */
#include "force_phases.h"

#include <math.h>
#include <string.h>

const tribo_force_law TRIBO_PHASE_FLIGHT = {.contact = TRIBO_CONTACT_OFF,
                                            .normal = TRIBO_NORMAL_SIGN,
                                            .normal_sign = -1.0,
                                            .tangent = TRIBO_TANGENT_STICK};

/* The normal lock holds while Psi_N* (tribo_lock_force) lies in the band of normal forces
   the set-valued sign allows (model.md §3), max(0, dy(1 - nu)) <= Psi_N* <= dy(1 + nu), and,
   slipping, while A > 0. */
static double lock_lower(const tribo_dyn_params *p, double dy)
{
    return fmax(0.0, dy * (1.0 - p->nu));
}

/* A lock or a creep of the contact point (the tangential rules and the lock's force are
   those of tribo_lock_force). */
static int contact_point_lock(const tribo_dyn_params *p, const tribo_force_law *law)
{
    return tribo_locked(law) && p->damping_point == TRIBO_DAMPING_CONTACT_POINT;
}

/* The rounding of the damped velocity at y (tribo_velocity_rounding). */
static double damped_velocity_rounding(const tribo_dyn_params *p, const tribo_pose *g, const double *y)
{
    const double spin = p->damping_point == TRIBO_DAMPING_CENTRE ? 0.0 : g->cx * y[TRIBO_IOMEGA];
    return tribo_velocity_rounding(p, y[TRIBO_IV], spin);
}

/* With the rigid stick (model.md §3b) a slip in a contact-point lock ends where the contact
   point comes to rest, vs = 0: a stick there is the rigid one, whose stretch is quasi-static,
   not a spring that has to come off the limit first. */
static int slip_ends_at_rest(const tribo_dyn_params *p, const tribo_force_law *law)
{
    return p->rigid_stick && contact_point_lock(p, law) && law->tangent == TRIBO_TANGENT_SLIP &&
           !law->compliant_slip;
}

/* The rolling rule's switch functions (model.md §3c): turning, the spin reaching 0 (past 0 by
   more than its rounding where the phase started from rest: Omega creeps away from 0 there, and
   rounding would see it cross back again and again); in the rolling lock, the torque that holds
   it, Mr* = ev->roll_torque, reaching either edge of its band, -mu_r Psi_N or +mu_r Psi_N. */
static void roll_switch_functions(const tribo_dyn_params *p, const tribo_force_law *law,
                                  const tribo_contact_eval *ev, const double *y, double *g)
{
    if (law->roll == TRIBO_ROLL_TURNING) {
        g[TRIBO_SWITCH_ROLL_A] = law->roll_sign * y[TRIBO_IOMEGA];
        if (law->roll_from_rest)
            g[TRIBO_SWITCH_ROLL_A] += tribo_velocity_rounding(p, y[TRIBO_IOMEGA], 0.0);
    } else if (law->roll == TRIBO_ROLL_LOCK) {
        const double band = p->mu_roll * ev->psi_n;
        g[TRIBO_SWITCH_ROLL_A] = band + ev->roll_torque;
        g[TRIBO_SWITCH_ROLL_B] = band - ev->roll_torque;
    }
}

void tribo_switch_functions(const tribo_dyn_params *p, const tribo_force_law *law, const double *y,
                            double *g)
{
    tribo_contact_eval ev;
    for (int i = 0; i < TRIBO_N_SWITCHES; i++)
        g[i] = 1.0;
    if (isfinite(p->chute_length))
        g[TRIBO_SWITCH_EXIT] = p->chute_length - y[TRIBO_IX];
    g[TRIBO_SWITCH_CONTACT] = -y[TRIBO_IGAP];
    if (!tribo_touching(law))
        return;
    /* the contact as the phase sees it, even where delta_y has just gone negative (with its
       pose: the only one these functions take, since they run several times a step) */
    tribo_contact_at(p, law, y, &ev);
    const double dy = -y[TRIBO_IGAP];
    if (law->normal == TRIBO_NORMAL_CREEP) {
        /* the indentation on the band's edge reaches 0 (lift-off: taken before its clamp at 0,
           so that the root is seen where the load passes 0, as a vibrating plate's does,
           model.md §9b), or stops moving the way the creep goes: the load turns back into the
           band */
        g[TRIBO_SWITCH_CONTACT] = ev.psi_n / (1.0 - p->nu * law->normal_sign);
        g[TRIBO_SWITCH_NORMAL_A] = -law->normal_sign * tribo_lock_force_rate(p, law, y);
    }
    if (tribo_locked(law)) {
        if (law->normal == TRIBO_NORMAL_LOCK) {
            const double psi_star = ev.psi_n;
            g[TRIBO_SWITCH_NORMAL_A] = psi_star - lock_lower(p, dy);
            g[TRIBO_SWITCH_NORMAL_B] = dy * (1.0 + p->nu) - psi_star;
        }
        if (contact_point_lock(p, law) && law->tangent == TRIBO_TANGENT_SLIP)
            tribo_lock_force(p, law, &ev.pose, y, &g[TRIBO_SWITCH_LOCK_FACTOR]);
    } else if (p->nu > 0.0) {
        /* a sign phase that started at rest (out of a lock at its band's edge, where the
           velocity creeps away from 0, or at an edge the load stays on) would see rounding
           cross 0 again and again: its velocity must pass 0 by more than its rounding */
        g[TRIBO_SWITCH_NORMAL_A] = tribo_damped_velocity(p, &ev.pose, y);
        if (law->started_at_rest)
            g[TRIBO_SWITCH_NORMAL_A] += law->normal_sign * damped_velocity_rounding(p, &ev.pose, y);
    }
    switch (law->tangent) {
    case TRIBO_TANGENT_STICK:
        g[TRIBO_SWITCH_TANGENT_A] = ev.limit - y[TRIBO_IDX];
        g[TRIBO_SWITCH_TANGENT_B] = ev.limit + y[TRIBO_IDX];
        break;
    case TRIBO_TANGENT_RIGID: /* the quasi-static stretch -Psi_T* reaches the limit */
        g[TRIBO_SWITCH_TANGENT_A] = ev.limit + ev.psi_t;
        g[TRIBO_SWITCH_TANGENT_B] = ev.limit - ev.psi_t;
        break;
    default:
        /* a slip of the rigid stick ends where the contact point comes to rest, past 0 by more
           than the rounding of vs: one the rigid stick starts from rest (its constraint force
           at the limit) creeps away from 0, and rounding would see it cross back at once */
        g[TRIBO_SWITCH_TANGENT_A] =
            slip_ends_at_rest(p, law)
                ? law->slip_sign * ev.vs +
                      tribo_velocity_rounding(p, y[TRIBO_IU], ev.pose.h * y[TRIBO_IOMEGA])
                : law->slip_sign * ev.vs - ev.limit_rate;
        break;
    }
    roll_switch_functions(p, law, &ev, y, g);
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
    if (tribo_locked(ph)) {
        dir[TRIBO_SWITCH_NORMAL_A] = -1;
        if (ph->normal == TRIBO_NORMAL_LOCK)
            dir[TRIBO_SWITCH_NORMAL_B] = -1;
        if (contact_point_lock(p, ph) && ph->tangent == TRIBO_TANGENT_SLIP)
            dir[TRIBO_SWITCH_LOCK_FACTOR] = -1;
    } else if (p->nu > 0.0) {
        dir[TRIBO_SWITCH_NORMAL_A] = ph->normal_sign < 0 ? +1 : -1; /* vn reaches 0 */
    }
    dir[TRIBO_SWITCH_TANGENT_A] = -1;
    if (ph->tangent != TRIBO_TANGENT_SLIP)
        dir[TRIBO_SWITCH_TANGENT_B] = -1;
    if (ph->roll == TRIBO_ROLL_TURNING || ph->roll == TRIBO_ROLL_LOCK)
        dir[TRIBO_SWITCH_ROLL_A] = -1;
    if (ph->roll == TRIBO_ROLL_LOCK)
        dir[TRIBO_SWITCH_ROLL_B] = -1;
}

static void tangent_from_state(const tribo_dyn_params *p, double *y, tribo_force_law *law);
static void settle_tangent(const tribo_dyn_params *p, double *y, tribo_force_law *law,
                           const tribo_force_law *old);

/* The rate of the damped velocity (dvn/dtau, or the centre's dV/dtau) at y under the law. */
static double damped_velocity_rate(const tribo_dyn_params *p, const tribo_force_law *law,
                                   const double *y)
{
    double f[TRIBO_NMOTION];
    tribo_contact_eval ev;
    tribo_dynamics_rhs(p, law, y, f, &ev);
    if (p->damping_point == TRIBO_DAMPING_CENTRE)
        return f[TRIBO_IV];
    const double Om = y[TRIBO_IOMEGA];
    return f[TRIBO_IV] + tribo_pose_kappa(p->eps2, &ev.pose) * Om * Om + ev.pose.cx * f[TRIBO_IOMEGA];
}

/* The damped velocity's rate (dvn/dtau) at y in the normal phase of sign s (s = 0: the
   spring force alone, Psi_N = delta_y), under the tangential rule that phase has on a copy of
   y: settled as after a switch from old (settle_tangent), or, where old is NULL, the one the
   state gives (tangent_from_state). */
static double sign_phase_rate(const tribo_dyn_params *p, const double *y,
                              const tribo_force_law *law, const tribo_force_law *old, double s)
{
    double z[TRIBO_NSTATE_MAX];
    memcpy(z, y, sizeof z);
    tribo_force_law trial = *law;
    trial.normal = TRIBO_NORMAL_SIGN;
    trial.normal_sign = s;
    if (old)
        settle_tangent(p, z, &trial, old);
    else
        tangent_from_state(p, z, &trial);
    return damped_velocity_rate(p, &trial, z);
}

/* Where no lock can hold the contact point (A <= 0, a Painleve-type configuration, model.md
   §3): the sign under which vn leaves 0 consistently, s dvn/dtau > 0 in the phase that sign
   leads into (its Coulomb limit decides stick or slip; the stretch is never raised to a new
   limit). Where both signs are consistent (A < 0 allows it), or neither, vn leaves in the
   direction dvn/dtau has under the spring force alone. */
static double leaving_sign(const tribo_dyn_params *p, const double *y, const tribo_force_law *law)
{
    /* each phase with the tangential rule it gives the stretch */
    const int lifts = sign_phase_rate(p, y, law, NULL, +1.0) > 0.0;
    const int presses = sign_phase_rate(p, y, law, NULL, -1.0) < 0.0;
    if (lifts != presses)
        return lifts ? +1.0 : -1.0;
    return sign_phase_rate(p, y, law, NULL, 0.0) > 0.0 ? +1.0 : -1.0;
}

static int in_band(const tribo_dyn_params *p, double dy, double psi_star)
{
    return p->nu > 0.0 && psi_star >= lock_lower(p, dy) && psi_star <= dy * (1.0 + p->nu);
}

/* Whether a sign phase of sign s, with the tangential rule it would have (settled as after a
   switch), takes the damped velocity away from 0 that way: s dvn/dtau > 0 (model.md §3). */
static int sign_leaves(const tribo_dyn_params *p, const double *y, const tribo_force_law *law,
                       const tribo_force_law *old, double s)
{
    return s * sign_phase_rate(p, y, law, old, s) > 0.0;
}

/* A lock with the compliant stick (Psi_T = -dx) where its force lies in the band and the
   stretch within its limit: law set to it, 1; else 0 and law unchanged. */
static int compliant_stick_lock(const tribo_dyn_params *p, const double *y, double dy,
                                tribo_force_law *law)
{
    tribo_force_law stick = *law;
    stick.normal = TRIBO_NORMAL_LOCK;
    stick.normal_sign = 0.0;
    stick.tangent = TRIBO_TANGENT_STICK;
    stick.slip_sign = 0.0;
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    double A;
    const double psi_star = tribo_lock_force(p, &stick, &g, y, &A);
    if (!(A > 0.0 && in_band(p, dy, psi_star) && fabs(y[TRIBO_IDX]) <= p->mu * psi_star))
        return 0;
    *law = stick;
    return 1;
}

/* A lock of the contact at y (a copy z of it) under the tangential rule the lock itself would
   have, settled as after a switch (settle_tangent: with the rigid stick a stick is the rigid
   one, which stops the contact point). Returns its Psi_N*, and A. */
static double lock_candidate(const tribo_dyn_params *p, const double *y, const tribo_force_law *old,
                             tribo_force_law *law, double *z, double *A)
{
    memcpy(z, y, TRIBO_NSTATE_MAX * sizeof *z);
    law->normal = TRIBO_NORMAL_LOCK;
    law->normal_sign = 0.0;
    settle_tangent(p, z, law, old);
    tribo_pose g;
    tribo_pose_at(p->eps2, z[TRIBO_IPHI], &g);
    return tribo_lock_force(p, law, &g, z, A);
}

/* The rule of a contact whose damped velocity is exactly 0 (model.md §3, §3b): a normal lock
   if the force that holds it, under the tangential rule the lock itself has, is within the
   band: that rule and the state it gives (a rigid stick stops the contact point) are the
   lock's, so that the rule that entered the lock is the rule that holds it (never re-derived
   later under another: the contact would leave the lock it entered at once, and vn return
   through 0 again and again). The rule before may be a slip at a zero limit, the contact
   having been unloaded. Otherwise the sign the net normal force gives the velocity under that
   rule: below the band the contact lifts (s = +1), above it presses in (s = -1), where the
   sign phase then leaves 0 that way under its own tangential rule (sign_leaves); where A <= 0
   there is no lock (leaving_sign). A lock holds the indentation dy. Returns 1 where it set
   law's tangential rule (and y) too. */
static int normal_at_rest(const tribo_dyn_params *p, double *y, double dy, tribo_force_law *law,
                          const tribo_force_law *old)
{
    if (p->damping_point == TRIBO_DAMPING_CENTRE) {
        /* the centre's lock does not depend on the tangential rule: V held at 0 */
        double A;
        tribo_pose g;
        tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
        const double psi_star = tribo_lock_force(p, law, &g, y, &A);
        law->normal = in_band(p, dy, psi_star) ? TRIBO_NORMAL_LOCK : TRIBO_NORMAL_SIGN;
        law->normal_sign = law->normal == TRIBO_NORMAL_LOCK ? 0.0 : psi_star < lock_lower(p, dy) ? +1.0 : -1.0;
        return 0;
    }
    tribo_force_law as_locked = *law;
    double z[TRIBO_NSTATE_MAX], A;
    const double psi_star = lock_candidate(p, y, old, &as_locked, z, &A);
    if (!(A > 0.0)) {
        law->normal = TRIBO_NORMAL_SIGN;
        law->normal_sign = leaving_sign(p, y, law);
        return 0;
    }
    if (in_band(p, dy, psi_star)) {
        *law = as_locked;
        memcpy(y, z, sizeof z);
        return 1;
    }
    /* no lock under its own rule: the sign its force points to, where the sign phase leaves 0
       that way under its own tangential rule (which may differ from the lock's: a stick where
       the lock would slip, a limit of its own); else the other sign, where that one does; else
       the lock with the compliant stick, where that holds */
    const double s0 = psi_star < lock_lower(p, dy) ? +1.0 : -1.0;
    law->normal = TRIBO_NORMAL_SIGN;
    law->normal_sign = s0;
    if (sign_leaves(p, y, law, old, s0))
        return 0;
    if (sign_leaves(p, y, law, old, -s0)) {
        law->normal_sign = -s0;
        return 0;
    }
    return compliant_stick_lock(p, y, dy, law);
}

/* d2h/dphi2 at phi: -kappa (model.md §3), exactly as flight.c has it, so that a contact the
   flight's search makes is made here too. */
static double h_curvature(const tribo_dyn_params *p, double phi)
{
    tribo_pose g;
    tribo_pose_at(p->eps2, phi, &g);
    return -tribo_pose_kappa(p->eps2, &g);
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

/* A slip through a switch that was not a tangential one (the normal rule changed): it goes on,
   the stretch put on the new phase's limit, where the stretch is on that limit to within the
   rounding of the located switch (a stretch clamped to a lower limit included) and would leave
   it; with the rigid stick in a contact-point lock, wherever the contact point still slides
   (a stick there would be rigid, and the contact point does not stop while it slides). Where
   the slip goes on, law and y are set and it returns 1. */
static int slip_goes_on(const tribo_dyn_params *p, double *y, tribo_force_law *law, double sigma)
{
    tribo_force_law slip = *law;
    slip.tangent = TRIBO_TANGENT_SLIP;
    slip.slip_sign = sigma;
    tribo_contact_eval ev;
    tribo_contact_at(p, &slip, y, &ev);
    if (contact_point_lock(p, &slip)) {
        double A;
        tribo_lock_force(p, &slip, &ev.pose, y, &A);
        if (!(A > 0.0))
            return 0;
    }
    int goes_on;
    if (slip_ends_at_rest(p, &slip)) {
        goes_on = sigma * ev.vs > tribo_velocity_rounding(p, y[TRIBO_IU], ev.pose.h * y[TRIBO_IOMEGA]);
    } else {
        const double stretch = sigma * y[TRIBO_IDX];
        goes_on = stretch >= ev.limit - 1e-9 * (ev.limit + fabs(stretch)) &&
                  stretch_leaves_limit(sigma, ev.vs, ev.limit_rate);
    }
    if (!goes_on)
        return 0;
    *law = slip;
    y[TRIBO_IDX] = sigma * ev.limit;
    return 1;
}

/* A slip of a contact-point lock in direction sigma from here, the stretch put on its limit
   (the spring energy that changes is booked by tribo_phase_after); 0 where that slip has no
   lock (A <= 0) and nothing changes. */
static int slip_goes_on_forced(const tribo_dyn_params *p, double *y, tribo_force_law *law,
                               double sigma)
{
    tribo_force_law slip = *law;
    slip.tangent = TRIBO_TANGENT_SLIP;
    slip.slip_sign = sigma;
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    double A;
    const double psi = tribo_lock_force(p, &slip, &g, y, &A);
    if (!(A > 0.0))
        return 0;
    *law = slip;
    y[TRIBO_IDX] = sigma * p->mu * psi;
    return 1;
}

/* The rigid stick (model.md §3b) in a contact-point lock that sticks: the contact point is
   brought to rest (tribo_stop_contact_point: the energy of the spring's ringing and of the
   relative motion is booked as dissipated by tribo_phase_after) and held there by the
   constraint forces while they lie strictly within the Coulomb limit, the stretch at its
   quasi-static value -Psi_T*. Beyond the limit the contact slips, from rest, the way the
   constraint force cannot hold it (sigma = -sgn Psi_T*, under which sigma dvs/dtau >= 0), the
   stretch on the limit. Where that slip has no lock (A <= 0, model.md §3) the compliant stick
   stays, as in the compliant model; so it does where the constraint's normal force lies outside
   the lock's band (a lock, not a creep, which follows its edge): the rigid lock would end at
   once, into a sign phase with the compliant stick, under which the net normal force points
   back into the lock (the lock under the compliant stick holds; model.md §3b). */
static void stick_rigidly(const tribo_dyn_params *p, double *y, tribo_force_law *law)
{
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    double z[TRIBO_NSTATE_MAX];
    memcpy(z, y, sizeof z);
    tribo_stop_contact_point(p, law, &g, z);
    double psi_n, psi_t;
    tribo_rigid_forces(p, law, &g, z[TRIBO_IOMEGA], &psi_n, &psi_t);
    tribo_force_law next = *law;
    if (law->normal == TRIBO_NORMAL_LOCK && !in_band(p, -y[TRIBO_IGAP], psi_n))
        return;
    if (fabs(psi_t) < p->mu * psi_n) {
        next.tangent = TRIBO_TANGENT_RIGID;
        next.slip_sign = 0.0;
        z[TRIBO_IDX] = -psi_t;
    } else {
        next.tangent = TRIBO_TANGENT_SLIP;
        next.slip_sign = psi_t > 0.0 ? -1.0 : 1.0;
        double A;
        const double psi_slip = tribo_lock_force(p, &next, &g, z, &A);
        if (!(A > 0.0))
            return;
        z[TRIBO_IDX] = next.slip_sign * p->mu * psi_slip;
    }
    *law = next;
    memcpy(y, z, sizeof z);
}

/* Whether a compliant stick entering a contact-point lock is a slide the spring cannot hold:
   the ringing it would start about a stretch of 0, sqrt(dx^2 + vs^2 / w^2) at the spring's
   frequency w (w^2 = det W / W_NN, the contact point's tangential inverse mass with the normal
   held), reaches the Coulomb limit of a slip in the direction of vs. The rigid stick's limit of
   such a contact is a slip, not a stop (stick_rigidly stops only the spring's ringing). */
static int slides_through(const tribo_dyn_params *p, const double *y, const tribo_force_law *law)
{
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    const double vs = y[TRIBO_IU] + g.h * y[TRIBO_IOMEGA];
    tribo_force_law slip = *law;
    slip.tangent = TRIBO_TANGENT_SLIP;
    slip.slip_sign = vs >= 0.0 ? 1.0 : -1.0;
    double A, w[3];
    const double L = p->mu * tribo_lock_force(p, &slip, &g, y, &A);
    if (!(A > 0.0))
        return 0;
    tribo_contact_inverse_mass(p, &g, w);
    const double dx = y[TRIBO_IDX], w2 = (w[0] * w[2] - w[1] * w[1]) / w[0];
    return dx * dx + vs * vs / w2 > L * L;
}

/* The tangential rule of a contact phase after a switch that was not a tangential one: a slip
   that goes on (slip_goes_on), else the rule the state gives (tangent_from_state); with the
   rigid stick, a stick in a contact-point lock is the rigid one (stick_rigidly), or a slip
   where the contact slides through (slides_through). */
static void settle_tangent(const tribo_dyn_params *p, double *y, tribo_force_law *law,
                           const tribo_force_law *old)
{
    const int was_slipping = tribo_touching(old) && old->tangent == TRIBO_TANGENT_SLIP;
    if (!(was_slipping && slip_goes_on(p, y, law, old->slip_sign)))
        tangent_from_state(p, y, law);
    if (p->rigid_stick && contact_point_lock(p, law) && law->tangent == TRIBO_TANGENT_STICK) {
        tribo_pose g;
        tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
        const double sigma = y[TRIBO_IU] + g.h * y[TRIBO_IOMEGA] >= 0.0 ? 1.0 : -1.0;
        if (!(slides_through(p, y, law) && slip_goes_on_forced(p, y, law, sigma)))
            stick_rigidly(p, y, law);
    }
}

/* A contact-point lock whose tangential rule was decided after its normal rule (a lock through
   a tangential switch, or a creep's load turning back into the band): Psi_N* and A change with
   the rule, so the lock is checked under the rule it has now, never under another (model.md
   §3b); where it does not hold there, the contact leaves it as a contact at rest does
   (normal_at_rest), and the tangential rule follows the new normal phase. */
static void confirm_lock(const tribo_dyn_params *p, double *y, tribo_force_law *law,
                         const tribo_force_law *old)
{
    if (!contact_point_lock(p, law))
        return;
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    double A;
    const double psi_star = tribo_lock_force(p, law, &g, y, &A);
    if (law->normal == TRIBO_NORMAL_CREEP) {
        /* a creep sits on its band's edge by construction; only a slip's A can end it */
        if (!(A > 0.0)) {
            law->normal = TRIBO_NORMAL_SIGN;
            law->normal_sign = leaving_sign(p, y, law);
            settle_tangent(p, y, law, old);
        }
        return;
    }
    if (A > 0.0 && in_band(p, -y[TRIBO_IGAP], psi_star))
        return;
    if (!normal_at_rest(p, y, -y[TRIBO_IGAP], law, old))
        settle_tangent(p, y, law, old);
}

/* Whether a particle touching the plate at rest (delta_y = 0 and d(delta_y)/dtau = 0) is
   pressed into it: d2(delta_y)/dtau2 > 0 in flight, i.e. the net normal force pulls it
   down against the rate at which rotation lifts the lowest point, h''(phi) Omega^2.
   Without this, a particle set down on the plate would start in flight, and the contact
   root, zero at the start and a small step later, would never see it sink in. */
static int pressed_in(const tribo_dyn_params *p, const double *y)
{
    const double Om = y[TRIBO_IOMEGA];
    const double curvature = h_curvature(p, y[TRIBO_IPHI]) * Om * Om + (p->g_n - tribo_force_n(p));
    if (!tribo_vibrating(p))
        return tribo_pressed_in(p, curvature, 0.0);
    /* its rate, h''' Omega^3 - dF_N/dtau (h''' = -dkappa/dphi; model.md §9b) */
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    const double kappa = tribo_pose_kappa(p->eps2, &g);
    const double rate = -tribo_pose_kappa_slope(&g, kappa) * Om * Om * Om - p->vib_rate_n;
    return tribo_pressed_in(p, curvature, rate);
}

/* Whether a sign phase starts at rest at y: its damped velocity within its rounding of 0, and
   so slow to leave it that it takes more than a unit of time (the contact's own time scale)
   to get out of that rounding, as out of a lock at its band's edge (where the normal force is
   continuous) or at a reversal with the load on an edge. Then the velocity creeps away from 0,
   noise can see it cross 0 again and again, and its switch must wait for it to pass 0
   decisively. (At a reversal the velocity leaves 0 at once, and the next reversal is a switch
   of its own, where a lock can end an oscillation that is left.) */
static int creeps(const tribo_dyn_params *p, const tribo_force_law *ph, const double *y)
{
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    const double rounding = damped_velocity_rounding(p, &g, y);
    if (fabs(tribo_damped_velocity(p, &g, y)) > rounding)
        return 0;
    return fabs(damped_velocity_rate(p, ph, y)) <= rounding;
}

/* Whether a contact made at y (delta_y = 0) is made: the contact point approaches the plate,
   vn = -d(delta_y)/dtau below minus its rounding, or, not moving away (vn in [-rounding, 0]),
   is pressed in (tribo_touch_makes_contact, the flight's rule too). A contact "made" while it
   moves away is delta_y reaching 0 by rounding: no contact, and no impact (model.md §3b). */
static int approaching(const tribo_dyn_params *p, const tribo_pose *g, const double *y)
{
    const double spin = g->cx * y[TRIBO_IOMEGA];
    const double vn = y[TRIBO_IV] + spin, rounding = tribo_velocity_rounding(p, y[TRIBO_IV], spin);
    return tribo_touch_makes_contact(vn, rounding, pressed_in(p, y));
}

/* ---- the phase after an event: contact, normal rule, tangential rule -------------------- */

/* Whether the contact is made or lost at this event (or, with fired = NULL, whether the state
   is in contact): sets law->contact. Returns 0 where nothing happens at all: a contact "made"
   by rounding while the contact point moves away (model.md §3b). */
static int contact_after(const tribo_dyn_params *p, const tribo_force_law *old, const tribo_pose *g,
                         const double *y, const int *fired, tribo_force_law *law)
{
    const double dy = -y[TRIBO_IGAP];
    if (fired && fired[TRIBO_SWITCH_CONTACT]) {
        if (!tribo_touching(old) && !approaching(p, g, y))
            return 0;
        law->contact = tribo_touching(old) ? TRIBO_CONTACT_OFF : TRIBO_CONTACT_ON;
    } else if (fired && tribo_touching(old) && dy < 0.0) {
        /* another switch where the lowest point is already above the plate: the contact
           was lost within the root finding's resolution of this switch, and its root,
           negative from the restart on, would never be seen (the phase would stay in
           contact with no force, its tangent switch firing at every stretch rounding) */
        law->contact = TRIBO_CONTACT_OFF;
    } else if (!fired) {
        law->contact = dy > 0.0 || (dy == 0.0 && approaching(p, g, y)) ? TRIBO_CONTACT_ON
                                                                      : TRIBO_CONTACT_OFF;
    }
    return 1;
}

/* The stretch at an event in contact (model.md §3): 0 on a new contact made at a switch; a
   slip's on its limit (CVODE's integrated stretch follows it only to the tolerances, and what
   the slip does next is decided against it). */
static void stretch_at_event(const tribo_dyn_params *p, const tribo_force_law *old, double *y,
                             const int *fired, int onset)
{
    if (onset && fired)
        y[TRIBO_IDX] = 0.0;
    if (!onset && old->tangent == TRIBO_TANGENT_SLIP) {
        tribo_contact_eval ev;
        tribo_contact_at(p, old, y, &ev);
        y[TRIBO_IDX] = old->slip_sign * ev.limit;
    }
}

/* The damped velocity, found past 0 by its rounding, put exactly at 0: the contact point's by
   a normal impulse there (which takes out -vn^2 / (2 W_NN) of the energy), the centre's by
   setting V (model.md §3, "Phases and switches"); in the rolling lock, which holds Omega at 0,
   the contact point's is V too (§3c). */
static void stop_damped_velocity(const tribo_dyn_params *p, const tribo_force_law *law,
                                 const tribo_pose *g, double *y)
{
    if (p->damping_point == TRIBO_DAMPING_CENTRE || law->roll == TRIBO_ROLL_LOCK) {
        y[TRIBO_IV] = 0.0;
        return;
    }
    double w[3];
    tribo_contact_inverse_mass(p, g, w);
    const double P_n = -(y[TRIBO_IV] + g->cx * y[TRIBO_IOMEGA]) / w[0];
    y[TRIBO_IV] += P_n;
    y[TRIBO_IOMEGA] += p->inv_inertia * g->cx * P_n;
}

/* The normal rule after a switch of the normal law itself (fired: NORMAL_A, NORMAL_B or
   LOCK_FACTOR; model.md §3, §3b): out of a lock or a creep, or the damped velocity reaching 0.
   Returns 1 where it set the tangential rule too (normal_at_rest). */
static int normal_after_switch(const tribo_dyn_params *p, const tribo_force_law *old,
                                const tribo_pose *g, double *y, const int *fired, tribo_force_law *law)
{
    const double edge = fired[TRIBO_SWITCH_NORMAL_A] ? +1.0 : -1.0;
    if (fired[TRIBO_SWITCH_LOCK_FACTOR] && tribo_locked(old)) {
        /* a slipping lock or creep whose A reaches 0 (model.md §3) */
        law->normal = TRIBO_NORMAL_SIGN;
        law->normal_sign = leaving_sign(p, y, law);
    } else if (old->normal == TRIBO_NORMAL_CREEP) {
        /* the load turns back into the band: the lock holds the indentation the creep
           reached, a hair inside the band (1e-12 of it, far above the edge's rounding
           and far below anything the motion sees), so that the lock's own switch
           starts on the right side of its edge */
        law->normal = TRIBO_NORMAL_LOCK;
        law->normal_sign = 0.0;
        y[TRIBO_IGAP] *= 1.0 - 1e-12 * old->normal_sign; /* G < 0: s = +1 less deep */
        y[TRIBO_IY] = g->h + y[TRIBO_IGAP];
    } else if (old->normal == TRIBO_NORMAL_LOCK && p->rigid_stick && contact_point_lock(p, old) &&
               1.0 - p->nu * edge > 0.0) {
        /* with the rigid stick a load that goes on past the band's edge makes the lock
           creep along it (the lower edge only where nu < 1, where it is not 0) */
        law->normal = TRIBO_NORMAL_CREEP;
        law->normal_sign = edge;
    } else if (old->normal == TRIBO_NORMAL_LOCK) {
        /* out of the lock at its band's edge: the normal force is continuous there, and
           the damped velocity leaves 0 from rest (at the edge d(vn)/dtau = 0 too: it
           creeps, and its switch waits for it to pass 0 decisively, started_at_rest) */
        law->normal = TRIBO_NORMAL_SIGN;
        law->normal_sign = edge;
    } else {
        stop_damped_velocity(p, law, g, y);
        return normal_at_rest(p, y, -y[TRIBO_IGAP], law, old);
    }
    return 0;
}

/* The normal rule of the new phase (model.md §3): any sign where there is no dashpot; on a new
   contact the sign of the damped velocity, or, at rest, the rule at rest; after a normal
   switch, normal_after_switch; else the rule goes on. Returns 1 where it set the tangential rule
   too (a lock entered at rest keeps the rule it was entered under: normal_at_rest). */
static int normal_after(const tribo_dyn_params *p, const tribo_force_law *old, const tribo_pose *g,
                         double *y, const int *fired, int onset, int normal_event,
                         tribo_force_law *law)
{
    if (p->nu == 0.0) {
        law->normal = TRIBO_NORMAL_SIGN; /* the sign does not matter */
        law->normal_sign = -1.0;
    } else if (onset) {
        const double vn = tribo_damped_velocity(p, g, y);
        if (vn != 0.0) {
            law->normal = TRIBO_NORMAL_SIGN;
            law->normal_sign = vn < 0.0 ? -1.0 : 1.0;
        } else {
            return normal_at_rest(p, y, -y[TRIBO_IGAP], law, old);
        }
    } else if (normal_event) {
        return normal_after_switch(p, old, g, y, fired, law);
    }
    return 0;
}

/* A stick -> slip switch (fired TANGENT_A: the stretch reaches +limit, TANGENT_B: -limit;
   model.md §3): a slip in that direction, where the stretch leaves the limit; a lock that
   cannot slip that way is left. */
static void stick_to_slip(const tribo_dyn_params *p, const tribo_force_law *old, const tribo_pose *g,
                          double *y, const int *fired, tribo_force_law *law)
{
    law->tangent = TRIBO_TANGENT_SLIP;
    law->slip_sign = fired[TRIBO_SWITCH_TANGENT_A] ? +1.0 : -1.0;
    double A;
    if (contact_point_lock(p, law) && (tribo_lock_force(p, law, g, y, &A), !(A > 0.0))) {
        /* a lock that cannot slip this way is no lock (model.md §3): the contact
           leaves it, and the stretch is checked against the new normal phase's limit */
        law->normal = TRIBO_NORMAL_SIGN;
        law->normal_sign = leaving_sign(p, y, law);
        tangent_from_state(p, y, law);
        return;
    }
    tribo_contact_eval ev;
    tribo_contact_at(p, law, y, &ev);
    y[TRIBO_IDX] = law->slip_sign * ev.limit;
    /* slip only where the stretch leaves the limit: at a grazing crossing the first
       order can show the opposite by rounding, and a slip that starts with
       sigma vs < d(limit)/dtau never sees its slip -> stick switch, and does
       positive work. (The rigid stick's constraint force has passed the limit: its
       slip starts from rest at second order, sigma dvs/dtau >= 0, stick_rigidly.) */
    if (old->tangent == TRIBO_TANGENT_STICK &&
        !stretch_leaves_limit(law->slip_sign, ev.vs, ev.limit_rate)) {
        /* The switch was crossed by integration error alone: on the limit, the stick
           would see it crossed again at once. It starts that error's size inside
           (the spring energy this takes out is booked as dissipated). */
        y[TRIBO_IDX] = law->slip_sign * (ev.limit - 10.0 * (p->rtol * ev.limit + p->atol));
        law->tangent = TRIBO_TANGENT_STICK;
        law->slip_sign = 0.0;
    }
}

/* A slip -> stick switch (model.md §3): it sticks only where the stretch comes off the limit;
   with the rigid stick a slip in a contact-point lock ends where the contact point comes to
   rest (§3b), and sticks rigidly, or, where the rigid stick cannot hold the lock
   (stick_rigidly), as the compliant stick does: where the stretch comes off the limit; else the
   slip goes on and ends as the compliant one does (compliant_slip: a stick on the limit that
   the stretch would leave would slip again at once, and that slip stop again at once). */
static void slip_to_stick(const tribo_dyn_params *p, const tribo_force_law *old, double *y,
                          tribo_force_law *law)
{
    tribo_contact_eval ev;
    tribo_contact_at(p, law, y, &ev);
    y[TRIBO_IDX] = law->slip_sign * ev.limit;
    const int comes_off = !stretch_leaves_limit(law->slip_sign, ev.vs, ev.limit_rate);
    if (!slip_ends_at_rest(p, old) && !comes_off)
        return;
    const tribo_force_law slip = *law;
    law->tangent = TRIBO_TANGENT_STICK;
    law->slip_sign = 0.0;
    if (p->rigid_stick && contact_point_lock(p, law))
        stick_rigidly(p, y, law);
    if (law->tangent == TRIBO_TANGENT_STICK && !comes_off) {
        *law = slip;
        law->compliant_slip = 1;
    }
}

/* The tangential rule of the new phase: after a tangential switch (and nothing else at the
   event), the other rule where the stretch goes that way; else settled afresh. */
static void tangent_after(const tribo_dyn_params *p, const tribo_force_law *old, const tribo_pose *g,
                          double *y, const int *fired, int onset, int normal_event,
                          tribo_force_law *law)
{
    const int tangent_event = fired && !onset && !normal_event &&
                              (fired[TRIBO_SWITCH_TANGENT_A] || fired[TRIBO_SWITCH_TANGENT_B]);
    if (tangent_event && old->tangent != TRIBO_TANGENT_SLIP)
        stick_to_slip(p, old, g, y, fired, law);
    else if (tangent_event)
        slip_to_stick(p, old, y, law);
    else
        settle_tangent(p, y, law, old);
}

/* Whether the new phase starts at rest (creeps), and, with the rigid stick, a contact at rest
   whose load lies on an edge of the band and moves past it: it creeps along that edge (the
   sign phase it would start rings; model.md §3b). */
static void mark_start_at_rest(const tribo_dyn_params *p, const double *y, tribo_force_law *law)
{
    law->started_at_rest = tribo_touching(law) && law->normal == TRIBO_NORMAL_SIGN && p->nu > 0.0 &&
                           creeps(p, law, y);
    if (law->started_at_rest && p->rigid_stick && p->damping_point == TRIBO_DAMPING_CONTACT_POINT &&
        1.0 - p->nu * law->normal_sign > 0.0) {
        law->normal = TRIBO_NORMAL_CREEP;
        law->started_at_rest = 0;
    }
}

/* The normal and tangential rules of a contact phase after an event, its rolling rule set:
   the normal rule, then (unless that set it too) the tangential rule, the lock confirmed under
   both, and whether the phase starts at rest. */
static void contact_rules(const tribo_dyn_params *p, const tribo_force_law *old, const tribo_pose *g,
                          double *y, const int *fired, int onset, int normal_event,
                          tribo_force_law *law)
{
    if (!normal_after(p, old, g, y, fired, onset, normal_event, law))
        tangent_after(p, old, g, y, fired, onset, normal_event, law);
    confirm_lock(p, y, law, old);
    mark_start_at_rest(p, y, law);
    if (law->tangent != TRIBO_TANGENT_SLIP || !contact_point_lock(p, law))
        law->compliant_slip = 0;
}

/* ---- the rolling rule (model.md §3c) ------------------------------------------------------- */

/* Whether the rolling rule is decided at zero spin at this event: where Omega reached 0 (a
   turning phase's roll switch), where the rolling lock holds it there (at any event but the
   lock's own edge), or at a contact that starts without spin. */
static int spin_at_zero(const tribo_force_law *old, const double *y, const int *fired, int onset)
{
    const int roll_switch = fired && (fired[TRIBO_SWITCH_ROLL_A] || fired[TRIBO_SWITCH_ROLL_B]);
    if (onset)
        return y[TRIBO_IOMEGA] == 0.0;
    if (old->roll == TRIBO_ROLL_LOCK)
        return !roll_switch;
    return old->roll == TRIBO_ROLL_TURNING && roll_switch;
}

/* The rolling rule where the spin does not start at 0: none without rolling resistance; turning
   the way Omega does on a new contact; out of the rolling lock at an edge of its band, turning
   from rest the way the torque that reached it drives the grain (edge A: the holding torque at
   -mu_r Psi_N, resisting a positive drive); else the rule goes on. */
static void roll_goes_on(const tribo_dyn_params *p, const tribo_force_law *old, const double *y,
                         const int *fired, int onset, tribo_force_law *law)
{
    if (p->mu_roll == 0.0) {
        law->roll = TRIBO_ROLL_FREE;
        law->roll_sign = 0.0;
        law->roll_from_rest = 0;
    } else if (onset) {
        law->roll = TRIBO_ROLL_TURNING;
        law->roll_sign = y[TRIBO_IOMEGA] > 0.0 ? 1.0 : -1.0;
        law->roll_from_rest = 0;
    } else if (old->roll == TRIBO_ROLL_LOCK) {
        law->roll = TRIBO_ROLL_TURNING;
        law->roll_sign = fired[TRIBO_SWITCH_ROLL_A] ? 1.0 : -1.0;
        law->roll_from_rest = 1;
    }
}

/* Omega, found past 0 by its rounding at a roll switch, put exactly at 0, with the constraints of
   the phase kept (the contact point's normal velocity in a contact-point lock, its slip velocity
   in the rigid stick); the energy this takes out is booked by tribo_phase_after. */
static void stop_spin(const tribo_dyn_params *p, const tribo_force_law *law, const tribo_pose *g,
                      double *y)
{
    const double Om = y[TRIBO_IOMEGA];
    if (contact_point_lock(p, law))
        y[TRIBO_IV] += g->cx * Om;
    if (law->tangent == TRIBO_TANGENT_RIGID)
        y[TRIBO_IU] += g->h * Om;
    y[TRIBO_IOMEGA] = 0.0;
}

/* Whether the rolling lock holds the grain at y under the law (its rolling rule the lock, its
   normal and tangential rules set): the torque that holds it, Mr* = -(h Psi_T + cx Psi_N),
   within mu_r Psi_N (model.md §3c). At Psi_N = 0 (a contact just made) the band and the torque
   both open from 0: they are compared as they grow, per unit normal force, the forces' rates
   in the ratio of their values, Psi_T / Psi_N -> (dPsi_T/dtau) / (dPsi_N/dtau): -mu sigma in
   slip, -vs / (d(delta_y)/dtau (1 - nu s)) in stick, whose stretch grows at vs from 0. (Judged
   by the forces at that instant alone, a stick's Psi_T = 0, the lock could be taken where its
   torque leaves the band at once: its switch function would start at 0 and cross at once,
   which an integrator's root finding cannot see.) *turn: the sign the grain turns with where
   it does not hold, that of the torque that drives it, -Mr*. */
static int roll_lock_holds(const tribo_dyn_params *p, const tribo_force_law *law, const double *y,
                           double *turn)
{
    tribo_contact_eval ev;
    tribo_contact_at(p, law, y, &ev);
    double drive = -ev.roll_torque, band = p->mu_roll * ev.psi_n;
    if (!(ev.psi_n > 0.0)) {
        const double load_rate = (1.0 - p->nu * ev.sign_v) * (-ev.pose.cx * y[TRIBO_IOMEGA] - y[TRIBO_IV]);
        const double tangential = law->tangent == TRIBO_TANGENT_SLIP ? -p->mu * law->slip_sign
                                  : load_rate > 0.0                  ? -ev.vs / load_rate
                                                                     : 0.0;
        drive = ev.pose.cx + ev.pose.h * tangential;
        band = p->mu_roll;
    }
    *turn = drive >= 0.0 ? 1.0 : -1.0;
    return fabs(drive) <= band;
}

/* The phase of a contact whose spin is 0 at an event (spin_at_zero): the rolling lock, with the
   normal and tangential rules decided under it, where its holding torque lies within its band
   under them; else turning from rest, the way that torque drives the grain, the rules decided
   under that (model.md §3c). The rule that enters the rolling lock is the one that holds it. */
static tribo_force_law phase_at_zero_spin(const tribo_dyn_params *p, const tribo_force_law *old,
                                          const tribo_pose *g, double *y, const int *fired,
                                          int onset, int normal_event, tribo_force_law law)
{
    stop_spin(p, old, g, y);
    tribo_force_law locked = law;
    locked.roll = TRIBO_ROLL_LOCK;
    locked.roll_sign = 0.0;
    locked.roll_from_rest = 0;
    double z[TRIBO_NSTATE_MAX], turn;
    memcpy(z, y, sizeof z);
    contact_rules(p, old, g, z, fired, onset, normal_event, &locked);
    if (!tribo_touching(&locked) || roll_lock_holds(p, &locked, z, &turn)) {
        memcpy(y, z, sizeof z);
        return locked;
    }
    law.roll = TRIBO_ROLL_TURNING;
    law.roll_sign = turn;
    law.roll_from_rest = 1;
    contact_rules(p, old, g, y, fired, onset, normal_event, &law);
    return law;
}

/* The phase after an event (fired: the roots found) or, with fired = NULL, the phase a
   state is in when the integration (re)starts there. Adjusts y to put the switched
   boundary exactly on it (Y = h, damped velocity 0, delta_x = +-limit, Omega = 0), so that
   CVODE's root functions start at 0 and look at the direction the motion takes. */
static tribo_force_law next_phase(const tribo_dyn_params *p, const tribo_force_law *old, double *y,
                                  const int *fired)
{
    tribo_force_law ph = *old;
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    if (!contact_after(p, old, &g, y, fired, &ph))
        return *old;
    const int onset = tribo_touching(&ph) && (!tribo_touching(old) || !fired);
    if (fired && fired[TRIBO_SWITCH_CONTACT]) {
        y[TRIBO_IGAP] = 0.0;
        y[TRIBO_IY] = g.h;
    }
    if (!tribo_touching(&ph)) {
        /* model.md §3: the stretch is 0 when contact is regained; at lift-off it is already
           within a vanishing limit */
        y[TRIBO_IDX] = 0.0;
        return TRIBO_PHASE_FLIGHT;
    }
    stretch_at_event(p, old, y, fired, onset);
    const int normal_event = fired && (fired[TRIBO_SWITCH_NORMAL_A] || fired[TRIBO_SWITCH_NORMAL_B] ||
                                       fired[TRIBO_SWITCH_LOCK_FACTOR]);
    if (p->mu_roll > 0.0 && spin_at_zero(old, y, fired, onset))
        return phase_at_zero_spin(p, old, &g, y, fired, onset, normal_event, ph);
    roll_goes_on(p, old, y, fired, onset, &ph);
    contact_rules(p, old, &g, y, fired, onset, normal_event, &ph);
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

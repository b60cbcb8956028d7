/* dynamics.c: equations of motion (model.md §4) under the contact force law (model.md §3). */
#include "dynamics.h"

#include "contact.h"

#include <string.h>

/* d(mu Psi_N)/dtau for Psi_N = max(0, dy (1 - nu s)) at fixed s, one-sided where dy = 0:
   at the instant of contact the limit is 0 but already growing (past the lift-off, the law
   continued, p->past_liftoff: the unclamped one's). */
static double limit_rate(const tribo_dyn_params *p, const tribo_contact_eval *ev, double ddy)
{
    const double factor = 1.0 - p->nu * ev->sign_v;
    return factor > 0.0 && (p->past_liftoff || ev->delta_y > 0.0 || ddy > 0.0) ? p->mu * factor * ddy : 0.0;
}

const tribo_dyn_params *tribo_dyn_at(const tribo_dyn_params *p, double tau, tribo_dyn_params *at)
{
    if (!tribo_vibrating(p))
        return p;
    /* model.md §9b: (F_T_vib, F_N_vib) = Lambda_v sin(w_v tau + phi_v) (cos psi_v, sin psi_v) */
    const double phase = p->vib_omega * tau + p->vib_phase;
    const double force = p->vib_accel * sin(phase);
    const double rate = p->vib_accel * p->vib_omega * cos(phase);
    *at = *p;
    at->tau = tau;
    at->vib_t = force * p->vib_cos;
    at->vib_n = force * p->vib_sin;
    at->vib_rate_t = rate * p->vib_cos;
    at->vib_rate_n = rate * p->vib_sin;
    return at;
}

void tribo_contact_inverse_mass(const tribo_dyn_params *p, const tribo_pose *g, double w[3])
{
    w[0] = 1.0 + g->cx * g->cx * p->inv_inertia;
    w[1] = g->cx * g->h * p->inv_inertia;
    w[2] = 1.0 + g->h * g->h * p->inv_inertia;
}

/* model.md §3b: with (model.md §4) dU/dtau = Gamma sin(beta) + F_T + Psi_T,
   dV/dtau = -Gamma cos(beta) + F_N + Psi_N, I dOmega/dtau = h Psi_T + c Psi_N (c the normal
   force's lever arm with the rolling torque, tribo_normal_arm, §3c), and dh/dphi = -cx,
   dcx/dphi = kappa:
     d(vn)/dtau = (1 + cx c/I) Psi_N + W_NT Psi_T - (Gamma cos(beta) - F_N) + kappa Omega^2 = 0
     d(vs)/dtau = (h c/I) Psi_N + W_TT Psi_T + (Gamma sin(beta) + F_T) - cx Omega^2 = 0
   Returns the system's determinant (with mu_roll <= 1 it stays positive: docs/model.md §3c). In
   the rolling lock the grain is at rest: dU/dtau = dV/dtau = 0. */
static double rigid_system(const tribo_dyn_params *p, const tribo_force_law *law, const tribo_pose *g,
                           double Omega, double *psi_n, double *psi_t)
{
    if (law->roll == TRIBO_ROLL_LOCK) {
        *psi_n = p->g_n - tribo_force_n(p);
        *psi_t = -(p->g_t + tribo_force_t(p));
        return 1.0;
    }
    double w[3];
    tribo_contact_inverse_mass(p, g, w);
    const double arm = tribo_normal_arm(p, law, g);
    const double w_nn = 1.0 + g->cx * arm * p->inv_inertia, w_tn = arm * g->h * p->inv_inertia;
    const double spin2 = Omega * Omega;
    const double b_n = p->g_n - tribo_force_n(p) - tribo_pose_kappa(p->eps2, g) * spin2;
    const double b_t = g->cx * spin2 - (p->g_t + tribo_force_t(p));
    const double det = w_nn * w[2] - w[1] * w_tn;
    *psi_n = (w[2] * b_n - w[1] * b_t) / det;
    *psi_t = (w_nn * b_t - w_tn * b_n) / det;
    return det;
}

void tribo_rigid_forces(const tribo_dyn_params *p, const tribo_force_law *law, const tribo_pose *g,
                        double Omega, double *psi_n, double *psi_t)
{
    rigid_system(p, law, g, Omega, psi_n, psi_t);
}

void tribo_stop_contact_point(const tribo_dyn_params *p, const tribo_force_law *law,
                              const tribo_pose *g, double *y)
{
    if (law->roll == TRIBO_ROLL_LOCK) {
        y[TRIBO_IU] = y[TRIBO_IV] = 0.0;
        return;
    }
    double w[3];
    tribo_contact_inverse_mass(p, g, w);
    const double vn = y[TRIBO_IV] + g->cx * y[TRIBO_IOMEGA];
    const double vs = y[TRIBO_IU] + g->h * y[TRIBO_IOMEGA];
    const double det = w[0] * w[2] - w[1] * w[1];
    /* the impulse (P_N, P_T) at the contact point with W P = -(vn, vs) */
    const double P_n = (w[1] * vs - w[2] * vn) / det;
    const double P_t = (w[1] * vn - w[0] * vs) / det;
    y[TRIBO_IU] += P_t;
    y[TRIBO_IV] += P_n;
    y[TRIBO_IOMEGA] += p->inv_inertia * (g->cx * P_n + g->h * P_t);
}

double tribo_lock_force(const tribo_dyn_params *p, const tribo_force_law *law, const tribo_pose *g,
                        const double *y, double *A)
{
    if (law->tangent == TRIBO_TANGENT_RIGID) {
        double psi_n, psi_t;
        *A = rigid_system(p, law, g, y[TRIBO_IOMEGA], &psi_n, &psi_t);
        return psi_n;
    }
    if (p->damping_point == TRIBO_DAMPING_CENTRE) {
        *A = 1.0;
        return p->g_n - tribo_force_n(p); /* V held at 0: the normal force balances the normal load */
    }
    if (law->roll == TRIBO_ROLL_LOCK) {
        /* Omega and dOmega/dtau held at 0 (model.md §3c): vn = V, and dV/dtau = 0 */
        *A = 1.0;
        return p->g_n - tribo_force_n(p);
    }
    /* model.md §3: dvn/dtau = Psi_N (1 + cx c/I) + (cx h / I) Psi_T - (Gamma cos(beta) - F_N)
       + kappa Omega^2 = 0, c the normal force's lever arm (§3c) */
    const double Om = y[TRIBO_IOMEGA];
    const double load = p->g_n - tribo_force_n(p) - tribo_pose_kappa(p->eps2, g) * Om * Om;
    const double stick_factor = 1.0 + g->cx * tribo_normal_arm(p, law, g) * p->inv_inertia;
    const double coupling = g->cx * g->h * p->inv_inertia;
    if (law->tangent == TRIBO_TANGENT_SLIP) {
        *A = stick_factor - p->mu * law->slip_sign * coupling;
        return load / *A;
    }
    *A = stick_factor;
    return (load + coupling * y[TRIBO_IDX]) / stick_factor;
}

/* mu d(Psi_N*)/dtau in a normal lock that slips (the stretch is held at the limit and moves
   with it): Psi_N* = load / A along the motion, with dOmega/dtau = Psi_N* (c - mu sigma h) / I,
   d(kappa Omega^2)/dtau = kappa' Omega^3 + 2 kappa Omega dOmega/dtau and
   dA/dtau = (kappa (cx + c) - mu sigma (kappa h - cx^2)) Omega / I (dh/dphi = -cx,
   dcx/dphi = kappa; c = cx - mu_r sigma_r the normal force's lever arm, §3c). In the rolling
   lock Psi_N* does not move. */
static double lock_limit_rate(const tribo_dyn_params *p, const tribo_force_law *law,
                              const tribo_pose *g, const double *y, double psi_star, double A)
{
    if (p->damping_point == TRIBO_DAMPING_CENTRE || law->roll == TRIBO_ROLL_LOCK)
        return 0.0;
    const double Om = y[TRIBO_IOMEGA], sigma = law->slip_sign, arm = tribo_normal_arm(p, law, g);
    const double kappa = tribo_pose_kappa(p->eps2, g);
    const double spin_rate = p->inv_inertia * psi_star * (arm - p->mu * sigma * g->h);
    /* on a vibrating plate the load also follows the inertial force (model.md §9b) */
    const double load_rate = -(tribo_pose_kappa_slope(g, kappa) * Om * Om * Om +
                               2.0 * kappa * Om * spin_rate) -
                             p->vib_rate_n;
    const double A_rate = p->inv_inertia *
                          ((g->cx + arm) * kappa - p->mu * sigma * (kappa * g->h - g->cx * g->cx)) * Om;
    return p->mu * (load_rate - psi_star * A_rate) / A;
}

/* The rolling torque Mr of the law (model.md §3c), with the contact's forces set. */
static double roll_torque(const tribo_dyn_params *p, const tribo_force_law *law,
                          const tribo_contact_eval *ev, double Omega)
{
    switch (law->roll) {
    case TRIBO_ROLL_FREE: break;
    case TRIBO_ROLL_REGULARISED:
        return p->mu_roll > 0.0 ? -p->mu_roll * ev->psi_n * tanh(Omega / p->v_reg) : 0.0;
    case TRIBO_ROLL_TURNING: return -p->mu_roll * ev->psi_n * law->roll_sign;
    case TRIBO_ROLL_LOCK: return -(ev->pose.h * ev->psi_t + ev->pose.cx * ev->psi_n);
    }
    return 0.0;
}

void tribo_contact_at(const tribo_dyn_params *p, const tribo_force_law *law, const double *y,
                      tribo_contact_eval *ev)
{
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &ev->pose);
    ev->delta_y = p->past_liftoff ? -y[TRIBO_IGAP] : tribo_indentation(y[TRIBO_IGAP]);
    ev->in_contact = law->contact == TRIBO_CONTACT_BY_GEOMETRY ? ev->delta_y > 0.0
                                                                : law->contact == TRIBO_CONTACT_ON;
    ev->vs = y[TRIBO_IU] + ev->pose.h * y[TRIBO_IOMEGA]; /* model.md §2 */
    if (!ev->in_contact) {
        ev->sign_v = 0.0;
        ev->psi_n = ev->psi_t = ev->limit = ev->limit_rate = ev->roll_torque = 0.0;
        return;
    }
    /* d(delta_y)/dtau = (dh/dphi) Omega - V = -cx Omega - V (model.md §2) */
    const double ddy = -ev->pose.cx * y[TRIBO_IOMEGA] - y[TRIBO_IV];
    switch (law->normal) {
    case TRIBO_NORMAL_REGULARISED:
        ev->sign_v = p->nu > 0.0
                         ? tribo_regularised_sign(tribo_damped_velocity(p, &ev->pose, y), p->v_reg)
                         : 0.0;
        ev->psi_n = tribo_normal_force(ev->delta_y, p->nu, ev->sign_v);
        ev->limit_rate = limit_rate(p, ev, ddy);
        break;
    case TRIBO_NORMAL_SIGN:
        ev->sign_v = law->normal_sign;
        ev->psi_n = p->past_liftoff ? ev->delta_y * (1.0 - p->nu * ev->sign_v)
                                    : tribo_normal_force(ev->delta_y, p->nu, ev->sign_v);
        ev->limit_rate = limit_rate(p, ev, ddy);
        break;
    case TRIBO_NORMAL_LOCK:
    case TRIBO_NORMAL_CREEP: {
        /* the damped velocity held at 0: the normal force is whatever holds it (model.md §3) */
        double A;
        if (law->tangent == TRIBO_TANGENT_RIGID)
            tribo_rigid_forces(p, law, &ev->pose, y[TRIBO_IOMEGA], &ev->psi_n, &ev->psi_t);
        else
            ev->psi_n = tribo_lock_force(p, law, &ev->pose, y, &A);
        if (law->normal == TRIBO_NORMAL_CREEP) {
            /* on the band's edge: Psi_N* = delta_y (1 - nu s) */
            ev->sign_v = law->normal_sign;
            ev->delta_y = fmax(0.0, ev->psi_n / (1.0 - p->nu * law->normal_sign));
        } else {
            ev->sign_v = p->nu > 0.0 && ev->delta_y > 0.0 ? (1.0 - ev->psi_n / ev->delta_y) / p->nu
                                                           : 0.0;
        }
        ev->limit_rate = law->tangent == TRIBO_TANGENT_SLIP
                             ? lock_limit_rate(p, law, &ev->pose, y, ev->psi_n, A)
                             : 0.0;
        break;
    }
    }
    ev->limit = p->mu * ev->psi_n;
    switch (law->tangent) {
    case TRIBO_TANGENT_CLAMP:
        ev->psi_t = -tribo_clamp(y[TRIBO_IDX], ev->limit);
        break;
    case TRIBO_TANGENT_STICK:
        ev->psi_t = -y[TRIBO_IDX];
        break;
    case TRIBO_TANGENT_SLIP:
        ev->psi_t = -ev->limit * law->slip_sign;
        break;
    case TRIBO_TANGENT_RIGID: /* the constraint's, with the normal force */
        break;
    }
    ev->roll_torque = roll_torque(p, law, ev, y[TRIBO_IOMEGA]);
}

void tribo_dynamics_rhs(const tribo_dyn_params *p, const tribo_force_law *law, const double *y,
                        double *dydt, tribo_contact_eval *ev_out)
{
    tribo_contact_eval ev_local, *ev = ev_out ? ev_out : &ev_local;
    tribo_contact_at(p, law, y, ev);

    const double U = y[TRIBO_IU], V = y[TRIBO_IV], Om = y[TRIBO_IOMEGA];
    dydt[TRIBO_IX] = U;
    /* dG/dtau = dY/dtau - dh/dtau = V + cx Omega = vn (dh/dphi = -cx). In a normal lock the held
       quantity does not move: delta_y = -G for the contact point's (whatever error V carries;
       V itself follows -cx Omega through Psi_N*), Y for the centre dashpot's (dG/dtau =
       cx Omega). In a creep the indentation follows the band's edge, delta_y = Psi_N* /
       (1 - nu s), while the contact point's velocity is held at 0 as in a lock: G and Y move
       with d(delta_y)/dtau, an indentation rate that needs no normal velocity of the body (it
       is the normal law's, at the contact's stiffness, not the body's motion). */
    const int lock = tribo_locked(law);
    const int centre = p->damping_point == TRIBO_DAMPING_CENTRE;
    double creep_rate = 0.0; /* d(delta_y)/dtau in a creep */
    if (law->normal == TRIBO_NORMAL_CREEP && ev->in_contact)
        creep_rate = tribo_lock_force_rate(p, law, y) / (1.0 - p->nu * law->normal_sign);
    dydt[TRIBO_IY] = lock && centre ? 0.0 : V - creep_rate;
    dydt[TRIBO_IGAP] = lock ? (centre ? ev->pose.cx * Om : -creep_rate) : V + ev->pose.cx * Om;
    dydt[TRIBO_IPHI] = Om;
    /* model.md §4 */
    dydt[TRIBO_IU] = p->g_t + tribo_force_t(p) + ev->psi_t;
    dydt[TRIBO_IV] = lock && centre ? 0.0 : -p->g_n + tribo_force_n(p) + ev->psi_n;
    dydt[TRIBO_IOMEGA] = p->inv_inertia * (ev->pose.h * ev->psi_t + ev->pose.cx * ev->psi_n);
    /* model.md §3c: the rolling torque, and its power -mu_r Psi_N |Omega| <= 0 lost from E (in
       the rolling lock Omega is held at 0, and it does no work) */
    const int rolls = ev->in_contact && law->roll != TRIBO_ROLL_FREE;
    if (rolls)
        dydt[TRIBO_IOMEGA] = law->roll == TRIBO_ROLL_LOCK
                                 ? 0.0
                                 : p->inv_inertia * (ev->pose.h * ev->psi_t + ev->pose.cx * ev->psi_n +
                                                     ev->roll_torque);
    const double roll_power = rolls ? -ev->roll_torque * Om : 0.0;
    dydt[TRIBO_IWEXT] = p->F_T * U + p->F_N * V;

    if (!ev->in_contact || law->tangent == TRIBO_TANGENT_RIGID) {
        /* a rigid stick's stretch is its quasi-static value and the energy it stores is
           booked with it, both set along the phase by the integrator (model.md §3b): the
           constraint forces themselves do no work; a creep's dashpot does, and so does the
           rolling torque */
        dydt[TRIBO_IDX] = 0.0;
        dydt[TRIBO_IWDISS] = ev->in_contact ? (ev->delta_y - ev->psi_n) * -creep_rate : 0.0;
        if (rolls)
            dydt[TRIBO_IWDISS] += roll_power;
        return;
    }
    /* model.md §3: the stretch follows the slip velocity of the contact point; in slip it
       is held at the limit and moves with it. */
    const double ddx =
        law->tangent == TRIBO_TANGENT_SLIP ? law->slip_sign * ev->limit_rate : ev->vs;
    dydt[TRIBO_IDX] = ddx;
    /* Power lost from E (model.md §6): dE/dtau = Psi_T vs + dx ddx + (Psi_N - dy) vn
       + external power, so the contact dissipates -Psi_T vs - dx ddx + (dy - Psi_N) vn, with
       vn = V + cx Om. A contact-point lock holds vn = 0 (its V carries only integration
       error, which must not be booked as work); a creep's indentation moves at -vn =
       d(delta_y)/dtau, against the dashpot: (dy - Psi_N) vn = -nu s dy d(delta_y)/dtau >= 0. */
    const double vn = lock && !centre ? -creep_rate : V + ev->pose.cx * Om;
    dydt[TRIBO_IWDISS] = -ev->psi_t * ev->vs - y[TRIBO_IDX] * ddx + (ev->delta_y - ev->psi_n) * vn;
    if (rolls)
        dydt[TRIBO_IWDISS] += roll_power;
}

double tribo_lock_force_rate(const tribo_dyn_params *p, const tribo_force_law *law, const double *y)
{
    /* the direction of the motion, with the lock's force (which does not depend on how the
       indentation moves) */
    tribo_force_law lock = *law;
    lock.normal = TRIBO_NORMAL_LOCK;
    double f[TRIBO_NMOTION];
    tribo_dynamics_rhs(p, &lock, y, f, NULL);
    /* a step that turns the particle by 1e-5 rad and changes its spin by 1e-5 of its scale:
       the central difference is then exact to ~1e-10 of Psi_N*'s scale of change */
    const double Om = y[TRIBO_IOMEGA];
    double d = 1e-5 / (fabs(Om) + sqrt(fabs(f[TRIBO_IOMEGA])) + 1e-300);
    if (tribo_vibrating(p)) /* and moves the plate's phase by at most 1e-5 rad */
        d = fmin(d, 1e-5 / p->vib_omega);
    double z[2][TRIBO_NMOTION], psi[2];
    for (int k = 0; k < 2; k++) {
        memcpy(z[k], y, sizeof z[k]); /* y may be CVODE's vector: the motion and no more */
        const double step = k ? -d : d;
        for (int i = 0; i < TRIBO_NMOTION; i++)
            z[k][i] += step * f[i];
        tribo_pose g;
        tribo_pose_at(p->eps2, z[k][TRIBO_IPHI], &g);
        double A;
        /* on a vibrating plate the load moves with the time too (model.md §9b) */
        tribo_dyn_params at;
        psi[k] = tribo_lock_force(tribo_dyn_at(p, p->tau + step, &at), &lock, &g, z[k], &A);
    }
    return (psi[0] - psi[1]) / (2.0 * d);
}

double tribo_energy(const tribo_dyn_params *p, const double *y)
{
    tribo_pose g;
    tribo_pose_at(p->eps2, y[TRIBO_IPHI], &g);
    const double dy = tribo_indentation(y[TRIBO_IGAP]);
    const double U = y[TRIBO_IU], V = y[TRIBO_IV], Om = y[TRIBO_IOMEGA], dx = y[TRIBO_IDX];
    /* model.md §6 */
    return 0.5 * (U * U + V * V) + 0.125 * (1.0 + p->eps2) * Om * Om +
           (p->g_n * y[TRIBO_IY] - p->g_t * y[TRIBO_IX]) + 0.5 * dy * dy + 0.5 * dx * dx;
}

/* dynamics.h: rigid-body motion of the particle (model.md §4) as a first-order system,
   with the quadratures of the energy balance (dissipated and external work, model.md §6).
   The charge models' quadratures follow the motion in the state vector (charging.h). */
#ifndef TRIBO_DYNAMICS_H
#define TRIBO_DYNAMICS_H

#include "charge_model.h"
#include "geometry.h"

/* Components of the state vector. */
enum {
    TRIBO_IX,      /* X: centre along the plate, down-slope positive          */
    TRIBO_IY,      /* Y: centre height above the plate                        */
    TRIBO_IPHI,    /* phi: anticlockwise angle plate -> long axis             */
    TRIBO_IU,      /* U = dX/dtau                                             */
    TRIBO_IV,      /* V = dY/dtau                                             */
    TRIBO_IOMEGA,  /* Omega = dphi/dtau                                       */
    TRIBO_IDX,     /* delta_x: tangential spring stretch                      */
    TRIBO_IWDISS,  /* work dissipated by the contact forces                   */
    TRIBO_IWEXT,   /* work done by the external forces F_T_ext, F_N_ext        */
    TRIBO_NMOTION  /* the charge models' quadratures follow, from here          */
};

/* Room for the motion and every registered charge model's quadratures. */
#define TRIBO_NSTATE_MAX (TRIBO_NMOTION + TRIBO_CHARGE_MAX_QUADRATURES)

/* Everything the right-hand side needs, derived once from the scene. */
typedef struct tribo_dyn_params {
    double eps, eps2;
    double mu, nu, Gamma;
    double g_t, g_n;     /* Gamma sin(beta), Gamma cos(beta) */
    double inv_inertia;  /* 4 / (1 + eps^2): m (a^2 + b^2) / 4, model.md §4 */
    double v_reg;
    int damping_point;   /* tribo_damping_point: the velocity the normal dashpot opposes */
    double rtol, atol;   /* the event-driven integrator's tolerances: within them a state
                            cannot tell which side of a switch it is on */
    double F_T, F_N;     /* external force (inputs) */
    double chute_length; /* X where the chute ends (model.md §9); INFINITY: none */
    int end_at_liftoff;  /* the run ends at the first lift-off (run_end = first_liftoff) */
} tribo_dyn_params;

/* The normal velocity the dashpot opposes (model.md §3): the contact point's
   vn = V + cx Omega (= -d delta_y/dtau), or the centre's V (damping_point = 1). */
static inline double tribo_damped_velocity(const tribo_dyn_params *p, const tribo_pose *g,
                                           const double *y)
{
    return p->damping_point == TRIBO_DAMPING_CENTRE ? y[TRIBO_IV]
                                                    : y[TRIBO_IV] + g->cx * y[TRIBO_IOMEGA];
}

/* How the set-valued parts of the force law are resolved (model.md §3). The fixed-step
   integrator uses the regularised sign and the clamped stretch throughout; an
   event-driven integrator selects a phase per smooth piece of the motion. */
typedef enum {
    TRIBO_CONTACT_BY_GEOMETRY, /* in contact where delta_y > 0 (fixed step)              */
    TRIBO_CONTACT_OFF,         /* flight phase: no contact force whatever delta_y is       */
    TRIBO_CONTACT_ON           /* contact phase: the law with max(delta_y, 0), so that the
                                  right-hand side is smooth up to the located switch     */
} tribo_contact_rule;
typedef enum { TRIBO_NORMAL_REGULARISED, TRIBO_NORMAL_SIGN, TRIBO_NORMAL_LOCK } tribo_normal_rule;
typedef enum { TRIBO_TANGENT_CLAMP, TRIBO_TANGENT_STICK, TRIBO_TANGENT_SLIP } tribo_tangent_rule;

typedef struct tribo_force_law {
    tribo_contact_rule contact;
    tribo_normal_rule normal;
    double normal_sign;   /* s for TRIBO_NORMAL_SIGN (+1 / -1)              */
    tribo_tangent_rule tangent;
    double slip_sign;     /* for TRIBO_TANGENT_SLIP: the sign of the stretch held at the limit
                             (+1 / -1); the slip force opposes it (model.md §3) */
} tribo_force_law;

/* The normal force Psi_N* of the normal lock (model.md §3): the force that keeps the damped
   velocity at 0 (dvn/dtau = 0; for the centre dashpot dV/dtau = 0), in the law's tangential
   rule (stick: Psi_T = -delta_x; slip: Psi_T = -mu slip_sign Psi_N). *A is the factor of
   Psi_N in dvn/dtau: 1 + cx^2/I in stick, A = 1 + cx^2/I - mu sigma cx h / I in slip (1 for
   the centre dashpot); the lock exists only while A > 0. */
double tribo_lock_force(const tribo_dyn_params *p, const tribo_force_law *law, const tribo_pose *g,
                        const double *y, double *A);

/* The contact as seen by one evaluation of the right-hand side. */
typedef struct tribo_contact_eval {
    tribo_pose pose;
    double delta_y;   /* indentation (0 in flight) */
    int in_contact;
    double vs;        /* slip velocity U + h Omega of the contact point */
    double sign_v;    /* the s used in Psi_N (in a normal lock, the s that Psi_N* needs) */
    double psi_n, psi_t;
    double limit;     /* Coulomb limit mu Psi_N */
    double limit_rate; /* d(mu Psi_N)/dtau within the current normal and tangential rule
                          (in a normal lock: in slip, else 0) */
} tribo_contact_eval;

/* dy/dtau of the motion (the first TRIBO_NMOTION components) at state y under the force
   law; fills ev (may be NULL). */
void tribo_dynamics_rhs(const tribo_dyn_params *p, const tribo_force_law *law, const double *y,
                        double *dydt, tribo_contact_eval *ev);

/* Evaluate the contact at y without derivatives (for outputs and post-step work). */
void tribo_contact_at(const tribo_dyn_params *p, const tribo_force_law *law, const double *y,
                      tribo_contact_eval *ev);

/* Mechanical energy E of model.md §6. */
double tribo_energy(const tribo_dyn_params *p, const double *y);

#endif

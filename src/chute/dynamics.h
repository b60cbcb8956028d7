/* dynamics.h: rigid-body motion of the particle (model.md §4) as a first-order system,
   with the quadratures of the energy balance (dissipated and external work, model.md §6).
   The charge models' quadratures follow the motion in the state vector (charging.h). */
#ifndef TRIBO_DYNAMICS_H
#define TRIBO_DYNAMICS_H

#include "charge_interface.h"
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
    TRIBO_IGAP,    /* G: clearance of the lowest point above the plate, Y - h(phi) (-G the
                      indentation where G < 0), integrated beside Y: near the plate G is
                      the small difference of two O(1) numbers, and integrated itself it is
                      held to the absolute tolerance, not to rtol |Y| (at physical scale
                      the indentation is ~Gamma, 1e-8, below rtol |Y|), while Y, a parabola
                      in flight, is exact there. The contact reads G; the height and the
                      energy read Y. Both are put on the plate at a contact switch. */
    TRIBO_NMOTION  /* the charge models' quadratures follow, from here          */
};

/* Room for the motion, every registered charge model's quadratures and, on a vibrating plate,
   the work of the plate's inertial force W_vib (model.md §9b), last: a component of its own
   only there, so that a still plate's state (and CVODE's error norm over it) is unchanged. */
#define TRIBO_NSTATE_MAX (TRIBO_NMOTION + TRIBO_CHARGE_MAX_QUADRATURES + 1)

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
    int rigid_stick;     /* stick_model = rigid: a stick in a contact-point lock is a
                            constraint (model.md §3b) */
    double mu_roll;      /* rolling resistance (model.md §3c) */
    /* the plate's vibration (model.md §9b): the inertial force vib_accel sin(vib_omega tau +
       vib_phase) (vib_cos, vib_sin) in the plate's frame; vib_accel = 0 a still plate */
    double vib_accel, vib_omega, vib_phase, vib_cos, vib_sin;
    int vib_slot;        /* the index of W_vib in the state; 0 on a still plate (none) */
    /* the dynamics at one time (tribo_dyn_at): tau, the inertial force then and its rate;
       0 on a still plate */
    double tau, vib_t, vib_n, vib_rate_t, vib_rate_n;
    /* a contact phase's law continued past its lift-off, for the right-hand side of a one-step
       integrator: the indentation -G and Psi_N = delta_y (1 - nu s) unclamped. Up to the
       lift-off (G <= 0) it is the law itself; past it, where a step that crosses the lift-off
       is cut at the located root, it is smooth, where the clamps' kink would hold the step's
       error estimate at the order of the kink and its steps to a crawl. 0 elsewhere. */
    int past_liftoff;
} tribo_dyn_params;

/* Whether the plate vibrates (model.md §9b): the forces then depend on the time. */
static inline int tribo_vibrating(const tribo_dyn_params *p) { return p->vib_accel > 0.0; }

/* The dynamics at time tau (model.md §9b): p itself on a still plate, else a copy in *at with
   the plate's inertial force at tau. Every evaluation of the forces on a vibrating plate (the
   right-hand side, the locks, the switches, the phase after an event) takes the dynamics of
   its time; the flight reads the vibration from p and its own time. */
const tribo_dyn_params *tribo_dyn_at(const tribo_dyn_params *p, double tau, tribo_dyn_params *at);

/* The external force on the grain, along and normal to the plate: the inputs and the plate's
   inertial force (model.md §3, §9b). The one place they are summed: every law that reads the
   external force (§3's locks, §3b's rigid stick, §3c's rolling lock, §4) reads it here. */
static inline double tribo_force_t(const tribo_dyn_params *p) { return p->F_T + p->vib_t; }
static inline double tribo_force_n(const tribo_dyn_params *p) { return p->F_N + p->vib_n; }

/* The power of the plate's inertial force on the grain at y, dW_vib/dtau (model.md §9b). */
static inline double tribo_vibration_power(const tribo_dyn_params *p, const double *y)
{
    return p->vib_t * y[TRIBO_IU] + p->vib_n * y[TRIBO_IV];
}

/* Whether the lowest point, at rest on the plate (delta = 0, vn = 0), is pressed in: its
   indentation's second derivative `curvature` = h''(phi) Omega^2 + Gamma cos(beta) - F_N is
   positive. On a vibrating plate the load passes 0 smoothly where the grain lifts off (model.md
   §9b): within 1e-9 of the load's scale of 0 (the rounding of a located switch) its rate
   decides, so that a lift-off is not taken for a contact at once. */
static inline int tribo_pressed_in(const tribo_dyn_params *p, double curvature, double rate)
{
    if (!tribo_vibrating(p))
        return curvature > 0.0;
    const double scale = 1e-9 * (p->g_n + fabs(p->F_N) + p->vib_accel * fabs(p->vib_sin));
    return curvature > scale || (curvature >= -scale && rate > 0.0);
}

/* The rounding of a velocity a + b (V + cx Omega, say) in a state an event-driven integrator
   holds to its tolerances: within it a state cannot tell which way the velocity points. */
static inline double tribo_velocity_rounding(const tribo_dyn_params *p, double a, double b)
{
    return 10.0 * (p->rtol * (fabs(a) + fabs(b)) + p->atol);
}

/* Whether the lowest point reaching the plate makes a contact (model.md §3b), for the flight's
   search and the phase after it alike: it approaches, its normal velocity vn below minus its
   rounding, or it does not move away and is pressed in. A touch that moves away, however
   slowly, makes none: a grain that has just lifted off below the rounding, pressed in by its
   weight, would be taken as touching again at the same instant (an event cascade). */
static inline int tribo_touch_makes_contact(double vn, double rounding, int pressed_in)
{
    return vn < -rounding || (vn <= 0.0 && pressed_in);
}

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
/* CREEP: with the rigid stick (model.md §3b), a contact-point lock whose load reaches an edge
   of its band and goes on past it: the contact point stays at rest normally and the force is
   the lock's, Psi_N*, while the indentation follows the edge, delta_y = Psi_N* / (1 - nu s)
   (s = normal_sign: -1 the upper edge, pressing in; +1 the lower, lifting): the normal law's
   quasi-static motion there. (The compliant law leaves the lock into a sign phase, whose
   undamped normal spring an integrator must resolve for as long as the load creeps.) */
typedef enum {
    TRIBO_NORMAL_REGULARISED,
    TRIBO_NORMAL_SIGN,
    TRIBO_NORMAL_LOCK,
    TRIBO_NORMAL_CREEP
} tribo_normal_rule;
/* RIGID: the rigid stick of model.md §3b, only in a contact-point normal lock: the contact
   point is at rest and the forces are the constraint's (tribo_rigid_forces); the stretch is
   their quasi-static value, set by the integrator, not integrated. */
typedef enum {
    TRIBO_TANGENT_CLAMP,
    TRIBO_TANGENT_STICK,
    TRIBO_TANGENT_SLIP,
    TRIBO_TANGENT_RIGID
} tribo_tangent_rule;

/* The rolling torque Mr = -mu_r Psi_N sgn(Omega) (model.md §3c). FREE: none (mu_roll = 0, the
   paper's model; flight); REGULARISED: the fixed step's tanh(Omega / v_reg) for the sign;
   TURNING: the sign roll_sign, which Omega has; LOCK: the rolling lock, Omega held at 0 by the
   torque that holds it, Mr* = -(h Psi_T + cx Psi_N), while that lies within mu_r Psi_N. */
typedef enum {
    TRIBO_ROLL_FREE,
    TRIBO_ROLL_REGULARISED,
    TRIBO_ROLL_TURNING,
    TRIBO_ROLL_LOCK
} tribo_roll_rule;

typedef struct tribo_force_law {
    tribo_contact_rule contact;
    tribo_normal_rule normal;
    double normal_sign;   /* s for TRIBO_NORMAL_SIGN (+1 / -1)              */
    tribo_tangent_rule tangent;
    double slip_sign;     /* for TRIBO_TANGENT_SLIP: the sign of the stretch held at the limit
                             (+1 / -1); the slip force opposes it (model.md §3) */
    int started_at_rest;  /* for TRIBO_NORMAL_SIGN in contact: the phase began with the damped
                             velocity at 0 within its rounding (out of a lock at its band's
                             edge, or a reversal decided at 0), from where it creeps: its switch
                             waits for the velocity to pass 0 by more than that rounding */
    int compliant_slip;   /* for TRIBO_TANGENT_SLIP in a contact-point lock with the rigid stick:
                             a slip that went on where the rigid stick could not hold the lock
                             (its force outside the band) ends as the compliant stick's does,
                             where the stretch comes off the limit, not where the contact point
                             comes to rest (model.md §3b) */
    tribo_roll_rule roll;
    double roll_sign;     /* for TRIBO_ROLL_TURNING: the sign of Omega (+1 / -1) */
    int roll_from_rest;   /* for TRIBO_ROLL_TURNING: the phase began with Omega at 0 (out of the
                             rolling lock at its band's edge, or set down turning from rest): its
                             switch waits for Omega to pass 0 by more than its rounding */
} tribo_force_law;

/* Whether a rule holds the damped velocity at 0 with the lock's force: a lock or a creep. */
static inline int tribo_locked(const tribo_force_law *law)
{
    return law->normal == TRIBO_NORMAL_LOCK || law->normal == TRIBO_NORMAL_CREEP;
}

/* Whether a phase holds the contact point at rest normally (vn = 0): a contact-point lock,
   which also holds the indentation (dG/dtau = 0), or a creep. */
static inline int tribo_contact_point_lock(const tribo_dyn_params *p, const tribo_force_law *law)
{
    return law->contact == TRIBO_CONTACT_ON && tribo_locked(law) &&
           p->damping_point == TRIBO_DAMPING_CONTACT_POINT;
}

/* The contact's inverse mass (the Delassus matrix of the contact point's normal and tangential
   velocities vn = V + cx Omega, vs = U + h Omega, model.md §3b): a force (Psi_N, Psi_T) at the
   contact point changes (vn, vs) at the rate W (Psi_N, Psi_T). w[0] = W_NN = 1 + cx^2/I,
   w[1] = W_NT = cx h / I, w[2] = W_TT = 1 + h^2/I; det W = 1 + (cx^2 + h^2)/I >= 1. */
void tribo_contact_inverse_mass(const tribo_dyn_params *p, const tribo_pose *g, double w[3]);

/* The lever arm about the centre of the normal force with the rolling torque of a phase that
   turns (model.md §3c: Mr = -mu_r sigma_r Psi_N acts as the normal force moved by -mu_r sigma_r
   along the plate): cx - mu_r roll_sign, and cx in every other rule (in the rolling lock the
   torque is the one that holds the grain). */
static inline double tribo_normal_arm(const tribo_dyn_params *p, const tribo_force_law *law,
                                      const tribo_pose *g)
{
    return law->roll == TRIBO_ROLL_TURNING ? g->cx - p->mu_roll * law->roll_sign : g->cx;
}

/* The forces of the rigid stick (model.md §3b): Psi_N* and Psi_T* that keep the contact point
   at rest, d(vn)/dtau = 0 and d(vs)/dtau = 0, at the pose g and spin Omega, with the law's
   rolling torque (§3c; in the rolling lock the whole grain is at rest, Omega = 0). */
void tribo_rigid_forces(const tribo_dyn_params *p, const tribo_force_law *law, const tribo_pose *g,
                        double Omega, double *psi_n, double *psi_t);

/* Bring the contact point of y to rest (vn = vs = 0) by an impulse at the contact point: the
   velocities of the rigid stick nearest to y's in the particle's kinetic energy. The
   particle's angular momentum about the contact point does not change. In the rolling lock
   (Omega held at 0, model.md §3c) the whole grain is brought to rest: U = V = 0. */
void tribo_stop_contact_point(const tribo_dyn_params *p, const tribo_force_law *law,
                              const tribo_pose *g, double *y);

/* The normal force Psi_N* of the normal lock (model.md §3): the force that keeps the damped
   velocity at 0 (dvn/dtau = 0; for the centre dashpot dV/dtau = 0), in the law's tangential
   rule (stick: Psi_T = -delta_x; slip: Psi_T = -mu slip_sign Psi_N) and rolling rule (§3c).
   *A is the factor of Psi_N in dvn/dtau: 1 + cx c/I in stick, A = 1 + cx c/I - mu sigma cx h / I
   in slip, with c the normal force's lever arm (tribo_normal_arm); 1 for the centre dashpot and
   in the rolling lock; the lock exists only while A > 0. */
double tribo_lock_force(const tribo_dyn_params *p, const tribo_force_law *law, const tribo_pose *g,
                        const double *y, double *A);

/* d(Psi_N*)/dtau along the motion of a lock or a creep at y (the rate at which the load the lock
   carries changes), by a central difference along the right-hand side's direction. */
double tribo_lock_force_rate(const tribo_dyn_params *p, const tribo_force_law *law, const double *y);

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
    double roll_torque; /* the rolling torque Mr (model.md §3c; 0 without it) */
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

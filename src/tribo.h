/*
 * tribo.h: C API of the tribocharging particle model.
 *
 * A 2D elliptical particle (roundness ratio epsilon = b/a) on a tilted plate, with a
 * spring-dashpot normal contact, a stick/slip/roll Coulomb friction law and two
 * charge models resolved over the particle's boundary segments. The physics is the
 * contract of ../shared/MODEL.md (cited below as "MODEL §n").
 *
 * Usage:
 *   tribo_scene scene;
 *   tribo_scene_defaults(&scene);          // the paper's drop, MODEL §7
 *   scene.epsilon = 0.5;
 *   char err[256];
 *   tribo_model *m = tribo_create(&scene, err, sizeof err);
 *   if (!m) { puts(err); ... }
 *   tribo_advance(m, 1000.0);
 *   double q = tribo_get(m, TRIBO_Q_STATIC);
 *   tribo_free(m);
 *
 * Everything is dimensionless (MODEL.md preamble). An instance owns all its memory;
 * the library holds no global mutable state, so instances can run side by side (not
 * one instance from two threads at once).
 */
#ifndef TRIBO_H
#define TRIBO_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- status --------------------------------------------------------------------- */

typedef enum tribo_status {
    TRIBO_OK = 0,
    TRIBO_ERR_INVALID_ARGUMENT, /* a parameter or argument outside its valid range   */
    TRIBO_ERR_NOT_TUNABLE,      /* a structural or fixed parameter changed mid-run    */
    TRIBO_ERR_TIME,             /* advancing backwards, or to a non-finite time       */
    TRIBO_ERR_INTEGRATOR,       /* the integrator failed; the instance must be reset */
    TRIBO_ERR_STATE,            /* state bytes that do not belong to this scene       */
    TRIBO_ERR_MEMORY
} tribo_status;

/* ---- the scene: every parameter of MODEL §1, the initial state, the choices ----- */

typedef enum tribo_charge_models {
    TRIBO_CHARGE_NONE = 0,
    TRIBO_CHARGE_STATIC = 1,  /* MODEL §5a */
    TRIBO_CHARGE_SLIDING = 2, /* MODEL §5b */
    TRIBO_CHARGE_BOTH = 3
} tribo_charge_models;

typedef enum tribo_integrator_kind {
    TRIBO_INTEGRATOR_FIXED_STEP = 0, /* classical RK4, fixed step dt (the paper's)  */
    TRIBO_INTEGRATOR_CVODE = 1,      /* SUNDIALS CVODE, Adams, with event location  */
    TRIBO_INTEGRATOR_CVODE_BDF = 2   /* the same with BDF (for stiff scenes)        */
} tribo_integrator_kind;

typedef struct tribo_scene {
    /* MODEL §1 */
    double epsilon;  /* roundness ratio b/a, 0 < epsilon <= 1                        */
    double mu;       /* Coulomb friction coefficient                                  */
    double nu;       /* normal dissipation coefficient                                */
    double Gamma;    /* gravity / stiffness ratio mg/(ka)                             */
    double beta;     /* plate tilt, in DEGREES (0 <= beta < 90)                       */
    double tau0;     /* charging time constant                                        */
    double Sigma0;   /* static saturation charge density                              */
    double eta;      /* fraction of frictional work that raises the saturation density */
    double tau_r;    /* relaxation time of the elevated saturation density            */
    int n_segments;  /* boundary segments of equal arc length                         */
    double v_reg;    /* velocity scale of the regularised sign (fixed step, MODEL §3) */

    /* Initial state (defaults: the paper's drop, MODEL §7). The centre starts at
       Y = h(phi0) + gap0; the velocity is drop_speed straight down in the external
       frame, i.e. U = drop_speed sin(beta), V = -drop_speed cos(beta). */
    double X0;
    double gap0;       /* height of the lowest point above the plate, >= 0 */
    double phi0;       /* orientation of the long axis, rad */
    double drop_speed; /* >= 0 */
    double Omega0;     /* initial spin, rad per time unit */

    /* Choices */
    int charge_model; /* tribo_charge_models */
    int integrator;   /* tribo_integrator_kind */
    double dt;        /* step of the fixed-step integrator */
    double rtol;      /* CVODE relative tolerance */
    double atol;      /* CVODE absolute tolerance */
} tribo_scene;

/* Fill a scene with the paper's low-friction case (MODEL §7) at epsilon = 0.5, both
   charge models, CVODE at rtol = 1e-9, atol = 1e-11 (the fixed step's dt = 8e-5, the
   paper's, is set for when integrator = TRIBO_INTEGRATOR_FIXED_STEP is chosen). */
void tribo_scene_defaults(tribo_scene *scene);

/* ---- parameter descriptions: names, ranges, validation ------------------------- */

typedef enum tribo_param_variability {
    TRIBO_PARAM_STRUCTURAL, /* shapes the instance (memory, code paths): fixed for its life */
    TRIBO_PARAM_FIXED,      /* read at creation / reset only                               */
    TRIBO_PARAM_TUNABLE     /* may change between advances (tribo_set_param)              */
} tribo_param_variability;

typedef struct tribo_param_info {
    const char *name;        /* MODEL §1's name column (also the FMI variable name) */
    const char *description;
    const char *unit;        /* "1" where dimensionless */
    size_t offset;           /* offset of the field in tribo_scene */
    int is_integer;          /* field is an int rather than a double */
    double min, max;         /* valid range; +-INFINITY where open-ended */
    int min_inclusive, max_inclusive;
    tribo_param_variability variability;
} tribo_param_info;

/* The table of every scene parameter; *count receives its length. */
const tribo_param_info *tribo_param_table(size_t *count);
/* The entry named `name`, or NULL. */
const tribo_param_info *tribo_param_find(const char *name);
/* Read / write a parameter of a scene through its table entry. */
double tribo_param_read(const tribo_scene *scene, const tribo_param_info *p);
void tribo_param_write(tribo_scene *scene, const tribo_param_info *p, double value);
/* The valid range of `p` in words, e.g. "0 < epsilon <= 1" (for messages). */
void tribo_param_range_text(const tribo_param_info *p, char *buf, size_t n);
/* TRIBO_OK if `value` is valid for `p`; otherwise TRIBO_ERR_INVALID_ARGUMENT and a
   message naming the parameter, the value and the valid range. */
tribo_status tribo_param_check(const tribo_param_info *p, double value, char *msg, size_t msg_size);
/* Check every parameter of a scene; the first failure is reported as above. */
tribo_status tribo_scene_validate(const tribo_scene *scene, char *msg, size_t msg_size);

/* ---- the instance --------------------------------------------------------------- */

typedef struct tribo_model tribo_model;

/* Warnings of the core (e.g. contact outside the model's assumptions) go to this
   callback if one is set; level 0 = info, 1 = warning. */
typedef void (*tribo_log_fn)(void *user, int level, const char *message);

/* Create an instance at time 0 in the scene's initial state. On failure returns NULL
   and writes the reason into err (if err is not NULL). */
tribo_model *tribo_create(const tribo_scene *scene, char *err, size_t err_size);
void tribo_free(tribo_model *model);
void tribo_set_logger(tribo_model *model, tribo_log_fn fn, void *user);

/* Back to time 0 and the scene's initial state (tunables keep their current values). */
void tribo_reset(tribo_model *model);

/* Advance to time t >= the current time. The committed integration is independent
   of the times asked for: advancing in n calls to t1 < ... < tn gives bit-identical
   results to one call to tn (with constant inputs and parameters). */
tribo_status tribo_advance(tribo_model *model, double t);

/* Change a tunable parameter (MODEL §1: mu, nu, eta, tau0, tau_r, Sigma0) from the
   current time on. Structural and fixed parameters are rejected. */
tribo_status tribo_set_param(tribo_model *model, const char *name, double value);

/* External tangential / normal force (MODEL §3), held constant from the current
   time on. */
tribo_status tribo_set_external_force(tribo_model *model, double F_T, double F_N);

/* The scene the instance runs (including the current tunable values). */
const tribo_scene *tribo_get_scene(const tribo_model *model);

/* The reason for the last failure of a call on this instance ("" if none). */
const char *tribo_last_error(const tribo_model *model);

/* ---- what can be read ------------------------------------------------------------ */

typedef enum tribo_quantity {
    TRIBO_Q_TIME,
    TRIBO_Q_X, TRIBO_Q_Y, TRIBO_Q_PHI,       /* centre position, orientation (MODEL §2) */
    TRIBO_Q_U, TRIBO_Q_V, TRIBO_Q_OMEGA,     /* velocities                              */
    TRIBO_Q_DELTA_Y, TRIBO_Q_DELTA_X,        /* indentation, tangential spring stretch  */
    TRIBO_Q_IN_CONTACT, TRIBO_Q_SLIPPING,    /* 1 or 0                                  */
    TRIBO_Q_PSI_N, TRIBO_Q_PSI_T,            /* contact forces (MODEL §3)               */
    TRIBO_Q_STATIC,                          /* Q_static (MODEL §5a)                    */
    TRIBO_Q_SLIDING,                         /* Q_sliding (MODEL §5b)                   */
    TRIBO_Q_SIGMA_S,                         /* dynamic saturation density Sigma_s      */
    TRIBO_Q_OMEGA_WORK,                      /* cumulative frictional work per area     */
    TRIBO_Q_ENERGY,                          /* mechanical energy E (MODEL §6)          */
    TRIBO_Q_WORK_DISSIPATED,                 /* work dissipated by the contact so far   */
    TRIBO_Q_WORK_EXTERNAL,                   /* work done by F_T_ext, F_N_ext so far    */
    TRIBO_Q_CONTACT_TIME,                    /* time spent in contact so far            */
    TRIBO_Q_CONTACT_FRACTION,                /* contact time / time                     */
    TRIBO_Q_TURNS,                           /* revolutions made, |phi - phi0| / 2 pi   */
    TRIBO_Q_CONTACT_MODE,                    /* 0 flight, 1 sliding (quasi-fixed orientation,
                                                with rocking), 2 rolling, 3 tumbling,
                                                4 bouncing: over the last ~20 time units  */
    TRIBO_Q_FRACTION_FLIGHT,                 /* fraction of the time so far in each mode */
    TRIBO_Q_FRACTION_SLIDING,
    TRIBO_Q_FRACTION_ROLLING,
    TRIBO_Q_FRACTION_TUMBLING,
    TRIBO_Q_FRACTION_BOUNCING,
    TRIBO_Q_ASSUMPTION_WARNINGS,             /* times the contact went outside the model's
                                                assumptions (delta_y > 0.1 min(eps, rho_c)) */
    TRIBO_Q_COUNT
} tribo_quantity;

/* The value of a quantity at the current time. Charge quantities of a model the
   scene does not include read as 0 (Sigma_s as Sigma0). */
double tribo_get(tribo_model *model, tribo_quantity q);
/* Name of a quantity, e.g. "Q_static" (the FMI output names). */
const char *tribo_quantity_name(tribo_quantity q);

typedef enum tribo_segment_charge {
    TRIBO_SEGMENTS_STATIC,  /* q_i = sigma_i / sigma_0              (MODEL §5a) */
    TRIBO_SEGMENTS_SLIDING  /* Sigma_i / Sigma_0, mean = Q_sliding  (MODEL §5b) */
} tribo_segment_charge;

/* Copy the per-segment charge densities (n = n_segments values) at the current time.
   Fails if the scene does not include that model. */
tribo_status tribo_get_segment_charges(tribo_model *model, tribo_segment_charge which,
                                       double *out, size_t n);

/* Work counters of the integrator since creation or the last reset. */
typedef struct tribo_stats {
    long long steps;          /* integrator steps taken                            */
    long long rhs_evals;      /* right-hand-side evaluations                       */
    long long events;         /* switches of the force law located (CVODE)          */
    long long restarts;       /* integrator restarts (events, tunables, inputs)     */
    long long substeps;       /* extra sub-steps the fixed step took to stay stable */
    long long assumption_warnings; /* contact steps outside the model's assumptions */
} tribo_stats;
void tribo_get_stats(const tribo_model *model, tribo_stats *stats);

/* ---- the whole state, out and back in ----------------------------------------- */

/* The state is plain bytes (no pointers): the scene, the time, the dynamic state,
   the charges and the integrator's own state. Loading it into any instance created
   from a scene with the same structural parameters continues bit-identically. */
size_t tribo_state_size(const tribo_model *model);
tribo_status tribo_state_save(const tribo_model *model, void *buffer, size_t size);
tribo_status tribo_state_load(tribo_model *model, const void *buffer, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* TRIBO_H */

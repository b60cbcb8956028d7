/*
 * tribo.h: C API of the tribocharging particle model.
 *
 * A 2D elliptical particle (roundness ratio epsilon = b/a) on a tilted plate, with a
 * spring-dashpot normal contact, a stick/slip/roll Coulomb friction law and two
 * charge models resolved over the particle's boundary segments. The physics is the
 * model of docs/model.md (cited below as "model.md §n").
 *
 * Usage:
 *   tribo_scene scene;
 *   tribo_scene_defaults(&scene);          // the paper's drop, model.md §7
 *   scene.epsilon = 0.5;
 *   char err[256];
 *   tribo_model *m = tribo_create(&scene, err, sizeof err);
 *   if (!m) { puts(err); ... }
 *   tribo_advance(m, 1000.0);
 *   double q = tribo_get(m, TRIBO_QUANTITY_STATIC);
 *   tribo_free(m);
 *
 * Everything is dimensionless (docs/model.md preamble). An instance owns all its memory;
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
    TRIBO_ERR_MEMORY,
    TRIBO_INCOMPLETE,           /* not an error: an advance spent its work limit and
                                   stopped early, at tribo_get(model, TRIBO_QUANTITY_TIME); the
                                   instance is consistent there and advances on from it */
    TRIBO_ENDED                 /* not an error: the run is over where the scene ends it
                                   (run_end, model.md §9): the particle left the chute (at
                                   tribo_get(model, TRIBO_QUANTITY_EXIT_TIME)) or, with run_end =
                                   first_liftoff, its first contact was lost again (output
                                   lifted_off), or it came to rest on the chute (§3c, output
                                   at_rest; output end_reason says which); every output stays
                                   there, and any later
                                   advance past it returns this again and changes nothing
                                   (reset to run again) */
} tribo_status;

/* ---- the scene: every parameter of the table (quantities.def) ------------------- */

typedef enum tribo_integrator_kind {
    TRIBO_INTEGRATOR_FIXED_STEP = 0, /* classical RK4, fixed step dt (the paper's)  */
    TRIBO_INTEGRATOR_CVODE = 1,      /* SUNDIALS CVODE, Adams, with event location  */
    TRIBO_INTEGRATOR_CVODE_BDF = 2   /* the same with BDF (for stiff scenes)        */
} tribo_integrator_kind;

/* Where a run ends before the time asked for (parameter run_end, docs/model.md §9). */
typedef enum tribo_run_end {
    TRIBO_RUN_END_CHUTE_EXIT = 0,   /* only where the particle leaves the chute (default)  */
    TRIBO_RUN_END_FIRST_LIFTOFF = 1 /* also where the first contact made is lost again   */
} tribo_run_end;

/* Where the normal dashpot takes its velocity (parameter damping_point, docs/model.md §3). */
typedef enum tribo_damping_point {
    TRIBO_DAMPING_CONTACT_POINT = 0, /* vn = V + cx Omega, the indentation rate (default)  */
    TRIBO_DAMPING_CENTRE = 1         /* the centre's V: the paper's text read literally    */
} tribo_damping_point;

/* Why a run is over: the values of the output end_reason (docs/model.md §9, §3c). */
typedef enum tribo_end_reason {
    TRIBO_END_RUNNING = 0, /* it is not                                             */
    TRIBO_END_EXIT = 1,    /* the particle left the chute                           */
    TRIBO_END_LIFTOFF = 2, /* the first contact was lost again (run_end = first_liftoff) */
    TRIBO_END_REST = 3     /* the grain came to rest on the chute                   */
} tribo_end_reason;

/* How a contact at rest sticks (parameter stick_model, docs/model.md §3b). */
typedef enum tribo_stick_model {
    TRIBO_STICK_COMPLIANT = 0, /* the tangential spring of §3 at every scale (the paper's law) */
    TRIBO_STICK_RIGID = 1      /* in a contact-point normal lock the stick is a constraint,
                                  vs = 0: the rigid-body limit of the spring */
} tribo_stick_model;

/* The grain whose charge the outputs report (parameter grain_geometry, docs/model.md §8c). */
typedef enum tribo_grain_geometry {
    TRIBO_GRAIN_CYLINDER = 0, /* the model's cylinder (the paper's grain)                 */
    TRIBO_GRAIN_SPHEROID = 1  /* the prolate spheroid a, b, b, charged in bands           */
} tribo_grain_geometry;

/* The limit the gas sets on the spheroid's bands (parameter breakdown_model, docs/model.md
   §8b, §8e). */
typedef enum tribo_breakdown_model {
    TRIBO_BREAKDOWN_FIXED = 0,  /* Sigma_bd on every band and segment                     */
    TRIBO_BREAKDOWN_PASCHEN = 1 /* each contact episode's region at its Paschen limit      */
} tribo_breakdown_model;

/* The frame of the drop's velocity (parameter drop_frame, docs/model.md §9b). */
typedef enum tribo_drop_frame {
    TRIBO_DROP_FRAME_PLATE = 0, /* the plate's: the grain moves with it (default)        */
    TRIBO_DROP_FRAME_LAB = 1    /* the still external frame's                            */
} tribo_drop_frame;

#define TRIBO_CTYPE_REAL double
#define TRIBO_CTYPE_INTEGER int
#define TRIBO_CTYPE_COUNT int
#define TRIBO_CTYPE_ENUM(enumeration) int

/* Every parameter of the model, the initial state and the choices, one field per row of
   quantities.def (its description, unit, range and default are there; angles such as
   beta are in the unit the table gives). Everything is dimensionless (docs/model.md). */
typedef struct tribo_scene {
#define TRIBO_PARAMETER(name, type, ...) TRIBO_CTYPE_##type name;
#include "quantities.def"
} tribo_scene;

/* Fill a scene with the table's defaults: the paper's low-friction case (docs/model.md §7)
   at epsilon = 0.5, both charge models, CVODE at rtol = 1e-9, atol = 1e-11 (the fixed
   step's dt = 8e-5, the paper's, is set for when integrator = TRIBO_INTEGRATOR_FIXED_STEP
   is chosen). */
void tribo_scene_defaults(tribo_scene *scene);

/* ---- parameter descriptions: names, ranges, validation ------------------------- */

typedef enum tribo_param_variability {
    TRIBO_PARAM_STRUCTURAL, /* shapes the instance (memory, code paths): fixed for its life */
    TRIBO_PARAM_FIXED,      /* read at creation / reset only                               */
    TRIBO_PARAM_TUNABLE     /* may change between advances (tribo_set_param)              */
} tribo_param_variability;

typedef enum tribo_param_type {
    TRIBO_TYPE_REAL,    /* double */
    TRIBO_TYPE_INTEGER, /* int */
    TRIBO_TYPE_COUNT,   /* int that sizes the segment arrays */
    TRIBO_TYPE_ENUM     /* int naming an item of an enumeration (quantities.def) */
} tribo_param_type;

typedef struct tribo_param_info {
    const char *name;        /* the scene's field (also the FMI variable name) */
    const char *description;
    const char *unit;        /* "1" where dimensionless */
    unsigned vr;             /* the FMUs' value reference */
    size_t offset;           /* offset of the field in tribo_scene */
    tribo_param_type type;
    double min, max;         /* valid range; +-INFINITY where open-ended */
    int min_inclusive, max_inclusive;
    double start;            /* the default */
    tribo_param_variability variability;
} tribo_param_info;

/* The table of every scene parameter; *count receives its length. */
const tribo_param_info *tribo_param_table(size_t *count);
/* The entry named `name`, or NULL. */
const tribo_param_info *tribo_param_find(const char *name);
/* Read / write a parameter of a scene through its table entry (a tribo_scene for the rows
   of tribo_param_table, a tribo_si_scene for those of tribo_si_param_table, si.h). */
double tribo_param_read(const void *scene, const tribo_param_info *p);
void tribo_param_write(void *scene, const tribo_param_info *p, double value);
/* The valid range of `p` in words, e.g. "0 < epsilon <= 1" (for messages). */
void tribo_param_range_text(const tribo_param_info *p, char *buf, size_t n);
/* TRIBO_OK if `value` is valid for `p`; otherwise TRIBO_ERR_INVALID_ARGUMENT and a
   message naming the parameter, the value and the valid range. */
tribo_status tribo_param_check(const tribo_param_info *p, double value, char *msg, size_t msg_size);
/* tribo_param_check of values[i] against rows[i], i < n: TRIBO_OK, or the first refusal. */
tribo_status tribo_params_check(const tribo_param_info *rows, int n, const double *values, char *msg,
                                size_t msg_size);
/* Set the parameter `name` of a scene to `value` after checking it; an unknown name or
   an invalid value is refused with a message as above. */
tribo_status tribo_scene_set(tribo_scene *scene, const char *name, double value, char *msg,
                             size_t msg_size);
/* Apply settings "name=value name=value ..." (separated by white space) to a scene, each
   with tribo_scene_set; stops at the first one refused. */
tribo_status tribo_scene_apply(tribo_scene *scene, const char *settings, char *msg,
                               size_t msg_size);
/* The inputs (enum tribo_input order): name, unit, description, value reference and valid
   range (start 0, type REAL, variability TUNABLE), for tribo_param_check and messages. */
const tribo_param_info *tribo_input_table(size_t *count);
/* Check every parameter of a scene, then the combinations
   (tribo_scene_check_combinations); the first failure is reported as above. */
tribo_status tribo_scene_validate(const tribo_scene *scene, char *msg, size_t msg_size);
/* The combinations of valid parameters a scene must also satisfy: the drop lies on the chute,
   X0 < chute_length (model.md §9), and the rigid stick goes with the integrator and the
   dashpot (below). A failure names the parameters and their values. */
tribo_status tribo_scene_check_combinations(const tribo_scene *scene, char *msg, size_t msg_size);
/* Whether the rigid stick (stick_model = 1, model.md §3b) goes with an integrator and a
   dashpot's point: it is a phase of the event-driven integrator, held by the contact
   point's normal lock, so it needs CVODE and the contact point's dashpot. */
int tribo_rigid_stick_allowed(int integrator, int damping_point);

/* ---- the instance --------------------------------------------------------------- */

typedef struct tribo_model tribo_model;

/* Warnings of the core (e.g. contact outside the model's assumptions) go to this
   callback if one is set; level 0 = info, 1 = warning. */
typedef void (*tribo_log_fn)(void *user, int level, const char *message);

/* Create an instance at time 0 in the scene's initial state. On failure (an invalid scene,
   a NULL one, no memory, an integrator that cannot be set up: the SUNDIALS call that failed
   is named) returns NULL and writes the reason into err (if err is not NULL).
   Every function below given a NULL instance refuses it and does nothing: a status
   TRIBO_ERR_INVALID_ARGUMENT, a value NaN, tribo_last_error "the instance is NULL". */
tribo_model *tribo_create(const tribo_scene *scene, char *err, size_t err_size);
/* The same instance as tribo_create's, made faster where `like` (NULL: none; only read)
   shares the grain's shape with the scene: what depends on the roundness alone is copied from
   it, not computed again (most of the work of a create; a state load, which makes an instance
   of the scene it restores, gives the one it replaces). */
tribo_model *tribo_create_like(const tribo_scene *scene, const tribo_model *like, char *err,
                               size_t err_size);
void tribo_free(tribo_model *model);
void tribo_set_logger(tribo_model *model, tribo_log_fn fn, void *user);

/* Back to time 0 and the scene's initial state (tunables keep their current values).
   Fails (TRIBO_ERR_INTEGRATOR) if the integrator cannot start there. */
tribo_status tribo_reset(tribo_model *model);

/* Advance to time t >= the current time. The committed integration is independent
   of the times asked for: advancing in n calls to t1 < ... < tn gives bit-identical
   results to one call to tn (with constant inputs and parameters).
   One call does at most the scene's work_limit of work (in units of about half a
   microsecond of CPU: integrator.h); when that is spent it stops after a whole step and returns TRIBO_INCOMPLETE, at an
   earlier time (tribo_get TRIBO_QUANTITY_TIME) from which the next call goes on, with the same
   results as if it had not stopped. A time the integrator cannot resolve (beyond
   TRIBO_TIME_MAX, or a fixed step's grid finer than the rounding of t) is refused
   (TRIBO_ERR_TIME) and nothing changes. An advance that would give a non-finite output
   fails (TRIBO_ERR_INTEGRATOR) naming it. On a chute of finite length (model.md §9) the
   advance that carries the particle past its end stops there, exactly at the crossing, and
   returns TRIBO_ENDED, and so does the one that ends the run at the first lift-off
   (run_end = first_liftoff). */
tribo_status tribo_advance(tribo_model *model, double t);
#define TRIBO_TIME_MAX 1e12
/* tribo_advance to t, going on after each early stop (for a caller that needs no bound on
   the work of one call, e.g. a batch run); TRIBO_ENDED where the run ends (run_end). */
tribo_status tribo_advance_fully(tribo_model *model, double t);

/* Change a tunable parameter (the rows of variability TUNABLE in quantities.def) from the
   current time on. Structural and fixed parameters are rejected, and so is any change once
   the run has ended (TRIBO_ENDED). */
tribo_status tribo_set_param(tribo_model *model, const char *name, double value);

/* The inputs (quantities.def: the external force along and normal to the plate,
   docs/model.md §3), held constant from the current time on. */
typedef enum tribo_input {
#define TRIBO_INPUT(id, ...) TRIBO_INPUT_##id,
#include "quantities.def"
    TRIBO_INPUT_COUNT
} tribo_input;
/* (A change once the run has ended is refused, TRIBO_ENDED.) */
tribo_status tribo_set_inputs(tribo_model *model, const double values[TRIBO_INPUT_COUNT]);
/* The same for the two components of the external force. */
tribo_status tribo_set_external_force(tribo_model *model, double F_T, double F_N);

/* The scene the instance runs (including the current tunable values). */
const tribo_scene *tribo_get_scene(const tribo_model *model);

/* The reason for the last failure of a call on this instance ("" if none). */
const char *tribo_last_error(const tribo_model *model);

/* ---- what can be read ------------------------------------------------------------ */

typedef enum tribo_quantity {
#define TRIBO_TIME(id, ...) TRIBO_QUANTITY_##id,
#define TRIBO_OUTPUT(id, ...) TRIBO_QUANTITY_##id,
#include "quantities.def"
    TRIBO_QUANTITY_COUNT
} tribo_quantity;

/* The value of a quantity at the current time. Charge quantities of a model the
   scene does not include read as 0 (Sigma_s as Sigma0). */
double tribo_get(tribo_model *model, tribo_quantity q);
/* Name of a quantity, e.g. "Q_static" (the FMI output names). */
const char *tribo_quantity_name(tribo_quantity q);

/* The per-segment arrays, one per charge model, in the order of the registry. */
typedef enum tribo_segment_charge {
#define TRIBO_SEGMENTS(id, ...) TRIBO_SEGMENTS_##id,
#include "quantities.def"
    TRIBO_SEGMENTS_COUNT
} tribo_segment_charge;

/* Whether the instance's scene includes the charge model of that array (its switch
   charge_model_<name>). */
int tribo_includes_charge_model(const tribo_model *model, tribo_segment_charge which);

/* The spheroid's (grain_geometry = spheroid, model.md §8c) charge by the model of that array,
   in the units of the array times a^2; the charge its bands lost at the air-breakdown limit,
   the same way; the area of its bands at that limit (a^2). 0 for the cylinder or for a
   model the scene leaves out. */
double tribo_get_grain_charge(tribo_model *model, tribo_segment_charge which);
double tribo_get_grain_charge_lost(tribo_model *model, tribo_segment_charge which);
double tribo_get_grain_capped_area(tribo_model *model, tribo_segment_charge which);

/* Copy the per-segment charge densities (n = n_segments values) at the current time.
   Fails if the scene does not include that model. */
tribo_status tribo_get_segment_charges(tribo_model *model, tribo_segment_charge which,
                                       double *out, size_t n);
/* The mean of the values tribo_get_segment_charges copies, at the current time, without
   copying them: 0 if the scene does not include that model (NaN for no model's array). */
double tribo_get_mean_charge(tribo_model *model, tribo_segment_charge which);

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
/* Everything the bytes carry is checked (finite, within its range, consistent with the
   rest and with this instance's structure) before the instance changes; a refused state
   (TRIBO_ERR_STATE, with the reason) leaves the instance exactly as it was. */
tribo_status tribo_state_load(tribo_model *model, const void *buffer, size_t size);
/* The time of the instance a state was saved from (TRIBO_ERR_STATE if the bytes are not a
   state), for a caller that keeps a clock of its own beside the core's. */
tribo_status tribo_state_time(const void *buffer, size_t size, double *t);

#ifdef __cplusplus
}
#endif

#endif /* TRIBO_H */

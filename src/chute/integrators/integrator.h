/*
 * integrator.h: the contract between an instance and its integrator (internal to the core).
 *
 * An integrator advances the motion and commits points (states of the particle at one
 * time) in an order of its own, independent of the times it is asked for; between the
 * last committed point and the asked time it sets an output point that is not committed.
 * It does so only through the services below: it never writes the instance's fields.
 * Every hook returns a status; a failure carries its reason (tribo_fail) to the caller.
 *
 * The committed point never lies after the output point: an advance commits only the
 * steps that end at or before the asked time.
 *
 * An advance may end early, and only between steps: when tribo_work_spent says the work
 * limit of the advance is spent, or when the step just committed ends the run (model.md §9:
 * where the particle leaves the chute, the exit switch of force_phases.h, or with run_end =
 * first_liftoff where the first contact is lost again, each located exactly; §3c: where the
 * grain has come to rest, the event that enters that phase), it returns
 * tribo_stop_early() with the reason (the output point at the committed one). Every early
 * stop goes through it: after the work limit the next advance goes on from there as if
 * nothing had stopped; after the exit or the lift-off the run is over.
 */
#ifndef TRIBO_INTEGRATOR_H
#define TRIBO_INTEGRATOR_H

#include <stddef.h>

#include "charging.h"
#include "dynamics.h"
#include "motion.h"
#include "tribo.h"

/* The state of the particle at one time. */
typedef struct tribo_point {
    double t;
    double y[TRIBO_NSTATE_MAX];  /* the motion, then the charge models' quadratures */
    double contact_time;         /* time spent in contact so far */
    double charge_globals[TRIBO_CHARGE_MAX_GLOBALS]; /* the charge models' global states */
    tribo_contact_eval contact;  /* contact and forces at this point */
    int slipping;
    tribo_motion motion;         /* motion-class history and assumption check */
} tribo_point;

typedef struct tribo_integrator_ops {
    /* Allocate the integrator's data for the instance. */
    tribo_status (*create)(tribo_model *m, void **data);
    void (*destroy)(void *data);
    /* The committed point was set from outside (reset, a tunable or an input changed):
       start afresh from it (and commit it again, evaluated under the integrator's law). */
    tribo_status (*restart)(tribo_model *m, void *data);
    /* Commit the motion up to t, then set the output point at t (or stop early, above). */
    tribo_status (*advance)(tribo_model *m, void *data, double t);
    /* The integrator's own state, as plain bytes. */
    size_t (*state_size)(const void *data);
    void (*state_save)(const void *data, unsigned char *buffer);
    /* Check saved bytes against the committed point already loaded and the output time
       t_out (every value one the integrator can produce, its times consistent with both,
       and advancing to t_out commits nothing), then take them, applying the scene (which
       may differ from the one the integrator was made with in its fixed parameters).
       A refusal (TRIBO_ERR_STATE, with the reason) may leave the integrator's data
       changed: the caller restores it. */
    tribo_status (*state_load)(tribo_model *m, void *data, const unsigned char *buffer,
                               double t_out);
} tribo_integrator_ops;

/* The integrator of a kind (tribo_integrator_kind), or NULL for an unknown kind. */
const tribo_integrator_ops *tribo_integrator_of_kind(int kind);

/* ---- services: what an integrator reads ----------------------------------------------- */

const tribo_dyn_params *tribo_dynamics(const tribo_model *m);
const tribo_point *tribo_committed(const tribo_model *m);
/* Components of y in use: the motion and the charge models' quadratures. */
int tribo_state_length(const tribo_model *m);

/* ---- services: what an integrator writes ------------------------------------------------ */

/* Commit p (its charges are committed separately, by tribo_charge_*). */
void tribo_commit(tribo_model *m, const tribo_point *p);
/* The output point is about to be set: forget the charge updates queued for the last one. */
void tribo_output_begin(tribo_model *m);
/* Set the output point (its charge updates queued with TRIBO_CHARGE_PENDING). */
void tribo_output_set(tribo_model *m, const tribo_point *p);

/* Book-keeping of an interval of the motion from `from` to `to` (whose y and contact are
   set): the contact time, the motion-class history and the check of the contact model's
   assumptions. commit: the interval is committed (count and log a new violation). */
void tribo_book_interval(tribo_model *m, const tribo_point *from, tribo_point *to, int commit);

typedef enum tribo_counter {
    TRIBO_COUNT_STEPS,     /* integrator steps taken                        */
    TRIBO_COUNT_RHS_EVALS, /* right-hand-side evaluations                   */
    TRIBO_COUNT_EVENTS,    /* switches of the force law located             */
    TRIBO_COUNT_RESTARTS,  /* integrator restarts                           */
    TRIBO_COUNT_SUBSTEPS   /* extra sub-steps the fixed step took           */
} tribo_counter;
void tribo_count(tribo_model *m, tribo_counter which, long long n);

/* The work the scene's work_limit bounds: each kind of work weighs what it costs, so that a
   unit is about the same CPU time whatever the inputs (fitted to the CPU of advances over
   scenes where one kind dominates, the SI set-ups at the ends of their ranges and the
   dimensionless ones on 1e5 segments: docs/work_limit.md). The default limit then bounds an
   advance to under a second of CPU, and the paper's fixed step in communication steps of
   100 stays within it. A CVODE step costs what CVODE spent on it: its own book-keeping, each
   right-hand side it evaluated (more with BDF, whose Newton iteration solves a linear system
   per evaluation), each derivative of its interpolant taken, and each look for a grazing
   switch inside it. */
#define TRIBO_WORK_FIXED_STEP 0.6        /* an RK4 step or sub-step, with its sample         */
#define TRIBO_WORK_CVODE_STEP 2.0        /* a CVODE step's own book-keeping ...              */
#define TRIBO_WORK_RHS_ADAMS 3.0         /* ... each right-hand side of it, with Adams ...   */
#define TRIBO_WORK_RHS_BDF 6.0           /* ... or with BDF ...                              */
#define TRIBO_WORK_INTERPOLANT 0.7       /* ... each derivative of its interpolant taken ... */
#define TRIBO_WORK_GRAZING_LOOK 0.15     /* ... and each look at the switch functions inside */
#define TRIBO_WORK_FLIGHT_PIECE 1.0      /* a piece of a closed-form flight (flight.h) ...   */
#define TRIBO_WORK_FLIGHT_EVALUATION 0.2 /* ... and each look at its clearance              */
#define TRIBO_WORK_PROBE 0.25            /* a look of the charging sweep at the contact     */
#define TRIBO_WORK_SAMPLE 0.1            /* a sample of the sweep, per charge model ...     */
#define TRIBO_WORK_SAMPLE_BAND 0.15      /* ... and its patch over the spheroid's bands     */
#define TRIBO_WORK_SEGMENT_UPDATE 0.0016 /* each segment value charged ...                 */
#define TRIBO_WORK_SEGMENT_HELD 0.0019   /* ... and holds within the breakdown limit        */
#define TRIBO_WORK_LEAVE_TARGET 0.015    /* ... in instantaneous transfer where the globals
                                            move, its saturation where it left the contact  */
#define TRIBO_WORK_BAND 0.05             /* a segment's band of the spheroid widened under
                                            the patch (its models' bands charged as values) */
/* Book work of the advance under way (the units above). The charging services book their
   own. */
void tribo_work(tribo_model *m, double units);
/* Whether the advance under way has spent its work limit. */
int tribo_work_spent(const tribo_model *m);
/* Why an advance ends before the asked time. */
typedef enum tribo_stop_reason {
    TRIBO_STOP_WORK_LIMIT, /* the advance spent its work limit: TRIBO_INCOMPLETE */
    TRIBO_STOP_EXIT,       /* the committed point is the exit from the chute: TRIBO_ENDED */
    TRIBO_STOP_LIFTOFF,    /* the committed point is the first lift-off (run_end =
                              first_liftoff): TRIBO_ENDED */
    TRIBO_STOP_REST        /* the committed point holds the grain at rest (model.md §3c): the
                              normal lock, the rigid stick and the rolling lock at once, with
                              constant inputs, for ever: TRIBO_ENDED */
} tribo_stop_reason;
/* End the advance under way at the committed point: it becomes the output point; returns
   the status of the reason, with a message. */
tribo_status tribo_stop_early(tribo_model *m, tribo_stop_reason why);

/* A warning of the integrator, to the instance's logger. */
void tribo_warn(tribo_model *m, const char *message);
/* Record the reason for a failure; returns status. */
tribo_status tribo_fail(tribo_model *m, tribo_status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* ---- services: charging ----------------------------------------------------------------- */

/* Where a charge update goes: tribo_charge_destination (charging.h). */

/* The rates of the charge models' quadratures at a contact evaluation (for an integrator
   that integrates them with the motion; 0 in flight). */
void tribo_quadrature_rates(const tribo_model *m, const tribo_contact_eval *ev, double *rates);

/* A step of length h from `from` to `to` (whose y and contact are set) charged at its end
   point's contact: advances to's charge globals and fills the sample. */
void tribo_charge_step(tribo_model *m, const tribo_point *from, tribo_point *to, double h,
                       tribo_contact_sample *sample);
/* Charge the segments under a sample. */
tribo_status tribo_charge_sample(tribo_model *m, const tribo_contact_sample *sample,
                                 tribo_charge_destination where);

/* The contact at state y as the sweep sees it (tribo_contact_probe); reads only Y, phi, U
   and Omega of y. */
void tribo_probe_contact(const tribo_model *m, const double *y, double *s_centre,
                         double *half_width, double *centre_speed, tribo_contact_kinematics *k);
/* Sweep a contact over [a, b] seen through the probe (tribo_charging_sweep), to the
   scene's rtol / atol, advancing p's quadratures and charge globals. The sweep of one
   integrator step is bounded: it ends early, at *reached < b, once it has cost
   TRIBO_SWEEP_BUDGET (in tribo_charging_sweep's units), and the integrator then ends its
   step there. Where it ends depends on a alone, not on b, so the committed run stays
   independent of the times asked for and of the work limit. */
#define TRIBO_SWEEP_BUDGET 1e5
tribo_status tribo_charge_sweep(tribo_model *m, const tribo_contact_probe *probe, double a,
                                double b, tribo_point *p, tribo_charge_destination where,
                                double *reached);

extern const tribo_integrator_ops tribo_fixed_step_ops;
extern const tribo_integrator_ops tribo_cvode_ops;

#endif

/* model.h: the instance behind the opaque tribo_model (internal to the core). */
#ifndef TRIBO_MODEL_H
#define TRIBO_MODEL_H

#include "charging.h"
#include "dynamics.h"
#include "integrator.h"
#include "motion.h"
#include "tribo.h"

/* The state of the particle at one time. */
typedef struct tribo_point {
    double t;
    double y[TRIBO_NSTATE];
    double contact_time;      /* time spent in contact so far */
    double Sigma_s;           /* dynamic saturation density (MODEL §5b) */
    tribo_contact_eval contact; /* contact and forces at this point */
    int slipping;
    tribo_motion motion;      /* contact-mode history and assumption check */
} tribo_point;

struct tribo_model {
    tribo_scene scene;           /* validated; tunables hold their current values */
    tribo_dyn_params dyn;        /* derived from the scene and the inputs */
    tribo_charge_params charge;
    int has_charging;
    tribo_charging charging;     /* committed charges (unused when has_charging = 0) */

    /* The integrator commits points independently of the times asked for; the state at
       the asked time `out` is derived from the committed point without disturbing it. */
    tribo_point committed;
    tribo_point out;
    /* charge updates from committed.t to out.t, applied lazily to copies when read */
    tribo_contact_sample *pending;
    size_t n_pending, cap_pending;
    double *q_out, *sigma_out;   /* scratch copies for reads off the committed point */
    int charges_out_valid;

    const tribo_integrator_ops *integrator;
    void *integrator_data;

    tribo_stats stats;
    double motion_decay_h, motion_decay; /* exp(-h / TRIBO_MOTION_WINDOW) for the last h */
    tribo_log_fn log;
    void *log_user;
    char error[512];
};

/* Record the reason for a failure; returns status. */
tribo_status tribo_fail(tribo_model *m, tribo_status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* The initial point of the scene (MODEL §7 by default). */
void tribo_initial_point(const tribo_model *m, tribo_point *p);

/* Book-keeping of an interval of the motion from `from` to `to` (whose y and contact are
   set): the contact time, the contact-mode history and the check of the contact model's
   assumptions. commit: the interval is committed (count and log a new violation). */
void tribo_account_interval(tribo_model *m, const tribo_point *from, tribo_point *to, int commit);

/* Queue a charge update between the committed point and the output point. */
tribo_status tribo_pending_push(tribo_model *m, const tribo_contact_sample *sample);
void tribo_pending_clear(tribo_model *m);

/* Make the output point the committed one (before a tunable or input changes there);
   the caller then restarts the integrator. */
void tribo_commit_output(tribo_model *m);

/* Recompute dyn / charge from the scene (after a tunable changed). */
void tribo_derive_params(tribo_model *m);

#endif

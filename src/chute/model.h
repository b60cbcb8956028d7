/* model.h: the instance behind the opaque tribo_model (internal to the core; integrators
   see it only through integrator.h). */
#ifndef TRIBO_MODEL_H
#define TRIBO_MODEL_H

#include "charge_interface.h"
#include "charging.h"
#include "dynamics.h"
#include "integrator.h"
#include "motion.h"
#include "tribo.h"

/* The loosest tolerances CVODE and the event logic work to (model.md §3, "Tolerances"): a
   scene's rtol or atol above them runs at them. Within 10 (rtol |v| + atol) a state cannot
   tell which side of a switch it is on (dynamics.h); from rtol 0.05 to 0.1, or atol 1e-3
   (the indentation's scale at the paper's Gamma = 1e-3), the force law switched for ever at
   one instant or crept by 1e-6 per doStep (measured; rtol 1e-2 with atol 1e-4 ran every
   set-up tried): 100 times below the first failures. */
#define TRIBO_RTOL_LOOSEST 1e-3
#define TRIBO_ATOL_LOOSEST 1e-5

struct tribo_model {
    tribo_scene scene;           /* validated; tunables hold their current values */
    tribo_dyn_params dyn;        /* derived from the scene and the inputs */
    tribo_charging charging;     /* the charge models and their committed charges */
    int n_state;                 /* TRIBO_NMOTION + the charge models' quadratures */

    /* The integrator commits points independently of the times asked for; the state at
       the asked time `out` is derived from the committed point without disturbing it. */
    tribo_point committed;
    tribo_point out;
    /* charge updates from committed.t to out.t, applied lazily to copies when read */
    tribo_contact_sample *pending;
    size_t n_pending, cap_pending;
    int charges_out_valid;
    /* what the pending updates add to each model's sum and to the charge its breakdown limit
       took (valid when pending_sums_valid) */
    int pending_sums_valid;
    tribo_charge_totals pending_totals;

    /* the work done by the advance under way (integrator.h: the units of work_limit) */
    double work;
    /* why the run is over (model.md §9), for good: 0 it is not, TRIBO_END_EXIT the particle
       left the chute, TRIBO_END_LIFTOFF it lifted off (run_end = first_liftoff),
       TRIBO_END_REST it came to rest on the chute (§3c); the output point is where */
    int ended;

    const tribo_integrator_ops *integrator;
    void *integrator_data;

    tribo_stats stats;
    tribo_motion_scales motion_scales;   /* the classifier's, at the scene's Gamma */
    double motion_decay_h, motion_decay; /* exp(-h / its window) for the last h */
    tribo_log_fn log;
    void *log_user;
    char error[512];
};

/* What an instance is made of: its charge models, those of charge_selection's bits
   (bit i: charge_models[i]), and its integrator (NULL: the scene's integrator kind has
   none, and the instance is refused). tribo_create uses the registry (charge_registry.def)
   with the scene's selection (tribo_charge_selection) and the integrator of the scene's
   kind (create.c); a test can plug in models or an integrator of its own. */
typedef struct tribo_parts {
    const tribo_charge_model *const *charge_models;
    int n_charge_models;
    unsigned charge_selection;
    const tribo_integrator_ops *integrator;
} tribo_parts;

/* The registry's models as the scene selects them, with the scene's integrator. */
tribo_parts tribo_registry_parts(const tribo_scene *scene);

/* An instance of the scene made of the parts (tribo_create_like: what it takes from `like`,
   NULL for nothing). */
tribo_model *tribo_create_from_parts(const tribo_scene *scene, const tribo_parts *parts,
                                     const tribo_model *like, char *err, size_t err_size);

/* ---- the charges at the output point (charge_outputs.c) ------------------------------------ */

/* Makes the output point's per-segment values (the committed ones with the pending updates
   applied: copies, for the arrays only) when updates are pending. Returns 0 if out of
   memory. */
int tribo_charges_out(tribo_model *m);
/* Makes what the pending updates add to each model's sum. Returns 0 if out of memory. */
int tribo_pending_sums(tribo_model *m);
/* The view of the model at `index` of the instance's model set, for its own outputs. */
tribo_charge_view tribo_charge_view_of(tribo_model *m, int index);
/* The output point's values of the model at `index` (its own units; NULL if out of
   memory). */
const double *tribo_charge_values_of(tribo_model *m, int index);
/* The same for the model's band densities, with the bands' geometry (§8c; NULL without
   bands or if out of memory). */
const double *tribo_charge_bands_of(tribo_model *m, int index, const tribo_band_geometry **geometry);
/* The grain's charged area, sum of W_i L_i (a^2; 0 without bands, §8c). */
double tribo_charged_area(tribo_model *m);
/* The grain's outputs (docs/model.md §8c, grain.c; 0 without bands or for a model the scene
   leaves out): its charge by the model at `index`, in the units of the model's array times
   a^2; the charge its bands lost at the breakdown limit, the same way; the area (a^2) of its
   bands at the limit. */
double tribo_grain_charge(tribo_model *m, int index);
double tribo_grain_charge_lost(tribo_model *m, int index);
double tribo_grain_capped_area(tribo_model *m, int index);
/* Every model's outputs of the breakdown limit (docs/model.md §8b): the fraction of its
   segments at the limit, and the charge lost to the gas as a mean over the segments in the
   units of its array (0 for a model the scene leaves out). */
double tribo_capped_fraction(tribo_model *m, int index);
double tribo_charge_lost(tribo_model *m, int index);

/* Recompute dyn from the scene (after a tunable changed). */
void tribo_derive_params(tribo_model *m);

/* TRIBO_OK if every output at the output point is a finite number; else a failure naming
   the first that is not. */
tribo_status tribo_check_outputs(tribo_model *m);

#endif

/*
 * charge_interface.h: what a charge model is (docs/model.md §5), as the segment loop, the
 * exact contact-time sweep, both integrators, the saved state and the SI front end see it.
 *
 * A charge model has one value per boundary segment (its charge density), changed only
 * on the segments in contact; it may have global states (the sliding model's dynamic
 * saturation density Sigma_s) and quadratures (rates integrated along the motion: the
 * sliding model's frictional work per unit area omega). Everything else (which segments
 * touch, for how long, the saving and loading of states, the outputs' plumbing) is
 * generic: charging.c, charge_sweep.c, state_io.c, charge_outputs.c.
 *
 * To add a model: one file implementing a tribo_charge_model, and one row registering it in
 * charge_registry.def (CONTRIBUTING.md walks through it).
 */
#ifndef TRIBO_CHARGE_MODEL_H
#define TRIBO_CHARGE_MODEL_H

#include <stddef.h>

#include "tribo.h"

/* Room in a point for the global states and quadratures of every registered model. */
#define TRIBO_CHARGE_MAX_GLOBALS 4
#define TRIBO_CHARGE_MAX_QUADRATURES 2
#define TRIBO_CHARGE_MAX_MODELS 4

/* The contact as a quadrature's rate sees it (docs/model.md §5b). */
typedef struct tribo_contact_kinematics {
    double mu;      /* Coulomb friction coefficient, its current value    */
    double delta_y; /* indentation                                         */
    double vs;      /* slip velocity of the contact point, U + h Omega     */
    double rho_c;   /* radius of curvature of the boundary at the contact  */
    double h;       /* depth of the contact point below the centre: the patch's half-width
                       across the plane of motion is h Sc (model.md §8c)  */
} tribo_contact_kinematics;

/* ---- exponentials for exact updates over an interval --------------------------------- */

/* Exponentials of the last duration and time constant seen, so that a run at a fixed step
   costs no transcendental call per step; what a model does not ask for is not computed. A
   zeroed cache is empty. */
typedef struct tribo_decay_cache {
    double duration, tau, z; /* z = duration / tau */
    double decay, one_minus_decay; /* e^-z, 1 - e^-z */
    int has_phi1, has_moments;
    double phi1;     /* (1 - e^-z) / z */
    double zf1, zf2; /* z F_k(z), F_k(z) = int_0^1 v^k e^{-z v} dv */
} tribo_decay_cache;

/* e^-z and 1 - e^-z for z = duration / tau, recomputed only when either changed. */
const tribo_decay_cache *tribo_decay(tribo_decay_cache *k, double duration, double tau);
/* The same with phi1 too. */
const tribo_decay_cache *tribo_decay_phi1(tribo_decay_cache *k, double duration, double tau);
/* The same with the moments zf1, zf2 too. */
const tribo_decay_cache *tribo_decay_moments(tribo_decay_cache *k, double duration, double tau);

/* What drives the segments in contact over an interval: its duration and each global
   state at its start, middle and end (a quadratic in time through those three). */
typedef struct tribo_charge_forcing {
    double duration;
    const double *begin, *mid, *end; /* the model's own globals */
    /* a cache of exponentials that every model of the set shares over one interval: the
       models that relax over the same time constant take them once */
    tribo_decay_cache *decay;
} tribo_charge_forcing;

/* What a model's values are, for the SI front end (model.md §8): sigma_i over sigma0, or
   densities Sigma_i in units of sqrt(kappa k' a) (sigma_i = sign(sigma0) Sigma_i sqrt(kappa k' a)). */
typedef enum { TRIBO_CHARGE_PER_SIGMA0, TRIBO_CHARGE_PER_SIGMA_SCALE } tribo_charge_si_unit;

typedef struct tribo_charge_model {
    const char *name;  /* "static", "sliding": in messages */
    int n_globals;     /* at most TRIBO_CHARGE_MAX_GLOBALS over all registered models */
    int n_quadratures; /* at most TRIBO_CHARGE_MAX_QUADRATURES over all of them */
    size_t cache_size; /* bytes of scratch the model keeps per instance (zeroed at start) */

    /* The global states at the start of a run. */
    void (*start)(const tribo_scene *s, double *globals);

    /* The rate of quadrature k in contact (in flight it is 0). */
    double (*quadrature_rate)(int k, const tribo_contact_kinematics *c);

    /* The globals over one step of length h of the fixed-step integrator, from g0 to g1,
       given the quadratures at its ends (q0, q1) and whether it ends in contact. */
    void (*step_globals)(void *cache, const tribo_scene *s, double h, int in_contact,
                         const double *q0, const double *q1, const double *g0, double *g1);

    /* The globals over a piece of contact of length h swept from an integrator's dense
       output: from g0 to g_mid (at h/2) and g_end, given the rates of the quadratures at
       the quarter points (rates[k][0..4]) and the quadratures at the start, middle and
       end. Returns 0 to have the piece halved (its globals not accurate to rtol / atol). */
    int (*piece_globals)(void *cache, const tribo_scene *s, double h, const double (*rates)[5],
                         const double *q_begin, const double *q_mid, const double *q_end,
                         const double *g0, double *g_mid, double *g_end, double rtol,
                         double atol);

    /* The rate law on segments[0..count), in contact over an interval: exact given the
       forcing. Returns the change of their sum (what the outputs' means follow). */
    double (*charge)(void *cache, const tribo_scene *s, const tribo_charge_forcing *f,
                     double *segments, long count);

    /* The per-segment values as tribo_get_segment_charges reports them: linear in the
       model's own values (the charge lost to the gas is reported through it too). */
    void (*segment_values)(const tribo_scene *s, const double *globals, const double *segments,
                           double *out, int n);

    /* Whether saved values (the model's globals, its n finite segment values) are ones the
       model can produce, for a state being loaded; NULL: any finite values are. */
    int (*valid)(const tribo_scene *s, const double *globals, const double *segments, int n);

    /* The value a segment in contact holds at once with instantaneous transfer (tau0 = 0,
       docs/model.md §5c): the model's saturation at these globals (static: 1; sliding:
       Sigma_s). The generic code sets it; `charge` is called only with tau0 > 0. */
    double (*saturation)(const tribo_scene *s, const double *globals);

    /* The charge density Sigma (docs/model.md §8: in units of sqrt(kappa k' a), positive in
       the pair's polarity) that one unit of the model's own values stands for, a function
       of the scene's Sigma0 alone (static: Sigma0; sliding: 1). From it come the bound the
       air-breakdown density Sigma_bd sets on its values (§8b: Sigma_bd / unit, taken again
       only when Sigma_bd or Sigma0 changes) and the grain's initial density in its units
       (§8c: Sigma_init / unit). NULL: its values are no densities; neither applies. */
    double (*density_unit)(const tribo_scene *s);

    /* The unit of its reported values in the SI front end. */
    tribo_charge_si_unit si_unit;

    /* The global states' limits for t -> infinity with the grain at rest in contact (docs/model.md
       §3c: no work done, the contact held), written over globals; NULL: they hold still. The
       segments under the contact are then charged at these limits for an infinite duration:
       `charge` must take duration = INFINITY (decay e^-inf = 0) to the saturation exactly. */
    void (*rest_limits)(const tribo_scene *s, double *globals);
} tribo_charge_model;

/* A model's state at the output point of an instance, as the outputs of its own
   (quantities.def: Q_static, Sigma_s, ...) read it: the instance makes it
   (tribo_charge_view_of, model.h), the model's file computes its outputs from it. */
typedef struct tribo_charge_view {
    const tribo_scene *scene;
    int selected;
    int n;
    double sum;                /* of its n values, pending updates included (NaN: out of memory) */
    double lost;               /* the sum of what the breakdown limit took, pending included */
    double band_charge;        /* the grain's bands (§8c): their charge, sum of value times
                                  area (a^2), and what the limit took, the same way */
    double band_lost;
    const double *globals;     /* its global states */
    const double *quadratures; /* its quadratures   */
} tribo_charge_view;

/* Sum of an array of n values. */
double tribo_sum(const double *v, long n);

#endif

/* support.h: helpers the C tests share, so that each test states what it checks and not how
   an instance is made, run or saved. A helper fails the test (cr_assert) with the core's own
   message where the core refuses, so that a failure says why rather than crashing later on
   a NULL or a half-run instance. */
#ifndef TRIBO_TEST_SUPPORT_H
#define TRIBO_TEST_SUPPORT_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tribo.h"

/* ---- making scenes and instances ------------------------------------------------------
   Tests start from the table's defaults (the paper's drop) and name only what they change. */

/* The defaults with settings "name=value ..." applied; the test fails if one is refused. */
static inline tribo_scene scene_of(const char *settings)
{
    tribo_scene s;
    char err[512];
    tribo_scene_defaults(&s);
    cr_assert_eq(tribo_scene_apply(&s, settings, err, sizeof err), TRIBO_OK, "%s", err);
    return s;
}

/* Every registered charge model switched off (charge_registry.def): the motion alone. */
static inline void no_charge_models(tribo_scene *s)
{
#define TRIBO_CHARGE_MODEL(id, name, slot, model, on, values) s->charge_model_##name = 0;
#include "charge_registry.def"
#undef TRIBO_CHARGE_MODEL
}

/* A new instance of the scene; the test fails with the reason if there is none. */
static inline tribo_model *make(const tribo_scene *s)
{
    char err[512];
    tribo_model *m = tribo_create(s, err, sizeof err);
    cr_assert(m, "%s", err);
    return m;
}

/* The scene run by the fixed step and by CVODE at tight tolerances (rtol 1e-10, atol
   1e-12): the tight tolerances make CVODE the reference the fixed step is compared with. */
static inline void make_fixed_and_cvode(tribo_scene s, tribo_model **fixed, tribo_model **cvode)
{
    s.integrator = TRIBO_INTEGRATOR_FIXED_STEP;
    *fixed = make(&s);
    s.integrator = TRIBO_INTEGRATOR_CVODE;
    s.rtol = 1e-10;
    s.atol = 1e-12;
    *cvode = make(&s);
}

/* ---- running and comparing two instances ----------------------------------------------
   Most comparisons run two instances to the same time and measure how far apart they are. */

/* Advance both to t; the test fails with the reason if either fails. */
static inline void advance_both(tribo_model *a, tribo_model *b, double t)
{
    cr_assert_eq(tribo_advance_fully(a, t), TRIBO_OK, "%s", tribo_last_error(a));
    cr_assert_eq(tribo_advance_fully(b, t), TRIBO_OK, "%s", tribo_last_error(b));
}

/* The largest difference of their motion: X, Y, phi, U, V, Omega (the state the charges
   follow from, so the one a comparison of integrators needs). */
static inline double state_distance(tribo_model *a, tribo_model *b)
{
    const tribo_quantity q[] = {TRIBO_QUANTITY_X, TRIBO_QUANTITY_Y, TRIBO_QUANTITY_PHI,
                                TRIBO_QUANTITY_U, TRIBO_QUANTITY_V, TRIBO_QUANTITY_OMEGA};
    double d = 0.0;
    for (int i = 0; i < 6; i++)
        d = fmax(d, fabs(tribo_get(a, q[i]) - tribo_get(b, q[i])));
    return d;
}

/* Whether every quantity of the two is the same, bit for bit (a run that must not depend
   on how it was cut into advances or on the limits it ran under). */
static inline int same_outputs(tribo_model *a, tribo_model *b)
{
    for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++) {
        const double x = tribo_get(a, q), y = tribo_get(b, q);
        if (memcmp(&x, &y, sizeof x) != 0)
            return 0;
    }
    return 1;
}

/* ---- the energy bound (model.md §6) -------------------------------------------------------
   Along a run without external force E + work_dissipated never increases: a test samples it
   and holds its largest rise above its lowest value so far to a fraction of E's scale. */

typedef struct energy_watch {
    double lowest, rise, scale; /* the lowest E + W so far, the largest rise above it, max |E| */
} energy_watch;

static inline energy_watch energy_watch_start(void)
{
    const energy_watch w = {INFINITY, 0.0, 0.0};
    return w;
}

static inline void energy_watch_sample(energy_watch *w, tribo_model *m)
{
    const double E = tribo_get(m, TRIBO_QUANTITY_ENERGY);
    const double budget = E + tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED);
    w->scale = fmax(w->scale, fabs(E));
    w->rise = fmax(w->rise, budget - w->lowest);
    w->lowest = fmin(w->lowest, budget);
}

/* ---- saved states ----------------------------------------------------------------------
   The state tests save, corrupt and reload instances, so they need the bytes and where a
   field lies in them. */

/* The instance's whole state, saved into a new buffer of *size bytes (free it). */
static inline unsigned char *saved_state(const tribo_model *m, size_t *size)
{
    *size = tribo_state_size(m);
    unsigned char *bytes = malloc(*size);
    cr_assert(bytes);
    cr_assert_eq(tribo_state_save(m, bytes, *size), TRIBO_OK);
    return bytes;
}

/* A new instance of the scene s loaded with m's saved state. */
static inline tribo_model *loaded_copy(const tribo_model *m, const tribo_scene *s)
{
    size_t size;
    unsigned char *bytes = saved_state(m, &size);
    tribo_model *copy = make(s);
    cr_assert_eq(tribo_state_load(copy, bytes, size), TRIBO_OK, "%s", tribo_last_error(copy));
    free(bytes);
    return copy;
}

/* Where a state keeps whether (and why) its run has ended (state_io.c's layout): after the
   header, the parameters, F_T, F_N, the output time and the six work counters. */
static inline size_t state_ended_offset(void)
{
    size_t n_params;
    tribo_param_table(&n_params);
    return 8 + 2 * 8 + n_params * 8 + 3 * 8 + 6 * 8;
}

#endif

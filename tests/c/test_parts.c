/* The core's seams (src/chute/charge/charge_interface.h,
   src/chute/integrators/integrator.h): a charge model defined here, in the test, runs
   through both integrators and the state save/load without any change to them; every
   integrator hook's failure reaches the caller; an unknown integrator kind is refused. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "charge_registry.h"
#include "model.h"
#include "support.h"

/* ---- a test-only charge model: constant-rate charging ------------------------------------ */

/* Per segment c_i, dc_i/dtau = 1 / tau0 while in contact. One global state, the time spent
   in contact (it grows by the duration of every contact interval), and one quadrature,
   the slip distance |vs| integrated along the contact. */
static void start(const tribo_scene *s, double *g)
{
    (void)s;
    g[0] = 0.0;
}

static double quadrature_rate(int k, const tribo_contact_kinematics *c)
{
    (void)k;
    return fabs(c->vs);
}

static void step_globals(void *cache, const tribo_scene *s, double h, int in_contact,
                         const double *q0, const double *q1, const double *g0, double *g1)
{
    (void)cache, (void)s, (void)q0, (void)q1;
    g1[0] = g0[0] + (in_contact ? h : 0.0);
}

static int piece_globals(void *cache, const tribo_scene *s, double h, const double (*rates)[5],
                         const double *q_begin, const double *q_mid, const double *q_end,
                         const double *g0, double *g_mid, double *g_end, double rtol, double atol)
{
    (void)cache, (void)s, (void)rates, (void)q_begin, (void)q_mid, (void)q_end, (void)rtol,
        (void)atol;
    g_mid[0] = g0[0] + 0.5 * h;
    g_end[0] = g0[0] + h;
    return 1;
}

static double charge(void *cache, const tribo_scene *s, const tribo_charge_forcing *f, double *c,
                     long count)
{
    (void)cache;
    double change = 0.0;
    for (long i = 0; i < count; i++) {
        const double old = c[i];
        c[i] += f->duration / s->tau0;
        change += c[i] - old;
    }
    return change;
}

static void segment_values(const tribo_scene *s, const double *g, const double *c, double *out,
                           int n)
{
    (void)s, (void)g;
    memcpy(out, c, (size_t)n * sizeof *out);
}

static const tribo_charge_model constant_rate = {
    .name = "constant rate",
    .n_globals = 1,
    .n_quadratures = 1,
    .start = start,
    .quadrature_rate = quadrature_rate,
    .step_globals = step_globals,
    .piece_globals = piece_globals,
    .charge = charge,
    .segment_values = segment_values,
};

/* The registry's two models and this one, the test's registry (the FMUs' registry is
   charge_registry.def: a row there is the same one line). */
static const tribo_charge_model *const MODELS[] = {&tribo_charge_static, &tribo_charge_sliding,
                                                   &constant_rate};
enum { CONSTANT = 2 };

static tribo_model *make_with_constant(int integrator)
{
    tribo_scene s = scene_of("epsilon=0.3 n_segments=500");
    s.integrator = integrator;
    const tribo_parts parts = {.charge_models = MODELS, .n_charge_models = 3,
                               .charge_selection = 7 /* all three */,
                               .integrator = tribo_integrator_of_kind(integrator)};
    char err[512];
    tribo_model *m = tribo_create_from_parts(&s, &parts, NULL, err, sizeof err);
    cr_assert(m, "%s", err);
    return m;
}

/* The constant-rate model's charges (n_segments values, to free), their sum, its global
   and its quadrature. */
static double *constant_state(tribo_model *m, double *sum, double *contact, double *slip)
{
    const tribo_charge_view v = tribo_charge_view_of(m, CONSTANT);
    double *values = malloc((size_t)v.n * sizeof *values);
    cr_assert(values);
    cr_assert_eq(tribo_get_segment_charges(m, (tribo_segment_charge)CONSTANT, values, (size_t)v.n),
                 TRIBO_OK);
    *sum = 0.0;
    for (int i = 0; i < v.n; i++)
        *sum += values[i];
    /* the sum the outputs read, kept up to date with each charge, is the values' sum up to
       its rounding (measured 9e-16 relative here; bound 100x that) */
    cr_expect(fabs(v.sum - *sum) <= 1e-13 * *sum, "running sum %.17g, sum %.17g", v.sum, *sum);
    *contact = v.globals[0];
    *slip = v.quadratures[0];
    return values;
}

Test(parts, test_charge_model_runs_through_both_integrators)
{
    double slips[2];
    for (int k = 0; k < 2; k++) {
        const int integrator = k ? TRIBO_INTEGRATOR_CVODE : TRIBO_INTEGRATOR_FIXED_STEP;
        tribo_model *m = make_with_constant(integrator);
        cr_assert_eq(tribo_advance_fully(m, 200.0), TRIBO_OK, "%s", tribo_last_error(m));
        double sum, contact, slip;
        free(constant_state(m, &sum, &contact, &slip));
        const double contact_time = tribo_get(m, TRIBO_QUANTITY_CONTACT_TIME);
        cr_assert(contact_time > 10.0, "contact time %g", contact_time);
        /* its global follows the contact exactly as the instance books it */
        cr_expect(fabs(contact - contact_time) <= 1e-9 * contact_time,
                  "integrator %d: global %.17g, contact time %.17g", integrator, contact,
                  contact_time);
        /* at least one segment charges all the time the particle touches (tau0 = 1) */
        cr_expect(sum >= contact_time * (1.0 - 1e-9), "integrator %d: sum %g < contact time %g",
                  integrator, sum, contact_time);
        /* the registry's models ran beside it, untouched */
        cr_expect(tribo_get(m, TRIBO_QUANTITY_STATIC) > 0.0 && tribo_get(m, TRIBO_QUANTITY_SLIDING) > 0.0);
        cr_expect(slip > 0.0);
        slips[k] = slip;
        tribo_free(m);
    }
    /* the quadrature, integrated with the motion by the fixed step and by the sweep along
       CVODE's dense output, agrees as far as the two integrators' motions do (their contact
       times differ by 1.4e-5 relative here, the slip distances by 1.6e-5: bound 6x that) */
    cr_expect(fabs(slips[0] - slips[1]) <= 1e-4 * slips[1], "slip distance: fixed %.9g, CVODE %.9g",
              slips[0], slips[1]);
}

Test(parts, test_charge_model_survives_state_save_and_load)
{
    for (int k = 0; k < 2; k++) {
        const int integrator = k ? TRIBO_INTEGRATOR_CVODE : TRIBO_INTEGRATOR_FIXED_STEP;
        tribo_model *a = make_with_constant(integrator), *b = make_with_constant(integrator);
        cr_assert_eq(tribo_advance(a, 37.31234), TRIBO_OK);
        const size_t n = tribo_state_size(a);
        void *bytes = malloc(n);
        cr_assert_eq(tribo_state_save(a, bytes, n), TRIBO_OK);
        cr_assert_eq(tribo_state_load(b, bytes, n), TRIBO_OK, "%s", tribo_last_error(b));
        free(bytes);
        advance_both(a, b, 120.0);
        double sa, ca, qa, sb, cb, qb;
        double *va = constant_state(a, &sa, &ca, &qa), *vb = constant_state(b, &sb, &cb, &qb);
        cr_expect(sa == sb && ca == cb && qa == qb,
                  "integrator %d: the loaded instance continues otherwise", integrator);
        cr_expect(memcmp(va, vb, 500 * sizeof(double)) == 0);
        free(va);
        free(vb);
        cr_expect(state_distance(a, b) == 0.0);
        tribo_free(a);
        tribo_free(b);
    }
}

/* ---- the integrator contract ---------------------------------------------------------------- */

/* The fixed step, except that its restart fails once `fail_restart` is set. */
static int fail_restart;
static tribo_status failing_restart(tribo_model *m, void *data)
{
    if (fail_restart)
        return tribo_fail(m, TRIBO_ERR_INTEGRATOR, "restart refused (test)");
    return tribo_fixed_step_ops.restart(m, data);
}

Test(parts, a_failed_restart_reaches_the_caller)
{
    tribo_integrator_ops ops = tribo_fixed_step_ops;
    ops.restart = failing_restart;
    tribo_scene s;
    tribo_scene_defaults(&s);
    s.integrator = TRIBO_INTEGRATOR_FIXED_STEP;
    tribo_parts parts = tribo_registry_parts(&s);
    parts.integrator = &ops;
    char err[512];
    fail_restart = 0;
    tribo_model *m = tribo_create_from_parts(&s, &parts, NULL, err, sizeof err);
    cr_assert(m, "%s", err);
    cr_assert_eq(tribo_advance(m, 1.0), TRIBO_OK);
    fail_restart = 1;
    cr_expect_eq(tribo_set_param(m, "mu", 0.3), TRIBO_ERR_INTEGRATOR);
    cr_expect_str_eq(tribo_last_error(m), "restart refused (test)");
    cr_expect_eq(tribo_set_external_force(m, 0.1, 0.0), TRIBO_ERR_INTEGRATOR);
    cr_expect_eq(tribo_reset(m), TRIBO_ERR_INTEGRATOR);
    /* and at creation, which resets */
    cr_expect_null(tribo_create_from_parts(&s, &parts, NULL, err, sizeof err));
    cr_expect_str_eq(err, "restart refused (test)");
    fail_restart = 0;
    tribo_free(m);
}

Test(parts, an_unknown_integrator_kind_is_refused)
{
    cr_expect_null(tribo_integrator_of_kind(3));
    cr_expect_null(tribo_integrator_of_kind(-1));
    tribo_scene s = scene_of("");
    s.integrator = 7; /* past the table's range too: set directly */
    const tribo_parts parts = tribo_registry_parts(&s);
    char err[512];
    cr_expect_null(tribo_create_from_parts(&s, &parts, NULL, err, sizeof err));
    cr_expect(strstr(err, "integrator"), "%s", err);
}

Test(parts, a_selection_beyond_the_model_set_is_refused)
{
    tribo_scene s = scene_of("");
    const tribo_parts parts = {.charge_models = MODELS, .n_charge_models = 3,
                               .charge_selection = 8};
    char err[512];
    cr_expect_null(tribo_create_from_parts(&s, &parts, NULL, err, sizeof err));
    cr_expect_str_eq(err, "charge models selected (bits 0x8) beyond the 3 of the set");
}

/* Scene validation: every parameter outside model.md §1's range, NaN or infinite is
   refused at creation with a message naming it, its value and the valid range. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "param_table.h"
#include "support.h"
#include "tribo.h"

Test(params, defaults_are_valid_and_are_the_papers)
{
    tribo_scene s;
    tribo_scene_defaults(&s);
    char msg[256] = "";
    cr_expect_eq(tribo_scene_validate(&s, msg, sizeof msg), TRIBO_OK, "%s", msg);
    cr_expect_eq(s.Gamma, 0.001);
    cr_expect_eq(s.beta, 45 * (M_PI / 180.0)); /* rad: the double the degrees gave */
    cr_expect_eq(s.n_segments, 2000);
    cr_expect_eq(s.dt, 8e-5);
    cr_expect_eq(s.integrator, TRIBO_INTEGRATOR_CVODE);
    cr_expect_eq(s.drop_speed, 0.025);
    cr_expect_eq(s.tau_r, s.tau0);
}

/* Values just outside each bound, and the non-numbers. */
static int bad_values(const tribo_param_info *p, double *out)
{
    int n = 0;
    out[n++] = NAN;
    if (!(p->max == INFINITY && p->max_inclusive)) /* a closed infinite bound admits it */
        out[n++] = INFINITY;
    out[n++] = -INFINITY;
    if (isfinite(p->min))
        out[n++] = p->min_inclusive ? p->min - fmax(1e-9, fabs(p->min) * 1e-9) - (p->type != TRIBO_TYPE_REAL ? 1 : 0) : p->min;
    if (isfinite(p->max))
        out[n++] = p->max_inclusive ? p->max + fmax(1e-9, fabs(p->max) * 1e-9) + (p->type != TRIBO_TYPE_REAL ? 1 : 0) : p->max;
    if (p->type != TRIBO_TYPE_REAL)
        out[n++] = p->min + 0.5;
    return n;
}

Test(params, every_invalid_value_is_refused_with_its_message)
{
    size_t count;
    const tribo_param_info *table = tribo_param_table(&count);
    cr_assert(count >= 21);
    int checked = 0;
    for (size_t i = 0; i < count; i++) {
        double values[8];
        const int n = bad_values(&table[i], values);
        for (int k = 0; k < n; k++) {
            tribo_scene s;
            tribo_scene_defaults(&s);
            if (table[i].type != TRIBO_TYPE_REAL && !isfinite(values[k]))
                continue; /* an int field cannot hold them; the FMU checks doubles first */
            tribo_param_write(&s, &table[i], values[k]);
            if (table[i].type != TRIBO_TYPE_REAL && tribo_param_read(&s, &table[i]) != values[k])
                continue; /* 0.5 truncates in the field: checked through tribo_param_check */
            char err[256] = "";
            tribo_model *m = tribo_create(&s, err, sizeof err);
            cr_expect_null(m, "%s = %g was accepted", table[i].name, values[k]);
            tribo_free(m);
            char value_text[64];
            snprintf(value_text, sizeof value_text, "%.17g", values[k]);
            cr_expect(strstr(err, table[i].name) == err, "'%s' does not start with the name %s", err,
                      table[i].name);
            cr_expect(strstr(err, value_text) != NULL, "'%s' does not give the value %s", err,
                      value_text);
            cr_expect(strstr(err, "valid range") != NULL, "'%s' does not give the range", err);
            checked++;
        }
        /* the same through the per-parameter check, integers included */
        for (int k = 0; k < n; k++) {
            char msg[256] = "";
            cr_expect_eq(tribo_param_check(&table[i], values[k], msg, sizeof msg),
                         TRIBO_ERR_INVALID_ARGUMENT, "%s = %g passed the check", table[i].name,
                         values[k]);
            cr_expect(strstr(msg, table[i].name) == msg);
        }
    }
    cr_expect(checked > 60, "%d invalid scenes tried", checked);
}

Test(params, the_ranges_of_model_section_1)
{
    struct {
        const char *name;
        double ok, bad;
    } cases[] = {
        {"epsilon", 1.0, 0.0},   {"epsilon", 1e-3, 1.0 + 1e-12}, {"mu", 0.0, -1e-12},
        {"nu", 0.0, -1e-12},     {"Gamma", 1e-9, 0.0},           {"beta", 0.0, M_PI / 2},
        {"beta", nextafter(M_PI / 2, 0.0), -1e-9}, {"tau0", 0.0, -1e-12},            {"Sigma0", 1e-9, 0.0},
        {"eta", 0.0, -1e-12},    {"tau_r", 1e-9, 0.0},           {"n_segments", 16, 15},
        {"v_reg", 1e-12, 0.0},   {"charge_model_static", 1, 2},  {"integrator", 2, 3},
        {"dt", 1e-3, 0.0},       {"gap0", 0.0, -1e-9},           {"drop_speed", 0.0, -1e-9},
        {"damping_point", 1, 2}, {"damping_point", 0, -1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const tribo_param_info *p = tribo_param_find(cases[i].name);
        cr_assert(p, "%s missing", cases[i].name);
        cr_expect_eq(tribo_param_check(p, cases[i].ok, NULL, 0), TRIBO_OK, "%s = %g", p->name,
                     cases[i].ok);
        cr_expect_eq(tribo_param_check(p, cases[i].bad, NULL, 0), TRIBO_ERR_INVALID_ARGUMENT,
                     "%s = %g", p->name, cases[i].bad);
    }
}

Test(params, only_tunables_change_mid_run)
{
    tribo_scene s = scene_of("n_segments=64");
    tribo_model *m = tribo_create(&s, NULL, 0);
    cr_assert(m);
    cr_assert_eq(tribo_advance(m, 1.0), TRIBO_OK);
    const char *tunable[] = {"mu", "nu", "eta", "tau0", "tau_r", "Sigma0"};
    for (int i = 0; i < 6; i++) {
        cr_expect_eq(tribo_set_param(m, tunable[i], 0.5), TRIBO_OK, "%s: %s", tunable[i],
                     tribo_last_error(m));
        cr_expect_eq(tribo_param_read(tribo_get_scene(m), tribo_param_find(tunable[i])), 0.5);
    }
    cr_expect_eq(tribo_set_param(m, "epsilon", 0.7), TRIBO_ERR_NOT_TUNABLE);
    cr_expect(strstr(tribo_last_error(m), "epsilon") != NULL);
    cr_expect_eq(tribo_set_param(m, "n_segments", 32), TRIBO_ERR_NOT_TUNABLE);
    cr_expect_eq(tribo_set_param(m, "damping_point", 1), TRIBO_ERR_NOT_TUNABLE);
    cr_expect_eq(tribo_set_param(m, "mu", -1.0), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(tribo_last_error(m), "mu = -1") != NULL, "%s", tribo_last_error(m));
    cr_expect_eq(tribo_set_param(m, "mu", NAN), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_set_param(m, "no_such", 1.0), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_get_scene(m)->mu, 0.5, "a refused value leaves the old one");
    cr_expect_eq(tribo_advance(m, 0.5), TRIBO_ERR_TIME, "no going back");
    cr_expect_eq(tribo_advance(m, NAN), TRIBO_ERR_TIME);
    cr_expect_eq(tribo_set_external_force(m, INFINITY, 0.0), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_advance(m, 2.0), TRIBO_OK, "still usable");
    cr_expect(isfinite(tribo_get(m, TRIBO_QUANTITY_X)));
    tribo_free(m);
}

Test(params, segment_charges_of_a_missing_model_are_refused)
{
    tribo_scene s = scene_of("n_segments=32");
    no_charge_models(&s);
    s.charge_model_static = 1;
    tribo_model *m = tribo_create(&s, NULL, 0);
    cr_assert(m);
    double out[32];
    cr_expect_eq(tribo_get_segment_charges(m, TRIBO_SEGMENTS_SLIDING, out, 32),
                 TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_get_segment_charges(m, TRIBO_SEGMENTS_STATIC, out, 31),
                 TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_get_segment_charges(m, TRIBO_SEGMENTS_STATIC, out, 32), TRIBO_OK);
    cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_SLIDING), 0.0);
    tribo_free(m);
}

/* Sigma0 is tunable (model.md §5b): a new value changes the sliding model's saturation
   target from then on, not the charge already on the particle. Q_sliding is normalised by
   Sigma0 at the start (Sigma0,ref), so it does not jump when Sigma0 doubles (it halved
   before), the absolute mean density Sigma_mean does not jump either, and Sigma_s then
   relaxes towards the new Sigma0 through contact, the charge following it. A reset starts
   from the new Sigma0. Both integrators. */
Test(params, tuning_Sigma0_moves_the_target_not_the_charge)
{
    for (int integrator = 0; integrator < 2; integrator++) {
        tribo_scene s = scene_of("epsilon=0.3 n_segments=400 dt=1e-3");
        s.integrator = integrator ? TRIBO_INTEGRATOR_CVODE : TRIBO_INTEGRATOR_FIXED_STEP;
        tribo_model *m = make(&s);
        cr_assert_eq(tribo_advance(m, 50.0), TRIBO_OK);
        const double Q = tribo_get(m, TRIBO_QUANTITY_SLIDING), mean = tribo_get(m, TRIBO_QUANTITY_SIGMA_MEAN);
        cr_assert(Q > 0.1, "charged to %g", Q);
        cr_expect_float_eq(mean, Q * s.Sigma0, 1e-15 * mean, "Sigma_mean = Q_sliding Sigma0");
        cr_assert_eq(tribo_set_param(m, "Sigma0", 2.0 * s.Sigma0), TRIBO_OK);
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_SLIDING), Q, "Q_sliding jumped at the change");
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_SIGMA_MEAN), mean);
        /* continuous after it: a short advance changes Q_sliding little */
        cr_assert_eq(tribo_advance(m, 50.01), TRIBO_OK);
        cr_expect(fabs(tribo_get(m, TRIBO_QUANTITY_SLIDING) - Q) < 0.01 * Q, "Q_sliding %g after %g",
                  tribo_get(m, TRIBO_QUANTITY_SLIDING), Q);
        /* the new target: Sigma_s relaxes towards 2 Sigma0 in contact, and the charge with it */
        cr_assert_eq(tribo_advance(m, 100.0), TRIBO_OK);
        cr_expect(tribo_get(m, TRIBO_QUANTITY_SIGMA_S) > 1.5 * s.Sigma0, "Sigma_s = %g",
                  tribo_get(m, TRIBO_QUANTITY_SIGMA_S));
        cr_expect(tribo_get(m, TRIBO_QUANTITY_SLIDING) > 1.2 * Q, "Q_sliding %g after %g",
                  tribo_get(m, TRIBO_QUANTITY_SLIDING), Q);
        cr_expect_float_eq(tribo_get(m, TRIBO_QUANTITY_SIGMA_MEAN), tribo_get(m, TRIBO_QUANTITY_SLIDING) * s.Sigma0,
                           1e-14 * tribo_get(m, TRIBO_QUANTITY_SIGMA_MEAN), "still normalised by the start's");
        cr_assert_eq(tribo_reset(m), TRIBO_OK);
        cr_assert_eq(tribo_advance(m, 50.0), TRIBO_OK);
        cr_expect_float_eq(tribo_get(m, TRIBO_QUANTITY_SIGMA_MEAN), tribo_get(m, TRIBO_QUANTITY_SLIDING) * 2.0 * s.Sigma0,
                           1e-14 * tribo_get(m, TRIBO_QUANTITY_SIGMA_MEAN), "a reset starts from the new Sigma0");
        tribo_free(m);
    }
}

Test(params, a_message_finds_a_parameters_name_and_its_choices_in_the_table)
{
    size_t n;
    const tribo_param_info *rows = tribo_param_table(&n);
    for (size_t i = 0; i < n; i++)
        cr_expect_eq(tribo_param_of_field(rows[i].offset), &rows[i], "%s", rows[i].name);
    cr_expect_str_eq(TRIBO_PARAM_NAME(work_limit), "work_limit");
    cr_expect_str_eq(TRIBO_PARAM_ITEM_NAME(run_end, TRIBO_RUN_END_FIRST_LIFTOFF), "first_liftoff");
    cr_expect_str_eq(TRIBO_PARAM_ITEM_NAME(integrator, TRIBO_INTEGRATOR_CVODE_BDF), "cvode_bdf");
    /* a number has no items; an enumeration has no item past its last */
    cr_expect_str_eq(TRIBO_PARAM_ITEM_NAME(mu, 0), "?");
    cr_expect_str_eq(TRIBO_PARAM_ITEM_NAME(run_end, 2), "?");
}

Test(params, the_removed_charge_model_is_refused_naming_the_switches)
{
    /* the selection as one enumeration of subsets is gone: each model has its switch */
    tribo_scene s = scene_of("");
    char err[512];
    cr_expect_eq(tribo_scene_set(&s, "charge_model", 3, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "charge_model was removed") && strstr(err, "charge_model_static") &&
                  strstr(err, "charge_model_sliding") && !strchr(err, '\n'),
              "%s", err);
    cr_expect_eq(tribo_scene_apply(&s, "mu=0.2 charge_model=1", err, sizeof err),
                 TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "charge_model was removed"), "%s", err);
    tribo_model *m = make(&s);
    cr_expect_eq(tribo_set_param(m, "charge_model", 1), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(tribo_last_error(m), "charge_model was removed"), "%s", tribo_last_error(m));
    tribo_free(m);
    /* a name never in the table is unknown, as before */
    cr_expect_eq(tribo_scene_set(&s, "charge_models", 3, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_str_eq(err, "unknown parameter 'charge_models'");
}

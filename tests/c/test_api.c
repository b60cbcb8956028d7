/* The C API's constructors and entries given NULL where they need an object: each refuses
   it with an error (a status, a NULL instance with its reason, NaN), none dereferences it. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "model.h"
#include "separator.h"
#include "si.h"
#include "support.h"

Test(api, the_constructors_refuse_a_null_scene_or_parts_saying_so)
{
    char err[256] = "";
    cr_expect_null(tribo_create(NULL, err, sizeof err));
    cr_expect_str_eq(err, "scene is NULL");
    cr_expect_null(tribo_create(NULL, NULL, 0)); /* no room for the reason: still refused */
    cr_expect_null(tribo_create_like(NULL, NULL, err, sizeof err));
    cr_expect_str_eq(err, "scene is NULL");

    const tribo_scene s = scene_of("");
    cr_expect_null(tribo_create_from_parts(&s, NULL, NULL, err, sizeof err));
    cr_expect_str_eq(err, "parts is NULL");
    const tribo_parts parts = tribo_registry_parts(&s);
    cr_expect_null(tribo_create_from_parts(NULL, &parts, NULL, err, sizeof err));
    cr_expect_str_eq(err, "scene is NULL");

    cr_expect_null(tribo_separator_create(NULL, err, sizeof err));
    cr_expect_str_eq(err, "scene is NULL");

    tribo_si_derived d;
    cr_expect_eq(tribo_si_derive(NULL, &d, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_str_eq(err, "scene is NULL");
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    cr_expect_eq(tribo_si_derive(&si, NULL, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "NULL"), "%s", err);
    tribo_separator_scene sep;
    tribo_separator_scene_defaults(&sep);
    cr_expect_eq(tribo_separator_derive(&sep, NULL, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(strstr(err, "NULL"), "%s", err);
}

Test(api, an_invalid_scene_is_refused_with_the_one_message_of_its_validation)
{
    /* tribo_create leaves the validation to tribo_create_from_parts: one message, the
       scene's own */
    tribo_scene s = scene_of("");
    s.epsilon = 2.0;
    char err[256], expected[256];
    cr_expect_null(tribo_create(&s, err, sizeof err));
    cr_expect_eq(tribo_scene_validate(&s, expected, sizeof expected), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_str_eq(err, expected);
    /* an integrator kind past the table's range is the range's message, not a missing
       integrator's */
    s = scene_of("");
    s.integrator = 7;
    cr_expect_null(tribo_create(&s, err, sizeof err));
    cr_expect(strstr(err, "integrator = 7 is invalid"), "%s", err);
}

Test(api, the_scene_entries_refuse_a_null_scene)
{
    char err[256];
    cr_expect_eq(tribo_scene_set(NULL, "mu", 0.2, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_str_eq(err, "scene is NULL");
    cr_expect_eq(tribo_scene_apply(NULL, "mu=0.2", err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_str_eq(err, "scene is NULL");
    cr_expect_eq(tribo_scene_validate(NULL, err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_str_eq(err, "scene is NULL");
    cr_expect_eq(tribo_si_scene_apply(NULL, "mu=0.2", err, sizeof err), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_separator_scene_set(NULL, "voltage", 1.0, err, sizeof err),
                 TRIBO_ERR_INVALID_ARGUMENT);
    tribo_scene_defaults(NULL);
    tribo_si_scene_defaults(NULL);
    tribo_separator_scene_defaults(NULL);
}

Test(api, the_instance_entries_refuse_a_null_instance)
{
    const double inputs[TRIBO_INPUT_COUNT] = {0};
    double buffer[64];
    cr_expect_eq(tribo_reset(NULL), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_advance(NULL, 1.0), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_advance_fully(NULL, 1.0), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_set_param(NULL, "mu", 0.2), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_set_inputs(NULL, inputs), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_set_external_force(NULL, 0.0, 0.0), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_get_segment_charges(NULL, TRIBO_SEGMENTS_STATIC, buffer, 64),
                 TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_state_save(NULL, buffer, sizeof buffer), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_state_load(NULL, buffer, sizeof buffer), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_state_size(NULL), 0);
    cr_expect(isnan(tribo_get(NULL, TRIBO_QUANTITY_X)));
    cr_expect(isnan(tribo_get_mean_charge(NULL, TRIBO_SEGMENTS_STATIC)));
    cr_expect_not(tribo_includes_charge_model(NULL, TRIBO_SEGMENTS_STATIC));
    cr_expect_null(tribo_get_scene(NULL));
    cr_expect_str_eq(tribo_last_error(NULL), "the instance is NULL");
    tribo_stats stats = {.steps = 5};
    tribo_get_stats(NULL, &stats);
    cr_expect_eq(stats.steps, 0);
    tribo_set_logger(NULL, NULL, NULL);
    tribo_free(NULL);

    const double separator_inputs[TRIBO_SEPARATOR_INPUT_COUNT] = {0};
    cr_expect_eq(tribo_separator_set_inputs(NULL, separator_inputs), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_separator_advance(NULL, 1.0), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_separator_state_save(NULL, buffer, sizeof buffer), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_eq(tribo_separator_state_load(NULL, buffer, sizeof buffer), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect(isnan(tribo_separator_get(NULL, (tribo_separator_quantity)0)));
    cr_expect_str_eq(tribo_separator_last_error(NULL), "the instance is NULL");
    tribo_separator_free(NULL);
}

Test(api, null_arrays_given_to_an_instance_are_refused_with_its_message)
{
    const tribo_scene s = scene_of("n_segments=32");
    tribo_model *model = make(&s);
    cr_expect_eq(tribo_set_inputs(model, NULL), TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_str_eq(tribo_last_error(model), "the inputs' values are NULL");
    cr_expect_eq(tribo_get_segment_charges(model, TRIBO_SEGMENTS_STATIC, NULL, 32),
                 TRIBO_ERR_INVALID_ARGUMENT);
    cr_expect_str_eq(tribo_last_error(model), "the segment array to copy into is NULL");
    /* and the instance goes on */
    cr_expect_eq(tribo_advance(model, 1.0), TRIBO_OK, "%s", tribo_last_error(model));
    tribo_free(model);
}

Test(api, the_readers_of_a_null_scene_or_set_up_give_no_number)
{
    const tribo_param_info *mu = tribo_param_find("mu");
    cr_expect(isnan(tribo_param_read(NULL, mu)));
    tribo_param_write(NULL, mu, 0.2);
    cr_expect(isnan(tribo_si_segment_factor(NULL, TRIBO_SEGMENTS_STATIC)));
    cr_expect(isnan(tribo_si_get(NULL, NULL, TRIBO_SI_QUANTITY_T_STAR)));
    tribo_si_derived d;
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    cr_assert_eq(tribo_si_derive(&si, &d, NULL, 0), TRIBO_OK);
    cr_expect(isnan(tribo_si_segment_factor(&d, TRIBO_SEGMENTS_COUNT)));
    cr_expect(isnan(tribo_separator_calculated(NULL, (tribo_separator_quantity)0)));
    cr_expect(isnan(tribo_separator_reynolds(NULL)));
    cr_expect_eq(tribo_separator_bin(NULL), 0);
    cr_expect_eq(tribo_separator_bin_of(NULL, 0.0), 0);
    cr_expect_null(tribo_separator_get_scene(NULL));
    cr_expect_null(tribo_separator_get_derived(NULL));
}

/* An instance made like another is the one tribo_create makes, whatever it is like: the same
   roundness (whose boundary table it copies), another, one that charges nothing, none; its run
   gives the same outputs and segment charges, bit for bit. */
Test(api, an_instance_made_like_another_runs_as_one_made_alone)
{
    const tribo_scene s = scene_of("epsilon=0.6 n_segments=48 Omega0=2");
    tribo_scene uncharged = s;
    no_charge_models(&uncharged);
    const tribo_scene likes[] = {s, scene_of("epsilon=0.3 n_segments=48"), uncharged};
    char err[256] = "";
    for (int k = 0; k <= 3; k++) {
        tribo_model *like = k < 3 ? make(&likes[k]) : NULL;
        tribo_model *alone = make(&s), *made = tribo_create_like(&s, like, err, sizeof err);
        cr_assert_not_null(made, "like %d: %s", k, err);
        if (like)
            cr_assert_eq(tribo_advance(like, 3.0), TRIBO_OK); /* what it has run is not taken */
        advance_both(alone, made, 12.0);
        cr_expect(same_outputs(alone, made), "like %d: the outputs differ", k);
        for (int which = 0; which < TRIBO_SEGMENTS_COUNT; which++) {
            if (!tribo_includes_charge_model(alone, which))
                continue;
            double a[48], b[48];
            cr_assert_eq(tribo_get_segment_charges(alone, which, a, 48), TRIBO_OK);
            cr_assert_eq(tribo_get_segment_charges(made, which, b, 48), TRIBO_OK);
            cr_expect_eq(memcmp(a, b, sizeof a), 0, "like %d: model %d's charges differ", k, which);
        }
        tribo_free(alone);
        tribo_free(made);
        tribo_free(like);
    }
}

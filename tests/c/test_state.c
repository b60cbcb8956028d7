/* The state out and back in, and instances side by side: bit-identical continuation. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

/* Every test here runs under each integrator. */
static const int INTEGRATORS[] = {TRIBO_INTEGRATOR_FIXED_STEP, TRIBO_INTEGRATOR_CVODE,
                                  TRIBO_INTEGRATOR_CVODE_BDF};
#define FOR_EACH_INTEGRATOR for (int integ = 0; integ < 3; integ++)

static tribo_scene scene_with(int integrator)
{
    tribo_scene s = scene_of("epsilon=0.4 dt=2e-4 n_segments=300");
    s.mu = s.nu = 1.0;
    s.integrator = integrator;
    return s;
}
#define scene() scene_with(INTEGRATORS[integ])


/* Every quantity and both segment arrays, bit for bit. */
static void expect_same(tribo_model *a, tribo_model *b, const char *what)
{
    for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++) {
        const double x = tribo_get(a, q), y = tribo_get(b, q);
        cr_expect(memcmp(&x, &y, sizeof x) == 0, "%s: %s differs: %.17g vs %.17g", what,
                  tribo_quantity_name(q), x, y);
    }
    const int n = tribo_get_scene(a)->n_segments;
    double *u = malloc(2 * n * sizeof *u);
    for (int k = 0; k < 2; k++) {
        cr_assert_eq(tribo_get_segment_charges(a, k, u, n), TRIBO_OK);
        cr_assert_eq(tribo_get_segment_charges(b, k, u + n, n), TRIBO_OK);
        cr_expect(memcmp(u, u + n, n * sizeof *u) == 0, "%s: segment charges %d differ", what, k);
    }
    free(u);
}

/* A new instance of the scene, advanced to t. */
static tribo_model *made_and_run(const tribo_scene *s, double t)
{
    tribo_model *m = make(s);
    cr_assert_eq(tribo_advance(m, t), TRIBO_OK, "%s", tribo_last_error(m));
    return m;
}

Test(state, copy_out_and_in_continues_bit_identically)
{
    FOR_EACH_INTEGRATOR {
        tribo_scene s = scene();
        /* off the step grid, so that the saved point carries a partial step */
        tribo_model *a = made_and_run(&s, 3.00013);
        size_t n;
        unsigned char *saved = saved_state(a, &n);
        cr_assert_eq(tribo_advance(a, 10.0), TRIBO_OK);

        tribo_model *b = make(&s); /* a fresh instance */
        cr_assert_eq(tribo_state_load(b, saved, n), TRIBO_OK, "%s", tribo_last_error(b));
        cr_expect_eq(tribo_get(b, TRIBO_QUANTITY_TIME), 3.00013);
        cr_assert_eq(tribo_advance(b, 10.0), TRIBO_OK);
        expect_same(a, b, "restored instance");

        /* and back into the first instance, after it has moved on */
        cr_assert_eq(tribo_state_load(a, saved, n), TRIBO_OK);
        cr_assert_eq(tribo_advance(a, 10.0), TRIBO_OK);
        expect_same(a, b, "rewound instance");

        /* the saved bytes of equal states are equal */
        unsigned char *again_a = malloc(n), *again_b = malloc(n);
        cr_assert_eq(tribo_state_save(a, again_a, n), TRIBO_OK);
        cr_assert_eq(tribo_state_save(b, again_b, n), TRIBO_OK);
        cr_expect(memcmp(again_a, again_b, n) == 0);
        free(saved);
        free(again_a);
        free(again_b);
        tribo_free(a);
        tribo_free(b);
    }
}

Test(state, tunables_and_inputs_travel_with_the_state)
{
    FOR_EACH_INTEGRATOR {
        tribo_scene s = scene();
        tribo_model *a = made_and_run(&s, 2.0);
        cr_assert_eq(tribo_set_param(a, "mu", 0.3), TRIBO_OK);
        cr_assert_eq(tribo_set_external_force(a, 1e-4, -2e-4), TRIBO_OK);
        size_t n;
        unsigned char *saved = saved_state(a, &n);
        tribo_model *b = make(&s);
        cr_assert_eq(tribo_state_load(b, saved, n), TRIBO_OK);
        cr_expect_eq(tribo_get_scene(b)->mu, 0.3);
        advance_both(a, b, 6.0);
        expect_same(a, b, "with tunables and inputs");
        cr_expect(tribo_get(a, TRIBO_QUANTITY_WORK_EXTERNAL) != 0.0);
        free(saved);
        tribo_free(a);
        tribo_free(b);
    }
}

Test(state, foreign_or_corrupt_state_is_refused)
{
    FOR_EACH_INTEGRATOR {
        tribo_scene s = scene();
        tribo_model *a = made_and_run(&s, 1.0);
        size_t n;
        unsigned char *saved = saved_state(a, &n);
        cr_expect_eq(tribo_state_save(a, saved, n - 1), TRIBO_ERR_INVALID_ARGUMENT);

        tribo_scene other = s;
        other.epsilon = 0.41;
        tribo_model *b = make(&other);
        cr_expect_eq(tribo_state_load(b, saved, n), TRIBO_ERR_STATE);
        cr_expect(strstr(tribo_last_error(b), "epsilon") != NULL, "%s", tribo_last_error(b));
        cr_expect_eq(tribo_state_load(a, saved, n - 8), TRIBO_ERR_STATE);
        saved[0] ^= 0xff;
        cr_expect_eq(tribo_state_load(a, saved, n), TRIBO_ERR_STATE);
        cr_expect_eq(tribo_advance(a, 2.0), TRIBO_OK, "a refused load leaves the instance usable");
        free(saved);
        tribo_free(a);
        tribo_free(b);
    }
}

/* The committed integration does not depend on the times asked for: 250 advances by
   h = 0.0123 (not a multiple of dt) end exactly where one advance to 250 h does. */
Test(state, many_advances_equal_one)
{
    FOR_EACH_INTEGRATOR {
        tribo_scene s = scene();
        tribo_model *a = make(&s), *b = make(&s);
        const double h = 0.0123;
        for (int k = 1; k <= 250; k++) {
            cr_assert_eq(tribo_advance(a, k * h), TRIBO_OK);
            (void)tribo_get(a, TRIBO_QUANTITY_STATIC); /* reading must not disturb either */
        }
        cr_assert_eq(tribo_advance(b, 250 * h), TRIBO_OK);
        expect_same(a, b, "stepwise vs at once");
        tribo_free(a);
        tribo_free(b);
    }
}

Test(state, interleaved_instances_equal_each_alone)
{
    FOR_EACH_INTEGRATOR {
        tribo_scene s1 = scene(), s2 = scene();
        s2.epsilon = 0.8;
        s2.mu = s2.nu = 0.1;
        tribo_model *a = make(&s1), *b = make(&s2);
        for (int k = 1; k <= 40; k++) {
            advance_both(a, b, 0.25 * k);
        }
        tribo_model *a_alone = make(&s1), *b_alone = make(&s2);
        advance_both(a_alone, b_alone, 10.0);
        expect_same(a, a_alone, "first instance");
        expect_same(b, b_alone, "second instance");
        tribo_free(a);
        tribo_free(b);
        tribo_free(a_alone);
        tribo_free(b_alone);
    }
}

Test(state, reset_reruns_identically)
{
    FOR_EACH_INTEGRATOR {
        tribo_scene s = scene();
        tribo_model *a = make(&s), *b = make(&s);
        cr_assert_eq(tribo_advance(a, 4.0), TRIBO_OK);
        cr_assert_eq(tribo_reset(a), TRIBO_OK);
        cr_expect_eq(tribo_get(a, TRIBO_QUANTITY_TIME), 0.0);
        cr_expect_eq(tribo_get(a, TRIBO_QUANTITY_STATIC), 0.0);
        advance_both(a, b, 4.0);
        expect_same(a, b, "after reset");
        tribo_free(a);
        tribo_free(b);
    }
}

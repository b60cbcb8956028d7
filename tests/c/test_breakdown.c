/* The air-breakdown limit of a segment's charge density (model.md §8b) through whole runs:
   the limit holds and books what it takes, the default is the paper's model bit for bit,
   and the SI front end's default limit caps its physical runs. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "si.h"
#include "support.h"

/* A sliding run that would raise its segments past the limit, through both integrators and a
   save and load: no segment stands above it, some stand at it, and the charge lost is
   booked, restored with the state. */
Test(breakdown, a_sliding_run_stays_at_the_limit_and_books_the_lost_charge)
{
    for (int integrator = 0; integrator < 2; integrator++) {
        tribo_scene s = scene_of("epsilon=0.3 mu=1 nu=1 n_segments=400 charge_model_static=0 Sigma_bd=0.005 dt=1e-3");
        s.integrator = integrator;
        char err[512];
        tribo_model *m = tribo_create(&s, err, sizeof err);
        cr_assert(m, "%s", err);
        cr_assert_eq(tribo_advance_fully(m, 50.0), TRIBO_OK, "%s", tribo_last_error(m));
        const size_t size = tribo_state_size(m);
        void *saved = malloc(size);
        cr_assert_eq(tribo_state_save(m, saved, size), TRIBO_OK);
        cr_assert_eq(tribo_advance_fully(m, 100.0), TRIBO_OK, "%s", tribo_last_error(m));
        /* the values are Sigma_i / Sigma0,ref, Sigma0,ref = 0.01: the bound is 0.5 */
        double v[400], top = 0.0;
        cr_assert_eq(tribo_get_segment_charges(m, TRIBO_SEGMENTS_SLIDING, v, 400), TRIBO_OK);
        for (int i = 0; i < 400; i++)
            top = fmax(top, v[i]);
        cr_expect(top == 0.005 / 0.01, "integrator %d: top %.17g", integrator, top);
        const double fraction = tribo_get(m, TRIBO_QUANTITY_CAPPED_SLIDING);
        const double lost = tribo_get(m, TRIBO_QUANTITY_LOST_SLIDING);
        cr_expect(fraction > 0.0 && fraction < 1.0, "integrator %d: fraction %g", integrator, fraction);
        cr_expect(lost > 0.0, "integrator %d: lost %g", integrator, lost);
        cr_expect(tribo_get(m, TRIBO_QUANTITY_SIGMA_S) > 0.005, "the saturation is above the limit");
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_CAPPED_STATIC), 0.0); /* left out */
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_LOST_STATIC), 0.0);
        /* loaded, the run goes on to the same charges and the same loss, bit for bit */
        cr_assert_eq(tribo_state_load(m, saved, size), TRIBO_OK, "%s", tribo_last_error(m));
        cr_assert_eq(tribo_advance_fully(m, 100.0), TRIBO_OK, "%s", tribo_last_error(m));
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_LOST_SLIDING), lost);
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_CAPPED_SLIDING), fraction);
        free(saved);
        tribo_free(m);
    }
}

/* Without a limit (Sigma_bd = INF, the default) the model is the paper's: a limit that is
   never reached changes no output, not a bit, and books nothing. */
Test(breakdown, the_default_is_the_papers_model_bit_for_bit)
{
    tribo_scene s = scene_of("epsilon=0.3 mu=1 nu=1 n_segments=400");
    cr_assert(isinf(s.Sigma_bd));
    tribo_scene far = s;
    far.Sigma_bd = 1e300;
    char err[512];
    tribo_model *a = tribo_create(&s, err, sizeof err), *b = tribo_create(&far, err, sizeof err);
    cr_assert(a && b, "%s", err);
    cr_assert_eq(tribo_advance_fully(a, 100.0), TRIBO_OK);
    cr_assert_eq(tribo_advance_fully(b, 100.0), TRIBO_OK);
    for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++) {
        const double x = tribo_get(a, (tribo_quantity)q), y = tribo_get(b, (tribo_quantity)q);
        cr_expect(memcmp(&x, &y, sizeof x) == 0, "%s: %a against %a",
                  tribo_quantity_name((tribo_quantity)q), x, y);
    }
    cr_expect_eq(tribo_get(a, TRIBO_QUANTITY_LOST_SLIDING), 0.0);
    cr_expect_eq(tribo_get(a, TRIBO_QUANTITY_CAPPED_STATIC), 0.0);
    tribo_free(a);
    tribo_free(b);
}

/* The SI reference case (si_quantities.def's defaults: breakdown_density = 2.7e-5 C/m2) on
   a 0.3 m chute: the sliding model's densities would pass the limit (tests/regression's
   physical runs did before it); with it, none stands above 2.7e-5 C/m2, and some at it. */
Test(breakdown, the_si_default_caps_a_physical_run)
{
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    si.chute_length = 0.3;
    si.n_segments = 400;
    tribo_si_derived d;
    char err[512];
    cr_assert_eq(tribo_si_derive(&si, &d, err, sizeof err), TRIBO_OK, "%s", err);
    cr_expect_float_eq(d.scene.Sigma_bd, 2.7e-5 / d.sigma_scale, 1e-15 * d.scene.Sigma_bd);
    tribo_model *m = tribo_create(&d.scene, err, sizeof err);
    cr_assert(m, "%s", err);
    const tribo_status st = tribo_advance_fully(m, 0.5 / d.t_star);
    cr_assert(st == TRIBO_OK || st == TRIBO_ENDED, "%s", tribo_last_error(m));
    double *v = malloc(400 * sizeof *v), top = 0.0;
    cr_assert_eq(tribo_get_segment_charges(m, TRIBO_SEGMENTS_SLIDING, v, 400), TRIBO_OK);
    const double factor = tribo_si_segment_factor(&d, TRIBO_SEGMENTS_SLIDING);
    for (int i = 0; i < 400; i++)
        top = fmax(top, fabs(factor * v[i]));
    free(v);
    /* the bound, through Sigma_bd and back: to rounding */
    cr_expect(top <= 2.7e-5 * (1 + 1e-14) && top >= 2.7e-5 * (1 - 1e-14), "top %.17g", top);
    cr_expect(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_CAPPED_SLIDING) > 0.0);
    cr_expect(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_LOST_SLIDING) != 0.0);
    /* the static model's sigma0 = -1e-5 C/m2 stays below the limit */
    cr_expect_eq(tribo_si_get(&d, m, TRIBO_SI_QUANTITY_CAPPED_STATIC), 0.0);
    tribo_free(m);
}

/* Contact edge cases that once went wrong, with what went wrong asserted: a stiff normal lock
   under the fixed step, a particle set down at rest, a grazing stick-to-slip, a deep
   indentation. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "support.h"



/* The fixed step's regularised sign is stiff in normal lock (rate nu delta_y / v_reg):
   a soft contact (Gamma = 0.5) hit hard with nu = 1 once blew RK4 up at the paper's
   dt = 8e-5 (lambda dt ~ 3e3). It now sub-steps and agrees with CVODE. */
Test(contact_edge_cases, fixed_step_stable_in_a_stiff_normal_lock, .timeout = 120)
{
    tribo_scene s = scene_of("Gamma=0.5 drop_speed=1.0 nu=1.0");
    no_charge_models(&s);
    tribo_model *fixed, *cvode;
    make_fixed_and_cvode(s, &fixed, &cvode);
    advance_both(fixed, cvode, 5.0);
    tribo_stats st;
    tribo_get_stats(fixed, &st);
    cr_expect(st.substeps > 0, "the stiff lock was sub-stepped");
    cr_expect(state_distance(fixed, cvode) < 1e-3, "distance %.3g", state_distance(fixed, cvode));
    cr_expect(isfinite(tribo_get(fixed, TRIBO_QUANTITY_ENERGY)));
    tribo_free(fixed);
    tribo_free(cvode);
}

/* A particle set down on the plate at rest (drop speed 0): CVODE once started it in
   flight, its contact root zero at the start and a small step later, and let it fall
   through the plate; then, in contact, started it sticking where it slips (the stick /
   slip test tied at first order). It now agrees with the fixed step. */
Test(contact_edge_cases, particle_set_down_at_rest)
{
    tribo_scene s = scene_of("drop_speed=0.0 n_segments=400");
    tribo_model *fixed, *cvode;
    make_fixed_and_cvode(s, &fixed, &cvode);
    for (int k = 1; k <= 40; k++) {
        cr_assert_eq(tribo_advance(cvode, 0.5 * k), TRIBO_OK);
        cr_assert_eq(tribo_get(cvode, TRIBO_QUANTITY_IN_CONTACT), 1.0, "t = %g: left the plate", 0.5 * k);
        cr_assert(tribo_get(cvode, TRIBO_QUANTITY_DELTA_Y) < 0.01, "t = %g: sank in by %g", 0.5 * k,
                  tribo_get(cvode, TRIBO_QUANTITY_DELTA_Y));
        cr_assert(fabs(tribo_get(cvode, TRIBO_QUANTITY_DELTA_X)) <=
                  s.mu * tribo_get(cvode, TRIBO_QUANTITY_PSI_N) * (1 + 1e-9));
    }
    cr_assert_eq(tribo_advance(fixed, 20.0), TRIBO_OK);
    /* the fixed step's regularised lock creeps at |V| < 2 v_reg (measured 2.5e-6 here);
       the broken start was 30% off in X */
    cr_expect(state_distance(fixed, cvode) < 2.0 * s.v_reg * 20.0, "distance %.3g", state_distance(fixed, cvode));
    cr_expect(fabs(tribo_get(fixed, TRIBO_QUANTITY_STATIC) - tribo_get(cvode, TRIBO_QUANTITY_STATIC)) < 1e-4,
              "Q_static %g vs %g", tribo_get(fixed, TRIBO_QUANTITY_STATIC), tribo_get(cvode, TRIBO_QUANTITY_STATIC));
    tribo_free(fixed);
    tribo_free(cvode);
}

/* In stick under normal lock the undamped tangential oscillation can graze the
   (constant) Coulomb limit within one CVODE step; the switch was once missed and the
   stretch went 1.5e-4 past the limit. Sampled finely, it never leaves it. */
Test(contact_edge_cases, grazing_stick_to_slip_is_seen)
{
    tribo_scene s = scene_of("epsilon=0.01 mu=10.0 nu=3.0");
    no_charge_models(&s);
    s.integrator = TRIBO_INTEGRATOR_CVODE;
    tribo_model *m = make(&s);
    double closest = 0.0;
    for (int k = 1; k <= 5000; k++) {
        cr_assert_eq(tribo_advance(m, 0.01 * k), TRIBO_OK);
        const double dx = fabs(tribo_get(m, TRIBO_QUANTITY_DELTA_X)), L = s.mu * tribo_get(m, TRIBO_QUANTITY_PSI_N);
        cr_assert(dx <= L * (1 + 1e-9), "t = %g: |delta_x| = %.9g > mu Psi_N = %.9g", 0.01 * k, dx, L);
        if (L > 0)
            closest = fmax(closest, dx / L);
    }
    cr_expect(closest > 0.999, "the stretch came to %.6f of the limit", closest);
    tribo_free(m);
}

/* With the centre dashpot (damping_point = 1) at nu = 1 a particle turning over in normal
   lock indents far beyond the contact model's assumptions (delta_y ~ 0.4 for eps = 0.6):
   it is counted and reported through the logger as a warning, not returned quietly. */
static int warnings;
static char last_warning[512];
static void logger(void *user, int level, const char *msg)
{
    (void)user;
    if (level == 1) {
        warnings++;
        snprintf(last_warning, sizeof last_warning, "%s", msg);
    }
}

Test(contact_edge_cases, deep_indentation_is_reported)
{
    tribo_scene s = scene_of("epsilon=0.6 damping_point=1");
    s.mu = s.nu = 1.0;
    no_charge_models(&s);
    s.integrator = TRIBO_INTEGRATOR_CVODE;
    tribo_model *m = make(&s);
    warnings = 0;
    tribo_set_logger(m, logger, NULL);
    cr_assert_eq(tribo_advance(m, 100.0), TRIBO_OK);
    const double counted = tribo_get(m, TRIBO_QUANTITY_ASSUMPTION_WARNINGS);
    cr_expect(counted >= 1, "counted %g", counted);
    cr_expect_eq(warnings, (int)fmin(counted, 10), "logged %d of %g", warnings, counted);
    cr_expect(strstr(last_warning, "delta_y") && strstr(last_warning, "rho_c"), "%s", last_warning);
    /* the paper's low-friction drop stays within the assumptions */
    tribo_scene low;
    tribo_scene_defaults(&low);
    low.integrator = TRIBO_INTEGRATOR_CVODE;
    no_charge_models(&low);
    tribo_model *ok = make(&low);
    cr_assert_eq(tribo_advance(ok, 100.0), TRIBO_OK);
    cr_expect_eq(tribo_get(ok, TRIBO_QUANTITY_ASSUMPTION_WARNINGS), 0.0);
    tribo_free(m);
    tribo_free(ok);
}

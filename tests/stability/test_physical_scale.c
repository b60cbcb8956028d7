/* The stability checks of the matrix (matrix.h) on physical set-ups through the SI front end
   (docs/model.md §8, §9): the SI reference case (a 1 mm polyethylene grain dropped 10 mm
   onto a 0.3 m steel chute at 30 degrees) and a micro-scale one (a = 50 um) with every
   integrator, and a grid of Young's moduli (1 MPa .. 400 GPa) and sizes (10 um .. 10 mm)
   with CVODE: each runs from the drop to the chute's exit with finite outputs (SI ones too),
   0 <= Q_static <= 1 non-decreasing, the Coulomb limit, no indentation in flight, its energy
   balanced and its work bounded, or is refused with a message naming the SI inputs. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "physical_scale.h"

/* Every set-up here leaves the 0.3 m chute within 0.5 s (the reference case at 0.479 s,
   the grid's between 0.44 and 0.49 s with CVODE); 5 s is a bound, not a target. */
#define T_END_S 5.0
#define EVERY_S 1e-3

static void expect_stable(const stability_result *res, const char *what)
{
    cr_assert(res->finished, "%s: stopped: %s", what, res->error);
    cr_expect(res->all_finite, "%s: a quantity went NaN or infinite", what);
    cr_expect(res->charge_ok, "%s: Q_static left [0, 1] or decreased", what);
    cr_expect(res->coulomb_ok, "%s: the stretch left the Coulomb limit", what);
    cr_expect(res->contact_ok, "%s: indented while in flight", what);
    cr_expect(res->max_residual <= STABILITY_RESIDUAL_BOUND * res->energy_scale,
              "%s: energy residual %.3g, scale %.3g", what, res->max_residual, res->energy_scale);
    cr_expect(res->work <= STABILITY_WORK_BOUND, "%s: %.3g units of work", what, res->work);
}

static void derive(const char *settings, tribo_si_derived *d)
{
    char msg[1024];
    cr_assert_eq(physical_derive(settings, d, msg, sizeof msg), TRIBO_OK, "%s: %s", settings, msg);
}

/* ---- the reference case and the micro-scale one, every CVODE variant to the exit ------- */

/* (parameters by index: Criterion runs each test in a new process, where pointers of the
   parent's do not hold) */
static const char *const CASES[] = {PHYSICAL_REFERENCE, PHYSICAL_MICRO};

typedef struct named_run {
    int case_index, integrator;
} named_run;

ParameterizedTestParameters(physical_scale, to_the_exit)
{
    static named_run runs[] = {
        {0, TRIBO_INTEGRATOR_CVODE}, {0, TRIBO_INTEGRATOR_CVODE_BDF},
        {1, TRIBO_INTEGRATOR_CVODE}, {1, TRIBO_INTEGRATOR_CVODE_BDF},
    };
    return cr_make_param_array(named_run, runs, sizeof runs / sizeof runs[0]);
}

ParameterizedTest(named_run *r, physical_scale, to_the_exit, .timeout = STABILITY_TIMEOUT_S)
{
    tribo_si_derived d;
    derive(CASES[r->case_index], &d);
    stability_result res;
    physical_run(&d, r->integrator, T_END_S, EVERY_S, &res);
    char what[200];
    snprintf(what, sizeof what, "%s, %s", CASES[r->case_index],
             stability_integrator_name(r->integrator));
    expect_stable(&res, what);
    cr_expect(res.exited, "%s: did not leave the chute within %g s", what, T_END_S);
}

/* The fixed step cannot go to the exit (about 9e9 steps of dt = 8e-5 for the reference case:
   docs/reference_case.md); it runs tau = 50 from the first impact instead: the same grain
   started with its lowest point on the chute at the speed of its 10 mm drop, straight down
   (the drop height is normal to the chute: the fall is 10 mm / cos 30 degrees). */
ParameterizedTestParameters(physical_scale, fixed_step_from_the_impact)
{
    static int cases[] = {0, 1};
    return cr_make_param_array(int, cases, 2);
}

ParameterizedTest(int *c, physical_scale, fixed_step_from_the_impact,
                  .timeout = STABILITY_TIMEOUT_S)
{
    tribo_si_derived d;
    const double speed = sqrt(2.0 * 9.81 * 0.01 / cos(30.0 * M_PI / 180.0));
    char at_impact[256];
    snprintf(at_impact, sizeof at_impact, "%s drop_height=0 drop_speed=%.17g", CASES[*c], speed);
    derive(at_impact, &d);
    tribo_scene s = d.scene;
    s.integrator = TRIBO_INTEGRATOR_FIXED_STEP;
    s.stick_model = TRIBO_STICK_COMPLIANT; /* the fixed step has no rigid stick */
    stability_result res;
    stability_run_scene(&s, &d, 50.0, 0.5, &res);
    char what[300];
    snprintf(what, sizeof what, "%s, fixed step, tau 0..50", at_impact);
    expect_stable(&res, what);
    cr_expect(res.q_static > 0.0, "%s: no charge picked up at the impact", what);
}

/* ---- the grid of moduli and sizes, CVODE to the exit --------------------------------------- */

typedef struct grid_run {
    double E, size;
} grid_run;

ParameterizedTestParameters(physical_scale, grid)
{
    static grid_run runs[64];
    int n = 0;
    for (int j = 0; j < N_PHYSICAL_SIZES; j++)
        for (int i = 0; i < N_PHYSICAL_MODULI; i++)
            runs[n++] = (grid_run){PHYSICAL_MODULI[i], PHYSICAL_SIZES[j]};
    return cr_make_param_array(grid_run, runs, (size_t)n);
}

/* The one set-up of the grid the SI front end refuses: a 10 um grain of polyethylene's
   density with a 400 GPa modulus: Gamma = m' g / (k' a) = 7.3e-13, below the model's 1e-12
   (its weight would hardly press it into the wall). A real grain that hard is dense
   (alumina, 3900 kg/m3: Gamma 3e-12) and runs. */
static int refused(const grid_run *r) { return r->E > 1e11 && r->size < 50e-6; }

ParameterizedTest(grid_run *r, physical_scale, grid, .timeout = STABILITY_TIMEOUT_S)
{
    char settings[256], msg[1024];
    snprintf(settings, sizeof settings, "youngs_modulus_particle=%g semi_major_axis=%g", r->E,
             r->size / 2);
    tribo_si_derived d;
    const tribo_status st = physical_derive(settings, &d, msg, sizeof msg);
    if (refused(r)) {
        cr_assert_eq(st, TRIBO_ERR_INVALID_ARGUMENT, "%s: not refused", settings);
        cr_expect(strstr(msg, "Gamma = 7.3") && strstr(msg, "1e-12 <= Gamma") &&
                      strstr(msg, "semi_major_axis = 5e-06 m") &&
                      strstr(msg, "youngs_modulus_particle = 4e+11 Pa") && strstr(msg, "density = 950"),
                  "%s: the refusal does not name Gamma and its SI inputs: %s", settings, msg);
        return;
    }
    cr_assert_eq(st, TRIBO_OK, "%s: refused: %s", settings, msg);
    stability_result res;
    physical_run(&d, TRIBO_INTEGRATOR_CVODE, T_END_S, EVERY_S, &res);
    expect_stable(&res, settings);
    cr_expect(res.exited, "%s: did not leave the chute within %g s", settings, T_END_S);
    cr_expect(res.q_static > 0.0, "%s: no charge at the exit", settings);
}

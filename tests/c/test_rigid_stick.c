/* The rigid stick (stick_model = rigid, model.md §3b): grains set down on a chute against
   rigid-body mechanics, in the model's units and in SI; E + work_dissipated along rolling
   ellipses; the rigid phases saved and loaded; rigid and compliant converging as Gamma falls;
   the scenes that refuse it. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "si.h"
#include "support.h"

/* sin and cos of the chute's 30 degrees */
#define SIN_BETA 0.5
#define COS_BETA 0.86602540378443865

typedef struct exit_run {
    double t, impacts;
    long long events;
} exit_run;

static exit_run run_to_the_exit(const tribo_scene *s)
{
    tribo_model *m = make(s);
    cr_assert_eq(tribo_advance_fully(m, TRIBO_TIME_MAX), TRIBO_ENDED, "%s", tribo_last_error(m));
    tribo_stats st;
    tribo_get_stats(m, &st);
    const exit_run r = {tribo_get(m, TRIBO_QUANTITY_EXIT_TIME), tribo_get(m, TRIBO_QUANTITY_IMPACTS), st.events};
    tribo_free(m);
    return r;
}

/* A grain of the model's units set down at rest (no gap, no speed) on a chute tilted 30
   degrees, L = 1 / sqrt(Gamma) long. */
static tribo_scene set_down(const char *settings, double gamma, int stick_model)
{
    tribo_scene s = scene_of("beta=0.52359877559829887 gap0=0 drop_speed=0 nu=0.3");
    char err[512];
    cr_assert_eq(tribo_scene_apply(&s, settings, err, sizeof err), TRIBO_OK, "%s", err);
    s.Gamma = gamma;
    s.chute_length = 1.0 / sqrt(gamma);
    s.stick_model = stick_model;
    return s;
}

/* The cases of rigid-body mechanics: the centre's acceleration along the chute from rest, in
   units of the gravity g: a disc rolling without slip (its inertia m a^2 / 2: 2/3 sin beta),
   rolling and slipping (sin beta - mu cos beta), without friction (sin beta), and a flat
   grain sliding (sin beta - mu cos beta; eps 0.3 pitches forward by 0.03 rad under the
   friction torque and rocks about that tilt, which the translation ignores: a rounder grain
   pitches further, eps 0.6 by 0.17 rad, and moves off the formula by 2.8e-4). bound_units and
   bound_si: the relative error of the exit time allowed in the model's units (Gamma 1e-6)
   and in SI, about 5x the error measured (in parentheses). */
static const struct {
    const char *name, *settings;
    double accel, bound_units, bound_si;
} RIGID_BODY[] = {
    {"disc rolling", "epsilon=1 mu=0.5", 2.0 / 3.0 * SIN_BETA, 1e-9 /* 1.5e-10 */, 5e-12 /* 4.9e-13 */},
    {"disc rolling and slipping", "epsilon=1 mu=0.1", SIN_BETA - 0.1 * COS_BETA, 1e-9 /* 2.2e-10 */,
     1e-11 /* 1.4e-12 */},
    {"disc without friction", "epsilon=1 mu=0", SIN_BETA, 1.5e-9 /* 2.7e-10 */, 5e-14 /* 5.1e-15 */},
    {"eps 0.6 without friction", "epsilon=0.6 mu=0", SIN_BETA, 1.5e-9 /* 2.7e-10 */,
     1e-13 /* 1.5e-14 */},
    {"flat eps 0.3 sliding", "epsilon=0.3 mu=0.3", SIN_BETA - 0.3 * COS_BETA, 1e-7 /* 1.5e-8 */,
     5e-7 /* 1.1e-7 */},
};
#define N_RIGID_BODY (sizeof RIGID_BODY / sizeof RIGID_BODY[0])

/* Set down, the grain settles into its sustained contact at once: no impact, a lock and its
   tangential rule, and nothing else to the exit. */
static void expect_sustained_contact(const exit_run *r, const char *name)
{
    cr_expect_eq(r->impacts, 0.0, "%s: %g impacts", name, r->impacts);
    cr_expect(r->events <= 4, "%s: %lld events", name, r->events);
}

Test(rigid_stick, exit_times_are_rigid_body_mechanics_in_the_models_units)
{
    const double gamma = 1e-6;
    for (size_t i = 0; i < N_RIGID_BODY; i++) {
        const tribo_scene s = set_down(RIGID_BODY[i].settings, gamma, TRIBO_STICK_RIGID);
        const exit_run r = run_to_the_exit(&s);
        const double exact = sqrt(2.0 * s.chute_length / (RIGID_BODY[i].accel * gamma));
        cr_expect(fabs(r.t / exact - 1.0) <= RIGID_BODY[i].bound_units,
                  "%s: exit at %.12g, rigid-body mechanics %.12g (%.2e)", RIGID_BODY[i].name, r.t,
                  exact, r.t / exact - 1.0);
        expect_sustained_contact(&r, RIGID_BODY[i].name);
    }
}

Test(rigid_stick, exit_times_are_rigid_body_mechanics_in_si)
{
    /* polyethylene set down on 0.3 m of steel at 30 degrees (the SI FMUs' defaults); the SI
       front end's default stick is the rigid one */
    for (size_t i = 0; i < N_RIGID_BODY; i++) {
        tribo_si_scene si;
        tribo_si_scene_defaults(&si);
        cr_assert_eq(si.stick_model, TRIBO_STICK_RIGID);
        char err[512];
        /* (without rolling resistance: test_rolling.c has it) */
        cr_assert_eq(tribo_si_scene_apply(&si, "drop_height=0 chute_length=0.3 mu_roll=0", err, sizeof err),
                     TRIBO_OK);
        cr_assert_eq(tribo_si_scene_apply(&si, RIGID_BODY[i].settings, err, sizeof err), TRIBO_OK);
        tribo_si_derived d;
        cr_assert_eq(tribo_si_derive(&si, &d, err, sizeof err), TRIBO_OK, "%s", err);
        const exit_run r = run_to_the_exit(&d.scene);
        const double t = r.t * d.t_star, exact = sqrt(2.0 * 0.3 / (RIGID_BODY[i].accel * 9.81));
        cr_expect(fabs(t / exact - 1.0) <= RIGID_BODY[i].bound_si,
                  "%s: exit at %.12g s, rigid-body mechanics %.12g s (%.2e)", RIGID_BODY[i].name, t,
                  exact, t / exact - 1.0);
        expect_sustained_contact(&r, RIGID_BODY[i].name);
    }
}

/* Rigid and compliant stick converge as Gamma falls, where the compliant one can be afforded:
   the exit time of a rolling disc (measured relative differences 5.4e-7, 5.8e-9, 2.5e-10 at
   Gamma 1e-3, 1e-4, 1e-5) and of a rocking slide (6.7e-6, 1.3e-6, 2.5e-7), and the rolling
   disc's sliding charge, which the compliant stick's ringing raises (3.5e-2, 4.4e-3,
   3.8e-4): each at least 3x closer for each factor 10 of Gamma. */
Test(rigid_stick, rigid_and_compliant_converge_as_gamma_falls, .timeout = 360)
{
    const struct {
        const char *settings;
        tribo_quantity q;
    } cases[] = {{"epsilon=1 mu=0.5", TRIBO_QUANTITY_EXIT_TIME},
                 {"epsilon=0.5 mu=0.3", TRIBO_QUANTITY_EXIT_TIME},
                 {"epsilon=1 mu=0.5", TRIBO_QUANTITY_SLIDING}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double previous = INFINITY;
        for (double gamma = 1e-3; gamma > 0.99e-5; gamma /= 10.0) {
            double value[2];
            for (int sm = 0; sm < 2; sm++) {
                tribo_scene s = set_down(cases[c].settings, gamma, sm);
                s.tau0 = s.tau_r = s.chute_length; /* charging on the chute's time scale */
                tribo_model *m = make(&s);
                cr_assert_eq(tribo_advance_fully(m, TRIBO_TIME_MAX), TRIBO_ENDED, "%s", tribo_last_error(m));
                value[sm] = tribo_get(m, cases[c].q);
                tribo_free(m);
            }
            const double difference = fabs(value[1] / value[0] - 1.0);
            cr_expect(difference <= previous / 3.0, "%s, %s at Gamma %g: %.3g after %.3g",
                      cases[c].settings, tribo_quantity_name(cases[c].q), gamma, difference, previous);
            previous = difference;
        }
    }
}

/* Along rolling ellipses with the rigid stick E + work_dissipated never increases (the
   constraint forces do no work; the quasi-static stretch's energy is booked as it changes):
   what it seems to gain is the integration's error, measured at most 1.9e-7 of the energy's
   scale (sampled every 0.1 ms); the bound is 5x that. */
Test(rigid_stick, energy_and_dissipated_work_never_increase_along_rolling_ellipses, .timeout = 60)
{
    const char *grains[] = {"epsilon=0.9 mu=0.5", "epsilon=0.95 mu=0.5 semi_major_axis=2e-4",
                            "epsilon=0.7 mu=0.8 tilt=0.3"};
    for (size_t i = 0; i < sizeof grains / sizeof grains[0]; i++) {
        tribo_si_scene si;
        tribo_si_scene_defaults(&si);
        char err[512];
        cr_assert_eq(tribo_si_scene_apply(&si, "drop_height=0 chute_length=0.3", err, sizeof err), TRIBO_OK);
        cr_assert_eq(tribo_si_scene_apply(&si, grains[i], err, sizeof err), TRIBO_OK);
        tribo_si_derived d;
        cr_assert_eq(tribo_si_derive(&si, &d, err, sizeof err), TRIBO_OK, "%s", err);
        tribo_model *m = make(&d.scene);
        energy_watch w = energy_watch_start();
        tribo_status st = TRIBO_OK;
        for (int k = 1; st == TRIBO_OK; k++) {
            st = tribo_advance_fully(m, k * 1e-4 / d.t_star);
            cr_assert(st == TRIBO_OK || st == TRIBO_ENDED, "%s", tribo_last_error(m));
            energy_watch_sample(&w, m);
        }
        cr_expect(w.rise <= 1e-6 * w.scale, "%s: E + W rose by %.3g (%.2e of E's scale)", grains[i],
                  w.rise, w.rise / w.scale);
        tribo_free(m);
    }
}

/* A state saved anywhere along a run with the rigid stick (in a rigid stick, a creep, a slip,
   a flight) and loaded into a new instance goes on to the same exit bit for bit. */
Test(rigid_stick, its_phases_save_and_load_bit_for_bit, .timeout = 180)
{
    const char *grains[] = {"epsilon=1 mu=0.5 drop_height=0", "epsilon=0.6 drop_height=0",
                            "epsilon=0.9 mu=0.5"};
    for (size_t i = 0; i < sizeof grains / sizeof grains[0]; i++) {
        tribo_si_scene si;
        tribo_si_scene_defaults(&si);
        char err[512];
        cr_assert_eq(tribo_si_scene_apply(&si, "chute_length=0.3", err, sizeof err), TRIBO_OK);
        cr_assert_eq(tribo_si_scene_apply(&si, grains[i], err, sizeof err), TRIBO_OK);
        tribo_si_derived d;
        cr_assert_eq(tribo_si_derive(&si, &d, err, sizeof err), TRIBO_OK, "%s", err);
        tribo_model *whole = make(&d.scene);
        cr_assert_eq(tribo_advance_fully(whole, TRIBO_TIME_MAX), TRIBO_ENDED);
        const double t_exit = tribo_get(whole, TRIBO_QUANTITY_TIME);
        for (int k = 1; k <= 7; k++) {
            tribo_model *m = make(&d.scene), *loaded = make(&d.scene);
            cr_assert_eq(tribo_advance_fully(m, t_exit * k / 8.0), TRIBO_OK);
            size_t size;
            unsigned char *bytes = saved_state(m, &size);
            cr_assert_eq(tribo_state_load(loaded, bytes, size), TRIBO_OK, "%s", tribo_last_error(loaded));
            free(bytes);
            cr_assert_eq(tribo_advance_fully(loaded, TRIBO_TIME_MAX), TRIBO_ENDED);
            for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++)
                cr_expect(tribo_get(loaded, q) == tribo_get(whole, q), "%s, saved at %d/8: %s %.17g, %.17g",
                          grains[i], k, tribo_quantity_name(q), tribo_get(loaded, q), tribo_get(whole, q));
            tribo_free(m);
            tribo_free(loaded);
        }
        tribo_free(whole);
    }
}

/* A flat grain pressed onto the plate rolls in the rigid stick for thousands of CVODE steps
   between restarts; a state saved where the work limit stopped an advance loads again: its
   replayed steps reach the committed point bit for bit, also where putting the point back on
   the constraints a second time (as committing does) moves the last bit of a velocity. */
Test(rigid_stick, a_state_saved_after_a_long_rigid_stretch_loads_again, .timeout = 600)
{
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    si.epsilon = 0.22511708985426643;
    si.mu_roll = 0.0; /* it rolls and rocks in the rigid stick: with rolling resistance it rests */
    si.chute_length = INFINITY;
    char err[512];
    tribo_si_derived d;
    cr_assert_eq(tribo_si_derive(&si, &d, err, sizeof err), TRIBO_OK, "%s", err);
    tribo_model *m = make(&d.scene);
    double in[TRIBO_SI_INPUT_COUNT] = {0}, model_in[TRIBO_INPUT_COUNT];
    in[TRIBO_SI_INPUT_F_N] = -833.7959160855213; /* N/m, pressing it onto the plate */
    cr_assert_eq(tribo_si_model_inputs(&d, in, model_in, err, sizeof err), TRIBO_OK, "%s", err);
    cr_assert_eq(tribo_set_inputs(m, model_in), TRIBO_OK);
    cr_assert_eq(tribo_advance(m, 4.118101206701782e-07 / d.t_star), TRIBO_OK);
    int stops = 0;
    for (int k = 0; k < 3; k++) {
        const tribo_status st = tribo_advance(m, 0.4118105324802988 / d.t_star);
        cr_assert(st == TRIBO_OK || st == TRIBO_INCOMPLETE, "%s", tribo_last_error(m));
        stops += st == TRIBO_INCOMPLETE;
        size_t size;
        unsigned char *bytes = saved_state(m, &size);
        tribo_model *loaded = make(&d.scene);
        cr_expect_eq(tribo_state_load(loaded, bytes, size), TRIBO_OK, "at t = %.17g: %s",
                     tribo_get(m, TRIBO_QUANTITY_TIME), tribo_last_error(loaded));
        free(bytes);
        tribo_free(loaded);
    }
    cr_expect(stops > 0, "no advance stopped at the work limit");
    tribo_free(m);
}

/* The rigid stick is a phase of the event-driven integrator in the contact point's lock: the
   fixed step and the centre dashpot refuse it in one line that says what to set. */
Test(rigid_stick, the_fixed_step_and_the_centre_dashpot_refuse_it)
{
    const char *refused[] = {"stick_model=1 integrator=0", "stick_model=1 damping_point=1"};
    const char *words[] = {"integrator = 0", "damping_point = 1"};
    for (int i = 0; i < 2; i++) {
        const tribo_scene s = scene_of(refused[i]);
        char err[512];
        cr_expect_null(tribo_create(&s, err, sizeof err), "%s", refused[i]);
        cr_expect(strstr(err, "stick_model = 1 (rigid)") == err && strstr(err, words[i]) &&
                      strstr(err, "stick_model = 0") && !strchr(err, '\n'),
                  "%s", err);
    }
}

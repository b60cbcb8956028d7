/* Physical set-ups that once ended in an event cascade, and a sample of random ones with
   external normal forces under both stick models (random_setups.h), end without an
   integrator failure: at the chute's exit, at rest, at the horizon, or still going when their
   bounded work is spent. The whole random set is scripts/random_setups.sh. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <stdio.h>

#include "random_setups.h"

/* enough for each named set-up to pass the time at which it failed (the latest, 0.404 s for
   grain 482; the pressed grains rock, slowly, and are stopped by the work after ~0.01 s) */
#define HORIZON_S 0.5
#define WORK_CAP 4e5
#define RANDOM_SEED 7
#define RANDOM_COUNT 12

static void expect_no_failure(const char *name, const random_setup *r, int refusal_allowed)
{
    char why[1024];
    double t_end;
    const random_outcome o = random_setup_run(r, HORIZON_S, WORK_CAP, why, sizeof why, &t_end);
    cr_expect(o != RANDOM_FAILED, "%s (%s, F_N_ext = %g N/m) failed at %g s: %s", name,
              r->settings, r->F_N, t_end, why);
    if (!refusal_allowed)
        cr_expect(o != RANDOM_REFUSED, "%s refused: %s", name, why);
}

/* (by index: Criterion runs each test in a process of its own) */
ParameterizedTestParameters(random_setups, named)
{
    static int index[16];
    for (int i = 0; i < N_NAMED_SETUPS; i++)
        index[i] = i;
    return cr_make_param_array(int, index, N_NAMED_SETUPS);
}

ParameterizedTest(int *i, random_setups, named, .timeout = 120)
{
    expect_no_failure(NAMED_SETUPS[*i].name, &NAMED_SETUPS[*i].setup, 0);
}

ParameterizedTestParameters(random_setups, sample)
{
    static int stick_model[] = {TRIBO_STICK_COMPLIANT, TRIBO_STICK_RIGID};
    return cr_make_param_array(int, stick_model, 2);
}

ParameterizedTest(int *stick_model, random_setups, sample, .timeout = 300)
{
    for (int i = 0; i < RANDOM_COUNT; i++) {
        random_setup r;
        random_setup_make(RANDOM_SEED, i, *stick_model, &r);
        char name[64];
        snprintf(name, sizeof name, "random set-up %d of seed %d", i, RANDOM_SEED);
        expect_no_failure(name, &r, 1);
    }
}

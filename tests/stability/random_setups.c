/* random_setups.c: see random_setups.h. */
#include "random_setups.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* splitmix64: a fixed sequence for every seed, on every platform */
static unsigned long long next_bits(unsigned long long *state)
{
    unsigned long long z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* uniform in [lo, hi) */
static double uniform(unsigned long long *state, double lo, double hi)
{
    return lo + (hi - lo) * (double)(next_bits(state) >> 11) * 0x1p-53;
}

static double log_uniform(unsigned long long *state, double lo, double hi)
{
    return exp(uniform(state, log(lo), log(hi)));
}

void random_setup_make(unsigned long long seed, int index, int stick_model, random_setup *r)
{
    unsigned long long state = seed * 0x100000001b3ull + (unsigned long long)index;
    const double a = log_uniform(&state, 2.5e-5, 2.5e-3);
    const double epsilon = uniform(&state, 0.15, 1.0);
    const double phi0 = uniform(&state, 0.0, M_PI);
    const double modulus = log_uniform(&state, 1e7, 1e10);
    const double density = uniform(&state, 500.0, 3000.0);
    const double mu = uniform(&state, 0.0, 1.0) < 0.1 ? uniform(&state, 10.0, 100.0)
                                                      : uniform(&state, 0.0, 1.5);
    const double nu = uniform(&state, 0.05, 1.0);
    const double mu_roll = uniform(&state, 0.0, 1.0) < 0.1 ? uniform(&state, 0.05, 1.0)
                                                           : uniform(&state, 0.0, 0.05);
    const double tilt = uniform(&state, 0.0, M_PI / 3.0);
    const double drop = uniform(&state, 0.0, 0.02);
    r->F_N = uniform(&state, -1e4, 1e4);
    r->F_T = 0.0;
    snprintf(r->settings, sizeof r->settings,
             "chute_length=0.3 semi_major_axis=%.17g epsilon=%.17g phi0=%.17g "
             "youngs_modulus_particle=%.17g density=%.17g mu=%.17g nu=%.17g mu_roll=%.17g "
             "tilt=%.17g drop_height=%.17g stick_model=%d",
             a, epsilon, phi0, modulus, density, mu, nu, mu_roll, tilt, drop, stick_model);
}

random_outcome random_setup_run(const random_setup *r, double horizon_s, double work_cap, char *why,
                                size_t why_size, double *t_end_s)
{
    *t_end_s = 0.0;
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    tribo_si_derived d;
    if (tribo_si_scene_apply(&si, r->settings, why, why_size) != TRIBO_OK ||
        tribo_si_derive(&si, &d, why, why_size) != TRIBO_OK)
        return RANDOM_REFUSED;
    const double inputs[TRIBO_SI_INPUT_COUNT] = {[TRIBO_SI_INPUT_F_T] = r->F_T,
                                                 [TRIBO_SI_INPUT_F_N] = r->F_N};
    double model_inputs[TRIBO_INPUT_COUNT];
    if (tribo_si_model_inputs(&d, inputs, model_inputs, why, why_size) != TRIBO_OK)
        return RANDOM_REFUSED;
    /* the work is bounded in slices of the scene's work limit (an advance stops early when
       its slice is spent and goes on from there) */
    const double slice = 1e5;
    d.scene.work_limit = (int)slice;
    tribo_model *m = tribo_create(&d.scene, why, why_size);
    if (!m)
        return RANDOM_REFUSED;
    tribo_status st = tribo_set_inputs(m, model_inputs);
    for (double spent = 0.0; st == TRIBO_OK || st == TRIBO_INCOMPLETE; spent += slice) {
        if (spent >= work_cap)
            break;
        st = tribo_advance(m, horizon_s / d.t_star);
        if (st == TRIBO_OK)
            break;
    }
    *t_end_s = tribo_si_get(&d, m, TRIBO_SI_QUANTITY_TIME);
    snprintf(why, why_size, "%s", tribo_last_error(m));
    tribo_free(m);
    switch (st) {
    case TRIBO_OK: return RANDOM_HORIZON;
    case TRIBO_ENDED: return RANDOM_EXITED;
    case TRIBO_INCOMPLETE: return RANDOM_WORK_CAP;
    default: return RANDOM_FAILED;
    }
}

/* As they were filed, before rolling resistance (mu_roll = 0): the SI defaults on a 0.3 m chute
   with epsilon 0.2251..., pressed by -833.8 N/m (an event cascade at t = 0.027 s), its
   neighbours in epsilon and force; mu = 100 alone (a cascade at 0.34 s); grain 482 of the
   1000-grain polyethylene-on-steel population at mu = 0.5 (0.404 s). And the pressed grain with
   the default rolling resistance, which settles. */
#define FILED "chute_length=0.3 mu_roll=0 "
#define PRESSED FILED "epsilon=0.22511708985426643"
#define GRAIN_482                                                                                  \
    FILED "mu=0.5 semi_major_axis=0.00047066640954451073 epsilon=0.48543847235139137 "            \
          "phi0=1.6545354758427289 drop_height=0.01"
const named_setup NAMED_SETUPS[] = {
    {"pressed, eps 0.2251", {PRESSED, 0.0, -833.8}},
    {"pressed, eps 0.2241", {FILED "epsilon=0.22411708985426643", 0.0, -833.8}},
    {"pressed, eps 0.2261", {FILED "epsilon=0.22611708985426643", 0.0, -833.8}},
    {"pressed twice as hard", {PRESSED, 0.0, -1667.6}},
    {"mu 100", {FILED "mu=100", 0.0, 0.0}},
    {"grain 482", {GRAIN_482, 0.0, 0.0}},
    {"pressed, rolling resistance", {"epsilon=0.22511708985426643", 0.0, -833.8}},
};
const int N_NAMED_SETUPS = sizeof NAMED_SETUPS / sizeof NAMED_SETUPS[0];

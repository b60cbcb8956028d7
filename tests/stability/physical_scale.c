/* physical_scale.c: see physical_scale.h. */
#include "physical_scale.h"

#include <stdio.h>

const double PHYSICAL_MODULI[] = {1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 4e11};
const int N_PHYSICAL_MODULI = sizeof PHYSICAL_MODULI / sizeof PHYSICAL_MODULI[0];
const double PHYSICAL_SIZES[] = {10e-6, 100e-6, 1e-3, 10e-3};
const int N_PHYSICAL_SIZES = sizeof PHYSICAL_SIZES / sizeof PHYSICAL_SIZES[0];

tribo_status physical_derive(const char *settings, tribo_si_derived *d, char *msg, size_t msg_size)
{
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    tribo_status st = tribo_si_scene_apply(&si, PHYSICAL_REFERENCE, msg, msg_size);
    if (st == TRIBO_OK)
        st = tribo_si_scene_apply(&si, settings, msg, msg_size);
    if (st == TRIBO_OK)
        st = tribo_si_derive(&si, d, msg, msg_size);
    return st;
}

void physical_run(const tribo_si_derived *d, int integrator, double t_end_s, double every_s,
                  stability_result *r)
{
    tribo_scene s = d->scene;
    s.integrator = integrator;
    if (integrator == TRIBO_INTEGRATOR_FIXED_STEP)
        s.stick_model = TRIBO_STICK_COMPLIANT; /* the fixed step has no rigid stick */
    stability_run_scene(&s, d, t_end_s / d->t_star, every_s / d->t_star, r);
}

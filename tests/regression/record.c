/* record: the outputs of the paper's study grid and of the stability matrix, bit-exactly,
   for the regression test that holds a change to "behaviour does not change".

     tribo_regression_record > tests/regression/golden.txt

   At each sample time one line: run name, time (C99 hex float), "hash" and an FNV-1a hash
   of the bytes of every output and of both per-segment charge arrays. At the last sample
   of a run, also every output by name with its value in %a, so that a difference can be
   read. */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "matrix.h"

static uint64_t fnv1a(const void *data, size_t n, uint64_t h)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

static void print_outputs(const char *run, tribo_model *m, int last)
{
    const double t = tribo_get(m, TRIBO_Q_TIME);
    uint64_t h = 14695981039346656037ull;
    for (int q = 0; q < TRIBO_Q_COUNT; q++) {
        const double v = tribo_get(m, (tribo_quantity)q);
        h = fnv1a(&v, sizeof v, h);
        if (last)
            printf("%s %a %s %a\n", run, t, tribo_quantity_name((tribo_quantity)q), v);
    }
    const size_t n = (size_t)tribo_get_scene(m)->n_segments;
    double *seg = malloc(n * sizeof *seg);
    for (int which = 0; which < 2; which++)
        if (seg && tribo_get_segment_charges(m, (tribo_segment_charge)which, seg, n) == TRIBO_OK)
            h = fnv1a(seg, n * sizeof *seg, h);
    free(seg);
    printf("%s %a hash %016" PRIx64 "\n", run, t, h);
}

/* Advance through the sample times, printing the outputs at each. */
static void run_scene(const char *run, const tribo_scene *s, const double *times, int n_times)
{
    char err[512];
    tribo_model *m = tribo_create(s, err, sizeof err);
    if (!m) {
        printf("%s create-failed %s\n", run, err);
        return;
    }
    for (int k = 0; k < n_times; k++) {
        if (tribo_advance_fully(m, times[k]) != TRIBO_OK) {
            printf("%s %a advance-failed %s\n", run, times[k], tribo_last_error(m));
            break;
        }
        print_outputs(run, m, k == n_times - 1);
    }
    tribo_free(m);
}

int main(void)
{
    /* The study grid (model.md §7, the settings of the committed study: CVODE at rtol 1e-8,
       atol 1e-10), epsilon 0.1 ... 1.0, mu = nu = 0.1 and 1.0, both charge models; CVODE
       to tau = 1000, the fixed step (dt = 8e-5) to tau = 50. */
    const double cvode_times[] = {1, 5, 10, 20, 50, 100, 200, 500, 1000};
    const double fixed_times[] = {1, 5, 10, 20, 50};
    for (int integrator = 0; integrator < 2; integrator++) {
        for (int e = 1; e <= 10; e++) {
            for (int f = 0; f < 2; f++) {
                tribo_scene s;
                tribo_scene_defaults(&s);
                s.epsilon = e / 10.0;
                s.mu = s.nu = f ? 1.0 : 0.1;
                s.charge_model = TRIBO_CHARGE_BOTH;
                s.integrator = integrator ? TRIBO_INTEGRATOR_CVODE : TRIBO_INTEGRATOR_FIXED_STEP;
                s.rtol = 1e-8;
                s.atol = 1e-10;
                char run[64];
                snprintf(run, sizeof run, "study/%s/eps%.1f/mu%.1f",
                         integrator ? "cvode" : "fixed", s.epsilon, s.mu);
                if (integrator)
                    run_scene(run, &s, cvode_times, sizeof cvode_times / sizeof *cvode_times);
                else
                    run_scene(run, &s, fixed_times, sizeof fixed_times / sizeof *fixed_times);
            }
        }
    }

    /* The stability matrix, every case with every integrator, sampled as its test does
       (every 0.5 to tau = 50); every 10th sample is printed. */
    double times[100];
    for (int k = 0; k < 100; k++)
        times[k] = 0.5 * (k + 1);
    for (int c = 0; c < N_STABILITY_CASES; c++) {
        for (int i = 0; i < N_STABILITY_INTEGRATORS; i++) {
            tribo_scene s;
            tribo_scene_defaults(&s);
            tribo_scene_apply(&s, STABILITY_CASES[c].settings, NULL, 0);
            s.integrator = STABILITY_INTEGRATORS[i];
            char run[128];
            snprintf(run, sizeof run, "stability/%d/%s", c,
                     stability_integrator_name(STABILITY_INTEGRATORS[i]));
            for (char *p = run; *p; p++)
                if (*p == ' ')
                    *p = '_';
            char err[512];
            tribo_model *m = tribo_create(&s, err, sizeof err);
            if (!m) {
                printf("%s create-failed %s\n", run, err);
                continue;
            }
            for (int k = 0; k < 100; k++) {
                if (tribo_advance_fully(m, times[k]) != TRIBO_OK) {
                    printf("%s %a advance-failed %s\n", run, times[k], tribo_last_error(m));
                    break;
                }
                if ((k + 1) % 10 == 0)
                    print_outputs(run, m, k == 99);
            }
            tribo_free(m);
        }
    }
    return 0;
}

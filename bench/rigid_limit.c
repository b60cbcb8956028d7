/* The rigid stick against the compliant one where both are affordable (docs/reference_case.md,
   "Rigid and compliant stick"): grains placed on a 30 degree chute of length 1/sqrt(Gamma)
   (the distance the slow motion covers in the chute's time scale), charging times of the same
   scale, run to the exit with both stick models at Gamma = 1e-3 ... 1e-6. The differences
   shrink as Gamma does (model.md §3b: the rigid stick is the compliant one's limit).

   Usage: tribo_bench_rigid_limit (scripts/bench_rigid_limit.sh) */
#define _POSIX_C_SOURCE 199309L
#include "tribo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct outcome {
    double exit_time, q_static, q_sliding, cpu;
    long long events;
} outcome;

static outcome run(const char *settings, double gamma, int stick_model)
{
    tribo_scene s;
    char err[512];
    tribo_scene_defaults(&s);
    if (tribo_scene_apply(&s, "beta=0.5235987755982988 gap0=0 drop_speed=0", err, sizeof err) ||
        tribo_scene_apply(&s, settings, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        exit(1);
    }
    s.Gamma = gamma;
    s.stick_model = stick_model;
    s.chute_length = 1.0 / sqrt(gamma);
    s.tau0 = s.tau_r = 1.0 / sqrt(gamma);
    tribo_model *m = tribo_create(&s, err, sizeof err);
    if (!m) {
        fprintf(stderr, "%s: %s\n", settings, err);
        exit(1);
    }
    outcome o;
    const double c0 = cpu();
    if (tribo_advance_fully(m, TRIBO_TIME_MAX) != TRIBO_ENDED) {
        fprintf(stderr, "%s: %s\n", settings, tribo_last_error(m));
        exit(1);
    }
    o.cpu = cpu() - c0;
    tribo_stats st;
    tribo_get_stats(m, &st);
    o.events = st.events;
    o.exit_time = tribo_get(m, TRIBO_QUANTITY_EXIT_TIME);
    o.q_static = tribo_get(m, TRIBO_QUANTITY_STATIC);
    o.q_sliding = tribo_get(m, TRIBO_QUANTITY_SLIDING);
    tribo_free(m);
    return o;
}

int main(void)
{
    static const struct {
        const char *name, *settings;
    } GRAINS[] = {
        {"disc rolling, mu 0.5", "epsilon=1 mu=0.5 nu=0.3"},
        {"rocking slide, eps 0.5, mu 0.3", "epsilon=0.5 mu=0.3 nu=0.3"},
        {"rolling ellipse, eps 0.9, mu 0.5", "epsilon=0.9 mu=0.5 nu=0.3"},
    };
    printf("| grain | Gamma | exit time, relative difference | Q_static | Q_sliding | "
           "CPU [s] compliant / rigid | events compliant / rigid |\n|---|---|---|---|---|---|---|\n");
    for (size_t g = 0; g < sizeof GRAINS / sizeof GRAINS[0]; g++)
        for (double gamma = 1e-3; gamma >= 0.99e-6; gamma /= 10) {
            const outcome c = run(GRAINS[g].settings, gamma, TRIBO_STICK_COMPLIANT);
            const outcome r = run(GRAINS[g].settings, gamma, TRIBO_STICK_RIGID);
            printf("| %s | %.0e | %.2e | %.2e | %.2e | %.3f / %.3f | %lld / %lld |\n",
                   GRAINS[g].name, gamma, fabs(r.exit_time / c.exit_time - 1.0),
                   fabs(r.q_static / c.q_static - 1.0), fabs(r.q_sliding / c.q_sliding - 1.0),
                   c.cpu, r.cpu, c.events, r.events);
            fflush(stdout);
        }
    return 0;
}

/* The dimensionless rigid disc the work-precision and stick reports roll (docs/reference_case.md,
   "The rolling disc's charging"): a disc (epsilon = 1, mu = 0.5, nu = 0.3) set down on a
   30 degree chute of the model's units with the rigid stick (Gamma = 1e-6), both charge models
   at their defaults (tau0 = tau_r = 1, 2000 segments), rolling to tau = 2e5 (about 1060 turns).
   Prints the fastest CPU time of the rounds (the process's, from creation to the end), what
   the run gives, to compare revisions by, and the fastest CPU of the same run with every
   charge model switched off (the motion alone).

   Usage: tribo_bench_rigid_disc [rounds=5] (scripts/bench_rigid_disc.sh) */
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

/* The fastest CPU of `rounds` runs of the scene, from creation to tau = 2e5; the last run's
   instance through *last (freed by the caller). */
static double fastest(const tribo_scene *s, int rounds, tribo_model **last)
{
    char err[512];
    double best = INFINITY;
    *last = NULL;
    for (int r = 0; r < rounds; r++) {
        if (*last)
            tribo_free(*last);
        const double c0 = cpu();
        tribo_model *m = tribo_create(s, err, sizeof err);
        if (!m || tribo_advance_fully(m, 2e5) != TRIBO_OK) {
            fprintf(stderr, "%s\n", m ? tribo_last_error(m) : err);
            exit(1);
        }
        const double used = cpu() - c0;
        best = used < best ? used : best;
        *last = m;
    }
    return best;
}

int main(int argc, char **argv)
{
    const int rounds = argc > 1 ? atoi(argv[1]) : 5;
    if (rounds < 1) {
        fprintf(stderr, "usage: %s [rounds=5]\n", argv[0]);
        return 2;
    }
    tribo_scene s;
    char err[512];
    tribo_scene_defaults(&s);
    if (tribo_scene_apply(&s, "beta=0.5235987755982988 gap0=0 drop_speed=0 epsilon=1 mu=0.5 nu=0.3 "
                              "Gamma=1e-6 stick_model=1", err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    tribo_model *m;
    const double charged = fastest(&s, rounds, &m);
    tribo_stats st;
    tribo_get_stats(m, &st);
    printf("CPU %.4f s (fastest of %d)  steps %lld  events %lld  X %.17g  Q_static %.17g  "
           "Q_sliding %.17g", charged, rounds, st.steps, st.events, tribo_get(m, TRIBO_QUANTITY_X),
           tribo_get(m, TRIBO_QUANTITY_STATIC), tribo_get(m, TRIBO_QUANTITY_SLIDING));
    tribo_free(m);
    /* the motion alone: every charge model switched off */
    s.charge_model_static = s.charge_model_sliding = 0;
    printf("  motion alone %.4f s\n", fastest(&s, rounds, &m));
    tribo_free(m);
    return 0;
}

/* bench_charge_models: what each charge model costs on top of the motion.
 *
 *   tribo_bench_charge_models [t_end=1000] [rounds=1]
 *
 * Runs the paper's case (epsilon = 0.5, mu = nu = 0.1, model.md §7) with the fixed step
 * dt = 8e-5 with no charge model, the static, the sliding and both, in one process, and
 * prints steps per CPU second and each model's ratio to `none`. With rounds > 1 the
 * four runs are repeated in turn and the fastest of each kept, so that a noisy
 * neighbour on a shared machine hurts all four alike.
 */
#include "tribo.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cpu_clock.h"

int main(int argc, char **argv)
{
    double t_end = 1000.0;
    int rounds = 1;
    for (int i = 1; i < argc; i++) {
        if (strncmp(argv[i], "t_end=", 6) == 0)
            t_end = atof(argv[i] + 6);
        else if (strncmp(argv[i], "rounds=", 7) == 0)
            rounds = atoi(argv[i] + 7);
        else {
            fprintf(stderr, "usage: %s [t_end=1000] [rounds=1]\n", argv[0]);
            return 2;
        }
    }
    if (!(t_end > 0.0) || rounds < 1) {
        fprintf(stderr, "t_end must be > 0 and rounds >= 1\n");
        return 2;
    }
    static const char *const names[4] = {"none", "static", "sliding", "both"};
    double best[4] = {0, 0, 0, 0};
    long long steps[4] = {0, 0, 0, 0};
    double q_check[4][2];

    for (int r = 0; r < rounds; r++) {
        for (int c = 0; c < 4; c++) {
            tribo_scene scene;
            tribo_scene_defaults(&scene); /* the paper's low-friction case at eps = 0.5 */
            scene.integrator = TRIBO_INTEGRATOR_FIXED_STEP; /* at the paper's dt = 8e-5 */
            scene.charge_model_static = c & 1; /* c: 0 none, 1 static, 2 sliding, 3 both */
            scene.charge_model_sliding = c >> 1;
            char err[256];
            tribo_model *m = tribo_create(&scene, err, sizeof err);
            if (!m) {
                fprintf(stderr, "%s\n", err);
                return 1;
            }
            const double t0 = cpu_seconds();
            if (tribo_advance_fully(m, t_end) != TRIBO_OK) {
                fprintf(stderr, "%s\n", tribo_last_error(m));
                return 1;
            }
            const double cpu = cpu_seconds() - t0;
            tribo_stats st;
            tribo_get_stats(m, &st);
            steps[c] = st.steps;
            const double rate = (double)st.steps / cpu;
            if (rate > best[c])
                best[c] = rate;
            q_check[c][0] = tribo_get(m, TRIBO_QUANTITY_STATIC);
            q_check[c][1] = tribo_get(m, TRIBO_QUANTITY_SLIDING);
            tribo_free(m);
        }
    }
    printf("paper's case eps = 0.5, mu = nu = 0.1, dt = 8e-5, tau = 0..%g, best of %d round(s)\n",
           t_end, rounds);
    printf("%-8s %12s %14s %10s %10s %10s\n", "charge", "steps", "steps/s", "vs none",
           "Q_static", "Q_sliding");
    for (int c = 0; c < 4; c++)
        printf("%-8s %12lld %14.4g %10.3f %10.5f %10.5f\n", names[c], steps[c], best[c],
               best[c] / best[0], q_check[c][0], q_check[c][1]);
    return 0;
}

/* paper_run: the paper's drop (model.md §7) through the C API, printing the charge as it
 * builds up and the final state.
 *
 *   tribo_paper_run [name=value ...]
 *
 * Any scene parameter can be set by its name (epsilon=0.3 mu=1 nu=1 ...); t_end (default
 * 1000) and every (default 100) set the horizon and the print interval. On a chute
 * (chute_length=...) the run ends where the particle leaves it.
 */
#include "tribo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* t_end=..., every=... set the horizon; everything else goes to the scene. */
static int parse_args(int argc, char **argv, tribo_scene *scene, double *t_end, double *every)
{
    for (int i = 1; i < argc; i++) {
        char msg[256];
        if (strncmp(argv[i], "t_end=", 6) == 0 || strncmp(argv[i], "every=", 6) == 0) {
            char *end;
            const double value = strtod(argv[i] + 6, &end);
            if (*end || end == argv[i] + 6 || !(value > 0.0)) {
                fprintf(stderr, "%s: expected a number > 0\n", argv[i]);
                return -1;
            }
            *(argv[i][0] == 't' ? t_end : every) = value;
        } else if (tribo_scene_apply(scene, argv[i], msg, sizeof msg) != TRIBO_OK) {
            fprintf(stderr, "%s\n", msg);
            return -1;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    tribo_scene scene;
    tribo_scene_defaults(&scene);
    double t_end = 1000.0, every = 100.0;
    if (parse_args(argc, argv, &scene, &t_end, &every) != 0)
        return 2;

    char err[512];
    tribo_model *m = tribo_create(&scene, err, sizeof err);
    if (!m) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    printf("# epsilon = %g, mu = %g, nu = %g, Gamma = %g, beta = %g deg, tau0 = %g, "
           "charge_model_static = %d, charge_model_sliding = %d, integrator = %d (%s)\n",
           scene.epsilon, scene.mu, scene.nu, scene.Gamma, scene.beta * (180.0 / M_PI), scene.tau0,
           scene.charge_model_static, scene.charge_model_sliding, scene.integrator,
           scene.integrator == TRIBO_INTEGRATOR_FIXED_STEP ? "fixed step" : "CVODE");
    printf("%10s %12s %12s %12s %12s %10s %8s\n", "tau", "Q_static", "Q_sliding", "X", "Y",
           "contact", "turns");
    const clock_t start = clock();
    for (long k = 1;; k++) {
        double t = k * every;
        if (t > t_end)
            t = t_end;
        const tribo_status st = tribo_advance_fully(m, t);
        if (st != TRIBO_OK && st != TRIBO_ENDED) {
            fprintf(stderr, "%s\n", tribo_last_error(m));
            tribo_free(m);
            return 1;
        }
        printf("%10.2f %12.6f %12.6f %12.5f %12.6f %10.4f %8.3f\n", tribo_get(m, TRIBO_QUANTITY_TIME),
               tribo_get(m, TRIBO_QUANTITY_STATIC), tribo_get(m, TRIBO_QUANTITY_SLIDING),
               tribo_get(m, TRIBO_QUANTITY_X), tribo_get(m, TRIBO_QUANTITY_Y), tribo_get(m, TRIBO_QUANTITY_CONTACT_FRACTION),
               tribo_get(m, TRIBO_QUANTITY_TURNS));
        if (st == TRIBO_ENDED) { /* the particle left the chute (chute_length) */
            printf("%s\n", tribo_last_error(m));
            break;
        }
        if (t >= t_end)
            break;
    }
    const double cpu = (double)(clock() - start) / CLOCKS_PER_SEC;

    printf("\nfinal state at tau = %g:\n", tribo_get(m, TRIBO_QUANTITY_TIME));
    for (int q = TRIBO_QUANTITY_X; q < TRIBO_QUANTITY_COUNT; q++)
        printf("  %-18s % .10e\n", tribo_quantity_name((tribo_quantity)q),
               tribo_get(m, (tribo_quantity)q));
    tribo_stats stats;
    tribo_get_stats(m, &stats);
    printf("\n%lld steps, %lld sub-steps, %lld right-hand sides, %lld events, %.2f s CPU\n",
           stats.steps, stats.substeps, stats.rhs_evals, stats.events, cpu);
    tribo_free(m);
    return 0;
}

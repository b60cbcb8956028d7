/* paper_run: the paper's drop (MODEL §7) through the C API, printing the charge as it
 * builds up and the final state.
 *
 *   tribo_paper_run [name=value ...]
 *
 * Any scene parameter can be set by its name (epsilon=0.3 mu=1 nu=1 ...); t_end (default
 * 1000) and every (default 100) set the horizon and the print interval.
 */
#include "tribo.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int parse_args(int argc, char **argv, tribo_scene *scene, double *t_end, double *every)
{
    for (int i = 1; i < argc; i++) {
        char name[64];
        const char *eq = strchr(argv[i], '=');
        if (!eq || (size_t)(eq - argv[i]) >= sizeof name) {
            fprintf(stderr, "expected name=value, got '%s'\n", argv[i]);
            return -1;
        }
        memcpy(name, argv[i], (size_t)(eq - argv[i]));
        name[eq - argv[i]] = '\0';
        char *end;
        const double value = strtod(eq + 1, &end);
        if (*end != '\0' || end == eq + 1) {
            fprintf(stderr, "%s: '%s' is not a number\n", name, eq + 1);
            return -1;
        }
        if (strcmp(name, "t_end") == 0) {
            *t_end = value;
            continue;
        }
        if (strcmp(name, "every") == 0) {
            *every = value;
            continue;
        }
        const tribo_param_info *p = tribo_param_find(name);
        if (!p) {
            fprintf(stderr, "unknown parameter '%s'\n", name);
            return -1;
        }
        char msg[256];
        if (tribo_param_check(p, value, msg, sizeof msg) != TRIBO_OK) {
            fprintf(stderr, "%s\n", msg);
            return -1;
        }
        tribo_param_write(scene, p, value);
    }
    if (!(*t_end > 0.0) || !(*every > 0.0)) {
        fprintf(stderr, "t_end and every must be > 0\n");
        return -1;
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
           "charge_model = %d, integrator = %d (%s)\n",
           scene.epsilon, scene.mu, scene.nu, scene.Gamma, scene.beta, scene.tau0,
           scene.charge_model, scene.integrator,
           scene.integrator == TRIBO_INTEGRATOR_FIXED_STEP ? "fixed step" : "CVODE");
    printf("%10s %12s %12s %12s %12s %10s %8s\n", "tau", "Q_static", "Q_sliding", "X", "Y",
           "contact", "turns");
    const clock_t start = clock();
    for (long k = 1;; k++) {
        double t = k * every;
        if (t > t_end)
            t = t_end;
        if (tribo_advance(m, t) != TRIBO_OK) {
            fprintf(stderr, "%s\n", tribo_last_error(m));
            tribo_free(m);
            return 1;
        }
        printf("%10.2f %12.6f %12.6f %12.5f %12.6f %10.4f %8.3f\n", t, tribo_get(m, TRIBO_Q_STATIC),
               tribo_get(m, TRIBO_Q_SLIDING), tribo_get(m, TRIBO_Q_X), tribo_get(m, TRIBO_Q_Y),
               tribo_get(m, TRIBO_Q_CONTACT_FRACTION), tribo_get(m, TRIBO_Q_TURNS));
        if (t >= t_end)
            break;
    }
    const double cpu = (double)(clock() - start) / CLOCKS_PER_SEC;

    printf("\nfinal state at tau = %g:\n", tribo_get(m, TRIBO_Q_TIME));
    for (int q = TRIBO_Q_X; q < TRIBO_Q_COUNT; q++)
        printf("  %-18s % .10e\n", tribo_quantity_name((tribo_quantity)q),
               tribo_get(m, (tribo_quantity)q));
    tribo_stats stats;
    tribo_get_stats(m, &stats);
    printf("\n%lld steps, %lld right-hand sides, %.2f s CPU\n", stats.steps, stats.rhs_evals,
           cpu);
    tribo_free(m);
    return 0;
}

/* stability_report: runs the stability matrix and prints the markdown table of
   docs/stability.md.
 *
 *   tribo_stability_report [t_end=50]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "matrix.h"

int main(int argc, char **argv)
{
    double t_end = 50.0;
    if (argc > 1 && strncmp(argv[1], "t_end=", 6) == 0)
        t_end = atof(argv[1] + 6);
    printf("| case | integrator | CPU [s] | work | steps | sub-steps | events | max residual | "
           "energy scale | max delta_y | assumption warnings | Q_static | verdict |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    int failed = 0;
    for (int c = 0; c < N_STABILITY_CASES; c++) {
        for (int i = 0; i < N_STABILITY_INTEGRATORS; i++) {
            stability_result r;
            stability_run(&STABILITY_CASES[c], STABILITY_INTEGRATORS[i], t_end, 0.5, &r);
            const int ok = stability_passed(&r);
            failed += !ok;
            char verdict[600];
            if (ok)
                snprintf(verdict, sizeof verdict, "pass");
            else
                snprintf(verdict, sizeof verdict, "FAIL%s%s%s%s%s%s%s%s%s", r.finished ? "" : ": ",
                         r.finished ? "" : r.error, r.all_finite ? "" : " non-finite",
                         r.charge_ok ? "" : " charge", r.coulomb_ok ? "" : " Coulomb-limit",
                         r.contact_ok ? "" : " indented-in-flight",
                         r.max_residual <= STABILITY_RESIDUAL_BOUND * r.energy_scale ? "" : " energy",
                         r.work <= STABILITY_WORK_BOUND ? "" : " work", "");
            printf("| %s | %s | %.3f | %.3g | %lld | %lld | %lld | %.2e | %.2e | %.3g | %lld | %.4f | %s |\n",
                   STABILITY_CASES[c].name, stability_integrator_name(STABILITY_INTEGRATORS[i]),
                   r.cpu_seconds, r.work, r.stats.steps, r.stats.substeps, r.stats.events, r.max_residual,
                   r.energy_scale, r.max_delta_y, r.stats.assumption_warnings, r.q_static, verdict);
            fflush(stdout);
        }
    }
    fprintf(stderr, "%d of %d runs failed\n", failed, N_STABILITY_CASES * N_STABILITY_INTEGRATORS);
    return failed ? 1 : 0;
}

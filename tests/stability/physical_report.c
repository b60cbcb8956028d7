/* physical_scale_report: the physical-scale runs of test_physical_scale (physical_scale.h),
   as the markdown table of docs/stability.md's section on them.
 *
 *   tribo_physical_scale_report
 */
#include <stdio.h>
#include <string.h>

#include "physical_scale.h"

static int row(const char *name, const char *settings, int integrator)
{
    tribo_si_derived d;
    char msg[1024];
    if (physical_derive(settings, &d, msg, sizeof msg) != TRIBO_OK) {
        printf("| %s | %s | | | | | | | | | refused: %s |\n", name,
               stability_integrator_name(integrator), msg);
        return 0;
    }
    stability_result r;
    physical_run(&d, integrator, 5.0, 1e-3, &r);
    const int ok = stability_passed(&r) && r.exited;
    printf("| %s | %s | %.3g | %.4g | %.3f | %lld | %lld | %.2e | %.2e | %.3g | %s%s%s |\n", name,
           stability_integrator_name(integrator), d.scene.Gamma, r.t_reached * d.t_star,
           r.cpu_seconds, r.stats.steps, r.stats.events, r.max_residual, r.energy_scale,
           r.q_static, ok ? "pass" : "FAIL ", ok ? "" : r.error, ok || r.exited ? "" : " (no exit)");
    fflush(stdout);
    return !ok;
}

int main(void)
{
    printf("| set-up | integrator | Gamma | exit [s] | CPU [s] | steps | events | max residual | "
           "energy scale | Q_static | verdict |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    int failed = 0;
    const int cvode[] = {TRIBO_INTEGRATOR_CVODE, TRIBO_INTEGRATOR_CVODE_BDF};
    for (int i = 0; i < 2; i++) {
        failed += row("reference case (a = 0.5 mm)", PHYSICAL_REFERENCE, cvode[i]);
        failed += row("micro-scale (a = 50 um)", PHYSICAL_MICRO, cvode[i]);
    }
    for (int j = 0; j < N_PHYSICAL_SIZES; j++)
        for (int i = 0; i < N_PHYSICAL_MODULI; i++) {
            char name[64], settings[128];
            snprintf(name, sizeof name, "E = %g Pa, size 2a = %g m", PHYSICAL_MODULI[i],
                     PHYSICAL_SIZES[j]);
            snprintf(settings, sizeof settings, "youngs_modulus_particle=%g semi_major_axis=%g",
                     PHYSICAL_MODULI[i], PHYSICAL_SIZES[j] / 2);
            failed += row(name, settings, TRIBO_INTEGRATOR_CVODE);
        }
    fprintf(stderr, "%d runs failed\n", failed);
    return failed ? 1 : 0;
}

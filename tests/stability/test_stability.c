/* The stability matrix (matrix.c): every case with every integrator finishes,
   stays finite, keeps 0 <= Q_static <= 1 non-decreasing, holds the stretch within the
   Coulomb limit, does not sink into the plate in flight, balances its energy (model.md §6)
   and stays within the stated bound on its work (matrix.h). */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>

#include "matrix.h"

#include <string.h>

typedef struct run {
    int case_index, integrator;
} run;

ParameterizedTestParameters(stability, matrix)
{
    static run runs[256];
    int n = 0;
    for (int c = 0; c < N_STABILITY_CASES; c++)
        for (int i = 0; i < N_STABILITY_INTEGRATORS; i++) {
#ifdef TRIBO_SANITIZED
            /* Adams and BDF call the same code of ours (the right-hand side, the switches,
               the sweep), differing inside CVODE, which is not instrumented (a library
               built apart): the sanitizer build runs the fixed step and the default, Adams */
            if (STABILITY_INTEGRATORS[i] == TRIBO_INTEGRATOR_CVODE_BDF)
                continue;
            /* nor the fixed step's two costliest cases (17.5 and 2.7 million sub-steps:
               over a third of the matrix's time under the sanitizers), whose lines and
               branches of the core the other runs execute too (measured with gcov) */
            if (STABILITY_INTEGRATORS[i] == TRIBO_INTEGRATOR_FIXED_STEP &&
                (strcmp(STABILITY_CASES[c].name, "Gamma 0.5, drop 1, nu 1") == 0 ||
                 strcmp(STABILITY_CASES[c].name, "eps 0.01, mu 10, nu 3") == 0))
                continue;
#endif
            runs[n++] = (run){c, STABILITY_INTEGRATORS[i]};
        }
    return cr_make_param_array(run, runs, (size_t)n);
}

ParameterizedTest(run *r, stability, matrix, .timeout = STABILITY_TIMEOUT_S)
{
    const stability_case *c = &STABILITY_CASES[r->case_index];
    const char *integ = stability_integrator_name(r->integrator);
    stability_result res;
    stability_run(c, r->integrator, 50.0, 0.5, &res);
    cr_assert(res.finished, "%s, %s: stopped: %s", c->name, integ, res.error);
    cr_expect(res.all_finite, "%s, %s: a quantity went NaN or infinite", c->name, integ);
    cr_expect(res.charge_ok, "%s, %s: Q_static left [0, 1] or decreased", c->name, integ);
    cr_expect(res.coulomb_ok, "%s, %s: the stretch left the Coulomb limit", c->name, integ);
    cr_expect(res.contact_ok, "%s, %s: indented while in flight", c->name, integ);
    cr_expect(res.max_residual <= STABILITY_RESIDUAL_BOUND * res.energy_scale,
              "%s, %s: energy residual %.3g, scale %.3g", c->name, integ, res.max_residual,
              res.energy_scale);
    cr_expect(res.work <= STABILITY_WORK_BOUND, "%s, %s: %.3g units of work", c->name, integ,
              res.work);
}

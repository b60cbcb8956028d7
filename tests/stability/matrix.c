/* matrix.c: the stability matrix (see matrix.h). */
#include "matrix.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#define CASE(id, body) static void id(tribo_scene *s) { body; }
CASE(paper_low, (void)s)
CASE(needle_001, s->epsilon = 0.01)
CASE(needle_002, s->epsilon = 0.02)
CASE(near_disc, s->epsilon = 0.999)
CASE(disc, s->epsilon = 1.0)
CASE(mu_0, s->mu = 0.0)
CASE(mu_10, s->mu = 10.0)
CASE(nu_0, s->nu = 0.0)
CASE(nu_1, s->nu = 1.0)
CASE(nu_3, s->nu = 3.0)
CASE(gamma_stiff, s->Gamma = 1e-6)
CASE(gamma_soft, s->Gamma = 0.5)
CASE(tau0_fast, s->tau0 = 1e-6)
CASE(tau0_slow, s->tau0 = 1e6)
CASE(tau_r_fast, s->tau_r = 1e-6)
CASE(tau_r_slow, s->tau_r = 1e6)
CASE(eta_0, s->eta = 0.0)
CASE(eta_10, s->eta = 10.0)
CASE(beta_0, s->beta = 0.0)
CASE(beta_89, s->beta = 89.0)
CASE(drop_0, s->drop_speed = 0.0)
CASE(drop_1, s->drop_speed = 1.0)
CASE(n_16, s->n_segments = 16)
CASE(n_100000, s->n_segments = 100000)
CASE(high_friction, s->mu = s->nu = 1.0)
CASE(needle_no_slip_hard, { s->epsilon = 0.01; s->mu = 10.0; s->nu = 3.0; })
CASE(soft_fast_drop, { s->Gamma = 0.5; s->drop_speed = 1.0; s->nu = 1.0; })
CASE(stiff_charging, { s->tau0 = 1e-6; s->tau_r = 1e-6; s->eta = 10.0; s->n_segments = 100000; })
CASE(steep_frictionless, { s->beta = 89.0; s->mu = 0.0; s->nu = 0.0; s->drop_speed = 1.0; })
CASE(flat_rest_elastic, { s->beta = 0.0; s->drop_speed = 0.0; s->nu = 0.0; s->epsilon = 0.02; })
#undef CASE

const stability_case STABILITY_CASES[] = {
    {"paper, low friction", paper_low},
    {"epsilon = 0.01", needle_001},
    {"epsilon = 0.02", needle_002},
    {"epsilon = 0.999", near_disc},
    {"epsilon = 1", disc},
    {"mu = 0", mu_0},
    {"mu = 10", mu_10},
    {"nu = 0", nu_0},
    {"nu = 1", nu_1},
    {"nu = 3", nu_3},
    {"Gamma = 1e-6", gamma_stiff},
    {"Gamma = 0.5", gamma_soft},
    {"tau0 = 1e-6", tau0_fast},
    {"tau0 = 1e6", tau0_slow},
    {"tau_r = 1e-6", tau_r_fast},
    {"tau_r = 1e6", tau_r_slow},
    {"eta = 0", eta_0},
    {"eta = 10", eta_10},
    {"beta = 0", beta_0},
    {"beta = 89", beta_89},
    {"drop speed 0", drop_0},
    {"drop speed 1", drop_1},
    {"N = 16", n_16},
    {"N = 100000", n_100000},
    {"paper, high friction", high_friction},
    {"eps 0.01, mu 10, nu 3", needle_no_slip_hard},
    {"Gamma 0.5, drop 1, nu 1", soft_fast_drop},
    {"tau0 = tau_r = 1e-6, eta 10, N 1e5", stiff_charging},
    {"beta 89, mu = nu = 0, drop 1", steep_frictionless},
    {"flat, at rest, nu 0, eps 0.02", flat_rest_elastic},
};
const int N_STABILITY_CASES = sizeof STABILITY_CASES / sizeof STABILITY_CASES[0];

const int STABILITY_INTEGRATORS[] = {TRIBO_INTEGRATOR_FIXED_STEP, TRIBO_INTEGRATOR_CVODE,
                                     TRIBO_INTEGRATOR_CVODE_BDF};
const int N_STABILITY_INTEGRATORS = 3;

const char *stability_integrator_name(int integrator)
{
    switch (integrator) {
    case TRIBO_INTEGRATOR_FIXED_STEP: return "fixed step";
    case TRIBO_INTEGRATOR_CVODE: return "CVODE Adams";
    case TRIBO_INTEGRATOR_CVODE_BDF: return "CVODE BDF";
    }
    return "?";
}

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void stability_run(const stability_case *c, int integrator, double t_end, double every,
                   stability_result *r)
{
    memset(r, 0, sizeof *r);
    tribo_scene s;
    tribo_scene_defaults(&s); /* MODEL §7, low friction, eps = 0.5 */
    c->apply(&s);
    s.integrator = integrator;
    tribo_model *m = tribo_create(&s, r->error, sizeof r->error);
    if (!m)
        return;
    const double start = cpu_now();
    const double E0 = tribo_get(m, TRIBO_Q_ENERGY);
    r->all_finite = r->charge_ok = r->coulomb_ok = r->contact_ok = 1;
    r->energy_scale = fabs(E0);
    double q_prev = 0.0;
    int k = 1;
    for (; k * every <= t_end + 1e-9; k++) {
        if (tribo_advance(m, k * every) != TRIBO_OK) {
            snprintf(r->error, sizeof r->error, "%s", tribo_last_error(m));
            break;
        }
        for (int q = 0; q < TRIBO_Q_COUNT; q++)
            if (!isfinite(tribo_get(m, (tribo_quantity)q)))
                r->all_finite = 0;
        const double Q = tribo_get(m, TRIBO_Q_STATIC);
        if (!(Q >= q_prev && Q <= 1.0))
            r->charge_ok = 0;
        q_prev = Q;
        const double dx = tribo_get(m, TRIBO_Q_DELTA_X), psi_n = tribo_get(m, TRIBO_Q_PSI_N);
        if (fabs(dx) > s.mu * psi_n * (1.0 + 1e-9) + 1e-300)
            r->coulomb_ok = 0;
        /* a located contact switch is exact to rounding of the contact root */
        if (tribo_get(m, TRIBO_Q_IN_CONTACT) == 0.0 && tribo_get(m, TRIBO_Q_DELTA_Y) > 1e-12)
            r->contact_ok = 0;
        const double E = tribo_get(m, TRIBO_Q_ENERGY), W = tribo_get(m, TRIBO_Q_WORK_DISSIPATED),
                     We = tribo_get(m, TRIBO_Q_WORK_EXTERNAL);
        const double U = tribo_get(m, TRIBO_Q_U), V = tribo_get(m, TRIBO_Q_V);
        r->max_residual = fmax(r->max_residual, fabs(E + W - We - E0));
        r->energy_scale = fmax(r->energy_scale, fmax(fabs(E), fmax(fabs(W), 0.5 * (U * U + V * V))));
        r->max_delta_y = fmax(r->max_delta_y, tribo_get(m, TRIBO_Q_DELTA_Y));
    }
    r->finished = k * every > t_end + 1e-9;
    r->cpu_seconds = cpu_now() - start;
    tribo_get_stats(m, &r->stats);
    r->q_static = tribo_get(m, TRIBO_Q_STATIC);
    r->q_sliding = tribo_get(m, TRIBO_Q_SLIDING);
    tribo_free(m);
}

int stability_passed(const stability_result *r)
{
    return r->finished && r->all_finite && r->charge_ok && r->coulomb_ok && r->contact_ok &&
           r->max_residual <= STABILITY_RESIDUAL_BOUND * r->energy_scale &&
           r->cpu_seconds <= STABILITY_CPU_BOUND;
}

/* matrix.c: the stability matrix (see matrix.h). */
#include "matrix.h"

#include "model.h"
#include "si.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

const stability_case STABILITY_CASES[] = {
    {"paper, low friction", ""},
    {"epsilon = 0.01", "epsilon=0.01"},
    {"epsilon = 0.02", "epsilon=0.02"},
    {"epsilon = 0.999", "epsilon=0.999"},
    {"epsilon = 1", "epsilon=1.0"},
    {"mu = 0", "mu=0.0"},
    {"mu = 10", "mu=10.0"},
    {"nu = 0", "nu=0.0"},
    {"nu = 1", "nu=1.0"},
    {"nu = 3", "nu=3.0"},
    {"Gamma = 1e-6", "Gamma=1e-6"},
    {"Gamma = 0.5", "Gamma=0.5"},
    {"tau0 = 1e-6", "tau0=1e-6"},
    {"tau0 = 1e6", "tau0=1e6"},
    {"tau_r = 1e-6", "tau_r=1e-6"},
    {"tau_r = 1e6", "tau_r=1e6"},
    {"eta = 0", "eta=0.0"},
    {"eta = 10", "eta=10.0"},
    {"beta = 0", "beta=0.0"},
    /* beta in rad: 1.5533430342749532 is 89 * (M_PI / 180.0), 89 degrees */
    {"beta = 89", "beta=1.5533430342749532"},
    {"drop speed 0", "drop_speed=0.0"},
    {"drop speed 1", "drop_speed=1.0"},
    {"N = 16", "n_segments=16"},
    {"N = 100000", "n_segments=100000"},
    {"paper, high friction", "mu=1.0 nu=1.0"},
    {"eps 0.01, mu 10, nu 3", "epsilon=0.01 mu=10.0 nu=3.0"},
    {"Gamma 0.5, drop 1, nu 1", "Gamma=0.5 drop_speed=1.0 nu=1.0"},
    {"tau0 = tau_r = 1e-6, eta 10, N 1e5", "tau0=1e-6 tau_r=1e-6 eta=10.0 n_segments=100000"},
    {"beta 89, mu = nu = 0, drop 1", "beta=1.5533430342749532 mu=0.0 nu=0.0 drop_speed=1.0"},
    {"flat, at rest, nu 0, eps 0.02", "beta=0.0 drop_speed=0.0 nu=0.0 epsilon=0.02"},
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
    tribo_scene_defaults(&s); /* model.md §7, low friction, eps = 0.5 */
    if (tribo_scene_apply(&s, c->settings, r->error, sizeof r->error) != TRIBO_OK)
        return;
    s.integrator = integrator;
    stability_run_scene(&s, NULL, t_end, every, r);
}

void stability_run_scene(const tribo_scene *s, const tribo_si_derived *si, double t_end,
                         double every, stability_result *r)
{
    memset(r, 0, sizeof *r);
    tribo_model *m = tribo_create(s, r->error, sizeof r->error);
    if (!m)
        return;
    const double start = cpu_now();
    const double E0 = tribo_get(m, TRIBO_QUANTITY_ENERGY);
    r->all_finite = r->charge_ok = r->coulomb_ok = r->contact_ok = 1;
    r->energy_scale = fabs(E0);
    double q_prev = 0.0;
    int k = 1;
    for (; k * every <= t_end + 1e-9; k++) {
        /* (tribo_advance_fully, each advance's work booked: model.h) */
        tribo_status st;
        while ((st = tribo_advance(m, k * every)) == TRIBO_INCOMPLETE)
            r->work += m->work;
        r->work += m->work;
        if (st == TRIBO_ENDED)
            r->exited = 1;
        else if (st != TRIBO_OK) {
            snprintf(r->error, sizeof r->error, "%s", tribo_last_error(m));
            break;
        }
        for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++)
            if (!isfinite(tribo_get(m, (tribo_quantity)q)))
                r->all_finite = 0;
        for (int q = 0; si && q < TRIBO_SI_QUANTITY_COUNT; q++)
            if (!isfinite(tribo_si_get(si, m, (tribo_si_quantity)q)))
                r->all_finite = 0;
        const double Q = tribo_get(m, TRIBO_QUANTITY_STATIC);
        if (!(Q >= q_prev && Q <= 1.0))
            r->charge_ok = 0;
        q_prev = Q;
        const double dx = tribo_get(m, TRIBO_QUANTITY_DELTA_X), psi_n = tribo_get(m, TRIBO_QUANTITY_PSI_N);
        if (fabs(dx) > s->mu * psi_n * (1.0 + 1e-9) + 1e-300)
            r->coulomb_ok = 0;
        /* a located contact switch is exact to rounding of the contact root */
        if (tribo_get(m, TRIBO_QUANTITY_IN_CONTACT) == 0.0 && tribo_get(m, TRIBO_QUANTITY_DELTA_Y) > 1e-12)
            r->contact_ok = 0;
        const double E = tribo_get(m, TRIBO_QUANTITY_ENERGY), W = tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED),
                     We = tribo_get(m, TRIBO_QUANTITY_WORK_EXTERNAL);
        const double U = tribo_get(m, TRIBO_QUANTITY_U), V = tribo_get(m, TRIBO_QUANTITY_V);
        r->max_residual = fmax(r->max_residual, fabs(E + W - We - E0));
        r->energy_scale = fmax(r->energy_scale, fmax(fabs(E), fmax(fabs(W), 0.5 * (U * U + V * V))));
        r->max_delta_y = fmax(r->max_delta_y, tribo_get(m, TRIBO_QUANTITY_DELTA_Y));
        if (r->exited)
            break;
    }
    r->finished = r->exited || k * every > t_end + 1e-9;
    r->cpu_seconds = cpu_now() - start;
    tribo_get_stats(m, &r->stats);
    r->t_reached = tribo_get(m, TRIBO_QUANTITY_TIME);
    r->q_static = tribo_get(m, TRIBO_QUANTITY_STATIC);
    r->q_sliding = tribo_get(m, TRIBO_QUANTITY_SLIDING);
    tribo_free(m);
}

int stability_passed(const stability_result *r)
{
    return r->finished && r->all_finite && r->charge_ok && r->coulomb_ok && r->contact_ok &&
           r->max_residual <= STABILITY_RESIDUAL_BOUND * r->energy_scale &&
           r->work <= STABILITY_WORK_BOUND;
}

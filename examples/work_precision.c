/* work_precision: the runs behind the work-precision report (examples/work_precision.py).
 *
 *   tribo_work_precision [quick | chaos]
 *
 * For each case of the report (the paper's set-up, model.md §7, at a few roundness ratios
 * and frictions) it runs the fixed step at dt = 1e-2 ... 8e-5 and CVODE at rtol = 1e-3
 * ... 1e-10, plus a reference (CVODE, rtol 1e-12), and prints one CSV row per run: the
 * CPU time, the work, and every quantity the report measures errors on. `quick` runs a
 * short horizon with few settings (a smoke test of the pipeline, not a report). `chaos`
 * follows each case with CVODE alone to tau = 3000 and prints the state every 250, to
 * show where pointwise error stops converging.
 */
#include "tribo.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

typedef struct report_case {
    const char *name;
    double epsilon, mu;
} report_case;

static const report_case CASES[] = {
    {"eps0.3_low", 0.3, 0.1},
    {"eps0.9_low", 0.9, 0.1},
    {"eps0.6_high", 0.6, 1.0},
    {"disc_low", 1.0, 0.1},
};

/* Times at which the state is recorded: the short horizon, then the long ones that show
   whether pointwise error still converges there. */
static const double REPORT_HORIZONS[] = {20.0, 100.0, 300.0, 1000.0};
static const double CHAOS_HORIZONS[] = {250, 500, 750, 1000, 1250, 1500, 1750, 2000, 2250, 2500, 2750, 3000};
#define MAX_HORIZONS 12
static const double *HORIZONS = REPORT_HORIZONS;
static int N_HORIZONS = 4;

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct run_result {
    double cpu;
    tribo_stats stats;
    double state[MAX_HORIZONS][6];
    double q_static, q_sliding, contact_fraction, turns, residual;
} run_result;

/* One run to t_end, recording the state at the horizons and the largest energy-balance
   residual |E + W_diss - W_ext - E(0)| (model.md §6) at unit intervals. */
static int run(const tribo_scene *s, double t_end, run_result *r)
{
    char err[512];
    tribo_model *m = tribo_create(s, err, sizeof err);
    if (!m) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    const tribo_quantity state_q[6] = {TRIBO_QUANTITY_X, TRIBO_QUANTITY_Y, TRIBO_QUANTITY_PHI,
                                       TRIBO_QUANTITY_U, TRIBO_QUANTITY_V, TRIBO_QUANTITY_OMEGA};
    const double E0 = tribo_get(m, TRIBO_QUANTITY_ENERGY);
    int h = 0;
    r->residual = 0.0;
    const double start = cpu_seconds();
    for (double t = 1.0; t <= t_end + 1e-9; t += 1.0) {
        if (tribo_advance_fully(m, t) != TRIBO_OK) {
            fprintf(stderr, "%s\n", tribo_last_error(m));
            tribo_free(m);
            return -1;
        }
        const double res = tribo_get(m, TRIBO_QUANTITY_ENERGY) + tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED) -
                           tribo_get(m, TRIBO_QUANTITY_WORK_EXTERNAL) - E0;
        r->residual = fmax(r->residual, fabs(res));
        while (h < N_HORIZONS && fabs(t - HORIZONS[h]) < 1e-9) {
            for (int i = 0; i < 6; i++)
                r->state[h][i] = tribo_get(m, state_q[i]);
            h++;
        }
    }
    r->cpu = cpu_seconds() - start;
    r->q_static = tribo_get(m, TRIBO_QUANTITY_STATIC);
    r->q_sliding = tribo_get(m, TRIBO_QUANTITY_SLIDING);
    r->contact_fraction = tribo_get(m, TRIBO_QUANTITY_CONTACT_FRACTION);
    r->turns = tribo_get(m, TRIBO_QUANTITY_TURNS);
    tribo_get_stats(m, &r->stats);
    for (; h < N_HORIZONS; h++)
        for (int i = 0; i < 6; i++)
            r->state[h][i] = NAN;
    tribo_free(m);
    return 0;
}

/* Runs shorter than this are repeated and their CPU time averaged: a 5 ms run on a
   shared machine is noise. */
#define MIN_CPU 0.3

static int report(const report_case *c, const char *integrator, double setting, double t_end)
{
    tribo_scene s;
    tribo_scene_defaults(&s); /* model.md §7 */
    s.epsilon = c->epsilon;
    s.mu = s.nu = c->mu;
    if (strcmp(integrator, "fixed") == 0) {
        s.integrator = TRIBO_INTEGRATOR_FIXED_STEP;
        s.dt = setting;
    } else {
        s.integrator = TRIBO_INTEGRATOR_CVODE;
        s.rtol = setting;
        s.atol = setting * 1e-2;
    }
    run_result r;
    double total = 0.0;
    int repeats = 0;
    do {
        if (run(&s, t_end, &r) != 0)
            return -1;
        total += r.cpu;
        repeats++;
    } while (total < MIN_CPU && repeats < 50);
    printf("%s,%s,%.3g,%.6g,%d,%lld,%lld,%lld", c->name, integrator, setting, total / repeats,
           repeats, r.stats.steps, r.stats.rhs_evals, r.stats.events);
    for (int h = 0; h < N_HORIZONS; h++)
        for (int i = 0; i < 6; i++)
            printf(",%.17g", r.state[h][i]);
    printf(",%.17g,%.17g,%.17g,%.17g,%.17g\n", r.q_static, r.q_sliding, r.contact_fraction, r.turns,
           r.residual);
    fflush(stdout);
    return 0;
}

static int chaos(void)
{
    static const double rtols[] = {1e-6, 1e-8, 1e-10, 1e-11, 1e-12};
    HORIZONS = CHAOS_HORIZONS;
    N_HORIZONS = 12;
    printf("case,integrator,setting,cpu_s,repeats,steps,rhs_evals,events");
    for (int h = 0; h < N_HORIZONS; h++)
        printf(",X_%g,Y_%g,phi_%g,U_%g,V_%g,Omega_%g", HORIZONS[h], HORIZONS[h], HORIZONS[h],
               HORIZONS[h], HORIZONS[h], HORIZONS[h]);
    printf(",Q_static,Q_sliding,contact_fraction,turns,energy_residual\n");
    for (size_t k = 0; k < sizeof CASES / sizeof CASES[0]; k++)
        for (int i = 0; i < 5; i++)
            if (report(&CASES[k], "cvode", rtols[i], 3000.0) != 0)
                return 1;
    return 0;
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "chaos") == 0)
        return chaos();
    const int quick = argc > 1 && strcmp(argv[1], "quick") == 0;
    const double t_end = quick ? 20.0 : 1000.0;
    static const double dts[] = {1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 8e-5};
    static const double rtols[] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
    const int n_dt = quick ? 2 : 7, n_rtol = quick ? 2 : 8;

    printf("case,integrator,setting,cpu_s,repeats,steps,rhs_evals,events");
    for (int h = 0; h < N_HORIZONS; h++)
        printf(",X_%g,Y_%g,phi_%g,U_%g,V_%g,Omega_%g", HORIZONS[h], HORIZONS[h], HORIZONS[h],
               HORIZONS[h], HORIZONS[h], HORIZONS[h]);
    printf(",Q_static,Q_sliding,contact_fraction,turns,energy_residual\n");
    for (size_t k = 0; k < sizeof CASES / sizeof CASES[0]; k++) {
        if (report(&CASES[k], "reference", 1e-12, t_end) != 0 ||
            report(&CASES[k], "reference_check", 1e-11, t_end) != 0)
            return 1;
        for (int i = 0; i < n_rtol; i++)
            if (report(&CASES[k], "cvode", rtols[i], t_end) != 0)
                return 1;
        for (int i = 0; i < n_dt; i++)
            if (report(&CASES[k], "fixed", dts[i], t_end) != 0)
                return 1;
    }
    return 0;
}

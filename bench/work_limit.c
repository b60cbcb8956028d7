/* The work limit measured (scripts/bench_work_limit.sh; docs/fmu.md, "The work limit").

   1. The CPU one unit of work costs: scenes where one kind of work dominates, and the SI
      set-ups and the dimensionless ones on 1e5 segments that cost the most per unit,
      advanced until the default limit stops an advance; CPU per advance / work_limit.
   2. Ordinary use within the default: the paper's drop with the fixed step at its dt and
      with CVODE, in advances of 100 (none may stop early).
   3. The bound: random scenes with every parameter at the end of its range, its default,
      or (integers) anything between; three advances of 0.1 and one of 100 each; the worst
      CPU of one advance at the default limit.

   Usage: tribo_bench_work_limit [scenes=300] [seed=1] */
#define _POSIX_C_SOURCE 199309L
#include "si.h"
#include "tribo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A model of dimensionless settings, or (si) of the SI front end's settings; *time_unit:
   the settings' unit of time in the model's (1, or 1 / t_star). */
static tribo_model *make_scene(const char *settings, int si, double *time_unit)
{
    tribo_scene s;
    char msg[512];
    tribo_scene_defaults(&s);
    *time_unit = 1.0;
    if (si) {
        tribo_si_scene sis;
        tribo_si_derived d;
        tribo_si_scene_defaults(&sis);
        if (tribo_si_scene_apply(&sis, settings, msg, sizeof msg) != TRIBO_OK ||
            tribo_si_derive(&sis, &d, msg, sizeof msg) != TRIBO_OK) {
            fprintf(stderr, "%s: %s\n", settings, msg);
            exit(1);
        }
        s = d.scene;
        *time_unit = 1.0 / d.t_star;
    } else if (tribo_scene_apply(&s, settings, msg, sizeof msg) != TRIBO_OK ||
               tribo_scene_validate(&s, msg, sizeof msg) != TRIBO_OK) {
        fprintf(stderr, "%s: %s\n", settings, msg);
        exit(1);
    }
    tribo_model *m = tribo_create(&s, msg, sizeof msg);
    if (!m) {
        fprintf(stderr, "%s: %s\n", settings, msg);
        exit(1);
    }
    return m;
}

/* The SI scenes on an unbounded chute: on the default one (0.3 m) the grain leaves long
   before an advance reaches the limit */
#define ENDLESS " chute_length=inf"

static tribo_model *make(const char *settings)
{
    double unit;
    return make_scene(settings, 0, &unit);
}

/* Advance in steps of h (in the settings' unit of time) until an advance stops at the
   limit; the CPU of the stopped ones. */
static void unit_cost_of(const char *what, const char *settings, int si, double h)
{
    double time_unit;
    tribo_model *m = make_scene(settings, si, &time_unit);
    h *= time_unit;
    double spent = 0.0;
    int stopped = 0;
    for (int k = 0; k < 400 && stopped < 3; k++) {
        const double t = tribo_get(m, TRIBO_QUANTITY_TIME);
        const double c0 = cpu();
        const tribo_status st = tribo_advance(m, t + h);
        const double c = cpu() - c0;
        if (st == TRIBO_INCOMPLETE) {
            spent += c;
            stopped++;
        } else if (st != TRIBO_OK) {
            break;
        }
    }
    if (stopped)
        printf("  %-34s %6.3f us per unit  (%d advances stopped by the limit)\n", what,
               spent / stopped, stopped);
    else
        printf("  %-34s no advance reached the limit\n", what);
    tribo_free(m);
}

static void unit_cost(const char *what, const char *settings, double h)
{
    unit_cost_of(what, settings, 0, h);
}

static void ordinary(const char *what, const char *settings, double h, double t_end)
{
    tribo_model *m = make(settings);
    int early = 0;
    double worst = 0.0;
    for (double t = h; t <= t_end; t += h) {
        const double c0 = cpu();
        const tribo_status st = tribo_advance(m, t);
        worst = fmax(worst, cpu() - c0);
        early += st == TRIBO_INCOMPLETE;
        if (st != TRIBO_OK && st != TRIBO_INCOMPLETE)
            break;
    }
    printf("  %-34s advances of %g to %g: %d stopped early, slowest %.3f s of CPU\n", what, h,
           t_end, early, worst);
    tribo_free(m);
}

/* A parameter at random: an end of its range, its default, or an integer between. */
static double pick(const tribo_param_info *p, unsigned *seed)
{
    const int c = rand_r(seed) % 4;
    double lo = p->min, hi = p->max;
    if (!isfinite(hi))
        hi = 1e6;
    if (!p->min_inclusive)
        lo = lo == 0.0 ? 1e-300 : nextafter(lo, hi);
    if (!p->max_inclusive)
        hi = nextafter(hi, lo);
    if (c == 0)
        return lo;
    if (c == 1)
        return hi;
    if (c == 2 && p->type != TRIBO_TYPE_REAL)
        return floor(lo + (hi - lo + 1) * (rand_r(seed) / (RAND_MAX + 1.0)));
    return p->start;
}

/* The report, section after section in the order it prints: one function, so that it
   reads as the report does. */
int main(int argc, char **argv)
{
    const int scenes = argc > 1 ? atoi(argv[1]) : 300;
    unsigned seed = argc > 2 ? (unsigned)atoi(argv[2]) : 1u;

    printf("1. CPU per unit of work, per kind (the default limit, 1e6)\n");
    unit_cost("fixed steps (RK4)", "integrator=0", 1000.0);
    unit_cost("CVODE steps (no charging)", "charge_model_static=0 charge_model_sliding=0 n_segments=16 stick_model=0", 1e5);
    unit_cost("the sweep's looks (spinning needle)", "epsilon=1e-3 Gamma=10 tau0=1e9 eta=0 "
              "tau_r=1e9 n_segments=100000 phi0=-1e6 Omega0=-100 rtol=1e-14", 0.1);
    unit_cost("segment updates (wide contact)", "mu=100 eta=0 tau_r=1e9 n_segments=100000 "
              "v_reg=1000 phi0=1e6 drop_speed=10", 0.1);
    unit_cost("flight evaluations (Gamma 1e-12)", "mu=100 Gamma=1e-12 eta=0 n_segments=16 "
              "phi0=-1e6 Omega0=100 integrator=2 atol=1 drop_angle=-1.5", 0.1);
    unit_cost("CVODE, BDF (no charging)", "charge_model_static=0 charge_model_sliding=0 "
              "n_segments=16 integrator=2", 1e5);
    unit_cost("CVODE, rigid stick (no charging)", "charge_model_static=0 "
              "charge_model_sliding=0 n_segments=16 stick_model=1", 1e5);
    unit_cost("1e5 segments, Sigma_bd = 1e-6", "n_segments=100000 Sigma_bd=1e-6", 1000.0);
    unit_cost("1e5 segments, spheroid, Gamma 10", "n_segments=100000 grain_geometry=1 Gamma=10",
              1000.0);
    unit_cost("the same, tau0 = 0", "n_segments=100000 grain_geometry=1 Gamma=10 tau0=0", 1000.0);
    unit_cost("1e5 segments, fixed step, limit", "n_segments=100000 Sigma_bd=1e-3 integrator=0",
              1000.0);
    unit_cost_of("SI, epsilon = 1", "epsilon=1" ENDLESS, 1, 10.0);
    unit_cost_of("SI, epsilon = 1, 1e5 segments", "epsilon=1 n_segments=100000" ENDLESS, 1, 10.0);
    unit_cost_of("SI, epsilon = 1, charging_time = 1e-3", "epsilon=1 charging_time=1e-3" ENDLESS, 1,
                 10.0);
    unit_cost_of("SI, epsilon = 0.001", "epsilon=0.001" ENDLESS, 1, 10.0);
    unit_cost_of("SI, gravity = 1e4", "gravity=1e4" ENDLESS, 1, 10.0);
    unit_cost_of("SI, gravity = 1e4, 1e5 segments", "gravity=1e4 n_segments=100000" ENDLESS, 1,
                 10.0);
    unit_cost_of("SI, Young's moduli 1e3",
                 "youngs_modulus_particle=1e3 youngs_modulus_wall=1e3" ENDLESS, 1, 10.0);
    unit_cost_of("SI, epsilon = 0.001, no charging", "epsilon=0.001 charge_model_static=0 "
                 "charge_model_sliding=0" ENDLESS, 1, 10.0);

    printf("2. Ordinary use (the paper's drop)\n");
    ordinary("fixed step, dt = 8e-5", "integrator=0", 100.0, 1000.0);
    ordinary("CVODE", "", 100.0, 3000.0);

    printf("3. The bound: %d random scenes at the ends of the ranges (seed %u)\n", scenes, seed);
    size_t n;
    const tribo_param_info *table = tribo_param_table(&n);
    double worst = 0.0, total = 0.0;
    long advances = 0, over = 0;
    char worst_scene[4200] = "";
    for (int r = 0; r < scenes; r++) {
        tribo_scene s;
        char msg[512], settings[4096] = "";
        tribo_scene_defaults(&s);
        for (size_t i = 0; i < n; i++) {
            if (!strcmp(table[i].name, "work_limit") || !strcmp(table[i].name, "chute_length") ||
                !strcmp(table[i].name, "X0") || rand_r(&seed) % 2)
                continue;
            const double v = pick(&table[i], &seed);
            tribo_scene trial = s;
            if (tribo_scene_set(&trial, table[i].name, v, msg, sizeof msg) == TRIBO_OK &&
                tribo_scene_check_combinations(&trial, msg, sizeof msg) == TRIBO_OK) {
                s = trial;
                const size_t used = strlen(settings);
                snprintf(settings + used, sizeof settings - used, "%s=%.17g ", table[i].name, v);
            }
        }
        tribo_model *m = tribo_create(&s, msg, sizeof msg);
        if (!m)
            continue;
        const double steps[] = {0.1, 0.1, 0.1, 100.0};
        for (size_t k = 0; k < sizeof steps / sizeof steps[0]; k++) {
            const double t = tribo_get(m, TRIBO_QUANTITY_TIME);
            const double c0 = cpu();
            const tribo_status st = tribo_advance(m, t + steps[k]);
            const double c = cpu() - c0;
            total += c;
            advances++;
            over += c > 1.0;
            if (c > worst) {
                worst = c;
                snprintf(worst_scene, sizeof worst_scene, "%s(advance %zu of %g)", settings, k,
                         steps[k]);
            }
            if (st != TRIBO_OK && st != TRIBO_INCOMPLETE)
                break;
        }
        tribo_free(m);
    }
    printf("  %ld advances, %.1f s of CPU in all; over 1 s: %ld; the slowest %.3f s:\n    %s\n",
           advances, total, over, worst, worst_scene);
    return 0;
}

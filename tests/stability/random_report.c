/* random_setups: runs the named set-ups and `count` random physical set-ups (random_setups.h)
 * under both stick models and prints every run that failed, then a summary; exits 1 if one
 * did (scripts/random_setups.sh).
 *
 *   tribo_random_setups [count=1000] [seed=1] [horizon_s=0.5] [work=5e5] [verbose=0]
 *
 * work: the most work one run may do (units of integrator.h, about half a microsecond of CPU
 * each): a run still going then is counted apart, not as a failure.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "random_setups.h"

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *const OUTCOME[] = {"ended", "horizon", "work cap", "refused", "FAILED"};

typedef struct tally {
    int n[5];
    double cpu, slowest;
} tally;

static random_outcome run_one(const char *name, const random_setup *r, double horizon_s, double work,
                              int verbose, tally *t)
{
    char why[1024];
    double t_end;
    const double c0 = cpu_seconds();
    const random_outcome o = random_setup_run(r, horizon_s, work, why, sizeof why, &t_end);
    const double c = cpu_seconds() - c0;
    t->n[o]++;
    t->cpu += c;
    if (c > t->slowest)
        t->slowest = c;
    if (o == RANDOM_FAILED || verbose)
        printf("%s: %s at %.6g s (%.3f s CPU): %s F_N_ext=%.17g: %s\n", name, OUTCOME[o], t_end, c,
               r->settings, r->F_N, why);
    fflush(stdout);
    return o;
}

int main(int argc, char **argv)
{
    int count = 1000, verbose = 0;
    unsigned long long seed = 1;
    double horizon_s = 0.5, work = 5e5;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strncmp(a, "count=", 6))
            count = atoi(a + 6);
        else if (!strncmp(a, "seed=", 5))
            seed = strtoull(a + 5, NULL, 10);
        else if (!strncmp(a, "horizon_s=", 10))
            horizon_s = atof(a + 10);
        else if (!strncmp(a, "work=", 5))
            work = atof(a + 5);
        else if (!strncmp(a, "verbose=", 8))
            verbose = atoi(a + 8);
        else {
            fprintf(stderr, "usage: %s [count=1000] [seed=1] [horizon_s=0.5] [work=5e5] [verbose=0]\n",
                    argv[0]);
            return 2;
        }
    }
    int failed = 0;
    tally named;
    memset(&named, 0, sizeof named);
    for (int k = 0; k < N_NAMED_SETUPS; k++)
        failed += run_one(NAMED_SETUPS[k].name, &NAMED_SETUPS[k].setup, horizon_s, work, verbose,
                          &named) == RANDOM_FAILED;
    tally by_model[2];
    memset(by_model, 0, sizeof by_model);
    for (int i = 0; i < count; i++)
        for (int stick = 0; stick < 2; stick++) {
            random_setup r;
            random_setup_make(seed, i, stick, &r);
            char name[64];
            snprintf(name, sizeof name, "random %d (%s)", i, stick ? "rigid" : "compliant");
            failed += run_one(name, &r, horizon_s, work, verbose, &by_model[stick]) == RANDOM_FAILED;
        }
    printf("named: %d set-ups, %d failed, %.2f s CPU\n", N_NAMED_SETUPS, named.n[RANDOM_FAILED],
           named.cpu);
    for (int stick = 0; stick < 2; stick++) {
        const tally *t = &by_model[stick];
        printf("%s stick: %d set-ups (seed %llu, %g s, work cap %g): ", stick ? "rigid" : "compliant",
               count, seed, horizon_s, work);
        for (int o = 0; o < 5; o++)
            printf("%s%d %s", o ? ", " : "", t->n[o], OUTCOME[o]);
        printf("; %.1f s CPU, slowest %.2f s\n", t->cpu, t->slowest);
    }
    return failed ? 1 : 0;
}

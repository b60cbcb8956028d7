/* The core's cost of a population: settings lines of the SI front end (one grain each, as
   bench/population_feed.py writes a population's feed) run through the C API to the exit
   (or rest, or the horizon), each grain's CPU time measured alone. It uses only the SI front
   end's settings text and the model's advance, so that it compiles against earlier cores
   too (scripts/bench_population_core.sh --before REV): what differs is the core and its
   defaults. Prints the total, the median and the slowest grain's CPU, and the grains that
   ended in an error; exits 3 where one did (the population tests of tests/stability).
   Usage: tribo_population_core FEED [EXTRA_SETTINGS] [HORIZON_S=5] */
#include "feed_args.h"
#include "si.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cpu_clock.h"

static double per(long long count, double impacts)
{
    return impacts > 0.0 ? (double)count / impacts : 0.0;
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One grain: its CPU seconds, or a negative number where its set-up is refused. */
static double run_grain(const char *line, const char *extra, double horizon, int *failed,
                        double *impacts, tribo_stats *work)
{
    char err[1024];
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    tribo_si_derived d;
    if (tribo_si_scene_apply(&si, line, err, sizeof err) != TRIBO_OK ||
        tribo_si_scene_apply(&si, extra, err, sizeof err) != TRIBO_OK ||
        tribo_si_derive(&si, &d, err, sizeof err) != TRIBO_OK) {
        fprintf(stderr, "refused: %s\n", err);
        return -1.0;
    }
    const double start = cpu_seconds();
    tribo_model *m = tribo_create(&d.scene, err, sizeof err);
    if (!m) {
        fprintf(stderr, "refused: %s\n", err);
        return -1.0;
    }
    const tribo_status st = tribo_advance_fully(m, horizon / d.t_star);
    const double spent = cpu_seconds() - start;
    *failed = st != TRIBO_OK && st != TRIBO_ENDED;
    *impacts += tribo_get(m, TRIBO_QUANTITY_IMPACTS);
    tribo_stats st_grain;
    tribo_get_stats(m, &st_grain);
    work->steps += st_grain.steps;
    work->rhs_evals += st_grain.rhs_evals;
    work->events += st_grain.events;
    tribo_free(m);
    return spent;
}

int main(int argc, char **argv)
{
    feed_args args;
    if (!open_feed(argc, argv, &args))
        return 2;
    static char line[1 << 14];
    double *cost = NULL;
    int n = 0, capacity = 0, failed = 0;
    double impacts = 0.0;
    tribo_stats work = {0};
    while (fgets(line, sizeof line, args.feed)) {
        int fail = 0;
        const double c = run_grain(line, args.extra, args.horizon, &fail, &impacts, &work);
        if (c < 0.0) {
            fclose(args.feed);
            free(cost);
            return 1;
        }
        if (n == capacity) {
            capacity = capacity ? 2 * capacity : 1024;
            double *grown = realloc(cost, (size_t)capacity * sizeof *cost);
            if (!grown) {
                fclose(args.feed);
                free(cost);
                return 1;
            }
            cost = grown;
        }
        cost[n++] = c;
        failed += fail;
    }
    fclose(args.feed);
    double total = 0.0;
    for (int i = 0; i < n; i++)
        total += cost[i];
    qsort(cost, (size_t)n, sizeof *cost, by_value);
    printf("grains %d  CPU %.2f s  median %.2f ms  slowest %.3f s  failed %d  impacts %.0f  "
           "CPU per impact %.4f ms  per impact: steps %.1f  events %.2f  rhs %.1f\n",
           n, total, n ? 1e3 * cost[n / 2] : 0.0, n ? cost[n - 1] : 0.0, failed, impacts,
           impacts > 0.0 ? 1e3 * total / impacts : 0.0, per(work.steps, impacts),
           per(work.events, impacts), per(work.rhs_evals, impacts));
    free(cost);
    return failed ? 3 : 0;
}

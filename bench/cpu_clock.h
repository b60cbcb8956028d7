/* cpu_clock.h: the process's CPU time, which the benchmarks report (beside them, so that each
   still compiles alone against an earlier core: scripts/bench_at_revision.sh). */
#ifndef TRIBO_BENCH_CPU_CLOCK_H
#define TRIBO_BENCH_CPU_CLOCK_H

#include <time.h>

static inline double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif

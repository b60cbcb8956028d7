/* feed_args.h: the arguments of the benchmarks that run a feed's grains one by one
   (population_core.c, feeder_state.c): FEED [EXTRA_SETTINGS] [HORIZON_S=5]. A header beside
   them, so that each still compiles alone against an earlier core (bench_at_revision.sh). */
#ifndef TRIBO_BENCH_FEED_ARGS_H
#define TRIBO_BENCH_FEED_ARGS_H

#include <stdio.h>
#include <stdlib.h>

typedef struct feed_args {
    FILE *feed;
    const char *extra; /* settings applied after each grain's */
    double horizon;    /* seconds */
} feed_args;

/* The arguments, the feed file opened; 0 (said why on stderr) where they or the file are
   wrong. */
static inline int open_feed(int argc, char **argv, feed_args *a)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s FEED [EXTRA_SETTINGS] [HORIZON_S]\n", argv[0]);
        return 0;
    }
    a->extra = argc > 2 ? argv[2] : "";
    a->horizon = argc > 3 ? atof(argv[3]) : 5.0;
    a->feed = fopen(argv[1], "r");
    if (!a->feed)
        fprintf(stderr, "cannot read %s\n", argv[1]);
    return a->feed != NULL;
}

#endif

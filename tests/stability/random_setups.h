/* random_setups.h: random physical set-ups (the SI front end, docs/model.md §8) with external
   normal forces, run to the chute's exit, to rest (§3c) or to a horizon, each with a bounded
   amount of work: whatever the set-up, a run ends without an integrator failure. Shared by the
   command tribo_random_setups (scripts/random_setups.sh) and the test test_random_setups, and
   the set-ups that once failed, kept as named cases. */
#ifndef TRIBO_STABILITY_RANDOM_SETUPS_H
#define TRIBO_STABILITY_RANDOM_SETUPS_H

#include <stddef.h>

#include "si.h"

/* A set-up: SI settings (applied to si_quantities.def's defaults) and the inputs. */
typedef struct random_setup {
    char settings[1024];
    double F_T, F_N; /* N/m */
} random_setup;

/* Set-up `index` of the random sequence `seed` with the stick model (0 compliant, 1 rigid):
   the grain's size (a from 25 um to 2.5 mm, log-uniform), roundness (0.15 .. 1), orientation,
   Young's modulus (1e7 .. 1e10 Pa, log-uniform), density (500 .. 3000 kg/m3), friction
   (mu 0 .. 1.5, and one set-up in ten at 10 .. 100), dashpot (nu 0.05 .. 1), rolling
   resistance (mu_roll 0 .. 0.05, and one in ten at 0.05 .. 1), tilt (0 .. 60 degrees), drop
   (0 .. 20 mm) and an external normal
   force uniform in -1e4 .. 1e4 N/m, on a 0.3 m chute. The same for every run of the program. */
void random_setup_make(unsigned long long seed, int index, int stick_model, random_setup *r);

/* How a run ended. */
typedef enum random_outcome {
    RANDOM_EXITED,   /* at the chute's exit, or at rest (§3c) */
    RANDOM_HORIZON,  /* at the horizon */
    RANDOM_WORK_CAP, /* still going when its work was spent: not a failure, but not shown to end */
    RANDOM_REFUSED,  /* the set-up was refused with a message (a derived parameter out of range) */
    RANDOM_FAILED    /* the integrator failed: what this hunts */
} random_outcome;

/* Run a set-up to horizon_s seconds with at most work_cap units of work (the core's units,
   integrator.h: about half a microsecond of CPU each). *why receives the failure's or the
   refusal's message, or what ended the run. */
random_outcome random_setup_run(const random_setup *r, double horizon_s, double work_cap, char *why,
                                size_t why_size, double *t_end_s);

/* The set-ups that failed before the rule that confirms a lock was made the rule that entered it
   (docs/model.md §3b), kept as regression cases. */
typedef struct named_setup {
    const char *name;
    random_setup setup;
} named_setup;
extern const named_setup NAMED_SETUPS[];
extern const int N_NAMED_SETUPS;

#endif

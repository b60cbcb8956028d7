/* matrix.h: the stability matrix — the paper's set-up with one parameter at
   the edge of its range at a time, and a few edges combined — and the checks each run
   must pass. Shared by the Criterion test and the report program. */
#ifndef TRIBO_STABILITY_MATRIX_H
#define TRIBO_STABILITY_MATRIX_H

#include <math.h>

#include "tribo.h"

typedef struct stability_case {
    const char *name;
    const char *settings; /* from the paper's set-up (model.md §7), for tribo_scene_apply */
} stability_case;

extern const stability_case STABILITY_CASES[];
extern const int N_STABILITY_CASES;

/* The integrators every case runs with. */
extern const int STABILITY_INTEGRATORS[];
extern const int N_STABILITY_INTEGRATORS;
const char *stability_integrator_name(int integrator);

typedef struct stability_result {
    int finished;              /* every advance returned TRIBO_OK, or the particle left the
                                  chute (TRIBO_ENDED: exited) */
    int exited;                /* the run ended at the chute's end (model.md §9) */
    int all_finite;            /* no quantity NaN or infinite at any sample */
    int charge_ok;             /* 0 <= Q_static <= 1, never decreasing */
    int coulomb_ok;            /* |delta_x| <= mu Psi_N at every sample (model.md §3) */
    int contact_ok;            /* no indentation while in flight (model.md §2) */
    double max_residual;       /* max |E + W_diss - W_ext - E(0)| over the samples */
    double energy_scale;       /* largest |E|, work or kinetic energy seen: the residual's scale */
    double cpu_seconds;        /* measured, for the reports; not a check */
    double work;               /* the work the run booked (integrator.h's units) */
    tribo_stats stats;
    double q_static, q_sliding, max_delta_y;
    double t_reached;          /* the time the run ended at (the exit time if it exited) */
    char error[512];           /* why it did not finish */
} stability_result;

/* Run a case to t_end, sampling every `every` time units. */
void stability_run(const stability_case *c, int integrator, double t_end, double every,
                   stability_result *r);

/* The same checks on any scene, to t_end or the exit; with si (the scene's SI set-up, or
   NULL) also every SI quantity finite at every sample (all_finite). */
struct tribo_si_derived;
void stability_run_scene(const tribo_scene *s, const struct tribo_si_derived *si, double t_end,
                         double every, stability_result *r);

/* The energy balance holds when the residual is within this fraction of the run's energy
   scale (model.md §6), a balance accumulated over thousands of steps; docs/stability.md lists
   each run's residual against it. */
#define STABILITY_RESIDUAL_BOUND 1e-5
/* The bound on a run's cost, in work (integrator.h's units, about half a microsecond of CPU
   each, docs/work_limit.md): 2e7 units, about 10 s of CPU in an optimised build. A test
   asserts work, not CPU time, so that it holds on a busy machine and under the sanitizers;
   docs/stability.md lists each run's work and CPU time. */
#define STABILITY_WORK_BOUND 2e7
/* a wall-clock guard against a hang, at ten times the slowest run's idle time and more, not
   a bound on the run's cost */
#ifdef TRIBO_SANITIZED
#define STABILITY_TIMEOUT_S 600
#else
#define STABILITY_TIMEOUT_S 120
#endif

/* The verdict: 1 if every check passed. */
int stability_passed(const stability_result *r);

#endif

/* tribo_create with each of its allocations and each SUNDIALS call of CVODE's set-up failing
   in turn: every failure is refused with a reason and frees what was allocated, and one of
   the set-up names the SUNDIALS call that failed, as SUNDIALS' own examples do. The core's
   allocations fail through functions of this file over glibc's allocator (so the test is
   not built with the sanitizers, which bring their own), the SUNDIALS calls through the
   linker's --wrap (tests/c/CMakeLists.txt): a failure inside a SUNDIALS call is SUNDIALS'
   to handle (6.4's SUNContext_Create does not survive its own malloc failing), so the
   allocator fails none while one runs. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "support.h"

/* Allocations or SUNDIALS calls left before the one that fails (-1: none fails); whether a
   SUNDIALS call is running; the allocations not yet freed since counting began. */
static long countdown = -1;
static int in_sundials;
static int counting;
static long live;

static int fails(void) { return !in_sundials && countdown >= 0 && countdown-- == 0; }

/* ---- the allocator ------------------------------------------------------------------------- */

void *__libc_malloc(size_t n);
void *__libc_calloc(size_t count, size_t n);
void *__libc_realloc(void *p, size_t n);
void __libc_free(void *p);

void *malloc(size_t n)
{
    if (fails())
        return NULL;
    void *p = __libc_malloc(n);
    live += counting && p;
    return p;
}

void *calloc(size_t count, size_t n)
{
    if (fails())
        return NULL;
    void *p = __libc_calloc(count, n);
    live += counting && p;
    return p;
}

void *realloc(void *old, size_t n)
{
    if (fails())
        return NULL;
    void *p = __libc_realloc(old, n);
    live += counting && p && !old;
    return p;
}

void free(void *p)
{
    live -= counting && p;
    __libc_free(p);
}

/* ---- the SUNDIALS calls of the set-up: each fails as it reports a failure -------------------- */

#define WRAP(type, failure, name, params, args)                                                \
    type __real_##name params;                                                                  \
    type __wrap_##name params;                                                                  \
    type __wrap_##name params                                                                   \
    {                                                                                           \
        if (fails())                                                                            \
            return failure;                                                                     \
        in_sundials++;                                                                          \
        type result = __real_##name args;                                                       \
        in_sundials--;                                                                          \
        return result;                                                                          \
    }
WRAP(int, -1, SUNContext_Create, (void *comm, SUNContext *ctx), (comm, ctx))
WRAP(N_Vector, NULL, N_VNew_Serial, (sunindextype n, SUNContext ctx), (n, ctx))
WRAP(void *, NULL, CVodeCreate, (int lmm, SUNContext ctx), (lmm, ctx))
WRAP(int, CV_ILL_INPUT, CVodeSetErrHandlerFn, (void *mem, CVErrHandlerFn f, void *data),
     (mem, f, data))
WRAP(int, CV_MEM_FAIL, CVodeInit, (void *mem, CVRhsFn f, realtype t0, N_Vector y0),
     (mem, f, t0, y0))
WRAP(int, CV_ILL_INPUT, CVodeSVtolerances, (void *mem, realtype rtol, N_Vector atol),
     (mem, rtol, atol))
WRAP(int, CV_MEM_NULL, CVodeSetUserData, (void *mem, void *data), (mem, data))
WRAP(int, CV_MEM_FAIL, CVodeRootInit, (void *mem, int n, CVRootFn g), (mem, n, g))
WRAP(int, CV_MEM_NULL, CVodeSetNoInactiveRootWarn, (void *mem), (mem))
WRAP(int, CV_MEM_NULL, CVodeSetMaxHnilWarns, (void *mem, int n), (mem, n))
WRAP(SUNMatrix, NULL, SUNDenseMatrix, (sunindextype rows, sunindextype cols, SUNContext ctx),
     (rows, cols, ctx))
WRAP(SUNLinearSolver, NULL, SUNLinSol_Dense, (N_Vector y, SUNMatrix a, SUNContext ctx),
     (y, a, ctx))
WRAP(int, CVLS_MEM_FAIL, CVodeSetLinearSolver, (void *mem, SUNLinearSolver ls, SUNMatrix a),
     (mem, ls, a))
WRAP(SUNNonlinearSolver, NULL, SUNNonlinSol_FixedPoint, (N_Vector y, int m, SUNContext ctx),
     (y, m, ctx))
WRAP(int, CV_MEM_FAIL, CVodeSetNonlinearSolver, (void *mem, SUNNonlinearSolver nls),
     (mem, nls))

/* ---- the tests ----------------------------------------------------------------------------- */

/* The SUNDIALS calls of each set-up, which failures must name. */
static const char *const ADAMS[] = {
    "SUNContext_Create", "N_VNew_Serial",          "CVodeCreate",   "CVodeSetErrHandlerFn",
    "CVodeInit",         "CVodeSVtolerances",      "CVodeSetUserData", "CVodeRootInit",
    "CVodeSetNoInactiveRootWarn", "CVodeSetMaxHnilWarns", "SUNNonlinSol_FixedPoint",
    "CVodeSetNonlinearSolver"};
static const char *const BDF[] = {
    "SUNContext_Create", "N_VNew_Serial",          "CVodeCreate",   "CVodeSetErrHandlerFn",
    "CVodeInit",         "CVodeSVtolerances",      "CVodeSetUserData", "CVodeRootInit",
    "CVodeSetNoInactiveRootWarn", "CVodeSetMaxHnilWarns", "SUNDenseMatrix", "SUNLinSol_Dense",
    "CVodeSetLinearSolver"};

static void each_failure_in_turn(int integrator, const char *const *calls, int n_calls)
{
    tribo_scene s = scene_of("n_segments=64");
    s.integrator = integrator;
    const char prefix[] = "cannot set up CVODE: ";
    int named[16] = {0};
    long k = 0;
    for (;; k++) {
        char err[512] = "";
        counting = 1;
        live = 0;
        countdown = k;
        tribo_model *m = tribo_create(&s, err, sizeof err);
        countdown = -1;
        if (m) {
            tribo_free(m);
            counting = 0;
            cr_expect_eq(live, 0, "the instance made after %ld failures leaked %ld blocks", k, live);
            break;
        }
        counting = 0;
        cr_expect_eq(live, 0, "failure %ld leaked %ld blocks (%s)", k, live, err);
        if (strncmp(err, prefix, sizeof prefix - 1) != 0) {
            cr_expect(strncmp(err, "out of memory", 13) == 0, "failure %ld: %s", k, err);
            continue;
        }
        const char *what = err + sizeof prefix - 1;
        int known = strcmp(what, "out of memory") == 0;
        for (int i = 0; i < n_calls; i++) {
            const size_t len = strlen(calls[i]);
            if (strncmp(what, calls[i], len) == 0 && strncmp(what + len, " failed", 7) == 0)
                known = named[i] = 1;
        }
        cr_expect(known, "failure %ld: %s", k, err);
        cr_assert_lt(k, 10000);
    }
    cr_expect_gt(k, n_calls, "only %ld failures", k);
    for (int i = 0; i < n_calls; i++)
        cr_expect(named[i], "no failure named %s", calls[i]);
}

Test(out_of_memory, each_failure_of_an_adams_instance_is_refused_cleanly)
{
    each_failure_in_turn(TRIBO_INTEGRATOR_CVODE, ADAMS, sizeof ADAMS / sizeof *ADAMS);
}

Test(out_of_memory, each_failure_of_a_bdf_instance_is_refused_cleanly)
{
    each_failure_in_turn(TRIBO_INTEGRATOR_CVODE_BDF, BDF, sizeof BDF / sizeof *BDF);
}

Test(out_of_memory, each_failure_of_a_fixed_step_instance_is_refused_cleanly)
{
    each_failure_in_turn(TRIBO_INTEGRATOR_FIXED_STEP, NULL, 0);
}

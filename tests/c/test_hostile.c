/* Hostile and careless callers: the calls and values that fuzzing the FMUs tries, each held
   at the core that answers it. The FMU-level ones and the fuzz suite: tests/python. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "integrator.h"
#include "model.h"
#include "support.h"

static const int INTEGRATORS[] = {TRIBO_INTEGRATOR_FIXED_STEP, TRIBO_INTEGRATOR_CVODE};

static tribo_scene scene_with(int integrator)
{
    tribo_scene s = scene_of("n_segments=64 epsilon=0.4");
    s.integrator = integrator;
    return s;
}

static int outputs_finite(tribo_model *m)
{
    for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++)
        if (!isfinite(tribo_get(m, q)))
            return 0;
    return 1;
}

/* ---- the fixed step restores its own state at any time --------------------------- */

/* An importer that adds 0.1 to its time reaches 0.30000000000000004, 0.9999999999999999...:
   times a rounding error before a grid point. Saving there and loading back must work, into
   the instance itself and into a fresh one, and continue as the original does. */
Test(hostile, fixed_step_restores_its_own_state_at_accumulated_times, .timeout = 60)
{
    const tribo_scene s = scene_with(TRIBO_INTEGRATOR_FIXED_STEP);
    tribo_model *m = make(&s), *copy = make(&s);
    double t = 0.0;
    for (int k = 0; k < 120; k++) {
        t += 0.1;
        cr_assert_eq(tribo_advance(m, t), TRIBO_OK, "%s", tribo_last_error(m));
        size_t n;
        unsigned char *bytes = saved_state(m, &n);
        cr_assert_eq(tribo_state_load(m, bytes, n), TRIBO_OK, "t = %.17g: %s", t, tribo_last_error(m));
        cr_assert_eq(tribo_state_load(copy, bytes, n), TRIBO_OK, "t = %.17g: %s", t,
                     tribo_last_error(copy));
        free(bytes);
        cr_assert(same_outputs(m, copy), "t = %.17g", t);
    }
    advance_both(m, copy, 15.0);
    cr_expect(same_outputs(m, copy));
    tribo_free(m);
    tribo_free(copy);
}

/* The case of the report, in the core alone: 37.3 after steps of dt = 0.1. */
Test(hostile, fixed_step_state_at_37_3_loads_into_a_fresh_instance)
{
    tribo_scene s = scene_with(TRIBO_INTEGRATOR_FIXED_STEP);
    s.dt = 0.1;
    tribo_model *m = make(&s), *fresh = make(&s);
    cr_assert_eq(tribo_advance(m, 37.3), TRIBO_OK);
    size_t n;
    unsigned char *bytes = saved_state(m, &n);
    cr_expect_eq(tribo_state_load(fresh, bytes, n), TRIBO_OK, "%s", tribo_last_error(fresh));
    cr_expect(same_outputs(m, fresh));
    free(bytes);
    tribo_free(m);
    tribo_free(fresh);
}

/* ---- a state brings its tolerances along -------------------------------------------- */

Test(hostile, a_loaded_state_runs_on_with_its_own_tolerances, .timeout = 60)
{
    tribo_scene loose = scene_with(TRIBO_INTEGRATOR_CVODE);
    loose.rtol = 1e-6;
    loose.atol = 1e-8;
    const tribo_scene tight = scene_with(TRIBO_INTEGRATOR_CVODE); /* 1e-9, 1e-11 */
    tribo_model *saver = make(&loose), *other = make(&tight), *alone = make(&loose);
    cr_assert_eq(tribo_advance(saver, 10.0), TRIBO_OK);
    size_t n;
    unsigned char *bytes = saved_state(saver, &n);
    cr_assert_eq(tribo_state_load(other, bytes, n), TRIBO_OK, "%s", tribo_last_error(other));
    free(bytes);
    cr_expect_eq(tribo_get_scene(other)->rtol, 1e-6);
    advance_both(saver, other, 25.0);
    cr_assert_eq(tribo_advance(alone, 25.0), TRIBO_OK);
    /* the continuation is the saved run's, bit for bit (before: X 0.424780 against 0.424808) */
    cr_expect(same_outputs(saver, other), "X %.17g against %.17g", tribo_get(saver, TRIBO_QUANTITY_X),
              tribo_get(other, TRIBO_QUANTITY_X));
    cr_expect(same_outputs(alone, other));
    tribo_free(saver);
    tribo_free(other);
    tribo_free(alone);
}

/* ---- everything a state carries is checked, and a refusal changes nothing ------- */

/* Offsets in the core's state (state_io.c's layout): the header, the parameters, then the
   external force, the output time, the work counters, the committed point. */
static size_t params_end(void)
{
    size_t n_params;
    tribo_param_table(&n_params);
    return 24 + 8 * n_params;
}
#define OFFSET_T_OUT (params_end() + 16)
#define OFFSET_STEPS (params_end() + 24)
#define OFFSET_COMMITTED (params_end() + 24 + 48)

static void put(unsigned char *bytes, size_t offset, const void *v) { memcpy(bytes + offset, v, 8); }

typedef struct mutation {
    const char *what;
    size_t offset;
    unsigned char value[8];
} mutation;

static mutation mutate_double(const char *what, size_t offset, double v)
{
    mutation mu = {what, offset, {0}};
    memcpy(mu.value, &v, 8);
    return mu;
}

static mutation mutate_int(const char *what, size_t offset, int64_t v)
{
    mutation mu = {what, offset, {0}};
    memcpy(mu.value, &v, 8);
    return mu;
}

/* Each mutation is refused; the instance it was offered to stays as it was (its own saved
   bytes unchanged) and runs on as its untouched twin does. */
static void expect_refused(const tribo_scene *s, const mutation *mutations, int count, double t)
{
    tribo_model *source = make(s), *target = make(s), *twin = make(s);
    advance_both(source, target, t);
    cr_assert_eq(tribo_advance_fully(twin, t), TRIBO_OK);
    size_t n;
    unsigned char *bytes = saved_state(source, &n), *before = saved_state(target, &n);
    for (int i = 0; i < count; i++) {
        unsigned char *bad = malloc(n);
        memcpy(bad, bytes, n);
        put(bad, mutations[i].offset, mutations[i].value);
        tribo_stats stats_before, stats_after;
        tribo_get_stats(target, &stats_before);
        cr_expect_eq(tribo_state_load(target, bad, n), TRIBO_ERR_STATE, "integrator %d: %s accepted",
                     s->integrator, mutations[i].what);
        /* refused before any step is taken (a refusal reads the bytes, it does not run) */
        tribo_get_stats(target, &stats_after);
        cr_expect(stats_after.steps == stats_before.steps &&
                      stats_after.rhs_evals == stats_before.rhs_evals,
                  "%s: the refusal took steps", mutations[i].what);
        cr_expect(strlen(tribo_last_error(target)) > 0);
        size_t m;
        unsigned char *after = saved_state(target, &m);
        size_t first = 0;
        while (first < n && before[first] == after[first])
            first++;
        cr_expect(m == n && first == n, "integrator %d: %s changed the instance (byte %zu of %zu)",
                  s->integrator, mutations[i].what, first, n);
        free(after);
        free(bad);
    }
    advance_both(target, twin, t + 5.0);
    cr_expect(same_outputs(target, twin), "integrator %d: the refusals disturbed the run", s->integrator);
    free(bytes);
    free(before);
    tribo_free(source);
    tribo_free(target);
    tribo_free(twin);
}

Test(hostile, non_numbers_huge_times_and_counters_in_a_state_are_refused, .timeout = 120)
{
    for (int k = 0; k < 2; k++) {
        const tribo_scene s = scene_with(INTEGRATORS[k]);
        const mutation mutations[] = {
            mutate_double("NaN in X", OFFSET_COMMITTED + 8, NAN),
            mutate_double("infinity in Omega", OFFSET_COMMITTED + 8 * (1 + TRIBO_IOMEGA), INFINITY),
            mutate_double("an output time of 1e9", OFFSET_T_OUT, 1e9),
            mutate_double("an output time before the committed one", OFFSET_T_OUT, 0.5),
            mutate_double("NaN as the output time", OFFSET_T_OUT, NAN),
            mutate_int("a step counter about to overflow", OFFSET_STEPS, INT64_MAX),
            mutate_int("a negative step counter", OFFSET_STEPS, -1),
            mutate_double("an epsilon of another instance", 24, 0.3),
            mutate_double("mu out of its range", 32, -1.0),
        };
        expect_refused(&s, mutations, sizeof mutations / sizeof mutations[0], 3.3);
    }
}

/* The integrator's own bytes: CVODE's restart point and replay count, the fixed step's grid. */
Test(hostile, corrupt_integrator_bytes_are_refused, .timeout = 120)
{
    for (int k = 0; k < 2; k++) {
        const tribo_scene s = scene_with(INTEGRATORS[k]);
        tribo_model *probe = make(&s);
        const size_t end = tribo_state_size(probe);
        const size_t own = probe->integrator->state_size(probe->integrator_data);
        tribo_free(probe);
        const size_t at = end - own; /* fixed step: t_base, k; CVODE: t_restart, y_restart, count */
        const size_t count_at = at + 8 * (1 + TRIBO_NSTATE_MAX);
        const mutation fixed[] = {
            mutate_double("a grid start after the committed time", at, 100.0),
            mutate_int("a grid index off the committed time", at + 8, 7),
            mutate_int("a grid index of 2^62", at + 8, (int64_t)1 << 62),
        };
        const mutation cvode[] = {
            mutate_int("a replay of 2^62 steps", count_at, (int64_t)1 << 62),
            mutate_int("a replay that misses the committed point", count_at, 3),
            mutate_double("NaN in the restart point", at + 8, NAN),
            mutate_double("a restart point off the committed motion", at + 8 * (1 + TRIBO_IU), 0.5),
        };
        if (INTEGRATORS[k] == TRIBO_INTEGRATOR_FIXED_STEP)
            expect_refused(&s, fixed, 3, 3.3);
        else
            expect_refused(&s, cvode, 4, 3.3);
    }
}

/* ---- huge steps are refused or bounded, never wrong or endless -------------------- */

Test(hostile, huge_times_are_refused_or_bounded, .timeout = 300)
{
    for (int k = 0; k < 2; k++) {
        const tribo_scene s = scene_with(INTEGRATORS[k]);
        tribo_model *m = make(&s), *twin = make(&s);
        advance_both(m, twin, 1.0);
        /* past what the integrators resolve: refused, nothing changes */
        const double refused[] = {1e300, 1e18, TRIBO_TIME_MAX * 2};
        for (int i = 0; i < 3; i++) {
            cr_expect_eq(tribo_advance(m, refused[i]), TRIBO_ERR_TIME, "t = %g", refused[i]);
            cr_expect(strstr(tribo_last_error(m), "cannot advance") != NULL);
            cr_expect(same_outputs(m, twin));
        }
        /* within: one advance does a bounded amount of work (its limit, and the one step that
           passes it: a CVODE step of this scene is tens of units) and stops early, finite */
        cr_expect_eq(tribo_advance(m, 1e9), TRIBO_INCOMPLETE);
        cr_expect(m->work <= s.work_limit + 1000.0, "%.0f units", m->work);
        const double t = tribo_get(m, TRIBO_QUANTITY_TIME);
        cr_expect(t > 1.0 && t < 1e9, "t = %g", t);
        cr_expect(outputs_finite(m));
        tribo_free(m);
        tribo_free(twin);
    }
    /* a fixed step too fine for the time asked: refused with a reason */
    tribo_scene s = scene_with(TRIBO_INTEGRATOR_FIXED_STEP);
    s.dt = 1e-9;
    tribo_model *m = make(&s);
    cr_expect_eq(tribo_advance(m, 1e5), TRIBO_ERR_TIME);
    cr_expect(strstr(tribo_last_error(m), "dt = 1e-09") != NULL, "%s", tribo_last_error(m));
    tribo_free(m);
}

/* ---- the work of one advance is bounded, and stopping early changes nothing ------ */

Test(hostile, stopping_at_the_work_limit_gives_the_same_run, .timeout = 120)
{
    for (int k = 0; k < 2; k++) {
        tribo_scene s = scene_with(INTEGRATORS[k]);
        tribo_model *whole = make(&s);
        /* primes: stops fall everywhere; a few hundred of CVODE's steps to t = 20 */
        const int limit = k ? 97 : 997;
        s.work_limit = limit;
        tribo_model *parts = make(&s);
        cr_assert_eq(tribo_advance_fully(whole, 20.0), TRIBO_OK);
        int stops = 0;
        tribo_status st;
        long long steps = 0;
        while ((st = tribo_advance(parts, 20.0)) == TRIBO_INCOMPLETE) {
            tribo_stats stats;
            tribo_get_stats(parts, &stats);
            /* at most the limit, and one step past it */
            const double per_step = k ? TRIBO_WORK_CVODE_STEP : TRIBO_WORK_FIXED_STEP;
            cr_expect(stats.steps + stats.substeps - steps <= limit / per_step + 1,
                      "integrator %d: %lld steps in one advance", INTEGRATORS[k],
                      stats.steps + stats.substeps - steps);
            steps = stats.steps + stats.substeps;
            cr_expect(strstr(tribo_last_error(parts), "work_limit") != NULL);
            stops++;
        }
        cr_assert_eq(st, TRIBO_OK, "%s", tribo_last_error(parts));
        cr_expect(stops > 3, "integrator %d: %d stops", INTEGRATORS[k], stops);
        cr_expect(same_outputs(whole, parts), "integrator %d", INTEGRATORS[k]);
        tribo_free(whole);
        tribo_free(parts);
    }
}

/* Reading the scalar outputs costs the pending charge updates, never the segment arrays: no
   copy of them is made (it is made only for the arrays themselves). */
Test(hostile, scalar_outputs_do_not_copy_the_segments)
{
    for (int k = 0; k < 2; k++) {
        tribo_scene s = scene_with(INTEGRATORS[k]);
        s.n_segments = 100000;
        tribo_model *m = make(&s);
        cr_assert_eq(tribo_advance_fully(m, 3.0), TRIBO_OK);
        cr_assert_eq(tribo_advance(m, 3.00007), TRIBO_OK); /* a partial step: updates pending */
        cr_assert(m->n_pending > 0);
        double q[TRIBO_QUANTITY_COUNT];
        for (int i = 0; i < TRIBO_QUANTITY_COUNT; i++)
            q[i] = tribo_get(m, i);
        for (int i = 0; i < m->charging.n_models; i++)
            cr_expect_null(m->charging.slot[i].segments_out);
        /* and their means are those of the arrays (to their rounding, measured 1e-16
           relative; bound 1e-13) */
        double *values = malloc(100000 * sizeof *values);
        cr_assert_eq(tribo_get_segment_charges(m, TRIBO_SEGMENTS_STATIC, values, 100000), TRIBO_OK);
        double sum = 0.0;
        for (int i = 0; i < 100000; i++)
            sum += values[i];
        cr_expect(q[TRIBO_QUANTITY_STATIC] > 0.0 && fabs(q[TRIBO_QUANTITY_STATIC] - sum / 100000) <= 1e-13 * q[TRIBO_QUANTITY_STATIC],
                  "Q_static %.17g, mean %.17g", q[TRIBO_QUANTITY_STATIC], sum / 100000);
        free(values);
        tribo_free(m);
    }
}

/* ---- every parameter at either end of its range gives finite outputs ------------- */

Test(hostile, every_parameter_at_the_ends_of_its_range_computes, .timeout = 240)
{
    size_t count;
    const tribo_param_info *table = tribo_param_table(&count);
    for (size_t i = 0; i < count; i++) {
        const tribo_param_info *p = &table[i];
        for (int end = 0; end < 2; end++) {
            double v = end ? p->max : p->min;
            if (!(end ? p->max_inclusive : p->min_inclusive))
                v = nextafter(v, end ? -INFINITY : INFINITY);
            for (int k = 0; k < 2; k++) {
                if (strcmp(p->name, "integrator") == 0 && k > 0)
                    continue; /* the parameter itself chooses */
                tribo_scene s = scene_with(INTEGRATORS[k]);
                tribo_param_write(&s, p, v);
                char err[512];
                tribo_model *m = tribo_create(&s, err, sizeof err);
                if (s.stick_model == TRIBO_STICK_RIGID && s.integrator == TRIBO_INTEGRATOR_FIXED_STEP) {
                    /* the one combination refused: the fixed step has no rigid stick */
                    cr_expect(!m && strstr(err, "stick_model = 1") == err, "%s", err);
                    tribo_free(m);
                    continue;
                }
                cr_assert(m, "%s = %g: %s", p->name, v, err);
                /* a short run: at most ~1e5 fixed steps */
                const double t = fmin(1.0, 1e5 * s.dt);
                const tribo_status st = tribo_advance(m, t);
                /* (the shortest chute ends the run at once) */
                cr_expect(st == TRIBO_OK || st == TRIBO_INCOMPLETE || st == TRIBO_ENDED,
                          "%s = %g, integrator %d: %s", p->name, v, s.integrator,
                          tribo_last_error(m));
                cr_expect(outputs_finite(m), "%s = %g, integrator %d", p->name, v, s.integrator);
                tribo_free(m);
            }
        }
    }
    /* and the inputs at theirs */
    const tribo_param_info *inputs = tribo_input_table(NULL);
    for (int k = 0; k < 2; k++)
        for (int end = 0; end < 2; end++) {
            const tribo_scene s = scene_with(INTEGRATORS[k]);
            tribo_model *m = make(&s);
            const double F = end ? inputs[0].max : inputs[0].min;
            cr_assert_eq(tribo_set_external_force(m, F, F), TRIBO_OK);
            const tribo_status st = tribo_advance(m, 0.05);
            cr_expect(st == TRIBO_OK || st == TRIBO_INCOMPLETE, "F = %g: %s", F, tribo_last_error(m));
            cr_expect(outputs_finite(m), "F = %g, integrator %d", F, INTEGRATORS[k]);
            cr_expect_eq(tribo_set_external_force(m, 2 * F, 0.0), TRIBO_ERR_INVALID_ARGUMENT);
            tribo_free(m);
        }
}

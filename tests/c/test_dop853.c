/* DOP853 (src/chute/integrators/dop853.c), the one-step method of a vibrating plate's contact
   phases, on problems whose solutions are known. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "dop853.h"

/* The harmonic oscillator y'' = -y, y(0) = 1, y'(0) = 0, and a count of its evaluations. */
static void oscillator(void *ctx, double t, const double *y, double *dydt)
{
    (void)t;
    ++*(long *)ctx;
    dydt[0] = y[1];
    dydt[1] = -y[0];
}

static const double ATOL[2] = {1e-12, 1e-12};

Test(dop853, follows_the_oscillator_to_its_tolerance_in_few_steps)
{
    /* over 10 periods at rtol 1e-10: measured error 4.6e-10 at the end and 4.6e-10 on the
       dense output, in 198 steps of 15 evaluations (12 stages, 3 for the dense output) and 2
       at the start: none rejected. Bounds: 2e-9 (4 times the measured), 300 steps, and room
       for 10 rejected steps of 12 evaluations */
    long evals = 0;
    tribo_dop853 s;
    const double y0[2] = {1.0, 0.0}, end = 20.0 * M_PI;
    tribo_dop853_start(&s, oscillator, &evals, 2, 0.0, y0, 1e-10, ATOL, 1.0);
    int steps = 0;
    double worst_dense = 0.0;
    while (s.t < end) {
        cr_assert_eq(tribo_dop853_step(&s, fmin(1.0, end - s.t)), 0);
        steps++;
        /* the dense output inside the step, against cos t */
        for (int j = 1; j < 8; j++) {
            const double t = s.t_old + s.h_old * j / 8.0;
            worst_dense = fmax(worst_dense, fabs(tribo_dop853_dense(&s, t, 0) - cos(t)));
        }
        /* at the step's end, the end (but for the rounding of its time over the step) */
        cr_assert(fabs(tribo_dop853_dense(&s, s.t, 0) - s.y[0]) <= 1e-13);
    }
    const double error = fmax(fabs(s.y[0] - cos(s.t)), fabs(s.y[1] + sin(s.t)));
    cr_log_info("error %.3g, dense output's %.3g, %d steps, %ld evaluations", error, worst_dense,
                steps, evals);
    cr_expect(error <= 2e-9, "error %.3g", error);
    cr_expect(worst_dense <= 2e-9, "dense output's error %.3g", worst_dense);
    cr_expect(steps <= 300, "%d steps", steps);
    cr_expect(evals <= 15L * steps + 2 + 12L * 10, "%ld evaluations in %d steps", evals, steps);
}

/* Its error follows the tolerance: over 10 time units, measured 0.25 rtol at 1e-6 to 0.8 rtol
   at 1e-12, falling with it; bound 30 rtol. */
Test(dop853, its_error_follows_the_tolerance)
{
    double last = INFINITY;
    for (int k = 6; k <= 12; k += 2) {
        long evals = 0;
        tribo_dop853 s;
        const double y0[2] = {1.0, 0.0}, rtol = pow(10.0, -k), atol[2] = {rtol, rtol};
        tribo_dop853_start(&s, oscillator, &evals, 2, 0.0, y0, rtol, atol, 10.0);
        while (s.t < 10.0)
            cr_assert_eq(tribo_dop853_step(&s, fmin(10.0, 10.0 - s.t)), 0);
        const double error = fabs(s.y[0] - cos(s.t));
        cr_log_info("rtol %g: error %.3g", rtol, error);
        cr_expect(error <= 30.0 * rtol, "rtol %g: error %.3g", rtol, error);
        cr_expect(error < last, "rtol %g: error %.3g, no smaller than at a looser rtol", rtol, error);
        last = error;
    }
}

/* The same start gives the same steps, bit for bit (the saved state replays them). */
Test(dop853, the_same_start_gives_the_same_steps)
{
    long evals = 0;
    tribo_dop853 a, b;
    const double y0[2] = {0.3, -0.7};
    tribo_dop853_start(&a, oscillator, &evals, 2, 5.0, y0, 1e-9, ATOL, 0.5);
    for (int i = 0; i < 5; i++)
        cr_assert_eq(tribo_dop853_step(&a, 0.5), 0);
    tribo_dop853_start(&b, oscillator, &evals, 2, 5.0, y0, 1e-9, ATOL, 0.5);
    for (int i = 0; i < 5; i++)
        cr_assert_eq(tribo_dop853_step(&b, 0.5), 0);
    cr_expect(a.t == b.t && a.h == b.h && memcmp(a.y, b.y, sizeof a.y[0] * 2) == 0);
}

static void not_a_number(void *ctx, double t, const double *y, double *dydt)
{
    (void)ctx;
    (void)t;
    dydt[0] = y[0] > 1.5 ? NAN : 1.0;
}

/* A right-hand side that turns to NaN shrinks the step to the rounding of t: -1, the point
   reached kept. */
Test(dop853, a_step_it_cannot_take_is_refused)
{
    tribo_dop853 s;
    const double y0[1] = {1.0}, atol[1] = {1e-12};
    tribo_dop853_start(&s, not_a_number, NULL, 1, 0.0, y0, 1e-9, atol, 0.1);
    int st = 0;
    for (int i = 0; i < 100 && st == 0; i++)
        st = tribo_dop853_step(&s, 0.1);
    cr_expect_eq(st, -1);
    cr_expect(s.y[0] <= 1.5 && isfinite(s.y[0]), "y = %g", s.y[0]);
}

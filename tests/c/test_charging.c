/* The charge models of model.md §5 over the segments, and the sweep that charges a contact
   moving along an interval (as CVODE's dense output describes it). */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "charge_registry.h"
#include "charging.h"

/* The registry's models with the static and sliding ones selected (whatever others it
   registers). */
static tribo_charging make(double eps, int n)
{
    tribo_charging c;
    const unsigned both = 1u << TRIBO_SEGMENTS_STATIC | 1u << TRIBO_SEGMENTS_SLIDING;
    cr_assert_eq(
        tribo_charging_init(&c, TRIBO_CHARGE_MODELS, TRIBO_SEGMENTS_COUNT, both, eps, n, 0, NULL),
        0);
    return c;
}

/* tau0 = tau_r = 1, Sigma0 = 0.01, eta = 0.1 */
static tribo_scene params(void)
{
    tribo_scene s;
    tribo_scene_defaults(&s);
    return s;
}

static double *static_q(tribo_charging *c) { return c->slot[TRIBO_SEGMENTS_STATIC].segments; }
static double *sliding_sigma(tribo_charging *c) { return c->slot[TRIBO_SEGMENTS_SLIDING].segments; }

/* A sample of the given duration over [s_c - half, s_c + half], with the sliding model's
   Sigma_s at the start, middle and end. */
static tribo_contact_sample sample(const tribo_charging *c, double duration, double s_c,
                                   double half, double S0, double Sm, double S1)
{
    tribo_contact_sample s = {.duration = duration};
    tribo_charging_locate(c, s_c, half, &s);
    const int at = c->slot[TRIBO_SEGMENTS_SLIDING].globals_at;
    s.globals_begin[at] = S0;
    s.globals_mid[at] = Sm;
    s.globals_end[at] = S1;
    return s;
}

/* A contact held still over segment 5, charged in pieces of various lengths: both models
   are exact, q = 1 - e^{-T/tau0} (model.md §5a) and, with Sigma_s held, Sigma_i =
   Sigma_s (1 - e^{-T/tau0}) (model.md §5b); its neighbours stay at 0. */
Test(charging, exact_for_a_held_contact)
{
    tribo_charging c = make(0.5, 100);
    const tribo_scene P = params();
    const double seg = c.arc.perimeter / 100, S = 0.013;
    double T = 0.0;
    for (int k = 1; k <= 50; k++) {
        const tribo_contact_sample s = sample(&c, 0.01 * k, 5.5 * seg, 0.2 * seg, S, S, S);
        tribo_charging_apply(&c, &P, &s, TRIBO_CHARGE_COMMIT);
        T += s.duration;
    }
    const double *q = static_q(&c), *sigma = sliding_sigma(&c);
    cr_expect_float_eq(q[5], 1.0 - exp(-T / P.tau0), 1e-14);
    cr_expect_float_eq(sigma[5], S * (1.0 - exp(-T / P.tau0)), 1e-15);
    cr_expect(q[4] == 0.0 && q[6] == 0.0 && sigma[4] == 0.0);
    tribo_charging_free(&c);
}

/* Sigma_s quadratic in time over a sample: the update against a fine RK4 of
   dSigma_i/dtau = (Sigma_s(t) - Sigma_i) / tau0, for a small and a large tau0 / duration. */
Test(charging, sliding_update_exact_for_quadratic_saturation)
{
    const double durations[] = {1e-3, 0.3, 5.0};
    for (int k = 0; k < 3; k++) {
        tribo_charging c = make(0.5, 100);
        const tribo_scene P = params();
        const double seg = c.arc.perimeter / 100, d = durations[k];
        const double S0 = 0.010, Sm = 0.0123, S1 = 0.0117;
        double *sigma = sliding_sigma(&c);
        sigma[7] = 0.004;
        const tribo_contact_sample s = sample(&c, d, 7.5 * seg, 0.1 * seg, S0, Sm, S1);
        tribo_charging_apply(&c, &P, &s, TRIBO_CHARGE_COMMIT);
        /* reference: Sigma_s(u) = A + B u + C u^2 through the three values */
        const double C = 2 * (S0 - 2 * Sm + S1), B = S1 - S0 - C;
        double y = 0.004;
        const int n = 200000;
        const double h = d / n;
        for (int i = 0; i < n; i++) {
            const double u = (double)i / n, uh = (i + 0.5) / n, u1 = (double)(i + 1) / n;
            const double f0 = S0 + B * u + C * u * u, fh = S0 + B * uh + C * uh * uh,
                         f1 = S0 + B * u1 + C * u1 * u1;
            const double k1 = (f0 - y), k2 = (fh - (y + 0.5 * h * k1)),
                         k3 = (fh - (y + 0.5 * h * k2)), k4 = (f1 - (y + h * k3));
            y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        }
        cr_expect(fabs(sigma[7] - y) < 1e-15, "duration %g: %.17g vs %.17g", d, sigma[7], y);
        tribo_charging_free(&c);
    }
}

/* A charging time so short that duration / tau0 overflows (the smallest double) is the limit
   tau0 -> 0: the segment at the sample's final saturation, a number (model.md §5c). */
Test(charging, the_smallest_charging_time_is_instantaneous_transfer)
{
    tribo_charging c = make(0.5, 100);
    tribo_scene P = params();
    P.tau0 = DBL_TRUE_MIN;
    const double seg = c.arc.perimeter / 100;
    const double S0 = 0.010, Sm = 0.0123, S1 = 0.0117;
    double *sigma = sliding_sigma(&c);
    sigma[7] = 0.004;
    const tribo_contact_sample s = sample(&c, 0.3, 7.5 * seg, 0.1 * seg, S0, Sm, S1);
    tribo_charging_apply(&c, &P, &s, TRIBO_CHARGE_COMMIT);
    cr_expect(fabs(sigma[7] - S1) <= 1e-15, "%.17g, the end's saturation %.17g", sigma[7], S1);
    tribo_charging_free(&c);
}

/* The segment under the contact point charges however small the contact (model.md §5:
   overlap, not "midpoint inside"). */
Test(charging, segment_under_a_point_contact_charges)
{
    tribo_charging c = make(0.5, 64);
    const tribo_scene P = params();
    const double seg = c.arc.perimeter / 64;
    const double *q = static_q(&c);
    const tribo_contact_sample s = sample(&c, 1.0, 10.3 * seg, 0.0, 0.01, 0.01, 0.01);
    tribo_charging_apply(&c, &P, &s, TRIBO_CHARGE_COMMIT);
    cr_expect(q[10] > 0.6 && q[9] == 0.0 && q[11] == 0.0);
    /* and a contact across the start of the numbering reaches both ends */
    const tribo_contact_sample w = sample(&c, 1.0, 0.1 * seg, 0.5 * seg, 0.01, 0.01, 0.01);
    tribo_charging_apply(&c, &P, &w, TRIBO_CHARGE_COMMIT);
    cr_expect(q[0] > 0.6 && q[63] > 0.6 && q[1] == 0.0);
    tribo_charging_free(&c);
}

/* ---- the sweep, on a synthetic contact --------------------------------------------- */

typedef struct moving {
    double s0, speed, half; /* centre s0 + speed t, fixed half-width */
    double perimeter;
    double rate_end;        /* > 0: work rate sqrt(rate_end - t), singular at rate_end */
    double kink;            /* > 0: work rate |t - kink| instead */
} moving;

/* The work rate of the sliding model, mu |vs| sqrt(delta_y / rho_c) / 2, is `rate` for
   mu = 2, vs = rate, delta_y = rho_c = 1. */
static void probe(void *ctx, double t, double *s_c, double *half, double *speed,
                  tribo_contact_kinematics *k)
{
    const moving *mv = ctx;
    *s_c = fmod(mv->s0 + mv->speed * t, mv->perimeter);
    if (*s_c < 0)
        *s_c += mv->perimeter;
    *half = mv->half;
    const double rate = mv->kink > 0       ? 0.16 * fabs(t - mv->kink)
                        : mv->rate_end > 0 ? sqrt(fmax(0.0, mv->rate_end - t))
                                           : 0.0;
    *k = (tribo_contact_kinematics){2.0, 1.0, rate, 1.0, 1.0};
    *speed = fabs(mv->speed);
}

static tribo_charging *target;
static tribo_scene PARAMS;
static long samples;
static int apply(void *ctx, const tribo_contact_sample *s)
{
    (void)ctx;
    samples++;
    tribo_charging_apply(target, &PARAMS, s, TRIBO_CHARGE_COMMIT);
    return 0;
}

/* Contact time of segment [a, a + L) under a contact [c(t) - w, c(t) + w], c = s0 + v t,
   over [0, T]: the overlap is an interval of t (no wrap-around in this test). */
static double exact_contact_time(double a, double L, const moving *mv, double T)
{
    /* overlap while s0 + v t - w < a + L and s0 + v t + w > a */
    double lo = (a - mv->half - mv->s0) / mv->speed, hi = (a + L + mv->half - mv->s0) / mv->speed;
    if (mv->speed < 0) {
        const double x = lo;
        lo = hi;
        hi = x;
    }
    return fmax(0.0, fmin(hi, T) - fmax(lo, 0.0));
}

Test(charging, sweep_gives_each_segment_its_exact_contact_time)
{
    tribo_charging c = make(0.7, 400);
    target = &c;
    PARAMS = params();
    const double P = c.arc.perimeter, L = P / 400;
    moving mv = {0.2 * P, 0.06, 3.3 * L, P, 0.0, 0.0};
    const tribo_contact_probe pr = {probe, &mv};
    double work = 0.0, globals[TRIBO_CHARGE_MAX_GLOBALS];
    tribo_charging_start(&c, &PARAMS, globals); /* Sigma_s = Sigma0,ref = Sigma0 */
    const double T = 25.0; /* the contact travels 1.5, 0.28 of the perimeter */
    samples = 0;
    cr_assert_eq(tribo_charging_sweep(&c, &PARAMS, &pr, 0.0, T, 1e-8, 1e-10, &work, globals, apply,
                                      NULL, INFINITY, TRIBO_SWEEP_CELL_COST, NULL),
                 0);
    double worst = 0.0;
    int touched = 0;
    for (int i = 0; i < 400; i++) {
        const double t_exact = exact_contact_time(i * L, L, &mv, T);
        const double t_swept = -PARAMS.tau0 * log1p(-static_q(&c)[i]);
        worst = fmax(worst, fabs(t_swept - t_exact));
        touched += t_exact > 0;
    }
    cr_expect(touched > 100, "%d segments touched", touched);
    cr_expect(worst < 1e-8, "largest contact-time error %.3g", worst);
    tribo_charging_free(&c);
}

/* The sweep's end: at t ~ 2496 with rtol 1e-12, a work rate has its kink (vs = 0 at the
   slip-to-stick switch that ends a CVODE step) a fraction of a nanosecond before the end
   of the interval. For an interval just over twice the smallest piece, the sweep's "snap to
   the end" and "accept a tiny piece" must agree to the ulp, or it stalls for ever (this
   test then hits its timeout). Over such intervals, and longer ones, it must finish with a
   bounded number of pieces and integrate the rate (to 1e-9 over the long intervals); the
   same with a rate singular at the end, sqrt(b - t). */
Test(charging, sweep_finishes_at_a_kinked_or_singular_end, .timeout = 60)
{
    tribo_charging c = make(0.6, 2000);
    target = &c;
    PARAMS = params();
    const double b = 2495.9721242660285, min_piece = 1e-13 * (1.0 + b);
    for (int k = 0; k < 400; k++) {
        const double a = k < 200 ? b - 2.0 * min_piece - k * 1.25e-14 : b - 0.0141189799588;
        for (int kind = 0; kind < 2; kind++) {
            const double kink = b - 0.3 * (b - a) * (k < 200 ? 1.0 : 1e-8);
            moving mv = {1.0, 1e-6, 0.3, c.arc.perimeter, kind ? b : 0.0, kind ? 0.0 : kink};
            const tribo_contact_probe pr = {probe, &mv};
            double work = 0.0, globals[TRIBO_CHARGE_MAX_GLOBALS];
            tribo_charging_start(&c, &PARAMS, globals);
            samples = 0;
            cr_assert_eq(tribo_charging_sweep(&c, &PARAMS, &pr, a, b, 1e-12, 1e-14, &work,
                                              globals, apply, NULL, INFINITY, TRIBO_SWEEP_CELL_COST,
                                              NULL), 0);
            cr_assert(samples < 100000, "interval %d: %ld samples", k, samples);
            const double exact = kind ? 2.0 / 3.0 * pow(b - a, 1.5)
                                      : 0.08 * ((kink - a) * (kink - a) + (b - kink) * (b - kink));
            /* a piece under the smallest size is taken as it is, kink and all */
            const double tol = k < 200 ? 0.1 : 1e-9;
            cr_assert(fabs(work - exact) <= tol * exact,
                      "interval %d kind %d: omega %.17g, exact %.17g", k, kind, work, exact);
        }
    }
    tribo_charging_free(&c);
}

/* A contact held at one place whose half-width swells and shrinks, half(t) = H - k (t - tm)^2:
   its edges turn at tm. */
typedef struct swelling {
    double s0, H, k, tm;
} swelling;

static void swelling_probe(void *ctx, double t, double *s_c, double *half, double *speed,
                           tribo_contact_kinematics *k)
{
    const swelling *sw = ctx;
    *s_c = sw->s0;
    *half = sw->H - sw->k * (t - sw->tm) * (t - sw->tm);
    *speed = 0.0;
    *k = (tribo_contact_kinematics){0.3, 1.0, 0.0, 1.0, 1.0};
}

/* Instantaneous transfer (model.md §5c) charges every segment the contact reaches, also one
   its edges reach only where they turn between the probes of a piece: over [0, T] in one
   piece (its probes at 0, T/4, T/2, ...), the edges turning at 0.15 T into the segments
   99 and 110, which the probes do not reach. */
Test(charging, instantaneous_transfer_reaches_where_the_edges_turn_between_probes)
{
    tribo_charging c = make(0.7, 400);
    target = &c;
    PARAMS = params();
    PARAMS.tau0 = 0.0;
    const double L = c.arc.perimeter / 400, T = 2.0;
    /* the edges turn 0.025 L past the boundaries at 100 L and 110 L; the probe at T/4 sees
       them 0.05 L short of their turns */
    swelling sw = {105.0 * L, 5.025 * L, 0.05 * L / (0.1 * T * 0.1 * T), 0.15 * T};
    const tribo_contact_probe pr = {swelling_probe, &sw};
    double work = 0.0, globals[TRIBO_CHARGE_MAX_GLOBALS];
    tribo_charging_start(&c, &PARAMS, globals);
    samples = 0;
    cr_assert_eq(tribo_charging_sweep(&c, &PARAMS, &pr, 0.0, T, 1e-8, 1e-10, &work, globals, apply,
                                      NULL, INFINITY, TRIBO_SWEEP_CELL_COST, NULL),
                 0);
    const double *q = static_q(&c);
    cr_expect(q[99] > 0.0 && q[110] > 0.0, "the turns' segments: %g, %g", q[99], q[110]);
    cr_expect(q[98] == 0.0 && q[111] == 0.0, "beyond them: %g, %g", q[98], q[111]);
    tribo_charging_free(&c);
}

/* A contact wider than the boundary charges each segment once, and one far off the
   numbering (as a corrupt or overflowing state could give) a segment or two, without a cast
   of a double an integer cannot hold (the sanitizer build checks the casts); the sums the
   outputs read follow the values. */
Test(charging, a_contact_wider_than_the_boundary_charges_each_segment_once)
{
    tribo_charging c = make(0.5, 64);
    const tribo_scene P = params();
    const double wide[][2] = {{1.0, 1e148}, {1e148, 1e148}, {3.0, 1e300}};
    for (int k = 0; k < 3; k++) {
        const tribo_contact_sample s = sample(&c, 0.1, wide[k][0], wide[k][1], 0.01, 0.01, 0.01);
        cr_expect_eq(tribo_charging_apply(&c, &P, &s, TRIBO_CHARGE_COMMIT), 2 * 64);
    }
    const double *q = static_q(&c);
    double sum = 0.0;
    for (int i = 0; i < 64; i++) {
        cr_expect_float_eq(q[i], 1.0 - exp(-0.3 / P.tau0), 1e-15, "segment %d", i);
        sum += q[i];
    }
    const double running = tribo_charging_sum(&c, TRIBO_SEGMENTS_STATIC);
    cr_expect(fabs(running - sum) <= 1e-14 * sum, "running sum %.17g, sum %.17g", running, sum);
    const double far[][2] = {{-1e148, 1.0}, {1e300, 0.0}, {-1e300, 1e-300}};
    for (int k = 0; k < 3; k++) {
        const tribo_contact_sample s = sample(&c, 0.1, far[k][0], far[k][1], 0.01, 0.01, 0.01);
        const long updates = tribo_charging_apply(&c, &P, &s, TRIBO_CHARGE_COMMIT);
        cr_expect(updates >= 2 && updates <= 2 * 2, "%ld updates", updates);
    }
    tribo_charging_free(&c);
}

/* ---- the air-breakdown limit (model.md §8b) --------------------------------------------- */

/* One contact held over segment 5 past the limit: each model leaves the segment at its
   bound, and what it holds plus what it lost is the charge it would have had without the
   limit (a single sample: the same rate law, to rounding). */
Test(charging, a_contact_past_the_limit_stays_at_it_and_books_the_rest_as_lost)
{
    tribo_charging c = make(0.5, 100);
    tribo_scene P = params();
    P.Sigma_bd = 0.004; /* static bound Sigma_bd / Sigma0 = 0.4, sliding bound 0.004 */
    const double seg = c.arc.perimeter / 100, S = 0.013, T = 5.0;
    const tribo_contact_sample s = sample(&c, T, 5.5 * seg, 0.2 * seg, S, S, S);
    cr_expect_eq(tribo_charging_apply(&c, &P, &s, TRIBO_CHARGE_COMMIT), 2);
    const double uncapped[2] = {1.0 - exp(-T / P.tau0), S * (1.0 - exp(-T / P.tau0))};
    const double bound[2] = {0.4, 0.004};
    const double *held[2] = {static_q(&c), sliding_sigma(&c)};
    for (int k = 0; k < 2; k++) {
        const tribo_charge_slot *slot = &c.slot[k];
        cr_expect_eq(held[k][5], bound[k], "%s: %.17g", slot->model->name, held[k][5]);
        cr_expect_float_eq(held[k][5] + tribo_charging_lost(&c, k), uncapped[k], 4e-16 * uncapped[k],
                           "%s", slot->model->name);
        cr_expect_eq(tribo_charging_sum(&c, k), bound[k]);
        cr_expect_eq(tribo_charging_capped(slot, &P, held[k], 100), 1);
    }
    /* charging on at the limit only adds to the loss */
    const double lost = tribo_charging_lost(&c, 1);
    tribo_charging_apply(&c, &P, &s, TRIBO_CHARGE_COMMIT);
    cr_expect_eq(sliding_sigma(&c)[5], 0.004);
    cr_expect_float_eq(tribo_charging_lost(&c, 1) - lost,
                       (S - 0.004) * (1.0 - exp(-T / P.tau0)), 1e-17);
    tribo_charging_free(&c);
}

/* ---- a saturated boundary (charge_sweep.c, saturated_piece) ---------------------------- */

/* The boundary of a grain charged turn after turn: each segment a few units of rounding off
   each model's saturation (static 1, sliding Sigma_s = Sigma0, no work done), k of them for
   segment i (k < 16, the sweep's bound), below it. */
static void saturate_all(tribo_charging *c, int n)
{
    for (int i = 0; i < n; i++) {
        const double k = (double)(i % 9);
        static_q(c)[i] = 1.0 - k * DBL_EPSILON;
        sliding_sigma(c)[i] = PARAMS.Sigma0 * (1.0 - k * DBL_EPSILON);
    }
}

/* A contact travelling 0.28 of the boundary of n = 400 segments from segment 80 (to 191) over
   [0, T = 25], doing no work (model.md §5a, §5b). */
static void sweep_along(tribo_charging *c, double T)
{
    moving mv = {0.2 * c->arc.perimeter, 0.06, 0.3 * c->arc.perimeter / 400, c->arc.perimeter,
                 0.0, 0.0};
    const tribo_contact_probe pr = {probe, &mv};
    double work = 0.0, globals[TRIBO_CHARGE_MAX_GLOBALS];
    tribo_charging_start(c, &PARAMS, globals);
    samples = 0;
    cr_assert_eq(tribo_charging_sweep(c, &PARAMS, &pr, 0.0, T, 1e-8, 1e-10, &work, globals, apply,
                                      NULL, INFINITY, TRIBO_SWEEP_CELL_COST, NULL),
                 0);
}

/* Where every segment the contact crosses is within 16 units of rounding of its saturation
   and the globals hold still, the sweep leaves them as they are, giving its sink no sample:
   charging them would move none by more than that (the rate law only approaches the
   saturation). One segment farther off on the contact's way is charged, towards its
   saturation and not past it. */
Test(charging, a_saturated_boundary_is_left_as_it_is_and_a_segment_off_it_is_charged)
{
    tribo_charging c = make(0.7, 400);
    target = &c;
    PARAMS = params();
    saturate_all(&c, 400);
    double before[400];
    memcpy(before, static_q(&c), sizeof before);
    sweep_along(&c, 25.0);
    cr_expect_eq(samples, 0, "%ld samples", samples);
    cr_expect_eq(memcmp(before, static_q(&c), sizeof before), 0);
    /* segment 150 lies on the contact's way (it starts at 80 and covers 0.6 segments) */
    static_q(&c)[150] = 1.0 - 20.0 * DBL_EPSILON;
    sweep_along(&c, 25.0);
    cr_expect_gt(samples, 0);
    cr_expect_gt(static_q(&c)[150], 1.0 - 20.0 * DBL_EPSILON);
    cr_expect_leq(static_q(&c)[150], 1.0);
    tribo_charging_free(&c);
}

/* A sweep that starts on saturated segments tries a saturated piece first; where the
   boundary ahead is not saturated it drops that piece and starts again as a sweep that never
   hoped: every segment but those under the contact at the start is charged the same to the
   bit, in as many samples. */
Test(charging, a_sweep_that_hoped_for_a_saturated_boundary_is_the_sweep_that_did_not)
{
    double after[2][400];
    long count[2];
    for (int hope = 0; hope < 2; hope++) {
        tribo_charging c = make(0.7, 400);
        target = &c;
        PARAMS = params();
        for (int i = 0; i < 400; i++)
            static_q(&c)[i] = sliding_sigma(&c)[i] = 0.0;
        /* the contact starts over segment 80 */
        for (int i = 78; i <= 82; i++) {
            static_q(&c)[i] = hope ? 1.0 : 0.5;
            sliding_sigma(&c)[i] = hope ? PARAMS.Sigma0 : 0.5 * PARAMS.Sigma0;
        }
        sweep_along(&c, 25.0);
        memcpy(after[hope], static_q(&c), sizeof after[hope]);
        count[hope] = samples;
        tribo_charging_free(&c);
    }
    cr_expect_eq(count[0], count[1], "%ld and %ld samples", count[0], count[1]);
    for (int i = 0; i < 400; i++)
        if (i < 78 || i > 82)
            cr_expect_eq(after[0][i], after[1][i], "segment %d: %.17g and %.17g", i, after[0][i],
                         after[1][i]);
}

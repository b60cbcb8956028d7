/* The vibrating chute (model.md §9b): the plate's stroke as an inertial force in its frame, in
   both integrators, the flight's closed form, the locks and the vibration's work. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <string.h>

#include "flight.h"
#include "si.h"
#include "support.h"

#define HALF_PI 1.5707963267948966

/* A disc resting on a level plate that vibrates along its normal with throw number K, the
   plate's acceleration starting at its lowest, sin(w tau - pi/2), the run ending at the
   first lift-off: the rigid contact lifts off where sin(w tau - pi/2) first reaches 1/K. */
static tribo_scene resting_disc(double K, double Gamma, double omega, int stick_model)
{
    tribo_scene s = scene_of("epsilon=1 beta=0 mu=0.3 nu=0.3 gap0=0 drop_speed=0 n_segments=64 "
                             "vib_angle=1.5707963267948966 vib_phase=-1.5707963267948966 "
                             "run_end=1");
    no_charge_models(&s);
    s.stick_model = stick_model;
    s.Gamma = Gamma;
    s.vib_omega = omega;
    s.vib_accel = K * Gamma;
    return s;
}

static double liftoff_time(double K, double omega) { return (HALF_PI + asin(1.0 / K)) / omega; }

Test(vibration, a_resting_grain_lifts_off_where_the_plate_pulls_away_at_g)
{
    /* the paper's scale (Gamma 1e-3, a period of 628) and a 1 mm grain's at 50 Hz (Gamma 1e-8,
       w 2.2e-4): measured phase errors of the rigid contact at most 1.7e-15 rad (3.1e-14 when
       CVODE took the contact, before DOP853); bound 1e-9 rad, the rtol (the lift-off is a
       located switch) */
    const double Ks[] = {1.05, 1.5, 2.0, 4.0};
    const double scales[][2] = {{1e-3, 0.01}, {1e-8, 2.2e-4}};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 4; i++) {
            tribo_scene s = resting_disc(Ks[i], scales[j][0], scales[j][1], TRIBO_STICK_RIGID);
            tribo_model *m = make(&s);
            const double t_lift = liftoff_time(Ks[i], scales[j][1]);
            cr_assert_eq(tribo_advance_fully(m, 2.0 * t_lift), TRIBO_ENDED, "%s", tribo_last_error(m));
            cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_LIFTED_OFF), 1.0);
            const double phase_error = (tribo_get(m, TRIBO_QUANTITY_TIME) - t_lift) * scales[j][1];
            cr_log_info("K = %g, Gamma = %g: phase error %.3g", Ks[i], scales[j][0], phase_error);
            cr_expect(fabs(phase_error) <= 1e-9, "K = %g, Gamma = %g: lift-off phase off by %.3g",
                      Ks[i], scales[j][0], phase_error);
            cr_expect(fabs(tribo_get(m, TRIBO_QUANTITY_THROW_NUMBER) - Ks[i]) <= 1e-12 * Ks[i]);
            tribo_free(m);
        }
}

Test(vibration, the_compliant_contact_leaves_within_its_response_of_the_rigid_one)
{
    /* model.md §9b: the compliant contact leaves off the rigid one's phase by a phase of order
       w (its response time is of order 1: it leaves the lock at the band's lower edge, its
       spring unloading with its dashpot); measured -0.0069 and +0.0037 rad at w = 0.01 for
       K = 1.5, 4; bound 5 w */
    const double Ks[] = {1.5, 4.0};
    for (int i = 0; i < 2; i++) {
        tribo_scene s = resting_disc(Ks[i], 1e-3, 0.01, TRIBO_STICK_COMPLIANT);
        tribo_model *m = make(&s);
        const double t_lift = liftoff_time(Ks[i], 0.01);
        cr_assert_eq(tribo_advance_fully(m, 2.0 * t_lift), TRIBO_ENDED, "%s", tribo_last_error(m));
        const double lag = (tribo_get(m, TRIBO_QUANTITY_TIME) - t_lift) * 0.01;
        cr_log_info("K = %g: lag %.3g rad", Ks[i], lag);
        cr_expect(fabs(lag) <= 5.0 * 0.01 && lag != 0.0, "K = %g: lag %.3g rad", Ks[i], lag);
        tribo_free(m);
    }
}

Test(vibration, a_grain_below_the_throw_number_of_one_never_lifts_off)
{
    const double Ks[] = {0.5, 0.95};
    for (int i = 0; i < 2; i++)
        for (int stick = 0; stick < 2; stick++) {
            tribo_scene s = resting_disc(Ks[i], 1e-8, 2.2e-4, stick);
            tribo_model *m = make(&s);
            const double period = 2.0 * M_PI / 2.2e-4;
            for (int k = 1; k <= 40; k++) {
                cr_assert_eq(tribo_advance_fully(m, k * period / 8.0), TRIBO_OK, "K = %g: %s", Ks[i],
                             tribo_last_error(m));
                cr_assert_eq(tribo_get(m, TRIBO_QUANTITY_IN_CONTACT), 1.0, "K = %g at %g", Ks[i],
                             tribo_get(m, TRIBO_QUANTITY_TIME));
            }
            cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_LIFTED_OFF), 0.0);
            tribo_free(m);
        }
}

/* A 1 mm grain's scale on a level feeder (Gamma 1e-8, w 2.2e-4 for 50 Hz) with a stroke at
   psi_v and throw number K, the grain (roundness eps) dropped onto it. */
static tribo_scene feeder(double K, double psi, double eps, int integrator)
{
    tribo_scene s = scene_of("beta=0 mu=0.3 nu=0.3 gap0=0.01 drop_speed=0 n_segments=64 "
                             "mu_roll=0.01 Gamma=1e-8 vib_omega=2.2e-4 dt=0.01");
    no_charge_models(&s);
    s.epsilon = eps;
    s.vib_angle = psi;
    s.vib_accel = K * 1e-8 / sin(psi);
    s.integrator = integrator;
    s.stick_model = integrator == TRIBO_INTEGRATOR_FIXED_STEP ? TRIBO_STICK_COMPLIANT : TRIBO_STICK_RIGID;
    return s;
}

/* E - W_vib - W_ext at the output point (model.md §6, §9b) */
static double budget(tribo_model *m)
{
    return tribo_get(m, TRIBO_QUANTITY_ENERGY) - tribo_get(m, TRIBO_QUANTITY_WORK_VIBRATION) -
           tribo_get(m, TRIBO_QUANTITY_WORK_EXTERNAL);
}

Test(vibration, energy_less_the_vibrations_work_never_increases)
{
    /* model.md §6 with §9b: with the contact-point dashpot E - W_vib never increases; with
       the event-driven integrator (DOP853 in contact) it falls by what is booked as dissipated
       (E - W_vib + W_diss stays at its start), to its tolerance on the works; the fixed step's
       regularised laws book it to their own accuracy. The energies are ~1e-8. Measured: rises
       of at most 6.8e-22 (rounding and the works' tolerance); the event-driven balance
       residual at most 1.9e-14 (1.6e-13 with CVODE in contact). Bounds 1e-20 and 1e-12. */
    const double Ks[] = {0.8, 1.6, 3.0}, psis[] = {M_PI / 6, M_PI / 4, HALF_PI},
                 epss[] = {1.0, 0.6, 0.3};
    for (int i = 0; i < 3; i++)
        for (int integrator = 1; integrator >= 0; integrator--) {
            tribo_scene s = feeder(Ks[i], psis[i], epss[i], integrator);
            if (integrator == TRIBO_INTEGRATOR_FIXED_STEP)
                s.dt = 0.05; /* the fixed step over a cycle and a half: 3e5 steps */
            tribo_model *m = make(&s);
            const double start = budget(m) + tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED);
            double last = budget(m), rise = 0.0, balance = 0.0;
            const double period = 2.0 * M_PI / 2.2e-4, span = integrator ? 6.0 : 1.5;
            for (int k = 1; k <= 600; k++) {
                cr_assert_eq(tribo_advance_fully(m, k * span * period / 600.0), TRIBO_OK, "%s",
                             tribo_last_error(m));
                const double now = budget(m);
                rise = fmax(rise, now - last);
                balance = fmax(balance, fabs(now + tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED) - start));
                last = now;
            }
            cr_log_info("K %g, integrator %d: largest rise %.3g, balance residual %.3g, %g impacts",
                        Ks[i], integrator, rise, balance, tribo_get(m, TRIBO_QUANTITY_IMPACTS));
            cr_expect(tribo_get(m, TRIBO_QUANTITY_WORK_VIBRATION) != 0.0);
            cr_expect(rise <= 1e-20, "K = %g, integrator %d: E - W_vib rose by %.3g", Ks[i],
                      integrator, rise);
            if (integrator != TRIBO_INTEGRATOR_FIXED_STEP) {
                cr_expect(balance <= 1e-12, "K = %g: E - W_vib + W_diss moved by %.3g", Ks[i], balance);
                if (Ks[i] > 1.0)
                    cr_expect(tribo_get(m, TRIBO_QUANTITY_IMPACTS) > 2.0, "K = %g: %g impacts",
                              Ks[i], tribo_get(m, TRIBO_QUANTITY_IMPACTS));
            }
            tribo_free(m);
        }
}

Test(vibration, a_still_plate_does_no_work)
{
    for (int integrator = 0; integrator < 2; integrator++) {
        tribo_scene s = feeder(2.0, M_PI / 6, 0.6, integrator);
        s.vib_accel = 0.0;
        s.dt = 0.1;
        tribo_model *m = make(&s);
        cr_assert_eq(tribo_advance_fully(m, 3e3), TRIBO_OK, "%s", tribo_last_error(m));
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_WORK_VIBRATION), 0.0);
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_THROW_NUMBER), 0.0);
        tribo_free(m);
    }
}

Test(vibration, a_disc_on_a_plate_vibrating_along_its_normal_does_not_drift)
{
    /* model.md §9b: a stroke along the normal has no component along the plate (but the
       rounding of cos(pi/2), 6e-17 of it): a disc bounced on it, K = 2.5, stays where it
       fell; measured mean X 7.4e-14 semi-axes over 1000 cycles (539 impacts: it hops every
       other cycle); bound 1e-9 */
    tribo_scene s = feeder(2.5, HALF_PI, 1.0, TRIBO_INTEGRATOR_CVODE);
    tribo_model *m = make(&s);
    const double period = 2.0 * M_PI / 2.2e-4;
    double mean = 0.0;
    for (int k = 1; k <= 1000; k++) {
        cr_assert_eq(tribo_advance_fully(m, k * period), TRIBO_OK, "%s", tribo_last_error(m));
        mean += tribo_get(m, TRIBO_QUANTITY_X) / 1000.0;
    }
    cr_log_info("mean X %.3g over 1000 cycles, %g impacts", mean, tribo_get(m, TRIBO_QUANTITY_IMPACTS));
    cr_expect(tribo_get(m, TRIBO_QUANTITY_IMPACTS) >= 400.0); /* measured 539 */
    cr_expect(fabs(mean) <= 1e-9, "mean X %.3g", mean);
    tribo_free(m);
}

Test(vibration, the_fixed_step_and_cvode_agree_on_a_feeder_to_the_still_chutes_accuracy)
{
    /* docs/work_precision.md: the fixed step at dt = 8e-5 against CVODE, the state at tau = 20
       of the paper's eps = 0.3, mu = nu = 0.1 drop agrees to 8.8e-9 (measured here 9.2e-9
       against rtol 1e-10); on a plate vibrating fast enough to move that drop (w = 0.3, K = 3
       at psi_v = 30 degrees), measured 2.9e-8 (DOP853 in contact; 3.2e-8 when CVODE took it):
       the difference of the laws, the fixed step's regularised sign (v_reg 1e-6) against the
       set-valued one, which the stroke's load on the contact brings out (halving dt moves the
       fixed step by 4.6e-10, CVODE's rtol 1e-12 moved it by 2.5e-9). Bounds: 1.2e-8 still,
       6.4e-8 vibrating (twice the measured). */
    tribo_scene s = scene_of("epsilon=0.3 mu=0.1 nu=0.1 vib_omega=0.3 vib_angle=0.5235987755982988");
    no_charge_models(&s);
    s.vib_accel = 3.0 * s.Gamma * cos(s.beta) / sin(s.vib_angle);
    tribo_model *fixed, *cvode;
    make_fixed_and_cvode(s, &fixed, &cvode);
    advance_both(fixed, cvode, 20.0);
    const double d = state_distance(fixed, cvode);
    tribo_scene still = s;
    still.vib_accel = 0.0;
    tribo_model *fixed0, *cvode0;
    make_fixed_and_cvode(still, &fixed0, &cvode0);
    advance_both(fixed0, cvode0, 20.0);
    const double d0 = state_distance(fixed0, cvode0);
    cr_log_info("fixed step against CVODE at tau = 20: %.3g (still: %.3g)", d, d0);
    cr_expect(d0 <= 1.2e-8, "the still state differs by %.3g", d0);
    tribo_free(fixed0);
    tribo_free(cvode0);
    cr_expect(d <= 6.4e-8, "the state differs by %.3g", d);
    cr_expect(tribo_get(cvode, TRIBO_QUANTITY_WORK_VIBRATION) != 0.0);
    tribo_free(fixed);
    tribo_free(cvode);
}

/* ---- the flight's landing against a brute-force integration (flight.h) -------------------- */

/* A small deterministic generator (xorshift64*), so that the set-ups are the same every run. */
static double uniform(uint64_t *x, double lo, double hi)
{
    *x ^= *x >> 12;
    *x ^= *x << 25;
    *x ^= *x >> 27;
    return lo + (hi - lo) * (double)((*x * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

/* The free motion of model.md §4 and §9b (no contact force) integrated by RK4: X, Y, U, V, phi. */
static void free_rate(const tribo_dyn_params *p, double t, const double *z, double *dz)
{
    const double f = p->vib_accel * sin(p->vib_omega * t + p->vib_phase);
    dz[0] = z[2];
    dz[1] = z[3];
    dz[2] = p->g_t + f * p->vib_cos;
    dz[3] = -p->g_n + f * p->vib_sin;
    dz[4] = z[5];
    dz[5] = 0.0;
}

static void rk4_free(const tribo_dyn_params *p, double t, double *z, double h)
{
    double k[4][6], w[6];
    free_rate(p, t, z, k[0]);
    for (int i = 0; i < 6; i++)
        w[i] = z[i] + 0.5 * h * k[0][i];
    free_rate(p, t + 0.5 * h, w, k[1]);
    for (int i = 0; i < 6; i++)
        w[i] = z[i] + 0.5 * h * k[1][i];
    free_rate(p, t + 0.5 * h, w, k[2]);
    for (int i = 0; i < 6; i++)
        w[i] = z[i] + h * k[2][i];
    free_rate(p, t + h, w, k[3]);
    for (int i = 0; i < 6; i++)
        z[i] += h / 6.0 * (k[0][i] + 2.0 * (k[1][i] + k[2][i]) + k[3][i]);
}

/* The flight f from y0 at t0 searched (flight.h) up to t0 + H, `budget` looks a piece: the time
   it ends, *why, and the looks it took in *looks. */
static double flight_end(tribo_flight *f, const tribo_dyn_params *p, double t0, const double *y0,
                         double H, long budget, tribo_flight_end *why, long *looks)
{
    tribo_flight_start(f, p, t0, y0, TRIBO_NMOTION + 1);
    *why = TRIBO_FLIGHT_GOES_ON;
    double t = t0;
    long used;
    *looks = 0;
    while (*why == TRIBO_FLIGHT_GOES_ON && t < t0 + H && *looks < 1000000) {
        t = tribo_flight_end_of(f, p, t, t0 + H, budget, why, &used);
        *looks += used;
    }
    return t;
}

static double indentation_of(const tribo_dyn_params *p, const double *z)
{
    tribo_pose g;
    tribo_pose_at(p->eps2, z[4], &g);
    return g.h - z[1];
}

Test(vibration, the_flights_landing_is_the_first_one_a_dense_integration_finds)
{
    /* 10,000 random flights over a vibrating plate (roundness, spin, tilt, stroke, phase, start
       time, height and velocity), each searched for its landing (flight.h) over a horizon of
       H = 2000, against RK4 at H/2000 (and H/2000/256 around the crossing it brackets). No
       landing missed: the flight lands within the first bracket where the integration's
       indentation turns positive, or, where the integration finds none, neither does the
       flight; times equal to the refined crossing's: measured within 6.1e-9 of H; bound 1e-6 H.
       Bounded in work: 10,000 x 2000 RK4 steps and the flight's own look-ups. */
    uint64_t x = 0x9e3779b97f4a7c15ull;
    int landed = 0, both_none = 0;
    double worst = 0.0;
    const double H = 2000.0;
    const int N = 2000;
    for (int k = 0; k < 10000; k++) {
        tribo_dyn_params p;
        memset(&p, 0, sizeof p);
        p.eps = uniform(&x, 0.2, 1.0);
        p.eps2 = p.eps * p.eps;
        p.Gamma = pow(10.0, uniform(&x, -4.0, -2.0));
        const double beta = uniform(&x, 0.0, 1.2);
        p.g_t = p.Gamma * sin(beta);
        p.g_n = p.Gamma * cos(beta);
        p.inv_inertia = 4.0 / (1.0 + p.eps2);
        p.rtol = 1e-9;
        p.atol = 1e-11;
        p.chute_length = INFINITY;
        p.vib_omega = pow(10.0, uniform(&x, -3.0, -1.0));
        p.vib_accel = p.Gamma * uniform(&x, 0.0, 5.0);
        const double psi = uniform(&x, -HALF_PI, HALF_PI);
        p.vib_cos = cos(psi);
        p.vib_sin = sin(psi);
        p.vib_phase = uniform(&x, 0.0, 2.0 * M_PI);
        p.vib_slot = TRIBO_NMOTION;
        const double t0 = uniform(&x, 0.0, 1000.0);
        double y0[TRIBO_NSTATE_MAX] = {0};
        y0[TRIBO_IPHI] = uniform(&x, -M_PI, M_PI);
        y0[TRIBO_IOMEGA] = uniform(&x, -1.0, 1.0) * (k % 4 == 0 ? 0.0 : 0.02);
        tribo_pose g;
        tribo_pose_at(p.eps2, y0[TRIBO_IPHI], &g);
        y0[TRIBO_IGAP] = uniform(&x, 0.0, 0.05);
        y0[TRIBO_IY] = g.h + y0[TRIBO_IGAP];
        y0[TRIBO_IU] = uniform(&x, -0.02, 0.02);
        y0[TRIBO_IV] = uniform(&x, -0.02, 0.02);

        /* the flight's landing within the horizon */
        tribo_flight f;
        tribo_flight_end why;
        long looks;
        const double t = flight_end(&f, &p, t0, y0, H, 1000, &why, &looks);
        cr_assert(why != TRIBO_FLIGHT_GOES_ON || t >= t0 + H, "set-up %d: the search stalled", k);
        const double s_flight = why == TRIBO_FLIGHT_CONTACT ? t - t0 : INFINITY;

        /* the integration's first bracket where the indentation turns positive */
        double z[6] = {y0[TRIBO_IX], y0[TRIBO_IY], y0[TRIBO_IU], y0[TRIBO_IV], y0[TRIBO_IPHI],
                       y0[TRIBO_IOMEGA]};
        const double ds = H / N;
        double s_cross = INFINITY;
        for (int j = 0; j < N && !isfinite(s_cross); j++) {
            double before[6];
            memcpy(before, z, sizeof z);
            rk4_free(&p, t0 + j * ds, z, ds);
            if (indentation_of(&p, z) < 0.0)
                continue;
            /* refine: the same interval in 256 steps, the crossing between two of them */
            double w[6], prev = indentation_of(&p, before);
            memcpy(w, before, sizeof w);
            for (int i = 0; i < 256; i++) {
                rk4_free(&p, t0 + j * ds + i * ds / 256.0, w, ds / 256.0);
                const double now = indentation_of(&p, w);
                if (now >= 0.0) {
                    s_cross = j * ds + (i + (-prev) / (now - prev)) * ds / 256.0;
                    break;
                }
                prev = now;
            }
            if (!isfinite(s_cross))
                s_cross = (j + 1) * ds;
        }
        if (!isfinite(s_cross)) {
            /* none found densely: the flight may only find one the grid stepped over */
            both_none += !isfinite(s_flight);
            continue;
        }
        landed++;
        cr_assert(s_flight <= s_cross + 1e-6 * H,
                  "set-up %d: landing missed: the flight lands at %.12g, the integration at %.12g", k,
                  s_flight, s_cross);
        /* an earlier landing than the integration's bracket is a touch the grid stepped over:
           the flight's own state there must be on the plate */
        double yl[TRIBO_NSTATE_MAX];
        tribo_flight_state(&f, &p, t0 + s_flight, yl);
        /* (to the rounding of its time: the search steps at least 4 roundings of the time) */
        const double on_plate = 1e-14 + 8.0 * DBL_EPSILON * (t0 + s_flight + 1.0) *
                                                (fabs(yl[TRIBO_IV]) + fabs(yl[TRIBO_IOMEGA]));
        cr_assert(fabs(yl[TRIBO_IGAP]) <= on_plate, "set-up %d: landed %.3g off the plate", k,
                  yl[TRIBO_IGAP]);
        if (s_flight >= s_cross - ds)
            worst = fmax(worst, fabs(s_flight - s_cross) / H);
    }
    cr_log_info("%d landings, %d flights without one; largest time difference %.3g of H", landed,
                both_none, worst);
    cr_expect(landed > 5000);
    cr_expect(worst <= 1e-6, "time off by %.3g of H", worst);
}

/* ---- the SI front end's vibration (model.md §8, §9b) -------------------------------------- */

static tribo_status si_derive(const char *settings, char *msg, size_t n, tribo_si_derived *d)
{
    tribo_si_scene s;
    tribo_si_scene_defaults(&s);
    const tribo_status st = tribo_si_scene_apply(&s, settings, msg, n);
    return st != TRIBO_OK ? st : tribo_si_derive(&s, d, msg, n);
}

Test(vibration, the_si_feeder_maps_onto_the_models_stroke)
{
    /* 0.5 mm at 50 Hz along 30 degrees on a level chute: K = A w^2 sin(psi) / g = 2.52 */
    tribo_si_derived d;
    char msg[512];
    cr_assert_eq(si_derive("tilt=0 vibration_amplitude=5e-4 vibration_frequency=50 "
                           "vibration_angle=0.5235987755982988",
                           msg, sizeof msg, &d),
                 TRIBO_OK, "%s", msg);
    const double w = 2.0 * M_PI * 50.0;
    cr_expect(fabs(d.scene.vib_omega - w * d.t_star) <= 1e-15 * w * d.t_star);
    cr_expect(fabs(d.scene.vib_accel - 5e-4 / d.a * pow(w * d.t_star, 2.0)) <= 1e-14 * d.scene.vib_accel);
    const double K = d.scene.vib_accel * sin(d.scene.vib_angle) / d.scene.Gamma;
    cr_expect(fabs(K - 5e-4 * w * w * 0.5 / 9.81) <= 1e-12 * K, "K = %.15g", K);
    /* a still chute (amplitude 0) keeps the model's still plate, whatever its frequency */
    cr_assert_eq(si_derive("vibration_frequency=0", msg, sizeof msg, &d), TRIBO_OK, "%s", msg);
    cr_expect_eq(d.scene.vib_accel, 0.0);
}

Test(vibration, bad_vibrations_are_refused_naming_the_parameter_its_value_and_range)
{
    const struct {
        const char *settings, *expect[3];
    } cases[] = {
        {"vibration_amplitude=-1e-4", {"vibration_amplitude", "-0.0001", "0 <= vibration_amplitude"}},
        {"vibration_amplitude=5e-4 vibration_frequency=0",
         {"vibration_frequency = 0 Hz", "vibration_amplitude = 0.0005 m", "(0, 1e6]"}},
        {"vibration_angle=2", {"vibration_angle", "2", "1.5708"}},
        {"vibration_angle=-1.6", {"vibration_angle", "-1.6", "-1.5708"}},
        /* Lambda_v above 10: 0.1 m at 100 kHz on a 1 mm grain (Lambda_v 39) */
        {"vibration_amplitude=0.1 vibration_frequency=1e5", {"vib_accel", "vibration_amplitude = 0.1 m", "<= 10"}},
        /* w_v above 1: 1 MHz */
        {"vibration_amplitude=1e-9 vibration_frequency=1e6", {"vib_omega", "vibration_frequency = 1e+06 Hz", "<= 1"}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        tribo_si_derived d;
        char msg[512] = "";
        cr_expect_eq(si_derive(cases[i].settings, msg, sizeof msg, &d), TRIBO_ERR_INVALID_ARGUMENT,
                     "%s: accepted", cases[i].settings);
        cr_expect(strchr(msg, '\n') == NULL, "%s: more than one line: %s", cases[i].settings, msg);
        for (int k = 0; k < 3; k++)
            cr_expect(strstr(msg, cases[i].expect[k]) != NULL, "%s: '%s' not in: %s",
                      cases[i].settings, cases[i].expect[k], msg);
    }
    /* the dimensionless ones by the model's own ranges */
    tribo_scene s;
    char msg[512];
    tribo_scene_defaults(&s);
    cr_expect_neq(tribo_scene_set(&s, "vib_accel", -1.0, msg, sizeof msg), TRIBO_OK);
    cr_expect(strstr(msg, "vib_accel") && strstr(msg, "-1"), "%s", msg);
    cr_expect_neq(tribo_scene_set(&s, "vib_omega", 0.0, msg, sizeof msg), TRIBO_OK);
    cr_expect(strstr(msg, "vib_omega") && strstr(msg, "1e-12"), "%s", msg);
    cr_expect_neq(tribo_scene_set(&s, "vib_angle", 1.6, msg, sizeof msg), TRIBO_OK);
    cr_expect(strstr(msg, "vib_angle") && strstr(msg, "1.6"), "%s", msg);
}

Test(vibration, a_saved_feeder_goes_on_bit_for_bit)
{
    /* the state carries W_vib and the phase of the stroke is the time's: a feeder saved in
       the middle of its hops and loaded into a fresh instance goes on as the one that was not
       saved, for both integrators */
    for (int integrator = 0; integrator < 2; integrator++) {
        tribo_scene s = feeder(2.5, M_PI / 6, 0.6, integrator);
        s.dt = 0.1;
        tribo_model *a = make(&s), *b = make(&s);
        const double period = 2.0 * M_PI / 2.2e-4;
        cr_assert_eq(tribo_advance_fully(a, 1.37 * period), TRIBO_OK, "%s", tribo_last_error(a));
        size_t size;
        unsigned char *bytes = saved_state(a, &size);
        cr_assert_eq(tribo_state_load(b, bytes, size), TRIBO_OK, "%s", tribo_last_error(b));
        free(bytes);
        advance_both(a, b, 2.5 * period);
        cr_expect(tribo_get(a, TRIBO_QUANTITY_WORK_VIBRATION) != 0.0);
        cr_expect(same_outputs(a, b), "integrator %d: the loaded run differs", integrator);
        tribo_free(a);
        tribo_free(b);
    }
    /* a still plate's state is refused by a vibrating one (vib_accel is structural: the
       vibrating state has W_vib, and the state's size says so first) */
    tribo_scene still = feeder(2.5, M_PI / 6, 0.6, TRIBO_INTEGRATOR_CVODE), shaken = still;
    still.vib_accel = 0.0;
    tribo_model *a = make(&still), *b = make(&shaken);
    size_t size;
    unsigned char *bytes = saved_state(a, &size);
    cr_expect_neq(tribo_state_load(b, bytes, size), TRIBO_OK);
    free(bytes);
    tribo_free(a);
    tribo_free(b);
}

Test(vibration, a_flight_from_a_liftoff_leaves_the_plate_in_few_looks)
{
    /* model.md §9b: where the plate lifts a grain off, its lowest point leaves with the
       indentation, its rate and its second derivative at 0 (but for rounding) and only the
       third moving it away; 1000 such starts (spinning ellipses, the stroke's phase where the
       load passes 0 going down): the search reaches the landing, or the horizon of two
       periods, in a bounded number of looks at the clearance (measured at most 8; 17,284 for one
       start before the search took the third derivative's escape step; bound 2000), and no
       landing is missed against RK4 (as above) */
    uint64_t x = 0x2545f4914f6cdd1dull;
    long worst = 0;
    int landed = 0;
    for (int k = 0; k < 1000; k++) {
        tribo_dyn_params p;
        memset(&p, 0, sizeof p);
        p.eps = uniform(&x, 0.5, 1.0);
        p.eps2 = p.eps * p.eps;
        p.Gamma = 1e-8;
        p.g_n = p.Gamma;
        p.inv_inertia = 4.0 / (1.0 + p.eps2);
        p.rtol = 1e-9;
        p.atol = 1e-11;
        p.chute_length = INFINITY;
        p.vib_omega = 2.2e-4;
        p.vib_accel = p.Gamma * uniform(&x, 1.2, 4.0);
        const double psi = uniform(&x, 0.3, HALF_PI);
        p.vib_cos = cos(psi);
        p.vib_sin = sin(psi);
        p.vib_slot = TRIBO_NMOTION;
        double y0[TRIBO_NSTATE_MAX] = {0};
        y0[TRIBO_IPHI] = uniform(&x, -M_PI, M_PI);
        y0[TRIBO_IOMEGA] = uniform(&x, -3e-5, 3e-5);
        tribo_pose g;
        tribo_pose_at(p.eps2, y0[TRIBO_IPHI], &g);
        const double Om = y0[TRIBO_IOMEGA], kappa = tribo_pose_kappa(p.eps2, &g);
        /* delta'' = -kappa Om^2 + g_n - Lambda sin(psi) sin(theta) = 0, the load falling */
        const double s_theta = (p.g_n - kappa * Om * Om) / (p.vib_accel * p.vib_sin);
        if (fabs(s_theta) >= 1.0)
            continue;
        const double theta = asin(s_theta);
        const double t0 = 1000.0;
        p.vib_phase = theta - p.vib_omega * t0;
        y0[TRIBO_IY] = g.h;
        y0[TRIBO_IGAP] = 0.0;
        y0[TRIBO_IV] = -g.cx * Om;
        y0[TRIBO_IU] = uniform(&x, -1e-5, 1e-5);
        const double H = 2.0 * 2.0 * M_PI / p.vib_omega;
        tribo_flight f;
        tribo_flight_end why;
        long looks;
        const double t = flight_end(&f, &p, t0, y0, H, 64, &why, &looks);
        worst = looks > worst ? looks : worst;
        cr_assert(looks <= 2000, "start %d: %ld looks (eps %g, Omega %g)", k, looks, p.eps, Om);
        if (why != TRIBO_FLIGHT_CONTACT)
            continue;
        landed++;
        /* no earlier landing in the integration, sampled at H / 4000 from a tenth of the
           flight on (the first instants are the lift-off's, at the plate by construction) */
        double z[6] = {0.0, y0[TRIBO_IY], y0[TRIBO_IU], y0[TRIBO_IV], y0[TRIBO_IPHI], Om};
        const double ds = H / 4000.0, s_flight = t - t0;
        for (int j = 0; (j + 1) * ds < s_flight; j++) {
            rk4_free(&p, t0 + j * ds, z, ds);
            if ((j + 1) * ds > 0.1 * s_flight)
                cr_assert(indentation_of(&p, z) < 1e-12, "start %d: a landing missed at %g", k,
                          (j + 1) * ds);
        }
    }
    cr_log_info("%d landings; at most %ld looks", landed, worst);
    cr_expect(landed > 500);
}

/* ---- the cost of an impact, and its contact against the fixed step ------------------------ */

Test(vibration, a_feeders_impact_takes_few_steps)
{
    /* A grain hopping on a feeder meets the plate once a cycle or so, and each contact has
       several switches (made, the normal velocity's reversal, stick and slip, the spin's
       turn under the rolling torque, lift-off): with Adams a vibrating plate's contact phases
       are taken by DOP853, which restarts at no cost at each (docs/integrators.md): measured
       10.1 steps and 4.45 events an impact over 33 impacts (CVODE's Adams took 76 steps an
       impact of the reference feed). Bound 20. */
    tribo_scene s = feeder(2.5, M_PI / 6, 0.6, TRIBO_INTEGRATOR_CVODE);
    tribo_model *m = make(&s);
    const double period = 2.0 * M_PI / 2.2e-4;
    cr_assert_eq(tribo_advance_fully(m, 40.0 * period), TRIBO_OK, "%s", tribo_last_error(m));
    tribo_stats st;
    tribo_get_stats(m, &st);
    const double impacts = tribo_get(m, TRIBO_QUANTITY_IMPACTS);
    cr_log_info("%g impacts: %.1f steps, %.2f events, %.1f right-hand sides each", impacts,
                st.steps / impacts, st.events / impacts, st.rhs_evals / impacts);
    cr_expect(impacts >= 20.0, "%g impacts", impacts);
    cr_expect(st.steps <= 20.0 * impacts, "%.1f steps an impact", st.steps / impacts);
    tribo_free(m);
}

Test(vibration, a_disc_landing_on_a_feeder_leaves_as_the_fixed_step_has_it)
{
    /* A 0.9 mm disc dropped without spin from 1 cm onto a level feeder lands in the rolling
       lock, whose band (mu_roll Psi_N) opens from 0 at the instant of contact: the tangential
       force's torque leaves it at once, and the disc turns through the contact. The
       event-driven law (DOP853 on a vibrating plate) and the fixed step's regularised one
       give the same lift-off: measured phi 2.8e-8 rad and U 2.1e-8 apart at the fixed step's
       dt 3e-4, about its own error (dt 1e-3 against 3e-4: 1.1e-8 and 1.3e-8) and its regularised
       law's; the test takes dt 1e-3, a third of dt 3e-4's cost (the fixed step integrates the
       drop of 1 cm too). A lock held through the contact instead leaves phi 3.2e-4 rad and U 1.1e-4 off: CVODE's BDF,
       which a vibrating plate keeps, did so until the lock was judged by the forces' rates as
       the band opens (force_phases.c roll_lock_holds; its first step after the contact, 4e-9
       long, hid the band's edge crossed), and now leaves 2.8e-8 and 2.1e-8 off, as DOP853.
       At dt 1e-3 both are 3.9e-8 (phi) and 3.4e-8 (U) apart; bounds 1e-6 both, for each: 25
       times that, 300 times below the held lock's error. */
    const char *grain = "epsilon=1 semi_major_axis=4.4e-4 phi0=2.98 drop_height=0.01 chute_length=0.1 "
                        "tilt=0 vibration_amplitude=5e-4 vibration_frequency=50 "
                        "vibration_angle=0.5235987755982988 run_end=1 stick_model=0";
    const char *integrators[3] = {"integrator=1", "integrator=0 dt=1e-3", "integrator=2"};
    double phi[3], U[3];
    for (int k = 0; k < 3; k++) {
        char settings[512], msg[512];
        snprintf(settings, sizeof settings, "%s %s", grain, integrators[k]);
        tribo_si_derived d;
        cr_assert_eq(si_derive(settings, msg, sizeof msg, &d), TRIBO_OK, "%s", msg);
        tribo_model *m = make(&d.scene);
        cr_assert_eq(tribo_advance_fully(m, 1.0 / d.t_star), TRIBO_ENDED, "%s", tribo_last_error(m));
        cr_assert_eq(tribo_get(m, TRIBO_QUANTITY_LIFTED_OFF), 1.0);
        phi[k] = tribo_get(m, TRIBO_QUANTITY_PHI);
        U[k] = tribo_get(m, TRIBO_QUANTITY_U);
        tribo_free(m);
    }
    cr_log_info("phi: %.3g apart; U: %.3g", fabs(phi[0] - phi[1]), fabs(U[0] - U[1]));
    cr_expect(fabs(phi[0] - phi[1]) <= 1e-6, "phi %.3g apart", fabs(phi[0] - phi[1]));
    cr_expect(fabs(U[0] - U[1]) <= 1e-6, "U %.3g apart", fabs(U[0] - U[1]));
    cr_log_info("BDF: phi %.3g apart, U %.3g", fabs(phi[2] - phi[1]), fabs(U[2] - U[1]));
    cr_expect(fabs(phi[2] - phi[1]) <= 1e-6, "BDF: phi %.3g apart", fabs(phi[2] - phi[1]));
    cr_expect(fabs(U[2] - U[1]) <= 1e-6, "BDF: U %.3g apart", fabs(U[2] - U[1]));
}

/* A feeder's drop given in the lab (drop_frame, model.md §9b): the grain's velocity relative
   to the plate is the drop's less the plate's, (Lambda_v / vib_omega) cos(vib_phase) along the
   stroke, at the drop's phase. */
static tribo_scene lab_drop(double phase, double drop_speed, double drop_angle, int frame)
{
    tribo_scene s = feeder(2.5, M_PI / 6, 0.6, TRIBO_INTEGRATOR_CVODE);
    s.vib_phase = phase;
    s.drop_speed = drop_speed;
    s.drop_angle = drop_angle;
    s.drop_frame = frame;
    s.run_end = TRIBO_RUN_END_FIRST_LIFTOFF;
    return s;
}

Test(vibration, a_grain_dropped_at_rest_in_the_lab_starts_against_the_plates_motion)
{
    const double phases[] = {0.0, 1.0, M_PI};
    for (int i = 0; i < 3; i++) {
        tribo_scene s = lab_drop(phases[i], 0.0, 0.0, TRIBO_DROP_FRAME_LAB);
        tribo_model *m = make(&s);
        const double plate = s.vib_accel / s.vib_omega * cos(phases[i]);
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_U), -plate * cos(M_PI / 6), "phase %g", phases[i]);
        cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_V), -plate * sin(M_PI / 6), "phase %g", phases[i]);
        tribo_free(m);
    }
}

Test(vibration, a_lab_drop_with_the_plates_velocity_is_a_drop_at_rest_on_the_plate)
{
    /* at the phase pi the plate moves at (Lambda_v / vib_omega) along the stroke's opposite,
       psi_v = 30 deg below the plate's axis backwards: in the external frame (beta = 0) the
       speed Lambda_v / vib_omega at psi_v - 90 deg from the vertical. The two runs differ by
       the rounding of the subtraction (about 1e-18 of U and V): measured 3.3e-17 semi-axes
       apart through the first impact to its lift-off; bound 1e-12 */
    tribo_scene s = lab_drop(M_PI, 0.0, 0.0, TRIBO_DROP_FRAME_PLATE);
    const double plate_speed = s.vib_accel / s.vib_omega;
    tribo_scene lab = lab_drop(M_PI, plate_speed, M_PI / 6 - M_PI / 2, TRIBO_DROP_FRAME_LAB);
    tribo_model *a = make(&s), *b = make(&lab);
    cr_expect(fabs(tribo_get(b, TRIBO_QUANTITY_U)) <= 1e-18 && fabs(tribo_get(b, TRIBO_QUANTITY_V)) <= 1e-18,
              "relative drop (%.3g, %.3g)", tribo_get(b, TRIBO_QUANTITY_U), tribo_get(b, TRIBO_QUANTITY_V));
    cr_assert_eq(tribo_advance_fully(a, 1e6), TRIBO_ENDED, "%s", tribo_last_error(a));
    cr_assert_eq(tribo_advance_fully(b, 1e6), TRIBO_ENDED, "%s", tribo_last_error(b));
    cr_expect_eq(tribo_get(a, TRIBO_QUANTITY_LIFTED_OFF), 1.0);
    cr_log_info("lab against plate after the first impact: %.3g", state_distance(a, b));
    cr_expect(state_distance(a, b) <= 1e-12, "%.3g apart", state_distance(a, b));
    cr_expect(fabs(tribo_get(a, TRIBO_QUANTITY_TIME) - tribo_get(b, TRIBO_QUANTITY_TIME)) <= 1e-6,
              "lift-off at %.17g and %.17g", tribo_get(a, TRIBO_QUANTITY_TIME), tribo_get(b, TRIBO_QUANTITY_TIME));
    tribo_free(a);
    tribo_free(b);
}

Test(vibration, on_a_still_plate_the_drops_frame_changes_nothing)
{
    tribo_scene s = lab_drop(0.3, 0.02, 0.4, TRIBO_DROP_FRAME_PLATE);
    s.vib_accel = 0.0;
    s.run_end = TRIBO_RUN_END_CHUTE_EXIT;
    tribo_scene lab = s;
    lab.drop_frame = TRIBO_DROP_FRAME_LAB;
    tribo_model *a = make(&s), *b = make(&lab);
    advance_both(a, b, 3e3);
    cr_expect(same_outputs(a, b), "a still plate's drop in the lab differs from the plate's");
    tribo_free(a);
    tribo_free(b);
}

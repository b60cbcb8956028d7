/* The invariants of model.md §6 on whole runs of the fixed-step integrator. */
#include <criterion/criterion.h>
#include <math.h>

#include "geometry.h"
#include "model.h"
#include "support.h"


static tribo_scene paper(double mu, double nu, double dt)
{
    tribo_scene s;
    tribo_scene_defaults(&s); /* model.md §7 at eps = 0.5 */
    s.mu = mu;
    s.nu = nu;
    s.integrator = TRIBO_INTEGRATOR_FIXED_STEP;
    s.dt = dt;
    no_charge_models(&s);
    return s;
}

/* mu = nu = 0: E is conserved. At dt = 1e-3 over tau = 1000 the largest drift measured
   is 1.3e-11, i.e. 2.0e-8 of E(0) (the particle slides 700 units down the plate and its
   kinetic energy grows to 400 E(0) meanwhile). */
Test(invariants, energy_conserved_without_friction, .timeout = 60)
{
    tribo_scene s = paper(0.0, 0.0, 1e-3);
    tribo_model *m = make(&s);
    const double E0 = tribo_get(m, TRIBO_QUANTITY_ENERGY);
    double drift = 0.0;
    int contacts = 0;
    for (int k = 1; k <= 1000; k++) {
        cr_assert_eq(tribo_advance(m, k), TRIBO_OK);
        drift = fmax(drift, fabs(tribo_get(m, TRIBO_QUANTITY_ENERGY) - E0));
        contacts += tribo_get(m, TRIBO_QUANTITY_IN_CONTACT) != 0.0;
    }
    cr_expect(contacts > 0, "the particle touched the plate");
    cr_expect(drift / E0 < 1e-7, "relative energy drift %.3g", drift / E0);
    tribo_free(m);
}

/* nu = 0, mu > 0: E falls only by the friction work, E(tau) = E(0) - W. The residual is
   the fixed step's error across the kinks of the contact law: second order. */
static double balance_residual(double mu, double dt, double *work)
{
    tribo_scene s = paper(mu, 0.0, dt);
    tribo_model *m = make(&s);
    const double E0 = tribo_get(m, TRIBO_QUANTITY_ENERGY);
    double worst = 0.0;
    for (int k = 1; k <= 1000; k++) {
        cr_assert_eq(tribo_advance(m, k), TRIBO_OK);
        const double r = tribo_get(m, TRIBO_QUANTITY_ENERGY) + tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED) - E0;
        worst = fmax(worst, fabs(r));
    }
    *work = tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED);
    tribo_free(m);
    return worst;
}

Test(invariants, energy_balance_with_friction_work, .timeout = 240)
{
    const double mus[] = {0.1, 1.0};
    for (int i = 0; i < 2; i++) {
        double w1, w2;
        const double r1 = balance_residual(mus[i], 1e-3, &w1);
        const double r2 = balance_residual(mus[i], 5e-4, &w2);
        cr_expect(w1 > 1e-3, "mu = %g: friction did work %g", mus[i], w1);
        cr_expect(r1 / w1 < 1e-5, "mu = %g dt = 1e-3: residual %.3g of W", mus[i], r1 / w1);
        cr_expect(r2 < r1 / 3.0, "mu = %g: residual %.3g at dt = 5e-4 vs %.3g at 1e-3", mus[i],
                  r2, r1);
    }
}

/* The same work counted independently: with nu = 0 the contact dissipates only by
   slipping, mu Psi_N |vs| (model.md §6), plus the spring energy a shrinking limit
   releases, which is small here. A Riemann sum over the grid must agree. */
Test(invariants, friction_work_is_mu_psi_n_slip_speed, .timeout = 60)
{
    tribo_scene s = paper(0.1, 0.0, 1e-4);
    tribo_model *m = make(&s);
    double sum = 0.0;
    const int n = 200000; /* tau = 20 */
    for (int k = 1; k <= n; k++) {
        cr_assert_eq(tribo_advance(m, k * s.dt), TRIBO_OK);
        if (tribo_get(m, TRIBO_QUANTITY_SLIPPING) != 0.0) {
            tribo_pose g;
            tribo_pose_at(s.epsilon * s.epsilon, tribo_get(m, TRIBO_QUANTITY_PHI), &g);
            const double vs = tribo_get(m, TRIBO_QUANTITY_U) + g.h * tribo_get(m, TRIBO_QUANTITY_OMEGA);
            sum += s.mu * tribo_get(m, TRIBO_QUANTITY_PSI_N) * fabs(vs) * s.dt;
        }
    }
    const double W = tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED);
    cr_expect(W > 1e-5, "W = %g", W);
    cr_expect(fabs(sum - W) < 0.02 * W, "sum mu Psi_N |vs| dt = %.6g, W = %.6g", sum, W);
    tribo_free(m);
}

/* Flat plate (beta = 0), dropped from rest at first touch without spin. */
static tribo_scene flat(double nu)
{
    tribo_scene s = paper(0.1, nu, 1e-3);
    s.beta = 0.0;
    s.drop_speed = 0.0;
    return s;
}

Test(invariants, flat_plate_elastic_oscillates_about_gamma, .timeout = 60)
{
    tribo_scene s = flat(0.0);
    tribo_model *m = make(&s);
    const double E0 = tribo_get(m, TRIBO_QUANTITY_ENERGY);
    double sum = 0.0, lo = INFINITY, hi = 0.0, drift = 0.0;
    const int n = 200000; /* tau = 200, ~32 periods of 2 pi */
    for (int k = 1; k <= n; k++) {
        cr_assert_eq(tribo_advance(m, k * s.dt), TRIBO_OK);
        const double dy = tribo_get(m, TRIBO_QUANTITY_DELTA_Y);
        sum += dy;
        lo = fmin(lo, dy);
        hi = fmax(hi, dy);
        drift = fmax(drift, fabs(tribo_get(m, TRIBO_QUANTITY_ENERGY) - E0));
    }
    const double G = s.Gamma;
    cr_expect(fabs(sum / n - G) < 0.01 * G, "mean delta_y %.6g, Gamma %g", sum / n, G);
    cr_expect(lo < 1e-3 * G && fabs(hi - 2 * G) < 1e-3 * G, "delta_y in [%g, %g]", lo, hi);
    cr_expect(drift < 1e-9 * fabs(E0) + 1e-15, "energy drift %g of %g", drift, E0);
    cr_expect_eq(tribo_get(m, TRIBO_QUANTITY_PHI), 0.0, "no rocking");
    tribo_free(m);
}

Test(invariants, flat_plate_damped_comes_to_normal_lock, .timeout = 60)
{
    const double nus[] = {0.2, 0.5, 0.9};
    for (int i = 0; i < 3; i++) {
        tribo_scene s = flat(nus[i]);
        tribo_model *m = make(&s);
        cr_assert_eq(tribo_advance(m, 200.0), TRIBO_OK);
        const double dy = tribo_get(m, TRIBO_QUANTITY_DELTA_Y), V = tribo_get(m, TRIBO_QUANTITY_V);
        const double G = s.Gamma;
        /* V = 0 up to the regularisation's velocity scale (model.md §3) */
        cr_expect(fabs(V) < s.v_reg, "nu = %g: V = %g", nus[i], V);
        cr_expect(dy >= G / (1 + nus[i]) && dy <= G / (1 - nus[i]),
                  "nu = %g: delta_y = %g outside [%g, %g]", nus[i], dy, G / (1 + nus[i]),
                  G / (1 - nus[i]));
        /* Psi_N balances gravity up to the creep's deceleration (measured: 1.5e-6 Gamma) */
        cr_expect_float_eq(tribo_get(m, TRIBO_QUANTITY_PSI_N), G, 1e-5 * G, "nu = %g: Psi_N = %.12g",
                           nus[i], tribo_get(m, TRIBO_QUANTITY_PSI_N));
        tribo_free(m);
    }
}

/* Static charge: 0 <= Q_static <= 1, never decreasing, over tumbling-prone runs, with
   both integrators. (The fixed step at nu = 1 sub-steps through the stiff regularised
   lock, ~3e4 sub-steps per time unit, hence the shorter horizon.) */
Test(invariants, static_charge_bounded_and_non_decreasing, .timeout = 180)
{
    const double mus[] = {0.1, 1.0};
    for (int integ = 0; integ < 2; integ++) {
        for (int i = 0; i < 2; i++) {
            tribo_scene s = paper(mus[i], mus[i], 1e-3);
            s.epsilon = 0.3;
            no_charge_models(&s);
            s.charge_model_static = 1;
            s.n_segments = 500;
            s.integrator = integ ? TRIBO_INTEGRATOR_CVODE : TRIBO_INTEGRATOR_FIXED_STEP;
            tribo_model *m = make(&s);
            double prev = 0.0;
            double q[500];
            for (int k = 1; k <= 400; k++) {
                cr_assert_eq(tribo_advance(m, 0.25 * k), TRIBO_OK);
                const double Q = tribo_get(m, TRIBO_QUANTITY_STATIC);
                cr_assert(Q >= prev && Q <= 1.0, "integrator %d mu = %g tau = %g: Q = %.17g after %.17g",
                          integ, mus[i], 0.25 * k, Q, prev);
                prev = Q;
            }
            cr_expect(prev > 0.05, "mu = %g: charged to %g", mus[i], prev);
            cr_assert_eq(tribo_get_segment_charges(m, TRIBO_SEGMENTS_STATIC, q, 500), TRIBO_OK);
            for (int j = 0; j < 500; j++)
                cr_assert(q[j] >= 0.0 && q[j] <= 1.0, "q[%d] = %g", j, q[j]);
            tribo_free(m);
        }
    }
}

/* A disc (eps = 1) dropped without spin rolls once the bounces die out: the contact point
   stays under the centre and U + Omega -> 0, accelerating at g sin(beta) / (1 + 1/2).
   What is left of U + Omega is the tangential spring's oscillation in stick, which the
   model does not damp: with the stretch within mu Psi_N and the spring's frequency
   sqrt(1/m + R^2/I) = sqrt(3), |U + Omega| <= sqrt(3) mu Psi_N, while U grows. */
Test(invariants, disc_rolls_without_slip, .timeout = 60)
{
    tribo_scene s = paper(0.5, 0.5, 1e-3);
    s.epsilon = 1.0;
    tribo_model *m = make(&s);
    cr_assert_eq(tribo_advance(m, 100.0), TRIBO_OK);
    const double U1 = tribo_get(m, TRIBO_QUANTITY_U);
    for (int k = 1; k <= 200; k++) {
        cr_assert_eq(tribo_advance(m, 100.0 + k), TRIBO_OK);
        const double U = tribo_get(m, TRIBO_QUANTITY_U), Om = tribo_get(m, TRIBO_QUANTITY_OMEGA);
        const double bound = sqrt(3.0) * s.mu * tribo_get(m, TRIBO_QUANTITY_PSI_N);
        cr_assert(fabs(U + Om) <= bound, "tau = %d: U + Omega = %g, bound %g (U = %g)", 100 + k,
                  U + Om, bound, U);
        const double dy = tribo_get(m, TRIBO_QUANTITY_DELTA_Y), gn = s.Gamma * sqrt(0.5);
        cr_assert(dy >= gn / (1 + s.nu) && dy <= gn / (1 - s.nu),
                  "rolling in steady contact (normal lock): delta_y = %g", dy);
        cr_assert_eq(tribo_get(m, TRIBO_QUANTITY_SLIPPING), 0.0);
    }
    const double accel = (tribo_get(m, TRIBO_QUANTITY_U) - U1) / 200.0;
    const double expected = s.Gamma * sin(M_PI / 4) / 1.5;
    cr_expect(fabs(accel - expected) < 1e-3 * expected, "acceleration %.6g, expected %.6g",
              accel, expected);
    tribo_free(m);
}

/* Without back-flow (tau_r -> infinity) the sliding model's saturation density integrates
   to Sigma_s = sqrt(Sigma0^2 + 2 eta omega) (model.md §5b), at every time, through every
   lift-off. (tau_r = infinity is past the range a scene may have, 1e9, which would relax
   Sigma_s by ~1e-8 over this run: it is set on the instance, where the exact updates take
   it, e^{-h/tau_r} = 1.) The fixed step books the work of a step that ends in flight too: before it
   did, each lift-off lost that step's increment (measured: 8e-8 of Sigma_s after 10
   lift-offs); now what is left is rounding (2.7e-11). CVODE's sweep integrates it to its
   tolerances (measured 4.5e-9). */
Test(invariants, saturation_density_follows_the_work_through_lift_offs, .timeout = 240)
{
    const double eps[] = {0.3, 0.9}, tolerance[] = {1e-10, 2e-8};
    for (int integ = 0; integ < 2; integ++) {
        for (int e = 0; e < 2; e++) {
            tribo_scene s = scene_of("n_segments=200");
            s.epsilon = eps[e];
            s.integrator = integ ? TRIBO_INTEGRATOR_CVODE : TRIBO_INTEGRATOR_FIXED_STEP;
            tribo_model *m = make(&s);
            m->scene.tau_r = INFINITY;
            double worst = 0.0;
            int lift_offs = 0, was_in_contact = 0;
            for (int k = 1; k <= 2000; k++) {
                cr_assert_eq(tribo_advance(m, 0.1 * k), TRIBO_OK);
                const double w = tribo_get(m, TRIBO_QUANTITY_OMEGA_WORK);
                const double expected = sqrt(s.Sigma0 * s.Sigma0 + 2.0 * s.eta * w);
                worst = fmax(worst, fabs(tribo_get(m, TRIBO_QUANTITY_SIGMA_S) - expected) / expected);
                const int in_contact = tribo_get(m, TRIBO_QUANTITY_IN_CONTACT) != 0.0;
                lift_offs += was_in_contact && !in_contact;
                was_in_contact = in_contact;
            }
            cr_expect(lift_offs >= 3, "eps = %g: %d lift-offs", eps[e], lift_offs);
            cr_expect(worst <= tolerance[integ], "integrator %d, eps = %g: Sigma_s off by %.3g",
                      integ, eps[e], worst);
            tribo_free(m);
        }
    }
}

/* With rolling resistance (model.md §3c) E falls by the rolling torque's work too, booked in
   W: at nu = 0 E(tau) = E(0) - W for the fixed step's regularised torque as for the friction
   alone, the residual second order in dt (measured 3.9e-7 of W at dt = 1e-3, 4x less at
   5e-4). */
Test(invariants, energy_balance_with_rolling_resistance, .timeout = 120)
{
    double r[2], w[2];
    for (int i = 0; i < 2; i++) {
        tribo_scene s = paper(0.5, 0.0, i ? 5e-4 : 1e-3);
        s.mu_roll = 0.2;
        tribo_model *m = make(&s);
        const double E0 = tribo_get(m, TRIBO_QUANTITY_ENERGY);
        r[i] = 0.0;
        for (int k = 1; k <= 1000; k++) {
            cr_assert_eq(tribo_advance(m, k), TRIBO_OK);
            const double res = tribo_get(m, TRIBO_QUANTITY_ENERGY) + tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED) - E0;
            r[i] = fmax(r[i], fabs(res));
        }
        w[i] = tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED);
        tribo_free(m);
    }
    cr_expect(w[0] > 1e-3, "the contact dissipated %g", w[0]);
    cr_expect(r[0] / w[0] < 1e-5, "dt = 1e-3: residual %.3g of W", r[0] / w[0]);
    cr_expect(r[1] < r[0] / 3.0, "residual %.3g at dt = 5e-4 vs %.3g at 1e-3", r[1], r[0]);
}

/* The rolling torque's work counted independently: a disc set down with the rigid stick rolls
   without slip, and the only work done on it is the torque's, mu_r Psi_N |Omega| with
   Psi_N* = Gamma cos(beta) (model.md §3c): W = mu_r Gamma cos(beta) |phi - phi0| at the exit
   (measured 2.8e-9 relative: the settling when set down; bound 1e-8). */
Test(invariants, the_rolling_torque_does_mu_roll_psi_n_per_radian)
{
    tribo_scene s = scene_of("beta=0.52359877559829887 gap0=0 drop_speed=0 nu=0.3 Gamma=1e-6 "
                             "chute_length=1000 stick_model=1 epsilon=1 mu=0.5 mu_roll=0.2");
    tribo_model *m = make(&s);
    cr_assert_eq(tribo_advance_fully(m, TRIBO_TIME_MAX), TRIBO_ENDED, "%s", tribo_last_error(m));
    const double W = tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED);
    const double expected = s.mu_roll * s.Gamma * cos(s.beta) * fabs(tribo_get(m, TRIBO_QUANTITY_PHI));
    cr_expect(fabs(W / expected - 1.0) < 1e-8, "W = %.12g, mu_r Psi_N |phi| = %.12g", W, expected);
    tribo_free(m);
}

/* §6's bound with the rolling torque: with the contact-point dashpot and no external force
   E + W never increases, for both stick models, along grains that bounce, rock and settle,
   tumble at high friction, or spin (CVODE, sampled every 0.5). What it seems to gain is the
   integration's error: measured at most 1.5e-8 of E's scale; the bound is 1e-7. */
Test(invariants, energy_and_dissipated_work_never_increase_with_rolling_resistance, .timeout = 60)
{
    const char *scenes[] = {
        "beta=0.087266462599716477 epsilon=0.5 mu=0.5 nu=0.3 mu_roll=0.2",
        "epsilon=0.3 mu=1 nu=1 mu_roll=0.05",
        "epsilon=0.7 mu=1 nu=0.5 mu_roll=0.05 Omega0=0.5",
        "epsilon=0.9 mu=0.3 nu=0.5 mu_roll=0.5",
    };
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        for (int stick = 0; stick < 2; stick++) {
            tribo_scene s = scene_of(scenes[i]);
            s.stick_model = stick;
            no_charge_models(&s);
            tribo_model *m = make(&s);
            energy_watch w = energy_watch_start();
            tribo_status st = TRIBO_OK;
            for (int k = 1; k <= 4000 && st == TRIBO_OK; k++) {
                st = tribo_advance_fully(m, 0.5 * k);
                cr_assert(st == TRIBO_OK || st == TRIBO_ENDED, "%s", tribo_last_error(m));
                energy_watch_sample(&w, m);
            }
            cr_expect(w.rise <= 1e-7 * w.scale, "%s, stick_model %d: E + W rose by %.3g (%.2e of E's scale)",
                      scenes[i], stick, w.rise, w.rise / w.scale);
            tribo_free(m);
        }
    }
}

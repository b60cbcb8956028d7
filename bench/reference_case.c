/* reference_case: the SI reference case measured through the C API (a command, not a test).
 *
 *   tribo_reference_case [rounds=3] [slice=2] ["name=value ..." SI settings]
 *
 * A 1 mm polyethylene particle (a = 0.5 mm, epsilon 0.6, rho 950 kg/m3, E 1 GPa, nu 0.46)
 * dropped from 10 mm straight down onto a steel chute (200 GPa, 0.29) tilted 30 degrees,
 * mu = nu = 0.3, L = 0.3 m, charging time 1 ms, both charge models (the defaults of
 * src/si/si_quantities.def with chute_length = 0.3 m). Any SI setting may be changed.
 *
 * 1. CVODE to the exit (tribo_advance_fully), `rounds` times, the fastest CPU time kept: the
 *    exit time and velocity, q/m of both charge models, impacts, the contact fraction.
 * 2. The same to the exit at CVODE tolerances 100 times looser and tighter: the bouncing
 *    and tumbling on the chute is chaotic, and the numbers at the exit spread with them.
 * 3. The fixed step at dt = 8e-5 on the same set-up: the steps it needs to the CVODE run's exit
 *    time, and its steps per CPU second measured over two slices of about `slice` CPU
 *    seconds each: the drop (flight) from the start, and the motion from the first impact (a
 *    run started at the impact: lowest point on the chute, CVODE's impact velocity). The
 *    estimate of its CPU time to the exit: the flight's steps at the first rate, the rest at
 *    the second.
 */
#include "si.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cpu_clock.h"

static tribo_model *create(const tribo_si_scene *si, tribo_si_derived *d)
{
    char err[1024];
    if (tribo_si_derive(si, d, err, sizeof err) != TRIBO_OK) {
        fprintf(stderr, "%s\n", err);
        exit(1);
    }
    tribo_model *m = tribo_create(&d->scene, err, sizeof err);
    if (!m) {
        fprintf(stderr, "%s\n", err);
        exit(1);
    }
    return m;
}

static void check(tribo_model *m, tribo_status st, tribo_status expected)
{
    if (st != expected) {
        fprintf(stderr, "advance: status %d (%s)\n", (int)st, tribo_last_error(m));
        exit(1);
    }
}

/* The fixed step's steps per CPU second over about `seconds` of CPU, from its start. */
static double fixed_rate(const tribo_si_scene *si, double seconds, double *tau_done)
{
    tribo_si_derived d;
    tribo_model *m = create(si, &d);
    const double t0 = cpu_seconds();
    double tau = 0.0, cpu = 0.0;
    while (cpu < seconds) {
        tau += 1.0;
        const tribo_status st = tribo_advance_fully(m, tau);
        if (st == TRIBO_ENDED)
            break;
        check(m, st, TRIBO_OK);
        cpu = cpu_seconds() - t0;
    }
    cpu = cpu_seconds() - t0;
    tribo_stats stats;
    tribo_get_stats(m, &stats);
    *tau_done = tribo_get(m, TRIBO_QUANTITY_TIME);
    tribo_free(m);
    return (double)stats.steps / cpu;
}

/* The report, section after section in the order it prints (the set-up, CVODE's run, the
   tolerances, the fixed step): one function, so that it reads as the report does. */
int main(int argc, char **argv)
{
    int rounds = 3;
    double slice = 2.0;
    tribo_si_scene si;
    tribo_si_scene_defaults(&si);
    si.chute_length = 0.3;
    for (int i = 1; i < argc; i++) {
        char err[512];
        if (strncmp(argv[i], "rounds=", 7) == 0)
            rounds = atoi(argv[i] + 7);
        else if (strncmp(argv[i], "slice=", 6) == 0)
            slice = atof(argv[i] + 6);
        else if (tribo_si_scene_apply(&si, argv[i], err, sizeof err) != TRIBO_OK) {
            fprintf(stderr, "%s\nusage: %s [rounds=3] [slice=2] [\"name=value ...\"]\n", err, argv[0]);
            return 2;
        }
    }
    if (rounds < 1 || !(slice > 0.0)) {
        fprintf(stderr, "rounds must be >= 1 and slice > 0\n");
        return 2;
    }
    si.integrator = TRIBO_INTEGRATOR_CVODE;

    /* 1. CVODE to the exit */
    tribo_si_derived d;
    double best = INFINITY;
    double q[TRIBO_SI_QUANTITY_COUNT];
    tribo_stats stats;
    for (int r = 0; r < rounds; r++) {
        tribo_model *m = create(&si, &d);
        const double t0 = cpu_seconds();
        check(m, tribo_advance_fully(m, TRIBO_TIME_MAX), TRIBO_ENDED);
        const double cpu = cpu_seconds() - t0;
        if (cpu < best)
            best = cpu;
        for (int k = 0; k < TRIBO_SI_QUANTITY_COUNT; k++)
            q[k] = tribo_si_get(&d, m, (tribo_si_quantity)k);
        tribo_get_stats(m, &stats);
        tribo_free(m);
    }
    const double tau_exit = q[TRIBO_SI_QUANTITY_EXIT_TIME] / d.t_star;

    /* the first impact, by CVODE: its time and velocity */
    tribo_model *m = create(&si, &d);
    double t_impact = NAN, u_impact = 0.0, v_impact = 0.0;
    for (double tau = 0.0;; tau += 1.0) {
        check(m, tribo_advance_fully(m, tau), TRIBO_OK);
        if (tribo_get(m, TRIBO_QUANTITY_IN_CONTACT) != 0.0)
            break;
        t_impact = tau;
        u_impact = tribo_get(m, TRIBO_QUANTITY_U);
        v_impact = tribo_get(m, TRIBO_QUANTITY_V);
    }
    tribo_free(m);

    printf("reference case: a = %g m, epsilon = %g, rho = %g kg/m3, E_p = %g Pa, nu_p = %g, "
           "E_w = %g Pa, nu_w = %g, tilt = %g deg, mu = %g, nu = %g, L = %g m, t0 = %g s, "
           "drop %g m at %g m/s, charge models: static %d, sliding %d\n",
           si.semi_major_axis, si.epsilon, si.density, si.youngs_modulus_particle,
           si.poisson_ratio_particle, si.youngs_modulus_wall, si.poisson_ratio_wall,
           si.tilt * 180.0 / M_PI, si.mu, si.nu, si.chute_length, si.charging_time,
           si.drop_height, si.drop_speed, si.charge_model_static, si.charge_model_sliding);
    printf("derived: t_star = %.4g s, Gamma = %.4g, tau0 = %.4g, Sigma0 = %.4g, k' = %.4g N/m2, "
           "m' = %.4g kg/m\n",
           d.t_star, d.scene.Gamma, d.scene.tau0, d.scene.Sigma0, d.k_prime, d.mass_per_length);
    printf("\nCVODE (rtol %g, atol %g), to the exit:\n", si.rtol, si.atol);
    printf("  exit time             %.6g s (tau = %.6g)\n", q[TRIBO_SI_QUANTITY_EXIT_TIME], tau_exit);
    printf("  exit velocity         u = %.6g m/s, v = %.6g m/s, omega = %.6g rad/s\n",
           q[TRIBO_SI_QUANTITY_U], q[TRIBO_SI_QUANTITY_V], q[TRIBO_SI_QUANTITY_OMEGA]);
    printf("  q/m at exit           static %.6g uC/kg, sliding %.6g uC/kg\n",
           1e6 * q[TRIBO_SI_QUANTITY_Q_PER_M_STATIC], 1e6 * q[TRIBO_SI_QUANTITY_Q_PER_M_SLIDING]);
    printf("  impacts               %.0f\n", q[TRIBO_SI_QUANTITY_IMPACTS]);
    printf("  contact fraction      %.6g\n", q[TRIBO_SI_QUANTITY_CONTACT_FRACTION]);
    printf("  first impact          %.6g s\n", t_impact * d.t_star);
    printf("  CPU time              %.3g s (fastest of %d)\n", best, rounds);
    printf("  work                  %lld steps, %lld rhs evaluations, %lld events, %lld restarts\n",
           stats.steps, stats.rhs_evals, stats.events, stats.restarts);

    /* 2. the spread with CVODE's tolerances */
    printf("\nthe same at other CVODE tolerances:\n");
    printf("  %-22s %10s %10s %14s %14s %8s %10s\n", "rtol, atol", "exit [s]", "u [m/s]",
           "static uC/kg", "sliding uC/kg", "impacts", "CPU [s]");
    const double tolerances[3] = {1e-7, si.rtol, 1e-11};
    for (int k = 0; k < 3; k++) {
        tribo_si_scene other = si;
        other.rtol = tolerances[k];
        other.atol = tolerances[k] * (si.atol / si.rtol);
        tribo_si_derived od;
        tribo_model *om = create(&other, &od);
        const double t0 = cpu_seconds();
        check(om, tribo_advance_fully(om, TRIBO_TIME_MAX), TRIBO_ENDED);
        const double cpu = cpu_seconds() - t0;
        printf("  %-9.0e %-12.0e %10.4g %10.4g %14.4g %14.4g %8.0f %10.3g\n", other.rtol, other.atol,
               tribo_si_get(&od, om, TRIBO_SI_QUANTITY_EXIT_TIME),
               tribo_si_get(&od, om, TRIBO_SI_QUANTITY_U),
               1e6 * tribo_si_get(&od, om, TRIBO_SI_QUANTITY_Q_PER_M_STATIC),
               1e6 * tribo_si_get(&od, om, TRIBO_SI_QUANTITY_Q_PER_M_SLIDING),
               tribo_si_get(&od, om, TRIBO_SI_QUANTITY_IMPACTS), cpu);
        tribo_free(om);
    }

    /* 3. the fixed step */
    tribo_si_scene fixed = si;
    fixed.integrator = TRIBO_INTEGRATOR_FIXED_STEP;
    fixed.stick_model = TRIBO_STICK_COMPLIANT; /* the fixed step has only the spring */
    fixed.dt = 8e-5;
    double tau_flight = 0.0, tau_contact = 0.0;
    const double rate_flight = fixed_rate(&fixed, slice, &tau_flight);
    tribo_si_scene from_impact = fixed;
    from_impact.drop_height = 0.0;
    from_impact.drop_speed = hypot(u_impact, v_impact) * d.velocity;
    from_impact.drop_angle = 0.0; /* the fall is straight down (drop_angle 0, omega0 0) */
    const double rate_contact = fixed_rate(&from_impact, slice, &tau_contact);
    const double steps_flight = t_impact / fixed.dt, steps_rest = (tau_exit - t_impact) / fixed.dt;
    const double estimate = steps_flight / rate_flight + steps_rest / rate_contact;
    printf("\nfixed step dt = %g (in t_star) on the same set-up:\n", fixed.dt);
    printf("  steps to the exit     %.4g (%.4g in the drop, %.4g after the first impact)\n",
           steps_flight + steps_rest, steps_flight, steps_rest);
    printf("  steps per CPU second  %.4g in the drop (tau 0..%.4g), %.4g from the first impact "
           "(tau 0..%.4g)\n",
           rate_flight, tau_flight, rate_contact, tau_contact);
    printf("  estimated CPU time    %.4g s (%.3g times CVODE's)\n", estimate, estimate / best);
    return 0;
}

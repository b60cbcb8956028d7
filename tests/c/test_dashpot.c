/* The normal dashpot on the contact point (model.md §3, damping_point = 0) and its normal
   lock, against the invariants of model.md §6, in both integrators; and the centre dashpot
   (damping_point = 1) that the tests must be able to tell from it. */
#include <criterion/criterion.h>
#include <math.h>

#include "force_phases.h"
#include "support.h"

/* ---- what the tests read off a run --------------------------------------------------------- */

/* The contact point's normal velocity vn = V + cx Omega at the output. */
static double contact_point_velocity(tribo_model *m)
{
    const double eps = tribo_get_scene(m)->epsilon;
    tribo_pose g;
    tribo_pose_at(eps * eps, tribo_get(m, TRIBO_QUANTITY_PHI), &g);
    return tribo_get(m, TRIBO_QUANTITY_V) + g.cx * tribo_get(m, TRIBO_QUANTITY_OMEGA);
}

/* In a contact-point normal lock at the output: in contact, vn held at 0 exactly. */
static int locked(tribo_model *m)
{
    return tribo_get(m, TRIBO_QUANTITY_IN_CONTACT) != 0.0 && contact_point_velocity(m) == 0.0;
}

/* A spinning drop (model.md §7 with spin Omega0 = 0.5) at eps and mu = nu. */
static tribo_scene spinning(double eps, double mu_nu, int integrator, int damping_point)
{
    tribo_scene s = scene_of("Omega0=0.5 dt=1e-3");
    s.epsilon = eps;
    s.mu = s.nu = mu_nu;
    s.integrator = integrator;
    s.damping_point = damping_point;
    no_charge_models(&s);
    return s;
}

typedef struct energy_record {
    double rise;    /* the largest E(t) - min over earlier samples of E */
    double turns;   /* the most revolutions away from phi0 at a sample */
    double contact; /* contact fraction at the end */
} energy_record;

/* E sampled every 0.05 to t_end. */
static energy_record energy_of_run(const tribo_scene *s, double t_end)
{
    tribo_model *m = make(s);
    energy_record r = {0.0, 0.0, 0.0};
    double lowest = tribo_get(m, TRIBO_QUANTITY_ENERGY);
    const int n = (int)lround(t_end / 0.05);
    for (int k = 1; k <= n; k++) {
        cr_assert_eq(tribo_advance(m, 0.05 * k), TRIBO_OK, "%s", tribo_last_error(m));
        const double E = tribo_get(m, TRIBO_QUANTITY_ENERGY);
        r.rise = fmax(r.rise, E - lowest);
        lowest = fmin(lowest, E);
        r.turns = fmax(r.turns, tribo_get(m, TRIBO_QUANTITY_TURNS));
    }
    r.contact = tribo_get(m, TRIBO_QUANTITY_CONTACT_FRACTION);
    tribo_free(m);
    return r;
}

/* ---- energy (model.md §6) -------------------------------------------------------------------- */

/* With the dashpot on the contact point and no external force, E never increases: the
   dashpot's power -nu delta_y |vn|, the slip's and the clamps' are all <= 0. A matrix of
   spinning drops that turn over and tumble, eps = 0.3, 0.6, 0.9 and mu = nu = 0.1, 1, 3,
   both integrators. What E may seem to gain is the integrator's error: measured, the
   largest rise is 5.2e-14 for the fixed step (dt = 1e-3, v_reg = 1e-6, to tau = 100:
   rounding) and 1.1e-12 for CVODE (rtol 1e-9, atol 1e-11, to tau = 300), against
   E(0) = 0.035 ... 0.058; the tolerances are 19x and 9x those. The centre dashpot gains
   up to 0.25 on such runs (next test). */
Test(dashpot, energy_never_increases_at_the_contact_point, .timeout = 480)
{
    const double eps[] = {0.3, 0.6, 0.9}, mus[] = {0.1, 1.0, 3.0};
    const int integrators[] = {TRIBO_INTEGRATOR_FIXED_STEP, TRIBO_INTEGRATOR_CVODE};
    const double horizon[] = {100.0, 300.0}, tolerance[] = {1e-12, 1e-11};
    for (int i = 0; i < 2; i++) {
        int turned = 0;
        for (int e = 0; e < 3; e++) {
            for (int f = 0; f < 3; f++) {
                const tribo_scene s =
                    spinning(eps[e], mus[f], integrators[i], TRIBO_DAMPING_CONTACT_POINT);
                const energy_record r = energy_of_run(&s, horizon[i]);
                cr_expect(r.rise <= tolerance[i],
                          "integrator %d, eps = %g, mu = nu = %g: E rose by %.3g", integrators[i],
                          eps[e], mus[f], r.rise);
                cr_expect(r.contact > 0.0, "eps = %g, mu = %g: it touched the plate", eps[e], mus[f]);
                turned += r.turns >= 0.5;
            }
        }
        cr_expect(turned == 9, "integrator %d: %d of 9 runs turned over", integrators[i], turned);
    }
}

/* The centre dashpot does work -nu delta_y sgn(V)(V + cx Omega), positive at times while the
   particle spins: on the same kind of run E gains 0.25 by tau = 20 (measured, both
   integrators), so the test above would tell the two laws apart. */
Test(dashpot, the_centre_dashpot_can_gain_energy, .timeout = 480)
{
    const int integrators[] = {TRIBO_INTEGRATOR_FIXED_STEP, TRIBO_INTEGRATOR_CVODE};
    for (int i = 0; i < 2; i++) {
        const tribo_scene centre = spinning(0.3, 1.0, integrators[i], TRIBO_DAMPING_CENTRE);
        const tribo_scene point = spinning(0.3, 1.0, integrators[i], TRIBO_DAMPING_CONTACT_POINT);
        const energy_record c = energy_of_run(&centre, 20.0), p = energy_of_run(&point, 20.0);
        cr_expect(c.rise > 0.1, "integrator %d: the centre dashpot's E rose by %.3g", integrators[i],
                  c.rise);
        cr_expect(p.rise < 1e-9, "integrator %d: the contact point's E rose by %.3g", integrators[i],
                  p.rise);
    }
}

/* ---- the normal lock (model.md §3) ---------------------------------------------------------- */

/* The paper's high-friction drop at eps = 0.3 comes to a normal lock and rocks in it: the
   lock holds the indentation delta_y (not the centre's height) while the particle turns
   (by 0.37 rad), the centre rising and falling with it (by 0.16), and Psi_N* stays inside
   the band of §3. With the centre dashpot the same lock holds Y instead, and delta_y moves
   (measured: by 0.14, half of eps: the indentation the contact-point dashpot is there to hold). */
Test(dashpot, lock_holds_the_indentation_while_the_particle_turns, .timeout = 60)
{
    for (int centre = 0; centre < 2; centre++) {
        tribo_scene s = scene_of("epsilon=0.3 mu=1 nu=1");
        s.damping_point = centre ? TRIBO_DAMPING_CENTRE : TRIBO_DAMPING_CONTACT_POINT;
        no_charge_models(&s);
        tribo_model *m = make(&s);
        int n_locked = 0;
        double dy0 = NAN, Y0 = NAN, dy_moved = 0.0, Y_moved = 0.0, phi_lo = INFINITY,
               phi_hi = -INFINITY;
        for (int k = 1; k <= 4000; k++) {
            cr_assert_eq(tribo_advance(m, 0.01 * k), TRIBO_OK, "%s", tribo_last_error(m));
            const int in_lock = centre ? tribo_get(m, TRIBO_QUANTITY_IN_CONTACT) != 0.0 &&
                                             tribo_get(m, TRIBO_QUANTITY_V) == 0.0
                                       : locked(m);
            if (!in_lock)
                continue;
            const double dy = tribo_get(m, TRIBO_QUANTITY_DELTA_Y), Y = tribo_get(m, TRIBO_QUANTITY_Y);
            const double psi = tribo_get(m, TRIBO_QUANTITY_PSI_N), phi = tribo_get(m, TRIBO_QUANTITY_PHI);
            if (n_locked++ == 0) {
                dy0 = dy;
                Y0 = Y;
            }
            dy_moved = fmax(dy_moved, fabs(dy - dy0));
            Y_moved = fmax(Y_moved, fabs(Y - Y0));
            phi_lo = fmin(phi_lo, phi);
            phi_hi = fmax(phi_hi, phi);
            cr_assert(psi >= fmax(0.0, dy * (1.0 - s.nu)) && psi <= dy * (1.0 + s.nu),
                      "t = %g: Psi_N* = %g outside the band for delta_y = %g", 0.01 * k, psi, dy);
        }
        cr_expect(n_locked > 3000, "centre %d: locked at %d of 4000 samples", centre, n_locked);
        cr_expect(phi_hi - phi_lo > 1e-2, "centre %d: it turned by %g in the lock", centre,
                  phi_hi - phi_lo);
        if (centre) {
            cr_expect(Y_moved == 0.0 && dy_moved > 1e-4, "centre: Y moved %g, delta_y %g", Y_moved,
                      dy_moved);
        } else {
            /* delta_y = h(phi) - Y recomputed from the held value: rounding only */
            cr_expect(dy_moved <= 1e-15 && Y_moved > 1e-4, "contact point: delta_y moved %g, Y %g",
                      dy_moved, Y_moved);
        }
        tribo_free(m);
    }
}

/* Held over a long lock: the paper's high-friction drop at eps = 0.2 locks at tau = 1.1 and
   slides down the plate in the lock to tau = 5000 (rocking, ~1e4 CVODE steps). delta_y stays
   at its value (the lock's points are put back on it, model.md §3: measured, exactly), and
   the energy balance E + W = E(0) holds to 1.9e-11 (measured; 1e-10 here). */
Test(dashpot, lock_holds_the_indentation_over_a_long_run, .timeout = 60)
{
    tribo_scene s = scene_of("epsilon=0.2 mu=1 nu=1");
    no_charge_models(&s);
    tribo_model *m = make(&s);
    const double E0 = tribo_get(m, TRIBO_QUANTITY_ENERGY);
    cr_assert_eq(tribo_advance(m, 2.0), TRIBO_OK);
    cr_assert(locked(m));
    const double dy0 = tribo_get(m, TRIBO_QUANTITY_DELTA_Y), X0 = tribo_get(m, TRIBO_QUANTITY_X);
    double dy_moved = 0.0, residual = 0.0, phi_lo = INFINITY, phi_hi = -INFINITY;
    for (int k = 3; k <= 5000; k++) {
        cr_assert_eq(tribo_advance(m, k), TRIBO_OK, "%s", tribo_last_error(m));
        cr_assert(locked(m), "tau = %d: left the lock", k);
        dy_moved = fmax(dy_moved, fabs(tribo_get(m, TRIBO_QUANTITY_DELTA_Y) - dy0));
        residual = fmax(residual, fabs(tribo_get(m, TRIBO_QUANTITY_ENERGY) +
                                       tribo_get(m, TRIBO_QUANTITY_WORK_DISSIPATED) - E0));
        phi_lo = fmin(phi_lo, tribo_get(m, TRIBO_QUANTITY_PHI));
        phi_hi = fmax(phi_hi, tribo_get(m, TRIBO_QUANTITY_PHI));
    }
    cr_expect(dy_moved <= 1e-15 * dy0, "delta_y moved by %g of %g", dy_moved, dy0);
    cr_expect(residual < 1e-10, "energy balance residual %.3g", residual);
    cr_expect(phi_hi - phi_lo > 1e-2 && tribo_get(m, TRIBO_QUANTITY_X) - X0 > 1.0,
              "it rocked (phi in [%g, %g]) and slid (to X = %g)", phi_lo, phi_hi,
              tribo_get(m, TRIBO_QUANTITY_X));
    tribo_free(m);
}

/* Psi_N* is the force that keeps vn = 0 (model.md §3), in its stick and its slip form: the
   normal force the motion itself needs, dV/dtau + Gamma cos(beta), by central differences
   of V over +-1e-3 inside one lock (no switch in between), must equal it. Measured: they
   agree to 1.1e-10 (slip) and 7e-11 (stick) over ~250 samples each, against Psi_N ~ 1e-3
   (the differences' own error); the tolerance is 1e-9. */
static void check_lock_force(const char *settings, int want_slip, double *worst, int *samples)
{
    tribo_scene s = scene_of(settings);
    no_charge_models(&s);
    const double h = 1e-3, g_n = s.Gamma * cos(s.beta);
    tribo_model *m = make(&s);
    for (int k = 1; k <= 300; k++) {
        const double t = 0.1 * k;
        tribo_stats before, after;
        cr_assert_eq(tribo_advance(m, t - h), TRIBO_OK);
        tribo_get_stats(m, &before);
        const int lock_a = locked(m);
        const double V_a = tribo_get(m, TRIBO_QUANTITY_V);
        cr_assert_eq(tribo_advance(m, t), TRIBO_OK);
        const int lock_t = locked(m), slip = tribo_get(m, TRIBO_QUANTITY_SLIPPING) != 0.0;
        const double psi = tribo_get(m, TRIBO_QUANTITY_PSI_N);
        cr_assert_eq(tribo_advance(m, t + h), TRIBO_OK);
        tribo_get_stats(m, &after);
        if (!(lock_a && lock_t && locked(m)) || after.events != before.events || slip != want_slip)
            continue;
        const double needed = (tribo_get(m, TRIBO_QUANTITY_V) - V_a) / (2.0 * h) + g_n;
        *worst = fmax(*worst, fabs(needed - psi));
        ++*samples;
    }
    tribo_free(m);
}

Test(dashpot, lock_force_is_the_constraint_force_of_the_motion, .timeout = 60)
{
    double worst_slip = 0.0, worst_stick = 0.0;
    int n_slip = 0, n_stick = 0;
    /* slides in the lock (slip) ... */
    check_lock_force("epsilon=0.3 mu=1 nu=1", 1, &worst_slip, &n_slip);
    /* ... and rocks in it on a flat plate, given a spin (stick) */
    check_lock_force("epsilon=0.3 mu=1 nu=1 beta=0 Omega0=0.02 drop_speed=0.01", 0, &worst_stick,
                     &n_stick);
    cr_expect(n_slip > 50 && n_stick > 50, "samples: %d slipping, %d sticking", n_slip, n_stick);
    cr_expect(worst_slip < 1e-9 && worst_stick < 1e-9, "Psi_N* off by %.3g (slip), %.3g (stick)",
              worst_slip, worst_stick);
}

/* The flat-plate rest band of model.md §6 with CVODE: dropped without spin, 0 < nu < 1, the
   particle comes to a normal lock (vn = V = 0 there, cx = 0) with
   Gamma/(1+nu) <= delta_y <= Gamma/(1-nu) and Psi_N* = Gamma. (The fixed step's version is
   in test_invariants.) */
Test(dashpot, flat_plate_comes_to_rest_in_the_band)
{
    const double nus[] = {0.2, 0.5, 0.9};
    for (int i = 0; i < 3; i++) {
        tribo_scene s = scene_of("beta=0 drop_speed=0 gap0=0.001 mu=0.1");
        s.nu = nus[i];
        no_charge_models(&s);
        tribo_model *m = make(&s);
        cr_assert_eq(tribo_advance(m, 200.0), TRIBO_OK);
        const double dy = tribo_get(m, TRIBO_QUANTITY_DELTA_Y), G = s.Gamma;
        cr_expect(locked(m) && tribo_get(m, TRIBO_QUANTITY_V) == 0.0, "nu = %g: not at rest", nus[i]);
        cr_expect(dy >= G / (1 + nus[i]) && dy <= G / (1 - nus[i]),
                  "nu = %g: delta_y = %g outside [%g, %g]", nus[i], dy, G / (1 + nus[i]),
                  G / (1 - nus[i]));
        cr_expect_float_eq(tribo_get(m, TRIBO_QUANTITY_PSI_N), G, 1e-15, "nu = %g: Psi_N = %.17g", nus[i],
                           tribo_get(m, TRIBO_QUANTITY_PSI_N));
        tribo_free(m);
    }
}

/* ---- A <= 0 (model.md §3) ---------------------------------------------------------------------- */

static tribo_dyn_params params_of(const tribo_scene *s)
{
    tribo_dyn_params p = {0};
    p.eps = s->epsilon;
    p.eps2 = s->epsilon * s->epsilon;
    p.mu = s->mu;
    p.nu = s->nu;
    p.Gamma = s->Gamma;
    p.g_t = s->Gamma * sin(s->beta);
    p.g_n = s->Gamma * cos(s->beta);
    p.inv_inertia = 4.0 / (1.0 + p.eps2);
    p.v_reg = s->v_reg;
    p.damping_point = s->damping_point;
    p.rtol = s->rtol;
    p.atol = s->atol;
    p.chute_length = s->chute_length;
    return p;
}

/* A slipping contact whose vn reaches 0: with A > 0 it enters the normal lock; where the
   slip makes A <= 0 (high mu, a Painleve-type configuration: friction's torque would drive
   the contact point into the plate) there is no lock, and vn leaves 0 in a direction
   consistent with the phase it leads into, s dvn/dtau > 0. */
Test(dashpot, no_lock_where_slip_makes_A_non_positive)
{
    tribo_scene s = scene_of("epsilon=0.3 mu=3 nu=1");
    tribo_dyn_params p = params_of(&s);
    const tribo_force_law slip_in = {.contact = TRIBO_CONTACT_ON, .normal = TRIBO_NORMAL_SIGN, .normal_sign = -1.0,
                                       .tangent = TRIBO_TANGENT_SLIP, .slip_sign = 1.0};
    const int fired[TRIBO_N_SWITCHES] = {[TRIBO_SWITCH_NORMAL_A] = 1};
    int found = 0;
    for (int j = -150; j <= 150 && !found; j++) {
        const double phi = 0.01 * j, dy = 0.01, Om = 0.01;
        tribo_pose g;
        tribo_pose_at(p.eps2, phi, &g);
        double A;
        tribo_lock_force(&p, &slip_in, &g, (double[TRIBO_NSTATE_MAX]){0}, &A);
        if (A > 0.0)
            continue;
        found = 1;
        double y[TRIBO_NSTATE_MAX] = {0};
        y[TRIBO_IPHI] = phi;
        y[TRIBO_IY] = g.h - dy;
        y[TRIBO_IGAP] = -dy;
        y[TRIBO_IOMEGA] = Om;
        y[TRIBO_IV] = -(g.cx * Om); /* vn = 0 */
        y[TRIBO_IU] = 0.05 - g.h * Om; /* slipping forwards */
        y[TRIBO_IDX] = p.mu * dy * (1.0 + p.nu); /* on the limit of the pressing phase */
        const tribo_force_law after = tribo_phase_after(&p, &slip_in, y, fired);
        cr_expect_eq(after.normal, TRIBO_NORMAL_SIGN, "phi = %g, A = %g: locked", phi, A);
        double f[TRIBO_NSTATE_MAX];
        tribo_contact_eval ev;
        tribo_dynamics_rhs(&p, &after, y, f, &ev);
        const double dvn = f[TRIBO_IV] + tribo_pose_kappa(p.eps2, &ev.pose) * Om * Om +
                           ev.pose.cx * f[TRIBO_IOMEGA];
        cr_expect(after.normal_sign * dvn > 0.0, "phi = %g: s = %g but dvn/dtau = %g", phi,
                  after.normal_sign, dvn);

        /* the same state at low friction (A > 0) locks */
        tribo_dyn_params low = p;
        low.mu = 0.3;
        y[TRIBO_IDX] = low.mu * dy * (1.0 + low.nu);
        const tribo_force_law locks = tribo_phase_after(&low, &slip_in, y, fired);
        cr_expect_eq(locks.normal, TRIBO_NORMAL_LOCK, "phi = %g at mu = 0.3", phi);
    }
    cr_assert(found, "no orientation with A <= 0 at eps = 0.3, mu = 3");
}

/* The same through whole runs: spinning drops at mu = 3 slip through configurations with
   A <= 0 (counted), yet no slipping lock ever has A <= 0, and a slipping lock's switch
   function for A is A itself. */
Test(dashpot, runs_visit_A_non_positive_without_a_lock_there, .timeout = 60)
{
    int visited = 0, slipping_locks = 0;
    const double eps[] = {0.3, 0.5}, spins[] = {0.5, -0.5};
    for (int e = 0; e < 2; e++) {
        for (int w = 0; w < 2; w++) {
            tribo_scene s = scene_of("mu=3 nu=3");
            s.epsilon = eps[e];
            s.Omega0 = spins[w];
            no_charge_models(&s);
            const tribo_dyn_params p = params_of(&s);
            tribo_model *m = make(&s);
            for (int k = 1; k <= 6000; k++) {
                cr_assert_eq(tribo_advance(m, 0.05 * k), TRIBO_OK, "%s", tribo_last_error(m));
                if (tribo_get(m, TRIBO_QUANTITY_SLIPPING) == 0.0)
                    continue;
                const double dx = tribo_get(m, TRIBO_QUANTITY_DELTA_X);
                const tribo_force_law slip = {.contact = TRIBO_CONTACT_ON,
                                              .normal = TRIBO_NORMAL_LOCK,
                                              .tangent = TRIBO_TANGENT_SLIP,
                                              .slip_sign = dx > 0.0 ? 1.0 : -1.0};
                double y[TRIBO_NSTATE_MAX] = {0}, A, g[TRIBO_N_SWITCHES];
                y[TRIBO_IPHI] = tribo_get(m, TRIBO_QUANTITY_PHI);
                tribo_pose pose;
                tribo_pose_at(p.eps2, y[TRIBO_IPHI], &pose);
                y[TRIBO_IY] = tribo_get(m, TRIBO_QUANTITY_Y);
                y[TRIBO_IGAP] = y[TRIBO_IY] - pose.h;
                y[TRIBO_IOMEGA] = tribo_get(m, TRIBO_QUANTITY_OMEGA);
                y[TRIBO_IV] = tribo_get(m, TRIBO_QUANTITY_V);
                y[TRIBO_IU] = tribo_get(m, TRIBO_QUANTITY_U);
                y[TRIBO_IDX] = dx;
                tribo_lock_force(&p, &slip, &pose, y, &A);
                if (locked(m)) {
                    slipping_locks++;
                    cr_assert(A > 0.0, "tau = %g: a slipping lock with A = %g", 0.05 * k, A);
                    tribo_switch_functions(&p, &slip, y, g);
                    cr_assert_eq(g[TRIBO_SWITCH_LOCK_FACTOR], A);
                } else {
                    visited += A <= 0.0;
                }
            }
            tribo_free(m);
        }
    }
    cr_expect(visited > 0 && slipping_locks > 0, "%d samples slipping with A <= 0, %d in a slipping lock",
              visited, slipping_locks);
}

/* A contact-point lock's held indentation comes back from a saved state, and from a tunable
   changed inside the lock (both restart CVODE from the committed point): the runs continue
   bit-identically, and the lock is still a lock after the change. */
Test(dashpot, lock_survives_save_load_and_a_tunable_change)
{
    tribo_scene s = scene_of("epsilon=0.2 mu=1 nu=1 n_segments=200");
    tribo_model *a = make(&s), *b = make(&s);
    advance_both(a, b, 10.0);
    cr_assert(locked(a));
    size_t size;
    unsigned char *bytes = saved_state(a, &size);
    advance_both(a, b, 60.0);
    tribo_model *c = make(&s);
    cr_assert_eq(tribo_state_load(c, bytes, size), TRIBO_OK, "%s", tribo_last_error(c));
    cr_assert_eq(tribo_advance(c, 60.0), TRIBO_OK);
    for (int q = 0; q < TRIBO_QUANTITY_COUNT; q++)
        cr_expect_eq(tribo_get(a, (tribo_quantity)q), tribo_get(c, (tribo_quantity)q), "%s",
                     tribo_quantity_name((tribo_quantity)q));
    cr_assert(locked(b));
    const double dy = tribo_get(b, TRIBO_QUANTITY_DELTA_Y);
    cr_assert_eq(tribo_set_param(b, "mu", 0.9), TRIBO_OK);
    cr_assert_eq(tribo_advance(b, 61.0), TRIBO_OK);
    cr_expect(locked(b) && fabs(tribo_get(b, TRIBO_QUANTITY_DELTA_Y) - dy) <= 1e-15 * dy,
              "delta_y %.17g, was %.17g",
              tribo_get(b, TRIBO_QUANTITY_DELTA_Y), dy);
    free(bytes);
    tribo_free(a);
    tribo_free(b);
    tribo_free(c);
}
